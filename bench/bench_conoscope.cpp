// Conoscope speed: white-light and monochromatic figures, exact modes and Fresnel at both faces, on all
// cores (OpenMP). Reports wall time per figure and ns per pixel-wavelength (pixels inside the aperture).
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

namespace petroscope {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog minerals = load_mineral_catalog(minerals_directory());
    return minerals;
}

ConoscopeSettings settings_for(const Mineral& mineral, int size_px, bool white) {
    ConoscopeSettings settings;
    settings.size_px = size_px;
    settings.thickness_um = 30.0;
    settings.wavelengths_nm = white ? WavelengthGrid{}.wavelengths_nm() : std::vector<double>{589.3};
    const Cut cut = mineral.optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
    settings.crystal_axes = cut_orientation(cut, mineral.optical_class, mineral.principal_n(589.3), 0.0, 0.0);
    return settings;
}

void time_figure(benchmark::State& state, const Mineral& mineral, const ConoscopeSettings& settings, bool white) {
    const PrincipalIndexFunction indices = [&mineral](double nm) { return mineral.principal_n(nm); };
    const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    for (auto _ : state) {
        Image image = render_conoscope(settings, indices, white ? &integrator : nullptr);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    const double aperture_pixels = std::numbers::pi / 4.0 * settings.size_px * settings.size_px;
    state.counters["ns_per_pixel_wavelength"] = benchmark::Counter(
        aperture_pixels * static_cast<double>(settings.wavelengths_nm.size()) * 1e-9,
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void run_figure(benchmark::State& state, const char* mineral_name, bool white, SpectrumSampling spectrum = SpectrumSampling::interpolated) {
    const Mineral& mineral = catalog().find(mineral_name);
    ConoscopeSettings settings = settings_for(mineral, static_cast<int>(state.range(0)), white);
    settings.spectrum = spectrum;
    time_figure(state, mineral, settings, white);
}

// Optical activity costs at most 1.5 times the figure without it (issue 19): quartz, 1 mm, optic axis, white
// light, 512²; Arg 0 without the gyration, Arg 1 with it (right-handed).
void quartz_activity(benchmark::State& state, SpectrumSampling spectrum) {
    const Mineral& quartz = catalog().find("quartz");
    ConoscopeSettings settings = settings_for(quartz, 512, true);
    settings.thickness_um = 1000.0;
    settings.spectrum = spectrum;
    if (state.range(0) == 1) settings.gyration = mineral_gyration(quartz, Handedness::right);
    time_figure(state, quartz, settings, true);
}
void QuartzOpticalActivity(benchmark::State& state) { quartz_activity(state, SpectrumSampling::interpolated); }
void QuartzOpticalActivityExactSpectrum(benchmark::State& state) { quartz_activity(state, SpectrumSampling::exact); }

// The library layer's whole call, as the CLI and Python make it: the default figure (muscovite, 30 µm,
// white light D65) planned, rendered, converted to display colours and measured. bench/bench_python.py
// times the same call from Python.
void LibraryLayerDefaultFigure(benchmark::State& state) {
    ConoscopeRequest request;
    request.size_px = static_cast<int>(state.range(0));
    for (auto _ : state) {
        ConoscopeFigure figure = render_conoscope_figure(plan_conoscope(request, catalog()));
        benchmark::DoNotOptimize(figure.image.linear_rgb.pixels.data());
    }
}

// A plate costs what the figure costs (issue 22's outlier: quartz, 300 µm, white light, 512², without and
// with the gypsum plate; Arg 1 puts the plate in).
void QuartzThickPlate(benchmark::State& state) {
    ConoscopeRequest request;
    request.mineral = "quartz";
    request.thickness_um = 300.0;
    if (state.range(0) == 1) request.plate = PlateRequest{};
    for (auto _ : state) {
        ConoscopeFigure figure = render_conoscope_figure(plan_conoscope(request, catalog()));
        benchmark::DoNotOptimize(figure.image.linear_rgb.pixels.data());
    }
}

// The same for crystals without optical activity: the default figure (muscovite, 30 µm, acute bisectrix) and
// calcite 30 µm on its optic axis, 512², without and with the gypsum plate (second argument 1).
void InactivePlate(benchmark::State& state) {
    ConoscopeRequest request;
    request.mineral = state.range(0) == 0 ? "muscovite" : "calcite";
    if (state.range(1) == 1) request.plate = PlateRequest{};
    for (auto _ : state) {
        ConoscopeFigure figure = render_conoscope_figure(plan_conoscope(request, catalog()));
        benchmark::DoNotOptimize(figure.image.linear_rgb.pixels.data());
    }
}

void WhiteLightBiaxial(benchmark::State& state) { run_figure(state, "muscovite", true); }
void WhiteLightUniaxial(benchmark::State& state) { run_figure(state, "calcite", true); }
// The same with the modes solved at every wavelength (--exact-spectrum) instead of at 8 spectral nodes.
void WhiteLightBiaxialExactSpectrum(benchmark::State& state) { run_figure(state, "muscovite", true, SpectrumSampling::exact); }
void WhiteLightUniaxialExactSpectrum(benchmark::State& state) { run_figure(state, "calcite", true, SpectrumSampling::exact); }
void MonochromaticBiaxial(benchmark::State& state) { run_figure(state, "muscovite", false); }
void MonochromaticUniaxial(benchmark::State& state) { run_figure(state, "calcite", false); }

BENCHMARK(LibraryLayerDefaultFigure)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(QuartzThickPlate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(InactivePlate)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(WhiteLightBiaxial)->Arg(128)->Arg(256)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(WhiteLightUniaxial)->Arg(128)->Arg(256)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(WhiteLightBiaxialExactSpectrum)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(WhiteLightUniaxialExactSpectrum)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(QuartzOpticalActivity)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(QuartzOpticalActivityExactSpectrum)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MonochromaticBiaxial)->Arg(512)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MonochromaticUniaxial)->Arg(512)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
