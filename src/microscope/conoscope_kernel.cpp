#include "conoscope_kernel.hpp"

#include "interference.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

// A sample is accepted when the last Newton step moved q by less than kConvergedStep·q: with quadratic
// convergence the remaining error is about C·(kConvergedStep·q)², C = |g''/2g'| of order 1 away from the
// binormals (and below 1e6 outside kNearBinormal of them), so below ε·q.
constexpr double kConvergedStep = 1e-9;
// Within this angle (rad) of a binormal the sheets are nearly degenerate: Newton converges only linearly
// and the vibration directions come from near-cancelling projections, so the reference path takes over.
constexpr double kNearBinormal = 1e-6;

// The sheet equation of optics/slab.cpp, g_σ(q) = A|N|² + B((N·b₁)(N·b₂) + σ|N × b₁||N × b₂|) − 1 with
// N = (ξ, q), and its partial derivatives, for one sample.
struct SheetValue {
    double g, dg_dq, dg_dxi_x, dg_dxi_y;
};

// Always inlined: a call inside the sample loops would stop their vectorisation.
[[gnu::always_inline]] inline SheetValue sheet_value(double a, double b, double sigma, double xi_x, double xi_y, double b1x, double b1y, double b1z,
                              double b2x, double b2y, double b2z, double q) {
    const double n2 = xi_x * xi_x + xi_y * xi_y + q * q;
    const double nb1 = xi_x * b1x + xi_y * b1y + q * b1z;
    const double nb2 = xi_x * b2x + xi_y * b2y + q * b2z;
    const double p1 = std::max(n2 - nb1 * nb1, 0.0);
    const double p2 = std::max(n2 - nb2 * nb2, 0.0);
    const double root = std::sqrt(p1 * p2);
    const double half_inverse_root = root > 0.0 ? 0.5 / root : 0.0;
    // ∂/∂v of |N × b₁||N × b₂| for v = q, ξ_x, ξ_y, with ∂pᵢ/∂v = 2(N_v − (N·bᵢ)b_{i,v}).
    const auto droot = [&](double n_v, double b1v, double b2v) {
        return half_inverse_root * (2.0 * (n_v - nb1 * b1v) * p2 + p1 * 2.0 * (n_v - nb2 * b2v));
    };
    return {a * n2 + b * (nb1 * nb2 + sigma * root) - 1.0,
            2.0 * a * q + b * (b1z * nb2 + b2z * nb1 + sigma * droot(q, b1z, b2z)),
            2.0 * a * xi_x + b * (b1x * nb2 + b2x * nb1 + sigma * droot(xi_x, b1x, b2x)),
            2.0 * a * xi_y + b * (b1y * nb2 + b2y * nb1 + sigma * droot(xi_y, b1y, b2y))};
}

// Pointers to one sample array set, so that the loops see plain restrict-free arrays of doubles.
struct CrystalArrays {
    const double *a, *b, *inverse_n_beta2, *b1x, *b1y, *b1z, *b2x, *b2y, *b2z;
    const double *eta_xx, *eta_yy, *eta_zz, *eta_xy, *eta_xz, *eta_yz;
    explicit CrystalArrays(const SampleCrystal& c)
        : a(c.half_sum.data()), b(c.half_difference.data()), inverse_n_beta2(c.inverse_n_beta2.data()),
          b1x(c.binormal_1[0].data()), b1y(c.binormal_1[1].data()), b1z(c.binormal_1[2].data()),
          b2x(c.binormal_2[0].data()), b2y(c.binormal_2[1].data()), b2z(c.binormal_2[2].data()),
          eta_xx(c.impermeability[0].data()), eta_yy(c.impermeability[1].data()), eta_zz(c.impermeability[2].data()),
          eta_xy(c.impermeability[3].data()), eta_xz(c.impermeability[4].data()), eta_yz(c.impermeability[5].data()) {}
};

