#include "local_modes.hpp"

#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/slab.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>

namespace petroscope::detail {
namespace {

using complex = std::complex<double>;
template <typename Real>
using Matrix3c = Eigen::Matrix<std::complex<Real>, 3, 3>;
template <typename Real>
using Matrix3r = Eigen::Matrix<Real, 3, 3>;

// A medium in the local frame, in the arithmetic `Real`: ε and, if it is optically active, Landau's gyration
// tensor g and the chirality κ = (tr g/2)·I − g of the equivalent bianisotropic relations (optics/gyration.hpp).
template <typename Real>
struct LocalMedium {
    Matrix3c<Real> epsilon;
    Matrix3r<Real> gyration = Matrix3r<Real>::Zero(), chirality = Matrix3r<Real>::Zero();
    bool active = false;
    explicit LocalMedium(const OpticalMedium& medium)
        : epsilon(medium.permittivity().template cast<std::complex<Real>>()), active(medium.is_active()) {
        if (!active) return;
        const Eigen::Matrix3d lab_gyration = medium.lab_gyration();
        gyration = lab_gyration.template cast<Real>();
        chirality = chirality_tensor(lab_gyration).template cast<Real>();
    }
};

// Thresholds that depend on the arithmetic: the relative separation (squared) below which two roots of the
// quartic are one double root, the relative |Im q| below which a mode of a lossless medium propagates, and for
// a lossless active medium (see general_modes) the relative |Im q| below which a root is real and the relative
// separation below which two roots are one double root (about √ε: Newton's accuracy at a double root). Double
// needs looser ones.
template <typename Real>
struct Thresholds;
template <>
struct Thresholds<long double> {
    static constexpr long double double_root_squared = 1e-20L, propagating = 1e-12L, nearly_real = 1e-7L, active_double_root = 1e-9L;
};
template <>
struct Thresholds<double> {
    static constexpr double double_root_squared = 1e-16, propagating = 1e-7, nearly_real = 1e-7, active_double_root = 1e-7;
};

// A polynomial in q with complex coefficients, lowest degree first (degree ≤ 4 here).
template <typename Real>
struct Polynomial {
    std::array<std::complex<Real>, 5> c{};
    Polynomial operator*(const Polynomial& other) const {
        Polynomial product;
        for (int i = 0; i < 5; ++i) {
            for (int j = 0; i + j < 5; ++j) product.c[i + j] += c[i] * other.c[j];
        }
        return product;
    }
    Polynomial operator-(const Polynomial& other) const {
        Polynomial difference;
        for (int i = 0; i < 5; ++i) difference.c[i] = c[i] - other.c[i];
        return difference;
    }
    Polynomial operator+(const Polynomial& other) const {
        Polynomial sum;
        for (int i = 0; i < 5; ++i) sum.c[i] = c[i] + other.c[i];
        return sum;
    }
    std::complex<Real> operator()(std::complex<Real> q, std::complex<Real>* derivative) const {
        std::complex<Real> value = Real(0), slope = Real(0);
        for (int i = 4; i >= 0; --i) {
            slope = slope * q + value;
            value = value * q + c[i];
        }
        *derivative = slope;
        return value;
    }
};

template <typename Real>
Polynomial<Real> constant(std::complex<Real> a) { return Polynomial<Real>{{a, Real(0), Real(0), Real(0), Real(0)}}; }
template <typename Real>
Polynomial<Real> linear(std::complex<Real> a, std::complex<Real> b) { return Polynomial<Real>{{a, b, Real(0), Real(0), Real(0)}}; }       // a + bq
template <typename Real>
Polynomial<Real> quadratic(std::complex<Real> a, std::complex<Real> c2) { return Polynomial<Real>{{a, Real(0), c2, Real(0), Real(0)}}; }  // a + c₂q²

// The wave equation N × (N × E) + εE + i(g·N) × E = 0 as M(q)E = 0 with N = (ξ, 0, q):
// M = ε + NNᵀ − |N|²I + i[(g·N)×] (Born & Wolf §15.2; Landau & Lifshitz vol. 8 §101; docs/theory.md §1, §9).
template <typename Real>
Matrix3c<Real> wave_matrix(const LocalMedium<Real>& medium, Real xi, std::complex<Real> q) {
    Matrix3c<Real> m = medium.epsilon;
    m(0, 0) -= q * q;
    m(1, 1) -= xi * xi + q * q;
    m(2, 2) -= xi * xi;
    m(0, 2) += xi * q;
    m(2, 0) += xi * q;
    if (medium.active) {
        const Vector3c<Real> g_n = (medium.gyration.col(0) * xi).template cast<std::complex<Real>>() + medium.gyration.col(2).template cast<std::complex<Real>>() * q;
        const Vector3c<Real> i_g = std::complex<Real>(Real(0), Real(1)) * g_n;
        m(0, 1) -= i_g.z();
        m(1, 0) += i_g.z();
        m(0, 2) += i_g.y();
        m(2, 0) -= i_g.y();
        m(1, 2) -= i_g.x();
        m(2, 1) += i_g.x();
    }
    return m;
}

// The mode with field E, its H and z flux: H = N × E, or for an active medium H = N × E + iκE (from
// B = H − iκE; optics/gyration.hpp), with which the tangential E and H are continuous and ½ Re(E × H*) is
// the flux (Berreman, JOSA 62, 502 (1972)).
template <typename Real>
LocalMode<Real> make_mode(std::complex<Real> q, Real xi, const Vector3c<Real>& e_field, const LocalMedium<Real>* active = nullptr) {
    LocalMode<Real> mode;
    mode.q = q;
    mode.e_field = e_field;
    const Vector3c<Real> n_vector(xi, Real(0), q);
    mode.h_field = bilinear_cross(n_vector, e_field);
    if (active) mode.h_field += std::complex<Real>(Real(0), Real(1)) * (active->chirality.template cast<std::complex<Real>>() * e_field);
    mode.flux_z = poynting_z(e_field, mode.h_field);
    return mode;
}

// The same with E scaled to unit length and its largest component real and positive.
template <typename Real>
LocalMode<Real> complete(std::complex<Real> q, Real xi, Vector3c<Real> e_field, const LocalMedium<Real>* active = nullptr) {
    Eigen::Index largest = 0;
    e_field.cwiseAbs2().maxCoeff(&largest);
    e_field *= std::conj(e_field[largest]) / (std::sqrt(magnitude_squared(e_field[largest])) * e_field.norm());
    return make_mode(q, xi, e_field, active);
}

template <typename Real>
LocalModes<Real> isotropic_modes(complex n_double, Real xi) {
    const std::complex<Real> n(n_double.real(), n_double.imag());
    // Q = √(n² − ξ²) = √((n − ξ)(n + ξ)) on the branch that decays (or propagates) toward +z.
    std::complex<Real> big_q = std::sqrt((n - xi) * (n + xi));
    if (big_q.imag() < Real(0) || (big_q.imag() == Real(0) && big_q.real() < Real(0))) big_q = -big_q;
    LocalModes<Real> modes;
    const bool evanescent = big_q.real() == Real(0) || std::abs(big_q.real()) < Real(1e-15L) * std::abs(big_q);
    for (int direction = 0; direction < 2; ++direction) {
        const std::complex<Real> q = direction == 0 ? big_q : -big_q;
        // s: E ∥ ŷ; p: E ∥ ŝ × k̂ = (q, 0, −ξ)/n for N = (ξ, 0, q).
        const LocalMode<Real> s = make_mode(q, xi, Vector3c<Real>(Real(0), Real(1), Real(0)));
        const LocalMode<Real> p = make_mode(q, xi, Vector3c<Real>(q / n, Real(0), -xi / n));
        auto& pair = direction == 0 ? modes.forward : modes.backward;
        pair = {s, p};
        for (auto& mode : pair) mode.evanescent = evanescent;
    }
    return modes;
}

// Lossless anisotropic medium whose four modes propagate: the robust sheet solver. The
// vibration directions come from the binormal geometry, well conditioned even where the two roots of a
// sheet nearly meet (grazing incidence), where null vectors of M(q) are not. Forward: energy toward +z.
template <typename Real>
bool propagating_anisotropic_modes(const OpticalMedium& medium, double xi, LocalModes<Real>& modes) {
    const BasicBinormalFrame<Real> frame(Indicatrix{medium.real_n(), medium.axes});
    std::array<SheetMode<Real>, 4> roots;
    if (!solve_sheet_modes(frame, {xi, 0.0}, roots)) return false;
    for (int sheet = 0; sheet < 2; ++sheet) {
        const auto s = static_cast<std::size_t>(sheet);
        LocalMode<Real> first = complete<Real>(roots[2 * s].q, xi, roots[2 * s].e_field.template cast<std::complex<Real>>());
        LocalMode<Real> second = complete<Real>(roots[2 * s + 1].q, xi, roots[2 * s + 1].e_field.template cast<std::complex<Real>>());
        if (first.flux_z < second.flux_z) std::swap(first, second);
        modes.forward[s] = first;
        modes.backward[s] = second;
    }
    return true;
}

// det A by Gaussian elimination with complete pivoting (Golub & Van Loan, Matrix Computations, 4th ed.,
// §3.4.8; backward stable), pivots chosen by |z|² (no hypotl).
template <typename Real>
std::complex<Real> determinant_full_pivoting(Matrix3c<Real> a) {
    std::complex<Real> determinant = Real(1);
    for (int k = 0; k < 3; ++k) {
        const auto [best, pivot_row, pivot_column] = largest_entry(a, k);
        if (!(best > Real(0))) return Real(0);
        if (pivot_row != k) {
            a.row(k).swap(a.row(pivot_row));
            determinant = -determinant;
        }
        if (pivot_column != k) {
            a.col(k).swap(a.col(pivot_column));
            determinant = -determinant;
        }
        determinant *= a(k, k);
        const std::complex<Real> inverse = std::conj(a(k, k)) / best;
        for (int i = k + 1; i < 3; ++i) {
            const std::complex<Real> factor = a(i, k) * inverse;
            for (int j = k + 1; j < 3; ++j) a(i, j) -= factor * a(k, j);
        }
    }
    return determinant;
}

// The roots of det M(q) = 0, a quartic, for any medium: the eigenvalues of its companion matrix (double is
// enough for starting values), polished by Newton in `Real`. `real_on_axis`: det M is real for real q.
template <typename Real>
std::array<std::complex<Real>, 4> quartic_roots(const LocalMedium<Real>& medium, Real xi, bool real_on_axis) {
    const auto x = [&](int i, int j) { return medium.epsilon(i, j); };
    // The components of i(g·N) = i(ξ g₀ + q g₂), linear in q (zero for an inactive medium).
    const auto i_g = [&](int c) {
        const std::complex<Real> i(Real(0), Real(1));
        return linear<Real>(i * xi * medium.gyration(c, 0), i * medium.gyration(c, 2));
    };
    const Polynomial<Real> m00 = quadratic<Real>(x(0, 0), -Real(1)), m01 = constant<Real>(x(0, 1)) - i_g(2), m02 = linear<Real>(x(0, 2), xi) + i_g(1);
    const Polynomial<Real> m10 = constant<Real>(x(1, 0)) + i_g(2), m11 = quadratic<Real>(x(1, 1) - xi * xi, -Real(1)), m12 = constant<Real>(x(1, 2)) - i_g(0);
    const Polynomial<Real> m20 = linear<Real>(x(2, 0), xi) - i_g(1), m21 = constant<Real>(x(2, 1)) + i_g(0), m22 = constant<Real>(x(2, 2) - xi * xi);
    const Polynomial<Real> determinant = m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) + m02 * (m10 * m21 - m11 * m20);
    Eigen::Matrix4cd companion = Eigen::Matrix4cd::Zero();
    for (int i = 0; i < 3; ++i) companion(i + 1, i) = 1.0;
    for (int i = 0; i < 4; ++i) {
        const std::complex<Real> coefficient = -determinant.c[static_cast<std::size_t>(i)] / determinant.c[4];
        companion(i, 3) = complex(static_cast<double>(coefficient.real()), static_cast<double>(coefficient.imag()));
    }
    Eigen::ComplexEigenSolver<Eigen::Matrix4cd> solver(companion, false);
    // Newton from q: `steps` on the coefficient form, then on det M(q) by a pivoted LU. The coefficient form
    // cancels to about 1e-17 near nearly-double roots (close sheets); the LU is backward stable, so a few
    // steps on it make q exact to rounding. Returns the root and |det M| there.
    const auto polish = [&](std::complex<Real> q, int steps) {
        for (int step = 0; step < steps; ++step) {
            std::complex<Real> slope;
            const std::complex<Real> value = determinant(q, &slope);
            if (std::abs(slope) == Real(0)) break;
            const std::complex<Real> change = value / slope;
            q -= change;
            if (std::abs(change) <= std::numeric_limits<Real>::epsilon() * std::abs(q)) break;
        }
        std::complex<Real> value = Real(0);
        for (int step = 0; step < 3; ++step) {
            std::complex<Real> slope;
            determinant(q, &slope);
            value = determinant_full_pivoting(wave_matrix(medium, xi, q));
            if (std::abs(slope) == Real(0)) break;
            q -= value / slope;
        }
        return std::pair{q, std::abs(value)};
    };
    std::array<std::complex<Real>, 4> roots;
    for (int i = 0; i < 4; ++i) {
        const std::complex<Real> start(solver.eigenvalues()[i].real(), solver.eigenvalues()[i].imag());
        auto [q, residual] = polish(start, 6);
        // A lossless active medium's det M(q) is real on the real axis (M is Hermitian there), so its roots are
        // real or conjugate pairs. Two close real roots can come out of the double-precision eigenvalues as a
        // conjugate pair a ± ib, on the boundary between Newton's basins of the two roots. Started on the real
        // axis, outward at a ± 2b, Newton converges to each real root (linearly, as at a double root, so with more
        // steps); the start with the smaller |det M| wins.
        if (real_on_axis && std::abs(start.imag()) <= Real(1e-5) * std::max(Real(1), std::abs(start))) {
            const auto [real_q, real_residual] = polish(std::complex<Real>(start.real() + Real(2) * start.imag(), Real(0)), 80);
            if (real_residual <= residual) q = real_q;
        }
        roots[static_cast<std::size_t>(i)] = q;
    }
    return roots;
}

// The roots of a polynomial that is real on the real axis, those within rounding of it made real: a root whose
// |Im q| is below Thresholds::nearly_real (relative), and the member of a conjugate pair whose other member is.
template <typename Real>
std::array<std::complex<Real>, 4> real_within_rounding(const std::array<std::complex<Real>, 4>& roots) {
    const auto tolerance = [](const std::complex<Real>& q) { return Thresholds<Real>::nearly_real * std::max(Real(1), std::abs(q)); };
    const auto nearly_real = [&](const std::complex<Real>& q) { return std::abs(q.imag()) <= tolerance(q); };
    std::array<std::complex<Real>, 4> result = roots;
    for (std::size_t i = 0; i < 4; ++i) {
        bool real = nearly_real(roots[i]);
        for (std::size_t j = 0; j < 4; ++j) {
            const bool conjugates = std::abs(roots[i] - std::conj(roots[j])) <= Real(2) * tolerance(roots[i]);
            real = real || (j != i && conjugates && nearly_real(roots[j]));
        }
        if (real) result[i] = roots[i].real();
    }
    return result;
}

// General medium: the roots of the quartic, their null vectors, forward and backward.
template <typename Real>
LocalModes<Real> general_modes(const OpticalMedium& medium, double xi_double) {
    const LocalMedium<Real> local(medium);
    const LocalMedium<Real>* active = local.active ? &local : nullptr;
    const Real xi = xi_double;
    const bool lossless = medium.is_lossless();
    std::array<std::complex<Real>, 4> roots = quartic_roots(local, xi, active && lossless);
    // A lossless active medium's roots are real or conjugate pairs (quartic_roots). Two close real roots, where the
    // gyration barely splits the two waves of a direction, keep imaginary parts of rounding size: within that they
    // are real, and a pair within about √ε (Newton's accuracy at a double root) is one double root.
    Real double_root_squared = Thresholds<Real>::double_root_squared;
    if (active && lossless) {
        roots = real_within_rounding(roots);
        double_root_squared = Thresholds<Real>::active_double_root * Thresholds<Real>::active_double_root;
    }
    // Null vectors: of a simple root, M(q) has rank 2 and its null vector is the (unconjugated) cross
    // product of two of its rows, the largest of the three; a double root (degenerate modes) takes the two
    // smallest singular vectors of M at the pair's mean, one each.
    std::array<LocalMode<Real>, 4> all;
    for (std::size_t i = 0; i < 4; ++i) {
        const Matrix3c<Real> m = wave_matrix(local, xi, roots[i]);
        std::size_t partner = i;
        for (std::size_t j = 0; j < 4 && partner == i; ++j) {
            if (j != i && magnitude_squared(roots[i] - roots[j]) <= double_root_squared * magnitude_squared(roots[i])) partner = j;
        }
        if (partner != i) {
            // The pair's two-dimensional near-null space, M's two smallest singular vectors at the pair's mean,
            // one each.
            const Eigen::JacobiSVD<Matrix3c<Real>> svd(wave_matrix(local, xi, (roots[i] + roots[partner]) / Real(2)), Eigen::ComputeFullV);
            all[i] = complete<Real>(roots[i], xi, svd.matrixV().col(partner < i ? 1 : 2), active);
            continue;
        }
        Vector3c<Real> null_vector = bilinear_cross<Real>(m.row(0).transpose(), m.row(1).transpose());
        for (const auto& [a, b] : {std::pair{1, 2}, std::pair{2, 0}}) {
            const Vector3c<Real> candidate = bilinear_cross<Real>(m.row(a).transpose(), m.row(b).transpose());
            if (candidate.squaredNorm() > null_vector.squaredNorm()) null_vector = candidate;
        }
        all[i] = complete(roots[i], xi, null_vector, active);
    }
    // Forward: energy toward +z for propagating modes of a lossless medium, otherwise decay toward +z.
    const auto toward_plus_z = [lossless](LocalMode<Real>& mode) {
        const Real scale = std::max(Real(1), std::abs(mode.q));
        mode.evanescent = lossless ? std::abs(mode.q.imag()) > Thresholds<Real>::propagating * scale : std::abs(mode.q.real()) < Thresholds<Real>::propagating * scale;
        return (lossless && !mode.evanescent) ? mode.flux_z : mode.q.imag();
    };
    std::array<std::pair<Real, std::size_t>, 4> order;
    for (std::size_t i = 0; i < 4; ++i) order[i] = {toward_plus_z(all[i]), i};
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const auto index_of = [xi](const LocalMode<Real>& mode) { return std::sqrt(xi * xi + mode.q * mode.q).real(); };
    const auto by_index = [&](const LocalMode<Real>& a, const LocalMode<Real>& b) { return index_of(a) < index_of(b); };
    LocalModes<Real> modes;
    modes.forward = {all[order[0].second], all[order[1].second]};
    modes.backward = {all[order[2].second], all[order[3].second]};
    std::sort(modes.forward.begin(), modes.forward.end(), by_index);
    std::sort(modes.backward.begin(), modes.backward.end(), by_index);
    return modes;
}

}  // namespace

template <typename Real>
LocalModes<Real> local_modes(const OpticalMedium& medium, double xi) {
    if (medium.has_s_and_p_waves()) return isotropic_modes<Real>(medium.principal_n[0], xi);
    // Lossless and inactive with four propagating modes: the Biot–Fresnel sheets, exact on the optic axes and
    // well conditioned near grazing. Otherwise (evanescent or absorbing modes, optical activity): the quartic
    // and its null vectors.
    LocalModes<Real> modes;
    if (!medium.is_active() && medium.is_lossless() && propagating_anisotropic_modes(medium, xi, modes)) return modes;
    return general_modes<Real>(medium, xi);
}

template LocalModes<double> local_modes(const OpticalMedium&, double);
template LocalModes<long double> local_modes(const OpticalMedium&, double);

}  // namespace petroscope::detail
