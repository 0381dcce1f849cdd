#!/usr/bin/env bash
# One regression of tests/fuzz/regressions/cases.txt: runs `nbar ARGS...` in the regressions
# folder under a 2 GB address-space limit (under the sanitizers, which reserve far more address
# space than they use, a 2 GB resident limit instead) and a time limit, and checks its exit code,
# that its standard error matches the expected message, and that its standard output holds no
# nan, inf or null number. @TMP@ in an argument stands for a scratch path (for files nbar writes: @TMP@.svg).
#   run_regression.sh NBAR REGRESSIONS_DIR EXIT_CODE MESSAGE_REGEX ARGS...
set -uo pipefail
nbar="$1" dir="$2" want_code="$3" want_message="$4"
shift 4
cd "$dir" || exit 2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
args=()
for arg in "$@"; do
  args+=("${arg//@TMP@/$work/scratch}")
done
if [ "${NBAR_SANITIZED:-0}" = 1 ]; then
  export ASAN_OPTIONS="${ASAN_OPTIONS:-}:hard_rss_limit_mb=2048:allocator_may_return_null=0"
else
  ulimit -v 2097152
fi
timeout 120 "$nbar" "${args[@]}" >"$work/out" 2>"$work/err"
code=$?
if [ "$code" -eq 124 ]; then echo "FAIL: nbar $* ran past the time limit"; exit 1; fi
if [ "$code" -ne "$want_code" ]; then
  echo "FAIL: nbar $* exited $code, expected $want_code"; head -c 2000 "$work/err"; exit 1
fi
if [ -n "$want_message" ] && ! grep -Eq -- "$want_message" "$work/err"; then
  echo "FAIL: nbar $* said:"; head -c 2000 "$work/err"; echo; echo "expected a match of: $want_message"; exit 1
fi
# Numbers only: a word nan or inf, or null where JSON has a number (in a list, or after a key
# other than those documented to be null).
if grep -qiwE -- '-?(nan|inf|infinity)' "$work/out"; then
  echo "FAIL: nan or inf in the output of nbar $*"; head -c 1000 "$work/out"; exit 1
fi
if grep -E -- '(\[|,)[[:space:]]*null|"[a-z_]+": null' "$work/out" | grep -vqE '"(stop_reason|safety_factor)": null'; then
  echo "FAIL: null for a number in the JSON output of nbar $*"; head -c 1000 "$work/out"; exit 1
fi
echo "ok: nbar $* -> $code: $(head -c 300 "$work/err")"
