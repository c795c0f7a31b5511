#pragma once
// The colour of an image point straight from its spectral nodes, where neither a plate nor optical activity is
// in the way. Behind real polars the transmission is Σ_k (c₀ₖ + c₁ₖ)² − 4 sin²(δ/2)·Σ_k c₀ₖc₁ₖ (interference.hpp,
// pair_intensity). The colour of the first term is a quadratic form in the node values, so only the fringe term
// is summed over the wavelengths, with two interpolated quantities (δ and the product) instead of three or five
// (docs/theory.md, "White light from spectral nodes").
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

private:
    /// Σ_w W(w)·f(w)·g(w) for the interpolants f, g of the node values `left`, `right`: leftᵀ·M_c·right per channel.
    Eigen::Vector3d weighted_product(const NodeValues& left, const NodeValues& right) const;
    /// The fringe term Σ_w W(w)·P(w)·sin²(δ(w)/2) wavelength by wavelength.
    Eigen::Vector3d fringe_sum(const SpectralNodes& nodes, const NodeValues& product, const NodeValues& phase_difference) const;

    static constexpr std::size_t kFormRows = 3 * kSpectralNodes;
    // The three channels' matrices M_c = Σ_w W_c(w)·ℓᵢ(w)·ℓⱼ(w) (ℓ the nodes' basis), column j after column j − 1,
    // each column the channels' rows one after the other: element [j·kFormRows + c·8 + i] is M_c(i, j).
    std::array<double, kFormRows * kSpectralNodes> form_{};
    std::array<std::vector<double>, 3> channel_weights_;  // per channel: W(w)
};

}  // namespace petroscope::detail
