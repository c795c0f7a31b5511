// The microscope's layer stack and grain response against closed forms: Fresnel's equations, the
// crossed-polar intensity of a retarder with per-mode Fresnel factors, extinction directions from the
// indicatrix section, and the exact coherent 4×4 solution.
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/optics/orientation.hpp"
#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

constexpr double kPi = std::numbers::pi;

DispersiveMedium constant_medium(const Eigen::Vector3d& n, const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity()) {
    DispersiveMedium medium;
    medium.principal_n = [n](double) { return n; };
    medium.axes = axes;
    return medium;
}

OpticalLayer isotropic_layer(double n, double thickness_um) {
    return {OpticalMedium::isotropic(n).permittivity(),
            thickness_um};
}

// Fresnel (Born & Wolf §1.5.2): a glass plate in air, single pass, s and p: T = (1 − R)² for each.
TEST(LayerStack, GlassPlateFollowsFresnelAtEveryAngle) {
    const double n = 1.5;
    for (const double angle_deg : {0.0, 20.0, 45.0, std::atan(n) * 180.0 / kPi, 70.0}) {
        const double sin_in = std::sin(angle_deg * kPi / 180.0), cos_in = std::cos(angle_deg * kPi / 180.0);
        const double cos_t = std::sqrt(1.0 - sin_in * sin_in / (n * n));
        const double r_s = (cos_in - n * cos_t) / (cos_in + n * cos_t);
        const double r_p = (n * cos_in - cos_t) / (n * cos_in + cos_t);
        const ModalJones modal = single_pass_jones({isotropic_layer(n, 100.0)}, 0, 550.0, {sin_in * 0.6, sin_in * 0.8});
        const Eigen::Matrix2cd jones = modal.at(100.0);
        EXPECT_NEAR(std::norm(jones(0, 0)), std::pow(1.0 - r_s * r_s, 2), 1e-13) << angle_deg;
        EXPECT_NEAR(std::norm(jones(1, 1)), std::pow(1.0 - r_p * r_p, 2), 1e-13) << angle_deg;
        EXPECT_LT(std::abs(jones(0, 1)) + std::abs(jones(1, 0)), 1e-13) << angle_deg;
    }
}

// forward_boundary must satisfy the boundary conditions G·t − B·r = F (tangential E and H continuous) and, where
// every wave is lossless and propagating, carry each incident wave's flux into the transmitted and reflected waves.
// Pairs of random media: lossless on both sides (the 2×2 split by flux orthogonality), an absorbing or an
// evanescent medium below (the 4×4 elimination).
TEST(LayerStack, ForwardBoundarySatisfiesTheBoundaryConditionsAndConservesFlux) {
    std::mt19937_64 rng(2611);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_residual = 0.0, worst_flux = 0.0;
    for (int i = 0; i < 3000; ++i) {
        const OpticalMedium below = testing::random_medium_of_kind(rng, i % 4), above = testing::random_medium_of_kind(rng, (i / 4) % 3);
        const double largest_xi = i % 8 == 7 ? 2.5 : 0.95;  // 2.5: the lower medium's waves are often evanescent
        const double radius = largest_xi * std::sqrt(unit(rng)), azimuth = 2.0 * kPi * unit(rng);
        const Eigen::Vector2d xi = radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
        const MediumWaves from = berreman_modes(below.permittivity(), xi), to = berreman_modes(above.permittivity(), xi);
        const ForwardBoundary boundary = forward_boundary(from, to);
        for (int m = 0; m < 2; ++m) {
            const Eigen::Vector4cd residual = to[0].psi * boundary.transmission(0, m) + to[1].psi * boundary.transmission(1, m) -
                                              from[2].psi * boundary.reflection(0, m) - from[3].psi * boundary.reflection(1, m) - from[m].psi;
            worst_residual = std::max(worst_residual, residual.norm() / from[m].psi.norm());
            const auto lossless = [](const MediumWaves& waves) {
                return std::all_of(waves.begin(), waves.end(), [](const BerremanMode& wave) { return wave.q.imag() == 0.0; });
            };
            if (!lossless(from) || !lossless(to)) continue;
            const double carried = to[0].flux_z * std::norm(boundary.transmission(0, m)) + to[1].flux_z * std::norm(boundary.transmission(1, m)) -
                                   from[2].flux_z * std::norm(boundary.reflection(0, m)) - from[3].flux_z * std::norm(boundary.reflection(1, m));
            worst_flux = std::max(worst_flux, std::abs(carried - from[m].flux_z) / from[m].flux_z);
        }
    }
    std::printf("forward_boundary: residual %.2e, flux %.2e\n", worst_residual, worst_flux);
    EXPECT_LT(worst_residual, 1e-13);
    EXPECT_LT(worst_flux, 1e-13);
}

