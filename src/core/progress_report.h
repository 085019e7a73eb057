#pragma once
// Progress lines with elapsed time and time left, for long bakes. Thread-safe:
// worker threads report fractions; a line is printed at most every half second
// (to stderr, so stdout stays machine-readable).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>

namespace rsl {

class ProgressReport {
public:
    ProgressReport(std::string label, bool enabled) : label_(std::move(label)), enabled_(enabled) {}

    // A ProgressCallback (src/core/progress.h) for loops over `total` items.
    void operator()(size_t done, size_t total) { update(double(done) / double(std::max<size_t>(total, 1))); }

    // fraction in [0, 1] of the whole job.
    void update(double fraction) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const double elapsed = seconds();
        if (elapsed - last_print_ < 0.5 && fraction < 1.0) return;
        last_print_ = elapsed;
        fraction = std::clamp(fraction, 0.0, 1.0);
        if (fraction > 0.02) {
            const double left = elapsed * (1.0 - fraction) / fraction;
            std::fprintf(stderr, "\r%s: %5.1f%%  %.1f s elapsed, ~%.0f s left   ", label_.c_str(), 100 * fraction,
                         elapsed, left);
        } else {
            std::fprintf(stderr, "\r%s: %5.1f%%  %.1f s elapsed   ", label_.c_str(), 100 * fraction, elapsed);
        }
        std::fflush(stderr);
    }
    void finish(const std::string& summary) {
        if (!enabled_) return;
        std::fprintf(stderr, "\r%s: done in %.1f s%s%s          \n", label_.c_str(), seconds(),
                     summary.empty() ? "" : ", ", summary.c_str());
    }
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::string label_;
    bool enabled_;
    std::mutex mutex_;
    double last_print_ = -1;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace rsl
