#include "petroscope/verification/interface_suite.hpp"

#include "petroscope/core/angles.hpp"

#include "petroscope/optics/berreman.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/indicatrix.hpp"
#include "petroscope/optics/interface.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

namespace petroscope {
namespace {

using Kind = InterfaceWave::Kind;

InterfaceIncidence unpolarized(const Eigen::Vector3d& direction) {
    InterfaceIncidence incidence;
    incidence.direction = direction;
    return incidence;
}

InterfaceIncidence polarized(const Eigen::Vector3d& direction, const JonesVector& jones) {
    InterfaceIncidence incidence;
    incidence.direction = direction;
    incidence.jones = jones;
    incidence.coherency = coherency_from_jones(jones);
    return incidence;
}

const InterfaceWave* wave_of(const InterfaceResult& result, Kind kind, std::optional<InterfaceMode> mode = std::nullopt) {
    for (const InterfaceWave& wave : result.waves) {
        if (wave.kind == kind && (!mode || wave.mode == *mode)) return &wave;
    }
    return nullptr;
}

double total_power(const InterfaceResult& result) {
    double total = 0.0;
    for (const InterfaceWave& wave : result.waves) total += wave.power;
    return total;
}

Eigen::Vector3d unit_vector(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

Eigen::Matrix3d rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
}

// Isotropic (1–2.6), uniaxial or biaxial (1.3–2.8, birefringence up to 0.3), lossless, random orientation.
OpticalMedium random_medium(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    if (kind == 0) return OpticalMedium::isotropic(1.0 + 1.6 * unit(rng));
    const double n1 = 1.3 + 1.2 * unit(rng);
    const double n3 = n1 + (kind == 1 ? 0.6 * (unit(rng) - 0.5) : 0.001 + 0.3 * unit(rng));
    const double n2 = kind == 1 ? n1 : n1 + (0.02 + 0.96 * unit(rng)) * (n3 - n1);
    return OpticalMedium{Eigen::Vector3cd(n1, n2, n3), rotation(rng)};
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

VerificationTest fresnel_and_snell() {
    VerificationTest test{"isotropic-fresnel-snell",
                          "Reflection and refraction at isotropic interfaces 1 → 1.5, 1.5 → 1 and 1 → 2.4 from 0° to 89.9° (every 0.1°, "
                          "below the critical angle), geometry in random orientations: r_s, r_p, t_s, t_p equal the Fresnel formulas; "
                          "the reflection angle equals the incidence angle; n₁ sin θ₁ = n₂ sin θ₂; incident, reflected and refracted "
                          "wave normals lie in one plane with the normal; R + T = 1.",
                          "paper §3.1 statements 1–2; Born & Wolf §1.5.2",
                          {}};
    std::mt19937_64 rng(31);
    double worst_coefficient = 0.0, worst_geometry = 0.0, worst_energy = 0.0;
    for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4}}) {
        for (int tenth = 0; tenth <= 899; ++tenth) {
            const double theta = tenth * 0.1 * kDegree;
            const double sin2 = n1 * std::sin(theta) / n2;
            if (sin2 >= 1.0) continue;
            const double c1 = std::cos(theta), c2 = std::sqrt(1.0 - sin2 * sin2);
            const double r_s = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2), r_p = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
            const double t_s = 2 * n1 * c1 / (n1 * c1 + n2 * c2), t_p = 2 * n1 * c1 / (n2 * c1 + n1 * c2);
            const Eigen::Matrix3d frame = rotation(rng);
            const Eigen::Vector3d normal = frame.col(2);
            const Eigen::Vector3d k_in = frame * Eigen::Vector3d(std::sin(theta), 0.0, c1);
            for (int polarization = 0; polarization < 2; ++polarization) {
                const JonesVector jones = polarization == 0 ? JonesVector(1, 0) : JonesVector(0, 1);
                const InterfaceResult result = solve_interface(normal, polarized(k_in, jones), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
                const InterfaceWave& reflected = *wave_of(result, Kind::reflected);
                const InterfaceWave& transmitted = *wave_of(result, Kind::transmitted);
                const JonesVector expected_r = polarization == 0 ? JonesVector(r_s, 0) : JonesVector(0, r_p);
                const JonesVector expected_t = polarization == 0 ? JonesVector(t_s, 0) : JonesVector(0, t_p);
                worst_coefficient = std::max({worst_coefficient, (*reflected.jones - expected_r).norm(), (*transmitted.jones - expected_t).norm()});
                const Eigen::Vector3d plane_normal = k_in.cross(normal);
                worst_geometry = std::max({worst_geometry, std::abs(reflected.direction.dot(normal) + c1),
                                           std::abs(n1 * std::sin(theta) - n2 * transmitted.direction.cross(normal).norm()),
                                           std::abs(reflected.direction.dot(plane_normal)), std::abs(transmitted.direction.dot(plane_normal))});
                worst_energy = std::max(worst_energy, std::abs(total_power(result) - 1.0));
            }
        }
    }
    test.check("max |Fresnel amplitude − closed form|", worst_coefficient, 0.0, 1e-12);
    test.check("max error of reflection law, Snell's law, coplanarity", worst_geometry, 0.0, 1e-12);
    test.check("max |R + T − 1|", worst_energy, 0.0, 1e-12);
    return test;
}

