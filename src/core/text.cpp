#include "petroscope/core/text.hpp"

#include "petroscope/core/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <utility>

namespace petroscope {

InputError located_error(const std::string& file, int line, const std::string& what) {
    return InputError(file + ":" + std::to_string(line) + ": " + what);
}

namespace {

/// The length of the UTF-8 sequence that starts `text` and its code point, or 0 when the bytes there are
/// not a well-formed sequence (RFC 3629, section 4: no overlong forms, no surrogates, at most U+10FFFF).
std::pair<std::size_t, char32_t> utf8_sequence(std::string_view text) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(0);
    std::size_t length = 0;
    char32_t code = 0, least = 0;
    if (lead < 0x80) return {1, lead};
    if (lead >= 0xC2 && lead <= 0xDF) length = 2, code = lead & 0x1Fu, least = 0x80;
    else if (lead >= 0xE0 && lead <= 0xEF) length = 3, code = lead & 0x0Fu, least = 0x800;
    else if (lead >= 0xF0 && lead <= 0xF4) length = 4, code = lead & 0x07u, least = 0x10000;
    else return {0, 0};
    if (text.size() < length) return {0, 0};
    for (std::size_t i = 1; i < length; ++i) {
        if ((byte(i) & 0xC0u) != 0x80u) return {0, 0};
        code = (code << 6) | (byte(i) & 0x3Fu);
    }
    if (code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return {0, 0};
    return {length, code};
}

/// Characters a terminal does not show as themselves: C0 and C1 controls, DEL, and the invisible
/// line separators and bidirectional controls of Unicode (U+2028/9, U+200E/F, U+202A…E, U+2066…9).
bool shown_escaped(char32_t code) {
    return code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0x200E || code == 0x200F || (code >= 0x2028 && code <= 0x202E) ||
           (code >= 0x2066 && code <= 0x2069);
}

void append_escape(std::string& out, char32_t code) {
    char buffer[12];
    switch (code) {
        case '\n': out += "\\n"; return;
        case '\r': out += "\\r"; return;
        case '\t': out += "\\t"; return;
        default: break;
    }
    if (code < 0x100) std::snprintf(buffer, sizeof buffer, "\\x%02x", static_cast<unsigned>(code));
    else std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(code));
    out += buffer;
}

}  // namespace

std::string quote_input(std::string_view text, std::size_t max_characters) {
    std::string out = "'";
    std::size_t at = 0, characters = 0;
    while (at < text.size() && characters < max_characters) {
        const auto [length, code] = utf8_sequence(text.substr(at));
        if (length == 0) {
            append_escape(out, static_cast<unsigned char>(text[at]));  // a byte that is not UTF-8
            at += 1;
        } else {
            if (shown_escaped(code)) append_escape(out, code);
            else out.append(text.substr(at, length));
            at += length;
        }
        ++characters;
    }
    out += "'";
    if (at < text.size()) {
        out.insert(out.size() - 1, "\u2026");  // an ellipsis inside the quotes: the text goes on
        out += " (" + std::to_string(text.size()) + " bytes)";
    }
    return out;
}

std::string_view trim(std::string_view text) {
    const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    return text;
}

std::string to_lower(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return lower;
}

std::vector<std::string> split(std::string_view text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        parts.emplace_back(trim(text.substr(start, end - start)));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return parts;
}

std::vector<std::string> split_whitespace(std::string_view text) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < text.size() && text[j] != ' ' && text[j] != '\t') ++j;
        if (j > i) words.emplace_back(text.substr(i, j - i));
        i = j;
    }
    return words;
}

void for_each_line(std::string_view text, const std::function<void(int, std::string_view)>& visit) {
    int line_number = 0;
    std::size_t position = 0;
    while (position < text.size()) {
        const std::size_t end = std::min(text.find('\n', position), text.size());
        visit(++line_number, text.substr(position, end - position));
        position = end + 1;
    }
}

std::optional<double> parse_double(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') {
        text.remove_prefix(1);
        if (!text.empty() && (text.front() == '-' || text.front() == '+')) return std::nullopt;  // "+-3"
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

std::string format_significant(double value, int digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    return text;
}

std::string format_with_uncertainty(double value, double sigma) {
    if (!(std::isfinite(sigma) && sigma > 0.0) || !std::isfinite(value))
        return format_significant(value, 6) + " +- " + format_significant(sigma, 6);
    // Decimal places that keep two significant digits of sigma; none when sigma >= 10.
    const int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(sigma))));
    char text[80];
    std::snprintf(text, sizeof text, "%.*f +- %.*f", decimals, value, decimals, sigma);
    return text;
}

std::string format_number(double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
            diagonal = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
        }
    }
    return row[b.size()];
}

}  // namespace petroscope
