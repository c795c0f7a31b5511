// The vectorised conoscope kernel against the reference path (optics/slab.hpp, Newton to convergence,
// normalised vibration directions): the same transmission to 1e-10 for random crystals, orientations,
// thicknesses and polarizers, at random directions and within 1e-3 … 1e-12 rad of a binormal; and with
// an accessory plate after the crystal (the complex effective analyzer of conoscope_kernel.hpp).
#include "conoscope_evaluator.hpp"
#include "conoscope_fixtures.hpp"
#include "kernel_against_reference.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

TEST(ConoscopeKernel, MatchesTheReferencePathEverywhere) {
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_random = 0.0, worst_near_binormal = 0.0;
    int samples = 0;
    for (int crystal_case = 0; crystal_case < 300; ++crystal_case) {
        const Indicatrix indicatrix = crystal_case % 3 == 0 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
        ConoscopeSettings settings;
        settings.numerical_aperture = 0.95;
        settings.thickness_um = std::pow(10.0, -1.0 + 4.0 * unit(rng));  // 0.1 µm … 1 mm
        settings.polarizer_deg = 360.0 * unit(rng);
        settings.analyzer_deg = settings.polarizer_deg + 90.0 * std::floor(2.0 * unit(rng)) + 10.0 * unit(rng);
        settings.analyzer_in = crystal_case % 5 != 0;
        settings.crystal_axes = indicatrix.axes;
        // Five wavelengths with a little dispersion of every index.
        settings.wavelengths_nm = {400.0, 480.0, 550.0, 650.0, 750.0};
        const Eigen::Vector3d n_550 = indicatrix.principal_n;
        const PrincipalIndexFunction indices = [&](double nm) {
            return Eigen::Vector3d((n_550.array() + 0.004 * (550.0 * 550.0 / (nm * nm) - 1.0)).matrix());
        };
        const detail::ConoscopeEvaluator evaluator(settings, indices);
        detail::SpectralScratch scratch;
        std::vector<double> plus(5), minus(5);
        const BinormalFrame frame(Indicatrix{indices(550.0), indicatrix.axes});
        for (int direction = 0; direction < 40; ++direction) {
            Eigen::Vector2d xi;
            if (direction < 20) {
                xi = 0.95 * std::sqrt(unit(rng)) * Eigen::Vector2d(std::cos(2 * M_PI * unit(rng)), std::sin(2 * M_PI * unit(rng)));
            } else {
                // Near the binormal's exit at 550 nm: ξ = nβ·(b_x, b_y), nudged by 10^[−12, −3].
                const Eigen::Vector3d b = (direction % 2 == 0 ? frame.binormal_1 : frame.binormal_2) *
                                          ((direction % 2 == 0 ? frame.binormal_1 : frame.binormal_2).z() < 0 ? -1.0 : 1.0);
                const double n_beta = 1.0 / std::sqrt(frame.b);
                const double nudge = direction % 5 == 0 ? 0.0 : std::pow(10.0, -12.0 + 9.0 * unit(rng));
                xi = n_beta * b.head<2>() + nudge * Eigen::Vector2d(std::cos(7.0 * direction), std::sin(7.0 * direction));
                if (xi.norm() > 0.95) continue;
            }
            evaluator.spectral_pair(xi, scratch, false, plus.data(), minus.data());
            for (std::size_t w = 0; w < 5; ++w) {
                const std::array<double, 2> reference = evaluator.reference_pair(w, xi);
                // The phase δ = k₀d(q_fast − q_slow) carries a rounding error of a few ε·k₀d·q, which bounds
                // any two evaluations' agreement; the differences are reported relative to that scale.
                const double k0_thickness = 2.0 * M_PI * settings.thickness_um * 1e3 / settings.wavelengths_nm[w];
                const double phase_rounding = 4.0 * 2.2e-16 * k0_thickness * 2.5;
                const double difference = std::max(std::abs(plus[w] - reference[0]), std::abs(minus[w] - reference[1]));
                double& worst = direction < 20 ? worst_random : worst_near_binormal;
                worst = std::max(worst, difference - phase_rounding);
                ASSERT_TRUE(std::isfinite(plus[w]) && std::isfinite(minus[w]));
                ++samples;
            }
        }
    }
    EXPECT_GT(samples, 30000);
    EXPECT_LT(worst_random, 1e-13);
    // Both paths determine the vibration directions at an angle δ from a binormal only to about ε/δ
    // (docs/theory.md, "Eigenmodes"); the kernel keeps samples down to δ = 1e-6 rad, so the two agree to a few
    // times ε/1e-6 ≈ 2e-10 there, whatever the thickness.
    EXPECT_LT(worst_near_binormal, 1e-9);
    std::printf("kernel vs reference beyond the phase rounding: random directions %.2e, near binormals %.2e, %d samples\n", worst_random,
                worst_near_binormal, samples);
}

