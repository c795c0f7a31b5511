#include "petroscope/optics/slab.hpp"

#include "petroscope/core/fast_math.hpp"
#include "petroscope/optics/eigenmodes.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <type_traits>

namespace petroscope {
namespace {

// The sheet equation g_σ(q) = A|N|² + B(N·b₁)(N·b₂) + σB|N × b₁||N × b₂| − 1 with N = (ξ, q),
// A = (a + c)/2, B = (a − c)/2, σ = +1 fast, −1 slow: the Biot–Fresnel form of eigenmodes.hpp
// multiplied by |N|² (|N|²c₁c₂ = (N·b₁)(N·b₂), |N|²s₁s₂ = |N × b₁||N × b₂|), so that its roots are
// the k_z/k₀ of the modes on that sheet.
template <typename Real>
struct SheetEquation {
    Real a_half_sum, b_half_difference, sigma;
    Real xi2;          // |ξ|²
    Real u1, u2;       // ξ·b₁, ξ·b₂ (tangential parts)
    Real b1z, b2z;     // z components of the binormals

    Real value(Real q, Real* derivative) const {
        using std::max, std::sqrt;
        const Real n2 = xi2 + q * q;
        const Real nb1 = u1 + q * b1z;
        const Real nb2 = u2 + q * b2z;
        const Real p1 = max(n2 - nb1 * nb1, Real(0));  // |N × b₁|²
        const Real p2 = max(n2 - nb2 * nb2, Real(0));
        const Real root = sqrt(p1 * p2);
        const Real g = a_half_sum * n2 + b_half_difference * (nb1 * nb2 + sigma * root) - Real(1);
        const Real dp1 = Real(2) * (q - nb1 * b1z);
        const Real dp2 = Real(2) * (q - nb2 * b2z);
        const Real droot = root > Real(0) ? Real(0.5) * (dp1 * p2 + p1 * dp2) / root : Real(0);
        *derivative = Real(2) * a_half_sum * q + b_half_difference * (b1z * nb2 + b2z * nb1 + sigma * droot);
        return g;
    }
    Real value(Real q) const {
        Real unused = 0;
        return value(q, &unused);
    }

