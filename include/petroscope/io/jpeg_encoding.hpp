#pragma once
// How a JPEG file was encoded, read from its quantization tables and frame header, and the same encoding
// applied to another image: the fit repeats a photo's encoding on its best-fit model to measure the
// systematic error the encoding causes (docs/fitting.md, "The photo's encoding").
#include "petroscope/core/image.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace petroscope {

struct JpegEncoding {
    int components = 3;       // 1: grayscale, 3: YCbCr
    int luma_quality = 0;     // the IJG quality (1 … 100) whose scaled Annex K table is nearest the file's
    int chroma_quality = 0;   //   … for the chroma table (equal to luma_quality for grayscale)
    bool standard_tables = false;  // both tables are exactly IJG-scaled Annex K tables at these qualities
    int chroma_step_x = 1;    // luma samples per chroma sample: 2 × 2 for 4:2:0, 1 × 1 for 4:4:4
    int chroma_step_y = 1;
};

/// "quality 85, 4:2:0" or "quality ≈ 90/88 (non-standard tables), 4:2:2".
std::string describe(const JpegEncoding& encoding);

/// The encoding of JPEG bytes; none when they are not a JPEG (no SOI marker). Throws InputError, naming
/// `source`, for a JPEG whose tables or frame header are missing or malformed.
std::optional<JpegEncoding> jpeg_encoding_of(std::span<const std::uint8_t> bytes, const std::string& source);

/// The encoding of the file at `path`; none when it is not a JPEG. Throws InputError naming the file.
std::optional<JpegEncoding> read_jpeg_encoding(const std::filesystem::path& path);

/// Whether encode_like_jpeg repeats `encoding` exactly: it writes libjpeg's standard tables at one
/// quality, with 4:2:0 chroma (OpenCV on Debian 12); other files get that at their luma quality.
bool reproducible(const JpegEncoding& encoding);

/// `camera_values` (0 … 1, 1 or 3 channels) quantised to 8 bits, JPEG-encoded as `encoding` says (or
/// the nearest, see reproducible) and decoded, as camera values 0 … 1 with the same channels.
Image encode_like_jpeg(const Image& camera_values, const JpegEncoding& encoding);

}  // namespace petroscope
