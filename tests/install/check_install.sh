#!/usr/bin/env bash
# ctest `install`: installs the current build into a temporary prefix and builds an outside program
# (tests/install/consumer) against what was installed, twice: through the CMake package
# (find_package(glint)) and through pkg-config (glint-core.pc, glint.pc). Each build must see only
# the prefix, never glint's source or build tree, and each program must run and print "ok".
# Usage: check_install.sh SOURCE_DIR BUILD_DIR CXX
set -euo pipefail
src=$(cd "$1" && pwd -P)
build=$(cd "$2" && pwd -P)
cxx=$3

# Outside both trees, so that a path into either one can only come from a leak in the package.
work=$(mktemp -d "${TMPDIR:-/tmp}/glint-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() {
  echo "check_install: $*" >&2
  exit 1
}
# Fails if FILES mention the source or the build tree.
no_tree_paths() {
  local hits
  hits=$(grep -lF -e "$src" -e "$build" "$@" || true)
  [[ -z $hits ]] || fail "paths into the source or build tree in: $hits"
}

cmake --install "$build" --prefix "$prefix" >"$work/install.log"
cp -r "$src/tests/install/consumer" "$work/consumer"
[[ -f $prefix/include/glint/units/catalogue.h && -f $prefix/include/glint/rtl_model/fast_sim.h ]] ||
  fail "headers not under $prefix/include/glint/<layer>/"
mapfile -t metadata < <(find "$prefix" -name '*.cmake' -o -name '*.pc')
((${#metadata[@]} >= 5)) || fail "CMake package or .pc files missing: ${metadata[*]}"
no_tree_paths "${metadata[@]}"

# 1. CMake: find_package(glint) from the prefix only (no package registry, no system glint).
cmake -S "$work/consumer" -B "$work/cmake" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >"$work/configure.log" ||
  { cat "$work/configure.log"; fail "configuring the consumer failed"; }
grep -q "^glint_DIR:PATH=$prefix/" "$work/cmake/CMakeCache.txt" || fail "glint not found in $prefix"
cmake --build "$work/cmake" -j 2 >"$work/build.log" 2>&1 ||
  { cat "$work/build.log"; fail "building the consumer against the CMake package failed"; }
mapfile -t link_lines < <(find "$work/cmake" -name link.txt)
no_tree_paths "$work/cmake/compile_commands.json" "${link_lines[@]}"

# 2. pkg-config: the same sources, compiled and linked with the flags the .pc files give.
pcdir=$(dirname "$(find "$prefix" -name glint.pc)")
export PKG_CONFIG_PATH=$pcdir
core_flags=$(pkg-config --cflags --libs glint-core)
all_flags=$(pkg-config --cflags --libs glint)
echo "pkg-config glint-core: $core_flags"
echo "pkg-config glint: $all_flags"
[[ $core_flags != *systemc* ]] || fail "glint-core.pc pulls in SystemC"
# shellcheck disable=SC2086  # the flags are meant to split into words
{
  "$cxx" -Wall -Wextra -Werror "$work/consumer/main.cpp" $core_flags -o "$work/pc_consumer" &
  "$cxx" -Wall -Wextra -Werror "$work/consumer/sc_main.cpp" $all_flags -o "$work/pc_consumer_sc" &
  wait -n && wait -n
} || fail "building the consumer with pkg-config failed"

# Both builds of each program must run, pass their own checks and print the same.
for program in consumer consumer_sc; do
  cmake_out=$("$work/cmake/$program") || fail "$program (CMake build) failed: $cmake_out"
  pc_out=$("$work/pc_$program") || fail "$program (pkg-config build) failed: $pc_out"
  echo "$cmake_out"
  [[ $cmake_out == "$pc_out" ]] || fail "$program: CMake and pkg-config builds differ: $pc_out"
  [[ $(tail -n 1 <<<"$cmake_out") == *": ok" ]] || fail "$program did not report ok"
done
echo "check_install: installed package works (CMake and pkg-config)"
