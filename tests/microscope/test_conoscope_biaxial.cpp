// Biaxial acute-bisectrix figures: melatopes where Mallard's law puts them, isogyres that keep to the
// polarizers.
#include "conoscope_fixtures.hpp"
#include "figure_measurements.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace petroscope {
namespace {

// Mallard: the binormal leaves into air at sin V' = nβ sin V, imaged at r/r_max = sin V'/NA
// (docs/theory.md §5, "Mallard's law"; Nesse, Introduction to Optical Mineralogy).
double mallard_radius_px(const Mineral& mineral, const ConoscopeSettings& settings) {
    const OpticalSummary summary = optical_summary(mineral, settings.wavelengths_nm[0]);
    const double v = 0.5 * *summary.two_v_deg * std::numbers::pi / 180.0;
    return summary.n_beta * std::sin(v) / settings.numerical_aperture * settings.size_px / 2;
}

class MelatopeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MelatopeTest, MelatopesLieWhereMallardsLawPutsThemOnTheAxialPlaneTrace) {
    const Mineral& mineral = testing::repository_minerals().find(GetParam());
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::acute_bisectrix, 10.0, 1024);
    settings.stage_deg = 45.0;  // axial plane trace along NE–SW
    const Image map = testing::retardation_map(settings, testing::indices_of(mineral));
    const double expected = mallard_radius_px(mineral, settings);
    for (const double sign : {+1.0, -1.0}) {
        const Eigen::Vector2d guess_offset = sign * expected / std::sqrt(2.0) * Eigen::Vector2d(1.0, 1.0);
        const Eigen::Vector2d found = testing::darkest_point(map, {512.0 + guess_offset.x(), 512.0 - guess_offset.y()}, 12);
        EXPECT_NEAR(found.norm(), expected, 1.0) << GetParam();
        std::printf("%s melatope: r = %.3f px, Mallard %.3f px, %.3f px off the trace (1024^2)\n", GetParam().c_str(),
                    found.norm(), expected, std::abs(found.x() - found.y()) / std::sqrt(2.0));
        // Distance from the trace x = y.
        EXPECT_LT(std::abs(found.x() - found.y()) / std::sqrt(2.0), 1.0) << GetParam();
        EXPECT_GT(found.dot(Eigen::Vector2d(sign, sign)), 0.0);
    }
}

INSTANTIATE_TEST_SUITE_P(AcuteBisectrixFigures, MelatopeTest, ::testing::Values("muscovite", "aragonite", "topaz"));

TEST(ConoscopeBiaxial, IsogyresFormAStraightCrossAtZeroDegrees) {
    // At 0° the E–W and N–S lines are mirror planes of the indicatrix: the modes there are pure p and s,
    // and nothing passes the crossed analyzer.
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    const ConoscopeSettings settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 60.0, 512);
    for (double t = -0.84; t <= 0.84; t += 0.01) {
        EXPECT_LT(conoscope_point_transmission(settings, testing::indices_of(muscovite), {t, 0.0})[0], 1e-24);
        EXPECT_LT(conoscope_point_transmission(settings, testing::indices_of(muscovite), {0.0, t})[0], 1e-24);
    }
}

TEST(ConoscopeBiaxial, IsogyresPassThroughTheMelatopesAt45Degrees) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    ConoscopeSettings settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 60.0, 512);
    settings.stage_deg = 45.0;
    const auto indices = testing::indices_of(muscovite);
    const double radius_xi = mallard_radius_px(muscovite, settings) / (settings.size_px / 2) * settings.numerical_aperture;
    const Eigen::Vector2d melatope = radius_xi / std::sqrt(2.0) * Eigen::Vector2d(1, 1);
    // Dark at the melatope, bright at the centre (the cross has opened into hyperbolae) ...
    EXPECT_LT(conoscope_point_transmission(settings, indices, melatope)[0], 1e-5);
    EXPECT_GT(conoscope_point_transmission(settings, indices, Eigen::Vector2d::Zero())[0], 0.1);
    // ... and the isogyre leaves the melatope across the trace: along the perpendicular through it the
    // vibration directions stay near the polarizers, so it stays darker than along the trace.
    const Eigen::Vector2d along(1 / std::sqrt(2.0), 1 / std::sqrt(2.0)), across(-1 / std::sqrt(2.0), 1 / std::sqrt(2.0));
    for (const double step : {0.01, 0.02, 0.03}) {
        const double on_trace = conoscope_point_transmission(settings, indices, melatope - step * along)[0];
        const double on_isogyre = conoscope_point_transmission(settings, indices, melatope + step * across)[0];
        EXPECT_LT(on_isogyre, 0.5 * on_trace) << step;
    }
}

TEST(ConoscopeBiaxial, TurningTheStageTurnsTheMelatopesButNotTheIsogyreCross) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    ConoscopeSettings settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 10.0, 512);
    const double expected_radius = mallard_radius_px(muscovite, settings);
    for (const double stage_deg : {0.0, 30.0, 45.0}) {
        settings.stage_deg = stage_deg;
        const Image map = testing::retardation_map(settings, testing::indices_of(muscovite));
        const double a = stage_deg * std::numbers::pi / 180.0;
        const Eigen::Vector2d guess = expected_radius * Eigen::Vector2d(std::cos(a), std::sin(a));
        const Eigen::Vector2d found = testing::darkest_point(map, {256.0 + guess.x(), 256.0 - guess.y()}, 8);
        EXPECT_NEAR(std::atan2(found.y(), found.x()) * 180.0 / std::numbers::pi, stage_deg, 0.3);
        EXPECT_NEAR(found.norm(), expected_radius, 1.0);
    }
}

}  // namespace
}  // namespace petroscope
