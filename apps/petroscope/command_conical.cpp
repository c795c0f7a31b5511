// petroscope conical: the screen behind a biaxial slab cut perpendicular to an optic axis (internal conical
// refraction), in wave optics (Belsky–Khapalyuk–Berry) or ray optics (the exact interface model).
#include "cli_common.hpp"
#include "frame_command.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/conical_wave.hpp"
#include "petroscope/microscope/frame_measurements.hpp"

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
    std::string crystal_ = "KGd(WO4)2";
    std::string length_ = "20mm";
    std::string wavelength_ = "633nm";
    std::string mode_ = "wave";
    std::string beam_ = "gaussian";
    std::string waist_ = "40um";
    std::string pinhole_ = "25um";
    std::string filter_ = "50mm";
    std::string polarization_ = "unpolarized";
    double z_ = 0.0;
    double rotate_deg_ = 0.0;
    double tilt_deg_ = 0.0;
    std::string screen_distance_ = "50mm";
    long long rays_ = 200000;
    bool allow_large_ = false;
    int size_px_ = 1024;
};

// "unpolarized", "circular" (right), "circular:left", "linear:ANGLE" (degrees from +x): a Stokes vector with
// (x, y) in the roles of (s, p) (optics/polarization.hpp).
Eigen::Vector4d parse_polarization(const std::string& text) {
    if (text == "unpolarized") return {1, 0, 0, 0};
    if (text == "circular" || text == "circular:right") return {1, 0, 0, 1};
    if (text == "circular:left") return {1, 0, 0, -1};
    if (text.starts_with("linear:")) {
        if (const auto angle = parse_double(text.substr(7))) {
            const double phi = 2.0 * *angle * std::numbers::pi / 180.0;
            return {1, std::cos(phi), std::sin(phi), 0};
        }
    }
    throw InputError("--polarization " + quote_input(text) + ": expected unpolarized, linear:ANGLE (degrees from +x), circular or circular:left");
}

Image normalised_gray(const Image& image) {
    float peak = 0.0f;
    for (const float value : image.pixels) peak = std::max(peak, value);
    Image rgb(image.width, image.height, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = peak > 0.0f ? image.pixels[i] / peak : 0.0f;
    }
    return rgb;
}

// The rings' radii (µm; bright outer, dark, bright inner) and the mean of the normalised screen.
nlohmann::json ring_measurements(double outer_bright_um, double dark_um, double inner_bright_um, const Image& screen) {
    return {{"ring_outer_bright_um", outer_bright_um}, {"ring_dark_um", dark_um}, {"ring_inner_bright_um", inner_bright_um},
            {"mean_luminance", mean_colour(screen, false).luminance}};
}

