// Berreman 4×4 solver: its modes against Maxwell's equations, its stacks against closed forms (Fresnel, Airy,
// total internal reflection, wave plates), energy conservation and Poynting's theorem in absorbing layers.
#include "petroscope/optics/berreman.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr Complex kI(0.0, 1.0);

Eigen::Matrix3cd isotropic(Complex n) { return (n * n) * Eigen::Matrix3cd::Identity(); }

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
}

Eigen::Matrix3d rotation_z(double angle) {
    return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// ε = R·diag(ñ²)·Rᵀ with complex principal indices ñ = n + iκ (real symmetric and positive when κ = 0).
Eigen::Matrix3cd principal_epsilon(const Eigen::Vector3cd& indices, const Eigen::Matrix3d& axes) {
    const Eigen::Matrix3cd r = axes.cast<Complex>();
    return r * indices.cwiseProduct(indices).asDiagonal() * r.transpose();
}

struct RandomMedium {
    Eigen::Matrix3cd epsilon;
    double n_min = 0.0;
};

// Indices 1.3–2.5 (biaxial, uniaxial or isotropic), random orientation, absorption index up to `kappa_max`.
RandomMedium random_medium(std::mt19937_64& rng, double kappa_max = 0.0) {
    std::uniform_real_distribution<double> index(1.3, 2.5), unit(0.0, 1.0);
    Eigen::Vector3d n(index(rng), index(rng), index(rng));
    const auto kind = rng() % 6;
    if (kind == 0) n.setConstant(n.x());  // isotropic
    if (kind == 1) n.y() = n.x();         // uniaxial
    Eigen::Vector3cd indices = n.cast<Complex>();
    for (int i = 0; i < 3; ++i) indices[i] += kI * kappa_max * unit(rng);
    return {principal_epsilon(indices, random_rotation(rng)), n.minCoeff()};
}

Eigen::Vector2d random_xi(std::mt19937_64& rng, double radius_max) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double radius = radius_max * std::sqrt(unit(rng));
    const double azimuth = 2.0 * kPi * unit(rng);
    return radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
}

