// The photo model's real optics (issue 18): the projections of directions onto the photo and their radial
// distortion, the illumination envelope, an analyzer that is turned or leaks; each against its own formula
// or an independent computation, their derivatives against central differences, and fits of photos made by
// the conoscope renderer through those optics.
#include "bayer_mosaic.hpp"
#include "photo_cost.hpp"
#include "photo_model.hpp"
#include "camera_optics_photo.hpp"
#include "realistic_camera_case.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
using testing::index_of;

ConoscopePhotoModel calcite_model(Projection projection) {
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find("calcite"), Cut::optic_axis);
    model.projection = projection;
    return model;
}

TEST(PhotoOptics, EachProjectionFollowsItsLawAndReachesTheApertureAtTheFieldRadius) {
    for (const Projection projection : {Projection::sine, Projection::tangent, Projection::equidistant}) {
        const ConoscopePhotoModel model = calcite_model(projection);
        const double na = model.settings.numerical_aperture;
        PhotoParameters values = default_photo_parameters(200, 200);
        at(values, PhotoParameter::field_radius_px) = 80.0;
        at(values, PhotoParameter::rotation_deg) = 30.0;
        double worst = 0.0;
        for (const double distortion : {0.0, 0.08, -0.05}) {
            at(values, PhotoParameter::distortion) = distortion;
            for (const double u : {0.0, 0.3, 1.0, 1.2}) {
                // A pixel u field radii from the centre, 40° from the image's x axis (y down in the image).
                const Eigen::Vector2d pixel(100.0 + 80.0 * u * std::cos(40.0 * kDegree), 100.0 - 80.0 * u * std::sin(40.0 * kDegree));
                const Eigen::Vector2d xi = detail::pixel_direction(model, values, pixel);
                const double expected = testing::projected_xi(projection, na, u * (1.0 + distortion * u * u));
                if (expected < 0.0) {  // beyond grazing: the model's |ξ| ≥ 1 shows no light
                    EXPECT_GE(xi.norm(), 1.0);
                    continue;
                }
                worst = std::max(worst, std::abs(xi.norm() - expected));
                // The image turned by 30° counter-clockwise against the lab: the lab sees the pixel at 40° − 30°.
                if (u > 0.0) EXPECT_NEAR(std::atan2(xi.y(), xi.x()), 10.0 * kDegree, 1e-12);
            }
        }
        at(values, PhotoParameter::distortion) = 0.0;
        const Eigen::Vector2d edge = detail::pixel_direction(model, values, Eigen::Vector2d(180.0, 100.0));
        std::printf("%s: largest |xi| error %.2e, |xi| at the field radius %.15f (NA %.2f)\n", std::string(projection_name(projection)).c_str(),
                    worst, edge.norm(), na);
        EXPECT_LT(worst, 1e-14);
        EXPECT_NEAR(edge.norm(), na, 1e-15);
    }
}

TEST(PhotoOptics, DirectionDerivativesMatchCentralDifferences) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (const Projection projection : {Projection::sine, Projection::tangent, Projection::equidistant}) {
        const ConoscopePhotoModel model = calcite_model(projection);
        for (int trial = 0; trial < 20; ++trial) {
            PhotoParameters values = default_photo_parameters(200, 200);
            at(values, PhotoParameter::center_x_px) = 90.0 + 20.0 * unit(rng);
            at(values, PhotoParameter::center_y_px) = 90.0 + 20.0 * unit(rng);
            at(values, PhotoParameter::field_radius_px) = 70.0 + 40.0 * unit(rng);
            at(values, PhotoParameter::rotation_deg) = 360.0 * unit(rng);
            at(values, PhotoParameter::distortion) = 0.1 * (unit(rng) - 0.5);
            const Eigen::Vector2d pixel(200.0 * unit(rng), 200.0 * unit(rng));
            const std::array<Eigen::Vector2d, 5> analytic = detail::direction_derivatives(model, values, pixel);
            for (std::size_t j = 0; j < detail::kDirectionParameters.size(); ++j) {
                const std::size_t p = index_of(detail::kDirectionParameters[j]);
                constexpr double kStep = 1e-5;
                PhotoParameters plus = values, minus = values;
                plus[p] += kStep;
                minus[p] -= kStep;
                const Eigen::Vector2d numeric =
                    (detail::pixel_direction(model, plus, pixel) - detail::pixel_direction(model, minus, pixel)) / (2.0 * kStep);
                worst = std::max(worst, (analytic[j] - numeric).norm() / std::max(numeric.norm(), 1e-3));
            }
        }
    }
    std::printf("largest relative error of d xi / d parameter: %.2e\n", worst);
    EXPECT_LT(worst, 1e-6);
}

