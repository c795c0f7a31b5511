// The extension module behind `import petroscope` (python/petroscope/__init__.py re-exports it).
#include "bindings.hpp"
#include "convert.hpp"

PYBIND11_MODULE(_petroscope, module) {
    module.doc() = "petroscope: the polarizing microscope and light in crystals, computed exactly (the C++ library's bindings).";
    petroscope::python::register_exceptions(module);
    petroscope::python::bind_results(module);
    petroscope::python::bind_minerals(module);
    petroscope::python::bind_light(module);
    petroscope::python::bind_conoscope(module);
    petroscope::python::bind_orthoscope(module);
    petroscope::python::bind_conical(module);
    petroscope::python::bind_chart(module);
    petroscope::python::bind_interface(module);
    petroscope::python::bind_fit(module);
    petroscope::python::bind_sweep(module);
}