// a × b without conjugation (Eigen's cross() conjugates complex results, OrthoMethods.h).
Eigen::Vector3cd cross(const Eigen::Vector3cd& a, const Eigen::Vector3cd& b) {
    return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

// S_z = ½ Re(ψ₁ψ₂* + ψ₃ψ₄*) (Berreman, J. Opt. Soc. Am. 62, 502 (1972); docs/theory.md §3).
double flux(const Eigen::Vector4cd& psi) {
    return 0.5 * (psi[0] * std::conj(psi[1]) + psi[2] * std::conj(psi[3])).real();
}

double total(const std::array<double, 2>& powers) { return powers[0] + powers[1]; }

Eigen::Vector4cd transmitted_psi(const StackResponse& response) {
    return response.transmitted_amplitudes[0] * response.transmitted_modes[0].psi +
           response.transmitted_amplitudes[1] * response.transmitted_modes[1].psi;
}

Eigen::Vector3cd transmitted_e(const StackResponse& response) {
    return response.transmitted_amplitudes[0] * response.transmitted_modes[0].e_field +
           response.transmitted_amplitudes[1] * response.transmitted_modes[1].e_field;
}

// Fresnel amplitudes at an isotropic interface in terms of q = n cos θ (Born & Wolf, Principles of Optics,
// §1.5.2, eqs. 20–21; docs/theory.md §3). r_p is Born & Wolf's; berreman.hpp's p basis keeps the transverse
// part of E along +ρ̂ for both the incident and the reflected wave, which reverses the sign of r_p.
struct Fresnel {
    Complex r_s, t_s, r_p, t_p;
};
Fresnel fresnel(Complex n1, Complex n2, Complex q1, Complex q2) {
    return {(q1 - q2) / (q1 + q2), 2.0 * q1 / (q1 + q2), (n2 * n2 * q1 - n1 * n1 * q2) / (n2 * n2 * q1 + n1 * n1 * q2),
            2.0 * n1 * n2 * q1 / (n2 * n2 * q1 + n1 * n1 * q2)};
}

// The forward root of q² = n² − ξ², decaying toward +z (or positive when real).
Complex forward_q(Complex n, double xi) {
    Complex q = std::sqrt(n * n - xi * xi);
    if (q.imag() < 0.0 || (q.imag() == 0.0 && q.real() < 0.0)) q = -q;
    return q;
}

TEST(BerremanModes, AreMaxwellPlaneWavesClassifiedAndOrdered) {
    // Each mode must satisfy H = N × E and N × H = −εE with N = (ξ, q) (Maxwell's curl equations for a plane
    // wave, H in units of √(ε₀/μ₀)); ψ must hold (E_x, H_y, E_y, −H_x); forward waves carry energy toward +z
    // (lossless, propagating) or decay toward +z; each pair is ordered by increasing |Re q|.
    std::mt19937_64 rng(2001);
    double worst_maxwell = 0.0, worst_psi = 0.0;
    for (int i = 0; i < 5000; ++i) {
        const bool absorbing = i % 2 == 1;
        const RandomMedium medium = random_medium(rng, absorbing ? 0.3 : 0.0);
        const Eigen::Vector2d xi = random_xi(rng, 1.2 * medium.n_min);  // some evanescent waves too
        const auto modes = berreman_modes(medium.epsilon, xi);
        for (int m = 0; m < 4; ++m) {
            const BerremanMode& mode = modes[m];
            const Eigen::Vector3cd n_vector(xi.x(), xi.y(), mode.q);
            ASSERT_GT(mode.e_field.norm(), 0.1);
            const double scale = mode.e_field.norm() * (1.0 + n_vector.norm() * n_vector.norm());
            worst_maxwell = std::max(worst_maxwell, (mode.h_field - cross(n_vector, mode.e_field)).norm() / scale);
            worst_maxwell =
                std::max(worst_maxwell, (cross(n_vector, mode.h_field) + medium.epsilon * mode.e_field).norm() / scale);
            const Eigen::Vector4cd psi(mode.e_field.x(), mode.h_field.y(), mode.e_field.y(), -mode.h_field.x());
            worst_psi = std::max(worst_psi, (psi - mode.psi).norm());
            EXPECT_EQ(mode.forward, m < 2);
            if (mode.evanescent) {
                EXPECT_FALSE(absorbing);
                EXPECT_EQ(mode.flux_z, 0.0);
            } else {
                EXPECT_NEAR(mode.flux_z, flux(mode.psi), 1e-15);
            }
            if (absorbing || mode.evanescent) {
                EXPECT_EQ(mode.q.imag() > 0.0, mode.forward);
            } else {
                EXPECT_EQ(mode.q.imag(), 0.0);  // snapped: exactly real in lossless media
                EXPECT_EQ(mode.flux_z > 0.0, mode.forward);
            }
        }
        for (int pair = 0; pair < 4; pair += 2) {
            EXPECT_LE(std::abs(modes[pair].q.real()),
                      std::abs(modes[pair + 1].q.real()) + 1e-8 * (1.0 + std::abs(modes[pair].q)));
        }
    }
    std::printf("Berreman modes: Maxwell residual %.2e, psi %.2e\n", worst_maxwell, worst_psi);
    EXPECT_LT(worst_maxwell, 1e-12);
    EXPECT_LT(worst_psi, 1e-15);
}

TEST(BerremanModes, BothWaysAgreeWithEachDirectionSolvedAlone) {
    // berreman_modes_both_ways takes the waves of −ξ from the decomposition of ξ (inversion symmetry): they must be
    // the waves berreman_modes finds for −ξ, classified and ordered alike, for lossless and absorbing media and for
    // ξ beyond the smallest index (evanescent waves).
    std::mt19937_64 rng(2027);
    double worst_q = 0.0, worst_field = 0.0, worst_flux = 0.0;
    for (int i = 0; i < 3000; ++i) {
        const RandomMedium medium = random_medium(rng, i % 2 == 1 ? 0.3 : 0.0);
        const Eigen::Vector2d xi = random_xi(rng, 1.2 * medium.n_min);
        const auto both_ways = berreman_modes_both_ways(medium.epsilon, xi);
        for (int direction = 0; direction < 2; ++direction) {
            const auto alone = berreman_modes(medium.epsilon, direction == 0 ? xi : Eigen::Vector2d(-xi));
            for (int m = 0; m < 4; ++m) {
                const BerremanMode &a = alone[m], &b = both_ways[direction][m];
                ASSERT_EQ(a.forward, b.forward);
                ASSERT_EQ(a.evanescent, b.evanescent);
                worst_q = std::max(worst_q, std::abs(a.q - b.q) / (1.0 + std::abs(a.q)));
                // The same unit E up to a phase: |⟨a, b⟩| = 1.
                worst_field = std::max(worst_field, 1.0 - std::abs(a.e_field.dot(b.e_field)) / (a.e_field.norm() * b.e_field.norm()));
                worst_flux = std::max(worst_flux, std::abs(a.flux_z - b.flux_z));
            }
        }
    }
    std::printf("Berreman modes both ways: q %.2e, field 1 - |<a, b>| %.2e, flux %.2e\n", worst_q, worst_field, worst_flux);
    EXPECT_LT(worst_q, 1e-13);
    EXPECT_LT(worst_field, 1e-12);
    EXPECT_LT(worst_flux, 1e-13);
}

TEST(BerremanModes, IsotropicMediaGiveClosedFormSAndPModes) {
    // s: E = ŝ = ẑ × ρ̂; p: E = (q ρ̂ − |ξ| ẑ)/n (unit, transverse part along +ρ̂, docs/conventions.md); ρ̂ = x̂ at
    // normal incidence, where p is E along x̂ and ψ_p = (1, n, 0, 0).
    const double n = 1.5;
    const auto normal = berreman_modes(isotropic(n), Eigen::Vector2d::Zero());
    EXPECT_LT((normal[0].psi - Eigen::Vector4cd(0.0, 0.0, 1.0, n)).norm(), 1e-15);
    EXPECT_LT((normal[1].psi - Eigen::Vector4cd(1.0, n, 0.0, 0.0)).norm(), 1e-15);
    EXPECT_LT((normal[2].psi - Eigen::Vector4cd(0.0, 0.0, 1.0, -n)).norm(), 1e-15);
    EXPECT_LT((normal[3].psi - Eigen::Vector4cd(1.0, -n, 0.0, 0.0)).norm(), 1e-15);
    const double phi = 2.0, xi = 0.9;
    const Eigen::Vector3cd rho(std::cos(phi), std::sin(phi), 0.0), s_hat(-std::sin(phi), std::cos(phi), 0.0);
    const auto modes = berreman_modes(isotropic(n), xi * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    const double q = std::sqrt(n * n - xi * xi);
    EXPECT_LT((modes[0].e_field - s_hat).norm(), 1e-15);
    EXPECT_LT((modes[1].e_field - (q * rho - xi * Eigen::Vector3cd::UnitZ()) / n).norm(), 1e-15);
    EXPECT_LT((modes[3].e_field - (q * rho + xi * Eigen::Vector3cd::UnitZ()) / n).norm(), 1e-15);
    EXPECT_NEAR(modes[0].flux_z, 0.5 * q, 1e-15);  // ½ Re(E × H*)_z = ½ n cos θ for a unit E
    EXPECT_NEAR(modes[1].flux_z, 0.5 * q, 1e-15);
}

TEST(BerremanModes, ExactDegeneracyOnAnOpticAxisGivesFiniteFluxOrthogonalModes) {
    // Wave normal along the optic axis (uniaxial, axis ∥ z, ξ = 0) or a binormal (biaxial, binormal turned onto z;
    // or a randomly oriented biaxial crystal with ξ chosen so that N = n_β·b̂ lies on a binormal b̂; degenerate to
    // rounding): any vibration direction is a mode. The degenerate pair must be finite, satisfy Maxwell's equations, be
    // [s-like (E·ρ̂ = 0), p-like], share q = n_β b̂_z, and carry no cross flux, so that powers add.
    const double n_alpha = 1.5, n_beta = 1.6, n_gamma = 1.7;
    const double v = std::atan(std::sqrt((1.0 / (n_alpha * n_alpha) - 1.0 / (n_beta * n_beta)) /
                                         (1.0 / (n_beta * n_beta) - 1.0 / (n_gamma * n_gamma))));  // docs/theory.md §1; Born & Wolf §15.3.3
    const Eigen::Vector3cd biaxial(n_alpha, n_beta, n_gamma);
    struct Case {
        Eigen::Matrix3cd epsilon;
        Eigen::Vector2d xi;
        double q;
    };
    std::vector<Case> cases{
        {principal_epsilon(Eigen::Vector3cd(1.55, 1.55, 1.65), Eigen::Matrix3d::Identity()), Eigen::Vector2d::Zero(),
         1.55},
        {principal_epsilon(biaxial,
                           Eigen::AngleAxisd(-v, Eigen::Vector3d::UnitY()).toRotationMatrix()),  // binormal → z
         Eigen::Vector2d::Zero(), n_beta}};
    std::mt19937_64 rng(2006);
    for (int i = 0; i < 20; ++i) {
        const Eigen::Matrix3d axes = random_rotation(rng);
        Eigen::Vector3d binormal = axes * Eigen::Vector3d(std::sin(v), 0.0, std::cos(v));
        if (binormal.z() < 0.0) binormal = -binormal;
        if (binormal.z() < 0.3) continue;  // keep q well away from grazing
        cases.push_back({principal_epsilon(biaxial, axes), n_beta * binormal.head<2>(), n_beta * binormal.z()});
    }
    for (const Case& c : cases) {
        const auto modes = berreman_modes(c.epsilon, c.xi);
        const Eigen::Vector3cd rho = c.xi.norm() > 0.0
                                         ? Eigen::Vector3cd(c.xi.x() / c.xi.norm(), c.xi.y() / c.xi.norm(), 0.0)
                                         : Eigen::Vector3cd::UnitX();
        // Only the forward pair lies on the binormal when ξ ≠ 0 (the backward wave normal (ξ, −q) does not).
        for (int pair = 0; pair < (c.xi.norm() > 0.0 ? 2 : 4); pair += 2) {
            const BerremanMode& s = modes[pair];
            const BerremanMode& p = modes[pair + 1];
            for (const BerremanMode& mode : {s, p}) {
                ASSERT_TRUE(mode.psi.allFinite());
                const Eigen::Vector3cd n_vector(c.xi.x(), c.xi.y(), mode.q);
                EXPECT_LT((cross(n_vector, mode.h_field) + c.epsilon * mode.e_field).norm(), 1e-12);
                EXPECT_NEAR(std::abs(mode.q), c.q, 1e-12);
            }
            EXPECT_EQ(s.q, p.q);
            EXPECT_LT(std::abs(s.e_field.dot(rho)), 1e-12);
            const double cross_flux = flux(s.psi + p.psi) - flux(s.psi) - flux(p.psi);
            EXPECT_LT(std::abs(cross_flux), 1e-14);
        }
    }
}

TEST(BerremanStack, IsotropicInterfaceMatchesFresnel) {
    // n₁ → n₂, 0–89.9° below the critical angle, ξ along varying azimuths: r and t equal the Fresnel amplitudes
    // (with the p-sign convention above), R = |r|², T = (n₂cos θ₂)/(n₁cos θ₁)|t|² (Born & Wolf §1.5.3; docs/theory.md §3).
    double worst_amplitude = 0.0, worst_power = 0.0;
    const std::array<std::pair<double, double>, 3> pairs{{{1.0, 1.5}, {1.5, 1.0}, {1.0, 2.4}}};
    for (const auto& [n1, n2] : pairs) {
        for (int step = 0; step <= 899; ++step) {
            const double theta = step * 0.1 * kPi / 180.0;
            const double xi = n1 * std::sin(theta);
            if (xi >= n2) continue;  // total internal reflection: next test
            const double phi = 0.37 * step;
            const Eigen::Vector2d xi_vector = xi * Eigen::Vector2d(std::cos(phi), std::sin(phi));
            const auto modes = berreman_modes(isotropic(n1), xi_vector);
            const Complex q1 = n1 * std::cos(theta), q2 = forward_q(n2, xi);
            const Fresnel f = fresnel(n1, n2, q1, q2);
            for (int polarization = 0; polarization < 2; ++polarization) {  // 0: s, 1: p
                const StackResponse response =
                    solve_stack(isotropic(n1), {}, isotropic(n2), 550.0, xi_vector, modes[polarization].psi);
                const Complex r = polarization == 0 ? f.r_s : -f.r_p;
                const Complex t = polarization == 0 ? f.t_s : f.t_p;
                const int other = 1 - polarization;
                worst_amplitude = std::max({worst_amplitude, std::abs(response.reflected_amplitudes[polarization] - r),
                                            std::abs(response.transmitted_amplitudes[polarization] - t),
                                            std::abs(response.reflected_amplitudes[other]),
                                            std::abs(response.transmitted_amplitudes[other])});
                const double transmittance = (q2.real() / q1.real()) * std::norm(t);
                worst_power = std::max({worst_power, std::abs(response.reflected_power[polarization] - std::norm(r)),
                                        std::abs(response.transmitted_power[polarization] - transmittance),
                                        std::abs(std::norm(r) + transmittance - 1.0)});
            }
        }
    }
    std::printf("Berreman vs Fresnel: amplitudes %.2e, powers %.2e\n", worst_amplitude, worst_power);
    EXPECT_LT(worst_amplitude, 1e-12);
    EXPECT_LT(worst_power, 1e-12);
}

TEST(BerremanStack, TotalInternalReflectionReflectsEverything) {
    // 1.5 → 1 beyond the critical angle (41.81°): R_s = R_p = 1, the transmitted waves are evanescent and carry
    // nothing, and r equals the Fresnel formula with cos θ₂ imaginary (q₂ = i√(ξ² − n₂²); Born & Wolf §1.5.4, docs/theory.md §3),
    // which gives the s and p waves different phases.
    const double n1 = 1.5, n2 = 1.0;
    double worst_power = 0.0, worst_amplitude = 0.0;
    for (int step = 0; step <= 480; ++step) {
        const double theta = (41.9 + 0.1 * step) * kPi / 180.0;
        const double xi = n1 * std::sin(theta);
        const Eigen::Vector2d xi_vector = xi * Eigen::Vector2d(std::cos(0.1 * step), std::sin(0.1 * step));
        const auto modes = berreman_modes(isotropic(n1), xi_vector);
        const Fresnel f = fresnel(n1, n2, n1 * std::cos(theta), Complex(0.0, std::sqrt(xi * xi - n2 * n2)));
        for (int polarization = 0; polarization < 2; ++polarization) {
            const StackResponse response =
                solve_stack(isotropic(n1), {}, isotropic(n2), 633.0, xi_vector, modes[polarization].psi);
            for (int m = 0; m < 2; ++m) {
                EXPECT_TRUE(response.transmitted_modes[m].evanescent);
                EXPECT_EQ(response.transmitted_power[m], 0.0);
            }
            worst_power = std::max(worst_power, std::abs(total(response.reflected_power) - 1.0));
            const Complex r = polarization == 0 ? f.r_s : -f.r_p;
            worst_amplitude = std::max(worst_amplitude, std::abs(response.reflected_amplitudes[polarization] - r));
        }
    }
    std::printf("Berreman TIR: |R - 1| %.2e, amplitudes vs Fresnel %.2e\n", worst_power, worst_amplitude);
    EXPECT_LT(worst_power, 1e-12);
    EXPECT_LT(worst_amplitude, 1e-12);
}

struct RandomStack {
    RandomMedium ambient, substrate;
    std::vector<StackLayer> layers;
    Eigen::Vector2d xi;
    double wavelength_nm = 550.0;
};

RandomStack random_stack(std::mt19937_64& rng, double kappa_max) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    RandomStack stack;
    stack.ambient = random_medium(rng);
    stack.substrate = random_medium(rng);
    const int count = static_cast<int>(rng() % 5);
    for (int i = 0; i < count; ++i) {
        const double thickness_um = rng() % 8 == 0 ? 20.0 * unit(rng) : 2.0 * unit(rng);
        stack.layers.push_back({random_medium(rng, kappa_max).epsilon, thickness_um});
    }
    stack.xi = random_xi(rng, 0.999 * stack.ambient.n_min);
    stack.wavelength_nm = 400.0 + 300.0 * unit(rng);
    return stack;
}

Eigen::Vector4cd random_incident(std::mt19937_64& rng, const Eigen::Matrix3cd& ambient, const Eigen::Vector2d& xi) {
    std::normal_distribution<double> normal;
    const auto modes = berreman_modes(ambient, xi);
    return Complex(normal(rng), normal(rng)) * modes[0].psi + Complex(normal(rng), normal(rng)) * modes[1].psi;
}

TEST(BerremanStack, LosslessStacksConserveEnergy) {
    // Lossless random anisotropic ambient, 0–4 layers (up to 20 µm, so thick layers with evanescent waves
    // occur) and substrate, ξ below the ambient's smallest index (its waves propagate): R + T = 1 (Poynting's
    // theorem with Im ε = 0; the modes of a lossless medium carry no cross flux).
    std::mt19937_64 rng(2002);
    double worst = 0.0;
    int total_reflections = 0;
    for (int i = 0; i < 10000; ++i) {
        const RandomStack stack = random_stack(rng, 0.0);
        const Eigen::Vector4cd incident = random_incident(rng, stack.ambient.epsilon, stack.xi);
        const StackResponse response = solve_stack(stack.ambient.epsilon, stack.layers, stack.substrate.epsilon,
                                                   stack.wavelength_nm, stack.xi, incident);
        ASSERT_GT(response.incident_flux_z, 0.0);
        const double t = total(response.transmitted_power);
        if (t == 0.0) ++total_reflections;
        worst = std::max(worst, std::abs(total(response.reflected_power) + t - 1.0));
    }
    std::printf("Berreman energy: worst |R + T - 1| = %.2e over 10^4 stacks (%d totally reflected)\n", worst,
                total_reflections);
    EXPECT_LT(worst, 1e-10);
}

TEST(BerremanStack, ThinFilmMatchesAiry) {
    // One isotropic film n₂ (transparent or absorbing) of thickness d on a substrate n₃ from n₁:
    // r = (r₁₂ + r₂₃e^{2iβ})/(1 + r₁₂r₂₃e^{2iβ}), t = t₁₂t₂₃e^{iβ}/(1 + r₁₂r₂₃e^{2iβ}), β = k₀q₂d
    // (Born & Wolf, §1.6.4, eqs. 57–58), for s and p, at normal and oblique incidence.
    const double n1 = 1.0, n3 = 1.52;
    double worst = 0.0;
    for (const Complex n2 : {Complex(1.38), Complex(2.35), Complex(2.0, 0.3)}) {
        for (const double thickness_um : {0.0, 0.1, 0.2768, 1.3}) {
            for (const double theta_deg : {0.0, 30.0, 60.0, 85.0}) {
                const double wavelength_nm = 589.3;
                const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
                const double xi = n1 * std::sin(theta_deg * kPi / 180.0);
                const Eigen::Vector2d xi_vector(0.6 * xi, -0.8 * xi);
                const Complex q1 = forward_q(n1, xi), q2 = forward_q(n2, xi), q3 = forward_q(n3, xi);
                const Fresnel f12 = fresnel(n1, n2, q1, q2), f23 = fresnel(n2, n3, q2, q3);
                const Complex phase = std::exp(kI * k0 * q2 * thickness_um);
                const auto modes = berreman_modes(isotropic(n1), xi_vector);
                for (int polarization = 0; polarization < 2; ++polarization) {
                    const Complex r12 = polarization == 0 ? f12.r_s : -f12.r_p;
                    const Complex r23 = polarization == 0 ? f23.r_s : -f23.r_p;
                    const Complex t12 = polarization == 0 ? f12.t_s : f12.t_p;
                    const Complex t23 = polarization == 0 ? f23.t_s : f23.t_p;
                    const Complex denominator = 1.0 + r12 * r23 * phase * phase;
                    const Complex r = (r12 + r23 * phase * phase) / denominator;
                    const Complex t = t12 * t23 * phase / denominator;
                    const StackResponse response =
                        solve_stack(isotropic(n1), {{isotropic(n2), thickness_um}}, isotropic(n3), wavelength_nm,
                                    xi_vector, modes[polarization].psi);
                    worst = std::max({worst, std::abs(response.reflected_amplitudes[polarization] - r),
                                      std::abs(response.transmitted_amplitudes[polarization] - t),
                                      std::abs(response.reflected_amplitudes[1 - polarization]),
                                      std::abs(response.transmitted_amplitudes[1 - polarization])});
                }
            }
        }
    }
    std::printf("Berreman vs Airy: %.2e\n", worst);
    EXPECT_LT(worst, 1e-12);
}

TEST(BerremanStack, FrustratedTotalReflectionAcrossThickGapsIsStable) {
    // Glass | air gap | glass beyond the critical angle: the gap's waves are evanescent, the Airy formula with
    // imaginary q₂ gives the tunnelling amplitude (Born & Wolf, §1.6.4), and the scattering-matrix recursion must
    // follow it into gaps where e^{k₀|q₂|d} would overflow a plain transfer-matrix product (d = 200 µm).
    const double n_glass = 1.5, xi = 1.2, wavelength_nm = 500.0;
    const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
    const Complex q_glass = forward_q(n_glass, xi), q_gap = forward_q(1.0, xi);
    const Fresnel f12 = fresnel(n_glass, 1.0, q_glass, q_gap), f23 = fresnel(1.0, n_glass, q_gap, q_glass);
    const auto modes = berreman_modes(isotropic(n_glass), {xi, 0.0});
    double worst = 0.0, worst_energy = 0.0;
    for (const double gap_um : {0.05, 0.2, 1.0, 5.0, 200.0}) {
        const Complex phase = std::exp(kI * k0 * q_gap * gap_um);
        const StackResponse response = solve_stack(isotropic(n_glass), {{isotropic(1.0), gap_um}}, isotropic(n_glass),
                                                   wavelength_nm, {xi, 0.0}, modes[0].psi);
        const Complex denominator = 1.0 + f12.r_s * f23.r_s * phase * phase;
        worst = std::max(
            {worst, std::abs(response.reflected_amplitudes[0] - (f12.r_s + f23.r_s * phase * phase) / denominator),
             std::abs(response.transmitted_amplitudes[0] - f12.t_s * f23.t_s * phase / denominator)});
        worst_energy =
            std::max(worst_energy, std::abs(total(response.reflected_power) + total(response.transmitted_power) - 1.0));
        ASSERT_TRUE(std::isfinite(response.reflected_power[0]));
    }
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(worst_energy, 1e-12);
}

TEST(BerremanStack, IsotropicLayerAtExactGrazingIncidenceStaysExact) {
    // Glass | air film | glass at ξ = 1: q = 0 in the film, where its forward and backward waves coincide (an
    // exceptional point of Δ) but its characteristic matrix does not care (Born & Wolf, §1.6.2). Integrating
    // dψ/dz = i k₀ Δ ψ across the film: (ψ₃, ψ₄) ← [[cos β, i sin β/q], [i q sin β, cos β]] (s) and
    // (ψ₁, ψ₂) ← [[cos β, i (q/ε) sin β], [i (ε/q) sin β, cos β]] (p), β = k₀qd, i.e. [[1, ik₀d], [0, 1]] and
    // [[1, 0], [ik₀εd, 1]] at q = 0. Matching ψ_inc + rψ_back = M⁻¹·tψ_trans gives the exact amplitudes.
    const double n_glass = 1.5, xi = 1.0, wavelength_nm = 550.0, thickness_um = 0.3;
    const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
    const auto modes = berreman_modes(isotropic(n_glass), {xi, 0.0});
    Eigen::Matrix4cd film = Eigen::Matrix4cd::Identity();  // ψ(d) = film·ψ(0), ε = 1, q = 0
    film(2, 3) = kI * k0 * thickness_um;
    film(1, 0) = kI * k0 * thickness_um;
    double worst = 0.0;
    for (int polarization = 0; polarization < 2; ++polarization) {
        const StackResponse response =
            solve_stack(isotropic(n_glass), {{isotropic(1.0), thickness_um}}, isotropic(n_glass), wavelength_nm,
                        {xi, 0.0}, modes[polarization].psi);
        // film·(ψ_inc + r ψ_back) − t ψ_trans = 0 in the two rows of this polarisation.
        Eigen::Matrix2cd system;
        Eigen::Vector2cd rhs;
        const Eigen::Vector4cd back = film * modes[2 + polarization].psi, incident = film * modes[polarization].psi;
        const int row = polarization == 0 ? 2 : 0;
        for (int k = 0; k < 2; ++k) {
            system(k, 0) = back[row + k];
            system(k, 1) = -modes[polarization].psi[row + k];  // the substrate is the same glass
            rhs[k] = -incident[row + k];
        }
        const Eigen::Vector2cd x = system.fullPivLu().solve(rhs);
        worst = std::max({worst, std::abs(response.reflected_amplitudes[polarization] - x[0]),
                          std::abs(response.transmitted_amplitudes[polarization] - x[1])});
        EXPECT_NEAR(total(response.reflected_power) + total(response.transmitted_power), 1.0, 1e-10);
    }
    std::printf("Berreman film at grazing incidence: %.2e\n", worst);
    EXPECT_LT(worst, 1e-9);
}

// Stokes parameters of the transverse field (E_x, E_y) (Born & Wolf, §1.4.2).
Eigen::Vector4d stokes(const Eigen::Vector3cd& e) {
    return {std::norm(e.x()) + std::norm(e.y()), std::norm(e.x()) - std::norm(e.y()),
            2.0 * (std::conj(e.x()) * e.y()).real(), 2.0 * (std::conj(e.x()) * e.y()).imag()};
}

TEST(BerremanStack, QuarterWavePlateTurnsLinearIntoCircularLight) {
    // A uniaxial plate, optic axis in its plane at 45°, d = λ/(4(n_e − n_o)), between media of the same ε (no
    // interface: reflections vanish exactly). Light polarised along x (45° from the axis) leaves circular:
    // the retardation 2π(n_e − n_o)d/λ = π/2 (the textbook limit, docs/theory.md §4; Born & Wolf §15.4.3).
    const double n_o = 1.544, n_e = 1.553, wavelength_nm = 589.3;
    const Eigen::Matrix3cd epsilon = principal_epsilon(Eigen::Vector3cd(n_e, n_o, n_o), rotation_z(kPi / 4.0));
    const double thickness_um = wavelength_nm * 1e-3 / (4.0 * (n_e - n_o));
    const auto modes = berreman_modes(epsilon, Eigen::Vector2d::Zero());
    // x̂ = Σ a_m E_m over the two forward modes (their E are orthonormal at normal incidence).
    const Complex a0 = modes[0].e_field.dot(Eigen::Vector3cd::UnitX()),
                  a1 = modes[1].e_field.dot(Eigen::Vector3cd::UnitX());
    const Eigen::Vector4cd incident = a0 * modes[0].psi + a1 * modes[1].psi;
    ASSERT_LT(std::abs(incident[2]), 1e-15);  // E_y = 0: linear along x
    const StackResponse response =
        solve_stack(epsilon, {{epsilon, thickness_um}}, epsilon, wavelength_nm, Eigen::Vector2d::Zero(), incident);
    const Eigen::Vector4d s = stokes(transmitted_e(response));
    std::printf("Berreman quarter-wave plate: |S3|/S0 = 1 - %.2e\n", 1.0 - std::abs(s[3]) / s[0]);
    EXPECT_GT(std::abs(s[3]) / s[0], 1.0 - 1e-10);
    EXPECT_LT(total(response.reflected_power), 1e-20);
}

TEST(BerremanStack, BirefringentPlateInAnOrdinaryIndexSurround) {
    // Optic axis along x in the plate's plane, isotropic surround of index n_o, normal incidence: the o wave
    // (E ∥ y) meets no index step (t = e^{ik₀n_o d}, r = 0) and the e wave (E ∥ x) is a Fabry–Perot film of
    // index n_e (Airy, Born & Wolf §1.6.4), with no coupling between them.
    const double n_o = 1.658, n_e = 1.486, wavelength_nm = 633.0;  // calcite
    const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
    const Eigen::Matrix3cd plate = principal_epsilon(Eigen::Vector3cd(n_e, n_o, n_o), Eigen::Matrix3d::Identity());
    const auto modes = berreman_modes(isotropic(n_o), Eigen::Vector2d::Zero());  // [s = E ∥ y, p = E ∥ x]
    double worst = 0.0;
    for (const double thickness_um : {0.5, 3.0, 30.0}) {
        const StackResponse o = solve_stack(isotropic(n_o), {{plate, thickness_um}}, isotropic(n_o), wavelength_nm,
                                            Eigen::Vector2d::Zero(), modes[0].psi);
        worst = std::max({worst, std::abs(o.transmitted_amplitudes[0] - std::exp(kI * k0 * n_o * thickness_um)),
                          std::abs(o.reflected_amplitudes[0]), std::abs(o.transmitted_amplitudes[1])});
        const StackResponse e = solve_stack(isotropic(n_o), {{plate, thickness_um}}, isotropic(n_o), wavelength_nm,
                                            Eigen::Vector2d::Zero(), modes[1].psi);
        const Complex r12 = (n_o - n_e) / (n_o + n_e), phase = std::exp(kI * k0 * n_e * thickness_um);
        const Complex denominator = 1.0 - r12 * r12 * phase * phase;
        worst = std::max({worst, std::abs(e.reflected_amplitudes[1] - r12 * (1.0 - phase * phase) / denominator),
                          std::abs(e.transmitted_amplitudes[1] - (1.0 - r12 * r12) * phase / denominator),
                          std::abs(e.transmitted_amplitudes[0])});
    }
    EXPECT_LT(worst, 1e-12);
}

// 5-point Gauss–Legendre rule on [−1, 1] (Abramowitz & Stegun, Table 25.4).
constexpr std::array<double, 5> kGaussNodes{-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                            0.9061798459386640};
constexpr std::array<double, 5> kGaussWeights{0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                              0.4786286704993665, 0.2369268850561891};

TEST(BerremanStack, AbsorbingLayerObeysPoyntingsTheorem) {
    // Lossless ambient and substrate, one absorbing anisotropic layer (complex symmetric ε, κ up to 0.3):
    // ∂S_z/∂z = −(k₀/2)·Im(E*·εE) (Poynting's theorem for exp(−iωt) fields, Born & Wolf §1.1.4 with the
    // complex permittivity), so R + T + A = 1 with A = (k₀/2)∫ Im(E*·εE) dz / S_inc. The field inside the layer
    // is rebuilt from the transmitted field with the layer's own modes and integrated by Gauss–Legendre; the
    // same rebuilt field must also match incident + reflected at the lower face (continuity of ψ).
    std::mt19937_64 rng(2003);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_energy = 0.0, worst_continuity = 0.0;
    for (int i = 0; i < 300; ++i) {
        const RandomMedium ambient = random_medium(rng), substrate = random_medium(rng);
        const RandomMedium layer = random_medium(rng, 0.3);
        const double thickness_um = 0.05 + 0.5 * unit(rng), wavelength_nm = 400.0 + 300.0 * unit(rng);
        const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
        const Eigen::Vector2d xi = random_xi(rng, 0.999 * ambient.n_min);
        const Eigen::Vector4cd incident = random_incident(rng, ambient.epsilon, xi);
        const StackResponse response = solve_stack(ambient.epsilon, {{layer.epsilon, thickness_um}}, substrate.epsilon,
                                                   wavelength_nm, xi, incident);
        const auto modes = berreman_modes(layer.epsilon, xi);
        Eigen::Matrix4cd basis;
        for (int m = 0; m < 4; ++m) basis.col(m) = modes[m].psi;
        const Eigen::Vector4cd c = basis.fullPivLu().solve(transmitted_psi(response));  // at the upper face
        const auto field = [&](double z) {                                              // z above the lower face
            Eigen::Vector3cd e = Eigen::Vector3cd::Zero();
            Eigen::Vector4cd psi = Eigen::Vector4cd::Zero();
            for (int m = 0; m < 4; ++m) {
                const Complex propagation = std::exp(kI * k0 * modes[m].q * (z - thickness_um));
                e += c[m] * propagation * modes[m].e_field;
                psi += c[m] * propagation * modes[m].psi;
            }
            return std::make_pair(e, psi);
        };
        const Eigen::Vector4cd below = incident + response.reflected_amplitudes[0] * response.reflected_modes[0].psi +
                                       response.reflected_amplitudes[1] * response.reflected_modes[1].psi;
        worst_continuity = std::max(worst_continuity, (field(0.0).second - below).norm() / below.norm());
        double absorbed = 0.0;
        const int panels = 40;
        const double h = thickness_um / panels;
        for (int panel = 0; panel < panels; ++panel) {
            for (int g = 0; g < 5; ++g) {
                const Eigen::Vector3cd e = field((panel + 0.5 + 0.5 * kGaussNodes[g]) * h).first;
                absorbed += 0.5 * h * kGaussWeights[g] * 0.5 * k0 * e.dot(layer.epsilon * e).imag();
            }
        }
        const double a = absorbed / response.incident_flux_z;
        const double r = total(response.reflected_power), t = total(response.transmitted_power);
        EXPECT_GT(a, 0.0);
        worst_energy = std::max(worst_energy, std::abs(r + t + a - 1.0));
    }
    std::printf("Berreman absorbing layer: |R + T + A - 1| %.2e, continuity %.2e\n", worst_energy, worst_continuity);
    EXPECT_LT(worst_energy, 1e-11);
    EXPECT_LT(worst_continuity, 1e-11);
}

TEST(BerremanStack, ZeroThicknessLayerChangesNothing) {
    // A layer of zero thickness is no layer, whatever its ε (absorbing, anisotropic): the two interfaces it adds
    // compose to the identity (continuity of ψ across a plane).
    std::mt19937_64 rng(2004);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
        RandomStack stack = random_stack(rng, 0.2);
        const Eigen::Vector4cd incident = random_incident(rng, stack.ambient.epsilon, stack.xi);
        const StackResponse plain = solve_stack(stack.ambient.epsilon, stack.layers, stack.substrate.epsilon,
                                                stack.wavelength_nm, stack.xi, incident);
        const size_t position = rng() % (stack.layers.size() + 1);
        stack.layers.insert(stack.layers.begin() + static_cast<std::ptrdiff_t>(position),
                            {random_medium(rng, 0.3).epsilon, 0.0});
        const StackResponse with_layer = solve_stack(stack.ambient.epsilon, stack.layers, stack.substrate.epsilon,
                                                     stack.wavelength_nm, stack.xi, incident);
        const double scale = std::sqrt(std::abs(plain.incident_flux_z));
        for (int m = 0; m < 2; ++m) {
            worst =
                std::max({worst, std::abs(plain.reflected_amplitudes[m] - with_layer.reflected_amplitudes[m]) / scale,
                          std::abs(plain.transmitted_amplitudes[m] - with_layer.transmitted_amplitudes[m]) / scale});
        }
    }
    std::printf("Berreman zero-thickness layer: %.2e\n", worst);
    EXPECT_LT(worst, 1e-13);
}

