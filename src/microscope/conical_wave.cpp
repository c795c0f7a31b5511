#include "petroscope/microscope/conical_wave.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/fast_math.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

namespace petroscope {
namespace {

// ---- Bessel functions J₀(x), J₁(x) for 0 ≤ x < kLargestArgument --------------------------------------

// Below kHankelFrom: Taylor polynomials of degree kTaylorDegree about the centres m + ½ of the unit
// intervals [m, m + 1]. |J_ν^{(n)}| ≤ 1 (DLMF 10.14.1 with 10.6.7), so the remainder is below
// 0.5¹⁵/15! ≈ 2e-17.
constexpr int kTaylorDegree = 14;
constexpr int kTaylorIntervals = 20;
constexpr double kHankelFrom = kTaylorIntervals;
// From kHankelFrom on: Hankel's expansion with kHankelTerms terms in each of P and Q; at x ≥ 20 the first
// omitted term, √(2/πx)·a₁₆(ν)/x¹⁶, is below 2e-15, and the result agrees with std::cyl_bessel_j to 6e-15.
constexpr int kHankelTerms = 8;
// sine_cosine (core/fast_math.hpp) keeps its accuracy below 2¹⁹·π.
constexpr double kLargestArgument = 1.0e6;

struct TaylorTables {
    std::array<std::array<double, kTaylorDegree + 1>, kTaylorIntervals> j0{}, j1{};
};

// J_n for any integer n, J_{−n} = (−1)ⁿ J_n (DLMF 10.4.1).
double bessel_integer_order(int order, double x) {
    const double value = std::cyl_bessel_j(static_cast<double>(std::abs(order)), x);
    return (order < 0 && order % 2 != 0) ? -value : value;
}

TaylorTables make_taylor_tables() {
    TaylorTables tables;
    for (int m = 0; m < kTaylorIntervals; ++m) {
        const double centre = m + 0.5;
        double scale = 1.0;  // 1/(2ⁿ n!)
        for (int n = 0; n <= kTaylorDegree; ++n) {
            // dⁿJ_ν/dxⁿ = 2⁻ⁿ Σₖ (−1)ᵏ C(n, k) J_{ν−n+2k} (DLMF 10.6.7); the Taylor coefficient is that over n!.
            double sum0 = 0.0, sum1 = 0.0, binomial = 1.0;
            for (int k = 0; k <= n; ++k) {
                const double sign = k % 2 == 0 ? 1.0 : -1.0;
                sum0 += sign * binomial * bessel_integer_order(2 * k - n, centre);
                sum1 += sign * binomial * bessel_integer_order(1 + 2 * k - n, centre);
                binomial = binomial * (n - k) / (k + 1);
            }
            tables.j0[m][n] = sum0 * scale;
            tables.j1[m][n] = sum1 * scale;
            scale /= 2.0 * (n + 1);
        }
    }
    return tables;
}

const TaylorTables& taylor_tables() {
    static const TaylorTables tables = make_taylor_tables();
    return tables;
}

struct HankelSeries {
    std::array<double, kHankelTerms> p{}, q{};  // P = Σ p_k x^{−2k}, Q = Σ q_k x^{−2k−1}
};

// a_k(ν) = Πⱼ₌₁ᵏ (4ν² − (2j − 1)²)/(k! 8ᵏ); P = Σ (−1)ᵏ a_{2k}(ν) x^{−2k}, Q = Σ (−1)ᵏ a_{2k+1}(ν) x^{−2k−1}
// (DLMF 10.17.1, 10.17.3).
constexpr HankelSeries hankel_series(int order) {
    HankelSeries series;
    const double mu = 4.0 * order * order;
    double a = 1.0;  // a_0
    for (int k = 0; k < 2 * kHankelTerms; ++k) {
        const double sign = (k / 2) % 2 == 0 ? 1.0 : -1.0;
        (k % 2 == 0 ? series.p[k / 2] : series.q[k / 2]) = sign * a;
        a *= (mu - (2.0 * k + 1.0) * (2.0 * k + 1.0)) / (8.0 * (k + 1));
    }
    return series;
}

constexpr HankelSeries kHankel0 = hankel_series(0);
constexpr HankelSeries kHankel1 = hankel_series(1);

struct BesselPair {
    double j0, j1;
};

inline BesselPair bessel_taylor(const TaylorTables& tables, double x) {
    const int m = std::min(static_cast<int>(x), kTaylorIntervals - 1);  // x may round up to kHankelFrom
    const double d = x - (m + 0.5);
    const auto& c0 = tables.j0[m];
    const auto& c1 = tables.j1[m];
    double j0 = c0[kTaylorDegree], j1 = c1[kTaylorDegree];
    for (int n = kTaylorDegree - 1; n >= 0; --n) {
        j0 = j0 * d + c0[n];
        j1 = j1 * d + c1[n];
    }
    return {j0, j1};
}

// For kHankelFrom ≤ x < kLargestArgument, branch-free so that loops over x vectorise:
// J₀ = √(2/πx)(P₀ cos χ − Q₀ sin χ), J₁ = √(2/πx)(P₁ sin χ + Q₁ cos χ), χ = x − π/4 (DLMF 10.17.3; for
// ν = 1, ω = χ − π/2); cos x and sin x from core/fast_math.hpp.
inline BesselPair bessel_hankel(double x) {
    const auto [sin_x, cos_x] = sine_cosine(x);
    // cos(x − π/4) = (cos x + sin x)/√2, sin(x − π/4) = (sin x − cos x)/√2.
    constexpr double inverse_sqrt2 = std::numbers::sqrt2 / 2.0;
    const double cos_chi = (cos_x + sin_x) * inverse_sqrt2;
    const double sin_chi = (sin_x - cos_x) * inverse_sqrt2;
    const double y = 1.0 / x;
    const double y2 = y * y;
    const double amplitude = std::sqrt(2.0 * std::numbers::inv_pi * y);
    const double p0 = polynomial(kHankel0.p, y2), q0 = y * polynomial(kHankel0.q, y2);
    const double p1 = polynomial(kHankel1.p, y2), q1 = y * polynomial(kHankel1.q, y2);
    return {amplitude * (p0 * cos_chi - q0 * sin_chi), amplitude * (p1 * sin_chi + q1 * cos_chi)};
}

inline BesselPair bessel_j01(double x) {
    return x < kHankelFrom ? bessel_taylor(taylor_tables(), x) : bessel_hankel(x);
}

// ---- Quadrature in P ----------------------------------------------------------------------------------

constexpr int kGaussPoints = 10;
// At most 1e6 nodes (40 MB of coefficients, ~1 ms per profile sample): beyond, |Z| is so large that the
// quadrature is the wrong tool.
constexpr double kMostPanels = 1e5;

struct GaussLegendre {
    std::array<double, kGaussPoints> nodes{}, weights{};  // on [−1, 1]
};

// Newton's method on P_n from the starting guesses cos(π(i + ¾)/(n + ½)); P_n by the three-term
// recurrence, P_n' = n(xP_n − P_{n−1})/(x² − 1), weights 2/((1 − x²)P_n'²) (Abramowitz & Stegun 25.4.29).
GaussLegendre make_gauss_legendre() {
    GaussLegendre rule;
    constexpr int n = kGaussPoints;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double previous = 1.0, current = x;
            for (int order = 2; order <= n; ++order) {
                const double next = ((2.0 * order - 1.0) * x * current - (order - 1.0) * previous) / order;
                previous = current;
                current = next;
            }
            derivative = n * (x * current - previous) / (x * x - 1.0);
            const double step = current / derivative;
            x -= step;
            if (std::abs(step) < 1e-16) break;
        }
        rule.nodes[i] = x;
        rule.weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    return rule;
}

const GaussLegendre& gauss_legendre() {
    static const GaussLegendre rule = make_gauss_legendre();
    return rule;
}

// The P nodes shared by every ρ of a profile, ascending, with the ρ-independent factors of the integrands:
// coefficient0 = w P a(P) e^{−iZP²/2} cos(ρ₀P), coefficient1 = w P a(P) e^{−iZP²/2} sin(ρ₀P) (docs/theory.md
// §8), split into real and imaginary parts for the vectorised sums.
struct SpectralNodes {
    std::vector<double> p, c0_re, c0_im, c1_re, c1_im;
};

// a(P): the incident beam's angular spectrum, the order-0 Hankel transform ∫₀^∞ E(ρ) J₀(Pρ) ρ dρ of
// E = exp(−ρ²/2) (Gaussian) or of the unit disc, J₁(P)/P (Gradshteyn & Ryzhik 6.631.4, 5.52.1), the
// latter times exp(−σ²P²/2), the transform of the edge-softening Gaussian.
double angular_spectrum(ConicalBeam beam, double p) {
    if (beam == ConicalBeam::gaussian) return std::exp(-0.5 * p * p);
    const double j1_over_p = p < 1e-4 ? 0.5 - p * p / 16.0 : bessel_j01(p).j1 / p;  // J₁(P)/P = ½ − P²/16 + …
    const double sigma = kConicalPinholeEdgeWidth;
    return j1_over_p * std::exp(-0.5 * sigma * sigma * p * p);
}

// P_max: the Gaussian's P·a(P) falls below 3e-17 at P = 9; the softened pinhole's factor exp(−σ²P²/2)
// reaches 3e-18 at P = 9/σ.
double largest_p(ConicalBeam beam) { return beam == ConicalBeam::gaussian ? 9.0 : 9.0 / kConicalPinholeEdgeWidth; }

// Panels of one period of the fastest oscillation: the integrands vary as cos((ρ₀ ± ρ)P)·e^{−iZP²/2}, local
// angular frequency ≤ Ω(P) = ρ₀ + ρ_max + |Z|P; 2π is added so that panels are at most one unit of P
// wide, the scale of a(P). Panel j ends where the phase Φ(P) = cP + |Z|P²/2 (c = ρ₀ + ρ_max + 2π) reaches
// j·Φ(P_max)/N. A 10-point Gauss–Legendre rule on a panel of phase 2π errs by about 5e-15 of the
// panel's width times the integrand's size (A&S 25.4.30), so the sum errs by less than 1e-12.
SpectralNodes spectral_nodes(const ConicalWaveParameters& parameters, double rho_max) {
    const double p_max = largest_p(parameters.beam);
    const double c = parameters.rho0 + rho_max + 2.0 * std::numbers::pi;
    const double chirp = std::abs(parameters.z);
    const double total_phase = c * p_max + 0.5 * chirp * p_max * p_max;
    const double panel_count = std::ceil(total_phase / (2.0 * std::numbers::pi));
    if (panel_count > kMostPanels) {
        throw InputError("Z = " + format_number(parameters.z) + " with a profile to rho = " + format_number(rho_max) + " needs " +
                         format_number(panel_count * kGaussPoints) + " quadrature nodes (at most " +
                         format_number(kMostPanels * kGaussPoints) + "); reduce |Z|, rho0 or the profile's radius");
    }
    const int panels = static_cast<int>(panel_count);
    // The root P ≥ 0 of cP + |Z|P²/2 = Φ, in the form without cancellation.
    const auto p_at_phase = [&](double phase) { return 2.0 * phase / (c + std::sqrt(c * c + 2.0 * chirp * phase)); };
    const GaussLegendre& rule = gauss_legendre();
    SpectralNodes nodes;
    const std::size_t count = static_cast<std::size_t>(panels) * kGaussPoints;
    for (auto* v : {&nodes.p, &nodes.c0_re, &nodes.c0_im, &nodes.c1_re, &nodes.c1_im}) v->reserve(count);
    double start = 0.0;
    for (int j = 1; j <= panels; ++j) {
        const double end = j == panels ? p_max : p_at_phase(total_phase * j / panels);
        const double half = 0.5 * (end - start), middle = 0.5 * (end + start);
        // Gauss–Legendre nodes are symmetric; taking them from the most negative keeps P ascending.
        for (int i = kGaussPoints - 1; i >= 0; --i) {
            const double p = middle + half * rule.nodes[i];
            const double amplitude = half * rule.weights[i] * p * angular_spectrum(parameters.beam, p);
            const double chirp_phase = -0.5 * parameters.z * p * p;  // e^{−iZP²/2}
            const double chirped_re = amplitude * std::cos(chirp_phase), chirped_im = amplitude * std::sin(chirp_phase);
            const double cosine = std::cos(parameters.rho0 * p), sine = std::sin(parameters.rho0 * p);
            nodes.p.push_back(p);
            nodes.c0_re.push_back(chirped_re * cosine);
            nodes.c0_im.push_back(chirped_im * cosine);
            nodes.c1_re.push_back(chirped_re * sine);
            nodes.c1_im.push_back(chirped_im * sine);
        }
        start = end;
    }
    return nodes;
}

// B₀(ρ) = Σ c0_k J₀(ρP_k), B₁(ρ) = Σ c1_k J₁(ρP_k): the nodes with ρP < kHankelFrom (a prefix, P ascending)
// take the Taylor tables, the rest the vectorised Hankel expansion.
std::pair<std::complex<double>, std::complex<double>> hankel_sums(const SpectralNodes& nodes, double rho) {
    const int count = static_cast<int>(nodes.p.size());
    const int split = rho > 0.0 ? static_cast<int>(std::lower_bound(nodes.p.begin(), nodes.p.end(), kHankelFrom / rho) -
                                                   nodes.p.begin())
                                : count;
    const TaylorTables& tables = taylor_tables();
    double b0_re = 0.0, b0_im = 0.0, b1_re = 0.0, b1_im = 0.0;
    for (int k = 0; k < split; ++k) {
        const BesselPair j = bessel_taylor(tables, rho * nodes.p[k]);
        b0_re += nodes.c0_re[k] * j.j0;
        b0_im += nodes.c0_im[k] * j.j0;
        b1_re += nodes.c1_re[k] * j.j1;
        b1_im += nodes.c1_im[k] * j.j1;
    }
    const double *p = nodes.p.data(), *c0_re = nodes.c0_re.data(), *c0_im = nodes.c0_im.data();
    const double *c1_re = nodes.c1_re.data(), *c1_im = nodes.c1_im.data();
#pragma omp simd reduction(+ : b0_re, b0_im, b1_re, b1_im)
    for (int k = split; k < count; ++k) {
        const BesselPair j = bessel_hankel(rho * p[k]);
        b0_re += c0_re[k] * j.j0;
        b0_im += c0_im[k] * j.j0;
        b1_re += c1_re[k] * j.j1;
        b1_im += c1_im[k] * j.j1;
    }
    return {{b0_re, b0_im}, {b1_re, b1_im}};
}

void check(bool condition, const std::string& what) {
    if (!condition) throw InputError(what);
}

double intensity(std::complex<double> b0, std::complex<double> b1, const Eigen::Vector4d& stokes, double cos_phi,
                 double sin_phi) {
    // I = S0(|B₀|² + |B₁|²) + 2 Re(B₀B₁*)(S1 cos φ + S2 sin φ) (docs/theory.md §8).
    return stokes[0] * (std::norm(b0) + std::norm(b1)) +
           2.0 * (b0 * std::conj(b1)).real() * (stokes[1] * cos_phi + stokes[2] * sin_phi);
}

// Position of the extremum of the parabola through samples k − 1, k, k + 1 (k = 0: the profile is even in ρ).
double refined_position(const std::vector<double>& values, const std::vector<double>& rho, std::size_t k) {
    const double step = rho[1] - rho[0];
    if (k == 0 || k + 1 >= values.size()) return rho[k];
    const double curvature = values[k - 1] - 2.0 * values[k] + values[k + 1];
    const double offset = curvature != 0.0 ? 0.5 * (values[k - 1] - values[k + 1]) / curvature : 0.0;
    return rho[k] + offset * step;
}

}  // namespace

