#include "petroscope/fit/orthoscope_fit.hpp"

#include "cancel_between_iterations.hpp"
#include "grain_camera.hpp"
#include "solver_messages.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

namespace petroscope {
namespace {

constexpr double kReferenceNm = 550.0;
// A colour residual of 0.03 rms (8 code levels of 255) is the most a fit of a real grain may leave.
constexpr double kAcceptableRmsCode = 0.03;
// The colour means of a photo are not trusted below one code level (camera, JPEG): the 1σ floor.
constexpr double kCodeFloor = 1.0 / 255.0;
// Codes up to this are dark: a photo this dark everywhere may be grey (an extinct grain) and still be used.
constexpr double kDarkCode = 4.0 / 255.0;
// Priors of the camera terms fitted with the grain when a reference calibrates the camera: a channel gain
// 10% from the others' mean, or a contrast 30% from 1, costs as much as one colour residual of two code
// levels (a camera balanced on its light keeps its channels within about 10% of each other; a camera's
// tone curve is steeper than sRGB's by up to about a third).
constexpr double kGainPrior = (2.0 / 255.0) / 0.1, kContrastPrior = (2.0 / 255.0) / 0.3;
// Parameter layout of the least squares. kGain0 + c: channel c's gain relative to the reference's, fitted
// where no reference lights the channel; kContrast: the camera's contrast curve (detail::camera_tone).
enum Slot { kThickness = 0, kAngle0 = 1, kExposure = 4, kGain0 = 5, kContrast = 8, kSlots = 9 };

/// The camera at some parameters: gains on the linear display channels and the contrast of its tone curve.
struct Camera {
    Eigen::Vector3d gains = Eigen::Vector3d::Ones();
    double contrast = 1.0;
};

/// Everything that does not depend on the grain's parameters: per photo, the microscope optics.
class GrainModel {
public:
    GrainModel(const std::vector<GrainPhoto>& photos, const Mineral& mineral, const OrthoscopeFitOptions& options,
               const SpectralIntegrator& integrator)
        : photos_(photos), mineral_(mineral), options_(options), integrator_(integrator),
          display_(xyz_to_display_matrix(integrator.white_xyz(), options.white_balance, 1.0)) {
        for (const GrainPhoto& photo : photos) {
            auto settings = std::make_unique<MicroscopeSettings>(options.microscope);
            settings->stage_deg = photo.stage_deg;
            settings->plate = photo.plate;
            if (settings->condenser_rings == 0) {  // automatic: enough for the thickest grain searched
                const double spread = condenser_phase_spread_rad(*settings, DispersiveMedium::of(mineral), options.thickness_max_um);
                settings->condenser_rings = condenser_rings_for(settings->condenser_na, spread);
            }
            optics_.push_back(std::make_unique<MicroscopeOptics>(*settings, options.mounting));
            settings_.push_back(std::move(settings));
        }
        if (std::any_of(photos.begin(), photos.end(), [](const GrainPhoto& photo) { return photo.reference.has_value(); })) {
            references_ = reference_colours();
        }
    }

    /// Whether a reference region calibrates the camera.
    bool calibrated() const { return references_.has_value(); }
    const detail::ReferenceColours& references() const { return *references_; }

    std::size_t photo_count() const { return photos_.size(); }
    const Mineral& mineral() const { return mineral_; }
    const GrainPhoto& photo(std::size_t k) const { return photos_[k]; }

    /// The indicatrix axes at stage 0 for the orientation parameters (degrees) of the options' mode.
    Eigen::Matrix3d axes(const double* angles_deg) const {
        switch (options_.orientation) {
            case GrainOrientation::known: return options_.known_axes;
            case GrainOrientation::max_birefringence: {
                // X along E, Z along N, Y down the microscope axis (X × Y = Z), then turned about the axis.
                Eigen::Matrix3d in_plane;
                in_plane << 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0;
                return rotation_z_deg(angles_deg[0]) * in_plane;
            }
            case GrainOrientation::free: return euler_zyz_deg(angles_deg[0], angles_deg[1], angles_deg[2]);
        }
        return options_.known_axes;
    }

    /// Per photo, the responses of a grain with these axes.
    std::vector<GrainResponse> responses(const Eigen::Matrix3d& axes) const {
        std::vector<GrainResponse> result;
        const DispersiveMedium grain = DispersiveMedium::of(mineral_, axes, options_.handedness);
        for (const auto& optics : optics_) result.emplace_back(*optics, grain);
        return result;
    }

