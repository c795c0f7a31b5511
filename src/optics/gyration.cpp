#include "petroscope/optics/gyration.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <numbers>

namespace petroscope {

std::string_view handedness_name(Handedness handedness) { return handedness == Handedness::right ? "right" : "left"; }

Handedness parse_handedness(std::string_view text) {
    if (text == "right") return Handedness::right;
    if (text == "left") return Handedness::left;
    throw InputError("unknown handedness " + quote_input(text) + " (expected right or left)");
}

Eigen::Matrix3d gyration_tensor(const Eigen::Vector3d& rotatory_power_rad_per_um, const Eigen::Matrix3d& axes,
                                double wavelength_nm, Handedness handedness) {
    // gᵢᵢ = λρᵢ/π (gyration.hpp); the enantiomorph is the mirror image, g → −g (a pseudo-tensor).
    const double sign = handedness == Handedness::right ? 1.0 : -1.0;
    const Eigen::Vector3d principal = sign * wavelength_nm * 1e-3 / std::numbers::pi * rotatory_power_rad_per_um;
    return turned_gyration(principal.asDiagonal(), axes);
}

Eigen::Matrix3d turned_gyration(const Eigen::Matrix3d& gyration, const Eigen::Matrix3d& axes) {
    const Eigen::Matrix3d lab = axes * gyration * axes.transpose();
    return 0.5 * (lab + lab.transpose());
}

Eigen::Matrix3d chirality_tensor(const Eigen::Matrix3d& gyration) {
    return 0.5 * gyration.trace() * Eigen::Matrix3d::Identity() - gyration;
}

}  // namespace petroscope