    template <typename Other>
    SheetEquation<Other> as() const {
        return {Other(a_half_sum), Other(b_half_difference), Other(sigma), Other(xi2), Other(u1), Other(u2), Other(b1z), Other(b2z)};
    }
};

// The sheet equation of `frame` for sheet 0 (fast) or 1 (slow) at tangential wavevector ξ.
template <typename Real>
SheetEquation<Real> sheet_equation(const BasicBinormalFrame<Real>& frame, const Eigen::Vector2d& xi, int sheet) {
    const Real xi_x = xi.x(), xi_y = xi.y();
    return {Real(0.5) * (frame.a + frame.c),
            Real(0.5) * (frame.a - frame.c),
            sheet == 0 ? Real(1) : Real(-1),
            xi_x * xi_x + xi_y * xi_y,
            xi_x * frame.binormal_1.x() + xi_y * frame.binormal_1.y(),
            xi_x * frame.binormal_2.x() + xi_y * frame.binormal_2.y(),
            frame.binormal_1.z(),
            frame.binormal_2.z()};
}

// Newton steps in long double, each kept only if it lowers |g| and moves q by less than 1e-6·q (the root is
// already that close): at the kink of a sheet on a binormal a plain step can jump.
long double polished(const SheetEquation<long double>& equation, long double q) {
    long double derivative = 0.0L;
    long double value = equation.value(q, &derivative);
    for (int step = 0; step < 3 && value != 0.0L && derivative != 0.0L; ++step) {
        const long double next = q - value / derivative;
        if (!(std::abs(next - q) <= 1e-6L * std::abs(q))) break;
        long double next_derivative = 0.0L;
        const long double next_value = equation.value(next, &next_derivative);
        if (!(std::abs(next_value) < std::abs(value))) break;
        q = next;
        value = next_value;
        derivative = next_derivative;
    }
    return q;
}

// Roots are polished in long double whatever `Real`. Near grazing incidence g'(q) ∝ q → 0, and evaluating g
// in double leaves q off by about ε/g'; polished in long double the root is exact to its last bit, so the
// mode fields solve the wave equation to rounding. Near a binormal |N × b| keeps only half the digits
// (√ε: 1e-8 in double), which would split the two sheets' roots there by more than kCommonNormalSplitting.
template <typename Real>
Real polish(const SheetEquation<Real>& equation, Real q) {
    return static_cast<Real>(polished(equation.template as<long double>(), q));
}

// Root of the sheet equation between `end_a` (where g < 0: q = 0) and `end_b` (where g > 0), by Newton's
// method kept inside the shrinking bracket; bisection whenever a Newton step would leave it.
double solve_bracketed(const SheetEquation<double>& equation, double end_a, double end_b, double guess) {
    double negative_end = end_a;
    double positive_end = end_b;
    double q = (std::isfinite(guess) && (guess - end_a) * (guess - end_b) < 0.0) ? guess : 0.5 * (end_a + end_b);
    for (int iteration = 0; iteration < 200; ++iteration) {
        double derivative = 0.0;
        const double g = equation.value(q, &derivative);
        if (g == 0.0) return q;
        (g < 0.0 ? negative_end : positive_end) = q;
        double next = q - g / derivative;
        const bool inside = (next - negative_end) * (next - positive_end) < 0.0;
        if (!inside || !std::isfinite(next)) next = 0.5 * (negative_end + positive_end);
        if (std::abs(next - q) <= 2.0 * std::numeric_limits<double>::epsilon() * std::abs(q) ||
            next == negative_end || next == positive_end) {
            return next;
        }
        q = next;
    }
    return q;
}

// Uniaxial crystal (b₂ = ±b₁ = ±b): |N × b₁||N × b₂| = |N|² − (N·b)², so g_σ is the quadratic
// αq² + βq + γ (α > 0: the sheet is an ellipsoid). `orientation_sign` is b₁·b₂.
template <typename Real>
struct SheetQuadratic {
    Real alpha, beta, gamma;
    SheetQuadratic(const SheetEquation<Real>& e, Real orientation_sign) {
        const Real level = e.a_half_sum + e.sigma * e.b_half_difference;
        const Real cross = e.b_half_difference * (orientation_sign - e.sigma);
        alpha = level + cross * e.b1z * e.b1z;
        beta = Real(2) * cross * e.u1 * e.b1z;
        gamma = level * e.xi2 + cross * e.u1 * e.u1 - Real(1);
    }
    /// Negative when the line N = (ξ, q) misses the sheet (evanescent modes).
    Real discriminant() const { return beta * beta - Real(4) * alpha * gamma; }
    /// The real roots, lower then upper, for a discriminant ≥ 0, by the numerically stable form (Press et
    /// al., Numerical Recipes, §5.6).
    std::pair<Real, Real> roots(Real discriminant) const {
        const Real t = Real(-0.5) * (beta + std::copysign(std::sqrt(discriminant), beta));
        const Real r1 = t / alpha;
        const Real r2 = t != Real(0) ? gamma / t : -r1;
        return std::minmax(r1, r2);
    }
};

// The forward root when g(0) < 0: then the roots are real and of opposite signs (a discriminant that
// rounding makes slightly negative is taken as zero), and the upper one is forward.
double forward_quadratic_root(const SheetQuadratic<double>& quadratic) {
    return quadratic.roots(std::max(quadratic.discriminant(), 0.0)).second;
}

// Relative splitting of the two sheets' roots below which their vibration directions are taken at one
// common wave normal. Within ~1e-16 rad of a binormal the two roots' normals can lie on opposite sides of
// it, where the projection of the binormal flips: computed separately, D_fast at one normal and D_slow at
// the other can then be parallel. At a common normal they are orthogonal by construction, and the modes
// being degenerate to this precision, any orthogonal pair is a solution. Roots polished in long double from
// a long-double frame split by about 3e-10 on a binormal; from a double frame (the double-precision
// interface solve) by about √ε of double (4e-8 measured), which its own threshold covers.
constexpr double kCommonNormalSplitting = 1e-9;
constexpr double kCommonNormalSplittingOfDoubleFrames = 1e-7;

// The fields of the two modes with wave vectors (ξ, q_fast) and (ξ, q_slow): E = η·D, H = N × E; at a
// common normal when the roots split by less than `common_normal_splitting` (relative).
template <typename Real>
std::array<std::pair<Eigen::Matrix<Real, 3, 1>, Eigen::Matrix<Real, 3, 1>>, 2> mode_fields(
    const BasicBinormalFrame<Real>& frame, const Eigen::Vector2d& xi, Real q_fast, Real q_slow, double common_normal_splitting) {
    using Vector = Eigen::Matrix<Real, 3, 1>;
    const Vector n_fast(xi.x(), xi.y(), q_fast), n_slow(xi.x(), xi.y(), q_slow);
    Vector d_fast, d_slow;
    if (std::abs(q_fast - q_slow) <= Real(common_normal_splitting) * std::abs(q_fast)) {
        std::tie(d_fast, d_slow) = vibration_directions(frame, Vector((n_fast + n_slow).normalized()));
    } else {
        d_fast = vibration_directions(frame, Vector(n_fast.normalized())).first;
        d_slow = vibration_directions(frame, Vector(n_slow.normalized())).second;
    }
    const Vector e_fast = frame.impermeability * d_fast, e_slow = frame.impermeability * d_slow;
    return {{{e_fast, n_fast.cross(e_fast)}, {e_slow, n_slow.cross(e_slow)}}};
}

// Amplitudes (s, p) of the forward (`sign` = +1) or backward (−1) plane waves of an isotropic medium of
// index n whose sum has the tangential field ψ. Forward s: ψ = (0, 0, 1, Q); forward p (unit E):
// ψ = (Q/n, n, 0, 0); the backward waves flip the sign of Q (Q = √(n² − |ξ|²)).
Eigen::Vector2d isotropic_amplitudes(const Eigen::Vector4d& psi, double n, double big_q, double sign) {
    return {0.5 * (psi[2] + sign * psi[3] / big_q), 0.5 * (psi[0] * n / big_q + sign * psi[1] / n)};
}

Eigen::Matrix2d isotropic_amplitudes(const SlabMode& first, const SlabMode& second, const TangentialWavevector& direction,
                                     double n, double big_q, double sign) {
    Eigen::Matrix2d amplitudes;
    amplitudes.col(0) = isotropic_amplitudes(tangential_field(first, direction), n, big_q, sign);
    amplitudes.col(1) = isotropic_amplitudes(tangential_field(second, direction), n, big_q, sign);
    return amplitudes;
}

}  // namespace

TangentialWavevector TangentialWavevector::from_xi(const Eigen::Vector2d& xi) {
    TangentialWavevector direction;
    direction.xi = xi;
    const double length = xi.norm();
    if (length > 0.0) direction.radial = xi / length;
    direction.azimuthal = {-direction.radial.y(), direction.radial.x()};
    return direction;
}

Eigen::Vector4d tangential_field(const SlabMode& mode, const TangentialWavevector& direction) {
    const Eigen::Vector2d& radial = direction.radial;
    const Eigen::Vector2d& azimuthal = direction.azimuthal;
    return {mode.e_field.head<2>().dot(radial), mode.h_field.head<2>().dot(azimuthal),
            mode.e_field.head<2>().dot(azimuthal), -mode.h_field.head<2>().dot(radial)};
}

SlabMode time_reversed(const SlabMode& mode) {
    return SlabMode{-mode.q, mode.e_field, -mode.h_field};
}

bool solve_forward_modes(const BinormalFrame& frame, const Eigen::Vector2d& xi, const Eigen::Vector2d& guess,
                         std::array<SlabMode, 2>& modes) {
    const double n_max = 1.0 / std::sqrt(frame.c);
    std::array<double, 2> q{};
    for (int sheet = 0; sheet < 2; ++sheet) {
        const SheetEquation<double> equation = sheet_equation(frame, xi, sheet);
        double derivative = 0.0;
        // |ξ| reaches the sheet's index: no propagating mode on this sheet.
        if (equation.value(0.0, &derivative) >= 0.0) return false;
        q[static_cast<std::size_t>(sheet)] =
            polish(equation, frame.uniaxial() ? forward_quadratic_root(SheetQuadratic(equation, frame.binormal_1.dot(frame.binormal_2)))
                                              : solve_bracketed(equation, 0.0, 2.0 * n_max, guess[sheet]));  // g(2 n_max) > 0
    }
    const auto fields = mode_fields(frame, xi, q[0], q[1], kCommonNormalSplitting);
    for (std::size_t sheet = 0; sheet < 2; ++sheet) modes[sheet] = SlabMode{q[sheet], fields[sheet].first, fields[sheet].second};
    return true;
}

template <typename Real>
bool solve_sheet_modes(const BasicBinormalFrame<Real>& frame, const Eigen::Vector2d& xi, std::array<SheetMode<Real>, 4>& modes) {
    const Real n_max = Real(1) / std::sqrt(frame.c);
    std::array<Real, 4> roots{};
    for (int sheet = 0; sheet < 2; ++sheet) {
        const SheetEquation<Real> equation = sheet_equation(frame, xi, sheet);
        if (frame.uniaxial()) {
            // Closed form; then Newton in long double, as for the other roots.
            const SheetQuadratic quadratic(equation, frame.binormal_1.dot(frame.binormal_2));
            const Real discriminant = quadratic.discriminant();
            if (!(discriminant >= Real(0))) return false;  // the line misses the sheet: evanescent modes
            const auto [lower, upper] = quadratic.roots(discriminant);
            roots[static_cast<std::size_t>(2 * sheet)] = polish(equation, upper);
            roots[static_cast<std::size_t>(2 * sheet + 1)] = polish(equation, lower);
            continue;
        }
        const SheetEquation<double> rounded = equation.template as<double>();
        // A point of the line inside the sheet; g is unimodal along the line (the sheet is star-shaped about
        // the origin), so each side of any inside point holds one root. q = 0 is inside when |ξ| is below the
        // sheet's index along ξ̂, the usual case; otherwise the minimum of g on [−2n_max, 2n_max] is searched
        // for (golden-section search, Press et al., Numerical Recipes §10.2).
        Real inside = Real(0);
        if (!(equation.value(inside) < Real(0))) {
            const Real golden = Real(0.5) * (std::sqrt(Real(5)) - Real(1));
            Real low = -Real(2) * n_max, high = Real(2) * n_max;
            Real left = high - golden * (high - low), right = low + golden * (high - low);
            Real g_left = equation.value(left), g_right = equation.value(right);
            for (int iteration = 0; iteration < 100 && high - low > Real(1e-12L); ++iteration) {
                if (g_left < g_right) {
                    high = right; right = left; g_right = g_left;
                    left = high - golden * (high - low); g_left = equation.value(left);
                } else {
                    low = left; left = right; g_left = g_right;
                    right = low + golden * (high - low); g_right = equation.value(right);
                }
            }
            inside = Real(0.5) * (low + high);
            if (!(equation.value(inside) < Real(0))) return false;  // the line misses the sheet: evanescent modes
        }
        for (int end = 0; end < 2; ++end) {
            // A root between the inside point and ±2 n_max, then Newton in long double.
            const double outside = end == 0 ? static_cast<double>(Real(2) * n_max) : static_cast<double>(-Real(2) * n_max);
            roots[static_cast<std::size_t>(2 * sheet + end)] =
                polish<Real>(equation, static_cast<Real>(solve_bracketed(rounded, static_cast<double>(inside), outside, std::numeric_limits<double>::quiet_NaN())));
        }
    }
    // The upper (end 0) and lower (end 1) roots of the two sheets, paired for the vibration directions.
    for (std::size_t end = 0; end < 2; ++end) {
        const auto fields = mode_fields(frame, xi, roots[end], roots[2 + end],
                                        std::is_same_v<Real, double> ? kCommonNormalSplittingOfDoubleFrames : kCommonNormalSplitting);
        modes[end] = {roots[end], fields[0].first};
        modes[2 + end] = {roots[2 + end], fields[1].first};
    }
    return true;
}

template bool solve_sheet_modes(const BasicBinormalFrame<double>&, const Eigen::Vector2d&, std::array<SheetMode<double>, 4>&);
template bool solve_sheet_modes(const BasicBinormalFrame<long double>&, const Eigen::Vector2d&, std::array<SheetMode<long double>, 4>&);

SlabModes solve_slab_modes(const BinormalFrame& frame, const TangentialWavevector& direction,
                           const Eigen::Vector2d& forward_guess) {
    SlabModes modes;
    std::array<SlabMode, 2> reverse;
    modes.propagating = solve_forward_modes(frame, direction.xi, forward_guess, modes.forward) &&
                        solve_forward_modes(frame, -direction.xi, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()), reverse);
    for (int sheet = 0; sheet < 2; ++sheet) modes.backward[sheet] = time_reversed(reverse[sheet]);
    return modes;
}