VerificationTest total_internal_reflection() {
    VerificationTest test{"total-internal-reflection",
                          "1.5 → 1 beyond the critical angle (41.81°), from 42° to 89.9°: R = 1, the transmitted wave is evanescent and "
                          "carries no power, and r_s, r_p differ in phase by δ with tan(δ/2) = cos θ √(sin²θ − n²)/sin²θ (n = n₂/n₁), so "
                          "45° linear light leaves elliptical: |S3|/S0 = sin δ, |S2|/S0 = |cos δ|.",
                          "paper §3.1 statement 3; Born & Wolf §1.5.4",
                          {}};
    const double n1 = 1.5, n2 = 1.0, n = n2 / n1;
    double worst_reflectance = 0.0, worst_transmitted = 0.0, worst_polarization = 0.0;
    int propagating_transmitted = 0;
    for (int tenth = 420; tenth <= 899; ++tenth) {
        const double theta = tenth * 0.1 * kDegree;
        const Eigen::Vector3d k_in(std::sin(theta), 0.0, std::cos(theta));
        const InterfaceResult result = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(std::sqrt(0.5), std::sqrt(0.5))),
                                                       OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        const InterfaceWave& reflected = *wave_of(result, Kind::reflected);
        const InterfaceWave& transmitted = *wave_of(result, Kind::transmitted);
        worst_reflectance = std::max(worst_reflectance, std::abs(reflected.power - 1.0));
        worst_transmitted = std::max(worst_transmitted, transmitted.power);
        propagating_transmitted += transmitted.evanescent ? 0 : 1;
        const double s2 = std::sin(theta) * std::sin(theta);
        const double delta = 2.0 * std::atan(std::cos(theta) * std::sqrt(s2 - n * n) / s2);
        worst_polarization = std::max({worst_polarization, std::abs(std::abs(reflected.stokes[3]) / reflected.stokes[0] - std::sin(delta)),
                                       std::abs(std::abs(reflected.stokes[2]) / reflected.stokes[0] - std::abs(std::cos(delta)))});
    }
    test.check("max |R − 1|", worst_reflectance, 0.0, 1e-12);
    test.check("max transmitted power", worst_transmitted, 0.0, 1e-12);
    test.check("transmitted waves reported as propagating", propagating_transmitted, 0.0, 0.0);
    test.check("max error of the reflected Stokes vector (ellipticity)", worst_polarization, 0.0, 1e-12);
    return test;
}

