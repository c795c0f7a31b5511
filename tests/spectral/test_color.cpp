// XYZ to display colour (include/petroscope/spectral/color.hpp): the sRGB matrix and transfer curve, Bradford
// adaptation, CIELAB and CIEDE2000.
#include "petroscope/spectral/color.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace petroscope {
namespace {

// IEC 61966-2-1 D65 white and CIE illuminant A white (Y = 1), as tabulated by Lindbloom.
const Eigen::Vector3d kWhiteD65(0.95047, 1.0, 1.08883);
const Eigen::Vector3d kWhiteA(1.09850, 1.0, 0.35585);

TEST(Srgb, WhiteMapsToUnitRgb) {
    // The 4-digit matrix of IEC 61966-2-1 and the 5-digit white agree to 1.7e-4 (blue channel 0.99983).
    const Eigen::Vector3d rgb = xyz_to_linear_srgb(srgb_white_xyz());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 2e-4) << "channel " << c;
    EXPECT_EQ(srgb_white_xyz(), kWhiteD65);
}

TEST(Srgb, PrimariesMapToUnitVectors) {
    // Columns of the inverse (RGB → XYZ) matrix of IEC 61966-2-1; the two 4-digit matrices are inverse to
    // each other to ~4e-5.
    const Eigen::Vector3d primaries[3] = {{0.4124, 0.2126, 0.0193}, {0.3576, 0.7152, 0.1192}, {0.1805, 0.0722, 0.9505}};
    for (int p = 0; p < 3; ++p) {
        const Eigen::Vector3d rgb = xyz_to_linear_srgb(primaries[p]);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], p == c ? 1.0 : 0.0, 1e-4) << "primary " << p << " channel " << c;
    }
}

TEST(Srgb, TransferCurve) {
    EXPECT_EQ(encode_srgb(0.0), 0.0);
    // 1.055·1 − 0.055 is 1 up to one rounding (4 ulp allowed).
    EXPECT_DOUBLE_EQ(encode_srgb(1.0), 1.0);
    EXPECT_DOUBLE_EQ(encode_srgb(0.001), 0.01292);  // linear segment
    // 18% grey: 1.055·0.18^(1/2.4) − 0.055 = 0.46135612950044164 (evaluated independently in Python).
    EXPECT_NEAR(encode_srgb(0.18), 0.46135612950044164, 1e-15);
}

TEST(Srgb, TransferCurveIsContinuousAtTheBreakpoint) {
    // The IEC constants make the two branches meet at 0.0031308 to 2.9e-8 (12.92·c = 0.040449936 against
    // 1.055·c^(1/2.4) − 0.055 = 0.0404499075).
    const double breakpoint = 0.0031308;
    const double below = encode_srgb(breakpoint);
    const double above = encode_srgb(std::nextafter(breakpoint, 1.0));
    EXPECT_DOUBLE_EQ(below, 12.92 * breakpoint);
    EXPECT_LT(std::abs(above - below), 3e-8);
    // Monotonic across it.
    EXPECT_LT(encode_srgb(breakpoint - 1e-6), below);
    EXPECT_LT(above, encode_srgb(breakpoint + 1e-6));
}

