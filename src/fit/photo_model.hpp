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
/// thickness within half the minimum and twice the maximum, centres within the image's size outside it,
/// field radius 0.05–5 sizes, rotation ±360°, tilt ±89°, azimuth ±720°, gains 1e-3–1e3, black level
/// −0.5–0.9, gamma 0.5–5, blur variance 0–2500 px², envelope radius 0.05–100 sizes and power 2–40,
/// distortion ±0.3, analyzer offset ±45°, extinction ratio 0–0.2.
PhotoBounds photo_parameter_bounds(double thickness_min_um, double thickness_max_um, int width_px, int height_px);

/// ξ (units of k₀) of the light shown at `pixel` for the geometry of `values`: the pixel's offset from
/// the centre, y flipped to point N, turned by −rotation back into the lab; its length u in field radii,
/// distorted to u·(1 + distortion·u²), is projected to |ξ| = sin θ_air as model.projection says, so that
/// |ξ| = NA at the field radius (docs/fitting.md, "The model"); |ξ| = 1 (grazing, dark) where the
/// projection shows no direction.
Eigen::Vector2d pixel_direction(const ConoscopePhotoModel& model, const PhotoParameters& values, const Eigen::Vector2d& pixel);

/// The parameters that act on the photo only through ξ, in the order of direction_derivatives.
constexpr std::array<PhotoParameter, 5> kDirectionParameters{PhotoParameter::center_x_px, PhotoParameter::center_y_px,
                                                             PhotoParameter::field_radius_px, PhotoParameter::rotation_deg,
                                                             PhotoParameter::distortion};

/// ∂ξ/∂p at `pixel` for the kDirectionParameters (per pixel, pixel, pixel, degree, unit).
std::array<Eigen::Vector2d, 5> direction_derivatives(const ConoscopePhotoModel& model, const PhotoParameters& values,
                                                     const Eigen::Vector2d& pixel);

/// The light at `pixel` relative to the envelope's centre: exp(−(r/R)^p) for IlluminationProfile::falloff
/// (1 for even), and its derivatives by envelope centre x, y, radius and power; its log's gradient over the
/// photo g = ∇ln E (per pixel, x right, y down) and g's derivatives by the same four.
struct EnvelopeValue {
    double value = 1.0;
    std::array<double, 4> derivatives{};
    Eigen::Vector2d log_gradient = Eigen::Vector2d::Zero();
    std::array<Eigen::Vector2d, 4> log_gradient_derivatives{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
                                                           Eigen::Vector2d::Zero()};
};
EnvelopeValue illumination_envelope(const ConoscopePhotoModel& model, const PhotoParameters& values, const Eigen::Vector2d& pixel);

/// The figure's terms through the analyzer as set (turned by analyzer_offset_deg), and through the analyzer
/// turned a further 90° (the light it blocks, of which a leaking analyzer passes extinction_ratio); the
/// second is empty unless asked for. Both have the same phases: the modes do not depend on the analyzer.
struct AnalyzerTerms {
    std::vector<InterferenceTerms> passed, blocked;
    std::vector<unsigned char> from_nodes;  // per sample: the terms came from the spectral nodes (ConoscopeTerms::evaluate)
};

/// Whether a sample's terms carry no light: what analyzer_terms leaves beyond grazing, where only the phase is kept.
inline bool shows_no_light(const InterferenceTerms& terms) {
    return terms.mean == 0.0 && terms.modulation == 0.0 && terms.sine_modulation == 0.0;
}

/// passed + extinction_ratio · blocked (passed alone when blocked is empty).
void leaked_terms(const AnalyzerTerms& terms, double extinction_ratio, std::vector<InterferenceTerms>& out);

/// [sample·W + w]: the phase's gradient (x right, y down) and Laplacian over the photo, the gradient of its
/// squared gradient ∇|∇Φ|², and its curvature along the gradient ∇Φᵀ·HessΦ·∇Φ (for the blur's second-order phase).
struct PhaseDerivatives {
    std::vector<double> gradient_x, gradient_y, laplacian;
    std::vector<double> squared_gradient_x, squared_gradient_y, curvature_along_gradient;
};

/// Room for PhotoModelEvaluator::blur_response, [sample·W + w]: the phase change's gradient and Laplacian over the photo,
/// and the change of |∇Φ|².
struct PhaseChangeRoom {
    std::vector<double> gradient_x, gradient_y, laplacian, squared_gradient;
};

/// Linear sRGB of every sample, and optionally its derivatives by thickness, by the blur's σ² and by the
/// point where the figure is sampled (d_shift_x, d_shift_y: per pixel). With `keep_fringe_terms` (and the
/// derivatives), also each wavelength's blurred fringes and their derivative by the phase, [sample·W + w],
/// for blur_response.
struct LinearSamples {
    std::vector<Eigen::Vector3d> rgb, d_thickness, d_blur2, d_shift_x, d_shift_y;
    bool keep_fringe_terms = false;
    std::vector<double> fringes, fringes_per_phase;
};

class PhotoModelEvaluator {
public:
    PhotoModelEvaluator(const ConoscopePhotoModel& model, SampleLattice lattice);

    const SampleLattice& lattice() const { return lattice_; }
    const ConoscopePhotoModel& model() const { return model_; }
    std::size_t sample_count() const { return lattice_.pixels.size(); }
    std::size_t wavelength_count() const { return model_.rgb_per_transmission.size(); }
    double numerical_aperture() const { return model_.settings.numerical_aperture; }

