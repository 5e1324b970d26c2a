#!/usr/bin/env bash
# ctest docs.unit_keys: a checked-in file generated from the program must be exactly what the
# command prints now, so that the manual cannot drift from the code it is generated from. On a
# difference it prints the diff and the command that regenerates the file.
# Usage: check_generated.sh FILE COMMAND [ARGS...]
set -euo pipefail
file=$1
shift
generated=$(mktemp)
trap 'rm -f "$generated"' EXIT
"$@" >"$generated"
if ! diff -u "$file" "$generated"; then
  echo "FAIL: $file differs from '$*' (above: - the file, + the program)."
  echo "Regenerate it: $* > $file"
  exit 1
fi
echo "PASS: $file is what '$(basename "$1") ${*:2}' prints ($(wc -l <"$file") lines)"
