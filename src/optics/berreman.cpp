// GCC 12 reports -Wmaybe-uninitialized inside its own AVX-512 intrinsics when Eigen's complex-matrix code is
// inlined (GCC bug 105593, as for interface.cpp in CMakeLists.txt); the state must hold where Eigen is included.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif

#include "petroscope/optics/berreman.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

namespace petroscope {
namespace {

using Complex = std::complex<double>;
using Matrix42cd = Eigen::Matrix<Complex, 4, 2>;

// ε ∝ identity within this fraction of |ε|: built in closed form (s and p).
constexpr double kIsotropicTolerance = 1e-12;
// ε Hermitian within this fraction of |ε|: lossless (rotated real tensors are symmetric only to rounding).
constexpr double kHermitianTolerance = 1e-13;
// |Im q| above this fraction of 1 + |q|: the amplitude varies along z (eigenvalue noise is ~1e-15·|Δ|).
constexpr double kEvanescentTolerance = 1e-10;
// Two q of a pair closer than this fraction of 1 + |q|: degenerate. Near √ε_machine it balances the error of
// the eigenvectors of a nearly degenerate pair (ε_machine/gap) against that of treating it as exact (gap).
constexpr double kDegenerateTolerance = 1e-8;

// The largest |mᵢⱼ|, from the squared moduli (no hypot per entry).
double max_abs(const Eigen::Matrix3cd& m) { return std::sqrt(m.cwiseAbs2().maxCoeff()); }

// |z| without hypot's guard against overflow, which moduli of indices and fields never come near.
double modulus(Complex z) { return std::sqrt(std::norm(z)); }

bool amplitude_varies(Complex q) { return std::abs(q.imag()) > kEvanescentTolerance * (1.0 + modulus(q)); }

// Time-averaged z flux of a tangential field, S_z = ½ Re(E × H*)_z = ½ Re(ψ₁ψ₂* + ψ₃ψ₄*) (Berreman 1972). The same in the lab and plane-of-incidence frames (a rotation about z).
double flux_of(const Eigen::Vector4cd& psi) {
    return 0.5 * (psi[0] * std::conj(psi[1]) + psi[2] * std::conj(psi[3])).real();
}

// The Hermitian form of that flux: S_z(ψ) = ψᴴ J ψ, so the cross flux of two waves is Re(aᴴ J b)·2.
Eigen::Matrix2cd flux_form(const Matrix42cd& basis) {
    Eigen::Matrix4cd j = Eigen::Matrix4cd::Zero();
    j(0, 1) = j(1, 0) = j(2, 3) = j(3, 2) = 0.25;
    return basis.adjoint() * j * basis;
}

// The plane of incidence: ρ̂ = ξ/|ξ| (x̂ at ξ = 0), ŝ = ẑ × ρ̂. The frame (ρ̂, ŝ, ẑ) is the lab frame turned
// about z by atan2(ξ_y, ξ_x); Berreman's Δ for the x–z plane of incidence applies there.
struct PlaneOfIncidence {
    double xi = 0.0;  // |ξ|
    double cos_phi = 1.0, sin_phi = 0.0;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns ρ̂, ŝ, ẑ in the lab frame

    explicit PlaneOfIncidence(const Eigen::Vector2d& xi_lab) : xi(xi_lab.norm()) {
        if (xi > 0.0) {
            cos_phi = xi_lab.x() / xi;
            sin_phi = xi_lab.y() / xi;
        }
        rotation << cos_phi, -sin_phi, 0.0, sin_phi, cos_phi, 0.0, 0.0, 0.0, 1.0;
    }

    // A vector of the plane frame in the lab frame: turned about z by the plane's azimuth.
    Eigen::Vector3cd vector_to_lab(const Eigen::Vector3cd& v) const {
        return {cos_phi * v[0] - sin_phi * v[1], sin_phi * v[0] + cos_phi * v[1], v[2]};
    }

    // (E_x, E_y) and (H_y, −H_x) = (H × ẑ)_{x,y} both turn as plane vectors about z.
    Eigen::Vector4cd to_lab(const Eigen::Vector4cd& p) const {
        return {cos_phi * p[0] - sin_phi * p[2], cos_phi * p[1] - sin_phi * p[3], sin_phi * p[0] + cos_phi * p[2],
                sin_phi * p[1] + cos_phi * p[3]};
    }
    Eigen::Vector4cd to_plane(const Eigen::Vector4cd& p) const {
        return {cos_phi * p[0] + sin_phi * p[2], cos_phi * p[1] + sin_phi * p[3], -sin_phi * p[0] + cos_phi * p[2],
                -sin_phi * p[1] + cos_phi * p[3]};
    }
};

// A homogeneous medium seen in the plane-of-incidence frame.
struct Medium {
    Eigen::Matrix3cd epsilon;  // ε' = Rᵀ ε R, R = (ρ̂, ŝ, ẑ); for a chiral medium the bianisotropic ε_b = ε + κ²
    Eigen::Matrix3d chirality = Eigen::Matrix3d::Zero();  // κ' = Rᵀ κ R
    double xi = 0.0;
    bool chiral = false;
    bool isotropic = false;
    bool lossless = false;
    Complex isotropic_epsilon;  // ε̄ = tr ε / 3

