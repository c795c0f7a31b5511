// petroscope conoscope: interference figures.
#include "cli_common.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

namespace petroscope::cli {
namespace {

struct ConoscopeOptions {
    std::string mineral = "muscovite";
    std::string thickness = "30um";
    std::string cut;
    double azimuth_deg = 0.0;
    double tilt_deg = 0.0;
    std::string euler;
    double na = 0.85;
    int size_px = 512;
    std::string wavelength;
    std::string wavelength_grid = "380:780:5";
    std::string illuminant = "D65";
    bool no_white_balance = false;
    double exposure = 1.0;
    double stage_deg = 0.0;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    bool no_analyzer = false;
    double surround_n = 1.54;
    std::string plate;
    double plate_deg = 45.0;
    double wedge_position = 0.5;
    std::string output;
};

Eigen::Vector3d parse_euler(const std::string& text) {
    const auto parts = split(text, ',');
    Eigen::Vector3d angles;
    if (parts.size() == 3) {
        for (int i = 0; i < 3; ++i) {
            const auto value = parse_double(parts[static_cast<std::size_t>(i)]);
            if (!value) break;
            angles[i] = *value;
            if (i == 2) return angles;
        }
    }
    throw InputError("--euler '" + text + "': expected three angles in degrees, a,b,c (ZYZ: R = Rz(a)·Ry(b)·Rz(c))");
}

void run_conoscope(const ConoscopeOptions& options, const std::string& minerals_dir, const std::string& command_line) {
    const auto started = std::chrono::steady_clock::now();
    ConoscopeSettings settings;
    settings.thickness_um = with_option("--thickness", [&] { return parse_length_um(options.thickness); });
    if (!(settings.thickness_um > 0.0)) throw InputError("--thickness '" + options.thickness + "': the thickness must be > 0");
    settings.numerical_aperture = options.na;
    settings.size_px = options.size_px;
    settings.stage_deg = options.stage_deg;
    settings.polarizer_deg = options.polarizer_deg;
    settings.analyzer_deg = options.analyzer_deg;
    settings.analyzer_in = !options.no_analyzer;
    settings.surround_n = options.surround_n;
    if (!(options.exposure > 0.0)) throw InputError("--exposure must be > 0");

    const bool monochromatic = !options.wavelength.empty();
    std::optional<WavelengthGrid> grid;
    if (monochromatic) {
        settings.wavelengths_nm = {with_option("--wavelength", [&] { return parse_wavelength_nm(options.wavelength); })};
        if (!(settings.wavelengths_nm[0] > 0.0)) throw InputError("--wavelength '" + options.wavelength + "': must be > 0");
    } else {
        grid = with_option("--wavelengths", [&] { return WavelengthGrid::parse(options.wavelength_grid); });
        settings.wavelengths_nm = grid->wavelengths_nm();
    }
    settings.validate();
    ImageResult result(options.output);  // fails now, before rendering, if the output cannot be written

    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    const Mineral& mineral = catalog.find(options.mineral);
    if (!options.plate.empty()) {
        const PlateKind kind = with_option("--plate", [&] { return parse_plate(options.plate); });
        settings.plate = with_option("--plate", [&] {
            return make_accessory_plate(kind, catalog.find(plate_mineral_name(kind)), options.plate_deg, options.wedge_position);
        });
    }
    if (mineral.absorbing()) {
        std::cerr << "petroscope: note: " << mineral.name
                  << " absorbs (pleochroism); the conoscope uses its refractive indices only, absorption is left out\n";
    }
    for (const auto& warning : mineral.range_warnings(settings.wavelengths_nm)) std::cerr << "petroscope: warning: " << warning << '\n';

    const Eigen::Vector3d reference_n = mineral.principal_n(mineral.reference_wavelength_nm);
    std::string cut_used;
    if (!options.euler.empty()) {
        const Eigen::Vector3d angles = parse_euler(options.euler);
        settings.crystal_axes = euler_zyz_deg(angles[0], angles[1], angles[2]);
    } else {
        const Cut cut = !options.cut.empty() ? parse_cut(options.cut)
                        : mineral.optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
        cut_used = std::string(cut_name(cut));
        settings.crystal_axes = cut_orientation(cut, mineral.optical_class, reference_n, options.azimuth_deg, options.tilt_deg);
    }

    const PrincipalIndexFunction principal_n = [&mineral](double nm) { return mineral.principal_n(nm); };
    const auto progress = [](double fraction) { show_progress("rendering", fraction); };
    Image linear_rgb;
    nlohmann::json light;
    if (monochromatic) {
        const Image intensity = render_conoscope(settings, principal_n, nullptr, progress);
        linear_rgb = gray_image_to_rgb(intensity, options.exposure);
        light = {{"mode", "monochromatic"}, {"wavelength_nm", settings.wavelengths_nm[0]},
                 {"pixel_values", "transmitted intensity relative to the incident (after the polarizer), in every channel, times exposure"}};
    } else {
        const LightSource source = load_light_source(options.illuminant);
        const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), source);
        const Image xyz = render_conoscope(settings, principal_n, &integrator, progress);
        linear_rgb = xyz_image_to_linear_srgb(xyz, integrator.white_xyz(), !options.no_white_balance, options.exposure);
        light = {{"mode", "white"}, {"illuminant", source.name},
                 {"wavelengths_nm", {{"start", grid->start_nm}, {"end", grid->end_nm}, {"step", grid->step_nm}, {"count", grid->size()}}},
                 {"white_balance", !options.no_white_balance},
                 {"pixel_values", "linear sRGB (EXR/TIFF) or encoded sRGB (PNG); white = parallel polars without the crystal, times exposure"}};
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    nlohmann::json axes = nlohmann::json::array();
    const Eigen::Matrix3d staged = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    for (int c = 0; c < 3; ++c) axes.push_back({staged(0, c), staged(1, c), staged(2, c)});
    const nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "conoscope"},
        {"command_line", command_line},
        {"mineral", {{"name", mineral.name}, {"file", mineral.file},
                     {"principal_n_xyz_at_reference", {reference_n[0], reference_n[1], reference_n[2]}},
                     {"reference_wavelength_nm", mineral.reference_wavelength_nm}}},
        {"thickness_um", settings.thickness_um},
        {"orientation", {{"cut", cut_used.empty() ? nlohmann::json(nullptr) : nlohmann::json(cut_used)},
                         {"azimuth_deg", options.azimuth_deg}, {"tilt_deg", options.tilt_deg},
                         {"euler_zyz_deg", options.euler.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.euler)},
                         {"indicatrix_axes_xyz_lab_after_stage", axes}}},
        {"stage_deg", settings.stage_deg},
        {"polarizer_deg", settings.polarizer_deg},
        {"analyzer_deg", settings.analyzer_in ? nlohmann::json(settings.analyzer_deg) : nlohmann::json(nullptr)},
        {"analyzer_in", settings.analyzer_in},
        {"numerical_aperture", settings.numerical_aperture},
        {"surround_n", settings.surround_n},
        {"plate", settings.plate ? nlohmann::json{{"kind", plate_name(settings.plate->kind)}, {"thickness_um", settings.plate->thickness_um},
                                                  {"slow_deg", settings.plate->slow_deg}, {"description", settings.plate->description}}
                                 : nlohmann::json(nullptr)},
        {"size_px", settings.size_px},
        {"exposure", options.exposure},
        {"light", light},
        {"model", "single-pass Jones through the slab from its exact eigenmodes, Fresnel transmission at both faces, no multiple reflections"},
        {"image_frame", "x to the East (right), y to the North (up); image point (x, y) shows the wave with sin(theta_air)(cos phi, sin phi) = NA (x, y)"},
        {"seconds", seconds},
    };
    result.write(linear_rgb, sidecar);
    std::cerr << "petroscope: wrote " << options.output << " and " << options.output << ".json (" << settings.size_px << "x"
              << settings.size_px << ", " << settings.wavelengths_nm.size() << " wavelength"
              << (settings.wavelengths_nm.size() == 1 ? "" : "s") << ", " << seconds << " s)\n";
}

}  // namespace

