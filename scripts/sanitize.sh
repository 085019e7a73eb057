#!/usr/bin/env bash
# The sanitizer pass of CI (docs/design/FUZZING.md): one clang-14 build with
# AddressSanitizer and UBSan (RSL_FUZZ=ON, so the same build holds the
# fuzzers), the test suite run in it, then every fuzzer for a short time.
# Any sanitizer report fails its test or fuzzer (UBSan does not recover).
#   scripts/sanitize.sh [FUZZ_SECONDS]     (default 30 per fuzzer; 0: none)
# The GL renderer and viewer are left out of this build (RSL_BUILD_GL=OFF):
# Mesa's llvmpipe is not built with the sanitizers, and their tests stay on
# the plain build. So are the Python module and the packaging tests
# (RSL_BUILD_PYTHON=OFF; tests/CMakeLists.txt): a sanitized library loads only
# into a sanitized host. Environment: RSL_SANITIZE_BUILD_DIR (default build-sanitize).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
build=${RSL_SANITIZE_BUILD_DIR:-build-sanitize}
start=$(date +%s)

# ccache shares objects between clones of the tree (a CI run in a fresh
# clone reuses what the session built): paths under the tree are hashed
# relative to it, and the build folder's own path is left out.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
echo "== configure + build ($build: clang-14, ASan + UBSan, no GL)"
# RSL_NATIVE=ON: the same CPU extensions as the plain build of scripts/quickstart.sh.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang-14 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DRSL_NATIVE=ON -DRSL_FUZZ=ON -DRSL_BUILD_GL=OFF -DRSL_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" --parallel "$(nproc)"
built=$(date +%s)

echo "== the test suite under ASan + UBSan"
# Leaks are reported too (LeakSanitizer); a report ends the program with status 1.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# bench-scale-smoke is left to the plain build: it times a benchmark's plumbing,
# runs 3 minutes under ASan, and its code paths are the renderer's, tested here.
(cd "$build" && ctest --output-on-failure --parallel "$(nproc)" --timeout 1800 -E '^bench-scale-smoke$')
tested=$(date +%s)

if [ "$seconds" -gt 0 ]; then
  RSL_FUZZ_BUILD_DIR="$build" RSL_FUZZ_WORK_DIR="$build/fuzz-ci" scripts/fuzz.sh all "$seconds" "$(nproc)"
fi
echo "== sanitizers: build $((built - start)) s, tests $((tested - built)) s, fuzzers $(($(date +%s) - tested)) s"
