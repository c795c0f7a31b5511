#include "spectral_nodes.hpp"

#include "conoscope_kernel.hpp"
#include "interference.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace petroscope::detail {

SpectralNodes::SpectralNodes(const std::vector<double>& grid_nm)
    : grid_size_(grid_nm.size()), padded_size_(padded_length(grid_nm.size())) {
    const auto [shortest, longest] = std::minmax_element(grid_nm.begin(), grid_nm.end());
    // The σ interval (nm⁻¹), mapped to x ∈ [−1, 1].
    const double sigma_low_per_nm = 1.0 / *longest, sigma_high_per_nm = 1.0 / *shortest;
    const double middle_per_nm = 0.5 * (sigma_high_per_nm + sigma_low_per_nm), half_per_nm = 0.5 * (sigma_high_per_nm - sigma_low_per_nm);
    // Chebyshev–Lobatto points x_j = cos(jπ/(n − 1)) with barycentric weights (−1)ʲ, halved at both ends.
    constexpr int n = static_cast<int>(kSpectralNodes);
    std::array<double, kSpectralNodes> x{}, weight{};
    for (int j = 0; j < n; ++j) {
        x[j] = std::cos(std::numbers::pi * j / (n - 1));
        weight[j] = (j % 2 == 0 ? 1.0 : -1.0) * (j == 0 || j == n - 1 ? 0.5 : 1.0);
        nodes_nm_[j] = 1.0 / (middle_per_nm + half_per_nm * x[j]);
    }
    // Chebyshev coefficients from values at the Lobatto points (Trefethen 2013, eq. 3.11 with the DCT-I):
    // c_k = (2/(n − 1))·Σ″_j f_j cos(πjk/(n − 1)), Σ″ halving the first and last terms, c_{n−1} halved too.
    for (int row = 0; row < 2; ++row) {
        const int k = n - 2 + row;
        for (int j = 0; j < n; ++j) {
            const double ends = (j == 0 || j == n - 1 ? 0.5 : 1.0) * (k == n - 1 ? 0.5 : 1.0);
            tail_rows_[row][j] = 2.0 / (n - 1) * ends * std::cos(std::numbers::pi * j * k / (n - 1));
        }
    }
    basis_.assign(kSpectralNodes * padded_size_, 0.0);
    for (std::size_t w = 0; w < padded_size_; ++w) {
        const double at = (1.0 / grid_nm[std::min(w, grid_size_ - 1)] - middle_per_nm) / half_per_nm;
        std::array<double, kSpectralNodes> term{};
        double sum = 0.0;
        int coinciding = -1;
        for (int j = 0; j < n; ++j) {
            if (at == x[j]) coinciding = j;
            term[j] = weight[j] / (at - x[j]);
            sum += term[j];
        }
        for (int j = 0; j < n; ++j) {
            const double value = coinciding >= 0 ? (j == coinciding ? 1.0 : 0.0) : term[j] / sum;
            basis_[static_cast<std::size_t>(j) * padded_size_ + w] = value;
        }
    }
    single_basis_.resize(basis_.size());
    std::transform(basis_.begin(), basis_.end(), single_basis_.begin(), [](double value) { return static_cast<float>(value); });
}

namespace {

// Interpolates δ and `Quantities` (2 or 4) node quantities to every grid wavelength, in vector lanes over
// the wavelengths (the node values are the same in every lane), and stores evaluate(w, v₀, v₁, v₂, v₃, δ).
// The quantities are scalars: GCC 12 does not vectorise a loop whose body holds a local array.
template <int Quantities, typename Evaluate>
void over_grid(const SpectralNodes& nodes, const std::array<NodeValues, 4>& values, const NodeValues& phase, double* out,
               const Evaluate& evaluate) {
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size();
    const int count = static_cast<int>(nodes.grid_size());
    const NodeValues &a0 = values[0], &a1 = values[1], &a2 = values[2], &a3 = values[3];
#pragma omp simd
    for (int w = 0; w < count; ++w) {
        double v0 = 0.0, v1 = 0.0, v2 = 0.0, v3 = 0.0, delta = 0.0;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            const double b = basis[j * stride + static_cast<std::size_t>(w)];
            delta += b * phase[j];
            v0 += b * a0[j];
            v1 += b * a1[j];
            if constexpr (Quantities == 4) {
                v2 += b * a2[j];
                v3 += b * a3[j];
            }
        }
        out[w] = evaluate(w, v0, v1, v2, v3, delta);
    }
}

}  // namespace

