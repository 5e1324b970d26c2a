#!/bin/sh
# Re-derives the lane factors from scratch: the calibration set and the hold-out mapped to OSU
# 0.18 um and timed by OpenSTA (synth_set.py --liberty osu018, about an hour of one core), the
# factors fitted by node_fit.py --lanes, then the fresh header compared with the stored
# src/cost/node_lanes_osu018.h and the proxy checked on the fresh sets. The ctest
# calibration_node_lanes (configuration resynth) runs it:
#   ctest --test-dir build -C resynth -R calibration_node_lanes --output-on-failure
# usage: node_lanes_rederive.sh GLINT CALIBRATION_REPORT REPO_ROOT WORK_DIR
set -eu
glint=$1
report=$2
root=$3
work=$4
mkdir -p "$work"
cd "$root"
python3 tests/calibration/synth_set.py "$glint" --set tests/calibration/set.txt \
  --liberty osu018 --timeout 900 -o "$work/set_osu018.json"
python3 tests/calibration/synth_set.py "$glint" --set tests/calibration/holdout.txt \
  --liberty osu018 --timeout 900 -o "$work/holdout_osu018.json"
python3 tests/calibration/node_fit.py --lanes "$glint" "$work/set_osu018.json" \
  --holdout "$work/holdout_osu018.json" -o "$work/node_lanes_osu018.h"
"$report" "$work/set_osu018.json"
"$report" "$work/holdout_osu018.json"
if diff -u src/cost/node_lanes_osu018.h "$work/node_lanes_osu018.h"; then
  echo "PASS: lane factors re-derived as stored"
else
  echo "FAIL: the re-derived lane factors differ from the stored ones (above)"
  exit 1
fi
