// petroscope conoscope: interference figures.
#include "cli_common.hpp"
#include "cli_light.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <chrono>
#include <iostream>
#include <memory>

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
    LightOptions light;
    double stage_deg = 0.0;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    bool no_analyzer = false;
    double surround_n = 1.54;
    bool stack = false;
    bool exact = false;
    PlateOptions plate;
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
    const ResolvedLight light_used = resolve_light(options.light);
    settings.wavelengths_nm = light_used.wavelengths_nm;
    settings.validate();
    ImageResult result(options.output);  // fails now, before rendering, if the output cannot be written

    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    const Mineral& mineral = catalog.find(options.mineral);
    settings.plate = make_plate(options.plate, catalog);
    if (options.stack || options.exact) {
        settings.mounting = standard_mounting(catalog);
        settings.exact = options.exact;
        settings.validate();
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
    nlohmann::json light;
    const Image linear_rgb = render_in_light(
        options.light, light_used,
        [&](const SpectralIntegrator* integrator) { return render_conoscope(settings, principal_n, integrator, progress); },
        "parallel polars without the crystal", light);
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
        {"surround_n", settings.mounting ? nlohmann::json(nullptr) : nlohmann::json(settings.surround_n)},
        {"mounting", settings.mounting ? nlohmann::json{{"slide", "crown glass"}, {"slide_um", settings.mounting->slide_um},
                                                        {"cement", "canada balsam"}, {"lower_cement_um", settings.mounting->lower_cement_um},
                                                        {"upper_cement_um", settings.mounting->upper_cement_um}, {"cover", "crown glass"},
                                                        {"cover_um", settings.mounting->cover_um}}
                                       : nlohmann::json(nullptr)},
        {"plate", plate_json(settings.plate)},
        {"size_px", settings.size_px},
        {"exposure", options.light.exposure},
        {"light", light},
        {"model", settings.exact ? "exact coherent 4x4 transfer matrix (Berreman) through the whole section, per image point"
                  : settings.mounting ? "single-pass Jones through the whole section (every layer's exact waves, Fresnel at every interface), per image point"
                                      : "single-pass Jones through the slab from its exact eigenmodes, Fresnel transmission at both faces, no multiple reflections"},
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
    add_light_options(command, options->light);
    command->add_option("--stage-deg", options->stage_deg, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    command->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    auto* analyzer = command->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_flag("--no-analyzer", options->no_analyzer, "Take the analyzer out (plane-polarized light)")->excludes(analyzer);
    add_plate_options(command, options->plate);
    auto* surround = command->add_option("--surround-n", options->surround_n, "Index of the mounting medium on both faces (Canada balsam ~1.54)")->capture_default_str();
    command->add_flag("--stack", options->stack,
                      "The whole thin section: air, slide glass, balsam, crystal, balsam, cover glass, air (docs/orthoscope.md); slower")
        ->excludes(surround);
    command->add_flag("--exact", options->exact, "With the whole stack: coherent 4x4 transfer matrix, every multiple reflection; slowest")
        ->excludes(surround);
    command->add_option("-o,--output", options->output, "Output image: .png (sRGB, for viewing), .exr or .tif (float); a JSON sidecar <output>.json is written beside it")->required();
    command->callback([options, &minerals_dir, command_line] { run_conoscope(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
