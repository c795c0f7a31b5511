// The vectorisable sin², sin, cos and exp against the C library's, over the range of interference phases.
#include "petroscope/core/fast_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

namespace petroscope {
namespace {

// The largest error(x)/(ε + ε|x|) over 10⁶ arguments of either sign, |x| from 1e-8 to 1e5 (a 10 mm calcite
// slab's phase in the violet is about 3e4 rad): the argument itself is known only to ε|x|.
double worst_scaled_error(std::uint64_t seed, double epsilon, const std::function<double(double)>& error) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> exponent(-8.0, 5.0), sign(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const double x = std::copysign(std::pow(10.0, exponent(rng)), sign(rng));
        worst = std::max(worst, error(x) / (epsilon + epsilon * std::abs(x)));
    }
    return worst;
}

TEST(FastMath, SinSquaredMatchesTheLibrarySine) {
    EXPECT_LT(worst_scaled_error(9, 4e-16, [](double x) { return std::abs(sin_squared(x) - std::sin(x) * std::sin(x)); }), 1.0);
    EXPECT_EQ(sin_squared(0.0), 0.0);
    EXPECT_NEAR(sin_squared(M_PI / 2), 1.0, 1e-16);
}

TEST(FastMath, SineMatchesTheLibrarySineWithItsSign) {
    EXPECT_LT(worst_scaled_error(10, 2e-16, [](double x) { return std::abs(sine(x) - std::sin(x)); }), 1.0);
    EXPECT_EQ(sine(0.0), 0.0);
    EXPECT_NEAR(sine(M_PI / 2), 1.0, 1e-16);
    EXPECT_NEAR(sine(-M_PI / 2), -1.0, 1e-16);
    EXPECT_NEAR(sine(3 * M_PI / 2), -1.0, 1e-15);
    EXPECT_NEAR(sine(5 * M_PI / 2), 1.0, 1e-15);
}

TEST(FastMath, SineAndCosineMatchTheLibraryFunctions) {
    EXPECT_LT(worst_scaled_error(11, 2e-16, [](double x) {
                  const SineCosine both = sine_cosine(x);
                  return std::max(std::abs(both.sine - std::sin(x)), std::abs(both.cosine - std::cos(x)));
              }),
              1.0);
    EXPECT_EQ(sine_cosine(0.0).cosine, 1.0);
    EXPECT_NEAR(sine_cosine(M_PI).cosine, -1.0, 1e-16);
    EXPECT_NEAR(sine_cosine(M_PI / 2).cosine, 0.0, 1e-16);
    EXPECT_NEAR(sine_cosine(-3 * M_PI).cosine, -1.0, 1e-15);
    EXPECT_NEAR(sine_cosine(4 * M_PI).cosine, 1.0, 1e-15);
}

// Within 2 ulp of e^x (4.5e-16 relative) over the whole normal range, plus the argument's own rounding, ε|x|
// relative in the result (x up to 709); at the ends 0 below the normal range, and NaN through.
TEST(FastMath, ExponentialMatchesTheLibraryExponential) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> argument(-708.0, 709.0), small(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const double x = i % 2 == 0 ? argument(rng) : small(rng);
        const double exact = std::exp(x);
        worst = std::max(worst, std::abs(exponential(x) - exact) / (exact * (4.5e-16 + 1.2e-16 * std::abs(x))));
    }
    EXPECT_LT(worst, 1.0);
    EXPECT_EQ(exponential(0.0), 1.0);
    EXPECT_NEAR(exponential(1.0), M_E, 4e-16);
    EXPECT_NEAR(exponential(-700.0) / std::exp(-700.0), 1.0, 1e-13);
    EXPECT_EQ(exponential(-709.0), 0.0);
    EXPECT_EQ(exponential(-1e300), 0.0);
    EXPECT_EQ(exponential(-std::numeric_limits<double>::infinity()), 0.0);
    EXPECT_TRUE(std::isnan(exponential(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace petroscope
