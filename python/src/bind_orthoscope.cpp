// Thin sections (from arrays or files) and orthoscope(): a section between the polars.
#include "bindings.hpp"
#include "computations.hpp"

#include "petroscope/optics/orientation.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <tuple>

namespace petroscope::python {
namespace {

ThinSectionGrain make_grain(int label, std::string mineral, std::array<double, 3> angles_deg, std::optional<double> thickness_um,
                            const std::optional<std::string>& handedness) {
    if (label < 0 || label > 65535) throw py::value_error("label: expected 0 to 65535, got " + std::to_string(label));
    for (const double angle : angles_deg) {
        if (!std::isfinite(angle)) throw py::value_error("euler_zyz_deg: expected finite angles in degrees");
    }
    std::optional<Handedness> hand;
    if (handedness) {
        hand = parse_handedness(*handedness);
        const Mineral& record = catalog().find(mineral);
        if (!record.optically_active()) throw py::value_error("handedness: " + record.name + " is not optically active: it has no handedness");
    }
    return {label, std::move(mineral), euler_zyz_deg(angles_deg[0], angles_deg[1], angles_deg[2]), thickness_um, 0, hand};
}

// The label map: a 2-D array of integers 0 … 65535 (any integer dtype); TypeError or ValueError otherwise.
std::vector<std::uint16_t> label_map(const py::array& labels, int& width_px, int& height_px) {
    const char kind = labels.dtype().kind();
    if (kind != 'i' && kind != 'u') throw py::type_error("labels: expected an array of integers, got dtype " + std::string(py::str(labels.dtype())));
    if (labels.ndim() != 2) throw py::value_error("labels: expected a 2-D array (height, width), got " + std::to_string(labels.ndim()) + " dimensions");
    const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(labels);
    height_px = static_cast<int>(values.shape(0));
    width_px = static_cast<int>(values.shape(1));
    std::vector<std::uint16_t> map(static_cast<std::size_t>(values.size()));
    for (std::size_t i = 0; i < map.size(); ++i) {
        const std::int64_t value = values.data()[i];
        if (value < 0 || value > 65535) throw py::value_error("labels: values must be 0 to 65535, found " + std::to_string(value));
        map[i] = static_cast<std::uint16_t>(value);
    }
    return map;
}

ThinSection make_section(const py::array& labels, std::vector<ThinSectionGrain> grains, double pixel_size_um, double thickness_um,
                         std::string name) {
    ThinSection section;
    section.labels = label_map(labels, section.width_px, section.height_px);
    section.grains = std::move(grains);
    section.pixel_size_um = pixel_size_um;
    section.thickness_um = thickness_um;
    section.name = std::move(name);
    section.validate();
    for (const ThinSectionGrain& grain : section.grains) catalog().find(grain.mineral);  // unknown minerals fail now
    return section;
}

OrthoscopeRequest orthoscope_request(const ThinSection& section, bool analyzer_in, double stage_deg, double polarizer_deg,
                                     double analyzer_deg, const std::optional<std::string>& plate, double plate_slow_deg,
                                     double wedge_position, double condenser_na, int condenser_rings, std::optional<double> thickness_um,
                                     bool exact, const py::object& light) {
    return {.section = section, .analyzer_in = analyzer_in, .stage_deg = stage_deg, .polarizer_deg = polarizer_deg,
            .analyzer_deg = analyzer_deg, .plate = plate_argument(plate, plate_slow_deg, wedge_position), .condenser_na = condenser_na,
            .condenser_rings = condenser_rings, .thickness_um = thickness_um, .exact = exact, .light = light_argument(light)};
}

Result orthoscope(const OrthoscopeRequest& request, const py::object& progress) {
    return compute(request, progress, &plan_orthoscope, &render_orthoscope_image, &orthoscope_result);
}

// The arguments of orthoscope() and of the request a sweep steps.
auto orthoscope_arguments() {
    return std::make_tuple(py::arg("section"), py::kw_only(), py::arg("analyzer_in") = true, py::arg("stage_deg") = 0.0,
                           py::arg("polarizer_deg") = 0.0, py::arg("analyzer_deg") = 90.0, py::arg("plate") = py::none(),
                           py::arg("plate_slow_deg") = 45.0, py::arg("wedge_position") = 0.5, py::arg("condenser_na") = 0.0,
                           py::arg("condenser_rings") = 0, py::arg("thickness_um") = py::none(), py::arg("exact") = false,
                           py::arg("light") = py::none());
}

}  // namespace

Result orthoscope_result(const OrthoscopePlan& plan, const OrthoscopeImage& image) {
    return {to_numpy(image.image.linear_rgb), {"R", "G", "B"},
            "linear sRGB; 1 = white, the light after the polarizer, times the exposure" +
                std::string(plan.light.monochromatic() ? " (monochromatic: the transmitted intensity in every channel)" : ""),
            measurements_dict(image.measurements), plan.notes, py::dict()};
}

void bind_orthoscope(py::module_& module) {
    py::class_<ThinSectionGrain>(module, "Grain", "One grain of a thin section: its label in the map, its mineral and orientation.")
        .def(py::init(&make_grain), py::arg("label"), py::arg("mineral"), py::kw_only(),
             py::arg("euler_zyz_deg") = std::array<double, 3>{0.0, 0.0, 0.0}, py::arg("thickness_um") = py::none(),
             py::arg("handedness") = py::none(),
             "label: its value in the label map (0 to 65535). mineral: name or alias. euler_zyz_deg: orientation of the\n"
             "indicatrix (docs/conventions.md). thickness_um: its own thickness instead of the section's. handedness:\n"
             "'right' or 'left', the form of an optically active mineral (quartz, paratellurite); None: right.")
        .def_readonly("label", &ThinSectionGrain::label)
        .def_readonly("mineral", &ThinSectionGrain::mineral)
        .def_readonly("thickness_um", &ThinSectionGrain::thickness_um)
        .def_property_readonly("handedness", [](const ThinSectionGrain& g) {
            return g.handedness ? std::optional<std::string>(handedness_name(*g.handedness)) : std::nullopt;
        })
        .def_property_readonly("euler_zyz_deg", [](const ThinSectionGrain& g) { return euler_zyz_deg_of(g.crystal_axes); });

    py::class_<ThinSection>(module, "Section", "A thin section: a map of grain labels and the grains' minerals and orientations.")
        .def(py::init(&make_section), py::arg("labels"), py::arg("grains"), py::kw_only(), py::arg("pixel_size_um") = 1.0,
             py::arg("thickness_um") = 30.0, py::arg("name") = "section",
             "labels: 2-D integer array (height, width), row 0 at the North. grains: a Grain for every label used.\n"
             "pixel_size_um: the edge of a pixel on the specimen. thickness_um: the section's uniform thickness.")
        .def_readonly("name", &ThinSection::name)
        .def_readonly("width_px", &ThinSection::width_px)
        .def_readonly("height_px", &ThinSection::height_px)
        .def_readonly("pixel_size_um", &ThinSection::pixel_size_um)
        .def_readonly("grains", &ThinSection::grains)
        .def_property_readonly("labels", [](const ThinSection& s) {
            py::array_t<std::uint16_t> labels({s.height_px, s.width_px});
            std::copy(s.labels.begin(), s.labels.end(), labels.mutable_data());
            return labels;
        }, "the label map, uint16 (height, width)")
        .def("__repr__", [](const ThinSection& s) {
            return "<petroscope.Section " + s.name + ", " + std::to_string(s.width_px) + "x" + std::to_string(s.height_px) + ", " +
                   std::to_string(s.grains.size()) + " grains>";
        });

    py::class_<OrthoscopeRequest>(module, "_OrthoscopeRequest", "An orthoscope() call's arguments, checked for type (petroscope.sweep steps them).");
    def_with_arguments(module, "_orthoscope_request", &orthoscope_request, orthoscope_arguments());
    def_with_arguments(module, "orthoscope", make_then_compute(&orthoscope_request, &orthoscope), orthoscope_arguments(),
                       py::arg("progress") = py::none(),
                       R"(A thin section as seen through the eyepieces.

section: a Section (petroscope.Section from arrays, or petroscope.read_section(path)).
analyzer_in: False for plane-polarized light. stage_deg: stage rotation, counter-clockwise.
polarizer_deg, analyzer_deg: directions from E toward N. plate: 'gypsum', 'mica' or 'wedge', with
plate_slow_deg and wedge_position (0 to 1). condenser_na: the condenser cone (0: parallel light),
condenser_rings its sampling (0: automatic). thickness_um: a uniform thickness instead of the section's.
exact: the 4x4 transfer matrix (every multiple reflection). light: a Light, a wavelength in nm or None.
progress: called with the fraction done; return False to cancel. Ctrl-C cancels.

Returns a Result: image float32 (height, width, 3), linear sRGB; measurements: the field's mean colour.)");
}

}  // namespace petroscope::python
