#!/usr/bin/env python3
"""glint's energy at osu018 fitted to, and checked against, the gate-level reference.

    python3 tests/calibration/energy_fit.py build/glint -o src/cost/energy_fit_osu018.h

For every lane of tests/calibration/power_osu018.json (gate_power.py: OpenSTA's report_power on
the library-mapped lane, simulated on the lane's vectors) runs

    glint sim VECTORS --unit SPEC --node osu018 --activity operand --json

(the RTL lane is operand gating), checks glint counts the same requests and computed requests
and cycles (the lane's schedule: they must be the testbench's), takes glint's energy per request
split into clock, register, the datapath by kind (datapath_by_kind) and leakage, and fits five
factors (cost/energy.h's EnergyScale: clock_bit, register_bit, and one factor per group of
datapath kinds, GROUPS below) by non-negative least squares on the relative error, on the
calibration lanes only. The reference is internal_averaged + switching + leakage: OpenSTA 2.0.17's own
`internal` counts the rise and the fall energy on every transition (src/cost/README.md, "Energy",
says why the averaged one). Prints a table per lane (reference, glint before and after, ratio)
and the worst ratio on the calibration set and on the hold-out; writes the factors with their
residuals as a C++ header. glint's parts are divided by the factors the report says it applied
(`scale`), so a re-fit starts from the library's weights whatever the build holds.

    python3 tests/calibration/energy_fit.py build/glint --check GUARD

is the normal suite's check (ctest calibration_energy): glint's energy as built, every lane's
ratio to the reference within 1 +- GUARD; prints PASS: or FAIL: and exits 1 on a failure.
Pure Python (no numpy): five unknowns.
"""
import argparse
import json
import os
import re
import subprocess
import sys

# node_fit.py (beside this script) fits the node proxy the same way: its non-negative least squares.
from node_fit import nnls

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STORED = os.path.join(ROOT, "tests", "calibration", "power_osu018.json")
LIBRARY = os.path.join(ROOT, "src", "cost", "energy_osu018.h")
FACTORS = ["clock", "register", "arithmetic", "table", "selection"]
# The datapath's kinds (the report's datapath_by_kind) and EnergyScale's field for each.
KINDS = {"adder": "adder_bit", "multiplier": "multiplier_bit", "comparator": "comparator_bit",
         "mux": "mux_bit", "table": "table_bit", "gate": "gate"}
# The datapath's kinds each factor covers. Five factors on 18 calibration lanes: the lanes cannot
# separate more. Multipliers and adders are one factor (carry-save arrays of the same full adders,
# and every lane with many adder bits has many multiplier bits); the comparators, muxes and glue
# gates another (small, select logic); the tables their own (lut's and pwp's against the rest).
GROUPS = {"clock": [], "register": [], "arithmetic": ["adder", "multiplier"], "table": ["table"],
          "selection": ["mux", "comparator", "gate"]}
# The header's fields, per factor.
FIELDS = {"clock": ["clock_bit"], "register": ["register_bit"],
          **{k: [KINDS[kind] for kind in kinds] for k, kinds in GROUPS.items() if kinds}}


def reference(lane):
    e = lane["energy_pj_per_request"]
    return lane["internal_averaged_pj_per_request"] + e["switching"] + e["leakage"]


def library_weights():
    """The library's per-bit energies as src/cost/energy_weights.py derived them (unscaled)."""
    text = open(LIBRARY).read()
    return {field: float(re.search(r"w\.%s = ([0-9.eE+-]+);" % field, text).group(1))
            for field in KINDS.values()}


def unscaled_parts(energy, weights):
    """glint's parts per request at the library's weights: the clock and registers divided by the
    factor the glint that ran applied (its report's `scale`), the datapath's switching bits per
    kind times the library's weight of the kind, summed per factor (a factor fitted to 0 would
    leave nothing to divide)."""
    p, scale, bits = energy["per_request"], energy["scale"], energy["switching_bits_by_kind"]
    raw = {"clock": p["clock"] / scale["clock_bit"],
           "register": p["register"] / scale["register_bit"], "leakage": p["leakage"]}
    for k, group in GROUPS.items():
        if group:
            raw[k] = sum(bits[kind] * weights[KINDS[kind]] for kind in group)
    return raw


