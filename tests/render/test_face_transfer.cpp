// The reciprocity the tracer relies on inside crystals, against direct forward solves of the interface
// model: light from air into a mode, and a mode reflected into a mode, carry the reversed problem's powers.
#include "face_transfer.hpp"

#include "petroscope/optics/polarization.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <random>

namespace petroscope::detail {
namespace {

TEST(FaceTransfer, ForwardTransfersIntoACrystalModeAreTheReversedProblemsByReciprocity) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> gauss;
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    const Eigen::Vector3d outward = Eigen::Vector3d(0.2, -0.3, 1.0).normalized();
    int compared = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Eigen::Quaterniond turn = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
        const OpticalMedium calcite{Eigen::Vector3cd(1.658, 1.658, 1.486), turn.toRotationMatrix()};
        const Eigen::Vector3d wave_normal = (outward + 0.5 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))).normalized();
        if (walks_off(wave_normal, outward)) continue;
        for (const InterfaceMode mode : {InterfaceMode::ordinary, InterfaceMode::extraordinary}) {
            for (const Branch& branch : branches_from_inside(outward, wave_normal, mode, air, calcite)) {
                if (branch.in_crystal) {
                    // Mode → mode: solve the reversed branch as incident and read the traced mode's power.
                    if (walks_off(-branch.wave_normal, outward)) continue;
                    InterfaceIncidence incidence;
                    incidence.direction = -branch.wave_normal;
                    incidence.mode = branch.mode;
                    for (const InterfaceWave& wave : solve_interface(outward, incidence, calcite, air).waves) {
                        if (wave.kind == InterfaceWave::Kind::reflected && wave.mode == mode && wave.direction.dot(-wave_normal) > 1.0 - 1e-9) {
                            EXPECT_NEAR(wave.power, branch.power, 1e-10);
                            ++compared;
                        }
                    }
                    continue;
                }
                // Air → mode: the power of the traced mode for unpolarized, s, +45° and circular light.
                const Eigen::RowVector4d row = refraction_in_row(branch);
                const std::array<Eigen::Vector4d, 4> states{Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 1, 0, 0), Eigen::Vector4d(1, 0, 1, 0),
                                                            Eigen::Vector4d(1, 0, 0, 1)};
                for (const Eigen::Vector4d& state : states) {
                    InterfaceIncidence incidence;
                    incidence.direction = -branch.wave_normal;
                    incidence.coherency = coherency_from_stokes(state);
                    for (const InterfaceWave& wave : solve_interface(-outward, incidence, air, calcite).waves) {
                        if (wave.kind == InterfaceWave::Kind::transmitted && wave.mode == mode && wave.direction.dot(-wave_normal) > 1.0 - 1e-9) {
                            EXPECT_NEAR(wave.power, row.dot(state), 1e-10) << wave_mode_name(mode) << " state " << state.transpose();
                            ++compared;
                        }
                    }
                }
            }
        }
    }
    EXPECT_GT(compared, 300);
}

}  // namespace
}  // namespace petroscope::detail
