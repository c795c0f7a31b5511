#include "face_transfer.hpp"

#include "petroscope/optics/polarization.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace petroscope::detail {
namespace {

// The reverse of a traced wave must come out of the forward solution to within rounding (the solver
// works in extended precision).
constexpr double kSameDirection = 1.0 - 1e-7;

const InterfaceWave* find_wave(const InterfaceResult& result, InterfaceWave::Kind kind, const Eigen::Vector3d& direction) {
    const InterfaceWave* best = nullptr;
    double best_dot = kSameDirection;
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind != kind || wave.evanescent) continue;
        const double dot = wave.direction.dot(direction);
        if (dot > best_dot) {
            best_dot = dot;
            best = &wave;
        }
    }
    return best;
}

// Unpolarized, s, +45°, right circular: the Stokes basis states whose results give a linear map by
// differences (each has S0 = 1).
const std::array<Eigen::Vector4d, 4>& basis_states() {
    static const std::array<Eigen::Vector4d, 4> states{Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 1, 0, 0), Eigen::Vector4d(1, 0, 1, 0),
                                                       Eigen::Vector4d(1, 0, 0, 1)};
    return states;
}

std::array<InterfaceResult, 4> solve_basis_states(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction, const OpticalMedium& medium1,
                                                  const OpticalMedium& medium2) {
    std::array<InterfaceResult, 4> results;
    for (std::size_t k = 0; k < 4; ++k) {
        InterfaceIncidence incidence;
        incidence.direction = direction;
        incidence.coherency = coherency_from_stokes(basis_states()[k]);
        results[k] = solve_interface(normal, incidence, medium1, medium2);
    }
    return results;
}

std::vector<Branch> branches(const InterfaceResult& result, bool crystal_reflects) {
    std::vector<Branch> out;
    for (const InterfaceWave& wave : result.waves) {
        if (wave.evanescent || !(wave.power > 0.0)) continue;
        const bool in_crystal = (wave.kind == InterfaceWave::Kind::reflected) == crystal_reflects;
        out.push_back({in_crystal, wave.mode, wave.direction, wave.ray_direction, wave.power, wave.stokes});
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
    return branches(solve_interface(-outward, incidence, outside, crystal), false);
}

std::vector<Branch> branches_from_inside(const Eigen::Vector3d& outward, const Eigen::Vector3d& wave_normal, InterfaceMode mode,
                                         const OpticalMedium& outside, const OpticalMedium& crystal) {
    InterfaceIncidence incidence;
    incidence.direction = wave_normal;
    incidence.mode = mode;
    return branches(solve_interface(outward, incidence, crystal, outside), true);
}

std::optional<Eigen::Matrix4d> reflection_mueller(const Eigen::Vector3d& outward, const Eigen::Vector3d& traced, const Eigen::Vector3d& branch,
                                                  const OpticalMedium& outside, const OpticalMedium& crystal) {
    const std::array<InterfaceResult, 4> results = solve_basis_states(-outward, -branch, outside, crystal);
    std::array<Eigen::Vector4d, 4> out;
    for (std::size_t k = 0; k < 4; ++k) {
        const InterfaceWave* wave = find_wave(results[k], InterfaceWave::Kind::reflected, -traced);
        if (!wave) return std::nullopt;
        out[k] = wave->stokes;
    }
    Eigen::Matrix4d mueller;
    mueller.col(0) = out[0];
    for (int k = 1; k < 4; ++k) mueller.col(k) = out[static_cast<std::size_t>(k)] - out[0];
    return mueller;
}

std::optional<Eigen::Vector4d> refraction_out_stokes(const Eigen::Vector3d& outward, const Eigen::Vector3d& traced, const Eigen::Vector3d& branch,
                                                     InterfaceMode branch_mode, const OpticalMedium& outside, const OpticalMedium& crystal) {
    InterfaceIncidence incidence;
    incidence.direction = -branch;
    incidence.mode = branch_mode;
    const InterfaceResult result = solve_interface(outward, incidence, crystal, outside);
    const InterfaceWave* wave = find_wave(result, InterfaceWave::Kind::transmitted, -traced);
    if (!wave) return std::nullopt;
    return wave->stokes;
}

Eigen::RowVector4d refraction_in_row(const Branch& branch) {
    return 0.5 * Eigen::RowVector4d(branch.stokes[0], branch.stokes[1], -branch.stokes[2], -branch.stokes[3]);
}

}  // namespace petroscope::detail
