#include "figure_location.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace petroscope::detail {
namespace {

// The luminance (mean of the channels) averaged over blocks of factor × factor pixels; a partial last row or
// column of blocks is dropped.
struct Grid {
    int width = 0, height = 0, factor = 1;
    std::vector<double> values;
    double at(int x, int y) const { return values[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

Grid block_luminance(const Image& photo, int factor) {
    Grid grid;
    grid.factor = factor;
    grid.width = std::max(1, photo.width / factor);
    grid.height = std::max(1, photo.height / factor);
    grid.values.assign(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height), 0.0);
    const double weight = 1.0 / (static_cast<double>(factor) * factor * photo.channels);
    for (int y = 0; y < std::min(photo.height, grid.height * factor); ++y) {
        for (int x = 0; x < std::min(photo.width, grid.width * factor); ++x) {
            double sum = 0.0;
            for (int c = 0; c < photo.channels; ++c) sum += photo.at(x, y, c);
            grid.values[static_cast<std::size_t>(y / factor) * static_cast<std::size_t>(grid.width) + static_cast<std::size_t>(x / factor)] += weight * sum;
        }
    }
    return grid;
}

// The grid divided by its local mean (a box of 2·radius + 1 blocks, applied twice: nearly a Gaussian; cut at the
// grid's edges): light that falls off smoothly across the frame multiplies the camera values (E·F)^(1/γ) by a
// smooth factor, which this removes, so that light centred away from the figure does not make another point look
// like its centre of symmetry. The box's radius is this fraction of the grid's width (σ ≈ 0.1 of the frame):
// wider than an isogyre, narrower than the light's falloff.
constexpr int kLightRadiusFraction = 8;
void divide_by_local_mean(Grid& grid, int radius) {
    std::vector<double> mean = grid.values, ones(grid.values.size(), 1.0);
    const auto box = [&grid, radius](std::vector<double>& values, bool along_x) {
        std::vector<double> out(values.size(), 0.0);
        for (int y = 0; y < grid.height; ++y) {
            for (int x = 0; x < grid.width; ++x) {
                double sum = 0.0;
                for (int d = -radius; d <= radius; ++d) {
                    const int xx = along_x ? x + d : x, yy = along_x ? y : y + d;
                    if (xx >= 0 && yy >= 0 && xx < grid.width && yy < grid.height) sum += values[static_cast<std::size_t>(yy * grid.width + xx)];
                }
                out[static_cast<std::size_t>(y * grid.width + x)] = sum;
            }
        }
        values.swap(out);
    };
    for (int pass = 0; pass < 2; ++pass) {
        for (const bool along_x : {true, false}) {
            box(mean, along_x);
            box(ones, along_x);  // the weights the cut box had: its mean is sum / weight
        }
    }
    double largest = 0.0;
    for (std::size_t i = 0; i < mean.size(); ++i) largest = std::max(largest, mean[i] / ones[i]);
    for (std::size_t i = 0; i < mean.size(); ++i) grid.values[i] /= std::max(mean[i] / ones[i], 1e-3 * largest);
}

// The overlap a centre needs, as a fraction of the frame: a figure a fifth of the frame off centre each way (the
// most a fit is asked to find) overlaps its half turn on 0.6² = 36% of it. Smaller overlaps, strips along the
// frame's edges, can be as symmetric about their own middle by chance as the figure is about its centre.
constexpr double kLeastOverlap = 1.0 / 3.0;

// The correlation of the grid with its half turn p → s − p (s = 2c in block indices), over the overlap; −∞ where
// the overlap is under kLeastOverlap of the grid or flat.
double half_turn_correlation(const Grid& grid, int s_x, int s_y) {
    const int x_begin = std::max(0, s_x - (grid.width - 1)), x_end = std::min(grid.width - 1, s_x);
    const int y_begin = std::max(0, s_y - (grid.height - 1)), y_end = std::min(grid.height - 1, s_y);
    const double count = static_cast<double>(x_end - x_begin + 1) * static_cast<double>(y_end - y_begin + 1);
    if (x_end < x_begin || y_end < y_begin || count < kLeastOverlap * grid.width * grid.height) return -std::numeric_limits<double>::infinity();
    double sum = 0.0, sum_squares = 0.0, sum_products = 0.0;
    for (int y = y_begin; y <= y_end; ++y) {
        for (int x = x_begin; x <= x_end; ++x) {
            const double a = grid.at(x, y), b = grid.at(s_x - x, s_y - y);
            sum += a;
            sum_squares += a * a;
            sum_products += a * b;
        }
    }
    // The pairs (p, s − p) run over the overlap twice, so both members have the same mean and variance.
    const double mean = sum / count, variance = sum_squares / count - mean * mean;
    if (!(variance > 1e-12)) return -std::numeric_limits<double>::infinity();
    return (sum_products / count - mean * mean) / variance;
}

struct Best {
    int s_x = 0, s_y = 0;
    double correlation = -std::numeric_limits<double>::infinity();
};

Best best_over(const Grid& grid, int s_x_min, int s_x_max, int s_y_min, int s_y_max) {
    Best best;
    for (int s_y = std::max(0, s_y_min); s_y <= std::min(2 * grid.height - 2, s_y_max); ++s_y) {
        for (int s_x = std::max(0, s_x_min); s_x <= std::min(2 * grid.width - 2, s_x_max); ++s_x) {
            const double correlation = half_turn_correlation(grid, s_x, s_y);
            if (correlation > best.correlation) best = {s_x, s_y, correlation};
        }
    }
    return best;
}

// Block index s/2 as pixel coordinates: block i covers pixels [i·f, (i + 1)·f).
double pixel_coordinate(int s, int factor) { return (0.5 * s + 0.5) * factor; }

}  // namespace

std::optional<Eigen::Vector2d> half_turn_symmetry_centre_px(const Image& photo) {
    const int longest = std::max(photo.width, photo.height);
    Grid coarse = block_luminance(photo, std::max(1, (longest + 63) / 64));
    divide_by_local_mean(coarse, std::max(1, coarse.width / kLightRadiusFraction));
    const Best rough = best_over(coarse, 0, 2 * coarse.width - 2, 0, 2 * coarse.height - 2);
    if (!std::isfinite(rough.correlation)) return std::nullopt;
    Grid fine = block_luminance(photo, std::max(1, (longest + 127) / 128));
    divide_by_local_mean(fine, std::max(1, fine.width / kLightRadiusFraction));
    // The rough centre on the fine grid, searched within two coarse blocks of it.
    const double ratio = static_cast<double>(coarse.factor) / fine.factor;
    const auto fine_index = [&](int s) { return static_cast<int>(std::lround(2.0 * pixel_coordinate(s, coarse.factor) / fine.factor - 1.0)); };
    const int reach = static_cast<int>(std::ceil(4.0 * ratio));
    const int s_x = fine_index(rough.s_x), s_y = fine_index(rough.s_y);
    const Best refined = best_over(fine, s_x - reach, s_x + reach, s_y - reach, s_y + reach);
    return Eigen::Vector2d(pixel_coordinate(refined.s_x, fine.factor), pixel_coordinate(refined.s_y, fine.factor));
}

}  // namespace petroscope::detail