// A uniaxial plate, c in the section plane at 45° between crossed polars, normal incidence: each mode m
// crosses the stack with the product τₘ of the normal-incidence Fresnel factors 2nₐ/(nₐ + n_b) of its
// interfaces, so I = ¼(τ_o² + τ_e² − 2τ_oτ_e cos δ), δ = 2π(n_e − n_o)d/λ (Born & Wolf §15.4.2).
TEST(GrainResponse, CrossedPolarsMatchRetarderWithFresnelFactors) {
    const double n_o = 1.544, n_e = 1.553, glass = 1.52, balsam = 1.54, wavelength_nm = 550.0, d_um = 30.0;
    SectionMounting mounting;
    mounting.slide = constant_medium(Eigen::Vector3d::Constant(glass));
    mounting.cover = mounting.slide;
    mounting.cement = constant_medium(Eigen::Vector3d::Constant(balsam));
    const DispersiveMedium quartz = constant_medium({n_o, n_o, n_e}, cut_orientation(Cut::optic_normal, OpticalClass::uniaxial, {n_o, n_o, n_e}, 45.0, 0.0));
    MicroscopeSettings settings;
    settings.wavelengths_nm = {wavelength_nm};
    const MicroscopeOptics optics(settings, mounting);
    const GrainResponse response(optics, quartz);
    std::vector<double> transmission;
    response.transmission(d_um, transmission);
    const auto t = [](double a, double b) { return 2.0 * a / (a + b); };
    const auto tau = [&](double n) { return t(1.0, glass) * t(glass, balsam) * t(balsam, n) * t(n, balsam) * t(balsam, glass) * t(glass, 1.0); };
    const double delta = 2.0 * kPi * (n_e - n_o) * d_um * 1e3 / wavelength_nm;
    const double expected = 0.25 * (std::pow(tau(n_o), 2) + std::pow(tau(n_e), 2) - 2.0 * tau(n_o) * tau(n_e) * std::cos(delta));
    EXPECT_NEAR(transmission[0], expected, 1e-13);
}

// Optical activity in the section: a basal quartz plate, 1 mm, at normal incidence (NA 0), turns the plane by ρd,
// so that crossed/(crossed + parallel) = sin²(ρd) whatever the Fresnel factors of the isotropic layers, single pass
// and coherent (the reflections between the faces are of order R ≈ 1e-5, and a round trip undoes the rotation, which
// is reciprocal). The two circular modes' face transmissions differ only in second order in g ≈ 7e-5: to 1e-6.
TEST(GrainResponse, ABasalQuartzPlateTurnsThePlaneByItsRotatoryPower) {
    const double n_o = 1.54425, n_e = 1.55336, wavelength_nm = 589.3, d_um = 1000.0;
    const double rho_axis = 21.72 * kPi / 180.0 * 1e-3;  // rad/µm
    SectionMounting mounting;
    mounting.slide = mounting.cover = constant_medium(Eigen::Vector3d::Constant(1.52));
    mounting.cement = constant_medium(Eigen::Vector3d::Constant(1.54));
    DispersiveMedium quartz = constant_medium({n_o, n_o, n_e});
    const Eigen::Vector3d rotatory_power(-0.5 * rho_axis, -0.5 * rho_axis, rho_axis);
    quartz.gyration = [rotatory_power](double nm) { return gyration_tensor(rotatory_power, Eigen::Matrix3d::Identity(), nm, Handedness::right); };
    for (const bool exact : {false, true}) {
        MicroscopeSettings settings;
        settings.wavelengths_nm = {wavelength_nm};
        settings.exact = exact;
        std::vector<double> crossed, parallel;
        GrainResponse(MicroscopeOptics(settings, mounting), quartz).transmission(d_um, crossed);
        settings.polars.analyzer_deg = 0.0;
        GrainResponse(MicroscopeOptics(settings, mounting), quartz).transmission(d_um, parallel);
        const double expected = std::pow(std::sin(rho_axis * d_um), 2);
        std::printf("basal quartz, %s: crossed fraction %.9f, sin^2(rho d) %.9f\n", exact ? "exact" : "single pass", crossed[0] / (crossed[0] + parallel[0]),
                    expected);
        EXPECT_NEAR(crossed[0] / (crossed[0] + parallel[0]), expected, 1e-6 * expected) << (exact ? "exact" : "single pass");
    }
}

