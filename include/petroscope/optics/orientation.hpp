#pragma once
// Orienting a crystal in the microscope: Euler angles and the named cuts of optical mineralogy.
// Frames and angle senses: docs/conventions.md.
#include <Eigen/Core>

#include <string>
#include <string_view>

namespace petroscope {

enum class OpticalClass { isotropic, uniaxial, biaxial };

/// R = Rz(alpha)·Ry(beta)·Rz(gamma), angles in degrees, active right-handed rotations; the columns of R
/// are the indicatrix axes X, Y, Z in the lab frame.
Eigen::Matrix3d euler_zyz_deg(double alpha_deg, double beta_deg, double gamma_deg);

/// Rotation by `angle_deg` about the lab z axis (the microscope axis), counter-clockwise as seen by the
/// observer looking down the microscope.
Eigen::Matrix3d rotation_z_deg(double angle_deg);

enum class Cut { optic_axis, acute_bisectrix, obtuse_bisectrix, optic_normal };
Cut parse_cut(std::string_view name);  // "optic-axis", …; throws InputError listing the names
std::string_view cut_name(Cut cut);

/// The indicatrix axes (columns, lab frame) for a named cut. `principal_n` are the indices along X, Y, Z
/// at the reference wavelength (they fix V and the acute bisectrix). The cut direction (optic axis,
/// bisectrix or optic normal) is first put along the microscope axis with the optic axial plane (or an
/// inclined uniaxial optic axis) E–W, then tilted by `tilt_deg` toward +x, then turned by `azimuth_deg`
/// about the microscope axis. Throws InputError when the cut does not exist for the optical class.
Eigen::Matrix3d cut_orientation(Cut cut, OpticalClass optical_class, const Eigen::Vector3d& principal_n,
                                double azimuth_deg, double tilt_deg);

/// The angle V_z of each binormal from the indicatrix Z axis: tan²V_z = (1/nα² − 1/nβ²)/(1/nβ² − 1/nγ²)
/// (docs/theory.md §1, "Binormals and biradials"; Born & Wolf §15.3.3), in radians, for indices along X, Y, Z.
double binormal_angle_from_z(const Eigen::Vector3d& principal_n);

}  // namespace petroscope
