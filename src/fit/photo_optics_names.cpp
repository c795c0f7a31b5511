// The names of the photo model's closed sets (projection, field stop, illumination, colour sensor), as the CLI, Python and
// report.json spell them.
#include "petroscope/fit/conoscope_fit.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <array>
#include <string>
#include <utility>

namespace petroscope {
namespace {

template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<Enum, std::string_view>, N>;

constexpr NameTable<Projection, 3> kProjections{{{Projection::sine, "sine"}, {Projection::tangent, "tangent"},
                                                 {Projection::equidistant, "equidistant"}}};
constexpr NameTable<FieldStop, 2> kFieldStops{{{FieldStop::sharp, "sharp"}, {FieldStop::none, "none"}}};
constexpr NameTable<IlluminationProfile, 2> kIlluminations{{{IlluminationProfile::even, "even"}, {IlluminationProfile::falloff, "falloff"}}};
constexpr NameTable<ColourSensor, 2> kColourSensors{{{ColourSensor::full_colour, "full-colour"}, {ColourSensor::bayer, "bayer"}}};

template <typename Enum, std::size_t N>
std::string_view name_in(const NameTable<Enum, N>& table, Enum value) {
    for (const auto& [entry, name] : table) {
        if (entry == value) return name;
    }
    return "unknown";
}

template <typename Enum, std::size_t N>
Enum parse_in(const NameTable<Enum, N>& table, std::string_view name, std::string_view what) {
    std::string names;
    for (const auto& [entry, entry_name] : table) {
        if (entry_name == name) return entry;
        names += (names.empty() ? "" : ", ") + std::string(entry_name);
    }
    throw InputError("unknown " + std::string(what) + " " + quote_input(name) + " (expected one of " + names + ")");
}

}  // namespace

std::string_view projection_name(Projection projection) { return name_in(kProjections, projection); }
Projection parse_projection(std::string_view name) { return parse_in(kProjections, name, "projection"); }
std::string_view field_stop_name(FieldStop stop) { return name_in(kFieldStops, stop); }
FieldStop parse_field_stop(std::string_view name) { return parse_in(kFieldStops, name, "field stop"); }
std::string_view illumination_name(IlluminationProfile illumination) { return name_in(kIlluminations, illumination); }
IlluminationProfile parse_illumination(std::string_view name) { return parse_in(kIlluminations, name, "illumination"); }
std::string_view colour_sensor_name(ColourSensor sensor) { return name_in(kColourSensors, sensor); }
ColourSensor parse_colour_sensor(std::string_view name) { return parse_in(kColourSensors, name, "colour sensor"); }

}  // namespace petroscope
