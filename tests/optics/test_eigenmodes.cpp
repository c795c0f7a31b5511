// Eigenmodes of a wave normal: the Biot–Fresnel construction against a direct 3×3 eigensolver, on and
// near the binormals included.
#include "petroscope/optics/eigenmodes.hpp"

#include "support/random_crystals.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

// Reference: the transverse restriction of η, P·η·P with P = I − k̂k̂ᵀ, has eigenvalues 0 (along k̂) and
// 1/n² of the two modes (Born & Wolf §15.2); a symmetric eigensolver gets them to machine precision.
Eigen::Vector2d reference_inverse_squared(const Indicatrix& indicatrix, const Eigen::Vector3d& k_hat) {
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - k_hat * k_hat.transpose();
    const Eigen::Matrix3d transverse = projector * indicatrix.impermeability() * projector;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(transverse);
    const Eigen::Vector3d values = solver.eigenvalues();  // ascending; values[0] ≈ 0
    return {values[2], values[1]};                          // (fast, slow) = (largest, middle)
}

// Index error |n − n_ref| from 1/n² values.
double index_error(const Eigen::Vector2d& inverse_n2, const Eigen::Vector2d& reference) {
    return std::max(std::abs(1.0 / std::sqrt(inverse_n2[0]) - 1.0 / std::sqrt(reference[0])),
                    std::abs(1.0 / std::sqrt(inverse_n2[1]) - 1.0 / std::sqrt(reference[1])));
}

TEST(Eigenmodes, IndicesMatchDirectEigensolverOverRandomDirections) {
    std::mt19937_64 rng(20261121);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const Indicatrix indicatrix = testing::random_biaxial(rng);
        const BinormalFrame frame(indicatrix);
        const Eigen::Vector3d k_hat = testing::random_unit_vector(rng);
        worst = std::max(worst, index_error(inverse_squared_indices(frame, k_hat), reference_inverse_squared(indicatrix, k_hat)));
    }
    EXPECT_LT(worst, 1e-12);
}

TEST(Eigenmodes, IndicesMatchDirectEigensolverOnAndNearBinormals) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> exponent(-12.0, -3.0);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const Indicatrix indicatrix = testing::random_biaxial(rng);
        const BinormalFrame frame(indicatrix);
        const Eigen::Vector3d binormal = (i % 2 == 0) ? frame.binormal_1 : frame.binormal_2;
        // A direction at angular distance 10^[-12, -3] rad (every 10th exactly on the binormal).
        const double distance = (i % 10 == 0) ? 0.0 : std::pow(10.0, exponent(rng));
        const Eigen::Vector3d offset = binormal.cross(testing::random_unit_vector(rng)).normalized();
        const Eigen::Vector3d k_hat = (binormal * std::cos(distance) + offset * std::sin(distance)).normalized();
        worst = std::max(worst, index_error(inverse_squared_indices(frame, k_hat), reference_inverse_squared(indicatrix, k_hat)));
    }
    EXPECT_LT(worst, 1e-12);
}

TEST(Eigenmodes, VibrationDirectionsSolveTheWaveEquation) {
    // P·η·D = D/n² for each mode, D ⟂ k̂, D_fast ⟂ D_slow (Born & Wolf §15.2 eq. 19).
    std::mt19937_64 rng(11);
    for (int i = 0; i < 20000; ++i) {
        const Indicatrix indicatrix = testing::random_biaxial(rng);
        const BinormalFrame frame(indicatrix);
        const Eigen::Vector3d k_hat = testing::random_unit_vector(rng);
        const ModePair modes = eigenmodes(frame, k_hat);
        const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - k_hat * k_hat.transpose();
        const double separation = std::abs(1.0 / (modes.fast.n * modes.fast.n) - 1.0 / (modes.slow.n * modes.slow.n));
        for (const WaveMode* mode : {&modes.fast, &modes.slow}) {
            const Eigen::Vector3d residual = projector * frame.impermeability * mode->d_hat - mode->d_hat / (mode->n * mode->n);
            // The eigenvector is determined to about ε/separation (ill-conditioned near the binormals).
            EXPECT_LT(residual.norm(), 1e-13 + 1e-16 / separation) << "case " << i;
            EXPECT_NEAR(mode->d_hat.dot(k_hat), 0.0, 1e-14);
            EXPECT_NEAR(mode->d_hat.norm(), 1.0, 1e-14);
        }
        EXPECT_NEAR(modes.fast.d_hat.dot(modes.slow.d_hat), 0.0, 1e-14);
        EXPECT_LE(modes.fast.n, modes.slow.n);
    }
}

TEST(Eigenmodes, UniaxialOrdinaryWaveVibratesPerpendicularToThePrincipalPlane) {
    // Calcite-like, negative: ω = 1.658, ε = 1.486; optic axis along a random direction.
    std::mt19937_64 rng(3);
    for (int i = 0; i < 1000; ++i) {
        const Eigen::Matrix3d axes = testing::random_rotation(rng);
        const BinormalFrame frame(Indicatrix{{1.658, 1.658, 1.486}, axes});
        const Eigen::Vector3d optic_axis = axes.col(2);
        const Eigen::Vector3d k_hat = testing::random_unit_vector(rng);
        const ModePair modes = eigenmodes(frame, k_hat);
        // Negative crystal: the ordinary wave is the slow one, with n = ω in every direction.
        EXPECT_NEAR(modes.slow.n, 1.658, 1e-14);
        EXPECT_NEAR(modes.slow.d_hat.dot(optic_axis), 0.0, 1e-12);
        // Extraordinary: 1/n² = cos²θ/ω² + sin²θ/ε² (Born & Wolf §15.3.3).
        const double cos_theta = k_hat.dot(optic_axis);
        const double expected = cos_theta * cos_theta / (1.658 * 1.658) + (1.0 - cos_theta * cos_theta) / (1.486 * 1.486);
        EXPECT_NEAR(1.0 / (modes.fast.n * modes.fast.n), expected, 1e-14);
        EXPECT_NEAR(modes.fast.d_hat.dot(k_hat.cross(optic_axis)), 0.0, 1e-12);  // in the principal plane
    }
}

TEST(Eigenmodes, RayDirectionIsThePoyntingVector) {
    // S ∝ E × H with H ∝ k̂ × E; the walk-off formula must agree with the cross products.
    std::mt19937_64 rng(5);
    for (int i = 0; i < 10000; ++i) {
        const BinormalFrame frame(testing::random_biaxial(rng));
        const Eigen::Vector3d k_hat = testing::random_unit_vector(rng);
        for (const WaveMode& mode : {eigenmodes(frame, k_hat).fast, eigenmodes(frame, k_hat).slow}) {
            const Eigen::Vector3d poynting = mode.e_field.cross(k_hat.cross(mode.e_field)).normalized();
            EXPECT_LT((poynting - mode.ray_direction).norm(), 1e-12);
        }
    }
}

}  // namespace
}  // namespace petroscope
