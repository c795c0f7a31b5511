#include "node_colour.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <limits>
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

// `values` interpolated to the grid wavelengths begin … begin + length − 1, one quantity at a time: its eight node
// values stay in vector registers, where several quantities at once would spill them to memory.
void interpolate_chunk(const double* basis, std::size_t stride, std::size_t begin, std::size_t length, const NodeValues& values, double* out) {
#pragma omp simd
    for (std::size_t i = 0; i < length; ++i) out[i] = interpolate_at(basis, stride, begin + i, values);
}

// An amplitude of an oscillating term, a + cos Γ·r − sin Γ·q (NodeColour::Amplitude), as the node values of a, r and q in
// single precision (it is bounded by 1 and needed to kTermTolerance), zero where it has none (r and q only behind a
// plate); bit g of `present` says that values[g] is set.
struct AmplitudeParts {
    std::array<std::array<float, kSpectralNodes>, 3> values{};
    unsigned present = 0;
};

// The parts an amplitude_chunk interpolates, bit g for AmplitudeParts::values[g]: a alone, a and r (an inactive crystal's
// cos θ amplitude behind a plate), q alone (its sin θ amplitude), all three; none (no second amplitude).
constexpr unsigned kPlainAmplitude = 1u, kPlainAndInPhase = 3u, kQuadratureOnly = 4u, kAllParts = 7u, kNoAmplitude = 0u;

// Interpolated parts of an amplitude: a, r and q at one wavelength.
struct PartSums {
    float a = 0.0f, r = 0.0f, q = 0.0f;
};

// One amplitude's node values times the basis value `l` of node j added to `sums`, for the parts in Parts.
template <unsigned Parts>
inline void accumulate(float l, const AmplitudeParts& parts, std::size_t j, PartSums& sums) {
    if constexpr ((Parts & 1u) != 0) sums.a += l * parts.values[0][j];
    if constexpr ((Parts & 2u) != 0) sums.r += l * parts.values[1][j];
    if constexpr ((Parts & 4u) != 0) sums.q += l * parts.values[2][j];
}

// a + cos Γ·r − sin Γ·q from the interpolated parts in Parts.
template <unsigned Parts>
inline float combined(const PartSums& sums, float plate_cosine, float plate_minus_sine) {
    float sum = sums.a;
    if constexpr ((Parts & 2u) != 0) sum += plate_cosine * sums.r;
    if constexpr ((Parts & 4u) != 0) sum += plate_minus_sine * sums.q;
    return sum;
}

// One or two amplitudes (`first_parts`, `second_parts`; `out`) at the grid wavelengths begin … begin + length − 1, each from
// the parts in First and Second (a superset of those it has: the others are zero): every node quantity is interpolated in the same pass,
// each basis value loaded once for all, and r and q weighted with the plate's cos Γ and −sin Γ (`plate_cosine`,
// `plate_minus_sine`).
template <unsigned First, unsigned Second>
void amplitude_chunk(const float* basis, const float* plate_cosine, const float* plate_minus_sine, std::size_t stride, std::size_t begin,
                     std::size_t length, const AmplitudeParts& first_parts, const AmplitudeParts& second_parts, std::array<float*, 2> out) {
#pragma omp simd
    for (std::size_t i = 0; i < length; ++i) {
        PartSums first, second;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            const float l = basis[j * stride + begin + i];
            accumulate<First>(l, first_parts, j, first);
            accumulate<Second>(l, second_parts, j, second);
        }
        constexpr bool kPlate = ((First | Second) & 6u) != 0;
        const float cosine = kPlate ? plate_cosine[begin + i] : 0.0f, minus_sine = kPlate ? plate_minus_sine[begin + i] : 0.0f;
        out[0][i] = combined<First>(first, cosine, minus_sine);
        if constexpr (Second != kNoAmplitude) out[1][i] = combined<Second>(second, cosine, minus_sine);
    }
}

// Whether an amplitude's parts are among `parts`.
bool within(const AmplitudeParts& amplitude, unsigned parts) { return (amplitude.present & ~parts) == 0; }

