#include "petroscope/api/crystal_orientation.hpp"

#include "petroscope/core/error.hpp"

#include <cmath>

namespace petroscope {

Cut default_cut(OpticalClass optical_class) {
    return optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
}

std::optional<Cut> cut_used(const Mineral& mineral, const CrystalOrientation& orientation) {
    if (orientation.euler_zyz_deg) return std::nullopt;
    return orientation.cut.value_or(default_cut(mineral.optical_class));
}

Eigen::Matrix3d indicatrix_axes(const Mineral& mineral, const CrystalOrientation& orientation) {
    if (orientation.euler_zyz_deg) {
        const Eigen::Vector3d& angles = *orientation.euler_zyz_deg;
        if (!angles.allFinite()) throw InputError("Euler angles must be finite numbers of degrees");
        return euler_zyz_deg(angles[0], angles[1], angles[2]);
    }
    if (!std::isfinite(orientation.azimuth_deg) || !std::isfinite(orientation.tilt_deg)) {
        throw InputError("the azimuth and tilt must be finite numbers of degrees");
    }
    const Eigen::Vector3d reference_n = mineral.principal_n(mineral.reference_wavelength_nm);
    return cut_orientation(*cut_used(mineral, orientation), mineral.optical_class, reference_n, orientation.azimuth_deg, orientation.tilt_deg);
}

}  // namespace petroscope
