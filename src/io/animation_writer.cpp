#include "animation_writer.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace petroscope {
namespace {

void put_u16(std::ofstream& out, int value) {
    out.put(static_cast<char>(value & 0xff));
    out.put(static_cast<char>((value >> 8) & 0xff));
}

struct Box {
    std::array<int, 3> low{0, 0, 0}, high{31, 31, 31};  // inclusive, in 5-bit units, channels R, G, B
};

}  // namespace

PalettedImage median_cut_palette(const cv::Mat& bgr) {
    constexpr int bins = 32 * 32 * 32;
    const auto bin_of = [](int r, int g, int b) { return (r << 10) | (g << 5) | b; };
    std::vector<std::uint32_t> histogram(bins, 0);
    std::vector<std::array<std::uint64_t, 3>> colour_sums(bins, {0, 0, 0});  // of the pixels in each bin, R, G, B
    for (int y = 0; y < bgr.rows; ++y) {
        const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            const auto bin = static_cast<std::size_t>(bin_of(row[x][2] >> 3, row[x][1] >> 3, row[x][0] >> 3));
            ++histogram[bin];
            for (int c = 0; c < 3; ++c) colour_sums[bin][static_cast<std::size_t>(c)] += row[x][2 - c];
        }
    }
    const auto count_in = [&](const Box& box) {
        std::uint64_t count = 0;
        for (int r = box.low[0]; r <= box.high[0]; ++r)
            for (int g = box.low[1]; g <= box.high[1]; ++g)
                for (int b = box.low[2]; b <= box.high[2]; ++b) count += histogram[static_cast<std::size_t>(bin_of(r, g, b))];
        return count;
    };
    // Shrink a box to the occupied bins.
    const auto shrink = [&](Box box) {
        Box tight{{31, 31, 31}, {0, 0, 0}};
        for (int r = box.low[0]; r <= box.high[0]; ++r)
            for (int g = box.low[1]; g <= box.high[1]; ++g)
                for (int b = box.low[2]; b <= box.high[2]; ++b) {
                    if (histogram[static_cast<std::size_t>(bin_of(r, g, b))] == 0) continue;
                    const std::array<int, 3> point{r, g, b};
                    for (int c = 0; c < 3; ++c) {
                        tight.low[c] = std::min(tight.low[c], point[c]);
                        tight.high[c] = std::max(tight.high[c], point[c]);
                    }
                }
        return tight.low[0] > tight.high[0] ? box : tight;
    };
    std::vector<Box> boxes{shrink(Box{})};
    std::vector<std::uint64_t> populations{count_in(boxes.front())};
    while (boxes.size() < 256) {
        // Split the box whose population times longest side is largest (ties: the first) at the median of its
        // population along that side.
        std::size_t chosen = boxes.size();
        int axis = 0;
        double largest = 0.0;
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            const double population = static_cast<double>(populations[k]);
            for (int c = 0; c < 3; ++c) {
                const int side = boxes[k].high[c] - boxes[k].low[c];
                if (side > 0 && population * side > largest) largest = population * side, axis = c, chosen = k;
            }
        }
        if (chosen == boxes.size()) break;  // every box is a single bin
        const Box box = boxes[chosen];
        const std::uint64_t half = populations[chosen] / 2;
        std::uint64_t running = 0;
        int cut = box.low[axis];
        for (; cut < box.high[axis]; ++cut) {
            Box slab = box;
            slab.low[axis] = slab.high[axis] = cut;
            running += count_in(slab);
            if (running >= half) break;
        }
        cut = std::min(cut, box.high[axis] - 1);
        Box lower = box, upper = box;
        lower.high[axis] = cut;
        upper.low[axis] = cut + 1;
        boxes[chosen] = shrink(lower);
        boxes.push_back(shrink(upper));
        populations[chosen] = count_in(boxes[chosen]);
        populations.push_back(count_in(boxes.back()));
    }
    // Each box's colour is the mean of the pixels in it.
    PalettedImage result;
    result.palette_rgb.assign(256 * 3, 0);
    std::vector<std::uint8_t> bin_index(bins, 0);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        std::array<std::uint64_t, 3> sum{0, 0, 0};
        std::uint64_t count = 0;
        const Box& box = boxes[k];
        for (int r = box.low[0]; r <= box.high[0]; ++r)
            for (int g = box.low[1]; g <= box.high[1]; ++g)
                for (int b = box.low[2]; b <= box.high[2]; ++b) {
                    const auto bin = static_cast<std::size_t>(bin_of(r, g, b));
                    count += histogram[bin];
                    for (std::size_t c = 0; c < 3; ++c) sum[c] += colour_sums[bin][c];
                }
        for (std::size_t c = 0; c < 3; ++c) result.palette_rgb[3 * k + c] = static_cast<std::uint8_t>(count > 0 ? (sum[c] + count / 2) / count : 0);
    }
    // Every occupied bin takes the palette colour nearest its pixels' mean (a box's mean can lie far from
    // the sparse corners of a large box).
    for (std::size_t bin = 0; bin < static_cast<std::size_t>(bins); ++bin) {
        if (histogram[bin] == 0) continue;
        int best_distance = 1 << 30;
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            int distance = 0;
            for (std::size_t c = 0; c < 3; ++c) {
                const int difference = static_cast<int>(colour_sums[bin][c] / histogram[bin]) - result.palette_rgb[3 * k + c];
                distance += difference * difference;
            }
            if (distance < best_distance) best_distance = distance, bin_index[bin] = static_cast<std::uint8_t>(k);
        }
    }
    result.indices.resize(static_cast<std::size_t>(bgr.rows) * bgr.cols);
    for (int y = 0; y < bgr.rows; ++y) {
        const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            result.indices[static_cast<std::size_t>(y) * bgr.cols + x] = bin_index[static_cast<std::size_t>(bin_of(row[x][2] >> 3, row[x][1] >> 3, row[x][0] >> 3))];
        }
    }
    return result;
}

