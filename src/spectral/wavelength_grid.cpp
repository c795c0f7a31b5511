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

// Why a grid is not usable, or empty.
std::string grid_problem(double start_nm, double end_nm, double step_nm) {
    if (!std::isfinite(start_nm) || !std::isfinite(end_nm) || !std::isfinite(step_nm)) return "not a finite number";
    if (start_nm <= 0.0 || end_nm < start_nm) return "need 0 < START <= END";
    if (step_nm <= 0.0) return "STEP must be > 0";
    if (!(sample_count(start_nm, end_nm, step_nm) <= kMaxSamples)) return "more than 100000 wavelengths";
    return {};
}

}  // namespace

void WavelengthGrid::validate() const {
    if (const std::string problem = grid_problem(start_nm, end_nm, step_nm); !problem.empty()) {
        throw InputError("invalid wavelength grid " + format_number(start_nm) + ":" + format_number(end_nm) + ":" + format_number(step_nm) +
                         ": " + problem + " (expected START:END:STEP in nm, e.g. 380:780:5)");
    }
}

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
    if (const std::string problem = grid_problem(*start, *end, *step); !problem.empty()) throw fail(problem);
    return WavelengthGrid{*start, *end, *step};
}

}  // namespace petroscope