TEST(BerremanStack, RotatingEverythingAboutTheNormalChangesNoAmplitude) {
    // The modes are normalised in the (ρ̂, ŝ) frame of ξ, so turning every ε, ξ and the incident field about z
    // by the same angle must leave every amplitude unchanged (the lab-frame ψ and the plane-of-incidence Δ agree).
    std::mt19937_64 rng(2005);
    double worst = 0.0;
    for (int i = 0; i < 1000; ++i) {
        const RandomStack stack = random_stack(rng, 0.1);
        const Eigen::Vector4cd incident = random_incident(rng, stack.ambient.epsilon, stack.xi);
        const double angle = 2.0 * kPi * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const Eigen::Matrix3cd r = rotation_z(angle).cast<Complex>();
        const auto turn = [&](const Eigen::Matrix3cd& e) { return Eigen::Matrix3cd(r * e * r.transpose()); };
        std::vector<StackLayer> layers = stack.layers;
        for (StackLayer& layer : layers) layer.epsilon = turn(layer.epsilon);
        const double c = std::cos(angle), s = std::sin(angle);
        const Eigen::Vector4cd turned(c * incident[0] - s * incident[2], c * incident[1] - s * incident[3],
                                      s * incident[0] + c * incident[2], s * incident[1] + c * incident[3]);
        const StackResponse a = solve_stack(stack.ambient.epsilon, stack.layers, stack.substrate.epsilon,
                                            stack.wavelength_nm, stack.xi, incident);
        const StackResponse b =
            solve_stack(turn(stack.ambient.epsilon), layers, turn(stack.substrate.epsilon), stack.wavelength_nm,
                        rotation_z(angle).topLeftCorner<2, 2>() * stack.xi, turned);
        const double scale = std::sqrt(a.incident_flux_z);
        for (int m = 0; m < 2; ++m) {
            worst = std::max({worst, std::abs(a.reflected_amplitudes[m] - b.reflected_amplitudes[m]) / scale,
                              std::abs(a.transmitted_amplitudes[m] - b.transmitted_amplitudes[m]) / scale});
        }
    }
    std::printf("Berreman rotation about z: %.2e\n", worst);
    EXPECT_LT(worst, 1e-11);
}

