#include "petroscope/fit/conoscope_fit.hpp"

#include "bayer_mosaic.hpp"
#include "cancel_between_iterations.hpp"
#include "figure_location.hpp"
#include "photo_cost.hpp"
#include "photo_model.hpp"
#include "solver_messages.hpp"
#include "stop_out_of_reach.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <Eigen/Eigenvalues>
#include <ceres/ceres.h>

#include <algorithm>
#include <limits>
#include <map>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

namespace petroscope {
namespace {

using detail::PhotoCost;
using detail::PhotoLevel;
using Bounds = detail::PhotoBounds;

constexpr std::array<std::string_view, kPhotoParameterCount> kNames{
    "thickness_um", "center_x_px", "center_y_px", "field_radius_px", "rotation_deg", "tilt_deg", "azimuth_deg",
    "gain_r",       "gain_g",      "gain_b",      "black_level",     "gamma",        "blur_variance_px2",
    "envelope_center_x_px", "envelope_center_y_px", "envelope_radius_px", "envelope_power", "distortion", "analyzer_offset_deg",
    "extinction_ratio", "crosstalk_rg", "crosstalk_rb", "crosstalk_gr", "crosstalk_gb", "crosstalk_br", "crosstalk_bg"};

constexpr std::size_t index_of(PhotoParameter p) { return static_cast<std::size_t>(p); }

// A 1σ beyond these says the photo does not determine the parameter (in its own unit; thickness and
// envelope radius relative; the centres and the field radius: uncertainties() sets theirs).
constexpr std::array<double, kPhotoParameterCount> kUnidentifiedSigma{0.2, 0.0, 0.0, 0.0, 20.0, 20.0, 45.0, 0.5, 0.5, 0.5,
                                                                      0.2, 1.0, 25.0, 0.0, 0.0, 0.5, 10.0, 0.2, 10.0, 0.05,
                                                                      0.2, 0.2, 0.2, 0.2, 0.2, 0.2};

/// The photo as three channels of camera values; InputError for what cannot be fitted.
Image colour_photo(const Image& photo, bool white_light) {
    if (photo.width < 32 || photo.height < 32) {
        throw InputError("the photo is " + std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                         " px: too small for a fit (at least 32x32)");
    }
    bool grey = photo.channels < 3;
    if (!grey) {
        double largest_difference = 0.0;
        for (int y = 0; y < photo.height; ++y) {
            for (int x = 0; x < photo.width; ++x) {
                largest_difference = std::max({largest_difference, std::abs(double(photo.at(x, y, 0)) - photo.at(x, y, 1)),
                                               std::abs(double(photo.at(x, y, 1)) - photo.at(x, y, 2))});
            }
        }
        grey = largest_difference < 0.5 / 255.0;
    }
    if (grey && white_light) {
        throw InputError("the photo is grayscale, but the figure is in white light, whose interference colours the fit compares; "
                         "give a colour photo, or fit in monochromatic light (--wavelength)");
    }
    Image rgb(photo.width, photo.height, 3);
    for (int y = 0; y < photo.height; ++y) {
        for (int x = 0; x < photo.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                const float value = photo.at(x, y, std::min(c, photo.channels >= 3 ? 2 : 0));
                if (!std::isfinite(value)) throw InputError("the photo has a non-finite value at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")");
                rgb.at(x, y, c) = value;
            }
        }
    }
    return rgb;
}

/// The radius around `centre` where the mean value on circles about it falls below `fraction` of the inner
/// field's (within `fallback`/2) for five pixels running: a field edge (conoscopic photos show the lit
/// aperture on black) or how far the light reaches. `fallback` when not found.
double radius_where_light_falls(const Image& photo, const Eigen::Vector2d& centre, double fraction, double fallback) {
    const int bins = static_cast<int>(std::hypot(photo.width, photo.height)) + 1;
    std::vector<double> sum(bins, 0.0), count(bins, 0.0);
    for (int y = 0; y < photo.height; ++y) {
        for (int x = 0; x < photo.width; ++x) {
            const int bin = static_cast<int>(std::hypot(x + 0.5 - centre.x(), y + 0.5 - centre.y()));
            sum[bin] += (photo.at(x, y, 0) + photo.at(x, y, 1) + photo.at(x, y, 2)) / 3.0;
            count[bin] += 1.0;
        }
    }
    const auto mean = [&](int bin) { return sum[bin] / std::max(count[bin], 1.0); };
    const int inner = static_cast<int>(0.5 * fallback);
    std::vector<double> inner_means;
    for (int bin = 0; bin < inner; ++bin) inner_means.push_back(mean(bin));
    if (inner_means.empty()) return fallback;
    std::nth_element(inner_means.begin(), inner_means.begin() + inner_means.size() / 2, inner_means.end());
    const double threshold = fraction * inner_means[inner_means.size() / 2];
    for (int bin = inner; bin + 5 < bins; ++bin) {
        // A ring mostly outside the image says nothing.
        if (count[bin] < 0.3 * 2.0 * std::numbers::pi * (bin + 0.5)) break;
        bool dark = true;
        for (int k = 0; k < 5 && dark; ++k) dark = mean(bin + k) < threshold;
        if (dark) return bin;
    }
    return fallback;
}

/// The least-squares problem of one level over `values` (which must outlive it): fixed parameters held
/// by a subset manifold, free ones within their bounds.
std::unique_ptr<ceres::Problem> make_problem(const PhotoLevel& level, PhotoParameters& values, const ConoscopeFitOptions& options,
                                             const Bounds& bounds) {
    auto problem = std::make_unique<ceres::Problem>();
    problem->AddResidualBlock(new PhotoCost(level, options.free, options.robust_scale), nullptr, values.data());
    std::vector<int> fixed;
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        if (!options.free[static_cast<std::size_t>(j)]) fixed.push_back(j);
    }
    if (fixed.size() == kPhotoParameterCount) {
        problem->SetParameterBlockConstant(values.data());
    } else if (!fixed.empty()) {
        problem->SetManifold(values.data(), new ceres::SubsetManifold(kPhotoParameterCount, fixed));
    }
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const auto k = static_cast<std::size_t>(j);
        if (!options.free[k]) continue;
        values[k] = std::clamp(values[k], bounds.lower[k], bounds.upper[k]);
        problem->SetParameterLowerBound(values.data(), j, bounds.lower[k]);
        problem->SetParameterUpperBound(values.data(), j, bounds.upper[k]);
    }
    return problem;
}