// Newton starts for one side and sheet of a biaxial crystal. Cold: the isotropic guess |N| = nβ, one
// fixed-point step q = √(n_σ(N̂)² − |ξ|²) and one Newton step. Warm: the previous roots moved along ∂q/∂ξ.
// Side is a template parameter, as are the sheet and the mode elsewhere: a loop-invariant condition
// inside the loop body stops GCC's vectoriser.
template <int Sheet, int Side>
void newton_starts(const SampleCrystal& crystal, KernelScratch& scratch, bool warm) {
    constexpr double sigma = Sheet == 0 ? 1.0 : -1.0;
    constexpr double direction = Side == 0 ? 1.0 : -1.0;
    const CrystalArrays c(crystal);
    const double *xi_x0 = scratch.xi_x.data(), *xi_y0 = scratch.xi_y.data();
    double* start = scratch.q_start[Side][Sheet].data();
    const int count = static_cast<int>(crystal.padded_size());
    if (warm) {
        const double *q = scratch.q[Side][Sheet].data(), *dq_x = scratch.dq_dxi_x[Side][Sheet].data();
        const double *dq_y = scratch.dq_dxi_y[Side][Sheet].data();
        const double *previous_x = scratch.previous_xi_x[Side].data(), *previous_y = scratch.previous_xi_y[Side].data();
#pragma omp simd
        for (int i = 0; i < count; ++i) {
            start[i] = q[i] + dq_x[i] * (direction * xi_x0[i] - previous_x[i]) + dq_y[i] * (direction * xi_y0[i] - previous_y[i]);
        }
        return;
    }
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double xi_x = direction * xi_x0[i], xi_y = direction * xi_y0[i];
        const double xi2 = xi_x * xi_x + xi_y * xi_y;
        const double q_iso = std::sqrt(std::max(1.0 / c.inverse_n_beta2[i] - xi2, 1e-6));
        const SheetValue iso = sheet_value(c.a[i], c.b[i], sigma, xi_x, xi_y, c.b1x[i], c.b1y[i], c.b1z[i], c.b2x[i],
                                           c.b2y[i], c.b2z[i], q_iso);
        // g + 1 = |N|²/n_σ(N̂)².
        double q = std::sqrt(std::max((xi2 + q_iso * q_iso) / (iso.g + 1.0) - xi2, 1e-6));
        const SheetValue first = sheet_value(c.a[i], c.b[i], sigma, xi_x, xi_y, c.b1x[i], c.b1y[i], c.b1z[i], c.b2x[i],
                                             c.b2y[i], c.b2z[i], q);
        start[i] = q - first.g / first.dg_dq;
    }
}

// The forward root q of one side and sheet at every sample (the closed form for a uniaxial crystal, two
// Newton steps from the start for a biaxial one) and ∂q/∂ξ; sheet_failed marks roots that did not
// converge. Roots and vibrations are separate loops: fused into one, bench_conoscope's WhiteLight/512
// figures took 199 ms (biaxial) and 121 ms (uniaxial) instead of 168 and 93 ms.
template <bool Uniaxial, int Sheet, int Side>
void solve_roots(const SampleCrystal& crystal, KernelScratch& scratch) {
    constexpr double sigma = Sheet == 0 ? 1.0 : -1.0;
    constexpr double direction = Side == 0 ? 1.0 : -1.0;
    const CrystalArrays c(crystal);
    const double orientation = crystal.uniaxial_orientation;
    const double *xi_x0 = scratch.xi_x.data(), *xi_y0 = scratch.xi_y.data();
    const double* start = scratch.q_start[Side][Sheet].data();
    double *q_out = scratch.q[Side][Sheet].data(), *dq_x = scratch.dq_dxi_x[Side][Sheet].data();
    double* dq_y = scratch.dq_dxi_y[Side][Sheet].data();
    std::int64_t* unconverged = scratch.sheet_failed[Side][Sheet].data();
    const int count = static_cast<int>(crystal.padded_size());
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double xi_x = direction * xi_x0[i], xi_y = direction * xi_y0[i];
        double q = 0.0;
        bool converged = false;
        if constexpr (Uniaxial) {
            // Closed form: the quadratic of optics/slab.cpp (forward_quadratic_root).
            const double xi2 = xi_x * xi_x + xi_y * xi_y;
            const double u1 = xi_x * c.b1x[i] + xi_y * c.b1y[i];
            const double level = c.a[i] + sigma * c.b[i];
            const double cross = c.b[i] * (orientation - sigma);
            const double alpha = level + cross * c.b1z[i] * c.b1z[i];
            const double beta = 2.0 * cross * u1 * c.b1z[i];
            const double gamma = level * xi2 + cross * u1 * u1 - 1.0;
            const double t = -0.5 * (beta + std::copysign(std::sqrt(std::max(beta * beta - 4.0 * alpha * gamma, 0.0)), beta));
            const double other_root = t != 0.0 ? gamma / t : -t / alpha;
            q = std::max(t / alpha, other_root);
            // No real root (g(0) ≥ 0): evanescent; the reference path reports it.
            converged = gamma < 0.0;
        } else {
            q = start[i];
            const SheetValue first = sheet_value(c.a[i], c.b[i], sigma, xi_x, xi_y, c.b1x[i], c.b1y[i], c.b1z[i], c.b2x[i],
                                                 c.b2y[i], c.b2z[i], q);
            q -= first.g / first.dg_dq;
            const SheetValue second = sheet_value(c.a[i], c.b[i], sigma, xi_x, xi_y, c.b1x[i], c.b1y[i], c.b1z[i], c.b2x[i],
                                                  c.b2y[i], c.b2z[i], q);
            const double last_step = second.g / second.dg_dq;
            q -= last_step;
            // Implicit function theorem at the root: ∂q/∂ξ = −(∂g/∂ξ)/(∂g/∂q), ξ of this side.
            dq_x[i] = -second.dg_dxi_x / second.dg_dq;
            dq_y[i] = -second.dg_dxi_y / second.dg_dq;
            converged = std::abs(last_step) <= kConvergedStep * q;
        }
        q_out[i] = q;
        unconverged[i] = static_cast<std::int64_t>(!(converged && q > 0.0));
    }
}