TEST(PhotoOptics, EnvelopeIsItsFormulaAndItsDerivativesMatchCentralDifferences) {
    ConoscopePhotoModel model = calcite_model(Projection::sine);
    PhotoParameters values = default_photo_parameters(200, 200);
    at(values, PhotoParameter::envelope_center_x_px) = 110.0;
    at(values, PhotoParameter::envelope_center_y_px) = 95.0;
    at(values, PhotoParameter::envelope_radius_px) = 70.0;
    at(values, PhotoParameter::envelope_power) = 3.5;
    const Eigen::Vector2d pixel(150.0, 60.0);
    EXPECT_EQ(detail::illumination_envelope(model, values, pixel).value, 1.0);  // even light
    model.illumination = IlluminationProfile::falloff;
    const detail::EnvelopeValue envelope = detail::illumination_envelope(model, values, pixel);
    EXPECT_NEAR(envelope.value, std::exp(-std::pow(std::hypot(40.0, 35.0) / 70.0, 3.5)), 1e-15);
    for (std::size_t e = 0; e < 4; ++e) {
        const std::size_t p = index_of(PhotoParameter::envelope_center_x_px) + e;
        constexpr double kStep = 1e-5;
        PhotoParameters plus = values, minus = values;
        plus[p] += kStep;
        minus[p] -= kStep;
        const double numeric =
            (detail::illumination_envelope(model, plus, pixel).value - detail::illumination_envelope(model, minus, pixel).value) / (2.0 * kStep);
        EXPECT_NEAR(envelope.derivatives[e], numeric, 1e-8 * std::max(1.0, std::abs(numeric))) << "envelope parameter " << e;
    }
    // At the envelope's centre, for p = 2 (where (r²)^(p/2 − 1) is 0⁰): light 1, every derivative finite and 0.
    at(values, PhotoParameter::envelope_power) = 2.0;
    const detail::EnvelopeValue centre = detail::illumination_envelope(model, values, Eigen::Vector2d(110.0, 95.0));
    EXPECT_EQ(centre.value, 1.0);
    for (const double d : centre.derivatives) EXPECT_EQ(d, 0.0);
}

TEST(PhotoOptics, AnAnalyzerThatPassesWhatItShouldBlockShowsTheLightWithoutAnalyzer) {
    // Extinction ratio 1: the analyzer passes both vibrations fully, so passed + blocked must be the
    // figure without an analyzer, computed on its own, at every wavelength, point and thickness.
    const ConoscopePhotoModel model = calcite_model(Projection::sine);
    PhotoParameters values = default_photo_parameters(64, 64);
    at(values, PhotoParameter::analyzer_offset_deg) = 7.0;
    const detail::PhotoModelEvaluator evaluator(model, detail::sample_lattice({32.0, 32.0}, 30.0, 4, 64, 64));
    detail::AnalyzerTerms parts;
    evaluator.analyzer_terms(values, true, parts);
    std::vector<InterferenceTerms> leaked;
    detail::leaked_terms(parts, 1.0, leaked);
    ConoscopeSettings open = model.settings;
    open.crystal_axes = model.orientation(0.0, 0.0);
    open.analyzer_in = false;
    std::vector<Eigen::Vector2d> xis;
    for (const Eigen::Vector2d& pixel : evaluator.lattice().pixels) xis.push_back(detail::pixel_direction(model, values, pixel));
    std::vector<InterferenceTerms> without_analyzer;
    ConoscopeTerms(open, model.principal_n).evaluate(xis, without_analyzer);
    ASSERT_EQ(leaked.size(), without_analyzer.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < leaked.size(); ++k) {
        EXPECT_EQ(parts.passed[k].phase_per_um, parts.blocked[k].phase_per_um);
        for (const double d : {10.0, 100.0, 1000.0}) worst = std::max(worst, std::abs(leaked[k].transmission(d) - without_analyzer[k].transmission(d)));
    }
    std::printf("%zu terms: largest difference %.2e\n", leaked.size(), worst);
    EXPECT_LT(worst, 1e-12);
}

