// Natural optical activity: the rotation of the plane of polarization along the optic axis, the exact 4×4
// modes of a gyrotropic crystal against the closed form of the uniaxial crystal, the coupled-mode slab against
// those exact modes, energy conservation at active interfaces, and the inactive limit.
#include "petroscope/optics/berreman.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/slab.hpp"

#include "support/random_crystals.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

namespace petroscope {
namespace {

using Complex = std::complex<double>;

// Quartz at 589.3 nm, optic axis along z: indices (Ghosh 1999) and rotatory powers along and across the axis
// (21.72 °/mm, Lowry 1912; −0.5 times that across it, the mineral record's assumption).
constexpr double kWavelengthNm = 589.3;
constexpr double kNo = 1.54425, kNe = 1.55336;
constexpr double kDegPerMmToRadPerUm = std::numbers::pi / 180.0 * 1e-3;
const double kRhoAxis = 21.72 * kDegPerMmToRadPerUm;
const double kRhoNormal = -0.5 * kRhoAxis;

Eigen::Matrix3d quartz_gyration(Handedness handedness, const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity()) {
    return gyration_tensor(Eigen::Vector3d(kRhoNormal, kRhoNormal, kRhoAxis), axes, kWavelengthNm, handedness);
}

Eigen::Matrix3cd quartz_epsilon() { return Eigen::Vector3cd(kNo * kNo, kNo * kNo, kNe * kNe).asDiagonal(); }

BinormalFrame quartz_frame() { return BinormalFrame(Indicatrix{{kNo, kNo, kNe}, Eigen::Matrix3d::Identity()}); }

Eigen::Matrix3cd isotropic(double n) { return Complex(n * n) * Eigen::Matrix3cd::Identity(); }

// The slab's Jones matrix with optical activity, in a surround of index n, for the tangential wavevector ξ.
Eigen::Matrix2cd active_slab_jones(const Eigen::Vector2d& xi, const Eigen::Matrix3d& gyration, double n_surround, double thickness_um) {
    const TangentialWavevector direction = TangentialWavevector::from_xi(xi);
    const SlabModes modes = solve_slab_modes(quartz_frame(), direction, Eigen::Vector2d::Constant(NAN));
    SlabTransfer transfer = slab_transfer(modes, direction, n_surround, n_surround);
    transfer.gyration_coupling = gyration_coupling(modes.forward, xi, gyration);
    return slab_jones(transfer, kWavelengthNm, thickness_um);
}

TEST(OpticalActivity, AlongTheAxisRightQuartzTurnsThePlaneClockwiseForTheObserverByRhoTimesD) {
    // docs/conventions.md: right-handed (dextrorotatory) quartz turns the plane clockwise for an observer looking
    // toward the source, i.e. from N toward E (negative azimuths); left-handed quartz the other way. 1 mm at
    // 589.3 nm: 21.72°. The surround has the ordinary index, so both faces transmit everything.
    const double thickness_um = 1000.0;
    for (const Handedness handedness : {Handedness::right, Handedness::left}) {
        const Eigen::Matrix2cd jones = active_slab_jones(Eigen::Vector2d::Zero(), quartz_gyration(handedness), kNo, thickness_um);
        // At ξ = 0, ρ̂ = x̂ and ŝ = ŷ: (s, p) = (E_y, E_x). The input vibrates E–W.
        const Eigen::Vector2cd out = jones * Eigen::Vector2cd(0.0, 1.0);
        const Complex ratio = out[0] / out[1];  // E_y / E_x
        const double azimuth = std::atan(ratio.real());
        const double expected = (handedness == Handedness::right ? -1.0 : 1.0) * kRhoAxis * thickness_um;
        EXPECT_NEAR(azimuth, expected, 1e-6 * std::abs(expected)) << handedness_name(handedness);
        EXPECT_NEAR(ratio.imag(), 0.0, 1e-9) << "the light leaves linearly polarized";
        EXPECT_NEAR(out.squaredNorm(), 1.0, 1e-12) << "index-matched faces transmit everything";
    }
}

TEST(OpticalActivity, OnTheAxisTheExactModesAreCircularAndSplitByTheRotatoryPower) {
    // Exact along the axis of the bianisotropic form (gyration.hpp): q = √(n_o² + κ²) ± κ with κ = g₃₃/2, and
    // E ∝ (1, ±i, 0).
    const Eigen::Matrix3d gyration = quartz_gyration(Handedness::right);
    const auto modes = berreman_modes(quartz_epsilon(), chirality_tensor(gyration), Eigen::Vector2d::Zero());
    const double kappa = 0.5 * gyration(2, 2);
    const double mean = std::sqrt(kNo * kNo + kappa * kappa);
    EXPECT_NEAR(modes[0].q.real(), mean - kappa, 1e-14);
    EXPECT_NEAR(modes[1].q.real(), mean + kappa, 1e-14);
    for (int m = 0; m < 2; ++m) {
        const Eigen::Vector3cd& e = modes[m].e_field;
        const double circularity = 2.0 * std::imag(std::conj(e.x()) * e.y()) / (std::norm(e.x()) + std::norm(e.y()));
        EXPECT_NEAR(std::abs(circularity), 1.0, 1e-12) << "mode " << m;
        EXPECT_NEAR(std::abs(e.z()), 0.0, 1e-14);
    }
    // Right quartz: the faster mode (index n_o − κ) is the one whose field turns clockwise for the observer.
    const Eigen::Vector3cd& fast = modes[0].e_field;
    EXPECT_LT(std::imag(std::conj(fast.x()) * fast.y()), 0.0);
}

// Landau's plane-wave equation for the wave normal ŝ and index n: M·E = 0 with
// M = n²(ŝŝᵀ − I) + ε + i·n·[(g·ŝ)×].
Eigen::Matrix3cd landau_matrix(const Eigen::Vector3d& s_hat, double n, const Eigen::Matrix3d& gyration) {
    const Eigen::Vector3d g = gyration * s_hat;
    Eigen::Matrix3d cross;
    cross << 0.0, -g.z(), g.y(), g.z(), 0.0, -g.x(), -g.y(), g.x(), 0.0;
    return (n * n * (s_hat * s_hat.transpose() - Eigen::Matrix3d::Identity())).cast<Complex>() + quartz_epsilon() +
           Complex(0.0, n) * cross.cast<Complex>();
}

// The closed form of the uniaxial gyrotropic crystal (ε = diag(o, o, e), g = diag(g₁, g₁, g₃), θ from the axis):
// det M = (n² − o)(n²P − oe) − n²G + n⁴S = 0 with P = o sin²θ + e cos²θ, G = e g₃² cos²θ + o g₁² sin²θ and
// S = sin²θ cos²θ (g₃ − g₁)² (worked out from Landau & Lifshitz vol. 8 §101 with G = g·N; docs/theory.md §9).
// Divided by P it is (1 + S/P)u² − (o + u_e + G/P)u + o·u_e = 0 for u = n², u_e = oe/P the extraordinary index²;
// its discriminant is written with u_e − o = o(e − o)sin²θ/P so that no difference of nearly equal numbers
// appears near the axis, where the two roots differ by only ~g.
std::array<double, 2> closed_form_indices(double theta, double g1, double g3) {
    const double o = kNo * kNo, e = kNe * kNe, s2 = std::pow(std::sin(theta), 2), c2 = std::pow(std::cos(theta), 2);
    const double p = o * s2 + e * c2, g = (e * g3 * g3 * c2 + o * g1 * g1 * s2) / p, s = s2 * c2 * (g3 - g1) * (g3 - g1) / p;
    const double u_e = o * e / p, split = o * (e - o) * s2 / p;  // u_e − o
    const double discriminant = split * split + 2.0 * (o + u_e) * g + g * g - 4.0 * s * o * u_e;
    const double sum = o + u_e + g, root = std::sqrt(discriminant);
    return {std::sqrt((sum - root) / (2.0 * (1.0 + s))), std::sqrt((sum + root) / (2.0 * (1.0 + s)))};
}

// The ellipticity of a field's vibration ⟂ ŝ: S₃/S₀ of its components along two unit vectors ⟂ ŝ.
double ellipticity(const Eigen::Vector3cd& e, const Eigen::Vector3d& s_hat) {
    const Eigen::Vector3d first = (std::abs(s_hat.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX()).cross(s_hat).normalized();
    const Eigen::Vector3d second = s_hat.cross(first);
    const Complex a = first.cast<Complex>().dot(e), b = second.cast<Complex>().dot(e);  // dot conjugates its first argument: real vectors
    return 2.0 * std::imag(std::conj(a) * b) / (std::norm(a) + std::norm(b));
}

TEST(OpticalActivity, ExactModesMatchTheClosedFormOfTheUniaxialGyrotropicCrystal) {
    // For each 4×4 forward mode at ξ (from the axis out to 0.9): its index n = |N| and direction θ satisfy the
    // closed form, and its field is the null vector of Landau's M (the ellipticity with it) — to 1e-10.
    const Eigen::Matrix3d gyration = quartz_gyration(Handedness::right);
    const Eigen::Matrix3d kappa = chirality_tensor(gyration);
    double worst_index = 0.0, worst_field = 0.0, worst_ellipticity = 0.0;
    for (double radius : {0.0, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 0.6, 0.9}) {
        for (double azimuth : {0.0, 0.7, 2.0}) {
            const Eigen::Vector2d xi = radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
            const auto modes = berreman_modes(quartz_epsilon(), kappa, xi);
            for (int m = 0; m < 2; ++m) {
                const Eigen::Vector3d normal(xi.x(), xi.y(), modes[m].q.real());
                const double n = normal.norm();
                const Eigen::Vector3d s_hat = normal / n;
                const auto indices = closed_form_indices(std::acos(s_hat.z()), gyration(0, 0), gyration(2, 2));
                const double closed_n = std::abs(indices[0] - n) < std::abs(indices[1] - n) ? indices[0] : indices[1];
                worst_index = std::max(worst_index, std::abs(closed_n - n) / n);
                // The null vector of M(n): the bilinear cross product of two of its rows, the pair giving the longest.
                const Eigen::Matrix3cd landau = landau_matrix(s_hat, closed_n, gyration);
                Eigen::Vector3cd null = Eigen::Vector3cd::Zero();
                for (const auto& [i, j] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
                    // Eigen's cross of complex vectors is conjugated (Eigen/src/Geometry/OrthoMethods.h); undo it.
                    const Eigen::Vector3cd candidate = landau.row(i).transpose().cross(Eigen::Vector3cd(landau.row(j).transpose())).conjugate();
                    if (candidate.norm() > null.norm()) null = candidate;
                }
                const Eigen::Vector3cd& e = modes[m].e_field;
                worst_field = std::max(worst_field, 1.0 - std::abs(null.dot(e)) / (null.norm() * e.norm()));
                worst_ellipticity = std::max(worst_ellipticity, std::abs(ellipticity(null, s_hat) - ellipticity(e, s_hat)));
            }
        }
    }
    std::printf("gyrotropic modes vs closed form: index %.1e, field %.1e, ellipticity %.1e\n", worst_index, worst_field, worst_ellipticity);
    EXPECT_LT(worst_index, 1e-10);
    EXPECT_LT(worst_field, 1e-10);
    EXPECT_LT(worst_ellipticity, 1e-10);
}

TEST(OpticalActivity, CoupledModesOfTheSlabAgreeWithTheExactModes) {
    // The slab's coupled-mode generator Q (slab.hpp) has eigenvalues q̄ ± √(Δ² + c₀c₁); they are the exact 4×4
    // forward q up to second order in the coupling: κ²/(2n) ≈ 4e-10 with κ = g₃₃/2 ≈ 3.6e-5 (the coupling to the
    // backward waves, 2n away, and the q-dependence of g·N), near the axis and far from it. Bound: 1e-9.
    const Eigen::Matrix3d gyration = quartz_gyration(Handedness::right);
    double worst = 0.0;
    for (double radius : {0.0, 1e-4, 1e-3, 3e-3, 1e-2, 0.1, 0.5, 0.9}) {
        const Eigen::Vector2d xi = radius * Eigen::Vector2d(std::cos(0.4), std::sin(0.4));
        const TangentialWavevector direction = TangentialWavevector::from_xi(xi);
        const SlabModes linear = solve_slab_modes(quartz_frame(), direction, Eigen::Vector2d::Constant(NAN));
        const Eigen::Vector2d c = gyration_coupling(linear.forward, xi, gyration);
        const double mean = 0.5 * (linear.forward[0].q + linear.forward[1].q);
        const double half = 0.5 * (linear.forward[0].q - linear.forward[1].q);
        const double split = std::sqrt(half * half + c[0] * c[1]);
        const auto exact = berreman_modes(quartz_epsilon(), chirality_tensor(gyration), xi);
        worst = std::max({worst, std::abs(mean - split - exact[0].q.real()), std::abs(mean + split - exact[1].q.real())});
    }
    std::printf("coupled-mode q vs exact: %.1e\n", worst);
    EXPECT_LT(worst, 1e-9);
}

TEST(OpticalActivity, InterfacesWithAnActiveMediumConserveEnergy) {
    // Glass | quartz (random orientation, handedness and thickness up to 100 µm) | glass: R + T = 1 at both active
    // interfaces. (At 2 mm the propagation phase k₀d·q ≈ 2e4 rad adds rounding: 2e-12.)
    std::mt19937_64 rng(1919);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    double worst = 0.0;
    for (int i = 0; i < 200; ++i) {
        const Eigen::Matrix3d axes = testing::random_rotation(rng);
        const Eigen::Matrix3cd epsilon = (axes * Eigen::Vector3d(kNo * kNo, kNo * kNo, kNe * kNe).asDiagonal() * axes.transpose()).cast<Complex>();
        const Eigen::Matrix3d kappa = chirality_tensor(quartz_gyration(i % 2 == 0 ? Handedness::right : Handedness::left, axes));
        const double n_glass = 1.4 + 0.2 * unit(rng);
        const double radius = 0.95 * std::min(n_glass, kNo) * std::sqrt(unit(rng));
        const Eigen::Vector2d xi = radius * Eigen::Vector2d(std::cos(6.0 * unit(rng)), std::sin(6.0 * unit(rng))).normalized();
        const auto glass = berreman_modes(isotropic(n_glass), xi);
        const Eigen::Vector4cd incident = Complex(normal(rng), normal(rng)) * glass[0].psi + Complex(normal(rng), normal(rng)) * glass[1].psi;
        const StackResponse response = solve_stack(isotropic(n_glass), {StackLayer{epsilon, 100.0 * unit(rng), kappa}},
                                                   isotropic(n_glass), kWavelengthNm, xi, incident);
        const double sum = response.reflected_power[0] + response.reflected_power[1] + response.transmitted_power[0] +
                           response.transmitted_power[1];
        worst = std::max(worst, std::abs(sum - 1.0));
    }
    std::printf("active stacks: worst |R + T - 1| = %.1e\n", worst);
    EXPECT_LT(worst, 1e-12);
}

TEST(OpticalActivity, AVanishingChiralityReproducesTheInactiveModes) {
    // The chiral Δ (the 6×6 elimination of berreman.cpp, complex Schur form) with κ = 1e-30 against the
    // inactive closed-form Δ (real Schur form), for random biaxial crystals and directions: the same q to
    // 1e-13, and the same fields to within rounding over the separation of the pair's q (a mode's field
    // moves by about the perturbation over the distance to the nearest other root: Davis & Kahan, SIAM J.
    // Numer. Anal. 7, 1 (1970); Golub & Van Loan §7.2.4), with rounding ≈ 50 ε ‖Δ‖ ≈ 3e-14.
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_q = 0.0, worst_field_times_gap = 0.0;
    for (int i = 0; i < 300; ++i) {
        const Indicatrix indicatrix = testing::random_biaxial(rng);
        const Eigen::Matrix3d axes = indicatrix.axes;
        const Eigen::Matrix3cd epsilon =
            (axes * indicatrix.principal_n.array().square().matrix().asDiagonal() * axes.transpose()).cast<Complex>();
        const double radius = 0.95 * indicatrix.principal_n.minCoeff() * std::sqrt(unit(rng));
        const double azimuth = 6.28 * unit(rng);
        const Eigen::Vector2d xi = radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
        const auto plain = berreman_modes(epsilon, xi);
        const auto chiral = berreman_modes(epsilon, 1e-30 * Eigen::Matrix3d::Identity(), xi);
        for (int m = 0; m < 4; ++m) {
            const int sibling = m ^ 1;  // the other mode of the same direction (forward 0, 1; backward 2, 3)
            const double gap = std::abs(plain[m].q - plain[sibling].q);
            worst_q = std::max(worst_q, std::abs(plain[m].q - chiral[m].q));
            worst_field_times_gap = std::max(worst_field_times_gap, (plain[m].psi - chiral[m].psi).norm() * gap);
        }
    }
    std::printf("vanishing chirality: worst |dq| = %.1e, worst |dpsi| x gap = %.1e\n", worst_q, worst_field_times_gap);
    EXPECT_LT(worst_q, 1e-13);
    EXPECT_LT(worst_field_times_gap, 3e-14);
}

TEST(OpticalActivity, HandednessNamesParseAndUnknownOnesAreRefused) {
    EXPECT_EQ(parse_handedness("right"), Handedness::right);
    EXPECT_EQ(parse_handedness("left"), Handedness::left);
    try {
        parse_handedness("sideways");
        FAIL() << "expected an error";
    } catch (const std::exception& error) {
        EXPECT_NE(std::string(error.what()).find("expected right or left"), std::string::npos) << error.what();
    }
}

TEST(OpticalActivity, TheLeftFormIsTheMirrorImage) {
    const Eigen::Matrix3d axes = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
    const Eigen::Matrix3d right = quartz_gyration(Handedness::right, axes), left = quartz_gyration(Handedness::left, axes);
    EXPECT_TRUE((right + left).isZero(1e-20));
    // g_ss = λρ(ŝ)/π along each principal axis.
    EXPECT_NEAR(axes.col(2).dot(right * axes.col(2)), kWavelengthNm * 1e-3 * kRhoAxis / std::numbers::pi, 1e-18);
}

}  // namespace
}  // namespace petroscope
