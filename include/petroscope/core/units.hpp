#pragma once
// Parsing of physical quantities typed by users: "30um", "1.5 mm", "589nm", "0.5893um".
// Every function throws InputError naming the value and the accepted units.
#include <string_view>

namespace petroscope {

/// A length with a unit (nm, um, µm, mm, cm, m), returned in micrometres.
double parse_length_um(std::string_view text);

/// A wavelength with a unit (nm, um, µm), or a bare number taken as nm; returned in nanometres.
double parse_wavelength_nm(std::string_view text);

}  // namespace petroscope
