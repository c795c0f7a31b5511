#pragma once
// The vectorised conoscope kernel against its reference path (optics/slab.hpp) for random crystals: the pieces
// that the kernel tests with a plate and with optical activity share.
#include "conoscope_evaluator.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace petroscope::testing {

/// The largest difference between a monochromatic batch of directions through the kernel and the reference path.
inline double batch_difference(const detail::ConoscopeEvaluator& evaluator, const std::vector<Eigen::Vector2d>& xis,
                               detail::KernelScratch& scratch) {
    std::vector<double> plus(xis.size()), minus(xis.size());
    evaluator.monochromatic_pairs(xis, scratch, plus.data(), minus.data());
    double worst = 0.0;
    for (std::size_t k = 0; k < xis.size(); ++k) {
        const std::array<double, 2> reference = evaluator.reference_pair(0, xis[k]);
        worst = std::max({worst, std::abs(plus[k] - reference[0]), std::abs(minus[k] - reference[1])});
    }
    return worst;
}

/// Figure settings for the crystal axes `axes`: NA 0.95, 10 … 32 µm (phases whose rounding stays below 1e-13),
/// random polars nearly crossed, the analyzer out in every fourth case.
inline ConoscopeSettings random_thin_slab(const Eigen::Matrix3d& axes, int crystal_case, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    ConoscopeSettings settings;
    settings.numerical_aperture = 0.95;
    settings.thickness_um = std::pow(10.0, 0.5 * unit(rng) + 1.0);
    settings.polarizer_deg = 360.0 * unit(rng);
    settings.analyzer_deg = settings.polarizer_deg + 90.0 + 20.0 * (unit(rng) - 0.5);
    settings.analyzer_in = crystal_case % 4 != 0;
    settings.crystal_axes = axes;
    return settings;
}

/// The largest differences between the kernel and the reference path.
struct KernelDifferences {
    double white = 0.0;  // white light: five wavelengths, 30 random directions
    double batch = 0.0;  // the same directions in one monochromatic batch at 589.3 nm
};

/// `settings` (its wavelengths replaced) with the indices `principal_n` dispersed by 0.004·(550²/λ² − 1) (λ in nm), at
/// 30 random directions |ξ| ≤ 0.95: at 400, 480, 550, 650 and 750 nm, then in a monochromatic batch at 589.3 nm.
inline KernelDifferences kernel_against_reference(ConoscopeSettings settings, const Eigen::Vector3d& principal_n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    settings.wavelengths_nm = {400.0, 480.0, 550.0, 650.0, 750.0};
    const PrincipalIndexFunction indices = [principal_n](double nm) {
        return Eigen::Vector3d((principal_n.array() + 0.004 * (550.0 * 550.0 / (nm * nm) - 1.0)).matrix());
    };
    KernelDifferences worst;
    const detail::ConoscopeEvaluator spectral(settings, indices);
    detail::SpectralScratch scratch;
    std::vector<double> plus(5), minus(5);
    std::vector<Eigen::Vector2d> xis;
    for (int direction = 0; direction < 30; ++direction) {
        const Eigen::Vector2d xi =
            0.95 * std::sqrt(unit(rng)) * Eigen::Vector2d(std::cos(2.0 * std::numbers::pi * unit(rng)), std::sin(2.0 * std::numbers::pi * unit(rng)));
        xis.push_back(xi);
        spectral.spectral_pair(xi, scratch, false, plus.data(), minus.data());
        for (std::size_t w = 0; w < 5; ++w) {
            const std::array<double, 2> reference = spectral.reference_pair(w, xi);
            worst.white = std::max({worst.white, std::abs(plus[w] - reference[0]), std::abs(minus[w] - reference[1])});
        }
    }
    settings.wavelengths_nm = {589.3};
    const detail::ConoscopeEvaluator monochromatic(settings, indices);
    worst.batch = batch_difference(monochromatic, xis, scratch.every_wavelength);
    return worst;
}

}  // namespace petroscope::testing
