// The paper's 3D scene (scenes/calcite-box.json) at its full 480 × 435 px and depth 15: paths and
// crystal-face interactions per second on every core, and the noise of the pixels that see the crystal.
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/scene_file.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
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
    std::vector<double> noise;
    for (auto _ : state) {
        const RenderResult result = render_scene(scene, spectrum, settings);
        statistics = result.statistics;
        noise.clear();
        for (int y = 0; y < result.stokes_xyz.height; ++y) {
            for (int x = 0; x < result.stokes_xyz.width; ++x) {
                const double luminance = result.stokes_xyz.at(x, y, 1), error = result.standard_error_y.at(x, y, 0);
                if (luminance > 0.1 && error > 1e-6 * luminance) noise.push_back(error / luminance);
            }
        }
    }
    std::sort(noise.begin(), noise.end());
    state.counters["paths_per_s"] = static_cast<double>(statistics.paths) / statistics.seconds;
    state.counters["face_interactions_per_s"] = static_cast<double>(statistics.crystal_interactions) / statistics.seconds;
    state.counters["crystal_px_noise_median"] = noise.empty() ? 0.0 : noise[noise.size() / 2];
}
BENCHMARK(PapersScene)->Arg(4)->Arg(16)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
