// Orthoscopic renders of small sections against the Michel-Lévy chart and the physics of extinction
// (issue 4's acceptance): interference colours, the gypsum plate's addition and subtraction, isotropic
// grains dark between crossed polars, extinction every 90° of stage rotation.
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/michel_levy.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog instance = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return instance;
}

/// A section of `size`² pixels, one grain per vertical strip, each strip `size`/count wide.
ThinSection strips(const std::vector<std::pair<std::string, Eigen::Matrix3d>>& grains, double thickness_um, int size = 32) {
    ThinSection section;
    section.name = "strips";
    section.width_px = section.height_px = size;
    section.thickness_um = thickness_um;
    section.labels.resize(static_cast<std::size_t>(size) * size);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            section.labels[static_cast<std::size_t>(y) * size + x] = static_cast<std::uint16_t>(1 + x * grains.size() / size);
        }
    }
    for (std::size_t k = 0; k < grains.size(); ++k) {
        ThinSectionGrain grain;
        grain.label = static_cast<int>(k + 1);
        grain.mineral = catalog().find(grains[k].first).name;
        grain.crystal_axes = grains[k].second;
        section.grains.push_back(grain);
    }
    section.validate();
    return section;
}

struct WhiteLight {
    std::vector<double> wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    SpectralIntegrator integrator{wavelengths_nm, load_cie_1931_observer(), load_light_source("D65")};
    Eigen::Vector3d lab(const Eigen::Vector3d& xyz) const { return xyz_to_lab(xyz, integrator.white_xyz()); }
};

Eigen::Vector3d pixel_xyz(const Image& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }

/// c in the section plane, at `azimuth_deg` from E toward N.
Eigen::Matrix3d c_in_plane(const std::string& mineral, double azimuth_deg) {
    const Mineral& record = catalog().find(mineral);
    return cut_orientation(Cut::optic_normal, record.optical_class, record.principal_n(record.reference_wavelength_nm), azimuth_deg, 0.0);
}

// Quartz with c in the section at 45°, 30 µm: Γ = (n_e − n_o)·d ≈ 275 nm at 550 nm (white of the first order),
// and the render matches the chart at that Γ. Γ is measured from the render: the chart entry of least ΔE00.
// The chart carries quartz's own dispersion of birefringence (against the dispersion-free classic chart the
// best match moves to 280 nm and ΔE00 at 275 nm is 1.7: quartz's Δn grows toward the blue).
TEST(Orthoscope, QuartzAt30MicronsMatchesTheChart) {
    const WhiteLight light;
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = light.wavelengths_nm;
    settings.mounting = standard_mounting(catalog());
    const Image image = render_orthoscope(strips({{"quartz", c_in_plane("quartz", 45.0)}}, 30.0), catalog(), settings, &light.integrator);
    const Eigen::Vector3d grain_lab = light.lab(pixel_xyz(image, 16, 16));

    MichelLevySettings chart;
    chart.wavelengths_nm = light.wavelengths_nm;
    chart.max_retardation_nm = 1000.0;
    chart.mineral = &catalog().find("quartz");
    const std::vector<MichelLevyStep> steps = michel_levy_colours(chart, settings.mounting, light.integrator);
    double best_difference = 1e9, best_retardation = -1.0;
    for (const MichelLevyStep& step : steps) {
        const double difference = delta_e_2000(grain_lab, light.lab(step.xyz));
        if (difference < best_difference) {
            best_difference = difference;
            best_retardation = step.retardation_nm;
        }
    }
    EXPECT_NEAR(best_retardation, 270.0, 5.0);
    const Eigen::Vector3d n = catalog().find("quartz").principal_n(550.0);
    const double quartz_retardation_nm = (n[2] - n[0]) * 30.0e3;
    EXPECT_NEAR(quartz_retardation_nm, 270.0, 5.0);
    const auto& at_quartz = steps[static_cast<std::size_t>(std::lround(quartz_retardation_nm))];
    EXPECT_LT(delta_e_2000(grain_lab, light.lab(at_quartz.xyz)), 1.0);
}