std::pair<std::complex<double>, std::complex<double>> ConicalProfile::at(double r) const {
    if (rho.size() < 2 || b0.size() != rho.size() || b1.size() != rho.size()) {
        throw InputError("conical profile is empty or inconsistent");
    }
    const double rho_max = rho.back();
    if (!(r >= 0.0 && r <= rho_max * (1.0 + 1e-12))) {
        throw InputError("radius " + format_number(r) + " is outside the conical profile (0 to " + format_number(rho_max) + ")");
    }
    const double position = r / rho_max * static_cast<double>(rho.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(position), rho.size() - 2);
    const double t = position - static_cast<double>(i);
    return {b0[i] + t * (b0[i + 1] - b0[i]), b1[i] + t * (b1[i + 1] - b1[i])};
}

ConicalProfile conical_profile(const ConicalWaveParameters& parameters, double rho_max, int samples, const ProgressCallback& progress) {
    check(std::isfinite(parameters.rho0) && parameters.rho0 >= 0.0,
          "ring radius rho0 must be a finite number >= 0 (got " + format_number(parameters.rho0) + ")");
    check(std::isfinite(parameters.z), "observation distance Z must be finite");
    check(std::isfinite(rho_max) && rho_max > 0.0, "profile radius must be positive (got " + format_number(rho_max) + ")");
    check(samples >= 2, "a conical profile needs at least 2 samples (got " + std::to_string(samples) + ")");
    check(rho_max * largest_p(parameters.beam) < kLargestArgument,
          "profile radius " + format_number(rho_max) + " is too large for the Bessel evaluation (expected below " +
              format_number(kLargestArgument / largest_p(parameters.beam)) + ")");
    const SpectralNodes nodes = spectral_nodes(parameters, rho_max);
    ConicalProfile profile;
    profile.rho.resize(samples);
    profile.b0.resize(samples);
    profile.b1.resize(samples);
    ProgressRelay relay(progress);
    std::atomic<int> done{0};
#pragma omp parallel for schedule(dynamic, 8)
    for (int i = 0; i < samples; ++i) {
        if (relay.cancelled()) continue;
        const double rho = rho_max * i / (samples - 1);
        profile.rho[i] = rho;
        std::tie(profile.b0[i], profile.b1[i]) = hankel_sums(nodes, rho);
        relay.count_done(done, samples);
    }
    relay.stop_if_cancelled();
    return profile;
}

