// Internal conical refraction in ray optics (the paper's pinhole scene): the ring's radius and centre,
// its rotation with the crystal, and power conservation on and near the optic axis.
#include "petroscope/core/error.hpp"
#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/conical_wave.hpp"
#include "petroscope/optics/interface.hpp"
#include "petroscope/optics/medium.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/polarization.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace petroscope {
namespace {

// KGd(WO4)2 at 632.8 nm (Loiko et al., Appl. Opt. 51, 2951 (2012)): nα, nβ, nγ = 2.0135, 2.0458, 2.0860; a 20 mm slab; a 25 µm pinhole
// in a 50 mm collimating filter, so that the rays' blur L·θ (L = D + d/nβ) stays below R₀.
ConicalRaySettings kgw_settings() {
    ConicalRaySettings settings;
    settings.principal_n = {2.0135, 2.0458, 2.0860};
    settings.slab_um = 20000.0;
    settings.pinhole_radius_um = 25.0;
    settings.filter_um = 50000.0;
    settings.screen_distance_um = 50000.0;
    settings.rays = 150000;
    settings.size_px = 256;
    return settings;
}

TEST(ConicalRay, ConeAngleAndRingRadiusFollowTheIndices) {
    // tan χ = √((nβ² − nα²)(nγ² − nβ²))/(nα nγ); A = R₀/l = ½ tan χ: χ = 2.012°, A = 17.57 mrad (Berry, J. Opt. A 6, 289 (2004); docs/theory.md §8).
    const Eigen::Vector3d n(2.0135, 2.0458, 2.0860);
    const double tan_chi = std::sqrt((n[1] * n[1] - n[0] * n[0]) * (n[2] * n[2] - n[1] * n[1])) / (n[0] * n[2]);
    EXPECT_NEAR(std::tan(conical_cone_angle_rad(n)), tan_chi, 1e-12);
    EXPECT_NEAR(conical_cone_angle_rad(n) * 180.0 / M_PI, 2.012, 5e-4);
    EXPECT_NEAR(0.5 * tan_chi * 1000.0, 17.57, 5e-3);
    EXPECT_NEAR(std::tan(conical_cone_angle_rad({2.0860, 2.0135, 2.0458})), tan_chi, 1e-15);  // any order
}

TEST(ConicalRay, DarkRingHasRadiusADAndPassesThroughThePointBelowThePinhole) {
    const ConicalRayResult result = trace_conical_rays(kgw_settings());
    const double a_d = result.ring_radius_um;
    EXPECT_NEAR(result.rings.dark_um, a_d, 0.01 * a_d);
    // One pixel of a 256-pixel image 4 R₀ wide.
    const double pixel_um = 4.0 * a_d / 256.0;
    EXPECT_NEAR((result.rings.centre_um - result.pinhole_point_um).norm(), result.rings.dark_um, pixel_um);
    EXPECT_LT(result.rings.inner_bright_um, result.rings.dark_um);
    EXPECT_GT(result.rings.outer_bright_um, result.rings.dark_um);
    EXPECT_LE(result.max_interface_power_sum, 1.0 + 1e-12);
    EXPECT_EQ(result.non_finite, 0);
    std::printf("ray mode: R0 = A d = %.3f um, dark ring %.3f um, bright rings %.3f / %.3f um, centre %.3f um from the pinhole point\n",
                a_d, result.rings.dark_um, result.rings.inner_bright_um, result.rings.outer_bright_um,
                (result.rings.centre_um - result.pinhole_point_um).norm());
}

TEST(ConicalRay, TurningTheSlabAboutItsOpticAxisTurnsThePatternAboutThePinholePoint) {
    for (const double turn_deg : {30.0, 125.0}) {
        ConicalRaySettings settings = kgw_settings();
        settings.rotate_deg = turn_deg;
        const ConicalRayResult result = trace_conical_rays(settings);
        const Eigen::Vector2d offset = result.rings.centre_um - result.pinhole_point_um;
        EXPECT_NEAR(std::remainder(std::atan2(offset.y(), offset.x()) * 180.0 / M_PI - turn_deg, 360.0), 0.0, 0.3) << turn_deg;
    }
}

TEST(ConicalRay, RaysExactlyAlongTheOpticAxisConservePowerAndStayFinite) {
    // A point source whose rays all enter at normal incidence: every refracted wave lies exactly on the
    // binormal, where the two modes are degenerate.
    ConicalRaySettings settings = kgw_settings();
    settings.source = ConicalRaySettings::Source::point;
    settings.angular_width_rad = 0.0;
    settings.rays = 2000;
    const ConicalRayResult exact = trace_conical_rays(settings);
    EXPECT_LE(exact.max_interface_power_sum, 1.0 + 1e-12);
    EXPECT_EQ(exact.non_finite, 0);
    double collected = 0.0;
    for (const float value : exact.screen.pixels) collected += value;
    EXPECT_GT(collected, 0.5 * settings.rays);  // most of the light arrives (minus the reflections)
    // And within 1e-9 rad of it.
    settings.angular_width_rad = 1e-9;
    const ConicalRayResult near = trace_conical_rays(settings);
    EXPECT_LE(near.max_interface_power_sum, 1.0 + 1e-12);
    EXPECT_EQ(near.non_finite, 0);
}

TEST(ConicalRay, WaveAndRayOpticsAgreeInTheGeometricLimit) {
    // A Gaussian beam E = exp(−r²/2w²) focused on the entrance face has the angular intensity
    // exp(−k₀²w²θ²): per axis σ_θ = 1/(√2 k₀ w). Its ray equivalent is a point source with those angles;
    // the screen at D lies Z = (D + l/nβ)/(k₀w²) from the focal image plane (Berry 2004; docs/theory.md §8). ρ₀/Z =
    // A nβ k₀ w does not depend on l, and the wave theory's inner ring reaches its ray position only as
    // Z^(−1/4) (at larger Z, fringes appear inside it): w = 40 µm, l = 800 mm, D = 1 mm give ρ₀ = 351,
    // Z = 25 (ρ₀/Z = 14), a numerical regime rather than a practical crystal.
    const Eigen::Vector3d n(2.0135, 2.0458, 2.0860);
    const double wavelength_um = 0.633, k0 = 2.0 * M_PI / wavelength_um, w = 40.0, l = 800000.0, d_screen = 1000.0;
    ConicalRaySettings rays;
    rays.principal_n = n;
    rays.slab_um = l;
    rays.source = ConicalRaySettings::Source::point;
    rays.angular_width_rad = 1.0 / (std::sqrt(2.0) * k0 * w);
    rays.screen_distance_um = d_screen;
    rays.rays = 200000;
    rays.size_px = 128;
    const ConicalRayResult traced = trace_conical_rays(rays);

    ConicalWaveParameters wave;
    wave.rho0 = traced.ring_radius_um / w;
    wave.z = (d_screen + l / n[1]) / (k0 * w * w);
    const ConicalRings rings = conical_rings(conical_profile(wave, wave.rho0 + 4.0 + 1.5 * wave.z, 8000), wave.rho0);
    std::printf("geometric limit (rho0 = %.1f, Z = %.1f): rings wave %.1f / %.1f um, ray %.1f / %.1f um\n", wave.rho0, wave.z,
                rings.inner_bright * w, rings.outer_bright * w, traced.rings.inner_bright_um, traced.rings.outer_bright_um);
    EXPECT_NEAR(traced.rings.inner_bright_um / (rings.inner_bright * w), 1.0, 0.02);
    EXPECT_NEAR(traced.rings.outer_bright_um / (rings.outer_bright * w), 1.0, 0.02);
}

TEST(ConicalRay, BadInputIsRejected) {
    ConicalRaySettings settings = kgw_settings();
    settings.principal_n = {1.6584, 1.6584, 1.4864};  // calcite: uniaxial
    EXPECT_THROW(trace_conical_rays(settings), InputError);
    settings = kgw_settings();
    settings.slab_um = 0.0;
    EXPECT_THROW(trace_conical_rays(settings), InputError);
    settings = kgw_settings();
    settings.screen_distance_um = -5.0;
    EXPECT_THROW(trace_conical_rays(settings), InputError);
    settings = kgw_settings();
    settings.pinhole_radius_um = 20000.0;  // larger than the slab
    EXPECT_THROW(trace_conical_rays(settings), InputError);
}

// The slab crossing from Berreman's modes against the exact interface model (optics/interface.hpp: an
// independent solver in long double) applied face by face: for rays from 1e-5 to 0.03 rad off the binormal, in
// unpolarized and linearly polarized light, each wave's ray direction and the power it carries out agree.
// Berreman's modes take two waves whose q differ by less than 1e-8 as degenerate (optics/berreman.hpp), which
// near the binormal means within about 1e-6 rad of it; there, as on the axis itself, each solver picks its own
// pair of waves (both on the cone), and only the total power is compared.
TEST(ConicalRay, SlabCrossingAgreesWithTheInterfaceModel) {
    const Eigen::Vector3d n(2.0135, 2.0458, 2.0860);
    const Eigen::Matrix3d axes = cut_orientation(Cut::optic_axis, OpticalClass::biaxial, n, 20.0, 0.0);
    const OpticalMedium crystal{n.cast<std::complex<double>>(), axes};
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double worst_direction = 0.0, worst_weight = 0.0, worst_total = 0.0;
    int compared = 0;
    for (const double offset_rad : {0.0, 1e-7, 1e-5, 1e-3, 3e-2}) {
        for (int k = 0; k < 8; ++k) {
            const double azimuth = 0.785 * k + 0.1;
            const Eigen::Vector3d direction = Eigen::Vector3d(offset_rad * std::cos(azimuth), offset_rad * std::sin(azimuth), 1.0).normalized();
            const Eigen::Vector4d stokes = k % 2 == 0 ? Eigen::Vector4d(1, 0, 0, 0) : Eigen::Vector4d(1, std::cos(azimuth), std::sin(azimuth), 0);
            InterfaceIncidence incidence;
            incidence.direction = direction;
            incidence.coherency = coherency_from_stokes(stokes);  // (s, p) of this ray; the lab frame does not matter here
            const SlabCrossing crossing = cross_slab(crystal.permittivity(), direction, incidence.coherency);
            double total = 0.0, reference_total = 0.0;
            for (const SlabWave& wave : crossing.waves) total += wave.weight;
            for (const InterfaceWave& inside : solve_interface(normal, incidence, air, crystal).waves) {
                if (inside.kind != InterfaceWave::Kind::transmitted || inside.power <= 0.0) continue;
                InterfaceIncidence internal;
                internal.direction = inside.direction;
                internal.mode = inside.mode;
                double out = 0.0;
                for (const InterfaceWave& wave : solve_interface(normal, internal, crystal, air).waves) {
                    if (wave.kind == InterfaceWave::Kind::transmitted) out += wave.power;
                }
                const double weight = inside.power * out;
                reference_total += weight;
                if (offset_rad < 1e-5) continue;
                // The same wave of the other solver: the nearer ray direction.
                const SlabWave* match = nullptr;
                for (const SlabWave& wave : crossing.waves) {
                    if (match == nullptr || (wave.ray_direction - inside.ray_direction).norm() < (match->ray_direction - inside.ray_direction).norm()) match = &wave;
                }
                ASSERT_NE(match, nullptr);
                worst_direction = std::max(worst_direction, (match->ray_direction - inside.ray_direction).norm());
                worst_weight = std::max(worst_weight, std::abs(match->weight - weight));
                ++compared;
            }
            worst_total = std::max(worst_total, std::abs(total - reference_total));
            EXPECT_LE(crossing.largest_power_sum, 1.0 + 1e-12);
        }
    }
    std::printf("%d waves: ray directions within %.1e, powers within %.1e; totals within %.1e\n", compared, worst_direction, worst_weight,
                worst_total);
    EXPECT_EQ(compared, 2 * 3 * 8);
    EXPECT_LT(worst_direction, 1e-9);
    EXPECT_LT(worst_weight, 1e-9);
    EXPECT_LT(worst_total, 1e-12);
}

}  // namespace
}  // namespace petroscope