TEST(Bradford, SameWhiteIsIdentity) {
    for (const Eigen::Vector3d& white : {kWhiteD65, kWhiteA, Eigen::Vector3d(1.0, 1.0, 1.0)}) {
        const Eigen::Matrix3d m = bradford_adaptation(white, white);
        EXPECT_LT((m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12) << m;
    }
}

TEST(Bradford, MapsSourceWhiteToTargetWhite) {
    const Eigen::Matrix3d to_a = bradford_adaptation(kWhiteD65, kWhiteA);
    EXPECT_LT((to_a * kWhiteD65 - kWhiteA).cwiseAbs().maxCoeff(), 1e-12);
    const Eigen::Matrix3d to_d65 = bradford_adaptation(kWhiteA, kWhiteD65);
    EXPECT_LT((to_d65 * kWhiteA - kWhiteD65).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((to_d65 * to_a - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Bradford, MatchesLindbloomsPublishedD65ToAMatrix) {
    // B. Lindbloom, "Chromatic Adaptation" (brucelindbloom.com), Bradford matrix D65 → A, printed to 7 decimals.
    Eigen::Matrix3d published;
    published << 1.2164557, 0.1109905, -0.1549325,
                 0.1533326, 0.9152313, -0.0559953,
                -0.0239469, 0.0358984, 0.3147529;
    EXPECT_LT((bradford_adaptation(kWhiteD65, kWhiteA) - published).cwiseAbs().maxCoeff(), 5e-8);
}

TEST(Lab, WhiteIsL100AndNeutral) {
    for (const Eigen::Vector3d& white : {kWhiteD65, kWhiteA}) {
        const Eigen::Vector3d lab = xyz_to_lab(white, white);
        EXPECT_EQ(lab[0], 100.0);
        EXPECT_EQ(lab[1], 0.0);
        EXPECT_EQ(lab[2], 0.0);
    }
    const Eigen::Vector3d black = xyz_to_lab(Eigen::Vector3d::Zero(), kWhiteD65);
    EXPECT_NEAR(black.norm(), 0.0, 1e-12);
}

TEST(Lab, LightnessOnBothBranches) {
    // CIE 15:2004 §8.2.1: L* = 116 (Y/Yn)^(1/3) − 16 above ε = 216/24389, L* = κ·Y/Yn below, κ = 24389/27.
    const auto lightness = [](double relative_y) { return xyz_to_lab(relative_y * kWhiteD65, kWhiteD65)[0]; };
    EXPECT_NEAR(lightness(0.18), 116.0 * std::cbrt(0.18) - 16.0, 1e-12);
    EXPECT_NEAR(lightness(0.001), 24389.0 / 27.0 * 0.001, 1e-12);
    // Both branches give L* = 8 at ε.
    const double epsilon = 216.0 / 24389.0;
    EXPECT_NEAR(lightness(epsilon * (1.0 - 1e-12)), 8.0, 1e-9);
    EXPECT_NEAR(lightness(epsilon * (1.0 + 1e-12)), 8.0, 1e-9);
}

TEST(Lab, SrgbRedUnderD65) {
    // sRGB red (XYZ 0.412456, 0.212673, 0.019334, Lindbloom) has L*a*b* = (53.24, 80.09, 67.20) relative to D65.
    const Eigen::Vector3d lab = xyz_to_lab({0.412456, 0.212673, 0.019334}, kWhiteD65);
    EXPECT_NEAR(lab[0], 53.24, 0.005);
    EXPECT_NEAR(lab[1], 80.09, 0.005);
    EXPECT_NEAR(lab[2], 67.20, 0.005);
}

// G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations", Color Res. Appl. 30(1), 21–30 (2005), Table 1:
// all 34 pairs (L*1, a*1, b*1, L*2, a*2, b*2, ΔE00).
struct SharmaPair {
    double l1, a1, b1, l2, a2, b2, delta_e;
};
constexpr SharmaPair kSharmaPairs[34] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

TEST(DeltaE2000, SharmaWuDalalTestData) {
    // The published ΔE are rounded to 4 decimals, so an exact implementation is within 5e-5 of each.
    for (int i = 0; i < 34; ++i) {
        const SharmaPair& p = kSharmaPairs[i];
        const double delta_e = delta_e_2000({p.l1, p.a1, p.b1}, {p.l2, p.a2, p.b2});
        EXPECT_NEAR(delta_e, p.delta_e, 5e-5 + 1e-12) << "Sharma et al. pair " << i + 1;
    }
}

TEST(DeltaE2000, SymmetricAndZeroForEqualColours) {
    for (int i = 0; i < 34; ++i) {
        const SharmaPair& p = kSharmaPairs[i];
        const Eigen::Vector3d lab1(p.l1, p.a1, p.b1), lab2(p.l2, p.a2, p.b2);
        EXPECT_NEAR(delta_e_2000(lab1, lab2), delta_e_2000(lab2, lab1), 1e-12) << "pair " << i + 1;
        EXPECT_EQ(delta_e_2000(lab1, lab1), 0.0) << "pair " << i + 1;
    }
    // Neutral colours (zero chroma, where the hue is undefined): ΔE00 reduces to the lightness term.
    const double l_term = std::pow(55.0 - 50.0, 2);
    const double s_l = 1.0 + 0.015 * l_term / std::sqrt(20.0 + l_term);
    EXPECT_NEAR(delta_e_2000({50.0, 0.0, 0.0}, {60.0, 0.0, 0.0}), 10.0 / s_l, 1e-12);
}

TEST(DisplayImages, GrayToRgbCopiesTimesExposure) {
    Image gray(2, 1, 1);
    gray.at(0, 0, 0) = 0.25f;
    gray.at(1, 0, 0) = 1.0f;
    const Image rgb = gray_image_to_rgb(gray, 2.0);
    ASSERT_EQ(rgb.channels, 3);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(rgb.at(0, 0, c), 0.5f);
        EXPECT_EQ(rgb.at(1, 0, c), 2.0f);
    }
}

TEST(DisplayImages, WhiteBalancedSourceWhiteBecomesUnitRgb) {
    // A pixel equal to the light's own white (here A) is shown as sRGB white after Bradford white balance.
    Image xyz(1, 1, 3);
    for (int c = 0; c < 3; ++c) xyz.at(0, 0, c) = static_cast<float>(kWhiteA[c]);
    const Image rgb = xyz_image_to_linear_srgb(xyz, kWhiteA, true, 1.0);
    // float storage (6e-8) on top of the 1.7e-4 matrix/white mismatch of the sRGB standard.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb.at(0, 0, c), 1.0, 2e-4) << "channel " << c;
    // Without white balance the cast stays: A is reddish, so R > B.
    const Image cast = xyz_image_to_linear_srgb(xyz, kWhiteA, false, 1.0);
    EXPECT_GT(cast.at(0, 0, 0), cast.at(0, 0, 2));
}

}  // namespace
}  // namespace petroscope
