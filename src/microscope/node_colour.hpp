#pragma once
// The colour of an image point straight from its spectral nodes, where no plate is in the way. Behind real polars
// the transmission is Σ_k (c₀ₖ + c₁ₖ)² − 4 sin²(δ/2)·Σ_k c₀ₖc₁ₖ (interference.hpp, pair_intensity); that of an
// optically active crystal S + X cos 2Ω + Y sin 2Ω with smooth S, X, Y. The colour of the smooth terms is a
// quadratic or linear form in node values, so only the oscillating term is summed over the wavelengths, from two
// or three interpolated quantities, and not even that where it is smooth itself (docs/theory.md, "White light
// from spectral nodes").
#include "spectral_nodes.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace petroscope::detail {

class NodeColour {
public:
    /// `weights`: the colour weights W(w) = (x̄, ȳ, z̄)·source of the grid's wavelengths (SpectralIntegrator::weights),
    /// one per grid wavelength of `nodes`.
    NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights);

    /// Σ_w W(w)·I(w) with I = Σ_k |c₀ₖe^{iφ₀} + c₁ₖe^{iφ₁}|² over `pairs` amplitude pairs (amplitudes[2k],
    /// amplitudes[2k + 1], as for interpolated_transmission) and δ = φ₀ − φ₁, all interpolated from the nodes of
    /// `nodes` (the nodes this object was made for). The product P = Σ_k c₀ₖc₁ₖ is interpolated from its node
    /// values; none where its interpolation error (SpectralNodes::tail) exceeds `product_tolerance`.
    std::optional<Eigen::Vector3d> xyz(const SpectralNodes& nodes, const std::array<NodeValues, 4>& amplitudes, int pairs,
                                       const NodeValues& phase_difference, double product_tolerance) const;

    /// The same for an optically active crystal without a plate: one component behind the analyzer, two without it
    /// (spectral_nodes.hpp, ActiveNodeFields). Each component's |R + iI|² is written S + X·cos 2Ω + Y·sin 2Ω with
    /// smooth S, X, Y, which are interpolated with Ω from their node values; none where one of them is too rough
    /// or Ω vanishes at a node.
    std::optional<Eigen::Vector3d> active_xyz(const SpectralNodes& nodes, const ActiveNodeFields& fields, const NodeValues& phase_difference) const;

private:
    /// Σ_w W(w)·f(w)·g(w) for the interpolants f, g of the node values `left`, `right`: leftᵀ·M_c·right per channel.
    Eigen::Vector3d weighted_product(const NodeValues& left, const NodeValues& right) const;
    /// Σ_w W(w)·(c(w)·cos θ(w) + s(w)·sin θ(w)) as forms in node values where θ changes so little over the spectrum
    /// that cos θ and sin θ are smooth enough; none elsewhere.
    std::optional<Eigen::Vector3d> smooth_rotation(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                                   const NodeValues& sine_part) const;
    /// Σ_w W(w)·c(w)·sin²θ(w) (not Active; `sine_part` unused) or Σ_w W(w)·(c(w)·cos θ(w) + s(w)·sin θ(w)) (Active),
    /// wavelength by wavelength, from the node values of θ, c and s.
    template <bool Active>
    Eigen::Vector3d oscillating_sum(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                    const NodeValues& sine_part) const;

    static constexpr std::size_t kFormRows = 3 * kSpectralNodes;
    // The three channels' matrices M_c = Σ_w W_c(w)·ℓᵢ(w)·ℓⱼ(w) (ℓ the nodes' basis), column j after column j − 1,
    // each column the channels' rows one after the other: element [j·kFormRows + c·8 + i] is M_c(i, j).
    std::array<double, kFormRows * kSpectralNodes> form_{};
    std::array<NodeValues, 3> linear_form_{};             // per channel: Σ_w W(w)·ℓⱼ(w)
    std::array<std::vector<double>, 3> channel_weights_;  // per channel: W(w)
};

}  // namespace petroscope::detail
