// The warning hook of error.h: stderr by default, replaceable for tests.
#include "src/core/error.h"

#include <cstdio>
#include <mutex>

namespace rsl {
namespace {

std::mutex& warning_mutex() {
    static std::mutex mutex;
    return mutex;
}

WarningHandler& installed_handler() {
    static WarningHandler handler;
    return handler;
}

}  // namespace

WarningHandler set_warning_handler(WarningHandler handler) {
    std::lock_guard lock(warning_mutex());
    std::swap(installed_handler(), handler);
    return handler;
}

void emit_warning(const std::string& message) {
    std::lock_guard lock(warning_mutex());
    if (const WarningHandler& handler = installed_handler()) {
        handler(message);
        return;
    }
    std::fprintf(stderr, "rsl: warning: %s\n", message.c_str());
    std::fflush(stderr);
}

}  // namespace rsl
