#include "petroscope/io/json_reader.hpp"

#include "petroscope/core/text.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope {

InputError JsonValue::error(const std::string& expected) const {
    return InputError(file_ + ": " + (path_.empty() ? std::string("(document)") : path_) + ": " + expected);
}

JsonValue JsonValue::operator[](const std::string& key) const {
    if (!value_.is_object()) throw error("expected an object with the key " + quote_input(key));
    const auto found = value_.find(key);
    const std::string child = path_.empty() ? key : path_ + "." + key;
    if (found == value_.end()) throw InputError(file_ + ": " + child + ": missing");
    return JsonValue(*found, file_, child);
}

JsonValue JsonValue::at(std::size_t index) const {
    if (!value_.is_array() || index >= value_.size()) throw error("expected an array with an element " + std::to_string(index));
    return JsonValue(value_[index], file_, path_ + "[" + std::to_string(index) + "]");
}

void JsonValue::only_keys(const std::vector<std::string>& allowed) const {
    if (!value_.is_object()) throw error("expected an object");
    for (const auto& item : value_.items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
        std::string list;
        for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
        throw error("unknown key " + quote_input(item.key()) + " (valid keys: " + list + ")");
    }
}

std::size_t JsonValue::size() const {
    if (!value_.is_array()) throw error("expected an array");
    return value_.size();
}

double JsonValue::number() const {
    if (!value_.is_number()) throw error("expected a number");
    const double value = value_.get<double>();
    if (!std::isfinite(value)) throw error("expected a finite number");
    return value;
}

std::complex<double> JsonValue::complex_number() const {
    if (value_.is_array()) {
        const std::vector<double> parts = numbers(2);
        return {parts[0], parts[1]};
    }
    if (!value_.is_number()) throw error("expected a number or a pair [real, imaginary]");
    return number();
}

std::string JsonValue::text() const {
    if (!value_.is_string()) throw error("expected a string");
    return value_.get<std::string>();
}

std::vector<double> JsonValue::numbers(std::size_t count) const {
    if (!value_.is_array() || value_.size() != count) throw error("expected an array of " + std::to_string(count) + " numbers");
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) values.push_back(at(i).number());
    return values;
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(file + ": invalid JSON at byte " + std::to_string(e.byte) + ": " + e.what());
    } catch (const nlohmann::json::exception& e) {
        // Valid syntax the reader cannot hold, e.g. a number beyond the range of a double (1e7451).
        throw InputError(file + ": unreadable JSON: " + e.what());
    }
}

}  // namespace petroscope
