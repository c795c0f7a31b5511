#include "local_modes.hpp"

#include "petroscope/optics/slab.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>

namespace petroscope::detail {
namespace {

using complex = std::complex<double>;
using Matrix3x = Eigen::Matrix<ExtendedComplex, 3, 3>;

// A polynomial in q with complex coefficients, lowest degree first (degree ≤ 4 here).
using extended = ExtendedComplex;

struct Polynomial {
    std::array<extended, 5> c{};
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
    extended operator()(extended q, extended* derivative) const {
        extended value = 0.0L, slope = 0.0L;
        for (int i = 4; i >= 0; --i) {
            slope = slope * q + value;
            value = value * q + c[i];
        }
        *derivative = slope;
        return value;
    }
};

Polynomial constant(extended a) { return Polynomial{{a, 0.0L, 0.0L, 0.0L, 0.0L}}; }
Polynomial linear(extended a, extended b) { return Polynomial{{a, b, 0.0L, 0.0L, 0.0L}}; }       // a + bq
Polynomial quadratic(extended a, extended c2) { return Polynomial{{a, 0.0L, c2, 0.0L, 0.0L}}; }  // a + c₂q²

// The wave equation N × (N × E) + εE = 0 as M(q)E = 0 with N = (ξ, 0, q):
// M = ε + NNᵀ − |N|²I (Born & Wolf §15.2; docs/theory.md §1).
Matrix3x wave_matrix(const Matrix3x& epsilon, Extended xi, ExtendedComplex q) {
    Matrix3x m = epsilon;
    m(0, 0) -= q * q;
    m(1, 1) -= xi * xi + q * q;
    m(2, 2) -= xi * xi;
    m(0, 2) += xi * q;
    m(2, 0) += xi * q;
    return m;
}

// The mode with field E (H = N × E and the z flux follow).
LocalMode make_mode(ExtendedComplex q, Extended xi, const ExtendedVector3& e_field) {
    LocalMode mode;
    mode.q = q;
    mode.e_field = e_field;
    const ExtendedVector3 n_vector(xi, 0.0L, q);
    mode.h_field = bilinear_cross(n_vector, e_field);
    mode.flux_z = poynting_z(e_field, mode.h_field);
    return mode;
}

// The same with E scaled to unit length and its largest component real and positive.
LocalMode complete(ExtendedComplex q, Extended xi, ExtendedVector3 e_field) {
    Eigen::Index largest = 0;
    e_field.cwiseAbs2().maxCoeff(&largest);
    e_field *= std::conj(e_field[largest]) / (std::sqrt(magnitude_squared(e_field[largest])) * e_field.norm());
    return make_mode(q, xi, e_field);
}

LocalModes isotropic_modes(complex n_double, Extended xi) {
    const ExtendedComplex n(n_double.real(), n_double.imag());
    // Q = √(n² − ξ²) = √((n − ξ)(n + ξ)) on the branch that decays (or propagates) toward +z.
    ExtendedComplex big_q = std::sqrt((n - xi) * (n + xi));
    if (big_q.imag() < 0.0L || (big_q.imag() == 0.0L && big_q.real() < 0.0L)) big_q = -big_q;
    LocalModes modes;
    const bool evanescent = big_q.real() == 0.0L || std::abs(big_q.real()) < 1e-15L * std::abs(big_q);
    for (int direction = 0; direction < 2; ++direction) {
        const ExtendedComplex q = direction == 0 ? big_q : -big_q;
        // s: E ∥ ŷ; p: E ∥ ŝ × k̂ = (q, 0, −ξ)/n for N = (ξ, 0, q).
        const LocalMode s = make_mode(q, xi, ExtendedVector3(0.0L, 1.0L, 0.0L));
        const LocalMode p = make_mode(q, xi, ExtendedVector3(q / n, 0.0L, -xi / n));
        auto& pair = direction == 0 ? modes.forward : modes.backward;
        pair = {s, p};
        for (auto& mode : pair) mode.evanescent = evanescent;
    }
    return modes;
}

// Lossless anisotropic medium whose four modes propagate: the robust sheet solver, in long double. The
// vibration directions come from the binormal geometry, well conditioned even where the two roots of a
// sheet nearly meet (grazing incidence), where null vectors of M(q) are not. Forward: energy toward +z.
bool propagating_anisotropic_modes(const OpticalMedium& medium, double xi, LocalModes& modes) {
    const BasicBinormalFrame<Extended> frame(Indicatrix{medium.real_n(), medium.axes});
    std::array<ExtendedSlabMode, 4> roots;
    if (!solve_sheet_modes_extended(frame, {xi, 0.0}, roots)) return false;
    for (int sheet = 0; sheet < 2; ++sheet) {
        const auto s = static_cast<std::size_t>(sheet);
        LocalMode first = complete(roots[2 * s].q, xi, roots[2 * s].e_field.cast<ExtendedComplex>());
        LocalMode second = complete(roots[2 * s + 1].q, xi, roots[2 * s + 1].e_field.cast<ExtendedComplex>());
        if (first.flux_z < second.flux_z) std::swap(first, second);
        modes.forward[s] = first;
        modes.backward[s] = second;
    }
    return true;
}

// det A by Gaussian elimination with complete pivoting (Golub & Van Loan, Matrix Computations, 4th ed.,
// §3.4.8; backward stable), pivots chosen by |z|² (no hypotl).
ExtendedComplex determinant_full_pivoting(Matrix3x a) {
    ExtendedComplex determinant = 1.0L;
    for (int k = 0; k < 3; ++k) {
        int pivot_row = k, pivot_column = k;
        Extended best = -1.0L;
        for (int j = k; j < 3; ++j) {
            for (int i = k; i < 3; ++i) {
                if (magnitude_squared(a(i, j)) > best) {
                    best = magnitude_squared(a(i, j));
                    pivot_row = i;
                    pivot_column = j;
                }
            }
        }
        if (!(best > 0.0L)) return 0.0L;
        if (pivot_row != k) {
            a.row(k).swap(a.row(pivot_row));
            determinant = -determinant;
        }
        if (pivot_column != k) {
            a.col(k).swap(a.col(pivot_column));
            determinant = -determinant;
        }
        determinant *= a(k, k);
        const ExtendedComplex inverse = std::conj(a(k, k)) / best;
        for (int i = k + 1; i < 3; ++i) {
            const ExtendedComplex factor = a(i, k) * inverse;
            for (int j = k + 1; j < 3; ++j) a(i, j) -= factor * a(k, j);
        }
    }
    return determinant;
}

// The roots of det M(q) = 0, a quartic, for any medium: the eigenvalues of its companion matrix (double is
// enough for starting values), polished by Newton in long double.
std::array<ExtendedComplex, 4> quartic_roots(const Matrix3x& epsilon, Extended xi) {
    const auto x = [&](int i, int j) { return epsilon(i, j); };
    const Polynomial m00 = quadratic(x(0, 0), -1.0L), m01 = constant(x(0, 1)), m02 = linear(x(0, 2), xi);
    const Polynomial m10 = constant(x(1, 0)), m11 = quadratic(x(1, 1) - xi * xi, -1.0L), m12 = constant(x(1, 2));
    const Polynomial m20 = linear(x(2, 0), xi), m21 = constant(x(2, 1)), m22 = constant(x(2, 2) - xi * xi);
    const Polynomial determinant = m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) + m02 * (m10 * m21 - m11 * m20);
    Eigen::Matrix4cd companion = Eigen::Matrix4cd::Zero();
    for (int i = 0; i < 3; ++i) companion(i + 1, i) = 1.0;
    for (int i = 0; i < 4; ++i) {
        const extended coefficient = -determinant.c[static_cast<std::size_t>(i)] / determinant.c[4];
        companion(i, 3) = complex(static_cast<double>(coefficient.real()), static_cast<double>(coefficient.imag()));
    }
    Eigen::ComplexEigenSolver<Eigen::Matrix4cd> solver(companion, false);
    std::array<ExtendedComplex, 4> roots;
    for (int i = 0; i < 4; ++i) {
        extended q(solver.eigenvalues()[i].real(), solver.eigenvalues()[i].imag());
        for (int step = 0; step < 6; ++step) {
            extended slope;
            const extended value = determinant(q, &slope);
            if (std::abs(slope) == 0.0L) break;
            q -= value / slope;
        }
        // The coefficient form cancels to about 1e-17 near nearly-double roots (close sheets); det M(q) by a
        // pivoted LU is backward stable, so a few more Newton steps on it make q exact in long double.
        for (int step = 0; step < 3; ++step) {
            extended slope;
            determinant(q, &slope);
            const extended value = determinant_full_pivoting(wave_matrix(epsilon, xi, q));
            if (std::abs(slope) == 0.0L) break;
            q -= value / slope;
        }
        roots[static_cast<std::size_t>(i)] = q;
    }
    return roots;
}

// General medium: the roots of the quartic, their null vectors, forward and backward.
LocalModes general_modes(const OpticalMedium& medium, double xi_double) {
    const Matrix3x epsilon = medium.permittivity().cast<ExtendedComplex>();
    const Extended xi = xi_double;
    const std::array<ExtendedComplex, 4> roots = quartic_roots(epsilon, xi);
    // Null vectors: of a simple root, M(q) has rank 2 and its null vector is the (unconjugated) cross
    // product of two of its rows, the largest of the three; a double root (degenerate modes) takes the two
    // smallest singular vectors.
    std::array<LocalMode, 4> all;
    for (std::size_t i = 0; i < 4; ++i) {
        const Matrix3x m = wave_matrix(epsilon, xi, roots[i]);
        bool double_root = false;
        for (std::size_t j = 0; j < 4; ++j) {
            double_root = double_root || (j != i && magnitude_squared(roots[i] - roots[j]) <= 1e-20L * magnitude_squared(roots[i]));
        }
        if (double_root) {
            const Eigen::JacobiSVD<Matrix3x> svd(m, Eigen::ComputeFullV);
            bool second = false;
            for (std::size_t j = 0; j < i; ++j) second = second || magnitude_squared(roots[i] - roots[j]) <= 1e-20L * magnitude_squared(roots[i]);
            all[i] = complete(roots[i], xi, svd.matrixV().col(second ? 1 : 2));
            continue;
        }
        ExtendedVector3 null_vector = bilinear_cross(m.row(0).transpose(), m.row(1).transpose());
        for (const auto& [a, b] : {std::pair{1, 2}, std::pair{2, 0}}) {
            const ExtendedVector3 candidate = bilinear_cross(m.row(a).transpose(), m.row(b).transpose());
            if (candidate.squaredNorm() > null_vector.squaredNorm()) null_vector = candidate;
        }
        all[i] = complete(roots[i], xi, null_vector);
    }
    // Forward: energy toward +z for propagating modes of a lossless medium, otherwise decay toward +z.
    const bool lossless = medium.is_lossless();
    const auto toward_plus_z = [lossless](LocalMode& mode) {
        const Extended scale = std::max(Extended(1), std::abs(mode.q));
        mode.evanescent = lossless ? std::abs(mode.q.imag()) > 1e-12L * scale : std::abs(mode.q.real()) < 1e-12L * scale;
        return (lossless && !mode.evanescent) ? mode.flux_z : mode.q.imag();
    };
    std::array<std::pair<Extended, std::size_t>, 4> order;
    for (std::size_t i = 0; i < 4; ++i) order[i] = {toward_plus_z(all[i]), i};
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const auto index_of = [xi](const LocalMode& mode) { return std::sqrt(xi * xi + mode.q * mode.q).real(); };
    const auto by_index = [&](const LocalMode& a, const LocalMode& b) { return index_of(a) < index_of(b); };
    LocalModes modes;
    modes.forward = {all[order[0].second], all[order[1].second]};
    modes.backward = {all[order[2].second], all[order[3].second]};
    std::sort(modes.forward.begin(), modes.forward.end(), by_index);
    std::sort(modes.backward.begin(), modes.backward.end(), by_index);
    return modes;
}

}  // namespace

LocalModes local_modes(const OpticalMedium& medium, double xi) {
    if (medium.is_isotropic()) return isotropic_modes(medium.principal_n[0], xi);
    // Lossless with four propagating modes: the Biot–Fresnel sheets in long double, exact on the optic
    // axes and well conditioned near grazing. Otherwise (evanescent or absorbing modes): the long-double
    // quartic and its null vectors.
    LocalModes modes;
    if (medium.is_lossless() && propagating_anisotropic_modes(medium, xi, modes)) return modes;
    return general_modes(medium, xi);
}

}  // namespace petroscope::detail
