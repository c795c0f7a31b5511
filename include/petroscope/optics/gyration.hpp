#pragma once
// Natural optical activity (gyrotropy): the gyration tensor of a crystal and the constitutive relation that
// carries it. Conventions (the handedness, the sense of rotation): docs/conventions.md; the model:
// docs/theory.md, "Optical activity".
#include <Eigen/Core>

#include <string_view>

namespace petroscope {

/// The largest rotatory power accepted as input, °/mm: beyond it a value is taken for a gross mistake (a formula's
/// pole among the visible wavelengths, °/m written for °/mm). Quartz turns 21.7 °/mm at 589 nm; paratellurite's
/// record reaches about 1400 °/mm across its axis at 360 nm.
inline constexpr double kMaxRotatoryPowerDegPerMm = 1e4;

/// The two enantiomorphic forms of an optically active crystal. Right = dextrorotatory: along its optic axis
/// (any direction for a cubic crystal) it turns the plane of polarization clockwise for an observer looking
/// toward the light source (docs/conventions.md).
enum class Handedness { right, left };
std::string_view handedness_name(Handedness handedness);
/// "right" or "left"; throws InputError naming both otherwise.
Handedness parse_handedness(std::string_view text);

/// Landau's gyration tensor g (dimensionless): D = εE + i(g·N)×E for a plane wave exp(i(k₀N·r − ωt))
/// (Landau & Lifshitz, Electrodynamics of Continuous Media, §§100–101; Nye, Physical Properties of Crystals,
/// ch. XIV). Built from the rotatory powers ρᵢ (rad/µm, positive dextrorotatory, of the right-handed form)
/// of waves along the principal axes (columns of `axes`, lab frame) as gᵢᵢ = λρᵢ/π: a wave along a
/// principal direction of an isotropic background turns its plane by π·g_ss/λ per unit length. The left-handed
/// form has −g.
Eigen::Matrix3d gyration_tensor(const Eigen::Vector3d& rotatory_power_rad_per_um, const Eigen::Matrix3d& axes,
                                double wavelength_nm, Handedness handedness);

/// A gyration tensor given in the frame whose axes are the columns of `axes` (lab frame), seen in the lab:
/// A·g·Aᵀ, made symmetric to the last bit.
Eigen::Matrix3d turned_gyration(const Eigen::Matrix3d& gyration, const Eigen::Matrix3d& axes);

/// The chirality tensor κ of the equivalent bianisotropic relations D = ε_b E + iκH, B = H − iκE
/// (Berreman, JOSA 62, 502 (1972), his optically active media): κ = (tr g/2)·I − g, and ε_b = ε + κ², give
/// exactly Landau's plane-wave equation N × (N × E) + εE + i(g·N) × E = 0, by the identity
/// N × (κE) + κ(N × E) = ((tr κ)·I − κ)N × E for a symmetric κ (docs/theory.md, "Optical activity").
Eigen::Matrix3d chirality_tensor(const Eigen::Matrix3d& gyration);

}  // namespace petroscope
