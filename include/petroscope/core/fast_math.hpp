#pragma once
// Branch-free elementary functions that compilers can vectorise (std::sin cannot be, without
// -ffast-math), accurate to a few ulp.
#include <cmath>

namespace petroscope {

namespace fast_math_detail {

/// x = kπ + r with |r| ≤ π/2: sin r and k. π is split in two parts (Cody & Waite 1980; the split of fdlibm's
/// __ieee754_rem_pio2), then sin r is the Taylor series to degree 23 (truncation < 1e-20).
struct ReducedSine {
    double sine_r, k;
};
inline ReducedSine reduced_sine(double x) {
    constexpr double inverse_pi = 0.318309886183790671538;
    constexpr double pi_high = 3.14159265346825122833e+00;   // first 33 bits of π: k·pi_high is exact
    constexpr double pi_low = 1.21542010130123844986e-10;    // π − pi_high
    // Round to the nearest integer by adding and removing 1.5·2⁵² (exact for |x/π| < 2⁵¹; vectorises,
    // unlike nearbyint under strict floating-point semantics).
    constexpr double round_shift = 6755399441055744.0;
    const double k = (x * inverse_pi + round_shift) - round_shift;
    const double r = (x - k * pi_high) - k * pi_low;
    const double r2 = r * r;
    // sin r = r·Σ (−1)ⁿ r²ⁿ/(2n+1)!, Horner from the degree-23 term.
    double series = -1.0 / 25852016738884976640000.0;
    series = series * r2 + 1.0 / 51090942171709440000.0;
    series = series * r2 - 1.0 / 121645100408832000.0;
    series = series * r2 + 1.0 / 355687428096000.0;
    series = series * r2 - 1.0 / 1307674368000.0;
    series = series * r2 + 1.0 / 6227020800.0;
    series = series * r2 - 1.0 / 39916800.0;
    series = series * r2 + 1.0 / 362880.0;
    series = series * r2 - 1.0 / 5040.0;
    series = series * r2 + 1.0 / 120.0;
    series = series * r2 - 1.0 / 6.0;
    series = series * r2 + 1.0;
    return {r * series, k};
}

}  // namespace fast_math_detail

/// sin²(x) for |x| < 2²⁰·π. sin² has period π, so no quadrant bookkeeping is needed.
inline double sin_squared(double x) {
    const double sine = fast_math_detail::reduced_sine(x).sine_r;
    return sine * sine;
}

/// sin(x) for |x| < 2²⁰·π: sin(kπ + r) = (−1)ᵏ sin r.
inline double sine(double x) {
    const auto [sine_r, k] = fast_math_detail::reduced_sine(x);
    const double odd = k - 2.0 * std::floor(0.5 * k);  // 0 or 1
    return (1.0 - 2.0 * odd) * sine_r;
}

}  // namespace petroscope
