#pragma once
// How a crystal lies in the microscope, as every front end describes it: a named cut of optical
// mineralogy, tilted and turned, or ZYZ Euler angles. Frames and angle senses: docs/conventions.md.
#include "petroscope/minerals/mineral.hpp"
#include "petroscope/optics/orientation.hpp"

#include <Eigen/Core>

#include <optional>

namespace petroscope {

struct CrystalOrientation {
    std::optional<Cut> cut;                        // none: default_cut of the mineral's optical class
    double azimuth_deg = 0.0;                      // the cut turned about the microscope axis (cut_orientation)
    double tilt_deg = 0.0;                         // the cut direction tilted toward the azimuth
    std::optional<Eigen::Vector3d> euler_zyz_deg;  // instead of a cut: R = Rz(a)·Ry(b)·Rz(c) (euler_zyz_deg)
};

/// The cut a figure shows unless told otherwise: the acute bisectrix of a biaxial crystal, the optic axis
/// of a uniaxial one (and of an isotropic one, where every direction is alike).
Cut default_cut(OpticalClass optical_class);

/// The cut `orientation` names for `mineral` (its default when none); none with Euler angles.
std::optional<Cut> cut_used(const Mineral& mineral, const CrystalOrientation& orientation);

/// The indicatrix axes (columns, lab frame, stage at 0) of `mineral` so oriented; the cut is placed with the
/// indices at the mineral's reference wavelength. Throws InputError for a cut the class does not have or
/// non-finite angles.
Eigen::Matrix3d indicatrix_axes(const Mineral& mineral, const CrystalOrientation& orientation);

}  // namespace petroscope