// The gypsum plate (Γ_plate = 550 nm, slow NE–SW): a grain whose slow direction is parallel to the plate's shows
// the chart's colour at Γ + 550; crossed, at |Γ − 550|. The plate's own surfaces reflect about 8% (it stands
// in air); the chart's retarder is lossless, so the render is compared after dividing by the plate's
// transmission, measured on the balsam-only strip with the analyzer out. The chart is the classic
// dispersion-free one (the gypsum record's birefringence has no dispersion; quartz's is small).
TEST(Orthoscope, GypsumPlateAddsAndSubtracts) {
    const WhiteLight light;
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = light.wavelengths_nm;
    settings.mounting = standard_mounting(catalog());
    // Quartz is positive: c (the e vibration) is its slow direction. Strip 1: c NE–SW; strip 2: c NW–SE;
    // strip 3: balsam only.
    const ThinSection section = strips({{"quartz", c_in_plane("quartz", 45.0)}, {"quartz", c_in_plane("quartz", 135.0)},
                                        {"canada balsam", Eigen::Matrix3d::Identity()}},
                                       30.0, 48);
    settings.microscope.polars.analyzer_in = false;
    const double without_plate = render_orthoscope(section, catalog(), settings, &light.integrator).at(40, 24, 1);
    settings.microscope.plate = make_accessory_plate(PlateKind::gypsum, catalog().find("gypsum"), 45.0);
    const double plate_transmission = render_orthoscope(section, catalog(), settings, &light.integrator).at(40, 24, 1) / without_plate;
    EXPECT_NEAR(plate_transmission, 0.92, 0.01);  // (1 − R)², R = ((1.52 − 1)/(1.52 + 1))² per face
    settings.microscope.polars.analyzer_in = true;
    const Image image = render_orthoscope(section, catalog(), settings, &light.integrator);

    MichelLevySettings chart;
    chart.wavelengths_nm = light.wavelengths_nm;
    chart.max_retardation_nm = 1000.0;
    const std::vector<MichelLevyStep> steps = michel_levy_colours(chart, settings.mounting, light.integrator);
    const Eigen::Vector3d n = catalog().find("quartz").principal_n(550.0);
    const double quartz_retardation_nm = (n[2] - n[0]) * 30.0e3;
    const auto chart_lab = [&](double retardation_nm) { return light.lab(steps[static_cast<std::size_t>(std::lround(retardation_nm))].xyz); };
    const auto render_lab = [&](int x) { return light.lab(pixel_xyz(image, x, 24) / plate_transmission); };
    EXPECT_LT(delta_e_2000(render_lab(8), chart_lab(quartz_retardation_nm + 550.0)), 2.0);
    EXPECT_LT(delta_e_2000(render_lab(24), chart_lab(std::abs(quartz_retardation_nm - 550.0))), 2.0);
    EXPECT_LT(delta_e_2000(render_lab(40), chart_lab(550.0)), 2.0);
}

// Isotropic grains (almandine, basaltic glass, balsam-like) stay below 1e-6 of the parallel-polar
// transmission at every stage angle.
TEST(Orthoscope, IsotropicGrainsStayDarkBetweenCrossedPolars) {
    const WhiteLight light;
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = light.wavelengths_nm;
    settings.mounting = standard_mounting(catalog());
    const ThinSection section = strips({{"almandine", euler_zyz_deg(10, 20, 30)}, {"crown glass", Eigen::Matrix3d::Identity()}}, 30.0);
    for (double stage = 0.0; stage < 360.0; stage += 30.0) {
        settings.microscope.stage_deg = stage;
        settings.microscope.polars.analyzer_deg = 90.0;
        const Image crossed = render_orthoscope(section, catalog(), settings, &light.integrator);
        settings.microscope.polars.analyzer_deg = 0.0;
        const Image parallel = render_orthoscope(section, catalog(), settings, &light.integrator);
        for (const int x : {8, 24}) EXPECT_LT(crossed.at(x, 16, 1), 1e-6 * parallel.at(x, 16, 1)) << stage;
    }
}