void interpolated_transmission(const SpectralNodes& nodes, const std::array<NodeValues, 4>& amplitudes, int pairs,
                               const NodeValues& phase_difference, double* out) {
    if (pairs == 1) {
        over_grid<2>(nodes, amplitudes, phase_difference, out, [](int, double c0, double c1, double, double, double delta) {
            return pair_intensity(c0, c1, sin_squared(0.5 * delta));
        });
    } else {
        over_grid<4>(nodes, amplitudes, phase_difference, out, [](int, double c0, double c1, double c2, double c3, double delta) {
            const double sin2 = sin_squared(0.5 * delta);
            return pair_intensity(c0, c1, sin2) + pair_intensity(c2, c3, sin2);
        });
    }
}

void interpolated_terms(const SpectralNodes& nodes, const RotationNodeTerms& terms, double thickness_um, InterferenceTerms* out) {
    // In chunks: the interpolation in vector lanes over the wavelengths into arrays, then the terms' fields.
    constexpr std::size_t kChunk = 64;
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size(), count = nodes.grid_size();
    const auto& [smooth, cosine, sine, angle] = terms;
    const double per_um = 1.0 / thickness_um;
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
        const std::size_t length = std::min(kChunk, count - begin);
        std::array<double, kChunk> mean, modulation, sine_modulation, phase;
#pragma omp simd
        for (std::size_t i = 0; i < length; ++i) {
            double s = 0.0, x = 0.0, y = 0.0, theta = 0.0;
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                const double b = basis[j * stride + begin + i];
                s += b * smooth[j];
                x += b * cosine[j];
                y += b * sine[j];
                theta += b * angle[j];
            }
            mean[i] = s;
            modulation[i] = x;
            sine_modulation[i] = y;
            phase[i] = theta * per_um;
        }
        for (std::size_t i = 0; i < length; ++i) out[begin + i] = {mean[i], modulation[i], phase[i], sine_modulation[i]};
    }
}

std::optional<RotationNodeTerms> active_node_terms(const ActiveNodeFields& fields, const NodeValues& phase_difference) {
    // Per component k at node j, with h = δ/2 and Ω = √(h² + b₀b₁) (spectral_nodes.hpp, interpolated_active_transmission):
    // |R + iI|² = cos²Ω·A² + 2cosΩ·(sinΩ/Ω)·AB + (sin²Ω/Ω²)·(B² + h²C²) with A = F₀ + F₁, B = G₁ − G₀, C = F₀ − F₁,
    // which is S + X·cos 2Ω + Y·sin 2Ω with D = (B² + h²C²)/Ω², S = (A² + D)/2, X = (A² − D)/2, Y = AB/Ω; the
    // components' S, X, Y add.
    RotationNodeTerms terms;
    const std::array<NodeValues, 4>&first = fields.component[0], &second = fields.component[1];
    const double second_weight = fields.components == 2 ? 1.0 : 0.0;
    double least_omega = std::numeric_limits<double>::infinity();
#pragma omp simd reduction(min : least_omega)
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const double h = 0.5 * phase_difference[j];
        const double omega = active_rotation(h, fields.coupling_product[j]);
        least_omega = std::min(least_omega, omega);
        terms.angle[j] = 2.0 * omega;
        const double inverse_omega = 1.0 / std::max(omega, kLeastRotation_rad);
        const ActiveSums u = active_sums(first, j), v = active_sums(second, j);
        const double a_squared = u.a * u.a + second_weight * v.a * v.a;
        const double d = (u.b * u.b + h * h * u.c * u.c + second_weight * (v.b * v.b + h * h * v.c * v.c)) * inverse_omega * inverse_omega;
        terms.smooth[j] = 0.5 * (a_squared + d);
        terms.cosine[j] = 0.5 * (a_squared - d);
        terms.sine[j] = (u.a * u.b + second_weight * v.a * v.b) * inverse_omega;
    }
    if (!(least_omega > kLeastRotation_rad)) return std::nullopt;
    return terms;
}

bool interpolable(const SpectralNodes& nodes, const RotationNodeTerms& terms) {
    return nodes.tail(terms.angle) <= kPhaseTolerance_rad &&
           nodes.tails_within(std::array<const NodeValues*, 3>{&terms.smooth, &terms.cosine, &terms.sine}, kTermTolerance);
}

void interpolated_transmission(const SpectralNodes& nodes, const std::array<NodeValues, 4>& lab_fields, const NodeValues& phase_difference,
                               const PlateAnalyzers& analyzers, double* out) {
    const auto& b = analyzers.lab;
    const double *re_x0 = b[0][0], *re_y0 = b[0][1], *im_x0 = b[0][2], *im_y0 = b[0][3];
    const double *re_x1 = b[1][0], *re_y1 = b[1][1], *im_x1 = b[1][2], *im_y1 = b[1][3];
    const bool second = analyzers.count == 2;
    // lab_fields: x of the fast and slow mode, then y of the fast and slow mode.
    over_grid<4>(nodes, lab_fields, phase_difference, out, [&](int w, double x0, double x1, double y0, double y1, double delta) {
        const SineCosine phase = sine_cosine(delta);
        const double first = complex_analyzer_intensity(re_x0[w], re_y0[w], im_x0[w], im_y0[w], x0, y0, x1, y1, phase.cosine, phase.sine);
        return second ? first + complex_analyzer_intensity(re_x1[w], re_y1[w], im_x1[w], im_y1[w], x0, y0, x1, y1, phase.cosine, phase.sine)
                      : first;
    });
}

