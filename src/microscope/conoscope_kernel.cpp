#include "conoscope_kernel.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

// Newton steps after the fixed-point start; a sample is accepted when the last step moved q by less
// than kConvergedStep·q (with quadratic convergence the remaining error is then below ε·q).
constexpr int kNewtonSteps = 3;
constexpr double kConvergedStep = 1e-12;
// Within this angle (rad) of a binormal the sheets are nearly degenerate: Newton converges only linearly
// and the vibration directions come from near-cancelling projections, so the reference path takes over.
constexpr double kNearBinormal = 1e-6;

// The sheet equation of optics/slab.cpp, g_σ(q) = A|N|² + B((N·b₁)(N·b₂) + σ|N × b₁||N × b₂|) − 1,
// divided by its derivative: the Newton step for one sample.
inline double newton_step(double a, double b, double sigma, double xi2, double u1, double u2, double b1z, double b2z,
                          double q) {
    const double n2 = xi2 + q * q;
    const double nb1 = u1 + q * b1z;
    const double nb2 = u2 + q * b2z;
    const double p1 = std::max(n2 - nb1 * nb1, 0.0);
    const double p2 = std::max(n2 - nb2 * nb2, 0.0);
    const double root = std::sqrt(p1 * p2);
    const double dp1 = 2.0 * (q - nb1 * b1z);
    const double dp2 = 2.0 * (q - nb2 * b2z);
    const double droot = root > 0.0 ? 0.5 * (dp1 * p2 + p1 * dp2) / root : 0.0;
    const double derivative = 2.0 * a * q + b * (b1z * nb2 + b2z * nb1 + sigma * droot);
    return (a * n2 + b * (nb1 * nb2 + sigma * root) - 1.0) / derivative;
}

// g_σ(q) + 1 = |N|²/n_σ(N̂)².
inline double sheet_ratio(double a, double b, double sigma, double xi2, double u1, double u2, double b1z, double b2z,
                          double q) {
    const double n2 = xi2 + q * q;
    const double nb1 = u1 + q * b1z;
    const double nb2 = u2 + q * b2z;
    const double p1 = std::max(n2 - nb1 * nb1, 0.0);
    const double p2 = std::max(n2 - nb2 * nb2, 0.0);
    return a * n2 + b * (nb1 * nb2 + sigma * std::sqrt(p1 * p2));
}

