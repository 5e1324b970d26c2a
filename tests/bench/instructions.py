#!/usr/bin/env python3
"""Instruction counts of glint's speed workloads against stored baselines (instructions.json).

Counts instructions, not seconds: on a shared or virtual machine the wall and CPU clocks of one
run drift by more than the regressions worth catching, while the instructions a single-threaded
run executes on fixed inputs repeat to within a few dozen in a billion (tests/bench/RESULTS.md).

  instructions.py BUILD_DIR                  compare every workload with its baseline
  instructions.py BUILD_DIR --update [--runs N] [--host TEXT]
                                             measure and rewrite the baselines (the median of N)
  instructions.py BUILD_DIR --runs N         measure N times, print the spread, compare nothing

Prints "PASS:", "FAIL:" (exit 1, naming each workload outside the tolerance) or "SKIP:" (exit 0)
when the baselines were measured on another build, counter or C library than BUILD_DIR's, whose
counts are not comparable, or when the counter is missing.
"""

import argparse
import concurrent.futures
import datetime
import glob
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
BASELINES = os.path.join(HERE, "instructions.json")

# glibc picks its string and maths functions by CPU (AVX2 memchr, FMA pow): pinned to the x86-64
# baseline versions, so that a host with other CPU features counts the same instructions.
TUNABLES = ("glibc.cpu.hwcaps=-AVX512F,-AVX2,-AVX,-FMA,-FMA4,-BMI1,-BMI2,-LZCNT,-MOVBE,-POPCNT,"
            "-SSE4_1,-SSE4_2,-SSSE3,-ERMS")


def update_hint(build_dir):
    return f"{os.path.relpath(__file__, SOURCE)} {build_dir} --update --runs 5"


def fail_usage(message):
    print(f"instructions.py: {message}", file=sys.stderr)
    sys.exit(2)


def build_identity(build_dir):
    """What the counts depend on besides the source: compiler, build type, flags, C library."""
    cache = {}
    with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as f:
        for line in f:
            match = re.match(r"([A-Za-z_0-9]+):[A-Z]+=(.*)", line.rstrip("\n"))
            if match:
                cache[match.group(1)] = match.group(2)
    build_type = cache.get("CMAKE_BUILD_TYPE", "")
    flags = " ".join(
        filter(None, [cache.get("CMAKE_CXX_FLAGS", ""),
                      cache.get("CMAKE_CXX_FLAGS_" + build_type.upper(), "")]))
    compiler = "unknown"
    for path in glob.glob(os.path.join(build_dir, "CMakeFiles", "*", "CMakeCXXCompiler.cmake")):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        found = dict(re.findall(r'set\(CMAKE_CXX_COMPILER_(ID|VERSION) "([^"]*)"\)', text))
        compiler = f"{found.get('ID', '?')} {found.get('VERSION', '?')}"
    libc = " ".join(platform.libc_ver())
    return {"compiler": compiler, "build_type": build_type, "flags": flags, "libc": libc,
            "machine": platform.machine()}


class Cachegrind:
    """Valgrind's cachegrind without cache simulation: the guest instructions executed."""

    name = "cachegrind"

    @staticmethod
    def version():
        if not shutil.which("valgrind"):
            return None
        out = subprocess.run(["valgrind", "--version"], capture_output=True, text=True).stdout
        return f"cachegrind {out.strip().removeprefix('valgrind-')}"

    @staticmethod
    def wrap(command, out):
        return ["valgrind", "-q", "--tool=cachegrind", "--cache-sim=no",
                f"--cachegrind-out-file={out}", *command]

    @staticmethod
    def parse(line):
        return int(line.split()[1]) if line.startswith("summary:") else None


class Perf:
    """perf stat's user-space instructions: needs a hardware counter (none in most VMs)."""

    name = "perf"

    @staticmethod
    def version():
        if not shutil.which("perf"):
            return None
        probe = subprocess.run(["perf", "stat", "-x,", "-e", "instructions:u", "true"],
                               capture_output=True, text=True)
        if probe.returncode != 0 or "<not supported>" in probe.stderr:
            return None
        out = subprocess.run(["perf", "--version"], capture_output=True, text=True).stdout
        return out.strip().replace("perf version", "perf")

    @staticmethod
    def wrap(command, out):
        return ["perf", "stat", "-x,", "-e", "instructions:u", "-o", out, "--", *command]

    @staticmethod
    def parse(line):
        fields = line.split(",")
        if len(fields) > 2 and fields[2].startswith("instructions"):
            return int(fields[0])
        return None


