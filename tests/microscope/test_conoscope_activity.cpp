// The conoscope with optical activity: quartz's centre between crossed polars, the sense of rotation, a thin
// section's figure (unchanged by activity beyond 1e-3), a zero gyration (today's figure to 1e-12), and the
// vectorised kernel against the reference path for random active crystals, with and without a plate. The
// interference terms of an active crystal are tested in test_conoscope_terms.cpp.
#include "conoscope_evaluator.hpp"
#include "conoscope_fixtures.hpp"
#include "kernel_against_reference.hpp"

#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/minerals/mineral_parser.hpp"
#include "petroscope/spectral/colorimetry.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace petroscope {
namespace {

const Mineral& quartz() { return testing::repository_minerals().find("quartz"); }

// Monochromatic basal plate (optic axis along the microscope), 65 px so that the middle pixel is ξ = 0.
ConoscopeSettings basal_plate(const Mineral& mineral, Handedness handedness, double thickness_um, double wavelength_nm) {
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, thickness_um, 65, wavelength_nm);
    settings.gyration = mineral_gyration(mineral, handedness);
    return settings;
}
ConoscopeSettings basal_quartz(Handedness handedness, double thickness_um = 1000.0) {
    return basal_plate(quartz(), handedness, thickness_um, 589.3);
}

double centre(const ConoscopeSettings& settings, const Mineral& mineral = quartz()) {
    return render_conoscope(settings, testing::indices_of(mineral), nullptr).at(32, 32, 0);
}

double rotation_rad(double thickness_um) { return quartz().principal_rotatory_power(589.3)[2] * thickness_um; }

// Crossed polars: sin²(ρd)·T at the centre of a basal plate, T the normal-incidence transmission of its two faces,
// (4n_s·n_o/(n_s + n_o)²)²; dark without the activity.
void expect_sin_squared_centre(const Mineral& mineral, double thickness_um, double wavelength_nm) {
    const double n_o = mineral.principal_n(wavelength_nm)[0];
    const double n_s = ConoscopeSettings{}.surround_n;
    const double faces = std::pow(4.0 * n_s * n_o / std::pow(n_s + n_o, 2), 2);
    const double rotation = mineral.principal_rotatory_power(wavelength_nm)[2] * thickness_um;
    for (const Handedness handedness : {Handedness::right, Handedness::left}) {
        const double expected = std::pow(std::sin(rotation), 2) * faces;
        EXPECT_NEAR(centre(basal_plate(mineral, handedness, thickness_um, wavelength_nm), mineral), expected, 1e-7 * expected)
            << handedness_name(handedness);
    }
    ConoscopeSettings inactive = basal_plate(mineral, Handedness::right, thickness_um, wavelength_nm);
    inactive.gyration = {};
    EXPECT_LT(centre(inactive, mineral), 1e-20);
}

TEST(ConoscopeActivity, TheCentreOfA1mmQuartzPlateIsSinSquaredOfTheRotationTimesTheFaces) {
    // 589.3 nm: ρd = 21.72° (the record's formula: 21.722°).
    EXPECT_NEAR(rotation_rad(1000.0) * 180.0 / std::numbers::pi, 21.72, 0.005);
    expect_sin_squared_centre(quartz(), 1000.0, 589.3);
}

TEST(ConoscopeActivity, TheCentreOfAParatellurite200umPlateIsSinSquaredOfTheRotationTimesTheFaces) {
    // The second active crystal: 632.8 nm, ρd = 17.4° (86.9 °/mm in its table; 0.2 % more in the record's formula),
    // with a birefringence 17 times quartz's around the axis.
    const Mineral& paratellurite = testing::repository_minerals().find("paratellurite");
    EXPECT_NEAR(paratellurite.principal_rotatory_power(632.8)[2] * 200.0 * 180.0 / std::numbers::pi, 17.38, 0.04);
    expect_sin_squared_centre(paratellurite, 200.0, 632.8);
}