    Medium(const Eigen::Matrix3cd& epsilon_lab, const PlaneOfIncidence& plane,
           const Eigen::Matrix3d& chirality_lab = Eigen::Matrix3d::Zero())
        : xi(plane.xi), chiral(!chirality_lab.isZero(0.0)) {
        if (chiral) chirality = plane.rotation.transpose() * chirality_lab * plane.rotation;
        // Rᵀ ε R with the real R applied to the real and imaginary parts apart (a lossless ε has none).
        const Eigen::Matrix3d imaginary = epsilon_lab.imag();
        epsilon.real() = plane.rotation.transpose() * epsilon_lab.real() * plane.rotation;
        epsilon.imag() = imaginary.isZero(0.0) ? imaginary : Eigen::Matrix3d(plane.rotation.transpose() * imaginary * plane.rotation);
        if (chiral) epsilon += (chirality * chirality).cast<Complex>();
        const double scale = max_abs(epsilon_lab);
        isotropic_epsilon = epsilon_lab.trace() / 3.0;
        isotropic = !chiral &&
            max_abs(epsilon_lab - isotropic_epsilon * Eigen::Matrix3cd::Identity()) <= kIsotropicTolerance * scale;
        lossless = max_abs(epsilon_lab - epsilon_lab.adjoint()) <= kHermitianTolerance * scale;
    }
};

// The bianisotropic medium's plane-wave equations, written for F = (E, H): (D, B) = M·F with
// M = [[ε_b, iκ], [−iκ, I]], and N × E = B, N × H = −D, i.e. (D, B) = R(N)·F with R(N) = [[0, −[N×]], [[N×], 0]]
// (Berreman, JOSA 62, 502 (1972), eqs. 1–6 with his optical-activity tensors ρ = iκ, ρ' = −iκ). With N = (ξ, 0, q):
// (M − R(ξx̂))·F = q·R(ẑ)·F. The rows of D_z and B_z have no q; they give E_z and H_z from the tangential components.
using Matrix6cd = Eigen::Matrix<Complex, 6, 6>;
Matrix6cd chiral_system(const Medium& medium) {
    const Complex i(0.0, 1.0);
    Matrix6cd c = Matrix6cd::Zero();
    c.topLeftCorner<3, 3>() = medium.epsilon;
    c.topRightCorner<3, 3>() = i * medium.chirality.cast<Complex>();
    c.bottomLeftCorner<3, 3>() = -i * medium.chirality.cast<Complex>();
    c.bottomRightCorner<3, 3>().setIdentity();
    // −R(ξx̂): [ξx̂×] = [[0, 0, 0], [0, 0, −ξ], [0, ξ, 0]], in the D rows +[ξx̂×]H, in the B rows −[ξx̂×]E.
    c(1, 5) += -medium.xi;
    c(2, 4) += medium.xi;
    c(4, 2) -= -medium.xi;
    c(5, 1) -= medium.xi;
    return c;
}

// Tangential (E_x, E_y, H_x, H_y) and normal (E_z, H_z) positions in F.
constexpr std::array<int, 4> kTangential{0, 1, 3, 4};
constexpr std::array<int, 2> kNormal{2, 5};

// F_z = −C_zz⁻¹·C_zt·F_t: the normal components that the D_z and B_z rows fix (the elimination of Berreman 1972).
Eigen::Matrix<Complex, 2, 4> normal_from_tangential(const Matrix6cd& c) {
    Eigen::Matrix2cd c_zz;
    Eigen::Matrix<Complex, 2, 4> c_zt;
    for (int r = 0; r < 2; ++r) {
        for (int k = 0; k < 2; ++k) c_zz(r, k) = c(kNormal[r], kNormal[k]);
        for (int k = 0; k < 4; ++k) c_zt(r, k) = c(kNormal[r], kTangential[k]);
    }
    return -c_zz.inverse() * c_zt;
}

// ψ = (E_x, H_y, E_y, −H_x) from F_t = (E_x, E_y, H_x, H_y): ψ = P·F_t.
Eigen::Matrix4cd psi_from_tangential() {
    Eigen::Matrix4cd p = Eigen::Matrix4cd::Zero();
    p(0, 0) = 1.0;
    p(1, 3) = 1.0;
    p(2, 1) = 1.0;
    p(3, 2) = -1.0;
    return p;
}

// Berreman's Δ of a chiral medium: the tangential rows give (C_tt + C_tz·F_z/F_t)·F_t = q·R_tt·F_t, where R(ẑ)
// maps (E_x, E_y, H_x, H_y) to (D_x, D_y, B_x, B_y) = (H_y, −H_x, −E_y, E_x); R_tt is its own inverse.
Eigen::Matrix4cd chiral_delta_matrix(const Medium& medium) {
    const Matrix6cd c = chiral_system(medium);
    const Eigen::Matrix<Complex, 2, 4> normal = normal_from_tangential(c);
    Eigen::Matrix4cd reduced;
    for (int r = 0; r < 4; ++r) {
        for (int k = 0; k < 4; ++k) {
            reduced(r, k) = c(kTangential[r], kTangential[k]) + c(kTangential[r], kNormal[0]) * normal(0, k) +
                            c(kTangential[r], kNormal[1]) * normal(1, k);
        }
    }
    Eigen::Matrix4cd r_tt = Eigen::Matrix4cd::Zero();
    r_tt(0, 3) = 1.0;
    r_tt(1, 2) = -1.0;
    r_tt(2, 1) = -1.0;
    r_tt(3, 0) = 1.0;
    const Eigen::Matrix4cd p = psi_from_tangential();
    return p * (r_tt * reduced) * p.transpose();  // P is orthogonal: P⁻¹ = Pᵀ
}

// Berreman's Δ for the x–z plane of incidence, dψ/dz = i k₀ Δ ψ, ψ = (E_x, H_y, E_y, −H_x) (Berreman,
// JOSA 62, 502 (1972), eq. 10, with μ = 1; an optically active medium takes chiral_delta_matrix). Derived from
// ∇ × E = i k₀ H, ∇ × H = −i k₀ ε E with ∂/∂x = i k₀ ξ, ∂/∂y = 0, eliminating E_z and H_z.
Eigen::Matrix4cd delta_matrix(const Eigen::Matrix3cd& e, double xi) {
    const Complex inverse_e33 = 1.0 / e(2, 2);  // one division; exact zeros of a real ε stay zero
    Eigen::Matrix4cd delta = Eigen::Matrix4cd::Zero();
    delta(0, 0) = -xi * e(2, 0) * inverse_e33;
    delta(0, 1) = 1.0 - xi * xi * inverse_e33;
    delta(0, 2) = -xi * e(2, 1) * inverse_e33;
    delta(1, 0) = e(0, 0) - e(0, 2) * e(2, 0) * inverse_e33;
    delta(1, 1) = -xi * e(0, 2) * inverse_e33;
    delta(1, 2) = e(0, 1) - e(0, 2) * e(2, 1) * inverse_e33;
    delta(2, 3) = 1.0;
    delta(3, 0) = e(1, 0) - e(1, 2) * e(2, 0) * inverse_e33;
    delta(3, 1) = -xi * e(1, 2) * inverse_e33;
    delta(3, 2) = e(1, 1) - e(1, 2) * e(2, 1) * inverse_e33 - xi * xi;
    return delta;
}

// The full fields of a tangential field ψ' (plane frame): E_z = −(ξ H_y + ε₃₁E_x + ε₃₂E_y)/ε₃₃ from
// (∇ × H)_z = −i k₀ (εE)_z, and H_z = ξ E_y from (∇ × E)_z = i k₀ H_z (the eliminations of Berreman 1972).
std::pair<Eigen::Vector3cd, Eigen::Vector3cd> fields_from_psi(const Medium& medium, const Eigen::Vector4cd& psi) {
    if (medium.chiral) {
        const Eigen::Vector4cd tangential = psi_from_tangential().transpose() * psi;
        const Eigen::Vector2cd normal = normal_from_tangential(chiral_system(medium)) * tangential;
        return {Eigen::Vector3cd(tangential[0], tangential[1], normal[0]), Eigen::Vector3cd(tangential[2], tangential[3], normal[1])};
    }
    const Eigen::Matrix3cd& e = medium.epsilon;
    const Complex ez = -(medium.xi * psi[1] + e(2, 0) * psi[0] + e(2, 1) * psi[2]) / e(2, 2);
    return {Eigen::Vector3cd(psi[0], psi[2], ez), Eigen::Vector3cd(-psi[3], psi[1], medium.xi * psi[2])};
}

// Two waves of one direction (forward or backward), as an invariant subspace of Δ: Δ·basis = basis·generator.
// For a layer only the subspace matters (its propagator is exp(i k₀ d generator)), which stays exact when the
// two waves are degenerate or nearly so; the individual modes are the generator's eigenvectors.
struct WavePair {
    Matrix42cd basis;
    Eigen::Matrix2cd generator;
};

struct Spectrum {
    WavePair forward, backward;
};

// Isotropic medium, ε = n² I (Born & Wolf, Principles of Optics, §1.5): q = ±√(n² − ξ²), the forward root
// decaying toward +z or, when real, positive. s: E = ŝ, H = N × E, ψ' = (0, 0, 1, ±q). p: E = ±(q ρ̂ − ξ ẑ)/n
// (transverse part along +ρ̂), H = N × E = ±n ŝ, ψ' = (q/n, ±n, 0, 0) with q the forward root.
// `inside_stack`: a layer at grazing incidence (q = 0) is an exceptional point of Δ where the forward and backward
// waves coincide and the mode basis is singular, although the layer's transfer matrix (a function of q², entire)
// is not. There |q| is raised to kGrazingQ, which moves q² by at most kGrazingQ² = 1e-12.
constexpr double kGrazingQ = 1e-6;
Spectrum isotropic_spectrum(const Medium& medium, bool inside_stack) {
    Complex q = std::sqrt(medium.isotropic_epsilon - medium.xi * medium.xi);
    if (amplitude_varies(q) ? q.imag() < 0.0 : q.real() < 0.0) q = -q;
    if (medium.lossless && !amplitude_varies(q)) q = q.real();
    if (medium.lossless && amplitude_varies(q)) q = Complex(0.0, q.imag());  // real ε̄ − ξ² < 0: q = i√(ξ² − ε̄)
    if (inside_stack && std::abs(q) < kGrazingQ) q = q == 0.0 ? Complex(kGrazingQ) : kGrazingQ * q / std::abs(q);
    const Complex n = std::sqrt(medium.isotropic_epsilon);
    Spectrum spectrum;
    spectrum.forward.basis << 0.0, q / n, 0.0, n, 1.0, 0.0, q, 0.0;
    spectrum.backward.basis << 0.0, q / n, 0.0, -n, 1.0, 0.0, -q, 0.0;
    spectrum.forward.generator = q * Eigen::Matrix2cd::Identity();
    spectrum.backward.generator = -q * Eigen::Matrix2cd::Identity();
    return spectrum;
}

// The Schur form Δ = U T Uᴴ (T upper triangular, U unitary; real when Δ is real with real eigenvalues) with its
// eigenvalues reordered: swapping the adjacent diagonal entries k and k + 1 takes one plane rotation G whose
// first column is the 2×2 block's eigenvector of T(k+1, k+1), x ∝ (T(k, k+1), T(k+1, k+1) − T(k, k)); then
// T ← Gᴴ T G, U ← U G (Golub & Van Loan, Matrix Computations, 4th ed., §7.6.2). The leading m columns of U then
// span the invariant subspace of the leading m eigenvalues, orthonormal, with Uᴴ Δ U restricted to it the
// leading block of T.
template <typename Scalar>
struct OrderedSchur {
    using Matrix = Eigen::Matrix<Scalar, 4, 4>;
    Matrix t, u;
    std::array<int, 4> label{0, 1, 2, 3};  // which eigenvalue of the first decomposition sits at each position

