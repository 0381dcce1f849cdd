#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz, clang, ASan + UBSan) in build-fuzz/ and runs each
# for SECONDS (default 60) under a 2 GB memory limit and a 10 s limit per input. The seeds are
# tests/fuzz/corpus/<kind>/ plus the examples (models) and examples/synthesis (tasks); what the
# run finds new goes to build-fuzz/corpus/<harness>/, kept between runs. A crash, a sanitizer
# report, a timeout or an out-of-memory input fails the script, and libFuzzer leaves the input in
# build-fuzz/findings/; turn it into a regression (tests/fuzz/regressions/, docs/fuzzing.md).
# NBAR_FUZZ_SEED fixes libFuzzer's random seed (CI sets it, so that its short runs mutate the same
# way each time and a run that fails here fails the same way on a developer's machine); unset,
# each run explores anew.
#   scripts/fuzz.sh [SECONDS] [HARNESS...]     e.g. scripts/fuzz.sh 3600 fuzz_check
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
shift || true
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then harnesses=(fuzz_model_reader fuzz_task_reader fuzz_law fuzz_check fuzz_sketch); fi
build="${NBAR_FUZZ_BUILD:-$root/build-fuzz}"
jobs="$(nproc)"
. "$root/scripts/cmake-options.sh"
configure_options "$build"

# -O1 with line tables only, as OSS-Fuzz builds: reports give file:line, and clang compiles the
# instrumented library in 3.6 minutes on 2 cores, where -O2 -g took over 15.
cmake -S "$root" -B "$build" -DNBAR_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" "${options[@]}" >/dev/null
cmake --build "$build" -j"$jobs" --target "${harnesses[@]}"

# The seeds of each harness: its own folder, and the project's example files of its kind.
seeds_of() {
  case "$1" in
    fuzz_model_reader | fuzz_check) echo "$root/tests/fuzz/corpus/model" "$build/seeds/examples" ;;
    fuzz_task_reader) echo "$root/tests/fuzz/corpus/task" "$root/examples/synthesis" ;;
    fuzz_law) echo "$root/tests/fuzz/corpus/law" ;;
    fuzz_sketch) echo "$root/tests/fuzz/corpus/sketch" ;;
  esac
}
mkdir -p "$build/seeds/examples" "$build/findings"
cp "$root"/examples/*.yaml "$build/seeds/examples/"

# One harness's run; its output goes to $build/<harness>.log. Fails on a finding.
run_harness() {
  local harness="$1" corpus="$build/corpus/$1"
  mkdir -p "$corpus"
  # shellcheck disable=SC2046
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -max_len=65536 -dict="$root/tests/fuzz/nbar.dict" -artifact_prefix="$build/findings/$harness-" \
    -print_final_stats=1 ${NBAR_FUZZ_SEED:+-seed="$NBAR_FUZZ_SEED"} "$corpus" $(seeds_of "$harness") \
    2>"$build/$harness.log"
}

# The harnesses run side by side, one per core: each still has a core for its SECONDS, and the
# five of CI take 3 minutes instead of 5. Each leaves its exit status in $build/<harness>.status.
for harness in "${harnesses[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  echo "== $harness for ${seconds} s"
  (if run_harness "$harness"; then echo 0; else echo 1; fi >"$build/$harness.status") &
done
wait

status=0
for harness in "${harnesses[@]}"; do
  if [ "$(cat "$build/$harness.status")" != 0 ]; then
    status=1
    tail -n 60 "$build/$harness.log"
    echo "== $harness FAILED; the input is in $build/findings/"
  else
    echo "== $harness"
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb|^Done" "$build/$harness.log" || true
  fi
done
exit $status
