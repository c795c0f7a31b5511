#pragma once
// The parts of the extension module, one function each.
#include <pybind11/pybind11.h>

namespace petroscope::python {

void bind_results(pybind11::module_& module);    // Result
void bind_minerals(pybind11::module_& module);   // minerals(), mineral(), Mineral
void bind_light(pybind11::module_& module);      // Light
void bind_conoscope(pybind11::module_& module);  // conoscope()
void bind_orthoscope(pybind11::module_& module); // Grain, Section, orthoscope()
void bind_conical(pybind11::module_& module);    // conical()
void bind_chart(pybind11::module_& module);      // michel_levy_colours()
void bind_interface(pybind11::module_& module);  // Medium, Wave, InterfaceResult, interface()
void bind_fit(pybind11::module_& module);        // fit_conoscope()
void bind_sweep(pybind11::module_& module);      // _sweep(), _sweep_fields()

}  // namespace petroscope::python