    /// The linear display colour of a response at a thickness, before the camera.
    Eigen::Vector3d linear(const GrainResponse& response, double thickness_um, std::vector<double>& spectrum) const {
        response.transmission(thickness_um, spectrum);
        return display_ * integrator_.integrate(spectrum);
    }

    /// The camera at the parameters: exposure × the reference's gains at the contrast (1 without a reference)
    /// × the relative gains.
    Camera camera(const double* parameters) const {
        const Eigen::Vector3d base = calibrated() ? detail::reference_gains(*references_, parameters[kContrast]) : Eigen::Vector3d::Ones();
        const Eigen::Vector3d relative(parameters[kGain0], parameters[kGain0 + 1], parameters[kGain0 + 2]);
        return {parameters[kExposure] * base.cwiseProduct(relative), parameters[kContrast]};
    }

    /// The code (0 … 1) the camera makes of a response at a thickness.
    Eigen::Vector3d code(const GrainResponse& response, double thickness_um, const Camera& camera, std::vector<double>& spectrum) const {
        return detail::camera_code(camera.gains.cwiseProduct(linear(response, thickness_um, spectrum)), camera.contrast);
    }

    /// 3 colour residuals per photo, then the priors of the 3 relative gains and of the contrast.
    std::size_t residual_count() const { return 3 * photos_.size() + 4; }

    /// Residuals at the parameters, given the grain's responses at their orientation: model − photo (code
    /// units), 3 per photo, then the priors (zero where the terms are held at 1).
    void residuals(const std::vector<GrainResponse>& grain, const double* parameters, double* out) const {
        const Camera at = camera(parameters);
        std::vector<double> spectrum;
        for (std::size_t k = 0; k < photos_.size(); ++k) {
            const Eigen::Vector3d difference = code(grain[k], parameters[kThickness], at, spectrum) - photos_[k].colour.mean_code;
            for (int c = 0; c < 3; ++c) out[3 * k + static_cast<std::size_t>(c)] = difference[c];
        }
        const std::size_t priors = 3 * photos_.size();
        for (std::size_t c = 0; c < 3; ++c) out[priors + c] = kGainPrior * std::log(parameters[kGain0 + c]);
        out[priors + 3] = kContrastPrior * std::log(parameters[kContrast]);
    }

    /// The rms of the colour residuals (code units) at the parameters.
    double colour_rms(const double* parameters) const { return colour_rms(responses(axes(parameters + kAngle0)), parameters); }

    /// The same with the grain's responses at the parameters' orientation given.
    double colour_rms(const std::vector<GrainResponse>& grain, const double* parameters) const {
        std::vector<double> out(residual_count());
        residuals(grain, parameters, out.data());
        double squares = 0.0;
        for (std::size_t r = 0; r < 3 * photos_.size(); ++r) squares += out[r] * out[r];
        return std::sqrt(squares / static_cast<double>(3 * photos_.size()));
    }

    double maximum_birefringence() const {
        const Eigen::Vector3d n = mineral_.principal_n(kReferenceNm);
        return n.maxCoeff() - n.minCoeff();
    }

private:
    /// The references' model colours: no birefringence, so the microscope without the crystal (the grain's
    /// response at thickness 0). Throws InputError when no reference is lit in any channel.
    detail::ReferenceColours reference_colours() const {
        const std::vector<GrainResponse> no_crystal = responses(Eigen::Matrix3d::Identity());
        std::vector<double> spectrum;
        detail::ReferenceColours references;
        for (std::size_t k = 0; k < photos_.size(); ++k) {
            if (!photos_[k].reference) continue;
            references.photos.push_back(k);
            references.model_linear.push_back(linear(no_crystal[k], 0.0, spectrum));
            references.measured_code.push_back(photos_[k].reference->mean_code);
        }
        if (!detail::mark_lit_channels(references)) {
            throw InputError("the reference region is dark in every photo that gives it (between crossed polars without a plate it is black, "
                             "which calibrates nothing): give it in a photo with the plate in, where it shows the plate's own colour");
        }
        return references;
    }

    const std::vector<GrainPhoto>& photos_;
    const Mineral& mineral_;
    const OrthoscopeFitOptions& options_;
    const SpectralIntegrator& integrator_;
    Eigen::Matrix3d display_;
    std::vector<std::unique_ptr<MicroscopeSettings>> settings_;  // the optics keep references to them
    std::vector<std::unique_ptr<MicroscopeOptics>> optics_;
    std::optional<detail::ReferenceColours> references_;
};

/// The grain's responses at the indicatrix axes last asked for. They are nearly all of a residual's cost (the
/// eigenmodes at every wavelength and illumination direction), and most of the numeric derivatives keep the axes:
/// those in the thickness, the camera's terms and the angles the orientation mode does not use. With this, a
/// Jacobian of every slot costs 8 responses instead of 19 for a free orientation, 4 for one in the plane and 1 for
/// a known one.
class ResponseCache {
public:
    explicit ResponseCache(const GrainModel& model) : model_(model) {}

