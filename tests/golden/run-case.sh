#!/usr/bin/env bash
# Runs one golden case: run-case.sh NBAR ROOT CASE_LINE DEST. Writes DEST/stdout, DEST/stderr,
# DEST/code and DEST/files/ (what the case wrote to $OUT), with $OUT's real path written back
# as $OUT.
set -euo pipefail
nbar="$1" root="$2" line="$3" dest="$4"
args="${line#*: }"
mkdir -p "$dest/files"
out="$(cd "$dest/files" && pwd)"
cd "$root"
# The arguments are words without quotes or spaces inside them; $OUT is replaced first.
read -r -a words <<<"${args//\$OUT/$out}"
set +e
"$nbar" "${words[@]}" >"$dest/stdout" 2>"$dest/stderr"
echo $? >"$dest/code"
set -e
sed -i "s|$out|\$OUT|g" "$dest/stdout" "$dest/stderr"
rmdir --ignore-fail-on-non-empty "$dest/files"  # git keeps no empty folders