// The single pass couples an active crystal's inactive waves inside by the gyration (docs/theory.md §9), with the
// inactive waves' face transfers. Against the exact waves of the active crystal (Berreman's bianisotropic modes,
// their own face transfers), over random orientations, a condenser cone of NA 0.3, 30 µm and 1 mm, quartz's
// gyration and 30 times it, the transmissions differ by 2.4e-7 and 6.9e-4: about as g², second order.
TEST(GrainResponse, TheCoupledWavesOfAnActiveCrystalAreItsExactWaves) {
    const double n_o = 1.54425, n_e = 1.55336, wavelength_nm = 589.3;
    const double rho_axis = 21.72 * kPi / 180.0 * 1e-3;  // rad/µm
    SectionMounting mounting;
    mounting.slide = mounting.cover = constant_medium(Eigen::Vector3d::Constant(1.52));
    mounting.cement = constant_medium(Eigen::Vector3d::Constant(1.54));
    MicroscopeSettings settings;
    settings.wavelengths_nm = {wavelength_nm};
    settings.condenser_na = 0.3;
    settings.condenser_rings = 2;
    const MicroscopeOptics optics(settings, mounting);
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> angle(0.0, 360.0);
    std::array<double, 2> worst{};
    for (const double scale : {1.0, 30.0}) {
        for (int trial = 0; trial < 10; ++trial) {
            DispersiveMedium quartz = constant_medium({n_o, n_o, n_e}, euler_zyz_deg(angle(rng), angle(rng) / 2.0, angle(rng)));
            const Eigen::Vector3d rotatory_power = scale * Eigen::Vector3d(-0.5 * rho_axis, -0.5 * rho_axis, rho_axis);
            quartz.gyration = [rotatory_power](double nm) { return gyration_tensor(rotatory_power, Eigen::Matrix3d::Identity(), nm, Handedness::right); };
            const Eigen::Matrix3cd epsilon = quartz.permittivity(wavelength_nm);
            const Eigen::Matrix3d chirality = quartz.chirality(wavelength_nm);
            for (const double d_um : {30.0, 1000.0}) {
                std::vector<double> coupled;
                GrainResponse(optics, quartz).transmission(d_um, coupled);
                double exact = 0.0;
                for (std::size_t k = 0; k < optics.directions().size(); ++k) {
                    const MicroscopeOptics::Path& path = optics.path(0, k);
                    const MediumWaves waves = berreman_modes(epsilon, chirality, optics.directions()[k].xi);
                    const Eigen::Vector2cd entry = forward_transmission(path.cement, waves) * path.into_crystal;
                    const Eigen::Matrix2cd exit = path.to_eye * forward_transmission(waves, path.cement);
                    const std::complex<double> i(0.0, 1.0);
                    const Eigen::Vector2cd field = exit.col(0) * entry[0] * std::exp(i * path.k0_per_um * waves[0].q * d_um) +
                                                   exit.col(1) * entry[1] * std::exp(i * path.k0_per_um * waves[1].q * d_um);
                    exact += optics.directions()[k].weight * field.squaredNorm();
                }
                double& slot = worst[scale > 1.0 ? 1 : 0];
                slot = std::max(slot, std::abs(coupled[0] - exact));
            }
        }
    }
    std::printf("coupled single pass against the exact waves, NA 0.3: quartz's gyration %.2g, 30 times it %.2g\n", worst[0], worst[1]);
    EXPECT_LT(worst[0], 1e-6);
    EXPECT_LT(worst[1], 1e-3);
}