VerificationTest brewster() {
    VerificationTest test{"brewster-angle",
                          "At tan θ_B = n₂/n₁ (1 → 1.5, 1.5 → 1, 1 → 2.4): R_p = 0 and the reflected wave is perpendicular to the refracted "
                          "one. The paper (§3.2, statement 3) says s-polarized light then has no refracted ray; that is wrong: s light is "
                          "partly reflected, R_s = sin²(θ₁ − θ₂)/sin²(θ₁ + θ₂) (0.1479 for 1 → 1.5), and the rest, T_s = 1 − R_s, is "
                          "refracted. The suite tests the physics.",
                          "paper §3.2; docs/theory.md §3; Born & Wolf §1.5.3",
                          {}};
    double worst_rp = 0.0, worst_perpendicular = 0.0, worst_rs = 0.0, worst_ts = 0.0;
    for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4}}) {
        const double theta = std::atan(n2 / n1);
        const Eigen::Vector3d k_in(std::sin(theta), 0.0, std::cos(theta));
        const InterfaceResult p = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(0, 1)), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        worst_rp = std::max(worst_rp, wave_of(p, Kind::reflected)->power);
        worst_perpendicular = std::max(worst_perpendicular, std::abs(wave_of(p, Kind::reflected)->direction.dot(wave_of(p, Kind::transmitted)->direction)));
        const InterfaceResult s = solve_interface({0, 0, 1}, polarized(k_in, JonesVector(1, 0)), OpticalMedium::isotropic(n1), OpticalMedium::isotropic(n2));
        const double theta2 = std::asin(n1 * std::sin(theta) / n2);
        const double r_s = std::pow(std::sin(theta - theta2) / std::sin(theta + theta2), 2);
        worst_rs = std::max(worst_rs, std::abs(wave_of(s, Kind::reflected)->power - r_s));
        worst_ts = std::max(worst_ts, std::abs(wave_of(s, Kind::transmitted)->power - (1.0 - r_s)));
    }
    test.check("max R_p", worst_rp, 0.0, 1e-15);
    test.check("max |k̂_reflected · k̂_refracted|", worst_perpendicular, 0.0, 1e-12);
    test.check("max |R_s − sin²(θ₁−θ₂)/sin²(θ₁+θ₂)|", worst_rs, 0.0, 1e-12);
    test.check("max |T_s − (1 − R_s)| (s light is transmitted)", worst_ts, 0.0, 1e-12);
    return test;
}

VerificationTest uniaxial_laws(int cases) {
    VerificationTest test{"uniaxial-ordinary-snell-and-slab",
                          "Calcite (ω = 1.6584, ε = 1.4864) in random orientations, incidence 0–89.9° from air: the ordinary wave obeys "
                          "Snell's law with n_o at every incidence; after a plane-parallel slab both the o and the e wave leave along "
                          "the incident direction.",
                          "paper §3.3; Born & Wolf §15.3",
                          {}};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_snell = 0.0, worst_exit = 0.0, worst_energy = 0.0;
    for (int i = 0; i < cases; ++i) {
        const OpticalMedium calcite = calcite_with_axis(unit_vector(rng));
        const double theta = 89.9 * kDegree * unit(rng), phi = 2 * std::numbers::pi * unit(rng);
        const Eigen::Vector3d k_in(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const InterfaceResult entry = solve_interface({0, 0, 1}, unpolarized(k_in), OpticalMedium::isotropic(1.0), calcite);
        const InterfaceWave& o = *wave_of(entry, Kind::transmitted, InterfaceMode::ordinary);
        worst_snell = std::max({worst_snell, std::abs(std::sin(theta) - 1.6584 * o.direction.cross(Eigen::Vector3d::UnitZ()).norm()),
                                std::abs(o.n.real() - 1.6584)});
        for (const InterfaceMode mode : {InterfaceMode::ordinary, InterfaceMode::extraordinary}) {
            InterfaceIncidence inside;
            inside.direction = wave_of(entry, Kind::transmitted, mode)->direction;
            inside.mode = mode;
            const InterfaceResult exit = solve_interface({0, 0, 1}, inside, calcite, OpticalMedium::isotropic(1.0));
            const InterfaceWave* out = wave_of(exit, Kind::transmitted);
            if (out->evanescent) continue;  // totally reflected at the exit face
            worst_exit = std::max(worst_exit, (out->direction - k_in).norm());
            worst_energy = std::max(worst_energy, std::abs(total_power(exit) - 1.0));
        }
    }
    test.check("max error of Snell's law for the o wave (and n_o)", worst_snell, 0.0, 1e-12);
    test.check("max |exit direction − incident direction|", worst_exit, 0.0, 1e-12);
    test.check("max |R + T − 1| at the exit face", worst_energy, 0.0, 1e-12);
    return test;
}

InterfaceIncidence random_incidence(std::mt19937_64& rng, const OpticalMedium& medium1, const Eigen::Vector3d& direction) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    InterfaceIncidence incidence;
    incidence.direction = direction;
    if (!medium1.has_s_and_p_waves()) {
        incidence.mode = unit(rng) < 0.5 ? InterfaceMode::fast : InterfaceMode::slow;
    } else {
        const Eigen::Vector3d axis = unit_vector(rng) * unit(rng);  // partially polarized
        incidence.coherency = coherency_from_stokes({1.0, axis.x(), axis.y(), axis.z()});
    }
    return incidence;
}

