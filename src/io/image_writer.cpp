#include "petroscope/io/image_writer.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/spectral/color.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

std::string image_format_name(ImageFormat format) {
    switch (format) {
        case ImageFormat::png: return "png";
        case ImageFormat::exr: return "openexr";
        case ImageFormat::tiff: return "tiff";
    }
    return "png";
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
    auto output = OIIO::ImageOutput::create(image_format_name(format));
    if (!output) throw InputError("cannot write " + path.string() + ": no " + image_format_name(format) + " writer (" + OIIO::geterror() + ")");
    const bool display = format == ImageFormat::png;
    OIIO::ImageSpec spec(linear_rgb.width, linear_rgb.height, 3, display ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    spec.attribute("Software", "petroscope");
    if (display) {
        spec.attribute("oiio:ColorSpace", "sRGB");
    } else {
        spec.attribute("oiio:ColorSpace", "linear");
        if (format == ImageFormat::tiff) spec.attribute("compression", "zip");
    }
    bool ok = output->open(path.string(), spec);
    if (ok && display) {
        std::vector<std::uint8_t> encoded(linear_rgb.pixels.size());
        std::transform(linear_rgb.pixels.begin(), linear_rgb.pixels.end(), encoded.begin(), srgb_code);
        ok = output->write_image(OIIO::TypeDesc::UINT8, encoded.data());
    } else if (ok) {
        ok = output->write_image(OIIO::TypeDesc::FLOAT, linear_rgb.pixels.data());
    }
    ok = output->close() && ok;
    if (!ok) throw InputError("cannot write " + path.string() + ": " + output->geterror());
    // The PNG writer does not report every failed write (a full disk, a file size limit): read the file
    // back whole, which fails on a truncated file.
    const auto check = OIIO::ImageInput::open(path.string());
    std::vector<float> back(linear_rgb.pixels.size());
    if (!check || check->spec().width != linear_rgb.width || check->spec().height != linear_rgb.height ||
        !check->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, back.data())) {
        const std::string reason = check ? check->geterror() : OIIO::geterror();
        throw InputError("cannot write " + path.string() + ": the file did not come out whole (is the disk full, or a file size limit set?)" +
                         (reason.empty() ? std::string() : " (" + reason + ")"));
    }
}

Image read_image(const std::filesystem::path& path) {
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) throw InputError("cannot read image " + path.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    Image image(spec.width, spec.height, spec.nchannels);
    const bool ok = input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data());
    input->close();
    if (!ok) throw InputError("cannot read image " + path.string() + ": " + input->geterror());
    return image;
}

}  // namespace petroscope
