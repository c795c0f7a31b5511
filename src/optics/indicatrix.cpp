#include "petroscope/optics/indicatrix.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace petroscope {

Eigen::Matrix3d Indicatrix::impermeability() const {
    const Eigen::Vector3d inverse_squares = principal_n.array().square().inverse();
    return axes * inverse_squares.asDiagonal() * axes.transpose();
}

template <typename Real>
BasicBinormalFrame<Real>::BasicBinormalFrame(const Indicatrix& indicatrix) {
    using std::atan2, std::cos, std::max, std::sin, std::sqrt;
    // Sort the axes by index: smallest index (largest impermeability a) first.
    std::array<int, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(),
                     [&](int i, int j) { return indicatrix.principal_n[i] < indicatrix.principal_n[j]; });
    const auto inverse_square = [&](int axis) {
        const Real n = indicatrix.principal_n[axis];
        return Real(1) / (n * n);
    };
    a = inverse_square(order[0]);
    b = inverse_square(order[1]);
    c = inverse_square(order[2]);
    // Orthonormalised in `Real` (Gram–Schmidt, handedness kept): a rotation built in double is orthogonal
    // only to ~1e-16, and η = R·D·Rᵀ and binormals made from R's columns would then describe crystals
    // that differ by that much, which shows where the modes' fluxes are small (grazing incidence).
    const Matrix raw = indicatrix.axes.cast<Real>();
    Matrix axes;
    axes.col(0) = raw.col(0).normalized();
    axes.col(1) = (raw.col(1) - raw.col(1).dot(axes.col(0)) * axes.col(0)).normalized();
    axes.col(2) = axes.col(0).cross(axes.col(1));
    e_a = axes.col(order[0]);
    e_c = axes.col(order[2]);
    // tan²V = (a − b)/(b − c) (docs/theory.md §1; Born & Wolf §15.3.3); atan2 keeps V defined for uniaxial (b = c or a = b)
    // and isotropic (all equal: V = 0) crystals.
    v_rad = atan2(sqrt(max(a - b, Real(0))), sqrt(max(b - c, Real(0))));
    if (b == c && a != b) {
        // Negative uniaxial: both binormals along the optic axis e_a (exactly, not through cos 90°).
        binormal_1 = e_a;
        binormal_2 = -e_a;
    } else {
        binormal_1 = cos(v_rad) * e_c + sin(v_rad) * e_a;
        binormal_2 = cos(v_rad) * e_c - sin(v_rad) * e_a;
    }
    // η = R·diag(1/n²)·Rᵀ, made exactly symmetric.
    Vector diagonal;
    for (int i = 0; i < 3; ++i) diagonal[i] = inverse_square(i);
    const Matrix product = axes * diagonal.asDiagonal() * axes.transpose();
    impermeability = Real(0.5) * (product + product.transpose());
}

template struct BasicBinormalFrame<double>;
template struct BasicBinormalFrame<long double>;

}  // namespace petroscope
