#include "node_colour.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <stdexcept>

namespace petroscope::detail {
namespace {

// Wavelengths per chunk of the fringe sum.
constexpr std::size_t kChunk = 128;
// The interpolation error allowed in sin²(δ/2) (SpectralNodes::tail) for the fringe term as a form: with
// |c₀c₁| ≤ 1/4 it changes a transmission by at most about 1e-4.
constexpr double kSmoothFringeTolerance = 1e-4;
// Beyond this range of δ over the nodes the tolerance cannot be met: sin²(δ/2) = (1 − cos δ)/2 with δ running
// linearly over a range Δ has Chebyshev coefficients of modulus J_k(Δ/2) (the Jacobi–Anger expansion), and J₆(Δ/2)
// passes 1e-4 between Δ = 2.5 and 3 rad.
constexpr double kSmoothFringePhaseRange_rad = 3.0;

}  // namespace

NodeColour::NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights) {
    if (weights.size() != nodes.grid_size()) throw std::invalid_argument("the colour weights and the spectral nodes use different grids");
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size();
    for (std::size_t c = 0; c < 3; ++c) {
        channel_weights_[c].resize(weights.size());
        for (std::size_t w = 0; w < weights.size(); ++w) channel_weights_[c][w] = weights[w][static_cast<Eigen::Index>(c)];
        for (std::size_t i = 0; i < kSpectralNodes; ++i) {
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                double sum = 0.0;
                for (std::size_t w = 0; w < weights.size(); ++w) sum += channel_weights_[c][w] * basis[i * stride + w] * basis[j * stride + w];
                form_[j * kFormRows + c * kSpectralNodes + i] = sum;
            }
        }
    }
}

Eigen::Vector3d NodeColour::weighted_product(const NodeValues& left, const NodeValues& right) const {
    // The three channels' M_c·right at once, then each dotted with `left`.
    std::array<double, kFormRows> form_times_right;
#pragma omp simd
    for (std::size_t row = 0; row < kFormRows; ++row) {
        double value = 0.0;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) value += form_[j * kFormRows + row] * right[j];
        form_times_right[row] = value;
    }
    Eigen::Vector3d result = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < kSpectralNodes; ++i) result[static_cast<Eigen::Index>(c)] += form_times_right[c * kSpectralNodes + i] * left[i];
    }
    return result;
}

std::optional<Eigen::Vector3d> NodeColour::xyz(const SpectralNodes& nodes, const std::array<NodeValues, 4>& amplitudes, int pairs,
                                               const NodeValues& phase_difference, double product_tolerance) const {
    NodeValues product{};
    for (int k = 0; k < pairs; ++k) {
        const NodeValues &c0 = amplitudes[2 * static_cast<std::size_t>(k)], &c1 = amplitudes[2 * static_cast<std::size_t>(k) + 1];
        for (std::size_t j = 0; j < kSpectralNodes; ++j) product[j] += c0[j] * c1[j];
    }
    if (!(nodes.tail(product) <= product_tolerance)) return std::nullopt;
    // The smooth term Σ_k Σ_w W(w)·sₖ(w)² with sₖ = c₀ₖ + c₁ₖ.
    Eigen::Vector3d smooth = Eigen::Vector3d::Zero();
    for (int k = 0; k < pairs; ++k) {
        const NodeValues &c0 = amplitudes[2 * static_cast<std::size_t>(k)], &c1 = amplitudes[2 * static_cast<std::size_t>(k) + 1];
        NodeValues sum;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) sum[j] = c0[j] + c1[j];
        smooth += weighted_product(sum, sum);
    }
    // Where δ changes little over the spectrum (a thin slab, the centre of a figure), sin²(δ/2) is as smooth as the
    // fields and the fringe term is a form in node values too.
    const auto [least, most] = std::minmax_element(phase_difference.begin(), phase_difference.end());
    if (*most - *least <= kSmoothFringePhaseRange_rad) {
        NodeValues fringe{};
        for (std::size_t j = 0; j < kSpectralNodes; ++j) fringe[j] = sin_squared(0.5 * phase_difference[j]);
        if (nodes.tail(fringe) <= kSmoothFringeTolerance) return smooth - 4.0 * weighted_product(product, fringe);
    }
    return smooth - 4.0 * fringe_sum(nodes, product, phase_difference);
}

Eigen::Vector3d NodeColour::fringe_sum(const SpectralNodes& nodes, const NodeValues& product, const NodeValues& phase_difference) const {
    // The fringe term Σ_w W(w)·P(w)·sin²(δ(w)/2), in vector lanes over the wavelengths, in chunks: first the
    // interpolation, then the sine, two loops whose iterations are short enough to overlap in the processor.
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    NodeValues half_phase;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) half_phase[j] = 0.5 * phase_difference[j];
    double x = 0.0, y = 0.0, z = 0.0;
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        const std::size_t length = std::min(kChunk, count - begin);
        std::array<double, kChunk> half_delta, p;
#pragma omp simd
        for (std::size_t i = 0; i < length; ++i) {
            half_delta[i] = interpolate_at(basis, stride, begin + i, half_phase);
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
    return {x, y, z};
}

}  // namespace petroscope::detail
