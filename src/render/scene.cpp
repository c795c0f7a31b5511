#include "petroscope/render/scene.hpp"

#include "petroscope/core/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace petroscope {

const SigmoidSpectrum* WallEmission::spectrum_at(double u, double v) const {
    switch (kind) {
    case Kind::off:
        return nullptr;
    case Kind::uniform:
        return &uniform;
    case Kind::texture: {
        const int column = std::clamp(static_cast<int>(u * texture_width), 0, texture_width - 1);
        const int row = std::clamp(static_cast<int>((1.0 - v) * texture_height), 0, texture_height - 1);
        const std::size_t texel = static_cast<std::size_t>(row) * static_cast<std::size_t>(texture_width) + static_cast<std::size_t>(column);
        return &palette[static_cast<std::size_t>(texel_palette_index[texel])];
    }
    }
    return nullptr;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> wall_texture_axes(Wall wall) {
    switch (wall) {
    case Wall::left:
        return {Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    case Wall::right:
        return {-Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    case Wall::front:
        return {-Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
    case Wall::back:
        return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
    case Wall::bottom:
        return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    case Wall::top:
        return {-Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    }
    return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
}

void check_scene(const Scene& scene) {
    const SceneBox& box = scene.box;
    if (!box.lower_mm.allFinite() || !box.upper_mm.allFinite() || !((box.upper_mm - box.lower_mm).minCoeff() > 0.0)) {
        throw InputError("box: every extent must be positive (upper > lower along x, y and z)");
    }
    const double size = (box.upper_mm - box.lower_mm).norm();
    for (std::size_t c = 0; c < scene.crystals.size(); ++c) {
        const ConvexPolyhedron& shape = scene.crystals[c].shape;
        const std::string name = "crystals[" + std::to_string(c) + "]";
        if (!((shape.lower() - box.lower_mm).minCoeff() > 1e-9 * size) || !((box.upper_mm - shape.upper()).minCoeff() > 1e-9 * size)) {
            throw InputError(name + ": the crystal touches or crosses a wall of the box; it must lie inside, clear of the walls");
        }
        for (std::size_t other = 0; other < c; ++other) {
            const ConvexPolyhedron& b = scene.crystals[other].shape;
            const bool apart = (shape.lower().array() > b.upper().array()).any() || (b.lower().array() > shape.upper().array()).any();
            if (!apart) {
                throw InputError(name + ": its bounding box overlaps that of crystals[" + std::to_string(other) +
                                 "]; crystals must be separated (touching crystals are not supported)");
            }
        }
    }
    const SceneCamera& camera = scene.camera;
    if (!camera.position_mm.allFinite() || !camera.target_mm.allFinite() || !camera.up.allFinite()) throw InputError("camera: position, target and up must be finite");
    const Eigen::Vector3d forward = camera.target_mm - camera.position_mm;
    if (!(forward.norm() > 0.0)) throw InputError("camera: target must differ from position");
    if (!(forward.normalized().cross(camera.up).norm() > 1e-6)) throw InputError("camera: up must not be parallel to the viewing direction");
    if (!(camera.sensor_width_mm > 0.0) || !(camera.sensor_height_mm > 0.0) || !(camera.sensor_distance_mm > 0.0)) {
        throw InputError("camera: sensor_width_mm, sensor_height_mm and sensor_distance_mm must be > 0");
    }
    if (camera.width_px < 1 || camera.height_px < 1) throw InputError("camera: width_px and height_px must be >= 1");
    for (const auto& crystal : scene.crystals) {
        if (crystal.shape.contains(camera.position_mm, 0.0)) throw InputError("camera: the camera is inside a crystal");
    }
}

}  // namespace petroscope
