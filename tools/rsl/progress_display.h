#pragma once
// How the tools (rsl's commands, benchmarks, demos) draw the progress the
// libraries report through callbacks (the libraries never print): one line
// per job on stderr, so that stdout stays machine-readable. On a terminal
// the line is redrawn in place, with the time elapsed and left; on a file
// or a pipe (a CI log) a plain line is written when a job starts, every
// ten seconds at most, and when it ends.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

namespace rsl::cli {

class ProgressDisplay {
public:
    // `enabled` false: nothing is drawn (a --quiet run).
    explicit ProgressDisplay(bool enabled = true, std::FILE* out = stderr)
        : out_(out), enabled_(enabled), terminal_(isatty(fileno(out)) != 0) {}
    ProgressDisplay(const ProgressDisplay&) = delete;
    ProgressDisplay& operator=(const ProgressDisplay&) = delete;
    ~ProgressDisplay() { end_line(); }

    // Job `what` is `fraction` done ([0, 1]; 1 ends it). Thread-safe: the
    // libraries call it from their worker threads. A job whose first report
    // is its end (a field read from the cache) draws nothing: the tool says
    // what it found.
    void operator()(const std::string& what, double fraction) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const double now = seconds();
        fraction = std::clamp(fraction, 0.0, 1.0);
        auto [job, started] = jobs_.try_emplace(what, Job{now, -1.0, fraction >= 1.0});
        Job& j = job->second;
        if (j.done) return;
        const double elapsed = now - j.start;
        if (fraction >= 1.0) {
            j.done = true;
            draw(fmt_line(what, "done in", elapsed), true);
            return;
        }
        const double interval = terminal_ ? 0.5 : 10.0;
        if (!started && now - j.last_draw < interval) return;
        j.last_draw = now;
        std::string line = what + ": " + std::to_string(int(100 * fraction)) + "%";
        if (fraction > 0.02) line += ", ~" + std::to_string(int(elapsed * (1.0 - fraction) / fraction + 0.5)) + " s left";
        draw(line, !terminal_);
    }
    // A line of its own (a job's summary); on a terminal it takes the place
    // of the line being redrawn, which the job's next report draws again.
    void note(const std::string& line) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        draw(line, true);
    }

private:
    struct Job {
        double start, last_draw;
        bool done;
    };
    static std::string fmt_line(const std::string& what, const char* verb, double seconds) {
        char number[32];
        std::snprintf(number, sizeof number, "%.1f", seconds);
        return what + ": " + verb + " " + number + " s";
    }
    // On a terminal an unfinished line is redrawn over the last one; a
    // finished one ends it. Elsewhere every line ends.
    void draw(const std::string& line, bool finished) {
        if (terminal_) {
            std::fprintf(out_, "\r%s\033[K", line.c_str());
            if (finished) std::fputc('\n', out_);
            open_line_ = !finished;
        } else {
            std::fprintf(out_, "%s\n", line.c_str());
        }
        std::fflush(out_);
    }
    void end_line() {
        if (open_line_) std::fputc('\n', out_), open_line_ = false;
    }
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    std::FILE* out_;
    bool enabled_, terminal_;
    bool open_line_ = false;
    std::mutex mutex_;
    std::map<std::string, Job> jobs_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// A progress callback (what, fraction) drawn by a display of its own, which
// lives as long as the callback's copies; empty when !enabled. For calls
// that take one, as prepare_render's SetupOptions::progress.
inline std::function<void(const std::string&, double)> drawn_progress(bool enabled = true) {
    if (!enabled) return {};
    auto display = std::make_shared<ProgressDisplay>();
    return [display](const std::string& what, double fraction) { (*display)(what, fraction); };
}

}  // namespace rsl::cli
