// petroscope fit orthoscope: a grain's thickness (and optic orientation) fitted to its interference colours
// in one or several crossed-polar photos. The method: docs/fitting.md.
#include "cli_common.hpp"
#include "cli_light.hpp"
#include "fit_report.hpp"

#include "petroscope/api/grain_fit.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/fit/solver_messages.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/atomic_file.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/json_sidecar.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

namespace petroscope::cli {
namespace {

struct GrainFitOptions {
    std::vector<std::string> photos, stages, plates, regions, masks, reference_regions, reference_masks;
    std::string mineral, orientation, euler, thickness_range = "1um:200um", output_dir, handedness = "right";
    double plate_deg = 45.0, condenser_na = 0.0, polarizer_deg = 0.0, analyzer_deg = 90.0;
    bool exposure_free = false, json = false, verbose = false;
    int candidates = 4;
    LightOptions light;
};

/// The k-th of a per-photo option: one value for all photos, or one per photo.
const std::string& per_photo(const std::vector<std::string>& values, std::size_t k, const std::string& option, std::size_t photos) {
    if (values.size() != 1 && values.size() != photos) {
        throw InputError(option + ": give one value for all " + std::to_string(photos) + " photos or one per photo (got " +
                         std::to_string(values.size()) + ")");
    }
    return values[values.size() == 1 ? 0 : k];
}

/// "x,y,w,h" in pixels, read for `option`.
std::array<int, 4> parse_region(const std::string& option, const std::string& text) {
    const auto parts = split(text, ',');
    std::array<int, 4> region{};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto value = parts.size() == 4 ? parse_double(parts[i]) : std::nullopt;
        if (!value || *value != std::floor(*value) || std::abs(*value) > 1e6) {
            throw InputError(option + " " + quote_input(text) + ": expected X,Y,WIDTH,HEIGHT in whole pixels (top-left corner first), e.g. 120,80,40,40");
        }
        region[i] = static_cast<int>(*value);
    }
    return region;
}

/// Where a region is marked: by masks (`--mask`) or rectangles (`--region`), one for all photos or one per photo.
struct RegionOptions {
    const std::vector<std::string>& masks;
    const std::vector<std::string>& regions;
    std::string mask_option, region_option;
};

/// The mask of photo k's region: its mask image, its rectangle, or (neither given) the whole photo.
Image region_mask(const RegionOptions& where, std::size_t k, std::size_t photos, const std::string& file, const Image& photo) {
    if (!where.masks.empty()) {
        const std::string& mask_file = per_photo(where.masks, k, where.mask_option, photos);
        Image mask = with_option(where.mask_option, [&] { return read_image(mask_file); });
        if (mask.width != photo.width || mask.height != photo.height) {
            throw InputError(where.mask_option + " " + mask_file + ": " + std::to_string(mask.width) + "x" + std::to_string(mask.height) +
                             ", but the photo " + file + " is " + std::to_string(photo.width) + "x" + std::to_string(photo.height));
        }
        return mask;
    }
    if (!where.regions.empty()) {
        const std::array<int, 4> r = parse_region(where.region_option, per_photo(where.regions, k, where.region_option, photos));
        return with_option(where.region_option, [&] { return rectangle_mask(photo.width, photo.height, r[0], r[1], r[2], r[3]); });
    }
    Image whole(photo.width, photo.height, 1);
    std::fill(whole.pixels.begin(), whole.pixels.end(), 1.0f);
    return whole;
}

/// The grain's colour in photo k, from its region or mask.
GrainColour measure(const GrainFitOptions& options, std::size_t k, const Image& photo) {
    const std::string& file = options.photos[k];
    if (photo.width == 0 || photo.height == 0) throw InputError("--photo " + file + ": the image is empty");
    const Image mask = region_mask({options.masks, options.regions, "--mask", "--region"}, k, options.photos.size(), file, photo);
    return with_option("--photo " + file, [&] { return grain_colour(photo, mask); });
}

/// The reference region's colour in photo k, if the options give it there ("none" for a photo without).
std::optional<GrainColour> measure_reference(const GrainFitOptions& options, std::size_t k, const Image& photo) {
    const RegionOptions where{options.reference_masks, options.reference_regions, "--reference-mask", "--reference-region"};
    const std::vector<std::string>& given = where.masks.empty() ? where.regions : where.masks;
    if (given.empty() || per_photo(given, k, where.masks.empty() ? where.region_option : where.mask_option, options.photos.size()) == "none") {
        return std::nullopt;
    }
    const Image mask = region_mask(where, k, options.photos.size(), options.photos[k], photo);
    return with_option("--photo " + options.photos[k] + " (reference region)", [&] { return grain_colour(photo, mask); });
}

/// Photo k's reference region: its measured and calibrated model colours, or null where it is not given.
nlohmann::json reference_json(const GrainPhoto& photo, const OrthoscopeFitResult& result, std::size_t k) {
    if (!photo.reference || !result.calibration) return nullptr;
    const Eigen::Vector3d& measured = photo.reference->mean_code;
    const Eigen::Vector3d& model = *result.calibration->model_code[k];
    return {{"pixels", photo.reference->pixels},
            {"mean_code", {measured.x(), measured.y(), measured.z()}},
            {"model_code", {model.x(), model.y(), model.z()}}};
}

/// The camera's calibration, or null without a reference region.
nlohmann::json calibration_json(const OrthoscopeFitResult& result) {
    if (!result.calibration) return nullptr;
    const CameraCalibration& camera = *result.calibration;
    nlohmann::json fitted = nlohmann::json::array();
    for (std::size_t c = 0; c < 3; ++c) {
        if (camera.fitted_with_grain[c]) fitted.push_back(std::string(1, "RGB"[c]));
    }
    return {{"channel_gains", {camera.channel_gains.x(), camera.channel_gains.y(), camera.channel_gains.z()}},
            {"gains_fitted_with_the_grain", fitted},
            {"contrast", fitted_value_json(camera.contrast)},
            {"reference_rms_code", camera.rms_code},
            {"meaning", "code = C(encode_srgb(gain * linear display colour)), C(y) = y^a / (y^a + (1 - y)^a) with a the contrast; the gains "
                        "at the reference region's light (the grain's may differ: 'exposure'); see docs/fitting.md"}};
}

nlohmann::json report_json(const GrainFitOptions& options, const std::vector<GrainPhoto>& photos, const OrthoscopeFitOptions& fit,
                           const OrthoscopeFitResult& result, double seconds) {
    nlohmann::json photo_entries = nlohmann::json::array();
    for (std::size_t k = 0; k < photos.size(); ++k) {
        const GrainPhoto& photo = photos[k];
        photo_entries.push_back({{"file", options.photos[k]},
                                 {"stage_deg", photo.stage_deg},
                                 {"plate", plate_json(photo.plate)},
                                 {"pixels", photo.colour.pixels},
                                 {"pixels_saturated", photo.colour.saturated},
                                 {"mean_code", {photo.colour.mean_code.x(), photo.colour.mean_code.y(), photo.colour.mean_code.z()}},
                                 {"model_code", {result.model_code[k].x(), result.model_code[k].y(), result.model_code[k].z()}},
                                 {"reference", reference_json(photo, result, k)}});
    }
    nlohmann::json candidates = nlohmann::json::array();
    for (const GrainCandidate& candidate : result.candidates) {
        candidates.push_back({{"thickness_um", candidate.thickness_um}, {"angles_deg", candidate.angles_deg}, {"rms_code", candidate.rms_code}});
    }
    const Eigen::Vector3d euler = euler_zyz_deg_of(result.axes);
    return {{"program", "petroscope 0.1.0"},
            {"command", "fit orthoscope"},
            {"mineral", options.mineral},
            {"handedness", handedness_name(fit.handedness)},
            {"photos", photo_entries},
            {"orientation", grain_orientation_name(fit.orientation)},
            {"condenser_na", fit.microscope.condenser_na},
            {"polarizer_deg", fit.microscope.polars.polarizer_deg},
            {"analyzer_deg", fit.microscope.polars.analyzer_deg},
            {"thickness_search_um", {fit.thickness_min_um, fit.thickness_max_um}},
            {"acceptable", result.acceptable},
            {"verdict", result.verdict},
            {"thickness_um", fitted_value_json(result.thickness_um)},
            {"thickness_lower_bound_um", result.thickness_lower_bound_um ? nlohmann::json(*result.thickness_lower_bound_um) : nlohmann::json(nullptr)},
            {"retardation_550nm", fitted_value_json(result.retardation_nm)},
            {"birefringence_550nm", fitted_value_json(result.birefringence)},
            {"angles_deg", {fitted_value_json(result.angles_deg[0]), fitted_value_json(result.angles_deg[1]), fitted_value_json(result.angles_deg[2])}},
            {"angles_meaning", fit.orientation == GrainOrientation::max_birefringence ? "[0]: the indicatrix X axis at stage 0, degrees from E toward N"
                               : fit.orientation == GrainOrientation::free           ? "ZYZ Euler angles of the indicatrix at stage 0"
                                                                                     : "unused (orientation given)"},
            {"euler_zyz_deg", {euler.x(), euler.y(), euler.z()}},
            {"exposure", fitted_value_json(result.exposure)},
            {"camera_calibration", calibration_json(result)},
            {"candidates", candidates},
            {"rms_code", result.rms_code},
            {"warnings", result.warnings},
            {"seconds", seconds},
            {"model", "mean sRGB code of the grain = encode_srgb(exposure * display(XYZ of the orthoscope's single-pass transmission)), through "
                      "the calibrated camera when a reference region is given; see docs/fitting.md"},
            {"sigma_meaning", "1 sigma from the Gauss-Newton covariance, residual variance floored at one code level"}};
}

/// Swatches, 64 px each, a row per photo: the grain's measured colour and the model's; with a reference
/// region, then the reference's measured and calibrated model colours (black where a photo has none).
Image swatches(const std::vector<GrainPhoto>& photos, const OrthoscopeFitResult& result) {
    constexpr int side = 64;
    const int columns = result.calibration ? 4 : 2;
    Image image(columns * side, side * static_cast<int>(photos.size()), 3);
    for (std::size_t k = 0; k < photos.size(); ++k) {
        const Eigen::Vector3d black = Eigen::Vector3d::Zero();
        const std::array<Eigen::Vector3d, 4> codes{
            photos[k].colour.mean_code, result.model_code[k], photos[k].reference ? photos[k].reference->mean_code : black,
            result.calibration && result.calibration->model_code[k] ? *result.calibration->model_code[k] : black};
        for (int y = 0; y < side; ++y) {
            for (int x = 0; x < columns * side; ++x) {
                const Eigen::Vector3d& code = codes[static_cast<std::size_t>(x / side)];
                for (int c = 0; c < 3; ++c) image.at(x, static_cast<int>(k) * side + y, c) = static_cast<float>(decode_srgb(code[c]));
            }
        }
    }
    return image;
}

// The request of the options; the grain's colour in each photo is measured here.
GrainFitRequest grain_fit_request(const GrainFitOptions& options) {
    if (!options.masks.empty() && !options.regions.empty()) throw InputError("--mask and --region: give one or the other");
    if (!options.reference_masks.empty() && !options.reference_regions.empty()) {
        throw InputError("--reference-mask and --reference-region: give one or the other");
    }
    GrainFitRequest request;
    request.mineral = options.mineral;
    request.exposure_free = options.exposure_free;
    request.candidates = options.candidates;
    request.condenser_na = options.condenser_na;
    request.polarizer_deg = options.polarizer_deg;
    request.analyzer_deg = options.analyzer_deg;
    request.light = light_from_options(options.light);
    if (request.light.monochromatic()) throw InputError("--wavelength: fit orthoscope needs white light (it reads interference colours)");
    request.handedness = with_option("--handedness", [&] { return parse_handedness(options.handedness); });
    std::tie(request.thickness_min_um, request.thickness_max_um) = length_range_um("--thickness-range", options.thickness_range);
    if (!options.euler.empty()) {
        if (!options.orientation.empty() && options.orientation != "known") throw InputError("--euler-deg gives the orientation: it needs --orientation known (or none)");
        request.orientation = GrainOrientation::known;
        const std::array<double, 3> angles = euler_angles_deg("--euler-deg", options.euler);
        request.euler_zyz_deg = Eigen::Vector3d(angles[0], angles[1], angles[2]);
    } else if (!options.orientation.empty()) {
        request.orientation = with_option("--orientation", [&] { return parse_grain_orientation(options.orientation); });
        if (request.orientation == GrainOrientation::known) throw InputError("--orientation known: give the orientation with --euler-deg ALPHA,BETA,GAMMA");
    }
    for (std::size_t k = 0; k < options.photos.size(); ++k) {
        GrainFitPhoto photo;
        photo.label = options.photos[k];
        const Image image = with_option("--photo", [&] { return read_image(options.photos[k]); });
        photo.colour = measure(options, k, image);
        photo.reference = measure_reference(options, k, image);
        if (!options.stages.empty()) {
            const std::string& text = per_photo(options.stages, k, "--stage-deg", options.photos.size());
            const auto value = parse_double(text);
            if (!value || !std::isfinite(*value)) throw InputError("--stage-deg " + quote_input(text) + ": expected an angle in degrees");
            photo.stage_deg = *value;
        }
        if (!options.plates.empty()) {
            const std::string& name = per_photo(options.plates, k, "--plate", options.photos.size());
            if (name != "none") photo.plate = plate_request({name, options.plate_deg, 0.5});
        }
        request.photos.push_back(photo);
    }
    return request;
}

void run_fit_orthoscope(const GrainFitOptions& options, const std::string& minerals_dir) {
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    with_option("--mineral", [&]() -> const Mineral& { return catalog.find(options.mineral); });  // a message naming the option
    const GrainFitPlan plan = plan_grain_fit(grain_fit_request(options), catalog);
    const OrthoscopeFitOptions& fit = plan.options;
    const std::vector<GrainPhoto>& photos = plan.photos;

    const std::filesystem::path folder(options.output_dir);
    if (!std::filesystem::is_directory(folder)) throw InputError("-o " + options.output_dir + ": not a folder (create it first)");
    PendingOutputs pending;
    const auto report_path = pending.add(folder / "report.json"), swatch_png = pending.add(folder / "colours.png");

    const auto begin = std::chrono::steady_clock::now();
    show_solver_messages(options.verbose);
    const OrthoscopeFitResult result = fit_grain(plan, [](double fraction_done) {
        show_progress("fit orthoscope", fraction_done);
        return true;
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

    const nlohmann::json report = report_json(options, photos, fit, result, seconds);
    write_image(swatches(photos, result), swatch_png, ImageFormat::png);
    write_json_file(report, report_path);
    pending.commit();

    finish_fit(options.json, report, result.acceptable, result.verdict, [&] {
        std::cout << "  thickness_um = " << fitted_value_text(result.thickness_um) << '\n';
        if (result.thickness_lower_bound_um) std::cout << "  thickness_um >= " << format_significant(*result.thickness_lower_bound_um, 4) << '\n';
        std::cout << "  retardation_550nm = " << fitted_value_text(result.retardation_nm) << '\n';
        std::cout << "  birefringence_550nm = " << fitted_value_text(result.birefringence) << '\n';
        if (fit.orientation == GrainOrientation::max_birefringence) std::cout << "  x_axis_deg = " << fitted_value_text(result.angles_deg[0]) << '\n';
        if (fit.orientation == GrainOrientation::free) {
            for (int a = 0; a < 3; ++a) std::cout << "  euler_deg[" << a << "] = " << fitted_value_text(result.angles_deg[static_cast<std::size_t>(a)]) << '\n';
        }
        if (result.exposure.free) std::cout << "  exposure = " << fitted_value_text(result.exposure) << '\n';
        if (result.calibration) {
            const Eigen::Vector3d& gains = result.calibration->channel_gains;
            std::cout << "  camera: gains " << format_significant(gains.x(), 4) << ' ' << format_significant(gains.y(), 4) << ' '
                      << format_significant(gains.z(), 4) << ", contrast " << fitted_value_text(result.calibration->contrast) << ", reference "
                      << format_significant(255.0 * result.calibration->rms_code, 3) << " code levels rms\n";
        }
        for (const std::string& warning : result.warnings) std::cout << "warning: " << warning << '\n';
        std::cout << "wrote " << (folder / "report.json").string() << " and colours.png (" << format_significant(seconds, 3) << " s)\n";
    });
}

}  // namespace

void add_fit_orthoscope_command(CLI::App* fit, const std::string& minerals_dir) {
    auto options = std::make_shared<GrainFitOptions>();
    CLI::App* command = fit->add_subcommand(
        "orthoscope",
        "Fit a grain's thickness (and optic orientation) to its colours in crossed-polar photos taken at known stage\n"
        "angles, with or without an accessory plate (PNG, JPEG or TIFF, sRGB). Writes report.json and colours.png\n"
        "(measured | model, a row per photo) into the -o folder. A reference region without birefringence calibrates\n"
        "the camera's colours.");
    command->add_option("--photo", options->photos, "A photograph (repeat for several)")->required();
    command->add_option("--mineral", options->mineral, "Mineral name or alias")->required();
    command->add_option("--stage-deg", options->stages, "Stage angle of each photo (one for all, or one per photo; default 0)")->delimiter(',');
    command->add_option("--plate", options->plates, "none | gypsum | mica for each photo (one for all, or one per photo)")->delimiter(',');
    command->add_option("--plate-deg", options->plate_deg, "Slow direction of the plate, degrees from E toward N")->capture_default_str();
    command->add_option("--region", options->regions, "X,Y,WIDTH,HEIGHT of the grain in pixels (one for all photos, or one per photo)");
    command->add_option("--mask", options->masks, "Image whose non-zero pixels mark the grain (one for all photos, or one per photo)");
    command->add_option("--reference-region", options->reference_regions,
                        "X,Y,WIDTH,HEIGHT of a region without birefringence (a hole, an isotropic grain, a grain at extinction) that\n"
                        "calibrates the camera: one for all photos, or one per photo (none where it is not so)");
    command->add_option("--reference-mask", options->reference_masks, "Image marking the reference region instead (one for all, or one per photo; none)");
    command->add_option("--orientation", options->orientation, "known | max-birefringence (default) | free");
    command->add_option("--euler-deg", options->euler, "The grain's orientation, ZYZ Euler angles ALPHA,BETA,GAMMA (implies known)");
    command->add_option("--thickness-range", options->thickness_range, "The global search range, MIN:MAX with units")->capture_default_str();
    command->add_flag("--exposure-free", options->exposure_free, "Fit the exposure too (one factor for all photos)");
    command->add_flag("--verbose", options->verbose, "Print the solver's own messages (Ceres, glog) on standard error");
    command->add_option("--condenser-na", options->condenser_na, "Condenser cone (Koehler), 0 = parallel light")->capture_default_str();
    command->add_option("--polarizer-deg", options->polarizer_deg, "Polarizer direction in the lab")->capture_default_str();
    command->add_option("--analyzer-deg", options->analyzer_deg, "Analyzer direction in the lab")->capture_default_str();
    command->add_option("--candidates", options->candidates, "Grid minima refined by Ceres")->capture_default_str()->check(CLI::Range(1, 20));
    command->add_option("--handedness", options->handedness, "right | left: the form of an optically active mineral (quartz, paratellurite)")->capture_default_str();
    add_light_options(command, options->light);
    add_fit_output_options(command, options->output_dir, options->json);
    command->callback([options, &minerals_dir] { run_fit_orthoscope(*options, minerals_dir); });
}

}  // namespace petroscope::cli