/// Least squares on one level from `values`; returns the final Ceres cost and adds the iterations. A solve that
/// competes with others stops once it cannot reach `lowest_cost`, the lowest of theirs (StopOutOfReach). Throws
/// Cancelled when the progress callback asks to stop.
double solve_level(const PhotoLevel& level, PhotoParameters& values, const ConoscopeFitOptions& options, const Bounds& bounds,
                   int max_iterations, double function_tolerance, int& iterations, ProgressRelay& relay,
                   double lowest_cost = std::numeric_limits<double>::infinity()) {
    const std::unique_ptr<ceres::Problem> problem = make_problem(level, values, options, bounds);
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = max_iterations;
    solver.num_threads = 1;  // the cost function uses every core itself
    solver.function_tolerance = function_tolerance;
    solver.parameter_tolerance = 1e-9;
    solver.logging_type = detail::solver_logging();
    // With bounds, each trust-region step is followed by a projected Armijo line search; by default it
    // interpolates cubically, which asks the cost's gradient at every trial point, and so the whole Jacobian
    // (most of an evaluation's work, and wasted on a rejected point). Quadratic interpolation needs only
    // the cost there; the Jacobian is then computed once per accepted step.
    solver.line_search_interpolation_type = ceres::QUADRATIC;
    CancelBetweenIterations cancel(relay);
    solver.callbacks.push_back(&cancel);
    StopOutOfReach out_of_reach(lowest_cost, max_iterations);
    if (std::isfinite(lowest_cost)) solver.callbacks.push_back(&out_of_reach);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem.get(), &summary);
    relay.stop_if_cancelled();
    iterations += static_cast<int>(summary.iterations.size());
    // A failed solve (the model undefined at the start: PhotoCost refuses such points) leaves `values` as
    // they were and ranks last.
    return summary.IsSolutionUsable() ? summary.final_cost : std::numeric_limits<double>::infinity();
}

/// The relative decrease of the cost below which a final refinement stops: a hundredth of what one standard
/// deviation of a parameter is worth. At the minimum, with n residuals of variance s², the cost ½Σr² is about
/// ½ns², and moving a parameter by 1σ raises it by ½s², a fraction 1/n of the cost.
double converged_fraction(const PhotoLevel& level) { return std::max(1e-8, 0.01 / std::max(1, 3 * level.usable_count)); }

/// A thickness within this relative distance of a bound counts as on it.
constexpr double kOnBound = 1e-6;

/// The refinement of `values` on `level` within `basin`. With every parameter free the basin's edge moves (its
/// neighbouring maximum moves with the geometry), so a refinement that ends on a thickness bound of the basin that is
/// not also `outer`'s goes on with that side opened out to `outer`'s, once per side. `basin` ends as the bounds the
/// last refinement used; returns its cost.
double refine_in_basin(const PhotoLevel& level, PhotoParameters& values, const ConoscopeFitOptions& options, const Bounds& outer, Bounds& basin,
                       int& iterations, ProgressRelay& relay) {
    const std::size_t k = index_of(PhotoParameter::thickness_um);
    double cost = solve_level(level, values, options, basin, 40, converged_fraction(level), iterations, relay);
    for (int side = 0; side < 2; ++side) {
        if (basin.lower[k] > outer.lower[k] && values[k] <= basin.lower[k] * (1.0 + kOnBound)) {
            basin.lower[k] = outer.lower[k];
        } else if (basin.upper[k] < outer.upper[k] && values[k] >= basin.upper[k] * (1.0 - kOnBound)) {
            basin.upper[k] = outer.upper[k];
        } else {
            break;
        }
        cost = solve_level(level, values, options, basin, 40, converged_fraction(level), iterations, relay);
    }
    return cost;
}

/// A local minimum of the cost over thickness and its basin: the thicknesses of the neighbouring local
/// maxima (or the ends of the scan), between which a refinement stays on this minimum.
struct ThicknessMinimum {
    double thickness_um, cost, lower_um, upper_um;
};

/// How a thickness scan chooses its steps: 0.25 rad of phase change of the finest fringe the level
/// resolves (at the starting geometry, where which fringes carry the cost is not known yet), or of the
/// fringes weighted by their power in the photo (at a fitted geometry).
enum class StepRule { finest_resolved_fringe, power_weighted_fringes };

