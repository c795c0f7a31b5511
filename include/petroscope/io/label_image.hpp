#pragma once
// Single-channel images of integers and floats, read and written exactly (no colour conversion, no
// rescaling): grain maps (PNG labels) and thickness maps (float µm).
#include <cstdint>
#include <filesystem>
#include <vector>

namespace petroscope {

struct LabelImage {
    int width = 0, height = 0;
    int bits = 8;                       // 8 or 16, as stored
    std::vector<std::uint16_t> labels;  // row-major, top row first
};

/// Whether the file starts with the 8-byte PNG signature 89 50 4E 47 0D 0A 1A 0A (ISO/IEC 15948:2004,
/// §5.2), whatever its name.
bool has_png_signature(const std::filesystem::path& path);

/// A single-channel 8- or 16-bit PNG, its values unscaled. Throws InputError naming the file and what was
/// expected (not a PNG, colour or alpha channels, 1/2/4-bit or palette images).
LabelImage read_label_png(const std::filesystem::path& path);

/// Writes `labels` (width × height, row-major) as a grey PNG: 8-bit when every value is ≤ 255, else 16-bit.
void write_label_png(const std::vector<std::uint16_t>& labels, int width, int height, const std::filesystem::path& path);

struct FloatImage {
    int width = 0, height = 0;
    std::vector<float> values;  // row-major, top row first
};

/// A single-channel floating-point image (TIFF, OpenEXR): integer images are refused, since their values
/// would be rescaled to 0 … 1. Throws InputError naming the file.
FloatImage read_float_image(const std::filesystem::path& path);
/// Writes a single-channel 32-bit float TIFF (zip-compressed).
void write_float_tiff(const std::vector<float>& values, int width, int height, const std::filesystem::path& path);

}  // namespace petroscope
