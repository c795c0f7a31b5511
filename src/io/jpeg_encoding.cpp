#include "petroscope/io/jpeg_encoding.hpp"

#include "petroscope/core/error.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

namespace petroscope {
namespace {

using Table = std::array<int, 64>;

// The example quantization tables of ITU-T T.81 (1992), Annex K, Tables K.1 (luminance) and K.2
// (chrominance), in natural (row-major) order; libjpeg scales them by quality.
constexpr Table kAnnexKLuma{16, 11, 10, 16, 24,  40,  51,  61,  12, 12, 14, 19, 26,  58,  60,  55,
                            14, 13, 16, 24, 40,  57,  69,  56,  14, 17, 22, 29, 51,  87,  80,  62,
                            18, 22, 37, 56, 68,  109, 103, 77,  24, 35, 55, 64, 81,  104, 113, 92,
                            49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};
constexpr Table kAnnexKChroma{17, 18, 24, 47, 99, 99, 99, 99, 18, 21, 26, 66, 99, 99, 99, 99, 24, 26, 56, 99, 99, 99,
                              99, 99, 47, 66, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99,
                              99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99};

/// The natural index of each coefficient in the order a DQT segment stores them (T.81 Figure 5: the
/// zig-zag over anti-diagonals, starting right along the top row).
Table zigzag_order() {
    Table order{};
    int k = 0;
    for (int diagonal = 0; diagonal < 15; ++diagonal) {
        for (int i = 0; i <= diagonal; ++i) {
            const int row = diagonal % 2 == 0 ? diagonal - i : i;
            const int column = diagonal - row;
            if (row < 8 && column < 8) order[static_cast<std::size_t>(k++)] = 8 * row + column;
        }
    }
    return order;
}

/// libjpeg's table for `quality` (jcparam.c: scale 5000/q below 50, 200 − 2q from 50; entries rounded,
/// kept within 1 … 255 for baseline files).
Table scaled_table(const Table& base, int quality) {
    const int scale = quality < 50 ? 5000 / quality : 200 - 2 * quality;
    Table table{};
    for (std::size_t k = 0; k < table.size(); ++k) table[k] = std::clamp((base[k] * scale + 50) / 100, 1, 255);
    return table;
}

struct NearestQuality {
    int quality = 0;
    bool exact = false;
};

/// The quality whose scaled `base` is nearest `table` (natural order) in Σ|ln ratio|.
NearestQuality nearest_quality(const Table& table, const Table& base) {
    NearestQuality best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int quality = 1; quality <= 100; ++quality) {
        const Table scaled = scaled_table(base, quality);
        double distance = 0.0;
        for (std::size_t k = 0; k < table.size(); ++k) distance += std::abs(std::log(double(std::max(table[k], 1)) / scaled[k]));
        if (distance < best_distance) {
            best_distance = distance;
            best = {quality, table == scaled};
        }
    }
    return best;
}

struct FrameComponent {
    int sampling_x, sampling_y, table;
};

}  // namespace

std::string describe(const JpegEncoding& encoding) {
    std::string text = encoding.luma_quality == encoding.chroma_quality
                           ? "quality " + std::to_string(encoding.luma_quality)
                           : "luma quality " + std::to_string(encoding.luma_quality) + ", chroma quality " + std::to_string(encoding.chroma_quality);
    if (!encoding.standard_tables) text += " (nearest IJG quality: the file's tables are its own)";
    if (encoding.components == 1) return text + ", grayscale";
    if (encoding.chroma_step_x == 2 && encoding.chroma_step_y == 2) return text + ", 4:2:0";
    if (encoding.chroma_step_x == 2 && encoding.chroma_step_y == 1) return text + ", 4:2:2";
    if (encoding.chroma_step_x == 1 && encoding.chroma_step_y == 1) return text + ", 4:4:4";
    return text + ", chroma subsampled " + std::to_string(encoding.chroma_step_x) + "x" + std::to_string(encoding.chroma_step_y);
}

