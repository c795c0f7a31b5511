// fit_conoscope(): a photo of an interference figure (a numpy array) fitted for the slab's thickness and the
// photo's unknowns.
#include "bindings.hpp"
#include "convert.hpp"

#include "petroscope/api/conoscope_photo_model.hpp"

#include <pybind11/stl.h>

#include <map>

namespace petroscope::python {
namespace {

// Camera values 0 … 1, float, H × W × 3 (or H × W in monochromatic light); TypeError or ValueError otherwise.
Image photo_argument(const py::array& photo) {
    if (photo.dtype().kind() != 'f') {
        throw py::type_error("photo: expected float camera values 0 to 1 (for 8-bit codes, divide by 255), got dtype " +
                             std::string(py::str(photo.dtype())));
    }
    const bool gray = photo.ndim() == 2;
    if (!gray && !(photo.ndim() == 3 && (photo.shape(2) == 3 || photo.shape(2) == 1))) {
        throw py::value_error("photo: expected an array (height, width, 3) or (height, width)");
    }
    const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(photo);
    Image image(static_cast<int>(values.shape(1)), static_cast<int>(values.shape(0)), gray ? 1 : static_cast<int>(values.shape(2)));
    std::copy(values.data(), values.data() + values.size(), image.pixels.begin());
    return image;
}

py::dict fit_result_dict(const ConoscopeFitResult& result, Image model_photo) {
    py::dict values, sigma, free, identifiable;
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const py::str name(std::string(photo_parameter_name(static_cast<PhotoParameter>(j))));
        const FittedValue& fitted = result.parameters[static_cast<std::size_t>(j)];
        values[name] = fitted.value;
        sigma[name] = fitted.sigma ? py::object(py::float_(*fitted.sigma)) : py::object(py::none());
        free[name] = fitted.free;
        identifiable[name] = fitted.identifiable;
    }
    py::list candidates;
    for (const ThicknessCandidate& c : result.candidates) {
        candidates.append(py::dict(py::arg("start_thickness_um") = c.start_thickness_um, py::arg("thickness_um") = c.thickness_um,
                                   py::arg("cost_per_residual") = c.cost));
    }
    py::dict report(py::arg("values") = values, py::arg("sigma") = sigma, py::arg("free") = free, py::arg("identifiable") = identifiable,
                    py::arg("acceptable") = result.acceptable, py::arg("verdict") = result.verdict, py::arg("rms_residual") = result.rms_residual,
                    py::arg("explained_variance") = result.explained_variance, py::arg("pixels_used") = result.pixels_used,
                    py::arg("pixels_saturated") = result.pixels_saturated, py::arg("iterations") = result.iterations,
                    py::arg("candidates") = candidates, py::arg("warnings") = result.warnings);
    report["model"] = to_numpy(model_photo);
    return report;
}

py::dict fit_conoscope(const py::array& photo_array, const std::string& mineral, const std::optional<std::string>& cut, const py::object& light,
                       double numerical_aperture, double polarizer_deg, double analyzer_deg, double surround_n, std::optional<double> thickness_um,
                       std::optional<std::pair<double, double>> thickness_range_um, double tilt_deg, double azimuth_deg,
                       const std::vector<std::string>& free, const std::map<std::string, double>& fixed, int candidates,
                       const py::object& progress) {
    const Image photo = photo_argument(photo_array);
    const ConoscopePhotoSetup setup{.cut = cut ? std::optional(parse_cut(*cut)) : std::nullopt, .light = light_argument(light),
                                    .numerical_aperture = numerical_aperture, .polarizer_deg = polarizer_deg,
                                    .analyzer_deg = analyzer_deg, .surround_n = surround_n};
    ConoscopeFitOptions options;
    options.initial = default_photo_parameters(photo.width, photo.height);
    at(options.initial, PhotoParameter::tilt_deg) = tilt_deg;
    at(options.initial, PhotoParameter::azimuth_deg) = azimuth_deg;
    set_thickness_search(options, thickness_um, thickness_range_um);
    options.candidates = candidates;
    options.free.fill(false);
    for (const std::string& name : free) options.free[static_cast<std::size_t>(parse_photo_parameter(name))] = true;
    for (const auto& [name, value] : fixed) {
        const auto p = static_cast<std::size_t>(parse_photo_parameter(name));
        options.initial[p] = value;
        options.free[p] = false;
    }
    auto [result, model_photo] = with_progress(progress, [&](const ProgressCallback& callback) {
        const ConoscopePhotoModel model = conoscope_photo_model(catalog().find(mineral), setup);
        ConoscopeFitResult fitted = fit_conoscope_photo(photo, model, options, callback);
        Image rendered = render_conoscope_photo(model, fitted.values, photo.width, photo.height);
        return std::pair{std::move(fitted), std::move(rendered)};
    });
    return fit_result_dict(result, std::move(model_photo));
}

}  // namespace

void bind_fit(py::module_& module) {
    const std::vector<std::string> default_free{"thickness_um", "center_x_px", "center_y_px", "field_radius_px", "rotation_deg", "gain_r",
                                                "gain_g",       "gain_b",      "black_level", "gamma",           "blur_variance_px2"};
    module.def("fit_conoscope", &fit_conoscope, py::arg("photo"), py::kw_only(), py::arg("mineral") = "muscovite", py::arg("cut") = py::none(),
               py::arg("light") = py::none(), py::arg("numerical_aperture") = 0.85, py::arg("polarizer_deg") = 0.0,
               py::arg("analyzer_deg") = 90.0, py::arg("surround_n") = 1.54, py::arg("thickness_um") = py::none(),
               py::arg("thickness_range_um") = py::none(), py::arg("tilt_deg") = 0.0, py::arg("azimuth_deg") = 0.0,
               py::arg("free") = default_free, py::arg("fixed") = std::map<std::string, double>{}, py::arg("candidates") = 3,
               py::arg("progress") = py::none(),
               R"(Fits a photo of a conoscopic figure: the slab's thickness, the figure's centre, scale and rotation,
the cut's tilt, the camera's gains, black level, gamma and blur (docs/fitting.md).

photo: camera values 0 to 1, float, (height, width, 3) or (height, width) in monochromatic light.
mineral, cut, light, numerical_aperture, polarizer_deg, analyzer_deg, surround_n: what is known of the
  photo, as for conoscope(). thickness_um: a starting thickness (searched from a third to three times it);
  thickness_range_um: (min, max) to search instead. tilt_deg, azimuth_deg: the cut's starting tilt.
free: the parameters fitted, by name (thickness_um, center_x_px, center_y_px, field_radius_px,
  rotation_deg, tilt_deg, azimuth_deg, gain_r, gain_g, gain_b, black_level, gamma, blur_variance_px2);
  fixed: {name: value} held at a value. candidates: thickness minima refined.
progress: called with the fraction done; return False to cancel. Ctrl-C cancels.

Returns a dict: values, sigma (1 sigma, None where fixed or not determined), free, identifiable (by
name); acceptable and verdict; rms_residual, explained_variance, pixels_used, pixels_saturated,
iterations, candidates, warnings; model: the best fit's photo (float32, like photo). A photo given as an
array carries no JPEG encoding: its systematic error is not checked (the command line's fit checks it).)");
}

}  // namespace petroscope::python
