// conical(): internal conical refraction on a screen, in wave or ray optics.
#include "bindings.hpp"
#include "computations.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <numbers>
#include <tuple>

namespace petroscope::python {
namespace {

Eigen::Vector4d stokes_argument(const py::object& polarization) {
    if (py::isinstance<py::str>(polarization)) return parse_polarization(polarization.cast<std::string>());
    try {
        const auto stokes = polarization.cast<std::array<double, 4>>();
        return {stokes[0], stokes[1], stokes[2], stokes[3]};
    } catch (const py::cast_error&) {
        throw py::type_error("polarization: expected 'unpolarized', 'linear:ANGLE', 'circular', 'circular:left' or a Stokes vector (S0, S1, S2, S3)");
    }
}

ConicalRequest conical_request(const std::string& crystal, double length_um, double wavelength_nm, const std::string& optics,
                               const std::string& beam, double waist_um, double pinhole_um, double filter_um, const py::object& polarization,
                               double z, double rotate_deg, double tilt_deg, double screen_distance_um, std::int64_t rays, int size_px) {
    return {.crystal = crystal, .length_um = length_um, .wavelength_nm = wavelength_nm, .optics = parse_conical_optics(optics),
            .beam = parse_conical_beam(beam), .waist_um = waist_um, .pinhole_um = pinhole_um, .filter_um = filter_um,
            .stokes = stokes_argument(polarization), .z = z, .rotate_deg = rotate_deg, .tilt_deg = tilt_deg,
            .screen_distance_um = screen_distance_um, .rays = rays, .size_px = size_px};
}

Result conical(const ConicalRequest& request, const py::object& progress) {
    return compute(request, progress, &plan_conical, &render_conical_screen, &conical_result);
}

// The arguments of conical() and of the request a sweep steps.
auto conical_arguments() {
    return std::make_tuple(py::kw_only(), py::arg("crystal") = "KGd(WO4)2", py::arg("length_um") = 20000.0, py::arg("wavelength_nm") = 633.0,
                           py::arg("optics") = "wave", py::arg("beam") = "gaussian", py::arg("waist_um") = 40.0, py::arg("pinhole_um") = 25.0,
                           py::arg("filter_um") = 50000.0, py::arg("polarization") = "unpolarized", py::arg("z") = 0.0,
                           py::arg("rotate_deg") = 0.0, py::arg("tilt_deg") = 0.0, py::arg("screen_distance_um") = 50000.0,
                           py::arg("rays") = 200000, py::arg("size_px") = 1024);
}

}  // namespace

Result conical_result(const ConicalPlan& plan, const ConicalScreen& screen) {
    Result result{to_numpy(screen.linear_rgb), {"I", "I", "I"},
                  plan.request.optics == ConicalOptics::wave ? "intensity of the paraxial theory, normalised so that the brightest pixel is 1"
                                                             : "collected ray power per pixel, normalised so that the brightest pixel is 1",
                  measurements_dict(screen.measurements), plan.notes, py::dict()};
    result.details["principal_n"] = plan.principal_n;
    result.details["cone_angle_deg"] = plan.cone_angle_rad * 180.0 / std::numbers::pi;
    result.details["ring_radius_um"] = plan.ring_radius_um;
    result.details["image_half_width_um"] = plan.half_width_um;
    result.details["image_centre_um"] = screen.image_centre_um;
    if (screen.power) result.details["power"] = *screen.power;
    if (screen.max_interface_power_sum) result.details["max_interface_power_sum"] = *screen.max_interface_power_sum;
    return result;
}

void bind_conical(py::module_& module) {
    py::class_<ConicalRequest>(module, "_ConicalRequest", "A conical() call's arguments, checked for type (petroscope.sweep steps them).");
    def_with_arguments(module, "_conical_request", &conical_request, conical_arguments());
    def_with_arguments(module, "conical", make_then_compute(&conical_request, &conical), conical_arguments(), py::arg("progress") = py::none(),
                       R"(The screen behind a biaxial slab cut perpendicular to an optic axis: internal conical refraction.

crystal: a biaxial mineral. length_um: the slab's length along the optic axis. wavelength_nm.
optics: 'wave' (paraxial Belsky-Khapalyuk-Berry theory) or 'ray' (rays through a pinhole, traced with
  the exact interface model).
beam (wave optics): 'gaussian' of waist waist_um, or 'pinhole' of radius pinhole_um. z: the observation
  plane Z (dimensionless, 0 = the focal image plane; docs/conical.md).
ray optics: pinhole_um, filter_um (thickness of the filter holding the pinhole), rotate_deg, tilt_deg of
  the slab, screen_distance_um, rays (1 to 1e8; 48 bytes of memory a ray).
polarization: 'unpolarized', 'linear:ANGLE' (degrees from +x), 'circular', 'circular:left', or a Stokes
  vector (S0, S1, S2, S3). size_px: 64 to 4096.
progress: called with the fraction done; return False to cancel. Ctrl-C cancels.

Returns a Result: image float32 (size_px, size_px, 3), three equal channels normalised to a brightest
pixel of 1, centred on the ring centre; measurements: the rings' radii in µm.)");
}

}  // namespace petroscope::python
