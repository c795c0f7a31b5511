#include "petroscope/api/scene_image.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace petroscope {

RenderSpectrum scene_render_spectrum() {
    return render_spectrum(load_cie_1931_observer(), load_light_source("D65"));
}

RenderSettings plan_scene_render(const SceneRenderRequest& request, Scene& scene) {
    const int max_samples = request.allow_large ? kSceneMaxSamples : kSceneLargeSamples;
    if (request.samples_per_pixel < 1 || request.samples_per_pixel > max_samples) {
        throw InputError("samples per pixel: " + std::to_string(request.samples_per_pixel) + " is out of range (1 to " + std::to_string(max_samples) +
                         (request.allow_large ? ")" : "; more only when large renders are allowed)"));
    }
    if (request.max_depth < 1 || request.max_depth > kSceneMaxDepth) {
        throw InputError("depth: " + std::to_string(request.max_depth) + " is out of range (1 to " + std::to_string(kSceneMaxDepth) + ")");
    }
    if (request.polarizer_deg && !std::isfinite(*request.polarizer_deg)) throw InputError("the camera polarizer's angle must be a finite number");
    if (request.polarizer_deg && request.no_polarizer) throw InputError("a camera polarizer angle and no polarizer exclude each other");
    if (!(request.exposure > 0.0) || !std::isfinite(request.exposure)) throw InputError("the exposure must be a finite number > 0");
    const long long pixels = static_cast<long long>(scene.camera.width_px) * scene.camera.height_px;
    if (!request.allow_large && pixels > kSceneLargePixels) {
        throw InputError("camera: " + std::to_string(scene.camera.width_px) + " x " + std::to_string(scene.camera.height_px) +
                         " px is above 4096 x 4096 (it needs " + format_number(std::round(static_cast<double>(pixels) * kSceneBytesPerPixel / 1e8) / 10.0) +
                         " GB); allow large renders to render it anyway");
    }
    if (request.polarizer_deg) {
        scene.camera.has_polarizer = true;
        scene.camera.polarizer_deg = *request.polarizer_deg;
    }
    if (request.no_polarizer) scene.camera.has_polarizer = false;
    RenderSettings settings;
    settings.samples_per_pixel = request.samples_per_pixel;
    settings.max_depth = request.max_depth;
    settings.seed = request.seed;
    return settings;
}

SceneImage render_scene_image(const Scene& scene, const RenderSpectrum& spectrum, const RenderSettings& settings, double exposure,
                              const ProgressCallback& progress) {
    SceneImage image{{}, render_scene(scene, spectrum, settings, progress), {}};
    const Image xyz = image.result.camera_xyz(scene.camera.has_polarizer, scene.camera.polarizer_deg);
    image.linear_rgb = Image(xyz.width, xyz.height, 3);
    for (int y = 0; y < xyz.height; ++y) {
        for (int x = 0; x < xyz.width; ++x) {
            const Eigen::Vector3d value = exposure * spectrum.xyz_to_linear_srgb * Eigen::Vector3d(xyz.at(x, y, 0), xyz.at(x, y, 1), xyz.at(x, y, 2));
            for (int c = 0; c < 3; ++c) image.linear_rgb.at(x, y, c) = static_cast<float>(value[c]);
            // Pixels that see a crystal: the others are exact (no wavelength depends on them).
            const double luminance = image.result.stokes_xyz.at(x, y, 1), error = image.result.standard_error_y.at(x, y, 0);
            if (luminance > 0.02 && error > 1e-6 * luminance) image.relative_errors.push_back(error / luminance);
        }
    }
    std::sort(image.relative_errors.begin(), image.relative_errors.end());
    return image;
}

}  // namespace petroscope
