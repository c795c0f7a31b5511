// conoscope(): the interference figure of a crystal slab.
#include "bindings.hpp"
#include "computations.hpp"

#include <pybind11/stl.h>

#include <tuple>

namespace petroscope::python {
namespace {

ConoscopeRequest conoscope_request(const std::string& mineral, double thickness_um, const std::optional<std::string>& cut,
                                   double azimuth_deg, double tilt_deg, const std::optional<std::array<double, 3>>& euler_zyz_deg,
                                   double numerical_aperture, int size_px, const py::object& light, double stage_deg, double polarizer_deg,
                                   double analyzer_deg, bool analyzer_in, double surround_n, const std::string& mounting,
                                   const std::optional<std::string>& plate, double plate_slow_deg, double wedge_position, bool exact_spectrum,
                                   const std::string& handedness) {
    return {.mineral = mineral, .thickness_um = thickness_um, .orientation = orientation_argument(cut, azimuth_deg, tilt_deg, euler_zyz_deg),
            .numerical_aperture = numerical_aperture, .size_px = size_px, .light = light_argument(light), .stage_deg = stage_deg,
            .polarizer_deg = polarizer_deg, .analyzer_deg = analyzer_deg, .analyzer_in = analyzer_in, .surround_n = surround_n,
            .mounting = parse_slab_mounting(mounting), .plate = plate_argument(plate, plate_slow_deg, wedge_position),
            .spectrum = exact_spectrum ? SpectrumSampling::exact : SpectrumSampling::interpolated,
            .handedness = parse_handedness(handedness)};
}

Result conoscope(const ConoscopeRequest& request, const py::object& progress) {
    return compute(request, progress, &plan_conoscope, &render_conoscope_figure, &conoscope_result);
}

// The arguments of conoscope() and of the request a sweep steps.
auto conoscope_arguments() {
    return std::make_tuple(py::kw_only(), py::arg("mineral") = "muscovite", py::arg("thickness_um") = 30.0, py::arg("cut") = py::none(),
                           py::arg("azimuth_deg") = 0.0, py::arg("tilt_deg") = 0.0, py::arg("euler_zyz_deg") = py::none(),
                           py::arg("numerical_aperture") = 0.85, py::arg("size_px") = 512, py::arg("light") = py::none(),
                           py::arg("stage_deg") = 0.0, py::arg("polarizer_deg") = 0.0, py::arg("analyzer_deg") = 90.0,
                           py::arg("analyzer_in") = true, py::arg("surround_n") = 1.54, py::arg("mounting") = "immersed",
                           py::arg("plate") = py::none(), py::arg("plate_slow_deg") = 45.0, py::arg("wedge_position") = 0.5,
                           py::arg("exact_spectrum") = false, py::arg("handedness") = "right");
}

}  // namespace

Result conoscope_result(const ConoscopePlan& plan, const ConoscopeFigure& figure) {
    Result result{to_numpy(figure.image.linear_rgb), {"R", "G", "B"},
                  "linear sRGB; 1 = white, the light of parallel polars without the crystal, times the exposure" +
                      std::string(plan.light.monochromatic() ? " (monochromatic: the transmitted intensity in every channel)" : ""),
                  measurements_dict(figure.measurements), plan.notes, py::dict()};
    result.details["cut"] = plan.cut ? py::object(py::str(std::string(cut_name(*plan.cut)))) : py::object(py::none());
    result.details["illuminant"] = figure.image.illuminant;
    result.details["measurements_axes_wavelength_nm"] = plan.axes_wavelength_nm;
    return result;
}

void bind_conoscope(py::module_& module) {
    py::class_<ConoscopeRequest>(module, "_ConoscopeRequest", "A conoscope() call's arguments, checked for type (petroscope.sweep steps them).");
    def_with_arguments(module, "_conoscope_request", &conoscope_request, conoscope_arguments());
    def_with_arguments(module, "conoscope", make_then_compute(&conoscope_request, &conoscope), conoscope_arguments(),
                       py::arg("progress") = py::none(),
                       R"(The conoscopic interference figure of a crystal slab, as through the Bertrand lens.

mineral: name or alias (petroscope.minerals()). thickness_um: the slab's thickness in µm.
cut: 'optic-axis', 'acute-bisectrix', 'obtuse-bisectrix' or 'optic-normal' (None: acute bisectrix for
  biaxial, optic axis for uniaxial minerals); azimuth_deg turns it about the microscope axis, tilt_deg
  tilts it toward the azimuth. euler_zyz_deg: (a, b, c) in degrees instead of a cut.
numerical_aperture: of the objective, 0 < NA < 1. size_px: width and height, 64 to 4096.
light: a Light, a wavelength in nm, or None (white light, D65).
stage_deg: stage rotation, counter-clockwise. polarizer_deg, analyzer_deg: directions from E toward N;
  analyzer_in=False takes the analyzer out.
surround_n: index on both faces (immersed). mounting: 'immersed', 'thin-section' (slide, balsam,
  cover; single pass) or 'thin-section-exact' (the 4x4 transfer matrix, every multiple reflection).
plate: 'gypsum', 'mica' or 'wedge'; plate_slow_deg its slow direction; wedge_position 0 to 1.
exact_spectrum: white light with the modes solved at every wavelength instead of at 8 and interpolated
  (slower; the reference the default is tested against).
handedness: 'right' or 'left', the form of an optically active mineral (quartz, paratellurite); right turns the plane of
  polarization clockwise seen looking toward the light. No effect on an inactive mineral (a note says so).
progress: called with the fraction done; return False to cancel (petroscope.Cancelled). Ctrl-C cancels.

Returns a Result: image float32 (size_px, size_px, 3), linear sRGB, row 0 at the North; measurements:
mean colour, the optic axes' image points and the melatopes found there (field units, x East, y North,
1 = the field's edge). Frames and angle senses: docs/conventions.md.)");
}

}  // namespace petroscope::python
