#pragma once
// The solver's logging as show_solver_messages (petroscope/fit/solver_messages.hpp) asks.
#include "petroscope/fit/solver_messages.hpp"

#include <ceres/types.h>

namespace petroscope::detail {

/// Sets glog's thresholds for the next solve and returns the Ceres logging type to solve with.
ceres::LoggingType solver_logging();

}  // namespace petroscope::detail
