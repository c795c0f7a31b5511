// The rule that stops a refinement which can no longer reach the lowest cost of those before it
// (src/fit/stop_out_of_reach.hpp): it stops only when even four times the largest rate of descent of its last three
// iterations, kept up for every iteration left, would leave it above that cost.
#include "stop_out_of_reach.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

ceres::IterationSummary iteration(int number, double cost, double cost_change) {
    ceres::IterationSummary summary;
    summary.iteration = number;
    summary.cost = cost;
    summary.cost_change = cost_change;
    return summary;
}

TEST(StopOutOfReach, StopsOnlyWhatCannotReachTheLowestCostAtFourTimesItsRecentRate) {
    StopOutOfReach far(10.0, 30);
    EXPECT_EQ(far(iteration(0, 60.0, 0.0)), ceres::SOLVER_CONTINUE);  // nothing known of its rate yet
    EXPECT_EQ(far(iteration(1, 50.0, 0.25)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);  // 50 − 29·4·0.25 = 21 > 10

    StopOutOfReach near(10.0, 30);
    EXPECT_EQ(near(iteration(1, 20.0, 0.25)), ceres::SOLVER_CONTINUE);  // 20 − 29·4·0.25 = −9 < 10
}

TEST(StopOutOfReach, AFastStartDoesNotKeepACrawlGoing) {
    // 2 per step at first, then 0.1: the first steps' rate counts while it is one of the last three.
    StopOutOfReach crawl(10.0, 30);
    EXPECT_EQ(crawl(iteration(1, 48.0, 2.0)), ceres::SOLVER_CONTINUE);  // 48 − 29·4·2 < 10
    EXPECT_EQ(crawl(iteration(2, 47.9, 0.1)), ceres::SOLVER_CONTINUE);  // 2 still among the last three
    EXPECT_EQ(crawl(iteration(3, 47.8, 0.1)), ceres::SOLVER_CONTINUE);
    EXPECT_EQ(crawl(iteration(4, 47.7, 0.1)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);  // 47.7 − 26·4·0.1 = 37.3 > 10
}

TEST(StopOutOfReach, ASolveThatSpeedsUpAgainGoesOn) {
    StopOutOfReach steady(10.0, 30), faster(10.0, 30);
    for (StopOutOfReach* solve : {&steady, &faster}) {
        EXPECT_EQ((*solve)(iteration(1, 30.0, 0.2)), ceres::SOLVER_CONTINUE);  // 30 − 29·4·0.2 = 6.8
        EXPECT_EQ((*solve)(iteration(2, 29.9, 0.1)), ceres::SOLVER_CONTINUE);  // 29.9 − 28·4·0.2 = 7.5
        EXPECT_EQ((*solve)(iteration(3, 29.8, 0.1)), ceres::SOLVER_CONTINUE);  // 29.8 − 27·4·0.2 = 8.2
    }
    EXPECT_EQ(steady(iteration(4, 29.7, 0.1)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);  // 29.7 − 26·4·0.1 = 19.3
    EXPECT_EQ(faster(iteration(4, 29.5, 0.3)), ceres::SOLVER_CONTINUE);                // 29.5 − 26·4·0.3 = −1.7
}

}  // namespace
}  // namespace petroscope
