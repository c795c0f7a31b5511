// The local interface model against closed forms (Snell, Fresnel, total internal reflection, Brewster),
// uniaxial birefringence, and energy conservation over random media, on and near the optic axes.
#include "petroscope/core/error.hpp"
#include "petroscope/optics/interface.hpp"

#include "support/random_crystals.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace petroscope {
namespace {

constexpr double kDegree = M_PI / 180.0;

InterfaceIncidence polarized(const Eigen::Vector3d& direction, const JonesVector& jones) {
    InterfaceIncidence incidence;
    incidence.direction = direction;
    incidence.jones = jones;
    incidence.coherency = coherency_from_jones(jones);
    return incidence;
}

const InterfaceWave& wave_of(const InterfaceResult& result, InterfaceWave::Kind kind, const std::string& mode = "") {
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind == kind && (mode.empty() || wave.mode == mode)) return wave;
    }
    throw std::runtime_error("no such wave");
}

double total_power(const InterfaceResult& result) {
    double total = 0.0;
    for (const InterfaceWave& wave : result.waves) total += wave.power;
    return total;
}

// A random orthonormal frame whose third column is the interface normal.
Eigen::Matrix3d random_frame(std::mt19937_64& rng) { return testing::random_rotation(rng); }

TEST(Interface, IsotropicFresnelCoefficientsSnellAndCoplanarity) {
    // Physics notes §4 (Born & Wolf §1.5.2): r_s, r_p, t_s, t_p, with the (s, p) basis of docs/interface.md.
    std::mt19937_64 rng(31);
    double worst_coefficient = 0.0, worst_geometry = 0.0;
    for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4}}) {
        for (int tenth = 0; tenth <= 899; ++tenth) {
            const double theta = tenth * 0.1 * kDegree;
            const double sin2 = n1 * std::sin(theta) / n2;
            if (sin2 >= 1.0) continue;  // total internal reflection: tested below
            const double c1 = std::cos(theta), c2 = std::sqrt(1.0 - sin2 * sin2);
            const double r_s = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2), r_p = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
            const double t_s = 2 * n1 * c1 / (n1 * c1 + n2 * c2), t_p = 2 * n1 * c1 / (n2 * c1 + n1 * c2);
            // A random orientation of the whole geometry: the normal is the frame's third column.
            const Eigen::Matrix3d frame = random_frame(rng);
            const Eigen::Vector3d normal = frame.col(2);
            const Eigen::Vector3d k_in = frame * Eigen::Vector3d(std::sin(theta), 0.0, c1);
            for (int polarization = 0; polarization < 2; ++polarization) {
                const JonesVector jones = polarization == 0 ? JonesVector(1, 0) : JonesVector(0, 1);
                const InterfaceResult result = solve_interface(normal, polarized(k_in, jones), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
                const InterfaceWave& reflected = wave_of(result, InterfaceWave::Kind::reflected);
                const InterfaceWave& transmitted = wave_of(result, InterfaceWave::Kind::transmitted);
                const JonesVector expected_r = polarization == 0 ? JonesVector(r_s, 0) : JonesVector(0, r_p);
                const JonesVector expected_t = polarization == 0 ? JonesVector(t_s, 0) : JonesVector(0, t_p);
                worst_coefficient = std::max({worst_coefficient, (*reflected.jones - expected_r).norm(), (*transmitted.jones - expected_t).norm()});
                // Law of reflection, Snell's law, coplanarity of incident, reflected, refracted and normal.
                const Eigen::Vector3d plane_normal = k_in.cross(normal);
                worst_geometry = std::max({worst_geometry, std::abs(reflected.direction.dot(normal) + c1),
                                           std::abs(n1 * std::sin(theta) - n2 * transmitted.direction.cross(normal).norm()),
                                           std::abs(reflected.direction.dot(plane_normal)), std::abs(transmitted.direction.dot(plane_normal))});
                EXPECT_NEAR(total_power(result), 1.0, 1e-12);
            }
        }
    }
    EXPECT_LT(worst_coefficient, 1e-12);
    EXPECT_LT(worst_geometry, 1e-12);
}

