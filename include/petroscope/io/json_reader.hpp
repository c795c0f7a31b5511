#pragma once
// Reading JSON documents with errors that name the file and the key path ("case.json: incident.direction:
// expected an array of 3 numbers").
#include "petroscope/core/error.hpp"

#include <nlohmann/json.hpp>

#include <complex>
#include <string>

namespace petroscope {

/// A value inside a JSON document, with its file and key path for error messages.
class JsonValue {
public:
    JsonValue(const nlohmann::json& value, std::string file, std::string path) : value_(value), file_(std::move(file)), path_(std::move(path)) {}

    const nlohmann::json& raw() const { return value_; }
    const std::string& path() const { return path_; }
    bool has(const std::string& key) const { return value_.is_object() && value_.contains(key); }
    /// The member `key` of an object; throws naming the path when it is missing.
    JsonValue operator[](const std::string& key) const;
    JsonValue at(std::size_t index) const;

    double number() const;                       // finite
    std::complex<double> complex_number() const;  // a number, or [re, im]
    std::string text() const;
    /// An array of exactly `count` finite numbers.
    std::vector<double> numbers(std::size_t count) const;

    /// Throws naming the first key of this object not in `allowed` ("… unknown key 'x' (valid keys: …)").
    void only_keys(const std::vector<std::string>& allowed) const;
    /// The number of elements of an array (throws if not an array).
    std::size_t size() const;

    InputError error(const std::string& expected) const;

private:
    const nlohmann::json& value_;
    std::string file_, path_;
};

/// Parses JSON text; syntax errors name the file and the byte offset.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

}  // namespace petroscope
