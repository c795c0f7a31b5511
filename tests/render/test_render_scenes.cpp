// The paper's birefringence check (§4.3): a texture seen through calcite appears twice, the copies offset
// by the e-ray's walk-off, each copy polarized so that a polarizer removes one or the other; outside the
// crystal the texture's colours come back exactly; noise falls as 1/√spp.
#include "render_scenes.hpp"

#include "petroscope/io/scene_file.hpp"
#include "petroscope/spectral/color.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numeric>
#include <numbers>
#include <vector>

namespace petroscope {
namespace {

constexpr double kSlabMm = 10.0, kAxisTiltDeg = 45.0, kPixelMm = 0.2;
constexpr int kSize = 64;

/// A calcite slab 24 × 24 × 10 mm on the bottom wall, its optic axis at 45° from the normal in the x–z
/// plane; the bottom wall black with one white square of 1 mm; the camera 2 m above looking straight down
/// (nearly orthographic), kPixelMm per pixel at the wall.
Scene slab_scene(const SigmoidSpectrum& behind) {
    Scene scene = testing::box_scene(kSize);
    scene.box.lower_mm = {-20, -20, 0};
    scene.box.upper_mm = {20, 20, 30};
    scene.camera.position_mm = {0, 0, 2000};
    scene.camera.sensor_distance_mm = 2000.0;
    scene.camera.sensor_width_mm = scene.camera.sensor_height_mm = kSize * kPixelMm;
    WallEmission& bottom = scene.box.walls[static_cast<std::size_t>(Wall::bottom)];
    bottom.kind = WallEmission::Kind::texture;
    bottom.texture_width = bottom.texture_height = 40;  // 1 mm texels over the 40 mm wall
    bottom.palette = {SigmoidSpectrum::constant(0.0), behind};
    bottom.texel_palette_index.assign(40 * 40, 0);
    bottom.texel_palette_index[20 * 40 + 20] = 1;  // the texel from x = 0 … 1 mm, y = −1 … 0 mm
    std::vector<Eigen::Vector3d> vertices;
    for (int k = 0; k < 8; ++k) vertices.emplace_back(k & 1 ? 12.0 : -12.0, k & 2 ? 12.0 : -12.0, (k & 4 ? kSlabMm : 0.0) + 1e-6);
    ConvexPolyhedron slab = make_convex_polyhedron(vertices, {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}});
    const double tilt = kAxisTiltDeg * std::numbers::pi / 180.0;
    const Eigen::Vector3d z(std::sin(tilt), 0.0, std::cos(tilt));
    Eigen::Matrix3d axes;
    axes << Eigen::Vector3d::UnitY().cross(z), Eigen::Vector3d::UnitY(), z;
    scene.crystals.push_back(testing::calcite_crystal(std::move(slab), axes));
    return scene;
}

/// The luminance-weighted centroid (px) and total of a Y image.
struct Spot {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    double total = 0.0;
};
Spot spot(const Image& xyz, int x0, int x1) {
    Spot s;
    for (int y = 0; y < xyz.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            const double value = xyz.at(x, y, 1);
            s.centroid += value * Eigen::Vector2d(x + 0.5, y + 0.5);
            s.total += value;
        }
    }
    if (s.total > 0.0) s.centroid /= s.total;
    return s;
}

