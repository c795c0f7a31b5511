#pragma once
// White light from a few wavelengths. Away from the optic axes, everything the conoscope computes for
// one image point is a smooth function of the wavenumber σ = 1/λ: the modes' fields and their phase
// difference δ. Only cos δ oscillates, up to thousands of times over the visible range in a thick
// slab. So the modes are solved at a few nodes, the fields and δ are interpolated to every wavelength of
// the grid, and the interference is evaluated there (docs/theory.md, "White light from spectral nodes").
#include "petroscope/microscope/conoscope.hpp"


#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace petroscope::detail {

/// Nodes per figure: the modes are solved at 8 wavelengths instead of every wavelength of the grid.
constexpr std::size_t kSpectralNodes = kSpectralNodeCount;

/// Polynomial interpolation in σ from Chebyshev–Lobatto nodes spanning the grid to every grid
/// wavelength, through the barycentric formula (Berrut & Trefethen 2004, SIAM Review 46, 501, eqs. 4.2
/// and 5.3): for a function analytic near [σ_min, σ_max] the error falls geometrically with the node count.
class SpectralNodes {
public:
    /// `grid_nm`: at least 2·kSpectralNodes distinct wavelengths (interpolates_spectrum).
    explicit SpectralNodes(const std::vector<double>& grid_nm);

    const std::array<double, kSpectralNodes>& wavelengths_nm() const { return nodes_nm_; }
    std::size_t grid_size() const { return grid_size_; }
    /// The stride of the basis: grid_size() rounded up to whole vectors.
    std::size_t padded_grid_size() const { return padded_size_; }
    /// Basis function j at grid wavelength w: basis()[j·padded_grid_size() + w].
    const double* basis() const { return basis_.data(); }
    /// The same basis rounded to single precision, for quantities bounded by 1 and needed to about 1e-4 (the amplitudes
    /// of oscillating terms): its rounding (6e-8) is immaterial there, and a vector holds twice the lanes.
    const float* single_basis() const { return single_basis_.data(); }

    /// An estimate of the interpolation error of a quantity from its node values: |c₆| + |c₇|, its last two
    /// Chebyshev coefficients. For a function analytic in a Bernstein ellipse of parameter ρ they fall like
    /// ρ⁻ᵏ and the error of the interpolant is of the order of the first one left out, |c₈| < |c₇|/ρ
    /// (Trefethen, Approximation Theory and Approximation Practice, 2013, Theorems 4.2 and 8.2).
    double tail(const std::array<double, kSpectralNodes>& values) const {
        double last_but_one = 0.0, last = 0.0;
#pragma omp simd reduction(+ : last_but_one, last)
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            last_but_one += tail_rows_[0][j] * values[j];
            last += tail_rows_[1][j] * values[j];
        }
        return std::abs(last_but_one) + std::abs(last);
    }
    /// Whether the tail() of each of `quantities` (nullptr: none) is at most `tolerance` (false if one is NaN).
    template <std::size_t Count>
    bool tails_within(const std::array<const std::array<double, kSpectralNodes>*, Count>& quantities, double tolerance) const {
        bool within = true;
        for (const std::array<double, kSpectralNodes>* values : quantities) within &= values == nullptr || tail(*values) <= tolerance;
        return within;
    }

private:
    std::array<double, kSpectralNodes> nodes_nm_{};
    std::array<std::array<double, kSpectralNodes>, 2> tail_rows_{};  // c₆ and c₇ from the node values
    std::size_t grid_size_ = 0, padded_size_ = 0;
    std::vector<double> basis_;
    std::vector<float> single_basis_;
};

/// Values of one quantity at the nodes.
using NodeValues = std::array<double, kSpectralNodes>;

/// Interpolation errors allowed (SpectralNodes::tail): 1e-3 rad in δ and 1e-4 in each mode's field (the incident
/// field is 1) change a transmission by at most about 1e-3, below ΔE₀₀ ≈ 0.1 where the colour is most sensitive;
/// beyond them every wavelength is solved (a thick slab of a strongly dispersive crystal).
inline constexpr double kPhaseTolerance_rad = 1e-3;
inline constexpr double kFieldTolerance = 1e-4;

/// The interpolant Σⱼ ℓⱼ(w)·values[j] at grid wavelength w (basis and stride of SpectralNodes), as two partial sums
/// over even and odd j: half the chain of dependent additions, for loops that vectorise over w.
inline double interpolate_at(const double* basis, std::size_t stride, std::size_t w, const NodeValues& values) {
    double even = 0.0, odd = 0.0;
    for (std::size_t j = 0; j < kSpectralNodes; j += 2) {
        even += basis[j * stride + w] * values[j];
        odd += basis[(j + 1) * stride + w] * values[j + 1];
    }
    return even + odd;
}

/// Transmission at every grid wavelength behind real analyzers (no plate): `pairs` amplitude pairs (c₀, c₁)
/// per analyzed component (one behind the analyzer, two without it), interpolated with δ, each giving
/// |c₀e^{iφ₀} + c₁e^{iφ₁}|² (interference.hpp). amplitudes[2k], amplitudes[2k + 1]: pair k.
void interpolated_transmission(const SpectralNodes& nodes, const std::array<NodeValues, 4>& amplitudes, int pairs,
                               const NodeValues& phase_difference, double* out);

