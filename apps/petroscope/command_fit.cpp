// petroscope fit conoscope: the slab thickness (and the unknowns of a real photo) fitted to a photograph of
// an interference figure. The method: docs/fitting.md.
#include "cli_common.hpp"
#include "heavy_commands.hpp"
#include "cli_light.hpp"
#include "fit_report.hpp"
#include "frame_command.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/fit/solver_messages.hpp"
#include "petroscope/api/conoscope_photo_model.hpp"
#include "petroscope/io/atomic_file.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/jpeg_encoding.hpp"
#include "petroscope/io/json_sidecar.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <map>

namespace petroscope::cli {
namespace {

// --free groups and the parameters they free.
const std::map<std::string, std::vector<PhotoParameter>>& free_groups() {
    static const std::map<std::string, std::vector<PhotoParameter>> groups{
        {"thickness", {PhotoParameter::thickness_um}},
        {"center", {PhotoParameter::center_x_px, PhotoParameter::center_y_px}},
        {"scale", {PhotoParameter::field_radius_px}},
        {"rotation", {PhotoParameter::rotation_deg}},
        {"tilt", {PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}},
        {"white-balance", {PhotoParameter::gain_r, PhotoParameter::gain_g, PhotoParameter::gain_b}},
        {"black", {PhotoParameter::black_level}},
        {"gamma", {PhotoParameter::gamma}},
        {"blur", {PhotoParameter::blur_variance_px2}},
        {"envelope", {PhotoParameter::envelope_center_x_px, PhotoParameter::envelope_center_y_px, PhotoParameter::envelope_radius_px,
                      PhotoParameter::envelope_power}},
        {"distortion", {PhotoParameter::distortion}},
        {"analyzer", {PhotoParameter::analyzer_offset_deg}},
        {"extinction", {PhotoParameter::extinction_ratio}},
        {"colour-matrix", {PhotoParameter::crosstalk_rg, PhotoParameter::crosstalk_rb, PhotoParameter::crosstalk_gr,
                           PhotoParameter::crosstalk_gb, PhotoParameter::crosstalk_br, PhotoParameter::crosstalk_bg}},
    };
    return groups;
}

struct FitOptions {
    std::string photo, mineral = "muscovite", cut, thickness, thickness_range, output_dir, handedness = "right";
    std::string projection = "sine", field_stop = "sharp", illumination = "even", sensor = "auto";
    std::string free = "thickness,center,scale,rotation,white-balance,black,gamma,blur";
    std::vector<std::string> fixed;
    double azimuth_deg = 0.0, tilt_deg = 0.0, na = 0.85, polarizer_deg = 0.0, analyzer_deg = 90.0, surround_n = 1.54;
    int candidates = 3;
    bool json = false;
    bool no_encoding_check = false;
    bool verbose = false;
    LightOptions light;
};

/// What the report says about the photo's encoding: none (PNG, TIFF), or the JPEG's and whether the
/// fit checked its systematic error.
nlohmann::json encoding_json(const std::optional<JpegEncoding>& jpeg, bool checked) {
    if (!jpeg) return "none (lossless)";
    return {{"format", "JPEG"},
            {"description", describe(*jpeg)},
            {"luma_quality", jpeg->luma_quality},
            {"chroma_quality", jpeg->chroma_quality},
            {"standard_tables", jpeg->standard_tables},
            {"chroma_samples_per", {jpeg->chroma_step_x, jpeg->chroma_step_y}},
            {"checked", checked},
            {"repeated_exactly", reproducible(*jpeg)}};
}

nlohmann::json report_json(const ConoscopeFitResult& result, const FitOptions& options, const ConoscopeFitOptions& fit_options,
                           const std::optional<JpegEncoding>& jpeg, double seconds) {
    nlohmann::json parameters = nlohmann::json::object();
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const FittedValue& value = result.parameters[static_cast<std::size_t>(j)];
        nlohmann::json entry = fitted_value_json(value);
        entry["initial"] = fit_options.initial[static_cast<std::size_t>(j)];
        if (result.encoding_shift && value.free) entry["encoding_shift"] = (*result.encoding_shift)[static_cast<std::size_t>(j)];
        if (result.mosaic_shift && value.free) entry["mosaic_shift"] = (*result.mosaic_shift)[static_cast<std::size_t>(j)];
        parameters[std::string(photo_parameter_name(static_cast<PhotoParameter>(j)))] = entry;
    }
    nlohmann::json candidates = nlohmann::json::array();
    for (const auto& candidate : result.candidates) {
        candidates.push_back({{"start_thickness_um", candidate.start_thickness_um}, {"thickness_um", candidate.thickness_um},
                              {"cost_per_residual", candidate.cost}});
    }
    return {{"program", "petroscope 0.1.0"},
            {"command", "fit conoscope"},
            {"photo", options.photo},
            {"photo_encoding", encoding_json(jpeg, static_cast<bool>(fit_options.photo_encoding))},
            {"mineral", options.mineral},
            {"cut", options.cut},
            {"numerical_aperture", options.na},
            {"polarizer_deg", options.polarizer_deg},
            {"analyzer_deg", options.analyzer_deg},
            {"surround_n", options.surround_n},
            {"handedness", options.handedness},
            {"projection", options.projection},
            {"field_stop", options.field_stop},
            {"illumination", options.illumination},
            {"sensor", colour_sensor_name(fit_options.sensor)},
            {"thickness_search_um", {fit_options.thickness_min_um, fit_options.thickness_max_um}},
            {"acceptable", result.acceptable},
            {"verdict", result.verdict},
            {"parameters", parameters},
            {"candidates", candidates},
            {"warnings", result.warnings},
            {"rms_residual", result.rms_residual},
            {"explained_variance", result.explained_variance},
            {"pixels_used", result.pixels_used},
            {"pixels_saturated", result.pixels_saturated},
            {"iterations", result.iterations},
            {"seconds", seconds},
            {"model", "camera value = black + (gain * envelope * linear sRGB)^(1/gamma); figure: single-pass Jones from the exact "
                      "eigenmodes (ConoscopeTerms; in white light interpolated from 8 spectral nodes where accurate) through the analyzer plus extinction_ratio times the light it blocks, blur by the "
                      "local fringe approximation; see docs/fitting.md"},
            {"sigma_meaning", "1 sigma from the Gauss-Newton covariance (J^T J)^+ with a cluster-robust (sandwich) correction over blocks of the field; "
                              "for a checked JPEG photo, plus encoding_shift in quadrature (the shift when the best fit is encoded "
                              "as the photo was and fitted again), and with a Bayer sensor plus mosaic_shift (the same through an "
                              "RGGB mosaic and bilinear demosaicing)"}};
}

std::string shown(double value) { return format_significant(value, 6); }

// The camera values of `values` written so that the PNG's codes equal them.
Image camera_values_for_png(const Image& values) {
    Image linear = values;
    for (float& v : linear.pixels) v = static_cast<float>(decode_srgb(std::clamp(static_cast<double>(v), 0.0, 1.0)));
    return linear;
}

void run_fit_conoscope(const FitOptions& options, const std::string& minerals_dir) {
    const Image photo_raw = with_option("--photo", [&] { return read_image(options.photo); });
    if (photo_raw.width == 0 || photo_raw.height == 0) throw InputError("--photo " + options.photo + ": the image is empty");
    const std::optional<JpegEncoding> jpeg = with_option("--photo", [&] { return read_jpeg_encoding(options.photo); });
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    const Mineral& mineral = with_option("--mineral", [&]() -> const Mineral& { return catalog.find(options.mineral); });
    ConoscopePhotoSetup setup;
    if (!options.cut.empty()) setup.cut = with_option("--cut", [&] { return parse_cut(options.cut); });
    setup.light = light_from_options(options.light);
    setup.numerical_aperture = options.na;
    setup.polarizer_deg = options.polarizer_deg;
    setup.analyzer_deg = options.analyzer_deg;
    setup.surround_n = options.surround_n;
    setup.handedness = with_option("--handedness", [&] { return parse_handedness(options.handedness); });
    setup.projection = with_option("--projection", [&] { return parse_projection(options.projection); });
    setup.field_stop = with_option("--field-stop", [&] { return parse_field_stop(options.field_stop); });
    setup.illumination = with_option("--illumination", [&] { return parse_illumination(options.illumination); });
    const ConoscopePhotoModel model = conoscope_photo_model(mineral, setup);

    ConoscopeFitOptions fit;
    fit.initial = default_photo_parameters(photo_raw.width, photo_raw.height);
    at(fit.initial, PhotoParameter::tilt_deg) = options.tilt_deg;
    at(fit.initial, PhotoParameter::azimuth_deg) = options.azimuth_deg;
    fit.candidates = options.candidates;
    std::optional<double> start_um;
    std::optional<std::pair<double, double>> range_um;
    if (!options.thickness.empty()) start_um = positive_length_um("--thickness", options.thickness);
    if (!options.thickness_range.empty()) range_um = length_range_um("--thickness-range", options.thickness_range);
    set_thickness_search(fit, start_um, range_um);
    fit.free.fill(false);
    for (const std::string& group : split(options.free, ',')) {
        const auto found = free_groups().find(group);
        if (found == free_groups().end()) {
            std::string names;
            for (const auto& [name, members] : free_groups()) names += (names.empty() ? "" : ", ") + name;
            throw InputError("--free " + quote_input(group) + ": unknown group (expected any of " + names + ")");
        }
        for (const PhotoParameter p : found->second) fit.free[static_cast<std::size_t>(p)] = true;
    }
    with_option("--free", [&] { free_envelope_with_falloff(fit, model); });
    for (const std::string& assignment : options.fixed) {
        const auto parts = split(assignment, '=');
        const auto value = parts.size() == 2 ? parse_double(parts[1]) : std::nullopt;
        if (!value) throw InputError("--fix " + quote_input(assignment) + ": expected NAME=VALUE, e.g. field_radius_px=250 or gamma=2.2");
        const PhotoParameter p = with_option("--fix", [&] { return parse_photo_parameter(parts[0]); });
        fit.initial[static_cast<std::size_t>(p)] = *value;
        fit.free[static_cast<std::size_t>(p)] = false;
    }

    if (jpeg && !options.no_encoding_check) {
        fit.photo_encoding = [encoding = *jpeg](const Image& camera_values) { return encode_like_jpeg(camera_values, encoding); };
    }
    // A colour JPEG is a camera's photo, and nearly every colour camera has a Bayer sensor; PNG and TIFF may be
    // rendered, and a grey photo comes from a monochrome sensor.
    const bool colour_jpeg = jpeg && photo_raw.channels >= 3;
    fit.sensor = options.sensor == "auto" ? (colour_jpeg ? ColourSensor::bayer : ColourSensor::full_colour) : parse_colour_sensor(options.sensor);

    // Reserve every output before the work starts: an unwritable folder fails at once, nothing half-written.
    const std::filesystem::path folder(options.output_dir);
    if (!std::filesystem::is_directory(folder)) throw InputError("-o " + options.output_dir + ": not a folder (create it first)");
    PendingOutputs pending;
    const auto model_png = pending.add(folder / "model.png"), side_png = pending.add(folder / "side_by_side.png");
    const auto residual_tiff = pending.add(folder / "residual.tiff"), report_path = pending.add(folder / "report.json");

    show_solver_messages(options.verbose);
    const auto begin = std::chrono::steady_clock::now();
    const ConoscopeFitResult result = fit_conoscope_photo(photo_raw, model, fit, [](double f) { show_progress("fitting", f); return true; });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

    // The best-fit rendering, photo | model | residual (×4 around grey), and the residual as float numbers.
    const int w = photo_raw.width, h = photo_raw.height;
    const Image rendered = render_conoscope_photo(model, result.values, w, h);
    Image side(3 * w, h, 3), residual(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) {
                const float observed = photo_raw.at(x, y, std::min(c, photo_raw.channels - 1));
                const float difference = rendered.at(x, y, c) - observed;
                residual.at(x, y, c) = difference;
                side.at(x, y, c) = observed;
                side.at(w + x, y, c) = rendered.at(x, y, c);
                side.at(2 * w + x, y, c) = std::clamp(0.5f + 4.0f * difference, 0.0f, 1.0f);
            }
        }
    }
    const nlohmann::json report = report_json(result, options, fit, jpeg, seconds);
    write_image(camera_values_for_png(rendered), model_png, ImageFormat::png);
    write_image(camera_values_for_png(side), side_png, ImageFormat::png);
    write_image(residual, residual_tiff, ImageFormat::tiff);
    write_json_file(report, report_path);
    pending.commit();

    finish_fit(options.json, report, result.acceptable, result.verdict, [&] {
        for (int j = 0; j < kPhotoParameterCount; ++j) {
            const bool envelope = j >= static_cast<int>(PhotoParameter::envelope_center_x_px) && j <= static_cast<int>(PhotoParameter::envelope_power);
            if (envelope && model.illumination == IlluminationProfile::even) continue;
            std::cout << "  " << photo_parameter_name(static_cast<PhotoParameter>(j)) << " = "
                      << fitted_value_text(result.parameters[static_cast<std::size_t>(j)]) << '\n';
        }
        std::cout << "  thickness minima (coarse cost per residual):";
        for (const auto& c : result.candidates) std::cout << ' ' << shown(c.thickness_um) << "um (" << shown(c.cost) << ")";
        std::cout << '\n';
        if (jpeg) {
            const std::string how = !fit.photo_encoding ? "not checked (--no-encoding-check): the 1-sigma values leave out its systematic error"
                                    : result.encoding_shift
                                        ? "checked: it shifts the thickness by " + shown((*result.encoding_shift)[0]) + " um, included in its 1 sigma"
                                        : "checked";
            std::cout << "  JPEG photo (" << describe(*jpeg) << "): " << how << '\n';
            if (fit.photo_encoding && !reproducible(*jpeg)) {
                std::cout << "warning: the check repeats this JPEG as libjpeg 4:2:0 at quality " << jpeg->luma_quality
                          << ", the nearest encoding it can write\n";
            }
        }
        if (result.mosaic_shift) {
            std::cout << "  Bayer sensor (--sensor bayer): its demosaicing, checked, shifts the thickness by " << shown((*result.mosaic_shift)[0])
                      << " um, included in its 1 sigma\n";
        }
        for (const auto& warning : result.warnings) std::cout << "warning: " << warning << '\n';
        std::cout << "wrote " << (folder / "report.json").string() << ", model.png, side_by_side.png, residual.tiff (" << shown(seconds) << " s)\n";
    });
}

}  // namespace

