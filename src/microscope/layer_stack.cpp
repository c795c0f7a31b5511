#include "petroscope/microscope/layer_stack.hpp"

#include "petroscope/optics/berreman.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace petroscope {
namespace {

Eigen::Matrix3cd ambient_permittivity(double ambient_n) {
    if (!(ambient_n >= 1.0) || !std::isfinite(ambient_n)) throw std::invalid_argument("ambient index must be finite and >= 1");
    return Eigen::Matrix3cd::Identity() * (ambient_n * ambient_n);
}

using Matrix42cd = Eigen::Matrix<std::complex<double>, 4, 2>;

// a·x = b by Gaussian elimination with partial pivoting (Golub & Van Loan, Matrix Computations, 4th ed., §3.4),
// written out for 4×4: the pivot is the largest |aᵢₖ|², the same choice as the largest |aᵢₖ| without a hypot each,
// and its reciprocal a* / |a|² (one real division; the moduli here are far from overflow) serves both sweeps.
Matrix42cd solve_4x4(Eigen::Matrix4cd a, Matrix42cd b) {
    std::array<std::complex<double>, 4> inverse_pivot;
    for (int k = 0; k < 4; ++k) {
        int pivot = k;
        for (int r = k + 1; r < 4; ++r) {
            if (std::norm(a(r, k)) > std::norm(a(pivot, k))) pivot = r;
        }
        if (pivot != k) {
            a.row(k).swap(a.row(pivot));
            b.row(k).swap(b.row(pivot));
        }
        inverse_pivot[k] = std::conj(a(k, k)) * (1.0 / std::norm(a(k, k)));
        for (int r = k + 1; r < 4; ++r) {
            const std::complex<double> factor = a(r, k) * inverse_pivot[k];
            for (int c = k + 1; c < 4; ++c) a(r, c) -= factor * a(k, c);
            b.row(r) -= factor * b.row(k);
        }
    }
    for (int k = 3; k >= 0; --k) {
        for (int c = k + 1; c < 4; ++c) b.row(k) -= a(k, c) * b.row(c);
        b.row(k) *= inverse_pivot[k];
    }
    return b;
}

// The rows ψᴴJ of two waves for the cross flux ψᴴJφ (S_z = ψᴴJψ, J = ¼·[[0, 1], [1, 0]] ⊕ ¼·[[0, 1], [1, 0]] for
// ψ = (E_x, H_y, E_y, −H_x); Berreman, JOSA 62, 502 (1972)).
Eigen::Matrix<std::complex<double>, 2, 4> flux_rows(const BerremanMode& first, const BerremanMode& second) {
    Eigen::Matrix<std::complex<double>, 2, 4> rows;
    for (int m = 0; m < 2; ++m) {
        const Eigen::Vector4cd& psi = (m == 0 ? first : second).psi;
        rows.row(m) << std::conj(psi[1]), std::conj(psi[0]), std::conj(psi[3]), std::conj(psi[2]);
    }
    return 0.25 * rows;
}

// Every wave of `waves` propagates in a lossless medium: berreman_modes and normal_incidence_waves give such waves
// a real q.
bool all_propagating(const MediumWaves& waves) {
    return std::all_of(waves.begin(), waves.end(), [](const BerremanMode& wave) { return wave.q.imag() == 0.0; });
}

}  // namespace