TEST(PhotoOptics, APixelCrossingGrazingGoesDarkWithoutMovingItsNeighboursPhaseDerivatives) {
    // Sine projection: |ξ| = NA·r/R reaches 1 at r = R/NA. The pixel 60 px right of the centre is put
    // 0.01 px inside that horizon and then 0.01 px beyond it: it goes dark, but as a neighbour in the phase's
    // difference stencils it must not step (its phase set to 0 moved its lit neighbour's gradient by Φ/2h).
    const ConoscopePhotoModel model = calcite_model(Projection::sine);
    const double na = model.settings.numerical_aperture;
    const detail::PhotoModelEvaluator evaluator(model, detail::sample_lattice({50.5, 50.5}, 40.0, 2, 100, 100));
    const auto index_at = [&](const Eigen::Vector2d& pixel) {
        const auto& pixels = evaluator.lattice().pixels;
        return static_cast<std::size_t>(std::find(pixels.begin(), pixels.end(), pixel) - pixels.begin());
    };
    const std::size_t crossing = index_at({80.5, 50.5}), lit = index_at({78.5, 50.5});
    ASSERT_LT(crossing, evaluator.sample_count());
    ASSERT_LT(lit, evaluator.sample_count());
    ASSERT_EQ(evaluator.lattice().neighbours[lit][1], static_cast<int>(crossing));
    const std::size_t w_count = evaluator.wavelength_count();
    std::array<detail::PhaseDerivatives, 2> phase;
    for (int side = 0; side < 2; ++side) {
        PhotoParameters values = default_photo_parameters(100, 100);
        at(values, PhotoParameter::field_radius_px) = 60.0 * na;
        at(values, PhotoParameter::center_x_px) = 20.5 + (side == 0 ? 0.01 : -0.01);
        at(values, PhotoParameter::center_y_px) = 50.5;
        std::vector<InterferenceTerms> terms;
        evaluator.terms(values, terms);
        evaluator.phase_derivatives(terms, phase[static_cast<std::size_t>(side)]);
        const InterferenceTerms& seen = terms[crossing * w_count];
        EXPECT_EQ(detail::shows_no_light(seen), side == 1) << "side " << side;
        EXPECT_TRUE(std::isfinite(seen.phase_per_um) && seen.phase_per_um != 0.0) << "side " << side;
    }
    double worst = 0.0;
    for (std::size_t w = 0; w < w_count; ++w) {
        const std::size_t i = lit * w_count + w;
        const double scale = std::hypot(phase[0].gradient_x[i], phase[0].gradient_y[i]);
        worst = std::max(worst, std::abs(phase[1].gradient_x[i] - phase[0].gradient_x[i]) / scale);
    }
    // The 0.02-px move itself changes the gradient there by 8e-4 (linear in the move: 2e-4 for 0.005 px); the step
    // to a phase of 0 was 6.1.
    std::printf("the lit neighbour's phase gradient moved by %.2e of itself\n", worst);
    EXPECT_LT(worst, 1e-2);
}

/// Whether the cost takes this parameter's derivative by a forward difference (through ξ or the terms).
bool forward_difference(std::size_t p) {
    return (p >= index_of(PhotoParameter::center_x_px) && p <= index_of(PhotoParameter::azimuth_deg)) || p == index_of(PhotoParameter::distortion) ||
           p == index_of(PhotoParameter::analyzer_offset_deg);
}

/// Each column of the cost's Jacobian at `values` against central differences of its residuals: the
/// relative difference |J_p − ΔR/Δp| / |ΔR/Δp| per parameter.
std::array<double, kPhotoParameterCount> jacobian_differences(const ConoscopePhotoModel& model, const PhotoParameters& values) {
    constexpr int kSize = 48;
    // The photo: the model itself at other values, so that the residuals are not zero.
    PhotoParameters other = values;
    at(other, PhotoParameter::thickness_um) += 1.0;
    at(other, PhotoParameter::envelope_radius_px) += 3.0;
    const Image photo = render_conoscope_photo(model, other, kSize, kSize);
    const detail::PhotoLevel level(model, detail::sample_lattice({24.0, 24.0}, 22.0, 2, kSize, kSize), photo, 0.0, 2.2, 0.995);
    PhotoParameterFlags free{};
    free.fill(true);
    const detail::PhotoCost cost(level, free, 0.05);
    const auto rows = static_cast<std::size_t>(cost.num_residuals());
    std::vector<double> residuals(rows), jacobian(rows * kPhotoParameterCount), plus(rows), minus(rows);
    const double* parameters = values.data();
    double* jacobian_block = jacobian.data();
    std::array<double, kPhotoParameterCount> result{};
    if (!cost.Evaluate(&parameters, residuals.data(), &jacobian_block)) return result;
    for (std::size_t p = 0; p < kPhotoParameterCount; ++p) {
        // Steps: small for the analytic columns, larger where the cost's own derivative is a forward
        // difference (ξ, the crystal's and analyzer's angles), whose truncation error it then dominates; the
        // distortion moves the outer fringes by hundreds of radians per unit, so its step stays small.
        const double step = p == index_of(PhotoParameter::distortion) ? 1e-5 : forward_difference(p) ? 1e-3 : 1e-6;
        PhotoParameters up = values, down = values;
        up[p] += step;
        down[p] -= step;
        const double* up_block = up.data();
        const double* down_block = down.data();
        if (!cost.Evaluate(&up_block, plus.data(), nullptr) || !cost.Evaluate(&down_block, minus.data(), nullptr)) return {};
        double difference2 = 0.0, norm2 = 0.0;
        for (std::size_t row = 0; row < rows; ++row) {
            const double numeric = (plus[row] - minus[row]) / (2.0 * step);
            difference2 += std::pow(jacobian[row * kPhotoParameterCount + p] - numeric, 2);
            norm2 += numeric * numeric;
        }
        result[p] = std::sqrt(difference2 / std::max(norm2, 1e-300));
        std::printf("%-22s |J| %.3e, relative difference %.2e\n", std::string(photo_parameter_name(static_cast<PhotoParameter>(p))).c_str(),
                    std::sqrt(norm2), result[p]);
    }
    return result;
}

