// petroscope conoscope: interference figures.
#include "cli_common.hpp"
#include "cli_light.hpp"
#include "frame_command.hpp"

#include "petroscope/api/conoscope_figure.hpp"

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
    ConoscopeRequest request() const;

    ConoscopeRequest plain_;  // the options bound as they are (numbers, names); defaults: the library's
    std::string thickness_ = "30um";
    std::string cut_;
    std::string euler_;
    LightOptions light_;
    bool no_analyzer_ = false;
    bool stack_ = false;
    bool exact_ = false;
    bool exact_spectrum_ = false;
    std::string handedness_ = "right";
    PlateOptions plate_;
};

ConoscopeRequest ConoscopeOptions::request() const {
    ConoscopeRequest request = plain_;
    request.thickness_um = positive_length_um("--thickness", thickness_);
    if (!euler_.empty()) {
        const std::array<double, 3> angles = euler_angles_deg("--euler", euler_);
        request.orientation.euler_zyz_deg = Eigen::Vector3d(angles[0], angles[1], angles[2]);
    } else if (!cut_.empty()) {
        request.orientation.cut = with_option("--cut", [&] { return parse_cut(cut_); });
    }
    request.light = light_from_options(light_);
    request.analyzer_in = !no_analyzer_;
    request.mounting = exact_ ? SlabMounting::thin_section_exact : stack_ ? SlabMounting::thin_section : SlabMounting::immersed;
    request.plate = plate_request(plate_);
    request.spectrum = exact_spectrum_ ? SpectrumSampling::exact : SpectrumSampling::interpolated;
    request.handedness = with_option("--handedness", [&] { return parse_handedness(handedness_); });
    return request;
}

// The optical activity used: the handedness and the rotatory powers along X, Y, Z at the reference wavelength.
nlohmann::json optical_activity_json(const ConoscopePlan& plan) {
    if (!plan.handedness) return nullptr;
    const Mineral& mineral = *plan.mineral;
    const double sign = *plan.handedness == Handedness::right ? 1.0 : -1.0;
    const Eigen::Vector3d rho = sign * mineral.principal_rotatory_power(mineral.reference_wavelength_nm) * 180.0 / std::numbers::pi * 1e3;
    return {{"handedness", handedness_name(*plan.handedness)},
            {"rotatory_power_deg_per_mm_xyz_at_reference", {rho[0], rho[1], rho[2]}},
            {"model", "gyration tensor g = lambda rho / pi along the indicatrix axes (positive: dextrorotatory); it couples the two "
                      "modes across the slab (first-order coupled modes, docs/theory.md 'Optical activity')"}};
}

// Every parameter of the figure but the light's (known once rendered).
nlohmann::json conoscope_sidecar(const ConoscopeRequest& request, const ConoscopePlan& plan) {
    const ConoscopeSettings& settings = plan.settings;
    const Mineral& mineral = *plan.mineral;
    const Eigen::Vector3d reference_n = mineral.principal_n(mineral.reference_wavelength_nm);
    nlohmann::json axes = nlohmann::json::array();
    const Eigen::Matrix3d staged = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    for (int c = 0; c < 3; ++c) axes.push_back({staged(0, c), staged(1, c), staged(2, c)});
    const auto& euler = request.orientation.euler_zyz_deg;
    return {
        {"program", "petroscope 0.1.0"},
        {"command", "conoscope"},
        {"mineral", {{"name", mineral.name}, {"file", mineral.file},
                     {"principal_n_xyz_at_reference", {reference_n[0], reference_n[1], reference_n[2]}},
                     {"reference_wavelength_nm", mineral.reference_wavelength_nm}}},
        {"optical_activity", optical_activity_json(plan)},
        {"thickness_um", settings.thickness_um},
        {"orientation", {{"cut", plan.cut ? nlohmann::json(cut_name(*plan.cut)) : nlohmann::json(nullptr)},
                         {"azimuth_deg", request.orientation.azimuth_deg}, {"tilt_deg", request.orientation.tilt_deg},
                         {"euler_zyz_deg", euler ? nlohmann::json{(*euler)[0], (*euler)[1], (*euler)[2]} : nlohmann::json(nullptr)},
                         {"indicatrix_axes_xyz_lab_after_stage", axes}}},
        {"stage_deg", settings.stage_deg},
        {"polarizer_deg", settings.polarizer_deg},
        {"analyzer_deg", settings.analyzer_in ? nlohmann::json(settings.analyzer_deg) : nlohmann::json(nullptr)},
        {"analyzer_in", settings.analyzer_in},
        {"numerical_aperture", settings.numerical_aperture},
        {"surround_n", settings.mounting ? nlohmann::json(nullptr) : nlohmann::json(settings.surround_n)},
        {"mounting", settings.mounting ? mounting_json(*settings.mounting) : nlohmann::json(nullptr)},
        {"plate", plate_json(settings.plate)},
        {"size_px", settings.size_px},
        {"spectrum", interpolates_spectrum(settings)
                         ? "modes solved at " + std::to_string(kSpectralNodeCount) +
                               " wavelengths and interpolated to the others; every wavelength solved near the optic axes and where "
                               "the interpolation's error estimate is too large (docs/conoscope.md)"
                         : settings.spectrum == SpectrumSampling::exact ? "every wavelength solved (--exact-spectrum)" : "every wavelength solved"},
        {"exposure", request.light.exposure},
        {"model", settings.exact ? "exact coherent 4x4 transfer matrix (Berreman) through the whole section, per image point"
                  : settings.mounting ? "single-pass Jones through the whole section (every layer's exact waves, Fresnel at every interface), per image point"
                                      : "single-pass Jones through the slab from its exact eigenmodes, Fresnel transmission at both faces, no multiple reflections"},
        {"image_frame", "x to the East (right), y to the North (up); image point (x, y) shows the wave with sin(theta_air)(cos phi, sin phi) = NA (x, y)"},
        {"measurements_frame", "field points: x to the East, y to the North, 1 = the edge of the field; azimuths from East toward North; "
                               "optic_axis: where the model images the optic axis (at measurements_axes_wavelength_nm); melatope: the dark spot measured there"},
        {"measurements_axes_wavelength_nm", plan.axes_wavelength_nm},
    };
}