ForwardBoundary forward_boundary(const MediumWaves& from, const MediumWaves& to) {
    if (all_propagating(from)) {
        // G·t − B·r = F (G: `to`'s forward waves, F and B: `from`'s forward and backward ones). In a lossless medium
        // waves of different q carry no cross flux (Poynting's theorem: JΔ = ΔᴴJ), so Fᴴ J B = 0 and Bᴴ J F = 0:
        // projecting on Fᴴ J and Bᴴ J splits the 4×4 system into two 2×2 ones.
        Matrix42cd forward_to, forward_from, backward_from;
        forward_to << to[0].psi, to[1].psi;
        forward_from << from[0].psi, from[1].psi;
        backward_from << from[2].psi, from[3].psi;
        const Eigen::Matrix<std::complex<double>, 2, 4> forward_rows = flux_rows(from[0], from[1]);
        const Eigen::Matrix<std::complex<double>, 2, 4> backward_rows = flux_rows(from[2], from[3]);
        const Eigen::Matrix2cd transmission = (forward_rows * forward_to).inverse() * (forward_rows * forward_from);
        const Eigen::Matrix2cd reflection = (backward_rows * backward_from).inverse() * (backward_rows * forward_to * transmission);
        return {transmission, reflection};
    }
    Eigen::Matrix4cd boundary;
    boundary << to[0].psi, to[1].psi, -from[2].psi, -from[3].psi;
    Matrix42cd incident;
    incident << from[0].psi, from[1].psi;
    const Matrix42cd amplitudes = solve_4x4(boundary, incident);
    return {amplitudes.topRows<2>(), amplitudes.bottomRows<2>()};
}

Eigen::Matrix2cd forward_transmission(const MediumWaves& from, const MediumWaves& to) { return forward_boundary(from, to).transmission; }

Eigen::Matrix2cd forward_propagation(const MediumWaves& waves, double k0_per_um, double thickness_um) {
    const std::complex<double> i(0.0, 1.0);
    return Eigen::Vector2cd(std::exp(i * k0_per_um * waves[0].q * thickness_um), std::exp(i * k0_per_um * waves[1].q * thickness_um))
        .asDiagonal();
}

MediumWaves normal_incidence_waves(const Eigen::Matrix3cd& epsilon) {
    using Complex = std::complex<double>;
    const Eigen::Matrix2cd eta = epsilon.topLeftCorner<2, 2>() - epsilon.block<2, 1>(0, 2) * epsilon.block<1, 2>(2, 0) / epsilon(2, 2);
    const Complex half_trace = 0.5 * (eta(0, 0) + eta(1, 1));
    // λ = tr/2 ± √(((η₀₀ − η₁₁)/2)² + η₀₁η₁₀): the discriminant in the form without cancellation.
    const Complex half_difference = 0.5 * (eta(0, 0) - eta(1, 1));
    const Complex root = std::sqrt(half_difference * half_difference + eta(0, 1) * eta(1, 0));
    std::array<Complex, 2> q_squared{half_trace - root, half_trace + root};
    std::array<Eigen::Vector2cd, 2> transverse;
    if (std::abs(root) <= 1e-12 * std::abs(half_trace)) {
        transverse = {Eigen::Vector2cd(0.0, 1.0), Eigen::Vector2cd(1.0, 0.0)};
        q_squared = {half_trace, half_trace};
    } else {
        for (int m = 0; m < 2; ++m) {
            // (η − λ)v = 0: v from whichever row of η − λ is larger.
            const Eigen::Vector2cd from_first(eta(0, 1), q_squared[m] - eta(0, 0));
            const Eigen::Vector2cd from_second(q_squared[m] - eta(1, 1), eta(1, 0));
            Eigen::Vector2cd v = from_first.squaredNorm() >= from_second.squaredNorm() ? from_first : from_second;
            const int larger = std::abs(v[0]) >= std::abs(v[1]) ? 0 : 1;
            v *= std::conj(v[larger]) / std::abs(v[larger]) / v.norm();  // unit, its larger component real > 0
            transverse[m] = v;
        }
    }
    std::array<Complex, 2> q{std::sqrt(q_squared[0]), std::sqrt(q_squared[1])};
    if (std::abs(q[0].real()) > std::abs(q[1].real())) {
        std::swap(q[0], q[1]);
        std::swap(transverse[0], transverse[1]);
    }
    MediumWaves waves;
    for (int m = 0; m < 2; ++m) {
        const Eigen::Vector2cd& e = transverse[m];
        const Complex e_z = -(epsilon(2, 0) * e[0] + epsilon(2, 1) * e[1]) / epsilon(2, 2);
        for (int direction = 0; direction < 2; ++direction) {
            BerremanMode& wave = waves[m + 2 * direction];
            const Complex wave_q = direction == 0 ? q[m] : -q[m];
            wave.q = wave_q;
            wave.e_field = Eigen::Vector3cd(e[0], e[1], e_z);
            wave.h_field = Eigen::Vector3cd(-wave_q * e[1], wave_q * e[0], 0.0);  // N × E, N = (0, 0, q)
            wave.psi = Eigen::Vector4cd(e[0], wave_q * e[0], e[1], wave_q * e[1]);
            wave.flux_z = 0.5 * (wave.e_field.cross(wave.h_field.conjugate())).z().real();
            wave.forward = direction == 0;
        }
    }
    return waves;
}

