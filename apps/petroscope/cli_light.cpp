#include "cli_light.hpp"

#include "cli_common.hpp"
#include "frame_command.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"

namespace petroscope::cli {

void add_light_options(CLI::App* command, LightOptions& options) {
    command->add_option("--wavelength", options.wavelength, "Monochromatic light at this wavelength (589nm, 0.633um); default: white light")
        ->type_name(wavelength_type);
    command->add_option("--wavelengths", options.wavelength_grid, "White-light grid START:END:STEP in nm")->capture_default_str();
    command->add_option("--illuminant", options.illuminant, "White light: D65, A (halogen) or blackbody:3200K")->capture_default_str();
    command->add_flag("--no-white-balance", options.no_white_balance, "Keep the colour cast of the illuminant");
    command->add_option("--exposure", options.exposure, "Scale the image brightness")->capture_default_str();
}

Light light_from_options(const LightOptions& options) {
    if (!(options.exposure > 0.0)) throw InputError("--exposure must be > 0");
    Light light;
    if (!options.wavelength.empty()) {
        const double wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(options.wavelength); });
        if (!(wavelength_nm > 0.0)) throw InputError("--wavelength " + quote_input(options.wavelength) + ": must be > 0");
        light.wavelength_nm = wavelength_nm;
    } else {
        light.grid = with_option("--wavelengths", [&] { return WavelengthGrid::parse(options.wavelength_grid); });
    }
    light.illuminant = options.illuminant;
    light.white_balance = !options.no_white_balance;
    light.exposure = options.exposure;
    return light;
}

nlohmann::json light_json(const Light& light, const DisplayImage& image, const std::string& white_meaning) {
    if (light.monochromatic()) {
        return {{"mode", "monochromatic"}, {"wavelength_nm", *light.wavelength_nm},
                {"pixel_values", "transmitted intensity relative to the incident (after the polarizer), in every channel, times exposure"}};
    }
    const WavelengthGrid& grid = light.grid;
    return {{"mode", "white"}, {"illuminant", image.illuminant},
            {"wavelengths_nm", {{"start", grid.start_nm}, {"end", grid.end_nm}, {"step", grid.step_nm}, {"count", grid.size()}}},
            {"white_balance", light.white_balance},
            {"pixel_values", "linear sRGB (EXR/TIFF) or encoded sRGB (PNG); white = " + white_meaning + ", times exposure"}};
}

void add_plate_options(CLI::App* command, PlateOptions& options) {
    command->add_option("--plate", options.plate, "Accessory plate: gypsum (first-order red), mica (quarter wave), wedge (quartz wedge)");
    command->add_option("--plate-deg", options.plate_deg, "The plate's slow direction, degrees from E toward N (45: NE-SW)")->capture_default_str();
    command->add_option("--wedge-position", options.wedge_position, "How far the quartz wedge is pushed in, 0 to 1 (0 to 4 orders)")->capture_default_str();
}

std::optional<PlateRequest> plate_request(const PlateOptions& options) {
    if (options.plate.empty()) return std::nullopt;
    return PlateRequest{with_option("--plate", [&] { return parse_plate(options.plate); }), options.plate_deg, options.wedge_position};
}

nlohmann::json plate_json(const std::optional<AccessoryPlate>& plate) {
    if (!plate) return nullptr;
    return {{"kind", plate_name(plate->kind)}, {"thickness_um", plate->thickness_um}, {"slow_deg", plate->slow_deg},
            {"description", plate->description}};
}

nlohmann::json mounting_json(const SectionMounting& mounting) {
    return {{"slide", "crown glass"}, {"slide_um", mounting.slide_um}, {"cement", "canada balsam"},
            {"lower_cement_um", mounting.lower_cement_um}, {"upper_cement_um", mounting.upper_cement_um},
            {"cover", "crown glass"}, {"cover_um", mounting.cover_um}};
}

}  // namespace petroscope::cli