TEST(BerremanStack, OpticAxisNormalToTheStackIsHandledExactlyAndContinuously) {
    // A uniaxial plate cut ⟂ its optic axis at normal incidence (the conoscope's centre): the o and e waves are
    // degenerate, so the plate acts as an isotropic film of index n_o (Airy, as above) for every polarisation.
    // Tilting the axis by δ splits them by ~(n_e − n_o)δ²: the response must change continuously (by at most
    // that retardation), not jump with the ill-conditioned eigenvectors near the degeneracy.
    const double n_o = 1.544, n_e = 1.553, wavelength_nm = 550.0, thickness_um = 30.0, n_out = 1.54;
    const double k0 = 2.0 * kPi * 1e3 / wavelength_nm;
    const auto modes = berreman_modes(isotropic(n_out), Eigen::Vector2d::Zero());
    const Complex r12 = (n_out - n_o) / (n_out + n_o), phase = std::exp(kI * k0 * n_o * thickness_um);
    const Complex denominator = 1.0 - r12 * r12 * phase * phase;
    const Complex r_airy = r12 * (1.0 - phase * phase) / denominator;
    const Complex t_airy = (1.0 - r12 * r12) * phase / denominator;
    const auto plate = [&](double tilt) {
        return principal_epsilon(Eigen::Vector3cd(n_o, n_o, n_e),
                                 Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix());
    };
    double worst_ratio = 0.0;
    for (int polarization = 0; polarization < 2; ++polarization) {
        const StackResponse on_axis = solve_stack(isotropic(n_out), {{plate(0.0), thickness_um}}, isotropic(n_out),
                                                  wavelength_nm, Eigen::Vector2d::Zero(), modes[polarization].psi);
        EXPECT_LT(std::abs(on_axis.reflected_amplitudes[polarization] - r_airy), 1e-12);
        EXPECT_LT(std::abs(on_axis.transmitted_amplitudes[polarization] - t_airy), 1e-12);
        EXPECT_LT(std::abs(on_axis.transmitted_amplitudes[1 - polarization]), 1e-12);
        for (const double tilt : {1e-12, 1e-9, 1e-7, 1e-5, 1e-3}) {
            const StackResponse tilted = solve_stack(isotropic(n_out), {{plate(tilt), thickness_um}}, isotropic(n_out),
                                                     wavelength_nm, Eigen::Vector2d::Zero(), modes[polarization].psi);
            const double retardation = k0 * thickness_um * (n_e - n_o) * tilt * tilt;
            double change = 0.0;
            for (int m = 0; m < 2; ++m) {
                change =
                    std::max({change, std::abs(tilted.transmitted_amplitudes[m] - on_axis.transmitted_amplitudes[m]),
                              std::abs(tilted.reflected_amplitudes[m] - on_axis.reflected_amplitudes[m])});
            }
            EXPECT_LT(change, 2.0 * retardation + 1e-11) << "tilt " << tilt;
            worst_ratio = std::max(worst_ratio, change / (2.0 * retardation + 1e-11));
            EXPECT_LT(std::abs(total(tilted.reflected_power) + total(tilted.transmitted_power) - 1.0), 1e-12);
        }
    }
    std::printf("Berreman optic axis tilted by 1e-12..1e-3 rad: change / (2 retardation + 1e-11) <= %.2f\n",
                worst_ratio);
}