PreparedFrame ConicalOptions::prepare(FrameContext& context) const {
    const double length_um = positive_length_um("--length", length_);
    const double wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(wavelength_); });
    if (!(wavelength_nm > 0.0)) throw InputError("--wavelength must be > 0");
    if (size_px_ < 64 || size_px_ > 4096) throw InputError("--size " + std::to_string(size_px_) + " is out of range (64 to 4096)");
    if (mode_ != "wave" && mode_ != "ray") throw InputError("--mode " + quote_input(mode_) + ": expected wave or ray");
    if (beam_ != "gaussian" && beam_ != "pinhole") throw InputError("--beam " + quote_input(beam_) + ": expected gaussian or pinhole");
    if (!std::isfinite(z_)) throw InputError("--z must be a finite number");
    const Eigen::Vector4d stokes = parse_polarization(polarization_);

    const Mineral& mineral = context.catalog().find(crystal_);
    if (mineral.optical_class != OpticalClass::biaxial) {
        throw InputError(mineral.name + " is " + std::string(optical_class_name(mineral.optical_class)) +
                         ": conical refraction needs a biaxial crystal (e.g. KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite)");
    }
    PreparedFrame prepared;
    for (const auto& warning : mineral.range_warnings({wavelength_nm})) prepared.notes.push_back("warning: " + warning);
    const Eigen::Vector3d n = mineral.principal_n(wavelength_nm);
    const double chi = conical_cone_angle_rad(n);
    const double a = 0.5 * std::tan(chi);
    const double ring_radius_um = a * length_um;
    nlohmann::json sidecar{{"program", "petroscope 0.1.0"}, {"command", "conical"},
                           {"crystal", {{"name", mineral.name}, {"file", mineral.file}, {"principal_n_xyz", {n[0], n[1], n[2]}}}},
                           {"wavelength_nm", wavelength_nm}, {"length_um", length_um}, {"mode", mode_},
                           {"polarization", polarization_}, {"cone_angle_chi_deg", chi * 180.0 / std::numbers::pi},
                           {"A_rad", a}, {"R0_um", ring_radius_um}, {"size_px", size_px_},
                           {"image_frame", "x to the right, y up; centred on the (predicted) ring centre, which lies R0 from the point below "
                                           "the pinhole toward the second binormal"}};
    const std::string summary = mode_ + " optics, R0 = " + format_number(ring_radius_um) + " um";
    const int size_px = size_px_;
    if (mode_ == "wave") {
        const bool gaussian = beam_ == "gaussian";
        const double scale_um = gaussian ? positive_length_um("--waist", waist_) : positive_length_um("--pinhole", pinhole_);
        ConicalWaveParameters parameters;
        parameters.beam = gaussian ? ConicalBeam::gaussian : ConicalBeam::pinhole;
        parameters.rho0 = ring_radius_um / scale_um;
        parameters.z = z_;
        const double half_width = parameters.rho0 + 4.0 + 1.5 * std::abs(z_);
        sidecar["beam"] = beam_;
        sidecar["scale_um"] = scale_um;
        sidecar["rho0"] = parameters.rho0;
        sidecar["Z"] = z_;
        sidecar["image_half_width_um"] = half_width * scale_um;
        sidecar["pixel_values"] = "intensity |D|^2 of the paraxial theory (physics notes §7), normalised so that the brightest pixel is 1";
        prepared.render = [=](const ProgressCallback&) {
            const ConicalProfile profile = conical_profile(parameters, half_width * std::numbers::sqrt2, 4 * size_px);
            const ConicalRings rings = conical_rings(profile, parameters.rho0);
            RenderedFrame frame{normalised_gray(conical_screen(profile, stokes, size_px, half_width)), sidecar, summary};
            frame.sidecar["rings"] = {{"units", "um from the ring centre (rho in units of the beam scale: divide by scale_um)"},
                                      {"outer_bright", rings.outer_bright * scale_um}, {"dark", rings.dark * scale_um},
                                      {"inner_bright", rings.inner_bright * scale_um}};
            frame.sidecar["power"] = conical_power(profile);
            frame.sidecar["measurements"] = ring_measurements(rings.outer_bright * scale_um, rings.dark * scale_um, rings.inner_bright * scale_um,
                                                   frame.linear_rgb);
            return frame;
        };
        return prepared;
    }
    ConicalRaySettings settings;
    settings.principal_n = n;
    settings.slab_um = length_um;
    settings.rotate_deg = rotate_deg_;
    settings.tilt_deg = tilt_deg_;
    settings.pinhole_radius_um = positive_length_um("--pinhole", pinhole_);
    settings.filter_um = positive_length_um("--filter", filter_);
    settings.screen_distance_um = positive_length_um("--screen-distance", screen_distance_);
    settings.stokes = stokes;
    // Every ray's two landings are kept for the ring measurement (48 bytes a ray, twice while the threads'
    // lists are merged): about 1 GB at 10⁷ rays, 10 GB at 10⁸.
    if (rays_ < 1 || rays_ > 100000000) throw InputError("--rays must be between 1 and 1e8");
    if (rays_ > 10000000 && !allow_large_) throw InputError("--rays " + std::to_string(rays_) + " is above 1e7 (about 1 GB per 1e7 rays); add --allow-large to trace them anyway");
    settings.rays = rays_;
    settings.size_px = size_px_;
    sidecar["pinhole_um"] = settings.pinhole_radius_um;
    sidecar["filter_um"] = settings.filter_um;
    sidecar["screen_distance_um"] = settings.screen_distance_um;
    sidecar["rotate_deg"] = settings.rotate_deg;
    sidecar["tilt_deg"] = settings.tilt_deg;
    sidecar["rays"] = settings.rays;
    sidecar["image_half_width_um"] = 2.0 * ring_radius_um;
    sidecar["pixel_values"] = "collected ray power per pixel, normalised so that the brightest pixel is 1";
    prepared.render = [=](const ProgressCallback& progress) {
        const ConicalRayResult traced = trace_conical_rays(settings, progress);
        RenderedFrame frame{normalised_gray(traced.screen), sidecar, summary};
        frame.sidecar["image_centre_um"] = {traced.ring_centre_um.x(), traced.ring_centre_um.y()};
        frame.sidecar["pinhole_point_um"] = {traced.pinhole_point_um.x(), traced.pinhole_point_um.y()};
        frame.sidecar["rings"] = {{"units", "um from the measured ring centre"},
                                  {"centre_um", {traced.rings.centre_um.x(), traced.rings.centre_um.y()}},
                                  {"outer_bright", traced.rings.outer_bright_um}, {"dark", traced.rings.dark_um},
                                  {"inner_bright", traced.rings.inner_bright_um}};
        frame.sidecar["max_interface_power_sum"] = traced.max_interface_power_sum;
        frame.sidecar["measurements"] = ring_measurements(traced.rings.outer_bright_um, traced.rings.dark_um, traced.rings.inner_bright_um,
                                               frame.linear_rgb);
        frame.sidecar["measurements"]["ring_centre_x_um"] = traced.rings.centre_um.x();
        frame.sidecar["measurements"]["ring_centre_y_um"] = traced.rings.centre_um.y();
        return frame;
    };
    return prepared;
}

