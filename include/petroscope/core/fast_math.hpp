#pragma once
// Branch-free elementary functions that compilers can vectorise (std::sin cannot be, without
// -ffast-math), accurate to a few ulp.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstddef>

namespace petroscope {

namespace fast_math_detail {

/// t^K for K a power of two, by squaring.
template <std::size_t K>
inline double power_of_two_power(double t) {
    if constexpr (K == 1) {
        return t;
    } else {
        const double half = power_of_two_power<K / 2>(t);
        return half * half;
    }
}

/// The largest power of two below n (n ≥ 2).
constexpr std::size_t split_below(std::size_t n) {
    std::size_t power = 1;
    while (2 * power < n) power *= 2;
    return power;
}

/// c_B + c_{B+1}t + … + c_{E−1}t^{E−1−B} by Estrin's scheme: the lower part plus t^h times the upper part, h the
/// largest power of two below the length (Knuth, The Art of Computer Programming 2, 3rd ed., 1997, §4.6.4).
template <std::size_t Begin, std::size_t End, std::size_t N>
inline double polynomial_part(const std::array<double, N>& coefficients, double t) {
    if constexpr (End - Begin == 1) {
        return coefficients[Begin];
    } else {
        constexpr std::size_t half = split_below(End - Begin);
        return polynomial_part<Begin, Begin + half>(coefficients, t) +
               power_of_two_power<half>(t) * polynomial_part<Begin + half, End>(coefficients, t);
    }
}

}  // namespace fast_math_detail

/// c₀ + c₁t + … + c_{N−1}t^{N−1}. Estrin's scheme: its chain of dependent operations grows like log N, where
/// Horner's grows like N, so vectorised loops that call it are not held up by the latency of one long chain.
template <std::size_t N>
inline double polynomial(const std::array<double, N>& coefficients, double t) {
    return fast_math_detail::polynomial_part<0, N>(coefficients, t);
}

namespace fast_math_detail {

/// y rounded to the nearest integer k by adding and removing 1.5·2⁵² (exact for |k| < 2⁵¹; vectorises, unlike
/// nearbyint under strict floating-point semantics). The sum, k + 1.5·2⁵², holds k's low bits in its own low bits
/// (two's complement of k for k < 0, as the shift is even).
struct Rounded {
    double k, shifted;
};
inline constexpr double kRoundShift = 6755399441055744.0;
inline Rounded round_to_integer(double y) {
    const double shifted = y + kRoundShift;
    return {shifted - kRoundShift, shifted};
}

/// x = k·π/D + r with |r| ≤ π/(2D), for D = 1 or 2. π/D is split in two parts (Cody & Waite 1980; the split of
/// fdlibm's __ieee754_rem_pio2), its first 33 bits so that k·high is exact for |k| < 2²⁰.
struct Reduction {
    double r, k;
};
template <int Divisor>
inline Reduction reduce_by_pi_over(double x) {
    static_assert(Divisor == 1 || Divisor == 2);
    constexpr double inverse = Divisor * 0.318309886183790671538;
    constexpr double high = 3.14159265346825122833e+00 / Divisor;  // halving is exact
    constexpr double low = 1.21542010130123844986e-10 / Divisor;   // π/D − high
    const double k = round_to_integer(x * inverse).k;
    return {(x - k * high) - k * low, k};
}

/// The Taylor coefficients of sin r / r in r², (−1)ⁿ/(2n+1)!.
constexpr std::array<double, 12> kSineTaylor{1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0, -1.0 / 39916800.0,
                                             1.0 / 6227020800.0, -1.0 / 1307674368000.0, 1.0 / 355687428096000.0,
                                             -1.0 / 121645100408832000.0, 1.0 / 51090942171709440000.0,
                                             -1.0 / 25852016738884976640000.0};

/// sin r by the first `Terms` terms of its Taylor series: to degree 23 (all 12, truncation < 1e-20 for |r| ≤ π/2)
/// or degree 15 (8, truncation < 5e-17 for |r| ≤ π/4).
template <std::size_t Terms = 12>
inline double sine_series(double r) {
    static_assert(Terms <= kSineTaylor.size());
    constexpr auto coefficients = [] {
        std::array<double, Terms> leading{};
        for (std::size_t n = 0; n < Terms; ++n) leading[n] = kSineTaylor[n];
        return leading;
    }();
    return r * polynomial(coefficients, r * r);
}

/// cos r for |r| ≤ π/4: the Taylor series Σ (−1)ⁿ r²ⁿ/(2n)! to degree 16 (truncation < 3e-18).
inline double cosine_series(double r) {
    constexpr std::array<double, 9> coefficients{1.0, -1.0 / 2.0, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0, -1.0 / 3628800.0,
                                                 1.0 / 479001600.0, -1.0 / 87178291200.0, 1.0 / 20922789888000.0};
    return polynomial(coefficients, r * r);
}

/// k mod 2 (0 or 1) for an integral k, without a branch.
inline double parity(double k) { return k - 2.0 * std::floor(0.5 * k); }

/// (−1)ᵏ for an integral k, without a branch.
inline double parity_sign(double k) { return 1.0 - 2.0 * parity(k); }

}  // namespace fast_math_detail

/// sin²(x) for |x| < 2¹⁹·π: with x = kπ/2 + r, |r| ≤ π/4, it is sin²r for even k and cos²r = 1 − sin²r for odd k, so
/// a shorter series than sine's serves.
inline double sin_squared(double x) {
    const auto [r, k] = fast_math_detail::reduce_by_pi_over<2>(x);
    const double sine = fast_math_detail::sine_series<8>(r);
    const double square = sine * sine;
    return square + fast_math_detail::parity(k) * (1.0 - 2.0 * square);
}

/// sin(x) for |x| < 2²⁰·π: sin(kπ + r) = (−1)ᵏ sin r.
inline double sine(double x) {
    const auto [r, k] = fast_math_detail::reduce_by_pi_over<1>(x);
    return fast_math_detail::parity_sign(k) * fast_math_detail::sine_series(r);
}

/// sin(x) and cos(x) for |x| < 2¹⁹·π from one reduction by π/2, x = kπ/2 + r with |r| ≤ π/4, where the series are
/// short: with s = sin r and c = cos r, (sin x, cos x) is (s, c), (c, −s), (−s, −c), (−c, s) for k mod 4 = 0, 1, 2, 3.
struct SineCosine {
    double sine, cosine;
};
inline SineCosine sine_cosine(double x) {
    constexpr double inverse = 2.0 * 0.318309886183790671538;
    constexpr double high = 3.14159265346825122833e+00 / 2, low = 1.21542010130123844986e-10 / 2;
    const auto [k, shifted] = fast_math_detail::round_to_integer(x * inverse);
    const double r = (x - k * high) - k * low;
    const double s = fast_math_detail::sine_series<8>(r), c = fast_math_detail::cosine_series(r);
    const auto bits = std::bit_cast<std::uint64_t>(shifted);  // k's low bits
    const bool odd = (bits & 1u) != 0;
    // sin x < 0 for k mod 4 = 2, 3 (bit 1 of k), cos x for k mod 4 = 1, 2 (bit 1 of k + 1): flip the sign bit.
    const std::uint64_t sine_flip = (bits & 2u) << 62, cosine_flip = ((bits + 1u) & 2u) << 62;
    return {std::bit_cast<double>(std::bit_cast<std::uint64_t>(odd ? c : s) ^ sine_flip),
            std::bit_cast<double>(std::bit_cast<std::uint64_t>(odd ? s : c) ^ cosine_flip)};
}

/// e^x for x ≤ 709, 0 below −708 (where e^x would be subnormal, under 2.3e-308), NaN for NaN. With x = k·ln 2 + r,
/// |r| ≤ ln(2)/2, it is 2ᵏ·e^r: k in the exponent's bits, e^r by its Taylor series to degree 13 (truncation < 1e-17;
/// ln 2 split in two parts as π is above, Cody & Waite 1980).
inline double exponential(double x) {
    constexpr double inverse = 1.44269504088896340736;  // 1/ln 2
    constexpr double high = 6.93147180369123816490e-01, low = 1.90821492927058770002e-10;
    constexpr std::array<double, 14> coefficients{1.0,           1.0,           1.0 / 2.0,      1.0 / 6.0,       1.0 / 24.0,
                                                  1.0 / 120.0,   1.0 / 720.0,   1.0 / 5040.0,   1.0 / 40320.0,   1.0 / 362880.0,
                                                  1.0 / 3628800.0, 1.0 / 39916800.0, 1.0 / 479001600.0, 1.0 / 6227020800.0};
    const double clamped = std::min(std::max(x, -708.0), 709.0);  // NaN passes through
    const auto [k, shifted] = fast_math_detail::round_to_integer(clamped * inverse);
    const double r = (clamped - k * high) - k * low;
    // k as an integer from shifted's low bits; 2ᵏ has the biased exponent k + 1023.
    const std::int64_t k_bits = std::bit_cast<std::int64_t>(shifted) - std::bit_cast<std::int64_t>(fast_math_detail::kRoundShift);
    const double scale = std::bit_cast<double>(static_cast<std::uint64_t>(k_bits + 1023) << 52);
    return x < -708.0 ? 0.0 : polynomial(coefficients, r) * scale;
}

/// sin x / x from x ≥ 0 and its sine, with the series 1 − x²/6 below 1e-6 (where the quotient loses digits and
/// the next term, x⁴/120, is below 1e-26).
inline double sinc_from_sine(double x, double sine_of_x) { return x > 1e-6 ? sine_of_x / x : 1.0 - x * x / 6.0; }

}  // namespace petroscope
