#include "figure_measurements.hpp"

#include <cmath>

namespace petroscope::testing {

std::vector<double> profile_minima(const std::vector<double>& profile, double threshold) {
    std::vector<double> minima;
    for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
        const double left = profile[i - 1], centre = profile[i], right = profile[i + 1];
        if (centre < threshold && centre <= left && centre < right) {
            const double curvature = left - 2.0 * centre + right;
            const double offset = curvature > 0.0 ? 0.5 * (left - right) / curvature : 0.0;
            minima.push_back(static_cast<double>(i) + offset);
        }
    }
    return minima;
}

double sample_bilinear(const Image& image, double x, double y) {
    const double u = x - 0.5, v = y - 0.5;
    const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= image.width || y0 + 1 >= image.height) return 0.0;
    const double fx = u - x0, fy = v - y0;
    return (1 - fx) * (1 - fy) * image.at(x0, y0, 0) + fx * (1 - fy) * image.at(x0 + 1, y0, 0) +
           (1 - fx) * fy * image.at(x0, y0 + 1, 0) + fx * fy * image.at(x0 + 1, y0 + 1, 0);
}

namespace {

double rotation_mismatch(const Image& reference, const Image& rotated, double angle_deg) {
    const double angle = angle_deg * M_PI / 180.0;
    const double c = std::cos(angle), s = std::sin(angle);
    const double half = 0.5 * reference.width;
    double sum = 0.0;
    for (int row = 0; row < rotated.height; ++row) {
        for (int column = 0; column < rotated.width; ++column) {
            // Display coordinates with y up, relative to the centre.
            const double x = column + 0.5 - half, y = -(row + 0.5 - half);
            if (x * x + y * y > 0.81 * half * half) continue;
            // Point of the reference that rotates onto (x, y): R(−β)(x, y).
            const double xr = c * x + s * y, yr = -s * x + c * y;
            const double difference = rotated.at(column, row, 0) - sample_bilinear(reference, xr + half, half - yr);
            sum += difference * difference;
        }
    }
    return sum;
}

}  // namespace

double registered_rotation_deg(const Image& reference, const Image& rotated, double guess_deg, double half_width_deg) {
    // Golden-section search (Press et al., Numerical Recipes §10.2) to 1e-4°.
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = guess_deg - half_width_deg, b = guess_deg + half_width_deg;
    double c = b - golden * (b - a), d = a + golden * (b - a);
    double fc = rotation_mismatch(reference, rotated, c), fd = rotation_mismatch(reference, rotated, d);
    while (b - a > 1e-4) {
        if (fc < fd) {
            b = d; d = c; fd = fc;
            c = b - golden * (b - a); fc = rotation_mismatch(reference, rotated, c);
        } else {
            a = c; c = d; fc = fd;
            d = a + golden * (b - a); fd = rotation_mismatch(reference, rotated, d);
        }
    }
    return 0.5 * (a + b);
}

}  // namespace petroscope::testing
