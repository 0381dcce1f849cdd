#!/usr/bin/env bash
# The golden-output test: every case of cases.txt run with NBAR must give exactly the expected
# exit code, standard output, standard error and files. check.sh NBAR [CASE_NAME_FILTER]
set -uo pipefail
nbar="$(realpath "$1")" filter="${2:-}"
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
while IFS= read -r line; do
  [[ -z "$line" || "$line" == \#* ]] && continue
  name="${line%%:*}"
  [[ -n "$filter" && "$name" != *"$filter"* ]] && continue
  "$here/run-case.sh" "$nbar" "$root" "$line" "$work/$name"
  if diff -r "$here/expected/$name" "$work/$name" >"$work/$name.diff" 2>&1; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED $name: nbar ${line#*: }"
    head -n 12 "$work/$name.diff"
    echo "  (if the change is intended: scripts/update-goldens.sh, then review git diff tests/golden)"
  fi
done <"$here/cases.txt"
echo "golden outputs: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