void ConicalOptions::add_options(CLI::App* command) {
    command->add_option("--crystal", crystal_, "Biaxial mineral (KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite, …)")->capture_default_str();
    command->add_option("--length", length_, "Slab thickness l along the optic axis")->capture_default_str()->type_name(length_type);
    command->add_option("--wavelength", wavelength_, "Wavelength")->capture_default_str()->type_name(wavelength_type);
    command->add_option("--mode", mode_, "wave or ray")->capture_default_str();
    command->add_option("--beam", beam_, "Wave mode: gaussian (waist --waist) or pinhole (radius --pinhole)")->capture_default_str();
    command->add_option("--waist", waist_, "Gaussian beam scale w, E(r) = exp(-r^2/2w^2)")->capture_default_str()->type_name(length_type);
    command->add_option("--pinhole", pinhole_, "Pinhole radius R")->capture_default_str()->type_name(length_type);
    command->add_option("--filter", filter_, "Ray mode: thickness h of the filter holding the pinhole (rays tilt by at most ~2R/h)")
        ->capture_default_str()->type_name(length_type);
    command->add_option("--polarization", polarization_, "unpolarized, linear:ANGLE (degrees from +x), circular[:left]")->capture_default_str();
    command->add_option("--z", z_, "Wave mode: observation plane Z (dimensionless, physics notes §7; 0 = focal image plane)")->capture_default_str();
    command->add_option("--rotate-deg", rotate_deg_, "Ray mode: turn the slab about its optic axis")->capture_default_str();
    command->add_option("--tilt-deg", tilt_deg_, "Ray mode: tilt the optic axis away from the slab normal")->capture_default_str();
    command->add_option("--screen-distance", screen_distance_, "Ray mode: screen distance D behind the slab")->capture_default_str()->type_name(length_type);
    command->add_option("--rays", rays_, "Ray mode: number of rays (up to 1e7, or 1e8 with --allow-large)")->capture_default_str();
    command->add_flag("--allow-large", allow_large_, "Ray mode: allow more than 1e7 rays (about 1 GB of memory per 1e7)");
    command->add_option("--size", size_px_, "Image size in pixels (64 to 4096)")->capture_default_str();
}

}  // namespace

std::unique_ptr<FrameOptions> make_conical_options() { return std::make_unique<ConicalOptions>(); }

}  // namespace petroscope::cli