VerificationTest random_energy(int cases) {
    VerificationTest test{"energy-random-media",
                          "Lossless media (isotropic, uniaxial, biaxial on either side, random indices and orientations), incidence from 0 to "
                          "89.99°, random partial polarizations or crystal modes: the powers of all generated waves add up to the incident "
                          "power, R + T = 1.",
                          "petroscope",
                          {}};
    std::mt19937_64 rng(2027);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < cases; ++i) {
        const OpticalMedium medium1 = random_medium(rng, static_cast<int>(rng() % 3));
        const OpticalMedium medium2 = random_medium(rng, static_cast<int>(rng() % 3));
        const Eigen::Matrix3d frame = rotation(rng);
        const double theta = 89.99 * kDegree * unit(rng), phi = 2 * std::numbers::pi * unit(rng);
        const Eigen::Vector3d direction = frame * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        worst = std::max(worst, std::abs(total_power(solve_interface(frame.col(2), random_incidence(rng, medium1, direction), medium1, medium2)) - 1.0));
    }
    test.check("max |R + T − 1| over " + std::to_string(cases) + " cases", worst, 0.0, 1e-12);
    return test;
}

VerificationTest near_optic_axis(int cases) {
    VerificationTest test{"energy-on-and-near-optic-axes",
                          "The paper's defect (§5): near-normal incidence on a biaxial plate along a binormal gave waves whose powers added "
                          "up to more than the incident power. Here light refracts onto a binormal of a random biaxial or uniaxial crystal, "
                          "exactly or within 1e-9 rad: R + T = 1, and nothing is NaN.",
                          "paper §5",
                          {}};
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    int non_finite = 0;
    for (int i = 0; i < cases; ++i) {
        const OpticalMedium crystal = random_medium(rng, i % 4 == 0 ? 1 : 2);
        const BinormalFrame frame(Indicatrix{crystal.real_n(), crystal.axes});
        Eigen::Vector3d binormal = i % 2 == 0 ? frame.binormal_1 : frame.binormal_2;
        if (binormal.z() < 0) binormal = -binormal;
        if (binormal.z() < 0.2) continue;
        // The binormal's wave index is nβ: the wave from medium 1 that refracts onto it has ξ = nβ·b_t.
        const double n_beta = 1.0 / std::sqrt(frame.b);
        const double offset = i % 3 == 0 ? 0.0 : 1e-9 * unit(rng);
        const Eigen::Vector2d xi = n_beta * binormal.head<2>() + offset * Eigen::Vector2d(std::cos(i), std::sin(i));
        const double n1 = 1.0 + 2.0 * unit(rng);
        if (xi.norm() >= n1) continue;
        InterfaceIncidence incidence;
        incidence.direction = {xi.x() / n1, xi.y() / n1, std::sqrt(1.0 - xi.squaredNorm() / (n1 * n1))};
        incidence.coherency = coherency_from_stokes({1.0, unit(rng) - 0.5, 0.0, 0.0});
        const InterfaceResult result = solve_interface({0, 0, 1}, incidence, OpticalMedium::isotropic(n1), crystal);
        worst = std::max(worst, std::abs(total_power(result) - 1.0));
        for (const InterfaceWave& wave : result.waves) non_finite += (wave.direction.allFinite() && std::isfinite(wave.power)) ? 0 : 1;
    }
    test.check("max |R + T − 1|", worst, 0.0, 1e-10);
    test.check("waves with a non-finite direction or power", non_finite, 0.0, 0.0);
    return test;
}

