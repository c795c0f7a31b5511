#include "photo_cost.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

constexpr int kThickness = static_cast<int>(PhotoParameter::thickness_um);
constexpr int kGainR = static_cast<int>(PhotoParameter::gain_r);
constexpr int kBlack = static_cast<int>(PhotoParameter::black_level);
constexpr int kGamma = static_cast<int>(PhotoParameter::gamma);
constexpr int kBlur = static_cast<int>(PhotoParameter::blur_variance_px2);
constexpr int kExtinction = static_cast<int>(PhotoParameter::extinction_ratio);
constexpr int kEnvelopeX = static_cast<int>(PhotoParameter::envelope_center_x_px);
constexpr int kCrosstalk = static_cast<int>(PhotoParameter::crosstalk_rg);
// The parameters whose derivative is taken by evaluating the figure's terms again; with those that act
// through ξ (kDirectionParameters), every parameter that changes the terms: the cache's key.
constexpr std::array<PhotoParameter, 3> kReevaluatedParameters{PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg,
                                                               PhotoParameter::analyzer_offset_deg};
constexpr auto kTermParameters = [] {
    std::array<PhotoParameter, kDirectionParameters.size() + kReevaluatedParameters.size()> all{};
    std::copy(kReevaluatedParameters.begin(), kReevaluatedParameters.end(),
              std::copy(kDirectionParameters.begin(), kDirectionParameters.end(), all.begin()));
    return all;
}();
// Forward-difference steps: ξ (units of k₀) and the angles of the crystal and analyzer (degrees). Phases reach 10⁴ rad, so
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

void PhotoCost::unlit_at(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, bool derivatives,
                         LinearSamples& out) const {
    std::array<double, kTermParameters.size()> geometry;
    for (std::size_t j = 0; j < geometry.size(); ++j) geometry[j] = at(values, kTermParameters[j]);
    std::lock_guard lock(cache_mutex_);
    if (!cache_valid_ || geometry != cached_geometry_) {
        level_.evaluator.analyzer_terms(values, free_[kExtinction], cached_terms_);
        level_.evaluator.phase_derivatives(cached_terms_.passed, cached_phase_);
        cached_geometry_ = geometry;
        cache_valid_ = true;
    }
    const double blur2 = total_blur2(values);
    if (cached_terms_.blocked.empty()) {
        level_.evaluator.linear(cached_terms_.passed, cached_phase_, values[kThickness], blur2, shifts, derivatives, out);
        return;
    }
    leaked_terms(cached_terms_, values[kExtinction], leaked_);
    level_.evaluator.linear(leaked_, cached_phase_, values[kThickness], blur2, shifts, derivatives, out);
}

double PhotoCost::total_blur2(const PhotoParameters& values) const {
    return values[kBlur] + level_.extra_blur_px * level_.extra_blur_px;
}

std::vector<Eigen::Vector3d> PhotoCost::model_values(const PhotoParameters& values) const {
    const std::vector<EnvelopeValue> envelope = level_.evaluator.envelope(values);
    LinearSamples linear;
    unlit_at(values, level_.evaluator.blur_shifts(envelope, total_blur2(values)), false, linear);
    level_.evaluator.illuminate(envelope, linear);
    return camera_values(linear.rgb, values);
}

