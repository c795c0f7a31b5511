#include "petroscope/io/image_writer.hpp"

#include "image_files.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/spectral/color.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace petroscope {

ImageFormat image_format_for(const std::filesystem::path& path) {
    const std::string extension = to_lower(path.extension().string());
    if (extension == ".png") return ImageFormat::png;
    if (extension == ".exr") return ImageFormat::exr;
    if (extension == ".tif" || extension == ".tiff") return ImageFormat::tiff;
    throw InputError("output " + path.string() + ": unknown image type " + quote_input(extension) +
                     " (expected .png for viewing, or .exr, .tif, .tiff for float data)");
}

namespace {

// 8-bit sRGB code of a linear value, round(255·encode_srgb(clamp(v))), as the number of code boundaries
// at or below it: the same codes as evaluating the curve, at a fraction of the cost (a frame has 786k
// values). A table of the code at the start of each of 4096 equal bins leaves at most a few boundaries
// to step over.
struct SrgbCodeTable {
    static constexpr int kBins = 4096;
    std::vector<double> boundaries;  // the smallest value with code 1, 2, … 255
    std::vector<std::uint8_t> first_code;  // code of k/kBins, k = 0 … kBins

    SrgbCodeTable() {
        const auto code_of = [](double value) { return std::lround(255.0 * encode_srgb(value)); };
        for (long code = 1; code <= 255; ++code) {
            // Bisected to adjacent doubles (the curve rises).
            double low = 0.0, high = 1.0;
            while (std::nextafter(low, high) < high) {
                const double middle = 0.5 * (low + high);
                (code_of(middle) >= code ? high : low) = middle;
            }
            boundaries.push_back(high);
        }
        for (int k = 0; k <= kBins; ++k) first_code.push_back(count_up(0, static_cast<double>(k) / kBins));
    }

    std::uint8_t count_up(int code, double value) const {
        while (code < 255 && boundaries[static_cast<std::size_t>(code)] <= value) ++code;
        return static_cast<std::uint8_t>(code);
    }
};

std::uint8_t srgb_code(float linear) {
    static const SrgbCodeTable table;
    // Clamped to [0, 1], NaN to 0 (a NaN must not reach the integer conversion below).
    const double clamped = linear > 0.0f ? std::min(static_cast<double>(linear), 1.0) : 0.0;
    // clamped·kBins is exact (a power of two), so the bin starts at or below the value.
    const int bin = static_cast<int>(clamped * SrgbCodeTable::kBins);
    return table.count_up(table.first_code[static_cast<std::size_t>(bin)], clamped);
}

}  // namespace

void write_image(const Image& linear_rgb, const std::filesystem::path& path, ImageFormat format) {
    if (linear_rgb.channels != 3) throw InputError("internal: write_image expects 3 channels");
    if (format == ImageFormat::png) {
        std::vector<std::uint8_t> encoded(linear_rgb.pixels.size());
        std::transform(linear_rgb.pixels.begin(), linear_rgb.pixels.end(), encoded.begin(), srgb_code);
        // Every write and the close are checked (image_file_png.cpp): a short file is reported there.
        write_png(path, linear_rgb.width, linear_rgb.height, 3, 8, encoded.data(), true);
        return;
    }
    if (format == ImageFormat::exr) {
        write_exr_float32(path, linear_rgb.width, linear_rgb.height, 3, linear_rgb.pixels.data());
    } else {
        write_tiff_float32(path, linear_rgb.width, linear_rgb.height, 3, linear_rgb.pixels.data());
    }
    // Not every failed write is reported (OpenEXR writes its offset table from a destructor, which cannot
    // throw; libtiff's close returns nothing): read the file back whole, which fails on a truncated file.
    DecodedImage back;
    std::string reason;
    try {
        back = read_image_file(path);
    } catch (const InputError& error) {
        reason = error.what();
    }
    if (!reason.empty() || back.width != linear_rgb.width || back.height != linear_rgb.height || back.channels != 3) {
        throw InputError("cannot write " + path.string() + ": the file did not come out whole (is the disk full, or a file size limit set?)" +
                         (reason.empty() ? std::string() : " (" + reason + ")"));
    }
}

Image read_image(const std::filesystem::path& path) {
    DecodedImage decoded = read_image_file(path);
    Image image;
    image.width = decoded.width;
    image.height = decoded.height;
    image.channels = decoded.channels;
    image.pixels = std::move(decoded.values);
    return image;
}

}  // namespace petroscope