TEST(ConoscopeKernel, WarmStartsAlongARowAndMonochromaticBatchesMatchTheReferencePath) {
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_row = 0.0, worst_batch = 0.0;
    for (int crystal_case = 0; crystal_case < 100; ++crystal_case) {
        const Indicatrix indicatrix = testing::random_biaxial(rng);
        ConoscopeSettings settings;
        settings.numerical_aperture = 0.95;
        settings.thickness_um = 30.0;
        settings.polarizer_deg = 360.0 * unit(rng);
        settings.analyzer_deg = settings.polarizer_deg + 90.0;
        settings.crystal_axes = indicatrix.axes;
        const PrincipalIndexFunction indices = [&](double nm) {
            return Eigen::Vector3d((indicatrix.principal_n.array() + 0.004 * (550.0 * 550.0 / (nm * nm) - 1.0)).matrix());
        };
        // A row of pixels at the spacing of a 256-pixel figure, warm-started one from the next.
        settings.wavelengths_nm = {420.0, 470.0, 520.0, 570.0, 620.0, 670.0, 720.0, 770.0, 780.0};
        const detail::ConoscopeEvaluator spectral(settings, indices);
        detail::SpectralScratch scratch;
        std::vector<double> plus(settings.wavelengths_nm.size()), minus(plus.size());
        const double y = 0.9 * (2.0 * unit(rng) - 1.0) * 0.7;
        for (int column = 0; column < 40; ++column) {
            const Eigen::Vector2d xi(-0.6 + 2.0 * 0.95 / 256.0 * column, y);
            spectral.spectral_pair(xi, scratch, column > 0, plus.data(), minus.data());
            for (std::size_t w = 0; w < plus.size(); ++w) {
                const std::array<double, 2> reference = spectral.reference_pair(w, xi);
                worst_row = std::max({worst_row, std::abs(plus[w] - reference[0]), std::abs(minus[w] - reference[1])});
            }
        }
        // Monochromatic: one batch of random directions.
        settings.wavelengths_nm = {589.3};
        const detail::ConoscopeEvaluator monochromatic(settings, indices);
        std::vector<Eigen::Vector2d> xis;
        for (int k = 0; k < 100; ++k) {
            xis.push_back(0.95 * std::sqrt(unit(rng)) * Eigen::Vector2d(std::cos(2 * M_PI * unit(rng)), std::sin(2 * M_PI * unit(rng))));
        }
        worst_batch = std::max(worst_batch, testing::batch_difference(monochromatic, xis, scratch.every_wavelength));
    }
    // 30 µm: k₀d ≤ 4.5e2, so the phase rounding is below 1e-12.
    EXPECT_LT(worst_row, 1e-12);
    EXPECT_LT(worst_batch, 1e-12);
    std::printf("kernel vs reference: warm-started rows %.2e, monochromatic batches %.2e\n", worst_row, worst_batch);
}

TEST(ConoscopeKernel, WithAPlateMatchesTheReferencePath) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const MineralCatalog& minerals = testing::repository_minerals();
    const std::array<std::pair<PlateKind, const char*>, 3> plates{{{PlateKind::gypsum, "gypsum"}, {PlateKind::mica, "muscovite"}, {PlateKind::wedge, "quartz"}}};
    double worst_spectral = 0.0, worst_batch = 0.0;
    for (int crystal_case = 0; crystal_case < 60; ++crystal_case) {
        const Indicatrix indicatrix = crystal_case % 3 == 0 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
        const auto& [kind, plate_mineral] = plates[static_cast<std::size_t>(crystal_case) % plates.size()];
        ConoscopeSettings settings = testing::random_thin_slab(indicatrix.axes, crystal_case, rng);
        settings.plate = make_accessory_plate(kind, minerals.find(plate_mineral), 180.0 * unit(rng), unit(rng));
        const testing::KernelDifferences difference = testing::kernel_against_reference(settings, indicatrix.principal_n, rng);
        worst_spectral = std::max(worst_spectral, difference.white);
        worst_batch = std::max(worst_batch, difference.batch);
    }
    EXPECT_LT(worst_spectral, 1e-12);
    EXPECT_LT(worst_batch, 1e-12);
    std::printf("kernel vs reference with a plate: white %.2e, monochromatic batches %.2e\n", worst_spectral, worst_batch);
}

}  // namespace
}  // namespace petroscope