TEST(BerremanStack, UniaxialSubstrateCutNormalToItsAxisReflectsAsItsOrdinaryIndex) {
    // Air onto a uniaxial crystal cut ⟂ its optic axis, normal incidence: both transmitted waves are o waves
    // (exactly degenerate in the substrate), R = ((n_o − 1)/(n_o + 1))² for any polarisation (Born & Wolf §1.5.2 with n_o),
    // and the per-mode powers add to T = 1 − R because the degenerate pair carries no cross flux.
    const double n_o = 1.658, n_e = 1.486;
    const Eigen::Matrix3cd substrate = principal_epsilon(Eigen::Vector3cd(n_o, n_o, n_e), Eigen::Matrix3d::Identity());
    const auto modes = berreman_modes(isotropic(1.0), Eigen::Vector2d::Zero());
    const double expected = std::pow((n_o - 1.0) / (n_o + 1.0), 2);
    for (const double azimuth : {0.0, 0.3, 1.0}) {
        const Eigen::Vector4cd incident = std::cos(azimuth) * modes[1].psi + std::sin(azimuth) * modes[0].psi;
        const StackResponse response =
            solve_stack(isotropic(1.0), {}, substrate, 550.0, Eigen::Vector2d::Zero(), incident);
        EXPECT_NEAR(total(response.reflected_power), expected, 1e-14);
        EXPECT_NEAR(total(response.transmitted_power), 1.0 - expected, 1e-14);
        for (const BerremanMode& mode : response.transmitted_modes) EXPECT_NEAR(std::abs(mode.q), n_o, 1e-14);
        // And back out of the crystal into air, from any combination of its degenerate forward waves.
        const auto inside = berreman_modes(substrate, Eigen::Vector2d::Zero());
        const StackResponse out = solve_stack(substrate, {}, isotropic(1.0), 550.0, Eigen::Vector2d::Zero(),
                                              std::cos(azimuth) * inside[0].psi + std::sin(azimuth) * inside[1].psi);
        EXPECT_NEAR(total(out.reflected_power), expected, 1e-14);
        EXPECT_NEAR(total(out.transmitted_power), 1.0 - expected, 1e-14);
    }
}

TEST(BerremanStack, RejectsNonPhysicalInput) {
    const Eigen::Matrix3cd air = isotropic(1.0);
    const Eigen::Vector4cd incident(1.0, 1.0, 0.0, 0.0);
    EXPECT_THROW(solve_stack(air, {}, air, 0.0, Eigen::Vector2d::Zero(), incident), std::invalid_argument);
    EXPECT_THROW(solve_stack(air, {{air, -1.0}}, air, 550.0, Eigen::Vector2d::Zero(), incident), std::invalid_argument);
}

}  // namespace
}  // namespace petroscope
