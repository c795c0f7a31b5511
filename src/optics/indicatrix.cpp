#include "petroscope/optics/indicatrix.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace petroscope {

Eigen::Matrix3d Indicatrix::impermeability() const {
    const Eigen::Vector3d inverse_squares = principal_n.array().square().inverse();
    return axes * inverse_squares.asDiagonal() * axes.transpose();
}

BinormalFrame::BinormalFrame(const Indicatrix& indicatrix) {
    // Sort the axes by index: smallest index (largest impermeability a) first.
    std::array<int, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(),
                     [&](int i, int j) { return indicatrix.principal_n[i] < indicatrix.principal_n[j]; });
    a = 1.0 / (indicatrix.principal_n[order[0]] * indicatrix.principal_n[order[0]]);
    b = 1.0 / (indicatrix.principal_n[order[1]] * indicatrix.principal_n[order[1]]);
    c = 1.0 / (indicatrix.principal_n[order[2]] * indicatrix.principal_n[order[2]]);
    e_a = indicatrix.axes.col(order[0]);
    e_c = indicatrix.axes.col(order[2]);
    // tan²V = (a − b)/(b − c) (physics notes §2); atan2 keeps V defined for uniaxial (b = c or a = b)
    // and isotropic (all equal: V = 0) crystals.
    v_rad = std::atan2(std::sqrt(std::max(a - b, 0.0)), std::sqrt(std::max(b - c, 0.0)));
    if (b == c && a != b) {
        // Negative uniaxial: both binormals along the optic axis e_a (exactly, not through cos 90°).
        binormal_1 = e_a;
        binormal_2 = -e_a;
    } else {
        binormal_1 = std::cos(v_rad) * e_c + std::sin(v_rad) * e_a;
        binormal_2 = std::cos(v_rad) * e_c - std::sin(v_rad) * e_a;
    }
    impermeability = indicatrix.impermeability();
}

}  // namespace petroscope
