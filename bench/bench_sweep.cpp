// Sweep speed (issue 7), end to end as a user runs it: `petroscope sweep conoscope` over 72 stage angles
// (0° to 355° by 5°) of the default figure of muscovite (30 µm, acute bisectrix) and of calcite (optic
// axis), 512², white light (81
// wavelengths), frames rendered in parallel on every core, PNG frames and sidecars, then the merge: CSV,
// contact sheet and animated GIF. Each iteration starts from an empty folder.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

void Sweep(benchmark::State& state, const std::string& mineral, const std::string& animation) {
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "petroscope-bench-sweep";
    const std::string command = std::string("'") + PETROSCOPE_BINARY + "' sweep conoscope --mineral " + mineral + " --vary stage-deg=0:355:5 --animation " + animation +
                                " -o '" + folder.string() + "' 2> /dev/null";
    for (auto _ : state) {
        state.PauseTiming();
        std::filesystem::remove_all(folder);
        state.ResumeTiming();
        if (std::system(command.c_str()) != 0) {
            state.SkipWithError("petroscope sweep failed");
            break;
        }
    }
    std::filesystem::remove_all(folder);
    state.counters["frames"] = 72;
}

BENCHMARK_CAPTURE(Sweep, muscovite_gif, std::string("muscovite"), std::string("gif"))->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);
BENCHMARK_CAPTURE(Sweep, muscovite_no_animation, std::string("muscovite"), std::string("none"))->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);
BENCHMARK_CAPTURE(Sweep, calcite_gif, std::string("calcite"), std::string("gif"))->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
