#include "petroscope/optics/interface.hpp"

#include "local_modes.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/eigenmodes.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <tuple>

namespace petroscope {
namespace {

using complex = std::complex<double>;
using detail::LocalMode;
using detail::LocalModes;
template <typename Real>
using Vector4c = Eigen::Matrix<std::complex<Real>, 4, 1>;
// At most 4 × 4 (the boundary system), so on the stack.
template <typename Real>
using SmallMatrix = Eigen::Matrix<std::complex<Real>, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
template <typename Real>
using SmallJones = Eigen::Matrix<std::complex<Real>, Eigen::Dynamic, 1, 0, 2, 1>;

template <typename Real>
complex rounded(std::complex<Real> z) { return {static_cast<double>(z.real()), static_cast<double>(z.imag())}; }

// √(N·N) for N = (ξ, 0, q): the (complex) index of a mode.
template <typename Real>
std::complex<Real> mode_index(Real xi, const LocalMode<Real>& mode) {
    std::complex<Real> n = std::sqrt(xi * xi + mode.q * mode.q);
    return n.real() < Real(0) ? -n : n;
}

// The local frame: z along the normal, x along the incident wave's tangential direction (so that the
// tangential wavevector is (ξ, 0)), y = z × x = ŝ. At normal incidence ŝ = normal × x̂ (or normal × ŷ when
// the normal lies along x), as in docs/interface.md. Rows: local axes in lab coordinates.
Eigen::Matrix3d local_frame(const Eigen::Vector3d& normal, const Eigen::Vector3d& k_hat) {
    const Eigen::Vector3d tangential = k_hat - k_hat.dot(normal) * normal;
    Eigen::Vector3d y;
    if (tangential.norm() > 1e-15) {
        y = normal.cross(tangential).normalized();
    } else {
        const Eigen::Vector3d reference = std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
        y = normal.cross(reference).normalized();
    }
    const Eigen::Vector3d x = y.cross(normal);
    Eigen::Matrix3d frame;
    frame.row(0) = x.transpose();
    frame.row(1) = y.transpose();
    frame.row(2) = normal.transpose();
    return frame;
}

OpticalMedium in_frame(const OpticalMedium& medium, const Eigen::Matrix3d& frame) {
    return OpticalMedium{medium.principal_n, frame * medium.axes, medium.gyration};
}

// The indices of the two waves of an optically active medium whose wave normal is k̂ (fast first): its modes
// at normal incidence on the plane ⟂ k̂, where q = n.
template <typename Real>
std::array<double, 2> active_indices(const OpticalMedium& medium, const Eigen::Vector3d& k_hat) {
    const LocalModes<Real> along = detail::local_modes<Real>(in_frame(medium, local_frame(k_hat, k_hat)), 0.0);
    return {static_cast<double>(along.forward[0].q.real()), static_cast<double>(along.forward[1].q.real())};
}

// The mode of sheet `sheet` (0: smaller Re n) of a medium without s and p waves. An optically active medium's
// waves are elliptical, neither ordinary nor extraordinary: fast and slow.
template <typename Real>
InterfaceMode anisotropic_mode(const OpticalMedium& medium, const LocalModes<Real>& modes, Real xi, int sheet, bool forward) {
    if (!medium.is_uniaxial() || medium.is_active()) return sheet == 0 ? InterfaceMode::fast : InterfaceMode::slow;
    // Uniaxial: the ordinary wave is the one whose index is n_o (the repeated principal index).
    const complex n_o_double = medium.principal_n[0] == medium.principal_n[1] ? medium.principal_n[0] : medium.principal_n[2];
    const std::complex<Real> n_o(n_o_double.real(), n_o_double.imag());
    const auto& pair = forward ? modes.forward : modes.backward;
    const auto distance = [&](const LocalMode<Real>& mode) { return detail::magnitude_squared(mode_index(xi, mode) - n_o); };
    const bool first_is_ordinary = distance(pair[0]) <= distance(pair[1]);
    return (sheet == 0) == first_is_ordinary ? InterfaceMode::ordinary : InterfaceMode::extraordinary;
}

template <typename Real>
Vector4c<Real> tangential(const LocalMode<Real>& mode) {
    return {mode.e_field.x(), mode.e_field.y(), mode.h_field.x(), mode.h_field.y()};
}

// ⟨u, v⟩ = ½(E_u × H_v* + E_v* × H_u)_z: the cross term of the z flux of a superposition of u and v (for
// u = v, twice the flux). Distinct modes of a lossless medium are exactly orthogonal in it.
template <typename Real>
std::complex<Real> flux_form(const LocalMode<Real>& u, const LocalMode<Real>& v) {
    return Real(0.5) * (detail::bilinear_cross<Real>(u.e_field, v.h_field.conjugate()) + detail::bilinear_cross<Real>(v.e_field.conjugate(), u.h_field)).z();
}

// Restores the exact power orthogonality of the propagating modes of a lossless medium (Gram–Schmidt in
// the flux form, in the given order). Rounding breaks it by about residual/splitting: near grazing
// incidence, where a sheet's forward and backward roots nearly meet, or on an optic axis, where any basis
// of the degenerate pair is a solution, and the per-wave powers would then not add up. The fields change
// by the relative amount of that broken orthogonality, within their conditioning.
template <typename Real>
void orthogonalize_fluxes(const std::vector<LocalMode<Real>*>& modes) {
    for (std::size_t i = 0; i < modes.size(); ++i) {
        if (modes[i]->evanescent) continue;
        for (std::size_t j = 0; j < i; ++j) {
            const LocalMode<Real>& u = *modes[j];
            if (u.evanescent) continue;
            const Real self = Real(2) * u.flux_z;  // flux_form(u, u), u's flux already restored
            const std::complex<Real> beta = std::conj(flux_form(u, *modes[i])) / self;
            modes[i]->e_field -= beta * u.e_field;
            modes[i]->h_field -= beta * u.h_field;
        }
        modes[i]->flux_z = detail::poynting_z(modes[i]->e_field, modes[i]->h_field);
    }
}

// One outgoing wave: a group of modes (one anisotropic mode, or the s and p modes of an isotropic medium).
template <typename Real>
struct Group {
    std::array<const LocalMode<Real>*, 2> modes{};
    std::array<int, 2> unknowns{};  // their columns in the boundary system
    std::size_t size = 1;           // 2 for the s and p modes of an isotropic medium
    InterfaceMode mode;
    InterfaceWave::Kind kind;
};

// x with A x = B by Gaussian elimination with complete pivoting (Golub & Van Loan, Matrix Computations,
// 4th ed., §3.4.8), pivots chosen by |z|² and inverted as z̄/|z|² (no hypotl, no complex division). An
// unknown whose pivot is below 4ε of the largest (a rank-deficient system) is set to zero, as Eigen's
// FullPivLU does.
template <typename Real>
SmallMatrix<Real> solve_full_pivoting(Eigen::Matrix<std::complex<Real>, 4, 4> a, const SmallMatrix<Real>& right_hand_sides) {
    const Eigen::Index columns = right_hand_sides.cols();
    Eigen::Matrix<std::complex<Real>, 4, 2> b = Eigen::Matrix<std::complex<Real>, 4, 2>::Zero();
    b.leftCols(columns) = right_hand_sides;
    std::array<int, 4> unknown_of_column{0, 1, 2, 3};
    Real largest_pivot = Real(0);
    int rank = 4;
    for (int k = 0; k < 4 && rank == 4; ++k) {
        const auto [best, pivot_row, pivot_column] = detail::largest_entry(a, k);
        largest_pivot = std::max(largest_pivot, best);
        const Real threshold = Real(4) * std::numeric_limits<Real>::epsilon();
        if (!(best > threshold * threshold * largest_pivot)) {
            rank = k;
            break;
        }
        a.row(k).swap(a.row(pivot_row));
        b.row(k).swap(b.row(pivot_row));
        a.col(k).swap(a.col(pivot_column));
        std::swap(unknown_of_column[static_cast<std::size_t>(k)], unknown_of_column[static_cast<std::size_t>(pivot_column)]);
        const std::complex<Real> inverse = std::conj(a(k, k)) / best;
        for (int i = k + 1; i < 4; ++i) {
            const std::complex<Real> factor = a(i, k) * inverse;
            for (int j = k + 1; j < 4; ++j) a(i, j) -= factor * a(k, j);
            for (int c = 0; c < 2; ++c) b(i, c) -= factor * b(k, c);
        }
        a(k, k) = inverse;  // kept for the back substitution
    }
    Eigen::Matrix<std::complex<Real>, 4, 2> permuted = Eigen::Matrix<std::complex<Real>, 4, 2>::Zero();
    for (int i = rank - 1; i >= 0; --i) {
        for (int c = 0; c < 2; ++c) {
            std::complex<Real> value = b(i, c);
            for (int j = i + 1; j < rank; ++j) value -= a(i, j) * permuted(j, c);
            permuted(i, c) = value * a(i, i);
        }
    }
    SmallMatrix<Real> x(4, columns);
    for (int k = 0; k < 4; ++k) x.row(unknown_of_column[static_cast<std::size_t>(k)]) = permuted.row(k).leftCols(columns);
    return x;
}

// The flux of the incident state `coherency` (in the input basis) over the input modes, which carry no
// cross flux.
template <typename Real>
Real incident_flux_of(const SmallMatrix<Real>& coherency, const std::vector<LocalMode<Real>*>& inputs) {
    Real flux = Real(0);
    for (std::size_t i = 0; i < inputs.size(); ++i) flux += coherency(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)).real() * inputs[i]->flux_z;
    return flux;
}

// One outgoing wave's share of the boundary solution: per mode of its group the amplitudes for each
// input basis state (1 × inputs) and the mode's flux, and the wave's transverse field in its own (s, p)
// basis per input state (2 × inputs).
template <typename Real>
struct WaveAmplitudes {
    int mode_count = 0;
    std::array<SmallMatrix<Real>, 2> modes;
    std::array<Real, 2> fluxes{};
    SmallMatrix<Real> basis_jones;
    bool carries_power = true;  // false for the evanescent waves of lossless media
};

struct WaveStokes {
    double power = 0.0;
    Eigen::Vector4d stokes = Eigen::Vector4d::Zero();
};

// The wave's power relative to the incident flux and its Stokes vector (S0 = power) for the incident
// state `coherency` (in the input basis) of flux `incident_flux`.
template <typename Real>
WaveStokes wave_stokes(const WaveAmplitudes<Real>& wave, const SmallMatrix<Real>& coherency, Real incident_flux) {
    Real flux = Real(0);
    for (std::size_t m = 0; m < static_cast<std::size_t>(wave.mode_count); ++m) flux += (wave.modes[m] * coherency * wave.modes[m].adjoint())(0, 0).real() * wave.fluxes[m];
    WaveStokes result;
    result.power = wave.carries_power ? static_cast<double>(std::abs(flux) / incident_flux) : 0.0;
    const SmallMatrix<Real> out = wave.basis_jones * coherency * wave.basis_jones.adjoint();
    CoherencyMatrix out_double;
    for (int i = 0; i < 2; ++i) for (int j = 0; j < 2; ++j) out_double(i, j) = rounded(out(i, j));
    const Eigen::Vector4d stokes = stokes_from_coherency(out_double);
    if (stokes[0] > 0.0) result.stokes = stokes * (result.power / stokes[0]);
    return result;
}

// The Mueller matrix of a wave for an isotropic medium 1 (inputs: its s and p modes, of equal flux):
// its Stokes vectors for unpolarized, s, +45° and right circular light, by differences (the map is linear).
template <typename Real>
Eigen::Matrix4d wave_mueller(const WaveAmplitudes<Real>& wave, const std::vector<LocalMode<Real>*>& inputs) {
    const std::array<Eigen::Vector4d, 4> states{Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 1, 0, 0), Eigen::Vector4d(1, 0, 1, 0),
                                                Eigen::Vector4d(1, 0, 0, 1)};
    Eigen::Matrix4d mueller;
    for (int k = 0; k < 4; ++k) {
        const SmallMatrix<Real> coherency = coherency_from_stokes(states[static_cast<std::size_t>(k)]).template cast<std::complex<Real>>();
        const Eigen::Vector4d stokes = wave_stokes(wave, coherency, incident_flux_of(coherency, inputs)).stokes;
        mueller.col(k) = k == 0 ? stokes : Eigen::Vector4d(stokes - mueller.col(0));
    }
    return mueller;
}

