#!/bin/bash
# `nbar solve` writes CSV as the sweep solves it and keeps no sample, so its memory does not grow
# with the number of steps: a four-bar solved over 1 000 001 steps must run under a 256 MB
# address-space limit. Keeping the sweep (about 650 bytes per step for this model: the samples
# and the table's rows) would need about 650 MB. Also checks that the CSV has every row.
#   streamed_csv_memory.sh NBAR MODEL
set -u
nbar=$1 model=$2
steps=1000001
out=$(mktemp)
trap 'rm -f "$out"' EXIT
(ulimit -v $((256 * 1024)) && exec "$nbar" solve "$model" --steps $steps --order 1 -o "$out")
code=$?
if [ $code -ne 0 ]; then
  echo "streamed_csv_memory: nbar solve --steps $steps exited with $code under a 256 MB limit" >&2
  exit 1
fi
rows=$(($(wc -l < "$out") - 1))
if [ "$rows" -ne $steps ]; then
  echo "streamed_csv_memory: $rows rows written, expected $steps" >&2
  exit 1
fi
echo "ok: $rows rows under a 256 MB address-space limit"
