// petroscope interface --case case.json [--json]: one plane wave at one interface.
#include "cli_common.hpp"

#include "petroscope/io/data_files.hpp"
#include "petroscope/io/interface_case.hpp"

#include <cstdio>
#include <iostream>
#include <memory>

namespace petroscope::cli {
namespace {

struct InterfaceOptions {
    std::string case_file;
    bool json = false;
};

void print_table(const InterfaceCase& interface_case, const InterfaceResult& result) {
    if (!interface_case.name.empty()) std::printf("%s\n", interface_case.name.c_str());
    std::printf("incident: n = %.12g, ray (%.9f, %.9f, %.9f)\n", result.incident_n.real(), result.incident_ray_direction.x(),
                result.incident_ray_direction.y(), result.incident_ray_direction.z());
    std::printf("%-12s %-14s %-40s %-16s %-16s %s\n", "wave", "mode", "direction (wave normal)", "n", "power", "Stokes S0 S1 S2 S3");
    double total = 0.0;
    for (const InterfaceWave& wave : result.waves) {
        const char* kind = wave.kind == InterfaceWave::Kind::reflected ? "reflected" : "transmitted";
        char direction[64];
        std::snprintf(direction, sizeof direction, "(%.9f, %.9f, %.9f)", wave.direction.x(), wave.direction.y(), wave.direction.z());
        char index[40];
        if (wave.n.imag() == 0.0) std::snprintf(index, sizeof index, "%.12g", wave.n.real());
        else std::snprintf(index, sizeof index, "%.9g%+.3gi", wave.n.real(), wave.n.imag());
        std::printf("%-12s %-14s %-40s %-16s %-16.13f %.6f %.6f %.6f %.6f%s\n", kind, std::string(wave_mode_name(wave.mode)).c_str(), direction, index, wave.power,
                    wave.stokes[0], wave.stokes[1], wave.stokes[2], wave.stokes[3], wave.evanescent ? "  (evanescent)" : "");
        total += wave.power;
    }
    std::printf("sum of powers: %.15f\n", total);
}

}  // namespace

void add_interface_command(CLI::App& app, const std::string& minerals_dir) {
    auto options = std::make_shared<InterfaceOptions>();
    CLI::App* command = app.add_subcommand(
        "interface",
        "One plane wave meeting one plane interface: every reflected and transmitted wave (direction, ray, index,\n"
        "power, polarization). The case file format is described in docs/interface.md.");
    command->add_option("--case", options->case_file, "Case file (JSON)")->required();
    command->add_flag("--json", options->json, "Print the result as JSON");
    command->callback([options, &minerals_dir] {
        const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
        const InterfaceCase interface_case = load_interface_case(options->case_file, catalog);
        const InterfaceResult result = solve_interface(interface_case.normal, interface_case.incidence, interface_case.medium1, interface_case.medium2);
        if (options->json) {
            std::cout << interface_result_json(result).dump(2) << '\n';
        } else {
            print_table(interface_case, result);
        }
    });
}

}  // namespace petroscope::cli
