// The progress relay: the callback's answer cancels, its exceptions come back to the caller.
#include "petroscope/core/progress.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace petroscope {
namespace {

TEST(ProgressRelay, GoesOnWhileTheCallbackSaysSoAndStopsWhenItSaysNo) {
    int calls = 0;
    const ProgressCallback stop_at_half = [&](double fraction_done) {
        ++calls;
        return fraction_done < 0.5;
    };
    ProgressRelay relay(stop_at_half);
    relay.report(0.25);
    EXPECT_FALSE(relay.cancelled());
    EXPECT_NO_THROW(relay.stop_if_cancelled());
    relay.report(0.5);
    EXPECT_TRUE(relay.cancelled());
    EXPECT_THROW(relay.stop_if_cancelled(), Cancelled);
    relay.report(0.75);  // not delivered once cancelled
    EXPECT_EQ(calls, 2);
}

TEST(ProgressRelay, AnExceptionFromTheCallbackCancelsAndIsRethrown) {
    const ProgressCallback failing = [](double) -> bool { throw std::runtime_error("interrupted"); };
    ProgressRelay relay(failing);
    relay.report(0.1);
    EXPECT_TRUE(relay.cancelled());
    EXPECT_THROW(relay.stop_if_cancelled(), std::runtime_error);
}

TEST(ProgressRelay, PollRepeatsTheLastFractionAndNoCallbackIsFine) {
    std::vector<double> seen;
    const ProgressCallback record = [&](double fraction_done) {
        seen.push_back(fraction_done);
        return true;
    };
    ProgressRelay relay(record);
    std::atomic<int> done{0};
    relay.count_done(done, 4);
    relay.poll();
    EXPECT_EQ(seen, (std::vector<double>{0.25, 0.25}));
    ProgressRelay silent(ProgressCallback{});
    silent.report(0.5);
    EXPECT_FALSE(silent.cancelled());
}

}  // namespace
}  // namespace petroscope