    void swap_adjacent(int k) {
        Eigen::Matrix<Scalar, 2, 1> x(t(k, k + 1), t(k + 1, k + 1) - t(k, k));
        const double length = x.norm();
        if (length > 0.0) {  // else the block is diagonal with equal entries: swapping changes nothing
            x /= length;
            Eigen::Matrix<Scalar, 2, 2> g;
            g << x[0], -Eigen::numext::conj(x[1]), x[1], Eigen::numext::conj(x[0]);
            t.template middleCols<2>(k) = t.template middleCols<2>(k) * g;
            t.template middleRows<2>(k) = g.adjoint() * t.template middleRows<2>(k);
            u.template middleCols<2>(k) = u.template middleCols<2>(k) * g;
            t(k + 1, k) = 0.0;
        }
        std::swap(label[k], label[k + 1]);
    }

    // Moves eigenvalue `which` (a label) to position `target`, from below it.
    void bring_to(int which, int target) {
        const int position = static_cast<int>(std::find(label.begin(), label.end(), which) - label.begin());
        for (int k = position - 1; k >= target; --k) swap_adjacent(k);
    }
};

// The unit eigenvector of Δ for the eigenvalue at position i of its Schur form Δ = U T Uᴴ: U·y with (T − tᵢᵢ)·y = 0,
// yᵢ = 1 and y zero below i, by back substitution (Golub & Van Loan, Matrix Computations, 4th ed., §7.6.4). None
// where an earlier eigenvalue lies within kBackSubstitutionGap·(1 + |tᵢᵢ|) of tᵢᵢ, where y is ill-determined;
// reordering the Schur form (bring_to) serves there.
constexpr double kBackSubstitutionGap = 1e-6;
template <typename Scalar>
std::optional<Eigen::Vector4cd> schur_eigenvector(const OrderedSchur<Scalar>& decomposition, int i) {
    const auto& t = decomposition.t;
    const double gap = kBackSubstitutionGap * (1.0 + std::abs(t(i, i)));
    Eigen::Matrix<Scalar, 4, 1> y = Eigen::Matrix<Scalar, 4, 1>::Zero();
    y[i] = 1.0;
    for (int k = i - 1; k >= 0; --k) {
        const Scalar denominator = t(k, k) - t(i, i);
        if (!(std::abs(denominator) > gap)) return std::nullopt;
        Scalar sum = 0.0;
        for (int j = k + 1; j <= i; ++j) sum += t(k, j) * y[j];
        y[k] = -sum / denominator;
    }
    const Eigen::Matrix<Scalar, 4, 1> vector = decomposition.u * y;
    return Eigen::Vector4cd(vector.template cast<Complex>() / vector.norm());
}

// The eigenvalues of Δ from its Schur form, each classified forward or backward by the sign of Im q or, when q
// is real, by the flux of its eigenvector (the first Schur vector once it leads); then the forward pair's
// invariant subspace as the leading Schur vectors once both lead, and the backward pair's likewise. The
// subspace stays well conditioned when the two forward waves are degenerate (optic axis), where the individual
// eigenvectors are not; it fails only where a forward and a backward wave meet (q → 0 at grazing incidence, an
// exceptional point of Δ).
template <typename Scalar>
Spectrum ordered_spectrum(const Medium& medium, const OrderedSchur<Scalar>& decomposition) {
    std::array<double, 4> forwardness;  // > 0 forward: Im q when the amplitude varies, else the flux
    for (int i = 0; i < 4; ++i) {
        Complex q = decomposition.t(i, i);
        // A Hermitian ε gives real q or complex-conjugate pairs (Δ is then J-self-adjoint): snap rounding noise.
        if (medium.lossless && !amplitude_varies(q)) q = q.real();
        if (amplitude_varies(q)) {
            forwardness[i] = q.imag();
        } else if (const auto vector = schur_eigenvector(decomposition, i)) {
            forwardness[i] = flux_of(*vector);
        } else {
            OrderedSchur<Scalar> leading = decomposition;
            leading.bring_to(i, 0);
            forwardness[i] = flux_of(leading.u.col(0).template cast<Complex>());
        }
    }
    std::array<int, 4> order{0, 1, 2, 3};
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return forwardness[a] > forwardness[b]; });
    const auto subspace = [&](int first, int second) {
        OrderedSchur<Scalar> leading = decomposition;
        leading.bring_to(first, 0);
        leading.bring_to(second, 1);
        return WavePair{leading.u.template leftCols<2>().template cast<Complex>(),
                        leading.t.template topLeftCorner<2, 2>().template cast<Complex>()};
    };
    return Spectrum{subspace(order[0], order[1]), subspace(order[2], order[3])};
}