    const std::vector<GrainResponse>& at(const double* parameters) {
        const Eigen::Matrix3d axes = model_.axes(parameters + kAngle0);
        if (!responses_ || axes != axes_) {
            responses_ = model_.responses(axes);
            axes_ = axes;
        }
        return *responses_;
    }

private:
    const GrainModel& model_;
    Eigen::Matrix3d axes_;
    std::optional<std::vector<GrainResponse>> responses_;
};

struct ColourCost {
    const GrainModel* model;
    mutable ResponseCache cache{*model};
    bool operator()(double const* const* parameters, double* residuals) const {
        model->residuals(cache.at(parameters[0]), parameters[0], residuals);
        return true;
    }
};

int angle_count(GrainOrientation orientation) {
    switch (orientation) {
        case GrainOrientation::known: return 0;
        case GrainOrientation::max_birefringence: return 1;
        case GrainOrientation::free: return 3;
    }
    return 0;
}

/// The fitted parameters: thickness, the orientation's angles, the exposure when asked; with a reference,
/// the exposure (the grain may lie in other light than the reference), the gains of the channels no
/// reference lights, and the contrast.
std::array<bool, kSlots> free_slots(const GrainModel& model, const OrthoscopeFitOptions& options) {
    std::array<bool, kSlots> free{};
    free[kThickness] = true;
    for (int a = 0; a < angle_count(options.orientation); ++a) free[static_cast<std::size_t>(kAngle0 + a)] = true;
    free[kExposure] = options.exposure_free || model.calibrated();
    for (std::size_t c = 0; c < 3; ++c) free[kGain0 + c] = model.calibrated() && !model.references().lit[c];
    free[kContrast] = model.calibrated();
    return free;
}

/// The parameters at a thickness and orientation with the camera at its start: the options' exposure
/// (1 with a reference, whose gains hold the exposure), relative gains and contrast 1.
std::array<double, kSlots> initial_parameters(const GrainModel& model, const OrthoscopeFitOptions& options, double thickness_um,
                                              const std::array<double, 3>& angles_deg) {
    return {thickness_um, angles_deg[0], angles_deg[1], angles_deg[2], model.calibrated() ? 1.0 : options.exposure, 1.0, 1.0, 1.0, 1.0};
}

/// One point of the global search.
struct GridPoint {
    double cost = 0.0;
    double thickness_um = 0.0;
    std::array<double, 3> angles_deg{};
};

/// The global search's thickness step: at most 15 nm of retardation at the maximum birefringence
/// (interference colours change visibly over ~30 nm), at most 3000 steps over the range.
double thickness_step_um(const GrainModel& model, const OrthoscopeFitOptions& options) {
    const double range = options.thickness_max_um - options.thickness_min_um;
    return std::max(0.015 / std::max(model.maximum_birefringence(), 1e-6), range / 3000.0);
}

/// The grid over orientation × thickness, every point's colour cost (Σ residual²); reports the first half
/// of the fit's progress.
std::vector<GridPoint> global_search(const GrainModel& model, const OrthoscopeFitOptions& options, ProgressRelay& relay) {
    const double range = options.thickness_max_um - options.thickness_min_um;
    const double step_um = thickness_step_um(model, options);
    const int thickness_steps = static_cast<int>(std::ceil(range / step_um)) + 1;
    std::vector<std::array<double, 3>> orientations;
    switch (options.orientation) {
        case GrainOrientation::known: orientations.push_back({0.0, 0.0, 0.0}); break;
        case GrainOrientation::max_birefringence:
            for (double a = 0.0; a < 180.0; a += 7.5) orientations.push_back({a, 0.0, 0.0});
            break;
        case GrainOrientation::free:
            // The indicatrix is symmetric under half-turns about its axes: α, γ over 180°, β over 90°.
            for (double alpha = 0.0; alpha < 180.0; alpha += 22.5) {
                for (double beta = 0.0; beta <= 90.0; beta += 15.0) {
                    for (double gamma = 0.0; gamma < 180.0; gamma += 22.5) orientations.push_back({alpha, beta, gamma});
                }
            }
            break;
    }
    std::vector<GridPoint> grid(orientations.size() * static_cast<std::size_t>(thickness_steps));
    const Camera camera = model.camera(initial_parameters(model, options, 0.0, {}).data());
    std::atomic<int> done{0};
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t o = 0; o < orientations.size(); ++o) {
        if (relay.cancelled()) continue;
        const std::vector<GrainResponse> grain = model.responses(model.axes(orientations[o].data()));
        std::vector<double> spectrum;
        for (int s = 0; s < thickness_steps; ++s) {
            const double thickness = std::min(options.thickness_min_um + s * step_um, options.thickness_max_um);
            double cost = 0.0;
            for (std::size_t k = 0; k < model.photo_count(); ++k) {
                cost += (model.code(grain[k], thickness, camera, spectrum) - model.photo(k).colour.mean_code).squaredNorm();
            }
            grid[o * static_cast<std::size_t>(thickness_steps) + static_cast<std::size_t>(s)] = {cost, thickness, orientations[o]};
        }
        relay.report(0.5 * static_cast<double>(++done) / static_cast<double>(orientations.size()));
    }
    relay.stop_if_cancelled();
    return grid;
}

/// The best `count` grid points, each more than 4 thickness steps from those chosen before it or, for a grain of
/// maximum birefringence, more than 20° away on the stage (modulo 180°): the two orientations 90° apart, slow and
/// fast directions swapped, give colours alike without a plate, and only the plate tells them apart.
std::vector<GridPoint> starting_points(std::vector<GridPoint> grid, int count, double thickness_step_um, GrainOrientation orientation) {
    std::sort(grid.begin(), grid.end(), [](const GridPoint& a, const GridPoint& b) { return a.cost < b.cost; });
    std::vector<GridPoint> chosen;
    for (const GridPoint& point : grid) {
        if (static_cast<int>(chosen.size()) >= count) break;
        const bool near_chosen = std::any_of(chosen.begin(), chosen.end(), [&](const GridPoint& other) {
            const bool same_angle = orientation != GrainOrientation::max_birefringence ||
                                    std::abs(std::remainder(other.angles_deg[0] - point.angles_deg[0], 180.0)) < 20.0;
            return same_angle && std::abs(other.thickness_um - point.thickness_um) < 4.0 * thickness_step_um;
        });
        if (!near_chosen) chosen.push_back(point);
    }
    return chosen;
}

/// Refines one start with Ceres (Levenberg–Marquardt, central differences); returns Σ residual²/2. Throws
/// Cancelled when the progress callback asks to stop.
double refine(const GrainModel& model, const OrthoscopeFitOptions& options, std::array<double, kSlots>& parameters, ProgressRelay& relay) {
    auto* cost = new ceres::DynamicNumericDiffCostFunction<ColourCost, ceres::CENTRAL>(new ColourCost{&model});
    cost->AddParameterBlock(kSlots);
    cost->SetNumResiduals(static_cast<int>(model.residual_count()));
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, parameters.data());
    const std::array<bool, kSlots> free = free_slots(model, options);
    std::vector<int> fixed;
    for (int j = 0; j < kSlots; ++j) {
        if (!free[static_cast<std::size_t>(j)]) fixed.push_back(j);
    }
    problem.SetManifold(parameters.data(), new ceres::SubsetManifold(kSlots, fixed));
    problem.SetParameterLowerBound(parameters.data(), kThickness, options.thickness_min_um);
    problem.SetParameterUpperBound(parameters.data(), kThickness, options.thickness_max_um);
    problem.SetParameterLowerBound(parameters.data(), kExposure, 0.05);
    problem.SetParameterUpperBound(parameters.data(), kExposure, 20.0);
    for (int c = 0; c < 3; ++c) {
        problem.SetParameterLowerBound(parameters.data(), kGain0 + c, 0.2);
        problem.SetParameterUpperBound(parameters.data(), kGain0 + c, 5.0);
    }
    problem.SetParameterLowerBound(parameters.data(), kContrast, 0.5);
    problem.SetParameterUpperBound(parameters.data(), kContrast, 2.0);
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = 100;
    solver.function_tolerance = 1e-12;
    solver.parameter_tolerance = 1e-10;
    solver.logging_type = detail::solver_logging();
    CancelBetweenIterations cancel(relay);
    solver.callbacks.push_back(&cancel);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    relay.stop_if_cancelled();
    return summary.final_cost;
}

