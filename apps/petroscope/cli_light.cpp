#include "cli_light.hpp"

#include "cli_common.hpp"
#include "frame_command.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/spectral/color.hpp"

namespace petroscope::cli {

void add_light_options(CLI::App* command, LightOptions& options) {
    command->add_option("--wavelength", options.wavelength, "Monochromatic light at this wavelength (589nm, 0.633um); default: white light")
        ->type_name(wavelength_type);
    command->add_option("--wavelengths", options.wavelength_grid, "White-light grid START:END:STEP in nm")->capture_default_str();
    command->add_option("--illuminant", options.illuminant, "White light: D65, A (halogen) or blackbody:3200K")->capture_default_str();
    command->add_flag("--no-white-balance", options.no_white_balance, "Keep the colour cast of the illuminant");
    command->add_option("--exposure", options.exposure, "Scale the image brightness")->capture_default_str();
}

ResolvedLight resolve_light(const LightOptions& options) {
    if (!(options.exposure > 0.0)) throw InputError("--exposure must be > 0");
    ResolvedLight light;
    if (!options.wavelength.empty()) {
        const double wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(options.wavelength); });
        if (!(wavelength_nm > 0.0)) throw InputError("--wavelength " + quote_input(options.wavelength) + ": must be > 0");
        light.wavelengths_nm = {wavelength_nm};
    } else {
        light.grid = with_option("--wavelengths", [&] { return WavelengthGrid::parse(options.wavelength_grid); });
        light.wavelengths_nm = light.grid->wavelengths_nm();
    }
    return light;
}

Image render_in_light(const LightOptions& options, const ResolvedLight& light,
                      const std::function<Image(const SpectralIntegrator*)>& render, const std::string& white_meaning,
                      nlohmann::json& light_json) {
    if (light.monochromatic()) {
        light_json = {{"mode", "monochromatic"}, {"wavelength_nm", light.wavelengths_nm[0]},
                      {"pixel_values", "transmitted intensity relative to the incident (after the polarizer), in every channel, times exposure"}};
        return gray_image_to_rgb(render(nullptr), options.exposure);
    }
    const LightSource source = load_light_source(options.illuminant);
    const SpectralIntegrator integrator(light.wavelengths_nm, load_cie_1931_observer(), source);
    const Image xyz = render(&integrator);
    const WavelengthGrid& grid = *light.grid;
    light_json = {{"mode", "white"}, {"illuminant", source.name},
                  {"wavelengths_nm", {{"start", grid.start_nm}, {"end", grid.end_nm}, {"step", grid.step_nm}, {"count", grid.size()}}},
                  {"white_balance", !options.no_white_balance},
                  {"pixel_values", "linear sRGB (EXR/TIFF) or encoded sRGB (PNG); white = " + white_meaning + ", times exposure"}};
    return xyz_image_to_linear_srgb(xyz, integrator.white_xyz(), !options.no_white_balance, options.exposure);
}

void add_plate_options(CLI::App* command, PlateOptions& options) {
    command->add_option("--plate", options.plate, "Accessory plate: gypsum (first-order red), mica (quarter wave), wedge (quartz wedge)");
    command->add_option("--plate-deg", options.plate_deg, "The plate's slow direction, degrees from E toward N (45: NE-SW)")->capture_default_str();
    command->add_option("--wedge-position", options.wedge_position, "How far the quartz wedge is pushed in, 0 to 1 (0 to 4 orders)")->capture_default_str();
}

std::optional<AccessoryPlate> make_plate(const PlateOptions& options, const MineralCatalog& catalog) {
    if (options.plate.empty()) return std::nullopt;
    return with_option("--plate", [&] {
        const PlateKind kind = parse_plate(options.plate);
        return make_accessory_plate(kind, catalog.find(plate_mineral_name(kind)), options.plate_deg, options.wedge_position);
    });
}

nlohmann::json plate_json(const std::optional<AccessoryPlate>& plate) {
    if (!plate) return nullptr;
    return {{"kind", plate_name(plate->kind)}, {"thickness_um", plate->thickness_um}, {"slow_deg", plate->slow_deg},
            {"description", plate->description}};
}

}  // namespace petroscope::cli
