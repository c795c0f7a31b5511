#pragma once
// White light behind an accessory plate from the spectral nodes: the plate as diag(μ₁, μ₂) on its axes, and a
// point's terms (node_colour.hpp, PlateNodeTerms) from its node fields (docs/theory.md, "White light from spectral
// nodes").
#include "node_colour.hpp"
#include "spectral_nodes.hpp"

#include "petroscope/microscope/polarizing_microscope.hpp"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace petroscope::detail {

/// An accessory plate whose lab Jones matrix J is diag(μ₁, μ₂) on its slow and fast axes r₁, r₂ at every
/// wavelength, followed by the analyzers a_k (one, or x̂ and ŷ without the analyzer). The transmission of a field E
/// leaving the crystal is Σ_k |a_kᵀJE|² = EᴴHE with, on the plate's axes, Hₘₙ = Gₘₙ·μ̄ₘμₙ and G = Σ_k (Rᵀa_k)(Rᵀa_k)ᵀ
/// (the Jones calculus of Yariv & Yeh, Optical Waves in Crystals, 1984, §5.1). |μₘ| is smooth over the spectrum (the
/// plate's Fresnel factors); Γ = arg(μ̄₁μ₂), the plate's retardation, need not be.
struct PlateFrame {
    Eigen::Vector2d slow, fast;  // r₁, r₂ in the lab (x, y)
    NodeValues slow_weight{}, fast_weight{}, cross_weight{};  // |μ₁|²G₁₁, |μ₂|²G₂₂ and 2|μ₁μ₂|G₁₂ at the nodes
    std::vector<double> phase_rad;                            // Γ at every grid wavelength
    bool cross = false;                                       // G₁₂ ≠ 0: an analyzer oblique to the plate's axes
};

/// `grid_jones_lab`: J at every grid wavelength (plate_jones_lab, single pass); J at the nodes is computed here. None
/// where J is not diagonal on the plate's axes to 1e-12 (every wavelength is then evaluated).
std::optional<PlateFrame> plate_frame(const AccessoryPlate& plate, const std::vector<Eigen::Matrix2cd>& grid_jones_lab, const SpectralNodes& nodes,
                                      const Eigen::Vector2d& analyzer, bool analyzer_in);

/// A crystal without optical activity: its node fields in the lab (x of the fast and slow mode, then y of the fast
/// and slow mode; the fast mode leads by δ). Writes every member of `terms`.
void plate_terms(const PlateFrame& plate, const std::array<NodeValues, 4>& lab_fields, const NodeValues& phase_difference, PlateNodeTerms& terms);

/// An optically active crystal: its node quantities on the lab's x and y (ActiveNodeFields, two components). Writes
/// every member of `terms`; false where Ω vanishes at a node (its terms are then of no use).
bool active_plate_terms(const PlateFrame& plate, const ActiveNodeFields& fields, const NodeValues& phase_difference, PlateNodeTerms& terms);

}  // namespace petroscope::detail
