#include "node_colour.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <stdexcept>

namespace petroscope::detail {
namespace {

// Wavelengths per chunk of the fringe sum.
constexpr std::size_t kChunk = 128;
// The interpolation error allowed (SpectralNodes::tail) in sin²(δ/2), or in cos θ and sin θ, for an oscillating
// term as a form in node values: it changes a transmission by at most about 1e-4 (|c₀c₁| ≤ 1/4, |X|, |Y| ≤ 1).
constexpr double kSmoothFringeTolerance = 1e-4;
// Beyond this range of the angle over the nodes the tolerance cannot be met: cos θ with θ running linearly over a
// range Δ has Chebyshev coefficients of modulus 2J_k(Δ/2) (the Jacobi–Anger expansion), sin²(δ/2) = (1 − cos δ)/2
// half of them, and J₆(Δ/2) passes 1e-4 between Δ = 2.5 and 3 rad.
constexpr double kSmoothFringePhaseRange_rad = 3.0;
bool narrow_range(const NodeValues& angle) {
    const auto [least, most] = std::minmax_element(angle.begin(), angle.end());
    return *most - *least <= kSmoothFringePhaseRange_rad;
}
// An optically active crystal's terms (active_xyz): 2Ω within kPhaseTolerance_rad, as δ elsewhere (spectral_nodes.hpp),
// and each of S, X, Y within 1e-4 of the transmission. Below kLeastRotation_rad of Ω at a node (no coupling on an optic
// axis) the terms' 1/Ω is left to the spectrum.
constexpr double kTermTolerance = 1e-4;
constexpr double kLeastRotation_rad = 1e-6;

}  // namespace

NodeColour::NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights) {
    if (weights.size() != nodes.grid_size()) throw std::invalid_argument("the colour weights and the spectral nodes use different grids");
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size();
    for (std::size_t c = 0; c < 3; ++c) {
        channel_weights_[c].resize(weights.size());
        for (std::size_t w = 0; w < weights.size(); ++w) channel_weights_[c][w] = weights[w][static_cast<Eigen::Index>(c)];
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            for (std::size_t w = 0; w < weights.size(); ++w) linear_form_[c][j] += channel_weights_[c][w] * basis[j * stride + w];
        }
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
    if (narrow_range(phase_difference)) {
        NodeValues fringe{};
        for (std::size_t j = 0; j < kSpectralNodes; ++j) fringe[j] = sin_squared(0.5 * phase_difference[j]);
        if (nodes.tail(fringe) <= kSmoothFringeTolerance) return smooth - 4.0 * weighted_product(product, fringe);
    }
    NodeValues half_phase;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) half_phase[j] = 0.5 * phase_difference[j];
    return smooth - 4.0 * oscillating_sum<false>(nodes, half_phase, product, product);
}

template <bool Active>
Eigen::Vector3d NodeColour::oscillating_sum(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                            const NodeValues& sine_part) const {
    // In vector lanes over the wavelengths, in chunks: first the interpolation, then the sine, two loops whose
    // iterations are short enough to overlap in the processor.
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    double x = 0.0, y = 0.0, z = 0.0;
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        const std::size_t length = std::min(kChunk, count - begin);
        std::array<double, kChunk> theta, c, s;
#pragma omp simd
        for (std::size_t i = 0; i < length; ++i) {
            theta[i] = interpolate_at(basis, stride, begin + i, angle);
            c[i] = interpolate_at(basis, stride, begin + i, cosine_part);
            if constexpr (Active) s[i] = interpolate_at(basis, stride, begin + i, sine_part);
        }
        const double *w_x = channel_weights_[0].data() + begin, *w_y = channel_weights_[1].data() + begin;
        const double* w_z = channel_weights_[2].data() + begin;
#pragma omp simd reduction(+ : x, y, z)
        for (std::size_t i = 0; i < length; ++i) {
            double term = 0.0;
            if constexpr (Active) {
                const SineCosine both = sine_cosine(theta[i]);
                term = c[i] * both.cosine + s[i] * both.sine;
            } else {
                term = c[i] * sin_squared(theta[i]);
            }
            x += w_x[i] * term;
            y += w_y[i] * term;
            z += w_z[i] * term;
        }
    }
    return {x, y, z};
}

std::optional<Eigen::Vector3d> NodeColour::smooth_rotation(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                                           const NodeValues& sine_part) const {
    if (!narrow_range(angle)) return std::nullopt;
    NodeValues cosine, sine;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const SineCosine both = sine_cosine(angle[j]);
        cosine[j] = both.cosine;
        sine[j] = both.sine;
    }
    if (!(nodes.tail(cosine) <= kSmoothFringeTolerance && nodes.tail(sine) <= kSmoothFringeTolerance)) return std::nullopt;
    return weighted_product(cosine_part, cosine) + weighted_product(sine_part, sine);
}

std::optional<Eigen::Vector3d> NodeColour::active_xyz(const SpectralNodes& nodes, const ActiveNodeFields& fields,
                                                      const NodeValues& phase_difference) const {
    // Per component k at node j, with h = δ/2 and Ω = √(h² + b₀b₁) (spectral_nodes.hpp, interpolated_active_transmission):
    // |R + iI|² = cos²Ω·A² + 2cosΩ·(sinΩ/Ω)·AB + (sin²Ω/Ω²)·(B² + h²C²) with A = F₀ + F₁, B = G₁ − G₀, C = F₀ − F₁,
    // which is S + X·cos 2Ω + Y·sin 2Ω with D = (B² + h²C²)/Ω², S = (A² + D)/2, X = (A² − D)/2, Y = AB/Ω; the
    // components' S, X, Y add.
    NodeValues smooth{}, cosine_part{}, sine_part{}, two_omega{};
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const double h = 0.5 * phase_difference[j];
        const double omega = std::sqrt(std::max(h * h + fields.coupling_product[j], 0.0));
        if (!(omega > kLeastRotation_rad)) return std::nullopt;
        two_omega[j] = 2.0 * omega;
        for (int k = 0; k < fields.components; ++k) {
            const std::array<NodeValues, 4>& f = fields.component[static_cast<std::size_t>(k)];
            const double a = f[0][j] + f[1][j], b = f[3][j] - f[2][j], c = f[0][j] - f[1][j];
            const double d = (b * b + h * h * c * c) / (omega * omega);
            smooth[j] += 0.5 * (a * a + d);
            cosine_part[j] += 0.5 * (a * a - d);
            sine_part[j] += a * b / omega;
        }
    }
    if (!(nodes.tail(two_omega) <= kPhaseTolerance_rad)) return std::nullopt;
    for (const NodeValues* part : {&smooth, &cosine_part, &sine_part}) {
        if (!(nodes.tail(*part) <= kTermTolerance)) return std::nullopt;
    }
    const std::optional<Eigen::Vector3d> smooth_in_wavelength = smooth_rotation(nodes, two_omega, cosine_part, sine_part);
    Eigen::Vector3d result = smooth_in_wavelength ? *smooth_in_wavelength : oscillating_sum<true>(nodes, two_omega, cosine_part, sine_part);
    for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t j = 0; j < kSpectralNodes; ++j) result[static_cast<Eigen::Index>(c)] += linear_form_[c][j] * smooth[j];
    }
    return result;
}

}  // namespace petroscope::detail
