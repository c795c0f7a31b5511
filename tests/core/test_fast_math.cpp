// The vectorisable sin² and sin against the C library's sin, over the range of interference phases.
#include "petroscope/core/fast_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace petroscope {
namespace {

TEST(FastMath, SinSquaredMatchesTheLibrarySine) {
    std::mt19937_64 rng(9);
    // Phases up to 1e5 rad (a 10 mm calcite slab in the violet is about 3e4 rad).
    std::uniform_real_distribution<double> exponent(-8.0, 5.0), sign(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const double x = std::copysign(std::pow(10.0, exponent(rng)), sign(rng));
        const double reference = std::sin(x) * std::sin(x);
        // The argument itself is known to ε|x|, so agreement is measured against that scale.
        worst = std::max(worst, std::abs(sin_squared(x) - reference) / (4e-16 + 4e-16 * std::abs(x)));
    }
    EXPECT_LT(worst, 1.0);
    EXPECT_EQ(sin_squared(0.0), 0.0);
    EXPECT_NEAR(sin_squared(M_PI / 2), 1.0, 1e-16);
}

TEST(FastMath, SineMatchesTheLibrarySineWithItsSign) {
    std::mt19937_64 rng(10);
    std::uniform_real_distribution<double> exponent(-8.0, 5.0), sign(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
        const double x = std::copysign(std::pow(10.0, exponent(rng)), sign(rng));
        worst = std::max(worst, std::abs(sine(x) - std::sin(x)) / (2e-16 + 2e-16 * std::abs(x)));
    }
    EXPECT_LT(worst, 1.0);
    EXPECT_EQ(sine(0.0), 0.0);
    EXPECT_NEAR(sine(M_PI / 2), 1.0, 1e-16);
    EXPECT_NEAR(sine(-M_PI / 2), -1.0, 1e-16);
    EXPECT_NEAR(sine(3 * M_PI / 2), -1.0, 1e-15);
    EXPECT_NEAR(sine(5 * M_PI / 2), 1.0, 1e-15);
}

}  // namespace
}  // namespace petroscope
