// Plane-parallel slab: the exact modes for a tangential wavevector, and the 2×2 entrance/exit transfer
// matrices against an independent 4×4 solve of the boundary conditions, energy conservation and the
// isotropic Fresnel formulas.
#include "petroscope/optics/eigenmodes.hpp"
#include "petroscope/optics/slab.hpp"

#include "support/random_crystals.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

// The tangential field of an isotropic medium's plane wave (the ψ of slab.hpp): forward (+1) or
// backward (−1), s (E ∥ ŝ) or p (unit E in the plane of incidence, transverse part along ±ρ̂).
Eigen::Vector4d isotropic_psi(double n, double xi, bool s_polarized, double direction) {
    const double q = direction * std::sqrt(n * n - xi * xi);
    const Eigen::Vector3d wave(xi, 0.0, q);  // in the plane-of-incidence frame (ρ̂, ŝ, ẑ)
    const Eigen::Vector3d e_field = s_polarized ? Eigen::Vector3d(Eigen::Vector3d::UnitY())
                                                : Eigen::Vector3d(std::abs(q) / n, 0.0, -direction * xi / n);
    const Eigen::Vector3d h_field = wave.cross(e_field);
    return {e_field.x(), h_field.y(), e_field.y(), -h_field.x()};
}

// Time-averaged z flux of a tangential field: S_z ∝ Re(E_ρ H_s* − E_s H_ρ*) = ψ₁ψ₂ + ψ₃ψ₄ (real ψ).
double flux(const Eigen::Vector4d& psi) { return psi[0] * psi[1] + psi[2] * psi[3]; }

struct RandomSlabCase {
    BinormalFrame frame;
    TangentialWavevector direction;
    double n_outside;
};

// Biaxial, or every third case uniaxial (the closed-form branch of the solver).
RandomSlabCase random_case(std::mt19937_64& rng) {
    const Indicatrix indicatrix = rng() % 3 == 0 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double n_outside = 1.0 + unit(rng) * 1.5;
    // Below every critical angle: |ξ| < min(n_outside, n_α).
    const double xi_max = 0.98 * std::min(n_outside, indicatrix.principal_n.minCoeff());
    const double radius = xi_max * std::sqrt(unit(rng));
    const double azimuth = 2.0 * M_PI * unit(rng);
    return {BinormalFrame(indicatrix),
            TangentialWavevector::from_xi(radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth))), n_outside};
}

TEST(SlabModes, EveryRootLiesOnItsSheetOfTheIndexSurface) {
    // |N| = n_σ(N̂) for N = (ξ, q): the defining property of a mode with that tangential wavevector.
    std::mt19937_64 rng(101);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const RandomSlabCase c = random_case(rng);
        const SlabModes modes = solve_slab_modes(c.frame, c.direction, Eigen::Vector2d::Constant(NAN));
        ASSERT_TRUE(modes.propagating);
        for (int sheet = 0; sheet < 2; ++sheet) {
            for (const SlabMode& mode : {modes.forward[sheet], modes.backward[sheet]}) {
                const Eigen::Vector3d wave(c.direction.xi.x(), c.direction.xi.y(), mode.q);
                const double index = 1.0 / std::sqrt(inverse_squared_indices(c.frame, wave.normalized())[sheet]);
                worst = std::max(worst, std::abs(wave.norm() - index));
            }
            EXPECT_GT(modes.forward[sheet].q, 0.0);
            EXPECT_LT(modes.backward[sheet].q, 0.0);
            // Forward modes carry energy toward +z, backward ones toward −z.
            EXPECT_GT(flux(tangential_field(modes.forward[sheet], c.direction)), 0.0);
            EXPECT_LT(flux(tangential_field(modes.backward[sheet], c.direction)), 0.0);
        }
    }
    EXPECT_LT(worst, 1e-13);
}