TEST(PhotoCost, JacobianMatchesCentralDifferencesWithEveryOpticsTermFree) {
    ConoscopePhotoModel model = calcite_model(Projection::tangent);
    model.illumination = IlluminationProfile::falloff;
    PhotoParameters values = default_photo_parameters(48, 48);
    at(values, PhotoParameter::thickness_um) = 40.0;
    at(values, PhotoParameter::tilt_deg) = 5.0;
    at(values, PhotoParameter::rotation_deg) = 10.0;
    at(values, PhotoParameter::envelope_radius_px) = 30.0;
    at(values, PhotoParameter::envelope_power) = 3.0;
    at(values, PhotoParameter::envelope_center_x_px) = 20.0;
    at(values, PhotoParameter::distortion) = 0.04;
    at(values, PhotoParameter::analyzer_offset_deg) = 3.0;
    at(values, PhotoParameter::extinction_ratio) = 0.01;
    const std::array<double, 6> crosstalk{0.03, -0.02, 0.01, 0.04, -0.03, 0.02};
    std::copy(crosstalk.begin(), crosstalk.end(), values.begin() + static_cast<std::ptrdiff_t>(index_of(PhotoParameter::crosstalk_rg)));
    // A linear camera: x^(1/γ) curves so sharply near black (the isogyres) that central differences of
    // the residuals there measure the curve, not the optics.
    at(values, PhotoParameter::gamma) = 1.0;
    // Without blur and with it (σ² = 1 px²: the geometry then also moves the phase's derivatives over the
    // photo, on which the fringe blur depends, and the envelope moves the figure's sampling point). Before
    // the cost followed the first, the geometry's columns differed by 3–14% (distortion 20%) with blur.
    for (const double blur2 : {0.0, 1.0}) {
        at(values, PhotoParameter::blur_variance_px2) = blur2;
        std::printf("blur variance %g px^2:\n", blur2);
        const std::array<double, kPhotoParameterCount> differences = jacobian_differences(model, values);
        for (std::size_t p = 0; p < kPhotoParameterCount; ++p) {
            EXPECT_LT(differences[p], forward_difference(p) ? 2e-3 : 1e-5) << photo_parameter_name(static_cast<PhotoParameter>(p)) << ", blur " << blur2;
            EXPECT_GT(differences[p], 0.0) << "the cost refused a point";
        }
    }
}

struct OpticsCase {
    const char* mineral;
    Cut cut;
    testing::OpticsTruth truth;
    bool polars_and_distortion_free;  // fit the analyzer's offset, the extinction ratio and the distortion too
    int size_px = 128;
};

void PrintTo(const OpticsCase& c, std::ostream* os) {
    *os << c.mineral << " " << c.truth.thickness_um << " um, " << projection_name(c.truth.projection);
}

class RealOpticsFitTest : public ::testing::TestWithParam<OpticsCase> {};

/// With PETROSCOPE_TEST_PHOTOS naming a folder, the case's photo goes there as a JPEG file
/// (MINERAL-THICKNESSum-PROJECTION-SIZEpx.jpg), to look at or to fit with the command line (docs/fitting.md shows one).
void save_test_photo(const OpticsCase& c, const std::vector<std::uint8_t>& jpeg_file) {
    const char* folder = std::getenv("PETROSCOPE_TEST_PHOTOS");
    if (folder == nullptr) return;
    const std::string name = std::string(c.mineral) + "-" + format_significant(c.truth.thickness_um, 6) + "um-" +
                             std::string(projection_name(c.truth.projection)) + "-" + std::to_string(c.size_px) + "px.jpg";
    std::ofstream file(std::filesystem::path(folder) / name, std::ios::binary);
    file.write(reinterpret_cast<const char*>(jpeg_file.data()), static_cast<std::streamsize>(jpeg_file.size()));
    ASSERT_TRUE(file.good()) << "could not write " << name << " into " << folder;
}

