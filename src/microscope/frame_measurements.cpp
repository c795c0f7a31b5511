#include "petroscope/microscope/frame_measurements.hpp"

#include "petroscope/optics/indicatrix.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>

namespace petroscope {
namespace {

double luminance_at(const Image& image, int x, int y) {
    if (image.channels < 3) return image.at(x, y, 0);
    return 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
}

}  // namespace

MeanColour mean_colour(const Image& linear_rgb, bool circular_field) {
    MeanColour mean;
    long long count = 0;
    const double half_x = 0.5 * linear_rgb.width, half_y = 0.5 * linear_rgb.height;
    for (int y = 0; y < linear_rgb.height; ++y) {
        for (int x = 0; x < linear_rgb.width; ++x) {
            const double u = (x + 0.5 - half_x) / half_x, v = (y + 0.5 - half_y) / half_y;
            if (circular_field && u * u + v * v > 1.0) continue;
            const int last = linear_rgb.channels - 1;
            mean.r += linear_rgb.at(x, y, 0);
            mean.g += linear_rgb.at(x, y, std::min(1, last));
            mean.b += linear_rgb.at(x, y, std::min(2, last));
            ++count;
        }
    }
    if (count == 0) return mean;
    mean.r /= static_cast<double>(count);
    mean.g /= static_cast<double>(count);
    mean.b /= static_cast<double>(count);
    mean.luminance = 0.2126 * mean.r + 0.7152 * mean.g + 0.0722 * mean.b;
    return mean;
}

std::vector<Eigen::Vector2d> conoscope_optic_axis_points(const ConoscopeSettings& settings, const Eigen::Vector3d& principal_n) {
    const Indicatrix indicatrix{principal_n, rotation_z_deg(settings.stage_deg) * settings.crystal_axes};
    const BinormalFrame frame(indicatrix);
    if (frame.a == frame.c) return {};  // isotropic: no optic axis
    const double n_along_axis = 1.0 / std::sqrt(frame.b);
    std::vector<Eigen::Vector2d> points;
    for (const Eigen::Vector3d& binormal : {frame.binormal_1, frame.binormal_2}) {
        if (std::abs(binormal.z()) < 1e-12) continue;  // in the plane of the slab: never imaged
        const Eigen::Vector2d point = std::copysign(n_along_axis, binormal.z()) * binormal.head<2>() / settings.numerical_aperture;
        if (!points.empty() && (points.back() - point).norm() < 1e-12) continue;  // uniaxial: b₁ = ±b₂
        points.push_back(point);
    }
    return points;
}

std::optional<Eigen::Vector2d> dark_spot_near(const Image& linear_rgb, const Eigen::Vector2d& guess, int window_px, double blur_px) {
    const int size = linear_rgb.width;
    const double half = 0.5 * size;
    const int reach = static_cast<int>(std::ceil(3.0 * blur_px));
    const int centre_x = static_cast<int>(std::floor(half + guess.x() * half));
    const int centre_y = static_cast<int>(std::floor(half - guess.y() * half));
    // The window, grown by the kernel's reach and one pixel for the parabola, must lie inside the field.
    const int margin = window_px + reach + 1;
    for (const int dx : {-margin, margin}) {
        for (const int dy : {-margin, margin}) {
            const double u = (centre_x + dx + 0.5 - half) / half, v = (centre_y + dy + 0.5 - half) / half;
            if (u * u + v * v > 1.0) return std::nullopt;
        }
    }
    // Separable Gaussian over the window plus its margin (the kernel sums to 1).
    std::vector<double> kernel(2 * reach + 1);
    double kernel_sum = 0.0;
    for (int k = -reach; k <= reach; ++k) kernel_sum += kernel[k + reach] = std::exp(-0.5 * k * k / (blur_px * blur_px));
    for (double& weight : kernel) weight /= kernel_sum;
    const int side = 2 * (window_px + 1) + 1, wide = side + 2 * reach;
    const int x0 = centre_x - window_px - 1, y0 = centre_y - window_px - 1;  // top-left of the smoothed block
    std::vector<double> rows(static_cast<std::size_t>(wide) * side), smoothed(static_cast<std::size_t>(side) * side);
    for (int j = 0; j < wide; ++j) {
        for (int i = 0; i < side; ++i) {
            double sum = 0.0;
            for (int k = -reach; k <= reach; ++k) sum += kernel[k + reach] * luminance_at(linear_rgb, x0 + i + k, y0 - reach + j);
            rows[static_cast<std::size_t>(j) * side + i] = sum;
        }
    }
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            double sum = 0.0;
            for (int k = -reach; k <= reach; ++k) sum += kernel[k + reach] * rows[static_cast<std::size_t>(j + reach + k) * side + i];
            smoothed[static_cast<std::size_t>(j) * side + i] = sum;
        }
    }
    const auto at = [&](int i, int j) { return smoothed[static_cast<std::size_t>(j) * side + i]; };
    int best_i = 1, best_j = 1;
    for (int j = 1; j < side - 1; ++j) {
        for (int i = 1; i < side - 1; ++i) {
            if (at(i, j) < at(best_i, best_j)) best_i = i, best_j = j;
        }
    }
    if (best_i == 1 || best_j == 1 || best_i == side - 2 || best_j == side - 2) return std::nullopt;
    // Vertex of the parabola through three samples (Press et al., Numerical Recipes §10.2, eq. 10.2.1).
    const auto vertex = [](double left, double centre, double right) {
        const double curvature = left - 2.0 * centre + right;
        return curvature > 0.0 ? 0.5 * (left - right) / curvature : 0.0;
    };
    const double x = x0 + best_i + 0.5 + vertex(at(best_i - 1, best_j), at(best_i, best_j), at(best_i + 1, best_j));
    const double y = y0 + best_j + 0.5 + vertex(at(best_i, best_j - 1), at(best_i, best_j), at(best_i, best_j + 1));
    return Eigen::Vector2d((x - half) / half, (half - y) / half);
}

}  // namespace petroscope
