// petroscope conical: the screen behind a biaxial slab cut perpendicular to an optic axis (internal conical
// refraction), in wave optics (Belsky–Khapalyuk–Berry) or ray optics (the exact interface model).
#include "cli_common.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/conical_wave.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>

namespace petroscope::cli {
namespace {

struct ConicalOptions {
    std::string crystal = "KGd(WO4)2";
    std::string length = "20mm";
    std::string wavelength = "633nm";
    std::string mode = "wave";
    std::string beam = "gaussian";
    std::string waist = "40um";
    std::string pinhole = "25um";
    std::string filter = "50mm";
    std::string polarization = "unpolarized";
    double z = 0.0;
    double rotate_deg = 0.0;
    double tilt_deg = 0.0;
    std::string screen_distance = "50mm";
    long long rays = 200000;
    int size_px = 1024;
    std::string output;
};

// "unpolarized", "circular" (right), "circular:left", "linear:ANGLE" (degrees from +x): a Stokes vector with
// (x, y) in the roles of (s, p) (optics/polarization.hpp).
Eigen::Vector4d parse_polarization(const std::string& text) {
    if (text == "unpolarized") return {1, 0, 0, 0};
    if (text == "circular" || text == "circular:right") return {1, 0, 0, 1};
    if (text == "circular:left") return {1, 0, 0, -1};
    if (text.starts_with("linear:")) {
        if (const auto angle = parse_double(text.substr(7))) {
            const double phi = 2.0 * *angle * std::numbers::pi / 180.0;
            return {1, std::cos(phi), std::sin(phi), 0};
        }
    }
    throw InputError("--polarization '" + text + "': expected unpolarized, linear:ANGLE (degrees from +x), circular or circular:left");
}

double positive_length_um(const std::string& option, const std::string& text) {
    const double value = with_option(option, [&] { return parse_length_um(text); });
    if (!(value > 0.0)) throw InputError(option + " '" + text + "': must be > 0");
    return value;
}

Image normalised_gray(const Image& image) {
    float peak = 0.0f;
    for (const float value : image.pixels) peak = std::max(peak, value);
    Image rgb(image.width, image.height, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = peak > 0.0f ? image.pixels[i] / peak : 0.0f;
    }
    return rgb;
}

void run_conical(const ConicalOptions& options, const std::string& minerals_dir, const std::string& command_line) {
    const auto started = std::chrono::steady_clock::now();
    const double length_um = positive_length_um("--length", options.length);
    const double wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(options.wavelength); });
    if (!(wavelength_nm > 0.0)) throw InputError("--wavelength must be > 0");
    if (options.size_px < 64 || options.size_px > 4096) throw InputError("--size " + std::to_string(options.size_px) + " is out of range (64 to 4096)");
    if (options.mode != "wave" && options.mode != "ray") throw InputError("--mode '" + options.mode + "': expected wave or ray");
    if (options.beam != "gaussian" && options.beam != "pinhole") throw InputError("--beam '" + options.beam + "': expected gaussian or pinhole");
    if (!std::isfinite(options.z)) throw InputError("--z must be a finite number");
    const Eigen::Vector4d stokes = parse_polarization(options.polarization);
    ImageResult result(options.output);

    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    const Mineral& mineral = catalog.find(options.crystal);
    if (mineral.optical_class != OpticalClass::biaxial) {
        throw InputError(mineral.name + " is " + std::string(optical_class_name(mineral.optical_class)) +
                         ": conical refraction needs a biaxial crystal (e.g. KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite)");
    }
    for (const auto& warning : mineral.range_warnings({wavelength_nm})) std::cerr << "petroscope: warning: " << warning << '\n';
    const Eigen::Vector3d n = mineral.principal_n(wavelength_nm);
    const double chi = conical_cone_angle_rad(n);
    const double a = 0.5 * std::tan(chi);
    const double ring_radius_um = a * length_um;
    nlohmann::json sidecar{{"program", "petroscope 0.1.0"}, {"command", "conical"}, {"command_line", command_line},
                           {"crystal", {{"name", mineral.name}, {"file", mineral.file}, {"principal_n_xyz", {n[0], n[1], n[2]}}}},
                           {"wavelength_nm", wavelength_nm}, {"length_um", length_um}, {"mode", options.mode},
                           {"polarization", options.polarization}, {"cone_angle_chi_deg", chi * 180.0 / std::numbers::pi},
                           {"A_rad", a}, {"R0_um", ring_radius_um}, {"size_px", options.size_px}};
    Image screen;
    if (options.mode == "wave") {
        const bool gaussian = options.beam == "gaussian";
        const double scale_um = gaussian ? positive_length_um("--waist", options.waist) : positive_length_um("--pinhole", options.pinhole);
        ConicalWaveParameters parameters;
        parameters.beam = gaussian ? ConicalBeam::gaussian : ConicalBeam::pinhole;
        parameters.rho0 = ring_radius_um / scale_um;
        parameters.z = options.z;
        const double half_width = parameters.rho0 + 4.0 + 1.5 * std::abs(options.z);
        const ConicalProfile profile = conical_profile(parameters, half_width * std::numbers::sqrt2, 4 * options.size_px);
        screen = conical_screen(profile, stokes, options.size_px, half_width);
        const ConicalRings rings = conical_rings(profile, parameters.rho0);
        sidecar["beam"] = options.beam;
        sidecar["scale_um"] = scale_um;
        sidecar["rho0"] = parameters.rho0;
        sidecar["Z"] = options.z;
        sidecar["image_half_width_um"] = half_width * scale_um;
        sidecar["rings"] = {{"units", "um from the ring centre (rho in units of the beam scale: divide by scale_um)"},
                            {"outer_bright", rings.outer_bright * scale_um}, {"dark", rings.dark * scale_um},
                            {"inner_bright", rings.inner_bright * scale_um}};
        sidecar["power"] = conical_power(profile);
        sidecar["pixel_values"] = "intensity |D|^2 of the paraxial theory (physics notes §7), normalised so that the brightest pixel is 1";
    } else {
        ConicalRaySettings settings;
        settings.principal_n = n;
        settings.slab_um = length_um;
        settings.rotate_deg = options.rotate_deg;
        settings.tilt_deg = options.tilt_deg;
        settings.pinhole_radius_um = positive_length_um("--pinhole", options.pinhole);
        settings.filter_um = positive_length_um("--filter", options.filter);
        settings.screen_distance_um = positive_length_um("--screen-distance", options.screen_distance);
        settings.stokes = stokes;
        if (options.rays < 1 || options.rays > 100000000) throw InputError("--rays must be between 1 and 1e8");
        settings.rays = options.rays;
        settings.size_px = options.size_px;
        const ConicalRayResult traced = trace_conical_rays(settings, [](double fraction) { show_progress("tracing", fraction); });
        screen = traced.screen;
        sidecar["pinhole_um"] = settings.pinhole_radius_um;
        sidecar["filter_um"] = settings.filter_um;
        sidecar["screen_distance_um"] = settings.screen_distance_um;
        sidecar["rotate_deg"] = settings.rotate_deg;
        sidecar["tilt_deg"] = settings.tilt_deg;
        sidecar["rays"] = settings.rays;
        sidecar["image_half_width_um"] = 2.0 * ring_radius_um;
        sidecar["image_centre_um"] = {traced.ring_centre_um.x(), traced.ring_centre_um.y()};
        sidecar["pinhole_point_um"] = {traced.pinhole_point_um.x(), traced.pinhole_point_um.y()};
        sidecar["rings"] = {{"units", "um from the measured ring centre"},
                            {"centre_um", {traced.rings.centre_um.x(), traced.rings.centre_um.y()}},
                            {"outer_bright", traced.rings.outer_bright_um}, {"dark", traced.rings.dark_um},
                            {"inner_bright", traced.rings.inner_bright_um}};
        sidecar["max_interface_power_sum"] = traced.max_interface_power_sum;
        sidecar["pixel_values"] = "collected ray power per pixel, normalised so that the brightest pixel is 1";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    sidecar["seconds"] = seconds;
    sidecar["image_frame"] = "x to the right, y up; centred on the (predicted) ring centre, which lies R0 from the point below the pinhole toward the second binormal";
    result.write(normalised_gray(screen), sidecar);
    std::cerr << "petroscope: wrote " << options.output << " and " << options.output << ".json (" << options.mode << " optics, R0 = "
              << ring_radius_um << " um, " << seconds << " s)\n";
}

}  // namespace