/// The lowest `count` local minima of the cost over thickness at the geometry of `values`: at each
/// thickness the camera is taken linear in x^(1/γ) per channel (gain and black level solved exactly), so
/// the scan needs no other unknown.
std::vector<ThicknessMinimum> thickness_minima(const PhotoLevel& level, const std::vector<Eigen::Vector3d>& rgb_per_transmission,
                                               const PhotoParameters& values, double min_um, double max_um, int count, StepRule step_rule) {
    std::vector<InterferenceTerms> terms;
    detail::PhaseDerivatives phase;
    level.evaluator.terms(values, terms);
    level.evaluator.phase_derivatives(terms, phase);
    const std::vector<detail::EnvelopeValue> envelope = level.evaluator.envelope(values);
    const double blur2 = at(values, PhotoParameter::blur_variance_px2) + level.extra_blur_px * level.extra_blur_px;
    const std::vector<Eigen::Vector2d> shifts = level.evaluator.blur_shifts(envelope, blur2);
    // Fringes are resolved (attenuation above e^−2) while σ²d²|∇Φ|² < 4: the largest phase among those,
    // found from the terms sorted by |∇Φ|, of the samples that show light (beyond grazing they keep a phase).
    std::vector<std::pair<double, double>> by_gradient;  // (|∇Φ|², |Φ|)
    for (std::size_t k = 0; k < terms.size(); ++k) {
        if (detail::shows_no_light(terms[k])) continue;
        by_gradient.emplace_back(phase.gradient_x[k] * phase.gradient_x[k] + phase.gradient_y[k] * phase.gradient_y[k], std::abs(terms[k].phase_per_um));
    }
    std::sort(by_gradient.begin(), by_gradient.end());
    std::vector<double> running_max(by_gradient.size());
    double largest = 0.0;
    for (std::size_t k = 0; k < by_gradient.size(); ++k) running_max[k] = largest = std::max(largest, by_gradient[k].second);
    const auto resolved_phase_per_um = [&](double thickness_um) {
        const double limit = 4.0 / (blur2 * thickness_um * thickness_um);
        const auto end = std::upper_bound(by_gradient.begin(), by_gradient.end(), std::pair{limit, 1e300});
        return end == by_gradient.begin() ? 0.0 : running_max[static_cast<std::size_t>(end - by_gradient.begin()) - 1];
    };
    // The colour each sample would show without fringes, E·Σ_w rgb_w·mean_w: what the fringes add to it is
    // the signal whose rate of change sets the step.
    const std::size_t wavelengths = level.evaluator.wavelength_count();
    std::vector<Eigen::Vector3d> fringe_free(level.evaluator.sample_count(), Eigen::Vector3d::Zero());
    for (std::size_t k = 0; k < terms.size(); ++k) {
        fringe_free[k / wavelengths] += rgb_per_transmission[k % wavelengths] * (terms[k].mean * envelope[k / wavelengths].value);
    }
    const double gamma = at(values, PhotoParameter::gamma);
    std::vector<double> thicknesses, costs;
    detail::LinearSamples linear;
    const bool weighted = step_rule == StepRule::power_weighted_fringes;
    for (double t = min_um; t <= max_um;) {
        level.evaluator.linear(terms, phase, t, blur2, shifts, weighted, linear);
        level.evaluator.illuminate(envelope, linear);
        // The power-weighted rate Φ_eff: the rms rate of change of the fringe signal s = rgb − fringe_free
        // relative to its rms, Φ_eff² = Σ|∂s/∂d|² / Σ|s|² (for one fringe s = A·cos(Φd): Φ); it weights
        // each fringe by its power in the photo, after the blur and after high orders wash out to white.
        double rate2 = 0.0, signal2 = 0.0;
        for (std::size_t k = 0; k < linear.rgb.size() && weighted; ++k) {
            rate2 += linear.d_thickness[k].squaredNorm();
            signal2 += (linear.rgb[k] - fringe_free[k]).squaredNorm();
        }
        const double rate_per_um = signal2 > 0.0 ? std::sqrt(rate2 / signal2) : 0.0;
        double cost = 0.0;
        for (int c = 0; c < 3; ++c) {
            // Least squares y ≈ a·z + b with z = max(x, 0)^(1/γ).
            double n = 0, sz = 0, sy = 0, szz = 0, szy = 0, syy = 0;
            for (std::size_t k = 0; k < linear.rgb.size(); ++k) {
                if (level.usable[k] == 0) continue;
                const double z = std::pow(std::max(linear.rgb[k][c], 0.0), 1.0 / gamma), y = level.observed[k][c];
                n += 1;
                sz += z;
                sy += y;
                szz += z * z;
                szy += z * y;
                syy += y * y;
            }
            const double vz = szz - sz * sz / n, vy = syy - sy * sy / n, cov = szy - sz * sy / n;
            cost += vz > 1e-300 ? vy - cov * cov / vz : vy;
        }
        thicknesses.push_back(t);
        costs.push_back(cost / std::max(1, 3 * level.usable_count));
        const double rate = weighted ? rate_per_um : resolved_phase_per_um(t);
        const double step = std::clamp(0.25 / (rate * t + 1e-12), 2e-4, 0.05);
        t *= 1.0 + step;
    }
    std::vector<ThicknessMinimum> minima;
    for (std::size_t i = 0; i < costs.size(); ++i) {
        const bool left = i == 0 || costs[i] <= costs[i - 1];
        const bool right = i + 1 == costs.size() || costs[i] <= costs[i + 1];
        if (!left || !right) continue;
        std::size_t low = i, high = i;
        while (low > 0 && costs[low - 1] >= costs[low]) --low;
        while (high + 1 < costs.size() && costs[high + 1] >= costs[high]) ++high;
        minima.push_back({thicknesses[i], costs[i], thicknesses[low], thicknesses[high]});
    }
    std::sort(minima.begin(), minima.end(), [](const ThicknessMinimum& a, const ThicknessMinimum& b) { return a.cost < b.cost; });
    if (static_cast<int>(minima.size()) > count) minima.resize(static_cast<std::size_t>(count));
    return minima;
}

/// A start of the geometry's refinement: a minimum of the thickness search and the scale it was found at.
struct SearchStart {
    double thickness_um, field_radius_px, cost;
};

/// Whether the crystal has two optic axes: three distinct principal indices (at the middle wavelength).
bool is_biaxial(const ConoscopePhotoModel& model) {
    const std::vector<double>& wavelengths = model.settings.wavelengths_nm;
    Eigen::Vector3d n = model.principal_n(wavelengths[wavelengths.size() / 2]);
    std::sort(n.begin(), n.end());
    return std::min(n[1] - n[0], n[2] - n[1]) > 1e-3 * (n[2] - n[0]);
}

/// The thickness search's lowest `options.candidates` minima. Where the scale is free, no field stop shows it and
/// the crystal is biaxial, the search runs at five scales a factor √2 apart about the starting one (0.25 … 1 frame
/// for the default half frame) and keeps the lowest minima of all: the distance between the melatopes fixes the
/// scale, but a scan at a wrong one puts them at the wrong distance, from where the refinement of the geometry need
/// not find its way (a 128² aragonite photo through a tangent projection, started at 64 px: 470 µm for 71). A
/// uniaxial figure hardly fixes its scale (thickness × scale² for a centred one; docs/fitting.md), and there the
/// scans at other scales only offer equally good minima elsewhere along that line. Scales outside `bounds` are skipped.
std::vector<SearchStart> search_starts(const PhotoLevel& level, const ConoscopePhotoModel& model, const PhotoParameters& start, double min_um,
                                       double max_um, const ConoscopeFitOptions& options, const Bounds& bounds) {
    const std::size_t r = index_of(PhotoParameter::field_radius_px);
    const int steps = options.free[r] && model.field_stop != FieldStop::sharp && is_biaxial(model) ? 2 : 0;  // each way
    std::vector<SearchStart> starts;
    for (int step = -steps; step <= steps; ++step) {
        const double radius_px = start[r] * std::pow(std::numbers::sqrt2, step);
        if (step != 0 && (radius_px < bounds.lower[r] || radius_px > bounds.upper[r])) continue;
        PhotoParameters values = start;
        values[r] = radius_px;
        for (const ThicknessMinimum& minimum :
             thickness_minima(level, model.rgb_per_transmission, values, min_um, max_um, options.candidates, StepRule::finest_resolved_fringe)) {
            starts.push_back({minimum.thickness_um, radius_px, minimum.cost});
        }
    }
    std::sort(starts.begin(), starts.end(), [](const SearchStart& a, const SearchStart& b) { return a.cost < b.cost; });
    if (static_cast<int>(starts.size()) > options.candidates) starts.resize(static_cast<std::size_t>(options.candidates));
    return starts;
}

