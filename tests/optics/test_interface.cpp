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

#include <cmath>
#include <cstdio>
#include <numbers>

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
// and 10^4 on or within 1e-9 rad of optic axes, and agreement with the 4×4 solver over 10^4 cases.
TEST(InterfaceAcceptance, VerificationSuiteAtAcceptanceSizes) {
    InterfaceSuiteSize size;
    size.random_energy_cases = 1000000;
    size.near_axis_cases = 20000;
    size.berreman_cases = 10000;
    size.uniaxial_cases = 5000;
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
