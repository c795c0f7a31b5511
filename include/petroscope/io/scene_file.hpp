#pragma once
// Scene files for `petroscope render` (JSON; the format is in docs/render.md): the box and its walls,
// the crystals, the camera. Errors name the file and the JSON path ("scene.json: crystals[0].mineral:
// unknown mineral 'calcyte'").
#include "petroscope/core/image.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/render/path_tracer.hpp"

#include <filesystem>
#include <string>

namespace petroscope {

/// Reads a scene; textures are read relative to the scene's folder, and their colours (sRGB-encoded
/// texels, IEC 61966-2-1) turned into sigmoid spectra under `spectrum`'s light.
Scene read_scene(const std::filesystem::path& file, const MineralCatalog& catalog, const RenderSpectrum& spectrum);
/// The same for a scene file's text already read: `file` names it in errors, and its folder holds the
/// textures.
Scene parse_scene(const std::string& text, const std::filesystem::path& file, const MineralCatalog& catalog, const RenderSpectrum& spectrum);

/// The paper's texture (Fig. 10): a grid of `cells` squares of `cell_px` pixels in distinct colours,
/// inside a grey border `border_cells` cells wide; sRGB-encoded values 0 … 1, 3 channels.
Image colour_grid_texture(int cells_x, int cells_y, int border_cells, int cell_px, double border_grey);

}  // namespace petroscope
