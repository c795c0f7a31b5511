// The interface model with optically active media: the limit of a vanishing gyration, the double-precision
// solve against the long-double one, and the input it refuses. The closed forms along the axis, R + T = 1 and
// the comparison with the 4×4 solver are the verification suite's "optically-active" test and its quartz
// cases (`petroscope verify`, Cli.VerifyPassesEveryTestAndReportsJson; Interface.EveryVerificationCasePasses).
#include "petroscope/core/error.hpp"
#include "petroscope/optics/interface.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

namespace petroscope {
namespace {

using Kind = InterfaceWave::Kind;

// Quartz's gyration along its axis at 589.3 nm, g₃₃ = λρ/π with ρ = 21.72°/mm.
constexpr double kQuartzGyration = 0.5893 * 21.72e-3 / 180.0;

// A random symmetric matrix whose entries lie within ±scale.
Eigen::Matrix3d random_symmetric(std::mt19937_64& rng, double scale) {
    std::uniform_real_distribution<double> entry(-scale, scale);
    Eigen::Matrix3d g;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j <= i; ++j) g(i, j) = g(j, i) = entry(rng);
    }
    return g;
}

// A random incidence up to `max_deg` from the normal z: a random partial polarization from a medium with s
// and p waves, otherwise one of its modes.
InterfaceIncidence random_incidence(std::mt19937_64& rng, const OpticalMedium& medium1, double max_deg) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    InterfaceIncidence incidence;
    const double theta = max_deg * std::numbers::pi / 180.0 * unit(rng), phi = 2.0 * std::numbers::pi * unit(rng);
    incidence.direction = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    if (medium1.has_s_and_p_waves()) {
        const Eigen::Vector3d stokes = testing::random_unit_vector(rng) * unit(rng);
        incidence.coherency = coherency_from_stokes({1.0, stokes.x(), stokes.y(), stokes.z()});
    } else {
        incidence.mode = unit(rng) < 0.5 ? InterfaceMode::fast : InterfaceMode::slow;
    }
    return incidence;
}

std::vector<const InterfaceWave*> waves_of(const InterfaceResult& result, Kind kind) {
    std::vector<const InterfaceWave*> waves;
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind == kind) waves.push_back(&wave);
    }
    std::sort(waves.begin(), waves.end(), [](const InterfaceWave* a, const InterfaceWave* b) { return a->n.real() < b->n.real(); });
    return waves;
}

double power_of(const std::vector<const InterfaceWave*>& waves) {
    double total = 0.0;
    for (const InterfaceWave* wave : waves) total += wave->power;
    return total;
}

// Two solutions wave by wave, per side: the total power, and for two distinct modes (indices ≥ 1e-6 apart)
// each one's power, index, direction and ray; a pair nearer than that splits its power arbitrarily, and an
// inactive isotropic medium's one s+p wave faces two circular waves.
struct Differences {
    double total_power = 0.0, mode_power = 0.0, geometry = 0.0;
    int distinct_modes = 0;
    void add(const InterfaceResult& a, const InterfaceResult& b) {
        for (const Kind kind : {Kind::reflected, Kind::transmitted}) {
            const auto waves_a = waves_of(a, kind), waves_b = waves_of(b, kind);
            total_power = std::max(total_power, std::abs(power_of(waves_a) - power_of(waves_b)));
            if (waves_a.size() != 2 || waves_b.size() != 2 || std::abs(waves_a[1]->n - waves_a[0]->n) < 1e-6) continue;
            for (std::size_t m = 0; m < 2; ++m) {
                const InterfaceWave &x = *waves_a[m], &y = *waves_b[m];
                mode_power = std::max(mode_power, std::abs(x.power - y.power));
                if (x.evanescent) continue;
                geometry = std::max({geometry, std::abs(x.n - y.n), (x.direction - y.direction).norm(), (x.ray_direction - y.ray_direction).norm()});
                ++distinct_modes;
            }
        }
    }
};