void add_conical_command(CLI::App& app, const std::string& minerals_dir, const std::string& command_line) {
    auto options = std::make_shared<ConicalOptions>();
    CLI::App* command = app.add_subcommand(
        "conical",
        "The screen behind a biaxial slab cut perpendicular to an optic axis: the double ring of internal conical\n"
        "refraction, in wave optics (paraxial Belsky-Khapalyuk-Berry theory, Gaussian beam or pinhole) or in ray\n"
        "optics (rays through a pinhole in a collimating filter, traced with the exact interface model).");
    command->add_option("--crystal", options->crystal, "Biaxial mineral (KGd(WO4)2, KY(WO4)2, KTP, LBO, aragonite, …)")->capture_default_str();
    command->add_option("--length", options->length, "Slab thickness l along the optic axis")->capture_default_str();
    command->add_option("--wavelength", options->wavelength, "Wavelength")->capture_default_str();
    command->add_option("--mode", options->mode, "wave or ray")->capture_default_str();
    command->add_option("--beam", options->beam, "Wave mode: gaussian (waist --waist) or pinhole (radius --pinhole)")->capture_default_str();
    command->add_option("--waist", options->waist, "Gaussian beam scale w, E(r) = exp(-r^2/2w^2)")->capture_default_str();
    command->add_option("--pinhole", options->pinhole, "Pinhole radius R")->capture_default_str();
    command->add_option("--filter", options->filter, "Ray mode: thickness h of the filter holding the pinhole (rays tilt by at most ~2R/h)")->capture_default_str();
    command->add_option("--polarization", options->polarization, "unpolarized, linear:ANGLE (degrees from +x), circular[:left]")->capture_default_str();
    command->add_option("--z", options->z, "Wave mode: observation plane Z (dimensionless, physics notes §7; 0 = focal image plane)")->capture_default_str();
    command->add_option("--rotate-deg", options->rotate_deg, "Ray mode: turn the slab about its optic axis")->capture_default_str();
    command->add_option("--tilt-deg", options->tilt_deg, "Ray mode: tilt the optic axis away from the slab normal")->capture_default_str();
    command->add_option("--screen-distance", options->screen_distance, "Ray mode: screen distance D behind the slab")->capture_default_str();
    command->add_option("--rays", options->rays, "Ray mode: number of rays")->capture_default_str();
    command->add_option("--size", options->size_px, "Image size in pixels (64 to 4096)")->capture_default_str();
    command->add_option("-o,--output", options->output, "Output image (.png, .exr, .tif) and its JSON sidecar")->required();
    command->callback([options, &minerals_dir, command_line] { run_conical(*options, minerals_dir, command_line); });
}

}  // namespace petroscope::cli