double conical_intensity(const ConicalProfile& profile, const Eigen::Vector4d& stokes, double rho, double phi) {
    const auto [b0, b1] = profile.at(rho);
    return intensity(b0, b1, stokes, std::cos(phi), std::sin(phi));
}

Image conical_screen(const ConicalProfile& profile, const Eigen::Vector4d& stokes, int size, double half_width) {
    check(size >= 1, "screen size must be at least 1 pixel (got " + std::to_string(size) + ")");
    check(std::isfinite(half_width) && half_width > 0.0, "screen half-width must be positive (got " + format_number(half_width) + ")");
    check(stokes.allFinite(), "Stokes vector must be finite");
    const double pixel_half = half_width / size;  // half a pixel, in units of w
    const double corner = std::sqrt(2.0) * (size - 1) * pixel_half;
    check(!profile.rho.empty() && profile.rho.back() >= corner,
          "conical profile reaches " + format_number(profile.rho.empty() ? 0.0 : profile.rho.back()) +
              " but the screen's corners lie at " + format_number(corner));
    Image image(size, size, 1);
#pragma omp parallel for schedule(static)
    for (int row = 0; row < size; ++row) {
        // Pixel centres in half-pixel units, odd integers, so that ρ² is exact and pixels at mirrored or
        // swapped positions get identical values.
        const double v = size - 1 - 2 * row;  // y up
        for (int column = 0; column < size; ++column) {
            const double u = 2 * column + 1 - size;
            const double radius_units = std::sqrt(u * u + v * v);
            const auto [b0, b1] = profile.at(radius_units * pixel_half);
            const double cos_phi = radius_units > 0.0 ? u / radius_units : 1.0;
            const double sin_phi = radius_units > 0.0 ? v / radius_units : 0.0;
            image.at(column, row, 0) = static_cast<float>(intensity(b0, b1, stokes, cos_phi, sin_phi));
        }
    }
    return image;
}