// Extinction: at normal incidence the vibration directions are the principal axes of the central section of
// the impermeability tensor η = ε⁻¹ (its xy block; Nye, Physical Properties of Crystals, ch. XIII). A grain goes
// dark when they lie along the polars and is brightest 45° away.
TEST(GrainResponse, ExtinctionWhereTheIndicatrixSectionPredicts) {
    const Eigen::Vector3d n(1.63, 1.66, 1.70);
    const Eigen::Matrix3d axes = euler_zyz_deg(37.0, 61.0, -23.0);
    const DispersiveMedium crystal = constant_medium(n, axes);
    SectionMounting mounting;
    mounting.slide = mounting.cover = constant_medium(Eigen::Vector3d::Constant(1.52));
    mounting.cement = constant_medium(Eigen::Vector3d::Constant(1.54));
    const Eigen::Matrix3d impermeability = axes * n.cwiseInverse().cwiseAbs2().asDiagonal() * axes.transpose();
    const Eigen::Matrix2d section = impermeability.topLeftCorner<2, 2>();
    const double principal_deg = 0.5 * std::atan2(2.0 * section(0, 1), section(0, 0) - section(1, 1)) * 180.0 / kPi;
    // The stage turns the crystal counter-clockwise: a vibration direction at φ reaches the polarizer (E–W) at
    // stage −φ (mod 90°).
    MicroscopeSettings settings;
    settings.wavelengths_nm = {589.3};
    std::vector<double> transmission;
    settings.stage_deg = -principal_deg;
    GrainResponse(MicroscopeOptics(settings, mounting), crystal).transmission(30.0, transmission);
    EXPECT_LT(transmission[0], 1e-20);
    settings.stage_deg = -principal_deg + 90.0;
    GrainResponse(MicroscopeOptics(settings, mounting), crystal).transmission(30.0, transmission);
    EXPECT_LT(transmission[0], 1e-20);
    settings.stage_deg = -principal_deg + 45.0;
    GrainResponse(MicroscopeOptics(settings, mounting), crystal).transmission(30.0, transmission);
    const double brightest = transmission[0];
    for (double offset_deg = 0.0; offset_deg < 90.0; offset_deg += 3.0) {
        settings.stage_deg = -principal_deg + offset_deg;
        GrainResponse(MicroscopeOptics(settings, mounting), crystal).transmission(30.0, transmission);
        EXPECT_LE(transmission[0], brightest * (1.0 + 1e-9)) << offset_deg;
    }
    EXPECT_GT(brightest, 0.05);
}

// An isotropic grain stays dark between crossed polars at every stage angle, even in a condenser cone
// (where oblique rays in the s/p frame rotate the polarization slightly: bounded, not zero).
TEST(GrainResponse, IsotropicGrainIsDarkBetweenCrossedPolars) {
    SectionMounting mounting;
    mounting.slide = mounting.cover = constant_medium(Eigen::Vector3d::Constant(1.52));
    mounting.cement = constant_medium(Eigen::Vector3d::Constant(1.54));
    const DispersiveMedium garnet = constant_medium(Eigen::Vector3d::Constant(1.83));
    MicroscopeSettings settings;
    settings.wavelengths_nm = {450.0, 550.0, 650.0};
    std::vector<double> crossed, parallel;
    for (double stage = 0.0; stage < 360.0; stage += 15.0) {
        settings.stage_deg = stage;
        settings.polars.analyzer_deg = 90.0;
        GrainResponse(MicroscopeOptics(settings, mounting), garnet).transmission(30.0, crossed);
        settings.polars.analyzer_deg = 0.0;
        GrainResponse(MicroscopeOptics(settings, mounting), garnet).transmission(30.0, parallel);
        for (std::size_t w = 0; w < crossed.size(); ++w) EXPECT_LT(crossed[w], 1e-6 * parallel[w]);
    }
}