// The centre of a 1 mm plate cut across an optic axis of a biaxial crystal with rotatory powers (30, −20, 40) °/mm
// along X, Y, Z and indices nα, nα + Δn/3, nα + Δn, relative to sin²(ρd)·T: ρ = ρ_x sin²V + ρ_z cos²V, the
// rotatory power along the optic axis in an isotropic background (sin²V = (1/nα² − 1/nβ²)/(1/nα² − 1/nγ²); docs/theory.md
// §9) and T the faces' transmission at nβ.
double biaxial_centre_deviation(double birefringence, Handedness handedness) {
    const double n_alpha = 1.54, n_beta = n_alpha + birefringence / 3.0, n_gamma = n_alpha + birefringence;
    std::ostringstream record;
    record.precision(17);
    record << "name: t\nsystem: orthorhombic\nclass: biaxial\nn_alpha: constant " << n_alpha << "\nn_alpha.source: a\nn_beta: constant "
           << n_beta << "\nn_beta.source: b\nn_gamma: constant " << n_gamma << "\nn_gamma.source: c\nrotatory_power_x: constant 30\n"
           << "rotatory_power_x.source: x\nrotatory_power_y: constant -20\nrotatory_power_y.source: y\nrotatory_power_z: constant 40\n"
           << "rotatory_power_z.source: z";
    const Mineral biaxial = parse_mineral(record.str(), "t.txt");
    const Eigen::Vector3d impermeability = biaxial.principal_n(589.3).cwiseInverse().cwiseAbs2();
    const double sin2_v = (impermeability[0] - impermeability[1]) / (impermeability[0] - impermeability[2]);
    const Eigen::Vector3d rho = biaxial.principal_rotatory_power(589.3);
    const double rotation = (rho[0] * sin2_v + rho[2] * (1.0 - sin2_v)) * 1000.0;
    const double n_s = ConoscopeSettings{}.surround_n;
    const double expected = std::pow(std::sin(rotation), 2) * std::pow(4.0 * n_s * n_beta / std::pow(n_s + n_beta, 2), 2);
    return centre(basal_plate(biaxial, handedness, 1000.0, 589.3), biaxial) / expected - 1.0;
}

TEST(ConoscopeActivity, AlongAnOpticAxisOfABiaxialCrystalThePlaneTurnsByTheRotatoryPowerAlongIt) {
    // In an anisotropic background the rotation along an optic axis differs from the isotropic formula by a
    // relative amount of the order of the birefringence: the deviation shrinks in proportion to Δn.
    for (const Handedness handedness : {Handedness::right, Handedness::left}) {
        const double coarse = biaxial_centre_deviation(3e-4, handedness), fine = biaxial_centre_deviation(3e-5, handedness);
        std::printf("biaxial optic-axis centre (%s) against sin^2(rho d) T: %.2e at birefringence 3e-4, %.2e at 3e-5\n",
                    std::string(handedness_name(handedness)).c_str(), coarse, fine);
        EXPECT_LT(std::abs(fine), 1e-5);
        EXPECT_NEAR(coarse / fine, 10.0, 1.0);
    }
}

TEST(ConoscopeActivity, TheAnalyzerTurnedWithThePlaneExtinguishesTheCentre) {
    // Right quartz turns the plane clockwise for the observer (toward negative azimuths, docs/conventions.md):
    // the analyzer at 90° − ρd restores the extinction, at 90° + ρd it does not; the left form the other way.
    const double rotation_deg = rotation_rad(1000.0) * 180.0 / std::numbers::pi;
    for (const Handedness handedness : {Handedness::right, Handedness::left}) {
        const double sense = handedness == Handedness::right ? -1.0 : 1.0;
        ConoscopeSettings settings = basal_quartz(handedness);
        settings.analyzer_deg = 90.0 + sense * rotation_deg;
        EXPECT_LT(centre(settings), 1e-12) << handedness_name(handedness);
        settings.analyzer_deg = 90.0 - sense * rotation_deg;
        EXPECT_GT(centre(settings), 0.4) << handedness_name(handedness);
    }
}

// White-light XYZ figure of quartz, 30 µm, every wavelength solved.
Image thin_section_figure(Cut cut, bool active) {
    ConoscopeSettings settings = testing::figure_settings(quartz(), cut, 30.0, 64);
    settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    settings.spectrum = SpectrumSampling::exact;
    if (active) settings.gyration = mineral_gyration(quartz(), Handedness::right);
    const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    return render_conoscope(settings, testing::indices_of(quartz()), &integrator);
}