def count(counter, command, env, scratch, cwd):
    """The instructions one run of `command` executes, as `counter` counts them."""
    out = os.path.join(scratch, counter.name + ".out")
    run = subprocess.run(counter.wrap(command, out), env=env, cwd=cwd,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"exit {run.returncode}: {run.stderr.strip()[-400:]}")
    with open(out, encoding="utf-8") as f:
        for line in f:
            value = counter.parse(line)
            if value is not None:
                return value
    raise RuntimeError(f"{counter.name} counted no instructions")


COUNTERS = {counter.name: counter for counter in (Cachegrind, Perf)}


def prepare_inputs(build_dir, inputs):
    """The workloads' inputs under BUILD_DIR/instructions: placeholders of their commands."""
    work = os.path.join(build_dir, "instructions")
    os.makedirs(work, exist_ok=True)
    rows = inputs["vector_rows"]
    vectors = os.path.join(work, f"eval_{rows}.vec")
    # eval_speed's file: the stream every speed program draws from (generated_stream.h).
    subprocess.run([os.path.join(build_dir, "tests", "eval_speed"), "--rows", str(rows),
                    "--file", vectors, "--write-only"], check=True)
    with open(os.path.join(SOURCE, inputs["scene"]), encoding="utf-8") as f:
        scene = json.load(f)
    scene["camera"]["resolution"] = inputs["scene_resolution"]
    scene_path = os.path.join(work, "scene.json")
    with open(scene_path, "w", encoding="utf-8") as f:
        json.dump(scene, f)
    return {"glint": os.path.join(build_dir, "glint"), "vectors": vectors, "scene": scene_path,
            "out": os.path.join(work, "out"), "work": work}


def measure(counter, workload, places, runs):
    """The counts of `runs` runs of one workload, each in a fresh output folder."""
    # A fixed environment: a larger one alone adds instructions (a 20 kB variable: +0.02 %).
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "LC_ALL": "C",
           "GLIBC_TUNABLES": TUNABLES}
    counts = []
    with tempfile.TemporaryDirectory() as scratch:
        for _ in range(runs):
            out = places["out"] + "." + workload["name"]
            shutil.rmtree(out, ignore_errors=True)
            command = [arg.format(**dict(places, out=out)) for arg in workload["command"]]
            counts.append(count(counter, command, env, scratch, places["work"]))
            shutil.rmtree(out, ignore_errors=True)
    return counts


def measure_all(counter, baselines, places, runs, jobs):
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {w["name"]: pool.submit(measure, counter, w, places, runs)
                   for w in baselines["workloads"]}
        return {name: future.result() for name, future in futures.items()}


def percent(measured, baseline):
    return 100.0 * (measured - baseline) / baseline


def compare(baselines, counts, build_dir):
    tolerance = baselines["tolerance_percent"]
    failures = 0
    for workload in baselines["workloads"]:
        name, baseline = workload["name"], workload["instructions"]
        measured = counts[name][0]
        change = percent(measured, baseline)
        line = (f"{name}: {measured:,} instructions, baseline {baseline:,} ({change:+.3f} %, "
                f"tolerance ±{tolerance} %)")
        if change > tolerance:
            failures += 1
            print(f"FAIL: {line}: more instructions than the baseline, a regression; if the "
                  f"change is meant to cost more, update the baselines: {update_hint(build_dir)}")
        elif change < -tolerance:
            failures += 1
            print(f"FAIL: {line}: fewer instructions than the baseline; if the change is meant "
                  f"to save them, update the baselines so that the guard keeps its edge: "
                  f"{update_hint(build_dir)}")
        else:
            print(f"ok: {line}")
    count = len(baselines["workloads"])
    if failures:
        print(f"FAIL: {failures} of {count} workloads outside ±{tolerance} % of their baselines")
        return 1
    print(f"PASS: {count} workloads within ±{tolerance} % of their baselines")
    return 0


