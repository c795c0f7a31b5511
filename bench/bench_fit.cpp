// Fitting a 512² white-light photo of a conoscopic figure with every nuisance parameter free (thickness,
// centre, scale, rotation, white balance, black level, gamma, blur): the photo is synthesised once
// (tests/fit/synthetic_photo.hpp: muscovite 300 µm, centre and scale off, camera turned, JPEG 85), with
// and without the check of the JPEG encoding's systematic error. Then issue 18's speed goal: the realistic-camera
// test bed's twenty cases (realistic_camera_case.hpp) at 512², thickness unknown (the default 5 µm – 5 mm
// search), every nuisance free; and one evaluation of the fit's cost with its Jacobian, most of a refinement's work.
// Last, the orthoscope fit of one grain from three photos (tests/fit/grain_photo.hpp) in each orientation mode.
#include "grain_photo.hpp"
#include "photo_cost.hpp"
#include "realistic_camera_case.hpp"
#include "synthetic_photo.hpp"

#include "petroscope/io/jpeg_encoding.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>

namespace {

using namespace petroscope;

void FitConoscopePhoto512(benchmark::State& state) {
    const Mineral& mineral = testing::fit_minerals().find("muscovite");
    const testing::PhotoLight light = testing::white_light();
    const ConoscopePhotoModel model = testing::photo_model(mineral, Cut::acute_bisectrix);
    testing::PhotoTruth truth;
    truth.thickness_um = 300.0;
    truth.center_dx_px = 14;
    truth.center_dy_px = -9;
    truth.radius_scale = 0.94;
    truth.rotation_deg = 6.0;
    truth.gains = {1.1, 0.92, 1.05};
    truth.gamma = 2.1;
    const int size_px = 512;
    std::vector<std::uint8_t> jpeg_file;
    const Image photo = testing::synthesize_photo(model, light, truth, size_px, 3, &jpeg_file);
    ConoscopeFitOptions options;
    options.initial = default_photo_parameters(size_px, size_px);
    at(options.initial, PhotoParameter::thickness_um) = 150.0;  // off by a factor of 2
    options.thickness_min_um = 50.0;
    options.thickness_max_um = 450.0;
    options.free = testing::microscope_unknowns();
    options.free[static_cast<std::size_t>(PhotoParameter::tilt_deg)] = false;
    options.free[static_cast<std::size_t>(PhotoParameter::azimuth_deg)] = false;
    // As the CLI does for a JPEG photo: the encoding's systematic error is measured too.
    const JpegEncoding encoding = jpeg_encoding_of(jpeg_file, "photo.jpg").value();
    if (state.range(0) != 0) options.photo_encoding = [encoding](const Image& image) { return encode_like_jpeg(image, encoding); };
    double thickness = 0.0;
    for (auto _ : state) {
        const ConoscopeFitResult result = fit_conoscope_photo(photo, model, options);
        thickness = at(result.values, PhotoParameter::thickness_um);
        std::fprintf(stderr, "fitted %.4f um (truth 300), acceptable %d, R2 %.4f\n", thickness, int(result.acceptable), result.explained_variance);
        benchmark::DoNotOptimize(thickness);
    }
    state.counters["thickness_um"] = thickness;
}
// Argument: 1 with the encoding check (what the CLI does for a JPEG), 0 without (a PNG or TIFF photo).
BENCHMARK(FitConoscopePhoto512)->Arg(1)->Arg(0)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

/// Case `state.range(0)` of the realistic-camera test bed, photographed at 512² (not timed) and fitted.
void FitRealisticCamera512(benchmark::State& state) {
    constexpr int kSize = 512;
    const int index = static_cast<int>(state.range(0));
    const testing::CameraCase c = testing::random_case(index, kSize);
    const testing::CameraCasePhoto shot = testing::photograph_case(index, c, kSize);
    double error_percent = 0.0;
    for (auto _ : state) {
        const ConoscopeFitResult result = fit_conoscope_photo(shot.photo, shot.model, shot.options);
        const FittedValue& thickness = result.parameters[testing::index_of(PhotoParameter::thickness_um)];
        error_percent = 100.0 * (thickness.value / c.optics.thickness_um - 1.0);
        std::fprintf(stderr, "case %d, %s %.2f um: fitted %.3f um +- %.3g (%+.3f%%), %s, R2 %.4f\n", index, c.mineral.mineral,
                     c.optics.thickness_um, thickness.value, thickness.sigma.value_or(0.0), error_percent,
                     result.acceptable ? "accepted" : "refused", result.explained_variance);
        benchmark::DoNotOptimize(error_percent);
    }
    state.counters["error_percent"] = error_percent;
}
BENCHMARK(FitRealisticCamera512)->DenseRange(0, 19)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

/// One evaluation of the fit's cost with its Jacobian on a final level of a 512² photo (case 10 of the test bed, the
/// lattice every 4th pixel: 16384 samples, as the fit's until its final level took every 5th; every term free that the
/// bed frees), the geometry moved a little each time so that the figure's terms are computed anew, as in every
/// iteration of a refinement.
void PhotoCostJacobian512(benchmark::State& state) {
    constexpr int kSize = 512, kCase = 10;
    const testing::CameraCase c = testing::random_case(kCase, kSize);
    const testing::CameraCasePhoto shot = testing::photograph_case(kCase, c, kSize);
    ConoscopePhotoModel terms_model = shot.model;
    terms_model.settings.thickness_um = 10000.0;  // as the fit: the thickest slab its bounds allow
    PhotoParameters values = shot.options.initial;
    at(values, PhotoParameter::thickness_um) = c.optics.thickness_um;
    const Eigen::Vector2d centre(at(values, PhotoParameter::center_x_px), at(values, PhotoParameter::center_y_px));
    const detail::PhotoLevel level(terms_model, detail::sample_lattice(centre, kSize, 4, kSize, kSize), shot.photo, 0.0,
                                   at(values, PhotoParameter::gamma), shot.options.saturated_level);
    const detail::PhotoCost cost(level, shot.options.free, shot.options.robust_scale);
    std::vector<double> residuals(static_cast<std::size_t>(cost.num_residuals()));
    std::vector<double> jacobian(residuals.size() * kPhotoParameterCount);
    double* jacobians[] = {jacobian.data()};
    int evaluation = 0;
    for (auto _ : state) {
        at(values, PhotoParameter::center_x_px) += (evaluation++ % 2 == 0 ? 1e-3 : -1e-3);
        const double* parameters[] = {values.data()};
        if (!cost.Evaluate(parameters, residuals.data(), jacobians)) {
            state.SkipWithError("the cost refused the point");
            break;
        }
        benchmark::DoNotOptimize(jacobian.data());
    }
    state.counters["samples"] = static_cast<double>(level.evaluator.sample_count());
}
BENCHMARK(PhotoCostJacobian512)->Unit(benchmark::kMillisecond)->UseRealTime();

// A quartz grain 30 µm thick, photographed at stage 0 and 30° and with the gypsum plate at 0 (the tests' camera:
// sRGB, noise, JPEG 85), fitted over the default 1–200 µm. Argument: the orientation mode, 0 known, 1 in the
// section's plane (maximum birefringence, the angle unknown), 2 free.
void FitOrthoscopeGrain(benchmark::State& state) {
    testing::GrainPhotos camera;
    const Mineral& quartz = testing::fit_minerals().find("quartz");
    const Eigen::Matrix3d axes = euler_zyz_deg(30.0, 70.0, 20.0);
    const std::vector<GrainPhoto> photos = camera.take("quartz", 30.0, axes, {{0.0, false}, {30.0, false}, {0.0, true}}, 31);
    const GrainOrientation modes[] = {GrainOrientation::known, GrainOrientation::max_birefringence, GrainOrientation::free};
    camera.options().orientation = modes[state.range(0)];
    camera.options().known_axes = axes;
    for (auto _ : state) {
        const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, quartz, camera.options(), camera.integrator());
        std::fprintf(stderr, "retardation %.2f nm, thickness %.3f um, rms %.2f codes\n", fit.retardation_nm.value, fit.thickness_um.value,
                     255.0 * fit.rms_code);
        benchmark::DoNotOptimize(fit.rms_code);
    }
}
BENCHMARK(FitOrthoscopeGrain)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
