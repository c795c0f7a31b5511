#include "node_colour.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <stdexcept>

namespace petroscope::detail {
namespace {

// Wavelengths per chunk of the fringe sum.
constexpr std::size_t kChunk = 128;

}  // namespace

NodeColour::NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights) {
    if (weights.size() != nodes.grid_size()) throw std::invalid_argument("the colour weights and the spectral nodes use different grids");
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size();
    smooth_form_.setZero();
    for (std::size_t c = 0; c < 3; ++c) {
        channel_weights_[c].resize(weights.size());
        for (std::size_t w = 0; w < weights.size(); ++w) channel_weights_[c][w] = weights[w][static_cast<Eigen::Index>(c)];
        for (std::size_t i = 0; i < kSpectralNodes; ++i) {
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                double sum = 0.0;
                for (std::size_t w = 0; w < weights.size(); ++w) sum += channel_weights_[c][w] * basis[i * stride + w] * basis[j * stride + w];
                smooth_form_(static_cast<Eigen::Index>(c * kSpectralNodes + i), static_cast<Eigen::Index>(j)) = sum;
            }
        }
    }
}

std::optional<Eigen::Vector3d> NodeColour::xyz(const SpectralNodes& nodes, const std::array<NodeValues, 4>& amplitudes, int pairs,
                                               const NodeValues& phase_difference, double product_tolerance) const {
    NodeValues product{};
    Eigen::Vector3d smooth = Eigen::Vector3d::Zero();
    for (int k = 0; k < pairs; ++k) {
        const NodeValues &c0 = amplitudes[2 * static_cast<std::size_t>(k)], &c1 = amplitudes[2 * static_cast<std::size_t>(k) + 1];
        NodeVector sum;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            sum[static_cast<Eigen::Index>(j)] = c0[j] + c1[j];
            product[j] += c0[j] * c1[j];
        }
        const Eigen::Matrix<double, 3 * kSpectralNodeCount, 1> form_times_sum = smooth_form_.lazyProduct(sum);
        for (int c = 0; c < 3; ++c) smooth[c] += form_times_sum.segment<kSpectralNodeCount>(kSpectralNodeCount * c).dot(sum);
    }
    if (!(nodes.tail(product) <= product_tolerance)) return std::nullopt;
    // The fringe term Σ_w W(w)·P(w)·sin²(δ(w)/2), in vector lanes over the wavelengths, in chunks: first the
    // interpolation, then the sine, two loops whose iterations are short enough to overlap in the processor.
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    double x = 0.0, y = 0.0, z = 0.0;
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        const std::size_t length = std::min(kChunk, count - begin);
        std::array<double, kChunk> half_delta, p;
#pragma omp simd
        for (std::size_t i = 0; i < length; ++i) {
            half_delta[i] = 0.5 * interpolate_at(basis, stride, begin + i, phase_difference);
            p[i] = interpolate_at(basis, stride, begin + i, product);
        }
        const double *w_x = channel_weights_[0].data() + begin, *w_y = channel_weights_[1].data() + begin;
        const double* w_z = channel_weights_[2].data() + begin;
#pragma omp simd reduction(+ : x, y, z)
        for (std::size_t i = 0; i < length; ++i) {
            const double fringe = p[i] * sin_squared(half_delta[i]);
            x += w_x[i] * fringe;
            y += w_y[i] * fringe;
            z += w_z[i] * fringe;
        }
    }
    return smooth - 4.0 * Eigen::Vector3d(x, y, z);
}

}  // namespace petroscope::detail
