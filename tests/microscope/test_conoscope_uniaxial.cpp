// Uniaxial optic-axis figures against the analytic isochromes and the dark cross.
#include "conoscope_fixtures.hpp"
#include "figure_measurements.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

// Optic axis along z (Born & Wolf §15.3.3): o wave q_o = √(ω² − ξ²); e wave on ξ²/ε² + q²/ω² = 1,
// q_e = (ω/ε)√(ε² − ξ²). Dark isochromes where d·|q_o − q_e| = mλ.
std::vector<double> analytic_dark_ring_xi(double n_o, double n_e, double thickness_um, double wavelength_nm, double xi_max) {
    const auto path_difference_nm = [&](double xi) {
        return thickness_um * 1e3 * std::abs(std::sqrt(n_o * n_o - xi * xi) - n_o / n_e * std::sqrt(n_e * n_e - xi * xi));
    };
    std::vector<double> radii;
    for (int order = 1;; ++order) {
        const double target = order * wavelength_nm;
        if (path_difference_nm(xi_max) < target) break;
        double low = 0.0, high = xi_max;  // the path difference grows monotonically with ξ
        for (int i = 0; i < 200; ++i) {
            const double middle = 0.5 * (low + high);
            (path_difference_nm(middle) < target ? low : high) = middle;
        }
        radii.push_back(0.5 * (low + high));
    }
    return radii;
}

void expect_rings_at_analytic_radii(const std::string& name, double thickness_um) {
    const Mineral& mineral = testing::repository_minerals().find(name);
    const int size = 1024;
    const ConoscopeSettings settings = testing::figure_settings(mineral, Cut::optic_axis, thickness_um, size);
    const Image figure = render_conoscope(settings, testing::indices_of(mineral), nullptr);
    const Eigen::Vector3d n = mineral.principal_n(589.3);
    // Only rings well inside the field: the last pixels are cut by the aperture.
    const double xi_max = 0.97 * settings.numerical_aperture;
    const std::vector<double> expected_xi = analytic_dark_ring_xi(n[0], n[2], thickness_um, 589.3, xi_max);
    ASSERT_GE(expected_xi.size(), 2u) << name;
    for (const int sign : {+1, -1}) {
        std::vector<double> measured;
        for (const double k : testing::profile_minima(testing::diagonal_profile(figure, sign), 0.02)) {
            const double radius_px = std::sqrt(2.0) * (k + 0.5);
            if (radius_px < 0.97 * size / 2) measured.push_back(radius_px);
        }
        ASSERT_EQ(measured.size(), expected_xi.size()) << name;
        double worst = 0.0;
        for (std::size_t m = 0; m < measured.size(); ++m) {
            const double expected_px = expected_xi[m] / settings.numerical_aperture * size / 2;
            EXPECT_NEAR(measured[m], expected_px, 0.5) << name << " ring " << m + 1;
            worst = std::max(worst, std::abs(measured[m] - expected_px));
        }
        std::printf("%s %.0f um: %zu dark rings, largest radius error %.3f px at 1024^2\n", name.c_str(), thickness_um,
                    measured.size(), worst);
    }
}

TEST(ConoscopeUniaxial, Calcite30umDarkRingsAtAnalyticRadii) { expect_rings_at_analytic_radii("calcite", 30.0); }
TEST(ConoscopeUniaxial, Quartz1mmDarkRingsAtAnalyticRadii) { expect_rings_at_analytic_radii("quartz", 1000.0); }

TEST(ConoscopeUniaxial, DarkCrossLiesAlongPolarizerAndAnalyzer) {
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    for (const double polarizer_deg : {0.0, 30.0}) {
        ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 30.0, 512);
        settings.polarizer_deg = polarizer_deg;
        settings.analyzer_deg = polarizer_deg + 90.0;
        const double p = polarizer_deg * M_PI / 180.0;
        for (double t = -0.84; t <= 0.84; t += 0.01) {
            // On the polarizer and analyzer directions the e and o waves are exactly p and s: no light.
            for (const Eigen::Vector2d& xi : {Eigen::Vector2d(t * std::cos(p), t * std::sin(p)), Eigen::Vector2d(-t * std::sin(p), t * std::cos(p))}) {
                EXPECT_LT(conoscope_point_transmission(settings, testing::indices_of(calcite), xi)[0], 1e-24);
            }
        }
        // And the arms are dark on the image while the diagonals are not.
        const Image figure = render_conoscope(settings, testing::indices_of(calcite), nullptr);
        double arms = 0.0, diagonals = 0.0;
        for (double radius = 50; radius < 240; radius += 1.0) {
            const double c = 256.0, cp = std::cos(p), sp = std::sin(p);
            arms += testing::sample_bilinear(figure, c + radius * cp, c - radius * sp);
            diagonals += testing::sample_bilinear(figure, c + radius * std::cos(p + M_PI / 4), c - radius * std::sin(p + M_PI / 4));
        }
        EXPECT_LT(arms, 0.01 * diagonals);
    }
}

TEST(ConoscopeUniaxial, ImageFrameIsNorthUpEastRightAndAzimuthCounterClockwise) {
    // docs/conventions.md: the optic axis tilted toward azimuth φ exits at azimuth φ on the image, with
    // φ = 0 to the right (East) and φ = 90° up (North).
    const Mineral& calcite = testing::repository_minerals().find("calcite");
    const Eigen::Vector3d n = calcite.principal_n(589.3);
    for (const double azimuth : {0.0, 90.0, 200.0}) {
        ConoscopeSettings settings = testing::figure_settings(calcite, Cut::optic_axis, 5.0, 256);
        settings.crystal_axes = cut_orientation(Cut::optic_axis, OpticalClass::uniaxial, n, azimuth, 15.0);
        const Image map = testing::retardation_map(settings, testing::indices_of(calcite));
        // Where the optic axis leaves the slab: the darkest point of the retardation map over the field.
        Eigen::Vector2d guess(128.0, 128.0);
        float darkest = 1e30f;
        for (int y = 8; y < 248; ++y) {
            for (int x = 8; x < 248; ++x) {
                const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, x, y);
                if (xi.norm() < 0.9 * settings.numerical_aperture && map.at(x, y, 0) < darkest) {
                    darkest = map.at(x, y, 0);
                    guess = {x, y};
                }
            }
        }
        const Eigen::Vector2d found = testing::darkest_point(map, guess, 2);
        const double measured = std::atan2(found.y(), found.x()) * 180.0 / M_PI;
        EXPECT_NEAR(std::remainder(measured - azimuth, 360.0), 0.0, 1.0) << azimuth;
        EXPECT_GT(found.norm(), 10.0);
    }
}

}  // namespace
}  // namespace petroscope
