#pragma once
// Plane-parallel layers between two half-spaces of air (or another isotropic medium), crossed by one plane wave: the Jones matrix of
// the element in the (s, p) bases of the air on either side, single pass (Fresnel at every interface, no
// multiple reflections) or exact (coherent 4×4, every multiple reflection). Microscope elements separated
// by air and lenses (the section, an accessory plate) are each one such element, incoherent with the
// others (docs/orthoscope.md).
#include "petroscope/optics/berreman.hpp"

#include <Eigen/Core>

#include <array>
#include <complex>
#include <vector>

namespace petroscope {

/// One layer: relative permittivity in the lab frame (z = microscope axis, upward) and thickness.
struct OpticalLayer {
    Eigen::Matrix3cd epsilon = Eigen::Matrix3cd::Identity();
    double thickness_um = 0.0;
    Eigen::Matrix3d chirality = Eigen::Matrix3d::Zero();  // optical activity, lab frame (optics/berreman.hpp); zero: inactive
};


/// The single-pass Jones matrix of air | layers | air for the tangential wavevector ξ (units of k₀), split over
/// the two modes of one layer, the "variable" one: J(d) = Σₘ term[m]·exp(i·phase_per_um[m]·d) for that layer's
/// thickness d in µm (its own thickness_um is not used). Columns: incident (s, p); rows: transmitted (s, p);
/// s = ŝ, p with its transverse part along +ρ̂ (docs/conventions.md), ρ̂ = ξ/|ξ| (x̂ at ξ = 0).
/// At each interface the forward waves of one medium are matched to the forward waves of the next with the
/// reflected waves eliminated (Berreman 1972; docs/theory.md §4): an exact 2×2 reduction of the 4×4 boundary
/// problem for the waves going up.
struct ModalJones {
    std::array<Eigen::Matrix2cd, 2> term;
    std::array<std::complex<double>, 2> phase_per_um;  // k₀·q of the variable layer's forward modes, rad/µm
    bool propagating = true;  // false when a forward mode of some layer is evanescent (no power crosses)

    Eigen::Matrix2cd at(double thickness_um) const;
};

/// The four waves of a medium for one ξ (berreman_modes: forward 0, 1; backward 2, 3).
using MediumWaves = std::array<BerremanMode, 4>;

/// The waves of a medium at normal incidence (ξ = 0) in closed form: the transverse field E_t is an eigenvector
/// of η = ε_tt − ε_tz·ε_zt/ε_zz with q² its eigenvalue, E_z = −ε_zt·E_t/ε_zz, H = N × E, and the backward waves
/// have −q and the same E (the wave equation holds q² only; Yeh, Optical Waves in Layered Media, §9.2).
/// q = √λ with Re q ≥ 0 (Im q ≥ 0 in an absorbing medium: decaying upward). Forward waves by increasing |Re q|;
/// a degenerate pair (|Δq²| ≤ 1e-12·|q²|) is [ŷ, x̂], the s and p of ξ = 0. Agrees with berreman_modes up to
/// the free phase and scale of each wave.
MediumWaves normal_incidence_waves(const Eigen::Matrix3cd& epsilon);

/// Forward waves of `from` meeting `to` at their common interface, with nothing coming back down from `to`
/// (Berreman 1972 eq. 13, tangential E and H continuous): the amplitudes of `to`'s forward waves and of
/// `from`'s backward waves (berreman_modes 2, 3) per unit amplitude of each incident forward wave (columns).
struct ForwardBoundary {
    Eigen::Matrix2cd transmission, reflection;
};
ForwardBoundary forward_boundary(const MediumWaves& from, const MediumWaves& to);

/// Forward waves of `from` → forward waves of `to` at their common interface, in the two media's wave bases
/// (single pass: forward_boundary's transmission).
Eigen::Matrix2cd forward_transmission(const MediumWaves& from, const MediumWaves& to);

/// Propagation of the forward waves across a layer: diag(exp(i·k₀·qₘ·d)), k₀ in rad/µm.
Eigen::Matrix2cd forward_propagation(const MediumWaves& waves, double k0_per_um, double thickness_um);

/// The split of a single-pass Jones matrix over the two forward waves of one layer: `below` takes the incident
/// amplitudes to that layer's forward waves at its lower face, `above` takes them from its upper face out.
ModalJones split_over_layer(const Eigen::Matrix2cd& below, const MediumWaves& layer, const Eigen::Matrix2cd& above,
                            double k0_per_um);

/// k₀ = 2π/λ in rad/µm for λ in nm; throws std::invalid_argument for λ ≤ 0.
double wavenumber_per_um(double wavelength_nm);

/// `ambient_n`: the index of the half-spaces (1: air; an immersion medium for index-matched tests).
ModalJones single_pass_jones(const std::vector<OpticalLayer>& layers, std::size_t variable_layer,
                             double wavelength_nm, const Eigen::Vector2d& xi, double ambient_n = 1.0);

/// The exact coherent Jones matrix of air | layers | air (Berreman 4×4, optics/berreman.hpp): every multiple
/// reflection inside the element, in the same bases as single_pass_jones.
Eigen::Matrix2cd coherent_jones(const std::vector<OpticalLayer>& layers, double wavelength_nm,
                                const Eigen::Vector2d& xi, double ambient_n = 1.0);

}  // namespace petroscope
