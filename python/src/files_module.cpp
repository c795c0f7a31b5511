// The extension module that uses the image libraries (libpng, libtiff, OpenEXR, libjpeg; OpenCV): reading thin sections and
// images, drawing the Michel-Lévy chart. It is kept apart from _petroscope so that `import petroscope` does
// not load them; the package imports it on first use.
#include "chart_arguments.hpp"
#include "convert.hpp"

#include "petroscope/api/scene_image.hpp"
#include "petroscope/io/chart_drawing.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/interface_case.hpp"
#include "petroscope/io/scene_file.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/verification/interface_cases.hpp"
#include "petroscope/verification/interface_suite.hpp"

#include <pybind11/stl.h>

namespace {

namespace py = pybind11;

py::list report_list(const petroscope::VerificationReport& report) {
    py::list tests;
    for (const petroscope::VerificationTest& test : report.tests) {
        py::list checks;
        for (const petroscope::VerificationCheck& check : test.checks) {
            checks.append(py::dict(py::arg("quantity") = check.quantity, py::arg("measured") = check.measured,
                                   py::arg("expected") = check.expected, py::arg("tolerance") = check.tolerance, py::arg("passed") = check.passed));
        }
        tests.append(py::dict(py::arg("name") = test.name, py::arg("statement") = test.statement, py::arg("source") = test.source,
                              py::arg("passed") = test.passed(), py::arg("checks") = checks));
    }
    return tests;
}

// A scene file rendered as `petroscope render` renders it: the image, the Stokes XYZ and their standard
// errors, the renderer's statistics and its estimate of the noise.
petroscope::python::Result render_scene(const std::string& path, int samples_per_pixel, int max_depth, std::optional<double> polarizer_deg,
                                        bool no_polarizer, std::uint64_t seed, double exposure, bool allow_large, const py::object& progress) {
    using namespace petroscope;
    const RenderSpectrum spectrum = scene_render_spectrum();
    Scene scene = parse_scene(read_text_file(path), path, python::catalog(), spectrum);
    const RenderSettings settings = plan_scene_render({samples_per_pixel, max_depth, polarizer_deg, no_polarizer, seed, exposure, allow_large}, scene);
    const SceneImage image = python::with_progress(progress, [&](const ProgressCallback& callback) {
        return render_scene_image(scene, spectrum, settings, exposure, callback);
    });
    const RenderStatistics& s = image.result.statistics;
    const auto quantile = [&](double q) -> py::object {
        if (image.relative_errors.empty()) return py::none();
        return py::float_(image.relative_errors[static_cast<std::size_t>(q * static_cast<double>(image.relative_errors.size() - 1))]);
    };
    python::Result result{python::to_numpy(image.linear_rgb), {"R", "G", "B"},
                          "linear sRGB (Bradford-adapted D65 white = 1) of the light through the camera polarizer, if any, times the exposure",
                          py::dict(py::arg("noise_median") = quantile(0.5), py::arg("noise_p90") = quantile(0.9)), {}, py::dict()};
    result.details["stokes_xyz"] = python::to_numpy(image.result.stokes_xyz);
    result.details["standard_error_y"] = python::to_numpy(image.result.standard_error_y);
    result.details["statistics"] = py::dict(py::arg("paths") = s.paths, py::arg("crystal_interactions") = s.crystal_interactions,
                                            py::arg("depth_limited") = s.depth_limited, py::arg("roulette_killed") = s.roulette_killed,
                                            py::arg("walked_off") = s.walked_off, py::arg("inconsistent") = s.inconsistent,
                                            py::arg("render_seconds") = s.seconds);
    return result;
}

}  // namespace

PYBIND11_MODULE(_files, module) {
    py::module_::import("petroscope._petroscope");  // registers Section and the exception translations
    module.def(
        "read_section",
        [](const std::string& path) { return petroscope::read_thin_section(path, petroscope::python::catalog()); }, py::arg("path"),
        "The thin section of a folder or description file (thin_sections/README.md).");
    module.def(
        "read_image", [](const std::string& path) { return petroscope::python::to_numpy(petroscope::read_image(path)); }, py::arg("path"),
        "An image file's values as float32 (height, width, channels): EXR and TIFF as stored, PNG and JPEG as codes / 255.");
    module.def(
        "interface_case",
        [](const std::string& path) {
            const petroscope::InterfaceCase interface_case = petroscope::load_interface_case(path, petroscope::python::catalog());
            const py::gil_scoped_release released;
            return petroscope::solve_interface(interface_case.normal, interface_case.incidence, interface_case.medium1, interface_case.medium2);
        },
        py::arg("path"), "Solves an interface case file (docs/interface.md), as `petroscope interface --case` does.");
    module.def(
        "verify",
        [](const std::optional<std::string>& cases_dir, bool own_sweeps) {
            const std::filesystem::path cases = cases_dir ? std::filesystem::path(*cases_dir)
                                                          : petroscope::data_directory().parent_path() / "verification" / "cases";
            petroscope::VerificationReport report;
            {
                const py::gil_scoped_release released;
                report = petroscope::check_case_directory(cases, petroscope::python::catalog());
                if (own_sweeps) {
                    for (petroscope::VerificationTest& test : petroscope::run_interface_suite({})) report.tests.push_back(std::move(test));
                }
            }
            return report_list(report);
        },
        py::kw_only(), py::arg("cases_dir") = py::none(), py::arg("own_sweeps") = true, "The verification suite (petroscope.verify).");
    module.def(
        "michel_levy_chart",
        [](const std::optional<std::string>& mineral, double max_retardation_nm, double step_nm, const py::object& light,
           double max_thickness_um) {
            if (!(max_thickness_um > 0.0)) throw py::value_error("max_thickness_um: expected a number > 0");
            const petroscope::MichelLevyColours chart = petroscope::python::chart_colours(mineral, max_retardation_nm, step_nm, light);
            petroscope::MichelLevyChartLayout layout;
            layout.max_thickness_um = max_thickness_um;
            return petroscope::python::to_numpy(petroscope::draw_michel_levy_chart(chart.steps, chart.linear_srgb, layout));
        },
        py::kw_only(), py::arg("mineral") = py::none(), py::arg("max_retardation_nm") = 2000.0, py::arg("step_nm") = 1.0,
        py::arg("light") = py::none(), py::arg("max_thickness_um") = 50.0, "The drawn chart (petroscope.michel_levy_chart).");
    module.def("render_scene", &render_scene, py::arg("path"), py::kw_only(), py::arg("samples_per_pixel") = 64, py::arg("max_depth") = 15,
               py::arg("polarizer_deg") = py::none(), py::arg("no_polarizer") = false, py::arg("seed") = 1, py::arg("exposure") = 1.0,
               py::arg("allow_large") = false, py::arg("progress") = py::none(), "A scene file rendered (petroscope.render_scene).");
}
