// fit_conoscope(): a photo of an interference figure (a numpy array) fitted for the slab's thickness and the
// photo's unknowns.
#include "bindings.hpp"
#include "convert.hpp"

#include "petroscope/api/conoscope_photo_model.hpp"
#include "petroscope/api/grain_fit.hpp"
#include "petroscope/fit/solver_messages.hpp"
#include "petroscope/microscope/thin_section.hpp"

#include <pybind11/eigen.h>

#include <pybind11/stl.h>

#include <algorithm>
#include <map>
#include <tuple>

namespace petroscope::python {
namespace {

// A fit's values by name, in four dicts: values, sigma (None where fixed or undetermined), free, identifiable.
struct FittedValues {
    py::dict values, sigma, free, identifiable;

    void add(const std::string& name, const FittedValue& fitted) {
        values[py::str(name)] = fitted.value;
        sigma[py::str(name)] = fitted.sigma ? py::object(py::float_(*fitted.sigma)) : py::object(py::none());
        free[py::str(name)] = fitted.free;
        identifiable[py::str(name)] = fitted.identifiable;
    }
    py::dict report() const {
        return py::dict(py::arg("values") = values, py::arg("sigma") = sigma, py::arg("free") = free, py::arg("identifiable") = identifiable);
    }
};

py::dict fit_result_dict(const ConoscopeFitResult& result, Image model_photo) {
    FittedValues fitted;
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        fitted.add(std::string(photo_parameter_name(static_cast<PhotoParameter>(j))), result.parameters[static_cast<std::size_t>(j)]);
    }
    py::list candidates;
    for (const ThicknessCandidate& c : result.candidates) {
        candidates.append(py::dict(py::arg("start_thickness_um") = c.start_thickness_um, py::arg("thickness_um") = c.thickness_um,
                                   py::arg("cost_per_residual") = c.cost));
    }
    py::dict report = fitted.report();
    report.attr("update")(py::dict(py::arg("acceptable") = result.acceptable, py::arg("verdict") = result.verdict, py::arg("rms_residual") = result.rms_residual,
                    py::arg("explained_variance") = result.explained_variance, py::arg("pixels_used") = result.pixels_used,
                    py::arg("pixels_saturated") = result.pixels_saturated, py::arg("iterations") = result.iterations,
                    py::arg("candidates") = candidates, py::arg("warnings") = result.warnings));
    report["mosaic_shift"] = py::none();
    if (result.mosaic_shift) {
        py::dict shift;
        for (int j = 0; j < kPhotoParameterCount; ++j) {
            const auto k = static_cast<std::size_t>(j);
            if (result.parameters[k].free) shift[py::str(std::string(photo_parameter_name(static_cast<PhotoParameter>(j))))] = (*result.mosaic_shift)[k];
        }
        report["mosaic_shift"] = shift;
    }
    report["model"] = to_numpy(model_photo);
    return report;
}

py::dict fit_conoscope(const py::array& photo_array, const std::string& mineral, const std::optional<std::string>& cut, const py::object& light,
                       double numerical_aperture, double polarizer_deg, double analyzer_deg, double surround_n, std::optional<double> thickness_um,
                       std::optional<std::pair<double, double>> thickness_range_um, double tilt_deg, double azimuth_deg,
                       const std::vector<std::string>& free, const std::map<std::string, double>& fixed, int candidates,
                       const std::string& handedness, const std::string& projection, const std::string& field_stop,
                       const std::string& illumination, const std::string& sensor, const py::object& progress, bool verbose) {
    const Image photo = image_argument(photo_array, "photo");
    show_solver_messages(verbose);
    const ConoscopePhotoSetup setup{.cut = cut ? std::optional(parse_cut(*cut)) : std::nullopt, .light = light_argument(light),
                                    .numerical_aperture = numerical_aperture, .polarizer_deg = polarizer_deg,
                                    .analyzer_deg = analyzer_deg, .surround_n = surround_n, .handedness = parse_handedness(handedness),
                                    .projection = parse_projection(projection), .field_stop = parse_field_stop(field_stop),
                                    .illumination = parse_illumination(illumination)};
    const ConoscopePhotoModel model = conoscope_photo_model(catalog().find(mineral), setup);
    ConoscopeFitOptions options;
    options.initial = default_photo_parameters(photo.width, photo.height);
    at(options.initial, PhotoParameter::tilt_deg) = tilt_deg;
    at(options.initial, PhotoParameter::azimuth_deg) = azimuth_deg;
    set_thickness_search(options, thickness_um, thickness_range_um);
    options.candidates = candidates;
    options.sensor = parse_colour_sensor(sensor);
    options.free.fill(false);
    for (const std::string& name : free) options.free[static_cast<std::size_t>(parse_photo_parameter(name))] = true;
    free_envelope_with_falloff(options, model);
    for (const auto& [name, value] : fixed) {
        const auto p = static_cast<std::size_t>(parse_photo_parameter(name));
        options.initial[p] = value;
        options.free[p] = false;
    }
    auto [result, model_photo] = with_progress(progress, [&](const ProgressCallback& callback) {
        ConoscopeFitResult fitted = fit_conoscope_photo(photo, model, options, callback);
        Image rendered = render_conoscope_photo(model, fitted.values, photo.width, photo.height);
        return std::pair{std::move(fitted), std::move(rendered)};
    });
    return fit_result_dict(result, std::move(model_photo));
}


// One value for all photos, or a list (or tuple) of one per photo.
std::vector<py::object> per_photo(const py::object& value, std::size_t photos, const std::string& argument) {
    if (!py::isinstance<py::list>(value) && !py::isinstance<py::tuple>(value)) return std::vector<py::object>(photos, value);
    const auto items = value.cast<std::vector<py::object>>();
    if (items.size() != photos) {
        throw py::value_error(argument + ": give one value for all " + std::to_string(photos) + " photos or a list of one per photo (got " +
                              std::to_string(items.size()) + ")");
    }
    return items;
}

// One photo's value of a per-photo argument as T; TypeError naming the argument and what it takes.
template <class T>
T photo_value(const py::object& value, const std::string& argument, const std::string& expected) {
    if (!py::isinstance<py::bool_>(value)) {
        try {
            return value.cast<T>();
        } catch (const py::cast_error&) {
        }
    }
    throw py::type_error(argument + ": expected " + expected + ", got " + std::string(py::str(py::type::of(value).attr("__name__"))));
}

// The grain's pixels in a photo: a mask array (non-zero: the grain), a region (x, y, width, height) or the whole photo.
Image grain_mask(const Image& photo, const py::object& mask, const py::object& region) {
    if (!mask.is_none()) {
        const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(mask);
        if (!values || values.ndim() != 2 || values.shape(0) != photo.height || values.shape(1) != photo.width) {
            throw py::value_error("mask: expected an array (height, width) of the photo's size, " + std::to_string(photo.height) + " x " +
                                  std::to_string(photo.width) + ", non-zero on the grain");
        }
        Image image(photo.width, photo.height, 1);
        std::transform(values.data(), values.data() + values.size(), image.pixels.begin(), [](float v) { return v != 0.0f ? 1.0f : 0.0f; });
        return image;
    }
    if (!region.is_none()) {
        std::array<int, 4> r{};
        try {
            r = region.cast<std::array<int, 4>>();
        } catch (const py::cast_error&) {
            throw py::type_error("region: expected (x, y, width, height) in whole pixels, the top-left corner first");
        }
        return rectangle_mask(photo.width, photo.height, r[0], r[1], r[2], r[3]);
    }
    Image whole(photo.width, photo.height, 1);
    std::fill(whole.pixels.begin(), whole.pixels.end(), 1.0f);
    return whole;
}

// Regions: one (x, y, width, height) for all photos, or a list of one per photo (None: none in that photo).
std::vector<py::object> per_photo_region(const py::object& region, std::size_t photos, const std::string& argument) {
    const auto first = [&] { return py::object(region[py::int_(0)]); };
    const bool listed = (py::isinstance<py::list>(region) || py::isinstance<py::tuple>(region)) && py::len(region) > 0 &&
                        (py::isinstance<py::list>(first()) || py::isinstance<py::tuple>(first()) || first().is_none());
    return listed ? per_photo(region, photos, argument) : std::vector<py::object>(photos, region);
}

// The reference region's colour in a photo, or none where neither its mask nor its region is given.
std::optional<GrainColour> reference_colour(const Image& photo, const py::object& mask, const py::object& region) {
    if (mask.is_none() && region.is_none()) return std::nullopt;
    return grain_colour(photo, grain_mask(photo, mask, region));
}

GrainFitRequest grain_fit_request(const py::object& photos_argument, const std::string& mineral, const py::object& stage_deg,
                                  const py::object& plate, double plate_slow_deg, const py::object& mask, const py::object& region,
                                  const py::object& reference_mask, const py::object& reference_region, const std::string& orientation,
                                  const std::optional<std::array<double, 3>>& euler_zyz_deg) {
    std::vector<py::array> photos;
    if (py::isinstance<py::array>(photos_argument)) {
        photos.push_back(photos_argument.cast<py::array>());
    } else {
        for (const py::handle photo : photos_argument) {
            if (!py::isinstance<py::array>(photo)) throw py::type_error("photos: expected a photo array or a list of photo arrays");
            photos.push_back(py::reinterpret_borrow<py::array>(photo));
        }
    }
    if (!mask.is_none() && !region.is_none()) throw py::value_error("mask and region: give one or the other");
    if (!reference_mask.is_none() && !reference_region.is_none()) throw py::value_error("reference_mask and reference_region: give one or the other");
    GrainFitRequest request;
    request.mineral = mineral;
    request.orientation = parse_grain_orientation(orientation);
    if (euler_zyz_deg) request.euler_zyz_deg = Eigen::Vector3d((*euler_zyz_deg)[0], (*euler_zyz_deg)[1], (*euler_zyz_deg)[2]);
    const auto stages = per_photo(stage_deg, photos.size(), "stage_deg"), plates = per_photo(plate, photos.size(), "plate");
    const auto masks = per_photo(mask, photos.size(), "mask"), regions = per_photo_region(region, photos.size(), "region");
    const auto reference_masks = per_photo(reference_mask, photos.size(), "reference_mask");
    const auto reference_regions = per_photo_region(reference_region, photos.size(), "reference_region");
    for (std::size_t k = 0; k < photos.size(); ++k) {
        const std::string label = "photos[" + std::to_string(k) + "]";
        const Image photo = image_argument(photos[k], label);
        const double stage = photo_value<double>(stages[k], "stage_deg", "an angle in degrees (or a list of one per photo)");
        const auto plate_name = photo_value<std::optional<std::string>>(plates[k], "plate", "'gypsum', 'mica', 'wedge' or None (or a list of one per photo)");
        GrainFitPhoto fit_photo{grain_colour(photo, grain_mask(photo, masks[k], regions[k])), stage, std::nullopt, label,
                                reference_colour(photo, reference_masks[k], reference_regions[k])};
        fit_photo.plate = plate_argument(plate_name, plate_slow_deg, 0.5);
        request.photos.push_back(std::move(fit_photo));
    }
    return request;
}

py::dict grain_fit_dict(const GrainFitPlan& plan, const OrthoscopeFitResult& result) {
    FittedValues fitted;
    fitted.add("thickness_um", result.thickness_um);
    fitted.add("retardation_550nm", result.retardation_nm);
    fitted.add("birefringence_550nm", result.birefringence);
    for (std::size_t a = 0; a < 3; ++a) fitted.add("angle_" + std::to_string(a) + "_deg", result.angles_deg[a]);
    fitted.add("exposure", result.exposure);
    py::list photos, candidates;
    for (std::size_t k = 0; k < plan.photos.size(); ++k) {
        const GrainColour& colour = plan.photos[k].colour;
        py::dict photo(py::arg("mean_code") = colour.mean_code, py::arg("model_code") = result.model_code[k], py::arg("pixels") = colour.pixels,
                       py::arg("pixels_saturated") = colour.saturated, py::arg("reference") = py::none());
        if (plan.photos[k].reference && result.calibration) {
            photo["reference"] = py::dict(py::arg("mean_code") = plan.photos[k].reference->mean_code,
                                          py::arg("model_code") = *result.calibration->model_code[k], py::arg("pixels") = plan.photos[k].reference->pixels);
        }
        photos.append(photo);
    }
    py::object calibration = py::none();
    if (result.calibration) {
        const CameraCalibration& camera = *result.calibration;
        py::list with_grain;
        for (std::size_t c = 0; c < 3; ++c) {
            if (camera.fitted_with_grain[c]) with_grain.append(std::string(1, "RGB"[c]));
        }
        calibration = py::dict(py::arg("channel_gains") = camera.channel_gains, py::arg("gains_fitted_with_the_grain") = with_grain,
                               py::arg("contrast") = camera.contrast.value, py::arg("contrast_sigma") = camera.contrast.sigma,
                               py::arg("reference_rms_code") = camera.rms_code);
    }
    for (const GrainCandidate& c : result.candidates) {
        candidates.append(py::dict(py::arg("thickness_um") = c.thickness_um, py::arg("angles_deg") = c.angles_deg, py::arg("rms_code") = c.rms_code));
    }
    py::dict report = fitted.report();
    report.attr("update")(py::dict(
        py::arg("acceptable") = result.acceptable, py::arg("verdict") = result.verdict, py::arg("rms_code") = result.rms_code,
        py::arg("thickness_lower_bound_um") = result.thickness_lower_bound_um, py::arg("euler_zyz_deg") = euler_zyz_deg_of(result.axes),
        py::arg("angles_meaning") = plan.options.orientation == GrainOrientation::max_birefringence ? "angle_0_deg: the indicatrix X axis at stage 0, from E toward N"
                                    : plan.options.orientation == GrainOrientation::free            ? "angle_0_deg … angle_2_deg: ZYZ Euler angles of the indicatrix at stage 0"
                                                                                                     : "unused (orientation given)",
        py::arg("photos") = photos, py::arg("candidates") = candidates, py::arg("camera_calibration") = calibration, py::arg("warnings") = result.warnings));
    return report;
}

py::dict fit_orthoscope(const py::object& photos, const std::string& mineral, const py::object& stage_deg, const py::object& plate,
                        double plate_slow_deg, const py::object& mask, const py::object& region, const py::object& reference_mask,
                        const py::object& reference_region, const std::string& orientation,
                        const std::optional<std::array<double, 3>>& euler_zyz_deg, std::pair<double, double> thickness_range_um,
                        bool exposure_free, int candidates, double condenser_na, double polarizer_deg, double analyzer_deg,
                        const py::object& light, const std::string& handedness, const py::object& progress, bool verbose) {
    show_solver_messages(verbose);
    GrainFitRequest request =
        grain_fit_request(photos, mineral, stage_deg, plate, plate_slow_deg, mask, region, reference_mask, reference_region, orientation, euler_zyz_deg);
    request.handedness = parse_handedness(handedness);
    std::tie(request.thickness_min_um, request.thickness_max_um) = thickness_range_um;
    request.exposure_free = exposure_free;
    request.candidates = candidates;
    request.condenser_na = condenser_na;
    request.polarizer_deg = polarizer_deg;
    request.analyzer_deg = analyzer_deg;
    request.light = light_argument(light);
    const GrainFitPlan plan = plan_grain_fit(request, catalog());
    const OrthoscopeFitResult result = with_progress(progress, [&](const ProgressCallback& callback) { return fit_grain(plan, callback); });
    return grain_fit_dict(plan, result);
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
               py::arg("handedness") = "right", py::arg("projection") = "sine", py::arg("field_stop") = "sharp",
               py::arg("illumination") = "even", py::arg("sensor") = "full-colour", py::arg("progress") = py::none(), py::arg("verbose") = false,
               R"(Fits a photo of a conoscopic figure: the slab's thickness, the figure's centre, scale and rotation,
the cut's tilt, the camera's gains, black level, gamma and blur (docs/fitting.md).

photo: camera values 0 to 1, float, (height, width, 3) or (height, width) in monochromatic light.
mineral, cut, light, numerical_aperture, polarizer_deg, analyzer_deg, surround_n: what is known of the
  photo, as for conoscope(). thickness_um: a starting thickness (searched from a third to three times it);
  thickness_range_um: (min, max) to search instead. tilt_deg, azimuth_deg: the cut's starting tilt.
free: the parameters fitted, by name (thickness_um, center_x_px, center_y_px, field_radius_px,
  rotation_deg, tilt_deg, azimuth_deg, gain_r, gain_g, gain_b, black_level, gamma, blur_variance_px2,
  distortion, analyzer_offset_deg, extinction_ratio, crosstalk_rg, crosstalk_rb, crosstalk_gr, crosstalk_gb,
  crosstalk_br, crosstalk_bg (the camera's colour matrix); envelope_center_x_px, envelope_center_y_px,
  envelope_radius_px, envelope_power are freed by illumination='falloff'); fixed: {name: value} held at a
  value. candidates: thickness minima refined. handedness: 'right' or 'left', the form of an optically
  active mineral (quartz).
projection: 'sine' (a microscope objective), 'tangent' (a camera or lens looking through the crystal, a
  figure on a screen) or 'equidistant'. field_stop: 'sharp' (the objective's aperture edge) or 'none'
  (the frame and the light's falloff bound the field). illumination: 'even' or 'falloff' (the light
  falls off as exp(-(r/R)^p) about its own centre, fitted). sensor: 'full-colour' (every colour at every
  pixel: a rendered photo) or 'bayer' (a colour camera's mosaic, demosaiced: the fit measures what the
  demosaicing does to its result and adds it to each 1 sigma).
progress: called with the fraction done; return False to cancel. Ctrl-C cancels.
verbose: the solver's (Ceres's) messages and its progress per iteration on standard error; off, it prints
  nothing (as the command line without --verbose).

Returns a dict: values, sigma (1 sigma, None where fixed or not determined), free, identifiable (by
name); acceptable and verdict; rms_residual, explained_variance, pixels_used, pixels_saturated,
iterations, candidates, warnings; mosaic_shift: with sensor='bayer', each free parameter's shift when the
best fit goes through the mosaic and is fitted again (None otherwise); model: the best fit's photo (float32, like photo). A photo given as an
array carries no JPEG encoding: its systematic error is not checked (the command line's fit checks it).)");
    module.def("fit_orthoscope", &fit_orthoscope, py::arg("photos"), py::kw_only(), py::arg("mineral"), py::arg("stage_deg") = 0.0,
               py::arg("plate") = py::none(), py::arg("plate_slow_deg") = 45.0, py::arg("mask") = py::none(), py::arg("region") = py::none(),
               py::arg("reference_mask") = py::none(), py::arg("reference_region") = py::none(), py::arg("orientation") = "max-birefringence", py::arg("euler_zyz_deg") = py::none(),
               py::arg("thickness_range_um") = std::pair(1.0, 200.0), py::arg("exposure_free") = false, py::arg("candidates") = 4,
               py::arg("condenser_na") = 0.0, py::arg("polarizer_deg") = 0.0, py::arg("analyzer_deg") = 90.0, py::arg("light") = py::none(),
               py::arg("handedness") = "right", py::arg("progress") = py::none(), py::arg("verbose") = false,
               R"(Fits a grain's thickness (and optic orientation) to its colours in crossed-polar photos (docs/fitting.md).

photos: one photo or a list, each camera values 0 to 1, float, (height, width, 3), sRGB as a camera stores it.
mineral: name or alias. stage_deg, plate ('gypsum', 'mica' or None), mask (array of the photo's size,
  non-zero on the grain), region ((x, y, width, height) in pixels): one for all photos or a list of one per
  photo; without mask or region the whole photo is the grain. plate_slow_deg: the plate's slow direction.
reference_mask, reference_region: a region without birefringence (a hole, an isotropic grain, a grain at
  extinction) that calibrates the camera's colours, given like mask and region (a list may hold None for a
  photo where the region is not so); black between crossed polars, it calibrates only in a photo with a
  plate, where it shows the plate's own colour. The exposure is then fitted too (docs/fitting.md).
orientation: 'max-birefringence' (the grain shows its highest colour; its angle is fitted), 'known' (give
  euler_zyz_deg) or 'free' (only the retardation is determined). thickness_range_um: (min, max) searched.
exposure_free: fit the exposure too. candidates: grid minima refined (1 to 20). condenser_na,
  polarizer_deg, analyzer_deg, light (white: a Light or None) as for orthoscope(). handedness: 'right' or
  'left', the form of an optically active mineral (quartz, paratellurite): with a plate in, it changes a grain's colour by
  about a code level.
progress: called with the fraction done; return False to cancel. Ctrl-C cancels.
verbose: the solver's (Ceres's) messages on standard error, as for fit_conoscope().

Returns a dict: values, sigma (1 sigma, None where fixed or not determined), free, identifiable, by name
(thickness_um, retardation_550nm in nm, birefringence_550nm, angle_0_deg … angle_2_deg, exposure) and
angles_meaning; acceptable, verdict, rms_code (sRGB code units 0 to 1), thickness_lower_bound_um (free
orientation), euler_zyz_deg of the fitted indicatrix, photos (measured and model colours, pixels used, and
the reference's or None), candidates, camera_calibration (channel_gains, gains_fitted_with_the_grain,
contrast, contrast_sigma, reference_rms_code; None without a reference region), warnings.)");
}

}  // namespace petroscope::python
