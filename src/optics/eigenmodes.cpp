#include "petroscope/optics/eigenmodes.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace petroscope {
namespace {

// Unit projection of `v` on the plane ⟂ k̂, or zero when `v` ∥ k̂. Projected twice ("twice is enough",
// Giraud et al., Numer. Math. 101, 87 (2005)): near a binormal the first projection is a tiny difference
// whose rounding leaves, once normalised, a component along k̂ of order ε/|transverse|.
template <typename Real>
Eigen::Matrix<Real, 3, 1> unit_transverse(const Eigen::Matrix<Real, 3, 1>& v, const Eigen::Matrix<Real, 3, 1>& k_hat) {
    using Vector = Eigen::Matrix<Real, 3, 1>;
    Vector transverse = v - v.dot(k_hat) * k_hat;
    const Real length = transverse.norm();
    if (!(length > Real(0))) return Vector::Zero();
    transverse /= length;
    transverse -= transverse.dot(k_hat) * k_hat;
    return transverse.normalized();
}

// Any unit vector ⟂ k̂.
template <typename Real>
Eigen::Matrix<Real, 3, 1> any_perpendicular(const Eigen::Matrix<Real, 3, 1>& k_hat) {
    using Vector = Eigen::Matrix<Real, 3, 1>;
    const Vector helper = std::abs(k_hat.x()) < Real(0.9) ? Vector::UnitX() : Vector::UnitY();
    return k_hat.cross(helper).normalized();
}

WaveMode complete_mode(const BinormalFrame& frame, const Eigen::Vector3d& k_hat, double inverse_n2,
                       const Eigen::Vector3d& d_hat) {
    WaveMode mode;
    mode.n = 1.0 / std::sqrt(inverse_n2);
    mode.d_hat = d_hat;
    mode.e_field = frame.impermeability * d_hat;
    // Walk-off: tan α = n²·(k̂·η·D̂), ŝ ∝ k̂ − tan α·D̂ (docs/theory.md §1, "Eigenmodes"; Born & Wolf §15.2).
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

template <typename Real>
std::pair<Eigen::Matrix<Real, 3, 1>, Eigen::Matrix<Real, 3, 1>> vibration_directions(const BasicBinormalFrame<Real>& frame,
                                                                                     const Eigen::Matrix<Real, 3, 1>& k_hat) {
    using Vector = Eigen::Matrix<Real, 3, 1>;
    const Vector p1 = unit_transverse(frame.binormal_1, k_hat);
    const Vector p2 = unit_transverse(frame.binormal_2, k_hat);
    const Vector sum = p1 + p2;         // ∥ D_slow
    const Vector difference = p1 - p2;  // ∥ D_fast
    const Real sum_norm = sum.norm();
    const Real difference_norm = difference.norm();
    if (sum_norm == Real(0) && difference_norm == Real(0)) {
        // On the binormal of a uniaxial (or in an isotropic) crystal: every direction is an eigenmode.
        const Vector first = any_perpendicular(k_hat);
        return {first, k_hat.cross(first)};
    }
    if (sum_norm >= difference_norm) {
        const Vector slow = sum / sum_norm;
        return {k_hat.cross(slow), slow};
    }
    const Vector fast = difference / difference_norm;
    return {fast, k_hat.cross(fast)};
}

template std::pair<Eigen::Vector3d, Eigen::Vector3d> vibration_directions(const BinormalFrame&, const Eigen::Vector3d&);
template std::pair<Eigen::Matrix<long double, 3, 1>, Eigen::Matrix<long double, 3, 1>> vibration_directions(
    const BasicBinormalFrame<long double>&, const Eigen::Matrix<long double, 3, 1>&);

ModePair eigenmodes(const BinormalFrame& frame, const Eigen::Vector3d& k_hat) {
    const Eigen::Vector2d inverse_n2 = inverse_squared_indices(frame, k_hat);
    const auto [d_fast, d_slow] = vibration_directions(frame, k_hat);
    return {complete_mode(frame, k_hat, inverse_n2[0], d_fast), complete_mode(frame, k_hat, inverse_n2[1], d_slow)};
}

}  // namespace petroscope
