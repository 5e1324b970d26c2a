#!/usr/bin/env python3
"""Synthesizes the calibration set (set.txt) with `glint synth` and stores what Yosys made of
every configuration; calibration_report (tests/calibration_report.cpp) holds the cost proxy to it.

    python3 tests/calibration/synth_set.py build/glint -o tests/calibration/set.json
    python3 tests/calibration/synth_set.py build/glint --set tests/calibration/holdout.txt \
        -o tests/calibration/holdout.json

With --liberty LIB (osu018, or a Liberty file) each configuration is mapped to that library and
timed by OpenSTA (`glint synth --liberty`): the stored results are its area in um2 and NAND2
equivalents and the worst path in ns, the data of the proxy's node constants (issue 26):

    python3 tests/calibration/synth_set.py build/glint --liberty osu018 --timeout 900 \
        -o tests/calibration/set_osu018.json

--timeout S gives up a configuration after S seconds (its process group killed) and stores it
as an error: abc's mapping of a 2^23-code table to osu018 had not ended after 17 minutes.

With --check FILE it re-synthesizes a sample (--sample N configurations, drawn with --seed) and
compares each with FILE's stored result: flip-flops equal, GE and depth within --tolerance (a
relative margin for another Yosys or ABC build; 0 holds them to the same figures). Run from the
repository's top folder (the vector files' paths are relative to it).
"""
import argparse
import json
import os
import random
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def read_set(path):
    configs = []
    for line in open(path):
        line = line.split("#", 1)[0].strip()
        if line:
            spec, vectors = line.split()
            configs.append({"spec": spec, "vectors": vectors})
    return configs


def run_synth(argv, timeout):
    """glint synth's JSON, or None after `timeout` seconds (its yosys and abc killed too)."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, 9)
        p.communicate()
        return None
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)}: exit {p.returncode}: {err}")
    return json.loads(out)


def synth(glint, c, root, liberty=None, timeout=None):
    argv = [glint, "synth", c["spec"], "--vectors", os.path.join(root, c["vectors"]), "--json"]
    if liberty:
        argv += ["--liberty", liberty]
    r = run_synth(argv, timeout)
    if r is None:
        return {"spec": c["spec"], "vectors": c["vectors"], "error": f"timeout {timeout} s"}
    if liberty:
        return {"spec": c["spec"], "vectors": c["vectors"], "canonical_spec": r["spec"],
                "area_um2": r["area_um2"], "nand2_equivalents": r["nand2_equivalents"],
                "flip_flops": r["flip_flops"], "cells": r["cells"], "depth": r["depth"],
                "timing": r["timing"],
                "stages": [{"stage": s["stage"], "depth": s["depth"],
                            "flip_flops": s["flip_flops"]} for s in r["stages"]],
                "yosys_seconds": round(r["yosys_seconds"], 1)}
    return {"spec": c["spec"], "vectors": c["vectors"], "canonical_spec": r["spec"],
            "ge": r["ge"], "transistors_yosys": r["transistors_yosys"],
            "flip_flops": r["flip_flops"], "cells": r["cells"], "depth": r["depth"],
            "stages": [{"stage": s["stage"], "depth": s["depth"], "flip_flops": s["flip_flops"]}
                       for s in r["stages"]],
            "yosys_seconds": round(r["yosys_seconds"], 1)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint")
    ap.add_argument("-o", "--output")
    ap.add_argument("--set", default=os.path.join(HERE, "set.txt"))
    ap.add_argument("--check")
    ap.add_argument("--sample", type=int, default=3)
    ap.add_argument("--seed", type=int)
    ap.add_argument("--tolerance", type=float, default=0.02)
    ap.add_argument("--liberty")
    ap.add_argument("--timeout", type=float)
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(HERE))
    configs = read_set(args.set)
    if args.check:
        stored = {(c["spec"], c["vectors"]): c for c in json.load(open(args.check))["configs"]}
        seed = args.seed if args.seed is not None else random.randrange(1 << 30)
        print(f"resynth: seed {seed}", flush=True)
        failed = 0
        for c in random.Random(seed).sample(configs, min(args.sample, len(configs))):
            s = stored[(c["spec"], c["vectors"])]
            r = synth(args.glint, c, root)
            ok = (r["flip_flops"] == s["flip_flops"] and
                  abs(r["ge"] - s["ge"]) <= args.tolerance * s["ge"] and
                  abs(r["depth"] - s["depth"]) <= args.tolerance * s["depth"])
            failed += not ok
            print(f"{'ok  ' if ok else 'FAIL'} {c['spec']} {c['vectors']}: GE {r['ge']:.1f} "
                  f"(stored {s['ge']:.1f}), depth {r['depth']} ({s['depth']}), flip-flops "
                  f"{r['flip_flops']} ({s['flip_flops']})", flush=True)
        return 1 if failed else 0
    results = []
    for c in configs:
        r = synth(args.glint, c, root, args.liberty, args.timeout)
        if "error" in r:
            print(f"{c['spec']} {c['vectors']}: {r['error']}", file=sys.stderr, flush=True)
        elif args.liberty:
            print(f"{c['spec']} {c['vectors']}: {r['area_um2']:.0f} um2, "
                  f"{r['timing']['critical_path_ns']} ns, {r['yosys_seconds']} s",
                  file=sys.stderr, flush=True)
        else:
            print(f"{c['spec']} {c['vectors']}: {r['ge']:.1f} GE, depth {r['depth']}, "
                  f"{r['yosys_seconds']} s", file=sys.stderr, flush=True)
        results.append(r)
    version = subprocess.run(["yosys", "-V"], capture_output=True, text=True).stdout.strip()
    rel = os.path.relpath(os.path.abspath(args.set), root)
    out = os.path.relpath(os.path.abspath(args.output), root)
    extra = (f" --liberty {args.liberty}" if args.liberty else "") + \
        (f" --timeout {args.timeout:g}" if args.timeout else "")
    doc = {"glint_calibration_set": 1,
           "command": f"python3 tests/calibration/synth_set.py build/glint --set {rel}{extra} -o {out}",
           "yosys": version, "configs": results}
    if args.liberty:
        sta = subprocess.run(["sta", "-version"], capture_output=True, text=True,
                             stdin=subprocess.DEVNULL)
        doc["liberty"] = args.liberty
        doc["opensta"] = sta.stdout.strip()
    with open(args.output, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