SlabTransfer slab_transfer(const SlabModes& modes, const TangentialWavevector& direction, double n_entrance,
                           double n_exit) {
    SlabTransfer transfer;
    transfer.propagating = modes.propagating;
    if (!modes.propagating) return transfer;
    const double xi2 = direction.xi.squaredNorm();
    const double q_entrance = std::sqrt(n_entrance * n_entrance - xi2);
    const double q_exit = std::sqrt(n_exit * n_exit - xi2);
    transfer.q = {modes.forward[0].q, modes.forward[1].q};
    // Entrance face: incident + reflected = Σ tₘ ψₘ⁺; the forward projection removes the reflected
    // waves, so (incident s, p) = F·t with F = forward amplitudes of the crystal modes.
    const Eigen::Matrix2d f = isotropic_amplitudes(modes.forward[0], modes.forward[1], direction, n_entrance, q_entrance, 1.0);
    transfer.entry = f.inverse();
    // Exit face: Σ uₘψₘ⁺ + Σ rⱼψⱼ⁻ = transmitted forward waves only. Their backward projection vanishes:
    // r = −(A⁻Ψ⁻)⁻¹(A⁻Ψ⁺)u, and the transmitted amplitudes are A⁺(Ψ⁺u + Ψ⁻r).
    const Eigen::Matrix2d forward_plus = isotropic_amplitudes(modes.forward[0], modes.forward[1], direction, n_exit, q_exit, 1.0);
    const Eigen::Matrix2d forward_minus = isotropic_amplitudes(modes.forward[0], modes.forward[1], direction, n_exit, q_exit, -1.0);
    const Eigen::Matrix2d backward_plus = isotropic_amplitudes(modes.backward[0], modes.backward[1], direction, n_exit, q_exit, 1.0);
    const Eigen::Matrix2d backward_minus = isotropic_amplitudes(modes.backward[0], modes.backward[1], direction, n_exit, q_exit, -1.0);
    transfer.exit = forward_plus - backward_plus * backward_minus.inverse() * forward_minus;
    return transfer;
}