// Anisotropic medium. A real Δ (a real ε, no activity) whose four eigenvalues are real (every wave
// propagates: the real Schur form has no 2×2 blocks) is reordered in real arithmetic, about three times
// cheaper; any other Δ in complex arithmetic.
Spectrum anisotropic_spectrum(const Medium& medium) {
    const Eigen::Matrix4cd delta = medium.chiral ? chiral_delta_matrix(medium) : delta_matrix(medium.epsilon, medium.xi);
    if (delta.imag().isZero(0.0)) {
        const Eigen::RealSchur<Eigen::Matrix4d> schur(delta.real());
        const Eigen::Matrix4d& t = schur.matrixT();
        if (schur.info() == Eigen::Success && t(1, 0) == 0.0 && t(2, 1) == 0.0 && t(3, 2) == 0.0) {
            return ordered_spectrum(medium, OrderedSchur<double>{t, schur.matrixU()});
        }
    }
    const Eigen::ComplexSchur<Eigen::Matrix4cd> schur(delta);
    return ordered_spectrum(medium, OrderedSchur<Complex>{schur.matrixT(), schur.matrixU()});
}

Spectrum medium_spectrum(const Medium& medium, bool inside_stack = false) {
    return medium.isotropic ? isotropic_spectrum(medium, inside_stack) : anisotropic_spectrum(medium);
}