ConicalRings conical_rings(const ConicalProfile& profile, double rho0) {
    check(profile.rho.size() >= 3, "conical profile is too short to locate its rings");
    const std::size_t n = profile.rho.size();
    std::vector<double> total(n);
    for (std::size_t k = 0; k < n; ++k) total[k] = std::norm(profile.b0[k]) + std::norm(profile.b1[k]);
    const double largest = *std::max_element(total.begin(), total.end());
    // Bright rings: local maxima above 1e-3 of the largest value; I is even in ρ, so ρ = 0 counts too.
    std::vector<std::size_t> maxima;
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double below = k == 0 ? total[1] : total[k - 1];
        if (total[k] >= 1e-3 * largest && total[k] > below && total[k] >= total[k + 1]) maxima.push_back(k);
    }
    check(maxima.size() >= 2, "the conical profile shows no pair of bright rings");
    ConicalRings best{};
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m + 1 < maxima.size(); ++m) {
        const auto first = total.begin() + static_cast<std::ptrdiff_t>(maxima[m]);
        const auto last = total.begin() + static_cast<std::ptrdiff_t>(maxima[m + 1]);
        const std::size_t valley = static_cast<std::size_t>(std::min_element(first, last) - total.begin());
        const double dark = refined_position(total, profile.rho, valley);
        if (std::abs(dark - rho0) < best_distance) {
            best_distance = std::abs(dark - rho0);
            best = {refined_position(total, profile.rho, maxima[m + 1]), dark, refined_position(total, profile.rho, maxima[m])};
        }
    }
    return best;
}

double conical_power(const ConicalProfile& profile) {
    check(profile.rho.size() >= 2, "conical profile is too short to integrate");
    const std::size_t n = profile.rho.size();
    const auto density = [&](std::size_t k) {
        return 2.0 * std::numbers::pi * profile.rho[k] * (std::norm(profile.b0[k]) + std::norm(profile.b1[k]));
    };
    double sum = 0.5 * (density(0) + density(n - 1));
    for (std::size_t k = 1; k + 1 < n; ++k) sum += density(k);
    return sum * (profile.rho[1] - profile.rho[0]);
}

}  // namespace petroscope