// A photo with no field stop, the figure larger than the frame and off its centre, the light falling off
// about another centre, the analyzer turned and leaking, the camera's white balance and tone curve off,
// blur, noise and JPEG; the scale is known (a centred figure fixes only thickness × scale² otherwise). The
// fit models every one of these, with the photo's projection: the thickness must come out within 2% and
// within its 2σ.
TEST_P(RealOpticsFitTest, ThicknessWithinTwoPercentAndTwoSigma) {
    const OpticsCase& c = GetParam();
    const int kSize = c.size_px;
    // The cases are written for 128² photos; a smaller photo shows the same figure and light, scaled.
    const testing::OpticsTruth truth = testing::scaled_truth(c.truth, kSize / 128.0);
    static const testing::PhotoLight light = testing::white_light();
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find(c.mineral), c.cut);
    std::vector<std::uint8_t> jpeg_file;
    const Image photo = testing::photo_through_optics(model, light, truth, kSize, 3, &jpeg_file);
    save_test_photo(c, jpeg_file);

    ConoscopeFitOptions options = testing::real_optics_fit(model, truth, jpeg_file, kSize);
    const double start_um = 2.0 * truth.thickness_um;
    at(options.initial, PhotoParameter::thickness_um) = start_um;
    options.thickness_min_um = start_um / 3.0;
    options.thickness_max_um = start_um * 3.0;
    options.free.fill(true);
    for (const PhotoParameter fixed : {PhotoParameter::field_radius_px, PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}) {
        options.free[index_of(fixed)] = false;
    }
    // The camera has no colour crosstalk (ConoscopeFit.CameraColourMatrixIsRecovered fits one).
    for (std::size_t k = index_of(PhotoParameter::crosstalk_rg); k <= index_of(PhotoParameter::crosstalk_bg); ++k) options.free[k] = false;
    for (const PhotoParameter p : {PhotoParameter::distortion, PhotoParameter::analyzer_offset_deg, PhotoParameter::extinction_ratio}) {
        options.free[index_of(p)] = c.polars_and_distortion_free;
    }
    const auto started = std::chrono::steady_clock::now();
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const auto value = [&](PhotoParameter p) { return at(result.values, p); };
    const double shift = result.encoding_shift ? (*result.encoding_shift)[0] : 0.0;
    std::printf("%s %g um, %s projection: fitted %.4f um, 1 sigma %.4g (JPEG shift %+.4g), error %+.3f%%, R2 %.4f; centre (%+.2f, %+.2f) px for (%+g, %+g); "
                "envelope centre (%+.1f, %+.1f) px for (%+g, %+g), radius %.1f px for %g, power %.2f for %g; analyzer %+.2f deg for %+g; "
                "extinction %.4f for %g; distortion %+.4f for %+g; %d iterations, %.1f s\n",
                c.mineral, truth.thickness_um, std::string(projection_name(truth.projection)).c_str(), thickness.value,
                thickness.sigma.value_or(-1.0), shift, 100.0 * (thickness.value / truth.thickness_um - 1.0), result.explained_variance,
                value(PhotoParameter::center_x_px) - 0.5 * kSize, value(PhotoParameter::center_y_px) - 0.5 * kSize, truth.center_dx_px,
                truth.center_dy_px, value(PhotoParameter::envelope_center_x_px) - 0.5 * kSize, value(PhotoParameter::envelope_center_y_px) - 0.5 * kSize,
                truth.envelope_dx_px, truth.envelope_dy_px, value(PhotoParameter::envelope_radius_px), truth.envelope_radius_px,
                value(PhotoParameter::envelope_power), truth.envelope_power, value(PhotoParameter::analyzer_offset_deg), truth.analyzer_offset_deg,
                value(PhotoParameter::extinction_ratio), truth.extinction_ratio, value(PhotoParameter::distortion), truth.distortion,
                result.iterations, seconds);
    ASSERT_TRUE(result.acceptable) << result.verdict;
    ASSERT_TRUE(thickness.identifiable);
    ASSERT_TRUE(thickness.sigma.has_value());
    EXPECT_NEAR(thickness.value, truth.thickness_um, 0.02 * truth.thickness_um);
    EXPECT_LE(std::abs(thickness.value - truth.thickness_um), 2.0 * *thickness.sigma);
    EXPECT_NEAR(value(PhotoParameter::center_x_px), 0.5 * kSize + truth.center_dx_px, 1.0);
    EXPECT_NEAR(value(PhotoParameter::center_y_px), 0.5 * kSize + truth.center_dy_px, 1.0);
}

testing::OpticsTruth optics(double thickness_um, Projection projection, double dx, double dy, double rotation_deg, double distortion,
                            double analyzer_deg, double extinction, Eigen::Vector3d gains, double gamma) {
    testing::OpticsTruth truth;
    truth.thickness_um = thickness_um;
    truth.projection = projection;
    truth.center_dx_px = dx;
    truth.center_dy_px = dy;
    truth.field_radius_px = 70.0;
    truth.rotation_deg = rotation_deg;
    truth.distortion = distortion;
    truth.envelope_dx_px = -0.7 * dx + 5.0;
    truth.envelope_dy_px = 0.5 * dy - 4.0;
    truth.envelope_radius_px = 75.0;
    truth.envelope_power = 2.5;
    truth.analyzer_offset_deg = analyzer_deg;
    truth.extinction_ratio = extinction;
    truth.gains = gains;
    truth.gamma = gamma;
    return truth;
}