// Single pass against the coherent 4×4 solution in an index-matched stack (immersion on both sides, glass and
// balsam close to the crystal): the multiple reflections are then of order r² ≈ 1e-5, so averaged over a
// 10 nm band the two agree to 1e-4. Checked for a biaxial crystal in an oblique direction, all four Jones entries.
TEST(LayerStack, SinglePassAgreesWithCoherentInIndexMatchedStack) {
    const Eigen::Matrix3d axes = euler_zyz_deg(20.0, 50.0, 10.0);
    const Eigen::Vector3d n(1.540, 1.545, 1.552);
    const Eigen::Vector2d xi(0.15, -0.08);
    const double ambient = 1.54;
    double worst = 0.0;
    for (double band_start = 400.0; band_start < 700.0; band_start += 50.0) {
        Eigen::Matrix2d single_sum = Eigen::Matrix2d::Zero(), coherent_sum = Eigen::Matrix2d::Zero();
        for (double wavelength = band_start; wavelength < band_start + 10.0; wavelength += 0.25) {
            const std::vector<OpticalLayer> layers{isotropic_layer(1.53, 20.0),
                                                   {OpticalMedium{n.cast<std::complex<double>>(), axes}.permittivity(), 30.0},
                                                   isotropic_layer(1.535, 20.0)};
            single_sum += single_pass_jones(layers, 1, wavelength, xi, ambient).at(30.0).cwiseAbs2();
            coherent_sum += coherent_jones(layers, wavelength, xi, ambient).cwiseAbs2();
        }
        worst = std::max(worst, (single_sum - coherent_sum).cwiseAbs().maxCoeff() / 40.0);
    }
    EXPECT_LT(worst, 1e-4);
    EXPECT_GT(worst, 0.0);
}

// Absorption: light vibrating along one principal axis of an absorbing crystal at normal incidence decays as
// exp(−4πκd/λ) (Born & Wolf §14.1), times the Fresnel factors of the real parts.
TEST(LayerStack, AbsorbingPlateFollowsBeerLambert) {
    const double n = 1.6, kappa = 2e-3, d_um = 30.0, wavelength_nm = 500.0;
    const Eigen::Vector3d principal_n(1.6, 1.65, 1.7), principal_kappa(kappa, 0.0, 0.0);
    const OpticalLayer layer{OpticalMedium::from_n_kappa(principal_n, principal_kappa, Eigen::Matrix3d::Identity()).permittivity(), d_um};
    const Eigen::Matrix2cd jones = single_pass_jones({layer}, 0, wavelength_nm, Eigen::Vector2d::Zero()).at(d_um);
    // At ξ = 0, p is x̂ (the X axis, absorbing): the (p, p) entry.
    const std::complex<double> index(n, kappa);
    const double fresnel = std::norm(2.0 / (1.0 + index) * 2.0 * index / (index + 1.0));
    const double expected = fresnel * std::exp(-4.0 * kPi * kappa * d_um * 1e3 / wavelength_nm);
    EXPECT_NEAR(std::norm(jones(1, 1)), expected, 1e-12);
}

// The closed form at normal incidence against Berreman's eigen-decomposition: the Jones matrix of a plate in
// air is basis-free, so both sets of waves must give the same one. Absorbing biaxial crystals in random
// orientations, an isotropic one rotated (degenerate), and a uniaxial one along its optic axis.
TEST(LayerStack, NormalIncidenceClosedFormMatchesBerreman) {
    const Eigen::Matrix3cd air = Eigen::Matrix3cd::Identity();
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> crystals{
        {{1.56, 1.60, 1.64}, {1e-3, 4e-3, 5e-3}}, {{1.83, 1.83, 1.83}, {0.0, 0.0, 0.0}},
        {{1.658, 1.658, 1.486}, {0.0, 0.0, 0.0}}, {{1.9, 2.0, 2.3}, {0.0, 0.0, 0.0}}};
    const std::vector<Eigen::Vector3d> angles{{0.0, 0.0, 0.0}, {23.0, 67.0, 41.0}, {-110.0, 145.0, 12.0}};
    const double k0 = wavenumber_per_um(550.0), d_um = 20.0;
    for (const auto& [n, kappa] : crystals) {
        for (const Eigen::Vector3d& a : angles) {
            const Eigen::Matrix3cd epsilon = OpticalMedium::from_n_kappa(n, kappa, euler_zyz_deg(a[0], a[1], a[2])).permittivity();
            const MediumWaves ambient = berreman_modes(air, Eigen::Vector2d::Zero());
            const MediumWaves closed = normal_incidence_waves(epsilon);
            const Eigen::Matrix2cd jones = forward_transmission(closed, ambient) * forward_propagation(closed, k0, d_um) *
                                           forward_transmission(ambient, closed);
            const Eigen::Matrix2cd reference = single_pass_jones({{epsilon, d_um}}, 0, 550.0, Eigen::Vector2d::Zero()).at(d_um);
            EXPECT_LT((jones - reference).cwiseAbs().maxCoeff(), 1e-12) << n.transpose() << " / " << a.transpose();
        }
    }
}

}  // namespace
}  // namespace petroscope