/// The analyzers after an accessory plate at every grid wavelength: SampleCrystal::plate_analyzer, complex
/// lab-frame vectors b, one or two of them.
struct PlateAnalyzers {
    int count = 1;
    std::array<std::array<const double*, 4>, 2> lab{};  // [k]: Re b_x, Re b_y, Im b_x, Im b_y
};

/// Transmission at every grid wavelength through a plate: the modes' lab-frame fields (x of the fast and
/// slow mode, y of the fast and slow mode) and δ interpolated, then |bᵀE|² summed over the analyzers.
void interpolated_transmission(const SpectralNodes& nodes, const std::array<NodeValues, 4>& lab_fields,
                               const NodeValues& phase_difference, const PlateAnalyzers& analyzers, double* out);

/// An optically active crystal's node quantities for one or two components of the field leaving the slab
/// (projected on the analyzer; on ŝ and ρ̂ without it; on x and y before a plate): per component the fields
/// F₀ = E_fast·t_fast and F₁ = E_slow·t_slow, and the coupled fields G₀ = b₀·E_fast·t_slow and
/// G₁ = b₁·E_slow·t_fast (conoscope_kernel.hpp, mode_field and coupled_field), and the product b₀b₁.
struct ActiveNodeFields {
    int components = 1;
    std::array<std::array<NodeValues, 4>, 2> component{};  // [k]: F₀, F₁, G₀, G₁
    NodeValues coupling_product{};
};

/// An active crystal's rotation Ω = √(h² + b₀b₁) for h = δ/2 (b₀b₁ ≥ 0 up to rounding).
inline double active_rotation(double half_delta, double coupling_product) {
    return std::sqrt(std::max(half_delta * half_delta + coupling_product, 0.0));
}

/// One component's A = F₀ + F₁, B = G₁ − G₀ and C = F₀ − F₁ (ActiveNodeFields' F₀, F₁, G₀, G₁ at node j), with which the
/// component leaving the slab is cos Ω·A + (sin Ω/Ω)·B + i(sin Ω/Ω)·h·C.
struct ActiveSums {
    double a, b, c;
};
inline ActiveSums active_sums(const std::array<NodeValues, 4>& component, std::size_t j) {
    return {component[0][j] + component[1][j], component[3][j] - component[2][j], component[0][j] - component[1][j]};
}

/// Below this Ω at a node (no coupling on an optic axis) an optically active crystal's terms, which hold 1/Ω, are
/// left to the spectrum.
inline constexpr double kLeastRotation_rad = 1e-6;

/// The terms of a transmission S + X cos θ + Y sin θ (RotationNodeTerms, and a plate's: NodeColour::plate_xyz) are
/// interpolated where θ is within kPhaseTolerance_rad, as δ is, and each term within 1e-4 of the transmission.
inline constexpr double kTermTolerance = 1e-4;

/// A point's transmission S + X cos θ + Y sin θ at the nodes, with θ = 2Ω (an optically active crystal) or θ = δ and
/// Y = 0 (an inactive one), S, X, Y and θ smooth over the spectrum.
struct RotationNodeTerms {
    NodeValues smooth{}, cosine{}, sine{}, angle{};  // S, X, Y, θ
};

/// Those of an optically active crystal without a plate, the components' S, X and Y added (NodeColour::active_xyz); none
/// where Ω is below kLeastRotation_rad at a node.
std::optional<RotationNodeTerms> active_node_terms(const ActiveNodeFields& fields, const NodeValues& phase_difference);

/// Whether θ is interpolated within kPhaseTolerance_rad and S, X, Y within kTermTolerance (SpectralNodes::tail).
bool interpolable(const SpectralNodes& nodes, const RotationNodeTerms& terms);

/// The interference terms (conoscope.hpp, InterferenceTerms) at every grid wavelength from `terms` at the nodes, θ being
/// that of a slab `thickness_um` thick: mean S, modulation X, sine_modulation Y and phase_per_um θ/thickness_um, all
/// interpolated.
void interpolated_terms(const SpectralNodes& nodes, const RotationNodeTerms& terms, double thickness_um, InterferenceTerms* out);

/// Transmission at every grid wavelength of an optically active crystal: each component of the field leaving
/// the slab is R + iI with R = cos Ω·(F₀ + F₁) + (sin Ω/Ω)·(G₁ − G₀) and I = (sin Ω/Ω)·(δ/2)·(F₀ − F₁),
/// Ω = √((δ/2)² + b₀b₁) (conoscope_kernel.cpp, active_amplitudes). Without `analyzers` the result is Σ_k |R_k + iI_k|²;
/// with them (a plate; the components are lab x and y) Σ over the analyzers b of |bᵀ(R + iI)|².
void interpolated_active_transmission(const SpectralNodes& nodes, const ActiveNodeFields& fields, const NodeValues& phase_difference,
                                      const PlateAnalyzers* analyzers, double* out);

}  // namespace petroscope::detail
