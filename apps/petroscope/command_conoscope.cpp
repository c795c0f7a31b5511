// petroscope conoscope: interference figures.
#include "cli_common.hpp"
#include "cli_light.hpp"
#include "frame_command.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/microscope/frame_measurements.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>
#include <memory>
#include <numbers>

namespace petroscope::cli {
namespace {

class ConoscopeOptions final : public FrameOptions {
public:
    std::string command() const override { return "conoscope"; }
    std::string description() const override {
        return "Render the interference figure of a crystal slab (conoscopic view through the Bertrand lens).\n"
               "Default: muscovite, 30 um, cut perpendicular to the acute bisectrix, crossed polars (polarizer E-W,\n"
               "analyzer N-S), NA 0.85, white light (D65). Frames and angle senses: docs/conventions.md.";
    }
    void add_options(CLI::App* command) override;
    PreparedFrame prepare(FrameContext& context) const override;

private:
    std::string mineral_ = "muscovite";
    std::string thickness_ = "30um";
    std::string cut_;
    double azimuth_deg_ = 0.0;
    double tilt_deg_ = 0.0;
    std::string euler_;
    double na_ = 0.85;
    int size_px_ = 512;
    LightOptions light_;
    double stage_deg_ = 0.0;
    double polarizer_deg_ = 0.0;
    double analyzer_deg_ = 90.0;
    bool no_analyzer_ = false;
    double surround_n_ = 1.54;
    bool stack_ = false;
    bool exact_ = false;
    PlateOptions plate_;
};

// Measured on the figure: its mean colour, and per optic axis its point in the field (x, y, azimuth from E
// toward N, radius; 1 = the field's edge) where the exact model puts it, and the dark spot found there when
// the polars are crossed and no plate is in (a melatope); null where there is nothing to measure.
nlohmann::json measure_figure(const Image& linear_rgb, const ConoscopeSettings& settings, const Eigen::Vector3d& principal_n) {
    const MeanColour mean = mean_colour(linear_rgb, true);
    nlohmann::json measured{{"mean_r", mean.r}, {"mean_g", mean.g}, {"mean_b", mean.b}, {"mean_luminance", mean.luminance}};
    const std::vector<Eigen::Vector2d> axes = conoscope_optic_axis_points(settings, principal_n);
    const double crossed = std::remainder(settings.analyzer_deg - settings.polarizer_deg, 180.0);
    const bool dark_melatopes = settings.analyzer_in && std::abs(std::abs(crossed) - 90.0) < 1e-9 && !settings.plate;
    for (std::size_t k = 0; k < 2; ++k) {
        const std::string axis = "optic_axis_" + std::to_string(k + 1), melatope = "melatope_" + std::to_string(k + 1);
        std::optional<Eigen::Vector2d> predicted, found;
        if (k < axes.size() && axes[k].norm() < 1.0) predicted = axes[k];
        if (predicted && dark_melatopes) found = dark_spot_near(linear_rgb, *predicted, settings.size_px / 32, settings.size_px / 256.0);
        for (const auto& [name, point] : {std::pair{axis, predicted}, std::pair{melatope, found}}) {
            const auto value = [&](double number) { return point ? nlohmann::json(number) : nlohmann::json(nullptr); };
            const Eigen::Vector2d p = point.value_or(Eigen::Vector2d::Zero());
            const double azimuth_deg = std::atan2(p.y(), p.x()) * 180.0 / std::numbers::pi;
            measured[name + "_x"] = value(p.x());
            measured[name + "_y"] = value(p.y());
            measured[name + "_azimuth_deg"] = value(azimuth_deg < 0.0 ? azimuth_deg + 360.0 : azimuth_deg);
            measured[name + "_radius"] = value(p.norm());
        }
    }
    return measured;
}

PreparedFrame ConoscopeOptions::prepare(FrameContext& context) const {
    ConoscopeSettings settings;
    settings.thickness_um = positive_length_um("--thickness", thickness_);
    settings.numerical_aperture = na_;
    settings.size_px = size_px_;
    settings.stage_deg = stage_deg_;
    settings.polarizer_deg = polarizer_deg_;
    settings.analyzer_deg = analyzer_deg_;
    settings.analyzer_in = !no_analyzer_;
    settings.surround_n = surround_n_;
    const ResolvedLight light_used = resolve_light(light_);
    settings.wavelengths_nm = light_used.wavelengths_nm;
    settings.validate();

    const MineralCatalog& catalog = context.catalog();
    const Mineral& mineral = catalog.find(mineral_);
    settings.plate = make_plate(plate_, catalog);
    if (stack_ || exact_) {
        settings.mounting = standard_mounting(catalog);
        settings.exact = exact_;
        settings.validate();
    }
    PreparedFrame prepared;
    if (mineral.absorbing()) {
        prepared.notes.push_back("note: " + mineral.name + " absorbs (pleochroism); the conoscope uses its refractive indices only, absorption is left out");
    }
    for (const auto& warning : mineral.range_warnings(settings.wavelengths_nm)) prepared.notes.push_back("warning: " + warning);

    const Eigen::Vector3d reference_n = mineral.principal_n(mineral.reference_wavelength_nm);
    std::string cut_used;
    if (!euler_.empty()) {
        const std::array<double, 3> angles = euler_angles_deg("--euler", euler_);
        settings.crystal_axes = euler_zyz_deg(angles[0], angles[1], angles[2]);
    } else {
        const Cut cut = !cut_.empty() ? parse_cut(cut_)
                        : mineral.optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
        cut_used = std::string(cut_name(cut));
        settings.crystal_axes = cut_orientation(cut, mineral.optical_class, reference_n, azimuth_deg_, tilt_deg_);
    }

    nlohmann::json axes = nlohmann::json::array();
    const Eigen::Matrix3d staged = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    for (int c = 0; c < 3; ++c) axes.push_back({staged(0, c), staged(1, c), staged(2, c)});
    nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "conoscope"},
        {"mineral", {{"name", mineral.name}, {"file", mineral.file},
                     {"principal_n_xyz_at_reference", {reference_n[0], reference_n[1], reference_n[2]}},
                     {"reference_wavelength_nm", mineral.reference_wavelength_nm}}},
        {"thickness_um", settings.thickness_um},
        {"orientation", {{"cut", cut_used.empty() ? nlohmann::json(nullptr) : nlohmann::json(cut_used)},
                         {"azimuth_deg", azimuth_deg_}, {"tilt_deg", tilt_deg_},
                         {"euler_zyz_deg", euler_.empty() ? nlohmann::json(nullptr) : nlohmann::json(euler_)},
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
        {"exposure", light_.exposure},
        {"model", settings.exact ? "exact coherent 4x4 transfer matrix (Berreman) through the whole section, per image point"
                  : settings.mounting ? "single-pass Jones through the whole section (every layer's exact waves, Fresnel at every interface), per image point"
                                      : "single-pass Jones through the slab from its exact eigenmodes, Fresnel transmission at both faces, no multiple reflections"},
        {"image_frame", "x to the East (right), y to the North (up); image point (x, y) shows the wave with sin(theta_air)(cos phi, sin phi) = NA (x, y)"},
        {"measurements_frame", "field points: x to the East, y to the North, 1 = the edge of the field; azimuths from East toward North; "
                               "optic_axis: where the model images the optic axis (at measurements_axes_wavelength_nm); melatope: the dark spot measured there"},
    };
    const LightOptions light_options = light_;
    // The optic axes disperse: they are placed at the light's wavelength, in white light at 555 nm (the peak of
    // the photopic luminous efficiency, CIE 1924).
    const double axes_wavelength_nm = light_used.monochromatic() ? settings.wavelengths_nm.front() : 555.0;
    sidecar["measurements_axes_wavelength_nm"] = axes_wavelength_nm;
    prepared.render = [settings, light_options, light_used, &mineral, sidecar, axes_wavelength_nm](const ProgressCallback& progress) {
        const PrincipalIndexFunction principal_n = [&mineral](double nm) { return mineral.principal_n(nm); };
        RenderedFrame frame;
        frame.sidecar = sidecar;
        frame.linear_rgb = render_in_light(
            light_options, light_used,
            [&](const SpectralIntegrator* integrator) { return render_conoscope(settings, principal_n, integrator, progress); },
            "parallel polars without the crystal", frame.sidecar["light"]);
        frame.sidecar["measurements"] = measure_figure(frame.linear_rgb, settings, mineral.principal_n(axes_wavelength_nm));
        const std::size_t count = settings.wavelengths_nm.size();
        frame.summary = std::to_string(settings.size_px) + "x" + std::to_string(settings.size_px) + ", " + std::to_string(count) +
                        " wavelength" + (count == 1 ? "" : "s");
        return frame;
    };
    return prepared;
}

void ConoscopeOptions::add_options(CLI::App* command) {
    command->add_option("--mineral", mineral_, "Mineral name or alias ('petroscope minerals' lists them)")->capture_default_str();
    command->add_option("--thickness", thickness_, "Slab thickness with unit: 30um, 1mm, …")->capture_default_str()->type_name(length_type);
    auto* cut = command->add_option("--cut", cut_,
                                    "optic-axis | acute-bisectrix | obtuse-bisectrix | optic-normal: which crystal direction lies along the\n"
                                    "microscope axis (default: acute-bisectrix for biaxial, optic-axis for uniaxial minerals)");
    auto* azimuth = command->add_option("--azimuth-deg", azimuth_deg_,
                                        "Turn the crystal about the microscope axis (counter-clockwise); at 0 the optic axial plane\n"
                                        "(or an inclined uniaxial optic axis) lies E-W");
    auto* tilt = command->add_option("--tilt-deg", tilt_deg_,
                                     "Tilt the cut direction away from the microscope axis toward the azimuth (off-centre figures)");
    command->add_option("--euler", euler_, "Orientation as ZYZ Euler angles a,b,c in degrees (instead of --cut)")
        ->excludes(cut)->excludes(azimuth)->excludes(tilt);
    command->add_option("--na", na_, "Numerical aperture of the objective (0 < NA < 1)")->capture_default_str();
    command->add_option("--size", size_px_, "Image width and height in pixels (64 to 4096)")->capture_default_str();
    add_light_options(command, light_);
    command->add_option("--stage-deg", stage_deg_, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    command->add_option("--polarizer-deg", polarizer_deg_, "Polarizer direction, degrees from E toward N")->capture_default_str();
    auto* analyzer = command->add_option("--analyzer-deg", analyzer_deg_, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_flag("--no-analyzer", no_analyzer_, "Take the analyzer out (plane-polarized light)")->excludes(analyzer);
    add_plate_options(command, plate_);
    auto* surround = command->add_option("--surround-n", surround_n_, "Index of the mounting medium on both faces (Canada balsam ~1.54)")->capture_default_str();
    command->add_flag("--stack", stack_,
                      "The whole thin section: air, slide glass, balsam, crystal, balsam, cover glass, air (docs/orthoscope.md); slower")
        ->excludes(surround);
    command->add_flag("--exact", exact_, "With the whole stack: coherent 4x4 transfer matrix, every multiple reflection; slowest")
        ->excludes(surround);
}

}  // namespace

std::unique_ptr<FrameOptions> make_conoscope_options() { return std::make_unique<ConoscopeOptions>(); }

}  // namespace petroscope::cli
