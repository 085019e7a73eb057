#pragma once
// Errors that reach the user name the file (or parameter) and what is wrong.
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <fmt/std.h>

// rsl::Error and rsl::InternalError themselves are public (the API throws them).
#include "rsl/error.h"

namespace rsl {

// "path: message" — the one shape of every input error. An empty path (a
// scene built in code, rsl::api) leaves just the message.
template <typename... Args>
[[noreturn]] void throw_file_error(const std::filesystem::path& path, fmt::format_string<Args...> format,
                                   Args&&... args) {
    std::string message = fmt::format(format, std::forward<Args>(args)...);
    if (path.empty()) throw Error(std::move(message));
    throw Error(fmt::format("{}: {}", path.string(), message));
}

template <typename... Args>
[[noreturn]] void throw_error(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// Warnings: problems the program works around but the user must hear about
// (degenerate triangles dropped, ...). Each is one line; by default it goes to
// stderr as "rsl: warning: <message>". Library code calls warn()/warn_file(),
// never prints itself, so tests and tools can capture warnings.
using WarningHandler = std::function<void(const std::string& message)>;
// Installs `handler` (empty: back to stderr) and returns the previous one.
// Thread-safe; warnings from parallel code are delivered one at a time (so a
// handler must not warn itself).
WarningHandler set_warning_handler(WarningHandler handler);
void emit_warning(const std::string& message);

template <typename... Args>
void warn(fmt::format_string<Args...> format, Args&&... args) {
    emit_warning(fmt::format(format, std::forward<Args>(args)...));
}
// "path: message", the shape of throw_file_error.
template <typename... Args>
void warn_file(const std::filesystem::path& path, fmt::format_string<Args...> format, Args&&... args) {
    emit_warning(fmt::format("{}: {}", path.string(), fmt::format(format, std::forward<Args>(args)...)));
}

// A broken invariant (rsl::InternalError): a bug in rsl, never the user's
// input. `rsl` prints it as "internal error" and exits with status 2, apart
// from bad input (rsl::Error, status 1), so a test can tell the two apart.
template <typename... Args>
[[noreturn]] void throw_internal_error(fmt::format_string<Args...> format, Args&&... args) {
    throw InternalError(fmt::format(format, std::forward<Args>(args)...));
}

// CHECK-style invariant that prints both sides, as pbrt's CHECK_EQ does.
#define RSL_CHECK(cond)                                                                                   \
    do {                                                                                                  \
        if (!(cond)) ::rsl::throw_internal_error("{}:{}: check failed: {}", __FILE__, __LINE__, #cond);   \
    } while (0)
#define RSL_CHECK_OP(a, op, b)                                                                            \
    do {                                                                                                  \
        auto&& rsl_a_ = (a);                                                                              \
        auto&& rsl_b_ = (b);                                                                              \
        if (!(rsl_a_ op rsl_b_))                                                                          \
            ::rsl::throw_internal_error("{}:{}: check failed: {} {} {} ({} vs {})", __FILE__, __LINE__, #a, \
                                        #op, #b, rsl_a_, rsl_b_);                                         \
    } while (0)
#define RSL_CHECK_EQ(a, b) RSL_CHECK_OP(a, ==, b)
#define RSL_CHECK_LE(a, b) RSL_CHECK_OP(a, <=, b)
#define RSL_CHECK_LT(a, b) RSL_CHECK_OP(a, <, b)
#define RSL_CHECK_GE(a, b) RSL_CHECK_OP(a, >=, b)
#define RSL_CHECK_GT(a, b) RSL_CHECK_OP(a, >, b)

// The same for hot loops: checked in Debug builds, compiled out (the
// condition not evaluated) in Release.
#ifdef NDEBUG
#define RSL_DCHECK(cond) \
    do {                 \
    } while (0)
#else
#define RSL_DCHECK(cond) RSL_CHECK(cond)
#endif

}  // namespace rsl