// Anisotropic grains go extinct every 90° of stage rotation, at the angle where a vibration direction of the
// indicatrix section (the principal axes of the xy block of ε⁻¹) reaches the polarizer, and are brightest 45°
// from there. Measured on monochromatic renders of a randomly oriented biaxial grain, stage in 1° steps.
TEST(Orthoscope, AnisotropicGrainGoesExtinctEvery90Degrees) {
    const Mineral& olivine = catalog().find("forsterite");
    const Eigen::Matrix3d axes = euler_zyz_deg(23.0, 67.0, 41.0);
    const ThinSection section = strips({{"forsterite", axes}}, 30.0, 16);
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = {589.3};
    settings.mounting = standard_mounting(catalog());
    std::vector<double> brightness;
    for (int stage = 0; stage < 360; ++stage) {
        settings.microscope.stage_deg = stage;
        brightness.push_back(render_orthoscope(section, catalog(), settings, nullptr).at(8, 8, 0));
    }
    const Eigen::Vector3d n = olivine.principal_n(589.3);
    const Eigen::Matrix2d section_block = (axes * n.cwiseInverse().cwiseAbs2().asDiagonal() * axes.transpose()).topLeftCorner<2, 2>();
    const double vibration_deg = 0.5 * std::atan2(2.0 * section_block(0, 1), section_block(0, 0) - section_block(1, 1)) * 180.0 / M_PI;
    const double maximum = *std::max_element(brightness.begin(), brightness.end());
    for (int k = 0; k < 4; ++k) {
        // Predicted extinction: stage = −vibration + 90k (mod 360); the nearest whole degree is within 0.5°.
        const double predicted = std::fmod(-vibration_deg + 90.0 * k + 720.0, 360.0);
        const int nearest = static_cast<int>(std::lround(predicted)) % 360;
        EXPECT_LT(brightness[static_cast<std::size_t>(nearest)], 2e-3 * maximum) << predicted;
        const int brightest = static_cast<int>(std::lround(predicted + 45.0)) % 360;
        EXPECT_GT(brightness[static_cast<std::size_t>(brightest)], 0.99 * maximum) << predicted;
    }
    // Every local minimum of the sweep lies at a predicted extinction.
    for (int stage = 0; stage < 360; ++stage) {
        const double here = brightness[static_cast<std::size_t>(stage)];
        if (here <= brightness[static_cast<std::size_t>((stage + 359) % 360)] && here <= brightness[static_cast<std::size_t>((stage + 1) % 360)]) {
            const double offset = std::remainder(stage + vibration_deg, 90.0);
            EXPECT_LT(std::abs(offset), 1.0) << stage;
        }
    }
}

// A thickness wedge: the table interpolation reproduces the directly computed transmission.
TEST(Orthoscope, WedgeInterpolationMatchesDirectEvaluation) {
    ThinSection section = strips({{"calcite", c_in_plane("calcite", 30.0)}}, 30.0, 64);
    section.thickness_kind = ThicknessKind::wedge;
    section.wedge_start_um = 0.0;
    section.wedge_end_um = 40.0;
    OrthoscopeSettings settings;
    settings.microscope.wavelengths_nm = {550.0};
    settings.mounting = standard_mounting(catalog());
    const Image image = render_orthoscope(section, catalog(), settings, nullptr);
    const MicroscopeOptics optics(settings.microscope, settings.mounting);
    const GrainResponse response(optics, DispersiveMedium::of(catalog().find("calcite"), section.grains[0].crystal_axes));
    std::vector<double> direct;
    double worst = 0.0;
    for (int x = 0; x < 64; ++x) {
        response.transmission(section.section_thickness_at(x, 10), direct);
        worst = std::max(worst, std::abs(image.at(x, 10, 0) - direct[0]));
    }
    EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace petroscope
