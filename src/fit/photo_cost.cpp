#include "photo_cost.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

constexpr int kCenterX = static_cast<int>(PhotoParameter::center_x_px);
constexpr int kTilt = static_cast<int>(PhotoParameter::tilt_deg);
constexpr int kAzimuth = static_cast<int>(PhotoParameter::azimuth_deg);
constexpr int kThickness = static_cast<int>(PhotoParameter::thickness_um);
constexpr int kGainR = static_cast<int>(PhotoParameter::gain_r);
constexpr int kBlack = static_cast<int>(PhotoParameter::black_level);
constexpr int kGamma = static_cast<int>(PhotoParameter::gamma);
constexpr int kBlur = static_cast<int>(PhotoParameter::blur_variance_px2);
// Forward-difference steps: ξ (units of k₀) and orientation angles (degrees). Phases reach 10⁴ rad, so
// the truncation error ½f''h stays near 10⁻³ of f' at h = 10⁻⁶ while rounding (10⁻¹³/h) is negligible.
constexpr double kXiStep = 1e-6;
constexpr double kAngleStep = 1e-5;

PhotoParameters to_values(const double* parameters) {
    PhotoParameters values;
    std::copy_n(parameters, kPhotoParameterCount, values.begin());
    return values;
}

}  // namespace

PhotoLevel::PhotoLevel(const ConoscopePhotoModel& model, SampleLattice lattice, const Image& photo, double extra_blur,
                       double gamma, double saturated_level)
    : evaluator(model, std::move(lattice)), extra_blur_px(extra_blur) {
    // The optics blur light, not camera values: blur the decoded photo (the model adds σ² in linear light).
    Image blurred = photo;
    if (extra_blur > 0.0) {
        for (float& value : blurred.pixels) value = static_cast<float>(std::pow(std::max(value, 0.0f), gamma));
        blurred = gaussian_blur(blurred, extra_blur);
        for (float& value : blurred.pixels) value = static_cast<float>(std::pow(value, 1.0 / gamma));
    }
    for (const Eigen::Vector2d& pixel : evaluator.lattice().pixels) {
        const int x = static_cast<int>(pixel.x()), y = static_cast<int>(pixel.y());
        Eigen::Vector3d value;
        bool saturated = false;
        for (int c = 0; c < 3; ++c) {
            const int channel = std::min(c, photo.channels - 1);
            value[c] = blurred.at(x, y, channel);
            // Saturation is judged on the photo itself: blurring would hide clipped pixels.
            saturated = saturated || photo.at(x, y, channel) >= saturated_level;
        }
        observed.push_back(value);
        usable.push_back(saturated ? 0 : 1);
        usable_count += saturated ? 0 : 1;
    }
}

PhotoCost::PhotoCost(const PhotoLevel& level, const PhotoParameterFlags& free, double robust_scale)
    : level_(level), free_(free), robust_scale_(robust_scale) {
    set_num_residuals(static_cast<int>(3 * level.evaluator.sample_count()));
    mutable_parameter_block_sizes()->push_back(kPhotoParameterCount);
}

void PhotoCost::linear_at(const PhotoParameters& values, bool derivatives, LinearSamples& out) const {
    std::array<double, 6> geometry;  // centre x, y, radius, rotation, tilt, azimuth
    std::copy_n(values.begin() + kCenterX, 6, geometry.begin());
    std::lock_guard lock(cache_mutex_);
    if (!cache_valid_ || geometry != cached_geometry_) {
        level_.evaluator.terms(values, cached_terms_);
        level_.evaluator.phase_derivatives(cached_terms_, cached_phase_);
        cached_geometry_ = geometry;
        cache_valid_ = true;
    }
    const double blur2 = values[kBlur] + level_.extra_blur_px * level_.extra_blur_px;
    level_.evaluator.linear(cached_terms_, cached_phase_, values[kThickness], blur2, derivatives, out);
}

std::vector<Eigen::Vector3d> PhotoCost::model_values(const PhotoParameters& values) const {
    LinearSamples linear;
    linear_at(values, false, linear);
    return camera_values(linear.rgb, values);
}

