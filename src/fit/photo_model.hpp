#pragma once
// The model of a conoscopic photograph at a set of sample pixels: the geometry that maps a pixel to the
// direction ξ of the light it shows, the figure's interference terms there, the blur, and the camera.
// fit/conoscope_fit.cpp fits it; docs/fitting.md states the equations.
#include "petroscope/fit/conoscope_fit.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace petroscope::detail {

/// Sample pixels on a square lattice, in rows (neighbours in order, for the kernel's warm starts).
struct SampleLattice {
    std::vector<Eigen::Vector2d> pixels;         // pixel centres: x to the right, y down
    std::vector<std::array<int, 4>> neighbours;  // left, right, up, down; −1 where there is none
    int stride_px = 1;
};

/// Every `stride_px`-th pixel (both directions) whose centre lies within `radius_px` of `centre`, inside
/// the image.
SampleLattice sample_lattice(const Eigen::Vector2d& centre, double radius_px, int stride_px, int width_px, int height_px);

/// The box the fit keeps every parameter in.
struct PhotoBounds {
    PhotoParameters lower, upper;
};

/// For a photo of `width_px` × `height_px` and a thickness search over [thickness_min_um, thickness_max_um]:
/// thickness within half the minimum and twice the maximum, centre within the image's size outside it,
/// field radius 0.05–5 sizes, rotation ±360°, tilt ±89°, azimuth ±720°, gains 1e-3–1e3, black level
/// −0.5–0.9, gamma 0.5–5, blur variance 0–2500 px².
PhotoBounds photo_parameter_bounds(double thickness_min_um, double thickness_max_um, int width_px, int height_px);

/// ξ (units of k₀) of the light shown at `pixel` for the geometry of `values`: the pixel's offset from
/// the centre, y flipped to point N, turned by −rotation back into the lab, times NA / field radius.
Eigen::Vector2d pixel_direction(const PhotoParameters& values, double numerical_aperture, const Eigen::Vector2d& pixel);

/// ∂ξ/∂p for p = centre x, centre y, field radius, rotation (per pixel, pixel, pixel, degree) at ξ.
std::array<Eigen::Vector2d, 4> direction_derivatives(const PhotoParameters& values, double numerical_aperture,
                                                     const Eigen::Vector2d& xi);

/// [sample·W + w]: the phase's squared gradient and Laplacian over the photo.
struct PhaseDerivatives {
    std::vector<double> gradient2, laplacian;
};

/// Linear sRGB of every sample, and optionally its derivatives by thickness and by the blur's σ².
struct LinearSamples {
    std::vector<Eigen::Vector3d> rgb, d_thickness, d_blur2;
};

class PhotoModelEvaluator {
public:
    PhotoModelEvaluator(const ConoscopePhotoModel& model, SampleLattice lattice);

    const SampleLattice& lattice() const { return lattice_; }
    std::size_t sample_count() const { return lattice_.pixels.size(); }
    std::size_t wavelength_count() const { return model_.rgb_per_transmission.size(); }
    double numerical_aperture() const { return model_.settings.numerical_aperture; }

    /// The interference terms of every sample at every wavelength, out[sample·W + w], for the geometry
    /// (centre, radius, rotation, tilt, azimuth) of `values`, each ξ moved by `xi_offset` (for ∂/∂ξ).
    void terms(const PhotoParameters& values, std::vector<InterferenceTerms>& out,
               const Eigen::Vector2d& xi_offset = Eigen::Vector2d::Zero()) const;

    /// The squared gradient |∇Φ|² (rad/µm/px)² and the Laplacian ∇²Φ (rad/µm/px²) of each phase over the
    /// photo, from the lattice neighbours (central differences; one-sided, and no Laplacian, at the edge).
    void phase_derivatives(const std::vector<InterferenceTerms>& terms, PhaseDerivatives& out) const;

    /// Linear sRGB at `thickness_um` with Gaussian blur of variance `blur2_px2`. The blur of a fringe
    /// cos φ whose phase is locally quadratic is exp(−½σ²|∇φ|²)·cos(φ + ½σ²∇²φ) to first order in σ²
    /// (docs/fitting.md), with φ = Φ·d.
    void linear(const std::vector<InterferenceTerms>& terms, const PhaseDerivatives& phase, double thickness_um,
                double blur2_px2, bool derivatives, LinearSamples& out) const;

private:
    const ConoscopePhotoModel& model_;
    SampleLattice lattice_;
};

/// The camera: value = black + (gain·max(linear, 10⁻⁶))^(1/γ), and its derivatives.
struct CameraValue {
    double value, d_linear, d_gain, d_gamma;
};
CameraValue camera_value(double linear, double gain, double black, double gamma);

/// The camera values of linear sRGB samples for the camera parameters of `values`.
std::vector<Eigen::Vector3d> camera_values(const std::vector<Eigen::Vector3d>& linear_rgb, const PhotoParameters& values);

/// A Gaussian blur (σ in pixels, edges clamped) of every channel of `image`; σ ≤ 0 returns it as it is.
Image gaussian_blur(const Image& image, double sigma_px);

}  // namespace petroscope::detail