InputError bad(const std::string& what) { return InputError(what); }

void check_vector(const Eigen::Vector3d& v, const std::string& what) {
    if (!v.allFinite() || v.norm() == 0.0) throw bad(what + " must be a finite, non-zero vector");
}

void check_medium(const OpticalMedium& medium, const std::string& what) {
    for (int i = 0; i < 3; ++i) {
        const complex n = medium.principal_n[i];
        if (!std::isfinite(n.real()) || !std::isfinite(n.imag()) || n.real() <= 0.0 || n.imag() < 0.0) {
            throw bad(what + ": refractive indices must be finite with n > 0 and κ >= 0");
        }
    }
    if (!medium.axes.allFinite() || !(medium.axes.transpose() * medium.axes).isIdentity(1e-9)) {
        throw bad(what + ": orientation is not a rotation");
    }
    const Eigen::Matrix3d& g = medium.gyration;
    if (!g.allFinite() || !(g - g.transpose()).isZero(1e-12 * std::max(1.0, g.cwiseAbs().maxCoeff()))) {
        throw bad(what + ": the gyration tensor must be finite and symmetric");
    }
}

// Indexed by InterfaceMode.
constexpr std::array<std::string_view, 5> kModeNames{"s+p", "fast", "slow", "ordinary", "extraordinary"};

