#!/bin/sh
# One hardening regression: runs nbar under a 2 GB address-space limit and a time limit, then
# checks its exit code, that standard error says `expected` (a fixed string, typically the
# file:line:column of the input at fault) and that standard output holds no nan, inf or null
# number. Usage: run_case.sh NBAR INPUTS_DIR limit|nolimit EXIT EXPECTED ARGS...
# It runs in INPUTS_DIR, so that messages name the inputs as the cases expect; an argument
# @TMP@ stands for a scratch directory (for files nbar writes).
set -u
nbar=$1 inputs=$2 limit=$3 want_exit=$4 expected=$5
shift 5
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
cd "$inputs" || exit 1
for arg in "$@"; do
  shift
  [ "$arg" = "@TMP@" ] && arg="$work/scratch"
  set -- "$@" "$arg"
done
(
  # 2 GB of address space (not under the sanitizers, which reserve terabytes of it)
  [ "$limit" = limit ] && ulimit -v 2000000
  exec timeout 60 "$nbar" "$@"
) >"$work/out" 2>"$work/err"
got=$?
status=0
if [ "$got" != "$want_exit" ]; then
  echo "FAIL: exit $got, expected $want_exit"
  status=1
fi
if [ -n "$expected" ] && ! grep -qF -- "$expected" "$work/err"; then
  echo "FAIL: standard error does not say: $expected"
  status=1
fi
# Numbers only: a word nan or inf, or null where JSON has a number (in a list or after a key
# other than the ones that are documented to be null).
if grep -qiwE -- '-?(nan|inf|infinity)' "$work/out"; then
  echo "FAIL: nan or inf in the output"
  status=1
fi
if grep -qE -- '(\[|,)[[:space:]]*null|"[a-z_]+": null' "$work/out" &&
   grep -E -- '(\[|,)[[:space:]]*null|"[a-z_]+": null' "$work/out" | grep -vqE '"(stop_reason|safety_factor)": null'; then
  echo "FAIL: null for a number in the JSON output"
  status=1
fi
if [ "$status" != 0 ]; then
  echo "--- standard error:"; head -c 2000 "$work/err"
  echo "--- standard output (start):"; head -c 1000 "$work/out"
fi
exit $status
