#pragma once
// Berreman's 4×4 transfer-matrix method for stacks of anisotropic, possibly absorbing, plane-parallel layers
// (Berreman, JOSA 62, 502 (1972); Yeh, JOSA 69, 742 (1979); Schubert, PRB 53, 4265 (1996); docs/theory.md §4).
// An independent solver: it shares no code with slab.hpp, eigenmodes.hpp or indicatrix.hpp, so that it can
// cross-check them. Time dependence exp(−iωt): absorbing media have Im ε > 0 and forward waves decay toward +z.
#include <Eigen/Core>

#include <array>
#include <complex>
#include <vector>

namespace petroscope {

/// A plane-wave mode of a homogeneous medium for a tangential wavevector ξ (units of k₀), from the
/// eigen-decomposition of Berreman's Δ matrix (Berreman, JOSA 62, 502 (1972); docs/theory.md §4).
///
/// Normalisation. Isotropic media (ε = n² I): s has E = ŝ; p has E = ±(q ρ̂ − |ξ| ẑ)/n (+ forward,
/// − backward; Re n ≥ 0), a unit E whose transverse part points along +ρ̂ for propagating waves
/// (docs/conventions.md). Anisotropic media: |E| = 1, and the larger in modulus of E·ρ̂ and E·ŝ (E·ŝ on a
/// tie) is real and positive.
struct BerremanMode {
    std::complex<double> q;             // k_z/k₀
    Eigen::Vector4cd psi;               // tangential field (E_x, H_y, E_y, −H_x) in the LAB frame (z = stack normal),
                                        // H in units of √(ε₀/μ₀) so H = N × E
    Eigen::Vector3cd e_field, h_field;  // full fields, lab frame
    double flux_z = 0.0;                // ½ Re(E × H*)_z
    bool forward = true;                // carries energy toward +z (or decays toward +z when its amplitude varies)
    /// True for a wave of a LOSSLESS medium (ε Hermitian to 1e-13) whose q is not real,
    /// |Im q| > 1e-10·(1 + |q|): it carries no power (flux_z = 0 identically). Waves of absorbing media are
    /// attenuated, carry power across an interface and are never flagged evanescent.
    bool evanescent = false;
};

/// The four modes of a medium of relative permittivity ε (3×3 complex, lab frame, z = normal) for the
/// tangential wavevector ξ = (ξ_x, ξ_y) (units of k₀; ε₃₃ ≠ 0).
///
/// Forward/backward: a wave whose amplitude varies along z (|Im q| > 1e-10·(1 + |q|)) is forward when it decays
/// toward +z (Im q > 0); any other wave is forward when flux_z > 0.
/// Order: forward modes at 0 and 1, backward modes at 2 and 3; within each pair by increasing |Re q| (the
/// faster wave first), ties (within 1e-8·(1 + |q|)) by increasing |Im q|.
/// Degenerate pairs (the two q of a pair equal within 1e-8·(1 + |q|): every isotropic medium; an anisotropic
/// medium whose wave normal lies on an optic axis) have no preferred eigenvectors; there the pair is
/// [s-like, p-like]: the first has E·ρ̂ = 0 (exactly s in an isotropic medium), the second carries no cross
/// flux with the first (exactly p in an isotropic medium), both with q the mean of the pair. Isotropic media
/// (ε ∝ identity to 1e-12) are built in closed form, [s, p] in each pair.
/// Near (not at) a degeneracy the two eigenvectors are accurate only to ~1e-16/gap (gap = |q₁ − q₂|, e.g. 1e-8
/// at a gap of 1e-8); in a lossless medium the second propagating mode is made exactly flux-orthogonal to the
/// first, so that per-mode powers still add. Where a forward and a backward wave meet (q → 0, grazing
/// incidence: an exceptional point of Δ) the modes are not defined.
/// ρ̂ = ξ/|ξ| (x̂ at ξ = 0), ŝ = ẑ × ρ̂.
std::array<BerremanMode, 4> berreman_modes(const Eigen::Matrix3cd& epsilon, const Eigen::Vector2d& xi);

/// berreman_modes(epsilon, xi) and berreman_modes(epsilon, −xi) from one eigen-decomposition: without optical activity
/// the medium is symmetric under inversion, so the forward waves of −ξ are the backward waves of ξ reversed
/// (q → −q; ψ = (E_x, H_y, E_y, −H_x) → (−E_x, H_y, −E_y, −H_x)). The same modes to rounding.
std::array<std::array<BerremanMode, 4>, 2> berreman_modes_both_ways(const Eigen::Matrix3cd& epsilon, const Eigen::Vector2d& xi);

/// The same for an optically active medium: Landau's relation D = εE + i(g·N) × E written as the bianisotropic
/// D = (ε + κ²)E + iκH, B = H − iκE with the chirality tensor κ (real symmetric, lab frame; optics/gyration.hpp),
/// whose plane waves are Landau's exactly and whose 6×6 constitutive matrix is Hermitian for a Hermitian ε, so
/// that the flux is conserved across interfaces. H is the field of that relation (B = μ₀H in the inactive
/// medium); the tangential E and H are continuous. κ = 0 is berreman_modes(epsilon, xi).
std::array<BerremanMode, 4> berreman_modes(const Eigen::Matrix3cd& epsilon, const Eigen::Matrix3d& chirality, const Eigen::Vector2d& xi);

/// A plane-parallel layer of relative permittivity ε (lab frame), chirality κ (zero: inactive; see berreman_modes)
/// and thickness in µm.
struct StackLayer {
    Eigen::Matrix3cd epsilon;
    double thickness_um = 0.0;
    Eigen::Matrix3d chirality = Eigen::Matrix3d::Zero();
};

/// The coherent response of ambient | layers | substrate (semi-infinite ambient and substrate, any ε
/// each) to an incident field.
struct StackResponse {
    std::array<BerremanMode, 2> reflected_modes;                 // the ambient's backward modes (berreman_modes 2, 3)
    std::array<std::complex<double>, 2> reflected_amplitudes;    // at the ambient's interface (z = 0)
    std::array<BerremanMode, 2> transmitted_modes;               // the substrate's forward modes (berreman_modes 0, 1)
    std::array<std::complex<double>, 2> transmitted_amplitudes;  // at the substrate's interface (z = Σd)
    double incident_flux_z = 0.0;                                // of the incident wave
    /// Each wave's |flux_z|·|amplitude|² relative to the incident flux; 0 for evanescent waves and when the
    /// incident flux is not positive. For a lossless ambient the cross terms vanish and R + T + A = 1;
    /// in an absorbing ambient the incident and reflected fluxes interfere and the split is not defined.
    std::array<double, 2> reflected_power{}, transmitted_power{};
};

/// The response of the stack to `incident_psi`: the tangential field (lab frame, (E_x, H_y, E_y, −H_x)) at
/// z = 0 of a wave going toward +z in the ambient, any combination of the ambient's forward modes. Its
/// components along the ambient's backward modes, if any, are discarded. Layers go from the ambient
/// (z = 0) upward; the wavelength is in vacuum, in nm, k₀ = 2π/λ.
///
/// Layers are crossed with a scattering-matrix recursion (Ko & Inkson, PRB 38, 9945 (1988); Li, JOSA A 13,
/// 1024 (1996)) in which only decaying exponentials appear, so that thick evanescent layers stay exact. Inside a
/// layer only the invariant subspaces of Δ spanned by its forward and by its backward waves are used (not the
/// individual eigenvectors), so degenerate and nearly degenerate layers (optic axis along the normal) are exact.
/// An isotropic layer at exact grazing incidence (q = 0) is handled by raising |q| to 1e-6 (q² moves by 1e-12);
/// an anisotropic layer, the ambient or the substrate at an exceptional point (q = 0) is not supported.
/// Throws std::invalid_argument for a non-positive wavelength or a negative thickness.
StackResponse solve_stack(const Eigen::Matrix3cd& ambient, const std::vector<StackLayer>& layers,
                          const Eigen::Matrix3cd& substrate, double wavelength_nm, const Eigen::Vector2d& xi,
                          const Eigen::Vector4cd& incident_psi);

/// The same with optically active half-spaces: the ambient's and the substrate's ε and chirality κ (their
/// thicknesses are not used).
StackResponse solve_stack(const StackLayer& ambient, const std::vector<StackLayer>& layers, const StackLayer& substrate,
                          double wavelength_nm, const Eigen::Vector2d& xi, const Eigen::Vector4cd& incident_psi);

}  // namespace petroscope
