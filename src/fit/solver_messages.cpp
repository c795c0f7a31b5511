#include "solver_messages.hpp"

#include <glog/logging.h>

#include <atomic>

namespace petroscope {
namespace {

std::atomic<bool> solver_messages_shown{false};

}  // namespace

void show_solver_messages(bool shown) { solver_messages_shown = shown; }

namespace detail {

ceres::LoggingType solver_logging() {
    const bool shown = solver_messages_shown;
    // glog drops messages below minloglevel (FATAL, which aborts, is always logged); shown, everything
    // goes to standard error, Ceres's per-iteration lines (VLOG(1)) included.
    FLAGS_minloglevel = shown ? google::GLOG_INFO : google::GLOG_FATAL;
    FLAGS_logtostderr = shown;
    FLAGS_v = shown ? 1 : 0;
    return shown ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
}

}  // namespace detail
}  // namespace petroscope
