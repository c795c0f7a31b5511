#include "petroscope/spectral/tabulated.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <stdexcept>

namespace petroscope {

TabulatedSpectrum::TabulatedSpectrum(std::vector<double> wavelengths_nm, std::vector<double> values)
    : wavelengths_nm_(std::move(wavelengths_nm)), values_(std::move(values)) {
    if (wavelengths_nm_.size() != values_.size() || wavelengths_nm_.size() < 2) {
        throw std::invalid_argument("TabulatedSpectrum needs >= 2 samples and one value per wavelength");
    }
}

double TabulatedSpectrum::operator()(double wavelength_nm) const {
    if (wavelength_nm < wavelengths_nm_.front() || wavelength_nm > wavelengths_nm_.back()) return 0.0;
    const auto upper = std::upper_bound(wavelengths_nm_.begin(), wavelengths_nm_.end(), wavelength_nm);
    if (upper == wavelengths_nm_.end()) return values_.back();
    const std::size_t i = static_cast<std::size_t>(upper - wavelengths_nm_.begin());
    const double t = (wavelength_nm - wavelengths_nm_[i - 1]) / (wavelengths_nm_[i] - wavelengths_nm_[i - 1]);
    return values_[i - 1] + t * (values_[i] - values_[i - 1]);
}

SpectralTable parse_spectral_csv(std::string_view text, const std::string& source_name) {
    SpectralTable table;
    std::vector<double> wavelengths;
    std::vector<std::vector<double>> values;
    int last_line = 1;
    for_each_line(text, [&](int line_number, std::string_view raw) {
        last_line = line_number;
        const std::string_view line = trim(raw);
        if (line.empty()) return;
        const auto fields = split(line, ',');
        if (table.column_names.empty() && wavelengths.empty()) {
            if (fields.size() < 2) throw located_error(source_name, line_number, "expected a header with a wavelength column and at least one more column");
            table.column_names.assign(fields.begin() + 1, fields.end());
            values.resize(table.column_names.size());
            return;
        }
        if (fields.size() != table.column_names.size() + 1) {
            throw located_error(source_name, line_number,
                                "expected " + std::to_string(table.column_names.size() + 1) + " comma-separated numbers, found " +
                                    std::to_string(fields.size()));
        }
        const auto wavelength = parse_double(fields[0]);
        if (!wavelength) throw located_error(source_name, line_number, "wavelength " + quote_input(fields[0]) + " is not a number");
        if (!wavelengths.empty() && *wavelength <= wavelengths.back()) {
            throw located_error(source_name, line_number, "wavelengths must increase");
        }
        wavelengths.push_back(*wavelength);
        for (std::size_t c = 0; c < values.size(); ++c) {
            const auto value = parse_double(fields[c + 1]);
            if (!value) throw located_error(source_name, line_number, "value " + quote_input(fields[c + 1]) + " is not a number");
            values[c].push_back(*value);
        }
    });
    if (wavelengths.size() < 2) throw located_error(source_name, last_line, "expected at least two rows of data");
    for (auto& column : values) table.columns.emplace_back(wavelengths, std::move(column));
    return table;
}

}  // namespace petroscope