// Every path of the real-optics model once, in every CI run and its sanitizer build: a tangent projection,
// no field stop, the light falling off (the polars and the distortion are fitted in the release run's cases).
INSTANTIATE_TEST_SUITE_P(
    Optics, RealOpticsFitTest,
    ::testing::Values(OpticsCase{"calcite", Cut::optic_axis, optics(50.0, Projection::tangent, -9.0, 6.0, 6.0, 0.0, 0.0, 0.0, {1.15, 0.9, 1.05}, 2.0),
                                 false, 96}));

// Slower (the release run, docs/testing.md): every term free, the analyzer turned and leaking, no field
// stop, a tangent projection (the equidistant one is among the known failures below). Quartz 400 µm was a known
// failure (+0.074%, 2.09σ) until the figure's terms came from the spectral nodes (+0.067%, 1.64σ).
INSTANTIATE_TEST_SUITE_P(
    AcceptanceOptics, RealOpticsFitTest,
    ::testing::Values(
        OpticsCase{"calcite", Cut::optic_axis, optics(50.0, Projection::tangent, -12.0, 8.0, 6.0, 0.0, 2.0, 0.002, {1.15, 0.9, 1.05}, 2.0), true},
        OpticsCase{"quartz", Cut::optic_axis, optics(400.0, Projection::tangent, -8.0, -11.0, 4.0, 0.0, 1.5, 0.001, {0.85, 1.0, 1.2}, 1.9), true}));

// Known failures, kept runnable (--gtest_also_run_disabled_tests) until the model handles them (issue 18
// stays open); both within 2% but outside their 2σ (measured with the figure's terms from the spectral nodes).
// Muscovite 60 µm through a sine projection with a pincushion distortion of 0.04: +0.41%, R² 0.98 (the frame
// reaches |ξ| → 1, where the sine projection packs the fringes of grazing light into a few pixels, finer than the
// pixel, and a camera's pixels average them in a way the model's blur does not follow; through a tangent projection
// the same photo came out −0.13%, 4σ); its 1σ, 0.015 µm, is 17 times smaller than the error because the encoding
// check's refit barely moved (+0.002 µm; +0.053 with every wavelength solved). Calcite 150 µm through an
// equidistant projection: −1.65%, 2.9σ (−0.585%, 8.4σ with the blur's σ⁴ phase): its encoding check's refit starts
// where the cost's gradient is large (max norm 351, against 0.009 at the end of the fit on the photo itself) and every
// step is rejected, so the JPEG's part of the 1σ depends on where the trust region collapses. docs/fitting.md, "Measured through real optics".
INSTANTIATE_TEST_SUITE_P(
    DISABLED_KnownOpticsFailures, RealOpticsFitTest,
    ::testing::Values(
        OpticsCase{"calcite", Cut::optic_axis, optics(150.0, Projection::equidistant, 10.0, -9.0, -8.0, 0.0, -2.5, 0.003, {1.1, 1.0, 0.8}, 2.4),
                   true},
        OpticsCase{"muscovite", Cut::acute_bisectrix, optics(60.0, Projection::sine, 9.0, 10.0, -5.0, 0.04, -3.0, 0.004, {0.9, 1.1, 0.95}, 2.3),
                   true}));

// Frees the figure's, the camera's and the light's terms (thickness … envelope power) but the scale and the tilt.
void free_figure_and_light_but_scale_and_tilt(ConoscopeFitOptions& options) {
    for (std::size_t k = 0; k <= index_of(PhotoParameter::envelope_power); ++k) options.free[k] = true;
    for (const PhotoParameter fixed : {PhotoParameter::field_radius_px, PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}) {
        options.free[index_of(fixed)] = false;
    }
}

