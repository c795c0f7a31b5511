// michel_levy_colours(): the Michel-Lévy chart's numbers (its drawing: files_module.cpp).
#include "bindings.hpp"
#include "chart_arguments.hpp"
#include "convert.hpp"

#include <pybind11/stl.h>

namespace petroscope::python {

py::dict colours_dict(const MichelLevyColours& chart) {
    const auto count = static_cast<py::ssize_t>(chart.steps.size());
    py::array_t<double> retardation(count), thickness(count), xyz({count, py::ssize_t{3}}), srgb({count, py::ssize_t{3}});
    for (py::ssize_t k = 0; k < count; ++k) {
        const MichelLevyStep& step = chart.steps[static_cast<std::size_t>(k)];
        retardation.mutable_at(k) = step.retardation_nm;
        thickness.mutable_at(k) = step.thickness_um;
        for (py::ssize_t c = 0; c < 3; ++c) {
            xyz.mutable_at(k, c) = step.xyz[c];
            srgb.mutable_at(k, c) = chart.linear_srgb[static_cast<std::size_t>(k)][c];
        }
    }
    py::dict colours;
    colours["retardation_nm"] = retardation;
    colours["thickness_um"] = thickness;
    colours["xyz"] = xyz;
    colours["linear_srgb"] = srgb;
    colours["birefringence"] = chart.birefringence_at_reference;
    colours["reference_wavelength_nm"] = chart.settings.reference_wavelength_nm;
    colours["illuminant"] = chart.illuminant;
    return colours;
}

MichelLevyColours chart_colours(const std::optional<std::string>& mineral, double max_retardation_nm, double step_nm, const py::object& light) {
    const MichelLevyRequest request{.mineral = mineral, .max_retardation_nm = max_retardation_nm, .step_nm = step_nm, .light = light_argument(light)};
    return without_gil([&] { return michel_levy_chart_colours(request, catalog()); });
}

void bind_chart(py::module_& module) {
    module.def(
        "michel_levy_colours",
        [](const std::optional<std::string>& mineral, double max_retardation_nm, double step_nm, const py::object& light) {
            return colours_dict(chart_colours(mineral, max_retardation_nm, step_nm, light));
        },
        py::kw_only(), py::arg("mineral") = py::none(), py::arg("max_retardation_nm") = 2000.0, py::arg("step_nm") = 1.0,
        py::arg("light") = py::none(),
        R"(The Michel-Lévy chart's numbers: a plate at 45° between crossed polars, in parallel white light, in a
standard mounting, at retardations 0, step_nm, … ≤ max_retardation_nm (stated at 550 nm).

mineral: its real dispersion of birefringence (a section containing X and Z); None: the classic chart
(no dispersion). light: a white Light (its exposure is not used) or None (D65).

Returns a dict: retardation_nm (N), thickness_um (N, of the plate), xyz (N × 3, Y = 1 for the light),
linear_srgb (N × 3, display colours), birefringence, reference_wavelength_nm, illuminant.)");
}

}  // namespace petroscope::python
