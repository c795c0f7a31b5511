#pragma once
// A sweep's animation: an animated GIF (own encoder: GIF89a, LZW, a median-cut palette per frame, looping)
// or an MP4 (OpenCV's VideoWriter, MPEG-4 part 2).
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace petroscope {

class AnimationWriter {
public:
    /// `format` is "gif" or "mp4"; frames are width × height, 8-bit BGR. Throws InputError.
    AnimationWriter(const std::filesystem::path& path, const std::string& format, double fps, int width, int height);
    /// The encoded frame (GIF: palette and LZW stream; nothing for MP4). Thread-safe, so that frames can be
    /// prepared in parallel and then added in order.
    std::vector<std::uint8_t> prepare(const cv::Mat& bgr) const;
    /// Appends the next frame, with what prepare() returned for it.
    void add(const cv::Mat& bgr, const std::vector<std::uint8_t>& prepared);
    /// Completes the file at `path`.
    void finish();

private:

    std::filesystem::path path_, video_path_;
    std::string format_;
    int width_, height_;
    int delay_centiseconds_ = 10;
    std::ofstream gif_;
    cv::VideoWriter video_;
};

/// A palette of at most 256 colours for `bgr` by median cut over a 5-bit-per-channel histogram (Heckbert,
/// "Color image quantization for frame buffer display", SIGGRAPH 1982), and each pixel's palette index.
struct PalettedImage {
    std::vector<std::uint8_t> palette_rgb;  // 3 bytes per entry, 256 entries
    std::vector<std::uint8_t> indices;      // one per pixel, row-major
};
PalettedImage median_cut_palette(const cv::Mat& bgr);

/// GIF's variable-length LZW code stream (GIF89a specification, appendix F) of `indices` with 8-bit
/// symbols, packed into bytes least significant bit first (not yet split into sub-blocks).
std::vector<std::uint8_t> gif_lzw_encode(const std::vector<std::uint8_t>& indices);

}  // namespace petroscope
