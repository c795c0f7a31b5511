// Orthoscope speed (issue 4): a 2048² random section (quartz, orthoclase, albite, biotite, muscovite) between
// crossed polars, 81 wavelengths, rendered to memory on all cores; parallel light and a condenser cone.
// The cost should grow with grains × wavelengths (× directions) plus pixels.
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <benchmark/benchmark.h>

namespace petroscope {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog instance = load_mineral_catalog(minerals_directory());
    return instance;
}

void CrossedPolars(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    const int grains = static_cast<int>(state.range(1));
    const double condenser_na = static_cast<double>(state.range(2)) / 100.0;
    ThinSection section = random_voronoi_section({"quartz", "orthoclase", "albite", "biotite", "muscovite"}, {}, grains, size, 2.0, 30.0, 1);
    section.validate();
    const std::vector<double> wavelengths = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const SpectralIntegrator integrator(wavelengths, load_cie_1931_observer(), load_light_source("D65"));
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = wavelengths;
    settings.microscope.condenser_na = condenser_na;
    settings.mounting = standard_mounting(catalog());
    for (auto _ : state) {
        const Image image = render_orthoscope(section, catalog(), settings, &integrator);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    state.counters["grains"] = static_cast<double>(section.grains.size());
}

BENCHMARK(CrossedPolars)
    ->Args({2048, 1, 0})
    ->Args({2048, 200, 0})
    ->Args({2048, 2000, 0})
    ->Args({2048, 200, 20})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace petroscope
BENCHMARK_MAIN();