std::optional<JpegEncoding> jpeg_encoding_of(std::span<const std::uint8_t> bytes, const std::string& source) {
    if (bytes.size() < 2 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
    const auto malformed = [&](const std::string& what) { return InputError(source + ": not a readable JPEG: " + what); };
    std::array<std::optional<Table>, 4> tables;  // natural order
    std::vector<FrameComponent> components;
    const Table order = zigzag_order();
    std::size_t position = 2;
    while (position + 2 <= bytes.size()) {
        if (bytes[position] != 0xFF) throw malformed("expected a marker at byte " + std::to_string(position));
        const std::uint8_t marker = bytes[position + 1];
        if (marker == 0xFF) {  // a fill byte before a marker
            ++position;
            continue;
        }
        position += 2;
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // markers without a length
        if (marker == 0xD9 || marker == 0xDA) break;                           // end of image, start of scan
        if (position + 2 > bytes.size()) break;
        const std::size_t length = (std::size_t{bytes[position]} << 8) | bytes[position + 1];
        if (length < 2 || position + length > bytes.size()) {
            throw malformed("the segment of marker 0xFF" + std::to_string(marker) + " at byte " + std::to_string(position - 2) + " is truncated");
        }
        const std::span<const std::uint8_t> segment = bytes.subspan(position + 2, length - 2);
        if (marker == 0xDB) {  // DQT (T.81 B.2.4.1): Pq·16 + Tq, then 64 entries of 8 or 16 bits
            for (std::size_t i = 0; i < segment.size();) {
                const int precision_bytes = (segment[i] >> 4) == 0 ? 1 : 2, destination = segment[i] & 0x0F;
                ++i;
                if (destination > 3 || i + 64 * static_cast<std::size_t>(precision_bytes) > segment.size()) {
                    throw malformed("a quantization table is malformed");
                }
                Table table{};
                for (std::size_t k = 0; k < 64; ++k, i += static_cast<std::size_t>(precision_bytes)) {
                    table[static_cast<std::size_t>(order[k])] = precision_bytes == 1 ? segment[i] : (segment[i] << 8) | segment[i + 1];
                }
                tables[static_cast<std::size_t>(destination)] = table;
            }
        } else if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
            // SOFn (T.81 B.2.2): P, Y, X, Nf, then per component C, H·16 + V, Tq.
            if (segment.size() < 6 || segment.size() < 6 + 3 * std::size_t{segment[5]}) throw malformed("the frame header is truncated");
            components.clear();
            for (std::size_t c = 0; c < segment[5]; ++c) {
                const std::uint8_t sampling = segment[7 + 3 * c];
                components.push_back({sampling >> 4, sampling & 0x0F, segment[8 + 3 * c]});
            }
        }
        position += length;
    }
    if (components.empty()) throw malformed("no frame header before the image data");
    if (components.size() != 1 && components.size() != 3) {
        throw malformed(std::to_string(components.size()) + " colour components (expected 1 or 3)");
    }
    const auto table_of = [&](const FrameComponent& component) -> const Table& {
        if (component.table > 3 || !tables[static_cast<std::size_t>(component.table)]) throw malformed("a component's quantization table is missing");
        if (component.sampling_x < 1 || component.sampling_y < 1) throw malformed("a component's sampling factor is 0");
        return *tables[static_cast<std::size_t>(component.table)];
    };
    JpegEncoding encoding;
    encoding.components = static_cast<int>(components.size());
    const NearestQuality luma = nearest_quality(table_of(components[0]), kAnnexKLuma);
    NearestQuality chroma = luma;
    if (encoding.components == 3) {
        chroma = nearest_quality(table_of(components[1]), kAnnexKChroma);
        encoding.chroma_step_x = components[0].sampling_x / components[1].sampling_x;
        encoding.chroma_step_y = components[0].sampling_y / components[1].sampling_y;
    }
    encoding.luma_quality = luma.quality;
    encoding.chroma_quality = chroma.quality;
    encoding.standard_tables = luma.exact && chroma.exact;
    return encoding;
}

std::optional<JpegEncoding> read_jpeg_encoding(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError(path.string() + ": cannot open the file");
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    return jpeg_encoding_of(bytes, path.string());
}

bool reproducible(const JpegEncoding& encoding) {
    if (!encoding.standard_tables) return false;
    return encoding.components == 1 ||
           (encoding.chroma_step_x == 2 && encoding.chroma_step_y == 2 && encoding.luma_quality == encoding.chroma_quality);
}

Image encode_like_jpeg(const Image& camera_values, const JpegEncoding& encoding) {
    const bool grey = encoding.components == 1;
    const int width = camera_values.width, height = camera_values.height;
    cv::Mat eight(height, width, grey ? CV_8UC1 : CV_8UC3);
    const auto to_byte = [](double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (grey) {
                double sum = 0.0;
                for (int c = 0; c < camera_values.channels; ++c) sum += camera_values.at(x, y, c);
                eight.at<std::uint8_t>(y, x) = to_byte(sum / camera_values.channels);
                continue;
            }
            for (int c = 0; c < 3; ++c) eight.at<cv::Vec3b>(y, x)[2 - c] = to_byte(camera_values.at(x, y, std::min(c, camera_values.channels - 1)));
        }
    }
    // OpenCV's writer on libjpeg's version-62 interface (Debian 12) sets one quality for both tables and
    // subsamples chroma 4:2:0 (grfmt_jpeg.cpp, jpeg_set_defaults): other files get that at the luma quality.
    const std::vector<int> parameters{cv::IMWRITE_JPEG_QUALITY, encoding.luma_quality};
    std::vector<std::uint8_t> bytes;
    if (!cv::imencode(".jpg", eight, bytes, parameters)) throw InputError("cannot encode an image as JPEG (" + describe(encoding) + ")");
    const cv::Mat decoded = cv::imdecode(bytes, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
    if (decoded.empty()) throw InputError("cannot decode the JPEG just encoded (" + describe(encoding) + ")");
    Image out(width, height, camera_values.channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < out.channels; ++c) {
                const std::uint8_t value = grey ? decoded.at<std::uint8_t>(y, x) : decoded.at<cv::Vec3b>(y, x)[2 - std::min(c, 2)];
                out.at(x, y, c) = static_cast<float>(value / 255.0);
            }
        }
    }
    return out;
}

}  // namespace petroscope
