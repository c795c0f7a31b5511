#pragma once
// Image files through the format libraries themselves (libpng, libtiff, OpenEXR, libjpeg): decoding to
// float values with no colour or gamma conversion, and the few encodings petroscope writes. Every failure
// throws InputError naming the file; the libraries' own messages are caught, never printed.
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// The type of the samples as stored in the file.
enum class SampleType { uint8, uint16, uint32, half, float32, float64 };

/// "8-bit unsigned integer", "16-bit float (half)", …, for messages.
std::string sample_type_name(SampleType type);

struct DecodedImage {
    int width = 0, height = 0, channels = 0;  // channels: 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA
    SampleType stored = SampleType::uint8;
    int bits_per_sample = 8;  // as stored: 1, 2 or 4 for low-depth PNG grey and palette images, read as uint8
    // Integers as code / maximum code (uint8 / 255, uint16 / 65535, uint32 / 4294967295), floats as they
    // are; row-major, top row first, channels interleaved.
    std::vector<float> values;
};

enum class ImageFileType { png, tiff, exr, jpeg };

/// The 8 bytes every PNG file starts with (ISO/IEC 15948:2004, §5.2).
inline constexpr std::array<unsigned char, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

/// The file's type by its first bytes (its signature), whatever its name. Throws InputError "cannot read
/// <what> <path>: …" when the file cannot be opened or is none of the supported types (listing them).
ImageFileType image_file_type_of(const std::filesystem::path& path, std::string_view what = "image");

/// Reads a PNG, TIFF (first image), OpenEXR (first part) or JPEG file. Throws InputError "cannot read
/// <what> <path>: <reason>".
DecodedImage read_image_file(const std::filesystem::path& path, std::string_view what = "image");

/// Writes `samples` (width × height × channels, interleaved; std::uint8_t for bit_depth 8, std::uint16_t
/// in native byte order for 16) as a PNG of 1 to 4 channels, with an sRGB chunk when `srgb` is true.
/// Throws InputError "cannot write <path>: <reason>", as do the writers below.
void write_png(const std::filesystem::path& path, int width, int height, int channels, int bit_depth, const void* samples, bool srgb);

/// Writes a 32-bit float TIFF of 1 (grey) or 3 (RGB) channels, deflate-compressed.
void write_tiff_float32(const std::filesystem::path& path, int width, int height, int channels, const float* samples);

/// Writes an OpenEXR file of FLOAT channels Y (1 channel) or R, G, B (3 channels), ZIP-compressed.
void write_exr_float32(const std::filesystem::path& path, int width, int height, int channels, const float* samples);

}  // namespace petroscope
