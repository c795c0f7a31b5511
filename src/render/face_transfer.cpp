#include "face_transfer.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace petroscope::detail {
namespace {

std::vector<Branch> branches(const InterfaceResult& result, bool crystal_reflects) {
    std::vector<Branch> out;
    for (const InterfaceWave& wave : result.waves) {
        if (wave.evanescent || !(wave.power > 0.0)) continue;
        const bool in_crystal = (wave.kind == InterfaceWave::Kind::reflected) == crystal_reflects;
        out.push_back({in_crystal, wave.mode, wave.direction, wave.ray_direction, wave.power, wave.stokes,
                       wave.mueller.value_or(Eigen::Matrix4d::Zero())});
    }
    return out;
}

}  // namespace

Eigen::Vector3d s_basis(const Eigen::Vector3d& normal, const Eigen::Vector3d& k) {
    const Eigen::Vector3d s = normal.cross(k);
    if (s.norm() > 1e-15) return s.normalized();
    const Eigen::Vector3d reference = std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return normal.cross(reference).normalized();
}

Eigen::Matrix4d stokes_frame_change(const Eigen::Vector3d& s_from, const Eigen::Vector3d& s_to, const Eigen::Vector3d& k) {
    // ŝ_to = cos φ ŝ_from + sin φ p̂_from: light linear at α from ŝ_from is at α − φ from ŝ_to.
    const Eigen::Vector3d p_from = s_from.cross(k);
    const double phi = std::atan2(s_to.dot(p_from), s_to.dot(s_from));
    const double c = std::cos(2.0 * phi), s = std::sin(2.0 * phi);
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m(1, 1) = c;
    m(1, 2) = s;
    m(2, 1) = -s;
    m(2, 2) = c;
    return m;
}

std::vector<Branch> branches_from_outside(const Eigen::Vector3d& outward, const Eigen::Vector3d& direction, const OpticalMedium& outside,
                                          const OpticalMedium& crystal) {
    InterfaceIncidence incidence;
    incidence.direction = direction;
    incidence.with_mueller = true;
    incidence.arithmetic = InterfaceArithmetic::double_precision;
    return branches(solve_interface(-outward, incidence, outside, crystal), false);
}

std::vector<Branch> branches_from_inside(const Eigen::Vector3d& outward, const Eigen::Vector3d& wave_normal, InterfaceMode mode,
                                         const OpticalMedium& outside, const OpticalMedium& crystal) {
    InterfaceIncidence incidence;
    incidence.direction = wave_normal;
    incidence.mode = mode;
    incidence.arithmetic = InterfaceArithmetic::double_precision;
    return branches(solve_interface(outward, incidence, crystal, outside), true);
}

Eigen::Matrix4d reflection_mueller(const Branch& branch) {
    const Eigen::Vector4d d(1, 1, -1, 1);
    return d.asDiagonal() * branch.mueller.transpose() * d.asDiagonal();
}

Eigen::Vector4d refraction_out_stokes(const Branch& branch) {
    const Eigen::RowVector4d& q = branch.mueller.row(0);
    return 2.0 * Eigen::Vector4d(q[0], q[1], -q[2], -q[3]);
}

Eigen::RowVector4d refraction_in_row(const Branch& branch) {
    return 0.5 * Eigen::RowVector4d(branch.stokes[0], branch.stokes[1], -branch.stokes[2], -branch.stokes[3]);
}

}  // namespace petroscope::detail
