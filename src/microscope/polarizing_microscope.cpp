#include "petroscope/microscope/polarizing_microscope.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/slab.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace petroscope {
namespace {

/// The lab-frame vectors of the (s, p) basis of a direction: columns ŝ and ρ̂ (layer_stack.hpp).
Eigen::Matrix2d sp_to_lab(const TangentialWavevector& direction) {
    Eigen::Matrix2d basis;
    basis << direction.azimuthal, direction.radial;
    return basis;
}

}  // namespace

double DispersiveMedium::birefringence(double wavelength_nm) const {
    const Eigen::Vector3d n = principal_n(wavelength_nm);
    return n.maxCoeff() - n.minCoeff();
}

Eigen::Matrix3d DispersiveMedium::lab_gyration(double wavelength_nm) const {
    if (!gyration) return Eigen::Matrix3d::Zero();
    return turned_gyration(gyration(wavelength_nm), axes);
}

GyrationFunction mineral_gyration(const Mineral& mineral, Handedness handedness) {
    if (!mineral.optically_active()) return {};
    return [&mineral, handedness](double wavelength_nm) { return mineral.gyration(wavelength_nm, handedness); };
}

DispersiveMedium DispersiveMedium::of(const Mineral& mineral, const Eigen::Matrix3d& axes) {
    DispersiveMedium medium;
    medium.principal_n = [&mineral](double wavelength_nm) { return mineral.principal_n(wavelength_nm); };
    if (mineral.absorbing()) {
        medium.principal_kappa = [&mineral](double wavelength_nm) { return mineral.principal_kappa(wavelength_nm); };
    }
    medium.axes = axes;
    return medium;
}

DispersiveMedium DispersiveMedium::of(const Mineral& mineral, const Eigen::Matrix3d& axes, Handedness handedness) {
    DispersiveMedium medium = of(mineral, axes);
    medium.gyration = mineral_gyration(mineral, handedness);
    return medium;
}

OpticalMedium DispersiveMedium::at(double wavelength_nm) const {
    const Eigen::Vector3d kappa = principal_kappa ? principal_kappa(wavelength_nm) : Eigen::Vector3d::Zero();
    return OpticalMedium::from_n_kappa(principal_n(wavelength_nm), kappa, axes);
}

namespace {

// The nodes and weights of the Gauss rule for ∫₀¹ u·g(u) du with n nodes, by Golub & Welsch (Math. Comp. 23, 221,
// 1969): the eigenvalues of the Jacobi matrix of the Jacobi polynomials P^(0,1) on [−1, 1], mapped by u = (1 + x)/2.
// Its recurrence: diagonal 1/((2k + 1)(2k + 3)), off-diagonal √(k(k + 1))/(2k + 1) (Gautschi, Orthogonal
// Polynomials, 2004, Table 1.1); the weights are μ₀·v₀²/4 with μ₀ = ∫(1 + x)dx = 2 and v the unit eigenvectors.
std::pair<Eigen::VectorXd, Eigen::VectorXd> gauss_nodes_weighted_by_u(int n) {
    Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < n; ++k) {
        jacobi(k, k) = 1.0 / ((2.0 * k + 1.0) * (2.0 * k + 3.0));
        if (k > 0) jacobi(k, k - 1) = jacobi(k - 1, k) = std::sqrt(k * (k + 1.0)) / (2.0 * k + 1.0);
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
    const Eigen::VectorXd nodes = (1.0 + solver.eigenvalues().array()) / 2.0;
    const Eigen::VectorXd weights = solver.eigenvectors().row(0).transpose().array().square() / 2.0;
    return {nodes, weights};
}

// The settings' directions; automatic rings (0) must have been resolved by the caller (condenser_rings_for).
std::vector<IlluminationSample> resolved_condenser_samples(const MicroscopeSettings& settings) {
    if (settings.condenser_na > 0.0 && settings.condenser_rings == 0) throw std::logic_error("the condenser's rings were not resolved");
    return condenser_samples(settings.condenser_na, settings.condenser_rings);
}

}  // namespace

