// Crystal orientation: the Euler convention and the named cuts put the right crystal directions along
// the microscope axis and E–W (docs/conventions.md).
#include "petroscope/core/error.hpp"
#include "petroscope/optics/indicatrix.hpp"
#include "petroscope/optics/orientation.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

constexpr double kDegree = M_PI / 180.0;
const Eigen::Vector3d kMuscovite(1.56, 1.5934, 1.598);  // negative, 2V ≈ 40°
const Eigen::Vector3d kTopaz(1.619, 1.6208, 1.627);     // positive, 2V ≈ 57°
const Eigen::Vector3d kCalcite(1.658, 1.658, 1.486);    // uniaxial negative (ω, ω, ε)

TEST(Orientation, EulerZyzIsRzRyRz) {
    const Eigen::Matrix3d r = euler_zyz_deg(30, 40, 50);
    const Eigen::Matrix3d expected = (Eigen::AngleAxisd(30 * kDegree, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(40 * kDegree, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(50 * kDegree, Eigen::Vector3d::UnitZ())).toRotationMatrix();
    EXPECT_TRUE(r.isApprox(expected, 1e-15));
    EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
    // Counter-clockwise seen from +z (the observer): x turns toward y.
    EXPECT_LT((rotation_z_deg(90) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

TEST(Orientation, AcuteBisectrixLiesAlongTheMicroscopeAxisWithTheAxialPlaneEastWest) {
    for (const Eigen::Vector3d& n : {kMuscovite, kTopaz}) {
        const Eigen::Matrix3d axes = cut_orientation(Cut::acute_bisectrix, OpticalClass::biaxial, n, 0, 0);
        const BinormalFrame frame(Indicatrix{n, axes});
        // Binormals symmetric about z in the x–z plane, at the acute angle V < 45° from z.
        for (const Eigen::Vector3d& b : {frame.binormal_1, frame.binormal_2}) {
            EXPECT_NEAR(b.y(), 0.0, 1e-15);
            EXPECT_LT(std::acos(std::abs(b.z())), M_PI / 4);
        }
        EXPECT_NEAR(std::abs(frame.binormal_1.x()), std::abs(frame.binormal_2.x()), 1e-15);
    }
}

TEST(Orientation, OpticAxisCutPutsOneBinormalOnTheAxisAndTheOtherToTheEast) {
  for (const Eigen::Vector3d& n : {kMuscovite, kTopaz}) {  // V_z above and below 45°
    const Eigen::Matrix3d axes = cut_orientation(Cut::optic_axis, OpticalClass::biaxial, n, 0, 0);
    const BinormalFrame frame(Indicatrix{n, axes});
    const bool first_on_axis = std::abs(frame.binormal_1.z()) > std::abs(frame.binormal_2.z());
    const Eigen::Vector3d on_axis = first_on_axis ? frame.binormal_1 : frame.binormal_2;
    const Eigen::Vector3d other = first_on_axis ? frame.binormal_2 : frame.binormal_1;
    EXPECT_NEAR(std::abs(on_axis.z()), 1.0, 1e-15);
    // The second binormal (as a line) leans toward +x, in the x–z plane.
    EXPECT_NEAR(other.y(), 0.0, 1e-15);
    EXPECT_GT(other.x() * other.z(), 0.0);
  }
}

TEST(Orientation, TiltAndAzimuthMoveAUniaxialOpticAxisTowardTheAzimuth) {
    const Eigen::Matrix3d axes = cut_orientation(Cut::optic_axis, OpticalClass::uniaxial, kCalcite, 120, 20);
    const Eigen::Vector3d optic_axis = axes.col(2);
    const Eigen::Vector3d expected(std::sin(20 * kDegree) * std::cos(120 * kDegree),
                                   std::sin(20 * kDegree) * std::sin(120 * kDegree), std::cos(20 * kDegree));
    EXPECT_LT((optic_axis - expected).norm(), 1e-15);
}

TEST(Orientation, OpticNormalCutOfAUniaxialCrystalLaysTheAxisEastWest) {
    const Eigen::Matrix3d axes = cut_orientation(Cut::optic_normal, OpticalClass::uniaxial, kCalcite, 0, 0);
    EXPECT_NEAR(std::abs(axes.col(2).x()), 1.0, 1e-15);
    const Eigen::Matrix3d turned = cut_orientation(Cut::optic_normal, OpticalClass::uniaxial, kCalcite, 90, 0);
    EXPECT_NEAR(std::abs(turned.col(2).y()), 1.0, 1e-15);
}

TEST(Orientation, BisectrixCutsOfAUniaxialCrystalAreRejected) {
    EXPECT_THROW(cut_orientation(Cut::acute_bisectrix, OpticalClass::uniaxial, kCalcite, 0, 0), InputError);
    EXPECT_THROW(parse_cut("basal"), InputError);
    EXPECT_EQ(parse_cut("optic-normal"), Cut::optic_normal);
}

TEST(Orientation, BinormalAngleMatchesTheHandbook2V) {
    // tan²V_z = (1/nα² − 1/nβ²)/(1/nβ² − 1/nγ²): muscovite 2V_x = 40° (V_z = 70°), topaz 2V_z ≈ 57°.
    EXPECT_NEAR(2 * (90 - binormal_angle_from_z(kMuscovite) / kDegree), 40.0, 0.1);
    EXPECT_NEAR(2 * binormal_angle_from_z(kTopaz) / kDegree, 56.8, 0.1);
}

}  // namespace
}  // namespace petroscope
