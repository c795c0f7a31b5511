// TIFF files (TIFF 6.0) through libtiff: reading the first image (read_tiff, for read_image_file) and
// write_tiff_float32.
#include "image_file_formats.hpp"
#include "image_files.hpp"

#include "petroscope/core/error.hpp"

#include <tiffio.h>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace petroscope {
namespace detail {
namespace {

// ---- TIFF (TIFF 6.0), through libtiff 4.5's per-handle message handlers: thread-safe, and nothing printed.

// Keeps a handle's first error in the std::string at `user_data`; 1 tells libtiff it was handled.
int keep_tiff_error(TIFF*, void* user_data, const char*, const char* format, va_list arguments) {
    auto* message = static_cast<std::string*>(user_data);
    if (message->empty()) {
        std::array<char, 512> text{};
        std::vsnprintf(text.data(), text.size(), format, arguments);
        *message = text.data();
    }
    return 1;
}

int ignore_tiff_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

using TiffHandle = std::unique_ptr<TIFF, decltype(&TIFFClose)>;

// Opens `path` (mode "r" or "w") with its errors kept in `message`, which must outlive the handle.
TiffHandle open_tiff(const std::filesystem::path& path, const char* mode, std::string& message) {
    const std::unique_ptr<TIFFOpenOptions, decltype(&TIFFOpenOptionsFree)> options(TIFFOpenOptionsAlloc(), TIFFOpenOptionsFree);
    if (!options) return {nullptr, TIFFClose};
    TIFFOpenOptionsSetErrorHandlerExtR(options.get(), keep_tiff_error, &message);
    TIFFOpenOptionsSetWarningHandlerExtR(options.get(), ignore_tiff_warning, nullptr);
    return {TIFFOpenExt(path.c_str(), mode, options.get()), TIFFClose};
}

std::string tiff_failure(const std::string& message) {
    return message.empty() ? "libtiff failed without giving a reason" : library_message("libtiff", message);
}

// The sample type from BitsPerSample (§8) and SampleFormat (§19).
SampleType tiff_sample_type(const ReadSource& source, TIFF* tiff) {
    std::uint16_t bits = 1, format = SAMPLEFORMAT_UINT;
    TIFFGetFieldDefaulted(tiff, TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLEFORMAT, &format);
    if (format == SAMPLEFORMAT_UINT && bits == 8) return SampleType::uint8;
    if (format == SAMPLEFORMAT_UINT && bits == 16) return SampleType::uint16;
    if (format == SAMPLEFORMAT_UINT && bits == 32) return SampleType::uint32;
    if (format == SAMPLEFORMAT_IEEEFP && bits == 16) return SampleType::half;
    if (format == SAMPLEFORMAT_IEEEFP && bits == 32) return SampleType::float32;
    if (format == SAMPLEFORMAT_IEEEFP && bits == 64) return SampleType::float64;
    const std::string kind = format == SAMPLEFORMAT_UINT ? "unsigned integers"
                             : format == SAMPLEFORMAT_INT ? "signed integers"
                             : format == SAMPLEFORMAT_IEEEFP ? "floats"
                                                             : "samples of format " + std::to_string(format);
    source.fail("its samples are " + std::to_string(bits) + "-bit " + kind +
                "; expected 8-, 16- or 32-bit unsigned integers, or 16-, 32- or 64-bit floats");
}

std::string photometric_name(std::uint16_t photometric) {
    switch (photometric) {
        case PHOTOMETRIC_MINISWHITE: return "min-is-white grey";
        case PHOTOMETRIC_MINISBLACK: return "min-is-black grey";
        case PHOTOMETRIC_RGB: return "RGB";
        case PHOTOMETRIC_PALETTE: return "palette colour";
        case PHOTOMETRIC_SEPARATED: return "separated (CMYK)";
        case PHOTOMETRIC_YCBCR: return "YCbCr";
        default: return "code " + std::to_string(photometric);
    }
}

// The channel count from SamplesPerPixel and PhotometricInterpretation (§8): grey (min-is-black) with an
// optional alpha, or RGB with an optional alpha. Min-is-white grey is refused rather than inverted.
int tiff_channels(const ReadSource& source, TIFF* tiff) {
    std::uint16_t samples = 1, photometric = 0;
    TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLESPERPIXEL, &samples);
    if (!TIFFGetField(tiff, TIFFTAG_PHOTOMETRIC, &photometric)) source.fail("it has no PhotometricInterpretation tag");
    const bool grey = photometric == PHOTOMETRIC_MINISBLACK && (samples == 1 || samples == 2);
    const bool colour = photometric == PHOTOMETRIC_RGB && (samples == 3 || samples == 4);
    if (!grey && !colour) {
        source.fail("its pixels are " + photometric_name(photometric) + ", SamplesPerPixel " + std::to_string(samples) +
                    "; expected min-is-black grey with 1 or 2 samples (grey, alpha), or RGB with 3 or 4 (RGB, alpha)");
    }
    return samples;
}

// Places a block of samples (a scanline or a tile) whose top-left pixel is (x, y), in rows of `block_width`
// pixels, clipped to the image: one plane of the image (PlanarConfiguration 2) or all its channels interleaved.
void place_tiff_block(DecodedImage& image, bool separate_planes, const std::vector<unsigned char>& block, std::size_t x, std::size_t y,
                      std::size_t block_width, std::size_t block_height, int plane) {
    const std::size_t channels = static_cast<std::size_t>(image.channels);
    const std::size_t block_samples_per_pixel = separate_planes ? 1 : channels;
    const std::size_t row_bytes = block_width * block_samples_per_pixel * static_cast<std::size_t>(sample_bits(image.stored) / 8);
    const std::size_t columns = std::min(block_width, static_cast<std::size_t>(image.width) - x);
    const std::size_t rows = std::min(block_height, static_cast<std::size_t>(image.height) - y);
    for (std::size_t row = 0; row < rows; ++row) {
        float* target = image.values.data() + ((y + row) * static_cast<std::size_t>(image.width) + x) * channels;
        if (separate_planes) target += plane;
        convert_samples(image.stored, block.data() + row * row_bytes, columns * block_samples_per_pixel, target,
                        separate_planes ? channels : 1);
    }
}

std::size_t tiff_row_bytes(const DecodedImage& image, std::size_t width, bool separate_planes) {
    return width * static_cast<std::size_t>((separate_planes ? 1 : image.channels) * sample_bits(image.stored) / 8);
}

bool read_tiff_scanlines(TIFF* tiff, bool separate_planes, DecodedImage& image) {
    const std::size_t width = static_cast<std::size_t>(image.width);
    std::vector<unsigned char> line(static_cast<std::size_t>(TIFFScanlineSize64(tiff)));
    if (line.size() < tiff_row_bytes(image, width, separate_planes)) return false;
    for (int plane = 0; plane < (separate_planes ? image.channels : 1); ++plane) {
        for (int y = 0; y < image.height; ++y) {
            if (TIFFReadScanline(tiff, line.data(), static_cast<std::uint32_t>(y), static_cast<std::uint16_t>(plane)) < 0) return false;
            place_tiff_block(image, separate_planes, line, 0, static_cast<std::size_t>(y), width, 1, plane);
        }
    }
    return true;
}

bool read_tiff_tiles(TIFF* tiff, bool separate_planes, DecodedImage& image) {
    std::uint32_t tile_width = 0, tile_height = 0;
    TIFFGetField(tiff, TIFFTAG_TILEWIDTH, &tile_width);
    TIFFGetField(tiff, TIFFTAG_TILELENGTH, &tile_height);
    std::vector<unsigned char> tile(static_cast<std::size_t>(TIFFTileSize64(tiff)));
    if (tile_width == 0 || tile_height == 0 || tile.size() < tiff_row_bytes(image, tile_width, separate_planes) * tile_height) return false;
    for (int plane = 0; plane < (separate_planes ? image.channels : 1); ++plane) {
        for (std::uint32_t y = 0; y < static_cast<std::uint32_t>(image.height); y += tile_height) {
            for (std::uint32_t x = 0; x < static_cast<std::uint32_t>(image.width); x += tile_width) {
                if (TIFFReadTile(tiff, tile.data(), x, y, 0, static_cast<std::uint16_t>(plane)) < 0) return false;
                place_tiff_block(image, separate_planes, tile, x, y, tile_width, tile_height, plane);
            }
        }
    }
    return true;
}

}  // namespace

