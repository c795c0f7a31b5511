#include "conoscope_evaluator.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace petroscope::detail {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Eigen::Vector2d unit_at(double angle_deg) { return {std::cos(angle_deg * kDegree), std::sin(angle_deg * kDegree)}; }

std::vector<BinormalFrame> frames_for(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n) {
    const Eigen::Matrix3d axes = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    std::vector<BinormalFrame> frames;
    for (const double wavelength_nm : settings.wavelengths_nm) {
        const Indicatrix indicatrix{principal_n(wavelength_nm), axes};
        if (!indicatrix.principal_n.allFinite() || indicatrix.principal_n.minCoeff() < 1.0) {
            std::ostringstream what;
            what << "the crystal's principal indices at " << wavelength_nm << " nm are not finite numbers >= 1";
            throw InputError(what.str());
        }
        frames.emplace_back(indicatrix);
    }
    return frames;
}

std::vector<double> k0_thickness_for(const ConoscopeSettings& settings) {
    std::vector<double> values;
    for (const double wavelength_nm : settings.wavelengths_nm) {
        values.push_back(2.0 * std::numbers::pi * settings.thickness_um * 1e3 / wavelength_nm);
    }
    return values;
}

}  // namespace

ConoscopeEvaluator::ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n)
    : settings_(settings),
      polars_{unit_at(settings.polarizer_deg), unit_at(settings.analyzer_deg), settings.analyzer_in},
      frames_(frames_for(settings, principal_n)),
      k0_thickness_(k0_thickness_for(settings)),
      crystal_(frames_, std::vector<double>(frames_.size(), settings.surround_n), k0_thickness_) {}

void ConoscopeEvaluator::transmission_pair(const Eigen::Vector2d& xi, KernelScratch& scratch, double* out_plus,
                                           double* out_minus) const {
    scratch.resize(crystal_.padded_size());
    if (!transmission_pair_kernel(crystal_, polars_, xi, scratch, out_plus, out_minus)) return;
    for (std::size_t w = 0; w < frames_.size(); ++w) {
        if (scratch.failed[w] == 0) continue;
        const std::array<double, 2> reference = reference_pair(w, xi);
        out_plus[w] = reference[0];
        out_minus[w] = reference[1];
    }
}

std::array<double, 2> ConoscopeEvaluator::reference_pair(std::size_t w, const Eigen::Vector2d& xi) const {
    const std::array<TangentialWavevector, 2> directions{TangentialWavevector::from_xi(xi), TangentialWavevector::from_xi(-xi)};
    const Eigen::Vector2d no_guess = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    std::array<std::array<SlabMode, 2>, 2> forward;
    std::array<double, 2> result{0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
        // No propagating mode on some sheet: no power crosses the slab.
        if (!solve_forward_modes(frames_[w], directions[side].xi, no_guess, forward[side])) return result;
    }
    for (int side = 0; side < 2; ++side) {
        SlabModes modes;
        modes.forward = forward[side];
        for (int sheet = 0; sheet < 2; ++sheet) modes.backward[sheet] = time_reversed(forward[1 - side][sheet]);
        const SlabTransfer transfer = slab_transfer(modes, directions[side], settings_.surround_n, settings_.surround_n);
        result[side] = analyzed_intensity(transfer, directions[side], k0_thickness_[w]);
    }
    return result;
}

double ConoscopeEvaluator::analyzed_intensity(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                              double k0_thickness) const {
    // An aplanatic condenser and objective keep the s and p amplitudes of each ray (Born & Wolf §8.8,
    // Richards & Wolf 1959): the polarizer's field P splits as (P·ŝ, P·ρ̂) in the (s, p) basis.
    const Eigen::Vector2d incident(polars_.polarizer.dot(direction.azimuthal), polars_.polarizer.dot(direction.radial));
    // Mode amplitudes are real for a lossless crystal between lossless media below the critical angle, so
    // each output amplitude is Σₘ cₘ·exp(iφₘ) with real cₘ, and |c₀e^{iφ₀} + c₁e^{iφ₁}|² =
    // (c₀ − c₁)² + 4c₀c₁cos²(δ/2) = (c₀ + c₁)² − 4c₀c₁sin²(δ/2), δ = φ₀ − φ₁; the form whose terms are both
    // non-negative is used, so rounding never makes an intensity negative.
    const Eigen::Vector2d mode_amplitudes = transfer.entry * incident;
    const double half_phase_sine = std::sin(0.5 * k0_thickness * (transfer.q[0] - transfer.q[1]));
    const double sin2 = half_phase_sine * half_phase_sine;
    const auto intensity = [&](const Eigen::Vector2d& c) {
        const double product = c[0] * c[1];
        return product >= 0.0 ? (c[0] - c[1]) * (c[0] - c[1]) + 4.0 * product * (1.0 - sin2)
                              : (c[0] + c[1]) * (c[0] + c[1]) - 4.0 * product * sin2;
    };
    if (polars_.analyzer_in) {
        const Eigen::Vector2d analyzer(polars_.analyzer.dot(direction.azimuthal), polars_.analyzer.dot(direction.radial));
        return intensity((analyzer.transpose() * transfer.exit).transpose().cwiseProduct(mode_amplitudes));
    }
    return intensity(transfer.exit.row(0).transpose().cwiseProduct(mode_amplitudes)) +
           intensity(transfer.exit.row(1).transpose().cwiseProduct(mode_amplitudes));
}

}  // namespace petroscope::detail
