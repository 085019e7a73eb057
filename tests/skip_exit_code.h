#pragma once

namespace rsl_test {

// The exit code of a test run that skipped and failed nothing (Automake's
// convention); tests/CMakeLists.txt gives it to CTest as SKIP_RETURN_CODE.
inline constexpr int kSkipExitCode = 77;

}  // namespace rsl_test