/// Central differences of `f` (parameters → values, `rows` of them) with respect to the free slots,
/// rows × free.size(), steps of 1e-5 relative (at least 1e-5).
template <typename Function>
Eigen::MatrixXd central_differences(const Function& f, Eigen::Index rows, const std::array<double, kSlots>& at, const std::vector<int>& free) {
    Eigen::MatrixXd result(rows, static_cast<Eigen::Index>(free.size()));
    for (std::size_t a = 0; a < free.size(); ++a) {
        const auto slot = static_cast<std::size_t>(free[a]);
        const double h = 1e-5 * std::max(std::abs(at[slot]), 1.0);
        std::array<double, kSlots> up = at, down = at;
        up[slot] += h;
        down[slot] -= h;
        result.col(static_cast<Eigen::Index>(a)) = (f(up) - f(down)) / (2.0 * h);
    }
    return result;
}

/// The residuals at the parameters, as a vector.
Eigen::VectorXd residual_vector(const GrainModel& model, ResponseCache& cache, const std::array<double, kSlots>& at) {
    Eigen::VectorXd residual(static_cast<Eigen::Index>(model.residual_count()));
    model.residuals(cache.at(at.data()), at.data(), residual.data());
    return residual;
}

/// The retardation (nm) and birefringence at 550 nm of the parameters (a dynamic vector: GCC 12 warns,
/// wrongly, of AVX-512 loads past a fixed-size 2-vector in the differences).
Eigen::VectorXd derived(const GrainModel& model, const std::array<double, kSlots>& at) {
    const double birefringence = normal_incidence_birefringence(model.mineral(), model.axes(at.data() + kAngle0), kReferenceNm);
    Eigen::VectorXd values(2);
    values << at[kThickness] * birefringence * 1e3, birefringence;
    return values;
}