// The vibration and field vectors ψ of one side and sheet from its roots, in the side's plane-of-incidence
// frame; sheet_failed also marks samples near a binormal or with a non-finite root.
template <bool Uniaxial, int Sheet, int Side>
void solve_vibrations(const SampleCrystal& crystal, KernelScratch& scratch) {
    constexpr double direction = Side == 0 ? 1.0 : -1.0;
    const CrystalArrays c(crystal);
    // A uniaxial crystal's binormals are its optic axis, b₂ = σb₁ (σ = crystal.uniaxial_orientation), so v₂ = σv₁ and
    // of S and T below one is 2|v₁|·v₁ and the other vanishes: this sheet's D is v₁ where its own combination is the
    // surviving one (T for the fast sheet when σ < 0, S for the slow one when σ > 0), N × v₁ otherwise. The scale of
    // D is free (the fields leaving the slab do not depend on it).
    const bool uniaxial_own = (Sheet == 0) == (crystal.uniaxial_orientation < 0.0);
    const double *xi_x0 = scratch.xi_x.data(), *xi_y0 = scratch.xi_y.data();
    const double *rho_x0 = scratch.rho_x.data(), *rho_y0 = scratch.rho_y.data(), *reversal = scratch.reversal.data();
    const double* q_in = scratch.q[Side][Sheet].data();
    auto& psi = scratch.psi[Side][Sheet];
    double *psi0 = psi[0].data(), *psi1 = psi[1].data(), *psi2 = psi[2].data(), *psi3 = psi[3].data();
    double* e_z = scratch.e_z[Side][Sheet].data();
    std::int64_t* failed = scratch.sheet_failed[Side][Sheet].data();
    const int count = static_cast<int>(crystal.padded_size());
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double xi_x = direction * xi_x0[i], xi_y = direction * xi_y0[i];
        const double rho_sign = Side == 0 ? 1.0 : reversal[i];
        const double rho_x = rho_sign * rho_x0[i], rho_y = rho_sign * rho_y0[i];
        const double s_x = -rho_y, s_y = rho_x;  // ŝ = ẑ × ρ̂
        const double xi2 = xi_x * xi_x + xi_y * xi_y;
        const double q = q_in[i];
        // Vibration direction (docs/theory.md §1, "Eigenmodes") from unnormalised projections of the binormals on the
        // plane ⟂ N, vᵢ = |N|²bᵢ − (N·bᵢ)N: S = |v₂|v₁ + |v₁|v₂ ∥ p̂₁ + p̂₂ (slow) and
        // T = |v₂|v₁ − |v₁|v₂ ∥ p̂₁ − p̂₂ (fast), orthogonal whatever rounding did to the vᵢ because the
        // weights are their computed norms; the longer is used, the other mode's is N × it.
        const double nx = xi_x, ny = xi_y, nz = q;
        const double n2 = xi2 + q * q;
        const double nb1 = xi_x * c.b1x[i] + xi_y * c.b1y[i] + q * c.b1z[i];
        const double v1x = n2 * c.b1x[i] - nb1 * nx, v1y = n2 * c.b1y[i] - nb1 * ny, v1z = n2 * c.b1z[i] - nb1 * nz;
        const double r1 = std::sqrt(v1x * v1x + v1y * v1y + v1z * v1z);
        double r2 = r1, dx, dy, dz;
        if constexpr (Uniaxial) {
            dx = uniaxial_own ? v1x : ny * v1z - nz * v1y;
            dy = uniaxial_own ? v1y : nz * v1x - nx * v1z;
            dz = uniaxial_own ? v1z : nx * v1y - ny * v1x;
        } else {
            const double nb2 = xi_x * c.b2x[i] + xi_y * c.b2y[i] + q * c.b2z[i];
            const double v2x = n2 * c.b2x[i] - nb2 * nx, v2y = n2 * c.b2y[i] - nb2 * ny, v2z = n2 * c.b2z[i] - nb2 * nz;
            r2 = std::sqrt(v2x * v2x + v2y * v2y + v2z * v2z);
            const double sx = r2 * v1x + r1 * v2x, sy = r2 * v1y + r1 * v2y, sz = r2 * v1z + r1 * v2z;
            const double tx = r2 * v1x - r1 * v2x, ty = r2 * v1y - r1 * v2y, tz = r2 * v1z - r1 * v2z;
            const double s_norm2 = sx * sx + sy * sy + sz * sz;
            const double t_norm2 = tx * tx + ty * ty + tz * tz;
            const bool own_longer = Sheet == 0 ? t_norm2 >= s_norm2 : s_norm2 >= t_norm2;
            const double ox = Sheet == 0 ? tx : sx, oy = Sheet == 0 ? ty : sy, oz = Sheet == 0 ? tz : sz;
            const double ax = Sheet == 0 ? sx : tx, ay = Sheet == 0 ? sy : ty, az = Sheet == 0 ? sz : tz;
            dx = own_longer ? ox : ny * az - nz * ay;
            dy = own_longer ? oy : nz * ax - nx * az;
            dz = own_longer ? oz : nx * ay - ny * ax;
        }
        // E = η·D, H = N × E.
        const double ex = c.eta_xx[i] * dx + c.eta_xy[i] * dy + c.eta_xz[i] * dz;
        const double ey = c.eta_xy[i] * dx + c.eta_yy[i] * dy + c.eta_yz[i] * dz;
        const double ez = c.eta_xz[i] * dx + c.eta_yz[i] * dy + c.eta_zz[i] * dz;
        const double hx = ny * ez - nz * ey, hy = nz * ex - nx * ez;
        psi0[i] = ex * rho_x + ey * rho_y;
        psi1[i] = hx * s_x + hy * s_y;
        psi2[i] = ex * s_x + ey * s_y;
        psi3[i] = -(hx * rho_x + hy * rho_y);
        e_z[i] = ez;
        // |vᵢ| = |N|²·sin(angle to bᵢ).
        const bool near_binormal = std::min(r1, r2) <= kNearBinormal * n2;
        failed[i] |= static_cast<std::int64_t>(near_binormal || !std::isfinite(q));
    }
}

