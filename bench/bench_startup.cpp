// Start-up and end to end (issue 22), as a user or a script meets them: the wall time of whole processes
// of the command-line tool, from spawn to exit, standard output and error to /dev/null.
//   StartUp/*       commands that compute nothing: `petroscope --help`, `petroscope minerals` (reads the
//                   mineral records), and `petroscope-full --help`, which loads every library (OpenCV,
//                   Ceres, cpp-httplib): what every command cost before petroscope handed the heavy ones to it.
//   EndToEnd/*      the default figure of the README, 512², white light (81 wavelengths), PNG and sidecar;
//                   and in monochromatic light, where nearly all of the time is start-up, data and files.
#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace {

/// Runs `arguments` (the first is the program) with its output discarded; false when it did not exit with 0.
bool run_quietly(std::vector<std::string> arguments) {
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t child = 0;
    const int spawned = posix_spawn(&child, argv.front(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    return spawned == 0 && waitpid(child, &status, 0) == child && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

const std::string kPetroscope = PETROSCOPE_BINARY;
const std::string kPetroscopeFull = PETROSCOPE_FULL_BINARY;
const std::string kFigure = (std::filesystem::temp_directory_path() / "petroscope-bench-startup.png").string();

void Run(benchmark::State& state, const std::vector<std::string>& arguments) {
    for (auto _ : state) {
        if (!run_quietly(arguments)) {
            state.SkipWithError("the command failed");
            break;
        }
    }
    std::filesystem::remove(kFigure);
    std::filesystem::remove(kFigure + ".json");
}

BENCHMARK_CAPTURE(Run, help, std::vector<std::string>{kPetroscope, "--help"})->Name("StartUp/help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, minerals, std::vector<std::string>{kPetroscope, "minerals"})->Name("StartUp/minerals")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, conoscope_help, std::vector<std::string>{kPetroscope, "conoscope", "--help"})
    ->Name("StartUp/conoscope_help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, full_help, std::vector<std::string>{kPetroscopeFull, "--help"})->Name("StartUp/full_help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, forwarded_fit_help, std::vector<std::string>{kPetroscope, "fit", "--help"})
    ->Name("StartUp/fit_help_through_petroscope")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, default_figure,
                  std::vector<std::string>{kPetroscope, "conoscope", "--mineral", "calcite", "--cut", "optic-axis", "--size", "512", "-o", kFigure})
    ->Name("EndToEnd/calcite_optic_axis_512")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Run, default_figure_monochromatic,
                  std::vector<std::string>{kPetroscope, "conoscope", "--mineral", "calcite", "--cut", "optic-axis", "--size", "512", "--wavelength", "589nm",
                                           "-o", kFigure})
    ->Name("EndToEnd/calcite_optic_axis_512_589nm")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
