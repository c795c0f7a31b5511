// The live microscope (`petroscope serve`, issue 21): what the server computes when the user changes the
// specimen, light, polars or plate (five renders give the stage harmonics), and the composition of a frame
// at a stage angle, which the page does in JavaScript on every frame while the user drags (the browser
// test reports the page's own time per frame). Goals: a first picture in 150 ms, the full 512² one in 0.5 s.
#include "petroscope/api/stage_harmonics.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"

#include <benchmark/benchmark.h>

namespace petroscope {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog instance = load_mineral_catalog(minerals_directory());
    return instance;
}

OrthoscopeRequest granite_request() {
    OrthoscopeRequest request;
    request.section = read_thin_section(shipped_directory("thin_sections") / "granite", catalog());
    return request;
}

// The granite example (512², 150 grains), white light, crossed polars; with the gypsum plate (arg 1).
void OrthoscopeHarmonics(benchmark::State& state) {
    OrthoscopeRequest request = granite_request();
    if (state.range(0) == 1) request.plate = PlateRequest{PlateKind::gypsum};
    for (auto _ : state) benchmark::DoNotOptimize(orthoscope_stage_harmonics(request, catalog()).coefficients.pixels.data());
}
BENCHMARK(OrthoscopeHarmonics)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Calcite cut ⟂ its optic axis, 30 µm, white light: the page's quick figure (128²) and the full one (512²).
void ConoscopeHarmonics(benchmark::State& state) {
    ConoscopeRequest request;
    request.mineral = "calcite";
    request.orientation.cut = Cut::optic_axis;
    request.size_px = static_cast<int>(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(conoscope_stage_harmonics(request, catalog()).coefficients.pixels.data());
}
BENCHMARK(ConoscopeHarmonics)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();

// One frame of the granite view at a stage angle, in C++ (the page's JavaScript does the same per frame).
void ComposeAtStage(benchmark::State& state) {
    const StageHarmonics harmonics = orthoscope_stage_harmonics(granite_request(), catalog());
    double stage_deg = 0.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(compose_at_stage(harmonics, stage_deg).pixels.data());
        stage_deg += 1.0;
    }
}
BENCHMARK(ComposeAtStage)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace petroscope
BENCHMARK_MAIN();
