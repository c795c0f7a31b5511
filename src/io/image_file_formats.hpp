#pragma once
// The pieces of image_files.cpp and image_file_<format>.cpp that more than one format uses: the file being read,
// failures and their messages, allocating and converting samples, and the per-format readers read_image_file calls.
#include "image_files.hpp"

#include "petroscope/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace petroscope::detail {

// A file being read: its errors read "cannot read <what> <path>: <reason>".
struct ReadSource {
    const std::filesystem::path& path;
    std::string_view what;

    [[noreturn]] void fail(const std::string& reason) const {
        throw InputError("cannot read " + std::string(what) + " " + path.string() + ": " + reason);
    }
};

[[noreturn]] void fail_writing(const std::filesystem::path& path, const std::string& reason);

std::string errno_text(int number);

// A format library's own message, quoted: it may carry text from the file.
std::string library_message(std::string_view library, std::string_view message);

struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FileHandle = std::unique_ptr<std::FILE, CloseFile>;

FileHandle open_for_reading(const ReadSource& source);

int sample_bits(SampleType type);

// An image of the given size with its values allocated. Fails on an empty image, and from 2^31 values (8 GiB
// of floats) on: such sizes come from damaged headers.
DecodedImage allocated_image(const ReadSource& source, std::int64_t width, std::int64_t height, int channels, SampleType stored);

// `count` samples of `type`, consecutive in native byte order from `bytes`, to target[0], target[step], ….
void convert_samples(SampleType type, const unsigned char* bytes, std::size_t count, float* target, std::size_t target_step);

// The readers read_image_file dispatches to, by the file's signature (image_file_type_of).
DecodedImage read_png(const ReadSource& source);
DecodedImage read_tiff(const ReadSource& source);
DecodedImage read_exr(const ReadSource& source);
DecodedImage read_jpeg(const ReadSource& source);

}  // namespace petroscope::detail