void add_conoscope_command(CLI::App& app, const std::string& minerals_dir, const std::string& command_line) {
    auto options = std::make_shared<ConoscopeOptions>();
    CLI::App* command = app.add_subcommand(
        "conoscope",
        "Render the interference figure of a crystal slab (conoscopic view through the Bertrand lens).\n"
        "Default: muscovite, 30 um, cut perpendicular to the acute bisectrix, crossed polars (polarizer E-W,\n"
        "analyzer N-S), NA 0.85, white light (D65). Frames and angle senses: docs/conventions.md.");
    command->add_option("--mineral", options->mineral, "Mineral name or alias ('petroscope minerals' lists them)")->capture_default_str();
    command->add_option("--thickness", options->thickness, "Slab thickness with unit: 30um, 1mm, …")->capture_default_str();
    auto* cut = command->add_option("--cut", options->cut,
                                    "optic-axis | acute-bisectrix | obtuse-bisectrix | optic-normal: which crystal direction lies along the\n"
                                    "microscope axis (default: acute-bisectrix for biaxial, optic-axis for uniaxial minerals)");
    auto* azimuth = command->add_option("--azimuth-deg", options->azimuth_deg,
                                        "Turn the crystal about the microscope axis (counter-clockwise); at 0 the optic axial plane\n"
                                        "(or an inclined uniaxial optic axis) lies E-W");
    auto* tilt = command->add_option("--tilt-deg", options->tilt_deg,
                                     "Tilt the cut direction away from the microscope axis toward the azimuth (off-centre figures)");
    command->add_option("--euler", options->euler, "Orientation as ZYZ Euler angles a,b,c in degrees (instead of --cut)")
        ->excludes(cut)->excludes(azimuth)->excludes(tilt);
    command->add_option("--na", options->na, "Numerical aperture of the objective (0 < NA < 1)")->capture_default_str();
    command->add_option("--size", options->size_px, "Image width and height in pixels (64 to 4096)")->capture_default_str();
    command->add_option("--wavelength", options->wavelength, "Monochromatic light at this wavelength (589nm, 0.633um); default: white light");
    command->add_option("--wavelengths", options->wavelength_grid, "White-light grid START:END:STEP in nm")->capture_default_str();
    command->add_option("--illuminant", options->illuminant, "White light: D65, A (halogen) or blackbody:3200K")->capture_default_str();
    command->add_flag("--no-white-balance", options->no_white_balance, "Keep the colour cast of the illuminant");
    command->add_option("--exposure", options->exposure, "Scale the image brightness")->capture_default_str();
    command->add_option("--stage-deg", options->stage_deg, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    command->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    auto* analyzer = command->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_flag("--no-analyzer", options->no_analyzer, "Take the analyzer out (plane-polarized light)")->excludes(analyzer);
    command->add_option("--plate", options->plate, "Accessory plate: gypsum (first-order red), mica (quarter wave), wedge (quartz wedge)");
    command->add_option("--plate-deg", options->plate_deg, "The plate's slow direction, degrees from E toward N (45: NE-SW)")->capture_default_str();
    command->add_option("--wedge-position", options->wedge_position, "How far the quartz wedge is pushed in, 0 to 1 (0 to 4 orders)")->capture_default_str();
    command->add_option("--surround-n", options->surround_n, "Index of the mounting medium on both faces (Canada balsam ~1.54)")->capture_default_str();
    command->add_option("-o,--output", options->output, "Output image: .png (sRGB, for viewing), .exr or .tif (float); a JSON sidecar <output>.json is written beside it")->required();
    command->callback([options, &minerals_dir, command_line] { run_conoscope(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