/// 1σ of the free parameters and the derived values from the Gauss–Newton covariance s²(JᵀJ)⁺, with
/// s² the residual variance (floored at one code level); directions of JᵀJ with relative eigenvalues
/// below 1e-10 are the photo's blind spots: parameters with a large share in them are not determined.
void uncertainties(const GrainModel& model, const OrthoscopeFitOptions& options, const std::array<double, kSlots>& best,
                   OrthoscopeFitResult& result) {
    const std::array<bool, kSlots> free_flags = free_slots(model, options);
    std::vector<int> free;
    for (int j = 0; j < kSlots; ++j) {
        if (free_flags[static_cast<std::size_t>(j)]) free.push_back(j);
    }
    ResponseCache cache(model);
    const Eigen::VectorXd residual = residual_vector(model, cache, best);
    const Eigen::MatrixXd j = central_differences([&](const auto& at) { return residual_vector(model, cache, at); }, residual.size(), best, free);
    const auto m = static_cast<double>(j.rows()), p = static_cast<double>(j.cols());
    const double variance = m > p ? std::max(residual.squaredNorm() / (m - p), kCodeFloor * kCodeFloor) : kCodeFloor * kCodeFloor;
    const Eigen::MatrixXd normal = j.transpose() * j;
    const Eigen::VectorXd scale = normal.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scale.asDiagonal() * normal * scale.asDiagonal());
    const double largest = eigen.eigenvalues().maxCoeff();
    Eigen::VectorXd inverse_eigen = Eigen::VectorXd::Zero(j.cols());
    std::vector<bool> blind(free.size(), false);
    for (Eigen::Index e = 0; e < j.cols(); ++e) {
        if (eigen.eigenvalues()[e] > 1e-10 * largest) {
            inverse_eigen[e] = 1.0 / eigen.eigenvalues()[e];
            continue;
        }
        for (Eigen::Index a = 0; a < j.cols(); ++a) {
            if (std::abs(eigen.eigenvectors()(a, e)) > 0.2) blind[static_cast<std::size_t>(a)] = true;
        }
    }
    const Eigen::MatrixXd covariance =
        variance * scale.asDiagonal() * eigen.eigenvectors() * inverse_eigen.asDiagonal() * eigen.eigenvectors().transpose() * scale.asDiagonal();

    const auto assign = [&](FittedValue& fitted, int slot, double limit) {
        fitted.value = best[static_cast<std::size_t>(slot)];
        const auto position = std::find(free.begin(), free.end(), slot);
        fitted.free = position != free.end();
        if (!fitted.free) return;
        const auto a = position - free.begin();
        const double sigma = std::sqrt(std::max(covariance(a, a), 0.0));
        fitted.identifiable = !blind[static_cast<std::size_t>(a)] && sigma <= limit;
        if (fitted.identifiable) fitted.sigma = sigma;
    };
    assign(result.thickness_um, kThickness, 0.25 * best[kThickness]);
    for (int a = 0; a < 3; ++a) assign(result.angles_deg[static_cast<std::size_t>(a)], kAngle0 + a, 30.0);
    assign(result.exposure, kExposure, 0.5 * best[kExposure]);
    if (result.calibration) assign(result.calibration->contrast, kContrast, 0.5);

    // Derived values: σ² = gᵀCg with g their gradient in the free parameters.
    const Eigen::VectorXd centre = derived(model, best);
    const Eigen::MatrixXd gradient = central_differences([&](const auto& at) { return derived(model, at); }, 2, best, free);
    const Eigen::Matrix2d derived_covariance = gradient * covariance * gradient.transpose();
    // The birefringence is a fitted value only when the orientation out of the section's plane is free.
    const bool orientation_fixed = options.orientation != GrainOrientation::free;
    result.retardation_nm = {centre[0], std::sqrt(std::max(derived_covariance(0, 0), 0.0)), true, true};
    result.birefringence = {centre[1], orientation_fixed ? std::nullopt : std::optional<double>(std::sqrt(std::max(derived_covariance(1, 1), 0.0))),
                            !orientation_fixed, true};
    if (result.retardation_nm.sigma && *result.retardation_nm.sigma > 0.25 * std::abs(centre[0])) {
        result.retardation_nm.identifiable = false;
        result.retardation_nm.sigma.reset();
    }
}