// A mode with its tangential field in the plane frame (what the boundary conditions use).
struct PlaneMode {
    BerremanMode mode;
    Eigen::Vector4cd psi_plane;
};

PlaneMode complete_mode(const Medium& medium, const PlaneOfIncidence& plane, Complex q, Eigen::Vector4cd psi,
                        bool forward) {
    if (medium.lossless && !amplitude_varies(q)) q = q.real();
    auto [e, h] = fields_from_psi(medium, psi);
    if (!medium.isotropic) {
        // |E| = 1, the larger of E·ρ̂, E·ŝ real and positive (E·ŝ on a tie).
        const Complex reference = std::norm(e.y()) >= std::norm(e.x()) ? e.y() : e.x();
        const double length = e.norm();
        const double reference_modulus = std::sqrt(std::norm(reference));
        if (length > 0.0 && reference_modulus > 0.0) {
            const Complex scale = std::conj(reference) / (reference_modulus * length);
            psi *= scale;
            e *= scale;
            h *= scale;
        }
    }
    PlaneMode result;
    result.psi_plane = psi;
    BerremanMode& mode = result.mode;
    mode.q = q;
    mode.psi = plane.to_lab(psi);
    mode.e_field = plane.vector_to_lab(e);
    mode.h_field = plane.vector_to_lab(h);
    mode.forward = forward;
    mode.evanescent = medium.lossless && amplitude_varies(q);
    mode.flux_z = mode.evanescent ? 0.0 : flux_of(psi);  // lossless and decaying: no flux, exactly
    return result;
}

// Coefficients c of the combination basis·c whose component `row` vanishes (a zero of a linear functional on
// the 2-D subspace), or e₀ when the functional vanishes on it.
Eigen::Vector2cd zero_component(const Matrix42cd& basis, int row) {
    const Eigen::Vector2cd c(basis(row, 1), -basis(row, 0));
    return c.norm() > 1e-12 ? Eigen::Vector2cd(c.normalized()) : Eigen::Vector2cd(1.0, 0.0);
}

