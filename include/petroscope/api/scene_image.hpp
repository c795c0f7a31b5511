#pragma once
// A scene (render/scene.hpp; from a file by io/scene_file.hpp) rendered to an image as every front end asks
// for it (the CLI's `render`, Python's render_scene): samples, depth, seed, the camera's polarizer and the
// exposure; the image in display colours with the renderer's own estimate of its noise (docs/render.md).
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/render/path_tracer.hpp"
#include "petroscope/render/scene.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace petroscope {

struct SceneRenderRequest {
    int samples_per_pixel = 64;           // 1 … max_samples_per_pixel(allow_large)
    int max_depth = 15;                   // crystal-face interactions along a path, 1 … 100000
    std::optional<double> polarizer_deg;  // a camera polarizer instead of the scene's (from the image's right toward up)
    bool no_polarizer = false;            // ignore the scene's camera polarizer
    std::uint64_t seed = 1;               // the image does not depend on the number of threads
    double exposure = 1.0;                // multiplies the image (1: a wall of white texels is white)
    bool allow_large = false;             // above 4096 × 4096 px or 65536 samples per pixel
};

/// Memory a pixel takes while rendering: 16 floats of Stokes XYZ and standard errors, the camera's XYZ and
/// the RGB image.
inline constexpr double kSceneBytesPerPixel = 88.0;
inline constexpr long long kSceneLargePixels = 4096LL * 4096LL;
inline constexpr int kSceneLargeSamples = 65536;
inline constexpr int kSceneMaxSamples = 1000000;
inline constexpr int kSceneMaxDepth = 100000;

/// The renderer's light: CIE D65 on its wavelength grid.
RenderSpectrum scene_render_spectrum();

/// Checks the request against the scene and puts its polarizer into the scene's camera; the settings to
/// render with. Throws InputError naming the value.
RenderSettings plan_scene_render(const SceneRenderRequest& request, Scene& scene);

struct SceneImage {
    Image linear_rgb;  // linear sRGB (Bradford-adapted D65 white = 1) through the camera's polarizer, times the exposure
    RenderResult result;
    /// The standard error of each pixel's luminance over its value, sorted, over the pixels with Y > 0.02
    /// that see a crystal (the others are exact up to the sampling of the pixel's area).
    std::vector<double> relative_errors;
};

/// Renders; throws Cancelled when `progress` says stop.
SceneImage render_scene_image(const Scene& scene, const RenderSpectrum& spectrum, const RenderSettings& settings, double exposure,
                              const ProgressCallback& progress = {});

}  // namespace petroscope
