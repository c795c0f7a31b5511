#pragma once
// Small text helpers shared by the parsers (mineral files, CSV tables, CLI values).
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

std::string_view trim(std::string_view text);
std::string to_lower(std::string_view text);
std::vector<std::string> split(std::string_view text, char separator);
/// Splits on runs of spaces and tabs.
std::vector<std::string> split_whitespace(std::string_view text);

/// Calls visit(line_number, line) for each line of `text` (numbered from 1, without the newline; a final
/// newline ends the last line rather than starting an empty one).
void for_each_line(std::string_view text, const std::function<void(int, std::string_view)>& visit);

/// The whole of `text` as a finite double, or nothing (no partial parses, no NaN/Inf).
std::optional<double> parse_double(std::string_view text);

/// The shortest text that reads back as `value` ("0.85", "1e-300").
std::string format_number(double value);

/// `value` rounded to `digits` significant digits ("%.*g"), for reports meant to be read.
std::string format_significant(double value, int digits);

/// "value +- sigma" with sigma rounded to two significant digits and value to the same decimal place
/// (the usual rule for a measurement and its uncertainty, e.g. "39.974 +- 0.048"); a zero or non-finite
/// sigma leaves the value at six significant digits.
std::string format_with_uncertainty(double value, double sigma);

/// `text` in single quotes, safe to print in a message to a terminal: control characters, bytes that are
/// not UTF-8 and Unicode's invisible line and direction controls come escaped (\n, \t, \x1b, \xff,
/// \u202e), and text beyond `max_characters` is cut ('abc…' (5000 bytes)). Every message that quotes
/// user input quotes it with this.
std::string quote_input(std::string_view text, std::size_t max_characters = 80);

/// Levenshtein edit distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace petroscope
