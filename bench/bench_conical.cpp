// Conical refraction speed, on all cores (OpenMP). Wave optics: a Gaussian beam's focal image (ρ₀ = 20, Z = 0)
// at one wavelength, the profile B₀(ρ), B₁(ρ) and then the screen; the profile spacing is a third of a pixel.
// Ray optics: the paper's pinhole scene (KGW 20 mm at 633 nm, 25 µm pinhole in a 50 mm filter, screen 50 mm
// behind), traced and its rings measured (issue 22's goal: 10⁶ rays in at most 2 s).
#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/conical_wave.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

namespace petroscope {
namespace {

void GaussianScreen(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    const double half_width = 25.0;  // ring of radius 20 w and its outer ring at 20.5 w, with a margin
    const double rho_max = std::sqrt(2.0) * half_width;
    const int samples = static_cast<int>(std::ceil(rho_max / (2.0 * half_width / size / 3.0))) + 1;
    ConicalWaveParameters parameters;
    parameters.rho0 = 20.0;
    const Eigen::Vector4d unpolarised(1.0, 0.0, 0.0, 0.0);
    for (auto _ : state) {
        const ConicalProfile profile = conical_profile(parameters, rho_max, samples);
        Image image = conical_screen(profile, unpolarised, size, half_width);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    state.counters["profile_samples"] = samples;
}

void GaussianProfile(benchmark::State& state) {
    const int samples = static_cast<int>(state.range(0));
    ConicalWaveParameters parameters;
    parameters.rho0 = 20.0;
    for (auto _ : state) {
        const ConicalProfile profile = conical_profile(parameters, std::sqrt(2.0) * 25.0, samples);
        benchmark::DoNotOptimize(profile.b0.data());
    }
}

void PinholeRays(benchmark::State& state) {
    ConicalRaySettings settings;  // KGW at 633 nm, 20 mm, screen 50 mm behind
    settings.filter_um = 50000.0;
    settings.rays = state.range(0);
    for (auto _ : state) {
        const ConicalRayResult result = trace_conical_rays(settings);
        benchmark::DoNotOptimize(result.screen.pixels.data());
    }
    state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(settings.rays), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(GaussianScreen)->Arg(512)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(GaussianProfile)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PinholeRays)->Arg(200000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