// Forward modes on one sheet for the tangential wavevector (xi_x, xi_y) at every wavelength: q, and ψ
// in the plane-of-incidence frame (rho_x, rho_y). Marks failures (no convergence, on a binormal,
// evanescent) in `failed`.
// Template parameters rather than arguments: a loop-invariant condition inside the loop body stops GCC's
// vectoriser.
template <bool Uniaxial, int Sheet>
void solve_sheet(const SpectralCrystal& crystal, double xi_x, double xi_y, double rho_x, double rho_y,
                 double* __restrict q_out, double* __restrict psi0, double* __restrict psi1, double* __restrict psi2,
                 double* __restrict psi3, std::int64_t* __restrict failed) {
    constexpr double sigma = Sheet == 0 ? 1.0 : -1.0;
    const double xi2 = xi_x * xi_x + xi_y * xi_y;
    const double s_x = -rho_y, s_y = rho_x;  // ŝ = ẑ × ρ̂
    const double orientation = crystal.uniaxial_orientation;
    const double* half_sum = crystal.half_sum.data();
    const double* half_difference = crystal.half_difference.data();
    const double* inverse_n_beta2 = crystal.inverse_n_beta2.data();
    const double *b1x = crystal.binormal_1[0].data(), *b1y = crystal.binormal_1[1].data(), *b1z = crystal.binormal_1[2].data();
    const double *b2x = crystal.binormal_2[0].data(), *b2y = crystal.binormal_2[1].data(), *b2z = crystal.binormal_2[2].data();
    const double *eta_xx = crystal.impermeability[0].data(), *eta_yy = crystal.impermeability[1].data();
    const double *eta_zz = crystal.impermeability[2].data(), *eta_xy = crystal.impermeability[3].data();
    const double *eta_xz = crystal.impermeability[4].data(), *eta_yz = crystal.impermeability[5].data();
    const int count = static_cast<int>(crystal.padded_size());
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double a = half_sum[i], b = half_difference[i], bz1 = b1z[i], bz2 = b2z[i];
        const double u1 = xi_x * b1x[i] + xi_y * b1y[i];
        const double u2 = xi_x * b2x[i] + xi_y * b2y[i];
        // |ξ| at or beyond the sheet's index: no propagating mode (g(0) ≥ 0).
        const bool evanescent = sheet_ratio(a, b, sigma, xi2, u1, u2, bz1, bz2, 0.0) >= 1.0;
        double q = 0.0;
        double last_step = 0.0;
        if constexpr (Uniaxial) {
            // Closed form: the quadratic of optics/slab.cpp (forward_quadratic_root).
            const double level = a + sigma * b;
            const double cross = b * (orientation - sigma);
            const double alpha = level + cross * bz1 * bz1;
            const double beta = 2.0 * cross * u1 * bz1;
            const double gamma = level * xi2 + cross * u1 * u1 - 1.0;
            const double t = -0.5 * (beta + std::copysign(std::sqrt(std::max(beta * beta - 4.0 * alpha * gamma, 0.0)), beta));
            const double other_root = t != 0.0 ? gamma / t : -t / alpha;
            q = std::max(t / alpha, other_root);
        } else {
            // Start: the isotropic guess |N| = nβ, then one fixed-point step q = √(n_σ(N̂)² − |ξ|²); then
            // kNewtonSteps Newton steps (written out: the vectoriser takes no inner loops).
            static_assert(kNewtonSteps == 3);
            const double q_iso = std::sqrt(std::max(1.0 / inverse_n_beta2[i] - xi2, 1e-6));
            const double ratio = sheet_ratio(a, b, sigma, xi2, u1, u2, bz1, bz2, q_iso);
            q = std::sqrt(std::max((xi2 + q_iso * q_iso) / ratio - xi2, 1e-6));
            q -= newton_step(a, b, sigma, xi2, u1, u2, bz1, bz2, q);
            q -= newton_step(a, b, sigma, xi2, u1, u2, bz1, bz2, q);
            last_step = newton_step(a, b, sigma, xi2, u1, u2, bz1, bz2, q);
            q -= last_step;
        }
        // Vibration direction (physics notes §2) from unnormalised projections of the binormals on the
        // plane ⟂ N, vᵢ = |N|²bᵢ − (N·bᵢ)N: S = |v₂|v₁ + |v₁|v₂ ∥ p̂₁ + p̂₂ (slow) and
        // T = |v₂|v₁ − |v₁|v₂ ∥ p̂₁ − p̂₂ (fast), orthogonal whatever rounding did to the vᵢ because the
        // weights are their computed norms; the longer is used, the other mode's is N × it.
        const double nx = xi_x, ny = xi_y, nz = q;
        const double n2 = xi2 + q * q;
        const double nb1 = u1 + q * bz1;
        const double nb2 = u2 + q * bz2;
        const double v1x = n2 * b1x[i] - nb1 * nx, v1y = n2 * b1y[i] - nb1 * ny, v1z = n2 * bz1 - nb1 * nz;
        const double v2x = n2 * b2x[i] - nb2 * nx, v2y = n2 * b2y[i] - nb2 * ny, v2z = n2 * bz2 - nb2 * nz;
        const double r1 = std::sqrt(v1x * v1x + v1y * v1y + v1z * v1z);
        const double r2 = std::sqrt(v2x * v2x + v2y * v2y + v2z * v2z);
        const double sx = r2 * v1x + r1 * v2x, sy = r2 * v1y + r1 * v2y, sz = r2 * v1z + r1 * v2z;
        const double tx = r2 * v1x - r1 * v2x, ty = r2 * v1y - r1 * v2y, tz = r2 * v1z - r1 * v2z;
        const double s_norm2 = sx * sx + sy * sy + sz * sz;
        const double t_norm2 = tx * tx + ty * ty + tz * tz;
        // Own direction if it is the longer one, else N × (the other's direction).
        const bool own_longer = Sheet == 0 ? t_norm2 >= s_norm2 : s_norm2 >= t_norm2;
        const double ox = Sheet == 0 ? tx : sx, oy = Sheet == 0 ? ty : sy, oz = Sheet == 0 ? tz : sz;
        const double ax = Sheet == 0 ? sx : tx, ay = Sheet == 0 ? sy : ty, az = Sheet == 0 ? sz : tz;
        const double dx = own_longer ? ox : ny * az - nz * ay;
        const double dy = own_longer ? oy : nz * ax - nx * az;
        const double dz = own_longer ? oz : nx * ay - ny * ax;
        // E = η·D, H = N × E.
        const double ex = eta_xx[i] * dx + eta_xy[i] * dy + eta_xz[i] * dz;
        const double ey = eta_xy[i] * dx + eta_yy[i] * dy + eta_yz[i] * dz;
        const double ez = eta_xz[i] * dx + eta_yz[i] * dy + eta_zz[i] * dz;
        const double hx = ny * ez - nz * ey, hy = nz * ex - nx * ez;
        q_out[i] = q;
        psi0[i] = ex * rho_x + ey * rho_y;
        psi1[i] = hx * s_x + hy * s_y;
        psi2[i] = ex * s_x + ey * s_y;
        psi3[i] = -(hx * rho_x + hy * rho_y);
        // |vᵢ| = |N|²·sin(angle to bᵢ).
        const bool near_binormal = std::min(r1, r2) <= kNearBinormal * n2;
        const bool converged = std::abs(last_step) <= kConvergedStep * q && q > 0.0;
        failed[i] = static_cast<std::int64_t>(evanescent || !converged || near_binormal || !std::isfinite(q));
    }
}

