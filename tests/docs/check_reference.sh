#!/usr/bin/env bash
# ctest docs.reference: the checked-in option reference (src/cli/reference.md) must be exactly what
# the program prints with `glint help --markdown`, so that no option, range or default in the
# manual can drift from what the parser accepts. On a difference it prints the diff and the
# command that regenerates the file.
# Usage: check_reference.sh GLINT REFERENCE_MD
set -euo pipefail
glint=$1
reference=$2
generated=$(mktemp)
trap 'rm -f "$generated"' EXIT
"$glint" help --markdown >"$generated"
if ! diff -u "$reference" "$generated"; then
  echo "FAIL: $reference differs from 'glint help --markdown' (above: - the file, + the program)."
  echo "Regenerate it: build/glint help --markdown > src/cli/reference.md"
  exit 1
fi
echo "PASS: $reference is the program's own reference ($(wc -l <"$reference") lines)"
