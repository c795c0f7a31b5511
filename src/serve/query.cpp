#include "petroscope/serve/query.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <cmath>

namespace petroscope::serve {
namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    return list;
}

}  // namespace

std::string parameter_message(std::string_view name, std::string_view message) {
    return "parameter " + quote_input(name, 40) + ": " + std::string(message);
}

QueryParameters::QueryParameters(const std::vector<std::pair<std::string, std::string>>& pairs) {
    for (const auto& [name, value] : pairs) {
        if (!values_.emplace(name, value).second) throw InputError(parameter_message(name, "given twice"));
    }
}

std::optional<std::string> QueryParameters::text(std::string_view name) const {
    const auto found = values_.find(name);
    if (found == values_.end()) return std::nullopt;
    return found->second;
}

std::string QueryParameters::text_or(std::string_view name, std::string fallback) const {
    return text(name).value_or(std::move(fallback));
}

std::optional<double> QueryParameters::optional_number(std::string_view name, double minimum, double maximum) const {
    const std::optional<std::string> value = text(name);
    if (!value) return std::nullopt;
    const std::optional<double> number = parse_double(*value);
    if (!number || *number < minimum || *number > maximum) {
        throw InputError(parameter_message(name, "expected a number from " + format_number(minimum) + " to " + format_number(maximum) +
                                                     ", got " + quote_input(*value)));
    }
    return number;
}

double QueryParameters::number(std::string_view name, double minimum, double maximum, double fallback) const {
    return optional_number(name, minimum, maximum).value_or(fallback);
}

long long QueryParameters::integer(std::string_view name, long long minimum, long long maximum, long long fallback) const {
    const std::optional<std::string> value = text(name);
    if (!value) return fallback;
    const std::optional<double> number = parse_double(*value);
    if (!number || *number != std::floor(*number) || *number < static_cast<double>(minimum) || *number > static_cast<double>(maximum)) {
        throw InputError(parameter_message(name, "expected a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum) +
                                                     ", got " + quote_input(*value)));
    }
    return static_cast<long long>(*number);
}

std::string QueryParameters::choice(std::string_view name, const std::vector<std::string>& choices) const {
    const std::optional<std::string> value = text(name);
    if (!value) return choices.front();
    for (const std::string& candidate : choices) {
        if (*value == candidate) return candidate;
    }
    throw InputError(parameter_message(name, "expected one of " + joined(choices) + ", got " + quote_input(*value)));
}

void QueryParameters::refuse_unknown(const std::vector<std::string>& known) const {
    for (const auto& [name, value] : values_) {
        bool found = false;
        for (const std::string& candidate : known) found = found || candidate == name;
        if (!found) throw InputError("unknown parameter " + quote_input(name, 40) + " (known here: " + joined(known) + ")");
    }
}

}  // namespace petroscope::serve
