#pragma once
// Options every rendering subcommand shares: the light (white or monochromatic) with its display
// conversion, and the accessory plate.
#include "petroscope/api/light.hpp"
#include "petroscope/api/plate.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace petroscope::cli {

struct LightOptions {
    std::string wavelength;  // empty: white light
    std::string wavelength_grid = "380:780:5";
    std::string illuminant = "D65";
    bool no_white_balance = false;
    double exposure = 1.0;
};
void add_light_options(CLI::App* command, LightOptions& options);

/// The light the options describe (validated; the option named in any error).
Light light_from_options(const LightOptions& options);

/// The sidecar's "light" entry of an image rendered in `light`: "pixel_values" says what 1 means
/// (`white_meaning`: what shows white).
nlohmann::json light_json(const Light& light, const DisplayImage& image, const std::string& white_meaning);

struct PlateOptions {
    std::string plate;  // empty: none
    double plate_deg = 45.0;
    double wedge_position = 0.5;
};
void add_plate_options(CLI::App* command, PlateOptions& options);
std::optional<PlateRequest> plate_request(const PlateOptions& options);
nlohmann::json plate_json(const std::optional<AccessoryPlate>& plate);

/// The sidecar's "mounting": the standard thin section's layers.
nlohmann::json mounting_json(const SectionMounting& mounting);

}  // namespace petroscope::cli
