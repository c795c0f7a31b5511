#pragma once
// The least-squares cost of a conoscopic photo for Ceres: one residual block of 3 residuals (R, G, B) per
// sample pixel, robustified by a Cauchy loss inside the block (so that one block can hold every sample and
// the expensive figure terms are computed once per evaluation for all of them).
#include "photo_model.hpp"

#include <ceres/ceres.h>

#include <mutex>

namespace petroscope::detail {

/// One resolution level of the fit: a sample lattice and the photo's values there.
struct PhotoLevel {
    /// The photo is blurred by `extra_blur_px` more in linear light (decoded with `gamma`, re-encoded after).
    PhotoLevel(const ConoscopePhotoModel& model, SampleLattice lattice, const Image& photo, double extra_blur_px, double gamma,
               double saturated_level);
    PhotoModelEvaluator evaluator;
    double extra_blur_px;                     // the photo was blurred by this much more (coarse levels)
    std::vector<Eigen::Vector3d> observed;    // camera values at the samples
    std::vector<unsigned char> usable;        // 0: saturated (or out of the image)
    int usable_count = 0;
};

class PhotoCost final : public ceres::CostFunction {
public:
    PhotoCost(const PhotoLevel& level, const PhotoParameterFlags& free, double robust_scale);

    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

    /// Model camera values at the samples (no loss), for reports.
    std::vector<Eigen::Vector3d> model_values(const PhotoParameters& values) const;

private:
    /// Linear sRGB of the samples before the illumination envelope, each figure taken `shifts` away (the
    /// envelope's effect on the blur), reusing the terms of the last geometry.
    void unlit_at(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, bool derivatives, LinearSamples& out) const;
    /// ∂(linear sRGB)/∂p of the geometry, analyzer and envelope parameters that are free (empty for the others).
    void derivatives_at(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, const LinearSamples& unlit,
                        const std::vector<EnvelopeValue>& envelope, std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount>& d_linear) const;

    /// The columns of d_linear for the free kDirectionParameters (they act through ξ), unlit.
    void direction_columns(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, const LinearSamples& unlit,
                           std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount>& d_linear) const;
    /// The terms unlit_at used: the cached ones, leaked by the extinction ratio where the analyzer leaks.
    const std::vector<InterferenceTerms>& seen_terms() const { return cached_terms_.blocked.empty() ? cached_terms_.passed : leaked_; }
    /// The blur's σ² in the model: the parameter plus the level's extra blur of the photo.
    double total_blur2(const PhotoParameters& values) const;

    const PhotoLevel& level_;
    PhotoParameterFlags free_;
    double robust_scale_;
    // The terms of the last geometry (the trust-region method evaluates each accepted point twice).
    mutable std::mutex cache_mutex_;
    mutable std::array<double, 8> cached_geometry_{};
    mutable bool cache_valid_ = false;
    mutable AnalyzerTerms cached_terms_;
    mutable std::vector<InterferenceTerms> leaked_;  // cached_terms_ leaked by the last extinction ratio
    mutable PhaseDerivatives cached_phase_;
    // Room for an evaluation's intermediate results, kept from one evaluation to the next: they fill tens of
    // megabytes, which fresh allocations would have the system map and clear at every evaluation. Evaluate holds
    // evaluation_mutex_ while it uses them.
    struct Scratch {
        LinearSamples unlit, moved;
        std::vector<InterferenceTerms> shifted;
        std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount> d_linear;
        std::array<std::vector<Eigen::Vector3d>, 2> d_xi;
        std::array<std::vector<double>, 2> d_phase_d_xi;
        std::array<std::vector<Eigen::Vector2d>, kDirectionParameters.size()> d_xi_d_parameters;  // [parameter][sample]: ∂ξ/∂p
        PhaseChangeRoom phase_change;
        std::vector<Eigen::Vector3d> through_blur;
        PhaseDerivatives moved_phase;
    };
    mutable std::mutex evaluation_mutex_;
    mutable Scratch scratch_;
    // The last evaluation's answer.
    mutable PhotoParameters last_values_{};
    mutable bool last_valid_ = false, last_has_jacobian_ = false;
    mutable std::vector<double> last_residuals_, last_jacobian_;
};

}  // namespace petroscope::detail