void add_fit_command(CLI::App& app, const std::string& minerals_dir) {
    CLI::App* fit = app.add_subcommand(std::string(kFitCommand.name), std::string(kFitCommand.description));
    fit->require_subcommand(1);
    auto options = std::make_shared<FitOptions>();
    CLI::App* conoscope = fit->add_subcommand(
        "conoscope",
        "Fit the slab thickness, the figure's centre, scale and rotation and the camera's response to a photo of an\n"
        "interference figure (PNG, JPEG or TIFF, 8 or 16 bit). Writes model.png, side_by_side.png (photo | model |\n"
        "residual x4 around grey), residual.tiff and report.json into the -o folder.");
    conoscope->add_option("--photo", options->photo, "The photograph")->required();
    conoscope->add_option("--mineral", options->mineral, "Mineral name or alias")->capture_default_str();
    conoscope->add_option("--cut", options->cut, "optic-axis | acute-bisectrix | obtuse-bisectrix | optic-normal (default by optical class)");
    conoscope->add_option("--tilt-deg", options->tilt_deg, "Starting (or fixed) tilt of the cut direction, degrees");
    conoscope->add_option("--azimuth-deg", options->azimuth_deg, "Starting (or fixed) azimuth of the tilt, degrees from E toward N");
    conoscope->add_option("--thickness", options->thickness, "Starting thickness with unit; searches thickness/3 … 3·thickness")->type_name(length_type);
    conoscope->add_option("--thickness-range", options->thickness_range, "The global search range, MIN:MAX with units (default 5um:5mm)");
    conoscope->add_option("--free", options->free, "Parameters to fit, comma-separated groups: thickness, center, scale, rotation, tilt,\n"
                                                   "white-balance, black, gamma, blur, distortion, analyzer, extinction, colour-matrix (the\n"
                                                   "camera's crosstalk between colours: free it for a camera's photo); envelope is freed by\n"
                                                   "--illumination falloff")->capture_default_str();
    conoscope->add_option("--projection", options->projection,
                          "How directions map to the photo: sine (microscope objective), tangent (camera or lens looking through\n"
                          "the crystal, figure on a screen), equidistant")->capture_default_str();
    conoscope->add_option("--field-stop", options->field_stop,
                          "sharp (the objective's aperture edge, at sin(theta_air) = NA) or none (the frame and the light's falloff\n"
                          "bound the field)")->capture_default_str();
    conoscope->add_option("--illumination", options->illumination,
                          "even, or falloff: the light falls off as exp(-(r/R)^p) about its own centre (fitted)")->capture_default_str();
    conoscope->add_option("--fix", options->fixed, "NAME=VALUE: hold a parameter (names as in report.json, e.g. field_radius_px=250)");
    conoscope->add_option("--na", options->na, "Numerical aperture of the objective")->capture_default_str();
    conoscope->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction in the lab")->capture_default_str();
    conoscope->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction in the lab")->capture_default_str();
    conoscope->add_option("--surround-n", options->surround_n, "Index of the medium around the slab")->capture_default_str();
    conoscope->add_option("--handedness", options->handedness, "right | left: the form of an optically active mineral (quartz, paratellurite)")
        ->capture_default_str();
    conoscope->add_option("--candidates", options->candidates, "Thickness minima refined by Ceres")->capture_default_str()->check(CLI::Range(1, 20));
    conoscope->add_flag("--verbose", options->verbose, "Print the solver's own messages (Ceres, glog) on standard error");
    conoscope->add_flag("--no-encoding-check", options->no_encoding_check,
                        "For a JPEG photo: skip repeating its encoding on the best fit (faster; the 1-sigma values then leave out\n"
                        "the encoding's systematic error)");
    conoscope->add_option("--sensor", options->sensor,
                          "The camera's sensor: bayer (a colour mosaic, demosaiced: nearly every colour camera; the fit measures what\n"
                          "the demosaicing does to its result and adds it to the 1-sigma values), full-colour (every colour at every\n"
                          "pixel: a rendered photo, a monochrome camera), or auto: bayer for a colour JPEG photo, full-colour otherwise")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "bayer", "full-colour"}));
    add_light_options(conoscope, options->light);
    add_fit_output_options(conoscope, options->output_dir, options->json);
    conoscope->callback([options, &minerals_dir] { run_fit_conoscope(*options, minerals_dir); });
    add_fit_orthoscope_command(fit, minerals_dir);
}

}  // namespace petroscope::cli