struct Statistics {
    double rms = 0.0, explained_variance = 0.0;
};

Statistics residual_statistics(const PhotoLevel& level, const PhotoCost& cost, const PhotoParameters& values) {
    const std::vector<Eigen::Vector3d> model = cost.model_values(values);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum2 = Eigen::Vector3d::Zero();
    double squared = 0.0, n = 0.0;
    for (std::size_t k = 0; k < model.size(); ++k) {
        if (level.usable[k] == 0) continue;
        squared += (model[k] - level.observed[k]).squaredNorm();
        sum += level.observed[k];
        sum2 += level.observed[k].cwiseProduct(level.observed[k]);
        n += 1.0;
    }
    const double total = (sum2 - sum.cwiseProduct(sum) / n).sum();
    return {std::sqrt(squared / (3.0 * n)), total > 0.0 ? 1.0 - squared / total : 0.0};
}

/// The squares of the systematic shifts of one quantity (`of` reads it from a shift): the encoding's and the
/// mosaic's, independent errors added in quadrature; 0 where neither was checked.
template <typename Quantity>
double systematic_variance(const ConoscopeFitResult& result, const Quantity& of) {
    double variance = 0.0;
    for (const std::optional<PhotoParameters>* shift : {&result.encoding_shift, &result.mosaic_shift}) {
        if (*shift) variance += of(**shift) * of(**shift);
    }
    return variance;
}

/// 1σ from the covariance C = (JᵀJ)⁺ made robust to residuals that are correlated over the photo
/// (blur, JPEG blocks, what the model leaves out): the cluster sandwich C·(Σ_b g_b g_bᵀ)·C with
/// g_b = J_bᵀr_b summed over square blocks of the field (Liang & Zeger 1986; Cameron & Miller 2015, eq. 11),
/// times G/(G − 1) for G blocks. Which free parameters the photo does not determine: those in near-null
/// directions of the scaled normal matrix, or with a huge 1σ.
void uncertainties(const PhotoCost& cost, const PhotoLevel& level, ConoscopeFitResult& result,
                   const ConoscopeFitOptions& options) {
    std::vector<int> free_indices;
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        if (options.free[static_cast<std::size_t>(j)]) free_indices.push_back(j);
    }
    const int m = cost.num_residuals();
    const int p = static_cast<int>(free_indices.size());
    std::vector<double> residuals(static_cast<std::size_t>(m));
    std::vector<double> jacobian(static_cast<std::size_t>(m) * kPhotoParameterCount);
    const double* parameter_block = result.values.data();
    double* jacobian_block = jacobian.data();
    if (!cost.Evaluate(&parameter_block, residuals.data(), &jacobian_block)) {
        // The model is undefined at the best fit (PhotoCost refuses it): no derivatives, so no 1σ.
        for (std::size_t k = 0; k < kPhotoParameterCount; ++k) result.parameters[k] = {result.values[k], std::nullopt, options.free[k], false};
        result.warnings.push_back("the model cannot be evaluated at the best fit, so no parameter has an uncertainty");
        return;
    }
    // Blocks of a quarter of the field radius.
    const double block_px = 0.25 * at(result.values, PhotoParameter::field_radius_px);
    std::map<std::pair<int, int>, Eigen::Matrix<double, kPhotoParameterCount, 1>> scores;
    for (std::size_t k = 0; k < level.evaluator.sample_count(); ++k) {
        const Eigen::Vector2d& pixel = level.evaluator.lattice().pixels[k];
        auto& score = scores.try_emplace({static_cast<int>(std::floor(pixel.x() / block_px)), static_cast<int>(std::floor(pixel.y() / block_px))},
                                         Eigen::Matrix<double, kPhotoParameterCount, 1>::Zero()).first->second;
        for (std::size_t row = 3 * k; row < 3 * k + 3; ++row) {
            score += Eigen::Map<const Eigen::Matrix<double, kPhotoParameterCount, 1>>(jacobian.data() + row * kPhotoParameterCount) * residuals[row];
        }
    }
    Eigen::Matrix<double, kPhotoParameterCount, kPhotoParameterCount> meat = Eigen::Matrix<double, kPhotoParameterCount, kPhotoParameterCount>::Zero();
    for (const auto& [cell, score] : scores) meat += score * score.transpose();
    const double clusters = static_cast<double>(scores.size());
    meat *= clusters / std::max(clusters - 1.0, 1.0);

    Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(p, p);
    for (int row = 0; row < m; ++row) {
        const double* jr = jacobian.data() + static_cast<std::size_t>(row) * kPhotoParameterCount;
        for (int a = 0; a < p; ++a) {
            for (int b = 0; b <= a; ++b) normal(a, b) += jr[free_indices[a]] * jr[free_indices[b]];
        }
    }
    normal = normal.selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd scale = normal.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd scaled = scale.asDiagonal() * normal * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
    std::vector<bool> unidentified(kPhotoParameterCount, false);
    const double largest = eigen.eigenvalues().maxCoeff();
    for (int e = 0; e < p; ++e) {
        if (eigen.eigenvalues()[e] > 1e-9 * largest) continue;
        for (int a = 0; a < p; ++a) {
            if (std::abs(eigen.eigenvectors()(a, e)) > 0.2) unidentified[static_cast<std::size_t>(free_indices[a])] = true;
        }
    }

    // C = (JᵀJ)⁺ from the same decomposition: S·V·Λ⁺·Vᵀ·S, the directions below 10⁻¹⁴ of the largest eigenvalue
    // dropped (they are reported as unidentified above; a pseudo-inverse, as a truncated SVD of J gives it).
    Eigen::VectorXd inverse_eigenvalues(p);
    for (int e = 0; e < p; ++e) {
        const double eigenvalue = eigen.eigenvalues()[e];
        inverse_eigenvalues[e] = eigenvalue > 1e-14 * largest ? 1.0 / eigenvalue : 0.0;
    }
    const Eigen::MatrixXd free_covariance =
        scale.asDiagonal() * eigen.eigenvectors() * inverse_eigenvalues.asDiagonal() * eigen.eigenvectors().transpose() * scale.asDiagonal();
    Eigen::Matrix<double, kPhotoParameterCount, kPhotoParameterCount> bread = Eigen::Matrix<double, kPhotoParameterCount, kPhotoParameterCount>::Zero();
    for (int a = 0; a < p; ++a) {
        for (int b = 0; b < p; ++b) bread(free_indices[a], free_indices[b]) = free_covariance(a, b);
    }
    const Eigen::Matrix<double, kPhotoParameterCount, kPhotoParameterCount> sandwich = bread * meat * bread.transpose();
    const double radius = at(result.values, PhotoParameter::field_radius_px);
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const auto k = static_cast<std::size_t>(j);
        FittedValue& fitted = result.parameters[k];
        fitted.value = result.values[k];
        fitted.free = options.free[k];
        if (!fitted.free) continue;
        const double variance_j = sandwich(j, j) + systematic_variance(result, [k](const PhotoParameters& shift) { return shift[k]; });
        const double sigma = variance_j >= 0.0 ? std::sqrt(variance_j) : std::numeric_limits<double>::infinity();
        double limit = kUnidentifiedSigma[k];
        if (j == static_cast<int>(PhotoParameter::thickness_um)) limit *= fitted.value;
        if (j >= static_cast<int>(PhotoParameter::center_x_px) && j <= static_cast<int>(PhotoParameter::field_radius_px)) limit = 0.1 * radius;
        if (j == static_cast<int>(PhotoParameter::envelope_radius_px)) limit *= fitted.value;
        if (j == static_cast<int>(PhotoParameter::envelope_center_x_px) || j == static_cast<int>(PhotoParameter::envelope_center_y_px)) {
            limit = 0.5 * at(result.values, PhotoParameter::envelope_radius_px);
        }
        fitted.identifiable = !unidentified[k] && std::isfinite(sigma) && sigma <= limit;
        if (fitted.identifiable) fitted.sigma = sigma;
    }
    // Pairs the photo cannot tell apart (|correlation| > 0.9999: either one's 1σ is over 70 times what it
    // would be with the other known, so only the model's finest details separate them): neither is a
    // measurement.
    // Above 0.999 the pair is only weakly separated: a warning, the 1σ says how weakly.
    for (int a = 0; a < p; ++a) {
        for (int b = 0; b < a; ++b) {
            const auto ka = static_cast<std::size_t>(free_indices[a]), kb = static_cast<std::size_t>(free_indices[b]);
            const double denominator = std::sqrt(bread(ka, ka) * bread(kb, kb));
            if (!(denominator > 0.0)) continue;
            const double correlation = bread(ka, kb) / denominator;
            if (std::abs(correlation) <= 0.999) continue;
            const bool degenerate = std::abs(correlation) > 0.9999;
            result.warnings.push_back(std::string(kNames[kb]) + " and " + std::string(kNames[ka]) + " are correlated " +
                                      format_significant(correlation, 6) +
                                      (degenerate ? ": the photo determines only a combination of them" : ": the photo separates them only weakly"));
            if (!degenerate) continue;
            for (const std::size_t k : {ka, kb}) {
                result.parameters[k].identifiable = false;
                result.parameters[k].sigma.reset();
            }
        }
    }
    const auto& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const auto& scale_fit = result.parameters[index_of(PhotoParameter::field_radius_px)];
    if (thickness.free && !thickness.identifiable && scale_fit.free) {
        // What the photo does determine: the ring radii, phase ∝ d·ξ² ∝ d·(pixels/r)², so d/r², with its 1σ
        // from the same covariance (var ln(d/r²) = var d/d² + 4 var r/r² − 4 cov(d, r)/(d·r)).
        const std::size_t d = index_of(PhotoParameter::thickness_um), r = index_of(PhotoParameter::field_radius_px);
        const double thickness_um = result.values[d], radius_px = result.values[r];
        // The systematic shifts of the combination add in quadrature, as for every parameter.
        const double relative_variance =
            sandwich(d, d) / (thickness_um * thickness_um) + 4.0 * sandwich(r, r) / (radius_px * radius_px) - 4.0 * sandwich(d, r) / (thickness_um * radius_px) +
            systematic_variance(result, [&](const PhotoParameters& shift) { return shift[d] / thickness_um - 2.0 * shift[r] / radius_px; });
        const double ratio = thickness_um / (radius_px * radius_px);
        const std::string sigma = relative_variance >= 0.0 ? " +- " + format_significant(ratio * std::sqrt(relative_variance), 3) : "";
        result.warnings.push_back("the thickness is not determined: a centred uniaxial figure fixes only thickness x scale^2 (the ring "
                                  "radii; scale = sin(theta) per pixel = NA / field_radius_px), here thickness_um / field_radius_px^2 = " +
                                  format_significant(ratio, 6) + sigma + "; fix the scale (--fix field_radius_px=...) or use an off-centre figure");
    }
    for (int j = 0; j < kPhotoParameterCount; ++j) {
        const FittedValue& fitted = result.parameters[static_cast<std::size_t>(j)];
        if (fitted.free && !fitted.identifiable) {
            result.warnings.push_back(std::string(kNames[static_cast<std::size_t>(j)]) + " is not determined by this photo; its value is not a measurement");
        }
    }
}

