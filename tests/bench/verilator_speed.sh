#!/usr/bin/env bash
# glint's fast mode side by side with Verilator on the same lane, in one run (the machine is shared
# and its speed drifts: pairs, not separate runs, make the ratio fair). `glint rtl` writes the lane
# of SPEC for sim_speed's material (white, Blinn, n = 50, eps 1e-3); Verilator builds it at -O3
# with tests/bench/verilator_speed.cpp driving it; then PAIRS times, in turn, sim_speed's fast mode
# on VECTORS rows and the Verilator model for as many cycles, on the same stream (t uniform over
# [T_MIN, 1], the same generator), each pair checked to have skipped the same requests. Prints
# every run's line, then the medians and their ratio.
# With --module datapath Verilator runs the unit's datapath module alone (no comparator, no merge
# buffer, a request started every cycle: units with II = 1), the least RTL that computes the lobe;
# the skip counts are then not compared (the datapath computes every request).
# Usage: verilator_speed.sh BUILD_DIR [--spec SPEC] [--vectors N] [--pairs K] [--threads T]
#                           [--t-min T_MIN] [--module lane|datapath]
# Defaults: horner:skip=off (every request computed), 20 000 000, 5 pairs, 2 threads, -1, lane.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: verilator_speed.sh BUILD_DIR [options]}" && pwd)
shift
spec=horner:skip=off vectors=20000000 pairs=5 threads=2 t_min=-1 module=lane
while (($#)); do
  (($# >= 2)) || { echo "verilator_speed.sh: $1 needs a value" >&2; exit 2; }
  case $1 in
    --spec) spec=$2 ;;
    --vectors) vectors=$2 ;;
    --pairs) pairs=$2 ;;
    --threads) threads=$2 ;;
    --t-min) t_min=$2 ;;
    --module) module=$2 ;;
    *) echo "verilator_speed.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift 2
done
command -v verilator > /dev/null || { echo "verilator_speed.sh: verilator not found" >&2; exit 2; }
case $module in
  lane | datapath) ;;
  *) echo "verilator_speed.sh: --module is lane or datapath, not '$module'" >&2; exit 2 ;;
esac
unit=${spec%%:*}
work="$build/verilator_speed/$module-$(printf '%s' "$spec" | tr -c 'A-Za-z0-9_.=-' '_')"
rm -rf "$work"
mkdir -p "$work"
"$build/glint" rtl "$spec" --material 'white shininess=50 lobe=blinn' --eps 1e-3 -o "$work/rtl" \
  > "$work/rtl.log"
lane="$work/rtl/glint_${unit}_lane.v"
in_bits=$(sed -n 's/^ *input  *wire \[\([0-9]*\):0\] in_t,.*/\1/p' "$lane")
in_bits=$((in_bits + 1))
defines="-DGLINT_IN_BITS=$in_bits"
if [[ $module == datapath ]]; then
  # The lane's header: "the datapath (L = 5 stages, II = 1)".
  latency=$(sed -n 's/.*the datapath (L = \([0-9]*\) stages, II = \([0-9]*\)).*/\1 \2/p' "$lane")
  read -r latency ii <<< "$latency"
  if [[ ${ii:-} != 1 ]]; then
    echo "verilator_speed.sh: --module datapath needs II = 1; $spec has II = ${ii:-?}" >&2
    exit 2
  fi
  defines+=" -DGLINT_DATAPATH_LATENCY=$latency"
fi
echo "building Verilator's model of $spec's $module (in_t $in_bits bits) in $work" >&2
verilator --cc --exe --build -O3 --x-assign fast --x-initial fast --noassert -j 2 \
  --prefix Vlane --top-module "glint_${unit}_$module" -Mdir "$work/obj" -o verilator_speed \
  -MAKEFLAGS "OPT_FAST=-O3 OPT_SLOW=-O1" -CFLAGS "-O3 $defines" \
  "$lane" "$work/rtl/glint_${unit}_datapath.v" "$here/verilator_speed.cpp" > "$work/build.log"

glint_rates=() verilator_rates=()
for ((k = 1; k <= pairs; ++k)); do
  glint_out=$("$build/tests/sim_speed" --vectors "$vectors" --units "$spec" --threads "$threads" \
    --t-min "$t_min" 2> /dev/null)
  echo "glint     $(head -1 <<< "$glint_out")"
  glint_rates+=("$(sed -n '1s/.* \([0-9.]*\) M vectors\/s.*/\1/p' <<< "$glint_out")")
  line=$("$work/obj/verilator_speed" "$vectors" "$t_min")
  echo "verilator $line"
  verilator_rates+=("$(sed -n 's/.* \([0-9.]*\) M cycles\/s.*/\1/p' <<< "$line")")
  # The two sides ran the same requests through the same comparator: equal skip counts.
  glint_skipped=$(sed -n '2s/.* skipped \([0-9]*\).*/\1/p' <<< "$glint_out")
  verilator_skipped=$(sed -n 's/.* skipped \([0-9]*\),.*/\1/p' <<< "$line")
  if [[ $module == lane && (-z $glint_skipped || $glint_skipped != "$verilator_skipped") ]]; then
    echo "FAIL: glint skipped '$glint_skipped' requests, Verilator's lane '$verilator_skipped'"
    exit 1
  fi
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
g=$(median "${glint_rates[@]}")
v=$(median "${verilator_rates[@]}")
echo "median of $pairs pairs, $spec ($module), $vectors rows, t in [$t_min, 1]: glint fast mode ($threads threads) $g M vectors/s, Verilator $v M cycles/s (one request a cycle): glint/Verilator $(awk -v g="$g" -v v="$v" 'BEGIN { printf "%.2f", g / v }')"
