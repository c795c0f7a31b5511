#include "petroscope/io/sweep_plan.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/grid_index.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace petroscope {
namespace {

struct NumberWithUnit {
    double value = 0.0;
    int decimals = 0;  // digits after the decimal point as written
    std::string unit;
};

NumberWithUnit parse_number_with_unit(std::string_view text, const std::string& whole) {
    const std::string_view trimmed = trim(text);
    std::size_t split_at = trimmed.size();
    while (split_at > 0 && !(std::isdigit(static_cast<unsigned char>(trimmed[split_at - 1])) || trimmed[split_at - 1] == '.')) --split_at;
    NumberWithUnit number;
    number.unit = std::string(trimmed.substr(split_at));
    const std::string_view digits = trimmed.substr(0, split_at);
    const auto value = parse_double(digits);
    if (!value || digits.find_first_of("eE") != std::string_view::npos) {
        throw InputError("--vary " + quote_input(whole) + ": " + quote_input(trimmed) + " is not a number (with an optional unit, e.g. 30 or 10um); expected NAME=START:END:STEP or NAME=V1,V2,…");
    }
    number.value = *value;
    const std::size_t point = digits.find('.');
    number.decimals = point == std::string_view::npos ? 0 : static_cast<int>(digits.size() - point - 1);
    return number;
}

// The one unit the numbers carry (those without one take it); two different units are an error.
std::string common_unit(const std::vector<NumberWithUnit>& numbers, const std::string& whole) {
    std::string unit;
    for (const NumberWithUnit& number : numbers) {
        if (number.unit.empty()) continue;
        if (!unit.empty() && unit != number.unit) {
            throw InputError("--vary " + quote_input(whole) + ": the numbers have different units (" + unit + ", " + number.unit + "); use one");
        }
        unit = number.unit;
    }
    return unit;
}

std::string format_fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    std::string result = text;
    if (result.find_first_not_of("-0.") == std::string::npos) result = decimals > 0 ? "0." + std::string(static_cast<std::size_t>(decimals), '0') : "0";
    return result;
}

}  // namespace

SweepParameter parse_sweep_parameter(std::string_view text, std::size_t max_values) {
    const std::string whole(text);
    const std::size_t equals = text.find('=');
    if (equals == std::string_view::npos) {
        throw InputError("--vary " + quote_input(whole) + ": expected NAME=START:END:STEP (e.g. azimuth-deg=0:360:5) or NAME=V1,V2,…");
    }
    SweepParameter parameter;
    parameter.name = std::string(trim(text.substr(0, equals)));
    if (parameter.name.starts_with("--")) parameter.name.erase(0, 2);
    if (parameter.name.empty()) throw InputError("--vary " + quote_input(whole) + ": the option name before '=' is missing");
    const std::string_view range = text.substr(equals + 1);
    if (range.find(':') == std::string_view::npos) {
        std::vector<NumberWithUnit> numbers;
        for (const std::string& part : split(range, ',')) numbers.push_back(parse_number_with_unit(part, whole));
        if (numbers.size() > max_values) throw InputError("--vary " + quote_input(whole) + ": more than " + std::to_string(max_values) + " values");
        const std::string unit = common_unit(numbers, whole);
        for (const NumberWithUnit& number : numbers) parameter.values.push_back(format_fixed(number.value, number.decimals) + unit);
        return parameter;
    }
    const std::vector<std::string> parts = split(range, ':');
    if (parts.size() != 3) throw InputError("--vary " + quote_input(whole) + ": expected START:END:STEP, three numbers separated by ':'");
    std::vector<NumberWithUnit> numbers;
    for (const std::string& part : parts) numbers.push_back(parse_number_with_unit(part, whole));
    const std::string unit = common_unit(numbers, whole);
    const NumberWithUnit &start = numbers[0], &end = numbers[1], &step = numbers[2];
    if (step.value == 0.0) throw InputError("--vary " + quote_input(whole) + ": the step is zero");
    const double steps = (end.value - start.value) / step.value;
    if (steps < -1e-9) {
        throw InputError("--vary " + quote_input(whole) + ": the step " + parts[2] + " leads away from the end " + parts[1] + " (use a " +
                         (step.value > 0 ? "negative" : "positive") + " step)");
    }
    if (steps + 1.0 > static_cast<double>(max_values)) {
        throw InputError("--vary " + quote_input(whole) + ": more than " + std::to_string(max_values) + " values");
    }
    const std::size_t count = static_cast<std::size_t>(std::floor(steps + 1e-9)) + 1;
    const int decimals = std::max(start.decimals, step.decimals);
    for (std::size_t i = 0; i < count; ++i) {
        parameter.values.push_back(format_fixed(start.value + static_cast<double>(i) * step.value, decimals) + unit);
    }
    return parameter;
}