TEST(ConoscopeActivity, InAThinSectionTheActivityChangesTheFigureByLessThan1e3) {
    // 30 µm turns the plane by 0.65°: in white light the figure (XYZ, Y = 1 for a perfect transmitter) changes
    // by less than 1e-3 anywhere, and far from the axis by far less.
    for (const Cut cut : {Cut::optic_axis, Cut::optic_normal}) {
        const Image active = thin_section_figure(cut, true), inactive = thin_section_figure(cut, false);
        double worst = 0.0;
        for (std::size_t i = 0; i < active.pixels.size(); ++i) worst = std::max(worst, double(std::abs(active.pixels[i] - inactive.pixels[i])));
        std::printf("30 um quartz (%s): largest change from the activity %.1e\n", cut == Cut::optic_axis ? "optic axis" : "optic normal", worst);
        EXPECT_LT(worst, 1e-3);
        EXPECT_GT(worst, 0.0);
    }
}

TEST(ConoscopeActivity, AZeroGyrationReproducesTheInactiveFigure) {
    // The active code path with g = 0 against the inactive one, monochromatic and at every wavelength of a white
    // spectrum, over a grid of directions: the same transmission to 1e-12 (it is unity-free rounding only).
    for (const bool white : {false, true}) {
        ConoscopeSettings settings = testing::figure_settings(quartz(), Cut::optic_axis, 300.0, 64);
        settings.polarizer_deg = 10.0;
        settings.analyzer_deg = 95.0;
        if (white) {
            settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
            settings.spectrum = SpectrumSampling::exact;
        }
        const detail::ConoscopeEvaluator inactive(settings, testing::indices_of(quartz()));
        settings.gyration = [](double) { return Eigen::Matrix3d::Zero().eval(); };
        const detail::ConoscopeEvaluator zero(settings, testing::indices_of(quartz()));
        const std::size_t count = settings.wavelengths_nm.size();
        std::vector<double> plus(count), minus(count), zero_plus(count), zero_minus(count);
        detail::SpectralScratch scratch, zero_scratch;
        double worst = 0.0;
        for (double x = -0.8; x <= 0.8; x += 0.1) {
            for (double y = 0.0; y <= 0.8; y += 0.1) {
                inactive.spectral_pair({x, y}, scratch, false, plus.data(), minus.data());
                zero.spectral_pair({x, y}, zero_scratch, false, zero_plus.data(), zero_minus.data());
                for (std::size_t w = 0; w < count; ++w) worst = std::max({worst, std::abs(plus[w] - zero_plus[w]), std::abs(minus[w] - zero_minus[w])});
            }
        }
        EXPECT_LT(worst, 1e-12) << (white ? "white" : "monochromatic");
    }
}

TEST(ConoscopeActivity, TheKernelMatchesTheReferencePathForRandomActiveCrystals) {
    // Random crystals with a random symmetric gyration tensor, components up to 10^−2.5 (about 45 times quartz's
    // g₃₃, so that the coupling is strong everywhere), 10–32 µm, random polars, analyzer in or out, a gypsum plate in a third of the cases.
    std::mt19937_64 rng(191);
    std::uniform_real_distribution<double> unit(0.0, 1.0), symmetric(-1.0, 1.0);
    const Mineral& gypsum = testing::repository_minerals().find("gypsum");
    double worst_spectral = 0.0, worst_batch = 0.0;
    for (int crystal_case = 0; crystal_case < 60; ++crystal_case) {
        const Indicatrix indicatrix = crystal_case % 2 == 0 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
        Eigen::Matrix3d g;
        for (int i = 0; i < 3; ++i) {
            for (int j = i; j < 3; ++j) g(i, j) = g(j, i) = std::pow(10.0, -3.5 + unit(rng)) * symmetric(rng);
        }
        ConoscopeSettings settings = testing::random_thin_slab(indicatrix.axes, crystal_case, rng);
        if (crystal_case % 3 == 0) settings.plate = make_accessory_plate(PlateKind::gypsum, gypsum, 180.0 * unit(rng));
        settings.gyration = [g](double) { return g; };
        const testing::KernelDifferences difference = testing::kernel_against_reference(settings, indicatrix.principal_n, rng);
        worst_spectral = std::max(worst_spectral, difference.white);
        worst_batch = std::max(worst_batch, difference.batch);
    }
    EXPECT_LT(worst_spectral, 1e-12);
    EXPECT_LT(worst_batch, 1e-12);
    std::printf("active kernel vs reference: white %.2e, monochromatic batches %.2e\n", worst_spectral, worst_batch);
}

}  // namespace
}  // namespace petroscope