    /// The interference terms of every sample at every wavelength, out[sample·W + w], for the geometry
    /// (centre, radius, rotation, distortion, tilt, azimuth) and the analyzer of `values`, each ξ moved by
    /// `xi_offset` (for ∂/∂ξ). The blocked terms are computed when `with_blocked` or the analyzer leaks. Each
    /// sample's terms come from the spectral nodes or every wavelength as `as_before` says (an earlier call's
    /// from_nodes, for derivatives by differences), or as ConoscopeTerms chooses without it.
    void analyzer_terms(const PhotoParameters& values, bool with_blocked, AnalyzerTerms& out,
                        const Eigen::Vector2d& xi_offset = Eigen::Vector2d::Zero(), const std::vector<unsigned char>* as_before = nullptr) const;
    /// The terms of what reaches the camera: analyzer_terms leaked by the extinction ratio.
    void terms(const PhotoParameters& values, std::vector<InterferenceTerms>& out, const Eigen::Vector2d& xi_offset = Eigen::Vector2d::Zero(),
               const std::vector<unsigned char>* as_before = nullptr) const;

    /// The illumination envelope at every sample.
    std::vector<EnvelopeValue> envelope(const PhotoParameters& values) const;
    /// Multiplies linear sRGB (and its derivatives, where computed) by the envelope.
    void illuminate(const std::vector<EnvelopeValue>& envelope, LinearSamples& samples) const;

    /// The phase's derivatives over the photo (PhaseDerivatives), from the lattice neighbours (central
    /// differences; one-sided, and no Laplacian or curvature, at the edge).
    void phase_derivatives(const std::vector<InterferenceTerms>& terms, PhaseDerivatives& out) const;

    /// Linear sRGB at `thickness_um` with Gaussian blur of variance `blur2_px2`. The blur of a fringe
    /// cos φ whose phase is locally quadratic is exp(−½σ²|∇φ|²)·cos(φ + ½σ²∇²φ − ½σ⁴∇φᵀHessφ∇φ) to first
    /// order in σ²·Hessφ, whatever σ²|∇φ|² (docs/fitting.md), with φ = Φ·d. Each sample's figure is taken
    /// `shifts[k]` pixels away (empty: none), through its phase's gradient: φ + d·∇Φ·shift (blur_shifts).
    void linear(const std::vector<InterferenceTerms>& terms, const PhaseDerivatives& phase, double thickness_um, double blur2_px2,
                const std::vector<Eigen::Vector2d>& shifts, bool derivatives, LinearSamples& out) const;

    /// What moving each sample's ξ by `xi_change[sample]` does to the linear sRGB through the fringe blur alone: the
    /// phase changes by δΦ = ∂Φ/∂ξ·δξ (`phase_per_xi`, per axis, [sample·W + w]), and so do its gradient, Laplacian and
    /// curvature along the gradient over the photo (phase_derivatives' stencils, linearised), times ∂(transmission)/∂ of
    /// each, summed over the wavelengths. A parameter that moves ξ by different amounts at different samples (the field
    /// radius, the rotation, the distortion, the centre of a projection other than the sine) changes them.
    /// `linear` holds the fringe terms of that thickness and blur (keep_fringe_terms); `room` holds the intermediate
    /// results (its contents are overwritten).
    void blur_response(const LinearSamples& linear, const PhaseDerivatives& phase, double thickness_um, double blur2_px2,
                       const std::vector<Eigen::Vector2d>& shifts, const std::array<std::vector<double>, 2>& phase_per_xi,
                       const std::vector<Eigen::Vector2d>& xi_change, PhaseChangeRoom& room, std::vector<Eigen::Vector3d>& out) const;

    /// Where a blurred photo of light E·F shows the figure F: blur(E·F) = E·blur(F)(p + σ²∇ln E) to first
    /// order in σ² (Taylor expansion under the Gaussian), so σ²·∇ln E per sample; empty for even light.
    std::vector<Eigen::Vector2d> blur_shifts(const std::vector<EnvelopeValue>& envelope, double blur2_px2) const;

private:
    /// The colour weights (model.rgb_per_transmission), a row per wavelength and a column per channel.
    Eigen::Matrix<double, Eigen::Dynamic, 3> colour_weights() const;

    const ConoscopePhotoModel& model_;
    SampleLattice lattice_;
};

/// The camera: value = black + (gain·max(linear, 10⁻⁶))^(1/γ), and its derivatives.
struct CameraValue {
    double value, d_linear, d_gain, d_gamma;
};
CameraValue camera_value(double linear, double gain, double black, double gamma);

/// The camera's colour matrix: ones on the diagonal (the gains scale each row), the crosstalk_* parameters off it
/// in the order rg, rb, gr, gb, br, bg (row, column).
Eigen::Matrix3d colour_matrix(const PhotoParameters& values);

/// The camera values of linear sRGB samples for the camera parameters of `values`.
std::vector<Eigen::Vector3d> camera_values(const std::vector<Eigen::Vector3d>& linear_rgb, const PhotoParameters& values);

/// A Gaussian blur (σ in pixels, edges clamped) of every channel of `image`; σ ≤ 0 returns it as it is.
Image gaussian_blur(const Image& image, double sigma_px);

}  // namespace petroscope::detail
