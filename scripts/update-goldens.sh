#!/bin/bash
# Regenerates the expected outputs of the golden-output test (tests/apps/golden_test.cpp):
# runs NBAR_BINARY (default build/apps/nbar/nbar) over every case of tests/golden/cases.txt
# and writes tests/golden/expected/<case>.stdout, .stderr, .code and, for the cases that write
# files under $OUT, tests/golden/expected/<case>.files/...
#
#   scripts/update-goldens.sh [NBAR_BINARY] [CASE...]
#
# With CASE names, only those cases are regenerated; otherwise the whole expected/ directory is
# rebuilt from scratch (so removed cases leave no files behind).
#
# The goldens pin the output of the code BEFORE a refactor: generate them with the old binary,
# then run the test against the new one. Regenerating from the new binary hides differences.
#
# How a case runs (tests/apps/golden_test.cpp does exactly the same):
#   - every `$OUT` in the arguments is replaced by the path of a fresh empty temporary directory;
#   - the command `cd REPO && NBAR_BINARY ARGS </dev/null` runs under /bin/sh, with COLUMNS=80
#     and without NBAR_LANG;
#   - in stdout, stderr and every file written under $OUT, that directory's path is replaced by
#     `$OUT` and the binary's path by `nbar`.
set -euo pipefail
export COLUMNS=80  # text tables wrap to the terminal's width: pin it, as golden_test.cpp does
unset NBAR_LANG   # English unless a case asks with --lang, as golden_test.cpp does

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
binary=${1:-$root/build/apps/nbar/nbar}
shift || true
case $binary in /*) ;; *) binary=$PWD/$binary ;; esac
[[ -x $binary ]] || { echo "update-goldens.sh: $binary is not an executable" >&2; exit 2; }

cases=$root/tests/golden/cases.txt
expected=$root/tests/golden/expected
only=("$@")

# Replaces $2 by $3 in file $1, byte for byte (no regular expressions).
replace_in_file() {
  FROM=$2 TO=$3 perl -0777 -pi -e 's/\Q$ENV{FROM}\E/$ENV{TO}/g' "$1"
}

wanted() {
  ((${#only[@]} == 0)) && return 0
  local c
  for c in "${only[@]}"; do [[ $c == "$1" ]] && return 0; done
  return 1
}

if ((${#only[@]} == 0)); then
  rm -rf "$expected"
fi
mkdir -p "$expected"

tmp=$(mktemp -d /tmp/nbar-goldens.XXXXXX)
trap 'rm -rf "$tmp"' EXIT

count=0
declare -A seen=()
while IFS= read -r line || [[ -n $line ]]; do
  [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
  name=${line%% *}
  args=""
  [[ $line == *" "* ]] && args=${line#* }
  if [[ ! $name =~ ^[A-Za-z0-9_]+$ ]]; then
    echo "update-goldens.sh: bad case name '$name' (letters, digits, underscores)" >&2; exit 2
  fi
  [[ -n ${seen[$name]:-} ]] && { echo "update-goldens.sh: duplicate case '$name'" >&2; exit 2; }
  seen[$name]=1
  wanted "$name" || continue

  out=$tmp/$name
  mkdir -p "$out"
  command="cd '$root' && '$binary' ${args//\$OUT/$out} </dev/null"
  code=0
  /bin/sh -c "$command" >"$expected/$name.stdout" 2>"$expected/$name.stderr" || code=$?
  echo "$code" >"$expected/$name.code"
  rm -rf "$expected/$name.files"
  if [[ -n $(ls -A "$out") ]]; then
    cp -r "$out" "$expected/$name.files"
  fi
  while IFS= read -r -d '' f; do
    replace_in_file "$f" "$out" '$OUT'
    replace_in_file "$f" "$binary" 'nbar'
  done < <(find "$expected/$name".stdout "$expected/$name".stderr "$expected/$name.files" -type f -print0 2>/dev/null)
  count=$((count + 1))
  printf '%-48s exit %d\n' "$name" "$code"
done <"$cases"

echo "update-goldens.sh: $count cases from $binary into ${expected#$root/} ($(du -sh "$expected" | cut -f1))"