std::vector<IlluminationSample> condenser_samples(double condenser_na, int rings) {
    if (!(condenser_na >= 0.0 && condenser_na < 1.0)) {
        throw InputError("condenser NA " + format_number(condenser_na) + " is out of range (expected 0 <= NA < 1)");
    }
    if (condenser_na == 0.0 || rings == 0) return {IlluminationSample{}};
    if (rings < 0 || rings > kMaxCondenserRings) throw InputError("condenser rings must be 1 to " + std::to_string(kMaxCondenserRings));
    // The mean over the disc |ξ| ≤ NA is ∫₀¹ du (1/2π)∮ f dφ with u = |ξ|²/NA². In u a Gauss–Radau rule with its
    // fixed node at the centre: f(u) = f(0) + u·g(u), so ∫f = f(0) + Σⱼ Wⱼ(f(uⱼ) − f(0))/uⱼ with the rule for u·g
    // (rings nodes), exact for polynomials of degree 2·rings in u. In φ, 4·rings + 2 equally spaced points,
    // exact for trigonometric degree 4·rings + 1. Together exact for polynomials in ξ of degree 4·rings + 1
    // (Stroud, Approximate Calculation of Multiple Integrals, 1971, §2.7): 7 directions for degree 5.
    const auto [nodes, weights] = gauss_nodes_weighted_by_u(rings);
    const int azimuths = 4 * rings + 2;
    std::vector<IlluminationSample> samples{{Eigen::Vector2d::Zero(), 1.0}};
    for (int j = 0; j < rings; ++j) {
        const double ring_weight = weights[j] / nodes[j];
        samples.front().weight -= ring_weight;
        const double radius = condenser_na * std::sqrt(nodes[j]);
        // Alternate rings half a step apart. azimuths is even: the second half of a ring is the first reversed,
        // exactly, so that a crystal's waves serve each direction and its opposite (berreman_modes_both_ways).
        const std::size_t first = samples.size();
        for (int m = 0; m < azimuths / 2; ++m) {
            const double azimuth = 2.0 * std::numbers::pi * (m + 0.5 * (j % 2)) / azimuths;
            samples.push_back({radius * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth)), ring_weight / azimuths});
        }
        for (int m = 0; m < azimuths / 2; ++m) samples.push_back({-samples[first + m].xi, ring_weight / azimuths});
    }
    return samples;
}

int condenser_rings_for(double condenser_na, double phase_spread_rad) {
    if (condenser_na == 0.0) return 0;
    const double rings = std::ceil((phase_spread_rad + 1.0) / 4.0);
    return static_cast<int>(std::clamp(rings, 1.0, static_cast<double>(kMaxCondenserRings)));
}

double condenser_phase_spread_rad(const MicroscopeSettings& microscope, const DispersiveMedium& crystal, double thickness_um) {
    const double shortest_nm = *std::min_element(microscope.wavelengths_nm.begin(), microscope.wavelengths_nm.end());
    const double smallest_n = crystal.principal_n(shortest_nm).minCoeff();
    return 2.0 * std::numbers::pi * thickness_um * crystal.birefringence(shortest_nm) * microscope.condenser_na / (shortest_nm * 1e-3 * smallest_n);
}

Eigen::Matrix2cd plate_jones_lab(const AccessoryPlate& plate, double wavelength_nm, bool exact) {
    // The plate is crossed at normal incidence, where (s, p) = (ŷ, x̂): its lab Jones matrix is S·J·Sᵀ.
    const Eigen::Matrix2d normal_basis = sp_to_lab(TangentialWavevector::from_xi(Eigen::Vector2d::Zero()));
    const std::vector<OpticalLayer> layers{{plate.medium.permittivity(wavelength_nm), plate.thickness_um}};
    const Eigen::Matrix2cd jones = exact ? coherent_jones(layers, wavelength_nm, Eigen::Vector2d::Zero())
                                         : single_pass_jones(layers, 0, wavelength_nm, Eigen::Vector2d::Zero()).at(plate.thickness_um);
    return normal_basis * jones * normal_basis.transpose();
}

MicroscopeOptics::MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting)
    : MicroscopeOptics(settings, mounting, resolved_condenser_samples(settings)) {}

MicroscopeOptics::MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting,
                                   std::vector<IlluminationSample> directions)
    : settings_(settings), mounting_(mounting), directions_(std::move(directions)) {
    for (const double wavelength_nm : settings.wavelengths_nm) {
        plate_jones_lab_.push_back(settings.plate ? plate_jones_lab(*settings.plate, wavelength_nm, settings.exact)
                                                  : Eigen::Matrix2cd::Identity());
        mounting_epsilon_.push_back({mounting.slide.permittivity(wavelength_nm), mounting.cement.permittivity(wavelength_nm),
                                     mounting.cover.permittivity(wavelength_nm)});
    }
    build_paths();
}

