#pragma once
// The commands that need the heavy libraries: chart and sweep (OpenCV: drawing, video), fit (Ceres) and
// serve (cpp-httplib, OpenSSL). `petroscope` starts in a few milliseconds because it links none of them: it
// hands these commands, with the whole command line, to `petroscope-full` beside it, which links everything
// (docs/cli.md, "Start-up").
#include <CLI/CLI.hpp>

#include <string>
#include <string_view>

namespace petroscope::cli {

struct CommandSummary {
    std::string_view name;
    std::string_view description;  // as `petroscope --help` lists it
};

inline constexpr CommandSummary kChartCommand{
    "chart",
    "Draw the Michel-Levy chart of interference colours (retardation x thickness, birefringence lines),\n"
    "computed with the orthoscope's own physics; --csv gives the numbers per retardation step."};
inline constexpr CommandSummary kSweepCommand{
    "sweep",
    "Render conoscope, orthoscope or conical over a range of one or two of its numeric options (a grid): numbered\n"
    "frames with JSON sidecars, a labelled contact sheet, an animation (GIF or MP4) and measurements.csv, in the\n"
    "folder -o DIR. Frames already there are skipped (an interrupted sweep resumes); --shard K/N renders a part,\n"
    "'petroscope sweep --merge DIR' joins the parts. Layout and columns: docs/sweep.md."};
inline constexpr CommandSummary kFitCommand{"fit", "Fit a model to microscope photographs (docs/fitting.md)"};
inline constexpr CommandSummary kServeCommand{
    "serve",
    "A polarizing microscope in the browser: serve its page and compute what it shows.\n"
    "Open the printed address; Ctrl-C stops the server. docs/browser.md tells how to use it."};

/// The file name of the program that runs the heavy commands, beside `petroscope`.
inline constexpr std::string_view kFullProgramName = "petroscope-full";

/// Adds chart, sweep, fit and serve to `app`: in `petroscope-full` the commands themselves, in `petroscope`
/// subcommands that run `petroscope-full` with the same arguments (argc, argv) in this process's place.
void add_heavy_commands(CLI::App& app, const std::string& minerals_dir, const std::string& command_line, int argc, char** argv);

}  // namespace petroscope::cli