// The 4×4 stack solver's answer for the interface's incident wave: the same tangential field, with ξ from the
// interface solution. `jones`: the incident state when medium 1 has s and p waves; otherwise the incident wave is
// medium 1's forward mode with the interface's incident index.
StackResponse stack_response(const InterfaceResult& result, const Eigen::Vector3d& direction, const OpticalMedium& medium1,
                             const OpticalMedium& medium2, const JonesVector& jones) {
    const Eigen::Vector2d xi = result.incident_n.real() * direction.head<2>();
    const StackLayer ambient{medium1.permittivity(), 0.0, chirality_tensor(medium1.lab_gyration())};
    const StackLayer substrate{medium2.permittivity(), 0.0, chirality_tensor(medium2.lab_gyration())};
    const auto modes = berreman_modes(ambient.epsilon, ambient.chirality, xi);
    Eigen::Vector4cd incident_psi;
    if (medium1.has_s_and_p_waves()) {
        incident_psi = jones[0] * modes[0].psi + jones[1] * modes[1].psi;
    } else {
        const auto index = [&](const BerremanMode& mode) { return std::abs(std::sqrt(xi.squaredNorm() + mode.q * mode.q) - result.incident_n); };
        incident_psi = index(modes[0]) <= index(modes[1]) ? modes[0].psi : modes[1].psi;
    }
    return solve_stack(ambient, {}, substrate, 589.3, xi, incident_psi);
}

// The largest difference between the interface solver's and the stack solver's wave powers. Compared per
// medium: a medium's s and p waves are one wave here; otherwise the two modes, matched by sorting their powers
// (the solvers order evanescent modes differently). Where the two modes' q nearly meet (an optic axis), how the
// power splits between them is ill-conditioned (the modes' fields move by about the rounding over the
// separation: Golub & Van Loan §7.2.4), and the double-precision 4×4 solver's split is good only to
// ~1e-16/separation: there the pair's total is compared, and `near_degenerate` counts it.
double power_difference(const InterfaceResult& result, const StackResponse& stack, const OpticalMedium& medium1, const OpticalMedium& medium2,
                        int& near_degenerate) {
    // Mode pairs whose q differ by less than this are compared by their total power.
    constexpr double kNearlyDegenerate = 1e-4;
    double worst = 0.0;
    const auto compare = [&](Kind kind, std::array<double, 2> berreman_power, const std::array<BerremanMode, 2>& modes, bool s_and_p) {
        std::vector<double> mine;
        for (const InterfaceWave& wave : result.waves) {
            if (wave.kind == kind) mine.push_back(wave.power);
        }
        const bool degenerate = !s_and_p && std::abs(modes[0].q - modes[1].q) < kNearlyDegenerate;
        if (s_and_p || degenerate) {
            near_degenerate += degenerate ? 1 : 0;
            worst = std::max(worst, std::abs(std::accumulate(mine.begin(), mine.end(), 0.0) - (berreman_power[0] + berreman_power[1])));
            return;
        }
        std::sort(mine.begin(), mine.end());
        std::sort(berreman_power.begin(), berreman_power.end());
        worst = std::max({worst, std::abs(mine.at(0) - berreman_power[0]), std::abs(mine.at(1) - berreman_power[1])});
    };
    compare(Kind::reflected, stack.reflected_power, stack.reflected_modes, medium1.has_s_and_p_waves());
    compare(Kind::transmitted, stack.transmitted_power, stack.transmitted_modes, medium2.has_s_and_p_waves());
    return worst;
}

JonesVector random_jones(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    JonesVector jones(std::complex<double>(unit(rng) - 0.5, unit(rng) - 0.5), std::complex<double>(unit(rng) - 0.5, unit(rng) - 0.5));
    return jones.normalized();
}

