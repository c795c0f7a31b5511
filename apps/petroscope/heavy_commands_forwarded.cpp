// petroscope: the heavy commands run by petroscope-full, which replaces this process (execv keeps its
// process id, standard streams, environment and working directory, so callers and signals see one program).
#include "heavy_commands.hpp"

#include "petroscope/core/error.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace petroscope::cli {
namespace {

[[noreturn]] void run_full_program(std::string_view command, int argc, char** argv) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    // Without /proc, argv[0] tells the folder only when it holds one (not when petroscope was found on the PATH).
    const std::string started_as = argv[0];
    if (error && started_as.find('/') == std::string::npos) {
        throw InputError("the command '" + std::string(command) + "' is run by " + std::string(kFullProgramName) +
                         ", but petroscope cannot tell its own folder (no /proc/self/exe); run petroscope-full directly");
    }
    const std::filesystem::path full = (error ? std::filesystem::path(started_as) : self).parent_path() / kFullProgramName;
    std::vector<char*> arguments(argv, argv + argc);
    arguments.push_back(nullptr);
    ::execv(full.c_str(), arguments.data());
    throw InputError("the command '" + std::string(command) + "' is run by " + full.string() + ", which could not be started (" +
                     std::strerror(errno) + "); build or install it beside petroscope");
}

void add_forwarded_command(CLI::App& app, const CommandSummary& summary, int argc, char** argv) {
    CLI::App* command = app.add_subcommand(std::string(summary.name), std::string(summary.description));
    // Everything after the command's name, --help included, is petroscope-full's to parse.
    command->set_help_flag();
    command->prefix_command();
    command->callback([summary, argc, argv] { run_full_program(summary.name, argc, argv); });
}

}  // namespace

void add_heavy_commands(CLI::App& app, const std::string&, const std::string&, int argc, char** argv) {
    for (const CommandSummary& summary : {kChartCommand, kSweepCommand, kFitCommand, kServeCommand}) add_forwarded_command(app, summary, argc, argv);
}

}  // namespace petroscope::cli