TEST(SlabModes, WarmStartFindsTheSameRoots) {
    std::mt19937_64 rng(102);
    for (int i = 0; i < 2000; ++i) {
        const RandomSlabCase c = random_case(rng);
        const SlabModes cold = solve_slab_modes(c.frame, c.direction, Eigen::Vector2d::Constant(NAN));
        const Eigen::Vector2d near(cold.forward[0].q * (1.0 + 1e-3), cold.forward[1].q * (1.0 - 1e-3));
        const SlabModes warm = solve_slab_modes(c.frame, c.direction, near);
        EXPECT_NEAR(warm.forward[0].q, cold.forward[0].q, 1e-14);
        EXPECT_NEAR(warm.forward[1].q, cold.forward[1].q, 1e-14);
    }
}

// Independent reference: the 4×4 boundary conditions solved directly (full-pivot LU), without the
// forward/backward projections that slab_transfer uses.
TEST(SlabTransfer, MatchesDirect4x4BoundarySolveAndConservesEnergy) {
    std::mt19937_64 rng(103);
    double worst_entry = 0.0, worst_exit = 0.0, worst_energy = 0.0;
    for (int i = 0; i < 10000; ++i) {
        const RandomSlabCase c = random_case(rng);
        const SlabModes modes = solve_slab_modes(c.frame, c.direction, Eigen::Vector2d::Constant(NAN));
        const SlabTransfer transfer = slab_transfer(modes, c.direction, c.n_outside, c.n_outside);
        const double xi = c.direction.xi.norm();
        const Eigen::Vector4d s_in = isotropic_psi(c.n_outside, xi, true, 1.0);
        const Eigen::Vector4d p_in = isotropic_psi(c.n_outside, xi, false, 1.0);
        const Eigen::Vector4d s_back = isotropic_psi(c.n_outside, xi, true, -1.0);
        const Eigen::Vector4d p_back = isotropic_psi(c.n_outside, xi, false, -1.0);
        // Entrance: incident + r_s ψ_s⁻ + r_p ψ_p⁻ = t_f ψ_f + t_sl ψ_sl.
        Eigen::Matrix4d entrance;
        entrance << -s_back, -p_back, tangential_field(modes.forward[0], c.direction), tangential_field(modes.forward[1], c.direction);
        for (int polarization = 0; polarization < 2; ++polarization) {
            const Eigen::Vector4d incident = polarization == 0 ? s_in : p_in;
            const Eigen::Vector4d x = entrance.fullPivLu().solve(incident);
            worst_entry = std::max(worst_entry, std::abs(x[2] - transfer.entry(0, polarization)));
            worst_entry = std::max(worst_entry, std::abs(x[3] - transfer.entry(1, polarization)));
            // R + T = 1 (modes are power-orthogonal, so the transmitted flux is the sum over modes).
            const double reflected = -(x[0] * x[0] * flux(s_back) + x[1] * x[1] * flux(p_back));
            const double transmitted = x[2] * x[2] * flux(tangential_field(modes.forward[0], c.direction)) + x[3] * x[3] * flux(tangential_field(modes.forward[1], c.direction));
            worst_energy = std::max(worst_energy, std::abs(reflected + transmitted - flux(incident)) / flux(incident));
        }
        // Exit: ψ_m + r₁ψ₁⁻ + r₂ψ₂⁻ = t_s ψ_s⁺ + t_p ψ_p⁺.
        Eigen::Matrix4d exit;
        exit << -tangential_field(modes.backward[0], c.direction), -tangential_field(modes.backward[1], c.direction), s_in, p_in;
        for (int mode = 0; mode < 2; ++mode) {
            const Eigen::Vector4d x = exit.fullPivLu().solve(tangential_field(modes.forward[mode], c.direction));
            worst_exit = std::max(worst_exit, std::abs(x[2] - transfer.exit(0, mode)));
            worst_exit = std::max(worst_exit, std::abs(x[3] - transfer.exit(1, mode)));
            const double incident = flux(tangential_field(modes.forward[mode], c.direction));
            const double reflected = -(x[0] * x[0] * flux(tangential_field(modes.backward[0], c.direction)) + x[1] * x[1] * flux(tangential_field(modes.backward[1], c.direction)));
            const double transmitted = x[2] * x[2] * flux(s_in) + x[3] * x[3] * flux(p_in);
            worst_energy = std::max(worst_energy, std::abs(reflected + transmitted - incident) / incident);
        }
    }
    EXPECT_LT(worst_entry, 1e-10);
    EXPECT_LT(worst_exit, 1e-10);
    EXPECT_LT(worst_energy, 1e-12);
}

