#pragma once
// Small scenes for the renderer's tests: a calcite rhomb or slab in a box, seen from above.
#include "petroscope/io/data_files.hpp"
#include "petroscope/render/path_tracer.hpp"

#include <filesystem>

namespace petroscope::testing {

inline const MineralCatalog& render_minerals() {
    static const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return catalog;
}

inline const RenderSpectrum& d65_spectrum() {
    static const RenderSpectrum spectrum = render_spectrum(load_cie_1931_observer(), load_light_source("D65"));
    return spectrum;
}

/// Calcite with its principal indices from the mineral file.
inline SceneCrystal calcite_crystal(ConvexPolyhedron shape, const Eigen::Matrix3d& axes) {
    const Mineral& calcite = render_minerals().find("calcite");
    SceneCrystal crystal;
    crystal.mineral = "calcite";
    crystal.principal_n = [&calcite](double nm) { return calcite.principal_n(nm); };
    crystal.axes = axes;
    crystal.shape = std::move(shape);
    return crystal;
}

/// A box 100 × 100 × 60 mm (z from 0) with a camera 200 mm above the bottom looking straight down.
inline Scene box_scene(int size_px) {
    Scene scene;
    scene.box.lower_mm = {-50, -50, 0};
    scene.box.upper_mm = {50, 50, 60};
    scene.camera.position_mm = {0, 0, 200};
    scene.camera.target_mm = {0, 0, 0};
    scene.camera.up = {0, 1, 0};
    scene.camera.sensor_width_mm = scene.camera.sensor_height_mm = 10.0;
    scene.camera.sensor_distance_mm = 30.0;
    scene.camera.width_px = scene.camera.height_px = size_px;
    return scene;
}

}  // namespace petroscope::testing
