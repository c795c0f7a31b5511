// The reciprocity the tracer relies on at every face, against direct forward solves of the interface
// model: light from air into a mode, a mode reflected into a mode, a mode out into air and air reflected
// off a crystal carry the reversed problem's powers and polarizations.
#include "face_transfer.hpp"

#include "petroscope/optics/polarization.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
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

// The forward solve's wave along `direction` of `kind`, or nullptr (a pointer into `result`, which must
// outlive it: not into a temporary).
const InterfaceWave* find_wave(InterfaceResult&& result, InterfaceWave::Kind kind, const Eigen::Vector3d& direction) = delete;
const InterfaceWave* find_wave(const InterfaceResult& result, InterfaceWave::Kind kind, const Eigen::Vector3d& direction) {
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind == kind && !wave.evanescent && wave.direction.dot(direction) > 1.0 - 1e-9) return &wave;
    }
    return nullptr;
}

TEST(FaceTransfer, ForwardTransfersFromOutsideAreTheReversedProblemsByReciprocity) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> gauss;
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    const Eigen::Vector3d outward = Eigen::Vector3d(-0.1, 0.4, 1.0).normalized();
    const std::array<Eigen::Vector4d, 4> states{Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 1, 0, 0), Eigen::Vector4d(1, 0, 1, 0),
                                                Eigen::Vector4d(1, 0, 0, 1)};
    int reflections = 0, refractions = 0;
    double worst = 0.0, circular_terms = 0.0;
    for (int trial = 0; trial < 40; ++trial) {
        const Eigen::Quaterniond turn = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
        // A biaxial crystal (aragonite's principal indices), calcite, and an absorbing uniaxial crystal whose
        // complex reflection coefficients give the reflections circular terms (reciprocity holds for any
        // symmetric ε; the renderer's crystals are lossless, so only reflection is compared there).
        const std::array<Eigen::Vector3cd, 3> indices{Eigen::Vector3cd(1.530, 1.681, 1.686), Eigen::Vector3cd(1.658, 1.658, 1.486),
                                                      Eigen::Vector3cd({2.0, 0.8}, {2.0, 0.8}, {1.7, 0.3})};
        const bool absorbing = trial % 3 == 2;
        const OpticalMedium crystal{indices[static_cast<std::size_t>(trial % 3)], turn.toRotationMatrix()};
        const Eigen::Vector3d traced = (-outward + 0.6 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))).normalized();
        if (!(traced.dot(-outward) > 0.05)) continue;
        for (const Branch& branch : branches_from_outside(outward, traced, air, crystal)) {
            if (!branch.in_crystal) {
                // Air → air: the forward reflection of light arriving along −branch, for each basis state.
                const Eigen::Matrix4d mueller = reflection_mueller(branch);
                circular_terms = std::max(circular_terms, std::abs(mueller(2, 3)));
                for (const Eigen::Vector4d& state : states) {
                    InterfaceIncidence incidence;
                    incidence.direction = -branch.wave_normal;
                    incidence.coherency = coherency_from_stokes(state);
                    const InterfaceResult forward = solve_interface(-outward, incidence, air, crystal);
                    const InterfaceWave* wave = find_wave(forward, InterfaceWave::Kind::reflected, -traced);
                    ASSERT_NE(wave, nullptr);
                    worst = std::max(worst, (mueller * state - wave->stokes).cwiseAbs().maxCoeff());
                    ++reflections;
                }
                continue;
            }
            // Mode → air: the light leaving along −traced for unit power of the mode arriving along −branch.
            if (absorbing || walks_off(-branch.wave_normal, outward)) continue;
            InterfaceIncidence incidence;
            incidence.direction = -branch.wave_normal;
            incidence.mode = branch.mode;
            const InterfaceResult forward = solve_interface(outward, incidence, crystal, air);
            const InterfaceWave* wave = find_wave(forward, InterfaceWave::Kind::transmitted, -traced);
            ASSERT_NE(wave, nullptr);
            worst = std::max(worst, (refraction_out_stokes(branch) - wave->stokes).cwiseAbs().maxCoeff());
            ++refractions;
        }
    }
    EXPECT_LT(worst, 1e-10);
    EXPECT_GT(circular_terms, 0.01);  // so that the signs of S3 are tested
    EXPECT_GT(reflections, 100);
    EXPECT_GT(refractions, 50);
}

}  // namespace
}  // namespace petroscope::detail