// The amplitudes of an oscillating sum (one for a fringe, two for a rotation) in one amplitude_chunk whose parts cover
// theirs: a fringe's plain amplitude, an optically active crystal's two, an inactive crystal's two behind a plate
// (a + cos Γ·r and −sin Γ·q), or any others with every part.
template <std::size_t Count>
void amplitude_chunks(const float* basis, const float* plate_cosine, const float* plate_minus_sine, std::size_t stride, std::size_t begin,
                      std::size_t length, const std::array<AmplitudeParts, Count>& parts, std::array<std::array<float, kChunk>, Count>& out) {
    const AmplitudeParts &first = parts[0], &second = parts[Count - 1];
    const std::array<float*, 2> to{out[0].data(), out[Count - 1].data()};
    if constexpr (Count == 1) {
        if (!within(first, kPlainAmplitude)) throw std::logic_error("NodeColour: a fringe's amplitude with the plate's phase");
        amplitude_chunk<kPlainAmplitude, kNoAmplitude>(basis, plate_cosine, plate_minus_sine, stride, begin, length, first, second, to);
    } else if (within(first, kPlainAmplitude) && within(second, kPlainAmplitude)) {
        amplitude_chunk<kPlainAmplitude, kPlainAmplitude>(basis, plate_cosine, plate_minus_sine, stride, begin, length, first, second, to);
    } else if (within(first, kPlainAndInPhase) && within(second, kQuadratureOnly)) {
        amplitude_chunk<kPlainAndInPhase, kQuadratureOnly>(basis, plate_cosine, plate_minus_sine, stride, begin, length, first, second, to);
    } else {
        amplitude_chunk<kAllParts, kAllParts>(basis, plate_cosine, plate_minus_sine, stride, begin, length, first, second, to);
    }
}

}  // namespace

NodeColour::Forms NodeColour::forms_of(const SpectralNodes& nodes, const std::array<std::vector<double>, 3>& channel_weights) {
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    Forms forms;
    for (std::size_t c = 0; c < 3; ++c) {
        const std::vector<double>& weight = channel_weights[c];
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            for (std::size_t w = 0; w < count; ++w) forms.linear[c][j] += weight[w] * basis[j * stride + w];
        }
        for (std::size_t i = 0; i < kSpectralNodes; ++i) {
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                double sum = 0.0;
                for (std::size_t w = 0; w < count; ++w) sum += weight[w] * basis[i * stride + w] * basis[j * stride + w];
                forms.quadratic[j * kFormRows + c * kSpectralNodes + i] = sum;
            }
        }
    }
    return forms;
}

NodeColour::NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights, const std::vector<double>& plate_phase_rad) {
    if (weights.size() != nodes.grid_size()) throw std::invalid_argument("the colour weights and the spectral nodes use different grids");
    for (std::size_t c = 0; c < 3; ++c) {
        channel_weights_[c].resize(weights.size());
        for (std::size_t w = 0; w < weights.size(); ++w) channel_weights_[c][w] = weights[w][static_cast<Eigen::Index>(c)];
    }
    plain_ = forms_of(nodes, channel_weights_);
    if (plate_phase_rad.empty()) return;
    if (plate_phase_rad.size() != weights.size()) throw std::invalid_argument("the plate's phase and the colour weights use different grids");
    std::array<std::vector<double>, 3> cosine_weights = channel_weights_, sine_weights = channel_weights_;
    plate_cosine_phase_.resize(nodes.padded_grid_size(), 0.0f);
    plate_minus_sine_phase_.resize(nodes.padded_grid_size(), 0.0f);
    for (std::size_t w = 0; w < weights.size(); ++w) {
        const double cosine = std::cos(plate_phase_rad[w]), sine = std::sin(plate_phase_rad[w]);
        for (std::size_t c = 0; c < 3; ++c) {
            cosine_weights[c][w] *= cosine;
            sine_weights[c][w] *= sine;
        }
        plate_cosine_phase_[w] = static_cast<float>(cosine);
        plate_minus_sine_phase_[w] = static_cast<float>(-sine);
    }
    plate_cosine_ = forms_of(nodes, cosine_weights);
    plate_sine_ = forms_of(nodes, sine_weights);
}

Eigen::Vector3d NodeColour::weighted_product(const Forms& forms, const NodeValues& left, const NodeValues& right) {
    // The three channels' M_c·right at once, then each dotted with `left`.
    std::array<double, kFormRows> form_times_right;
#pragma omp simd
    for (std::size_t row = 0; row < kFormRows; ++row) {
        double value = 0.0;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) value += forms.quadratic[j * kFormRows + row] * right[j];
        form_times_right[row] = value;
    }
    Eigen::Vector3d result = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < kSpectralNodes; ++i) result[static_cast<Eigen::Index>(c)] += form_times_right[c * kSpectralNodes + i] * left[i];
    }
    return result;
}