// A random incidence up to 85° from the normal z, and the wave: a random Jones vector, or a crystal mode.
std::pair<InterfaceIncidence, JonesVector> random_polarized_incidence(std::mt19937_64& rng, const OpticalMedium& medium1) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double theta = 85.0 * kDegree * unit(rng), phi = 2 * std::numbers::pi * unit(rng);
    const Eigen::Vector3d direction(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    InterfaceIncidence incidence;
    incidence.direction = direction;
    const JonesVector jones = random_jones(rng);
    if (medium1.has_s_and_p_waves()) {
        incidence = polarized(direction, jones);
    } else {
        incidence.mode = unit(rng) < 0.5 ? InterfaceMode::fast : InterfaceMode::slow;
    }
    return {incidence, jones};
}

VerificationTest against_berreman(int cases) {
    VerificationTest test{"interface-vs-4x4",
                          "The interface solver (modes from the Biot–Fresnel sheets or the quartic, boundary conditions solved directly) and "
                          "the independent Berreman 4×4 solver (modes from the eigenvectors of Δ) give every wave the same power, over random "
                          "lossless media and incidences (isotropic, uniaxial or biaxial on either side).",
                          "petroscope; Berreman, JOSA 62, 502 (1972)",
                          {}};
    std::mt19937_64 rng(4242);
    double worst = 0.0;
    int compared = 0, near_degenerate = 0;
    for (int i = 0; i < cases; ++i) {
        const OpticalMedium medium1 = random_medium(rng, static_cast<int>(rng() % 3));
        const OpticalMedium medium2 = random_medium(rng, static_cast<int>(rng() % 3));
        const auto [incidence, jones] = random_polarized_incidence(rng, medium1);
        const InterfaceResult result = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        worst = std::max(worst, power_difference(result, stack_response(result, incidence.direction, medium1, medium2, jones), medium1, medium2, near_degenerate));
        ++compared;
    }
    test.check("max |power difference| over " + std::to_string(compared) + " cases (" + std::to_string(near_degenerate) +
                   " nearly degenerate pairs compared by their total)",
               worst, 0.0, 1e-10);
    return test;
}

// Quartz's gyration along its axis at 589.3 nm: g₃₃ = λρ/π with ρ = 21.72°/mm (Lowry 1912).
constexpr double kQuartzGyration = 0.5893 * 21.72e-3 / 180.0;

// A random optically active medium: isotropic (g = g₀I), uniaxial (diag(g₁, g₁, g₃) in its frame) or biaxial
// (any symmetric g in its frame), gyrations from once to 100 times quartz's, of either sign.
OpticalMedium random_active_medium(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    OpticalMedium medium = random_medium(rng, kind);
    const auto random_gyration = [&] { return (unit(rng) < 0.5 ? -1.0 : 1.0) * kQuartzGyration * std::pow(100.0, unit(rng)); };
    if (kind == 0) {
        medium.gyration = random_gyration() * Eigen::Matrix3d::Identity();
    } else if (kind == 1) {
        const double g1 = random_gyration();
        medium.gyration = Eigen::Vector3d(g1, g1, random_gyration()).asDiagonal();
    } else {
        Eigen::Matrix3d g;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j <= i; ++j) g(i, j) = g(j, i) = random_gyration();
        }
        medium.gyration = g;
    }
    return medium;
}

