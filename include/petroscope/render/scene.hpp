#pragma once
// A scene for the spectral polarized ray tracer (docs/render.md): a box of one-sided emitting walls, convex
// crystals inside it, a pinhole camera with an optional linear polarizer. Lengths in mm.
#include "petroscope/render/polyhedron.hpp"
#include "petroscope/render/sigmoid_spectrum.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace petroscope {

/// What a wall emits into the box, unpolarized and the same in every direction: off, one spectrum, or a
/// texture whose texels each have a spectrum. Spectra are relative to the renderer's white light, D65
/// (a texel of ρ ≡ 1 emits D65 with Y = 1); `scale` multiplies them.
struct WallEmission {
    enum class Kind { off, uniform, texture };
    Kind kind = Kind::off;
    double scale = 1.0;
    SigmoidSpectrum uniform = SigmoidSpectrum::constant(0.0);
    int texture_width = 0, texture_height = 0;
    std::vector<int> texel_palette_index;  // row 0 at the wall's top edge (see wall_texture_axes)
    std::vector<SigmoidSpectrum> palette;

    /// The spectrum (before `scale`) at the wall point with texture coordinates (u, v) ∈ [0, 1]², nearest
    /// texel; nullptr when off.
    const SigmoidSpectrum* spectrum_at(double u, double v) const;
};

enum class Wall { left, right, front, back, bottom, top };  // x min, x max, y min, y max, z min, z max
inline constexpr int kWallCount = 6;

struct SceneBox {
    Eigen::Vector3d lower_mm{-1.0, -1.0, 0.0}, upper_mm{1.0, 1.0, 1.0};
    std::array<WallEmission, kWallCount> walls;
};

/// A wall's texture axes as seen from inside the box: u to the right, v up (image row 0 at v = 1).
/// Bottom: u = +x, v = +y; top: u = −x, v = +y; left (x min): u = +y, v = +z; right: u = −y, v = +z;
/// front (y min): u = −x, v = +z; back: u = +x, v = +z.
std::pair<Eigen::Vector3d, Eigen::Vector3d> wall_texture_axes(Wall wall);

struct SceneCrystal {
    std::string mineral;
    /// n + iκ of the indicatrix axes X, Y, Z at a wavelength (nm).
    std::function<Eigen::Vector3d(double)> principal_n;
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: X, Y, Z in the scene frame
    ConvexPolyhedron shape;
};

/// A pinhole camera (the paper's Fig. 14: sensor sw × sh at distance zn behind the pinhole).
struct SceneCamera {
    Eigen::Vector3d position_mm{0, -3, 1}, target_mm{0, 0, 0}, up{0, 0, 1};
    double sensor_width_mm = 36.0, sensor_height_mm = 24.0, sensor_distance_mm = 50.0;
    int width_px = 480, height_px = 320;
    /// A linear polarizer in front of the camera: its transmission axis from the image's right toward up.
    bool has_polarizer = false;
    double polarizer_deg = 0.0;
};

struct Scene {
    SceneBox box;
    std::vector<SceneCrystal> crystals;
    SceneCamera camera;
};

/// Checks what the renderer needs: a box of positive size, crystals inside it (clear of the walls) whose
/// bounding boxes do not overlap, a camera outside or inside the box with a positive sensor and size.
/// Throws InputError naming the crystal or the camera value.
void check_scene(const Scene& scene);

}  // namespace petroscope
