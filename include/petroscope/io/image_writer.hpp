#pragma once
// Writing images: PNG (8-bit sRGB, for viewing), OpenEXR and TIFF (32-bit float, linear, for numbers).
#include "petroscope/core/image.hpp"

#include <filesystem>

namespace petroscope {

enum class ImageFormat { png, exr, tiff };

/// The format for an output file name by its extension (.png, .exr, .tif, .tiff); throws InputError.
ImageFormat image_format_for(const std::filesystem::path& path);

/// Writes `linear_rgb` (3 channels, linear, 1 = white) to `path` in `format`; PNG values are clamped to
/// [0, 1] and sRGB-encoded. Throws InputError naming the file on any failure.
void write_image(const Image& linear_rgb, const std::filesystem::path& path, ImageFormat format);

/// Reads an image as float values (for tests and tools); throws InputError.
Image read_image(const std::filesystem::path& path);

}  // namespace petroscope
