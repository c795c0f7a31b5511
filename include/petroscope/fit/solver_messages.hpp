#pragma once
// Whether the fits let their solver (Ceres, which reports through glog) print on standard error.

namespace petroscope {

/// Off by default: a fit prints nothing but its caller's progress. On (`--verbose`): glog's messages and
/// Ceres's progress per iteration go to standard error. Process-wide, as glog's own settings are.
void show_solver_messages(bool shown);

}  // namespace petroscope