MicroscopeOptics MicroscopeOptics::for_directions(std::vector<IlluminationSample> directions) const {
    MicroscopeOptics optics(*this, std::move(directions));
    optics.build_paths();
    return optics;
}

MicroscopeOptics::MicroscopeOptics(const MicroscopeOptics& common, std::vector<IlluminationSample> directions)
    : settings_(common.settings_),
      mounting_(common.mounting_),
      directions_(std::move(directions)),
      plate_jones_lab_(common.plate_jones_lab_),
      mounting_epsilon_(common.mounting_epsilon_) {}

void MicroscopeOptics::build_paths() {
    if (settings_.exact) return;
    paths_.clear();
    paths_.reserve(settings_.wavelengths_nm.size() * directions_.size());
    for (std::size_t w = 0; w < settings_.wavelengths_nm.size(); ++w) {
        const double k0 = wavenumber_per_um(settings_.wavelengths_nm[w]);
        const MountingPermittivity& epsilon = mounting_epsilon_[w];
        for (const IlluminationSample& direction : directions_) {
            const MediumWaves air = berreman_modes(Eigen::Matrix3cd::Identity(), direction.xi);
            const MediumWaves slide = berreman_modes(epsilon.slide, direction.xi);
            const MediumWaves cover = berreman_modes(epsilon.cover, direction.xi);
            Path path;
            path.cement = berreman_modes(epsilon.cement, direction.xi);
            path.k0_per_um = k0;
            path.into_crystal = forward_propagation(path.cement, k0, mounting_.lower_cement_um) *
                                forward_transmission(slide, path.cement) * forward_propagation(slide, k0, mounting_.slide_um) *
                                forward_transmission(air, slide) * incident(direction.xi);
            path.to_eye = after_section(w, direction.xi) * forward_transmission(cover, air) *
                          forward_propagation(cover, k0, mounting_.cover_um) * forward_transmission(path.cement, cover) *
                          forward_propagation(path.cement, k0, mounting_.upper_cement_um);
            paths_.push_back(path);
        }
    }
}

Eigen::Vector2cd MicroscopeOptics::incident(const Eigen::Vector2d& xi) const {
    // An aplanatic condenser keeps the s and p amplitudes of each ray (Richards & Wolf 1959): the polarizer's
    // field P splits as (P·ŝ, P·ρ̂).
    return (sp_to_lab(TangentialWavevector::from_xi(xi)).transpose() * unit_at(settings_.polars.polarizer_deg)).cast<std::complex<double>>();
}

Eigen::Matrix2cd MicroscopeOptics::after_section(std::size_t wavelength, const Eigen::Vector2d& xi) const {
    // The objective keeps s and p too: the field behind it is a_s·ŝ + a_p·ρ̂ in the lab frame.
    Eigen::Matrix2cd after = plate_jones_lab_[wavelength] * sp_to_lab(TangentialWavevector::from_xi(xi)).cast<std::complex<double>>();
    if (settings_.polars.analyzer_in) {
        const Eigen::RowVector2cd analyzed = unit_at(settings_.polars.analyzer_deg).cast<std::complex<double>>().transpose() * after;
        after.row(0) = analyzed;
        after.row(1).setZero();
    }
    return after;
}

double MicroscopeOptics::analyzed_intensity(const Eigen::Matrix2cd& section_jones_sp, std::size_t wavelength,
                                            std::size_t direction) const {
    const Eigen::Vector2d& xi = directions_[direction].xi;
    return (after_section(wavelength, xi) * section_jones_sp * incident(xi)).squaredNorm();
}

std::vector<OpticalLayer> MicroscopeOptics::section_layers(std::size_t wavelength, const Eigen::Matrix3cd& crystal,
                                                           const Eigen::Matrix3d& crystal_chirality, double crystal_thickness_um) const {
    const MountingPermittivity& epsilon = mounting_epsilon_[wavelength];
    return {{epsilon.slide, mounting_.slide_um},
            {epsilon.cement, mounting_.lower_cement_um},
            {crystal, crystal_thickness_um, crystal_chirality},
            {epsilon.cement, mounting_.upper_cement_um},
            {epsilon.cover, mounting_.cover_um}};
}