// Optical activity (optics/slab.hpp, gyration_coupling and slab_propagation): the fast and slow amplitudes
// t = (t₀, t₁) cross the slab as exp(i·k₀d·Q)·t = e^{iφ̄}·(R + i·I) with the real vectors
// R = (c·t₀ − s·b₀·t₁, s·b₁·t₀ + c·t₁) and I = s·a·(t₀, −t₁), where a = k₀d(q_fast − q_slow)/2, bₘ = k₀d·cₘ,
// Ω = √(a² + b₀b₁), c = cos Ω and s = sin Ω/Ω. The phase e^{iφ̄} cancels in every intensity.
struct ActiveAmplitudes {
    double r0, r1, i0, i1;
};
[[gnu::always_inline]] inline ActiveAmplitudes active_amplitudes(double t0, double t1, double a, double b0, double b1) {
    const double omega = std::sqrt(a * a + b0 * b1);
    const SineCosine sc = sine_cosine(omega);
    const double s = sinc_from_sine(omega, sc.sine);
    return {sc.cosine * t0 - s * b0 * t1, s * b1 * t0 + sc.cosine * t1, s * a * t0, -s * a * t1};
}

// τ = (g·N̄)·(E_slow × E_fast) of optics/slab.hpp's gyration_coupling for one sample, with g = (g_xx, g_yy, g_zz,
// g_xy, g_xz, g_yz), N̄ = (ξ_x, ξ_y, q̄) and the lab-frame fields E_fast = (f_x, f_y, f_z), E_slow = (s_x, s_y, s_z).
// Scalars only: a struct or array argument here stops GCC 12 from vectorising the sample loop.
[[gnu::always_inline]] inline double coupling_tau(double g_xx, double g_yy, double g_zz, double g_xy, double g_xz, double g_yz, double xi_x,
                                                  double xi_y, double q_mean, double f_x, double f_y, double f_z, double s_x, double s_y,
                                                  double s_z) {
    const double gx = g_xx * xi_x + g_xy * xi_y + g_xz * q_mean;
    const double gy = g_xy * xi_x + g_yy * xi_y + g_yz * q_mean;
    const double gz = g_xz * xi_x + g_yz * xi_y + g_zz * q_mean;
    return gx * (s_y * f_z - s_z * f_y) + gy * (s_z * f_x - s_x * f_z) + gz * (s_x * f_y - s_y * f_x);
}