namespace {

// The field of one component at one wavelength from its interpolated F₀, F₁, G₀, G₁ (interpolated_active_transmission).
struct ComplexComponent {
    double real, imaginary;
};
[[gnu::always_inline]] inline ComplexComponent component_field(double f0, double f1, double g0, double g1, double cosine, double sinc,
                                                                 double half_delta) {
    return {cosine * (f0 + f1) + sinc * (g1 - g0), sinc * half_delta * (f0 - f1)};
}

// Interpolates δ, b₀b₁ and the 4·Components field quantities to every grid wavelength (scalars, as in over_grid)
// and stores evaluate(w, first, second) of the components' fields there.
template <int Components, typename Evaluate>
void over_grid_active(const SpectralNodes& nodes, const ActiveNodeFields& fields, const NodeValues& phase, double* out,
                      const Evaluate& evaluate) {
    const double* basis = nodes.basis();
    const std::size_t stride = nodes.padded_grid_size();
    const int count = static_cast<int>(nodes.grid_size());
    const auto &first = fields.component[0], &second = fields.component[1];
    const NodeValues& product = fields.coupling_product;
#pragma omp simd
    for (int w = 0; w < count; ++w) {
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0, b0 = 0.0, b1 = 0.0, b2 = 0.0, b3 = 0.0, delta = 0.0, p = 0.0;
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            const double b = basis[j * stride + static_cast<std::size_t>(w)];
            delta += b * phase[j];
            p += b * product[j];
            a0 += b * first[0][j];
            a1 += b * first[1][j];
            a2 += b * first[2][j];
            a3 += b * first[3][j];
            if constexpr (Components == 2) {
                b0 += b * second[0][j];
                b1 += b * second[1][j];
                b2 += b * second[2][j];
                b3 += b * second[3][j];
            }
        }
        const double half_delta = 0.5 * delta;
        const double omega = active_rotation(half_delta, p);
        const SineCosine sc = sine_cosine(omega);
        const double sinc = sinc_from_sine(omega, sc.sine);
        out[w] = evaluate(w, component_field(a0, a1, a2, a3, sc.cosine, sinc, half_delta),
                          component_field(b0, b1, b2, b3, sc.cosine, sinc, half_delta));
    }
}

}  // namespace

void interpolated_active_transmission(const SpectralNodes& nodes, const ActiveNodeFields& fields, const NodeValues& phase_difference,
                                      const PlateAnalyzers* analyzers, double* out) {
    const auto norm = [](ComplexComponent c) { return c.real * c.real + c.imaginary * c.imaginary; };
    if (fields.components == 1) {
        over_grid_active<1>(nodes, fields, phase_difference, out, [&](int, ComplexComponent u, ComplexComponent) { return norm(u); });
        return;
    }
    if (analyzers == nullptr) {
        over_grid_active<2>(nodes, fields, phase_difference, out,
                            [&](int, ComplexComponent u, ComplexComponent v) { return norm(u) + norm(v); });
        return;
    }
    const auto& b = analyzers->lab;
    const double *re_x0 = b[0][0], *re_y0 = b[0][1], *im_x0 = b[0][2], *im_y0 = b[0][3];
    const double *re_x1 = b[1][0], *re_y1 = b[1][1], *im_x1 = b[1][2], *im_y1 = b[1][3];
    const bool second = analyzers->count == 2;
    // |bᵀ(R + iI)|² = (b_re·R − b_im·I)² + (b_re·I + b_im·R)² with the components (x, y).
    const auto analyzed = [&](double re_x, double re_y, double im_x, double im_y, ComplexComponent x, ComplexComponent y) {
        const double real = re_x * x.real + re_y * y.real - im_x * x.imaginary - im_y * y.imaginary;
        const double imaginary = re_x * x.imaginary + re_y * y.imaginary + im_x * x.real + im_y * y.real;
        return real * real + imaginary * imaginary;
    };
    over_grid_active<2>(nodes, fields, phase_difference, out, [&](int w, ComplexComponent x, ComplexComponent y) {
        const double first = analyzed(re_x0[w], re_y0[w], im_x0[w], im_y0[w], x, y);
        return second ? first + analyzed(re_x1[w], re_y1[w], im_x1[w], im_y1[w], x, y) : first;
    });
}

}  // namespace petroscope::detail
