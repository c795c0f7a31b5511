// Invariants of every figure: turning crystal and polarizers together turns the image; no pixel beats
// the parallel-polar transmission of the empty stack; nothing is ever NaN, on an optic axis included.
#include "conoscope_fixtures.hpp"
#include "figure_measurements.hpp"

#include "support/random_crystals.hpp"

#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

TEST(ConoscopeInvariants, TurningCrystalAndPolarizersTogetherTurnsTheImage) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    const auto indices = testing::indices_of(muscovite);
    const ConoscopeSettings reference_settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 60.0, 512);
    const Image reference = render_conoscope(reference_settings, indices, nullptr);
    const Eigen::Vector3d n_ref = muscovite.principal_n(muscovite.reference_wavelength_nm);
    for (const double alpha : {30.0, 73.0}) {
        // By the stage ...
        ConoscopeSettings staged = reference_settings;
        staged.stage_deg = alpha;
        staged.polarizer_deg = alpha;
        staged.analyzer_deg = 90.0 + alpha;
        const double by_stage = testing::registered_rotation_deg(reference, render_conoscope(staged, indices, nullptr), alpha, 3.0);
        EXPECT_NEAR(by_stage, alpha, 0.2);
        // ... and by the crystal's azimuth.
        ConoscopeSettings turned = reference_settings;
        turned.crystal_axes = cut_orientation(Cut::acute_bisectrix, OpticalClass::biaxial, n_ref, alpha, 0.0);
        turned.polarizer_deg = alpha;
        turned.analyzer_deg = 90.0 + alpha;
        const double by_azimuth = testing::registered_rotation_deg(reference, render_conoscope(turned, indices, nullptr), alpha, 3.0);
        EXPECT_NEAR(by_azimuth, alpha, 0.2);
        std::printf("turned by %.0f deg: image rotation %.4f deg (stage), %.4f deg (azimuth)\n", alpha, by_stage, by_azimuth);
    }
}

TEST(ConoscopeInvariants, NoPixelExceedsTheEmptyStackAndNoneIsNaN) {
    // The bound: the same stack with parallel polarizers and no crystal (a "crystal" of the surround's
    // index), rendered by the same code.
    ConoscopeSettings empty;
    empty.size_px = 64;
    empty.numerical_aperture = 0.95;
    empty.analyzer_deg = 0.0;
    const Image bound = render_conoscope(empty, [&](double) { return Eigen::Vector3d::Constant(empty.surround_n); }, nullptr);

    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto& minerals = testing::repository_minerals().minerals();
    int cases = 0;
    for (const Mineral& mineral : minerals) {
        for (int trial = 0; trial < 4; ++trial, ++cases) {
            ConoscopeSettings settings;
            settings.size_px = trial % 2 == 0 ? 64 : 65;  // odd sizes put a pixel exactly on the axis
            settings.numerical_aperture = 0.95;
            settings.thickness_um = std::pow(10.0, -3.0 + 7.0 * unit(rng));  // 1 nm … 10 mm
            settings.wavelengths_nm = {380.0 + 400.0 * unit(rng)};
            settings.polarizer_deg = 360.0 * unit(rng);
            settings.analyzer_deg = trial == 3 ? settings.polarizer_deg : settings.polarizer_deg + 90.0;
            settings.analyzer_in = trial != 2;
            const Eigen::Vector3d n_ref = mineral.principal_n(mineral.reference_wavelength_nm);
            // Half the cases exactly on an optic axis, the others at random.
            settings.crystal_axes = trial < 2 && mineral.optical_class != OpticalClass::isotropic
                                        ? cut_orientation(Cut::optic_axis, mineral.optical_class, n_ref, 360.0 * unit(rng), 0.0)
                                        : testing::random_rotation(rng);
            const Image figure = render_conoscope(settings, testing::indices_of(mineral), nullptr);
            for (int y = 0; y < figure.height; ++y) {
                for (int x = 0; x < figure.width; ++x) {
                    const float value = figure.at(x, y, 0);
                    ASSERT_TRUE(std::isfinite(value)) << mineral.name << " case " << trial;
                    ASSERT_GE(value, 0.0f) << mineral.name << " case " << trial << " pixel " << x << "," << y;
                    if (settings.size_px == 64) ASSERT_LE(value, bound.at(x, y, 0) + 1e-6f) << mineral.name;
                    ASSERT_LE(value, 1.0f + 1e-6f) << mineral.name;
                }
            }
        }
    }
    EXPECT_EQ(cases, 4 * static_cast<int>(minerals.size()));
    // The empty stack with parallel polars passes everything inside the aperture.
    EXPECT_NEAR(bound.at(32, 32, 0), 1.0, 1e-12);
}

TEST(ConoscopeInvariants, ExactlyOnABinormalTheTransmissionIsFinite) {
    const Mineral& topaz = testing::repository_minerals().find("topaz");
    ConoscopeSettings settings = testing::figure_settings(topaz, Cut::optic_axis, 30.0, 65);
    // ξ = 0 is exactly along binormal 1 (up to the rounding of the rotation), and the odd image has a
    // pixel there.
    const std::vector<double> on_axis = conoscope_point_transmission(settings, testing::indices_of(topaz), Eigen::Vector2d::Zero());
    EXPECT_TRUE(std::isfinite(on_axis[0]));
    EXPECT_LT(on_axis[0], 1e-6);  // no retardation along the binormal: dark between crossed polars
    const Image figure = render_conoscope(settings, testing::indices_of(topaz), nullptr);
    EXPECT_TRUE(std::isfinite(figure.at(32, 32, 0)));
}

TEST(ConoscopeInvariants, WhiteLightNeverExceedsTheWhiteOfTheSource) {
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 30.0, 64);
    settings.wavelengths_nm = WavelengthGrid{}.wavelengths_nm();
    settings.analyzer_deg = 0.0;  // parallel polars: the brightest case
    const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    const Image xyz = render_conoscope(settings, testing::indices_of(calcite), &integrator);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            ASSERT_TRUE(std::isfinite(xyz.at(x, y, 1)));
            ASSERT_LE(xyz.at(x, y, 1), 1.0f + 1e-6f);
        }
    }
}

}  // namespace
}  // namespace petroscope