// Single-pass transmission for one side from its forward modes and the other side's (time-reversed:
// the backward modes), after optics/slab.cpp's slab_transfer and the conoscope's analyzed intensity.
// With a plate, the effective analyzers of SampleCrystal::plate_analyzer take the analyzer's place; an optically
// active crystal (Active) couples the modes across the slab (active_amplitudes).
template <bool AnalyzerIn, KernelOutput Output, bool Plate, bool Active, int Side>
void side_transmission(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch) {
    static_assert(!(Plate && Output != KernelOutput::transmission), "terms and fields are defined without a plate only");
    constexpr bool Terms = Output == KernelOutput::terms;
    constexpr int other = 1 - Side;
    const double *rho_x0 = scratch.rho_x.data(), *rho_y0 = scratch.rho_y.data(), *reversal = scratch.reversal.data();
    const double *xi_x0 = scratch.xi_x.data(), *xi_y0 = scratch.xi_y.data();
    const double *qf = scratch.q[Side][0].data(), *qs = scratch.q[Side][1].data();
    const auto& own = scratch.psi[Side];
    const auto& opposite = scratch.psi[other];
    const double *f0 = own[0][0].data(), *f1 = own[0][1].data(), *f2 = own[0][2].data(), *f3 = own[0][3].data();
    const double *s0 = own[1][0].data(), *s1 = own[1][1].data(), *s2 = own[1][2].data(), *s3 = own[1][3].data();
    const double *bf0 = opposite[0][0].data(), *bf1 = opposite[0][1].data(), *bf2 = opposite[0][2].data(), *bf3 = opposite[0][3].data();
    const double *bs0 = opposite[1][0].data(), *bs1 = opposite[1][1].data(), *bs2 = opposite[1][2].data(), *bs3 = opposite[1][3].data();
    const double* surround = crystal.surround_n.data();
    const double* k0_thickness = crystal.k0_thickness.data();
    const double *ez_fast = scratch.e_z[Side][0].data(), *ez_slow = scratch.e_z[Side][1].data();
    const auto& gyration = crystal.gyration;
    const double *g_xx = gyration[0].data(), *g_yy = gyration[1].data(), *g_zz = gyration[2].data();
    const double *g_xy = gyration[3].data(), *g_xz = gyration[4].data(), *g_yz = gyration[5].data();
    double* out = scratch.transmission[Side].data();
    double *mean = scratch.mean[Side].data(), *modulation = scratch.modulation[Side].data();
    double* sine_modulation = scratch.sine_modulation[Side].data();
    auto& field = scratch.mode_field[Side];
    double *field_s0 = field[0].data(), *field_s1 = field[1].data(), *field_p0 = field[2].data(), *field_p1 = field[3].data();
    double* phase = scratch.phase_difference[Side].data();
    auto& coupled = scratch.coupled_field[Side];
    double *coupled_s0 = coupled[0].data(), *coupled_s1 = coupled[1].data(), *coupled_p0 = coupled[2].data(), *coupled_p1 = coupled[3].data();
    double* coupling_product = scratch.coupling_product[Side].data();
    const double pol_x = polars.polarizer.x(), pol_y = polars.polarizer.y();
    const double ana_x = polars.analyzer.x(), ana_y = polars.analyzer.y();
    const auto& plate = crystal.plate_analyzer;
    const double *b0_re_x = plate[0][0].data(), *b0_re_y = plate[0][1].data(), *b0_im_x = plate[0][2].data(), *b0_im_y = plate[0][3].data();
    const double *b1_re_x = plate[1][0].data(), *b1_re_y = plate[1][1].data(), *b1_im_x = plate[1][2].data(), *b1_im_y = plate[1][3].data();
    const int count = static_cast<int>(crystal.padded_size());
#pragma omp simd
    for (int i = 0; i < count; ++i) {
        const double rho_sign = Side == 0 ? 1.0 : reversal[i];
        const double rho_x = rho_sign * rho_x0[i], rho_y = rho_sign * rho_y0[i];
        const double s_x = -rho_y, s_y = rho_x;
        const double xi2 = xi_x0[i] * xi_x0[i] + xi_y0[i] * xi_y0[i];
        // The aplanatic condenser and objective keep each ray's s and p amplitudes (conoscope_evaluator.cpp).
        const double p_s = pol_x * s_x + pol_y * s_y, p_p = pol_x * rho_x + pol_y * rho_y;
        const double a_s = ana_x * s_x + ana_y * s_y, a_p = ana_x * rho_x + ana_y * rho_y;
        const double n = surround[i];
        const double inverse_q = 1.0 / std::sqrt(n * n - xi2);
        const double n_over_q = n * inverse_q, inverse_n = 1.0 / n;
        // Amplitudes of the isotropic medium's forward (+) and backward (−) s and p waves in a field ψ:
        // s: (ψ₃ ± ψ₄/Q)/2, p: (ψ₁n/Q ± ψ₂/n)/2 (optics/slab.cpp).
        // Backward modes: ψ_b = (κψ'₁, −κψ'₂, κψ'₃, −κψ'₄) of the other side's forward modes, κ = ρ̂·ρ̂'.
        const double kappa = reversal[i];
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
        if constexpr (Active) {
            constexpr double direction = Side == 0 ? 1.0 : -1.0;
            // The coupling cₘ = τ/(2fₘ), fₘ = (Eₘ × Hₘ)_z = ψ₁ψ₂ + ψ₃ψ₄, E rebuilt from ψ (E·ρ̂, E·ŝ) and E·ẑ.
            const double tau = coupling_tau(g_xx[i], g_yy[i], g_zz[i], g_xy[i], g_xz[i], g_yz[i], direction * xi_x0[i], direction * xi_y0[i],
                                            0.5 * (qf[i] + qs[i]), f0[i] * rho_x + f2[i] * s_x, f0[i] * rho_y + f2[i] * s_y, ez_fast[i],
                                            s0[i] * rho_x + s2[i] * s_x, s0[i] * rho_y + s2[i] * s_y, ez_slow[i]);
            const double c0 = 0.5 * tau / (f0[i] * f1[i] + f2[i] * f3[i]), c1 = 0.5 * tau / (s0[i] * s1[i] + s2[i] * s3[i]);
            const double k0d = k0_thickness[i];
            if constexpr (Terms) {
                const double half_split = 0.5 * (qf[i] - qs[i]);
                const double w = std::sqrt(half_split * half_split + c0 * c1);
                const double inverse_w = w > 0.0 ? 1.0 / w : 0.0;
                // The analyzed components: behind the analyzer one, U_m = a·(mode m's exit column); without it ŝ and ρ̂.
                const ActiveTerms first = AnalyzerIn ? active_terms(a_s * e00 + a_p * e10, a_s * e01 + a_p * e11, t0, t1, c0, c1, half_split, inverse_w)
                                                     : active_terms(e00, e01, t0, t1, c0, c1, half_split, inverse_w);
                const ActiveTerms second = AnalyzerIn ? ActiveTerms{} : active_terms(e10, e11, t0, t1, c0, c1, half_split, inverse_w);
                mean[i] = first.mean + second.mean;
                modulation[i] = first.modulation + second.modulation;
                sine_modulation[i] = first.sine_modulation + second.sine_modulation;
                phase[i] = 2.0 * w;
            }
            if constexpr (Output == KernelOutput::fields) {
                field_s0[i] = e00 * t0;
                field_s1[i] = e01 * t1;
                field_p0[i] = e10 * t0;
                field_p1[i] = e11 * t1;
                phase[i] = k0d * (qf[i] - qs[i]);
                coupled_s0[i] = k0d * c0 * e00 * t1;
                coupled_s1[i] = k0d * c1 * e01 * t0;
                coupled_p0[i] = k0d * c0 * e10 * t1;
                coupled_p1[i] = k0d * c1 * e11 * t0;
                coupling_product[i] = k0d * c0 * k0d * c1;
                // As without activity, the transmission's slot only tells whether they are finite.
                out[i] = field_s0[i] + field_s1[i] + field_p0[i] + field_p1[i] + phase[i] + coupled_s0[i] + coupled_s1[i] + coupled_p0[i] +
                         coupled_p1[i] + coupling_product[i];
                continue;
            }
            const ActiveAmplitudes m = active_amplitudes(t0, t1, 0.5 * k0d * (qf[i] - qs[i]), k0d * c0, k0d * c1);
            // The field leaving the slab, R + i·I in (ŝ, ρ̂).
            const double rs = e00 * m.r0 + e01 * m.r1, rp = e10 * m.r0 + e11 * m.r1;
            const double is = e00 * m.i0 + e01 * m.i1, ip = e10 * m.i0 + e11 * m.i1;
            if constexpr (Plate) {
                // |b·(R + iI)|² = (b_re·R − b_im·I)² + (b_re·I + b_im·R)², b in (ŝ, ρ̂).
                const auto analyzed = [&](double re_x, double re_y, double im_x, double im_y) {
                    const double re_s = re_x * s_x + re_y * s_y, re_p = re_x * rho_x + re_y * rho_y;
                    const double im_s = im_x * s_x + im_y * s_y, im_p = im_x * rho_x + im_y * rho_y;
                    const double real = re_s * rs + re_p * rp - im_s * is - im_p * ip;
                    const double imaginary = re_s * is + re_p * ip + im_s * rs + im_p * rp;
                    return real * real + imaginary * imaginary;
                };
                out[i] = analyzed(b0_re_x[i], b0_re_y[i], b0_im_x[i], b0_im_y[i]);
                if constexpr (!AnalyzerIn) out[i] += analyzed(b1_re_x[i], b1_re_y[i], b1_im_x[i], b1_im_y[i]);
            } else if constexpr (AnalyzerIn) {
                const double real = a_s * rs + a_p * rp, imaginary = a_s * is + a_p * ip;
                out[i] = real * real + imaginary * imaginary;
            } else {
                out[i] = rs * rs + rp * rp + is * is + ip * ip;
            }
        } else if constexpr (Output == KernelOutput::fields) {
            // The field each mode leaves with, in (ŝ, ρ̂), and δ; the transmission's slot only tells whether they are finite.
            field_s0[i] = e00 * t0;
            field_s1[i] = e01 * t1;
            field_p0[i] = e10 * t0;
            field_p1[i] = e11 * t1;
            phase[i] = k0_thickness[i] * (qf[i] - qs[i]);
            out[i] = field_s0[i] + field_s1[i] + field_p0[i] + field_p1[i] + phase[i];
        } else {
            const double sin2 = sin_squared(0.5 * k0_thickness[i] * (qf[i] - qs[i]));
            // The field each mode leaves with, in (ŝ, ρ̂).
            const double s_fast = e00 * t0, s_slow = e01 * t1, p_fast = e10 * t0, p_slow = e11 * t1;
            if constexpr (Plate) {
                const double cos_delta = 1.0 - 2.0 * sin2, sin_delta = sine(k0_thickness[i] * (qf[i] - qs[i]));
                const auto analyzed = [&](double re_x, double re_y, double im_x, double im_y) {
                    return complex_analyzer_intensity(re_x * s_x + re_y * s_y, re_x * rho_x + re_y * rho_y, im_x * s_x + im_y * s_y,
                                                      im_x * rho_x + im_y * rho_y, s_fast, p_fast, s_slow, p_slow, cos_delta, sin_delta);
                };
                out[i] = analyzed(b0_re_x[i], b0_re_y[i], b0_im_x[i], b0_im_y[i]);
                if constexpr (!AnalyzerIn) out[i] += analyzed(b1_re_x[i], b1_re_y[i], b1_im_x[i], b1_im_y[i]);
            } else if constexpr (AnalyzerIn) {
                const double u0 = a_s * s_fast + a_p * p_fast, u1 = a_s * s_slow + a_p * p_slow;
                out[i] = pair_intensity(u0, u1, sin2);
                if constexpr (Terms) {
                    mean[i] = u0 * u0 + u1 * u1;
                    modulation[i] = 2.0 * u0 * u1;
                }
            } else {
                out[i] = pair_intensity(s_fast, s_slow, sin2) + pair_intensity(p_fast, p_slow, sin2);
                if constexpr (Terms) {
                    mean[i] = s_fast * s_fast + s_slow * s_slow + p_fast * p_fast + p_slow * p_slow;
                    modulation[i] = 2.0 * (s_fast * s_slow + p_fast * p_slow);
                }
            }
        }
    }
}

