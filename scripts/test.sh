#!/usr/bin/env bash
# Installs what is missing, runs the quick start, builds everything and runs the whole test suite
# twice: an optimised build (and the engine in WebAssembly, checked against it), then one under
# AddressSanitizer and UndefinedBehaviorSanitizer; then a short
# run of each libFuzzer harness (scripts/fuzz.sh, clang, ASan + UBSan; docs/fuzzing.md).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="$(nproc)"
"$root/scripts/install-deps.sh" --tests
. "$root/scripts/cmake-options.sh"

# Each stage's heading carries the time, so a CI log shows where its minutes went.
stage() { echo "== $* [$(date -u +%H:%M:%S)]"; }

stage "Quick start: the README's first command, timed (its build is the first part of the next stage's)"
quick_start_began=$(date +%s)
"$root/scripts/quickstart.sh"
echo "the quick start took $(( $(date +%s) - quick_start_began )) s (its installs were done above)"

stage "Release build: the rest, with the tests and the benchmarks"
# Tests and benchmarks named on: the build directory the quick start left has them off.
configure_options "$root/build"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DNBAR_BUILD_TESTS=ON -DNBAR_BUILD_BENCH=ON \
  "${options[@]}" >/dev/null
cmake --build "$root/build" -j"$jobs"
stage "Release tests"
ctest --test-dir "$root/build" --output-on-failure -j"$jobs"

stage "Packages: the wheel and the .deb made from that build, installed into a scratch folder and used"
"$root/scripts/package.sh"
"$root/tests/packaging/packages_test.sh" "$root/dist"

stage "The engine in WebAssembly, its answers against the Release build's (docs/javascript.md), and the static site in Chromium (docs/web.md)"
"$root/scripts/build-wasm.sh" "$root/build-wasm" --site --test

stage "AddressSanitizer + UndefinedBehaviorSanitizer build"
# The sanitizer stage is focused where its time buys most (it was 44 of 70 minutes on 2 cores):
# - -O1 with line tables only (-g1), as OSS-Fuzz builds: reports still give file:line, and the
#   build took 21 minutes where -O2 -g took 34;
# - only the CLI and the test program;
# - not the tests that drive the web app and the report in Chromium and Node (Web.NewUser, a
#   minute of taps whose timing the sanitized server stretches, among them; their C++, the
#   server and the report writer, is under the sanitizers in the WebApi, WebServer and Report
#   tests; the Release stage runs them) nor the 20 random nine-point instances of bench/ (the
#   same solver as the NinePoint tests, 95 s each here).
configure_options "$root/build-asan"
cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNBAR_SANITIZE=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DNBAR_BUILD_BENCH=OFF "${options[@]}" >/dev/null
cmake --build "$root/build-asan" -j"$jobs" --target nbar nbar_tests
stage "AddressSanitizer + UndefinedBehaviorSanitizer tests"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$root/scripts/lsan-suppressions.txt" \
  ctest --test-dir "$root/build-asan" --output-on-failure -j"$jobs" \
  -E '^(Web\.Browser|Web\.NewUser|Web\.YamlText|Report\.PhoneAndDesktop|BenchTasks/NinePointTask\.)'

stage "libFuzzer harnesses, ${NBAR_FUZZ_SECONDS:-60} s each (clang, ASan + UBSan)"
NBAR_FUZZ_SEED="${NBAR_FUZZ_SEED:-1}" "$root/scripts/fuzz.sh" "${NBAR_FUZZ_SECONDS:-60}"
stage "done"
