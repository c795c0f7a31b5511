// OpenEXR files (the OpenEXR file layout) through the OpenEXR library: reading the first part (read_exr, for
// read_image_file) and write_exr_float32.
#include "image_file_formats.hpp"
#include "image_files.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace petroscope {
namespace detail {
namespace {

// ---- OpenEXR (the OpenEXR file layout; channel naming after "Technical Introduction to OpenEXR"), through
// its C++ library, whose errors are exceptions.

// The channels read, in order: R, G, B with an optional A, luminance Y with an optional A, or the one
// channel of a single-channel file whatever its name (a thickness map's "Z" or "thickness").
std::vector<std::string> exr_channel_order(const ReadSource& source, const Imf::ChannelList& list) {
    std::vector<std::string> names;
    for (auto channel = list.begin(); channel != list.end(); ++channel) names.emplace_back(channel.name());
    if (names.size() == 1) return names;
    const std::array<std::vector<std::string>, 4> orders{{{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}}};
    for (const auto& order : orders) {
        if (std::is_permutation(order.begin(), order.end(), names.begin(), names.end())) return order;
    }
    std::string listed;
    for (const std::string& name : names) listed += (listed.empty() ? "" : ", ") + name;
    source.fail("its channels are " + quote_input(listed, 200) + "; expected R, G, B (and A), Y (and A) or a single channel");
}

// The stored type of an OpenEXR channel (UINT, HALF or FLOAT).
SampleType exr_sample_type(Imf::PixelType type) {
    if (type == Imf::UINT) return SampleType::uint32;
    return type == Imf::HALF ? SampleType::half : SampleType::float32;
}

// The data window's pixels, read as FLOAT whatever the stored type (the library converts; UINT channels are
// then scaled to code / maximum code); the stored type reported is that of the first channel (R or Y).
DecodedImage read_exr_pixels(const ReadSource& source, Imf::InputFile& file) {
    const Imf::ChannelList& list = file.header().channels();
    const Imath::Box2i window = file.header().dataWindow();
    const std::vector<std::string> order = exr_channel_order(source, list);
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1, height = std::int64_t{window.max.y} - window.min.y + 1;
    const std::size_t channels = order.size();
    DecodedImage image = allocated_image(source, width, height, static_cast<int>(channels), exr_sample_type(list[order.front()].type));
    const std::size_t pixel_bytes = channels * sizeof(float), row_bytes = pixel_bytes * static_cast<std::size_t>(width);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < channels; ++c) {
        if (list[order[c]].xSampling != 1 || list[order[c]].ySampling != 1) source.fail("its channel " + order[c] + " is subsampled");
        frame.insert(order[c], Imf::Slice::Make(Imf::FLOAT, image.values.data() + c, window, pixel_bytes, row_bytes));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    for (std::size_t c = 0; c < channels; ++c) {
        if (list[order[c]].type != Imf::UINT) continue;
        for (std::size_t i = c; i < image.values.size(); i += channels) {
            image.values[i] = static_cast<float>(image.values[i] / static_cast<double>(std::numeric_limits<std::uint32_t>::max()));
        }
    }
    return image;
}

}  // namespace

DecodedImage read_exr(const ReadSource& source) {
    try {
        Imf::InputFile file(source.path.c_str());
        return read_exr_pixels(source, file);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& error) {
        source.fail(library_message("OpenEXR", error.what()));
    }
}

}  // namespace detail

void write_exr_float32(const std::filesystem::path& path, int width, int height, int channels, const float* samples) {
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3)) {
        throw InputError("internal: write_exr_float32 expects a non-empty image of 1 or 3 channels");
    }
    const std::vector<std::string> names = channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
    const std::size_t pixel_bytes = static_cast<std::size_t>(channels) * sizeof(float);
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer frame;
        for (int c = 0; c < channels; ++c) {
            const std::string& name = names[static_cast<std::size_t>(c)];
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            frame.insert(name, Imf::Slice::Make(Imf::FLOAT, samples + c, Imath::V2i(0, 0), width, height, pixel_bytes,
                                                pixel_bytes * static_cast<std::size_t>(width)));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(height);
    } catch (const std::exception& error) {
        detail::fail_writing(path, detail::library_message("OpenEXR", error.what()));
    }
}

}  // namespace petroscope
