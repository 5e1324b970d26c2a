#!/usr/bin/env python3
"""Writes skip_energy.md: what Källberg & Larsson's tau skip buys in joules, at equal error.

For every shipped scene (traces/scenes/*.json, at its own resolution) and every default unit,
`glint render --node osu018` states the lane's energy on the frame with its skip and the same
lane built without it (skip=off, every request computed), and both lanes' errors on the frame
(issue 26 item 5): the first table. A saving is fair only at equal error, and the skip can change
the frame, so the second asks `glint size --objective energy` for the least energy per request
that meets one budget, the worst pixel error the default lane with the skip reaches on the scene,
over one grid per family with the skip fixed on, then fixed off; the third sums both up per unit.

Usage (from the repository's top folder, with a Release build in build/):
    python3 src/cli/guide/skip_energy.py build/glint
It rewrites src/cli/guide/skip_energy.md; a few minutes of CPU (the renders take seconds, the
sizing most of it).
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
NODE = "osu018"

# The grids the second table sizes over, around each default unit's own keys: the input and
# output widths (what any lane trades for error) and the key that sets the unit's accuracy.
# The skip key is appended fixed on, then fixed off.
GRIDS = {
    "pow": "pow:in=uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15,log_bits=6|8",
    "schlick": "schlick:in=uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15,match=none|minimax",
    "hast": "hast:in=uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15,d=2..5",
    "horner": "horner:in=uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15,degree=3..6",
    # Without the skip the table spans [0, 1], not [tau, 1]: it needs more entries.
    "lut": "lut:in=uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15,bits=5..10",
}


def run(cmd, ok=(0,)):
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=TOP)
    if done.returncode not in ok:
        sys.exit(f"skip_energy.py: {' '.join(cmd)} exited {done.returncode}:\n{done.stderr}")
    return done.stdout


def render(glint, scene, out):
    report = json.loads(run([glint, "render", scene, "-o", out, "--node", NODE, "--json"]))
    rows = []
    for u in report["units"]:
        if "error_without_skip" not in u:
            continue  # a lane without the skip (none in the default set)
        on, off = u["energy"], u["energy_without_skip"]
        e_on, e_off = u["errors"], u["error_without_skip"]["errors"]
        w = u["error_without_skip"]
        rows.append({
            "unit": u["unit"], "spec": u["spec"], "requests": u["requests"],
            "shaded": on["shaded_pixels"],
            "uj_on": on["total_pj"] / 1e6, "uj_off": off["total_pj"] / 1e6,
            "px_on": on["pj_per_shaded_pixel"], "px_off": off["pj_per_shaded_pixel"],
            "max_on": u["image_error"]["max_lsb"], "max_off": w["image_error"]["max_lsb"],
            "mean_on": u["image_error"]["mean_lsb"], "mean_off": w["image_error"]["mean_lsb"],
            "wlsb_on": e_on["weighted"]["max_lsb"], "wlsb_off": e_off["weighted"]["max_lsb"],
            "ulps_on": e_on["max_datapath_ulps"], "ulps_off": e_off["max_datapath_ulps"],
            "differ": w["pixels_differing"], "between": w["max_lsb_between"],
            "equal": w["equal_error"],
        })
    return report, rows


def size(glint, scene, grid, budget):
    doc = json.loads(run([glint, "size", "--scene", scene, "--chip", "rom", "--budget", budget,
                          "--objective", "energy", "--node", NODE, "--no-widen", "--json",
                          "--grid", grid], ok=(0, 1)))
    best = doc.get("best")
    return None if best is None else (best["spec"], best["value"])


def differ_cell(r):
    return f"{r['differ']} (≤ {r['between']})" if r["differ"] else "0"


def saving(on, off):
    return f"{100 * (off - on) / off:.1f} %" if off > 0 else "-"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint", help="the glint program (a Release build)")
    ap.add_argument("-o", default=os.path.join(HERE, "skip_energy.md"), help="the page to write")
    args = ap.parse_args()
    glint = os.path.abspath(args.glint)
    scenes = sorted(glob.glob(os.path.join(TOP, "traces", "scenes", "*.json")))
    first, sized = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for path in scenes:
            name = os.path.splitext(os.path.basename(path))[0]
            report, rows = render(glint, os.path.relpath(path, TOP), os.path.join(tmp, name))
            res = "x".join(str(v) for v in report["resolution"])
            for r in rows:
                first.append((name, res, len(report["lights"]), r))
                sized.append((name, os.path.relpath(path, TOP), r))
            print(f"skip_energy.py: rendered {name}", file=sys.stderr)
        second = []
        for name, scene, r in sized:
            family = r["spec"].split(":")[0]
            budget = f"image.max_lsb<={r['max_on']:g}"
            on = size(glint, scene, GRIDS[family] + ",skip=on", budget)
            off = size(glint, scene, GRIDS[family] + ",skip=off", budget)
            second.append((name, r, budget, on, off))
            print(f"skip_energy.py: sized {name} {family}", file=sys.stderr)

    out = ["# What the tau skip buys, in joules, at equal error",
           "",
           "Generated by `python3 src/cli/guide/skip_energy.py build/glint` (issue 26 item 5); do",
           "not edit. Energies are glint's model at the built-in node (`--node osu018`, a skipped",
           "request held out of the datapath: `--activity operand`, render's default;",
           "[src/cost/README.md](../../cost/README.md#energy)); they move when the model is",
           "re-fitted, so re-run the script rather than copy figures.",
           "",
           "## The same lane, the skip on and off",
           "",
           "Every shipped scene at its own resolution, every default unit at its defaults: `glint",
           "render SCENE --node osu018` (the units' `energy`, `energy_without_skip` and",
           "`error_without_skip` in report.json, [schema](../../render/render_report.md)). µJ per",
           "frame and pJ per shaded pixel (a pixel with at least one request) with the skip / without",
           "it, the saving; then the errors with / without: the frame's worst and mean pixel error",
           "(`max_lsb`, `mean_lsb`: LSBs of the 8-bit display), the worst pixel error over the",
           "requests (`weighted.max_lsb8`) and the datapath's own error (`max_datapath_ulps`);",
           "`differ`: pixels whose colour differs between the two frames (by at most that many",
           "LSBs); `equal`: the same `max_lsb` with and without the skip.",
           "",
           "| scene | unit | µJ/frame | saving | pJ/shaded px | max_lsb | mean_lsb | "
           "weighted.max_lsb8 | dp ulps | differ | equal |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, res, lights, r in first:
        out.append(
            f"| {name} ({res}, {lights} light{'s' if lights > 1 else ''}) | {r['unit']} "
            f"| {r['uj_on']:.2f} / {r['uj_off']:.2f} "
            f"| {saving(r['uj_on'], r['uj_off'])}, {r['uj_off'] - r['uj_on']:.2f} µJ "
            f"| {r['px_on']:.1f} / {r['px_off']:.1f} "
            f"| {r['max_on']:g} / {r['max_off']:g} | {r['mean_on']:.4f} / {r['mean_off']:.4f} "
            f"| {r['wlsb_on']:.2f} / {r['wlsb_off']:.2f} "
            f"| {r['ulps_on']:.2f} / {r['ulps_off']:.2f} "
            f"| {differ_cell(r)} | {'yes' if r['equal'] else '**no**'} |")
    out += ["",
            "## At equal error",
            "",
            "**What counts as equal error.** An architect signs a lane off against the worst pixel",
            "error it leaves on the frames that matter, in whole codes of the display: the budget",
            "`image.max_lsb<=K` that `glint size --scene` sizes against. Two lanes are at equal",
            "error when they meet the same such budget on the same frame; a same-spec comparison",
            "qualifies only where `equal` above is yes, and is exact only where `differ` is 0 (the",
            "frames are identical: the skip then removes only requests whose result is 0 anyway;",
            "hast's and horner's datapaths are built on [tau, 1] and give 0 below it, but for the",
            "slots that share a material's datapath built for a lower tau, as multi's lights do).",
            "Where the skip changes the frame (pow: fewer pixels off by 1 LSB without it; lut: a",
            "table over [0, 1] instead of [tau, 1], coarser at the highlight's foot), and to be",
            "sure where it does not, the fair saving is each side's least",
            "energy at one budget: the worst pixel error K the default lane with the skip reaches on",
            "the scene, over one grid per family around its defaults (input and output widths and",
            "the unit's accuracy key, below), the skip fixed on, then fixed off: `glint size",
            "--scene SCENE --budget 'image.max_lsb<=K' --objective energy --node osu018 --no-widen",
            "--grid 'GRID,skip=on'` (then `skip=off`); both sides choose from the same grid. pJ",
            "per request and µJ per frame (pJ per request x the frame's requests); `same spec`:",
            "the first table's saving, for comparison.",
            "",
            "| scene | unit | budget | with the skip | pJ/req | without the skip | pJ/req "
            "| saving | same spec |",
            "|---|---|---|---|---|---|---|---|---|"]
    per_unit = {}
    for name, r, budget, on, off in second:
        def cell(c):
            if c is None:
                return "none meets it", "-"
            return f"`{c[0]}`", f"{c[1]:.1f} ({c[1] * r['requests'] / 1e6:.2f} µJ)"
        con, coff = cell(on), cell(off)
        sav = saving(on[1], off[1]) if on and off else "-"
        out.append(f"| {name} | {r['unit']} | `{budget}` | {con[0]} | {con[1]} | {coff[0]} "
                   f"| {coff[1]} | {sav} | {saving(r['uj_on'], r['uj_off'])} |")
        u = per_unit.setdefault(r["unit"], {"same": [], "fair": [], "off_misses": []})
        u["same"].append(100 * (r["uj_off"] - r["uj_on"]) / r["uj_off"])
        if on and off:
            u["fair"].append(100 * (off[1] - on[1]) / off[1])
        elif on:
            u["off_misses"].append(name)
    out += ["", "Grids (the skip key appended):", ""]
    out += [f"- `{g}`" for g in GRIDS.values()]

    def span(values):
        if not values:
            return "-"
        lo, hi = min(values), max(values)
        return f"{lo:.0f} %" if round(lo) == round(hi) else f"{lo:.0f} to {hi:.0f} %"

    out += ["",
            "## Per unit, over the scenes",
            "",
            "The saving the skip buys, lowest to highest over the shipped scenes: the same spec",
            "with the skip and without it, and at equal error (above); where no lane of the grid",
            "without the skip meets the budget, the skip is what makes the budget reachable.",
            "",
            "| unit | same spec | at equal error | no lane without the skip meets the budget |",
            "|---|---|---|---|"]
    for unit, u in per_unit.items():
        out.append(f"| {unit} | {span(u['same'])} | {span(u['fair'])} | "
                   f"{', '.join(u['off_misses']) or '-'} |")
    with open(args.o, "w") as f:
        f.write("\n".join(out) + "\n")
    print(f"skip_energy.py: wrote {os.path.relpath(args.o, TOP)}", file=sys.stderr)


if __name__ == "__main__":
    main()
