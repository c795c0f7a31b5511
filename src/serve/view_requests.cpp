#include "petroscope/serve/view_requests.hpp"

#include "petroscope/api/crystal_orientation.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"


namespace petroscope::serve {
namespace {

constexpr double kMinThicknessUm = 0.01, kMaxThicknessUm = 1e5;  // 10 nm … 10 cm

std::optional<double> thickness_override_um(const QueryParameters& query) {
    return query.optional_number("thickness_um", kMinThicknessUm, kMaxThicknessUm);
}

Light light_from(const QueryParameters& query) {
    Light light;
    light.wavelength_nm = query.optional_number("wavelength_nm", 360.0, 830.0);
    light.illuminant = query.choice("illuminant", {"D65", "A"});
    return light;
}

std::optional<PlateRequest> plate_from(const QueryParameters& query) {
    const std::string name = query.choice("plate", {"none", "gypsum", "mica", "wedge"});
    if (name == "none") return std::nullopt;
    PlateRequest plate;
    plate.kind = parse_plate(name);
    plate.wedge_position = query.number("wedge_position", 0.0, 1.0, plate.wedge_position);
    return plate;
}

/// Light, analyzer and plate into either request.
template <typename Request>
void set_light_and_polars(Request& request, const QueryParameters& query) {
    request.light = light_from(query);
    request.analyzer_in = query.choice("analyzer", {"in", "out"}) == "in";
    request.plate = plate_from(query);
}

/// "a,b,c" in degrees, each finite; none otherwise.
std::optional<Eigen::Vector3d> euler_angles_deg(std::string_view text) {
    const std::vector<std::string> parts = split(text, ',');
    if (parts.size() != 3) return std::nullopt;
    Eigen::Vector3d angles;
    for (int k = 0; k < 3; ++k) {
        const std::optional<double> angle = parse_double(trim(parts[static_cast<std::size_t>(k)]));
        if (!angle) return std::nullopt;
        angles[k] = *angle;
    }
    return angles;
}

CrystalOrientation orientation_from(const QueryParameters& query) {
    CrystalOrientation orientation;
    if (const std::optional<std::string> euler = query.text("euler")) {
        orientation.euler_zyz_deg = euler_angles_deg(*euler);
        if (!orientation.euler_zyz_deg) {
            throw InputError(parameter_message("euler", "expected three angles in degrees a,b,c, got " + quote_input(*euler)));
        }
        return orientation;
    }
    if (const std::optional<std::string> cut = query.text("cut")) {
        try {
            orientation.cut = parse_cut(*cut);
        } catch (const InputError& error) {
            throw InputError(parameter_message("cut", error.what()));
        }
    }
    orientation.azimuth_deg = query.number("azimuth_deg", -360.0, 360.0, 0.0);
    orientation.tilt_deg = query.number("tilt_deg", -90.0, 90.0, 0.0);
    return orientation;
}

// The form of an optically active single crystal chosen on the page.
Handedness handedness_from(const QueryParameters& query) { return parse_handedness(query.choice("handedness", {"right", "left"})); }

const Mineral& mineral_from(const QueryParameters& query, const MineralCatalog& catalog) {
    const std::string name = query.text_or("mineral", "muscovite");
    try {
        return catalog.find(name);
    } catch (const InputError& error) {
        throw InputError(parameter_message("mineral", error.what()));
    }
}

}  // namespace

Illumination illumination_from(const QueryParameters& query) {
    return query.choice("polarizer", {"in", "out"}) == "in" ? Illumination::polarized : Illumination::unpolarized;
}

const std::vector<std::string>& view_parameter_names() {
    static const std::vector<std::string> names{"optics", "wavelength_nm", "illuminant", "polarizer", "analyzer", "plate", "wedge_position", "section",
                                                "seed", "x", "y", "mineral", "cut", "euler", "azimuth_deg", "tilt_deg", "thickness_um",
                                                "condenser_na", "na", "size_px", "handedness"};
    return names;
}

PickedGrain picked_grain(const QueryParameters& query, const SectionLookup& sections) {
    PickedGrain picked;
    picked.section = sections(query);
    const ThinSection& section = *picked.section;
    const auto x = static_cast<int>(query.integer("x", 0, section.width_px - 1, section.width_px / 2));
    const auto y = static_cast<int>(query.integer("y", 0, section.height_px - 1, section.height_px / 2));
    picked.grain = &section.grain_at(x, y);
    picked.thickness_um = thickness_override_um(query).value_or(section.thickness_at(x, y, *picked.grain));
    return picked;
}

ThinSection single_crystal_section(const QueryParameters& query, const MineralCatalog& catalog) {
    const Mineral& mineral = mineral_from(query, catalog);
    ThinSection section;
    section.name = "single crystal of " + mineral.name;
    section.width_px = section.height_px = kCrystalFieldPx;
    section.labels.assign(static_cast<std::size_t>(kCrystalFieldPx) * kCrystalFieldPx, 1);
    const Handedness chosen = handedness_from(query);
    const std::optional<Handedness> handedness = mineral.optically_active() ? std::optional(chosen) : std::nullopt;
    section.grains = {ThinSectionGrain{1, mineral.name, indicatrix_axes(mineral, orientation_from(query)), std::nullopt, 0, handedness}};
    section.thickness_um = thickness_override_um(query).value_or(30.0);
    section.validate();
    return section;
}

OrthoscopeRequest orthoscope_view_request(const QueryParameters& query, const MineralCatalog& catalog, const SectionLookup& sections) {
    OrthoscopeRequest request;
    if (query.has("section")) {
        request.section = *sections(query);
        request.thickness_um = thickness_override_um(query);
    } else {
        request.section = single_crystal_section(query, catalog);
    }
    request.condenser_na = query.number("condenser_na", 0.0, 0.95, 0.0);
    set_light_and_polars(request, query);
    return request;
}

ConoscopeRequest conoscope_view_request(const QueryParameters& query, const MineralCatalog& catalog, const SectionLookup& sections) {
    ConoscopeRequest request;
    request.handedness = handedness_from(query);
    if (query.has("section")) {
        const PickedGrain picked = picked_grain(query, sections);
        request.mineral = picked.grain->mineral;
        request.orientation.euler_zyz_deg = euler_zyz_deg_of(picked.grain->crystal_axes);
        request.thickness_um = picked.thickness_um;
        request.handedness = picked.grain->handedness.value_or(Handedness::right);  // the section's, as the orthoscope renders it
    } else {
        request.mineral = mineral_from(query, catalog).name;
        request.orientation = orientation_from(query);
        request.thickness_um = thickness_override_um(query).value_or(30.0);
    }
    request.numerical_aperture = query.number("na", 0.05, 0.95, 0.85);
    request.size_px = static_cast<int>(query.integer("size_px", 64, kServerMaxFigurePx, 512));
    set_light_and_polars(request, query);
    return request;
}

}  // namespace petroscope::serve
