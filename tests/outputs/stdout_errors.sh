#!/bin/sh
# Standard output is checked like any output (src/cli/README.md, "Output files"): every command
# whose standard output is /dev/full (text and --json), or closed, exits 2 and says why on
# standard error, and a --report beside it is left as it was when the run failed before its end.
# Usage: stdout_errors.sh GLINT SOURCE_DIR
set -eu
glint=$1
src=$2
traces=$src/traces
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

fails=0
# expect STATUS PATTERN REDIRECT ARGS...: runs glint ARGS with standard output sent to
# REDIRECT (/dev/full, or "closed"), and checks the exit status and that stderr matches PATTERN.
expect() {
  want=$1 pattern=$2 target=$3
  shift 3
  set +e
  if [ "$target" = closed ]; then
    "$glint" "$@" >&- 2>err.txt
  else
    "$glint" "$@" >"$target" 2>err.txt
  fi
  status=$?
  set -e
  if [ "$status" -ne "$want" ]; then
    echo "FAIL: glint $* > $target: exit $status, expected $want; stderr: $(head -c 300 err.txt)"
    fails=$((fails + 1))
  elif ! grep -q "$pattern" err.txt; then
    echo "FAIL: glint $* > $target: stderr lacks '$pattern': $(head -c 300 err.txt)"
    fails=$((fails + 1))
  fi
}

full='^glint: standard output: write failed: No space left on device$'
vec=$traces/phong_basic.vec
# The same commands succeed with a writable standard output (the failures below are the output's).
"$glint" units --json >/dev/null
"$glint" eval "$vec" --unit lut >/dev/null

expect 2 "$full" /dev/full units
expect 2 "$full" /dev/full units --json
expect 2 "$full" /dev/full tau --shininess 50 --eps 1e-3
expect 2 "$full" /dev/full tau --shininess 50 --eps 1e-3 --json
expect 2 "$full" /dev/full fit --shininess 50 --degree 4
expect 2 "$full" /dev/full fit --shininess 50 --degree 4 --json
expect 2 "$full" /dev/full eval "$vec" --unit lut
expect 2 "$full" /dev/full eval "$vec" --unit lut --json
expect 2 "$full" /dev/full sim "$vec" --unit lut
expect 2 "$full" /dev/full sim "$vec" --unit lut --json
expect 2 "$full" /dev/full sim "$vec" --unit lut --mode clocked --json
expect 2 "$full" /dev/full size --budget 'lsb8<=1' "$vec"
expect 2 "$full" /dev/full size --budget 'lsb8<=1' "$vec" --json
expect 2 "$full" /dev/full sweep "$vec" --grid 'lut:bits=4..5'
expect 2 "$full" /dev/full sweep "$vec" --grid 'lut:bits=4..5' --json
expect 2 "$full" /dev/full render "$traces/scenes/small.json" -o render --unit lut
expect 2 "$full" /dev/full render "$traces/scenes/small.json" -o render --unit lut --json
expect 2 "$full" /dev/full rtl lut --vectors "$vec" -o rtl
expect 2 "$full" /dev/full rtl lut --vectors "$vec" -o rtl --json
"$glint" sweep "$vec" --grid 'lut:bits=4..5' --shard 0/2 -o s0.json >/dev/null
"$glint" sweep "$vec" --grid 'lut:bits=4..5' --shard 1/2 -o s1.json >/dev/null
expect 2 "$full" /dev/full merge s0.json s1.json -o merged.json
expect 2 "$full" /dev/full merge s0.json s1.json --json
expect 2 "$full" /dev/full help
expect 2 "$full" /dev/full help --markdown
expect 2 "$full" /dev/full help sim
expect 2 "$full" /dev/full --help
expect 2 "$full" /dev/full --version
expect 2 "$full" /dev/full sim --help
# The streams written to "-" already failed this way; the message names their option.
expect 2 "^glint: --report - (standard output): write failed: No space left on device" \
  /dev/full sim "$vec" --unit lut --report -
expect 2 "^glint: --dump - (standard output): write failed: No space left on device" \
  /dev/full eval "$vec" --unit lut --dump -
# A closed standard output.
expect 2 '^glint: standard output: write failed: Bad file descriptor$' closed units --json
expect 2 '^glint: standard output: write failed: Bad file descriptor$' closed eval "$vec" --unit lut

# A pipe whose reader has left (its end closed before glint starts): SIGPIPE ends the run, as it
# does one writing --report -; with SIGPIPE ignored the write fails with EPIPE, reported.
piped() {
  rm -f left
  ( set +e
    while [ ! -e left ]; do sleep 0.05; done
    "$@" 2>err.txt
    echo $? >status.txt ) | (exec <&-; touch left)
  cat status.txt
}
status=$(piped "$glint" units --json)
[ "$status" = 141 ] || { echo "FAIL: units: exit $status, not SIGPIPE"; fails=$((fails + 1)); }
status=$(piped "$glint" sim "$vec" --unit lut --report -)
[ "$status" = 141 ] || { echo "FAIL: --report -: exit $status, not SIGPIPE"; fails=$((fails + 1)); }
status=$(trap '' PIPE; piped "$glint" units --json)
if [ "$status" != 2 ] || ! grep -q '^glint: standard output: write failed: Broken pipe$' err.txt
then
  echo "FAIL: units, SIGPIPE ignored: exit $status: $(cat err.txt)"
  fails=$((fails + 1))
fi

# A run whose --report - fails mid-way leaves its file outputs as they were.
echo old > dump.csv
expect 2 "(standard output): write failed" /dev/full sim "$vec" --unit lut --report - --dump dump.csv
[ "$(cat dump.csv)" = old ] || { echo "FAIL: dump.csv changed by a failed run"; fails=$((fails + 1)); }
leftover=$(find . -name '*.tmp.*')
[ -z "$leftover" ] || { echo "FAIL: temporaries left: $leftover"; fails=$((fails + 1)); }

[ "$fails" -eq 0 ] || { echo "FAIL: $fails cases"; exit 1; }
echo "PASS: every command reports a failed write to standard output"
