#pragma once
// The parameters of one request to the live microscope's server (`petroscope serve`): names and values
// from the URL's query, read as numbers, names and choices with the same limits as the command line. Every
// error is an InputError that names the parameter, quotes the value safely and says what was expected.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope::serve {

class QueryParameters {
public:
    QueryParameters() = default;
    /// Throws InputError for a name given twice.
    explicit QueryParameters(const std::vector<std::pair<std::string, std::string>>& pairs);

    bool has(std::string_view name) const { return values_.find(std::string(name)) != values_.end(); }
    std::optional<std::string> text(std::string_view name) const;
    std::string text_or(std::string_view name, std::string fallback) const;
    /// A finite number in [minimum, maximum]; `fallback` when absent.
    double number(std::string_view name, double minimum, double maximum, double fallback) const;
    std::optional<double> optional_number(std::string_view name, double minimum, double maximum) const;
    /// An integer in [minimum, maximum]; `fallback` when absent.
    long long integer(std::string_view name, long long minimum, long long maximum, long long fallback) const;
    /// One of `choices`, the first when absent.
    std::string choice(std::string_view name, const std::vector<std::string>& choices) const;
    /// Throws InputError naming the first parameter not in `known`, and listing those.
    void refuse_unknown(const std::vector<std::string>& known) const;

private:
    std::map<std::string, std::string, std::less<>> values_;
};

/// "parameter 'NAME': MESSAGE", the name quoted safely.
std::string parameter_message(std::string_view name, std::string_view message);

}  // namespace petroscope::serve