double wavenumber_per_um(double wavelength_nm) {
    if (!(wavelength_nm > 0.0)) throw std::invalid_argument("wavelength must be positive");
    return 2.0 * std::numbers::pi * 1e3 / wavelength_nm;
}

ModalJones split_over_layer(const Eigen::Matrix2cd& below, const MediumWaves& layer, const Eigen::Matrix2cd& above,
                            double k0_per_um) {
    ModalJones result;
    for (int m = 0; m < 2; ++m) {
        result.term[m] = above.col(m) * below.row(m);
        result.phase_per_um[m] = k0_per_um * layer[m].q;
    }
    result.propagating = !layer[0].evanescent && !layer[1].evanescent;
    return result;
}

Eigen::Matrix2cd ModalJones::at(double thickness_um) const {
    const std::complex<double> i(0.0, 1.0);
    return term[0] * std::exp(i * phase_per_um[0] * thickness_um) + term[1] * std::exp(i * phase_per_um[1] * thickness_um);
}

ModalJones single_pass_jones(const std::vector<OpticalLayer>& layers, std::size_t variable_layer,
                             double wavelength_nm, const Eigen::Vector2d& xi, double ambient_n) {
    if (variable_layer >= layers.size()) throw std::invalid_argument("single_pass_jones: no such layer");
    const double k0 = wavenumber_per_um(wavelength_nm);
    const MediumWaves ambient = berreman_modes(ambient_permittivity(ambient_n), xi);
    std::vector<MediumWaves> modes;
    modes.reserve(layers.size());
    bool propagating = true;
    for (const OpticalLayer& layer : layers) {
        modes.push_back(berreman_modes(layer.epsilon, layer.chirality, xi));
        if (modes.back()[0].evanescent || modes.back()[1].evanescent) propagating = false;
    }
    // The ambient → the variable layer's forward modes (just inside its lower face)…
    Eigen::Matrix2cd below = forward_transmission(ambient, modes[0]);
    for (std::size_t k = 0; k < variable_layer; ++k) {
        below = forward_transmission(modes[k], modes[k + 1]) * forward_propagation(modes[k], k0, layers[k].thickness_um) * below;
    }
    // … and from its upper face out to the ambient above.
    Eigen::Matrix2cd above = forward_transmission(modes.back(), ambient);
    for (std::size_t k = layers.size() - 1; k > variable_layer; --k) {
        above = above * forward_propagation(modes[k], k0, layers[k].thickness_um) * forward_transmission(modes[k - 1], modes[k]);
    }
    ModalJones result = split_over_layer(below, modes[variable_layer], above, k0);
    result.propagating = propagating;
    return result;
}

Eigen::Matrix2cd coherent_jones(const std::vector<OpticalLayer>& layers, double wavelength_nm,
                                const Eigen::Vector2d& xi, double ambient_n) {
    std::vector<StackLayer> stack;
    for (const OpticalLayer& layer : layers) stack.push_back({layer.epsilon, layer.thickness_um, layer.chirality});
    const Eigen::Matrix3cd ambient_epsilon = ambient_permittivity(ambient_n);
    const MediumWaves ambient = berreman_modes(ambient_epsilon, xi);
    Eigen::Matrix2cd jones;
    for (int column = 0; column < 2; ++column) {
        const StackResponse response = solve_stack(ambient_epsilon, stack, ambient_epsilon, wavelength_nm, xi, ambient[column].psi);
        jones(0, column) = response.transmitted_amplitudes[0];
        jones(1, column) = response.transmitted_amplitudes[1];
    }
    return jones;
}

}  // namespace petroscope