// The two modes of one direction, ordered as berreman_modes documents.
std::array<PlaneMode, 2> pair_modes(const Medium& medium, const PlaneOfIncidence& plane, const WavePair& pair,
                                    bool forward) {
    const Eigen::Matrix2cd& a = pair.generator;
    if (medium.isotropic) {  // closed form, [s, p]
        return {complete_mode(medium, plane, a(0, 0), pair.basis.col(0), forward),
                complete_mode(medium, plane, a(0, 0), pair.basis.col(1), forward)};
    }
    // Eigenvalues of the 2×2 generator: m ± √(((a₀₀ − a₁₁)/2)² + a₀₁a₁₀).
    const Complex mean = 0.5 * (a(0, 0) + a(1, 1));
    const Complex half_difference = 0.5 * (a(0, 0) - a(1, 1));
    const Complex root = std::sqrt(half_difference * half_difference + a(0, 1) * a(1, 0));
    std::array<Complex, 2> mu{mean - root, mean + root};
    const double scale = 1.0 + std::max(modulus(mu[0]), modulus(mu[1]));
    if (modulus(mu[0] - mu[1]) <= kDegenerateTolerance * scale) {
        // Degenerate: every vector of the subspace is a mode. s-like: E·ρ̂ = ψ'₁ = 0. p-like: no cross flux with
        // it (the flux form G restricted to the subspace), or E·ŝ = ψ'₃ = 0 where G vanishes (evanescent);
        // the Euclidean complement if neither is independent of the s-like vector.
        const Eigen::Vector2cd s_coefficients = zero_component(pair.basis, 0);
        const Eigen::Matrix2cd g = flux_form(pair.basis);
        const Eigen::Vector2cd gs = g * s_coefficients;
        Eigen::Vector2cd p_coefficients = gs.norm() > 1e-12 * (1.0 + g.norm())
                                              ? Eigen::Vector2cd(std::conj(gs[1]), -std::conj(gs[0])).normalized()
                                              : zero_component(pair.basis, 2);
        const auto independent = [&](const Eigen::Vector2cd& p) {
            return std::abs(s_coefficients[0] * p[1] - s_coefficients[1] * p[0]) > 1e-6;
        };
        if (!independent(p_coefficients))
            p_coefficients = {-std::conj(s_coefficients[1]), std::conj(s_coefficients[0])};
        return {complete_mode(medium, plane, mean, pair.basis * s_coefficients, forward),
                complete_mode(medium, plane, mean, pair.basis * p_coefficients, forward)};
    }
    // Distinct: (a − μ)v = 0 from whichever row of a − μ is the larger.
    std::array<Eigen::Vector4cd, 2> vectors;
    for (int i = 0; i < 2; ++i) {
        const Eigen::Vector2cd from_row_0(a(0, 1), mu[i] - a(0, 0));
        const Eigen::Vector2cd from_row_1(mu[i] - a(1, 1), a(1, 0));
        vectors[i] = pair.basis * (from_row_0.norm() >= from_row_1.norm() ? from_row_0 : from_row_1);
    }
    // By increasing |Re q|, ties by increasing |Im q|.
    const double tie = kDegenerateTolerance * scale;
    const bool swap = std::abs(std::abs(mu[0].real()) - std::abs(mu[1].real())) > tie
                          ? std::abs(mu[1].real()) < std::abs(mu[0].real())
                          : std::abs(mu[1].imag()) < std::abs(mu[0].imag());
    if (swap) {
        std::swap(mu[0], mu[1]);
        std::swap(vectors[0], vectors[1]);
    }
    // Two propagating waves of a lossless medium with distinct q carry no cross flux: with ε Hermitian the flux
    // ψᴴJψ is constant along z (Poynting's theorem), so JΔ = ΔᴴJ, and Δa = λa, Δb = μb with real λ ≠ μ give
    // (λ − μ)·bᴴJa = 0. Near a degeneracy the eigenvectors are accurate only to ε_machine/gap; removing from the
    // second its flux projection on the first (a change of that order) restores the orthogonality exactly, so
    // that the powers of the two waves add.
    if (medium.lossless && !amplitude_varies(mu[0]) && !amplitude_varies(mu[1])) {
        Matrix42cd both;
        both << vectors[0], vectors[1];
        const Eigen::Matrix2cd g = flux_form(both);
        if (std::abs(g(0, 0)) > 0.0) vectors[1] -= (g(0, 1) / g(0, 0)) * vectors[0];
    }
    return {complete_mode(medium, plane, mu[0], vectors[0], forward),
            complete_mode(medium, plane, mu[1], vectors[1], forward)};
}

// The spectrum of −ξ in its plane frame (ρ̂ and ŝ reversed) from that of ξ, for a medium without optical activity.
// There Berreman's Δ is that of ξ with ξ → −ξ, and Δ(−ξ) = −S·Δ(ξ)·S with S = diag(−1, 1, −1, 1) (delta_matrix: the
// entries odd in ξ are those S flips). So S maps an invariant subspace of q to one of −q, and a backward pair of ξ
// (S_z < 0, which S reverses, or Im q < 0) to the forward pair of −ξ.
Spectrum opposite_spectrum(const Spectrum& spectrum) {
    const Eigen::Vector4cd s(-1.0, 1.0, -1.0, 1.0);
    return Spectrum{WavePair{s.asDiagonal() * spectrum.backward.basis, -spectrum.backward.generator},
                    WavePair{s.asDiagonal() * spectrum.forward.basis, -spectrum.forward.generator}};
}

std::array<PlaneMode, 4> all_modes(const Medium& medium, const PlaneOfIncidence& plane, const Spectrum& spectrum) {
    const auto forward = pair_modes(medium, plane, spectrum.forward, true);
    const auto backward = pair_modes(medium, plane, spectrum.backward, false);
    return {forward[0], forward[1], backward[0], backward[1]};
}

std::array<BerremanMode, 4> lab_modes(const std::array<PlaneMode, 4>& modes) {
    return {modes[0].mode, modes[1].mode, modes[2].mode, modes[3].mode};
}

