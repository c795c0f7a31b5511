#include "petroscope/spectral/wavelength_grid.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace petroscope {

namespace {

// The number of samples as a double (it may not fit an int before it is checked). The tolerance keeps
// END itself when (END − START)/STEP is an integer up to rounding.
double sample_count(double start_nm, double end_nm, double step_nm) {
    return std::floor((end_nm - start_nm) / step_nm + 1e-9) + 1.0;
}

constexpr double kMaxSamples = 100000;

}  // namespace

int WavelengthGrid::size() const {
    return static_cast<int>(std::min(sample_count(start_nm, end_nm, step_nm), kMaxSamples));
}

std::vector<double> WavelengthGrid::wavelengths_nm() const {
    std::vector<double> wavelengths(static_cast<std::size_t>(size()));
    for (std::size_t i = 0; i < wavelengths.size(); ++i) wavelengths[i] = start_nm + step_nm * static_cast<double>(i);
    return wavelengths;
}

WavelengthGrid WavelengthGrid::monochromatic(double wavelength_nm) {
    return WavelengthGrid{wavelength_nm, wavelength_nm, 1.0};
}

WavelengthGrid WavelengthGrid::parse(std::string_view text) {
    const auto parts = split(text, ':');
    const auto fail = [&](const std::string& why) {
        return InputError("invalid wavelength grid " + quote_input(text) + ": " + why +
                          " (expected START:END:STEP in nm, e.g. 380:780:5)");
    };
    if (parts.size() != 3) throw fail("three numbers separated by ':' are needed");
    const auto start = parse_double(parts[0]);
    const auto end = parse_double(parts[1]);
    const auto step = parse_double(parts[2]);
    if (!start || !end || !step) throw fail("not a number");
    if (*start <= 0.0 || *end < *start) throw fail("need 0 < START <= END");
    if (*step <= 0.0) throw fail("STEP must be > 0");
    if (!(sample_count(*start, *end, *step) <= kMaxSamples)) throw fail("more than 100000 wavelengths");
    return WavelengthGrid{*start, *end, *step};
}

}  // namespace petroscope
