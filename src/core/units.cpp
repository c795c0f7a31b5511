#include "petroscope/core/units.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <utility>

namespace petroscope {
namespace {

struct UnitFactor {
    std::string_view suffix;
    double factor;
};

// Splits "30um" into 30 and the factor of "um" from `units`; throws with the accepted list otherwise.
double parse_with_units(std::string_view text, std::span<const UnitFactor> units, bool bare_allowed,
                        double bare_factor, std::string_view quantity, std::string_view accepted) {
    const std::string_view value = trim(text);
    for (const UnitFactor& unit : units) {
        if (value.size() > unit.suffix.size() && value.ends_with(unit.suffix)) {
            if (const auto number = parse_double(value.substr(0, value.size() - unit.suffix.size()))) {
                if (std::isfinite(*number * unit.factor)) return *number * unit.factor;
                break;  // overflows once converted
            }
        }
    }
    if (bare_allowed) {
        if (const auto number = parse_double(value); number && std::isfinite(*number * bare_factor)) return *number * bare_factor;
    }
    throw InputError("invalid " + std::string(quantity) + " " + quote_input(text) +
                     ": expected a number with a unit (" + std::string(accepted) + "), e.g. 30um");
}

}  // namespace

double parse_length_um(std::string_view text) {
    static constexpr std::array<UnitFactor, 6> units{{
        {"nm", 1e-3}, {"um", 1.0}, {"\u00b5m", 1.0}, {"mm", 1e3}, {"cm", 1e4}, {"m", 1e6}}};
    return parse_with_units(text, units, false, 0.0, "length", "nm, um, mm, cm, m");
}

double parse_wavelength_nm(std::string_view text) {
    static constexpr std::array<UnitFactor, 3> units{{{"nm", 1.0}, {"um", 1e3}, {"\u00b5m", 1e3}}};
    return parse_with_units(text, units, true, 1.0, "wavelength", "nm or um; a bare number is nm");
}

}  // namespace petroscope
