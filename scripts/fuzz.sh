#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/, clang-14, ASan + UBSan) and runs them
# (docs/design/FUZZING.md).
#   scripts/fuzz.sh [READER|all] [SECONDS] [JOBS]
#     READER: hdr exr obj gltf glb scene rslf rslv (default: all, one after another)
#     SECONDS: per fuzzer (default 60); JOBS: fuzzers run at once (default 1)
# New inputs go to $work/READER/corpus (the committed seeds in fuzz/corpus/READER
# are only read), findings to $work/READER/crash-*, oom-*, timeout-*, leak-*,
# each fuzzer's log to $work/READER/log. A hang over 10 s, an allocation or
# resident size over 2 GB, a sanitizer report or an exception other than
# rsl::Error is a finding. Exit status 1 when any fuzzer found something.
# Environment: RSL_FUZZ_BUILD_DIR (default build-fuzz), RSL_FUZZ_WORK_DIR
# (default $build/fuzz-work).
set -euo pipefail
cd "$(dirname "$0")/.."
readers=(hdr exr obj gltf glb scene rslf rslv)
which=${1:-all}
seconds=${2:-60}
jobs=${3:-1}
build=${RSL_FUZZ_BUILD_DIR:-build-fuzz}
work=${RSL_FUZZ_WORK_DIR:-$build/fuzz-work}
if [ "$which" != all ]; then
  [[ " ${readers[*]} " == *" $which "* ]] || { echo "usage: $0 [${readers[*]// /|}|all] [SECONDS] [JOBS]" >&2; exit 2; }
  readers=("$which")
fi

echo "== configure + build the fuzzers ($build, clang-14)"
# The same settings as scripts/sanitize.sh, so that the two can share a build.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang-14 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DRSL_FUZZ=ON -DRSL_BUILD_GL=OFF >/dev/null
cmake --build "$build" --parallel "$(nproc)" --target fuzzers

# One fuzzer: its summary line on stdout, 1 when it found something.
run_one() {
  local reader=$1 dir="$work/$1"
  mkdir -p "$dir/corpus"
  local dict=() words="fuzz/dict/${1/glb/gltf}.dict"  # glb's JSON chunk is glTF's
  [ -f "$words" ] && dict=(-dict="$words")
  local status=0
  "$build/fuzz/fuzz_$reader" "$dir/corpus" "fuzz/corpus/$reader" "${dict[@]}" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$dir/" >"$dir/log" 2>&1 || status=$?
  local last execs speed
  last=$(grep -E '^#[0-9]+' "$dir/log" | tail -1 || true)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  local corpus
  corpus=$(find "$dir/corpus" "fuzz/corpus/$reader" -type f | wc -l)
  if [ "$status" -ne 0 ]; then
    echo "$reader: FINDING (status $status) after ${execs:-?} runs; see $dir/log and $dir/"
    grep -m3 -E 'ERROR|rsl fuzz finding|SUMMARY' "$dir/log" | sed 's/^/  /' || true
    return 1
  fi
  echo "$reader: ${seconds} s, ${execs:-?} runs, ${speed:-?} exec/s, corpus $corpus files; ${last#* }"
}

echo "== fuzzing ${readers[*]}, $seconds s each, $jobs at a time; work folder $work"
failed=0 running=0
for reader in "${readers[@]}"; do
  if ((running >= jobs)); then  # the next one starts when any ends
    wait -n || failed=1
    running=$((running - 1))
  fi
  run_one "$reader" &
  running=$((running + 1))
done
for ((; running > 0; running--)); do wait -n || failed=1; done
exit $failed
