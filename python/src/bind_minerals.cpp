// Minerals: the catalog's names, and one mineral's indices, axes and summary at a wavelength.
#include "bindings.hpp"
#include "convert.hpp"

#include "petroscope/minerals/mineral.hpp"
#include "petroscope/optics/orientation.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>

namespace petroscope::python {
namespace {

void require_wavelength(double wavelength_nm) {
    if (!(wavelength_nm > 0.0) || !std::isfinite(wavelength_nm)) throw py::value_error("wavelength_nm: expected a finite number > 0");
}

}  // namespace

void bind_results(py::module_& module) {
    py::class_<Result>(module, "Result", "A rendered image with what its values mean and what was measured on it.")
        .def_readonly("image", &Result::image, "float32 array, height × width × channels")
        .def_readonly("channels", &Result::channels, "the meaning of each channel, e.g. ['R', 'G', 'B'] (linear sRGB)")
        .def_readonly("pixel_values", &Result::pixel_values, "what a pixel value of 1 means")
        .def_readonly("measurements", &Result::measurements, "numbers measured on the image, by name (None: nothing to measure)")
        .def_readonly("notes", &Result::notes, "notes and warnings for the user")
        .def_readonly("details", &Result::details, "quantities particular to the computation (units in the names)")
        // Picklable, so that a Result comes back from another process (Dask, multiprocessing).
        .def(py::pickle(
            [](const Result& r) { return py::make_tuple(r.image, r.channels, r.pixel_values, r.measurements, r.notes, r.details); },
            [](const py::tuple& state) {
                if (state.size() != 6) throw py::value_error("Result: expected the 6 fields of a pickled Result");
                return Result{state[0].cast<py::array_t<float>>(), state[1].cast<std::vector<std::string>>(), state[2].cast<std::string>(),
                              state[3].cast<py::dict>(), state[4].cast<std::vector<std::string>>(), state[5].cast<py::dict>()};
            }))
        .def("__repr__", [](const Result& result) {
            return "<petroscope.Result " + std::to_string(result.image.shape(1)) + "x" + std::to_string(result.image.shape(0)) + ", " +
                   std::to_string(result.image.shape(2)) + " channels, " + std::to_string(result.measurements.size()) + " measurements>";
        });
}

void bind_minerals(py::module_& module) {
    py::class_<Mineral>(module, "Mineral", "A mineral of the catalog: its optical class and dispersion formulas.")
        .def_readonly("name", &Mineral::name)
        .def_readonly("aliases", &Mineral::aliases)
        .def_readonly("formula", &Mineral::formula)
        .def_readonly("system", &Mineral::system, "crystal system")
        .def_property_readonly("optical_class", [](const Mineral& m) { return std::string(optical_class_name(m.optical_class)); },
                               "'isotropic', 'uniaxial' or 'biaxial'")
        .def_readonly("reference_wavelength_nm", &Mineral::reference_wavelength_nm)
        .def_readonly("source", &Mineral::source, "where the numbers come from")
        .def_readonly("file", &Mineral::file, "the record's file")
        .def(
            "principal_n",
            [](const Mineral& m, double wavelength_nm) -> Eigen::Vector3d {
                require_wavelength(wavelength_nm);
                return m.principal_n(wavelength_nm);
            },
            py::arg("wavelength_nm"), "Refractive indices along the indicatrix axes X, Y, Z (uniaxial: ω, ω, ε) at a wavelength in nm.")
        .def(
            "summary",
            [](const Mineral& m, double wavelength_nm) {
                require_wavelength(wavelength_nm);
                const OpticalSummary s = optical_summary(m, wavelength_nm);
                py::dict summary;
                summary["wavelength_nm"] = s.wavelength_nm;
                summary["n_alpha"] = s.n_alpha;
                summary["n_beta"] = s.n_beta;
                summary["n_gamma"] = s.n_gamma;
                summary["birefringence"] = s.birefringence;
                summary["two_v_deg"] = s.two_v_deg ? py::object(py::float_(*s.two_v_deg)) : py::object(py::none());
                summary["sign"] = s.sign;
                return summary;
            },
            py::arg("wavelength_nm"), "What optical mineralogy tables list: nα, nβ, nγ, birefringence, 2V (degrees) and sign.")
        .def("__repr__", [](const Mineral& m) { return "<petroscope.Mineral " + m.name + ", " + std::string(optical_class_name(m.optical_class)) + ">"; });

    module.def(
        "minerals",
        [] {
            std::vector<std::string> names;
            for (const Mineral& m : catalog().minerals()) names.push_back(m.name);
            return names;
        },
        "The names of the catalog's minerals.");
    module.def(
        "mineral", [](const std::string& name) -> const Mineral& { return catalog().find(name); }, py::arg("name"),
        py::return_value_policy::reference, "The mineral of this name or alias; ValueError for an unknown name (with the nearest names).");
}

}  // namespace petroscope::python
