#pragma once
// The four plane-wave modes of a homogeneous medium for a tangential wavevector (ξ, 0) in a frame whose
// z axis is the interface normal: two forward (toward +z, or decaying toward +z) and two backward.
#include "petroscope/optics/medium.hpp"

#include <Eigen/Core>

#include <array>
#include <complex>
#include <tuple>

namespace petroscope::detail {

// The interface model works in long double by default: near grazing incidence, critical angles and optic
// axes the modes are ill-conditioned (errors ∝ ε/cos θ or ε/root separation), and the fluxes of the waves
// balance to 1e-12 only if the modes solve the wave equation far below that. `Real` = double serves
// callers that need far less (the renderer), at about twice the speed; every template below is defined
// for both.
template <typename Real>
using Vector3c = Eigen::Matrix<std::complex<Real>, 3, 1>;

/// |z|² as re² + im². libstdc++'s std::norm and std::abs of a long-double complex number go through hypotl
/// (x87, about a hundred cycles); pivots, largest components and distances only need |z|².
template <typename Real>
Real magnitude_squared(const std::complex<Real>& z) { return z.real() * z.real() + z.imag() * z.imag(); }

/// Complete pivoting's search (Golub & Van Loan, Matrix Computations, 4th ed., §3.4.8): the entry of a(k:, k:)
/// with the largest |z|², as (|z|², row, column).
template <typename Real, int N>
std::tuple<Real, int, int> largest_entry(const Eigen::Matrix<std::complex<Real>, N, N>& a, int k) {
    std::tuple<Real, int, int> best{Real(-1), k, k};
    for (int j = k; j < N; ++j) {
        for (int i = k; i < N; ++i) {
            const Real size = magnitude_squared(a(i, j));
            if (size > std::get<0>(best)) best = {size, i, j};
        }
    }
    return best;
}

/// a × b without conjugation. Eigen's cross() conjugates its result for complex vectors (so that it is
/// orthogonal under the Hermitian product), which is not the vector identity H = N × E needs.
template <typename Real>
Vector3c<Real> bilinear_cross(const Vector3c<Real>& a, const Vector3c<Real>& b) {
    return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

/// ½ Re(E × H*): the time-averaged Poynting vector.
template <typename Real>
Eigen::Matrix<Real, 3, 1> poynting(const Vector3c<Real>& e_field, const Vector3c<Real>& h_field) {
    return Real(0.5) * bilinear_cross<Real>(e_field, h_field.conjugate()).real();
}

/// ½ Re(E × H*)_z: the z component alone.
template <typename Real>
Real poynting_z(const Vector3c<Real>& e_field, const Vector3c<Real>& h_field) {
    const auto re_product = [](const std::complex<Real>& a, const std::complex<Real>& b) { return a.real() * b.real() + a.imag() * b.imag(); };  // Re(a b*)
    return Real(0.5) * (re_product(e_field.x(), h_field.y()) - re_product(e_field.y(), h_field.x()));
}

template <typename Real>
struct LocalMode {
    std::complex<Real> q;              // k_z/k₀
    Vector3c<Real> e_field, h_field;   // H = N × E (+ iκE, active), N = (ξ, 0, q)
    Real flux_z = 0;                   // ½ Re(E × H*)_z
    bool evanescent = false;
};

template <typename Real>
struct LocalModes {
    std::array<LocalMode<Real>, 2> forward;   // by increasing Re n: fast (or s) first
    std::array<LocalMode<Real>, 2> backward;
};

/// `medium` must already be expressed in the local frame (its axes rotated). Isotropic inactive media: closed
/// form with s modes (E ∥ ŷ) and p modes (E ∥ ŝ × k̂); lossless inactive anisotropic media with propagating
/// modes: the Biot–Fresnel sheets of optics/slab.hpp (exact on the optic axes); otherwise (evanescent or
/// absorbing modes, optically active media): the roots of the quartic det(ε + NNᵀ − N²I + i[(g·N)×]) = 0
/// polished by Newton, with null vectors from the rows of the wave matrix (by SVD at a double root). An active
/// medium's H is N × E + iκE (optics/gyration.hpp).
template <typename Real>
LocalModes<Real> local_modes(const OpticalMedium& medium, double xi);

}  // namespace petroscope::detail