// The first image of the file, in strips or tiles, its channels interleaved or in planes.
DecodedImage read_tiff(const ReadSource& source) {
    std::string message;
    const TiffHandle tiff = open_tiff(source.path, "r", message);
    if (!tiff) source.fail(tiff_failure(message));
    std::uint32_t width = 0, height = 0;
    std::uint16_t planar = PLANARCONFIG_CONTIG;
    TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width);
    TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_PLANARCONFIG, &planar);
    const SampleType stored = tiff_sample_type(source, tiff.get());
    DecodedImage image = allocated_image(source, width, height, tiff_channels(source, tiff.get()), stored);
    const bool separate_planes = planar == PLANARCONFIG_SEPARATE;
    const bool ok = TIFFIsTiled(tiff.get()) ? read_tiff_tiles(tiff.get(), separate_planes, image)
                                            : read_tiff_scanlines(tiff.get(), separate_planes, image);
    if (!ok) source.fail(tiff_failure(message));
    return image;
}

}  // namespace detail

void write_tiff_float32(const std::filesystem::path& path, int width, int height, int channels, const float* samples) {
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3)) {
        throw InputError("internal: write_tiff_float32 expects a non-empty image of 1 or 3 channels");
    }
    std::string message;
    const detail::TiffHandle tiff = detail::open_tiff(path, "w", message);
    if (!tiff) detail::fail_writing(path, detail::tiff_failure(message));
    // TIFF 6.0 §8 (baseline fields), §14 (Predictor: none), §19 (SampleFormat); Compression 8 is deflate
    // (Adobe's TIFF Technical Note, "Adobe Deflate").
    TIFFSetField(tiff.get(), TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(width));
    TIFFSetField(tiff.get(), TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(height));
    TIFFSetField(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, channels);
    TIFFSetField(tiff.get(), TIFFTAG_BITSPERSAMPLE, 32);
    TIFFSetField(tiff.get(), TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
    TIFFSetField(tiff.get(), TIFFTAG_PHOTOMETRIC, channels == 1 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB);
    TIFFSetField(tiff.get(), TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tiff.get(), TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(tiff.get(), TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tiff.get(), 0));
    TIFFSetField(tiff.get(), TIFFTAG_SOFTWARE, "petroscope");
    // libtiff may encode a row in place, so each goes through a copy.
    const std::size_t row_values = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
    std::vector<float> row(row_values);
    for (int y = 0; y < height; ++y) {
        std::copy_n(samples + static_cast<std::size_t>(y) * row_values, row_values, row.begin());
        if (TIFFWriteScanline(tiff.get(), row.data(), static_cast<std::uint32_t>(y), 0) < 0) {
            detail::fail_writing(path, detail::tiff_failure(message));
        }
    }
    if (!TIFFFlush(tiff.get())) detail::fail_writing(path, detail::tiff_failure(message));
}

}  // namespace petroscope
