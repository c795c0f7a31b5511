// Image files: what the formats share, the file's type by its signature, and read_image_file, which hands the
// file to its format's reader (image_file_png.cpp, image_file_tiff.cpp, image_file_exr.cpp, image_file_jpeg.cpp).
#include "image_files.hpp"

#include "image_file_formats.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <half.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <system_error>
#include <type_traits>

namespace petroscope {
namespace detail {
namespace {

// One sample as a float: an integer as code / maximum code, a float as it is.
template <typename Sample>
float sample_value(Sample sample) {
    if constexpr (std::is_integral_v<Sample>) {
        return static_cast<float>(sample / static_cast<double>(std::numeric_limits<Sample>::max()));
    } else {
        return static_cast<float>(sample);
    }
}

template <typename Sample>
void convert_run(const unsigned char* bytes, std::size_t count, float* target, std::size_t target_step) {
    for (std::size_t i = 0; i < count; ++i) {
        Sample sample;
        std::memcpy(&sample, bytes + i * sizeof(Sample), sizeof(Sample));
        target[i * target_step] = sample_value(sample);
    }
}

}  // namespace

[[noreturn]] void fail_writing(const std::filesystem::path& path, const std::string& reason) {
    throw InputError("cannot write " + path.string() + ": " + reason);
}

std::string errno_text(int number) { return std::generic_category().message(number); }

std::string library_message(std::string_view library, std::string_view message) {
    return std::string(library) + ": " + quote_input(message, 200);
}

FileHandle open_for_reading(const ReadSource& source) {
    FileHandle file(std::fopen(source.path.c_str(), "rb"));
    if (!file) source.fail(errno_text(errno));
    return file;
}

int sample_bits(SampleType type) {
    switch (type) {
        case SampleType::uint8: return 8;
        case SampleType::uint16: return 16;
        case SampleType::uint32: return 32;
        case SampleType::half: return 16;
        case SampleType::float32: return 32;
        case SampleType::float64: return 64;
    }
    return 8;
}

DecodedImage allocated_image(const ReadSource& source, std::int64_t width, std::int64_t height, int channels, SampleType stored) {
    constexpr std::int64_t kMaxValues = std::int64_t{1} << 31;
    if (width <= 0 || height <= 0) source.fail("the image has no pixels (" + std::to_string(width) + " x " + std::to_string(height) + ")");
    // Compared by division, so that no product can overflow: width < ⌊kMaxValues/(height·channels)⌋ holds
    // exactly when width·height·channels ≤ kMaxValues − height·channels.
    if (width >= kMaxValues || height >= kMaxValues || width >= kMaxValues / height / channels) {
        source.fail("the image is too large (" + std::to_string(width) + " x " + std::to_string(height) + " x " + std::to_string(channels) +
                    " values; fewer than 2^31 are read)");
    }
    DecodedImage image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.channels = channels;
    image.stored = stored;
    image.bits_per_sample = sample_bits(stored);
    image.values.resize(static_cast<std::size_t>(width * height * channels));
    return image;
}

void convert_samples(SampleType type, const unsigned char* bytes, std::size_t count, float* target, std::size_t target_step) {
    switch (type) {
        case SampleType::uint8: return convert_run<std::uint8_t>(bytes, count, target, target_step);
        case SampleType::uint16: return convert_run<std::uint16_t>(bytes, count, target, target_step);
        case SampleType::uint32: return convert_run<std::uint32_t>(bytes, count, target, target_step);
        case SampleType::half: return convert_run<Imath::half>(bytes, count, target, target_step);
        case SampleType::float32: return convert_run<float>(bytes, count, target, target_step);
        case SampleType::float64: return convert_run<double>(bytes, count, target, target_step);
    }
}

}  // namespace detail

std::string sample_type_name(SampleType type) {
    switch (type) {
        case SampleType::uint8: return "8-bit unsigned integer";
        case SampleType::uint16: return "16-bit unsigned integer";
        case SampleType::uint32: return "32-bit unsigned integer";
        case SampleType::half: return "16-bit float (half)";
        case SampleType::float32: return "32-bit float";
        case SampleType::float64: return "64-bit float";
    }
    return "unknown";
}

ImageFileType image_file_type_of(const std::filesystem::path& path, std::string_view what) {
    const detail::ReadSource source{path, what};
    const detail::FileHandle file = detail::open_for_reading(source);
    std::array<unsigned char, 8> start{};
    const std::size_t count = std::fread(start.data(), 1, start.size(), file.get());
    if (count < start.size() && std::ferror(file.get())) source.fail(detail::errno_text(errno));
    const auto starts_with = [&](const auto& signature) {
        return std::size(signature) <= count && std::equal(std::begin(signature), std::end(signature), start.begin());
    };
    // TIFF 6.0 §2: byte order "II" or "MM", then 42 (43: BigTIFF). OpenEXR: the magic number 20000630,
    // little-endian. JPEG (T.81 B.1.1.3): the SOI marker FF D8, then the next marker's FF.
    using Bytes = std::initializer_list<unsigned char>;
    if (starts_with(kPngSignature)) return ImageFileType::png;
    for (const unsigned char version : std::array<unsigned char, 2>{42, 43}) {
        if (starts_with(Bytes{'I', 'I', version, 0}) || starts_with(Bytes{'M', 'M', 0, version})) return ImageFileType::tiff;
    }
    if (starts_with(Bytes{0x76, 0x2F, 0x31, 0x01})) return ImageFileType::exr;
    if (starts_with(Bytes{0xFF, 0xD8, 0xFF})) return ImageFileType::jpeg;
    std::string shown;
    for (std::size_t i = 0; i < count; ++i) {
        std::array<char, 4> hex{};
        std::snprintf(hex.data(), hex.size(), "%02X", start[i]);
        shown += (i == 0 ? "" : " ") + std::string(hex.data());
    }
    source.fail(count == 0 ? "the file is empty; expected a PNG, TIFF, OpenEXR or JPEG image"
                           : "it is not a PNG, TIFF, OpenEXR or JPEG image (it starts with the bytes " + shown + ")");
}

DecodedImage read_image_file(const std::filesystem::path& path, std::string_view what) {
    const detail::ReadSource source{path, what};
    const ImageFileType type = image_file_type_of(path, what);
    if (type == ImageFileType::png) return detail::read_png(source);
    if (type == ImageFileType::tiff) return detail::read_tiff(source);
    if (type == ImageFileType::exr) return detail::read_exr(source);
    return detail::read_jpeg(source);
}

}  // namespace petroscope
