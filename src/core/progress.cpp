#include "petroscope/core/progress.hpp"

namespace petroscope {

void ProgressRelay::report(double fraction_done) {
    if (!callback_ || cancelled()) return;
    const std::unique_lock lock(delivering_, std::try_to_lock);
    if (!lock.owns_lock()) return;
    last_fraction_ = fraction_done;
    try {
        if (!callback_(fraction_done)) cancelled_ = true;
    } catch (...) {
        failure_ = std::current_exception();
        cancelled_ = true;
    }
}

void ProgressRelay::stop_if_cancelled() const {
    if (failure_) std::rethrow_exception(failure_);
    if (cancelled()) throw Cancelled();
}

}  // namespace petroscope