template <bool Uniaxial, int Side>
void solve_side(const SampleCrystal& crystal, KernelScratch& scratch, bool warm) {
    if constexpr (!Uniaxial) {
        newton_starts<0, Side>(crystal, scratch, warm);
        newton_starts<1, Side>(crystal, scratch, warm);
    }
    solve_roots<Uniaxial, 0, Side>(crystal, scratch);
    solve_roots<Uniaxial, 1, Side>(crystal, scratch);
    solve_vibrations<Uniaxial, 0, Side>(crystal, scratch);
    solve_vibrations<Uniaxial, 1, Side>(crystal, scratch);
}

template <KernelOutput Output, bool Plate, bool Active = false>
void transmission_of_both_sides(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch) {
    if (polars.analyzer_in) {
        side_transmission<true, Output, Plate, Active, 0>(crystal, polars, scratch);
        side_transmission<true, Output, Plate, Active, 1>(crystal, polars, scratch);
    } else {
        side_transmission<false, Output, Plate, Active, 0>(crystal, polars, scratch);
        side_transmission<false, Output, Plate, Active, 1>(crystal, polars, scratch);
    }
}

}  // namespace

std::size_t padded_length(std::size_t samples) {
    // Fewer samples than lanes run in the scalar loop: padding would multiply the work.
    return samples < kLanes ? samples : (samples + kLanes - 1) / kLanes * kLanes;
}