SweepShard parse_sweep_shard(std::string_view text) {
    const std::vector<std::string> parts = split(text, '/');
    const auto whole_number = [](const std::string& part) -> int {
        const auto value = parse_double(part);
        return value && *value == std::floor(*value) && *value >= 1 && *value <= 1e6 ? static_cast<int>(*value) : 0;
    };
    if (parts.size() == 2) {
        const int index = whole_number(parts[0]), count = whole_number(parts[1]);
        if (index >= 1 && count >= 1 && index <= count) return {index, count};
    }
    throw InputError("--shard " + quote_input(text) + ": expected K/N with 1 <= K <= N, e.g. 2/8");
}

std::size_t SweepPlan::frame_count() const {
    std::size_t count = 1;
    for (const SweepParameter& parameter : parameters) count *= parameter.values.size();
    return count;
}

std::vector<std::string> SweepPlan::values_of(std::size_t frame) const {
    std::vector<std::size_t> counts;
    for (const SweepParameter& parameter : parameters) counts.push_back(parameter.values.size());
    const std::vector<std::size_t> indices = grid_indices(frame, counts);
    std::vector<std::string> values(parameters.size());
    for (std::size_t k = 0; k < parameters.size(); ++k) values[k] = parameters[k].values[indices[k]];
    return values;
}

std::string SweepPlan::label(std::size_t frame) const {
    const std::vector<std::string> values = values_of(frame);
    std::string text;
    for (std::size_t k = 0; k < parameters.size(); ++k) text += (k ? ", " : "") + parameters[k].name + " " + values[k];
    return text;
}

std::string SweepPlan::frame_name(std::size_t frame) const {
    const std::size_t digits = std::max<std::size_t>(4, std::to_string(frame_count() > 0 ? frame_count() - 1 : 0).size());
    std::string number = std::to_string(frame);
    return "frame_" + std::string(digits - std::min(digits, number.size()), '0') + number + ".png";
}

std::vector<std::string> SweepPlan::frame_arguments(std::size_t frame) const {
    std::vector<std::string> result = arguments;
    const std::vector<std::string> values = values_of(frame);
    for (std::size_t k = 0; k < parameters.size(); ++k) {
        result.push_back("--" + parameters[k].name);
        result.push_back(values[k]);
    }
    return result;
}

int SweepPlan::sheet_columns() const {
    if (columns > 0) return columns;
    if (parameters.size() == 2) return static_cast<int>(parameters[1].values.size());
    return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(frame_count()))));
}

nlohmann::json SweepPlan::to_json() const {
    nlohmann::json swept = nlohmann::json::array();
    for (const SweepParameter& parameter : parameters) swept.push_back({{"name", parameter.name}, {"values", parameter.values}});
    return {{"program", "petroscope 0.1.0"}, {"command", command}, {"arguments", arguments}, {"vary", swept},
            {"frames", frame_count()}, {"sheet", {{"columns", columns}, {"thumbnail_px", thumbnail_px}}},
            {"animation", {{"format", animation}, {"fps", fps}}}};
}

SweepPlan SweepPlan::from_json(const nlohmann::json& document, const std::string& file) {
    const JsonValue root(document, file, "");
    SweepPlan plan;
    plan.command = root["command"].text();
    const JsonValue arguments = root["arguments"];
    if (!arguments.raw().is_array()) throw arguments.error("an array of strings");
    for (std::size_t i = 0; i < arguments.raw().size(); ++i) plan.arguments.push_back(arguments.at(i).text());
    const JsonValue swept = root["vary"];
    if (!swept.raw().is_array() || swept.raw().empty() || swept.raw().size() > 2) throw swept.error("an array of one or two parameters");
    for (std::size_t i = 0; i < swept.raw().size(); ++i) {
        SweepParameter parameter{swept.at(i)["name"].text(), {}};
        const JsonValue values = swept.at(i)["values"];
        if (!values.raw().is_array() || values.raw().empty()) throw values.error("a non-empty array of strings");
        for (std::size_t j = 0; j < values.raw().size(); ++j) parameter.values.push_back(values.at(j).text());
        plan.parameters.push_back(std::move(parameter));
    }
    plan.columns = static_cast<int>(root["sheet"]["columns"].number());
    plan.thumbnail_px = static_cast<int>(root["sheet"]["thumbnail_px"].number());
    plan.animation = root["animation"]["format"].text();
    plan.fps = root["animation"]["fps"].number();
    if (static_cast<double>(plan.frame_count()) != root["frames"].number()) throw root["frames"].error("the number of frames of the grid");
    return plan;
}

}  // namespace petroscope
