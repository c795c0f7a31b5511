#pragma once
// The colour of an image point straight from its spectral nodes. Behind real polars the transmission is
// Σ_k (c₀ₖ + c₁ₖ)² − 4 sin²(δ/2)·Σ_k c₀ₖc₁ₖ (interference.hpp, pair_intensity); that of an optically active crystal
// S + X cos 2Ω + Y sin 2Ω with smooth S, X, Y; behind an accessory plate PlateNodeTerms' form. The colour of the
// smooth terms is a quadratic or linear form in node values, so only the oscillating terms are summed over the
// wavelengths, from a few interpolated quantities, and not even that where they are smooth themselves
// (docs/theory.md, "White light from spectral nodes").
#include "spectral_nodes.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace petroscope::detail {

/// A point's transmission behind an accessory plate that is diag(μ₁, μ₂) on its two axes (plate_terms.hpp), with
/// e^{iΓ} = μ̄₁μ₂/|μ₁μ₂| and θ = δ (inactive) or 2Ω (optically active):
/// I = S + X cos θ + Y sin θ + cos Γ·(T_r + U_r cos θ + V_r sin θ) − sin Γ·(T_i + U_i cos θ + V_i sin θ), where θ
/// and the terms are smooth over the spectrum and Γ, known at every grid wavelength, need not be.
struct PlateNodeTerms {
    bool active = false;  // unless active, Y, V_r, T_i and U_i are zero
    bool cross = false;   // unless cross (an analyzer oblique to the plate's axes), every T, U and V is zero
    // Left uninitialised: plate_terms and active_plate_terms write every one (a figure makes two such sets per point).
    NodeValues angle;  // θ
    NodeValues smooth, cosine, sine;                           // S, X, Y
    NodeValues in_phase, in_phase_cosine, in_phase_sine;        // T_r, U_r, V_r
    NodeValues quadrature, quadrature_cosine, quadrature_sine;  // T_i, U_i, V_i
};

class NodeColour {
public:
    /// `weights`: the colour weights W(w) = (x̄, ȳ, z̄)·source of the grid's wavelengths (SpectralIntegrator::weights),
    /// one per grid wavelength of `nodes`. `plate_phase_rad`: behind an accessory plate, its Γ(w) at every grid
    /// wavelength (for plate_xyz); empty without one.
    NodeColour(const SpectralNodes& nodes, const std::vector<Eigen::Vector3d>& weights, const std::vector<double>& plate_phase_rad = {});

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

    /// The colour behind a plate from its terms (PlateNodeTerms); none where a term or θ is too rough to interpolate
    /// or this object was made without the plate's phase.
    std::optional<Eigen::Vector3d> plate_xyz(const SpectralNodes& nodes, const PlateNodeTerms& terms) const;

private:
    static constexpr std::size_t kFormRows = 3 * kSpectralNodes;
    /// The forms of one spectral weight V(w) (W, W·cos Γ or W·sin Γ).
    struct Forms {
        // The three channels' matrices M_c = Σ_w V_c(w)·ℓᵢ(w)·ℓⱼ(w) (ℓ the nodes' basis), column j after column j − 1,
        // each column the channels' rows one after the other: element [j·kFormRows + c·8 + i] is M_c(i, j).
        std::array<double, kFormRows * kSpectralNodes> quadratic{};
        std::array<NodeValues, 3> linear{};  // per channel: Σ_w V_c(w)·ℓⱼ(w)
    };
    static Forms forms_of(const SpectralNodes& nodes, const std::array<std::vector<double>, 3>& channel_weights);
    /// Σ_w V(w)·f(w)·g(w) for the interpolants f, g of the node values `left`, `right`: leftᵀ·M_c·right per channel.
    static Eigen::Vector3d weighted_product(const Forms& forms, const NodeValues& left, const NodeValues& right);
    /// Σ_w V(w)·f(w) for the interpolant f of `values`.
    static Eigen::Vector3d weighted_sum(const Forms& forms, const NodeValues& values);
    /// cos θ and sin θ at the nodes where θ changes so little over the spectrum that they are as smooth as the fields;
    /// none elsewhere.
    static std::optional<std::array<NodeValues, 2>> smooth_cosine_sine(const SpectralNodes& nodes, const NodeValues& angle);
    /// Σ_w W(w)·(c(w)·cos θ(w) + s(w)·sin θ(w)) as forms in node values where smooth_cosine_sine serves; none elsewhere.
    std::optional<Eigen::Vector3d> smooth_rotation(const SpectralNodes& nodes, const NodeValues& angle, const NodeValues& cosine_part,
                                                   const NodeValues& sine_part) const;
    /// An oscillating term's amplitude a + Re(e^{iΓ}·(r + i·q)) = a + cos Γ·r − sin Γ·q: the node quantities a, r, q
    /// (nullptr: none; r and q only behind a plate).
    using Amplitude = std::array<const NodeValues*, 3>;
    /// Wavelength by wavelength: Σ_w W(w)·a(w)·sin²θ(w) (fringe: the first amplitude) or Σ_w W(w)·(a(w)·cos θ(w) +
    /// b(w)·sin θ(w)) (rotation), with θ and the amplitudes a, b interpolated from node values.
    enum class Oscillation { fringe, rotation };
    template <Oscillation Kind>
    Eigen::Vector3d oscillating_sum(const SpectralNodes& nodes, const NodeValues& angle, const std::array<Amplitude, 2>& amplitudes) const;

    Forms plain_;                                         // V = W
    Forms plate_cosine_, plate_sine_;                     // V = W·cos Γ and W·sin Γ (behind a plate)
    std::array<std::vector<double>, 3> channel_weights_;  // per channel: W(w)
    // Behind a plate, cos Γ(w) and −sin Γ(w) at every grid wavelength, padded to SpectralNodes::padded_grid_size() with zeros, in
    // single precision like the amplitudes they weight; empty without a plate.
    std::vector<float> plate_cosine_phase_, plate_minus_sine_phase_;
};

}  // namespace petroscope::detail
