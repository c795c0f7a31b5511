// Fitting synthetic photos of conoscopic figures whose parameters the fit does not see (issue 6): the
// figure's centre off by up to 5% of the field, its scale by up to 10%, the camera turned, white balance
// off by up to 20% per channel, a tone curve of gamma 1.8 … 2.4, blur σ = 1 px, noise σ = 2/255, JPEG
// quality 85; the fit starts from a thickness off by a factor of 2. The thickness must come out within
// 1% and within its reported 2σ.
#include "synthetic_photo.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/jpeg_encoding.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

namespace petroscope {
namespace {

struct FitCase {
    const char* mineral;
    Cut cut;
    double thickness_um;
    double start_factor;  // the fit starts from thickness × this
    int center_dx_px, center_dy_px;
    double radius_scale, rotation_deg, tilt_deg, gamma;
    Eigen::Vector3d gains;
    bool fix_scale;  // a centred uniaxial figure determines only thickness × scale²
    int size_px = 256;  // the photo's side
};

void PrintTo(const FitCase& c, std::ostream* os) { *os << c.mineral << " " << c.thickness_um << " um"; }

struct Fitted {
    ConoscopeFitResult result;
    testing::PhotoTruth truth;
    double seconds;  // the fit alone, not the synthesis of the photo
};

/// The fit of a synthetic JPEG photo of `c`, with the encoding check repeating the file's encoding, or
/// `encoding` instead when given.
Fitted fit_synthetic(const FitCase& c, int size_px, const std::function<Image(const Image&)>& encoding = {}) {
    const Mineral& mineral = testing::fit_minerals().find(c.mineral);
    static const testing::PhotoLight light = testing::white_light();
    const ConoscopePhotoModel model = testing::photo_model(mineral, c.cut);
    testing::PhotoTruth truth;
    truth.thickness_um = c.thickness_um;
    truth.center_dx_px = c.center_dx_px;
    truth.center_dy_px = c.center_dy_px;
    truth.radius_scale = c.radius_scale;
    truth.rotation_deg = c.rotation_deg;
    truth.tilt_deg = c.tilt_deg;
    truth.gains = c.gains;
    truth.gamma = c.gamma;
    std::vector<std::uint8_t> jpeg_file;
    const Image photo = testing::synthesize_photo(model, light, truth, size_px, 11, &jpeg_file);
    ConoscopeFitOptions options;
    // As the CLI does: the encoding read from the file, repeated on the best fit for its systematic error.
    const JpegEncoding file_encoding = jpeg_encoding_of(jpeg_file, "photo.jpg").value();
    options.photo_encoding = encoding ? encoding : [file_encoding](const Image& image) { return encode_like_jpeg(image, file_encoding); };
    options.initial = default_photo_parameters(size_px, size_px);
    const double start_um = c.thickness_um * c.start_factor;
    at(options.initial, PhotoParameter::thickness_um) = start_um;
    at(options.initial, PhotoParameter::tilt_deg) = c.tilt_deg;  // the orientation is known
    options.thickness_min_um = start_um / 3.0;
    options.thickness_max_um = start_um * 3.0;
    options.free = testing::microscope_unknowns();
    options.free[static_cast<std::size_t>(PhotoParameter::tilt_deg)] = false;
    options.free[static_cast<std::size_t>(PhotoParameter::azimuth_deg)] = false;
    if (c.fix_scale) {
        options.free[static_cast<std::size_t>(PhotoParameter::field_radius_px)] = false;
        at(options.initial, PhotoParameter::field_radius_px) = c.radius_scale * 0.5 * size_px;
    }
    const auto started = std::chrono::steady_clock::now();
    ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    return {std::move(result), truth, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()};
}

class ConoscopeFitTest : public ::testing::TestWithParam<FitCase> {};

TEST_P(ConoscopeFitTest, ThicknessWithinOnePercentAndTwoSigma) {
    const FitCase& c = GetParam();
    const int size_px = c.size_px;
    const Fitted fitted = fit_synthetic(c, size_px);
    const ConoscopeFitResult& result = fitted.result;
    const FittedValue& thickness = result.parameters[static_cast<std::size_t>(PhotoParameter::thickness_um)];
    const double shift = result.encoding_shift ? (*result.encoding_shift)[0] : 0.0;
    std::printf("%s %g um, %d px: fitted %.4f um, 1 sigma %.4g (JPEG shift %+.4g), error %+.3f%%, R2 %.4f, %d iterations, %zu candidates, %.1f s\n",
                c.mineral, c.thickness_um, size_px, thickness.value, thickness.sigma.value_or(-1.0), shift,
                100.0 * (thickness.value / c.thickness_um - 1.0), result.explained_variance, result.iterations, result.candidates.size(),
                fitted.seconds);
    ASSERT_TRUE(result.acceptable) << result.verdict;
    ASSERT_TRUE(thickness.identifiable);
    ASSERT_TRUE(thickness.sigma.has_value());
    EXPECT_NEAR(thickness.value, c.thickness_um, 0.01 * c.thickness_um);
    EXPECT_LE(std::abs(thickness.value - c.thickness_um), 2.0 * *thickness.sigma);
    // The nuisance parameters come back too (centre within a pixel, rotation within a degree).
    const double half = 0.5 * size_px;
    EXPECT_NEAR(at(result.values, PhotoParameter::center_x_px), half + c.center_dx_px, 1.0);
    EXPECT_NEAR(at(result.values, PhotoParameter::center_y_px), half + c.center_dy_px, 1.0);
    EXPECT_NEAR(std::remainder(at(result.values, PhotoParameter::rotation_deg) - c.rotation_deg, 180.0), 0.0, 1.0);
}

// Each path of the fit once, in every CI run and its sanitizer build: a centred uniaxial figure with
// the scale known, an off-centre (tilted) uniaxial figure and a biaxial figure with the scale fitted, and a
// figure a fifth of the frame off its centre and cut by its edge, which the fit finds by itself (the start is
// the frame's centre).
INSTANTIATE_TEST_SUITE_P(
    Figures, ConoscopeFitTest,
    ::testing::Values(
        FitCase{"calcite", Cut::optic_axis, 10.0, 2.0, 6, -5, 0.95, 8.0, 0.0, 1.8, {1.2, 0.85, 1.1}, true},
        FitCase{"calcite", Cut::optic_axis, 100.0, 2.0, 5, -6, 1.1, 7.0, 20.0, 2.1, {1.15, 0.9, 1.05}, false},
        FitCase{"muscovite", Cut::acute_bisectrix, 30.0, 2.0, 4, 6, 0.95, 9.0, 0.0, 2.2, {1.1, 0.95, 0.85}, false},
        FitCase{"calcite", Cut::optic_axis, 30.0, 2.0, 40, -30, 1.0, 7.0, 0.0, 2.1, {1.15, 0.9, 1.05}, false, 192}));

// The rest of the acceptance cases, slower (the release run, docs/testing.md): thick and tilted quartz,
// thicker muscovite, and the cases where the photo's JPEG encoding dominates the error.
INSTANTIATE_TEST_SUITE_P(
    AcceptanceFigures, ConoscopeFitTest,
    ::testing::Values(
        FitCase{"quartz", Cut::optic_axis, 2000.0, 0.5, 7, 2, 0.9, 5.0, 0.0, 2.3, {1.2, 0.9, 0.85}, true},
        FitCase{"quartz", Cut::optic_axis, 1000.0, 0.5, -6, 3, 0.93, -4.0, 25.0, 1.9, {0.8, 1.0, 1.15}, false},
        FitCase{"muscovite", Cut::acute_bisectrix, 300.0, 0.5, -7, -3, 1.06, -8.0, 0.0, 1.8, {0.9, 1.2, 1.0}, false},
        // Where JPEG's error dominates. Its 4:2:0 chroma subsampling and quantization blur the colours
        // more than the brightness, which the model's one blur cannot follow; the error is alike over the
        // whole figure, so the statistical 1σ does not see it: without the encoding check these four land
        // 2.3 … 8.8 statistical σ off (quartz 300 µm +0.021%, 1σ 0.022 µm; calcite 300 µm −0.22%, 0.074 µm;
        // calcite 2 mm −0.30%, 1.05 µm; muscovite 2 mm +0.22%, 1.9 µm). The encoding check measures the
        // shift by repeating the JPEG on the best fit (docs/fitting.md) and adds it to the 1σ.
        FitCase{"quartz", Cut::optic_axis, 300.0, 2.0, -4, -8, 1.08, -9.0, 0.0, 2.0, {0.9, 1.1, 1.0}, true},
        FitCase{"calcite", Cut::optic_axis, 300.0, 0.5, -9, 4, 1.05, -6.0, 0.0, 2.2, {0.85, 1.0, 1.2}, true},
        // The 2 mm slabs are photographed at 512² px: in a 256² photo the rings are finer than the blur.
        // Calcite (field radius 118 px; estimates from the birefringence at 550 nm): the first ring lies
        // about 9 px from the centre and the ring spacing P ≈ r₁²/2r falls to 3.3 px at the second ring,
        // where a blur of σ² = 1.08 px² (σ = 1 px and the pixel's own 1/12 px²) leaves a contrast
        // exp(−2π²σ²/P²) of 0.14; at 512² five rings keep a contrast above 0.28 (P from 9 down to 4 px).
        // Muscovite: the rings about each melatope are about 2.5 px apart at 256² (contrast 0.03) and 5 px
        // at 512² (0.43).
        FitCase{"calcite", Cut::optic_axis, 2000.0, 0.5, 3, 10, 0.92, 10.0, 0.0, 2.4, {1.1, 1.15, 0.8}, true, 512},
        FitCase{"muscovite", Cut::acute_bisectrix, 2000.0, 0.5, 2, -9, 0.97, 3.0, 0.0, 2.4, {1.0, 0.85, 1.2}, false, 512}));

// A centred uniaxial figure with the scale free: thickness and scale trade off (the ring radii fix
// thickness × scale² only), so neither may come back as a measurement.
TEST(ConoscopeFit, CentredUniaxialScaleFreeIsUnidentified) {
    const FitCase c{"calcite", Cut::optic_axis, 200.0, 1.0, 0, 0, 1.0, 0.0, 0.0, 2.2, {1.0, 1.0, 1.0}, false};
    const ConoscopeFitResult result = fit_synthetic(c, 256).result;
    const FittedValue& thickness = result.parameters[static_cast<std::size_t>(PhotoParameter::thickness_um)];
    for (const auto& warning : result.warnings) std::printf("warning: %s\n", warning.c_str());
    std::printf("thickness %.4f um, 1 sigma %.4g, identifiable %d\n", thickness.value, thickness.sigma.value_or(-1.0), thickness.identifiable ? 1 : 0);
    EXPECT_FALSE(thickness.identifiable);
    EXPECT_FALSE(thickness.sigma.has_value());
    EXPECT_FALSE(result.parameters[static_cast<std::size_t>(PhotoParameter::field_radius_px)].identifiable);
    // What it does determine, d/r² (the ring radii), comes with its 1σ and is within 1% of the truth. (Its 1σ
    // leaves out that d/r² is not exactly what the rings fix: the phase is not exactly quadratic in ξ, so the
    // ratio the fit returns moves along the valley it wanders in; here it is 2.3σ off.)
    const auto combination = std::find_if(result.warnings.begin(), result.warnings.end(),
                                          [](const std::string& w) { return w.find("thickness_um / field_radius_px^2 = ") != std::string::npos; });
    ASSERT_NE(combination, result.warnings.end());
    double ratio = 0.0, sigma = 0.0;
    const std::string_view label = "field_radius_px^2 = ";
    ASSERT_EQ(std::sscanf(combination->c_str() + combination->find(label) + label.size(), "%lf +- %lf", &ratio, &sigma), 2) << *combination;
    const double truth = c.thickness_um / std::pow(0.5 * 256, 2);
    std::printf("thickness / field radius^2: %.6g +- %.3g for %.6g\n", ratio, sigma, truth);
    EXPECT_GT(sigma, 0.0);
    EXPECT_NEAR(ratio, truth, 0.01 * truth);
}

// A photo whose thickness lies beyond the searched range (10 µm; the range 0.83–7.5 µm around a start of 2.5 µm):
// the refinement follows the cost past the range's end, from the scan's minimum nearest it, to the photo's
// thickness, and the result says that the search did not look there.
TEST(ConoscopeFit, AThicknessBeyondTheSearchedRangeIsReported) {
    const FitCase c{"calcite", Cut::optic_axis, 10.0, 0.25, 6, -5, 0.95, 8.0, 0.0, 1.8, {1.2, 0.85, 1.1}, true, 128};
    const ConoscopeFitResult result = fit_synthetic(c, c.size_px).result;
    const double thickness_um = at(result.values, PhotoParameter::thickness_um);
    for (const auto& warning : result.warnings) std::printf("warning: %s\n", warning.c_str());
    std::printf("thickness %.4f um (the range ends at 7.5 um)\n", thickness_um);
    EXPECT_GE(thickness_um, 7.5);
    EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(),
                            [](const std::string& w) { return w.find("beyond an end of the searched range (0.8333 to 7.5 um)") != std::string::npos; }));
}

