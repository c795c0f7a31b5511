// The conoscope through the whole thin-section stack (air, slide glass, balsam, crystal, balsam, cover
// glass, air) against the fast slab-in-balsam model. The glass and balsam layers are isotropic: they change
// each ray's s and p amplitudes by real Fresnel factors but add no retardation, so the dark isochromes
// (d·|q_o − q_e| = mλ) stay where they are, and on the polarizer and analyzer lines (pure s or p rays) the
// isogyres stay dark.
#include "conoscope_fixtures.hpp"

#include "petroscope/microscope/orthoscope.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

/// Local minima of a profile (strict on one side), by index.
std::vector<int> minima(const std::vector<double>& profile) {
    std::vector<int> found;
    for (std::size_t k = 1; k + 1 < profile.size(); ++k) {
        if (profile[k] < profile[k - 1] && profile[k] <= profile[k + 1]) found.push_back(static_cast<int>(k));
    }
    return found;
}

TEST(ConoscopeStack, IsochromesAndIsogyresStayWhereTheSlabModelPutsThem) {
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 30.0, 129);
    const Image slab = render_conoscope(settings, testing::indices_of(calcite), nullptr);
    settings.mounting = standard_mounting(testing::repository_minerals());
    const Image stack = render_conoscope(settings, testing::indices_of(calcite), nullptr);

    for (const int sign : {+1, -1}) {
        const std::vector<double> slab_profile = testing::diagonal_profile(slab, sign);
        const std::vector<double> stack_profile = testing::diagonal_profile(stack, sign);
        const std::vector<int> slab_minima = minima(slab_profile);
        EXPECT_GE(slab_minima.size(), 3u);
        EXPECT_EQ(minima(stack_profile), slab_minima);
        // Away from the dark rings the stack only loses light to the air–glass faces (4 faces, ≈ 0.92 near
        // the axis, less toward the edge of the field).
        for (std::size_t k = 0; k < slab_profile.size(); ++k) {
            if (slab_profile[k] < 0.05) continue;
            const double ratio = stack_profile[k] / slab_profile[k];
            EXPECT_GT(ratio, 0.80) << k;
            EXPECT_LT(ratio, 0.93) << k;
        }
    }
    // The isogyres: on the E–W and N–S lines through the centre (row and column 64 of 129) the rays are pure
    // p or s, eigenwaves of every layer: nothing reaches the crossed analyzer.
    for (int k = 0; k < 129; ++k) {
        EXPECT_LT(stack.at(k, 64, 0), 1e-12f) << k;
        EXPECT_LT(stack.at(64, k, 0), 1e-12f) << k;
    }
}

// Exact (coherent 4×4) against single pass through the whole stack, averaged over a 10 nm band (the 1.2 mm of
// glass between the two air faces makes fringes 0.08 nm apart). The exact result adds the light reflected back
// and forth between the air faces, (1 − R)²/(1 − R²) against (1 − R)²: a factor 1/(1 − R²) ≈ 1.0018 for
// R = ((1.517 − 1)/(1.517 + 1))². The glass–balsam and balsam–crystal faces (R ≈ 6e-5) form thinner cavities
// whose fringes (about 2.5 nm apart) the band averages only partly: measured 1.00201 on the axis and 1.00180
// at ξ = (0.2, 0.1), against 1.00178.
TEST(ConoscopeStack, ExactAddsTheAirFaceReflectionsToSinglePass) {
    const Mineral& quartz = testing::repository_minerals().find("quartz");
    const SectionMounting mounting = standard_mounting(testing::repository_minerals());
    DispersiveMedium crystal = DispersiveMedium::of(quartz, cut_orientation(Cut::optic_axis, OpticalClass::uniaxial, quartz.principal_n(589.3), 0.0, 0.0));
    MicroscopeSettings settings;
    settings.polars.analyzer_deg = 0.0;  // parallel polars: every ray carries light
    for (double wavelength = 545.0; wavelength < 555.0; wavelength += 0.02) settings.wavelengths_nm.push_back(wavelength);
    const double r = std::pow((1.5168 - 1.0) / (1.5168 + 1.0), 2);
    for (const Eigen::Vector2d& xi : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.2, 0.1)}) {
        std::vector<double> single, exact;
        settings.exact = false;
        GrainResponse(MicroscopeOptics(settings, mounting, {IlluminationSample{xi, 1.0}}), crystal).transmission(30.0, single);
        settings.exact = true;
        GrainResponse(MicroscopeOptics(settings, mounting, {IlluminationSample{xi, 1.0}}), crystal).transmission(30.0, exact);
        double single_mean = 0.0, exact_mean = 0.0;
        for (std::size_t w = 0; w < single.size(); ++w) {
            single_mean += single[w] / static_cast<double>(single.size());
            exact_mean += exact[w] / static_cast<double>(exact.size());
        }
        EXPECT_NEAR(exact_mean / single_mean, 1.0 / (1.0 - r * r), 3e-4) << xi.transpose();
    }
}

}  // namespace
}  // namespace petroscope
