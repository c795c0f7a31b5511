// The paper's 3D scene (scenes/calcite-box.json) at its full 480 × 435 px and depth 15: paths and
// crystal-face interactions per second on every core, and the rms noise of the luminance of the bright
// pixels that see the crystal (from two renders with different seeds).
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/scene_file.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace petroscope {
namespace {

void PapersScene(benchmark::State& state) {
    const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    const RenderSpectrum spectrum = render_spectrum(load_cie_1931_observer(), load_light_source("D65"));
    const Scene scene = read_scene(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json", catalog, spectrum);
    RenderSettings settings;
    settings.samples_per_pixel = static_cast<int>(state.range(0));
    RenderStatistics statistics;
    Image first;
    for (auto _ : state) {
        const RenderResult result = render_scene(scene, spectrum, settings);
        statistics = result.statistics;
        first = result.stokes_xyz;
    }
    // The true noise of the pixels that see the crystal: a second render with another seed; per pixel the
    // difference over √2 relative to the value (the per-pixel standard error assumes independent samples
    // and overstates the noise of the stratified wavelengths).
    settings.seed = 2;
    const RenderResult second = render_scene(scene, spectrum, settings);
    double squares = 0.0;
    int pixels = 0;
    std::vector<double> relative;
    for (int y = 0; y < first.height; ++y) {
        for (int x = 0; x < first.width; ++x) {
            const double a = first.at(x, y, 1), b = second.stokes_xyz.at(x, y, 1);
            if (std::min(a, b) < 0.1 || std::abs(a - b) < 1e-9 * a) continue;  // dark, or exact (no crystal on its paths)
            relative.push_back(std::abs(a - b) / std::sqrt(2.0) / (0.5 * (a + b)));
            squares += relative.back() * relative.back();
            ++pixels;
        }
    }
    state.counters["paths_per_s"] = static_cast<double>(statistics.paths) / statistics.seconds;
    state.counters["face_interactions_per_s"] = static_cast<double>(statistics.crystal_interactions) / statistics.seconds;
    state.counters["crystal_px"] = pixels;
    state.counters["crystal_px_rms_noise"] = pixels > 0 ? std::sqrt(squares / pixels) : 0.0;
    // |a − b|/√2 of a normal error has median 0.6745 σ.
    std::sort(relative.begin(), relative.end());
    state.counters["crystal_px_median_noise"] = relative.empty() ? 0.0 : relative[relative.size() / 2] / 0.6745;
}
BENCHMARK(PapersScene)->Arg(4)->Arg(16)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
