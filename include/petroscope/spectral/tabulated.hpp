#pragma once
// Tabulated functions of wavelength (CIE tables, illuminants) and the CSV format they come in.
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// y(λ) sampled at increasing λ (nm); linear interpolation between samples, zero outside.
class TabulatedSpectrum {
public:
    TabulatedSpectrum() = default;
    TabulatedSpectrum(std::vector<double> wavelengths_nm, std::vector<double> values);

    double operator()(double wavelength_nm) const;
    double min_nm() const { return wavelengths_nm_.front(); }
    double max_nm() const { return wavelengths_nm_.back(); }
    bool empty() const { return wavelengths_nm_.empty(); }

private:
    std::vector<double> wavelengths_nm_;
    std::vector<double> values_;
};

/// A CSV table: one header line, then rows of numbers; the first column is wavelength in nm and must
/// increase. `source_name` is used in error messages ("file:line: …").
struct SpectralTable {
    std::vector<std::string> column_names;         // without the wavelength column
    std::vector<TabulatedSpectrum> columns;        // one per column name
};
SpectralTable parse_spectral_csv(std::string_view text, const std::string& source_name);

}  // namespace petroscope
