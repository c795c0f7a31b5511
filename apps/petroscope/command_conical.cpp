// petroscope conical: the screen behind a biaxial slab cut perpendicular to an optic axis (internal conical
// refraction), in wave optics (Belsky–Khapalyuk–Berry) or ray optics (the exact interface model).
#include "cli_common.hpp"
#include "frame_command.hpp"

#include "petroscope/api/conical_screen.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"

#include <cmath>
#include <memory>
#include <numbers>

namespace petroscope::cli {
namespace {

class ConicalOptions final : public FrameOptions {
public:
    std::string command() const override { return "conical"; }
    std::string description() const override {
        return "The screen behind a biaxial slab cut perpendicular to an optic axis: the double ring of internal conical\n"
               "refraction, in wave optics (paraxial Belsky-Khapalyuk-Berry theory, Gaussian beam or pinhole) or in ray\n"
               "optics (rays through a pinhole in a collimating filter, traced with the exact interface model).";
    }
    void add_options(CLI::App* command) override;
    PreparedFrame prepare(FrameContext& context) const override;

private:
    ConicalRequest request() const;

    ConicalRequest plain_;  // the options bound as they are (numbers, names); defaults: the library's
    std::string length_ = "20mm";
    std::string wavelength_ = "633nm";
    std::string mode_ = "wave";
    std::string beam_ = "gaussian";
    std::string waist_ = "40um";
    std::string pinhole_ = "25um";
    std::string filter_ = "50mm";
    std::string polarization_ = "unpolarized";
    std::string screen_distance_ = "50mm";
    bool allow_large_ = false;
};

ConicalRequest ConicalOptions::request() const {
    ConicalRequest request = plain_;
    request.length_um = positive_length_um("--length", length_);
    request.wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(wavelength_); });
    if (!(request.wavelength_nm > 0.0)) throw InputError("--wavelength must be > 0");
    if (plain_.size_px < 64 || plain_.size_px > 4096) throw InputError("--size " + std::to_string(plain_.size_px) + " is out of range (64 to 4096)");
    if (!std::isfinite(plain_.z)) throw InputError("--z must be a finite number");
    request.optics = with_option("--mode", [&] { return parse_conical_optics(mode_); });
    request.beam = with_option("--beam", [&] { return parse_conical_beam(beam_); });
    request.stokes = with_option("--polarization", [&] { return parse_polarization(polarization_); });
    if (request.optics == ConicalOptics::wave) {
        if (request.beam == ConicalBeam::gaussian) request.waist_um = positive_length_um("--waist", waist_);
        else request.pinhole_um = positive_length_um("--pinhole", pinhole_);
        return request;
    }
    request.pinhole_um = positive_length_um("--pinhole", pinhole_);
    request.filter_um = positive_length_um("--filter", filter_);
    request.screen_distance_um = positive_length_um("--screen-distance", screen_distance_);
    // Every ray's two landings are kept for the ring measurement (48 bytes a ray, twice while the threads'
    // lists are merged): about 1 GB at 10⁷ rays, 10 GB at 10⁸.
    if (plain_.rays < 1 || plain_.rays > 100000000) throw InputError("--rays must be between 1 and 1e8");
    if (plain_.rays > 10000000 && !allow_large_) {
        throw InputError("--rays " + std::to_string(plain_.rays) + " is above 1e7 (about 1 GB per 1e7 rays); add --allow-large to trace them anyway");
    }
    return request;
}

nlohmann::json conical_sidecar(const ConicalPlan& plan, const std::string& mode, const std::string& beam, const std::string& polarization) {
    const ConicalRequest& request = plan.request;
    const Eigen::Vector3d& n = plan.principal_n;
    nlohmann::json sidecar{{"program", "petroscope 0.1.0"}, {"command", "conical"},
                           {"crystal", {{"name", plan.crystal->name}, {"file", plan.crystal->file}, {"principal_n_xyz", {n[0], n[1], n[2]}}}},
                           {"wavelength_nm", request.wavelength_nm}, {"length_um", request.length_um}, {"mode", mode},
                           {"polarization", polarization}, {"cone_angle_chi_deg", plan.cone_angle_rad * 180.0 / std::numbers::pi},
                           {"A_rad", 0.5 * std::tan(plan.cone_angle_rad)}, {"R0_um", plan.ring_radius_um}, {"size_px", request.size_px},
                           {"image_half_width_um", plan.half_width_um},
                           {"image_frame", "x to the right, y up; centred on the (predicted) ring centre, which lies R0 from the point below "
                                           "the pinhole toward the second binormal"}};
    if (request.optics == ConicalOptics::wave) {
        sidecar["beam"] = beam;
        sidecar["scale_um"] = plan.scale_um;
        sidecar["rho0"] = plan.wave.rho0;
        sidecar["Z"] = plan.wave.z;
        sidecar["pixel_values"] = "intensity |D|^2 of the paraxial theory (docs/conical.md), normalised so that the brightest pixel is 1";
        return sidecar;
    }
    sidecar["pinhole_um"] = plan.ray.pinhole_radius_um;
    sidecar["filter_um"] = plan.ray.filter_um;
    sidecar["screen_distance_um"] = plan.ray.screen_distance_um;
    sidecar["rotate_deg"] = plan.ray.rotate_deg;
    sidecar["tilt_deg"] = plan.ray.tilt_deg;
    sidecar["rays"] = plan.ray.rays;
    sidecar["pixel_values"] = "collected ray power per pixel, normalised so that the brightest pixel is 1";
    return sidecar;
}

