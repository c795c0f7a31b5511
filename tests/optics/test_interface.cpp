// The local interface model against closed forms (Snell, Fresnel, total internal reflection, Brewster),
// uniaxial birefringence, and energy conservation over random media, on and near the optic axes.
#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/optics/interface.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/verification/interface_cases.hpp"
#include "petroscope/verification/interface_suite.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

const InterfaceWave& wave_of(const InterfaceResult& result, InterfaceWave::Kind kind, std::optional<InterfaceMode> mode = std::nullopt) {
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind == kind && (!mode || wave.mode == *mode)) return wave;
    }
    throw std::runtime_error("no such wave");
}

double total_power(const InterfaceResult& result) {
    double total = 0.0;
    for (const InterfaceWave& wave : result.waves) total += wave.power;
    return total;
}


TEST(Interface, CalciteAtNormalIncidenceSplitsIntoOrdinaryAndExtraordinary) {
    const double n_o = 1.6584, n_e = 1.4864;
    // ω = 1.6584, ε = 1.4864 at 589.3 nm; the optic axis (Z) turned 45° from the face normal toward +x.
    const OpticalMedium calcite{Eigen::Vector3cd(n_o, n_o, n_e), euler_zyz_deg(0.0, 45.0, 0.0)};
    InterfaceIncidence unpolarized;
    const InterfaceResult result = solve_interface({0, 0, 1}, unpolarized, OpticalMedium::isotropic(1.0), calcite);
    const InterfaceWave& o = wave_of(result, InterfaceWave::Kind::transmitted, InterfaceMode::ordinary);
    const InterfaceWave& e = wave_of(result, InterfaceWave::Kind::transmitted, InterfaceMode::extraordinary);
    // Both wave normals along the face normal; o with n_o, e with n_e(45°) (Born & Wolf §15.3.3).
    EXPECT_LT((o.direction - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_LT((e.direction - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_NEAR(o.n.real(), n_o, 1e-12);
    const double n_e45 = 1.0 / std::sqrt(0.5 / (n_o * n_o) + 0.5 / (n_e * n_e));
    EXPECT_NEAR(e.n.real(), n_e45, 1e-12);
    // Walk-off of the e ray: tan α = ½ n_e(θ)² sin 2θ (1/n_e² − 1/n_o²) with θ = 45° (Born & Wolf §15.3.3).
    const double walk_off = std::atan(0.5 * n_e45 * n_e45 * (1.0 / (n_e * n_e) - 1.0 / (n_o * n_o)));
    EXPECT_NEAR(std::acos(e.ray_direction.dot(e.direction)), walk_off, 1e-12);
    EXPECT_NEAR(walk_off * 180.0 / std::numbers::pi, 6.2, 0.05);
    EXPECT_LT(o.ray_direction.cross(o.direction).norm(), 1e-12);  // o ray along its wave normal
    // Polarizations: o ⟂ the principal plane (x–z here, containing the normal and the axis), e in it.
    EXPECT_NEAR(std::abs(o.e_field.x()) + std::abs(o.e_field.z()), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(e.e_field.y()), 0.0, 1e-12);
    EXPECT_NEAR(total_power(result), 1.0, 1e-12);
}

// The verification suite (src/verification) at the acceptance sizes of issue 3: Fresnel, Snell and
// coplanarity sweeps, total internal reflection, Brewster, uniaxial laws, R + T = 1 over 10^6 random cases
// and 10^4 on or within 1e-9 rad of optic axes, agreement with the 4×4 solver over 10^4 cases, and
// optically active media over 10^5 cases.
TEST(InterfaceAcceptance, VerificationSuiteAtAcceptanceSizes) {
    InterfaceSuiteSize size;
    size.random_energy_cases = 1000000;
    size.near_axis_cases = 20000;
    size.berreman_cases = 10000;
    size.uniaxial_cases = 5000;
    size.optically_active_cases = 100000;
    for (const VerificationTest& test : run_interface_suite(size)) {
        for (const VerificationCheck& check : test.checks) {
            EXPECT_TRUE(check.passed) << test.name << ": " << check.quantity << " = " << check.measured << " (tolerance " << check.tolerance << ")";
            std::printf("%s: %s = %.3g (tolerance %.0e)\n", test.name.c_str(), check.quantity.c_str(), check.measured, check.tolerance);
        }
    }
}

// The shareable cases of verification/cases, with their analytic expectations (docs/verification.md).
TEST(Interface, EveryVerificationCasePasses) {
    const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    const VerificationReport report = check_case_directory(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "verification" / "cases", catalog);
    EXPECT_GE(report.tests.size(), 40u);
    for (const VerificationTest& test : report.tests) {
        EXPECT_TRUE(test.passed()) << test.name;
        for (const VerificationCheck& check : test.checks) {
            EXPECT_TRUE(check.passed) << test.name << ": " << check.quantity << " measured " << check.measured << " expected " << check.expected;
        }
    }
}

// The renderer's double-precision solve against the long-double one, over random media on either side
// (lossless of every kind, absorbing behind), incidence up to 89.99°, random polarizations and modes, and
// light refracted exactly onto a binormal: every wave's power, Stokes vector, direction and ray agree, and
// the double-precision powers still add up to the incident power. A pair of modes whose indices lie within
// 1e-6 of each other (an optic axis) is compared by its total, its split being arbitrary there (measured:
// 4.3e-11 off the binormals, 5.8e-10 on them; R + T − 1 in double 4.7e-15).
TEST(Interface, DoubleArithmeticAgreesWithLongDouble) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // Worst differences off and on a binormal (where the two modes' roots, polished from a double-precision
    // frame, split by about √ε of double and their fields follow to about that).
    std::array<double, 2> worst_power{}, worst_stokes{};
    double worst_direction = 0.0, worst_energy = 0.0;
    int compared = 0, on_axis = 0;
    for (int i = 0; i < 20000; ++i) {
        const OpticalMedium medium1 = testing::random_medium_of_kind(rng, static_cast<int>(rng() % 3));
        const OpticalMedium medium2 = testing::random_medium_of_kind(rng, static_cast<int>(rng() % 4));
        InterfaceIncidence incidence;
        std::size_t on_binormal = 0;
        const double theta = 89.99 * std::numbers::pi / 180.0 * unit(rng), phi = 2.0 * std::numbers::pi * unit(rng);
        incidence.direction = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
        if (i % 10 == 0 && medium1.is_isotropic() && !medium2.is_isotropic() && medium2.is_lossless()) {
            // Onto a binormal of medium 2 (ξ = n_β b_t, docs/interface.md), when medium 1 allows it.
            const BinormalFrame frame(Indicatrix{medium2.real_n(), medium2.axes});
            const Eigen::Vector3d binormal = frame.binormal_1.z() >= 0.0 ? frame.binormal_1 : Eigen::Vector3d(-frame.binormal_1);
            const Eigen::Vector2d xi = binormal.head<2>() / std::sqrt(frame.b);
            const double n1 = medium1.principal_n[0].real();
            if (binormal.z() >= 0.2 && xi.norm() < 0.99 * n1) {  // not grazing: as the verification suite's cases
                incidence.direction = {xi.x() / n1, xi.y() / n1, std::sqrt(1.0 - xi.squaredNorm() / (n1 * n1))};
                ++on_axis;
                on_binormal = 1;
            }
        }
        if (medium1.is_isotropic()) {
            const Eigen::Vector3d stokes = testing::random_unit_vector(rng) * unit(rng);
            incidence.coherency = coherency_from_stokes({1.0, stokes.x(), stokes.y(), stokes.z()});
            incidence.with_mueller = i % 2 == 0;
        } else {
            incidence.mode = unit(rng) < 0.5 ? InterfaceMode::fast : InterfaceMode::slow;
        }
        const InterfaceResult exact = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        incidence.arithmetic = InterfaceArithmetic::double_precision;
        const InterfaceResult fast = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        ASSERT_EQ(exact.waves.size(), fast.waves.size());
        if (medium1.is_lossless() && medium2.is_lossless()) worst_energy = std::max(worst_energy, std::abs(total_power(fast) - 1.0));
        for (std::size_t w = 0; w < exact.waves.size(); ++w) {
            const InterfaceWave &a = exact.waves[w], &b = fast.waves[w];
            ASSERT_EQ(a.kind, b.kind);
            // The other mode of the same medium, when it is nearly degenerate with this one.
            std::size_t partner = w;
            for (std::size_t other = 0; other < exact.waves.size(); ++other) {
                if (other != w && exact.waves[other].kind == a.kind) partner = other;
            }
            const bool paired = a.mode != InterfaceMode::isotropic && partner != w && std::abs(exact.waves[partner].n - a.n) < 1e-6;
            const double power_a = a.power + (paired ? exact.waves[partner].power : 0.0);
            const double power_b = b.power + (paired ? fast.waves[partner].power : 0.0);
            worst_power[on_binormal] = std::max(worst_power[on_binormal], std::abs(power_a - power_b));
            if (!paired) {  // (on a binormal the rays of the pair are any on the cone of internal conical refraction)
                double& stokes = worst_stokes[on_binormal];
                stokes = std::max(stokes, (a.stokes - b.stokes).cwiseAbs().maxCoeff());
                if (a.mueller) stokes = std::max(stokes, (*a.mueller - *b.mueller).cwiseAbs().maxCoeff());
            }
            if (!a.evanescent && !paired) {
                worst_direction = std::max({worst_direction, (a.direction - b.direction).norm(), (a.ray_direction - b.ray_direction).norm()});
            }
            ++compared;
        }
    }
    std::printf("double against long double over %d waves: power %.2g, Stokes %.2g, direction %.2g; on a binormal (%d cases): "
                "power %.2g, Stokes %.2g; double |R + T - 1| %.2g\n",
                compared, worst_power[0], worst_stokes[0], worst_direction, on_axis, worst_power[1], worst_stokes[1], worst_energy);
    EXPECT_GT(on_axis, 100);
    EXPECT_LT(worst_power[0], 1e-10);
    EXPECT_LT(worst_stokes[0], 1e-10);
    EXPECT_LT(worst_power[1], 2e-9);
    EXPECT_LT(worst_stokes[1], 2e-9);
    EXPECT_LT(worst_direction, 1e-12);
    EXPECT_LT(worst_energy, 1e-13);
}

TEST(Interface, BadInputIsRejected) {
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    EXPECT_THROW(solve_interface({0, 0, 0}, InterfaceIncidence{}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, NAN}, InterfaceIncidence{}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{Eigen::Vector3d(0, 0, -1)}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{Eigen::Vector3d(1, 0, 0)}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, air, OpticalMedium::isotropic(-1.5)), InputError);
    const OpticalMedium calcite{Eigen::Vector3cd(1.6584, 1.6584, 1.4864), Eigen::Matrix3d::Identity()};
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, calcite, air), InputError);  // no incident mode named
}