Eigen::Vector3d NodeColour::weighted_sum(const Forms& forms, const NodeValues& values) {
    double x = 0.0, y = 0.0, z = 0.0;
#pragma omp simd reduction(+ : x, y, z)
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        x += forms.linear[0][j] * values[j];
        y += forms.linear[1][j] * values[j];
        z += forms.linear[2][j] * values[j];
    }
    return {x, y, z};
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
        smooth += weighted_product(plain_, sum, sum);
    }
    // Where δ changes little over the spectrum (a thin slab, the centre of a figure), sin²(δ/2) is as smooth as the
    // fields and the fringe term is a form in node values too.
    if (narrow_range(phase_difference)) {
        NodeValues fringe{};
        for (std::size_t j = 0; j < kSpectralNodes; ++j) fringe[j] = sin_squared(0.5 * phase_difference[j]);
        if (nodes.tail(fringe) <= kSmoothFringeTolerance) return smooth - 4.0 * weighted_product(plain_, product, fringe);
    }
    NodeValues half_phase;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) half_phase[j] = 0.5 * phase_difference[j];
    return smooth - 4.0 * oscillating_sum<Oscillation::fringe>(nodes, half_phase, {Amplitude{&product}});
}

template <NodeColour::Oscillation Kind>
Eigen::Vector3d NodeColour::oscillating_sum(const SpectralNodes& nodes, const NodeValues& angle, const std::array<Amplitude, 2>& amplitudes) const {
    // In vector lanes over the wavelengths, in chunks: first the interpolations, then the sine, loops whose
    // iterations are short enough to overlap in the processor.
    constexpr std::size_t kAmplitudes = Kind == Oscillation::fringe ? 1 : 2;
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    std::array<AmplitudeParts, kAmplitudes> parts;
    for (std::size_t a = 0; a < kAmplitudes; ++a) {
        for (std::size_t g = 0; g < 3; ++g) {
            if (amplitudes[a][g] == nullptr) continue;
            if (g > 0 && plate_cosine_phase_.empty()) throw std::logic_error("NodeColour: an amplitude with the plate's phase, made without it");
            std::transform(amplitudes[a][g]->begin(), amplitudes[a][g]->end(), parts[a].values[g].begin(),
                           [](double value) { return static_cast<float>(value); });
            parts[a].present |= 1u << g;
        }
    }
    const double* basis = nodes.basis();
    double x = 0.0, y = 0.0, z = 0.0;
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        const std::size_t length = std::min(kChunk, count - begin);
        std::array<double, kChunk> theta;
        std::array<std::array<float, kChunk>, kAmplitudes> v;
        interpolate_chunk(basis, stride, begin, length, angle, theta.data());
        amplitude_chunks(nodes.single_basis(), plate_cosine_phase_.data(), plate_minus_sine_phase_.data(), stride, begin, length, parts, v);
        const double *w_x = channel_weights_[0].data() + begin, *w_y = channel_weights_[1].data() + begin;
        const double* w_z = channel_weights_[2].data() + begin;
#pragma omp simd reduction(+ : x, y, z)
        for (std::size_t i = 0; i < length; ++i) {
            double term = 0.0;
            if constexpr (Kind == Oscillation::fringe) {
                term = v[0][i] * sin_squared(theta[i]);
            } else {
                const SineCosine both = sine_cosine(theta[i]);
                term = v[0][i] * both.cosine + v[1][i] * both.sine;
            }
            x += w_x[i] * term;
            y += w_y[i] * term;
            z += w_z[i] * term;
        }
    }
    return {x, y, z};
}

std::optional<std::array<NodeValues, 2>> NodeColour::smooth_cosine_sine(const SpectralNodes& nodes, const NodeValues& angle) {
    if (!narrow_range(angle)) return std::nullopt;
    NodeValues cosine, sine;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const SineCosine both = sine_cosine(angle[j]);
        cosine[j] = both.cosine;
        sine[j] = both.sine;
    }
    if (!(nodes.tail(cosine) <= kSmoothFringeTolerance && nodes.tail(sine) <= kSmoothFringeTolerance)) return std::nullopt;
    return std::array<NodeValues, 2>{cosine, sine};
}

