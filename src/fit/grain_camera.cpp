#include "grain_camera.hpp"

#include "petroscope/spectral/color.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

/// C_a(y) = yᵃ / (yᵃ + (1 − y)ᵃ) (camera_tone), y clamped to 0 … 1.
double contrast_curve(double code, double contrast) {
    if (code <= 0.0 || code >= 1.0) return std::clamp(code, 0.0, 1.0);
    const double up = std::pow(code, contrast), down = std::pow(1.0 - code, contrast);
    return up / (up + down);
}

/// The inverse of camera_tone: the linear value of a code.
double linear_of_code(double code, double contrast) {
    return decode_srgb(contrast_curve(std::clamp(code, 0.0, 1.0), 1.0 / contrast));
}

/// One channel's gain (see reference_gains), g ≥ 1e-3; numerical slopes of the tone (steps of 1e-6 relative).
double channel_gain(const std::vector<double>& model_linear, const std::vector<double>& measured_code, double contrast) {
    double linear_products = 0.0, model_squares = 0.0;
    for (std::size_t k = 0; k < model_linear.size(); ++k) {
        linear_products += model_linear[k] * linear_of_code(measured_code[k], contrast);
        model_squares += model_linear[k] * model_linear[k];
    }
    double gain = std::max(linear_products / model_squares, 1e-3);
    for (int iteration = 0; iteration < 30; ++iteration) {
        double gradient = 0.0, curvature = 0.0;
        for (std::size_t k = 0; k < model_linear.size(); ++k) {
            const double x = gain * model_linear[k], h = 1e-6 * std::max(x, 1e-3);
            const double slope = (camera_tone(x + h, contrast) - camera_tone(x - h, contrast)) / (2.0 * h) * model_linear[k];
            gradient += slope * (camera_tone(x, contrast) - measured_code[k]);
            curvature += slope * slope;
        }
        if (curvature <= 0.0) break;  // every reference clipped: keep the linear estimate
        const double next = std::max(gain - gradient / curvature, 1e-3);
        const bool converged = std::abs(next - gain) <= 1e-12 * gain;
        gain = next;
        if (converged) break;
    }
    return gain;
}

}  // namespace

double camera_tone(double linear, double contrast) { return contrast_curve(encode_srgb(std::clamp(linear, 0.0, 1.0)), contrast); }

Eigen::Vector3d camera_code(const Eigen::Vector3d& linear, double contrast) {
    return {camera_tone(linear.x(), contrast), camera_tone(linear.y(), contrast), camera_tone(linear.z(), contrast)};
}

bool mark_lit_channels(ReferenceColours& references) {
    constexpr double kLitReference = 0.02;
    for (std::size_t c = 0; c < 3; ++c) {
        references.lit[c] = std::any_of(references.model_linear.begin(), references.model_linear.end(),
                                        [c](const Eigen::Vector3d& linear) { return linear[static_cast<Eigen::Index>(c)] >= kLitReference; });
    }
    return std::any_of(references.lit.begin(), references.lit.end(), [](bool lit) { return lit; });
}

Eigen::Vector3d reference_gains(const ReferenceColours& references, double contrast) {
    Eigen::Vector3d gains = Eigen::Vector3d::Zero();
    double lit_sum = 0.0;
    int lit_count = 0;
    for (std::size_t c = 0; c < 3; ++c) {
        if (!references.lit[c]) continue;
        const auto channel = static_cast<Eigen::Index>(c);
        std::vector<double> model_linear, measured;
        for (std::size_t r = 0; r < references.photos.size(); ++r) {
            model_linear.push_back(references.model_linear[r][channel]);
            measured.push_back(references.measured_code[r][channel]);
        }
        gains[channel] = channel_gain(model_linear, measured, contrast);
        lit_sum += gains[channel];
        ++lit_count;
    }
    for (std::size_t c = 0; c < 3; ++c) {
        if (!references.lit[c]) gains[static_cast<Eigen::Index>(c)] = lit_sum / std::max(lit_count, 1);
    }
    return gains;
}

}  // namespace petroscope::detail
