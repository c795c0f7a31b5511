#include "petroscope/optics/dispersion.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <array>
#include <cmath>

namespace petroscope {
namespace {

constexpr std::array<std::pair<DispersionModel::Kind, std::string_view>, 7> kKindNames{{
    {DispersionModel::Kind::constant, "constant"},
    {DispersionModel::Kind::cauchy, "cauchy"},
    {DispersionModel::Kind::rii_formula_1, "rii-formula-1"},
    {DispersionModel::Kind::rii_formula_2, "rii-formula-2"},
    {DispersionModel::Kind::rii_formula_4, "rii-formula-4"},
    {DispersionModel::Kind::table_nm, "table-nm"},
    {DispersionModel::Kind::drude, "drude"},
}};

// refractiveindex.info formulas 1 and 2 (database documentation, "formula" types), λ in µm:
// n² − 1 = C1 + Σᵢ C(2i) λ² / (λ² − Dᵢ), with Dᵢ = C(2i+1)² (formula 1) or C(2i+1) (formula 2).
double sellmeier_squared(const std::vector<double>& c, double lambda_um, bool squared_poles) {
    const double l2 = lambda_um * lambda_um;
    double n2 = 1.0 + c[0];
    for (std::size_t i = 1; i + 1 < c.size(); i += 2) {
        const double pole = squared_poles ? c[i + 1] * c[i + 1] : c[i + 1];
        n2 += c[i] * l2 / (l2 - pole);
    }
    return n2;
}

// refractiveindex.info formula 4, λ in µm:
// n² = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9) + C10 λ^C11 + C12 λ^C13 + …
double formula_4_squared(const std::vector<double>& c, double lambda_um) {
    const double l2 = lambda_um * lambda_um;
    double n2 = c[0];
    n2 += c[1] * std::pow(lambda_um, c[2]) / (l2 - std::pow(c[3], c[4]));
    n2 += c[5] * std::pow(lambda_um, c[6]) / (l2 - std::pow(c[7], c[8]));
    for (std::size_t i = 9; i + 1 < c.size(); i += 2) n2 += c[i] * std::pow(lambda_um, c[i + 1]);
    return n2;
}

InputError model_error(std::string_view model, const std::string& expected) {
    return InputError("dispersion model " + quote_input(model) + ": expected " + expected);
}

}  // namespace

std::string_view dispersion_kind_name(DispersionModel::Kind kind) {
    for (const auto& [k, name] : kKindNames) {
        if (k == kind) return name;
    }
    return "unknown";
}

DispersionModel DispersionModel::constant(double value) {
    DispersionModel model;
    model.kind_ = Kind::constant;
    model.coefficients_ = {value};
    return model;
}

DispersionModel DispersionModel::parse(std::string_view text) {
    const auto words = split_whitespace(trim(text));
    if (words.empty()) throw InputError("missing dispersion model (expected e.g. 'constant 1.544' or 'cauchy 1.53 0.0042')");
    DispersionModel model;
    bool known = false;
    for (const auto& [kind, name] : kKindNames) {
        if (words[0] == name) {
            model.kind_ = kind;
            known = true;
        }
    }
    if (!known) {
        throw InputError("unknown dispersion model " + quote_input(words[0]) +
                         " (expected constant, cauchy, rii-formula-1, rii-formula-2, rii-formula-4, table-nm or drude)");
    }
    const std::size_t count = words.size() - 1;
    if (model.kind_ == Kind::table_nm) {
        for (std::size_t i = 1; i < words.size(); ++i) {
            const auto pair = split(words[i], ':');
            const auto lambda = pair.size() == 2 ? parse_double(pair[0]) : std::nullopt;
            const auto value = pair.size() == 2 ? parse_double(pair[1]) : std::nullopt;
            if (!lambda || !value) throw model_error(words[0], "pairs WAVELENGTH_NM:VALUE, found " + quote_input(words[i]));
            if (*lambda <= 0.0) throw model_error(words[0], "positive wavelengths, found " + quote_input(words[i]));
            if (!model.coefficients_.empty() && *lambda <= model.coefficients_[model.coefficients_.size() - 2]) {
                throw model_error(words[0], "increasing wavelengths, found " + quote_input(words[i]) + " after a longer one");
            }
            model.coefficients_.push_back(*lambda);
            model.coefficients_.push_back(*value);
        }
        if (count < 2) throw model_error(words[0], "at least two WAVELENGTH_NM:VALUE pairs");
        return model;
    }
    for (std::size_t i = 1; i < words.size(); ++i) {
        const auto value = parse_double(words[i]);
        if (!value) throw model_error(words[0], "numbers, found " + quote_input(words[i]));
        model.coefficients_.push_back(*value);
    }
    switch (model.kind_) {
        case Kind::constant:
            if (count != 1) throw model_error(words[0], "one value");
            break;
        case Kind::cauchy:
            if (count < 2 || count > 4) throw model_error(words[0], "2 to 4 coefficients A B [C [D]]");
            break;
        case Kind::rii_formula_1:
        case Kind::rii_formula_2:
            if (count < 3 || count % 2 == 0) throw model_error(words[0], "C1 followed by pairs of coefficients (an odd count >= 3)");
            break;
        case Kind::rii_formula_4:
            if (count < 9 || count % 2 == 0) throw model_error(words[0], "9 coefficients, then pairs (an odd count >= 9)");
            break;
        case Kind::drude:
            if (count < 2 || count % 2 != 0) throw model_error(words[0], "pairs of coefficients K1 L1 [K2 L2 …]");
            break;
        case Kind::table_nm:
            break;
    }
    return model;
}

double DispersionModel::operator()(double wavelength_nm) const {
    const double lambda_um = wavelength_nm * 1e-3;
    const auto& c = coefficients_;
    switch (kind_) {
        case Kind::constant:
            return c[0];
        case Kind::cauchy: {
            // Cauchy: n = A + B/λ² + C/λ⁴ + D/λ⁶ (λ in µm).
            const double inverse_l2 = 1.0 / (lambda_um * lambda_um);
            double n = 0.0;
            for (std::size_t i = c.size(); i-- > 0;) n = n * inverse_l2 + c[i];
            return n;
        }
        case Kind::rii_formula_1:
            return std::sqrt(sellmeier_squared(c, lambda_um, true));
        case Kind::rii_formula_2:
            return std::sqrt(sellmeier_squared(c, lambda_um, false));
        case Kind::rii_formula_4:
            return std::sqrt(formula_4_squared(c, lambda_um));
        case Kind::table_nm: {
            if (wavelength_nm <= c.front()) return c[1];
            for (std::size_t i = 2; i < c.size(); i += 2) {
                if (wavelength_nm <= c[i]) {
                    const double t = (wavelength_nm - c[i - 2]) / (c[i] - c[i - 2]);
                    return c[i - 1] + t * (c[i + 1] - c[i - 1]);
                }
            }
            return c.back();
        }
        case Kind::drude: {
            // Drude's rotatory dispersion: Σᵢ Kᵢ/(λ² − Lᵢ²), λ and Lᵢ in µm (Drude, Lehrbuch der Optik, 1900;
            // Condon, Rev. Mod. Phys. 9, 432 (1937)).
            const double l2 = lambda_um * lambda_um;
            double value = 0.0;
            for (std::size_t i = 0; i + 1 < c.size(); i += 2) value += c[i] / (l2 - c[i + 1] * c[i + 1]);
            return value;
        }
    }
    return c[0];
}

std::string DispersionModel::describe() const {
    // Shortest text that reads back to the same double.
    std::string text(dispersion_kind_name(kind_));
    for (std::size_t i = 0; i < coefficients_.size(); ++i) {
        text += (kind_ == Kind::table_nm && i % 2 == 1) ? ':' : ' ';
        text += format_number(coefficients_[i]);
    }
    return text;
}

}  // namespace petroscope
