#!/usr/bin/env bash
# A sweep split into 4 shards run side by side by GNU parallel (Debian package `parallel`, which
# .ci/bootstrap installs), merged with `glint merge`: the merged JSON and CSV must be the bytes of
# the unsharded run. The recipe of src/cli/guide/sweep.md, as a test (ctest: sweep_parallel).
# Usage: parallel_merge.sh GLINT TRACES_DIR
set -euo pipefail
glint=$1
traces=$2
if ! command -v parallel >/dev/null; then
  echo "FAIL: GNU parallel is not installed (.ci/bootstrap installs it: apt-get install parallel)"
  exit 1
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/glint_sweep_parallel.XXXXXX")
trap 'rm -rf "$work"' EXIT
input=$traces/multi_light.vec
grids=(--grid 'horner:degree=2..5,in=uq1.11|uq1.15' --grid 'lut:bits=4..8' --grid pow
       --grid 'hast:d=2..4' --grid 'schlick:divider=pipelined|iterative')

"$glint" sweep "$input" "${grids[@]}" --jobs 1 -o "$work/all.json" --csv "$work/all.csv" >/dev/null
# -q: parallel quotes the command's words, so the grids' '|' reach glint unchanged.
parallel --will-cite --halt now,fail=1 -q "$glint" sweep "$input" "${grids[@]}" --jobs 1 \
  --shard {}/4 -o "$work/shard{}.json" ::: 0 1 2 3 >/dev/null
"$glint" merge "$work"/shard{0,1,2,3}.json -o "$work/merged.json" --csv "$work/merged.csv" >/dev/null
cmp "$work/all.json" "$work/merged.json"
cmp "$work/all.csv" "$work/merged.csv"
echo "PASS: 4 shards through GNU parallel merge to the unsharded run's bytes"
