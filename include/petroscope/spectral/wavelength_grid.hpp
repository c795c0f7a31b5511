#pragma once
// The wavelengths at which every spectral quantity is evaluated.
#include <string_view>
#include <vector>

namespace petroscope {

/// Uniform grid start_nm, start_nm + step_nm, …, ≤ end_nm. Each sample stands for a band of width step_nm
/// (a Riemann sum; on 5 nm steps it changes Y by < 2e-5 against the 1 nm tables, docs/theory.md §7).
struct WavelengthGrid {
    double start_nm = 380.0;
    double end_nm = 780.0;
    double step_nm = 5.0;

    std::vector<double> wavelengths_nm() const;
    int size() const;
    /// A single wavelength (monochromatic light).
    static WavelengthGrid monochromatic(double wavelength_nm);
    /// Throws InputError unless 0 < start ≤ end, step > 0 and at most 100000 samples.
    void validate() const;
    /// "START:END:STEP" in nm, e.g. "380:780:5"; throws InputError naming the value.
    static WavelengthGrid parse(std::string_view text);
};

}  // namespace petroscope
