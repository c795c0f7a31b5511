#pragma once
// The two plane-wave eigenmodes of a transparent crystal for a given wave normal.
#include "petroscope/optics/indicatrix.hpp"

#include <Eigen/Core>

namespace petroscope {

struct WaveMode {
    double n = 1.0;                    // refractive index (phase index) of the mode
    Eigen::Vector3d d_hat;             // unit vibration direction of D (⟂ the wave normal)
    Eigen::Vector3d e_field;           // E = η·D̂ (not ⟂ the wave normal in general)
    Eigen::Vector3d ray_direction;     // unit Poynting direction ŝ ∝ k̂ − tan α·D̂, tan α = n²(k̂·η·D̂)
};

struct ModePair {
    WaveMode fast;  // the smaller index
    WaveMode slow;  // the larger index
};

/// 1/n² = m ± Δ with m = (a + c)/2 + (a − c)/2·c₁c₂, Δ = (a − c)/2·s₁s₂, cᵢ = k̂·bᵢ, sᵢ = |k̂ × bᵢ|;
/// + is the fast wave (Biot–Fresnel; Born & Wolf, Principles of Optics, §15.3; docs/theory.md §1).
/// Written with cross products so that it stays exact on and near the binormals. Returns
/// (1/n_fast², 1/n_slow²) for the unit wave normal `k_hat`.
Eigen::Vector2d inverse_squared_indices(const BinormalFrame& frame, const Eigen::Vector3d& k_hat);

/// The vibration directions: D_slow ∥ p̂₁ + p̂₂, D_fast ∥ p̂₁ − p̂₂, p̂ᵢ the unit projections of the
/// binormals on the plane ⟂ k̂ (docs/theory.md §1, "Eigenmodes"); the longer of the two sums is normalised and the other
/// direction is k̂ × it. Exactly on a binormal any orthonormal pair is returned (the modes are
/// degenerate there). Returns (D̂_fast, D̂_slow).
template <typename Real>
std::pair<Eigen::Matrix<Real, 3, 1>, Eigen::Matrix<Real, 3, 1>> vibration_directions(const BasicBinormalFrame<Real>& frame,
                                                                                     const Eigen::Matrix<Real, 3, 1>& k_hat);

/// Both eigenmodes for the unit wave normal `k_hat`.
ModePair eigenmodes(const BinormalFrame& frame, const Eigen::Vector3d& k_hat);

}  // namespace petroscope
