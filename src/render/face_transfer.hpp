#pragma once
// The light transport across one crystal face for backward tracing, from the exact interface model
// (optics/interface.hpp). A path traced from the camera meets a face; the light that arrives along it
// came from the waves the interface solver creates for the reversed problem (reciprocity: the same
// directions, reversed). For each such branch the forward transfer onto the traced wave follows exactly
// from the reversed problem's own solution by reciprocity, so one solve serves the face: a Mueller matrix
// (air to air), a Stokes column (crystal mode to air), a Stokes row (air to a crystal mode) or a power
// (mode to mode). Stokes vectors are in each wave's (s, p) basis (docs/interface.md); s_basis gives that
// basis for a normal and a wave direction.
#include "petroscope/optics/interface.hpp"

#include <Eigen/Core>

#include <vector>

namespace petroscope::detail {

/// ŝ of a wave with unit direction `k` at a face with unit `normal` (the solver's, medium 1 to 2):
/// normalize(normal × k), or normal × x̂ (normal × ŷ when the normal lies along x) at normal incidence.
Eigen::Vector3d s_basis(const Eigen::Vector3d& normal, const Eigen::Vector3d& k);

/// The matrix taking a Stokes vector in the basis (ŝ_from, ŝ_from × k) to the basis (ŝ_to, ŝ_to × k) of
/// the same wave: a rotation of the frame by φ from ŝ_from toward p̂_from (S1, S2 turn by 2φ).
Eigen::Matrix4d stokes_frame_change(const Eigen::Vector3d& s_from, const Eigen::Vector3d& s_to, const Eigen::Vector3d& k);

/// Near grazing incidence inside a crystal a wave's ray and its wave normal can lie on opposite sides of
/// a face (walk-off): the ray reaches the face while the wave normal points away from it. The interface
/// model takes an incident wave by its wave normal, so this cannot be solved; the tracer ends such paths
/// and counts them.
inline bool walks_off(const Eigen::Vector3d& wave_normal_toward_face, const Eigen::Vector3d& outward) {
    return !(wave_normal_toward_face.dot(outward) > 0.0);
}

/// One wave of the reversed problem: where the traced path continues.
struct Branch {
    bool in_crystal = false;           // a crystal mode (else a wave in the surrounding air)
    InterfaceMode mode = InterfaceMode::isotropic;  // the wave's mode (isotropic for the outside wave)
    Eigen::Vector3d wave_normal;       // unit, along the traced (backward) direction
    Eigen::Vector3d ray;               // unit ray (Poynting) direction of the traced path
    double power = 0.0;                // of the reversed problem, as a selection weight
    Eigen::Vector4d stokes = Eigen::Vector4d::Zero();  // of the reversed problem's wave, its (s, p) basis
    /// From the surrounding medium: the reversed problem's Mueller matrix onto this wave (stokes = mueller ·
    /// (1, 0, 0, 0)); zero from inside the crystal.
    Eigen::Matrix4d mueller = Eigen::Matrix4d::Zero();
};

/// Both solve the interface in double precision (InterfaceArithmetic::double_precision; its accuracy is
/// tested against the long-double solve, test_interface.cpp).
///
/// The traced path arrives in the surrounding medium `outside` along `direction` at a face
/// whose outward normal is `outward`: the branches (reflected into the outside medium, refracted modes).
std::vector<Branch> branches_from_outside(const Eigen::Vector3d& outward, const Eigen::Vector3d& direction, const OpticalMedium& outside,
                                          const OpticalMedium& crystal);
/// The traced path arrives inside the crystal in `mode` with `wave_normal` (which must point out through
/// the face): the branches (reflected modes, the refracted outside wave unless totally reflected).
std::vector<Branch> branches_from_inside(const Eigen::Vector3d& outward, const Eigen::Vector3d& wave_normal, InterfaceMode mode,
                                         const OpticalMedium& outside, const OpticalMedium& crystal);

/// Forward transfers onto the traced wave, from the reversed problem's branch by reciprocity (lossless,
/// non-magnetic media with symmetric ε; Born & Wolf §1.5, Potton 2004, Rep. Prog. Phys. 67, 717). The
/// traced wave's backward direction is `traced`; the light of interest travels along −traced and comes
/// from −branch.wave_normal. The reversed problem's bases and the forward one's share ŝ and have opposite
/// p̂, which flips S2 and S3. Each is tested against direct forward solves (test_face_transfer.cpp).
///
/// Outside → outside (reflection off the face; a branch of branches_from_outside): the Mueller matrix
/// from the incident light (basis s_basis(−outward, −branch)) to the reflected light (basis
/// s_basis(−outward, −traced)). The Jones matrix of the reversed path is the transpose of the forward one
/// (in bases with reversed p̂): M = D M_revᵀ D with D = diag(1, 1, −1, 1).
Eigen::Matrix4d reflection_mueller(const Branch& branch);
/// Crystal mode (travelling along −branch) → outside light along −traced (a crystal branch of
/// branches_from_outside): its Stokes vector per unit incident power, basis s_basis(outward, −traced):
/// 2(q0, q1, −q2, −q3), q the reversed problem's power row (the branch's Mueller matrix's first row).
Eigen::Vector4d refraction_out_stokes(const Branch& branch);
/// Outside light (along −branch, basis s_basis(−outward, −branch)) → crystal mode along −traced, from
/// the reversed problem's branch of `branches_from_inside` by reciprocity (lossless media; Born & Wolf
/// §1.5, Potton 2004, Rep. Prog. Phys. 67, 717): the row q with power = q·S is ½(t0, t1, −t2, −t3), t the
/// branch's Stokes vector (its basis has the same ŝ and the opposite p̂). Tested against the forward solve.
Eigen::RowVector4d refraction_in_row(const Branch& branch);

}  // namespace petroscope::detail
