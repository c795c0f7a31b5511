// The light, and the orientation of a crystal in the lab.
#include "bindings.hpp"
#include "convert.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace petroscope::python {

void bind_light(py::module_& module) {
    py::class_<Light>(module, "Light", "The light through the microscope: white (an illuminant on a wavelength grid) or one wavelength.")
        .def(py::init([](std::optional<double> wavelength_nm, std::array<double, 3> wavelengths_nm, std::string illuminant, bool white_balance,
                         double exposure) {
                 Light light;
                 light.wavelength_nm = wavelength_nm;
                 light.grid = {wavelengths_nm[0], wavelengths_nm[1], wavelengths_nm[2]};
                 light.illuminant = std::move(illuminant);
                 light.white_balance = white_balance;
                 light.exposure = exposure;
                 light.validate();
                 return light;
             }),
             py::kw_only(), py::arg("wavelength_nm") = py::none(), py::arg("wavelengths_nm") = std::array<double, 3>{380.0, 780.0, 5.0},
             py::arg("illuminant") = "D65", py::arg("white_balance") = true, py::arg("exposure") = 1.0,
             "wavelength_nm: monochromatic light at this wavelength (None: white light).\n"
             "wavelengths_nm: white light's grid (start, end, step) in nm.\n"
             "illuminant: 'D65', 'A' (halogen) or 'blackbody:3200K'.\n"
             "white_balance: a white object shows white (otherwise the illuminant's colour cast stays).\n"
             "exposure: every pixel value is multiplied by it.")
        .def_property_readonly("wavelength_nm", [](const Light& l) { return l.wavelength_nm; })
        .def_property_readonly("wavelengths_nm", [](const Light& l) { return l.wavelengths_nm(); }, "every wavelength sampled, nm")
        .def_readonly("illuminant", &Light::illuminant)
        .def_readonly("white_balance", &Light::white_balance)
        .def_readonly("exposure", &Light::exposure)
        .def("__repr__", [](const Light& l) {
            return l.monochromatic() ? "<petroscope.Light " + std::to_string(*l.wavelength_nm) + " nm>"
                                     : "<petroscope.Light white, " + l.illuminant + ", " + std::to_string(l.grid.size()) + " wavelengths>";
        });

    module.def(
        "indicatrix_axes",
        [](const std::string& mineral, std::optional<std::string> cut, double azimuth_deg, double tilt_deg,
           std::optional<std::array<double, 3>> euler_zyz_deg) -> Eigen::Matrix3d {
            return indicatrix_axes(catalog().find(mineral), orientation_argument(cut, azimuth_deg, tilt_deg, euler_zyz_deg));
        },
        py::arg("mineral"), py::kw_only(), py::arg("cut") = py::none(), py::arg("azimuth_deg") = 0.0, py::arg("tilt_deg") = 0.0,
        py::arg("euler_zyz_deg") = py::none(),
        "The indicatrix axes X, Y, Z of the oriented crystal as the columns of a 3×3 array in the lab frame (x East,\n"
        "y North, z up the microscope), at stage 0. A cut is placed with the indices at the mineral's reference\n"
        "wavelength (docs/conventions.md).");
}

}  // namespace petroscope::python
