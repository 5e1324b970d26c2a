#!/bin/bash
# The long run of the co-simulation (ctest -C long -L long: rtl_random): COUNT random accepted
# specs of every unit (formats, table sizes, orders, degrees, fit methods and domains, matching,
# divider kinds, skip, tables=rom|ram) on random shipped traces under random backpressure, each through
# tests/rtl/cosim.sh. A spec glint refuses (exit 2: e.g. a table too wide) is drawn again.
# Usage: random_specs.sh GLINT WORKDIR COUNT [SEED]   (default seed: the time; printed, so that a
# failing draw can be repeated)
set -eu
glint=$1
work=$2
count=$3
seed=${4:-$(date +%s)}
echo "seed $seed"
RANDOM=$seed
here=$(cd "$(dirname "$0")" && pwd)
traces=(traces/phong_basic.vec traces/blinn_colored.vec traces/multi_light.vec
  traces/gaussian.vec traces/hard_cases.vec traces/contract_cases.vec)
pick() { local a=("$@"); echo "${a[RANDOM % ${#a[@]}]}"; }
formats() { echo "in=$(pick uq1.8 uq1.10 uq1.12 uq1.15),out=$(pick uq1.8 uq1.10 uq1.12 uq1.15)"; }
spec() {
  unit_spec
  echo ",tables=$(pick rom rom ram)"
}
unit_spec() {
  case $((RANDOM % 5)) in
    0) echo -n "lut:$(formats),bits=$((2 + RANDOM % 9)),skip=$(pick on on off)" ;;
    1) echo -n "hast:$(formats),d=$((1 + RANDOM % 8)),match=$(pick none minimax width)" ;;
    2) echo -n "horner:$(formats),degree=$((1 + RANDOM % 8)),domain=$(pick tau full),method=$(pick ls robust minimax)" ;;
    3) echo -n "pow:$(formats),log_bits=$((4 + RANDOM % 7)),exp_bits=$((3 + RANDOM % 6)),n=$(pick uq14.4 uq12.6)" ;;
    4) echo -n "schlick:$(formats),divider=$(pick pipelined iterative),match=$(pick none minimax width)" ;;
  esac
}
done_count=0
while [ "$done_count" -lt "$count" ]; do
  s=$(spec)
  t=$(pick "${traces[@]}")
  p=$(pick 0.3 0.6 0.9 1)
  rm -rf "$work/probe"
  mkdir -p "$work"
  if ! "$glint" rtl "$s" --vectors "$t" --no-sweep -o "$work/probe" > /dev/null 2>&1; then
    continue  # not an accepted spec
  fi
  echo "== $s on $t, sink ready $p"
  seed=()
  [ "$p" = 1 ] || seed=(--seed "$RANDOM")  # an always-ready sink has no pattern to seed
  bash "$here/cosim.sh" "$glint" "$work/case" "$s" --vectors "$t" --sink-ready "$p" \
    "${seed[@]}" | grep -E '^(PASS|FAIL)'
  done_count=$((done_count + 1))
done
echo "PASS: $count random specs"
