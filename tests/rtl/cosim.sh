#!/bin/sh
# Co-simulation of one generated lane (ctest label `rtl`): `glint rtl` writes the Verilog, the
# testbench and its vectors; `verilator --lint-only -Wall` must find nothing in the design; the
# testbench, built by Verilator, must report PASS: every result equal to glint's C++ datapath and
# accepted and retired at the edges glint's timing model says.
# Usage: cosim.sh GLINT WORKDIR SPEC [glint rtl options...]
set -eu
glint=$1
work=$2
spec=$3
shift 3
unit=${spec%%:*}
rm -rf "$work"
mkdir -p "$work"
"$glint" rtl "$spec" "$@" -o "$work"
# Deterministic: a second run writes the same bytes.
"$glint" rtl "$spec" "$@" -o "$work/again" > /dev/null
for f in "$work"/glint_*; do cmp "$f" "$work/again/${f##*/}"; done
design="$work/glint_${unit}_lane.v $work/glint_${unit}_datapath.v"
# shellcheck disable=SC2086 # two file names
verilator --lint-only -Wall --top-module "glint_${unit}_lane" $design
# Verilator's makefiles put $OBJCACHE before every compile: with ccache, Verilator's runtime
# sources (the same in every case) and a lane already built once (glint rtl is deterministic) come
# from the cache.
if [ -z "${OBJCACHE:-}" ] && command -v ccache > /dev/null; then export OBJCACHE=ccache; fi
# -O1 C++: the model runs a few hundred thousand cycles, so compiling it fast matters more.
# shellcheck disable=SC2086
verilator --binary --top-module "glint_${unit}_tb" -Mdir "$work/obj" -CFLAGS -O1 \
  -o tb $design "$work/glint_${unit}_tb.v" > "$work/verilator.log"
# tables=ram: the testbench loads the tables from the .cfg file glint rtl wrote beside.
cfg=""
if [ -f "$work/glint_${unit}_tb.cfg" ]; then cfg="+cfg=$work/glint_${unit}_tb.cfg"; fi
# shellcheck disable=SC2086 # empty or one argument
"$work/obj/tb" +vectors="$work/glint_${unit}_tb.vec" $cfg | tee "$work/tb.log"
grep -q "^PASS" "$work/tb.log"
# The testbench must see a wrong result and a wrong retire edge: the first request's expectations
# changed in a copy of the vectors, each run must fail.
for field in 4 6; do
  awk -v f=$field 'NR == 2 { $f = ($f == "3") ? "4" : "3" } 1' "$work/glint_${unit}_tb.vec" \
    > "$work/tampered.vec"
  # (the subshell's stderr: the shell's note that the testbench aborted, as $fatal does)
  # shellcheck disable=SC2086
  if ("$work/obj/tb" +vectors="$work/tampered.vec" $cfg > "$work/tampered.log" 2>&1) 2> /dev/null; then
    echo "FAIL: the testbench passed a tampered field $field"
    exit 1
  fi
  grep -q '^FAIL' "$work/tampered.log"
done
echo "PASS: tampered vectors are caught"
# tables=ram: the tables must come from the writes: with every written word 0, the run must fail.
if [ -n "$cfg" ]; then
  awk '/^\/\// { print; next } { $3 = "0" } 1' "$work/glint_${unit}_tb.cfg" > "$work/tampered.cfg"
  if ("$work/obj/tb" +vectors="$work/glint_${unit}_tb.vec" +cfg="$work/tampered.cfg" \
    > "$work/tampered.log" 2>&1) 2> /dev/null; then
    echo "FAIL: the testbench passed with every table written 0"
    exit 1
  fi
  grep -q '^FAIL' "$work/tampered.log"
  echo "PASS: zeroed table writes are caught"
fi