/// The camera found with the grain at the parameters: its gains at the reference's light, its contrast, and
/// the references' model colours and residual.
CameraCalibration calibration_at(const GrainModel& model, const std::array<double, kSlots>& parameters) {
    std::array<double, kSlots> at_reference = parameters;
    at_reference[kExposure] = 1.0;
    const Camera camera = model.camera(at_reference.data());
    const detail::ReferenceColours& references = model.references();
    CameraCalibration calibration;
    calibration.channel_gains = camera.gains;
    calibration.contrast.value = camera.contrast;
    for (std::size_t c = 0; c < 3; ++c) calibration.fitted_with_grain[c] = !references.lit[c];
    calibration.model_code.resize(model.photo_count());
    double squares = 0.0;
    for (std::size_t r = 0; r < references.photos.size(); ++r) {
        const Eigen::Vector3d code = detail::camera_code(camera.gains.cwiseProduct(references.model_linear[r]), camera.contrast);
        squares += (code - references.measured_code[r]).squaredNorm();
        calibration.model_code[references.photos[r]] = code;
    }
    calibration.rms_code = std::sqrt(squares / (3.0 * static_cast<double>(references.photos.size())));
    return calibration;
}

/// The global search, then Ceres from its best starting points; the best parameters to `best`, every refined
/// minimum to result.candidates (best first).
void search_and_refine(const GrainModel& model, const OrthoscopeFitOptions& options, ProgressRelay& relay, std::array<double, kSlots>& best,
                         OrthoscopeFitResult& result) {
    const std::vector<GridPoint> starts =
        starting_points(global_search(model, options, relay), std::max(options.candidates, 1), thickness_step_um(model, options), options.orientation);
    double best_cost = std::numeric_limits<double>::infinity();
    for (const GridPoint& start : starts) {
        std::array<double, kSlots> parameters = initial_parameters(model, options, start.thickness_um, start.angles_deg);
        const double cost = refine(model, options, parameters, relay);
        relay.report(0.5 + 0.5 * static_cast<double>(result.candidates.size() + 1) / static_cast<double>(starts.size()));
        result.candidates.push_back({parameters[kThickness], {parameters[kAngle0], parameters[kAngle0 + 1], parameters[kAngle0 + 2]},
                                     model.colour_rms(parameters.data())});
        if (cost < best_cost) {
            best_cost = cost;
            best = parameters;
        }
    }
    std::sort(result.candidates.begin(), result.candidates.end(), [](const GrainCandidate& a, const GrainCandidate& b) { return a.rms_code < b.rms_code; });
    // Angles shown in their principal range: the indicatrix repeats every 180° about the microscope axis.
    if (options.orientation == GrainOrientation::max_birefringence) best[kAngle0] -= 180.0 * std::floor(best[kAngle0] / 180.0);
}

/// Photos with a plate in which the fitted grain (its responses `grain`, seen by `camera`) shows within 8 code
/// levels of the plate's own colour: the grain is near extinction there, and the photo tells nothing of its
/// retardation or of slow and fast.
std::vector<std::string> plate_photos_at_extinction(const GrainModel& model, const std::vector<GrainResponse>& grain, const Camera& camera,
                                                    const OrthoscopeFitResult& result) {
    std::vector<double> spectrum;
    std::vector<std::string> labels;
    for (std::size_t k = 0; k < model.photo_count(); ++k) {
        if (!model.photo(k).plate) continue;
        const Eigen::Vector3d plate_only = model.code(grain[k], 0.0, camera, spectrum);
        if ((result.model_code[k] - plate_only).cwiseAbs().maxCoeff() < 8.0 / 255.0) {
            labels.push_back(model.photo(k).label.empty() ? "photo " + std::to_string(k + 1) : model.photo(k).label);
        }
    }
    return labels;
}