namespace {

// An optically active crystal's two forward waves in the single pass (docs/theory.md §9, "The single-pass slab:
// coupled modes"): the inactive crystal's waves, coupled inside by the gyration g (lab frame) as da/dz = i·k₀·Q·a,
// Q = [[q₀, i·c₀], [−i·c₁, q₁]] (optics/slab.hpp, gyration_coupling). Q = V·diag(λ)·V⁻¹, so the two waves of
// the active crystal are V's columns in the inactive basis, with q = λ: returned as (λ, V, V⁻¹). The coupling
// takes the inactive waves' real fields, which are those of a transparent crystal such as quartz.
struct CoupledWaves {
    Eigen::Vector2cd q;
    Eigen::Matrix2cd basis, inverse;
};

CoupledWaves coupled_waves(const MediumWaves& waves, const Eigen::Vector2d& xi, const Eigen::Matrix3d& gyration) {
    std::array<SlabMode, 2> forward;
    for (std::size_t m = 0; m < 2; ++m) {
        forward[m].q = waves[m].q.real();
        forward[m].e_field = waves[m].e_field.real();
        forward[m].h_field = waves[m].h_field.real();
    }
    const Eigen::Vector2d c = gyration_coupling(forward, xi, gyration);
    const std::complex<double> i(0.0, 1.0), q0 = waves[0].q, q1 = waves[1].q;
    const std::complex<double> root = std::sqrt(0.25 * (q0 - q1) * (q0 - q1) + c[0] * c[1]);
    CoupledWaves coupled;
    coupled.q = {0.5 * (q0 + q1) + root, 0.5 * (q0 + q1) - root};
    for (int m = 0; m < 2; ++m) {
        // (Q − λI)v = 0: v ∥ (i·c₀, λ − q₀) ∥ (λ − q₁, −i·c₁); the longer of the two is the better conditioned.
        const Eigen::Vector2cd first(i * c[0], coupled.q[m] - q0), second(coupled.q[m] - q1, -i * c[1]);
        coupled.basis.col(m) = first.squaredNorm() >= second.squaredNorm() ? first : second;
        coupled.basis.col(m).normalize();
    }
    coupled.inverse = coupled.basis.inverse();
    return coupled;
}

// A crystal's waves for each direction; a direction and its opposite from one decomposition.
std::vector<MediumWaves> crystal_waves(const Eigen::Matrix3cd& epsilon, const std::vector<IlluminationSample>& directions) {
    std::vector<MediumWaves> waves(directions.size());
    std::vector<bool> solved(directions.size(), false);
    for (std::size_t k = 0; k < directions.size(); ++k) {
        if (solved[k]) continue;
        const Eigen::Vector2d& xi = directions[k].xi;
        const auto opposite = std::find_if(directions.begin() + static_cast<std::ptrdiff_t>(k) + 1, directions.end(),
                                           [&xi](const IlluminationSample& other) { return other.xi == -xi; });
        if (xi.isZero()) {
            waves[k] = normal_incidence_waves(epsilon);
        } else if (opposite == directions.end()) {
            waves[k] = berreman_modes(epsilon, xi);
        } else {
            const std::size_t j = static_cast<std::size_t>(opposite - directions.begin());
            const auto both_ways = berreman_modes_both_ways(epsilon, xi);
            waves[k] = both_ways[0];
            waves[j] = both_ways[1];
            solved[j] = true;
        }
    }
    return waves;
}

}  // namespace

