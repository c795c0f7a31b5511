// The condenser cone: its cubature against the exact moments of the disc, the automatic choice of rings
// against a dense reference in white light, and the thickness series of a grain against direct evaluation.
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace petroscope {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog instance = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return instance;
}

// The mean of x^a·y^b over the unit disc: zero unless a and b are even, else
// (1/π)·∫₀¹ r^(a+b+1) dr·∮ cos^a sin^b dφ = 2·Γ((a+1)/2)·Γ((b+1)/2) / (π·(a + b + 2)·Γ((a+b)/2 + 1)).
double disc_mean(int a, int b) {
    if (a % 2 != 0 || b % 2 != 0) return 0.0;
    return 2.0 * std::tgamma((a + 1) / 2.0) * std::tgamma((b + 1) / 2.0) / (std::numbers::pi * (a + b + 2) * std::tgamma((a + b) / 2.0 + 1.0));
}

double cubature_mean(const std::vector<IlluminationSample>& samples, double na, int a, int b) {
    double sum = 0.0;
    for (const IlluminationSample& sample : samples) sum += sample.weight * std::pow(sample.xi.x() / na, a) * std::pow(sample.xi.y() / na, b);
    return sum;
}

// Every monomial up to degree 4·rings + 1 is averaged exactly; |ξ|^(4·rings + 2) is not (the degree is sharp).
TEST(CondenserCubature, ExactForPolynomialsUpToItsDegree) {
    const double na = 0.7;
    for (int rings = 1; rings <= 6; ++rings) {
        const std::vector<IlluminationSample> samples = condenser_samples(na, rings);
        ASSERT_EQ(samples.size(), static_cast<std::size_t>(1 + rings * (4 * rings + 2)));
        double worst = 0.0;
        for (const IlluminationSample& sample : samples) EXPECT_GT(sample.weight, 0.0) << rings;
        for (int degree = 0; degree <= 4 * rings + 1; ++degree) {
            for (int a = 0; a <= degree; ++a) worst = std::max(worst, std::abs(cubature_mean(samples, na, a, degree - a) - disc_mean(a, degree - a)));
        }
        EXPECT_LT(worst, 1e-14) << rings;
        double radial = 0.0;  // mean of |ξ/NA|^(4·rings + 2) = 1/(2·rings + 2)
        for (const IlluminationSample& sample : samples) radial += sample.weight * std::pow((sample.xi / na).squaredNorm(), 2 * rings + 1);
        EXPECT_GT(std::abs(radial - 1.0 / (2 * rings + 2)), 1e-10) << rings;
        std::printf("rings %d: %zu directions, worst moment error %.1e\n", rings, samples.size(), worst);
    }
}

struct WhiteLight {  // a 10 nm grid: both renders of a comparison share it
    std::vector<double> wavelengths_nm = WavelengthGrid{380.0, 780.0, 10.0}.wavelengths_nm();
    SpectralIntegrator integrator{wavelengths_nm, load_cie_1931_observer(), load_light_source("D65")};
};

// The automatic rings against 4 more: a random 30 µm section of the commonest birefringent rock-forming
// minerals (biotite and muscovite up to B ≈ 0.05), wide cones, in white light. The tolerance is the one of the
// white-light kernel's spectral nodes (max ΔE00 0.3 over the image).
TEST(CondenserCubature, AutomaticRingsMatchADenseReference) {
    ThinSection section = random_voronoi_section({"quartz", "biotite", "muscovite", "forsterite", "augite"}, {}, 8, 32, 4.0, 30.0, 3);
    section.validate();
    const WhiteLight light;
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = light.wavelengths_nm;
    settings.mounting = standard_mounting(catalog());
    for (const double na : {0.3, 0.6, 0.9}) {
        settings.microscope.condenser_na = na;
        settings.microscope.condenser_rings = 0;
        const int automatic = section_condenser_rings(section, catalog(), settings.microscope);
        const Image image = render_orthoscope(section, catalog(), settings, &light.integrator);
        settings.microscope.condenser_rings = automatic + 4;
        const Image reference = render_orthoscope(section, catalog(), settings, &light.integrator);
        double worst = 0.0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                const Eigen::Vector3d xyz(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
                const Eigen::Vector3d expected(reference.at(x, y, 0), reference.at(x, y, 1), reference.at(x, y, 2));
                const Eigen::Vector3d white = light.integrator.white_xyz();
                worst = std::max(worst, delta_e_2000(xyz_to_lab(xyz, white), xyz_to_lab(expected, white)));
            }
        }
        std::printf("NA %.1f: %d rings automatic, max dE00 %.3f against %d rings\n", na, automatic, worst, automatic + 4);
        EXPECT_LT(worst, 0.3) << na;
    }
}

TEST(CondenserCubature, RingsFollowTheSettingsOrTheSection) {
    ThinSection section = random_voronoi_section({"quartz"}, {}, 4, 16, 4.0, 30.0, 1);
    section.validate();
    MicroscopeSettings microscope;
    microscope.wavelengths_nm = {400.0, 700.0};
    EXPECT_EQ(section_condenser_rings(section, catalog(), microscope), 0);  // parallel light
    microscope.condenser_na = 0.9;
    microscope.condenser_rings = 5;
    EXPECT_EQ(section_condenser_rings(section, catalog(), microscope), 5);
    microscope.condenser_rings = 0;
    const int thin = section_condenser_rings(section, catalog(), microscope);
    section.thickness_um = 300.0;  // ten times the phase spread
    EXPECT_GT(section_condenser_rings(section, catalog(), microscope), thin);
    EXPECT_THROW(MicroscopeOptics(microscope, SectionMounting{}), std::logic_error);  // automatic, never resolved
}

// The thickness series (one complex product per term and step) against direct evaluation: an absorbing biaxial
// crystal (biotite) turned obliquely, in a cone, over 2000 steps.
TEST(GrainResponse, ThicknessSeriesMatchesDirectEvaluation) {
    MicroscopeSettings microscope;
    microscope.wavelengths_nm = {420.0, 550.0, 680.0};
    microscope.condenser_na = 0.5;
    microscope.condenser_rings = 2;
    const SectionMounting mounting = standard_mounting(catalog());
    const MicroscopeOptics optics(microscope, mounting);
    const GrainResponse response(optics, DispersiveMedium::of(catalog().find("biotite"), euler_zyz_deg(30.0, 50.0, -20.0)));
    const double first_um = 3.0, step_um = 0.05;
    double worst = 0.0, brightest = 0.0;
    std::vector<double> direct;
    response.transmission_series(first_um, step_um, 2000, [&](int k, const std::vector<double>& series) {
        response.transmission(first_um + k * step_um, direct);
        for (std::size_t w = 0; w < direct.size(); ++w) {
            worst = std::max(worst, std::abs(series[w] - direct[w]));
            brightest = std::max(brightest, direct[w]);
        }
    });
    EXPECT_GT(brightest, 1e-3);
    EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace petroscope
