#pragma once
// A Ceres iteration callback that lets a progress callback cancel a solve between its iterations: the
// solver stops (SOLVER_ABORT) and the caller then throws with ProgressRelay::stop_if_cancelled.
#include "petroscope/core/progress.hpp"

#include <ceres/iteration_callback.h>

namespace petroscope {

class CancelBetweenIterations final : public ceres::IterationCallback {
public:
    explicit CancelBetweenIterations(ProgressRelay& relay) : relay_(relay) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
        relay_.poll();
        return relay_.cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
    }

private:
    ProgressRelay& relay_;
};

}  // namespace petroscope
