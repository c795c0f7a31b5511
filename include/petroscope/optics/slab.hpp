#pragma once
// A plane-parallel crystal slab between two isotropic media, for one wavelength and one direction:
// the exact forward and backward modes for a given tangential wavevector and the single-pass
// transmission (Fresnel at both faces, no multiple reflections).
#include "petroscope/optics/indicatrix.hpp"

#include <Eigen/Core>

#include <array>
#include <complex>

namespace petroscope {

/// The direction of a plane wave crossing the stack, given by its tangential wavevector in units of k₀,
/// ξ = n·sin θ·(cos φ, sin φ), conserved across every planar interface (physics notes §3).
struct TangentialWavevector {
    Eigen::Vector2d xi = Eigen::Vector2d::Zero();
    Eigen::Vector2d radial = Eigen::Vector2d::UnitX();      // ρ̂ = ξ/|ξ| (x̂ at normal incidence): p direction
    Eigen::Vector2d azimuthal = Eigen::Vector2d::UnitY();   // ŝ = ẑ × ρ̂: s direction
    static TangentialWavevector from_xi(const Eigen::Vector2d& xi);
};

/// One plane-wave mode of the slab: q = k_z/k₀ and its tangential field ψ = (E_ρ, H_s, E_s, −H_ρ)
/// (Berreman's ordering in the plane-of-incidence frame, H in units of √(ε₀/μ₀), so H = N × E).
struct SlabMode {
    double q = 0.0;
    Eigen::Vector4d psi = Eigen::Vector4d::Zero();
};

/// The four modes of the crystal for one tangential wavevector: index 0 fast sheet, 1 slow sheet.
struct SlabModes {
    std::array<SlabMode, 2> forward;
    std::array<SlabMode, 2> backward;
    bool propagating = true;  // false when a sheet has no real solution (evanescent): no power crosses
};

/// Solves |N|²·(1/n_σ²(N̂)) = 1 for q along N = (ξ, q) on each sheet σ of the Biot–Fresnel index surface
/// (eigenmodes.hpp), by Newton's method safeguarded with bisection (closed form for uniaxial crystals).
/// `forward_guess` (fast, slow), if finite, starts the forward iterations (e.g. the previous wavelength's
/// roots).
SlabModes solve_slab_modes(const BinormalFrame& frame, const TangentialWavevector& direction,
                           const Eigen::Vector2d& forward_guess);

/// Single-pass transmission through the slab in the s/p bases of the isotropic entrance and exit media
/// (s = ŝ, p in the plane of incidence; its transverse part along +ρ̂).
/// entry: incident (s, p) amplitudes → forward mode amplitudes (fast, slow) just inside the entrance face;
/// exit: forward mode amplitudes at the exit face → transmitted (s, p) amplitudes in the exit medium.
/// Fields are matched at each face with the reflected waves eliminated by the isotropic media's
/// forward/backward amplitude projections, so both are exact 2×2 reductions of the 4×4 boundary problem.
struct SlabTransfer {
    Eigen::Vector2d q = Eigen::Vector2d::Zero();  // forward q of the fast and slow modes
    Eigen::Matrix2d entry = Eigen::Matrix2d::Zero();
    Eigen::Matrix2d exit = Eigen::Matrix2d::Zero();
    bool propagating = true;
};
SlabTransfer slab_transfer(const SlabModes& modes, const TangentialWavevector& direction, double n_entrance,
                           double n_exit);

/// The slab's Jones matrix in the (s, p) basis: exit · diag(exp(i·k₀·q_m·d)) · entry.
Eigen::Matrix2cd slab_jones(const SlabTransfer& transfer, double wavelength_nm, double thickness_um);

}  // namespace petroscope
