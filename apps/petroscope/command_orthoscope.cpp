// petroscope orthoscope: a thin section under plane-polarized light or between crossed polars.
#include "cli_common.hpp"
#include "cli_light.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/microscope/orthoscope.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>

namespace petroscope::cli {
namespace {

struct OrthoscopeOptions {
    std::string section;
    bool ppl = false;
    bool xpl = false;
    double stage_deg = 0.0;
    PlateOptions plate;
    double condenser_na = 0.0;
    int condenser_rings = 0;
    std::string thickness;
    bool exact = false;
    LightOptions light;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    std::string output;
};

nlohmann::json section_summary(const ThinSection& section) {
    std::map<std::string, int> grains_per_mineral;
    for (const ThinSectionGrain& grain : section.grains) ++grains_per_mineral[grain.mineral];
    nlohmann::json thickness;
    switch (section.thickness_kind) {
        case ThicknessKind::uniform: thickness = {{"kind", "uniform"}, {"thickness_um", section.thickness_um}}; break;
        case ThicknessKind::wedge:
            thickness = {{"kind", "wedge"}, {"start_um", section.wedge_start_um}, {"end_um", section.wedge_end_um},
                         {"along", section.wedge_along_x ? "x" : "y"}};
            break;
        case ThicknessKind::map: thickness = {{"kind", "map"}}; break;
    }
    return {{"name", section.name}, {"size_px", {section.width_px, section.height_px}},
            {"pixel_size_um", section.pixel_size_um}, {"grains", section.grains.size()},
            {"grains_per_mineral", grains_per_mineral}, {"thickness", thickness}};
}

void run_orthoscope(const OrthoscopeOptions& options, const std::string& minerals_dir, const std::string& command_line) {
    const auto started = std::chrono::steady_clock::now();
    OrthoscopeSettings settings;
    MicroscopeSettings& microscope = settings.microscope;
    microscope.stage_deg = options.stage_deg;
    microscope.polars = {options.polarizer_deg, options.analyzer_deg, !options.ppl};
    microscope.condenser_na = options.condenser_na;
    microscope.condenser_rings = options.condenser_rings;
    microscope.exact = options.exact;
    if (options.condenser_rings < 0 || options.condenser_rings > 64) throw InputError("--condenser-rings must be 0 (automatic) to 64");

    const ResolvedLight light_used = resolve_light(options.light);
    microscope.wavelengths_nm = light_used.wavelengths_nm;
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    settings.mounting = standard_mounting(catalog);
    microscope.plate = make_plate(options.plate, catalog);
    settings.validate();
    ThinSection section = read_thin_section(options.section, catalog);
    if (!options.thickness.empty()) {
        const double thickness_um = with_option("--thickness", [&] { return parse_length_um(options.thickness); });
        if (!(thickness_um > 0.0)) throw InputError("--thickness '" + options.thickness + "': the thickness must be > 0");
        section.thickness_kind = ThicknessKind::uniform;
        section.thickness_um = thickness_um;
    }
    ImageResult result(options.output);  // fails now, before rendering, if the output cannot be written

    std::vector<std::string> warned;
    for (const ThinSectionGrain& grain : section.grains) {
        if (std::find(warned.begin(), warned.end(), grain.mineral) != warned.end()) continue;
        warned.push_back(grain.mineral);
        for (const auto& warning : catalog.find(grain.mineral).range_warnings(microscope.wavelengths_nm)) {
            std::cerr << "petroscope: warning: " << warning << '\n';
        }
    }

    const auto progress = [](double fraction) { show_progress("rendering", fraction); };
    nlohmann::json light;
    const Image linear_rgb = render_in_light(
        options.light, light_used,
        [&](const SpectralIntegrator* integrator) { return render_orthoscope(section, catalog, settings, integrator, progress); },
        "the light after the polarizer", light);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const SectionMounting& mounting = settings.mounting;
    const nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "orthoscope"},
        {"command_line", command_line},
        {"section", section_summary(section)},
        {"section_file", thin_section_description_path(options.section).string()},
        {"view", options.ppl ? "plane-polarized light (analyzer out)" : "crossed polars"},
        {"stage_deg", microscope.stage_deg},
        {"polarizer_deg", microscope.polars.polarizer_deg},
        {"analyzer_deg", options.ppl ? nlohmann::json(nullptr) : nlohmann::json(microscope.polars.analyzer_deg)},
        {"plate", plate_json(microscope.plate)},
        {"condenser_na", microscope.condenser_na},
        {"condenser_directions", condenser_samples(microscope.condenser_na, microscope.condenser_rings > 0 ? microscope.condenser_rings
                                                                                                         : default_condenser_rings(microscope.condenser_na)).size()},
        {"mounting", {{"slide", "crown glass"}, {"slide_um", mounting.slide_um}, {"cement", "canada balsam"},
                      {"lower_cement_um", mounting.lower_cement_um}, {"upper_cement_um", mounting.upper_cement_um},
                      {"cover", "crown glass"}, {"cover_um", mounting.cover_um}}},
        {"model", microscope.exact ? "exact coherent 4x4 transfer matrix (Berreman) per element: section, plate"
                                   : "single-pass Jones from the exact eigenmodes of every layer, Fresnel at every interface, no multiple reflections"},
        {"exposure", options.light.exposure},
        {"light", light},
        {"image_frame", "x to the East (right), y to the North (up); the stage turns the section counter-clockwise about the image centre"},
        {"seconds", seconds},
    };
    result.write(linear_rgb, sidecar);
    std::cerr << "petroscope: wrote " << options.output << " and " << options.output << ".json (" << section.width_px << "x"
              << section.height_px << ", " << section.grains.size() << " grains, " << microscope.wavelengths_nm.size() << " wavelength"
              << (microscope.wavelengths_nm.size() == 1 ? "" : "s") << ", " << seconds << " s)\n";
}

}  // namespace

void add_orthoscope_command(CLI::App& app, const std::string& minerals_dir, const std::string& command_line) {
    auto options = std::make_shared<OrthoscopeOptions>();
    CLI::App* command = app.add_subcommand(
        "orthoscope",
        "Render a thin section as seen through the eyepieces: plane-polarized light (--ppl: absorption,\n"
        "pleochroism) or crossed polars (--xpl, the default: interference colours, extinction), with the stage\n"
        "turned and an accessory plate. Frames and angle senses: docs/conventions.md; the model: docs/orthoscope.md.");
    command->add_option("--section", options->section, "Thin section: its folder or description file (thin_sections/README.md)")->required();
    auto* ppl = command->add_flag("--ppl", options->ppl, "Plane-polarized light: analyzer out");
    command->add_flag("--xpl", options->xpl, "Crossed polars (default)")->excludes(ppl);
    command->add_option("--stage-deg", options->stage_deg, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    add_plate_options(command, options->plate);
    command->add_option("--condenser-na", options->condenser_na, "Condenser cone (Koehler), 0 = parallel light")->capture_default_str();
    command->add_option("--condenser-rings", options->condenser_rings, "Rings of directions sampling the cone (0: automatic, NA/0.05)")->capture_default_str();
    command->add_option("--thickness", options->thickness, "Override the section's thickness with a uniform one: 30um, …");
    command->add_flag("--exact", options->exact, "Coherent 4x4 transfer matrix (every multiple reflection) instead of single-pass Jones");
    add_light_options(command, options->light);
    command->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    command->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_option("-o,--output", options->output, "Output image: .png (sRGB), .exr or .tif (float); a JSON sidecar <output>.json is written beside it")->required();
    command->callback([options, &minerals_dir, command_line] { run_orthoscope(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
