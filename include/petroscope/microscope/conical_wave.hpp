#pragma once
// Internal conical refraction in wave optics: the paraxial diffraction integrals of Belsky & Khapalyuk
// (Opt. Spectrosc. 44, 436 (1978)) in the form of Berry (J. Opt. A 6, 289 (2004)) and Berry & Jeffrey
// (Prog. Opt. 50, 13 (2007)), for a beam along a binormal of a biaxial slab (docs/theory.md §8).
//
// Units: transverse lengths are in units of the beam scale w (the Gaussian's E(r) = exp(−r²/2w²), or the
// pinhole's radius), so ρ = r/w and ρ₀ = R₀/w; Z = [z − z_waist − l(1 − 1/nβ)]/(k₀w²). Fields are in
// units of the incident field at the centre of the beam: B₀ = exp(−ρ²/2) for ρ₀ = Z = 0 (Gaussian), and
// intensities in units of the incident intensity there, so that the incident beam carries π·S₀ w².
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"

#include <Eigen/Core>

#include <complex>
#include <utility>
#include <vector>

namespace petroscope {

/// Paraxial conical diffraction behind a biaxial slab cut ⟂ a binormal (docs/theory.md §8).
/// gaussian: E(r) = exp(−r²/2w²), angular spectrum a(P) = exp(−P²/2).
/// pinhole: a uniform disc of radius w whose edge is softened by a Gaussian of rms width
/// σ = kConicalPinholeEdgeWidth·w (the disc convolved with it): a(P) = exp(−σ²P²/2)·J₁(P)/P. The softening
/// makes the spectrum decay (a sharp edge's J₁(P)/P falls only as P^(−3/2)) and blurs the geometric
/// image's edges by σ, about a pixel of a typical screen; it lowers the beam's power from π to
/// 2π∫(J₁(P)/P)² e^{−σ²P²} P dP ≈ π − 2√π σ (see conical_power).
enum class ConicalBeam { gaussian, pinhole };

/// σ: rms width of the pinhole's edge, in units of its radius.
inline constexpr double kConicalPinholeEdgeWidth = 0.05;

struct ConicalWaveParameters {
    ConicalBeam beam = ConicalBeam::gaussian;
    double rho0 = 20.0;   // ρ₀ = R₀/w: ring radius in units of the beam scale w
    double z = 0.0;       // Z: dimensionless observation distance (docs/theory.md §8); 0 = focal image plane
};

/// B₀(ρ), B₁(ρ) sampled at ρ = i·rho_max/(samples − 1), i = 0 … samples − 1.
struct ConicalProfile {
    std::vector<double> rho;
    std::vector<std::complex<double>> b0, b1;
    /// Linear interpolation in ρ (complex); throws InputError outside [0, rho.back()].
    std::pair<std::complex<double>, std::complex<double>> at(double rho) const;
};

/// B₀ = ∫₀^∞ P a(P) e^{−iZP²/2} cos(ρ₀P) J₀(ρP) dP, B₁ = ∫₀^∞ P a(P) e^{−iZP²/2} sin(ρ₀P) J₁(ρP) dP, by
/// composite 10-point Gauss–Legendre quadrature on panels of one period of the fastest oscillation
/// (absolute error below 1e-12). Cost ∝ samples × (ρ₀ + rho_max + |Z|P_max/2)·P_max with P_max = 9
/// (Gaussian) or 9/σ (pinhole). Parallel over the samples (OpenMP). Throws InputError for ρ₀ < 0,
/// rho_max ≤ 0, samples < 2, non-finite values, or more than 1e6 nodes (|Z| ≳ 1.5e4 for the Gaussian,
/// ≳ 35 for the pinhole). `progress` hears the fraction of samples done; Cancelled when it says stop.
ConicalProfile conical_profile(const ConicalWaveParameters& parameters, double rho_max, int samples, const ProgressCallback& progress = {});

/// Intensity for incident Stokes vector (S0, S1, S2, S3) at (ρ, φ), φ from +x (the direction of the ring
/// centre's offset): I = S0(|B₀|² + |B₁|²) + 2 Re(B₀B₁*)(S1 cos φ + S2 sin φ) (docs/theory.md §8), in units
/// of the incident intensity at the beam's centre per unit S0.
double conical_intensity(const ConicalProfile& profile, const Eigen::Vector4d& stokes, double rho, double phi);

/// A square image of `size` × `size` pixels covering x, y ∈ [−half_width, half_width] (units of w) around
/// the ring centre, x to the right (+x toward the offset of the ring centre, φ = 0), y up (row 0 at the
/// top), pixel centres at (i + ½); one channel, the intensity of conical_intensity (∫I dx dy = π·S0 for
/// the Gaussian, the incident power). The profile must reach the corners (rho.back() ≥ √2·half_width).
Image conical_screen(const ConicalProfile& profile, const Eigen::Vector4d& stokes, int size, double half_width);

/// Positions (in ρ) of the outer bright ring, the dark (Poggendorff) ring and the inner bright ring, from
/// the sampled I = |B₀|² + |B₁|²: the bright rings are its local maxima above 1e-3 of its largest value, the
/// dark ring is the deepest sample between the two consecutive bright rings whose valley lies nearest to
/// ρ₀; each position is refined by the parabola through three samples. Throws InputError when no such
/// pair of bright rings exists.
struct ConicalRings { double outer_bright, dark, inner_bright; };
ConicalRings conical_rings(const ConicalProfile& profile, double rho0);

/// ∫(|B₀|² + |B₁|²) 2πρ dρ over the profile (trapezoid): π for the Gaussian at every Z when the profile
/// holds the whole beam (Parseval for the Hankel transforms: 2π∫|a(P)|² P dP).
double conical_power(const ConicalProfile& profile);

}  // namespace petroscope
