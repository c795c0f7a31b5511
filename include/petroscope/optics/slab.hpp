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
/// ξ = n·sin θ·(cos φ, sin φ), conserved across every planar interface (docs/theory.md §4).
struct TangentialWavevector {
    Eigen::Vector2d xi = Eigen::Vector2d::Zero();
    Eigen::Vector2d radial = Eigen::Vector2d::UnitX();      // ρ̂ = ξ/|ξ| (x̂ at normal incidence): p direction
    Eigen::Vector2d azimuthal = Eigen::Vector2d::UnitY();   // ŝ = ẑ × ρ̂: s direction
    static TangentialWavevector from_xi(const Eigen::Vector2d& xi);
};

/// One plane-wave mode of the slab: q = k_z/k₀, E and H = N × E (H in units of √(ε₀/μ₀)), N = (ξ, q).
struct SlabMode {
    double q = 0.0;
    Eigen::Vector3d e_field = Eigen::Vector3d::Zero();
    Eigen::Vector3d h_field = Eigen::Vector3d::Zero();
};

/// The tangential field ψ = (E·ρ̂, H·ŝ, E·ŝ, −H·ρ̂) of a mode in the plane-of-incidence frame of
/// `direction` (Berreman's ordering, docs/conventions.md "Fields and bases").
Eigen::Vector4d tangential_field(const SlabMode& mode, const TangentialWavevector& direction);

/// Time reversal of a mode of a lossless medium: N → −N, E → E, H → −H. The backward modes for ξ are
/// the time-reversed forward modes for −ξ.
SlabMode time_reversed(const SlabMode& mode);

/// The two forward modes (index 0 fast sheet, 1 slow sheet) for the tangential wavevector ξ: solves
/// |N|²·(1/n_σ²(N̂)) = 1 for q along N = (ξ, q) on each sheet σ of the Biot–Fresnel index surface
/// (eigenmodes.hpp) by Newton's method safeguarded with bisection (closed form for uniaxial crystals).
/// `guess` (fast, slow), if finite, starts the iterations (e.g. the previous wavelength's roots).
/// Returns false when a sheet has no propagating mode (|ξ| beyond its index: evanescent).
bool solve_forward_modes(const BinormalFrame& frame, const Eigen::Vector2d& xi, const Eigen::Vector2d& guess,
                         std::array<SlabMode, 2>& modes);

/// A mode in `Real` (long double or double): q and E (H = N × E), for the interface model
/// (optics/interface.hpp), whose fluxes balance far below double precision near grazing incidence when
/// `Real` is long double.
template <typename Real>
struct SheetMode {
    Real q = Real(0);
    Eigen::Matrix<Real, 3, 1> e_field = Eigen::Matrix<Real, 3, 1>::Zero();
};

/// Both real roots of each sheet for the tangential wavevector ξ, in `Real`, with their fields
/// (index 2σ, 2σ + 1 for sheet σ = 0 fast, 1 slow; forward and backward are for the caller to tell apart
/// by their flux, since in a tilted crystal both roots of a sheet can have q > 0). The roots bracket the
/// interval of q inside the sheet, found from the minimum of the sheet equation along the line N = (ξ, q).
/// Returns false when a sheet has no real root (evanescent modes). Defined for double and long double.
template <typename Real>
bool solve_sheet_modes(const BasicBinormalFrame<Real>& frame, const Eigen::Vector2d& xi, std::array<SheetMode<Real>, 4>& modes);

/// The four modes of the crystal for one tangential wavevector.
struct SlabModes {
    std::array<SlabMode, 2> forward;
    std::array<SlabMode, 2> backward;
    bool propagating = true;  // false when a sheet has no real solution (evanescent): no power crosses
};

/// Forward modes at ξ and backward modes as the time-reversed forward modes at −ξ.
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
    /// Optical activity (gyration_coupling): the forward amplitudes a = (fast, slow) obey da/dz = i·k₀·Q·a with
    /// Q = [[q_fast, i·c₀], [−i·c₁, q_slow]]; zero for an inactive crystal (Q diagonal).
    Eigen::Vector2d gyration_coupling = Eigen::Vector2d::Zero();
    bool propagating = true;
};
SlabTransfer slab_transfer(const SlabModes& modes, const TangentialWavevector& direction, double n_entrance,
                           double n_exit);

/// The coupling (c₀, c₁) of SlabTransfer that the gyration tensor g (lab frame, optics/gyration.hpp) puts between
/// the two forward modes of ξ: first-order coupled-mode theory (Yariv, IEEE J. Quantum Electron. 9, 919 (1973))
/// for the perturbation i(g·N)×E of D (Landau & Lifshitz vol. 8 §101), c₀ = τ/(2f_fast), c₁ = τ/(2f_slow) with τ = (g·N̄)·(E_slow × E_fast), fₘ = (Eₘ × Hₘ)_z and
/// N̄ = (ξ, (q_fast + q_slow)/2). Exact along the optic axis; elsewhere its error in q is of order g², below
/// 1e-9 for quartz (docs/theory.md, "Optical activity").
Eigen::Vector2d gyration_coupling(const std::array<SlabMode, 2>& forward, const Eigen::Vector2d& xi, const Eigen::Matrix3d& gyration);

/// The propagation of the forward amplitudes across the slab, exp(i·k₀d·Q): diagonal, exp(i·k₀d·q_m), for an
/// inactive crystal; otherwise e^{iφ̄}(cos Ω·I + i·(sin Ω/Ω)·k₀d·(Q − q̄I)), φ̄ = k₀d·q̄, q̄ the mean of the q,
/// Ω = k₀d·√(((q_fast − q_slow)/2)² + c₀c₁) (the exponential of a 2×2 matrix from its eigenvalues).
Eigen::Matrix2cd slab_propagation(const SlabTransfer& transfer, double k0_thickness);

/// The slab's Jones matrix in the (s, p) basis: exit · slab_propagation · entry.
Eigen::Matrix2cd slab_jones(const SlabTransfer& transfer, double wavelength_nm, double thickness_um);

}  // namespace petroscope
