#!/bin/sh
# `glint synth` (ctest label `rtl`): the generic flow and --liberty (tests/rtl/tiny.lib) on a small
# lane, and the refusal when yosys is not on PATH. Checks the report's fields rather than figures:
# every stage of the unit's layout has flip-flops and a depth, GE (generic) or area (liberty) > 0.
# Usage: synth.sh GLINT TINY_LIB
set -eu
glint=$1
lib=$2
json=$("$glint" synth lut:bits=4 --material "m shininess=50" --json | tr -d " \n")
for key in '"glint_synth_report":2' '"flow":"generic"' '"stage":"in"' '"stage":"lookup"' \
  '"stage":"interp"' '"stage":"lane"'; do
  echo "$json" | grep -q "$key" || { echo "FAIL: generic report lacks $key: $json"; exit 1; }
done
echo "$json" | grep -Eq '"ge":[1-9]' || { echo "FAIL: no GE > 0: $json"; exit 1; }
echo "$json" | grep -Eq '"flip_flops":[1-9]' || { echo "FAIL: no flip-flops: $json"; exit 1; }
json=$("$glint" synth lut:bits=4 --material "m shininess=50" --liberty "$lib" --json | tr -d " \n")
echo "$json" | grep -q '"flow":"liberty"' || { echo "FAIL: liberty flow: $json"; exit 1; }
echo "$json" | grep -Eq '"area_um2":[1-9]' || { echo "FAIL: no library area: $json"; exit 1; }
# tiny.lib has no delay tables: the area, and why there is no timing.
echo "$json" | grep -q '"timing":null' || { echo "FAIL: timing of an area-only library: $json"; exit 1; }
echo "$json" | grep -q '"timing_unavailable":' || { echo "FAIL: no reason for no timing: $json"; exit 1; }
echo "$json" | grep -q '"DFF":' || { echo "FAIL: no library flip-flop cell: $json"; exit 1; }
# Without yosys on PATH: exit 2 and a message naming it.
set +e
msg=$(PATH=/nonexistent "$glint" synth lut --material 'm shininess=50' 2>&1)
status=$?
set -e
[ "$status" -eq 2 ] || { echo "FAIL: exit $status without yosys"; exit 1; }
echo "$msg" | grep -q 'yosys' || { echo "FAIL: message does not name yosys: $msg"; exit 1; }
echo "PASS: glint synth"