TEST(RenderScenes, CalciteDoublesTheTextureByTheWalkOffAndAPolarizerSeparatesTheCopies) {
    const Scene scene = slab_scene(SigmoidSpectrum::constant(1.0));
    RenderSettings settings;
    settings.samples_per_pixel = 16;
    const RenderResult result = render_scene(scene, testing::d65_spectrum(), settings);
    EXPECT_EQ(result.statistics.inconsistent, 0u);
    // Walk-off of the e-ray for a wave normal at θ from the optic axis (Born & Wolf §15.3.3, with
    // n_o, n_e at 560 nm, near the peak of the luminance weights):
    // tan δ = (n_o² − n_e²) sin θ cos θ / (n_o² cos²θ + n_e² sin²θ).
    const Eigen::Vector3d n = testing::render_minerals().find("calcite").principal_n(560.0);
    const double n_o = n.x(), n_e = n.z(), theta = kAxisTiltDeg * std::numbers::pi / 180.0;
    const double tan_walk_off = (n_o * n_o - n_e * n_e) * std::sin(theta) * std::cos(theta) /
                                (n_o * n_o * std::cos(theta) * std::cos(theta) + n_e * n_e * std::sin(theta) * std::sin(theta));
    const double expected_offset_px = kSlabMm * tan_walk_off / kPixelMm;
    std::printf("walk-off %.3f deg, expected offset %.2f px\n", std::atan(tan_walk_off) * 180.0 / std::numbers::pi, expected_offset_px);

    // The o-ray vibrates normal to the principal plane (x–z): along y, the image's vertical.
    const Image ordinary = result.camera_xyz(true, 90.0), extraordinary = result.camera_xyz(true, 0.0), both = result.camera_xyz(false, 0.0);
    const Spot o = spot(ordinary, 0, kSize), e = spot(extraordinary, 0, kSize);
    const Eigen::Vector2d offset = e.centroid - o.centroid;
    std::printf("o copy at (%.2f, %.2f), e copy at (%.2f, %.2f): offset %.2f px along x, %.2f along y\n", o.centroid.x(), o.centroid.y(),
                e.centroid.x(), e.centroid.y(), offset.x(), offset.y());
    EXPECT_NEAR(std::abs(offset.x()), expected_offset_px, 1.0);
    EXPECT_NEAR(offset.y(), 0.0, 1.0);
    // Unpolarized, the two copies; through each polarizer setting the other copy vanishes.
    const int split = static_cast<int>(std::lround(0.5 * (o.centroid.x() + e.centroid.x())));
    const bool e_right = e.centroid.x() > o.centroid.x();
    const auto copy = [&](const Image& image, bool right) { return right ? spot(image, split, kSize).total : spot(image, 0, split).total; };
    const double o_unpolarized = copy(both, !e_right), e_unpolarized = copy(both, e_right);
    std::printf("copies unpolarized: o %.4g, e %.4g; e through the o polarizer %.3g%%, o through the e polarizer %.3g%%\n", o_unpolarized,
                e_unpolarized, 100.0 * copy(ordinary, e_right) / e_unpolarized, 100.0 * copy(extraordinary, !e_right) / o_unpolarized);
    EXPECT_GT(o_unpolarized, 0.3 * e_unpolarized);
    EXPECT_GT(e_unpolarized, 0.3 * o_unpolarized);
    EXPECT_LT(copy(ordinary, e_right), 0.02 * e_unpolarized);
    EXPECT_LT(copy(extraordinary, !e_right), 0.02 * o_unpolarized);
}

// The noise of a flat region seen through the crystal (the relative standard deviation over pixels of a
// uniformly grey wall seen through the slab) at 4 sample counts and its least-squares slope against spp
// on log scales.
struct NoiseCurve {
    std::vector<double> relative_noise;
    double slope = 0.0;
};

NoiseCurve flat_region_noise(bool stratified) {
    Scene scene = slab_scene(SigmoidSpectrum::constant(0.0));
    scene.camera.width_px = scene.camera.height_px = 8;
    WallEmission& bottom = scene.box.walls[static_cast<std::size_t>(Wall::bottom)];
    bottom.kind = WallEmission::Kind::uniform;
    bottom.uniform = SigmoidSpectrum::constant(0.5);
    NoiseCurve curve;
    std::vector<double> log_spp, log_noise;
    for (const int spp : {16, 64, 256, 1024}) {
        RenderSettings settings;
        settings.samples_per_pixel = spp;
        settings.seed = 7;
        settings.stratified = stratified;
        const Image xyz = render_scene(scene, testing::d65_spectrum(), settings).camera_xyz(false, 0.0);
        double sum = 0.0, sum2 = 0.0;
        for (int y = 0; y < xyz.height; ++y) {
            for (int x = 0; x < xyz.width; ++x) {
                sum += xyz.at(x, y, 1);
                sum2 += xyz.at(x, y, 1) * xyz.at(x, y, 1);
            }
        }
        const double n = xyz.width * xyz.height, mean = sum / n, deviation = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1));
        std::printf("%s, %4d spp: mean Y %.4f, relative noise %.5f\n", stratified ? "stratified" : "independent", spp, mean, deviation / mean);
        curve.relative_noise.push_back(deviation / mean);
        log_spp.push_back(std::log(spp));
        log_noise.push_back(std::log(deviation / mean));
    }
    const double mx = std::accumulate(log_spp.begin(), log_spp.end(), 0.0) / 4, my = std::accumulate(log_noise.begin(), log_noise.end(), 0.0) / 4;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
        sxy += (log_spp[k] - mx) * (log_noise[k] - my);
        sxx += (log_spp[k] - mx) * (log_spp[k] - mx);
    }
    curve.slope = sxy / sxx;
    std::printf("slope %.3f\n", curve.slope);
    return curve;
}