/// The model's photo (camera values, 0 outside the field), each pixel evaluated on a lattice of
/// `stride_px` anchored at `anchor` + its offset: the fringe blur takes the phase's derivatives between
/// lattice neighbours, so on the anchor's own lattice (a fit level's) the values are exactly those the fit
/// matched there, and every other pixel is the same model.
Image render_photo_on_lattices(const ConoscopePhotoModel& model, const PhotoParameters& values, int width_px, int height_px,
                               const Eigen::Vector2d& anchor, int stride_px) {
    const Eigen::Vector2d centre(at(values, PhotoParameter::center_x_px), at(values, PhotoParameter::center_y_px));
    // Without a field stop the light reaches the whole frame.
    const double radius = model.field_stop == FieldStop::sharp ? at(values, PhotoParameter::field_radius_px) : std::numeric_limits<double>::infinity();
    const double reach = model.field_stop == FieldStop::sharp ? radius + (centre - anchor).norm() + 2.0 * stride_px
                                                              : std::hypot(width_px, height_px) + 2.0 * stride_px;
    Image image(width_px, height_px, 3);
    std::vector<InterferenceTerms> terms;
    detail::PhaseDerivatives phase;
    detail::LinearSamples linear;
    for (int dy = 0; dy < stride_px; ++dy) {
        for (int dx = 0; dx < stride_px; ++dx) {
            const detail::PhotoModelEvaluator evaluator(
                model, detail::sample_lattice(anchor + Eigen::Vector2d(dx, dy), reach, stride_px, width_px, height_px));
            evaluator.terms(values, terms);
            evaluator.phase_derivatives(terms, phase);
            const std::vector<detail::EnvelopeValue> envelope = evaluator.envelope(values);
            const double blur2 = at(values, PhotoParameter::blur_variance_px2);
            evaluator.linear(terms, phase, at(values, PhotoParameter::thickness_um), blur2, evaluator.blur_shifts(envelope, blur2), false, linear);
            evaluator.illuminate(envelope, linear);
            const std::vector<Eigen::Vector3d> camera = detail::camera_values(linear.rgb, values);
            for (std::size_t k = 0; k < camera.size(); ++k) {
                const Eigen::Vector2d& pixel = evaluator.lattice().pixels[k];
                if ((pixel - centre).norm() > radius) continue;
                for (int c = 0; c < 3; ++c) image.at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()), c) = static_cast<float>(camera[k][c]);
            }
        }
    }
    return image;
}

}  // namespace