VerificationTest optically_active(int cases) {
    VerificationTest test{"optically-active",
                          "Interfaces with optically active media (Landau's relation D = εE + i(g·N) × E, as Berreman's bianisotropic "
                          "relations). (1) A quartz-like uniaxial crystal (n_o = 1.5443, n_e = 1.5534, g₃₃ = 7.1e-5 and 100 times that, "
                          "g₁₁ = −g₃₃/2, both hands), its optic axis along the normal, normal incidence from vacuum, s-polarized: the two "
                          "transmitted waves are circular with the indices n̄ ∓ g₃₃/2, n̄ = √(n_o² + g₃₃²/4); both have the admittance n̄, so "
                          "R = ((n̄ − 1)/(n̄ + 1))² and each carries (1 − R)/2; the fast one is right circular for g₃₃ > 0 (dextrorotatory, "
                          "docs/conventions.md). (2) Random lossless media, active on one side or both (isotropic, uniaxial or biaxial, "
                          "gyrations 1–100 times quartz's), random incidences up to 85°, crystal modes or random polarizations: R + T = 1, "
                          "and every wave's power equals the independent 4×4 solver's.",
                          "Landau & Lifshitz vol. 8 §§100–101; Berreman, JOSA 62, 502 (1972)",
                          {}};
    const double n_o = 1.5443, n_e = 1.5534;
    double worst_index = 0.0, worst_power = 0.0, worst_circularity = 0.0;
    for (const double g33 : {kQuartzGyration, -kQuartzGyration, 100 * kQuartzGyration, -100 * kQuartzGyration}) {
        OpticalMedium quartz{Eigen::Vector3cd(n_o, n_o, n_e)};
        quartz.gyration = Eigen::Vector3d(-g33 / 2, -g33 / 2, g33).asDiagonal();
        const InterfaceResult result = solve_interface({0, 0, 1}, polarized({0, 0, 1}, JonesVector(1, 0)), OpticalMedium::isotropic(1.0), quartz);
        const double n_bar = std::hypot(n_o, g33 / 2), reflectance = std::pow((n_bar - 1) / (n_bar + 1), 2);
        const InterfaceWave& fast = *wave_of(result, Kind::transmitted, InterfaceMode::fast);
        const InterfaceWave& slow = *wave_of(result, Kind::transmitted, InterfaceMode::slow);
        worst_index = std::max({worst_index, std::abs(fast.n - (n_bar - std::abs(g33) / 2)), std::abs(slow.n - (n_bar + std::abs(g33) / 2))});
        worst_power = std::max({worst_power, std::abs(wave_of(result, Kind::reflected)->power - reflectance), std::abs(fast.power - (1 - reflectance) / 2),
                                std::abs(slow.power - (1 - reflectance) / 2)});
        const double sense = g33 > 0 ? 1.0 : -1.0;  // S3 = +S0: right circular
        worst_circularity = std::max({worst_circularity, std::abs(fast.stokes[3] / fast.stokes[0] - sense), std::abs(slow.stokes[3] / slow.stokes[0] + sense)});
    }
    test.check("max |index − n̄ ∓ g₃₃/2| along the axis", worst_index, 0.0, 1e-12);
    test.check("max |power − closed form| along the axis", worst_power, 0.0, 1e-12);
    test.check("max |S3/S0 ∓ 1| of the transmitted waves (fast: right for g₃₃ > 0)", worst_circularity, 0.0, 1e-12);

    std::mt19937_64 rng(1972);
    double worst_energy = 0.0, worst_difference = 0.0;
    int near_degenerate = 0;
    for (int i = 0; i < cases; ++i) {
        // Active medium 2, active medium 1, or both.
        const int sides = i % 3;
        const int kind1 = static_cast<int>(rng() % 3), kind2 = static_cast<int>(rng() % 3);
        const OpticalMedium medium1 = sides == 0 ? random_medium(rng, kind1) : random_active_medium(rng, kind1);
        const OpticalMedium medium2 = sides == 1 ? random_medium(rng, kind2) : random_active_medium(rng, kind2);
        const auto [incidence, jones] = random_polarized_incidence(rng, medium1);
        const InterfaceResult result = solve_interface({0, 0, 1}, incidence, medium1, medium2);
        worst_energy = std::max(worst_energy, std::abs(total_power(result) - 1.0));
        worst_difference = std::max(worst_difference, power_difference(result, stack_response(result, incidence.direction, medium1, medium2, jones), medium1, medium2, near_degenerate));
    }
    test.check("max |R + T − 1| over " + std::to_string(cases) + " random cases", worst_energy, 0.0, 1e-12);
    test.check("max |power difference| from the 4×4 solver (" + std::to_string(near_degenerate) + " nearly degenerate pairs compared by their total)",
               worst_difference, 0.0, 1e-10);
    return test;
}

}  // namespace

std::vector<VerificationTest> run_interface_suite(const InterfaceSuiteSize& size) {
    return {fresnel_and_snell(),       total_internal_reflection(),          brewster(),
            uniaxial_laws(size.uniaxial_cases), random_energy(size.random_energy_cases), near_optic_axis(size.near_axis_cases),
            against_berreman(size.berreman_cases), optically_active(size.optically_active_cases)};
}

}  // namespace petroscope