std::vector<std::uint8_t> gif_lzw_encode(const std::vector<std::uint8_t>& indices) {
    constexpr int clear_code = 256, end_code = 257, max_code = 4096;
    std::vector<std::uint8_t> bytes;
    std::uint32_t buffer = 0;
    int buffered_bits = 0;
    int code_size = 9;
    const auto emit = [&](int code) {
        buffer |= static_cast<std::uint32_t>(code) << buffered_bits;
        buffered_bits += code_size;
        while (buffered_bits >= 8) {
            bytes.push_back(static_cast<std::uint8_t>(buffer & 0xff));
            buffer >>= 8;
            buffered_bits -= 8;
        }
    };
    std::unordered_map<std::uint32_t, int> table;  // (prefix code << 8 | symbol) → code
    int next_code = end_code + 1;
    emit(clear_code);
    if (!indices.empty()) {
        int prefix = indices[0];
        for (std::size_t i = 1; i < indices.size(); ++i) {
            const std::uint32_t key = static_cast<std::uint32_t>(prefix) << 8 | indices[i];
            const auto found = table.find(key);
            if (found != table.end()) {
                prefix = found->second;
                continue;
            }
            emit(prefix);
            // Codes widen by a bit once the new entry no longer fits; a full table (4096 codes) starts over.
            if (next_code == (1 << code_size)) ++code_size;
            table.emplace(key, next_code++);
            if (next_code == max_code) {
                emit(clear_code);
                table.clear();
                next_code = end_code + 1;
                code_size = 9;
            }
            prefix = indices[i];
        }
        emit(prefix);
    }
    emit(end_code);
    if (buffered_bits > 0) bytes.push_back(static_cast<std::uint8_t>(buffer & 0xff));
    return bytes;
}