SampleCrystal::SampleCrystal(const std::vector<const BinormalFrame*>& frames, const std::vector<double>& surround,
                             const std::vector<double>& k0_thickness_values)
    : count(frames.size()) {
    uniaxial = !frames.empty() && frames.front()->uniaxial();
    if (uniaxial) uniaxial_orientation = frames.front()->binormal_1.dot(frames.front()->binormal_2);
    for (std::size_t j = 0; j < padded_length(count); ++j) {
        const std::size_t w = std::min(j, count - 1);  // padding repeats the last sample
        const BinormalFrame& frame = *frames[w];
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

void set_plate(SampleCrystal& crystal, const std::vector<Eigen::Matrix2cd>& jones, const PolarizerPair& polars) {
    crystal.with_plate = true;
    for (int k = 0; k < 2; ++k) {
        for (auto& component : crystal.plate_analyzer[static_cast<std::size_t>(k)]) component.clear();
    }
    for (std::size_t j = 0; j < crystal.padded_size(); ++j) {
        const Eigen::Matrix2cd& plate = jones[std::min(j, jones.size() - 1)];
        // b = Jᵀa with the analyzer; without it the rows of J (the second used only then).
        const std::array<Eigen::Vector2cd, 2> analyzers =
            polars.analyzer_in ? std::array<Eigen::Vector2cd, 2>{plate.transpose() * polars.analyzer.cast<std::complex<double>>(), Eigen::Vector2cd::Zero()}
                               : std::array<Eigen::Vector2cd, 2>{plate.row(0).transpose(), plate.row(1).transpose()};
        for (std::size_t k = 0; k < 2; ++k) {
            const Eigen::Vector2cd& b = analyzers[k];
            const std::array<double, 4> parts{b.x().real(), b.y().real(), b.x().imag(), b.y().imag()};
            for (std::size_t c = 0; c < 4; ++c) crystal.plate_analyzer[k][c].push_back(parts[c]);
        }
    }
}

void set_gyration(SampleCrystal& crystal, const std::vector<Eigen::Matrix3d>& gyration) {
    crystal.gyrotropic = true;
    for (auto& component : crystal.gyration) component.clear();
    for (std::size_t j = 0; j < crystal.padded_size(); ++j) {
        const Eigen::Matrix3d& g = gyration[std::min(j, gyration.size() - 1)];
        const std::array<double, 6> components{g(0, 0), g(1, 1), g(2, 2), g(0, 1), g(0, 2), g(1, 2)};
        for (std::size_t c = 0; c < 6; ++c) crystal.gyration[c].push_back(components[c]);
    }
}

void KernelScratch::resize(std::size_t padded_samples) {
    for (auto* array : {&xi_x, &xi_y, &rho_x, &rho_y, &reversal}) array->resize(padded_samples);
    for (auto* set : {&q_start, &q, &dq_dxi_x, &dq_dxi_y, &e_z}) {
        for (auto& side : *set) for (auto& sheet : side) sheet.resize(padded_samples);
    }
    for (auto& side : psi) for (auto& sheet : side) for (auto& component : sheet) component.resize(padded_samples);
    for (auto& side : sheet_failed) for (auto& sheet : side) sheet.resize(padded_samples);
    for (auto* set : {&previous_xi_x, &previous_xi_y, &transmission, &mean, &modulation, &sine_modulation, &phase_difference, &coupling_product}) {
        for (auto& side : *set) side.resize(padded_samples);
    }
    for (auto* set : {&mode_field, &coupled_field}) {
        for (auto& side : *set) for (auto& component : side) component.resize(padded_samples);
    }
    failed.resize(padded_samples);
}

void set_sample_directions(KernelScratch& scratch, std::size_t first, std::size_t count, const Eigen::Vector2d& xi) {
    const double length = xi.norm();
    // ρ̂ = ξ/|ξ|, x̂ at ξ = 0; the opposite side's ρ̂ is −ρ̂, except at ξ = 0 where both use x̂.
    const double values[5] = {xi.x(), xi.y(), length > 0.0 ? xi.x() / length : 1.0, length > 0.0 ? xi.y() / length : 0.0,
                              length > 0.0 ? -1.0 : 1.0};
    std::vector<double>* arrays[5] = {&scratch.xi_x, &scratch.xi_y, &scratch.rho_x, &scratch.rho_y, &scratch.reversal};
    for (int k = 0; k < 5; ++k) std::fill_n(arrays[k]->begin() + static_cast<std::ptrdiff_t>(first), count, values[k]);
}

namespace {

/// The transmission from the modes in `scratch`, and each sample's failure flag; whether any failed.
bool transmit_and_flag(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch, KernelOutput output) {
    if (crystal.gyrotropic && output == KernelOutput::terms) {
        transmission_of_both_sides<KernelOutput::terms, false, true>(crystal, polars, scratch);
    } else if (crystal.gyrotropic && output == KernelOutput::fields) {
        transmission_of_both_sides<KernelOutput::fields, false, true>(crystal, polars, scratch);
    } else if (output == KernelOutput::terms) {
        transmission_of_both_sides<KernelOutput::terms, false>(crystal, polars, scratch);
    } else if (output == KernelOutput::fields) {
        transmission_of_both_sides<KernelOutput::fields, false>(crystal, polars, scratch);
    } else if (crystal.gyrotropic && crystal.with_plate) {
        transmission_of_both_sides<KernelOutput::transmission, true, true>(crystal, polars, scratch);
    } else if (crystal.gyrotropic) {
        transmission_of_both_sides<KernelOutput::transmission, false, true>(crystal, polars, scratch);
    } else if (crystal.with_plate) {
        transmission_of_both_sides<KernelOutput::transmission, true>(crystal, polars, scratch);
    } else {
        transmission_of_both_sides<KernelOutput::transmission, false>(crystal, polars, scratch);
    }
    // A sample needs all four modes (each side's backward modes are the other side's forward ones).
    const int count = static_cast<int>(crystal.size());
    const std::int64_t *f00 = scratch.sheet_failed[0][0].data(), *f01 = scratch.sheet_failed[0][1].data();
    const std::int64_t *f10 = scratch.sheet_failed[1][0].data(), *f11 = scratch.sheet_failed[1][1].data();
    const double *plus = scratch.transmission[0].data(), *minus = scratch.transmission[1].data();
    std::int64_t* failed = scratch.failed.data();
    std::int64_t failures = 0;
#pragma omp simd reduction(+ : failures)
    for (int i = 0; i < count; ++i) {
        const std::int64_t finite = std::isfinite(plus[i]) && std::isfinite(minus[i]) ? 1 : 0;
        failed[i] = f00[i] | f01[i] | f10[i] | f11[i] | (1 - finite);
        failures += failed[i];
    }
    return failures != 0;
}

}  // namespace

bool run_kernel(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch, bool warm, KernelOutput output) {
    if (crystal.uniaxial) {
        solve_side<true, 0>(crystal, scratch, warm);
        solve_side<true, 1>(crystal, scratch, warm);
    } else {
        solve_side<false, 0>(crystal, scratch, warm);
        solve_side<false, 1>(crystal, scratch, warm);
    }
    const bool any_failed = transmit_and_flag(crystal, polars, scratch, output);
    // The next run may start from these roots only if all of them are good.
    scratch.warm_ready = !any_failed;
    const int padded = static_cast<int>(crystal.padded_size());
    double *previous_x0 = scratch.previous_xi_x[0].data(), *previous_y0 = scratch.previous_xi_y[0].data();
    double *previous_x1 = scratch.previous_xi_x[1].data(), *previous_y1 = scratch.previous_xi_y[1].data();
    const double *xi_x = scratch.xi_x.data(), *xi_y = scratch.xi_y.data();
#pragma omp simd
    for (int i = 0; i < padded; ++i) {
        previous_x0[i] = xi_x[i];
        previous_y0[i] = xi_y[i];
        previous_x1[i] = -xi_x[i];
        previous_y1[i] = -xi_y[i];
    }
    return any_failed;
}

bool retransmit(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch, KernelOutput output) {
    return transmit_and_flag(crystal, polars, scratch, output);
}

}  // namespace petroscope::detail