/// What the user should know of a finished fit: assumptions, a calibration that does not hold, a rival thickness.
void add_warnings(const std::vector<GrainPhoto>& photos, const OrthoscopeFitOptions& options, OrthoscopeFitResult& result) {
    if (options.orientation == GrainOrientation::max_birefringence) {
        result.warnings.push_back("the thickness assumes the grain shows its highest interference colour (the section contains its fastest and "
                                  "slowest directions); cut otherwise, the grain is thicker than this");
        const bool plate = std::any_of(photos.begin(), photos.end(), [](const GrainPhoto& photo) { return photo.plate.has_value(); });
        if (!plate) result.warnings.push_back("without a photo with an accessory plate the slow and fast directions cannot be told apart (angle +-90 deg)");
    }
    if (result.calibration && result.calibration->rms_code > kAcceptableRmsCode) {
        result.warnings.push_back("the reference region's colours do not follow the calibrated camera (" +
                                  format_significant(255.0 * result.calibration->rms_code, 3) +
                                  " code levels rms): is it isotropic, or at extinction, in every photo that gives it?");
    }
    if (!result.thickness_um.identifiable) {
        result.warnings.push_back("the photos do not determine the thickness (with the orientation free only the retardation t*dn is "
                                  "measured); give the orientation (its Euler angles) or choose a grain of maximum birefringence");
    }
    if (result.thickness_um.identifiable && result.candidates.size() > 1 && result.candidates[1].rms_code < 1.5 * result.candidates[0].rms_code &&
        std::abs(result.candidates[1].thickness_um - result.candidates[0].thickness_um) > 0.05 * result.candidates[0].thickness_um) {
        result.warnings.push_back("another thickness, " + format_significant(result.candidates[1].thickness_um, 4) +
                                  " um, fits almost as well; add photos (another stage angle, the gypsum plate) to tell them apart");
    }
}

}  // namespace

double normal_incidence_birefringence(const Mineral& mineral, const Eigen::Matrix3d& axes, double wavelength_nm) {
    const Eigen::Vector3d n = mineral.principal_n(wavelength_nm);
    const Eigen::Matrix3d eta = axes * n.cwiseAbs2().cwiseInverse().asDiagonal() * axes.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> section(eta.topLeftCorner<2, 2>());
    return 1.0 / std::sqrt(section.eigenvalues()[0]) - 1.0 / std::sqrt(section.eigenvalues()[1]);
}

std::string_view grain_orientation_name(GrainOrientation orientation) {
    switch (orientation) {
        case GrainOrientation::known: return "known";
        case GrainOrientation::max_birefringence: return "max-birefringence";
        case GrainOrientation::free: return "free";
    }
    return "known";
}

GrainOrientation parse_grain_orientation(std::string_view name) {
    for (const GrainOrientation o : {GrainOrientation::known, GrainOrientation::max_birefringence, GrainOrientation::free}) {
        if (name == grain_orientation_name(o)) return o;
    }
    throw InputError("unknown grain orientation " + quote_input(name) + " (expected known, max-birefringence or free)");
}

Image rectangle_mask(int width_px, int height_px, int x0, int y0, int width, int height) {
    if (width <= 0 || height <= 0 || x0 < 0 || y0 < 0 || x0 + width > width_px || y0 + height > height_px) {
        throw InputError("region " + std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(width) + "," + std::to_string(height) +
                         " is empty or leaves the " + std::to_string(width_px) + "x" + std::to_string(height_px) + " photo");
    }
    Image mask(width_px, height_px, 1);
    for (int y = y0; y < y0 + height; ++y) {
        for (int x = x0; x < x0 + width; ++x) mask.at(x, y, 0) = 1.0f;
    }
    return mask;
}

