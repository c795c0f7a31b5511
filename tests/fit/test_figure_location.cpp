// Finding a conoscopic figure in a photo before any fit (fit/figure_location.hpp): synthetic camera photos of
// centred cuts, the figure off the frame's centre by up to a fifth of the frame and cut by the frame's edge.
#include "figure_location.hpp"
#include "realistic_camera_case.hpp"
#include "synthetic_photo.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>

namespace petroscope {
namespace {

struct LocationCase {
    const char* mineral;
    Cut cut;
    double thickness_um;
    int center_dx_px, center_dy_px;
    double radius_scale, rotation_deg;
};

void PrintTo(const LocationCase& c, std::ostream* os) { *os << c.mineral << " " << c.thickness_um << " um"; }

class FigureLocationTest : public ::testing::TestWithParam<LocationCase> {};

// Within 1.5 px, the finer search grid's block (192 px / 128), of where the photo's figure was put.
TEST_P(FigureLocationTest, TheHalfTurnSymmetryCentreIsTheFiguresCentre) {
    const LocationCase& c = GetParam();
    constexpr int kSize = 192;
    static const testing::PhotoLight light = testing::white_light();
    const testing::PhotoTruth truth{.thickness_um = c.thickness_um, .center_dx_px = c.center_dx_px, .center_dy_px = c.center_dy_px,
                                    .radius_scale = c.radius_scale, .rotation_deg = c.rotation_deg, .gains = {1.15, 0.9, 1.05},
                                    .supersampling = 2};
    const Image photo = testing::synthesize_photo(testing::photo_model(testing::fit_minerals().find(c.mineral), c.cut), light, truth, kSize, 5);
    const std::optional<Eigen::Vector2d> found = detail::half_turn_symmetry_centre_px(photo);
    ASSERT_TRUE(found.has_value());
    const Eigen::Vector2d located = *found, expected(0.5 * kSize + c.center_dx_px, 0.5 * kSize + c.center_dy_px);
    std::printf("%s %g um: located (%.2f, %.2f) for (%.1f, %.1f)\n", c.mineral, c.thickness_um, located.x(), located.y(), expected.x(), expected.y());
    EXPECT_LE((located - expected).norm(), 1.5);
}

// The realistic-camera bed's case 1 (docs/fitting.md): quartz 4.6 mm, whose rings are finer than the blur, 128²
// through a tangent projection, the figure (7.8, 23.7) px off the frame's centre and the light falling off about
// another centre, with a camera's vignetting, mosaic and JPEG. Before the light's falloff was divided out, the
// brighter part of the frame made (35, 39.5) look the most symmetric point.
TEST(FigureLocation, LightCentredAwayFromTheFigureDoesNotMoveItsCentre) {
    constexpr int kSize = 128, kCase = 1;
    const testing::CameraCase bed_case = testing::random_case(kCase, kSize);
    const Image photo = testing::photograph_case(kCase, bed_case, kSize).photo;
    const std::optional<Eigen::Vector2d> found = detail::half_turn_symmetry_centre_px(photo);
    ASSERT_TRUE(found.has_value());
    const Eigen::Vector2d expected(0.5 * kSize + bed_case.optics.center_dx_px, 0.5 * kSize + bed_case.optics.center_dy_px);
    std::printf("located (%.2f, %.2f) for (%.2f, %.2f)\n", found->x(), found->y(), expected.x(), expected.y());
    EXPECT_LE((*found - expected).norm(), 1.5);
}

TEST(FigureLocation, AFlatPhotoHasNoCentre) {
    Image flat(64, 48, 3);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 0.25f);
    EXPECT_FALSE(detail::half_turn_symmetry_centre_px(flat).has_value());
}

INSTANTIATE_TEST_SUITE_P(
    Figures, FigureLocationTest,
    ::testing::Values(LocationCase{"calcite", Cut::optic_axis, 30.0, 40, -30, 1.0, 7.0},
                      LocationCase{"calcite", Cut::optic_axis, 300.0, 20, 38, 1.1, 0.0},
                      LocationCase{"muscovite", Cut::acute_bisectrix, 30.0, -35, 25, 1.1, 9.0},
                      LocationCase{"quartz", Cut::optic_axis, 1000.0, -38, -38, 0.9, 20.0}));

}  // namespace
}  // namespace petroscope
