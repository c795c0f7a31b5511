// The vectorisable sin², sin and cos against the C library's, over the range of interference phases.
#include "petroscope/core/fast_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
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

}  // namespace
}  // namespace petroscope
