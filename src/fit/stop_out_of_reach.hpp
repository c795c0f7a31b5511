#pragma once
// A Ceres iteration callback for refinements that compete for the lowest cost: it stops a solve that cannot
// reach the lowest cost found so far within its remaining iterations, even descending at four times the largest
// rate of its last three iterations, for it can then only rank below that one. The rate of the last few iterations,
// not the largest ever: a refinement started far from the photo's geometry drops fast in its first steps and then
// crawls along its valley, and the first steps' rate would keep it going to the iteration limit.
#include <ceres/iteration_callback.h>

#include <algorithm>
#include <array>

namespace petroscope {

class StopOutOfReach final : public ceres::IterationCallback {
public:
    StopOutOfReach(double lowest_cost, int max_iterations) : lowest_cost_(lowest_cost), max_iterations_(max_iterations) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        if (summary.iteration == 0) return ceres::SOLVER_CONTINUE;  // nothing known of its rate yet
        recent_decreases_[static_cast<std::size_t>(summary.iteration) % recent_decreases_.size()] = summary.cost_change;
        const double rate = kRateMargin * *std::max_element(recent_decreases_.begin(), recent_decreases_.end());
        const double reachable = summary.cost - (max_iterations_ - summary.iteration) * rate;
        return reachable > lowest_cost_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }

private:
    static constexpr double kRateMargin = 4.0;
    double lowest_cost_;
    int max_iterations_;
    std::array<double, 3> recent_decreases_{};  // the cost's decrease in the last three iterations (0 before the first)
};

}  // namespace petroscope