std::string_view photo_parameter_name(PhotoParameter parameter) { return kNames[index_of(parameter)]; }

PhotoParameter parse_photo_parameter(std::string_view name) {
    const auto found = std::find(kNames.begin(), kNames.end(), name);
    if (found != kNames.end()) return static_cast<PhotoParameter>(found - kNames.begin());
    std::string names;
    for (const std::string_view known : kNames) names += (names.empty() ? "" : ", ") + std::string(known);
    throw InputError("unknown parameter " + quote_input(name) + " (expected one of " + names + ")");
}

PhotoParameters default_photo_parameters(int width_px, int height_px) {
    PhotoParameters values{};
    at(values, PhotoParameter::thickness_um) = 30.0;
    at(values, PhotoParameter::center_x_px) = 0.5 * width_px;
    at(values, PhotoParameter::center_y_px) = 0.5 * height_px;
    at(values, PhotoParameter::field_radius_px) = 0.5 * std::min(width_px, height_px);
    at(values, PhotoParameter::gain_r) = at(values, PhotoParameter::gain_g) = at(values, PhotoParameter::gain_b) = 1.0;
    at(values, PhotoParameter::gamma) = 2.2;
    at(values, PhotoParameter::blur_variance_px2) = 1.0;
    at(values, PhotoParameter::envelope_center_x_px) = 0.5 * width_px;
    at(values, PhotoParameter::envelope_center_y_px) = 0.5 * height_px;
    at(values, PhotoParameter::envelope_radius_px) = 0.5 * std::hypot(width_px, height_px);
    at(values, PhotoParameter::envelope_power) = 2.0;
    return values;
}

