#pragma once
// Progress reports from long computations, and cancelling them from the report.
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace petroscope {

/// Called now and then with the fraction done (0 … 1). Returns true to go on, false to cancel: the
/// computation then stops soon and throws Cancelled. Called by one thread at a time, not always the same.
using ProgressCallback = std::function<bool(double fraction_done)>;

/// Thrown by a computation whose progress callback asked it to stop.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled") {}
};

/// Passes the reports of a parallel computation's threads to one callback, one at a time, and keeps its
/// answer. Threads check cancelled() between pieces of work; after the parallel part the computation calls
/// stop_if_cancelled(). An exception thrown by the callback also cancels, and is rethrown there.
class ProgressRelay {
public:
    explicit ProgressRelay(ProgressCallback callback) : callback_(std::move(callback)) {}
    /// From any thread; a report while another thread's is being delivered is dropped.
    void report(double fraction_done);
    /// Reports `done` of `total` pieces of work after incrementing `done`.
    void count_done(std::atomic<int>& done, int total) { report(static_cast<double>(++done) / total); }
    /// Reports the last fraction again: lets the callback cancel during a long step.
    void poll() { report(last_fraction_); }
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    /// Throws what the callback threw, or Cancelled when it asked to stop.
    void stop_if_cancelled() const;
    /// After the parallel part: stop_if_cancelled(), then the report that all is done.
    void finish() {
        stop_if_cancelled();
        report(1.0);
    }

private:
    ProgressCallback callback_;
    std::mutex delivering_;
    std::atomic<bool> cancelled_{false};
    std::exception_ptr failure_;
    std::atomic<double> last_fraction_{0.0};
};

}  // namespace petroscope
