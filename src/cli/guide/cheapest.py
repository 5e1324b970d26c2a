#!/usr/bin/env python3
"""Writes cheapest.md: which unit is cheapest at 1 LSB of an 8-bit sRGB display (issue 27 item 4).

For Phong exponents n = 2, 4, ..., 512 (one material each, and all nine on one chip) and for the
shipped scenes, `glint size` picks the cheapest configuration of every unit family that keeps the
highlight within one display LSB, on a chip with ROM tables (the scene's materials fixed at
synthesis) and on one with loadable tables (a GPU's: registers the driver writes per material).
The page gives the winner and how far each family sits from it, then `glint sweep`'s error-area
plot for the nine exponents on the loadable chip.

Usage (from the repository's top folder, with a Release build in build/):
    python3 src/cli/guide/cheapest.py build/glint
It rewrites src/cli/guide/cheapest.md and src/cli/guide/cheapest/*.svg; about 6 minutes of CPU.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.normpath(os.path.join(HERE, "..", "..", ".."))

EXPONENTS = [2, 4, 8, 16, 32, 64, 128, 256, 512]
SCENES = ["teapot.json", "multi.json", "bunny.json"]
BUDGET = "max_lsb<=1"
SCENE_BUDGET = "image.max_lsb<=1"
CHIPS = [("rom", "ROM tables (the input's materials fixed at synthesis)"),
         ("ram", "loadable tables (registers the driver writes with each material, as a GPU's)")]

# size's default grid per family (src/sweep/size.cpp, src/cli/guide/size.md), plus the units
# outside the default set. size widens each where its answer improves beyond an end.
GRIDS = [
    "pow:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,log_bits=4..8/2,exp_bits=4|6",
    "schlick:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,match=none|width|minimax",
    "hast:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,d=2..5,match=none|minimax",
    "horner:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,degree=2..6",
    "lut:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,bits=4..9",
    "sfu:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.8|uq1.10|uq1.12",
]
# Grids of units that may not be in every build's catalogue yet: used when `glint units` lists
# them.
OPTIONAL_GRIDS = {
    "pwp": ["pwp:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.8|uq1.10|uq1.12,segments=2..5,degree=1..3",
            # The log domain: tables shared by every material, n per slot (the SFU's design).
            "pwp:domain=log,in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.8|uq1.9|uq1.10,segments=3..6,"
            "degree=1..2"],
}
PAPERS = {"schlick": "Schlick 1994", "hast": "Hast et al. 2003", "horner": "Öztürk et al. 2006",
          "sfu": "Tesla-class GPU SFU"}


def run(cmd, cwd=None):
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd)
    if done.returncode not in (0, 1):  # size exits 1 when nothing meets the budget
        sys.exit(f"cheapest.py: {' '.join(cmd)} exited {done.returncode}:\n{done.stderr}")
    return done.stdout


def write_trace(path, exponents):
    # One white Phong material per exponent, t swept over [-1, 1] in steps of 0.001 (as
    # traces/phong_basic.vec, finer), on an 8-bit sRGB display.
    with open(path, "w") as f:
        f.write("# cheapest.py: white Phong materials n = %s, t over [-1, 1] step 0.001\n"
                % ", ".join(map(str, exponents)))
        f.write("glint-vectors 1\neps 1e-3\ndisplay srgb8\nlights 1\n")
        for n in exponents:
            f.write(f"material n{n} specular=1,1,1 shininess={n} lobe=phong\n")
        f.write("columns t material\ndata\n")
        for n in exponents:
            for i in range(2001):
                f.write(f"{-1 + i * 0.001:.3f} n{n}\n")


def size(glint, grids, chip, inputs, budget, cwd):
    # Widening shares one cap over every grid: room for each family's rounds (size's default,
    # 1000, was spent before the last grids widened once pwp had two).
    cmd = [glint, "size", "--chip", chip, "--budget", budget, "--json",
           "--widen-configurations", "4000"]
    for g in grids:
        cmd += ["--grid", g]
    return json.loads(run(cmd + inputs, cwd))


def family_cell(family, best_value):
    if family.get("spec") is None:
        reached = family.get("reached", [])
        best = reached[0]["best"] if reached else float("nan")
        return f"misses ({best:.3g} LSB)"
    ratio = family["value"] / best_value
    return f"{family['value']:.0f} (x{ratio:.2f})" if ratio > 1.0005 else f"**{family['value']:.0f}**"


def table(rows, units):
    head = "| input | cheapest at 1 LSB | " + " | ".join(units) + " |"
    out = [head, "|" + "---|" * (len(units) + 2)]
    for label, doc in rows:
        best = doc.get("best")
        fams = {f["unit"]: f for f in doc["families"]}
        if best is None:
            out.append(f"| {label} | none meets it | " +
                       " | ".join(family_cell(fams[u], 1.0) if u in fams else "-" for u in units) +
                       " |")
            continue
        cells = [family_cell(fams[u], best["value"]) if u in fams else "-" for u in units]
        out.append(f"| {label} | `{best['spec']}` | " + " | ".join(cells) + " |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint", help="the glint program (a Release build)")
    args = ap.parse_args()
    glint = os.path.abspath(args.glint)
    catalogue = json.loads(run([glint, "units", "--json"]))
    names = [u["name"] for u in catalogue["units"]]
    grids = GRIDS + [g for u, gs in OPTIONAL_GRIDS.items() if u in names for g in gs]
    units = list(dict.fromkeys(g.split(":")[0] for g in grids))  # a family per unit
    commit = subprocess.run(["git", "-C", TOP, "rev-parse", "--short", "HEAD"],
                            stdout=subprocess.PIPE, text=True).stdout.strip()

    work = tempfile.mkdtemp(prefix="glint-cheapest-")
    try:
        traces = []
        for n in EXPONENTS:
            # Named relative to the work folder, the commands' working folder, so that no
            # temporary path reaches the plot's title.
            write_trace(os.path.join(work, f"n{n}.vec"), [n])
            traces.append((f"n = {n}", [f"n{n}.vec"]))
        every = "n2-512.vec"
        write_trace(os.path.join(work, every), EXPONENTS)
        traces.append(("n = 2..512 on one chip", [every]))
        for scene in SCENES:
            traces.append((f"scene {scene}",
                           ["--scene", os.path.join(TOP, "traces", "scenes", scene)]))

        sections = []
        for chip, what in CHIPS:
            rows = []
            for label, inputs in traces:
                budget = SCENE_BUDGET if inputs[0] == "--scene" else BUDGET
                print(f"cheapest.py: {chip} {label}", file=sys.stderr)
                rows.append((label, size(glint, grids, chip, inputs, budget, work)))
            sections.append((chip, what, table(rows, units)))

        plots = os.path.join(HERE, "cheapest")
        tmp_plots = os.path.join(work, "plots")
        cmd = [glint, "sweep", "--chip", "ram", "--plot", "plots", "-o", "sweep.json"]
        for g in grids:
            cmd += ["--grid", g]
        print("cheapest.py: sweep plot", file=sys.stderr)
        run(cmd + [every], work)
        os.makedirs(plots, exist_ok=True)
        for name in ("error_vs_area.svg",):
            shutil.copyfile(os.path.join(tmp_plots, name), os.path.join(plots, name))
    finally:
        shutil.rmtree(work, ignore_errors=True)

    lines = [
        "# Which unit is cheapest at one display LSB",
        "",
        "Generated by `python3 src/cli/guide/cheapest.py build/glint` (glint "
        f"{commit}); do not edit by hand. Each row is one `glint size` run: the budget is "
        f"`{BUDGET}` (the request-level error in LSBs of an 8-bit sRGB display) on the traces "
        f"and `{SCENE_BUDGET}` (the rendered image's) on the shipped scenes; the objective is "
        "area (GE, the proxy calibrated to Yosys: [src/cost/README.md](../../cost/README.md)). "
        "The traces hold one white Phong material of exponent n each (t over [-1, 1] in steps "
        "of 0.001, eps 1e-3), and one holds all nine: one chip serving every exponent.",
        "",
        "A cell gives the family's cheapest configuration meeting the budget, in GE, and its "
        "ratio to the winner (bold: the winner), or `misses` with the least error any of its "
        "configurations reached (`glint size` widens each grid while the answer improves; "
        "its grids are listed in the script). The papers' units: "
        + ", ".join(f"`{u}` ({p})" for u, p in PAPERS.items() if u in units)
        + "; `pow` and `lut` are the textbook baselines"
        + (", `pwp` the piecewise polynomial (in t with a table per material, or `domain=log` with "
           "tables shared by every material)." if "pwp" in units else ".")
        + " Energy is not in the table yet: glint's energy at the node (`--node osu018`, `glint "
        "size --objective energy`) is fitted to its gate-level reference only within -26 % to "
        "+48 % (src/cost/README.md, \"Energy\")."
        + " `sfu` and `pwp` have no lanes in the cost calibration set yet, so their areas are the "
        "proxy's uncalibrated estimate; `glint synth SPEC --vectors FILE` gives Yosys's figure "
        "for any cell's spec.",
        "",
    ]
    for chip, what, tab in sections:
        lines += [f"## `--chip {chip}`: {what}", "", tab, ""]
    lines += [
        "No unit meets one LSB on `multi.json`'s image: its `satin` material has a Gaussian lobe "
        "(Källberg & Larsson eq.7, roughness 0.25) and every unit computes t^n at the "
        "equivalent n = 2/ω² = 32, whose difference from the Gaussian alone is 2 LSB on the "
        "image: `glint render traces/scenes/multi.json --unit "
        "'sfu:in=uq1.23,out=uq1.16,skip=off'` has max_lsb 2, and 1 with `satin` made a Phong "
        "lobe of n = 32.",
        "",
    ]
    lines += [
        "## Error against area, n = 2..512 on one loadable chip",
        "",
        "`glint sweep --chip ram --plot` over the same grids (not widened) on the nine-exponent "
        "trace: the max error in LSBs against the area, one mark per configuration.",
        "",
        "![error against area](cheapest/error_vs_area.svg)",
        "",
    ]
    with open(os.path.join(HERE, "cheapest.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