TEST(Interface, TotalInternalReflectionReflectsEverythingAndMakesEllipticalLight) {
    // Beyond the critical angle (1.5 → 1: 41.81°) R = 1, the transmitted wave is evanescent, and r_s, r_p
    // differ in phase by δ with tan(δ/2) = cos θ √(sin²θ − n²)/sin²θ, n = n₂/n₁ (Born & Wolf §1.5.4).
    const double n1 = 1.5, n2 = 1.0, n = n2 / n1;
    for (const double theta_deg : {42.0, 50.0, 60.0, 75.0, 89.9}) {
        const double theta = theta_deg * kDegree;
        const Eigen::Vector3d k_in(std::sin(theta), 0.0, std::cos(theta));
        const InterfaceResult result = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(std::sqrt(0.5), std::sqrt(0.5))),
                                                       OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        const InterfaceWave& reflected = wave_of(result, InterfaceWave::Kind::reflected);
        const InterfaceWave& transmitted = wave_of(result, InterfaceWave::Kind::transmitted);
        EXPECT_NEAR(reflected.power, 1.0, 1e-12);
        EXPECT_TRUE(transmitted.evanescent);
        EXPECT_EQ(transmitted.power, 0.0);
        const double s2 = std::sin(theta) * std::sin(theta);
        const double delta = 2.0 * std::atan(std::cos(theta) * std::sqrt(s2 - n * n) / s2);
        // 45° linear input: S3/S0 = ±sin δ for the reflected wave, |S2/S0| = cos δ.
        EXPECT_NEAR(std::abs(reflected.stokes[3]) / reflected.stokes[0], std::sin(delta), 1e-12) << theta_deg;
        EXPECT_NEAR(std::abs(reflected.stokes[2]) / reflected.stokes[0], std::abs(std::cos(delta)), 1e-12) << theta_deg;
    }
}

TEST(Interface, BrewsterAngleReflectsNoPButTransmitsPartOfS) {
    // tan θ_B = n₂/n₁: R_p = 0 and reflected ⟂ refracted; s light is partly reflected, R_s =
    // sin²(θ₁ − θ₂)/sin²(θ₁ + θ₂), and the rest is transmitted (physics notes §4: the paper's claim that
    // s light at θ_B has no refracted ray is wrong).
    for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4}}) {
        const double theta = std::atan(n2 / n1);
        const Eigen::Vector3d k_in(std::sin(theta), 0.0, std::cos(theta));
        const InterfaceResult p = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(0, 1)), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        EXPECT_LT(wave_of(p, InterfaceWave::Kind::reflected).power, 1e-15);
        const Eigen::Vector3d reflected = wave_of(p, InterfaceWave::Kind::reflected).direction;
        const Eigen::Vector3d refracted = wave_of(p, InterfaceWave::Kind::transmitted).direction;
        EXPECT_NEAR(reflected.dot(refracted), 0.0, 1e-12);
        const InterfaceResult s = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(1, 0)), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        const double theta2 = std::asin(n1 * std::sin(theta) / n2);
        const double r_s = std::pow(std::sin(theta - theta2) / std::sin(theta + theta2), 2);
        EXPECT_NEAR(wave_of(s, InterfaceWave::Kind::reflected).power, r_s, 1e-12);
        EXPECT_NEAR(wave_of(s, InterfaceWave::Kind::transmitted).power, 1.0 - r_s, 1e-12);
        if (n1 == 1.0 && n2 == 1.5) EXPECT_NEAR(r_s, 0.1479289940828, 1e-12);
    }
}

