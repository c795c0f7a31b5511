#pragma once
// The four plane-wave modes of a homogeneous medium for a tangential wavevector (ξ, 0) in a frame whose
// z axis is the interface normal: two forward (toward +z, or decaying toward +z) and two backward.
#include "petroscope/optics/medium.hpp"

#include <Eigen/Core>

#include <array>
#include <complex>

namespace petroscope::detail {

// The interface model works in long double throughout: near grazing incidence, critical angles and optic
// axes the modes are ill-conditioned (errors ∝ ε/cos θ or ε/root separation), and the fluxes of the waves
// balance to 1e-12 only if the modes solve the wave equation far below that.
using Extended = long double;
using ExtendedComplex = std::complex<Extended>;
using ExtendedVector3 = Eigen::Matrix<ExtendedComplex, 3, 1>;

/// |z|² as re² + im². libstdc++'s std::norm and std::abs of a long-double complex number go through hypotl
/// (x87, about a hundred cycles); pivots, largest components and distances only need |z|².
inline Extended magnitude_squared(const ExtendedComplex& z) { return z.real() * z.real() + z.imag() * z.imag(); }

/// a × b without conjugation. Eigen's cross() conjugates its result for complex vectors (so that it is
/// orthogonal under the Hermitian product), which is not the vector identity H = N × E needs.
inline ExtendedVector3 bilinear_cross(const ExtendedVector3& a, const ExtendedVector3& b) {
    return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

/// ½ Re(E × H*): the time-averaged Poynting vector.
inline Eigen::Matrix<Extended, 3, 1> poynting(const ExtendedVector3& e_field, const ExtendedVector3& h_field) {
    return Extended(0.5) * bilinear_cross(e_field, h_field.conjugate()).real();
}

/// ½ Re(E × H*)_z: the z component alone.
inline Extended poynting_z(const ExtendedVector3& e_field, const ExtendedVector3& h_field) {
    const auto re_product = [](const ExtendedComplex& a, const ExtendedComplex& b) { return a.real() * b.real() + a.imag() * b.imag(); };  // Re(a b*)
    return Extended(0.5) * (re_product(e_field.x(), h_field.y()) - re_product(e_field.y(), h_field.x()));
}

struct LocalMode {
    ExtendedComplex q;                 // k_z/k₀
    ExtendedVector3 e_field, h_field;  // H = N × E, N = (ξ, 0, q)
    Extended flux_z = 0.0L;            // ½ Re(E × H*)_z
    bool evanescent = false;
};

struct LocalModes {
    std::array<LocalMode, 2> forward;   // by increasing Re n: fast (or s) first
    std::array<LocalMode, 2> backward;
};

/// `medium` must already be expressed in the local frame (its axes rotated). Isotropic media: closed form
/// with s modes (E ∥ ŷ) and p modes (E ∥ ŝ × k̂); lossless anisotropic media with propagating modes: the
/// Biot–Fresnel sheets of optics/slab.hpp (exact on the optic axes); otherwise (evanescent or absorbing):
/// the roots of the quartic det(ε + NNᵀ − N²I) = 0 polished by Newton, with null vectors by SVD.
LocalModes local_modes(const OpticalMedium& medium, double xi);

}  // namespace petroscope::detail
