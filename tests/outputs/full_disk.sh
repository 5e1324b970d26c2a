#!/bin/sh
# A full disk never costs a good output (src/cli/README.md, "Output files"): on a small tmpfs,
# an FST that vcd2fst cuts short (it exits 0), a --report and --dump, a render folder and Yosys's
# work folder each fail with exit 2 and a message naming the cause, keep the files that were there
# and leave no temporary. Needs root (mount); otherwise prints SKIP and exits 77.
# Usage: full_disk.sh GLINT SOURCE_DIR
set -eu
glint=$1
src=$2
vec=$src/traces/phong_basic.vec
work=$(mktemp -d)
disk=$work/disk
mkdir "$disk"
cleanup() {
  umount "$disk" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
# mount_disk KIB: a fresh tmpfs of that size on $disk.
mount_disk() {
  umount "$disk" 2>/dev/null || true
  mount -t tmpfs -o "size=$1k" glint-test "$disk"
}
if ! mount_disk 64 2>"$work/mount.txt"; then
  echo "SKIP: cannot mount a tmpfs (root needed): $(cat "$work/mount.txt")"
  exit 77
fi

fails=0
fail() {
  echo "FAIL: $*"
  fails=$((fails + 1))
}
# run EXPECTED_STATUS PATTERN ARGS...: glint ARGS, its status and stderr checked.
run() {
  want=$1 pattern=$2
  shift 2
  set +e
  "$glint" "$@" >"$work/out.txt" 2>"$work/err.txt"
  status=$?
  set -e
  [ "$status" -eq "$want" ] || fail "glint $*: exit $status, expected $want: $(head -c 400 "$work/err.txt")"
  grep -q "$pattern" "$work/err.txt" || fail "glint $*: stderr lacks '$pattern': $(head -c 400 "$work/err.txt")"
}
no_temporaries() {
  left=$(find "$1" -name '*.tmp.*' -o -name 'glint-synth.*' -o -name 'yosys-*')
  [ -z "$left" ] || fail "$2: left behind: $left"
}
kib() { echo $((($(wc -c <"$1") + 1023) / 1024)); }
# Fills the rest of $disk (what remains is less than a page).
fill() { dd if=/dev/zero of="$disk/filler" bs=4096 2>/dev/null || true; }

# 1. FST. The old trace (a short window) and the new one (the whole run) are first made on the
# normal disk: the check must pass a whole FST, and fst2vcd must read both.
cd "$work"
"$glint" sim "$vec" --unit lut --vcd old.fst --vcd-window 0:20 >/dev/null
"$glint" sim "$vec" --unit lut --vcd new.fst >/dev/null
fst2vcd -f old.fst >/dev/null && fst2vcd -f new.fst >/dev/null
[ "$(kib new.fst)" -gt $((2 * $(kib old.fst))) ] || fail "the new FST is not larger than the old"
# Room for the old files and half of the new FST: vcd2fst runs out of space and exits 0.
mount_disk $(($(kib old.fst) + $(kib old.gtkw) + $(kib new.fst) / 2 + 8))
cp old.fst old.gtkw "$disk/"
mv "$disk/old.fst" "$disk/t.fst"
mv "$disk/old.gtkw" "$disk/t.gtkw"
run 2 "vcd2fst wrote an incomplete FST" sim "$vec" --unit lut --vcd "$disk/t.fst"
grep -q "$disk/t.fst" "$work/err.txt" || fail "the FST message does not name the file"
cmp -s old.fst "$disk/t.fst" || fail "the old t.fst was changed"
cmp -s old.gtkw "$disk/t.gtkw" || fail "the old t.gtkw was changed"
fst2vcd -f "$disk/t.fst" >/dev/null || fail "the old t.fst no longer reads"
no_temporaries "$disk" "FST"

# 2. --report and --dump on a full disk: the old files stay.
mount_disk 256
echo '{"old": true}' >"$disk/r.json"
echo old >"$disk/d.csv"
fill
run 2 "No space left on device" sim "$vec" --unit lut --report "$disk/r.json" --dump "$disk/d.csv"
[ "$(cat "$disk/r.json")" = '{"old": true}' ] || fail "the old --report was changed"
[ "$(cat "$disk/d.csv")" = old ] || fail "the old --dump was changed"
no_temporaries "$disk" "--report/--dump"

# 3. A render folder on a full disk.
mount_disk 1024
mkdir "$disk/render"
echo old >"$disk/render/lut.png"
echo '{"old": true}' >"$disk/render/render.json"
fill
run 2 "No space left on device" render "$src/traces/scenes/small.json" --unit lut -o "$disk/render"
[ "$(cat "$disk/render/lut.png")" = old ] || fail "the old render/lut.png was changed"
[ "$(cat "$disk/render/render.json")" = '{"old": true}' ] || fail "the old render.json was changed"
[ "$(ls "$disk/render" | wc -l)" -eq 2 ] || fail "render folder gained files: $(ls "$disk/render")"
no_temporaries "$disk" "render"

# 4. Yosys with its work folder ($TMPDIR) on a small disk: it fails (a file it wrote cut short),
# or exits 0 with its netlist cut short; either is exit 2 naming yosys, and nothing is left.
if command -v yosys >/dev/null; then
  echo '{"old": true}' >"$work/synth.json"
  for size in 256 800; do
    mount_disk $size
    export TMPDIR="$disk"
    run 2 "synth: yosys" synth lut:bits=4 --material 'm shininess=50' --report "$work/synth.json"
    unset TMPDIR
    [ "$(cat "$work/synth.json")" = '{"old": true}' ] || fail "synth --report was changed"
    [ -z "$(ls -A "$disk")" ] || fail "synth with TMPDIR of ${size} KiB left: $(ls -A "$disk")"
  done
else
  echo "note: yosys not installed, synth not checked"
fi

[ "$fails" -eq 0 ] || { echo "FAIL: $fails checks"; exit 1; }
echo "PASS: a full disk keeps every old output and leaves no temporary"
