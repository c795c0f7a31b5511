// The rule that stops a refinement which can no longer reach the lowest cost of those before it
// (src/fit/stop_out_of_reach.hpp): it stops only when even its largest rate of descent so far, kept up for every
// iteration left, would leave it above that cost.
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

TEST(StopOutOfReach, StopsOnlyWhatCannotReachTheLowestCostAtItsLargestRate) {
    StopOutOfReach far(10.0, 30);
    EXPECT_EQ(far(iteration(0, 60.0, 0.0)), ceres::SOLVER_CONTINUE);  // nothing known of its rate yet
    EXPECT_EQ(far(iteration(1, 50.0, 1.0)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);  // 50 − 29·1 = 21 > 10

    StopOutOfReach near(10.0, 30);
    EXPECT_EQ(near(iteration(1, 20.0, 1.0)), ceres::SOLVER_CONTINUE);  // 20 − 29·1 < 10

    // The largest decrease is remembered: judged by its latest rate, 0.1 per step, this solve would have stopped at
    // iteration 2 (47.9 − 28·0.1 > 10); at 2 per step it goes on until too few iterations are left.
    StopOutOfReach slowing(10.0, 30);
    EXPECT_EQ(slowing(iteration(1, 48.0, 2.0)), ceres::SOLVER_CONTINUE);  // 48 − 29·2 < 10
    EXPECT_EQ(slowing(iteration(2, 47.9, 0.1)), ceres::SOLVER_CONTINUE);
    EXPECT_EQ(slowing(iteration(20, 29.0, 0.1)), ceres::SOLVER_CONTINUE);  // 29 − 10·2 = 9
    EXPECT_EQ(slowing(iteration(25, 28.5, 0.1)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);  // 28.5 − 5·2 = 18.5
}

}  // namespace
}  // namespace petroscope