void PhotoCost::direction_columns(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, const LinearSamples& unlit,
                                  std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount>& d_linear) const {
    // ∂/∂ξ by forward differences (two evaluations), with the phase's derivatives over the photo held; what
    // moving ξ unevenly over the photo does to those (and so to the fringe blur) is added through ∂Φ/∂ξ.
    const std::size_t samples = level_.evaluator.sample_count(), w_count = level_.evaluator.wavelength_count();
    const double blur2 = total_blur2(values);
    const std::vector<InterferenceTerms>& seen = seen_terms();
    std::vector<InterferenceTerms>& shifted = scratch_.shifted;
    LinearSamples& moved = scratch_.moved;
    std::array<std::vector<Eigen::Vector3d>, 2>& d_xi = scratch_.d_xi;
    std::array<std::vector<double>, 2>& d_phase_d_xi = scratch_.d_phase_d_xi;
    std::vector<Eigen::Vector3d>& through_blur = scratch_.through_blur;
    for (std::size_t axis = 0; axis < 2; ++axis) {
        level_.evaluator.terms(values, shifted, kXiStep * (axis == 0 ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY()),
                               &cached_terms_.from_nodes);
        level_.evaluator.linear(shifted, cached_phase_, values[kThickness], blur2, shifts, false, moved);
        d_xi[axis].resize(samples);
        d_phase_d_xi[axis].resize(seen.size());
        // Each sample's entries alone, on every core (as every loop over the samples below).
#pragma omp parallel for schedule(static)
        for (int sample = 0; sample < static_cast<int>(samples); ++sample) {
            const auto k = static_cast<std::size_t>(sample);
            d_xi[axis][k] = (moved.rgb[k] - unlit.rgb[k]) / kXiStep;
            for (std::size_t i = k * w_count; i < (k + 1) * w_count; ++i) {
                d_phase_d_xi[axis][i] = (shifted[i].phase_per_um - seen[i].phase_per_um) / kXiStep;
            }
        }
    }
    std::array<std::vector<Eigen::Vector2d>, kDirectionParameters.size()>& dxi = scratch_.d_xi_d_parameters;
    for (std::vector<Eigen::Vector2d>& per_parameter : dxi) per_parameter.resize(samples);
#pragma omp parallel for schedule(static)
    for (int sample = 0; sample < static_cast<int>(samples); ++sample) {
        const auto k = static_cast<std::size_t>(sample);
        const std::array<Eigen::Vector2d, 5> at = direction_derivatives(level_.evaluator.model(), values, level_.evaluator.lattice().pixels[k]);
        for (std::size_t j = 0; j < at.size(); ++j) dxi[j][k] = at[j];
    }
    for (std::size_t j = 0; j < kDirectionParameters.size(); ++j) {
        if (!free_[static_cast<std::size_t>(kDirectionParameters[j])]) continue;
        std::vector<Eigen::Vector3d>& column = d_linear[static_cast<std::size_t>(kDirectionParameters[j])];
        column.resize(samples);
        level_.evaluator.blur_response(unlit, cached_phase_, values[kThickness], blur2, shifts, d_phase_d_xi, dxi[j], scratch_.phase_change,
                                       through_blur);
        for (std::size_t k = 0; k < samples; ++k) column[k] = d_xi[0][k] * dxi[j][k].x() + d_xi[1][k] * dxi[j][k].y() + through_blur[k];
    }
}

void PhotoCost::derivatives_at(const PhotoParameters& values, const std::vector<Eigen::Vector2d>& shifts, const LinearSamples& unlit,
                               const std::vector<EnvelopeValue>& envelope,
                               std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount>& d_linear) const {
    const std::size_t samples = level_.evaluator.sample_count();
    const double blur2 = total_blur2(values);
    // Centre, radius, rotation and distortion act through ξ.
    if (std::any_of(kDirectionParameters.begin(), kDirectionParameters.end(), [&](PhotoParameter p) { return free_[static_cast<std::size_t>(p)]; })) {
        direction_columns(values, shifts, unlit, d_linear);
    }
    std::vector<InterferenceTerms>& shifted = scratch_.shifted;
    LinearSamples& moved = scratch_.moved;
    // Tilt, azimuth and the analyzer's offset change the terms themselves (and the phase's derivatives).
    PhaseDerivatives& moved_phase = scratch_.moved_phase;
    for (const PhotoParameter p : kReevaluatedParameters) {
        const auto j = static_cast<std::size_t>(p);
        if (!free_[j]) continue;
        PhotoParameters turned = values;
        turned[j] += kAngleStep;
        level_.evaluator.terms(turned, shifted, Eigen::Vector2d::Zero(), &cached_terms_.from_nodes);
        level_.evaluator.phase_derivatives(shifted, moved_phase);
        level_.evaluator.linear(shifted, moved_phase, values[kThickness], blur2, shifts, false, moved);
        d_linear[j].resize(samples);
        for (std::size_t k = 0; k < samples; ++k) d_linear[j][k] = (moved.rgb[k] - unlit.rgb[k]) / kAngleStep;
    }
    // The extinction ratio adds the blocked light: its derivative is that light.
    if (free_[kExtinction]) {
        level_.evaluator.linear(cached_terms_.blocked, cached_phase_, values[kThickness], blur2, shifts, false, moved);
        d_linear[kExtinction] = moved.rgb;
    }
    // Everything so far is unlit: the envelope multiplies it, and its own parameters multiply the unlit colour.
    for (std::size_t j = 0; j < kPhotoParameterCount; ++j) {
        for (std::size_t k = 0; k < d_linear[j].size(); ++k) d_linear[j][k] *= envelope[k].value;
    }
    // The envelope's parameters also move where the blurred photo shows the figure: shift = σ²·∇ln E.
    for (std::size_t e = 0; e < 4; ++e) {
        const std::size_t j = kEnvelopeX + e;
        if (!free_[j]) continue;
        d_linear[j].resize(samples);
        for (std::size_t k = 0; k < samples; ++k) {
            const Eigen::Vector2d d_shift = blur2 * envelope[k].log_gradient_derivatives[e];
            d_linear[j][k] = unlit.rgb[k] * envelope[k].derivatives[e] +
                             envelope[k].value * (unlit.d_shift_x[k] * d_shift.x() + unlit.d_shift_y[k] * d_shift.y());
        }
    }
}

