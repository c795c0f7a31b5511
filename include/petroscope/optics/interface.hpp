#pragma once
// The exact local model of a plane wave meeting a plane interface between two homogeneous media
// (isotropic or anisotropic, lossless or absorbing, optically active or not): every reflected and transmitted
// wave with its direction, ray, index, amplitude, power and polarization. Conventions: docs/interface.md.
#include "petroscope/optics/medium.hpp"
#include "petroscope/optics/polarization.hpp"

#include <Eigen/Core>

#include <complex>
#include <optional>
#include <string_view>
#include <vector>

namespace petroscope {

/// Which mode a wave is: the one (s+p) wave of an isotropic medium, the fast/slow eigenmodes (by Re n) of
/// a biaxial one or of an optically active one (elliptical waves), the ordinary/extraordinary ones of an
/// inactive uniaxial one. (Not eigenmodes.hpp's WaveMode, a mode's index and fields.)
enum class InterfaceMode { isotropic, fast, slow, ordinary, extraordinary };

/// The mode's name in files and output: "s+p", "fast", "slow", "ordinary", "extraordinary".
std::string_view wave_mode_name(InterfaceMode mode);
/// The inverse of wave_mode_name; nothing for any other text.
std::optional<InterfaceMode> parse_wave_mode(std::string_view name);

/// The arithmetic of the solve. long_double (x87 extended, 64-bit significand): the fluxes of the waves
/// balance to about 1e-15 even near grazing incidence, critical angles and optic axes (docs/interface.md).
/// double_precision: about twice as fast, for callers that need less (the renderer); it agrees with
/// long_double to about 4e-11 in every power and Stokes parameter, 6e-10 on an optic axis (tested).
enum class InterfaceArithmetic { long_double, double_precision };

struct InterfaceIncidence {
    /// Wave normal in medium 1 (lab frame); its component along the interface normal must be positive.
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
    /// Isotropic medium 1: the state in the incident wave's (s, p) basis (trace normalised by the solver).
    CoherencyMatrix coherency = CoherencyMatrix::Identity() * 0.5;
    /// Isotropic medium 1, fully polarized light: the Jones vector, so that output amplitudes are reported.
    std::optional<JonesVector> jones;
    /// Anisotropic or optically active medium 1 (required): the incident eigenmode, fast or slow, or for an
    /// inactive uniaxial medium ordinary or extraordinary.
    std::optional<InterfaceMode> mode;
    /// Isotropic medium 1: also give every wave its Mueller matrix (InterfaceWave::mueller), at the cost of
    /// four more evaluations of each wave's Stokes vector.
    bool with_mueller = false;
    InterfaceArithmetic arithmetic = InterfaceArithmetic::long_double;
};

struct InterfaceWave {
    enum class Kind { reflected, transmitted };
    Kind kind = Kind::reflected;
    InterfaceMode mode = InterfaceMode::isotropic;
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();      // unit wave normal (Re N), lab frame
    Eigen::Vector3d ray_direction = Eigen::Vector3d::Zero();  // unit time-averaged Poynting vector
    std::complex<double> n = 1.0;                             // √(N·N), N = k/k₀
    /// Normal component of the Poynting flux relative to the incident one (0 for evanescent waves).
    double power = 0.0;
    /// Of the transverse E field in the wave's (s, p) basis, scaled so that S0 = power.
    Eigen::Vector4d stokes = Eigen::Vector4d::Zero();
    /// Isotropic medium 1 and InterfaceIncidence::with_mueller: the Mueller matrix from the incident Stokes
    /// vector (the incident wave's (s, p) basis, S0 = 1 for unit incident power) to `stokes`, so that
    /// stokes = mueller · S for the incident state; its first row gives the wave's power for any incident
    /// polarization.
    std::optional<Eigen::Matrix4d> mueller;
    /// Fully polarized incidence on an isotropic medium 1, isotropic wave: (E_s, E_p) for the unit
    /// incident Jones vector (so r_s, r_p, t_s, t_p for s and p incidence).
    std::optional<JonesVector> jones;
    /// Fully polarized incidence, anisotropic mode: its complex amplitude relative to the mode's unit E
    /// field (phase: the largest component of the field is real and positive); `e_field` is that field.
    std::optional<std::complex<double>> amplitude;
    Eigen::Vector3cd e_field = Eigen::Vector3cd::Zero();
    /// Anisotropic mode: its unit vibration direction D (sign free); zero for an isotropic wave and for the
    /// elliptical waves of an optically active medium (their ellipse: `stokes`, `e_field`).
    Eigen::Vector3d d_direction = Eigen::Vector3d::Zero();
    bool evanescent = false;
};

struct InterfaceResult {
    std::vector<InterfaceWave> waves;  // reflected first, then transmitted; within each, by increasing Re n
    std::complex<double> incident_n = 1.0;
    Eigen::Vector3d incident_ray_direction = Eigen::Vector3d::Zero();
};

/// Solves the boundary conditions (continuous tangential E and H, Born & Wolf §1.1.3) for the plane wave
/// `incidence` going from medium 1 into medium 2 across the plane with unit normal `normal` (pointing from
/// medium 1 into medium 2). Medium 1 must be lossless (the incident wave is homogeneous). Throws
/// InputError for zero or non-finite vectors, an incident direction not toward medium 2, a missing or unsuitable mode.
InterfaceResult solve_interface(const Eigen::Vector3d& normal, const InterfaceIncidence& incidence, const OpticalMedium& medium1,
                                const OpticalMedium& medium2);

}  // namespace petroscope
