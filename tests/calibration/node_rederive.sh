#!/bin/sh
# Re-derives the node constants from scratch: the primitives mapped to OSU 0.18 um and timed by
# OpenSTA (primitives.py --liberty osu018, 3 minutes of one core), fitted by node_fit.py, and
# compares the header with the stored src/cost/node_osu018.h and the CSV with the stored one.
# The ctest calibration_node_primitives (configuration resynth) runs it:
#   ctest --test-dir build -C resynth -R calibration_node_primitives --output-on-failure
# usage: node_rederive.sh REPO_ROOT WORK_DIR
set -eu
root=$1
work=$2
mkdir -p "$work"
python3 "$root/tests/calibration/primitives.py" --liberty osu018 -o "$work/primitives_osu018.csv"
python3 "$root/tests/calibration/node_fit.py" --primitives "$work/primitives_osu018.csv" \
  -o "$work/node_osu018.h"
# The CSV's first two lines name the flow and the command: compare the data.
tail -n +3 "$root/tests/calibration/primitives_osu018.csv" > "$work/stored.csv"
tail -n +3 "$work/primitives_osu018.csv" > "$work/fresh.csv"
if diff -u "$work/stored.csv" "$work/fresh.csv" && \
   diff -u "$root/src/cost/node_osu018.h" "$work/node_osu018.h"; then
  echo "PASS: node constants re-derived as stored"
else
  echo "FAIL: the re-derived primitives or constants differ from the stored ones (above)"
  exit 1
fi