// The fringes' second-order blur (docs/fitting.md, "Blur"): a figure of fine fringes photographed by an ideal camera
// (pure gamma, no mosaic, no JPEG) after a Gaussian blur of σ = 2 px, the geometry and light of the realistic-camera
// bed's case 10 (calcite 50.77 µm, sine projection, 24 px off centre). With the blur's phase taken to first order in
// σ² only, the thickness came out −0.343% (−22σ); with the σ⁴ term, −0.081%.
TEST(ConoscopeFit, FineFringesUnderTwoPixelsOfBlurKeepTheirThickness) {
    const testing::CameraCase bed_case = testing::random_case(10, 128);
    testing::OpticsTruth truth = bed_case.optics;
    truth.blur_px = 2.0;
    truth.jpeg_quality = 0;
    truth.gains = {1.0, 0.95, 1.05};
    static const testing::PhotoLight light = testing::white_light();
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find(bed_case.mineral.mineral), bed_case.mineral.cut);
    const Image photo = testing::photo_through_optics(model, light, truth, 128, 7);
    ConoscopeFitOptions options = testing::real_optics_fit(model, truth, {}, 128);  // no JPEG: no encoding check
    free_figure_and_light_but_scale_and_tilt(options);
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const double error = thickness.value / truth.thickness_um - 1.0;
    std::printf("calcite %.2f um under a blur of 2 px: fitted %.4f um +- %.4f, error %+.3f%%, blur fitted %.3f px\n", truth.thickness_um,
                thickness.value, thickness.sigma.value_or(-1.0), 100.0 * error, std::sqrt(at(result.values, PhotoParameter::blur_variance_px2)));
    ASSERT_TRUE(result.acceptable) << result.verdict;
    EXPECT_LT(std::abs(error), 0.0015);  // the next order leaves −0.08%; without the σ⁴ term −0.34%
}


// Issue 18, item 2: the scale unknown. A biaxial figure off the frame's centre through a tangent projection, no field
// stop, the scale started at the default half frame (40 px for 49.7; the geometry and light of the realistic-camera
// bed's case 3 at 80², an ideal camera). The melatopes' distance fixes the scale, and the thickness search at several
// scales finds it; with the search at the starting scale only, this fit ended at 40.2 px and 71.44 µm (R² 0.89).
// The thickness is asserted within 2%, not within 2σ: it comes out 3.7σ low (70.672 ± 0.040 µm), and 4σ low with the
// scale known on the same camera's 96² photo (70.792 ± 0.008 µm), a small model error (docs/fitting.md, "What fails").
TEST(ConoscopeFit, BiaxialFigureOfUnknownScaleIsFoundFromTheSearchAtSeveralScales) {
    constexpr int kSize = 80;
    const testing::CameraCase bed_case = testing::random_case(3, 128);
    testing::OpticsTruth truth = testing::scaled_truth(bed_case.optics, kSize / 128.0);
    truth.jpeg_quality = 0;
    truth.gains = {1.05, 0.95, 1.0};
    static const testing::PhotoLight light = testing::white_light();
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find(bed_case.mineral.mineral), bed_case.mineral.cut);
    const Image photo = testing::photo_through_optics(model, light, truth, kSize, 5);
    ConoscopeFitOptions options = testing::real_optics_fit(model, truth, {}, kSize);  // no JPEG: no encoding check
    options.initial = default_photo_parameters(kSize, kSize);
    options.thickness_min_um = 25.0;
    options.thickness_max_um = 200.0;
    for (std::size_t k = 0; k <= index_of(PhotoParameter::envelope_power); ++k) options.free[k] = true;
    for (const PhotoParameter fixed : {PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}) options.free[index_of(fixed)] = false;
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const double radius_px = at(result.values, PhotoParameter::field_radius_px);
    std::printf("aragonite %.2f um, scale unknown: fitted %.4f um +- %.4f, field radius %.2f px for %.2f, R2 %.4f\n", truth.thickness_um, thickness.value,
                thickness.sigma.value_or(-1.0), radius_px, truth.field_radius_px, result.explained_variance);
    ASSERT_TRUE(result.acceptable) << result.verdict;
    ASSERT_TRUE(thickness.identifiable);
    EXPECT_NEAR(thickness.value, truth.thickness_um, 0.02 * truth.thickness_um);
    EXPECT_NEAR(radius_px, truth.field_radius_px, 0.01 * truth.field_radius_px);
}