AnimationWriter::AnimationWriter(const std::filesystem::path& path, const std::string& format, double fps, int width, int height)
    : path_(path), format_(format), width_(width), height_(height) {
    if (!(fps > 0.0 && fps <= 100.0)) throw InputError("animation frame rate " + std::to_string(fps) + " is out of range (0 < fps <= 100)");
    if (format == "gif") {
        delay_centiseconds_ = std::max(2, static_cast<int>(std::lround(100.0 / fps)));
        gif_.open(path, std::ios::binary);
        if (!gif_) throw InputError("cannot write the animation " + path.string());
        gif_.write("GIF89a", 6);
        put_u16(gif_, width);
        put_u16(gif_, height);
        gif_.put(0);  // no global colour table
        gif_.put(0);
        gif_.put(0);
        // NETSCAPE2.0 application extension: loop forever.
        const unsigned char loop[] = {0x21, 0xff, 0x0b, 'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0', 0x03, 0x01, 0x00, 0x00, 0x00};
        gif_.write(reinterpret_cast<const char*>(loop), sizeof loop);
    } else if (format == "mp4") {
        // FFmpeg picks the container by the extension, so the video goes to a sibling ending in .mp4 first.
        video_path_ = path.string() + ".mp4";
        video_.open(video_path_.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps, cv::Size(width, height));
        if (!video_.isOpened()) throw InputError("cannot open an MP4 writer for " + path.string() + " (OpenCV built without FFmpeg?)");
    } else {
        throw InputError("animation format " + quote_input(format) + ": expected gif, mp4 or none");
    }
}

std::vector<std::uint8_t> AnimationWriter::prepare(const cv::Mat& bgr) const {
    if (format_ != "gif") return {};
    const PalettedImage paletted = median_cut_palette(bgr);
    // Graphic control extension (the frame's delay), image descriptor with a 256-entry local colour table,
    // LZW minimum code size 8, the code stream in sub-blocks of at most 255 bytes, a zero-length block.
    std::vector<std::uint8_t> bytes{0x21, 0xf9, 0x04, 0x04, static_cast<std::uint8_t>(delay_centiseconds_ & 0xff),
                                    static_cast<std::uint8_t>(delay_centiseconds_ >> 8), 0x00, 0x00, 0x2c, 0, 0, 0, 0,
                                    static_cast<std::uint8_t>(width_ & 0xff), static_cast<std::uint8_t>(width_ >> 8),
                                    static_cast<std::uint8_t>(height_ & 0xff), static_cast<std::uint8_t>(height_ >> 8), 0x87};
    bytes.insert(bytes.end(), paletted.palette_rgb.begin(), paletted.palette_rgb.end());
    bytes.push_back(8);
    const std::vector<std::uint8_t> stream = gif_lzw_encode(paletted.indices);
    for (std::size_t offset = 0; offset < stream.size(); offset += 255) {
        const std::size_t length = std::min<std::size_t>(255, stream.size() - offset);
        bytes.push_back(static_cast<std::uint8_t>(length));
        bytes.insert(bytes.end(), stream.begin() + static_cast<std::ptrdiff_t>(offset), stream.begin() + static_cast<std::ptrdiff_t>(offset + length));
    }
    bytes.push_back(0);
    return bytes;
}

void AnimationWriter::add(const cv::Mat& bgr, const std::vector<std::uint8_t>& prepared) {
    if (format_ == "gif") {
        gif_.write(reinterpret_cast<const char*>(prepared.data()), static_cast<std::streamsize>(prepared.size()));
    } else {
        video_.write(bgr);
    }
}

void AnimationWriter::finish() {
    if (format_ == "gif") {
        gif_.put(0x3b);
        gif_.close();
        if (!gif_) throw InputError("cannot write the animation " + path_.string());
        return;
    }
    video_.release();
    std::error_code error;
    std::filesystem::rename(video_path_, path_, error);
    if (error) throw InputError("cannot write the animation " + path_.string() + ": " + error.message());
}

}  // namespace petroscope