// |c₀e^{iφ₀} + c₁e^{iφ₁}|² in the form whose terms are non-negative (see conoscope_evaluator.cpp).
inline double pair_intensity(double c0, double c1, double sin2) {
    const double product = c0 * c1;
    return product >= 0.0 ? (c0 - c1) * (c0 - c1) + 4.0 * product * (1.0 - sin2)
                          : (c0 + c1) * (c0 + c1) - 4.0 * product * sin2;
}

// Single-pass transmission for one side from its forward modes and the other side's (time-reversed:
// the backward modes), after optics/slab.cpp's slab_transfer and the conoscope's analyzed intensity.
template <bool AnalyzerIn>
void side_transmission(const SpectralCrystal& crystal, const PolarizerPair& polars, double xi2, double rho_x,
                       double rho_y, double reversal_sign, const KernelScratch& scratch, int side, double* __restrict out) {
    const int other = 1 - side;
    const double s_x = -rho_y, s_y = rho_x;
    const double p_s = polars.polarizer.x() * s_x + polars.polarizer.y() * s_y;
    const double p_p = polars.polarizer.x() * rho_x + polars.polarizer.y() * rho_y;
    const double a_s = polars.analyzer.x() * s_x + polars.analyzer.y() * s_y;
    const double a_p = polars.analyzer.x() * rho_x + polars.analyzer.y() * rho_y;
    const double *qf = scratch.q[side][0].data(), *qs = scratch.q[side][1].data();
    const auto& own = scratch.psi[side];
    const auto& opposite = scratch.psi[other];
    const double *f0 = own[0][0].data(), *f1 = own[0][1].data(), *f2 = own[0][2].data(), *f3 = own[0][3].data();
    const double *s0 = own[1][0].data(), *s1 = own[1][1].data(), *s2 = own[1][2].data(), *s3 = own[1][3].data();
    const double *bf0 = opposite[0][0].data(), *bf1 = opposite[0][1].data(), *bf2 = opposite[0][2].data(), *bf3 = opposite[0][3].data();
    const double *bs0 = opposite[1][0].data(), *bs1 = opposite[1][1].data(), *bs2 = opposite[1][2].data(), *bs3 = opposite[1][3].data();
    const double* surround = crystal.surround_n.data();
    const double* k0_thickness = crystal.k0_thickness.data();
    const double kappa = reversal_sign;  // ρ̂·ρ̂' of the two sides: −1, or +1 at ξ = 0
    const int count = static_cast<int>(crystal.padded_size());
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double n = surround[i];
        const double inverse_q = 1.0 / std::sqrt(n * n - xi2);
        const double n_over_q = n * inverse_q, inverse_n = 1.0 / n;
        // Amplitudes of the isotropic medium's forward (+) and backward (−) s and p waves in a field ψ:
        // s: (ψ₃ ± ψ₄/Q)/2, p: (ψ₁n/Q ± ψ₂/n)/2 (optics/slab.cpp).
        // Backward modes: ψ_b = (κψ'₁, −κψ'₂, κψ'₃, −κψ'₄) of the other side's forward modes.
        const double bf_0 = kappa * bf0[i], bf_1 = -kappa * bf1[i], bf_2 = kappa * bf2[i], bf_3 = -kappa * bf3[i];
        const double bs_0 = kappa * bs0[i], bs_1 = -kappa * bs1[i], bs_2 = kappa * bs2[i], bs_3 = -kappa * bs3[i];
        // F = A⁺Ψ⁺ (rows s, p; columns fast, slow); entrance and exit media are the same.
        const double f00 = 0.5 * (f2[i] + f3[i] * inverse_q), f01 = 0.5 * (s2[i] + s3[i] * inverse_q);
        const double f10 = 0.5 * (f0[i] * n_over_q + f1[i] * inverse_n), f11 = 0.5 * (s0[i] * n_over_q + s1[i] * inverse_n);
        const double fm00 = 0.5 * (f2[i] - f3[i] * inverse_q), fm01 = 0.5 * (s2[i] - s3[i] * inverse_q);
        const double fm10 = 0.5 * (f0[i] * n_over_q - f1[i] * inverse_n), fm11 = 0.5 * (s0[i] * n_over_q - s1[i] * inverse_n);
        const double bp00 = 0.5 * (bf_2 + bf_3 * inverse_q), bp01 = 0.5 * (bs_2 + bs_3 * inverse_q);
        const double bp10 = 0.5 * (bf_0 * n_over_q + bf_1 * inverse_n), bp11 = 0.5 * (bs_0 * n_over_q + bs_1 * inverse_n);
        const double bm00 = 0.5 * (bf_2 - bf_3 * inverse_q), bm01 = 0.5 * (bs_2 - bs_3 * inverse_q);
        const double bm10 = 0.5 * (bf_0 * n_over_q - bf_1 * inverse_n), bm11 = 0.5 * (bs_0 * n_over_q - bs_1 * inverse_n);
        // Entrance: t = F⁻¹ (P·ŝ, P·ρ̂).
        const double inverse_det_f = 1.0 / (f00 * f11 - f01 * f10);
        const double t0 = (f11 * p_s - f01 * p_p) * inverse_det_f;
        const double t1 = (f00 * p_p - f10 * p_s) * inverse_det_f;
        // Exit: T = F − (A⁺Ψ⁻)(A⁻Ψ⁻)⁻¹(A⁻Ψ⁺).
        const double inverse_det_bm = 1.0 / (bm00 * bm11 - bm01 * bm10);
        const double r00 = (bm11 * fm00 - bm01 * fm10) * inverse_det_bm, r01 = (bm11 * fm01 - bm01 * fm11) * inverse_det_bm;
        const double r10 = (bm00 * fm10 - bm10 * fm00) * inverse_det_bm, r11 = (bm00 * fm11 - bm10 * fm01) * inverse_det_bm;
        const double e00 = f00 - (bp00 * r00 + bp01 * r10), e01 = f01 - (bp00 * r01 + bp01 * r11);
        const double e10 = f10 - (bp10 * r00 + bp11 * r10), e11 = f11 - (bp10 * r01 + bp11 * r11);
        const double sin2 = sin_squared(0.5 * k0_thickness[i] * (qf[i] - qs[i]));
        if constexpr (AnalyzerIn) {
            out[i] = pair_intensity((a_s * e00 + a_p * e10) * t0, (a_s * e01 + a_p * e11) * t1, sin2);
        } else {
            out[i] = pair_intensity(e00 * t0, e01 * t1, sin2) + pair_intensity(e10 * t0, e11 * t1, sin2);
        }
    }
}

}  // namespace