GrainColour grain_colour(const Image& photo, const Image& mask, double saturated_level) {
    if (photo.channels < 3) {
        throw InputError("a grayscale photo (" + std::to_string(photo.channels) + " channel); interference colours need a colour photo");
    }
    if (mask.width != photo.width || mask.height != photo.height) {
        throw InputError("the mask is " + std::to_string(mask.width) + "x" + std::to_string(mask.height) + ", the photo " +
                         std::to_string(photo.width) + "x" + std::to_string(photo.height));
    }
    GrainColour colour;
    // A photo saved from a grey image has R = G = B everywhere; one of an extinct grain may too, but is dark.
    bool colour_seen = false, bright_seen = false;
    for (int y = 0; y < photo.height; ++y) {
        for (int x = 0; x < photo.width; ++x) {
            const Eigen::Vector3d value(photo.at(x, y, 0), photo.at(x, y, 1), photo.at(x, y, 2));
            colour_seen = colour_seen || value.x() != value.y() || value.y() != value.z();
            bright_seen = bright_seen || value.maxCoeff() > kDarkCode;
            if (mask.at(x, y, 0) == 0.0f) continue;
            if (value.maxCoeff() >= saturated_level) {
                ++colour.saturated;
                continue;
            }
            colour.mean_code += value;
            ++colour.pixels;
        }
    }
    if (colour.pixels == 0) {
        throw InputError(colour.saturated > 0 ? "every pixel of the grain's region is saturated (a channel at " + format_significant(saturated_level, 4) + " or above)"
                                               : std::string("the mask or region selects no pixel"));
    }
    colour.grey = !colour_seen && bright_seen;
    colour.mean_code /= static_cast<double>(colour.pixels);
    return colour;
}

OrthoscopeFitResult fit_orthoscope_grain(const std::vector<GrainPhoto>& photos, const Mineral& mineral, const OrthoscopeFitOptions& options,
                                         const SpectralIntegrator& integrator, const ProgressCallback& progress) {
    if (photos.empty()) throw InputError("no photo to fit");
    if (!(options.thickness_min_um > 0.0 && options.thickness_min_um < options.thickness_max_um && std::isfinite(options.thickness_max_um))) {
        throw InputError("the thickness range must be 0 < min < max (got " + format_significant(options.thickness_min_um, 6) + " to " +
                         format_significant(options.thickness_max_um, 6) + " um)");
    }
    if (options.microscope.wavelengths_nm.size() != integrator.weights().size()) {
        throw InputError("internal: the fit's wavelengths and the colour integrator's differ");
    }
    if (std::all_of(photos.begin(), photos.end(), [](const GrainPhoto& photo) { return photo.colour.grey; })) {
        std::string names;
        for (const GrainPhoto& photo : photos) names += (names.empty() ? "" : ", ") + (photo.label.empty() ? std::string("(unnamed)") : photo.label);
        throw InputError("grayscale photo" + std::string(photos.size() == 1 ? " " : "s ") + names +
                         " (R = G = B in every pixel): interference colours need a colour photo (a photo with the gypsum "
                         "plate gives a first-order grey grain colour)");
    }
    if (mineral.optical_class == OpticalClass::isotropic) throw InputError(mineral.name + " is isotropic: it stays dark between crossed polars");
    const GrainModel model(photos, mineral, options, integrator);
    ProgressRelay relay(progress);
    OrthoscopeFitResult result;
    std::array<double, kSlots> best{};
    search_and_refine(model, options, relay, best, result);
    if (model.calibrated()) result.calibration = calibration_at(model, best);
    uncertainties(model, options, best, result);
    result.axes = model.axes(best.data() + kAngle0);
    const std::vector<GrainResponse> grain = model.responses(result.axes);
    const Camera camera = model.camera(best.data());
    std::vector<double> spectrum;
    for (std::size_t k = 0; k < photos.size(); ++k) result.model_code.push_back(model.code(grain[k], best[kThickness], camera, spectrum));
    result.rms_code = model.colour_rms(grain, best.data());
    result.acceptable = std::isfinite(result.rms_code) && result.rms_code <= kAcceptableRmsCode;
    result.verdict = result.acceptable
                         ? "the model matches the grain's colours to " + format_significant(255.0 * result.rms_code, 3) + " code levels rms"
                         : "no acceptable fit: the colour residual is " + format_significant(255.0 * result.rms_code, 3) +
                               " code levels rms (at most " + format_significant(255.0 * kAcceptableRmsCode, 3) + " accepted); is it " + mineral.name + "?";
    if (options.orientation == GrainOrientation::free && result.retardation_nm.identifiable) {
        result.thickness_lower_bound_um = std::abs(result.retardation_nm.value) / (model.maximum_birefringence() * 1e3);
    }
    add_warnings(photos, options, result);
    for (const std::string& label : plate_photos_at_extinction(model, grain, camera, result)) {
        result.warnings.push_back(label + ": the grain is near extinction in this photo, which shows the plate's own colour and says nothing of the "
                                          "grain; take the photo with the plate at the grain's 45-degree position (brightest, 45 degrees from extinction)");
    }
    return result;
}

}  // namespace petroscope