// The solve, its inputs checked, in the arithmetic `Real`.
template <typename Real>
InterfaceResult solve_interface_in(const Eigen::Vector3d& normal_in, const InterfaceIncidence& incidence, const OpticalMedium& medium1,
                                   const OpticalMedium& medium2) {
    const Eigen::Vector3d normal = normal_in.normalized();
    const Eigen::Vector3d k_hat = incidence.direction.normalized();
    const double cos_incidence = k_hat.dot(normal);
    if (!(cos_incidence > 0.0)) {
        throw bad("the incident direction must point from medium 1 into medium 2 (positive component along the normal)");
    }
    const Eigen::Matrix3d frame = local_frame(normal, k_hat);
    const OpticalMedium local1 = in_frame(medium1, frame), local2 = in_frame(medium2, frame);

    // The incident wave: its index (a mode's, in an anisotropic medium 1) fixes ξ = n sin θ.
    InterfaceResult result;
    int incident_sheet = -1;
    if (medium1.has_s_and_p_waves()) {
        result.incident_n = medium1.principal_n[0];
    } else {
        const bool named_by_axis = medium1.is_uniaxial() && !medium1.is_active();
        const std::array<double, 2> n = medium1.is_active() ? active_indices<Real>(medium1, k_hat) : [&] {
            const ModePair pair = eigenmodes(BinormalFrame(Indicatrix{medium1.real_n(), medium1.axes}), k_hat);
            return std::array<double, 2>{pair.fast.n, pair.slow.n};
        }();
        const std::optional<InterfaceMode> mode = incidence.mode;
        if (mode == InterfaceMode::fast || mode == InterfaceMode::slow) {
            incident_sheet = mode == InterfaceMode::fast ? 0 : 1;
        } else if (named_by_axis && (mode == InterfaceMode::ordinary || mode == InterfaceMode::extraordinary)) {
            const double n_o = medium1.principal_n[0] == medium1.principal_n[1] ? medium1.principal_n[0].real() : medium1.principal_n[2].real();
            const bool fast_is_ordinary = std::abs(n[0] - n_o) <= std::abs(n[1] - n_o);
            incident_sheet = (mode == InterfaceMode::ordinary) == fast_is_ordinary ? 0 : 1;
        } else {
            throw bad(std::string(medium1.is_active() ? "medium 1 is optically active" : "medium 1 is anisotropic") +
                      ": the incident wave must be one of its modes, \"fast\" or \"slow\"" +
                      std::string(named_by_axis ? " (or \"ordinary\", \"extraordinary\")" : "") +
                      (mode ? ", not " + quote_input(wave_mode_name(*mode)) : ", but none was given"));
        }
        result.incident_n = n[static_cast<std::size_t>(incident_sheet)];
    }
    // ξ = n sin θ, with sin θ as the length of the tangential part of k̂ (√(1 − cos²θ) would lose it near
    // normal incidence).
    const Eigen::Vector3d tangential_part = k_hat - cos_incidence * normal;  // |…| = sin θ, exact near normal incidence
    const Real xi = static_cast<Real>(result.incident_n.real()) * static_cast<Real>(tangential_part.norm());
    LocalModes<Real> modes1 = detail::local_modes<Real>(local1, static_cast<double>(xi));
    LocalModes<Real> modes2 = detail::local_modes<Real>(local2, static_cast<double>(xi));

    // Incident waves (one per input basis state): s and p, or the chosen mode.
    std::vector<LocalMode<Real>*> inputs;
    if (incident_sheet < 0) {
        inputs = {&modes1.forward[0], &modes1.forward[1]};
    } else {
        // The propagating forward mode with the incident wave's index (an evanescent sibling may sort first).
        const std::complex<Real> incident_n(result.incident_n.real(), result.incident_n.imag());
        const auto mismatch = [&](const LocalMode<Real>& mode) {
            return mode.evanescent ? Real(1e300) : detail::magnitude_squared(mode_index(xi, mode) - incident_n);
        };
        inputs.push_back(mismatch(modes1.forward[0]) <= mismatch(modes1.forward[1]) ? &modes1.forward[0] : &modes1.forward[1]);
    }
    // Power orthogonality (lossless anisotropic media): the incident mode stays as it is, the others are
    // made orthogonal to it and to each other.
    if (!medium1.has_s_and_p_waves() && medium1.is_lossless()) {
        std::vector<LocalMode<Real>*> order{inputs.front()};
        for (LocalMode<Real>* mode : {&modes1.forward[0], &modes1.forward[1], &modes1.backward[0], &modes1.backward[1]}) {
            if (mode != inputs.front()) order.push_back(mode);
        }
        orthogonalize_fluxes(order);
    }
    if (!medium2.has_s_and_p_waves() && medium2.is_lossless()) orthogonalize_fluxes<Real>({&modes2.forward[0], &modes2.forward[1]});
    const Eigen::Matrix3d to_lab = frame.transpose();
    const auto lab_vector = [&](const Eigen::Matrix<Real, 3, 1>& local) -> Eigen::Vector3d {
        return to_lab * local.template cast<double>().normalized();
    };
    result.incident_ray_direction = lab_vector(detail::poynting(inputs.front()->e_field, inputs.front()->h_field));

    // Boundary conditions: Σ rⱼ ψ(backward₁ⱼ) − Σ tₖ ψ(forward₂ₖ) = −ψ(incident) for the tangential
    // (E_x, E_y, H_x, H_y), solved in `Real` (see local_modes.hpp).
    Eigen::Matrix<std::complex<Real>, 4, 4> system;
    system << tangential(modes1.backward[0]), tangential(modes1.backward[1]), -tangential(modes2.forward[0]),
        -tangential(modes2.forward[1]);
    const int input_count = static_cast<int>(inputs.size());
    SmallMatrix<Real> right_hand_sides(4, input_count);
    for (int i = 0; i < input_count; ++i) right_hand_sides.col(i) = -tangential(*inputs[static_cast<std::size_t>(i)]);
    const SmallMatrix<Real> amplitudes = solve_full_pivoting(system, right_hand_sides);

    // The incident state in the input basis, and its flux (the s and p modes carry no cross flux).
    SmallMatrix<Real> coherency = SmallMatrix<Real>::Ones(1, 1);
    std::optional<SmallJones<Real>> jones;
    if (incident_sheet < 0) {
        coherency = (incidence.coherency / incidence.coherency.trace().real()).template cast<std::complex<Real>>();
        if (incidence.jones) jones = (*incidence.jones / incidence.jones->norm()).template cast<std::complex<Real>>();
    } else {
        jones = SmallJones<Real>::Ones(1);
    }
    const Real incident_flux = incident_flux_of(coherency, inputs);

    std::array<Group<Real>, 4> groups;
    std::size_t group_count = 0;
    const auto add_groups = [&](const OpticalMedium& medium, const OpticalMedium& local, const LocalModes<Real>& modes, bool reflected) {
        const auto& pair = reflected ? modes.backward : modes.forward;
        const int base = reflected ? 0 : 2;
        const auto kind = reflected ? InterfaceWave::Kind::reflected : InterfaceWave::Kind::transmitted;
        if (medium.has_s_and_p_waves()) {
            groups[group_count++] = {{&pair[0], &pair[1]}, {base, base + 1}, 2, InterfaceMode::isotropic, kind};
        } else {
            for (int sheet = 0; sheet < 2; ++sheet) {
                groups[group_count++] = {{&pair[static_cast<std::size_t>(sheet)], nullptr}, {base + sheet, 0}, 1, anisotropic_mode(local, modes, xi, sheet, !reflected), kind};
            }
        }
    };
    add_groups(medium1, local1, modes1, true);
    add_groups(medium2, local2, modes2, false);

    const bool lossless = medium1.is_lossless() && medium2.is_lossless();
    result.waves.reserve(group_count);
    for (const Group<Real>& group : std::span(groups.data(), group_count)) {
        InterfaceWave wave;
        wave.kind = group.kind;
        wave.mode = group.mode;
        const LocalMode<Real>& lead = *group.modes[0];
        wave.n = rounded(mode_index(xi, lead));
        const Eigen::Matrix<Real, 3, 1> direction(xi, Real(0), lead.q.real());
        const Eigen::Vector3d local_direction = direction.template cast<double>().normalized();
        wave.direction = to_lab * local_direction;
        wave.evanescent = lead.evanescent;
        // Field of the wave per input state: E = Σ aₘ eₘ (3 × inputs), its modes' amplitudes and fluxes.
        SmallMatrix<Real> field = SmallMatrix<Real>::Zero(3, input_count);
        WaveAmplitudes<Real> wave_amplitudes;
        wave_amplitudes.carries_power = !(wave.evanescent && lossless);
        Eigen::Matrix<Real, 3, 1> ray = Eigen::Matrix<Real, 3, 1>::Zero();
        for (std::size_t m = 0; m < group.size; ++m) {
            const SmallMatrix<Real> a = amplitudes.row(group.unknowns[m]);
            field += group.modes[m]->e_field * a;
            wave_amplitudes.modes[m] = a;
            wave_amplitudes.fluxes[m] = group.modes[m]->flux_z;
            ++wave_amplitudes.mode_count;
            // A mode's ray is its own whatever its amplitude (zero-power waves included); an isotropic
            // wave's s and p rays coincide.
            ray += detail::poynting(group.modes[m]->e_field, group.modes[m]->h_field) * (std::abs(group.modes[m]->flux_z) > Real(0) ? Real(1) / std::abs(group.modes[m]->flux_z) : Real(1));
        }
        wave.ray_direction = ray.norm() > Real(0) ? lab_vector(ray) : wave.direction;
        // The wave's own (s, p) basis: ŝ = normal × k̂ (ŷ when k̂ ∥ normal), p̂ = ŝ × k̂.
        Eigen::Vector3d s_hat = Eigen::Vector3d::UnitZ().cross(local_direction);
        s_hat = s_hat.norm() > 1e-15 ? Eigen::Vector3d(s_hat.normalized()) : Eigen::Vector3d::UnitY();
        const Eigen::Vector3d p_hat = s_hat.cross(local_direction);
        SmallMatrix<Real>& basis_jones = wave_amplitudes.basis_jones;
        basis_jones.resize(2, input_count);
        basis_jones.row(0) = s_hat.template cast<Real>().template cast<std::complex<Real>>().transpose() * field;
        basis_jones.row(1) = p_hat.template cast<Real>().template cast<std::complex<Real>>().transpose() * field;
        const WaveStokes out = wave_stokes(wave_amplitudes, coherency, incident_flux);
        wave.power = out.power;
        wave.stokes = out.stokes;
        if (incident_sheet < 0 && incidence.with_mueller) wave.mueller = wave_mueller(wave_amplitudes, inputs);
        const OpticalMedium& local = group.kind == InterfaceWave::Kind::reflected ? local1 : local2;
        if (group.size == 1 && !local.is_active()) {
            // D = εE; its common phase removed through its largest component.
            const detail::Vector3c<Real> d = local.permittivity().template cast<std::complex<Real>>() * lead.e_field;
            Eigen::Index largest = 0;
            d.cwiseAbs2().maxCoeff(&largest);
            const detail::Vector3c<Real> phased = d * std::conj(d[largest]);  // its length does not matter
            wave.d_direction = to_lab * phased.real().template cast<double>().normalized();
        }
        if (jones) {
            if (group.size == 2) {
                const SmallJones<Real> out_jones = basis_jones * *jones;
                wave.jones = JonesVector(rounded(out_jones[0]), rounded(out_jones[1]));
            } else {
                wave.amplitude = rounded((amplitudes.row(group.unknowns[0]) * *jones)(0, 0));
                Eigen::Vector3cd local_field;
                for (int k = 0; k < 3; ++k) local_field[k] = rounded(lead.e_field[k]);
                wave.e_field = to_lab.template cast<complex>() * local_field;
            }
        }
        result.waves.push_back(wave);
    }
    return result;
}

}  // namespace

std::string_view wave_mode_name(InterfaceMode mode) { return kModeNames[static_cast<std::size_t>(mode)]; }

std::optional<InterfaceMode> parse_wave_mode(std::string_view name) {
    const auto found = std::find(kModeNames.begin(), kModeNames.end(), name);
    if (found == kModeNames.end()) return std::nullopt;
    return static_cast<InterfaceMode>(found - kModeNames.begin());
}

InterfaceResult solve_interface(const Eigen::Vector3d& normal, const InterfaceIncidence& incidence, const OpticalMedium& medium1,
                                const OpticalMedium& medium2) {
    check_vector(normal, "the interface normal");
    check_vector(incidence.direction, "the incident direction");
    check_medium(medium1, "medium 1");
    check_medium(medium2, "medium 2");
    if (!medium1.is_lossless()) throw bad("medium 1 must be transparent (κ = 0): the incident wave must be homogeneous");
    return incidence.arithmetic == InterfaceArithmetic::double_precision ? solve_interface_in<double>(normal, incidence, medium1, medium2)
                                                                         : solve_interface_in<long double>(normal, incidence, medium1, medium2);
}

}  // namespace petroscope