// The Bayer sensor's check (docs/fitting.md, "The camera's sensor"): the model's own photo of the realistic-camera
// bed's case 16 (quartz 333.17 µm, centred, sine projection) at 64², through an RGGB mosaic and bilinear
// demosaicing and nothing else, so that the thickness's whole error is the mosaic's. The check, which puts the best
// fit through the same mosaic and fits it again, measures it: the thickness came out −0.283 µm off (−0.085%) and the
// check's shift −0.252 µm, which takes its 1σ from 0.027 to 0.253 µm (10.6σ off without the check, 1.1σ with it).
// Left out of the sanitizer build (3.7 s in release), which tests the mosaic and the refit it shares with the encoding check.
TEST(ConoscopeFit, TheMosaicCheckMeasuresWhatABayerSensorDoesToTheModelsOwnPhoto) {
    constexpr int kSize = 64;
    const testing::CameraCase bed_case = testing::random_case(16, 128);
    const testing::OpticsTruth truth = testing::scaled_truth(bed_case.optics, kSize / 128.0);  // centred: the centre stays
    ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find(bed_case.mineral.mineral), bed_case.mineral.cut);
    ConoscopeFitOptions options = testing::real_optics_fit(model, truth, {}, kSize);
    PhotoParameters& values = options.initial;
    at(values, PhotoParameter::thickness_um) = truth.thickness_um;
    at(values, PhotoParameter::rotation_deg) = truth.rotation_deg;
    at(values, PhotoParameter::envelope_center_x_px) += truth.envelope_dx_px;
    at(values, PhotoParameter::envelope_center_y_px) += truth.envelope_dy_px;
    at(values, PhotoParameter::envelope_radius_px) = truth.envelope_radius_px;
    at(values, PhotoParameter::envelope_power) = truth.envelope_power;
    at(values, PhotoParameter::blur_variance_px2) = truth.blur_px * truth.blur_px;
    const Image photo = detail::through_bayer_mosaic(render_conoscope_photo(model, values, kSize, kSize), at(values, PhotoParameter::black_level),
                                                     at(values, PhotoParameter::gamma));
    options.thickness_min_um = 250.0;
    options.thickness_max_um = 450.0;
    options.sensor = ColourSensor::bayer;
    free_figure_and_light_but_scale_and_tilt(options);
    const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    ASSERT_TRUE(result.acceptable) << result.verdict;
    ASSERT_TRUE(result.mosaic_shift.has_value());
    EXPECT_FALSE(result.encoding_shift.has_value());  // a photo given without its encoding: only the mosaic is checked
    const double error_um = thickness.value - truth.thickness_um, shift_um = (*result.mosaic_shift)[index_of(PhotoParameter::thickness_um)];
    std::printf("quartz %.2f um through a Bayer mosaic: fitted %.4f um +- %.4f (error %+.4f um), the mosaic check's shift %+.4f um\n",
                truth.thickness_um, thickness.value, thickness.sigma.value_or(-1.0), error_um, shift_um);
    EXPECT_LT(std::abs(error_um), 0.002 * truth.thickness_um);
    EXPECT_NEAR(shift_um, error_um, 0.25 * std::abs(error_um));  // the check finds the mosaic's shift
    ASSERT_TRUE(thickness.sigma.has_value());
    EXPECT_LT(std::abs(error_um), 2.0 * *thickness.sigma);
    for (std::size_t k = 0; k < kPhotoParameterCount; ++k) {
        if (!options.free[k]) EXPECT_EQ((*result.mosaic_shift)[k], 0.0) << photo_parameter_name(static_cast<PhotoParameter>(k));
    }
}

// Item 2, a slightly tilted cut: the realistic-camera bed's case 6 (quartz 2.9 mm, sine projection, 24 px off the
// frame's centre; its camera, JPEG 75) with the optic axis tilted by 7° toward 275°, the tilt fitted from 0. The fit
// starts at the figure's centre of symmetry (docs/fitting.md, "Finding the figure"); from the frame's centre, as it
// did before with the tilt free, it ended at 596 µm with the figure 190 px out of the frame, refused. Measured:
// 2901.2 ± 20.4 µm (+0.41%), tilt 7.04° toward −81° (279°). In the sanitizer build it is left out (13 s in release).
TEST(ConoscopeFit, ASlightlyTiltedOpticAxisIsFoundWhereItsFigureLies) {
    constexpr int kSize = 128;
    const testing::CameraCase c = testing::tilted_case(6, testing::random_case(6, kSize));
    const testing::CameraCasePhoto shot = testing::photograph_case(6, c, kSize, testing::Scale::known, testing::Tilt::free);
    const ConoscopeFitResult result = fit_conoscope_photo(shot.photo, shot.model, shot.options);
    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    // A tilt of −t toward φ is a tilt of t toward φ + 180°.
    double tilt_deg = at(result.values, PhotoParameter::tilt_deg), azimuth_deg = at(result.values, PhotoParameter::azimuth_deg);
    if (tilt_deg < 0.0) {
        tilt_deg = -tilt_deg;
        azimuth_deg += 180.0;
    }
    const double azimuth_error_deg = std::remainder(azimuth_deg - c.optics.azimuth_deg, 360.0);
    std::printf("quartz %.2f um tilted %.2f deg toward %.0f: fitted %.3f um +- %.3g, tilt %.2f deg toward %.1f, R2 %.4f\n", c.optics.thickness_um,
                c.optics.tilt_deg, c.optics.azimuth_deg, thickness.value, thickness.sigma.value_or(-1.0), tilt_deg, azimuth_deg, result.explained_variance);
    ASSERT_TRUE(result.acceptable) << result.verdict;
    EXPECT_NEAR(thickness.value, c.optics.thickness_um, 0.02 * c.optics.thickness_um);
    EXPECT_NEAR(tilt_deg, c.optics.tilt_deg, 0.5);
    EXPECT_LT(std::abs(azimuth_error_deg), 10.0);
}

}  // namespace
}  // namespace petroscope
