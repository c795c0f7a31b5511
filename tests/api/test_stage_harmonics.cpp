// The stage harmonics (api/stage_harmonics.hpp) against direct renders at the same stage angle, and a grain's
// numbers (api/grain_optics.hpp) against closed forms and the extinction they predict.
#include "api_testing.hpp"

#include "petroscope/api/crystal_orientation.hpp"
#include "petroscope/api/grain_optics.hpp"
#include "petroscope/api/stage_harmonics.hpp"
#include "petroscope/core/angles.hpp"
#include "petroscope/optics/eigenmodes.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>

namespace petroscope {
namespace {

double largest_difference(const Image& a, const Image& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double largest = 0.0;
    for (std::size_t k = 0; k < std::min(a.pixels.size(), b.pixels.size()); ++k) largest = std::max(largest, std::fabs(double(a.pixels[k]) - b.pixels[k]));
    return largest;
}

ThinSection small_section() {
    ThinSection section = random_voronoi_section({"quartz", "calcite", "muscovite"}, {}, 8, 48, 10.0, 30.0, 3);
    section.validate();
    return section;
}

OrthoscopeRequest section_request(std::optional<PlateRequest> plate, bool analyzer_in) {
    OrthoscopeRequest request;
    request.section = small_section();
    request.plate = plate;
    request.analyzer_in = analyzer_in;
    return request;
}

/// At each of `stages_deg`, the composed picture against `render` of the request turned to that stage.
template <typename Request, typename Render>
void expect_composed_is_rendered(const StageHarmonics& harmonics, const Request& request, std::initializer_list<double> stages_deg,
                                 const Render& render) {
    for (const double stage_deg : stages_deg) {
        Request turned = request;
        turned.stage_deg = stage_deg;
        EXPECT_LT(largest_difference(compose_at_stage(harmonics, stage_deg), render(turned)), 2e-6) << "stage " << stage_deg;
    }
}

// Composed at a stage angle none of the five renders used, with the corners of the turned section showing
// glass: the same picture as the render at that stage, for every arrangement of polars and plates.
TEST(StageHarmonics, OrthoscopeComposedAtAnyStageIsTheRenderAtThatStage) {
    const std::vector<OrthoscopeRequest> requests{section_request(std::nullopt, true), section_request(PlateRequest{PlateKind::gypsum}, true),
                                                  section_request(PlateRequest{PlateKind::mica, 30.0}, true), section_request(std::nullopt, false)};
    for (const OrthoscopeRequest& request : requests) {
        expect_composed_is_rendered(orthoscope_stage_harmonics(request, minerals()), request, {17.0, 90.0, 233.5}, [](const OrthoscopeRequest& turned) {
            return render_orthoscope_image(plan_orthoscope(turned, minerals())).image.linear_rgb;
        });
    }
}

// A wedge-shaped section in one wavelength: per-pixel thicknesses, and glass at the middle's thickness outside.
TEST(StageHarmonics, OrthoscopeOfAWedgeInOneWavelength) {
    OrthoscopeRequest request = section_request(std::nullopt, true);
    request.section.thickness_kind = ThicknessKind::wedge;
    request.section.wedge_start_um = 10.0;
    request.section.wedge_end_um = 60.0;
    request.light.wavelength_nm = 589.3;
    const StageHarmonics harmonics = orthoscope_stage_harmonics(request, minerals());
    request.stage_deg = 61.0;
    const Image direct = render_orthoscope_image(plan_orthoscope(request, minerals())).image.linear_rgb;
    // Each render tabulates a grain over the thicknesses in view, at most 1 nm of retardation apart, and
    // interpolates linearly: the tables of the two renders differ, each by up to (π·1 nm/λ)²/8 = 3.6e-6.
    EXPECT_LT(largest_difference(compose_at_stage(harmonics, 61.0), direct), 2 * 3.6e-6);
}

// A quarter turn maps pixel centres onto pixel centres: the bilinear composition is then the figure rendered
// with the crystal turned.
TEST(StageHarmonics, ConoscopeComposedAtQuarterTurnsIsTheRenderThere) {
    ConoscopeRequest request;
    request.mineral = "calcite";
    request.orientation.cut = Cut::optic_axis;
    request.orientation.tilt_deg = 12.0;
    request.orientation.azimuth_deg = 20.0;
    request.size_px = 64;
    request.plate = PlateRequest{PlateKind::gypsum};
    expect_composed_is_rendered(conoscope_stage_harmonics(request, minerals()), request, {90.0, 180.0, 270.0}, [](const ConoscopeRequest& turned) {
        return render_conoscope_figure(plan_conoscope(turned, minerals())).image.linear_rgb;
    });
}

// Unpolarized light and no analyzer: the eye sees ½·tr(J J†), which turning the crystal does not change
// (tr(R J Rᵀ R J† Rᵀ) = tr(J J†)), even with biotite's pleochroism; every stage harmonic but c₀ vanishes.
TEST(StageHarmonics, WithoutPolarizerAndAnalyzerNothingDependsOnTheStage) {
    OrthoscopeRequest request;
    request.section = random_voronoi_section({"biotite", "calcite", "quartz"}, {}, 8, 32, 10.0, 30.0, 5);
    request.section.validate();
    request.analyzer_in = false;
    const StageHarmonics harmonics = orthoscope_stage_harmonics(request, minerals(), Illumination::unpolarized);
    double largest_c0 = 0.0, largest_other = 0.0;
    for (std::size_t k = 0; k < harmonics.coefficients.pixels.size(); ++k) {
        const double value = std::fabs(harmonics.coefficients.pixels[k]);
        if (k % kStageHarmonicChannels < 3) largest_c0 = std::max(largest_c0, value);
        else largest_other = std::max(largest_other, value);
    }
    EXPECT_GT(largest_c0, 0.5);
    EXPECT_LT(largest_other, 1e-6);
}

TEST(StageHarmonics, ARequestWithAStageIsRefused) {
    ConoscopeRequest request;
    request.stage_deg = 10.0;
    expect_input_error([&] { conoscope_stage_harmonics(request, minerals()); }, "leave the request's stage at 0");
}

// Calcite with its optic axis in the section plane at 30° from E: the ordinary wave (ω > ε) is the slow one
// and vibrates ⟂ the axis, at 120°; retardation (ω − ε)·d.
TEST(GrainOptics, CalciteWithItsAxisInThePlane) {
    const Mineral& calcite = minerals().find("calcite");
    const Eigen::Matrix3d axes = indicatrix_axes(calcite, CrystalOrientation{Cut::optic_axis, 30.0, 90.0, std::nullopt});
    const GrainOptics optics = grain_optics(calcite, axes, 2.0, 589.3);
    const Eigen::Vector3d n = calcite.principal_n(589.3);
    EXPECT_NEAR(optics.n_slow, n[0], 1e-12);
    EXPECT_NEAR(optics.n_fast, n[2], 1e-12);
    EXPECT_NEAR(optics.retardation_nm, (n[0] - n[2]) * 2000.0, 1e-9);
    ASSERT_TRUE(optics.slow_azimuth_deg.has_value());
    EXPECT_NEAR(*optics.slow_azimuth_deg, 120.0, 1e-9);
    EXPECT_NEAR(*optics.extinction_stage_deg, 60.0, 1e-9);
    EXPECT_EQ(optics.mineral.sign, "-");
}

TEST(GrainOptics, ACrystalCutAcrossItsOpticAxisHasNoExtinctionPosition) {
    const Mineral& quartz = minerals().find("quartz");
    const GrainOptics optics = grain_optics(quartz, indicatrix_axes(quartz, CrystalOrientation{Cut::optic_axis}), 30.0, 555.0);
    EXPECT_NEAR(optics.retardation_nm, 0.0, 1e-9);
    EXPECT_FALSE(optics.slow_azimuth_deg.has_value());
    EXPECT_FALSE(optics.extinction_stage_deg.has_value());
}

// sin²2χ of the two waves of a grain along the microscope axis: the ellipticity its optical activity gives them.
// To first order in the gyration g, Landau's D = εE + i(g·N) × E adds iγ[[0, 1], [−1, 0]] to the transverse
// impermeability diag(a, b), a, b = 1/n², with γ = (k̂·g·k̂)/n³, so the waves are ellipses of tan 2χ = 2γ/(a − b)
// (Landau & Lifshitz vol. 8 §101; docs/theory.md §9). Zero for an inactive mineral.
double activity_ellipticity(const Mineral& mineral, const Eigen::Matrix3d& axes, double wavelength_nm) {
    const Eigen::Vector3d k_hat = axes.transpose() * Eigen::Vector3d::UnitZ();  // in the indicatrix frame
    const Eigen::Vector3d g = wavelength_nm * 1e-3 / std::numbers::pi * mineral.principal_rotatory_power(wavelength_nm);
    const Eigen::Vector2d inverse_squared = inverse_squared_indices(BinormalFrame(Indicatrix{mineral.principal_n(wavelength_nm), axes}), Eigen::Vector3d::UnitZ());
    const double n = 1.0 / std::sqrt(inverse_squared.mean());
    const double gamma = k_hat.dot(g.asDiagonal() * k_hat) / (n * n * n);
    const double tan_2chi = 2.0 * gamma / (inverse_squared[0] - inverse_squared[1]);
    return tan_2chi * tan_2chi / (1.0 + tan_2chi * tan_2chi);
}

// Every grain of a section between crossed polars in one wavelength: dark at the extinction stage that
// grain_optics gives, and 45° from it T·sin²(πΓ/λ) with its retardation Γ, where T, the transmission of the
// section's faces (glass, balsam, crystal: Fresnel losses of a few per cent), lies between 0.8 and 1. A
// quartz grain is optically active: its waves are slightly elliptical, and at extinction it keeps
// T·sin²2χ·sin²(πΓ/λ) (measured 1.5e-5 for a grain cut along its axis).
TEST(GrainOptics, EveryGrainIsDarkAtItsExtinctionStage) {
    constexpr double kWavelengthNm = 555.0;
    OrthoscopeRequest request = section_request(std::nullopt, true);
    request.light.wavelength_nm = kWavelengthNm;
    const StageHarmonics harmonics = orthoscope_stage_harmonics(request, minerals());
    const ThinSection& section = request.section;
    int grains_checked = 0, active_grains_checked = 0;
    for (const ThinSectionGrain& grain : section.grains) {
        const GrainOptics optics = grain_optics(minerals().find(grain.mineral), grain.crystal_axes, section.thickness_um, kWavelengthNm);
        const double interference = std::pow(std::sin(std::numbers::pi * optics.retardation_nm / kWavelengthNm), 2);
        if (interference < 0.05) continue;  // near an optic axis, or a whole number of waves: too dim to tell
        const auto brightest = [&](double stage_deg) {  // over the grain's pixels
            const double phi = stage_deg * kDegree;
            double largest = 0.0;
            for (std::size_t p = 0; p < section.labels.size(); ++p) {
                if (section.labels[p] != grain.label) continue;
                const float* c = &harmonics.coefficients.pixels[p * kStageHarmonicChannels];
                largest = std::max(largest, c[0] + c[3] * std::cos(2 * phi) + c[6] * std::sin(2 * phi) + c[9] * std::cos(4 * phi) + c[12] * std::sin(4 * phi));
            }
            return largest;
        };
        const double dark = brightest(*optics.extinction_stage_deg), bright = brightest(*optics.extinction_stage_deg + 45.0);
        const double leak = activity_ellipticity(minerals().find(grain.mineral), grain.crystal_axes, kWavelengthNm) * interference;
        EXPECT_LT(dark, 1e-6 + leak) << grain.mineral << " grain " << grain.label;
        if (leak > 1e-6) {
            EXPECT_GT(dark, 0.8 * leak) << grain.mineral << " grain " << grain.label;
            ++active_grains_checked;
        }
        EXPECT_GT(bright / interference, 0.8) << grain.mineral << " grain " << grain.label;
        EXPECT_LT(bright / interference, 1.0) << grain.mineral << " grain " << grain.label;
        ++grains_checked;
    }
    EXPECT_GE(grains_checked, 5);
    EXPECT_GE(active_grains_checked, 1);
}

}  // namespace
}  // namespace petroscope