OpticalMedium calcite_with_axis(const Eigen::Vector3d& optic_axis) {
    // ω = 1.6584, ε = 1.4864 at 589.3 nm; Z (the optic axis) along `optic_axis`.
    const Eigen::Vector3d z = optic_axis.normalized();
    const Eigen::Vector3d x = (std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(z).normalized();
    OpticalMedium calcite;
    calcite.principal_n = Eigen::Vector3cd(1.6584, 1.6584, 1.4864);
    calcite.axes << x, z.cross(x), z;
    return calcite;
}

TEST(Interface, CalciteAtNormalIncidenceSplitsIntoOrdinaryAndExtraordinary) {
    const double n_o = 1.6584, n_e = 1.4864;
    const Eigen::Vector3d axis(std::sin(45 * kDegree), 0.0, std::cos(45 * kDegree));  // 45° to the face
    InterfaceIncidence unpolarized;
    const InterfaceResult result = solve_interface({0, 0, 1}, unpolarized, OpticalMedium::isotropic(1.0), calcite_with_axis(axis));
    const InterfaceWave& o = wave_of(result, InterfaceWave::Kind::transmitted, "ordinary");
    const InterfaceWave& e = wave_of(result, InterfaceWave::Kind::transmitted, "extraordinary");
    // Both wave normals along the face normal; o with n_o, e with n_e(45°) (Born & Wolf §15.3.3).
    EXPECT_LT((o.direction - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_LT((e.direction - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_NEAR(o.n.real(), n_o, 1e-12);
    const double n_e45 = 1.0 / std::sqrt(0.5 / (n_o * n_o) + 0.5 / (n_e * n_e));
    EXPECT_NEAR(e.n.real(), n_e45, 1e-12);
    // Walk-off of the e ray: tan α = ½ n_e(θ)² sin 2θ (1/n_e² − 1/n_o²) with θ = 45° (Born & Wolf §15.3.3).
    const double walk_off = std::atan(0.5 * n_e45 * n_e45 * (1.0 / (n_e * n_e) - 1.0 / (n_o * n_o)));
    EXPECT_NEAR(std::acos(e.ray_direction.dot(e.direction)), walk_off, 1e-12);
    EXPECT_NEAR(walk_off / kDegree, 6.2, 0.05);
    EXPECT_LT(o.ray_direction.cross(o.direction).norm(), 1e-12);  // o ray along its wave normal
    // Polarizations: o ⟂ the principal plane (x–z here, containing the normal and the axis), e in it.
    EXPECT_NEAR(std::abs(o.e_field.x()) + std::abs(o.e_field.z()), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(e.e_field.y()), 0.0, 1e-12);
    EXPECT_NEAR(total_power(result), 1.0, 1e-12);
}

TEST(Interface, OrdinaryWaveObeysSnellsLawAtEveryIncidence) {
    std::mt19937_64 rng(5);
    for (int i = 0; i < 2000; ++i) {
        const OpticalMedium calcite = calcite_with_axis(testing::random_unit_vector(rng));
        const double theta = 89.9 * kDegree * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const double phi = 2 * M_PI * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const Eigen::Vector3d k_in(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const InterfaceResult result = solve_interface({0, 0, 1}, InterfaceIncidence{k_in}, OpticalMedium::isotropic(1.0), calcite);
        const InterfaceWave& o = wave_of(result, InterfaceWave::Kind::transmitted, "ordinary");
        EXPECT_NEAR(std::sin(theta), 1.6584 * o.direction.cross(Eigen::Vector3d::UnitZ()).norm(), 1e-12);
        EXPECT_NEAR(o.n.real(), 1.6584, 1e-12);
    }
}

TEST(Interface, RaysLeaveAPlaneParallelSlabParallelToTheIncidentRay) {
    // Each refracted mode meets the second, parallel face: its transmitted wave into air leaves along the
    // original incident direction (the tangential wavevector is conserved through both faces).
    std::mt19937_64 rng(6);
    for (int i = 0; i < 500; ++i) {
        const OpticalMedium calcite = calcite_with_axis(testing::random_unit_vector(rng));
        const double theta = 80 * kDegree * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const Eigen::Vector3d k_in(std::sin(theta), 0.0, std::cos(theta));
        const InterfaceResult entry = solve_interface({0, 0, 1}, InterfaceIncidence{k_in}, OpticalMedium::isotropic(1.0), calcite);
        for (const std::string mode : {"ordinary", "extraordinary"}) {
            InterfaceIncidence inside;
            inside.direction = wave_of(entry, InterfaceWave::Kind::transmitted, mode).direction;
            inside.mode = mode;
            const InterfaceResult exit = solve_interface({0, 0, 1}, inside, calcite, OpticalMedium::isotropic(1.0));
            EXPECT_LT((wave_of(exit, InterfaceWave::Kind::transmitted).direction - k_in).norm(), 1e-12);
            EXPECT_NEAR(total_power(exit), 1.0, 1e-12);
        }
    }
}

// A random medium: isotropic, uniaxial or biaxial, lossless, indices 1.0–2.6.
OpticalMedium random_medium(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int kind = static_cast<int>(rng() % 3);
    if (kind == 0) return OpticalMedium::isotropic(1.0 + 1.6 * unit(rng));
    const Indicatrix indicatrix = kind == 1 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
    return OpticalMedium{indicatrix.principal_n.cast<std::complex<double>>(), indicatrix.axes};
}

InterfaceIncidence random_incidence(std::mt19937_64& rng, const OpticalMedium& medium1, const Eigen::Vector3d& direction) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    InterfaceIncidence incidence;
    incidence.direction = direction;
    if (!medium1.is_isotropic()) {
        incidence.mode = unit(rng) < 0.5 ? "fast" : "slow";
    } else {
        // A random partially polarized state: Stokes with degree of polarization in [0, 1].
        const Eigen::Vector3d axis = testing::random_unit_vector(rng) * unit(rng);
        incidence.coherency = coherency_from_stokes({1.0, axis.x(), axis.y(), axis.z()});
    }
    return incidence;
}

TEST(Interface, EnergyIsConservedOverAMillionRandomCases) {
    // Lossless media: the powers of all waves add up to the incident power (R + T = 1).
    std::mt19937_64 rng(2027);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const OpticalMedium medium1 = random_medium(rng), medium2 = random_medium(rng);
        const Eigen::Matrix3d frame = random_frame(rng);
        const double theta = 89.99 * kDegree * unit(rng), phi = 2 * M_PI * unit(rng);
        const Eigen::Vector3d direction = frame * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const InterfaceResult result = solve_interface(frame.col(2), random_incidence(rng, medium1, direction), medium1, medium2);
        worst = std::max(worst, std::abs(total_power(result) - 1.0));
    }
    EXPECT_LT(worst, 1e-12);
}

TEST(Interface, EnergyIsConservedOnAndNearAnOpticAxis) {
    // The paper's defect (§5): near-normal incidence on a biaxial plate along a binormal gave powers
    // adding up to more than the incident one. Here: incidence within 1e-9 rad of a binormal of medium 2
    // (inside the crystal), exactly on it included, for random biaxial and uniaxial crystals.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const Indicatrix indicatrix = i % 4 == 0 ? testing::random_uniaxial(rng) : testing::random_biaxial(rng);
        const OpticalMedium crystal{indicatrix.principal_n.cast<std::complex<double>>(), indicatrix.axes};
        const BinormalFrame frame(indicatrix);
        Eigen::Vector3d binormal = i % 2 == 0 ? frame.binormal_1 : frame.binormal_2;
        if (binormal.z() < 0) binormal = -binormal;
        if (binormal.z() < 0.2) continue;  // grazing binormals cannot be reached from medium 1 here
        // The binormal's wave index is nβ: the wave from air (n₁ = 1) that refracts onto it has ξ = nβ·b_t.
        const double n_beta = 1.0 / std::sqrt(frame.b);
        const double offset = i % 3 == 0 ? 0.0 : 1e-9 * unit(rng);
        const Eigen::Vector2d xi = n_beta * binormal.head<2>() + offset * Eigen::Vector2d(std::cos(i), std::sin(i));
        const double n1 = 1.0 + 2.0 * unit(rng);
        if (xi.norm() >= n1) continue;
        const Eigen::Vector3d direction(xi.x() / n1, xi.y() / n1, std::sqrt(1.0 - xi.squaredNorm() / (n1 * n1)));
        InterfaceIncidence incidence;
        incidence.direction = direction;
        incidence.coherency = coherency_from_stokes({1.0, unit(rng) - 0.5, 0.0, 0.0});
        const InterfaceResult result = solve_interface({0, 0, 1}, incidence, OpticalMedium::isotropic(n1), crystal);
        worst = std::max(worst, std::abs(total_power(result) - 1.0));
        for (const InterfaceWave& wave : result.waves) ASSERT_TRUE(wave.direction.allFinite() && std::isfinite(wave.power));
    }
    EXPECT_LT(worst, 1e-10);
}

TEST(Interface, BadInputIsRejected) {
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    EXPECT_THROW(solve_interface({0, 0, 0}, InterfaceIncidence{}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, NAN}, InterfaceIncidence{}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{Eigen::Vector3d(0, 0, -1)}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{Eigen::Vector3d(1, 0, 0)}, air, air), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, air, OpticalMedium::isotropic(-1.5)), InputError);
    EXPECT_THROW(solve_interface({0, 0, 1}, InterfaceIncidence{}, calcite_with_axis({1, 0, 0}), air), InputError);  // no mode named
}

}  // namespace
}  // namespace petroscope