def print_spread(counts):
    for name, runs in counts.items():
        spread = max(runs) - min(runs)
        print(f"{name}: {len(runs)} runs, median {int(statistics.median(runs)):,}, "
              f"min {min(runs):,}, max {max(runs):,}, spread {spread:,} instructions "
              f"({1e6 * spread / min(runs):.3f} ppm)")


def write_baselines(baselines):
    # One workload per line keeps a baseline update a one-line diff per workload.
    lines = ["{"]
    for key in ("tolerance_percent", "counter", "build", "measured", "inputs"):
        lines.append(f'  "{key}": {json.dumps(baselines[key], ensure_ascii=False)},')
    lines.append('  "workloads": [')
    rows = [f"    {json.dumps(w, ensure_ascii=False)}" for w in baselines["workloads"]]
    lines.append(",\n".join(rows))
    lines.append("  ]")
    lines.append("}")
    with open(BASELINES, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build_dir", help="a configured and built glint build folder")
    parser.add_argument("--update", action="store_true",
                        help="measure and rewrite the baselines for this build")
    parser.add_argument("--runs", type=int, default=1,
                        help="runs per workload (--update stores their median)")
    parser.add_argument("--counter", choices=sorted(COUNTERS),
                        help="with --update: the counter (default: the baselines' own)")
    parser.add_argument("--host", help="with --update: the host to record (default: "
                        "/proc/cpuinfo's model name and the core count)")
    parser.add_argument("--jobs", type=int, default=2, help="workloads measured side by side")
    args = parser.parse_args()
    if args.runs < 1 or args.jobs < 1:
        fail_usage("--runs and --jobs take a positive count")

    with open(BASELINES, encoding="utf-8") as f:
        baselines = json.load(f)
    args.build_dir = os.path.abspath(args.build_dir)
    for program in ("glint", "tests/eval_speed"):
        if not os.access(os.path.join(args.build_dir, program), os.X_OK):
            fail_usage(f"no {program} in {args.build_dir}: build it (benchmarks on) first")
    build = build_identity(args.build_dir)
    counter = COUNTERS[args.counter or baselines["counter"].split()[0]]
    counter_version = counter.version()
    if counter_version is None and args.update:
        fail_usage(f"no usable {counter.name} on this host: nothing to measure with")
    if counter_version is None:
        print(f"SKIP: no usable {counter.name} on this host (the baselines' counter is "
              f"{baselines['counter']})")
        return 0
    comparing = not args.update and args.runs == 1
    if comparing:
        differs = [f"{key} {baselines['build'].get(key)!r} here {build[key]!r}"
                   for key in build if baselines["build"].get(key) != build[key]]
        if baselines["counter"] != counter_version:
            differs.append(f"counter {baselines['counter']!r} here {counter_version!r}")
        if differs:
            print("SKIP: the baselines are for another build, whose counts are not comparable: "
                  + "; ".join(differs) + f" (to guard this build, {update_hint(args.build_dir)})")
            return 0

    places = prepare_inputs(args.build_dir, baselines["inputs"])
    try:
        counts = measure_all(counter, baselines, places, args.runs, args.jobs)
    except RuntimeError as error:
        print(f"FAIL: a workload did not run: {error}")
        return 1
    if args.runs > 1:
        print_spread(counts)
    if args.update:
        for workload in baselines["workloads"]:
            workload["instructions"] = int(statistics.median(counts[workload["name"]]))
        baselines["counter"] = counter_version
        baselines["build"] = build
        baselines["measured"] = {
            "date": datetime.date.today().isoformat(),
            "host": args.host or default_host(),
            "commit": subprocess.run(["git", "-C", SOURCE, "rev-parse", "--short", "HEAD"],
                                     capture_output=True, text=True).stdout.strip(),
            "runs": args.runs,
        }
        write_baselines(baselines)
        print(f"updated {BASELINES}")
        return 0
    return compare(baselines, counts, args.build_dir) if comparing else 0


def default_host():
    model = "unknown CPU"
    with open("/proc/cpuinfo", encoding="utf-8") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return f"{model}, {os.cpu_count()} cores"


if __name__ == "__main__":
    sys.exit(main())