SpectralCrystal::SpectralCrystal(const std::vector<BinormalFrame>& frames, const std::vector<double>& surround,
                                 const std::vector<double>& k0_thickness_values)
    : count(frames.size()) {
    uniaxial = !frames.empty() && frames.front().uniaxial();
    if (uniaxial) uniaxial_orientation = frames.front().binormal_1.dot(frames.front().binormal_2);
    // Fewer samples than lanes (monochromatic light) run in the scalar loop: padding would multiply the work.
    const std::size_t padded = count < kLanes ? count : (count + kLanes - 1) / kLanes * kLanes;
    for (std::size_t j = 0; j < padded; ++j) {
        const std::size_t w = std::min(j, count - 1);  // padding repeats the last wavelength
        const BinormalFrame& frame = frames[w];
        half_sum.push_back(0.5 * (frame.a + frame.c));
        half_difference.push_back(0.5 * (frame.a - frame.c));
        inverse_n_beta2.push_back(frame.b);
        for (int k = 0; k < 3; ++k) {
            binormal_1[k].push_back(frame.binormal_1[k]);
            binormal_2[k].push_back(frame.binormal_2[k]);
        }
        const Eigen::Matrix3d& eta = frame.impermeability;
        const std::array<double, 6> components{eta(0, 0), eta(1, 1), eta(2, 2), eta(0, 1), eta(0, 2), eta(1, 2)};
        for (int k = 0; k < 6; ++k) impermeability[k].push_back(components[k]);
        surround_n.push_back(surround[w]);
        k0_thickness.push_back(k0_thickness_values[w]);
    }
}

