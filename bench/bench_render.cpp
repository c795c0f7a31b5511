// The paper's 3D scene (scenes/calcite-box.json) at its full 480 × 435 px and depth 15 on every core:
// - PapersScene/SPP: paths and crystal-face interactions per second;
// - FlatRegionNoise/SPP: the same scene with the bottom wall a uniform grey, so that everything seen
//   through the crystal is a flat region: the median relative noise of the luminance of the pixels that
//   see the crystal, from two renders with different seeds (the per-pixel standard error of the renderer
//   assumes independent samples and overstates the noise of the stratified wavelengths).
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/scene_file.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace petroscope {
namespace {

struct PapersSceneData {
    MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    RenderSpectrum spectrum = render_spectrum(load_cie_1931_observer(), load_light_source("D65"));
    Scene scene = read_scene(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json", catalog, spectrum);
};

const PapersSceneData& papers_scene() {
    static const PapersSceneData data;
    return data;
}

void PapersScene(benchmark::State& state) {
    const PapersSceneData& data = papers_scene();
    RenderSettings settings;
    settings.samples_per_pixel = static_cast<int>(state.range(0));
    RenderStatistics statistics;
    for (auto _ : state) statistics = render_scene(data.scene, data.spectrum, settings).statistics;
    state.counters["paths_per_s"] = static_cast<double>(statistics.paths) / statistics.seconds;
    state.counters["face_interactions_per_s"] = static_cast<double>(statistics.crystal_interactions) / statistics.seconds;
}

void FlatRegionNoise(benchmark::State& state) {
    const PapersSceneData& data = papers_scene();
    Scene scene = data.scene;
    WallEmission& bottom = scene.box.walls[static_cast<std::size_t>(Wall::bottom)];
    bottom = WallEmission{};
    bottom.kind = WallEmission::Kind::uniform;
    bottom.uniform = SigmoidSpectrum::constant(0.5);
    RenderSettings settings;
    settings.samples_per_pixel = static_cast<int>(state.range(0));
    Image first, second;
    for (auto _ : state) {
        settings.seed = 1;
        first = render_scene(scene, data.spectrum, settings).stokes_xyz;
        settings.seed = 2;
        second = render_scene(scene, data.spectrum, settings).stokes_xyz;
    }
    std::vector<double> relative;
    for (int y = 0; y < first.height; ++y) {
        for (int x = 0; x < first.width; ++x) {
            const double a = first.at(x, y, 1), b = second.at(x, y, 1);
            if (std::min(a, b) < 0.1 || std::abs(a - b) < 1e-9 * a) continue;  // dark, or exact (no crystal on its paths)
            relative.push_back(std::abs(a - b) / std::sqrt(2.0) / (0.5 * (a + b)));
        }
    }
    std::sort(relative.begin(), relative.end());
    state.counters["crystal_px"] = static_cast<double>(relative.size());
    // |a − b|/√2 of a normal error has median 0.6745 σ.
    state.counters["median_noise"] = relative.empty() ? 0.0 : relative[relative.size() / 2] / 0.6745;
}

BENCHMARK(PapersScene)->Arg(32)->Arg(64)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(FlatRegionNoise)->Arg(32)->Arg(64)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
