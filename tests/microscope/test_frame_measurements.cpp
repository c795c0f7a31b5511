// Measurements on rendered figures (microscope/frame_measurements.hpp): where the model images the optic
// axes (Mallard's law), the dark spot of a melatope found on the image, mean colours.
#include "conoscope_fixtures.hpp"

#include "petroscope/microscope/frame_measurements.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace petroscope {
namespace {

constexpr double degree = std::numbers::pi / 180.0;

TEST(OpticAxisPoints, BiaxialAxesLieWhereMallardsLawPutsThem) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    ConoscopeSettings settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 30.0, 512);
    const OpticalSummary summary = optical_summary(muscovite, 589.3);
    const double radius = summary.n_beta * std::sin(0.5 * *summary.two_v_deg * degree) / settings.numerical_aperture;
    for (const double stage_deg : {0.0, 30.0, 45.0}) {
        settings.stage_deg = stage_deg;
        const auto points = conoscope_optic_axis_points(settings, muscovite.principal_n(589.3));
        ASSERT_EQ(points.size(), 2u);
        for (const Eigen::Vector2d& point : points) {
            EXPECT_NEAR(point.norm(), radius, 1e-12);
            // On the trace of the axial plane, E–W at stage 0, turned with the stage.
            EXPECT_NEAR(std::abs(std::sin(std::atan2(point.y(), point.x()) - stage_deg * degree)), 0.0, 1e-12);
        }
        EXPECT_NEAR((points[0] + points[1]).norm(), 0.0, 1e-12);
    }
}

TEST(OpticAxisPoints, UniaxialAxisSitsAtTheCentreOrTiltedOrNowhere) {
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    const Eigen::Vector3d n = calcite.principal_n(589.3);
    ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 30.0, 256);
    auto points = conoscope_optic_axis_points(settings, n);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_LT(points[0].norm(), 1e-12);
    // Tilted 20° toward azimuth 60°: sin θ_air = ω sin 20°.
    settings.crystal_axes = cut_orientation(Cut::optic_axis, calcite.optical_class, n, 60.0, 20.0);
    points = conoscope_optic_axis_points(settings, n);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].norm(), n[0] * std::sin(20.0 * degree) / settings.numerical_aperture, 1e-12);
    EXPECT_NEAR(std::atan2(points[0].y(), points[0].x()) / degree, 60.0, 1e-9);
    // A flash figure: the axis lies in the plane of the slab.
    settings.crystal_axes = cut_orientation(Cut::optic_normal, calcite.optical_class, n, 0.0, 0.0);
    EXPECT_TRUE(conoscope_optic_axis_points(settings, n).empty());
}

TEST(DarkSpot, FindsTheMelatopeOfAnOffCentreFigure) {
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    const Eigen::Vector3d n = calcite.principal_n(589.3);
    ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 30.0, 512);
    double worst_px = 0.0;
    for (const double azimuth_deg : {0.0, 30.0, 75.0, 200.0}) {
        settings.crystal_axes = cut_orientation(Cut::optic_axis, calcite.optical_class, n, azimuth_deg, 20.0);
        const Image figure = render_conoscope(settings, testing::indices_of(calcite), nullptr);
        const Eigen::Vector2d predicted = conoscope_optic_axis_points(settings, n).front();
        // Start the search 4 px away: the spot is found on the image, not taken from the guess.
        const auto found = dark_spot_near(figure, predicted + Eigen::Vector2d(4.0, -3.0) / 256.0, 16, 2.0);
        ASSERT_TRUE(found) << azimuth_deg;
        const double error_px = (*found - predicted).norm() * 256.0;
        worst_px = std::max(worst_px, error_px);
        EXPECT_LT(error_px, 0.5) << azimuth_deg;
    }
    std::printf("calcite 30 um tilted 20 deg, 512^2 at 589.3 nm: melatope found within %.3f px of the model's axis\n", worst_px);
}

TEST(DarkSpot, IsEmptyWithoutASpotOrAtTheFieldsEdge) {
    Image bright(128, 128, 1);
    std::fill(bright.pixels.begin(), bright.pixels.end(), 1.0f);
    // A slope: the darkest point of the window lies on its edge, not inside it.
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) bright.at(x, y, 0) = static_cast<float>(x);
    EXPECT_FALSE(dark_spot_near(bright, {0.0, 0.0}, 8, 1.5));
    EXPECT_FALSE(dark_spot_near(bright, {0.97, 0.0}, 8, 1.5));
    // A single dark pit is found to a fraction of a pixel.
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) bright.at(x, y, 0) = static_cast<float>(std::pow(x + 0.5 - 70.25, 2) + std::pow(y + 0.5 - 60.0, 2));
    const auto pit = dark_spot_near(bright, {6.0 / 64, 4.0 / 64}, 8, 1.5);
    ASSERT_TRUE(pit);
    EXPECT_NEAR(pit->x() * 64 + 64, 70.25, 1e-6);
    EXPECT_NEAR(64 - pit->y() * 64, 60.0, 1e-6);
}

TEST(MeanColour, AveragesTheFieldAndItsLuminance) {
    Image image(32, 32, 3);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            const Eigen::Vector2d offset(x + 0.5 - 16, y + 0.5 - 16);
            const float inside = offset.norm() < 16 ? 1.0f : 0.0f;
            image.at(x, y, 0) = 0.5f * inside;
            image.at(x, y, 1) = 0.25f * inside;
            image.at(x, y, 2) = inside;
        }
    }
    const MeanColour field = mean_colour(image, true);
    EXPECT_NEAR(field.r, 0.5, 1e-12);
    EXPECT_NEAR(field.g, 0.25, 1e-12);
    EXPECT_NEAR(field.b, 1.0, 1e-12);
    EXPECT_NEAR(field.luminance, 0.2126 * 0.5 + 0.7152 * 0.25 + 0.0722, 1e-12);
    EXPECT_LT(mean_colour(image, false).r, 0.5);  // the dark corners count over the whole image
}

}  // namespace
}  // namespace petroscope