bool PhotoCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
    const PhotoParameters values = to_values(parameters[0]);
    const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    const std::size_t rows = static_cast<std::size_t>(num_residuals());
    std::lock_guard evaluation(evaluation_mutex_);
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
    const std::vector<EnvelopeValue> envelope = level_.evaluator.envelope(values);
    const std::vector<Eigen::Vector2d> shifts = level_.evaluator.blur_shifts(envelope, total_blur2(values));
    LinearSamples& unlit = scratch_.unlit;
    unlit.keep_fringe_terms = true;  // for the blur's part of the geometry's derivatives
    unlit_at(values, shifts, want_jacobian, unlit);
    std::array<std::vector<Eigen::Vector3d>, kPhotoParameterCount>& d_linear = scratch_.d_linear;
    for (std::vector<Eigen::Vector3d>& column : d_linear) column.clear();  // empty: a column not computed
    if (want_jacobian) {
        derivatives_at(values, shifts, unlit, envelope, d_linear);
        // The blur moves the figure's sampling point too (shift = σ²·∇ln E).
        for (std::size_t k = 0; k < shifts.size(); ++k) {
            unlit.d_blur2[k] += unlit.d_shift_x[k] * envelope[k].log_gradient.x() + unlit.d_shift_y[k] * envelope[k].log_gradient.y();
        }
    }
    LinearSamples& base = unlit;
    level_.evaluator.illuminate(envelope, base);
    if (want_jacobian) {
        d_linear[kThickness].swap(base.d_thickness);
        d_linear[kBlur].swap(base.d_blur2);
    }
    const std::size_t samples = level_.evaluator.sample_count();
    const double c2 = robust_scale_ * robust_scale_;
    const Eigen::Matrix3d colours = colour_matrix(values);

#pragma omp parallel for schedule(static)
    for (int sample = 0; sample < static_cast<int>(samples); ++sample) {
        const auto k = static_cast<std::size_t>(sample);
        const Eigen::Vector3d mixed = colours * base.rgb[k];
        for (int c = 0; c < 3; ++c) {
            const std::size_t row = 3 * k + static_cast<std::size_t>(c);
            double* jacobian_row = want_jacobian ? jacobians[0] + row * kPhotoParameterCount : nullptr;
            if (level_.usable[k] == 0) {
                residuals[row] = 0.0;
                if (jacobian_row != nullptr) std::fill_n(jacobian_row, kPhotoParameterCount, 0.0);
                continue;
            }
            const CameraValue camera = camera_value(mixed[c], values[kGainR + c], values[kBlack], values[kGamma]);
            const double r = camera.value - level_.observed[k][c];
            // Cauchy loss ρ(s) = c²·ln(1 + s/c²) written into the residual: r' = sign(r)·√ρ(r²), so Σr'² = Σρ.
            const double s = r * r;
            const double robust = std::sqrt(c2 * std::log1p(s / c2));
            residuals[row] = std::copysign(robust, r);
            if (jacobian_row == nullptr) continue;
            const double chain = robust > 0.0 ? std::abs(r) / robust / (1.0 + s / c2) : 1.0;  // dr'/dr
            std::fill_n(jacobian_row, kPhotoParameterCount, 0.0);
            for (std::size_t j = 0; j < kPhotoParameterCount; ++j) {
                if (!d_linear[j].empty()) jacobian_row[j] = chain * camera.d_linear * colours.row(c).dot(d_linear[j][k]);
            }
            // Row c's crosstalk from the other two channels, in increasing order: ∂mixed_c/∂x_cc' = linear_c'.
            for (int m = 0; m < 2; ++m) {
                jacobian_row[kCrosstalk + 2 * c + m] = chain * camera.d_linear * base.rgb[k][m < c ? m : m + 1];
            }
            jacobian_row[kGainR + c] = chain * camera.d_gain;
            jacobian_row[kBlack] = chain;
            jacobian_row[kGamma] = chain * camera.d_gamma;
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
