#!/usr/bin/env bash
# Installs what is missing, builds everything and runs the whole test suite twice: an
# optimised build, then one under AddressSanitizer and UndefinedBehaviorSanitizer; then a short
# run of each libFuzzer harness (scripts/fuzz.sh, clang, ASan + UBSan; docs/fuzzing.md).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="$(nproc)"
"$root/scripts/install-deps.sh"
# ccache, when it is installed, makes rebuilds fast; nothing needs it.
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

echo "== Release build and tests"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
cmake --build "$root/build" -j"$jobs"
ctest --test-dir "$root/build" --output-on-failure -j"$jobs"

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNBAR_SANITIZE=ON \
  -DNBAR_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
cmake --build "$root/build-asan" -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$root/scripts/lsan-suppressions.txt" \
  ctest --test-dir "$root/build-asan" --output-on-failure -j"$jobs"

echo "== libFuzzer harnesses, ${NBAR_FUZZ_SECONDS:-60} s each (clang, ASan + UBSan)"
"$root/scripts/fuzz.sh" "${NBAR_FUZZ_SECONDS:-60}"
