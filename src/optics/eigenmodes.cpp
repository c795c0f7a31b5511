#include "petroscope/optics/eigenmodes.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace petroscope {
namespace {

// Unit projection of `v` on the plane ⟂ k̂, or zero when `v` ∥ k̂.
Eigen::Vector3d unit_transverse(const Eigen::Vector3d& v, const Eigen::Vector3d& k_hat) {
    const Eigen::Vector3d transverse = v - v.dot(k_hat) * k_hat;
    const double length = transverse.norm();
    return length > 0.0 ? Eigen::Vector3d(transverse / length) : Eigen::Vector3d::Zero();
}

// Any unit vector ⟂ k̂.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& k_hat) {
    const Eigen::Vector3d helper = std::abs(k_hat.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return k_hat.cross(helper).normalized();
}

WaveMode complete_mode(const BinormalFrame& frame, const Eigen::Vector3d& k_hat, double inverse_n2,
                       const Eigen::Vector3d& d_hat) {
    WaveMode mode;
    mode.n = 1.0 / std::sqrt(inverse_n2);
    mode.d_hat = d_hat;
    mode.e_field = frame.impermeability * d_hat;
    // Walk-off: tan α = n²·(k̂·η·D̂), ŝ ∝ k̂ − tan α·D̂ (physics notes §2).
    const double tan_alpha = mode.n * mode.n * k_hat.dot(mode.e_field);
    mode.ray_direction = (k_hat - tan_alpha * d_hat).normalized();
    return mode;
}

}  // namespace

Eigen::Vector2d inverse_squared_indices(const BinormalFrame& frame, const Eigen::Vector3d& k_hat) {
    const double c1 = k_hat.dot(frame.binormal_1);
    const double c2 = k_hat.dot(frame.binormal_2);
    const double s1 = k_hat.cross(frame.binormal_1).norm();
    const double s2 = k_hat.cross(frame.binormal_2).norm();
    const double half_sum = 0.5 * (frame.a + frame.c);
    const double half_difference = 0.5 * (frame.a - frame.c);
    const double m = half_sum + half_difference * c1 * c2;
    const double delta = half_difference * s1 * s2;
    return {m + delta, m - delta};
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> vibration_directions(const BinormalFrame& frame,
                                                                 const Eigen::Vector3d& k_hat) {
    const Eigen::Vector3d p1 = unit_transverse(frame.binormal_1, k_hat);
    const Eigen::Vector3d p2 = unit_transverse(frame.binormal_2, k_hat);
    const Eigen::Vector3d sum = p1 + p2;       // ∥ D_slow
    const Eigen::Vector3d difference = p1 - p2;  // ∥ D_fast
    const double sum_norm = sum.norm();
    const double difference_norm = difference.norm();
    if (sum_norm == 0.0 && difference_norm == 0.0) {
        // On the binormal of a uniaxial (or in an isotropic) crystal: every direction is an eigenmode.
        const Eigen::Vector3d first = any_perpendicular(k_hat);
        return {first, k_hat.cross(first)};
    }
    if (sum_norm >= difference_norm) {
        const Eigen::Vector3d slow = sum / sum_norm;
        return {k_hat.cross(slow), slow};
    }
    const Eigen::Vector3d fast = difference / difference_norm;
    return {fast, k_hat.cross(fast)};
}

ModePair eigenmodes(const BinormalFrame& frame, const Eigen::Vector3d& k_hat) {
    const Eigen::Vector2d inverse_n2 = inverse_squared_indices(frame, k_hat);
    const auto [d_fast, d_slow] = vibration_directions(frame, k_hat);
    return {complete_mode(frame, k_hat, inverse_n2[0], d_fast), complete_mode(frame, k_hat, inverse_n2[1], d_slow)};
}

}  // namespace petroscope
