// petroscope chart: the Michel-Lévy chart of interference colours, computed by the orthoscope's pipeline.
#include "cli_common.hpp"
#include "heavy_commands.hpp"

#include "petroscope/api/michel_levy_chart.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/chart_drawing.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/spectral/color.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

namespace petroscope::cli {
namespace {

struct ChartOptions {
    std::string mineral;
    double max_retardation_nm = 2000.0;
    double step_nm = 1.0;
    std::string max_thickness = "50um";
    std::string wavelength_grid = "380:780:5";
    std::string illuminant = "D65";
    bool no_white_balance = false;
    std::string csv;
    std::string output;
};

void write_csv(const std::vector<MichelLevyStep>& steps, const std::vector<Eigen::Vector3d>& linear_srgb,
               const std::filesystem::path& path, const std::filesystem::path& destination) {
    std::ofstream out(path);
    out << "retardation_nm,thickness_um,X,Y,Z,x,y,sR,sG,sB,sR8,sG8,sB8\n";
    char line[256];
    for (std::size_t k = 0; k < steps.size(); ++k) {
        const Eigen::Vector3d& xyz = steps[k].xyz;
        const double sum = xyz.sum();
        Eigen::Vector3d encoded;
        for (int c = 0; c < 3; ++c) encoded[c] = encode_srgb(std::clamp(linear_srgb[k][c], 0.0, 1.0));
        std::snprintf(line, sizeof line, "%.3f,%.6f,%.8f,%.8f,%.8f,%.8f,%.8f,%.6f,%.6f,%.6f,%ld,%ld,%ld\n", steps[k].retardation_nm,
                      steps[k].thickness_um, xyz[0], xyz[1], xyz[2], sum > 0.0 ? xyz[0] / sum : 0.0, sum > 0.0 ? xyz[1] / sum : 0.0,
                      encoded[0], encoded[1], encoded[2], std::lround(255.0 * encoded[0]), std::lround(255.0 * encoded[1]),
                      std::lround(255.0 * encoded[2]));
        out << line;
    }
    out.flush();
    if (!out) throw InputError(destination.string() + ": could not write the CSV (disk full or not writable)");
}

void run_chart(const ChartOptions& options, const std::string& minerals_dir, const std::string& command_line) {
    MichelLevyRequest request;
    if (!options.mineral.empty()) request.mineral = options.mineral;
    request.max_retardation_nm = options.max_retardation_nm;
    request.step_nm = options.step_nm;
    request.light.grid = with_option("--wavelengths", [&] { return WavelengthGrid::parse(options.wavelength_grid); });
    request.light.illuminant = options.illuminant;
    request.light.white_balance = !options.no_white_balance;
    MichelLevyChartLayout layout;
    layout.max_thickness_um = positive_length_um("--max-thickness", options.max_thickness);
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    if (!options.mineral.empty()) with_option("--mineral", [&]() -> const Mineral& { return catalog.find(options.mineral); });
    ImageResult result(options.output);
    std::filesystem::path csv_temporary;
    if (!options.csv.empty()) csv_temporary = result.add_companion(options.csv);
    const MichelLevyColours chart = michel_levy_chart_colours(request, catalog);
    const std::vector<MichelLevyStep>& steps = chart.steps;
    if (!csv_temporary.empty()) write_csv(steps, chart.linear_srgb, csv_temporary, options.csv);
    const MichelLevySettings& settings = chart.settings;
    const double birefringence = chart.birefringence_at_reference;
    const WavelengthGrid& grid = request.light.grid;
    const nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "chart"},
        {"command_line", command_line},
        {"plate", settings.mineral != nullptr ? nlohmann::json{{"mineral", settings.mineral->name}, {"file", settings.mineral->file},
                                                               {"section", "containing X and Z (largest birefringence)"},
                                                               {"birefringence_at_reference", birefringence}}
                                              : nlohmann::json{{"mineral", nullptr}, {"birefringence", birefringence},
                                                               {"dispersion", "none (classic chart)"}}},
        {"reference_wavelength_nm", settings.reference_wavelength_nm},
        {"retardation_nm", {{"max", settings.max_retardation_nm}, {"step", settings.step_nm}, {"count", steps.size()}}},
        {"view", "crossed polars, plate at 45 degrees, parallel light, standard mounting (crown glass, canada balsam)"},
        {"light", {{"illuminant", chart.illuminant}, {"white_balance", !options.no_white_balance},
                   {"wavelengths_nm", {{"start", grid.start_nm}, {"end", grid.end_nm}, {"step", grid.step_nm}, {"count", grid.size()}}}}},
        {"max_thickness_um", layout.max_thickness_um},
        {"csv", options.csv.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.csv)},
        {"model", "single-pass Jones from the exact eigenmodes of every layer, Fresnel at every interface (docs/orthoscope.md)"},
    };
    result.write(draw_michel_levy_chart(steps, chart.linear_srgb, layout), sidecar);
    std::cerr << "petroscope: wrote " << options.output << (options.csv.empty() ? "" : " and " + options.csv) << " ("
              << steps.size() << " retardations)\n";
}

}  // namespace

void add_chart_command(CLI::App& app, const std::string& minerals_dir, const std::string& command_line) {
    auto options = std::make_shared<ChartOptions>();
    CLI::App* command = app.add_subcommand(std::string(kChartCommand.name), std::string(kChartCommand.description));
    command->add_option("--mineral", options->mineral, "Use this mineral's real dispersion of birefringence (default: none, classic chart)");
    command->add_option("--max-retardation", options->max_retardation_nm, "Largest retardation in nm")->capture_default_str();
    command->add_option("--step", options->step_nm, "Retardation step in nm")->capture_default_str();
    command->add_option("--max-thickness", options->max_thickness, "Top of the thickness axis: 50um, …")->capture_default_str();
    command->add_option("--wavelengths", options->wavelength_grid, "Wavelength grid START:END:STEP in nm")->capture_default_str();
    command->add_option("--illuminant", options->illuminant, "D65, A (halogen) or blackbody:3200K")->capture_default_str();
    command->add_flag("--no-white-balance", options->no_white_balance, "Keep the colour cast of the illuminant");
    command->add_option("--csv", options->csv, "Also write retardation, thickness, X, Y, Z, x, y and sRGB per step to this CSV");
    command->add_option("-o,--output", options->output, "Chart image: .png, .exr or .tif; a JSON sidecar <output>.json beside it")->required();
    command->callback([options, &minerals_dir, command_line] { run_chart(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
