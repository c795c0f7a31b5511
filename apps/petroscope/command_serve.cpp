// petroscope serve: the live microscope in the browser (docs/browser.md).
#include "cli_common.hpp"

#include "petroscope/io/data_files.hpp"
#include "petroscope/serve/http_server.hpp"

#include <cstdio>
#include <memory>

namespace petroscope::cli {

void add_serve_command(CLI::App& app, const std::string& minerals_dir) {
    auto settings = std::make_shared<serve::ServeSettings>();
    CLI::App* command = app.add_subcommand("serve",
                                           "A polarizing microscope in the browser: serve its page and compute what it shows.\n"
                                           "Open the printed address; Ctrl-C stops the server. docs/browser.md tells how to use it.");
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
