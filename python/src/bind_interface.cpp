// interface(): one plane wave meeting one plane interface, every reflected and transmitted wave.
#include "bindings.hpp"
#include "convert.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/interface.hpp"
#include "petroscope/optics/orientation.hpp"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>

namespace petroscope::python {
namespace {

using complex = std::complex<double>;

Eigen::Matrix3d axes_argument(const std::array<double, 3>& angles_deg) {
    for (const double angle : angles_deg) {
        if (!std::isfinite(angle)) throw py::value_error("euler_zyz_deg: expected finite angles in degrees");
    }
    return euler_zyz_deg(angles_deg[0], angles_deg[1], angles_deg[2]);
}

// The incident wave of an isotropic medium 1: 'unpolarized', 's', 'p', a Jones vector (E_s, E_p) or a
// Stokes vector (S0, S1, S2, S3) in the (s, p) basis (docs/interface.md).
void set_polarization(const py::object& polarization, InterfaceIncidence& incidence) {
    if (py::isinstance<py::str>(polarization)) {
        const std::string text = polarization.cast<std::string>();
        if (text == "unpolarized") return;  // the default coherency, I/2
        if (text != "s" && text != "p") throw py::value_error("polarization: expected 'unpolarized', 's', 'p', (E_s, E_p) or (S0, S1, S2, S3), not " + quote_input(text));
        incidence.jones = text == "s" ? JonesVector(1.0, 0.0) : JonesVector(0.0, 1.0);
    } else if (py::len(polarization) == 2) {
        const auto jones = polarization.cast<std::array<complex, 2>>();
        incidence.jones = JonesVector(jones[0], jones[1]);
        if (incidence.jones->norm() == 0.0 || !incidence.jones->allFinite()) throw py::value_error("polarization: expected a non-zero finite Jones vector");
    } else if (py::len(polarization) == 4) {
        const auto s = polarization.cast<std::array<double, 4>>();
        const Eigen::Vector4d stokes(s[0], s[1], s[2], s[3]);
        if (!is_physical_stokes(stokes)) throw py::value_error("polarization: a Stokes vector needs S0 > 0 and S1² + S2² + S3² <= S0²");
        incidence.coherency = coherency_from_stokes(stokes);
        return;
    } else {
        throw py::type_error("polarization: expected 'unpolarized', 's', 'p', a Jones vector (E_s, E_p) or a Stokes vector (S0, S1, S2, S3)");
    }
    incidence.coherency = coherency_from_jones(*incidence.jones / incidence.jones->norm());
}

// Landau's gyration tensor in the indicatrix frame: none, three principal values along X, Y, Z, or a symmetric
// 3 × 3 matrix.
Eigen::Matrix3d gyration_argument(const py::object& gyration) {
    if (gyration.is_none()) return Eigen::Matrix3d::Zero();
    Eigen::Matrix3d g;
    if (py::len(gyration) == 3 && !py::isinstance<py::sequence>(gyration[py::int_(0)])) {
        const auto principal = gyration.cast<std::array<double, 3>>();
        g = Eigen::Vector3d(principal[0], principal[1], principal[2]).asDiagonal();
    } else {
        g = gyration.cast<Eigen::Matrix3d>();
    }
    if (!g.allFinite() || !(g - g.transpose()).isZero(0.0)) throw py::value_error("gyration: expected finite values along X, Y, Z or a symmetric 3 × 3 matrix");
    return g;
}

InterfaceArithmetic arithmetic_argument(const std::string& name) {
    if (name == "long_double") return InterfaceArithmetic::long_double;
    if (name == "double") return InterfaceArithmetic::double_precision;
    throw py::value_error("arithmetic: expected 'long_double' or 'double', not " + quote_input(name));
}

InterfaceResult interface(const OpticalMedium& medium1, const OpticalMedium& medium2, const Eigen::Vector3d& direction,
                          const Eigen::Vector3d& normal, const py::object& polarization, const std::optional<std::string>& mode,
                          const std::string& arithmetic) {
    InterfaceIncidence incidence;
    incidence.direction = direction;
    incidence.with_mueller = true;
    incidence.arithmetic = arithmetic_argument(arithmetic);
    if (mode) {
        incidence.mode = parse_wave_mode(*mode);
        if (!incidence.mode || *incidence.mode == InterfaceMode::isotropic) {
            throw py::value_error("mode: expected 'fast', 'slow', 'ordinary' or 'extraordinary', not " + quote_input(*mode));
        }
    }
    set_polarization(polarization, incidence);
    return without_gil([&] { return solve_interface(normal, incidence, medium1, medium2); });
}

}  // namespace

void bind_interface(py::module_& module) {
    py::class_<OpticalMedium>(module, "Medium", "A homogeneous medium: principal indices n + iκ along its indicatrix axes X, Y, Z.")
        .def(py::init([](const py::object& n, std::array<double, 3> angles_deg, const py::object& gyration) {
                 OpticalMedium medium;
                 medium.axes = axes_argument(angles_deg);
                 if (py::isinstance<py::float_>(n) || py::isinstance<py::int_>(n) || PyComplex_Check(n.ptr())) {
                     medium.principal_n = Eigen::Vector3cd::Constant(n.cast<complex>());
                 } else {
                     const auto principal = n.cast<std::array<complex, 3>>();
                     medium.principal_n = Eigen::Vector3cd(principal[0], principal[1], principal[2]);
                 }
                 medium.gyration = gyration_argument(gyration);
                 return medium;
             }),
             py::arg("n"), py::kw_only(), py::arg("euler_zyz_deg") = std::array<double, 3>{0.0, 0.0, 0.0}, py::arg("gyration") = py::none(),
             "n: one index (isotropic) or three along X, Y, Z; complex n + iκ for an absorbing medium.\n"
             "euler_zyz_deg: the orientation of the indicatrix axes in the lab frame (docs/conventions.md).\n"
             "gyration: natural optical activity, Landau's gyration tensor g (dimensionless) in the indicatrix frame:\n"
             "three values along X, Y, Z or a symmetric 3 × 3 matrix; g = λρ/π along a principal direction of rotatory\n"
             "power ρ (positive: dextrorotatory, docs/conventions.md). None: inactive.")
        .def_static(
            "of_mineral",
            [](const std::string& name, double wavelength_nm, std::array<double, 3> angles_deg, const std::string& handedness) {
                if (!(wavelength_nm > 0.0) || !std::isfinite(wavelength_nm)) throw py::value_error("wavelength_nm: expected a finite number > 0");
                const Mineral& mineral = catalog().find(name);
                const Handedness hand = parse_handedness(handedness);
                OpticalMedium medium = OpticalMedium::from_n_kappa(mineral.principal_n(wavelength_nm), mineral.principal_kappa(wavelength_nm),
                                                                   axes_argument(angles_deg));
                medium.gyration = mineral.gyration(wavelength_nm, hand);
                return medium;
            },
            py::arg("mineral"), py::arg("wavelength_nm"), py::kw_only(), py::arg("euler_zyz_deg") = std::array<double, 3>{0.0, 0.0, 0.0},
            py::arg("handedness") = "right",
            "The medium of a catalog mineral at a wavelength, its indicatrix so oriented; an optically active mineral\n"
            "(quartz) in the form `handedness`, 'right' or 'left'.")
        .def_property_readonly("principal_n", [](const OpticalMedium& m) { return Eigen::Vector3cd(m.principal_n); })
        .def_property_readonly("axes", [](const OpticalMedium& m) { return Eigen::Matrix3d(m.axes); }, "indicatrix X, Y, Z (columns), lab frame")
        .def_property_readonly("gyration", [](const OpticalMedium& m) { return Eigen::Matrix3d(m.gyration); },
                               "Landau's gyration tensor in the indicatrix frame (zero: inactive)");

    py::class_<InterfaceWave>(module, "Wave", "One reflected or transmitted plane wave (docs/interface.md).")
        .def_property_readonly("kind", [](const InterfaceWave& w) { return w.kind == InterfaceWave::Kind::reflected ? "reflected" : "transmitted"; })
        .def_property_readonly("mode", [](const InterfaceWave& w) { return std::string(wave_mode_name(w.mode)); },
                               "'s+p' (isotropic), 'ordinary'/'extraordinary' (uniaxial), 'fast'/'slow' (biaxial, or optically active)")
        .def_readonly("direction", &InterfaceWave::direction, "unit wave normal (Re N), lab frame")
        .def_readonly("ray_direction", &InterfaceWave::ray_direction, "unit time-averaged Poynting vector")
        .def_readonly("n", &InterfaceWave::n, "√(N·N), complex")
        .def_readonly("power", &InterfaceWave::power, "normal Poynting flux relative to the incident one")
        .def_readonly("stokes", &InterfaceWave::stokes, "(S0, S1, S2, S3) in the wave's (s, p) basis, S0 = power")
        .def_readonly("mueller", &InterfaceWave::mueller,
                      "isotropic medium 1 (from interface()): the 4 × 4 Mueller matrix from the incident Stokes vector (S0 = 1) to `stokes`; else None")
        .def_property_readonly("jones", [](const InterfaceWave& w) { return w.jones ? std::optional<Eigen::Vector2cd>(*w.jones) : std::nullopt; },
                               "(E_s, E_p) for a unit incident Jones vector (isotropic waves, polarized incidence)")
        .def_readonly("amplitude", &InterfaceWave::amplitude, "an anisotropic mode's complex amplitude (polarized incidence)")
        .def_readonly("e_field", &InterfaceWave::e_field)
        .def_readonly("d_direction", &InterfaceWave::d_direction, "an anisotropic mode's vibration direction (zero for the elliptical waves of an active medium)")
        .def_readonly("evanescent", &InterfaceWave::evanescent)
        .def("__repr__", [](const InterfaceWave& w) {
            return std::string("<petroscope.Wave ") + (w.kind == InterfaceWave::Kind::reflected ? "reflected " : "transmitted ") +
                   std::string(wave_mode_name(w.mode)) + ", power " + std::to_string(w.power) + ">";
        });

    py::class_<InterfaceResult>(module, "InterfaceResult", "Every wave of one interface problem, reflected first, by increasing Re n.")
        .def_readonly("waves", &InterfaceResult::waves)
        .def_readonly("incident_n", &InterfaceResult::incident_n)
        .def_readonly("incident_ray_direction", &InterfaceResult::incident_ray_direction);

    module.def("interface", &interface, py::arg("medium1"), py::arg("medium2"), py::kw_only(), py::arg("direction"),
               py::arg("normal") = py::make_tuple(0.0, 0.0, 1.0), py::arg("polarization") = "unpolarized", py::arg("mode") = py::none(),
               py::arg("arithmetic") = "long_double",
               R"(One plane wave going from medium1 into medium2 across a plane interface: every reflected and
transmitted wave, solved exactly (the local interface model, docs/interface.md).

direction: the incident wave normal (lab frame), toward medium 2. normal: the interface normal, from
medium 1 into medium 2. polarization (isotropic medium 1): 'unpolarized', 's', 'p', a Jones vector
(E_s, E_p) or a Stokes vector (S0, S1, S2, S3). mode (anisotropic or optically active medium 1): the
incident eigenmode, 'fast', 'slow', or for an inactive uniaxial medium 'ordinary' or 'extraordinary'.
Medium 1 must be lossless. arithmetic: 'long_double'
(fluxes balance to about 1e-15 even near grazing and optic axes) or 'double' (about twice as fast, within
about 4e-11 of it in every power and Stokes parameter; the renderer's).)");
}

}  // namespace petroscope::python