ConoscopeFitResult fit_conoscope_photo(const Image& photo_in, const ConoscopePhotoModel& model, const ConoscopeFitOptions& given_options,
                                       const ProgressCallback& progress) {
    // Under even light the envelope's parameters act on nothing: they stay fixed.
    ConoscopeFitOptions options = given_options;
    if (model.illumination == IlluminationProfile::even) {
        for (std::size_t k = index_of(PhotoParameter::envelope_center_x_px); k <= index_of(PhotoParameter::envelope_power); ++k) options.free[k] = false;
    }
    if (!(options.thickness_min_um > 0.0) || !(options.thickness_max_um >= options.thickness_min_um)) {
        throw InputError("the thickness range must be positive and ordered, e.g. 10um:5mm");
    }
    if (model.rgb_per_transmission.size() != model.settings.wavelengths_nm.size()) {
        throw InputError("the colour weights and the figure use different wavelength grids");
    }
    ProgressRelay relay(progress);
    const auto reached = [&relay](double fraction_done) {
        relay.report(fraction_done);
        relay.stop_if_cancelled();
    };
    const bool white_light = model.settings.wavelengths_nm.size() > 1;
    const Image photo = colour_photo(photo_in, white_light);
    // A held parameter outside the box the fit keeps the free ones in is a value the model is not meant for
    // (a zero field or envelope radius, an extinction ratio of 2): refused, naming it.
    const Bounds bounds = detail::photo_parameter_bounds(options.thickness_min_um, options.thickness_max_um, photo.width, photo.height);
    for (std::size_t k = 0; k < kPhotoParameterCount; ++k) {
        const double value = options.initial[k];
        if (options.free[k] || (value >= bounds.lower[k] && value <= bounds.upper[k])) continue;
        throw InputError(std::string(kNames[k]) + " = " + format_significant(value, 6) + " is outside " + format_significant(bounds.lower[k], 6) +
                         " ... " + format_significant(bounds.upper[k], 6) + " for this photo and thickness range");
    }
    PhotoParameters start = options.initial;
    const bool centre_free = options.free[index_of(PhotoParameter::center_x_px)] && options.free[index_of(PhotoParameter::center_y_px)];
    // An untilted cut's figure is symmetric under a half turn about its centre. A cut tilted a little (the tilt free
    // from 0) shows nearly that figure moved, and without a field stop to fix the projection's centre the untilted
    // start is best placed where the figure is; with one, the stop's centre is the projection's.
    const bool tilt_free = options.free[index_of(PhotoParameter::tilt_deg)];
    const bool symmetric_start = at(start, PhotoParameter::tilt_deg) == 0.0 && (!tilt_free || model.field_stop == FieldStop::none);
    if (options.locate_centre && centre_free && symmetric_start) {
        if (const std::optional<Eigen::Vector2d> located = detail::half_turn_symmetry_centre_px(photo)) {
            at(start, PhotoParameter::center_x_px) = located->x();
            at(start, PhotoParameter::center_y_px) = located->y();
        }
    }
    const Eigen::Vector2d centre(at(start, PhotoParameter::center_x_px), at(start, PhotoParameter::center_y_px));
    const bool sharp_stop = model.field_stop == FieldStop::sharp;
    const double edge = sharp_stop ? radius_where_light_falls(photo, centre, 0.2, at(start, PhotoParameter::field_radius_px)) : 0.0;
    if (sharp_stop && options.free[index_of(PhotoParameter::field_radius_px)]) at(start, PhotoParameter::field_radius_px) = edge;
    // An envelope to be fitted starts where the light has fallen to 1/e (in camera values e^(−1/γ)).
    if (model.illumination == IlluminationProfile::falloff && options.free[index_of(PhotoParameter::envelope_radius_px)]) {
        at(start, PhotoParameter::envelope_radius_px) = radius_where_light_falls(
            photo, centre, std::exp(-1.0 / at(start, PhotoParameter::gamma)), at(start, PhotoParameter::envelope_radius_px));
    }
    // Samples within 0.85 of a sharp field edge (the blur and the edge's position are not modelled), or
    // over the whole frame.
    const double sample_radius = sharp_stop ? 0.85 * std::min(edge, at(start, PhotoParameter::field_radius_px))
                                            : std::hypot(std::max(centre.x(), photo.width - centre.x()), std::max(centre.y(), photo.height - centre.y()));

    // Four levels: the thickness search at the starting geometry and a refinement that finds the geometry
    // (both on the photo blurred further, so that they see the figure despite a wrong geometry), a
    // second thickness scan on the unblurred photo at that geometry, and the full photo; each samples the
    // field on a lattice of about this many pixels.
    const double sampled_area = std::min(std::numbers::pi * sample_radius * sample_radius, static_cast<double>(photo.width) * photo.height);
    const auto stride = [&](double samples) { return std::max(1, static_cast<int>(std::lround(std::sqrt(sampled_area / samples)))); };
    // The figure's terms are interpolated from spectral nodes where that holds the phase to 1e-3 rad at the thickest
    // slab fitted (ConoscopeTerms).
    ConoscopePhotoModel terms_model = model;
    terms_model.settings.thickness_um = bounds.upper[index_of(PhotoParameter::thickness_um)];
    const auto level = [&](int lattice_stride, double extra_blur) {
        return std::make_unique<PhotoLevel>(terms_model, detail::sample_lattice(centre, sample_radius, lattice_stride, photo.width, photo.height),
                                            photo, extra_blur, at(start, PhotoParameter::gamma), options.saturated_level);
    };
    const int search_stride = stride(2500.0), coarse_stride = stride(5000.0);
    const auto search = level(search_stride, search_stride);
    const auto coarse = level(coarse_stride, 0.75 * coarse_stride);
    const auto scan = level(coarse_stride, 0.0);
    // The full photo on about 10000: the last refinement and the encoding check, most of a fit, scale with it. At 512² that is
    // every 5th pixel (every 4th for 15000: the realistic-camera bed in 0.83 of the time, the same cases within 2% and
    // 2σ, each error moved within about its 1σ; docs/fitting.md, "Benchmark").
    const auto fine = level(stride(10000.0), 0.0);
    if (fine->usable_count < 0.1 * static_cast<double>(fine->evaluator.sample_count()) || fine->usable_count < 50) {
        throw InputError("the photo is saturated: only " + std::to_string(fine->usable_count) + " of " +
                         std::to_string(fine->evaluator.sample_count()) + " sample pixels in the field are below full scale");
    }
    reached(0.02);

    ConoscopeFitResult result;
    result.pixels_used = fine->usable_count;
    result.pixels_saturated = static_cast<int>(fine->evaluator.sample_count()) - fine->usable_count;
    // The thickness range scanned (one thickness when it is fixed), and bounds that keep a refinement of
    // a minimum in its basin (out to the global bound where the basin reaches the end of the range).
    const bool thickness_free = options.free[index_of(PhotoParameter::thickness_um)];
    const double scan_min_um = thickness_free ? options.thickness_min_um : at(start, PhotoParameter::thickness_um);
    const double scan_max_um = thickness_free ? options.thickness_max_um : at(start, PhotoParameter::thickness_um);
    const auto basin_bounds = [&](const ThicknessMinimum& minimum) {
        Bounds basin = bounds;
        const std::size_t k = index_of(PhotoParameter::thickness_um);
        if (minimum.lower_um > scan_min_um) basin.lower[k] = minimum.lower_um;
        if (minimum.upper_um < scan_max_um) basin.upper[k] = minimum.upper_um;
        return basin;
    };
    const std::vector<SearchStart> starts = search_starts(*search, model, start, scan_min_um, scan_max_um, options, bounds);
    reached(0.15);

    // The small corrections of the optics (distortion, the analyzer's offset and leak) and of the camera's
    // colours (its colour matrix) are fitted on the full photo only: on the blurred levels, far from the fit,
    // they only add ways to wander (a calcite figure through an equidistant lens went to the distortion's
    // bound, past its fold, and to 870 µm for 150).
    ConoscopeFitOptions polars_held = options;
    for (const PhotoParameter p : {PhotoParameter::distortion, PhotoParameter::analyzer_offset_deg, PhotoParameter::extinction_ratio}) {
        polars_held.free[index_of(p)] = false;
    }
    for (std::size_t k = index_of(PhotoParameter::crosstalk_rg); k <= index_of(PhotoParameter::crosstalk_bg); ++k) polars_held.free[k] = false;
    // Every minimum is refined on the coarse level, for the geometry and the camera. Its thickness is not
    // held in the basin: at a wrong starting geometry the search's minima need not be the photo's.
    PhotoParameters geometry = start;
    double geometry_cost = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < starts.size(); ++k) {
        PhotoParameters values = start;
        at(values, PhotoParameter::thickness_um) = starts[k].thickness_um;
        at(values, PhotoParameter::field_radius_px) = starts[k].field_radius_px;
        const double cost = solve_level(*coarse, values, polars_held, bounds, 30, 1e-6, result.iterations, relay, geometry_cost);
        if (cost < geometry_cost) {
            geometry_cost = cost;
            geometry = values;
        }
        reached(0.15 + 0.4 * static_cast<double>(k + 1) / static_cast<double>(starts.size()));
    }
    // The coarse level's blur hides the fine fringes of a thick slab, and there thickness trades against
    // blur (the attenuation depends on σ·d), so its thickness and blur are not trusted: the thickness is
    // scanned again on the unblurred photo at the geometry and camera of its lowest minimum, from the
    // starting blur. The fringes that tell the minima apart are those the blur attenuates, so each minimum
    // is then refined there, within its basin, with the blur and the camera but not the geometry (whose
    // figure terms are then computed once); the lowest is refined on the full photo with every parameter.
    at(geometry, PhotoParameter::blur_variance_px2) = at(start, PhotoParameter::blur_variance_px2);
    const std::vector<ThicknessMinimum> minima =
        thickness_minima(*scan, model.rgb_per_transmission, geometry, scan_min_um, scan_max_um, options.candidates,
                         StepRule::power_weighted_fringes);
    ConoscopeFitOptions geometry_held = polars_held;
    for (std::size_t k = index_of(PhotoParameter::center_x_px); k <= index_of(PhotoParameter::azimuth_deg); ++k) geometry_held.free[k] = false;
    std::size_t best = 0;
    double best_scan_cost = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < minima.size(); ++k) {
        PhotoParameters values = geometry;
        at(values, PhotoParameter::thickness_um) = minima[k].thickness_um;
        const double residual_count = std::max(1, 3 * scan->usable_count);
        const double cost = solve_level(*scan, values, geometry_held, basin_bounds(minima[k]), 20, 1e-6, result.iterations, relay,
                                        best_scan_cost * residual_count) /
                            residual_count;
        result.candidates.push_back({minima[k].thickness_um, at(values, PhotoParameter::thickness_um), cost});
        if (cost < best_scan_cost) {
            best_scan_cost = cost;
            best = k;
            result.values = values;
        }
        reached(0.55 + 0.15 * static_cast<double>(k + 1) / static_cast<double>(minima.size()));
    }
    Bounds final_bounds = basin_bounds(minima[best]);
    const double best_cost = refine_in_basin(*fine, result.values, options, bounds, final_bounds, result.iterations, relay) /
                             std::max(1, 3 * fine->usable_count);
    const double fitted_um = at(result.values, PhotoParameter::thickness_um);
    // The refinement may leave the searched range (its bounds are half and twice its ends), but the search did
    // not look there for other minima.
    if (thickness_free && (fitted_um <= scan_min_um * (1.0 + kOnBound) || fitted_um >= scan_max_um * (1.0 - kOnBound))) {
        result.warnings.push_back("the thickness, " + format_significant(fitted_um, 6) + " um, is at or beyond an end of the searched range (" +
                                  format_significant(scan_min_um, 4) + " to " + format_significant(scan_max_um, 4) +
                                  " um), where no other minimum was looked for: search a range that contains it "
                                  "(--thickness-range; thickness_range_um in Python)");
    }
    result.candidates[best].thickness_um = fitted_um;
    std::sort(result.candidates.begin(), result.candidates.end(),
              [](const ThicknessCandidate& a, const ThicknessCandidate& b) { return a.cost < b.cost; });
    reached(0.95);

    // One cost on the fine level for the checks, the uncertainties and the statistics: the figure's
    // terms at the best fit's geometry are computed once and kept by it.
    const PhotoCost cost(*fine, options.free, options.robust_scale);
    // The systematic errors of what the camera did that the model does not follow: the best-fit model's photo,
    // altered as the photo was, fitted again from the best fit on the same samples (a parametric bootstrap
    // without noise; Efron & Tibshirani 1993, §10.6). Unaltered, this refit returns the best fit itself.
    const bool bayer = options.sensor == ColourSensor::bayer;
    if (options.photo_encoding || bayer) {
        Image best_fit = render_photo_on_lattices(model, result.values, photo.width, photo.height, centre, fine->evaluator.lattice().stride_px);
        // The fine level's own samples exactly as the fit matched them (at the sampled area's edge its
        // derivatives are one-sided).
        const std::vector<Eigen::Vector3d> matched = cost.model_values(result.values);
        for (std::size_t k = 0; k < matched.size(); ++k) {
            const Eigen::Vector2d& pixel = fine->evaluator.lattice().pixels[k];
            for (int c = 0; c < 3; ++c) best_fit.at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()), c) = static_cast<float>(matched[k][c]);
        }
        const auto shift_when_fitted = [&](const Image& altered) {
            const detail::PhotoLevel altered_level(terms_model, fine->evaluator.lattice(), altered, 0.0, at(start, PhotoParameter::gamma),
                                                   options.saturated_level);
            PhotoParameters refitted = result.values;
            solve_level(altered_level, refitted, options, final_bounds, 40, converged_fraction(altered_level), result.iterations, relay);
            PhotoParameters shift{};
            for (std::size_t k = 0; k < shift.size(); ++k) shift[k] = refitted[k] - result.values[k];
            return shift;
        };
        if (options.photo_encoding) result.encoding_shift = shift_when_fitted(options.photo_encoding(best_fit));
        if (bayer) {
            result.mosaic_shift = shift_when_fitted(
                detail::through_bayer_mosaic(best_fit, at(result.values, PhotoParameter::black_level), at(result.values, PhotoParameter::gamma)));
        }
    }
    reached(0.98);

    uncertainties(cost, *fine, result, options);
    // A thickness left on the box's bound (half the searched range's start, twice its end) is not at a minimum of the
    // cost, which would go on past it: the photo does not determine it there, whatever the covariance says.
    const std::size_t thickness_index = index_of(PhotoParameter::thickness_um);
    if (thickness_free && (fitted_um <= bounds.lower[thickness_index] * (1.0 + kOnBound) || fitted_um >= bounds.upper[thickness_index] * (1.0 - kOnBound))) {
        result.parameters[thickness_index].identifiable = false;
        result.parameters[thickness_index].sigma.reset();
        result.warnings.push_back("the thickness ended on the bound of the fit, " + format_significant(fitted_um, 6) +
                                  " um, not at a minimum: the photo does not determine it (a figure blurred or cut away?)");
    }
    const Statistics statistics = residual_statistics(*fine, cost, result.values);
    result.rms_residual = statistics.rms;
    result.explained_variance = statistics.explained_variance;
    // An acceptable fit explains most of the photo's variation (a figure of another crystal, or no
    // figure at all, leaves it unexplained).
    constexpr double kMinimumExplained = 0.5;
    const double explained = statistics.explained_variance;
    result.acceptable = std::isfinite(best_cost) && std::isfinite(explained) && explained >= kMinimumExplained;
    if (!std::isfinite(best_cost)) {
        result.verdict = "no acceptable fit: the least-squares refinement failed (the model is undefined where it started)";
    } else if (result.acceptable) {
        result.verdict = "the model explains " + format_significant(100.0 * explained, 3) + "% of the photo's variance (rms residual " +
                         format_significant(statistics.rms, 3) + ")";
    } else {
        result.verdict = "no acceptable fit: the best model explains only " + format_significant(100.0 * explained, 3) +
                         "% of the photo's variance (cost " + format_significant(best_cost, 4) + " per residual, rms residual " +
                         format_significant(statistics.rms, 3) + ")";
    }
    reached(1.0);
    return result;
}

Image render_conoscope_photo(const ConoscopePhotoModel& model, const PhotoParameters& values, int width_px, int height_px) {
    const Eigen::Vector2d centre(at(values, PhotoParameter::center_x_px), at(values, PhotoParameter::center_y_px));
    return render_photo_on_lattices(model, values, width_px, height_px, centre, 1);
}

}  // namespace petroscope