def glint_energy(glint, lane):
    vectors = lane["input"].split()[-1]
    out = subprocess.run([glint, "sim", os.path.join(ROOT, vectors), "--unit", lane["spec"],
                          "--node", "osu018", "--activity", "operand", "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["units"][0]["energy"]


def off_cycles(row):
    """glint's cycles short of or beyond the testbench's by more than the drain (5 %)."""
    g, ref = row["cycles"]
    return abs(g - ref) > 0.05 * ref


def predict(parts, f):
    return sum(parts[k] * f[k] for k in FACTORS) + parts["leakage"]


def write_header(path, f, rows, fitted, command):
    cal = [r["after"] for r in rows if r["set"] == "calibration"]
    hold = [r["after"] for r in rows if r["set"] != "calibration"]
    lines = [
        "// Generated by " + command,
        "// The energy model's factors (cost/energy.h's EnergyScale) fitted to the gate-level",
        "// reference tests/calibration/power_osu018.json (OpenSTA report_power on the mapped lanes,",
        "// internal_averaged + switching + leakage) by non-negative least squares on the relative",
        "// error of %d of the %d calibration lanes (a lane whose cycles glint miscounts is left" % (
            fitted, len(cal)),
        "// out). The datapath's kinds in groups of one factor each:",
        "//   " + "; ".join("%s: %s" % (k, ", ".join(GROUPS[k])) for k in FACTORS if GROUPS[k]),
        "// Residuals, glint / reference after the fit: calibration %.3f-%.3f, hold-out (%d lanes,"
        % (min(cal), max(cal), len(hold)),
        "// fitted on nothing) %.3f-%.3f. Per lane: src/cost/README.md, \"Energy\"; tests/bench/"
        % (min(hold), max(hold)),
        "// RESULTS.md. Do not edit: re-run the script.",
        "#pragma once",
        "",
        "#include \"cost/energy.h\"",
        "",
        "namespace glint {",
        "",
        "inline EnergyScale make_energy_scale_osu018() {",
        "  EnergyScale s;",
    ]
    for k in FACTORS:
        for field in FIELDS[k]:
            lines.append("  s.%s = %.6f;" % (field, f[k]))
    lines += ["  return s;", "}", "", "}  // namespace glint", ""]
    with open(path, "w") as out:
        out.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint")
    ap.add_argument("--stored", default=STORED)
    ap.add_argument("-o", "--output", help="write the fitted factors as this C++ header")
    ap.add_argument("--check", type=float, metavar="GUARD",
                    help="no fit: every lane's ratio within 1 +- GUARD, as built")
    ap.add_argument("--miscounted", type=int, default=0, metavar="N",
                    help="with --check: the lanes whose cycles glint miscounts, not held to the "
                         "guard, must be N (a fix of the cycle count then fails the check: re-fit)")
    args = ap.parse_args()

    stored = json.load(open(args.stored))
    weights = library_weights()
    rows, mismatches = [], []
    for lane in stored["lanes"]:
        e = glint_energy(args.glint, lane)
        for key in ("requests", "computed"):
            if e[key] != lane[key]:
                mismatches.append("%s %s: %s glint %d, reference %d"
                                  % (lane["spec"], lane["input"], key, e[key], lane[key]))
        p = e["per_request"]
        built = {k: e["scale"][FIELDS[k][0]] for k in FACTORS}
        row = {"spec": lane["spec"], "vectors": os.path.basename(lane["input"].split()[-1]),
               "set": lane["set"], "ref": reference(lane), "raw": unscaled_parts(e, weights),
               "built": p["total"], "cycles": (e["cycles"], lane["cycles"])}
        if off_cycles(row):
            mismatches.append("%s %s: cycles glint %d, reference %d (left out of the fit)"
                              % (lane["spec"], lane["input"], e["cycles"], lane["cycles"]))
        rows.append(row)

    cal = []
    if args.check is not None:
        f = built
    else:
        # A lane whose cycles glint miscounts (beyond the pipeline's drain) says nothing about
        # the weights: left out of the fit, still in the table and the check.
        cal = [r for r in rows if r["set"] == "calibration" and not off_cycles(r)]
        # Relative error: each lane's row divided by its reference, so every lane weighs alike.
        a = [[r["raw"][k] / r["ref"] for k in FACTORS] for r in cal]
        b = [1 - r["raw"]["leakage"] / r["ref"] for r in cal]
        f = dict(zip(FACTORS, nnls(a, b)))
    ones = {k: 1.0 for k in FACTORS}
    for r in rows:
        r["before"] = predict(r["raw"], ones) / r["ref"]
        # The check holds what glint reports; the fit, what its factors would make it report.
        r["after"] = (r["built"] if args.check is not None else predict(r["raw"], f)) / r["ref"]

    print("factors: " + ", ".join("%s %.4f" % (k, f[k]) for k in FACTORS))
    print("%-66s %-17s %-11s %8s %8s %8s %6s %6s %11s" % (
        "spec", "vectors", "set", "ref pJ", "before", "after", "before", "after", "cycles g/ref"))
    for r in rows:
        print("%-66s %-17s %-11s %8.1f %8.1f %8.1f %6.3f %6.3f %5d/%5d" % (
            r["spec"], r["vectors"], r["set"], r["ref"], r["before"] * r["ref"],
            r["after"] * r["ref"], r["before"], r["after"], *r["cycles"]))
    worst = {}
    for s in ("calibration", "holdout"):
        ratios = [r["after"] for r in rows if r["set"] == s]
        worst[s] = max(ratios, key=lambda x: abs(x - 1))
        print("%s: %d lanes, ratio %.3f-%.3f, worst %.3f (%+.1f %%)"
              % (s, len(ratios), min(ratios), max(ratios), worst[s], 100 * (worst[s] - 1)))
    for m in mismatches:
        print("count mismatch: " + m)

    if args.output:
        write_header(args.output, f, rows, len(cal), " ".join(
            ["python3", "tests/calibration/energy_fit.py", "build/glint", "-o",
             os.path.relpath(os.path.abspath(args.output), ROOT)]))
        print("wrote " + args.output)
    if args.check is not None:
        bad = [r for r in rows if abs(r["after"] - 1) > args.check and not off_cycles(r)]
        miscounted = [r for r in rows if off_cycles(r)]
        requests_differ = len(mismatches) > len(miscounted)
        if len(miscounted) != args.miscounted:
            print("FAIL: %d lanes with glint's cycles off the reference's, expected %d: re-fit"
                  % (len(miscounted), args.miscounted))
        if requests_differ or bad or len(miscounted) != args.miscounted:
            for r in bad:
                print("FAIL: %s on %s: glint/reference %.3f outside 1 +- %.2f"
                      % (r["spec"], r["vectors"], r["after"], args.check))
            if requests_differ:
                print("FAIL: glint and the reference count different requests")
            return 1
        print("PASS: %d lanes within 1 +- %.2f of the gate-level reference, %d with glint's cycles "
              "off not held to it" % (len(rows) - len(miscounted), args.check, len(miscounted)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
