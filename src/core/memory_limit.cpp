#include "src/core/memory_limit.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include <sys/resource.h>

#include <fmt/format.h>

#include "src/core/error.h"

namespace rsl {
namespace {

constexpr uint64_t kUnset = ~uint64_t(0);
std::atomic<uint64_t> g_limit{kUnset};
std::atomic<const char*> g_setter{"rsl::api::set_memory_limit"};

std::optional<uint64_t> meminfo_total() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    uint64_t kilobytes = 0;
    std::string unit;
    while (in >> key >> kilobytes >> unit)
        if (key == "MemTotal:") return kilobytes * 1024;
    return std::nullopt;
}

// cgroup v2's memory.max ("max" when unlimited); v1's limit_in_bytes.
std::optional<uint64_t> cgroup_limit() {
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(path);
        std::string text;
        if (!(in >> text) || text == "max") continue;
        try {
            const uint64_t bytes = std::stoull(text);
            if (bytes > 0 && bytes < (uint64_t(1) << 60)) return bytes;
        } catch (const std::exception&) {
        }
    }
    return std::nullopt;
}

}  // namespace

uint64_t default_memory_limit() {
    uint64_t machine = meminfo_total().value_or(0);
    const auto smaller = [&](uint64_t bytes) { machine = machine ? std::min(machine, bytes) : bytes; };
    if (const auto cgroup = cgroup_limit()) smaller(*cgroup);
    rlimit address_space{};  // `ulimit -v`
    if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
        smaller(uint64_t(address_space.rlim_cur));
    return machine ? machine / 5 * 4 : 0;
}

uint64_t memory_limit() {
    uint64_t limit = g_limit.load();
    if (limit != kUnset) return limit;
    const char* text = std::getenv("RSL_MEMORY_LIMIT");
    limit = text && *text ? parse_memory_size(text, "RSL_MEMORY_LIMIT") : default_memory_limit();
    uint64_t expected = kUnset;
    g_limit.compare_exchange_strong(expected, limit);
    return g_limit.load();
}

void set_memory_limit(uint64_t bytes) { g_limit.store(bytes); }

void set_memory_limit_setter(const char* name) { g_setter.store(name); }

uint64_t parse_memory_size(const std::string& text, const std::string& what) {
    if (text == "none" || text == "0") return 0;
    std::istringstream in(text);
    double value = 0;
    std::string unit;
    if (!(in >> value) || !std::isfinite(value) || value < 0) value = -1;
    in >> unit;
    std::string rest;
    const double scale = unit.empty() || unit == "B"             ? 1.0
                         : unit == "K" || unit == "KB" || unit == "KiB" ? 1024.0
                         : unit == "M" || unit == "MB" || unit == "MiB" ? 1024.0 * 1024
                         : unit == "G" || unit == "GB" || unit == "GiB" ? 1024.0 * 1024 * 1024
                         : unit == "T" || unit == "TB" || unit == "TiB" ? 1024.0 * 1024 * 1024 * 1024
                                                                        : -1.0;
    const double bytes = value * scale;
    if (value < 0 || scale < 0 || (in >> rest) || !(bytes >= 1) || bytes > 9.0e18)
        throw_error("{} '{}': not a memory size (expected a number of bytes with K, M, G or T, such as 8G, or none)",
                    what, text);
    return uint64_t(bytes);
}

std::string memory_size_text(uint64_t bytes) {
    const double b = double(bytes);
    if (b >= 1e9) return fmt::format("{:.1f} GB", b / 1e9);
    if (b >= 1e6) return fmt::format("{:.0f} MB", b / 1e6);
    if (b >= 1e3) return fmt::format("{:.0f} kB", b / 1e3);
    return fmt::format("{} bytes", bytes);
}

uint64_t image_memory_bytes(int width, int height) {
    return kImageBytesPerPixel * uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));
}

void check_memory_estimate(uint64_t estimate_bytes, const std::filesystem::path& file, const std::string& what) {
    const uint64_t limit = memory_limit();
    if (limit == 0 || estimate_bytes <= limit) return;
    throw_file_error(file,
                     "needs about {} of memory ({}), over rsl's limit of {}: make the scene smaller (fewer parts "
                     "or vertices, a coarser subdivision or fields, a smaller image), or raise the limit with {} or "
                     "RSL_MEMORY_LIMIT (docs/SCENE_FORMAT.md, \"Memory\")",
                     memory_size_text(estimate_bytes), what, memory_size_text(limit), g_setter.load());
}

}  // namespace rsl
