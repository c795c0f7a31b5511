#pragma once
// Polarization states in the (s, p) basis of a wave, as Jones vectors, coherency matrices and Stokes
// vectors. Basis and signs: docs/interface.md.
#include <Eigen/Core>

#include <complex>

namespace petroscope {

/// (E_s, E_p).
using JonesVector = Eigen::Vector2cd;
/// C = ⟨J J†⟩: C_ss = ⟨|E_s|²⟩, C_sp = ⟨E_s E_p*⟩, … (Born & Wolf §10.8).
using CoherencyMatrix = Eigen::Matrix2cd;

/// S0 = C_ss + C_pp, S1 = C_ss − C_pp, S2 = 2 Re C_sp, S3 = −2 Im C_sp: S1 = +S0 for s, S2 = +S0 for linear
/// light at +45° from ŝ toward p̂, S3 = +S0 for (1, i)/√2, which turns from ŝ toward p̂ (right-handed:
/// clockwise as seen facing the oncoming wave, Born & Wolf's convention, for fields ∝ exp(i(k·r − ωt))).
Eigen::Vector4d stokes_from_coherency(const CoherencyMatrix& coherency);
CoherencyMatrix coherency_from_stokes(const Eigen::Vector4d& stokes);
CoherencyMatrix coherency_from_jones(const JonesVector& jones);

/// A Stokes vector of real light: finite, S0 > 0 and S1² + S2² + S3² ≤ S0² (to rounding, 1e-12 relative).
bool is_physical_stokes(const Eigen::Vector4d& stokes);

}  // namespace petroscope