std::optional<Eigen::Vector3d> NodeColour::smooth_rotation(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                                           const NodeValues& sine_part) const {
    const std::optional<std::array<NodeValues, 2>> cosine_sine = smooth_cosine_sine(nodes, angle);
    if (!cosine_sine) return std::nullopt;
    return weighted_product(plain_, cosine_part, (*cosine_sine)[0]) + weighted_product(plain_, sine_part, (*cosine_sine)[1]);
}

std::optional<Eigen::Vector3d> NodeColour::active_xyz(const SpectralNodes& nodes, const ActiveNodeFields& fields,
                                                      const NodeValues& phase_difference) const {
    const std::optional<RotationNodeTerms> terms = active_node_terms(fields, phase_difference);
    if (!terms || !interpolable(nodes, *terms)) return std::nullopt;
    const auto& [smooth, cosine_part, sine_part, two_omega] = *terms;
    const std::optional<Eigen::Vector3d> smooth_in_wavelength = smooth_rotation(nodes, two_omega, cosine_part, sine_part);
    const Eigen::Vector3d oscillating =
        smooth_in_wavelength ? *smooth_in_wavelength : oscillating_sum<Oscillation::rotation>(nodes, two_omega, {Amplitude{&cosine_part}, Amplitude{&sine_part}});
    return oscillating + weighted_sum(plain_, smooth);
}

std::optional<Eigen::Vector3d> NodeColour::plate_xyz(const SpectralNodes& nodes, const PlateNodeTerms& terms) const {
    if (plate_cosine_phase_.empty()) return std::nullopt;
    if (!(nodes.tail(terms.angle) <= kPhaseTolerance_rad)) return std::nullopt;
    // The terms that are not zero (PlateNodeTerms); U_i = −T_i.
    const bool cross = terms.cross, active_cross = terms.active && terms.cross;
    const NodeValues* sine_term = terms.active ? &terms.sine : nullptr;
    const std::array<const NodeValues*, 8> checked{&terms.smooth, &terms.cosine, sine_term, cross ? &terms.in_phase : nullptr,
                                                   cross ? &terms.in_phase_cosine : nullptr, active_cross ? &terms.in_phase_sine : nullptr,
                                                   active_cross ? &terms.quadrature : nullptr, cross ? &terms.quadrature_sine : nullptr};
    if (!nodes.tails_within(checked, kTermTolerance)) return std::nullopt;
    // Where θ changes little over the spectrum every term is smooth, cos θ and sin θ included: three linear forms in
    // node values, one per spectral weight (W, W·cos Γ, W·sin Γ).
    if (const std::optional<std::array<NodeValues, 2>> cosine_sine = smooth_cosine_sine(nodes, terms.angle)) {
        const auto& [cosine, sine] = *cosine_sine;
        NodeValues plain, in_phase, quadrature;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            plain[j] = terms.smooth[j] + terms.cosine[j] * cosine[j] + terms.sine[j] * sine[j];
            in_phase[j] = terms.in_phase[j] + terms.in_phase_cosine[j] * cosine[j] + terms.in_phase_sine[j] * sine[j];
            quadrature[j] = terms.quadrature[j] + terms.quadrature_cosine[j] * cosine[j] + terms.quadrature_sine[j] * sine[j];
        }
        if (nodes.tail(plain) <= kTermTolerance && nodes.tail(in_phase) <= kTermTolerance && nodes.tail(quadrature) <= kTermTolerance) {
            return weighted_sum(plain_, plain) + weighted_sum(plate_cosine_, in_phase) - weighted_sum(plate_sine_, quadrature);
        }
    }
    // I − S − T-terms = (X + cos Γ·U_r − sin Γ·U_i)·cos θ + (Y + cos Γ·V_r − sin Γ·V_i)·sin θ.
    const Eigen::Vector3d steady = weighted_sum(plain_, terms.smooth) + weighted_sum(plate_cosine_, terms.in_phase) - weighted_sum(plate_sine_, terms.quadrature);
    const Amplitude cosine_amplitude{&terms.cosine, cross ? &terms.in_phase_cosine : nullptr, active_cross ? &terms.quadrature_cosine : nullptr};
    const Amplitude sine_amplitude{sine_term, active_cross ? &terms.in_phase_sine : nullptr, cross ? &terms.quadrature_sine : nullptr};
    return steady + oscillating_sum<Oscillation::rotation>(nodes, terms.angle, {cosine_amplitude, sine_amplitude});
}

}  // namespace petroscope::detail
