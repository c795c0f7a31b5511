#pragma once
// Options every rendering subcommand shares: the light (white or monochromatic) with its display
// conversion, and the accessory plate.
#include "petroscope/core/image.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/spectral/colorimetry.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace petroscope::cli {

struct LightOptions {
    std::string wavelength;  // empty: white light
    std::string wavelength_grid = "380:780:5";
    std::string illuminant = "D65";
    bool no_white_balance = false;
    double exposure = 1.0;
};
void add_light_options(CLI::App* command, LightOptions& options);

/// The wavelengths the options ask for (validated; the option named in any error).
struct ResolvedLight {
    std::vector<double> wavelengths_nm;
    std::optional<WavelengthGrid> grid;  // white light
    bool monochromatic() const { return !grid; }
};
ResolvedLight resolve_light(const LightOptions& options);

/// Renders with `render` (given the colour integrator in white light, nullptr in monochromatic light) and
/// converts to linear sRGB for display; `light_json` receives the sidecar's "light" entry, whose
/// "pixel_values" says what 1 means (`white_meaning`).
Image render_in_light(const LightOptions& options, const ResolvedLight& light,
                      const std::function<Image(const SpectralIntegrator*)>& render, const std::string& white_meaning,
                      nlohmann::json& light_json);

struct PlateOptions {
    std::string plate;  // empty: none
    double plate_deg = 45.0;
    double wedge_position = 0.5;
};
void add_plate_options(CLI::App* command, PlateOptions& options);
std::optional<AccessoryPlate> make_plate(const PlateOptions& options, const MineralCatalog& catalog);
nlohmann::json plate_json(const std::optional<AccessoryPlate>& plate);

}  // namespace petroscope::cli