Eigen::Vector2d gyration_coupling(const std::array<SlabMode, 2>& forward, const Eigen::Vector2d& xi, const Eigen::Matrix3d& gyration) {
    const Eigen::Vector3d mean_normal(xi.x(), xi.y(), 0.5 * (forward[0].q + forward[1].q));
    const double tau = (gyration * mean_normal).dot(forward[1].e_field.cross(forward[0].e_field));
    const double flux_fast = forward[0].e_field.cross(forward[0].h_field).z();
    const double flux_slow = forward[1].e_field.cross(forward[1].h_field).z();
    return {0.5 * tau / flux_fast, 0.5 * tau / flux_slow};
}

Eigen::Matrix2cd slab_propagation(const SlabTransfer& transfer, double k0_thickness) {
    Eigen::Matrix2cd propagation = Eigen::Matrix2cd::Zero();
    const Eigen::Vector2d& c = transfer.gyration_coupling;
    if (c.isZero(0.0)) {
        propagation(0, 0) = std::polar(1.0, k0_thickness * transfer.q[0]);
        propagation(1, 1) = std::polar(1.0, k0_thickness * transfer.q[1]);
        return propagation;
    }
    const double half_splitting = 0.5 * k0_thickness * (transfer.q[0] - transfer.q[1]);
    const double omega = std::sqrt(half_splitting * half_splitting + k0_thickness * k0_thickness * c[0] * c[1]);
    const double sinc = sinc_from_sine(omega, std::sin(omega));
    const std::complex<double> i(0.0, 1.0);
    propagation << std::cos(omega) + i * sinc * half_splitting, -sinc * k0_thickness * c[0],
                   sinc * k0_thickness * c[1], std::cos(omega) - i * sinc * half_splitting;
    return std::polar(1.0, 0.5 * k0_thickness * (transfer.q[0] + transfer.q[1])) * propagation;
}

Eigen::Matrix2cd slab_jones(const SlabTransfer& transfer, double wavelength_nm, double thickness_um) {
    if (!transfer.propagating) return Eigen::Matrix2cd::Zero();
    const double k0_thickness = 2.0 * std::numbers::pi * thickness_um * 1e3 / wavelength_nm;
    return transfer.exit.cast<std::complex<double>>() * slab_propagation(transfer, k0_thickness) *
           transfer.entry.cast<std::complex<double>>();
}

}  // namespace petroscope