// A tiny gyration sends a medium down the active path (the quartic with the gyration term, H = N × E + iκE)
// instead of the Biot–Fresnel sheets or the closed-form s and p waves. Its two waves are then split by about
// the gyration only, the hardest case for that path: an inactive isotropic medium's s+p wave becomes two
// circular waves whose roots nearly coincide, and a random symmetric gyration vanishes on a cone of directions
// where the two waves cross. Two roots of the quartic closer than about √ε cannot be told apart, so where
// the waves are split by 1e-13 to 1e-9 (relative) R + T = 1 holds to that floor only: measured 5e-11 at a
// gyration of 1e-13, 3.5e-10 at 1e-9 (both in total reflection, where the two evanescent waves nearly
// coincide), below 1e-15 at 1e-5 (a seventh of quartz's). At 1e-13 the waves are the inactive ones (measured:
// side totals 5e-11, powers of modes ≥ 1e-6 apart 8e-10, index, direction and ray 7e-15).
TEST(InterfaceActivity, AVanishingGyrationGivesTheInactiveWaves) {
    for (const double scale : {1e-13, 1e-9, 1e-5}) {
        std::mt19937_64 rng(23);
        Differences differences;
        double worst_energy = 0.0;
        for (int i = 0; i < 3000; ++i) {
            const bool active_first = i % 2 == 1;
            const OpticalMedium medium1 = testing::random_medium_of_kind(rng, active_first ? 1 + static_cast<int>(rng() % 2) : 0);
            const OpticalMedium medium2 = testing::random_medium_of_kind(rng, static_cast<int>(rng() % 3));
            OpticalMedium barely1 = medium1, barely2 = medium2;
            (active_first ? barely1 : barely2).gyration = random_symmetric(rng, scale);
            const InterfaceIncidence incidence = random_incidence(rng, medium1, 80.0);
            const InterfaceResult active = solve_interface({0, 0, 1}, incidence, barely1, barely2);
            worst_energy = std::max(worst_energy, std::abs(power_of(waves_of(active, Kind::reflected)) + power_of(waves_of(active, Kind::transmitted)) - 1.0));
            differences.add(solve_interface({0, 0, 1}, incidence, medium1, medium2), active);
        }
        std::printf("gyration %.0e: |R + T - 1| %.2g; against none: side totals %.2g, mode power %.2g, index/direction/ray %.2g over "
                    "%d distinct modes\n",
                    scale, worst_energy, differences.total_power, differences.mode_power, differences.geometry, differences.distinct_modes);
        EXPECT_LT(worst_energy, scale < 1e-6 ? 1e-9 : 1e-12) << scale;
        if (scale > 1e-13) continue;
        EXPECT_GT(differences.distinct_modes, 3000);
        EXPECT_LT(differences.total_power, 1e-9);
        EXPECT_LT(differences.mode_power, 1e-8);
        EXPECT_LT(differences.geometry, 1e-12);
    }
}

// The renderer's double-precision solve against the long-double one, active media on one side or both with
// gyrations from once to 100 times quartz's, incidence up to 85° (measured: side totals 3e-12, powers of modes
// ≥ 1e-6 apart 2e-10, index, direction and ray 1e-14; R + T − 1 in double 3e-15).
TEST(InterfaceActivity, DoubleArithmeticAgreesWithLongDouble) {
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Differences differences;
    double worst_energy = 0.0;
    for (int i = 0; i < 3000; ++i) {
        OpticalMedium medium1 = testing::random_medium_of_kind(rng, static_cast<int>(rng() % 3));
        OpticalMedium medium2 = testing::random_medium_of_kind(rng, static_cast<int>(rng() % 3));
        const double scale = kQuartzGyration * std::pow(100.0, unit(rng));
        if (i % 3 != 1) medium2.gyration = random_symmetric(rng, scale);
        if (i % 3 != 0) medium1.gyration = random_symmetric(rng, scale);
        InterfaceIncidence incidence = random_incidence(rng, medium1, 85.0);
        const InterfaceResult exact = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        incidence.arithmetic = InterfaceArithmetic::double_precision;
        const InterfaceResult fast = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        differences.add(exact, fast);
        worst_energy = std::max(worst_energy, std::abs(power_of(waves_of(fast, Kind::reflected)) + power_of(waves_of(fast, Kind::transmitted)) - 1.0));
    }
    std::printf("active media, double against long double: total power %.2g, mode power %.2g, index/direction/ray %.2g over %d "
                "distinct modes; double |R + T - 1| %.2g\n",
                differences.total_power, differences.mode_power, differences.geometry, differences.distinct_modes, worst_energy);
    EXPECT_GT(differences.distinct_modes, 6000);
    EXPECT_LT(differences.total_power, 1e-10);
    EXPECT_LT(differences.mode_power, 1e-9);
    EXPECT_LT(differences.geometry, 1e-12);
    EXPECT_LT(worst_energy, 1e-13);
}

TEST(InterfaceActivity, BadInputIsRejected) {
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    OpticalMedium quartz{Eigen::Vector3cd(1.5443, 1.5443, 1.5534)};
    quartz.gyration = Eigen::Vector3d(-kQuartzGyration / 2, -kQuartzGyration / 2, kQuartzGyration).asDiagonal();
    // Not symmetric, or not finite.
    OpticalMedium bad = quartz;
    bad.gyration(0, 1) = 1e-5;
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, air, bad), InputError);
    bad.gyration(1, 0) = bad.gyration(0, 1) = NAN;
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, air, bad), InputError);
    // An active medium 1 needs one of its elliptical waves, fast or slow: none, or an axis name, is refused.
    InterfaceIncidence incidence;
    EXPECT_THROW(solve_interface({0, 0, 1}, incidence, quartz, air), InputError);
    incidence.mode = InterfaceMode::ordinary;
    try {
        solve_interface({0, 0, 1}, incidence, quartz, air);
        ADD_FAILURE() << "an ordinary wave of active quartz was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("optically active"), std::string::npos) << e.what();
    }
    incidence.mode = InterfaceMode::slow;
    EXPECT_NO_THROW(solve_interface({0, 0, 1}, incidence, quartz, air));
    // An active isotropic medium has no s and p waves either.
    OpticalMedium chlorate = OpticalMedium::isotropic(1.515);
    chlorate.gyration = 2e-5 * Eigen::Matrix3d::Identity();
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, chlorate, air), InputError);
    EXPECT_NO_THROW(solve_interface({0, 0, 1}, incidence, chlorate, air));
}

}  // namespace
}  // namespace petroscope