TEST(SlabTransfer, IsotropicSlabGivesTheFresnelProducts) {
    // A slab of index n₂ in a medium n₁: single pass t₁₂·t₂₁ for s and for p (Born & Wolf §1.5.2; docs/theory.md §3), and no
    // s–p mixing, whatever mode basis the degenerate crystal returns.
    for (const double n_slab : {1.5, 2.4, 1.2}) {
        for (const double xi : {0.0, 0.3, 0.7, 0.99}) {
            const double n_outside = 1.0;
            const BinormalFrame frame(Indicatrix{Eigen::Vector3d::Constant(n_slab), Eigen::Matrix3d::Identity()});
            const TangentialWavevector direction = TangentialWavevector::from_xi({xi * 0.6, xi * 0.8});
            const SlabTransfer transfer =
                slab_transfer(solve_slab_modes(frame, direction, Eigen::Vector2d::Constant(NAN)), direction, n_outside, n_outside);
            const Eigen::Matrix2d jones = transfer.exit * transfer.entry;  // zero thickness
            const double cos1 = std::sqrt(1.0 - xi * xi / (n_outside * n_outside));
            const double cos2 = std::sqrt(1.0 - xi * xi / (n_slab * n_slab));
            const double t_s12 = 2 * n_outside * cos1 / (n_outside * cos1 + n_slab * cos2);
            const double t_s21 = 2 * n_slab * cos2 / (n_slab * cos2 + n_outside * cos1);
            const double t_p12 = 2 * n_outside * cos1 / (n_slab * cos1 + n_outside * cos2);
            const double t_p21 = 2 * n_slab * cos2 / (n_outside * cos2 + n_slab * cos1);
            EXPECT_NEAR(jones(0, 0), t_s12 * t_s21, 1e-13) << "n " << n_slab << " xi " << xi;
            EXPECT_NEAR(jones(1, 1), t_p12 * t_p21, 1e-13) << "n " << n_slab << " xi " << xi;
            EXPECT_NEAR(jones(0, 1), 0.0, 1e-13);
            EXPECT_NEAR(jones(1, 0), 0.0, 1e-13);
        }
    }
}

TEST(SlabJones, PhaseDifferenceIsTheTextbookRetardationAtNormalIncidence) {
    // Optic axis in the slab plane, normal incidence: δ = 2π d (n_slow − n_fast)/λ (docs/theory.md §4; Born & Wolf §15.4.3).
    const BinormalFrame frame(Indicatrix{{1.544, 1.544, 1.553}, Eigen::Matrix3d(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()))});
    const TangentialWavevector direction = TangentialWavevector::from_xi(Eigen::Vector2d::Zero());
    const SlabTransfer transfer = slab_transfer(solve_slab_modes(frame, direction, Eigen::Vector2d::Constant(NAN)), direction, 1.544, 1.544);
    const Eigen::Matrix2cd jones = slab_jones(transfer, 550.0, 30.0);
    // With the optic axis along x (p at normal incidence) the Jones matrix is diagonal in (s, p).
    const double retardation = std::arg(jones(1, 1) / jones(0, 0));
    const double expected = std::remainder(2 * M_PI * 30e3 * (1.553 - 1.544) / 550.0, 2 * M_PI);
    EXPECT_NEAR(retardation, expected, 1e-12);
    EXPECT_NEAR(std::abs(jones(0, 1)), 0.0, 1e-14);
}

}  // namespace
}  // namespace petroscope