GrainResponse::GrainResponse(const MicroscopeOptics& optics, const DispersiveMedium& crystal)
    : optics_(optics), crystal_(crystal) {
    const MicroscopeSettings& settings = optics.settings();
    crystal_.axes = rotation_z_deg(settings.stage_deg) * crystal.axes;
    if (settings.exact) return;
    const std::vector<IlluminationSample>& directions = optics.directions();
    single_pass_.resize(settings.wavelengths_nm.size());
    for (std::size_t w = 0; w < settings.wavelengths_nm.size(); ++w) {
        const Eigen::Matrix3cd epsilon = crystal_.permittivity(settings.wavelengths_nm[w]);
        const Eigen::Matrix3d gyration = crystal_.lab_gyration(settings.wavelengths_nm[w]);
        const std::vector<MediumWaves> all_waves = crystal_waves(epsilon, directions);
        for (std::size_t k = 0; k < directions.size(); ++k) {
            const MicroscopeOptics::Path& path = optics.path(w, k);
            const MediumWaves& waves = all_waves[k];
            if (waves[0].evanescent || waves[1].evanescent) continue;
            Eigen::Vector2cd entry = forward_transmission(path.cement, waves) * path.into_crystal;
            Eigen::Matrix2cd exit = path.to_eye * forward_transmission(waves, path.cement);
            Eigen::Vector2cd q(waves[0].q, waves[1].q);
            if (!gyration.isZero(0.0)) {  // the active crystal's waves, in the inactive basis (coupled_waves)
                const CoupledWaves coupled = coupled_waves(waves, directions[k].xi, gyration);
                entry = coupled.inverse * entry;
                exit = exit * coupled.basis;
                q = coupled.q;
            }
            const std::array<Eigen::Vector2cd, 2> amplitude{exit.col(0) * entry[0], exit.col(1) * entry[1]};
            const std::array<std::complex<double>, 2> phase{path.k0_per_um * q[0], path.k0_per_um * q[1]};
            const double weight = directions[k].weight;
            Spectrum& spectrum = single_pass_[w];
            const auto add = [&spectrum](std::complex<double> coefficient, std::complex<double> rate_per_um) {
                if (rate_per_um == 0.0) {
                    spectrum.constant += coefficient.real();
                } else {
                    spectrum.terms.push_back({coefficient, rate_per_um});
                }
            };
            add(weight * amplitude[0].squaredNorm(), phase[0] - std::conj(phase[0]));
            add(weight * amplitude[1].squaredNorm(), phase[1] - std::conj(phase[1]));
            add(2.0 * weight * amplitude[1].dot(amplitude[0]), phase[0] - std::conj(phase[1]));
        }
    }
}

void GrainResponse::transmission(double thickness_um, std::vector<double>& out) const {
    const MicroscopeSettings& settings = optics_.settings();
    const std::size_t wavelength_count = settings.wavelengths_nm.size();
    const std::vector<IlluminationSample>& directions = optics_.directions();
    out.assign(wavelength_count, 0.0);
    if (settings.exact) {
        for (std::size_t w = 0; w < wavelength_count; ++w) {
            const double wavelength_nm = settings.wavelengths_nm[w];
            const std::vector<OpticalLayer> layers =
                optics_.section_layers(w, crystal_.permittivity(wavelength_nm), crystal_.chirality(wavelength_nm), thickness_um);
            for (std::size_t k = 0; k < directions.size(); ++k) {
                const Eigen::Matrix2cd jones = coherent_jones(layers, wavelength_nm, directions[k].xi);
                out[w] += directions[k].weight * optics_.analyzed_intensity(jones, w, k);
            }
        }
        return;
    }
    const std::complex<double> i(0.0, 1.0);
    for (std::size_t w = 0; w < wavelength_count; ++w) {
        double sum = single_pass_[w].constant;
        for (const Term& term : single_pass_[w].terms) sum += (term.coefficient * std::exp(i * term.rate_per_um * thickness_um)).real();
        out[w] = sum;
    }
}

void GrainResponse::transmission_series(double first_um, double step_um, int count,
                                        const std::function<void(int, const std::vector<double>&)>& consume) const {
    std::vector<double> spectrum;
    if (optics_.settings().exact) {
        for (int k = 0; k < count; ++k) {
            transmission(first_um + k * step_um, spectrum);
            consume(k, spectrum);
        }
        return;
    }
    // Each term's phasor c·exp(i·rate·d) at d = first_um, and its factor per step.
    const std::complex<double> i(0.0, 1.0);
    std::vector<std::complex<double>> phasor, factor;
    for (const Spectrum& wavelength : single_pass_) {
        for (const Term& term : wavelength.terms) {
            phasor.push_back(term.coefficient * std::exp(i * term.rate_per_um * first_um));
            factor.push_back(std::exp(i * term.rate_per_um * step_um));
        }
    }
    spectrum.resize(single_pass_.size());
    for (int k = 0; k < count; ++k) {
        std::size_t t = 0;
        for (std::size_t w = 0; w < single_pass_.size(); ++w) {
            double sum = single_pass_[w].constant;
            for (std::size_t end = t + single_pass_[w].terms.size(); t < end; ++t) {
                sum += phasor[t].real();
                phasor[t] *= factor[t];
            }
            spectrum[w] = sum;
        }
        consume(k, spectrum);
    }
}

}  // namespace petroscope