bool PhotoCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
    const PhotoParameters values = to_values(parameters[0]);
    const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    const std::size_t rows = static_cast<std::size_t>(num_residuals());
    // Ceres asks for the same point up to three times per iteration (the candidate's gradient, its cost,
    // the accepted point's Jacobian): answer repeats from the last evaluation.
    {
        std::lock_guard lock(cache_mutex_);
        if (last_valid_ && values == last_values_ && (!want_jacobian || last_has_jacobian_)) {
            std::copy(last_residuals_.begin(), last_residuals_.end(), residuals);
            if (want_jacobian) std::copy(last_jacobian_.begin(), last_jacobian_.end(), jacobians[0]);
            return true;
        }
    }
    LinearSamples base;
    linear_at(values, want_jacobian, base);
    const std::size_t samples = level_.evaluator.sample_count();
    const double c2 = robust_scale_ * robust_scale_;

    // ∂(linear sRGB)/∂p for the geometry parameters, by forward differences: centre, radius and rotation
    // through ∂/∂ξ (two evaluations), tilt and azimuth each on their own.
    std::array<std::vector<Eigen::Vector3d>, 6> d_geometry;
    if (want_jacobian) {
        std::vector<InterferenceTerms> shifted;
        LinearSamples moved;
        const double blur2 = values[kBlur] + level_.extra_blur_px * level_.extra_blur_px;
        std::array<std::vector<Eigen::Vector3d>, 2> d_xi;
        const bool any_direction = free_[kCenterX] || free_[kCenterX + 1] || free_[kCenterX + 2] || free_[kCenterX + 3];
        for (int axis = 0; axis < 2 && any_direction; ++axis) {
            level_.evaluator.terms(values, shifted, kXiStep * (axis == 0 ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY()));
            level_.evaluator.linear(shifted, cached_phase_, values[kThickness], blur2, false, moved);
            d_xi[axis].resize(samples);
            for (std::size_t k = 0; k < samples; ++k) d_xi[axis][k] = (moved.rgb[k] - base.rgb[k]) / kXiStep;
        }
        for (int j = 0; j < 4; ++j) {
            if (free_[kCenterX + j]) d_geometry[j].resize(samples);
        }
        const double na = level_.evaluator.numerical_aperture();
        for (std::size_t k = 0; k < samples && any_direction; ++k) {
            const Eigen::Vector2d xi = pixel_direction(values, na, level_.evaluator.lattice().pixels[k]);
            const std::array<Eigen::Vector2d, 4> dxi = direction_derivatives(values, na, xi);
            for (int j = 0; j < 4; ++j) {
                if (!d_geometry[j].empty()) d_geometry[j][k] = d_xi[0][k] * dxi[j].x() + d_xi[1][k] * dxi[j].y();
            }
        }
        for (const int j : {kTilt, kAzimuth}) {
            if (!free_[j]) continue;
            PhotoParameters turned = values;
            turned[j] += kAngleStep;
            level_.evaluator.terms(turned, shifted);
            level_.evaluator.linear(shifted, cached_phase_, values[kThickness], blur2, false, moved);
            d_geometry[j - kCenterX].resize(samples);
            for (std::size_t k = 0; k < samples; ++k) d_geometry[j - kCenterX][k] = (moved.rgb[k] - base.rgb[k]) / kAngleStep;
        }
    }

    for (std::size_t k = 0; k < samples; ++k) {
        for (int c = 0; c < 3; ++c) {
            const std::size_t row = 3 * k + static_cast<std::size_t>(c);
            double* jacobian_row = want_jacobian ? jacobians[0] + row * kPhotoParameterCount : nullptr;
            if (level_.usable[k] == 0) {
                residuals[row] = 0.0;
                if (jacobian_row != nullptr) std::fill_n(jacobian_row, kPhotoParameterCount, 0.0);
                continue;
            }
            const CameraValue camera = camera_value(base.rgb[k][c], values[kGainR + c], values[kBlack], values[kGamma]);
            const double r = camera.value - level_.observed[k][c];
            // Cauchy loss ρ(s) = c²·ln(1 + s/c²) written into the residual: r' = sign(r)·√ρ(r²), so Σr'² = Σρ.
            const double s = r * r;
            const double robust = std::sqrt(c2 * std::log1p(s / c2));
            residuals[row] = std::copysign(robust, r);
            if (jacobian_row == nullptr) continue;
            const double chain = robust > 0.0 ? std::abs(r) / robust / (1.0 + s / c2) : 1.0;  // dr'/dr
            std::fill_n(jacobian_row, kPhotoParameterCount, 0.0);
            const double d_linear = chain * camera.d_linear;
            jacobian_row[kThickness] = d_linear * base.d_thickness[k][c];
            for (int j = 0; j < 6; ++j) {
                if (!d_geometry[j].empty()) jacobian_row[kCenterX + j] = d_linear * d_geometry[j][k][c];
            }
            jacobian_row[kGainR + c] = chain * camera.d_gain;
            jacobian_row[kBlack] = chain;
            jacobian_row[kGamma] = chain * camera.d_gamma;
            jacobian_row[kBlur] = d_linear * base.d_blur2[k][c];
        }
    }
    // Ceres must never see a non-finite value (it would print every residual block and fail the solve): a
    // point where the model is undefined is refused, so that the step to it is rejected.
    const auto finite = [](double value) { return std::isfinite(value); };
    if (!std::all_of(residuals, residuals + rows, finite) ||
        (want_jacobian && !std::all_of(jacobians[0], jacobians[0] + rows * kPhotoParameterCount, finite))) {
        return false;
    }
    std::lock_guard lock(cache_mutex_);
    last_values_ = values;
    last_valid_ = true;
    last_has_jacobian_ = want_jacobian;
    last_residuals_.assign(residuals, residuals + rows);
    if (want_jacobian) last_jacobian_.assign(jacobians[0], jacobians[0] + rows * kPhotoParameterCount);
    return true;
}

}  // namespace petroscope::detail
