#pragma once
// XYZ to display colour: linear sRGB, the sRGB transfer curve, white balance.
#include <Eigen/Core>

namespace petroscope {

/// XYZ of the sRGB reference white (D65, Y = 1), IEC 61966-2-1.
Eigen::Vector3d srgb_white_xyz();

/// Linear sRGB from XYZ with the matrix of IEC 61966-2-1 (docs/theory.md §7).
Eigen::Vector3d xyz_to_linear_srgb(const Eigen::Vector3d& xyz);

/// The sRGB transfer curve: 12.92c for c ≤ 0.0031308, else 1.055c^(1/2.4) − 0.055 (IEC 61966-2-1).
double encode_srgb(double linear);

/// The inverse of encode_srgb: c/12.92 for c ≤ 0.04045, else ((c + 0.055)/1.055)^2.4 (IEC 61966-2-1).
double decode_srgb(double encoded);

/// Bradford chromatic adaptation (Lam 1985; Lindbloom's tables): maps colours seen under a light whose
/// white is `source_white_xyz` to how they look under `target_white_xyz`.
Eigen::Matrix3d bradford_adaptation(const Eigen::Vector3d& source_white_xyz, const Eigen::Vector3d& target_white_xyz);

/// CIE 1976 L*a*b* of `xyz` relative to `white_xyz` (CIE 15:2004 §8.2.1).
Eigen::Vector3d xyz_to_lab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz);

/// CIEDE2000 colour difference ΔE₀₀ (Sharma, Wu & Dalal 2005, eqs. 1–22).
double delta_e_2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2);

}  // namespace petroscope

#include "petroscope/core/image.hpp"

namespace petroscope {

/// The display conversion of one XYZ colour as a matrix: exposure · M_sRGB · (Bradford adaptation to the
/// sRGB white when `white_balance`).
Eigen::Matrix3d xyz_to_display_matrix(const Eigen::Vector3d& source_white_xyz, bool white_balance, double exposure);

/// Display conversion of an XYZ image seen under a light whose white is `source_white_xyz`: optional
/// Bradford white balance to the sRGB white, linear sRGB, times `exposure`.
Image xyz_image_to_linear_srgb(const Image& xyz, const Eigen::Vector3d& source_white_xyz, bool white_balance,
                               double exposure);

/// A one-channel intensity image as grey linear RGB, times `exposure`.
Image gray_image_to_rgb(const Image& gray, double exposure);

}  // namespace petroscope
