#pragma once
// A float image in memory: rows top to bottom, interleaved channels.
#include <cstddef>
#include <vector>

namespace petroscope {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;

    Image() = default;
    Image(int width_px, int height_px, int channel_count)
        : width(width_px), height(height_px), channels(channel_count),
          pixels(static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px) *
                 static_cast<std::size_t>(channel_count), 0.0f) {}

    float& at(int x, int y, int channel) { return pixels[index(x, y, channel)]; }
    float at(int x, int y, int channel) const { return pixels[index(x, y, channel)]; }

private:
    std::size_t index(int x, int y, int channel) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                   static_cast<std::size_t>(channels) + static_cast<std::size_t>(channel);
    }
};

}  // namespace petroscope
