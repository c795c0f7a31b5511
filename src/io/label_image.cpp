#include "petroscope/io/label_image.hpp"

#include "image_files.hpp"
#include "petroscope/core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>

namespace petroscope {
namespace {

std::string channel_words(int channels) {
    switch (channels) {
        case 2: return "2 channels (grey and alpha)";
        case 3: return "3 channels (colour, or a palette image)";
        case 4: return "4 channels (colour and alpha)";
        default: return std::to_string(channels) + " channels";
    }
}

}  // namespace

bool has_png_signature(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::array<char, 8> start{};
    if (!file.read(start.data(), start.size())) return false;
    return std::equal(start.begin(), start.end(), kPngSignature.begin(),
                      [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; });
}

LabelImage read_label_png(const std::filesystem::path& path) {
    const std::string shown = path.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw InputError("grain map " + shown + " does not exist or is not a file");
    if (!has_png_signature(path)) {
        throw InputError("grain map " + shown + " is not a PNG file (it does not start with the PNG signature 89 50 4E 47 0D 0A 1A 0A); "
                         "expected a single-channel 8- or 16-bit PNG of grain labels");
    }
    const DecodedImage decoded = read_image_file(path, "grain map");
    const int bits = decoded.bits_per_sample;
    if (decoded.channels != 1) {
        throw InputError("grain map " + shown + " has " + channel_words(decoded.channels) +
                         "; expected a single grey channel holding one label per pixel");
    }
    if (!((decoded.stored == SampleType::uint8 && bits == 8) || (decoded.stored == SampleType::uint16 && bits == 16))) {
        throw InputError("grain map " + shown + " has " + std::to_string(bits) + " bits per pixel; expected 8 or 16");
    }
    LabelImage image;
    image.width = decoded.width;
    image.height = decoded.height;
    image.bits = bits;
    // The decoded values are code / maximum code: exact enough to give the codes back.
    const double max_code = bits == 16 ? 65535.0 : 255.0;
    image.labels.resize(decoded.values.size());
    std::transform(decoded.values.begin(), decoded.values.end(), image.labels.begin(),
                   [max_code](float value) { return static_cast<std::uint16_t>(std::lround(value * max_code)); });
    return image;
}

void write_label_png(const std::vector<std::uint16_t>& labels, int width, int height, const std::filesystem::path& path) {
    const bool wide = std::any_of(labels.begin(), labels.end(), [](std::uint16_t label) { return label > 255; });
    if (wide) {
        write_png(path, width, height, 1, 16, labels.data(), false);
    } else {
        const std::vector<std::uint8_t> narrow(labels.begin(), labels.end());
        write_png(path, width, height, 1, 8, narrow.data(), false);
    }
}

FloatImage read_float_image(const std::filesystem::path& path) {
    const std::string shown = path.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw InputError("thickness map " + shown + " does not exist or is not a file");
    DecodedImage decoded = read_image_file(path, "thickness map");
    if (decoded.channels != 1) {
        throw InputError("thickness map " + shown + " has " + channel_words(decoded.channels) +
                         "; expected a single channel of thicknesses in micrometres");
    }
    if (decoded.stored != SampleType::half && decoded.stored != SampleType::float32 && decoded.stored != SampleType::float64) {
        throw InputError("thickness map " + shown + " holds " + sample_type_name(decoded.stored) +
                         " values; expected floating-point micrometres (e.g. a 32-bit float TIFF)");
    }
    FloatImage image;
    image.width = decoded.width;
    image.height = decoded.height;
    image.values = std::move(decoded.values);
    return image;
}

void write_float_tiff(const std::vector<float>& values, int width, int height, const std::filesystem::path& path) {
    write_tiff_float32(path, width, height, 1, values.data());
}

}  // namespace petroscope
