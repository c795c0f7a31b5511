// petroscope serve: the live microscope in the browser (docs/browser.md).
#include "cli_common.hpp"
#include "heavy_commands.hpp"

#include "petroscope/io/data_files.hpp"
#include "petroscope/serve/http_server.hpp"

#include <cstdio>
#include <memory>

namespace petroscope::cli {

void add_serve_command(CLI::App& app, const std::string& minerals_dir) {
    auto settings = std::make_shared<serve::ServeSettings>();
    CLI::App* command = app.add_subcommand(std::string(kServeCommand.name), std::string(kServeCommand.description));
    command->add_option("--host", settings->host, "Address to listen on (default: this machine only)")->capture_default_str();
    command->add_option("--port", settings->port, "Port (0: any free port, printed)")->capture_default_str()->check(CLI::Range(0, 65535));
    command->add_flag("--verbose", settings->verbose, "Print one line per request on standard error");
    command->callback([settings, &minerals_dir] {
        const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
        const serve::LiveMicroscope microscope(catalog, shipped_directory("web"), shipped_directory("thin_sections"));
        serve::serve_until_interrupted(microscope, *settings, [](const std::string& url) {
            std::printf("petroscope: the microscope is at %s (Ctrl-C stops)\n", url.c_str());
            std::fflush(stdout);
        });
        std::printf("petroscope: stopped\n");
    });
}

}  // namespace petroscope::cli
