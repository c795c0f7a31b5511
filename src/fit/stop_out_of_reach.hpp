#pragma once
// A Ceres iteration callback for refinements that compete for the lowest cost: it stops a solve that cannot
// reach the lowest cost found so far within its remaining iterations, even descending at the largest rate it
// has shown, for it can then only rank below that one.
#include <ceres/iteration_callback.h>

#include <algorithm>

namespace petroscope {

class StopOutOfReach final : public ceres::IterationCallback {
public:
    StopOutOfReach(double lowest_cost, int max_iterations) : lowest_cost_(lowest_cost), max_iterations_(max_iterations) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        largest_decrease_ = std::max(largest_decrease_, summary.cost_change);
        const double reachable = summary.cost - (max_iterations_ - summary.iteration) * largest_decrease_;
        return summary.iteration > 0 && reachable > lowest_cost_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }

private:
    double lowest_cost_;
    int max_iterations_;
    double largest_decrease_ = 0.0;
};

}  // namespace petroscope
