// petroscope render: a scene (a box of emitting walls, calcite or other crystals, a pinhole camera) by
// backward spectral polarized ray tracing; the paper's 3D verification scene is scenes/calcite-box.json.
#include "cli_common.hpp"
#include "frame_command.hpp"

#include "petroscope/api/scene_image.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/scene_file.hpp"
#include "petroscope/spectral/color.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

namespace petroscope::cli {
namespace {

class RenderOptions final : public FrameOptions {
public:
    std::string command() const override { return "render"; }
    std::string description() const override {
        return "Render a scene file by backward spectral polarized ray tracing: walls that glow with RGB textures turned\n"
               "into smooth spectra, crystals traced with the exact interface model at every face (both refracted modes,\n"
               "reflection, total internal reflection), Stokes vectors and Mueller matrices, a pinhole camera with an\n"
               "optional polarizer. Format and method: docs/render.md. The paper's scene: scenes/calcite-box.json.";
    }
    void add_options(CLI::App* command) override;
    PreparedFrame prepare(FrameContext& context) const override;

private:
    std::string scene_;
    int spp_ = 64;
    int depth_ = 15;
    std::optional<double> polarizer_deg_;
    bool no_polarizer_ = false;
    long long seed_ = 1;
    double exposure_ = 1.0;
    bool allow_large_ = false;
};

void RenderOptions::add_options(CLI::App* command) {
    command->add_option("--scene", scene_, "Scene file (JSON, docs/render.md)")->required();
    command->add_option("--spp", spp_, "Samples (paths) per pixel, 1 to 1000000")->capture_default_str();
    command->add_option("--depth", depth_, "Trace depth: the most crystal-face interactions along a path, 1 to 100000")->capture_default_str();
    command->add_option("--polarizer-deg", polarizer_deg_,
                        "A linear polarizer in front of the camera, its transmission axis in degrees from the image's right toward up "
                        "(overrides the scene's camera.polarizer_deg)");
    command->add_flag("--no-polarizer", no_polarizer_, "Ignore the scene's camera polarizer");
    command->add_option("--seed", seed_, "Random seed (the image does not depend on the number of threads)")->capture_default_str();
    command->add_option("--exposure", exposure_, "Multiplies the image (1: a wall of white texels is white)")->capture_default_str();
    command->add_flag("--allow-large", allow_large_,
                      "Allow images above 4096x4096 px (88 bytes per pixel: 1.5 GB at 4096x4096, 24 GB at the scene limit 16384x16384) and "
                      "more than 65536 samples per pixel");
}

/// FNV-1a 64 (Fowler, Noll & Vo) of the scene file's bytes: identifies the scene in the sidecar.
std::string scene_hash(const std::string& text) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (const unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ULL;
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(hash));
    return buffer;
}

PreparedFrame RenderOptions::prepare(FrameContext& context) const {
    // The library checks these too; here the messages name the options.
    if (spp_ < 1 || spp_ > kSceneMaxSamples) throw InputError("--spp " + std::to_string(spp_) + " is out of range (1 to 1000000)");
    if (depth_ < 1 || depth_ > kSceneMaxDepth) throw InputError("--depth " + std::to_string(depth_) + " is out of range (1 to 100000)");
    if (polarizer_deg_ && !std::isfinite(*polarizer_deg_)) throw InputError("--polarizer-deg must be a finite angle");
    if (polarizer_deg_ && no_polarizer_) throw InputError("--polarizer-deg and --no-polarizer exclude each other");
    if (!(exposure_ > 0.0) || !std::isfinite(exposure_)) throw InputError("--exposure must be > 0");
    const auto spectrum = std::make_shared<RenderSpectrum>(scene_render_spectrum());
    const std::string scene_text = read_text_file(scene_);  // read once: parsed and hashed alike
    const auto scene = std::make_shared<Scene>(parse_scene(scene_text, scene_, context.catalog(), *spectrum));
    const long long pixels = static_cast<long long>(scene->camera.width_px) * scene->camera.height_px;
    if (!allow_large_ && pixels > kSceneLargePixels) {
        throw InputError(scene_ + ": camera: " + std::to_string(scene->camera.width_px) + " x " + std::to_string(scene->camera.height_px) +
                         " px is above 4096 x 4096 (it needs " + format_number(std::round(static_cast<double>(pixels) * kSceneBytesPerPixel / 1e8) / 10.0) +
                         " GB); add --allow-large to render it anyway");
    }
    if (!allow_large_ && spp_ > kSceneLargeSamples) {
        throw InputError("--spp " + std::to_string(spp_) + " is above 65536; add --allow-large to render it anyway");
    }
    const RenderSettings settings = plan_scene_render({.samples_per_pixel = spp_, .max_depth = depth_, .polarizer_deg = polarizer_deg_,
                                                       .no_polarizer = no_polarizer_, .seed = static_cast<std::uint64_t>(seed_),
                                                       .exposure = exposure_, .allow_large = allow_large_},
                                                      *scene);
    const double exposure = exposure_;
    const SceneCamera& camera = scene->camera;
    nlohmann::json sidecar{{"program", "petroscope 0.1.0"},
                           {"command", "render"},
                           {"scene", {{"file", scene_}, {"fnv1a64", scene_hash(scene_text)}}},
                           {"samples_per_pixel", spp_},
                           {"max_depth", depth_},
                           {"split_depth", settings.split_depth},
                           {"roulette_depth", settings.roulette_depth},
                           {"roulette_power", settings.roulette_power},
                           {"stratified", settings.stratified},
                           {"seed", seed_},
                           {"exposure", exposure},
                           {"width_px", camera.width_px},
                           {"height_px", camera.height_px},
                           {"polarizer_deg", camera.has_polarizer ? nlohmann::json(camera.polarizer_deg) : nlohmann::json(nullptr)},
                           {"light", "D65 (CIE), wavelengths 380-780 nm by 1 nm, one per path, stratified per pixel"},
                           {"crystals", nlohmann::json::array()},
                           {"pixel_values", "linear sRGB (Bradford-adapted D65 white = 1) of the light through the camera polarizer, if any"}};
    for (const SceneCrystal& crystal : scene->crystals) {
        const Eigen::Vector3d z = crystal.axes.col(2);
        sidecar["crystals"].push_back({{"mineral", crystal.mineral}, {"faces", crystal.shape.faces.size()},
                                       {"indicatrix_z", {z.x(), z.y(), z.z()}},
                                       {"principal_n_589nm", {crystal.principal_n(589.3).x(), crystal.principal_n(589.3).y(), crystal.principal_n(589.3).z()}}});
    }
    PreparedFrame prepared;
    prepared.render = [scene, spectrum, settings, sidecar, exposure](const ProgressCallback& progress) {
        const SceneImage image = render_scene_image(*scene, *spectrum, settings, exposure, progress);
        const std::vector<double>& relative_errors = image.relative_errors;
        const Image& rgb = image.linear_rgb;
        const RenderStatistics& s = image.result.statistics;
        RenderedFrame frame{rgb, sidecar, std::to_string(rgb.width) + "x" + std::to_string(rgb.height) + ", " + std::to_string(settings.samples_per_pixel) + " spp"};
        frame.sidecar["statistics"] = {{"paths", s.paths},
                                       {"paths_per_second", static_cast<double>(s.paths) / std::max(s.seconds, 1e-9)},
                                       {"crystal_interactions", s.crystal_interactions},
                                       {"depth_limited", s.depth_limited},
                                       {"roulette_killed", s.roulette_killed},
                                       {"walked_off", s.walked_off},
                                       {"inconsistent", s.inconsistent},
                                       {"render_seconds", s.seconds}};
        const auto quantile = [&](double q) {
            return relative_errors.empty() ? nlohmann::json(nullptr)
                                           : nlohmann::json(relative_errors[static_cast<std::size_t>(q * static_cast<double>(relative_errors.size() - 1))]);
        };
        frame.sidecar["estimated_noise"] = {{"what", "standard error of each pixel's luminance Y (unpolarized S0) over its value, over the pixels with "
                                                     "Y > 0.02 that see a crystal (the others are exact up to pixel-area sampling)"},
                                            {"pixels", relative_errors.size()},
                                            {"median", quantile(0.5)},
                                            {"p90", quantile(0.9)}};
        return frame;
    };
    return prepared;
}

}  // namespace

std::unique_ptr<FrameOptions> make_render_options() { return std::make_unique<RenderOptions>(); }

}  // namespace petroscope::cli
