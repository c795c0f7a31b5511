#pragma once
// Refractive index (or extinction coefficient, or rotatory power) as a function of wavelength: the dispersion
// models of minerals/README.md.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

class DispersionModel {
public:
    enum class Kind { constant, cauchy, rii_formula_1, rii_formula_2, rii_formula_4, table_nm, drude };

    /// Parses "MODEL P1 P2 …" (minerals/README.md). Throws InputError with a message that names the
    /// model and what was expected; the caller adds the file and line.
    static DispersionModel parse(std::string_view text);
    static DispersionModel constant(double value);

    /// The value at `wavelength_nm` (the formula's own unit conversion is done inside).
    double operator()(double wavelength_nm) const;

    Kind kind() const { return kind_; }
    const std::vector<double>& coefficients() const { return coefficients_; }
    /// Text form, as written in a mineral file.
    std::string describe() const;

private:
    Kind kind_ = Kind::constant;
    std::vector<double> coefficients_;  // for table_nm: λ₀, v₀, λ₁, v₁, …
};

/// The name of each model as written in files: "constant", "cauchy", "rii-formula-1", …
std::string_view dispersion_kind_name(DispersionModel::Kind kind);

}  // namespace petroscope