// Plain Monte Carlo (every number drawn independently): the noise falls as 1/√spp. The renderer's
// stratified samples fall at least as fast and are below plain Monte Carlo at every count.
TEST(RenderScenesAcceptance, NoiseFallsAsOneOverSquareRootOfSamples) {
    const NoiseCurve independent = flat_region_noise(false);
    EXPECT_NEAR(independent.slope, -0.5, 0.1);
    const NoiseCurve stratified = flat_region_noise(true);
    EXPECT_LT(stratified.slope, -0.5);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_LT(stratified.relative_noise[k], independent.relative_noise[k]) << "sample count #" << k;
}

// Outside the crystal every pixel whose footprint lies within one cell of the texture shows the cell's
// own colour: ΔE00 < 1 against the texture (the paper's scene, at a fifth of its resolution).
TEST(RenderScenes, TextureOutsideTheCrystalIsReproduced) {
    const std::filesystem::path file = std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json";
    Scene scene = read_scene(file, testing::render_minerals(), testing::d65_spectrum());
    scene.camera.width_px = 96;
    scene.camera.height_px = 87;
    RenderSettings settings;
    settings.samples_per_pixel = 4;
    const Image xyz = render_scene(scene, testing::d65_spectrum(), settings).camera_xyz(false, 0.0);
    const Image texture = colour_grid_texture(16, 13, 3, 16, 0.5);
    const Eigen::Matrix3d to_xyz = testing::d65_spectrum().xyz_to_linear_srgb.inverse();
    const Eigen::Vector3d white = to_xyz * Eigen::Vector3d::Ones();
    const SceneCamera& camera = scene.camera;
    const Eigen::Vector3d forward = (camera.target_mm - camera.position_mm).normalized(), right = forward.cross(camera.up).normalized(),
                          up = right.cross(forward);
    // The texture cell under an image point (pixel units), or −1 when the ray meets the crystal.
    const auto cell = [&](double px, double py) {
        const Eigen::Vector3d d = (camera.sensor_distance_mm * forward + (px / camera.width_px - 0.5) * camera.sensor_width_mm * right +
                                   (0.5 - py / camera.height_px) * camera.sensor_height_mm * up).normalized();
        if (intersect(scene.crystals[0].shape, camera.position_mm, d)) return -1;
        const Eigen::Vector3d p = camera.position_mm + (scene.box.lower_mm.z() - camera.position_mm.z()) / d.z() * d;
        const double u = (p.x() - scene.box.lower_mm.x()) / (scene.box.upper_mm.x() - scene.box.lower_mm.x());
        const double v = (p.y() - scene.box.lower_mm.y()) / (scene.box.upper_mm.y() - scene.box.lower_mm.y());
        if (u <= 0.0 || u >= 1.0 || v <= 0.0 || v >= 1.0) return -1;
        return static_cast<int>(u * 16) + 100 * static_cast<int>((1.0 - v) * 13);
    };
    int compared = 0;
    double worst = 0.0;
    for (int y = 0; y < camera.height_px; ++y) {
        for (int x = 0; x < camera.width_px; ++x) {
            const int c = cell(x, y);
            if (c < 0 || cell(x + 1, y) != c || cell(x, y + 1) != c || cell(x + 1, y + 1) != c) continue;
            Eigen::Vector3d expected;
            for (int k = 0; k < 3; ++k) expected[k] = decode_srgb(texture.at((c % 100) * 16 + 8, (c / 100) * 16 + 8, k));
            const Eigen::Vector3d rendered(xyz.at(x, y, 0), xyz.at(x, y, 1), xyz.at(x, y, 2));
            worst = std::max(worst, delta_e_2000(xyz_to_lab(rendered, white), xyz_to_lab(to_xyz * expected, white)));
            ++compared;
        }
    }
    std::printf("%d pixels compared, worst dE00 %.3g\n", compared, worst);
    EXPECT_GT(compared, 2000);
    EXPECT_LT(worst, 1.0);
}

}  // namespace
}  // namespace petroscope
