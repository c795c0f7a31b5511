#pragma once
// One long-lived thread that runs the server's renders one at a time, whichever request thread asks. Its
// OpenMP team and its allocator arena stay warm between requests: fresh threads each paid for new OpenMP
// threads and first touches of fresh memory (page faults), about 100 ms per 512² view on a 2-core VM.
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

namespace petroscope::serve {

class RenderThread {
public:
    RenderThread();
    ~RenderThread();
    RenderThread(const RenderThread&) = delete;
    RenderThread& operator=(const RenderThread&) = delete;

    /// Runs `work` on the render thread after the work asked for before it; returns its result or rethrows
    /// what it threw.
    template <typename Work>
    auto run(Work work) -> decltype(work()) {
        std::packaged_task<decltype(work())()> task(std::move(work));
        auto result = task.get_future();
        post([&task] { task(); });
        return result.get();
    }

private:
    void post(std::function<void()> job);
    void loop();

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> jobs_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace petroscope::serve