// exp(x) for a 2×2 complex matrix by Lagrange–Sylvester interpolation on its eigenvalues m ± δ
// (Moler & Van Loan, SIAM Rev. 45, 3 (2003), "polynomial methods"): exp(x) = a I + b (x − m I) with
// a = (e^{m+δ} + e^{m−δ})/2 = e^m cosh δ and b = (e^{m+δ} − e^{m−δ})/(2δ) = e^m sinh δ/δ. The second forms
// (series for sinh δ/δ at small δ) serve |δ| ≤ ½, where the first would cancel; the first serves larger |δ|,
// where e^m cosh δ could overflow although e^{m±δ} (decaying waves) do not.
Eigen::Matrix2cd exp2(const Eigen::Matrix2cd& x) {
    const Complex m = 0.5 * (x(0, 0) + x(1, 1));
    const Complex half_difference = 0.5 * (x(0, 0) - x(1, 1));
    const Complex delta = std::sqrt(half_difference * half_difference + x(0, 1) * x(1, 0));
    const Eigen::Matrix2cd shifted = x - m * Eigen::Matrix2cd::Identity();
    Complex a, b;
    if (std::abs(delta) <= 0.5) {
        const Complex d2 = delta * delta;
        const Complex sinhc = std::abs(delta) < 1e-3 ? 1.0 + d2 / 6.0 * (1.0 + d2 / 20.0) : std::sinh(delta) / delta;
        const Complex em = std::exp(m);
        a = em * std::cosh(delta);
        b = em * sinhc;
    } else {
        const Complex e_plus = std::exp(m + delta), e_minus = std::exp(m - delta);
        a = 0.5 * (e_plus + e_minus);
        b = (e_plus - e_minus) / (2.0 * delta);
    }
    return a * Eigen::Matrix2cd::Identity() + b * shifted;
}

// A scattering matrix between two reference planes, in mode amplitudes: outgoing (forward above, backward
// below) from incoming (forward below, backward above):
//   forward_out = t·forward_in + r_back·backward_in,  backward_out = r·forward_in + t_back·backward_in.
struct Scattering {
    Eigen::Matrix2cd t = Eigen::Matrix2cd::Identity(), r = Eigen::Matrix2cd::Zero();
    Eigen::Matrix2cd t_back = Eigen::Matrix2cd::Identity(), r_back = Eigen::Matrix2cd::Zero();
};

// The interface from medium 1 (below) to medium 2 (above): continuity of the tangential fields
// F₁f₁ + B₁b₁ = F₂f₂ + B₂b₂ (Berreman 1972; Yeh, JOSA 69, 742 (1979)) solved for the outgoing (f₂, b₁):
// [F₂  −B₁]·(f₂, b₁) = [F₁  −B₂]·(f₁, b₂).
Scattering interface(const Matrix42cd& forward_1, const Matrix42cd& backward_1, const Matrix42cd& forward_2,
                     const Matrix42cd& backward_2) {
    Eigen::Matrix4cd outgoing, incoming;
    outgoing << forward_2, -backward_1;
    incoming << forward_1, -backward_2;
    const Eigen::Matrix4cd s = outgoing.fullPivLu().solve(incoming);
    Scattering result;
    result.t = s.topLeftCorner<2, 2>();
    result.r_back = s.topRightCorner<2, 2>();
    result.r = s.bottomLeftCorner<2, 2>();
    result.t_back = s.bottomRightCorner<2, 2>();
    return result;
}

// Redheffer's star product: `lower` followed by `upper` (Redheffer, J. Math. Phys. 41, 1 (1962); Li, JOSA A 13,
// 1024 (1996)). The multiple reflections between the two sum to (I − r_back,lower·r_upper)⁻¹.
Scattering star(const Scattering& lower, const Scattering& upper) {
    const Eigen::Matrix2cd identity = Eigen::Matrix2cd::Identity();
    const Eigen::Matrix2cd up = (identity - lower.r_back * upper.r).inverse();
    const Eigen::Matrix2cd down = (identity - upper.r * lower.r_back).inverse();
    Scattering result;
    result.t = upper.t * up * lower.t;
    result.r = lower.r + lower.t_back * upper.r * up * lower.t;
    result.t_back = lower.t_back * down * upper.t_back;
    result.r_back = upper.r_back + upper.t * up * lower.r_back * upper.t_back;
    return result;
}

Matrix42cd columns(const std::array<PlaneMode, 4>& modes, int first) {
    Matrix42cd m;
    m << modes[first].psi_plane, modes[first + 1].psi_plane;
    return m;
}

}  // namespace

std::array<BerremanMode, 4> berreman_modes(const Eigen::Matrix3cd& epsilon, const Eigen::Vector2d& xi) {
    return berreman_modes(epsilon, Eigen::Matrix3d::Zero(), xi);
}

std::array<BerremanMode, 4> berreman_modes(const Eigen::Matrix3cd& epsilon, const Eigen::Matrix3d& chirality, const Eigen::Vector2d& xi) {
    const PlaneOfIncidence plane(xi);
    const Medium medium(epsilon, plane, chirality);
    return lab_modes(all_modes(medium, plane, medium_spectrum(medium)));
}

