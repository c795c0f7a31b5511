#include "bayer_mosaic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace petroscope::detail {
namespace {

// The channel an RGGB sensor measures at (x, y): 0 red, 1 green, 2 blue.
int measured_channel(int x, int y) {
    if ((x % 2 == 0) == (y % 2 == 0)) return y % 2 == 0 ? 0 : 2;
    return 1;
}

// Bilinear interpolation's weight of a neighbour (dx, dy) ∈ {−1, 0, 1}² that measured `channel`: red and blue lie on
// a lattice of step 2, so the tent of half-width 2 (weights 1, ½, ¼); green on a lattice turned by 45°, whose tent
// reaches only the four nearest pixels (1, ¼).
double weight(int channel, int dx, int dy) {
    if (channel == 1) return dx == 0 && dy == 0 ? 1.0 : (std::abs(dx) + std::abs(dy) == 1 ? 0.25 : 0.0);
    return 0.25 * (2 - std::abs(dx)) * (2 - std::abs(dy));
}

}  // namespace

Image through_bayer_mosaic(const Image& camera_values, double black_level, double gamma) {
    // The raw mosaic: each pixel's own channel, made linear.
    std::vector<double> raw(static_cast<std::size_t>(camera_values.width) * static_cast<std::size_t>(camera_values.height));
    for (int y = 0; y < camera_values.height; ++y) {
        for (int x = 0; x < camera_values.width; ++x) {
            raw[static_cast<std::size_t>(y) * static_cast<std::size_t>(camera_values.width) + static_cast<std::size_t>(x)] =
                std::pow(std::max(camera_values.at(x, y, measured_channel(x, y)) - black_level, 0.0), gamma);
        }
    }
    const auto linear = [&](int x, int y) { return raw[static_cast<std::size_t>(y) * static_cast<std::size_t>(camera_values.width) + static_cast<std::size_t>(x)]; };
    Image out(camera_values.width, camera_values.height, 3);
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0, weights = 0.0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= out.width || yy >= out.height || measured_channel(xx, yy) != c) continue;
                        sum += weight(c, dx, dy) * linear(xx, yy);
                        weights += weight(c, dx, dy);
                    }
                }
                out.at(x, y, c) = static_cast<float>(black_level + std::pow(sum / weights, 1.0 / gamma));
            }
        }
    }
    return out;
}

}  // namespace petroscope::detail
