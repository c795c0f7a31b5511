#include "petroscope/api/conical_screen.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/microscope/frame_measurements.hpp"
#include "petroscope/optics/polarization.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace petroscope {

ConicalOptics parse_conical_optics(std::string_view name) {
    if (name == "wave") return ConicalOptics::wave;
    if (name == "ray") return ConicalOptics::ray;
    throw InputError("optics " + quote_input(name) + ": expected wave or ray");
}

ConicalBeam parse_conical_beam(std::string_view name) {
    if (name == "gaussian") return ConicalBeam::gaussian;
    if (name == "pinhole") return ConicalBeam::pinhole;
    throw InputError("beam " + quote_input(name) + ": expected gaussian or pinhole");
}

Eigen::Vector4d parse_polarization(std::string_view text) {
    if (text == "unpolarized") return {1, 0, 0, 0};
    if (text == "circular" || text == "circular:right") return {1, 0, 0, 1};
    if (text == "circular:left") return {1, 0, 0, -1};
    if (text.starts_with("linear:")) {
        if (const auto angle = parse_double(text.substr(7)); angle && std::isfinite(*angle)) {
            const double phi = 2.0 * *angle * std::numbers::pi / 180.0;  // S1 = cos 2ψ, S2 = sin 2ψ (Born & Wolf §1.4.2)
            return {1, std::cos(phi), std::sin(phi), 0};
        }
    }
    throw InputError("polarization " + quote_input(text) + ": expected unpolarized, linear:ANGLE (degrees from +x), circular or circular:left");
}

namespace {

void require_positive(double value, const char* what) {
    if (!(value > 0.0) || !std::isfinite(value)) throw InputError(std::string(what) + " must be a positive finite length");
}

}  // namespace

ConicalPlan plan_conical(const ConicalRequest& request, const MineralCatalog& catalog) {
    require_positive(request.length_um, "the slab length");
    if (!(request.wavelength_nm > 0.0) || !std::isfinite(request.wavelength_nm)) throw InputError("the wavelength must be a positive finite number of nm");
    if (request.size_px < 64 || request.size_px > 4096) throw InputError("image size " + std::to_string(request.size_px) + " px is out of range (expected 64 to 4096)");
    if (!std::isfinite(request.z)) throw InputError("Z must be a finite number");
    if (!is_physical_stokes(request.stokes)) throw InputError("the Stokes vector must have S0 > 0 and S1² + S2² + S3² ≤ S0²");
    const Mineral& crystal = catalog.find(request.crystal);
    if (crystal.optical_class != OpticalClass::biaxial) {
        throw InputError(crystal.name + " is " + std::string(optical_class_name(crystal.optical_class)) +
                         ": conical refraction needs a biaxial crystal (e.g. KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite)");
    }
    if (crystal.optically_active()) {
        throw InputError(crystal.name + " is optically active, which conical refraction does not model yet (its rings assume the "
                                        "inactive crystal's waves, docs/conical.md); take an inactive biaxial crystal");
    }
    ConicalPlan plan;
    plan.request = request;
    plan.crystal = &crystal;
    for (const std::string& warning : crystal.range_warnings({request.wavelength_nm})) plan.notes.push_back("warning: " + warning);
    plan.principal_n = crystal.principal_n(request.wavelength_nm);
    plan.cone_angle_rad = conical_cone_angle_rad(plan.principal_n);
    plan.ring_radius_um = 0.5 * std::tan(plan.cone_angle_rad) * request.length_um;  // R₀ = A·l, A = ½ tan χ (Berry 2004)
    if (request.optics == ConicalOptics::wave) {
        const bool gaussian = request.beam == ConicalBeam::gaussian;
        plan.scale_um = gaussian ? request.waist_um : request.pinhole_um;
        require_positive(plan.scale_um, gaussian ? "the beam waist" : "the pinhole radius");
        plan.wave = {request.beam, plan.ring_radius_um / plan.scale_um, request.z};
        plan.half_width_um = (plan.wave.rho0 + 4.0 + 1.5 * std::abs(request.z)) * plan.scale_um;
        return plan;
    }
    require_positive(request.pinhole_um, "the pinhole radius");
    require_positive(request.filter_um, "the filter thickness");
    require_positive(request.screen_distance_um, "the screen distance");
    if (!std::isfinite(request.rotate_deg) || !std::isfinite(request.tilt_deg)) throw InputError("angles must be finite numbers of degrees");
    if (request.rays < 1 || request.rays > 100000000) throw InputError("the number of rays must be between 1 and 1e8");
    plan.ray = {.principal_n = plan.principal_n, .slab_um = request.length_um, .rotate_deg = request.rotate_deg,
                .tilt_deg = request.tilt_deg, .pinhole_radius_um = request.pinhole_um, .filter_um = request.filter_um,
                .screen_distance_um = request.screen_distance_um, .stokes = request.stokes, .rays = request.rays,
                .size_px = request.size_px};
    plan.half_width_um = 2.0 * plan.ring_radius_um;
    return plan;
}

namespace {

Image normalised_gray(const Image& image) {
    float peak = 0.0f;
    for (const float value : image.pixels) peak = std::max(peak, value);
    Image rgb(image.width, image.height, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = peak > 0.0f ? image.pixels[i] / peak : 0.0f;
    }
    return rgb;
}

Measurements ring_measurements(double outer_bright_um, double dark_um, double inner_bright_um, const Image& screen) {
    return {{"ring_outer_bright_um", outer_bright_um}, {"ring_dark_um", dark_um}, {"ring_inner_bright_um", inner_bright_um},
            {"mean_luminance", mean_colour(screen, false).luminance}};
}

}  // namespace

ConicalScreen render_conical_screen(const ConicalPlan& plan, const ProgressCallback& progress) {
    const int size_px = plan.request.size_px;
    ConicalScreen result;
    if (plan.request.optics == ConicalOptics::wave) {
        const double half_width = plan.half_width_um / plan.scale_um;  // in units of the beam scale
        const ConicalProfile profile = conical_profile(plan.wave, half_width * std::numbers::sqrt2, 4 * size_px, progress);
        const ConicalRings rings = conical_rings(profile, plan.wave.rho0);
        result.linear_rgb = normalised_gray(conical_screen(profile, plan.request.stokes, size_px, half_width));
        result.measurements = ring_measurements(rings.outer_bright * plan.scale_um, rings.dark * plan.scale_um,
                                                rings.inner_bright * plan.scale_um, result.linear_rgb);
        result.power = conical_power(profile);
        return result;
    }
    const ConicalRayResult traced = trace_conical_rays(plan.ray, progress);
    result.linear_rgb = normalised_gray(traced.screen);
    result.measurements = ring_measurements(traced.rings.outer_bright_um, traced.rings.dark_um, traced.rings.inner_bright_um, result.linear_rgb);
    result.measurements.push_back({"ring_centre_x_um", traced.rings.centre_um.x()});
    result.measurements.push_back({"ring_centre_y_um", traced.rings.centre_um.y()});
    result.max_interface_power_sum = traced.max_interface_power_sum;
    result.image_centre_um = traced.ring_centre_um - traced.pinhole_point_um;
    return result;
}

}  // namespace petroscope
