// Long computations report progress up to 1 and stop with Cancelled when the callback says no.
#include "conoscope_fixtures.hpp"

#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/orthoscope.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace petroscope {
namespace {

/// Records every report; answers no from the `stop_after`-th on (never when 0).
struct Recorder {
    std::vector<double> fractions;
    int stop_after = 0;
    ProgressCallback callback() {
        return [this](double fraction_done) {
            fractions.push_back(fraction_done);
            return stop_after == 0 || static_cast<int>(fractions.size()) < stop_after;
        };
    }
};

ConoscopeSettings small_figure(bool whole_stack) {
    const Mineral& muscovite = testing::repository_minerals().find("muscovite");
    ConoscopeSettings settings = testing::figure_settings(muscovite, Cut::acute_bisectrix, 30.0, 64);
    if (whole_stack) settings.mounting = standard_mounting(testing::repository_minerals());
    return settings;
}

TEST(Cancel, TheConoscopeReportsUpToOneAndStopsWhenAsked) {
    const PrincipalIndexFunction indices = testing::indices_of(testing::repository_minerals().find("muscovite"));
    for (const bool whole_stack : {false, true}) {
        SCOPED_TRACE(whole_stack ? "whole stack" : "slab");
        Recorder all;
        render_conoscope(small_figure(whole_stack), indices, nullptr, all.callback());
        ASSERT_FALSE(all.fractions.empty());
        EXPECT_EQ(all.fractions.back(), 1.0);
        EXPECT_TRUE(std::all_of(all.fractions.begin(), all.fractions.end(), [](double f) { return f > 0.0 && f <= 1.0; }));
        Recorder first_only{{}, 1};
        EXPECT_THROW(render_conoscope(small_figure(whole_stack), indices, nullptr, first_only.callback()), Cancelled);
        EXPECT_EQ(first_only.fractions.size(), 1u);  // nothing is delivered after the answer no
    }
}

TEST(Cancel, TheConicalRayTracerStopsWhenAsked) {
    ConicalRaySettings settings;
    settings.principal_n = {2.0135, 2.0458, 2.0860};
    settings.rays = 100000;
    settings.size_px = 64;
    Recorder first_only{{}, 1};
    EXPECT_THROW(trace_conical_rays(settings, first_only.callback()), Cancelled);
    EXPECT_EQ(first_only.fractions.size(), 1u);
}

}  // namespace
}  // namespace petroscope