// The measurement of `name` (present by render_conical_screen's contract).
double measured(const Measurements& measurements, const std::string& name) {
    for (const Measurement& m : measurements) {
        if (m.name == name) return m.value.value_or(std::nan(""));
    }
    return std::nan("");
}

PreparedFrame ConicalOptions::prepare(FrameContext& context) const {
    const auto plan = std::make_shared<const ConicalPlan>(plan_conical(request(), context.catalog()));
    PreparedFrame prepared;
    prepared.notes = plan->notes;
    const nlohmann::json sidecar = conical_sidecar(*plan, mode_, beam_, polarization_);
    const std::string summary = mode_ + " optics, R0 = " + format_number(plan->ring_radius_um) + " um";
    prepared.render = [plan, sidecar, summary](const ProgressCallback& progress) {
        const ConicalScreen screen = render_conical_screen(*plan, progress);
        RenderedFrame frame{screen.linear_rgb, sidecar, summary};
        const Measurements& m = screen.measurements;
        const bool wave = plan->request.optics == ConicalOptics::wave;
        frame.sidecar["rings"] = {{"units", wave ? "um from the ring centre (rho in units of the beam scale: divide by scale_um)" : "um from the measured ring centre"},
                                  {"outer_bright", measured(m, "ring_outer_bright_um")}, {"dark", measured(m, "ring_dark_um")},
                                  {"inner_bright", measured(m, "ring_inner_bright_um")}};
        if (screen.power) frame.sidecar["power"] = *screen.power;
        if (!wave) {
            frame.sidecar["image_centre_um"] = {screen.image_centre_um.x(), screen.image_centre_um.y()};
            frame.sidecar["pinhole_point_um"] = {0.0, 0.0};
            frame.sidecar["rings"]["centre_um"] = {measured(m, "ring_centre_x_um"), measured(m, "ring_centre_y_um")};
            frame.sidecar["max_interface_power_sum"] = *screen.max_interface_power_sum;
        }
        frame.sidecar["measurements"] = measurements_json(m);
        return frame;
    };
    return prepared;
}

void ConicalOptions::add_options(CLI::App* command) {
    command->add_option("--crystal", plain_.crystal, "Biaxial mineral (KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite, …)")->capture_default_str();
    command->add_option("--length", length_, "Slab thickness l along the optic axis")->capture_default_str()->type_name(length_type);
    command->add_option("--wavelength", wavelength_, "Wavelength")->capture_default_str()->type_name(wavelength_type);
    command->add_option("--mode", mode_, "wave or ray")->capture_default_str();
    command->add_option("--beam", beam_, "Wave mode: gaussian (waist --waist) or pinhole (radius --pinhole)")->capture_default_str();
    command->add_option("--waist", waist_, "Gaussian beam scale w, E(r) = exp(-r^2/2w^2)")->capture_default_str()->type_name(length_type);
    command->add_option("--pinhole", pinhole_, "Pinhole radius R")->capture_default_str()->type_name(length_type);
    command->add_option("--filter", filter_, "Ray mode: thickness h of the filter holding the pinhole (rays tilt by at most ~2R/h)")
        ->capture_default_str()->type_name(length_type);
    command->add_option("--polarization", polarization_, "unpolarized, linear:ANGLE (degrees from +x), circular[:left]")->capture_default_str();
    command->add_option("--z", plain_.z, "Wave mode: observation plane Z (dimensionless, docs/conical.md; 0 = focal image plane)")->capture_default_str();
    command->add_option("--rotate-deg", plain_.rotate_deg, "Ray mode: turn the slab about its optic axis")->capture_default_str();
    command->add_option("--tilt-deg", plain_.tilt_deg, "Ray mode: tilt the optic axis away from the slab normal")->capture_default_str();
    command->add_option("--screen-distance", screen_distance_, "Ray mode: screen distance D behind the slab")->capture_default_str()->type_name(length_type);
    command->add_option("--rays", plain_.rays, "Ray mode: number of rays (up to 1e7, or 1e8 with --allow-large)")->capture_default_str();
    command->add_flag("--allow-large", allow_large_, "Ray mode: allow more than 1e7 rays (about 1 GB of memory per 1e7)");
    command->add_option("--size", plain_.size_px, "Image size in pixels (64 to 4096)")->capture_default_str();
}

}  // namespace

std::unique_ptr<FrameOptions> make_conical_options() { return std::make_unique<ConicalOptions>(); }

}  // namespace petroscope::cli
