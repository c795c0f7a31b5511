// The gypsum plate in conoscopy (issue 4): in an optic-axis figure the slow vibration is radial for a
// positive crystal (the e' wave) and tangential for a negative one, so near the centre the retardations add
// (second-order blue) in the quadrants where the radius is parallel to the plate's slow direction (NE and SW
// for the usual NE–SW plate) and subtract (first-order yellow) in the others; negative crystals the reverse
// (Nesse, Introduction to Optical Mineralogy, ch. 7).
#include "conoscope_fixtures.hpp"

#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

/// CIELAB b* (blue < 0 < yellow) in each quadrant on the diagonals, at 35% of the field radius.
std::array<double, 4> quadrant_b_star(const Mineral& mineral, double thickness_um) {
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, thickness_um, 64);
    settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 10.0}.wavelengths_nm();
    settings.plate = make_accessory_plate(PlateKind::gypsum, testing::repository_minerals().find("gypsum"), 45.0);
    const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    const Image xyz = render_conoscope(settings, testing::indices_of(mineral), &integrator);
    const int offset = static_cast<int>(0.35 * 32 / std::sqrt(2.0));
    const std::array<std::pair<int, int>, 4> pixels{{{32 + offset, 31 - offset},    // NE
                                                     {31 - offset, 31 - offset},    // NW
                                                     {31 - offset, 32 + offset},    // SW
                                                     {32 + offset, 32 + offset}}};  // SE
    std::array<double, 4> b_star{};
    for (int q = 0; q < 4; ++q) {
        const auto [x, y] = pixels[static_cast<std::size_t>(q)];
        const Eigen::Vector3d colour(xyz.at(x, y, 0), xyz.at(x, y, 1), xyz.at(x, y, 2));
        b_star[static_cast<std::size_t>(q)] = xyz_to_lab(colour, integrator.white_xyz())[2];
    }
    return b_star;
}

TEST(ConoscopePlate, PositiveOpticAxisFigureIsBlueInNortheastAndSouthwest) {
    const std::array<double, 4> b = quadrant_b_star(testing::repository_minerals().find("quartz"), 300.0);
    EXPECT_LT(b[0], -10.0);  // NE blue
    EXPECT_LT(b[2], -10.0);  // SW blue
    EXPECT_GT(b[1], 10.0);   // NW yellow
    EXPECT_GT(b[3], 10.0);   // SE yellow
}

TEST(ConoscopePlate, NegativeOpticAxisFigureIsTheReverse) {
    const std::array<double, 4> b = quadrant_b_star(testing::repository_minerals().find("calcite"), 30.0);
    EXPECT_GT(b[0], 10.0);
    EXPECT_GT(b[2], 10.0);
    EXPECT_LT(b[1], -10.0);
    EXPECT_LT(b[3], -10.0);
}

// Figures that differ only in polars and plate share each point's eigenmodes (render_conoscope_polarization_set);
// each equals its own render: a biaxial crystal off-centre (some points near a binormal go to the
// reference path), with and without analyzer and plates.
TEST(ConoscopePlate, FiguresSharingTheirModesEqualTheirOwnRenders) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    ConoscopeSettings base = testing::figure_settings(muscovite, Cut::acute_bisectrix, 60.0, 64);
    base.wavelengths_nm = WavelengthGrid{380.0, 780.0, 10.0}.wavelengths_nm();
    const SpectralIntegrator integrator(base.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    std::vector<ConoscopeSettings> settings(4, base);
    settings[1].analyzer_in = false;
    settings[2].plate = make_accessory_plate(PlateKind::gypsum, testing::repository_minerals().find("gypsum"), 45.0);
    settings[3].plate = make_accessory_plate(PlateKind::mica, muscovite, 10.0);
    settings[3].polarizer_deg = 30.0;
    settings[3].analyzer_deg = 75.0;
    const std::vector<Image> shared = render_conoscope_polarization_set(settings, testing::indices_of(muscovite), integrator);
    ASSERT_EQ(shared.size(), settings.size());
    for (std::size_t k = 0; k < settings.size(); ++k) {
        const Image alone = render_conoscope(settings[k], testing::indices_of(muscovite), &integrator);
        double largest = 0.0;
        for (std::size_t p = 0; p < alone.pixels.size(); ++p) largest = std::max(largest, double(std::fabs(alone.pixels[p] - shared[k].pixels[p])));
        EXPECT_LE(largest, 1e-7) << "figure " << k;  // float images of the same double computations
    }
    settings[1].thickness_um = 61.0;
    EXPECT_THROW(render_conoscope_polarization_set(settings, testing::indices_of(muscovite), integrator), InputError);
}

}  // namespace
}  // namespace petroscope