TEST(Interface, WaveModeNamesRoundTrip) {
    for (const InterfaceMode mode : {InterfaceMode::isotropic, InterfaceMode::fast, InterfaceMode::slow, InterfaceMode::ordinary, InterfaceMode::extraordinary}) {
        EXPECT_EQ(parse_wave_mode(wave_mode_name(mode)), mode) << wave_mode_name(mode);
    }
    EXPECT_EQ(wave_mode_name(InterfaceMode::isotropic), "s+p");
    EXPECT_EQ(parse_wave_mode("total"), std::nullopt);
    EXPECT_EQ(parse_wave_mode(""), std::nullopt);
    // Biaxial medium 1: a mode is required, and the uniaxial names do not apply.
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    const OpticalMedium biaxial{Eigen::Vector3cd(1.5, 1.6, 1.7), Eigen::Matrix3d::Identity()};
    InterfaceIncidence incidence;
    EXPECT_THROW(solve_interface({0, 0, 1}, incidence, biaxial, air), InputError);
    incidence.mode = InterfaceMode::ordinary;
    EXPECT_THROW(solve_interface({0, 0, 1}, incidence, biaxial, air), InputError);
    incidence.mode = InterfaceMode::fast;
    EXPECT_NO_THROW(solve_interface({0, 0, 1}, incidence, biaxial, air));
}

}  // namespace
}  // namespace petroscope
