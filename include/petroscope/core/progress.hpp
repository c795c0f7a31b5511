#pragma once
// Progress reports from long renders.
#include <functional>

namespace petroscope {

/// Called now and then from the rendering thread with the fraction done (0 … 1).
using ProgressCallback = std::function<void(double fraction_done)>;

}  // namespace petroscope
