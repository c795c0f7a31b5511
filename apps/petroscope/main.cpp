// petroscope and petroscope-full: a physically exact simulator of the polarizing microscope. This file only
// wires the subcommands together; each lives in its own command_*.cpp, and heavy_commands.hpp tells which
// of them petroscope hands to petroscope-full.
#include "cli_common.hpp"
#include "frame_command.hpp"
#include "heavy_commands.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/heap.hpp"
#include "petroscope/io/atomic_file.hpp"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    petroscope::install_interrupt_cleanup();
    petroscope::keep_large_blocks_in_heap();
    CLI::App app{
        "petroscope: a physically exact simulator of the petrographic (polarizing) microscope.\n"
        "Interference figures are computed per wavelength from the exact eigenmodes of the crystal.\n\n"
        "Examples:\n"
        "  petroscope conoscope -o figure.png                       (muscovite, acute bisectrix, white light)\n"
        "  petroscope conoscope --mineral calcite --thickness 30um --wavelength 589nm -o calcite.png\n"
        "  petroscope minerals                                       (list the minerals)\n"
        "  petroscope minerals show quartz --wavelength 589nm --json\n"
        "  petroscope interface --case verification/cases/brewster-p.json\n"
        "  petroscope verify                                           (the interface model's verification suite)\n"
        "  petroscope conical --crystal KGW --length 20mm --wavelength 633nm -o ring.png\n"
        "  petroscope orthoscope --section thin_sections/granite --plate gypsum -o granite.png\n"
        "  petroscope chart --csv chart.csv -o chart.png\n"
        "  petroscope sweep conoscope --mineral calcite --cut optic-axis --tilt-deg 20 --vary azimuth-deg=0:330:30 -o sweep/\n"
        "  petroscope fit conoscope --photo figure.jpg --mineral calcite --thickness 100um -o fit/\n"
        "  petroscope render --scene scenes/calcite-box.json --spp 64 -o calcite-box.png\n"
        "  petroscope serve                                             (the microscope in the browser)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "petroscope 0.1.0");
    std::string minerals_dir;
    app.add_option("--minerals-dir", minerals_dir, "Folder of mineral records (default: $PETROSCOPE_MINERALS or the minerals/ folder of the source tree)");
    const std::string command_line = petroscope::cli::joined_command_line(argc, argv);
    petroscope::cli::add_minerals_command(app, minerals_dir);
    petroscope::cli::add_frame_command(app, petroscope::cli::make_conoscope_options(), minerals_dir, command_line);
    petroscope::cli::add_interface_command(app, minerals_dir);
    petroscope::cli::add_verify_command(app, minerals_dir);
    petroscope::cli::add_frame_command(app, petroscope::cli::make_conical_options(), minerals_dir, command_line);
    petroscope::cli::add_section_command(app, minerals_dir);
    petroscope::cli::add_frame_command(app, petroscope::cli::make_orthoscope_options(), minerals_dir, command_line);
    petroscope::cli::add_frame_command(app, petroscope::cli::make_render_options(), minerals_dir, command_line);
    petroscope::cli::add_heavy_commands(app, minerals_dir, command_line, argc, argv);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version end with 0; every malformed command line with 2, like any other bad input.
        return app.exit(e) == 0 ? 0 : 2;
    } catch (const petroscope::cli::ExitCode& exit) {
        return exit.code;
    } catch (const petroscope::InputError& e) {
        std::cerr << "petroscope: error: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "petroscope: internal error: " << e.what() << '\n';
        return 3;
    }
    return 0;
}
