#include "petroscope/io/label_image.hpp"

#include "petroscope/core/error.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <string>

namespace petroscope {
namespace {

constexpr std::array<unsigned char, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

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
    auto input = OIIO::ImageInput::create("png");
    OIIO::ImageSpec spec;
    if (!input || !input->open(shown, spec)) {
        throw InputError("cannot read grain map " + shown + ": " + (input ? input->geterror() : OIIO::geterror()));
    }
    const int bits = spec.get_int_attribute("oiio:BitsPerSample", static_cast<int>(8 * spec.format.size()));
    if (spec.nchannels != 1) {
        throw InputError("grain map " + shown + " has " + channel_words(spec.nchannels) +
                         "; expected a single grey channel holding one label per pixel");
    }
    if (!((spec.format == OIIO::TypeDesc::UINT8 && bits == 8) || (spec.format == OIIO::TypeDesc::UINT16 && bits == 16))) {
        throw InputError("grain map " + shown + " has " + std::to_string(bits) + " bits per pixel; expected 8 or 16");
    }
    LabelImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.bits = bits;
    const std::size_t count = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    image.labels.resize(count);
    bool ok = false;
    if (bits == 16) {
        ok = input->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, image.labels.data());
    } else {
        std::vector<std::uint8_t> narrow(count);
        ok = input->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, narrow.data());
        std::copy(narrow.begin(), narrow.end(), image.labels.begin());
    }
    input->close();
    if (!ok) throw InputError("cannot read grain map " + shown + ": " + input->geterror());
    return image;
}

void write_label_png(const std::vector<std::uint16_t>& labels, int width, int height, const std::filesystem::path& path) {
    const std::string shown = path.string();
    auto output = OIIO::ImageOutput::create("png");
    if (!output) throw InputError("cannot write " + shown + ": no PNG writer (" + OIIO::geterror() + ")");
    const bool wide = std::any_of(labels.begin(), labels.end(), [](std::uint16_t label) { return label > 255; });
    OIIO::ImageSpec spec(width, height, 1, wide ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "petroscope");
    bool ok = output->open(shown, spec);
    if (ok && wide) {
        ok = output->write_image(OIIO::TypeDesc::UINT16, labels.data());
    } else if (ok) {
        std::vector<std::uint8_t> narrow(labels.begin(), labels.end());
        ok = output->write_image(OIIO::TypeDesc::UINT8, narrow.data());
    }
    ok = output->close() && ok;
    if (!ok) throw InputError("cannot write " + shown + ": " + output->geterror());
}

FloatImage read_float_image(const std::filesystem::path& path) {
    const std::string shown = path.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw InputError("thickness map " + shown + " does not exist or is not a file");
    auto input = OIIO::ImageInput::open(shown);
    if (!input) throw InputError("cannot read thickness map " + shown + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.nchannels != 1) {
        throw InputError("thickness map " + shown + " has " + channel_words(spec.nchannels) + "; expected a single channel of thicknesses in micrometres");
    }
    const auto base = spec.format.basetype;
    if (base != OIIO::TypeDesc::FLOAT && base != OIIO::TypeDesc::HALF && base != OIIO::TypeDesc::DOUBLE) {
        throw InputError("thickness map " + shown + " holds " + std::string(spec.format.c_str()) +
                         " values; expected floating-point micrometres (e.g. a 32-bit float TIFF)");
    }
    FloatImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.values.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height));
    const bool ok = input->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, image.values.data());
    input->close();
    if (!ok) throw InputError("cannot read thickness map " + shown + ": " + input->geterror());
    return image;
}

void write_float_tiff(const std::vector<float>& values, int width, int height, const std::filesystem::path& path) {
    const std::string shown = path.string();
    auto output = OIIO::ImageOutput::create("tiff");
    if (!output) throw InputError("cannot write " + shown + ": no TIFF writer (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
    spec.attribute("Software", "petroscope");
    spec.attribute("compression", "zip");
    bool ok = output->open(shown, spec) && output->write_image(OIIO::TypeDesc::FLOAT, values.data());
    ok = output->close() && ok;
    if (!ok) throw InputError("cannot write " + shown + ": " + output->geterror());
}

}  // namespace petroscope
