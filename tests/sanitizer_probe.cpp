// Deliberate undefined behaviour and a heap overflow, for the sanitized
// build only (RSL_SANITIZE): its ctest cases check that each sanitizer
// reports and ends the program with a failure, so that a sanitizer that
// silently stopped working would fail CI too (docs/design/FUZZING.md).
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    volatile int largest = std::numeric_limits<int>::max();
    if (mode == "ubsan") {  // signed overflow: UBSan
        const int sum = largest + argc;
        std::printf("%d\n", sum);
        return 0;
    }
    if (mode == "asan") {  // one past the end of a heap block: ASan
        std::vector<int> values(4, 1);
        volatile int past_end = 3 + argc - 1;
        std::printf("%d\n", values.data()[past_end + 1]);
        return 0;
    }
    std::fprintf(stderr, "usage: %s ubsan|asan\n", argv[0]);
    return 2;
}
