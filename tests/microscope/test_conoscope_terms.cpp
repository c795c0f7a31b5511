// The thickness-independent interference terms that fitting uses must reproduce the figure's transmission
// at every thickness: T(d) = mean + modulation·cos(phase_per_um·d) (+ sine_modulation·sin(phase_per_um·d) for an
// optically active crystal) against conoscope_point_transmission,
// which evaluates each thickness on its own (vectorised kernel, reference path where it flags samples).
#include "conoscope_fixtures.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

struct TermsCase {
    const char* mineral;
    Cut cut;
    double tilt_deg;
    bool analyzer_in;
    bool optically_active = false;  // with the mineral's gyration: the sine term of InterferenceTerms
};

class ConoscopeTermsTest : public ::testing::TestWithParam<TermsCase> {};

TEST_P(ConoscopeTermsTest, ReproduceTransmissionAtEveryThickness) {
    const TermsCase& c = GetParam();
    const Mineral& mineral = testing::repository_minerals().find(c.mineral);
    ConoscopeSettings settings = testing::figure_settings(mineral, c.cut, 1.0, 64);
    settings.crystal_axes = cut_orientation(c.cut, mineral.optical_class, mineral.principal_n(mineral.reference_wavelength_nm), 30.0, c.tilt_deg);
    settings.wavelengths_nm = {400.0, 486.1, 550.0, 656.3, 700.0};
    settings.analyzer_in = c.analyzer_in;
    settings.polarizer_deg = 10.0;
    settings.analyzer_deg = 100.0;
    if (c.optically_active) settings.gyration = mineral_gyration(mineral, Handedness::left);
    const PrincipalIndexFunction indices = testing::indices_of(mineral);
    // A row of neighbouring directions (warm starts) plus the axis and points near the edge of the field.
    std::vector<Eigen::Vector2d> xis;
    for (int k = 0; k < 12; ++k) xis.emplace_back(-0.8 + 0.13 * k, 0.05 * k - 0.3);
    xis.emplace_back(0.0, 0.0);
    xis.emplace_back(0.84, 0.0);
    const ConoscopeTerms terms(settings, indices);
    std::vector<InterferenceTerms> values;
    terms.evaluate(xis, values);
    ASSERT_EQ(values.size(), xis.size() * settings.wavelengths_nm.size());
    for (const double thickness_um : {0.7, 30.0, 412.5, 2000.0}) {
        settings.thickness_um = thickness_um;
        for (std::size_t k = 0; k < xis.size(); ++k) {
            const std::vector<double> expected = conoscope_point_transmission(settings, indices, xis[k]);
            for (std::size_t w = 0; w < expected.size(); ++w) {
                // Phase error grows with d: |Δφ| ≲ 1e-12·φ, so 1e-9 covers 2 mm (φ ≈ 10⁴ rad for calcite).
                EXPECT_NEAR(values[k * expected.size() + w].transmission(thickness_um), expected[w], 1e-9)
                    << c.mineral << " d = " << thickness_um << " um, xi = (" << xis[k].transpose() << "), w = " << w;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Minerals, ConoscopeTermsTest,
                         ::testing::Values(TermsCase{"calcite", Cut::optic_axis, 0.0, true}, TermsCase{"calcite", Cut::optic_axis, 25.0, false},
                                           TermsCase{"quartz", Cut::optic_axis, 10.0, true},
                                           TermsCase{"quartz", Cut::optic_axis, 10.0, true, true},
                                           TermsCase{"quartz", Cut::optic_axis, 0.0, false, true},
                                           TermsCase{"muscovite", Cut::acute_bisectrix, 0.0, true},
                                           TermsCase{"forsterite", Cut::acute_bisectrix, 15.0, false}));

TEST(ConoscopeTerms, RefuseAPlate) {
    const Mineral& mineral = testing::repository_minerals().find("calcite");
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, 30.0, 64);
    settings.plate = make_accessory_plate(PlateKind::gypsum, testing::repository_minerals().find("gypsum"), 45.0);
    EXPECT_THROW(ConoscopeTerms(settings, testing::indices_of(mineral)), InputError);
}

}  // namespace
}  // namespace petroscope
