#!/usr/bin/env bash
# One regression of tests/fuzz/regressions/cases.txt: runs `nbar ARGS...` in the regressions
# folder under a 2 GB address-space limit (under the sanitizers, which reserve far more address
# space than they use, a 2 GB resident limit instead) and a time limit, and checks its exit code
# and that its standard error matches the expected message.
#   run_regression.sh NBAR REGRESSIONS_DIR EXIT_CODE MESSAGE_REGEX ARGS...
set -uo pipefail
nbar="$1" dir="$2" want_code="$3" want_message="$4"
shift 4
cd "$dir" || exit 2
err="$(mktemp)"
trap 'rm -f "$err"' EXIT
if [ "${NBAR_SANITIZED:-0}" = 1 ]; then
  export ASAN_OPTIONS="${ASAN_OPTIONS:-}:hard_rss_limit_mb=2048:allocator_may_return_null=0"
else
  ulimit -v 2097152
fi
timeout 120 "$nbar" "$@" >/dev/null 2>"$err"
code=$?
if [ "$code" -eq 124 ]; then echo "FAIL: nbar $* ran past the time limit"; exit 1; fi
if [ "$code" -ne "$want_code" ]; then
  echo "FAIL: nbar $* exited $code, expected $want_code"; head -c 2000 "$err"; exit 1
fi
if ! grep -Eq -- "$want_message" "$err"; then
  echo "FAIL: nbar $* said:"; head -c 2000 "$err"; echo; echo "expected a match of: $want_message"; exit 1
fi
echo "ok: nbar $* -> $code: $(head -c 300 "$err")"
