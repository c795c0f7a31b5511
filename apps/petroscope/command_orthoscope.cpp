// petroscope orthoscope: a thin section under plane-polarized light or between crossed polars.
#include "cli_common.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

namespace petroscope::cli {
namespace {

struct OrthoscopeOptions {
    std::string section;
    bool ppl = false;
    bool xpl = false;
    double stage_deg = 0.0;
    std::string plate;
    double plate_deg = 45.0;
    double wedge_position = 0.5;
    double condenser_na = 0.0;
    int condenser_rings = 0;
    std::string thickness;
    bool exact = false;
    std::string wavelength;
    std::string wavelength_grid = "380:780:5";
    std::string illuminant = "D65";
    bool no_white_balance = false;
    double exposure = 1.0;
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
    if (!(options.exposure > 0.0)) throw InputError("--exposure must be > 0");
    OrthoscopeSettings settings;
    MicroscopeSettings& microscope = settings.microscope;
    microscope.stage_deg = options.stage_deg;
    microscope.polars = {options.polarizer_deg, options.analyzer_deg, !options.ppl};
    microscope.condenser_na = options.condenser_na;
    microscope.condenser_rings = options.condenser_rings;
    microscope.exact = options.exact;
    if (options.condenser_rings < 0 || options.condenser_rings > 64) throw InputError("--condenser-rings must be 0 (automatic) to 64");

    const bool monochromatic = !options.wavelength.empty();
    std::optional<WavelengthGrid> grid;
    if (monochromatic) {
        microscope.wavelengths_nm = {with_option("--wavelength", [&] { return parse_wavelength_nm(options.wavelength); })};
    } else {
        grid = with_option("--wavelengths", [&] { return WavelengthGrid::parse(options.wavelength_grid); });
        microscope.wavelengths_nm = grid->wavelengths_nm();
    }
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    settings.mounting = standard_mounting(catalog);
    if (!options.plate.empty()) {
        const PlateKind kind = with_option("--plate", [&] { return parse_plate(options.plate); });
        microscope.plate = with_option("--plate", [&] {
            return make_accessory_plate(kind, catalog.find(plate_mineral_name(kind)), options.plate_deg, options.wedge_position);
        });
    }
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
    Image linear_rgb;
    nlohmann::json light;
    if (monochromatic) {
        linear_rgb = gray_image_to_rgb(render_orthoscope(section, catalog, settings, nullptr, progress), options.exposure);
        light = {{"mode", "monochromatic"}, {"wavelength_nm", microscope.wavelengths_nm[0]},
                 {"pixel_values", "transmitted intensity relative to the incident (after the polarizer), in every channel, times exposure"}};
    } else {
        const LightSource source = load_light_source(options.illuminant);
        const SpectralIntegrator integrator(microscope.wavelengths_nm, load_cie_1931_observer(), source);
        const Image xyz = render_orthoscope(section, catalog, settings, &integrator, progress);
        linear_rgb = xyz_image_to_linear_srgb(xyz, integrator.white_xyz(), !options.no_white_balance, options.exposure);
        light = {{"mode", "white"}, {"illuminant", source.name},
                 {"wavelengths_nm", {{"start", grid->start_nm}, {"end", grid->end_nm}, {"step", grid->step_nm}, {"count", grid->size()}}},
                 {"white_balance", !options.no_white_balance},
                 {"pixel_values", "linear sRGB (EXR/TIFF) or encoded sRGB (PNG); white = the light after the polarizer, times exposure"}};
    }
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
        {"plate", microscope.plate ? nlohmann::json{{"kind", plate_name(microscope.plate->kind)},
                                                    {"thickness_um", microscope.plate->thickness_um},
                                                    {"slow_deg", microscope.plate->slow_deg},
                                                    {"description", microscope.plate->description}}
                                   : nlohmann::json(nullptr)},
        {"condenser_na", microscope.condenser_na},
        {"condenser_directions", condenser_samples(microscope.condenser_na, microscope.condenser_rings > 0 ? microscope.condenser_rings
                                                                                                         : default_condenser_rings(microscope.condenser_na)).size()},
        {"mounting", {{"slide", "crown glass"}, {"slide_um", mounting.slide_um}, {"cement", "canada balsam"},
                      {"lower_cement_um", mounting.lower_cement_um}, {"upper_cement_um", mounting.upper_cement_um},
                      {"cover", "crown glass"}, {"cover_um", mounting.cover_um}}},
        {"model", microscope.exact ? "exact coherent 4x4 transfer matrix (Berreman) per element: section, plate"
                                   : "single-pass Jones from the exact eigenmodes of every layer, Fresnel at every interface, no multiple reflections"},
        {"exposure", options.exposure},
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
    command->add_option("--plate", options->plate, "Accessory plate: gypsum (first-order red), mica (quarter wave), wedge (quartz wedge)");
    command->add_option("--plate-deg", options->plate_deg, "The plate's slow direction, degrees from E toward N (45: NE-SW)")->capture_default_str();
    command->add_option("--wedge-position", options->wedge_position, "How far the quartz wedge is pushed in, 0 to 1 (0 to 4 orders)")->capture_default_str();
    command->add_option("--condenser-na", options->condenser_na, "Condenser cone (Koehler), 0 = parallel light")->capture_default_str();
    command->add_option("--condenser-rings", options->condenser_rings, "Rings of directions sampling the cone (0: automatic, NA/0.05)")->capture_default_str();
    command->add_option("--thickness", options->thickness, "Override the section's thickness with a uniform one: 30um, …");
    command->add_flag("--exact", options->exact, "Coherent 4x4 transfer matrix (every multiple reflection) instead of single-pass Jones");
    command->add_option("--wavelength", options->wavelength, "Monochromatic light at this wavelength (589nm, 0.633um); default: white light");
    command->add_option("--wavelengths", options->wavelength_grid, "White-light grid START:END:STEP in nm")->capture_default_str();
    command->add_option("--illuminant", options->illuminant, "White light: D65, A (halogen) or blackbody:3200K")->capture_default_str();
    command->add_flag("--no-white-balance", options->no_white_balance, "Keep the colour cast of the illuminant");
    command->add_option("--exposure", options->exposure, "Scale the image brightness")->capture_default_str();
    command->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    command->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_option("-o,--output", options->output, "Output image: .png (sRGB), .exr or .tif (float); a JSON sidecar <output>.json is written beside it")->required();
    command->callback([options, &minerals_dir, command_line] { run_orthoscope(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
