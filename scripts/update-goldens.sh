#!/usr/bin/env bash
# Regenerates tests/golden/expected/ from the cases in tests/golden/cases.txt, run with the nbar
# given (default build/apps/nbar/nbar). Review `git diff tests/golden` before committing: every
# difference must be one you meant.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
nbar="$(realpath "${1:-$root/build/apps/nbar/nbar}")"
golden="$root/tests/golden"
rm -rf "$golden/expected"
while IFS= read -r line; do
  [[ -z "$line" || "$line" == \#* ]] && continue
  "$golden/run-case.sh" "$nbar" "$root" "$line" "$golden/expected/${line%%:*}"
done <"$golden/cases.txt"
echo "$(ls "$golden/expected" | wc -l) cases written to tests/golden/expected ($(du -sh "$golden/expected" | cut -f1))"
