// petroscope-full: the heavy commands themselves.
#include "cli_common.hpp"
#include "heavy_commands.hpp"

namespace petroscope::cli {

void add_heavy_commands(CLI::App& app, const std::string& minerals_dir, const std::string& command_line, int, char**) {
    add_chart_command(app, minerals_dir, command_line);
    add_sweep_command(app, minerals_dir);
    add_fit_command(app, minerals_dir);
    add_serve_command(app, minerals_dir);
}

}  // namespace petroscope::cli
