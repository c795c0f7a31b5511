// Numerical robustness (issue 9): 10⁵ random image points of random minerals, every one finite and within
// the physical bound. The cases reach for the edges: orientations with the optic axis (a binormal)
// exactly along the ray, thicknesses from 1 nm to 10 mm, NA up to 0.95 with points on the field's edge,
// wavelengths at the ends of each mineral's dispersion formulas, accessory plates at any angle.
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

/// The wavelengths (nm) where every axis of `mineral` has a valid formula: its ends, within 380–780 nm
/// where the validity reaches beyond.
std::array<double, 2> valid_ends_nm(const Mineral& mineral) {
    double low = 380.0, high = 780.0;
    for (const PrincipalAxis& axis : mineral.axes) {
        if (!axis.range_um) continue;
        low = std::max(low, 1000.0 * (*axis.range_um)[0]);
        high = std::min(high, 1000.0 * (*axis.range_um)[1]);
    }
    return {low, std::max(low, high)};
}

TEST(Robustness, RandomImagePointsAreFiniteAndWithinTheBound) {
    const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    const Mineral& gypsum = catalog.find("gypsum");
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    constexpr int kCases = 100000;
    int exact_axis = 0, plates = 0, violations = 0;
    double largest = 0.0;
    for (int k = 0; k < kCases; ++k) {
        const Mineral& mineral = catalog.minerals()[static_cast<std::size_t>(rng() % catalog.minerals().size())];
        ConoscopeSettings settings;
        settings.numerical_aperture = 0.05 + 0.9 * unit(rng);
        settings.thickness_um = std::pow(10.0, -3.0 + 7.0 * unit(rng));  // 1 nm … 10 mm
        settings.polarizer_deg = 180.0 * unit(rng);
        settings.analyzer_deg = unit(rng) < 0.5 ? settings.polarizer_deg + 90.0 : 180.0 * unit(rng);
        settings.stage_deg = 360.0 * unit(rng);
        const auto [low, high] = valid_ends_nm(mineral);
        const double pick = unit(rng);
        settings.wavelengths_nm = {pick < 0.35 ? low : pick < 0.7 ? high : low + (high - low) * unit(rng)};
        Eigen::Vector2d xi = Eigen::Vector2d::Zero();
        if (unit(rng) < 0.2 && mineral.optical_class != OpticalClass::isotropic) {
            // The first binormal (optic axis) exactly along the microscope axis, and the point on it.
            settings.crystal_axes = cut_orientation(Cut::optic_axis, mineral.optical_class, mineral.principal_n(settings.wavelengths_nm[0]), 0.0, 0.0);
            ++exact_axis;
        } else {
            settings.crystal_axes = testing::random_rotation(rng);
            const double r = unit(rng) < 0.1 ? 1.0 : std::sqrt(unit(rng)), phi = 2.0 * std::numbers::pi * unit(rng);
            xi = settings.numerical_aperture * r * Eigen::Vector2d(std::cos(phi), std::sin(phi));
        }
        if (unit(rng) < 0.05) {
            settings.plate = make_accessory_plate(unit(rng) < 0.5 ? PlateKind::gypsum : PlateKind::mica, unit(rng) < 0.5 ? gypsum : catalog.find("muscovite"),
                                                  360.0 * unit(rng));
            ++plates;
        }
        const std::vector<double> transmission =
            conoscope_point_transmission(settings, [&mineral](double nm) { return mineral.principal_n(nm); }, xi);
        for (const double t : transmission) {
            // Intensity after the analyzer over that after the polarizer: between 0 and 1 (Fresnel losses only).
            if (!std::isfinite(t) || t < -1e-12 || t > 1.0 + 1e-12) {
                if (++violations <= 10) {
                    ADD_FAILURE() << mineral.name << ": T = " << t << " at " << settings.wavelengths_nm[0] << " nm, d = " << settings.thickness_um
                                  << " um, xi = " << xi.transpose();
                }
            }
            largest = std::max(largest, t);
        }
    }
    std::printf("%d cases (%d along an optic axis exactly, %d with a plate): largest T %.15f, %d out of bounds\n", kCases, exact_axis, plates, largest,
                violations);
    EXPECT_EQ(violations, 0);
}

}  // namespace
}  // namespace petroscope