void KernelScratch::resize(std::size_t padded_wavelengths) {
    for (auto& side : q) for (auto& sheet : side) sheet.resize(padded_wavelengths);
    for (auto& side : psi) for (auto& sheet : side) for (auto& component : sheet) component.resize(padded_wavelengths);
    for (auto& side : sheet_failed) for (auto& sheet : side) sheet.resize(padded_wavelengths);
    for (auto& side : transmission) side.resize(padded_wavelengths);
    failed.resize(padded_wavelengths);
}

bool transmission_pair_kernel(const SpectralCrystal& crystal, const PolarizerPair& polars, const Eigen::Vector2d& xi,
                              KernelScratch& scratch, double* out_plus, double* out_minus) {
    const double length = xi.norm();
    const Eigen::Vector2d radial = length > 0.0 ? Eigen::Vector2d(xi / length) : Eigen::Vector2d::UnitX();
    // ρ̂ of −ξ is −ρ̂, except at ξ = 0 where both sides use x̂.
    const std::array<Eigen::Vector2d, 2> radials{radial, length > 0.0 ? Eigen::Vector2d(-radial) : radial};
    const std::array<Eigen::Vector2d, 2> xis{xi, -xi};
    using SheetSolver = void (*)(const SpectralCrystal&, double, double, double, double, double*, double*, double*, double*,
                                 double*, std::int64_t*);
    const std::array<SheetSolver, 2> solvers = crystal.uniaxial ? std::array<SheetSolver, 2>{solve_sheet<true, 0>, solve_sheet<true, 1>}
                                                                : std::array<SheetSolver, 2>{solve_sheet<false, 0>, solve_sheet<false, 1>};
    for (int side = 0; side < 2; ++side) {
        for (int sheet = 0; sheet < 2; ++sheet) {
            auto& psi = scratch.psi[side][sheet];
            solvers[sheet](crystal, xis[side].x(), xis[side].y(), radials[side].x(), radials[side].y(), scratch.q[side][sheet].data(),
                           psi[0].data(), psi[1].data(), psi[2].data(), psi[3].data(), scratch.sheet_failed[side][sheet].data());
        }
    }
    const double reversal_sign = length > 0.0 ? -1.0 : 1.0;
    const auto transmit = polars.analyzer_in ? side_transmission<true> : side_transmission<false>;
    transmit(crystal, polars, length * length, radials[0].x(), radials[0].y(), reversal_sign, scratch, 0, scratch.transmission[0].data());
    transmit(crystal, polars, length * length, radials[1].x(), radials[1].y(), reversal_sign, scratch, 1, scratch.transmission[1].data());
    // A sample needs all four modes (each side's backward modes are the other side's forward ones).
    bool any_failed = false;
    for (std::size_t i = 0; i < crystal.size(); ++i) {
        const auto& f = scratch.sheet_failed;
        out_plus[i] = scratch.transmission[0][i];
        out_minus[i] = scratch.transmission[1][i];
        const bool finite = std::isfinite(out_plus[i]) && std::isfinite(out_minus[i]);
        scratch.failed[i] = static_cast<std::int64_t>(f[0][0][i] | f[0][1][i] | f[1][0][i] | f[1][1][i] | !finite);
        any_failed = any_failed || scratch.failed[i] != 0;
    }
    return any_failed;
}

}  // namespace petroscope::detail