PreparedFrame ConoscopeOptions::prepare(FrameContext& context) const {
    const ConoscopeRequest request = this->request();
    const auto plan = std::make_shared<const ConoscopePlan>(plan_conoscope(request, context.catalog()));
    PreparedFrame prepared;
    prepared.notes = plan->notes;
    const nlohmann::json sidecar = conoscope_sidecar(request, *plan);
    prepared.render = [plan, sidecar](const ProgressCallback& progress) {
        const ConoscopeFigure figure = render_conoscope_figure(*plan, progress);
        RenderedFrame frame{figure.image.linear_rgb, sidecar, ""};
        frame.sidecar["light"] = light_json(plan->light, figure.image, "parallel polars without the crystal");
        frame.sidecar["measurements"] = measurements_json(figure.measurements);
        const std::size_t count = plan->settings.wavelengths_nm.size();
        frame.summary = std::to_string(plan->settings.size_px) + "x" + std::to_string(plan->settings.size_px) + ", " + std::to_string(count) +
                        " wavelength" + (count == 1 ? "" : "s");
        return frame;
    };
    return prepared;
}

void ConoscopeOptions::add_options(CLI::App* command) {
    command->add_option("--mineral", plain_.mineral, "Mineral name or alias ('petroscope minerals' lists them)")->capture_default_str();
    command->add_option("--thickness", thickness_, "Slab thickness with unit: 30um, 1mm, …")->capture_default_str()->type_name(length_type);
    auto* cut = command->add_option("--cut", cut_,
                                    "optic-axis | acute-bisectrix | obtuse-bisectrix | optic-normal: which crystal direction lies along the\n"
                                    "microscope axis (default: acute-bisectrix for biaxial, optic-axis for uniaxial minerals)");
    auto* azimuth = command->add_option("--azimuth-deg", plain_.orientation.azimuth_deg,
                                        "Turn the crystal about the microscope axis (counter-clockwise); at 0 the optic axial plane\n"
                                        "(or an inclined uniaxial optic axis) lies E-W");
    auto* tilt = command->add_option("--tilt-deg", plain_.orientation.tilt_deg,
                                     "Tilt the cut direction away from the microscope axis toward the azimuth (off-centre figures)");
    command->add_option("--euler", euler_, "Orientation as ZYZ Euler angles a,b,c in degrees (instead of --cut)")
        ->excludes(cut)->excludes(azimuth)->excludes(tilt);
    command->add_option("--na", plain_.numerical_aperture, "Numerical aperture of the objective (0 < NA < 1)")->capture_default_str();
    command->add_option("--size", plain_.size_px, "Image width and height in pixels (64 to 4096)")->capture_default_str();
    add_light_options(command, light_);
    command->add_option("--stage-deg", plain_.stage_deg, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    command->add_option("--polarizer-deg", plain_.polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    auto* analyzer = command->add_option("--analyzer-deg", plain_.analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
    command->add_flag("--no-analyzer", no_analyzer_, "Take the analyzer out (plane-polarized light)")->excludes(analyzer);
    add_plate_options(command, plate_);
    auto* surround = command->add_option("--surround-n", plain_.surround_n, "Index of the mounting medium on both faces (Canada balsam ~1.54)")->capture_default_str();
    command->add_flag("--stack", stack_,
                      "The whole thin section: air, slide glass, balsam, crystal, balsam, cover glass, air (docs/orthoscope.md); slower")
        ->excludes(surround);
    command->add_flag("--exact", exact_, "With the whole stack: coherent 4x4 transfer matrix, every multiple reflection; slowest")
        ->excludes(surround);
    command->add_option("--handedness", handedness_,
                        "right | left: which form of an optically active mineral (quartz, paratellurite: both occur; right turns the\n"
                        "plane of polarization clockwise seen looking toward the light, docs/conventions.md)")
        ->capture_default_str();
    command->add_flag("--exact-spectrum", exact_spectrum_,
                      "White light: solve the crystal's modes at every wavelength instead of at 8 and interpolating\n"
                      "(3 to 6 times slower; the reference the default is tested against, docs/conoscope.md)");
}

}  // namespace

std::unique_ptr<FrameOptions> make_conoscope_options() { return std::make_unique<ConoscopeOptions>(); }

}  // namespace petroscope::cli
