#pragma once
// Precompute timing of the baselines: wall seconds, and seconds spent inside
// parallel tasks summed over the threads that ran them (docs/BASELINES.md
// reports precompute as thread-seconds, so that stages sharing one pass can
// be told apart).
#include <chrono>
#include <mutex>

namespace rsl::baselines_timing {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

class ThreadSeconds {
public:
    template <class Work>
    void time(Work&& work) {
        const auto start = Clock::now();
        work();
        const double seconds = seconds_since(start);
        std::lock_guard<std::mutex> lock(mutex_);
        total_ += seconds;
    }
    double total() const { return total_; }

private:
    std::mutex mutex_;
    double total_ = 0;
};

}  // namespace rsl::baselines_timing
