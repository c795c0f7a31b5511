// The thickness-independent interference terms that fitting uses must reproduce the figure's transmission
// at every thickness: T(d) = mean + modulation·cos(phase_per_um·d) (+ sine_modulation·sin(phase_per_um·d) for an
// optically active crystal) against conoscope_point_transmission,
// which evaluates each thickness on its own (vectorised kernel, reference path where it flags samples).
#include "conoscope_fixtures.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

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

// In white light the terms come from the spectral nodes where they can; they must match the terms solved at every
// wavelength within what the nodes' error bounds allow: 1e-4 in each term (so 3e-4 in a transmission) and 1e-3 rad in
// the phase at the thickest slab, settings.thickness_um.
struct NodeTermsCase {
    const char* mineral;
    Cut cut;
    double tilt_deg;
    double thickest_um;
    bool optically_active = false;
};

class ConoscopeNodeTermsTest : public ::testing::TestWithParam<NodeTermsCase> {};

TEST_P(ConoscopeNodeTermsTest, MatchEveryWavelengthSolvedUpToTheThickestSlab) {
    const NodeTermsCase& c = GetParam();
    const Mineral& mineral = testing::repository_minerals().find(c.mineral);
    ConoscopeSettings settings = testing::figure_settings(mineral, c.cut, c.thickest_um, 64);
    settings.crystal_axes = cut_orientation(c.cut, mineral.optical_class, mineral.principal_n(mineral.reference_wavelength_nm), 30.0, c.tilt_deg);
    settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    settings.polarizer_deg = 10.0;
    settings.analyzer_deg = 100.0;
    if (c.optically_active) settings.gyration = mineral_gyration(mineral, Handedness::right);
    const PrincipalIndexFunction indices = testing::indices_of(mineral);
    // A lattice over the field, row by row (warm starts), the axis included.
    std::vector<Eigen::Vector2d> xis;
    for (int row = -8; row <= 8; ++row) {
        for (int column = -8; column <= 8; ++column) {
            if (row * row + column * column <= 64) xis.emplace_back(0.1 * column, 0.1 * row);
        }
    }
    std::vector<InterferenceTerms> from_nodes, exact;
    std::vector<unsigned char> paths;
    ConoscopeTerms(settings, indices).evaluate(xis, from_nodes, &paths);
    ConoscopeSettings every_wavelength = settings;
    every_wavelength.spectrum = SpectrumSampling::exact;
    ConoscopeTerms(every_wavelength, indices).evaluate(xis, exact);
    const std::size_t interpolated = static_cast<std::size_t>(std::count(paths.begin(), paths.end(), 1));
    EXPECT_GT(interpolated, xis.size() / 2) << "most points come from the nodes";
    double worst = 0.0;
    for (const double thickness_um : {0.3 * c.thickest_um, c.thickest_um}) {
        for (std::size_t i = 0; i < exact.size(); ++i) {
            worst = std::max(worst, std::abs(from_nodes[i].transmission(thickness_um) - exact[i].transmission(thickness_um)));
        }
    }
    EXPECT_LT(worst, 1.3e-3) << c.mineral;
    std::printf("%s, thickest %.0f um: %zu of %zu points from the nodes, largest transmission difference %.2g\n", c.mineral, c.thickest_um,
                interpolated, xis.size(), worst);
}

INSTANTIATE_TEST_SUITE_P(Minerals, ConoscopeNodeTermsTest,
                         ::testing::Values(NodeTermsCase{"calcite", Cut::optic_axis, 0.0, 100.0}, NodeTermsCase{"calcite", Cut::optic_axis, 20.0, 10000.0},
                                           NodeTermsCase{"muscovite", Cut::acute_bisectrix, 0.0, 2000.0},
                                           NodeTermsCase{"aragonite", Cut::acute_bisectrix, 10.0, 10000.0},
                                           NodeTermsCase{"quartz", Cut::optic_axis, 0.0, 10000.0, true},
                                           NodeTermsCase{"quartz", Cut::optic_axis, 15.0, 2000.0, true}));

// Terms asked to come as before (for derivatives by differences) come exactly so: every point from the nodes where
// they did, every wavelength solved where not, the same numbers at the same directions.
TEST(ConoscopeTerms, TermsAsBeforeTakeTheSameWay) {
    const Mineral& mineral = testing::repository_minerals().find("calcite");
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, 10000.0, 64);
    settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const PrincipalIndexFunction indices = testing::indices_of(mineral);
    std::vector<Eigen::Vector2d> xis;
    for (int k = 0; k <= 40; ++k) xis.emplace_back(-0.8 + 0.04 * k, 0.0);
    const ConoscopeTerms terms(settings, indices);
    std::vector<InterferenceTerms> first, again, solved;
    std::vector<unsigned char> paths, none(xis.size(), 0);
    terms.evaluate(xis, first, &paths);
    ASSERT_GT(std::count(paths.begin(), paths.end(), 1), 0);
    ASSERT_GT(std::count(paths.begin(), paths.end(), 0), 0) << "the optic axis and the finest rings are solved at every wavelength";
    terms.evaluate(xis, again, nullptr, &paths);
    ConoscopeSettings every_wavelength = settings;
    every_wavelength.spectrum = SpectrumSampling::exact;
    ConoscopeTerms(every_wavelength, indices).evaluate(xis, solved);
    std::vector<InterferenceTerms> forced_exact;
    terms.evaluate(xis, forced_exact, nullptr, &none);
    for (std::size_t i = 0; i < first.size(); ++i) {
        EXPECT_EQ(first[i].transmission(10000.0), again[i].transmission(10000.0)) << i;
        EXPECT_EQ(forced_exact[i].transmission(10000.0), solved[i].transmission(10000.0)) << i;
    }
}

TEST(ConoscopeTerms, RefuseAPlate) {
    const Mineral& mineral = testing::repository_minerals().find("calcite");
    ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, 30.0, 64);
    settings.plate = make_accessory_plate(PlateKind::gypsum, testing::repository_minerals().find("gypsum"), 45.0);
    EXPECT_THROW(ConoscopeTerms(settings, testing::indices_of(mineral)), InputError);
}

}  // namespace
}  // namespace petroscope
