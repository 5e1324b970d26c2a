# shellcheck shell=bash
# Shared by the .ci scripts: package lists, the configure-and-build step, and timed phases.

# What building and running glint needs (Debian packages). gtkwave: vcd2fst for --vcd t.fst;
# libassimp-dev: PLY, glTF and STL meshes; libpng-dev: the PNG encoder; libopenexr-dev: render
# --float exr; yosys: glint synth; qflow-tech-osu018 and opensta: its built-in node (OSU 0.18 um
# cells) and their timing; verilator: the RTL co-simulations; ninja-build and ccache: the builds;
# libsollya-dev: horner's fixed-point fits (fpminimax) and certified sup norms (src/fit/sollya_fit.h).
GLINT_PACKAGES=(g++ cmake ninja-build ccache pkg-config libsystemc-dev libfmt-dev libcli11-dev
  nlohmann-json3-dev libtinyobjloader-dev libassimp-dev libstb-dev libpng-dev libopenexr-dev
  fonts-dejavu-core libfast-float-dev gtkwave yosys qflow-tech-osu018 opensta libsollya-dev)
# What the test suite and the benchmarks need on top: GoogleTest, Google Benchmark, RapidCheck,
# MPFR (the 200-bit oracle), libspng (png_speed's comparison of encoders), GNU parallel (the
# sharded-sweep test), Verilator, Icarus Verilog (the gate-level energy reference,
# tests/calibration/gate_power.py: it reads the library's cell models, whose UDPs Verilator
# cannot), Python 3 (the documentation checks), Valgrind (the instruction counts of
# tests/bench/instructions.py); clang, its sanitizer and libFuzzer runtimes and
# llvm-symbolizer for the sanitizer and fuzz build; Chromium, headless, for the HTML pages' test in
# a browser (html.browser).
GLINT_TEST_PACKAGES=(libgtest-dev libgmock-dev libbenchmark-dev librapidcheck-dev libmpfr-dev
  libspng-dev parallel verilator iverilog python3 valgrind clang libclang-rt-dev llvm chromium)

# ccache keys on paths relative to the checkout (BASEDIR) and leaves the build folder out of the
# key of objects with debug information (NOHASHDIR), so a clone elsewhere on the machine still hits.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}

# glint_build DIR TARGET CMAKE_ARGS...: configure DIR (Ninja and ccache when a new build folder
# is made and they are installed) and build TARGET ("all" for everything). CMake's and the
# compiler's output goes to stderr; results of the later steps go to stdout.
glint_build() {
  local dir=$1 target=$2
  shift 2
  local args=()
  if [[ ! -f $dir/CMakeCache.txt ]] && command -v ninja >/dev/null; then
    args+=(-G Ninja)
  fi
  if command -v ccache >/dev/null; then
    args+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  fi
  # `|| return`: errexit does not hold inside a function called from `phase`'s `||`.
  cmake -S . -B "$dir" "${args[@]}" "$@" >&2 || return
  cmake --build "$dir" -j "$(nproc)" --target "$target" >&2 || return
}

# phase NAME COMMAND...: runs COMMAND and prints "ci: NAME  S s" (its wall time) on stderr, and
# adds the line to the summary that phase_summary prints. A failing command fails the phase.
GLINT_PHASES=()
phase() {
  local name=$1
  shift
  local start=$SECONDS status=0
  echo "ci: $name ..." >&2
  "$@" || status=$?
  local line
  line=$(printf 'ci: %-22s %5d s' "$name" $((SECONDS - start)))
  ((status == 0)) || line+="  FAILED (exit $status)"
  echo "$line" >&2
  GLINT_PHASES+=("$line")
  return "$status"
}
phase_summary() {
  printf '%s\n' "${GLINT_PHASES[@]}" >&2
}

# The clang build of CI: AddressSanitizer and UndefinedBehaviorSanitizer (any finding aborts:
# -fno-sanitize-recover), warnings as errors, the libraries instrumented for libFuzzer. One build
# serves both the sanitizer suite (.ci/sanitize) and the fuzz harnesses (.ci/fuzz). No benchmarks:
# nothing runs them under the sanitizers. Line tables only for debug information: what the
# sanitizers' and libFuzzer's stack traces need (file, line, inlined frames), at ~17 % less
# compile time than -g (horner.cpp: 12.6 against 15.3 CPU-s) and half the object size.
glint_clang_build() {
  local dir=$1
  shift
  glint_build "$dir" all -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
    -DGLINT_SANITIZE=address,undefined -DGLINT_FUZZ=ON -DGLINT_WERROR=ON \
    -DGLINT_BUILD_TESTS=ON -DGLINT_BUILD_BENCHMARKS=OFF "$@"
}