// The encoding check's premise: the best fit's rendering (render_conoscope_photo) is the model the fit
// matched at its samples, so an encoding that changes nothing shifts nothing.
TEST(ConoscopeFit, EncodingCheckOfALosslessEncodingShiftsNothing) {
    const FitCase c{"muscovite", Cut::acute_bisectrix, 30.0, 2.0, 4, 6, 0.95, 9.0, 0.0, 2.2, {1.1, 0.95, 0.85}, false};
    const ConoscopeFitResult result = fit_synthetic(c, 256, [](const Image& image) { return image; }).result;
    ASSERT_TRUE(result.encoding_shift.has_value());
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const FittedValue& value = result.parameters[static_cast<std::size_t>(j)];
        if (!value.sigma) continue;
        const double shift = (*result.encoding_shift)[static_cast<std::size_t>(j)];
        std::printf("%s: shift %.3g, 1 sigma %.3g\n", std::string(photo_parameter_name(static_cast<PhotoParameter>(j))).c_str(), shift, *value.sigma);
        EXPECT_LE(std::abs(shift), 1e-3 * *value.sigma) << photo_parameter_name(static_cast<PhotoParameter>(j));
    }
}

// A camera whose colour matrix mixes the channels (its sensor's colours are not the observer's): the model's own
// photo with crosstalk of up to 6%, noise σ = 2/255, the thickness starting 1.5 times off and the colour matrix at
// the identity. The fit recovers the matrix (each term within 3σ) and the thickness (within 2σ). (On the
// realistic-camera test bed, taking the colour matrix and the look curve out of the photos moved the thicknesses
// fitted with the matrix held by up to 0.5%: docs/fitting.md.)
TEST(ConoscopeFit, CameraColourMatrixIsRecovered) {
    constexpr int kSize = 96;
    const ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find("calcite"), Cut::optic_axis);
    PhotoParameters truth = default_photo_parameters(kSize, kSize);
    at(truth, PhotoParameter::thickness_um) = 40.0;
    at(truth, PhotoParameter::center_x_px) += 3.0;
    at(truth, PhotoParameter::center_y_px) -= 2.0;
    at(truth, PhotoParameter::field_radius_px) = 42.0;
    at(truth, PhotoParameter::gain_r) = 1.1;
    at(truth, PhotoParameter::gain_b) = 0.9;
    at(truth, PhotoParameter::black_level) = 0.03;  // the noise is not clipped at black
    // Unblurred: a rendering's blur takes the phase's derivatives otherwise than the fit's samples do.
    at(truth, PhotoParameter::blur_variance_px2) = 0.0;
    const std::array<double, 6> crosstalk{0.05, -0.03, 0.04, 0.06, -0.02, 0.03};  // rg, rb, gr, gb, br, bg
    const std::size_t first = static_cast<std::size_t>(PhotoParameter::crosstalk_rg);
    std::copy(crosstalk.begin(), crosstalk.end(), truth.begin() + static_cast<std::ptrdiff_t>(first));
    Image photo = render_conoscope_photo(model, truth, kSize, kSize);
    std::mt19937 random(5);
    std::normal_distribution<float> noise(0.0f, 2.0f / 255.0f);
    for (float& value : photo.pixels) value = std::clamp(value + noise(random), 0.0f, 1.0f);

    ConoscopeFitOptions options;
    options.initial = default_photo_parameters(kSize, kSize);
    at(options.initial, PhotoParameter::thickness_um) = 60.0;
    at(options.initial, PhotoParameter::field_radius_px) = 42.0;
    options.thickness_min_um = 20.0;
    options.thickness_max_um = 180.0;
    options.free = testing::microscope_unknowns();
    for (const PhotoParameter fixed : {PhotoParameter::field_radius_px, PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}) {
        options.free[static_cast<std::size_t>(fixed)] = false;
    }
    for (std::size_t k = first; k < first + crosstalk.size(); ++k) options.free[k] = true;
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    ASSERT_TRUE(result.acceptable) << result.verdict;
    for (std::size_t k = 0; k < crosstalk.size(); ++k) {
        const FittedValue& fitted = result.parameters[first + k];
        std::printf("%s: %+.4f +- %.4f for %+.2f\n", std::string(photo_parameter_name(static_cast<PhotoParameter>(first + k))).c_str(), fitted.value,
                    fitted.sigma.value_or(-1.0), crosstalk[k]);
        ASSERT_TRUE(fitted.identifiable && fitted.sigma.has_value());
        EXPECT_LE(std::abs(fitted.value - crosstalk[k]), 3.0 * *fitted.sigma);
    }
    const FittedValue& thickness = result.parameters[static_cast<std::size_t>(PhotoParameter::thickness_um)];
    std::printf("thickness %.4f +- %.4f um for 40\n", thickness.value, thickness.sigma.value_or(-1.0));
    ASSERT_TRUE(thickness.sigma.has_value());
    EXPECT_LE(std::abs(thickness.value - 40.0), 2.0 * *thickness.sigma);
}

}  // namespace
}  // namespace petroscope