std::array<std::array<BerremanMode, 4>, 2> berreman_modes_both_ways(const Eigen::Matrix3cd& epsilon, const Eigen::Vector2d& xi) {
    const PlaneOfIncidence plane(xi), opposite_plane(-xi);
    const Medium medium(epsilon, plane), opposite(epsilon, opposite_plane);
    const Spectrum spectrum = medium_spectrum(medium);
    const auto modes = all_modes(medium, plane, spectrum);
    const auto opposite_modes = all_modes(opposite, opposite_plane, medium.isotropic ? medium_spectrum(opposite) : opposite_spectrum(spectrum));
    return {lab_modes(modes), lab_modes(opposite_modes)};
}

// Stable formulation: inside each layer the forward waves are referred to the layer's lower face and the
// backward waves to its upper face, so crossing the layer multiplies them by exp(i k₀ d A_f) and
// exp(−i k₀ d A_b) (A the generators of the forward and backward subspaces of Δ), whose eigenvalues decay or
// have unit modulus. The plain transfer-matrix product exp(i k₀ Δ d) would mix growing exponentials
// exp(k₀ d |Im q|) with decaying ones and lose every digit in thick evanescent layers; the scattering matrices,
// combined by the star product, never form a growing exponential (Ko & Inkson, PRB 38, 9945 (1988); Li 1996).
StackResponse solve_stack(const Eigen::Matrix3cd& ambient, const std::vector<StackLayer>& layers,
                          const Eigen::Matrix3cd& substrate, double wavelength_nm, const Eigen::Vector2d& xi,
                          const Eigen::Vector4cd& incident_psi) {
    return solve_stack(StackLayer{ambient}, layers, StackLayer{substrate}, wavelength_nm, xi, incident_psi);
}

StackResponse solve_stack(const StackLayer& ambient, const std::vector<StackLayer>& layers, const StackLayer& substrate,
                          double wavelength_nm, const Eigen::Vector2d& xi, const Eigen::Vector4cd& incident_psi) {
    if (!(wavelength_nm > 0.0) || !std::isfinite(wavelength_nm)) {
        throw std::invalid_argument("solve_stack: the wavelength must be positive and finite");
    }
    for (const StackLayer& layer : layers) {
        if (!(layer.thickness_um >= 0.0) || !std::isfinite(layer.thickness_um)) {
            throw std::invalid_argument("solve_stack: layer thicknesses must be non-negative and finite");
        }
    }
    const double k0_per_um = 2.0 * std::numbers::pi * 1e3 / wavelength_nm;  // k₀ = 2π/λ
    const PlaneOfIncidence plane(xi);

    const Medium ambient_medium(ambient.epsilon, plane, ambient.chirality);
    const auto ambient_modes = all_modes(ambient_medium, plane, medium_spectrum(ambient_medium));
    const Medium substrate_medium(substrate.epsilon, plane, substrate.chirality);
    const auto substrate_modes = all_modes(substrate_medium, plane, medium_spectrum(substrate_medium));

    Scattering total;  // identity
    Matrix42cd forward_below = columns(ambient_modes, 0), backward_below = columns(ambient_modes, 2);
    for (const StackLayer& layer : layers) {
        const Medium medium(layer.epsilon, plane, layer.chirality);
        const Spectrum spectrum = medium_spectrum(medium, true);
        total = star(total, interface(forward_below, backward_below, spectrum.forward.basis, spectrum.backward.basis));
        // Across the layer: ψ(z + d) = exp(i k₀ Δ d) ψ(z) restricted to each invariant subspace.
        Scattering propagation;
        const double phase = k0_per_um * layer.thickness_um;
        propagation.t = exp2(Complex(0.0, phase) * spectrum.forward.generator);
        propagation.t_back = exp2(Complex(0.0, -phase) * spectrum.backward.generator);
        total = star(total, propagation);
        forward_below = spectrum.forward.basis;
        backward_below = spectrum.backward.basis;
    }
    total =
        star(total, interface(forward_below, backward_below, columns(substrate_modes, 0), columns(substrate_modes, 2)));

    // The incident wave's forward-mode amplitudes (its backward-mode components are discarded).
    Eigen::Matrix4cd ambient_basis;
    ambient_basis << columns(ambient_modes, 0), columns(ambient_modes, 2);
    const Eigen::Vector4cd all_amplitudes = ambient_basis.fullPivLu().solve(plane.to_plane(incident_psi));
    const Eigen::Vector2cd incident = all_amplitudes.head<2>();
    const Eigen::Vector2cd reflected = total.r * incident;
    const Eigen::Vector2cd transmitted = total.t * incident;

    StackResponse response;
    response.incident_flux_z = flux_of(columns(ambient_modes, 0) * incident);
    const double incident_flux = response.incident_flux_z;
    const auto power = [&](const BerremanMode& mode, Complex amplitude) {
        if (mode.evanescent || !(incident_flux > 0.0)) return 0.0;
        return std::norm(amplitude) * std::abs(mode.flux_z) / incident_flux;
    };
    for (int i = 0; i < 2; ++i) {
        response.reflected_modes[i] = ambient_modes[2 + i].mode;
        response.reflected_amplitudes[i] = reflected[i];
        response.reflected_power[i] = power(ambient_modes[2 + i].mode, reflected[i]);
        response.transmitted_modes[i] = substrate_modes[i].mode;
        response.transmitted_amplitudes[i] = transmitted[i];
        response.transmitted_power[i] = power(substrate_modes[i].mode, transmitted[i]);
    }
    return response;
}

}  // namespace petroscope
