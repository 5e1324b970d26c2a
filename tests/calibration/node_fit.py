#!/usr/bin/env python3
"""The cost proxy at a real node: its per-part constants, and what whole lanes add to them.

    python3 tests/calibration/node_fit.py --primitives tests/calibration/primitives_osu018.csv \\
        -o src/cost/node_osu018.h

fits the constants glint uses (src/cost/node_osu018.h, cost/node.h) on the primitives mapped to
the library and timed by OpenSTA (primitives.py --liberty osu018): per kind, um2 per GE and the
delay's terms, printed with their residuals and written as the C++ header.

    python3 tests/calibration/node_fit.py --lanes build/glint tests/calibration/set_osu018.json \\
        --holdout tests/calibration/holdout_osu018.json -o src/cost/node_lanes_osu018.h

fits, on the calibration lanes alone, what primitives mapped one by one cannot show: the overlap
of arithmetic parts in a row on a path (NodeOverlap: an adder before a multiplier; an adder,
comparator or select after one) and the area abc saves by sharing logic across a lane's parts
(NodePart::lane_area of multipliers, ROMs and the other logic; registers and RAMs are kept as
measured). It reads each lane's parts from `glint sim --node osu018 --json` (the path's chain of
primitives with their own delays, the area per part before the lane factors), so the build's own
factors do not enter; minimises the sum of squared log ratios (proxy / library, proxy / OpenSTA)
by coordinate descent on a grid of 0.01, and prints the ratios on the set and the hold-out, which
is fitted on nothing. The lanes' check is calibration_report (src/cost/README.md, "At a real
node"). Pure Python (no numpy): the fits are small.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def solve(a, b):
    """Least squares by the normal equations (Gaussian elimination; small, well-scaled)."""
    n = len(a[0])
    m = [[sum(r[i] * r[j] for r in a) for j in range(n)] + [sum(r[i] * y for r, y in zip(a, b))]
         for i in range(n)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        if abs(m[c][c]) < 1e-300:
            continue
        for r in range(n):
            if r != c:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][n] / m[i][i] if abs(m[i][i]) > 1e-300 else 0.0 for i in range(n)]


def nnls(a, b):
    """Lawson-Hanson active set: min |a x - b| with x >= 0."""
    n = len(a[0])
    x, free = [0.0] * n, []
    for _ in range(3 * n):
        r = [y - sum(ai * xi for ai, xi in zip(row, x)) for row, y in zip(a, b)]
        w = [sum(row[j] * ri for row, ri in zip(a, r)) for j in range(n)]
        cand = [j for j in range(n) if j not in free and w[j] > 1e-9]
        if not cand:
            break
        free.append(max(cand, key=lambda j: w[j]))
        while True:
            z = solve([[row[j] for j in free] for row in a], b)
            if all(v > 0 for v in z):
                x = [0.0] * n
                for j, v in zip(free, z):
                    x[j] = v
                break
            alpha = min(x[j] / (x[j] - v) for j, v in zip(free, z) if v <= 0)
            zz = dict(zip(free, z))
            x = [x[j] + alpha * (zz.get(j, 0.0) - x[j]) for j in range(n)]
            free = [j for j in free if x[j] > 1e-12]
    return x


def ranks(v):
    order = sorted(range(len(v)), key=lambda i: v[i])
    r = [0.0] * len(v)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return r


def spearman(a, b):
    if len(a) < 3:
        return float("nan")
    ra, rb = ranks(a), ranks(b)
    ma, mb = sum(ra) / len(ra), sum(rb) / len(rb)
    sab = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    saa = sum((x - ma) ** 2 for x in ra)
    sbb = sum((y - mb) ** 2 for y in rb)
    return sab / (saa * sbb) ** 0.5 if saa and sbb else float("nan")


# ---- per-part constants from the primitives at the node (primitives.py --liberty) -------------

# Proxy kind -> primitives.csv kinds it is fitted on.
AREA_KINDS = {"adder": ["adder"], "comparator": ["comparator"],
              "multiplier": ["multiplier", "const_multiplier"], "divider": ["divider_row"],
              "mux": ["mux"], "shifter": ["shifter"], "lzd": ["lzd"], "rom": ["rom"],
              "ram": ["ram"], "ram_computed": ["ram"], "dff": ["register/"], "dffe": ["register/enable"]}


def log2(v):
    return math.log2(max(v, 1))


def clog2(v):
    return (max(v, 1) - 1).bit_length()


def delay_terms(kind, r):
    """(x, y, loads) of a primitive row as builder.h passes them to NodeDelay::at."""
    a, b = r["a"], r["b"]
    if kind == "multiplier":
        if r["kind"] == "const_multiplier":
            ones = int(r["variant"].split("ones=")[1])
            return a + ones, min(a, ones), 0
        return a + b, min(a, b), 0
    if kind in ("mux", "ram", "ram_computed"):
        # The select's loads as y: abc buffers the net (a tree, log2 of its loads deep).
        return clog2(b if kind == "mux" else a), a * b, a * b
    if kind == "rom":
        return b, a, 0
    return a, a, 0


TERMS = ("c0", "x", "log2", "load", "load2")
# Which of c0, per_x, per_log2, per_load each kind's delay uses (the shapes of the data).
DELAY_SHAPE = {"adder": "c0 x", "comparator": "c0 log2", "multiplier": "c0 x log2",
               "divider": "c0 x", "mux": "c0 x log2", "ram": "c0 x log2", "ram_computed": "c0 x log2",
               "rom": "c0 log2",
               "shifter": "c0 x", "lzd": "c0 x"}


def fit_primitives(path, out):
    rows = []
    for line in open(path):
        if line.startswith("#") or line.startswith("kind,"):
            continue
        k, a, b, variant, ge, depth, um2, ns, cells = next(csv.reader([line]))
        rows.append({"kind": k, "a": int(a), "b": int(b), "variant": variant, "ge": float(ge),
                     "depth": int(depth), "um2": float(um2), "ns": float(ns)})
    reg_ns = next(r["ns"] for r in rows if r["kind"] == "wire")
    lines, consts = [], {}
    for kind, sources in AREA_KINDS.items():
        sel = [r for r in rows if any(r["kind"] == s or f"{r['kind']}/{r['variant']}" == s
                                      for s in sources)]
        ratio = sum(r["um2"] for r in sel) / sum(r["ge"] for r in sel)
        res = [r["um2"] / (r["ge"] * ratio) - 1 for r in sel]
        c = {"um2": ratio, "area_res": (min(res), max(res), len(sel)), "delay": [0.0] * len(TERMS)}
        shape = DELAY_SHAPE.get(kind)
        if shape:
            cols = [t for t in TERMS if t in shape.split()]
            feats = []
            for r in sel:
                x, y, loads = delay_terms(kind, r)
                f = {"c0": 1.0, "x": x, "log2": log2(y), "load": loads, "load2": loads * loads}
                feats.append([f[t] for t in cols])
            logic = [r["ns"] - reg_ns for r in sel]
            # Relative errors on the whole path (register overhead included), as a lane's stage.
            coef = solve([[v / (y + reg_ns) for v in f] for f, y in zip(feats, logic)],
                         [y / (y + reg_ns) for y in logic])
            full = dict(zip(cols, coef))
            c["delay"] = [full.get(t, 0.0) for t in TERMS]
            pred = [sum(v * cc for v, cc in zip(f, coef)) for f in feats]
            dres = [(max(p, 0) + reg_ns) / (y + reg_ns) - 1 for p, y in zip(pred, logic)]
            c["delay_res"] = (min(dres), max(dres))
        consts[kind] = c
    # Registers and glue gates have no primitive of their own: a register's delay is reg_ns, a
    # glue gate's one stage of the adder's carry chain (its ns per bit).
    consts["gates"] = {"um2": 32.0 / 1.5, "area_res": None,
                       "delay": [consts["adder"]["delay"][1], 0, 0, 0, 0]}
    print(f"register to register: {reg_ns:.4f} ns")
    for kind, c in consts.items():
        d = c["delay"]
        print(f"{kind:10} {c['um2']:7.2f} um2/GE" +
              (f" ({c['area_res'][0]:+.1%}..{c['area_res'][1]:+.1%}, {c['area_res'][2]})"
               if c["area_res"] else "") +
              f"  ns = {d[0]:.4f} + {d[1]:.5f} x + {d[2]:.4f} log2 y + {d[3]:.6f} L + {d[4]:.3g} L^2" +
              (f" ({c['delay_res'][0]:+.1%}..{c['delay_res'][1]:+.1%})"
               if "delay_res" in c else ""))
    if out:
        write_header(out, path, reg_ns, consts)
    return 0


def write_header(out, source, reg_ns, consts):
    body = []
    for kind, c in consts.items():
        d = c["delay"]
        note = []
        if c["area_res"]:
            note.append(f"area {c['area_res'][0]:+.0%}..{c['area_res'][1]:+.0%} over "
                        f"{c['area_res'][2]} primitives")
        else:
            note.append("area: the library's AND2 (32 um2) per 1.5 GE")
        if "delay_res" in c:
            note.append(f"delay {c['delay_res'][0]:+.0%}..{c['delay_res'][1]:+.0%}")
        elif kind == "gates":
            note.append("delay: a stage of the adder's carry chain")
        body.append(f"  // {kind}: {'; '.join(note)}\n"
                    f"  k.{kind} = {{{c['um2']:.4f}, {{{d[0]:.5f}, {d[1]:.6f}, {d[2]:.5f}, "
                    f"{d[3]:.7f}, {d[4]:.4g}}}}};")
    # The stored command, whatever file was fitted: a re-derivation compares headers as text.
    text = f"""// Generated by tests/calibration/node_fit.py --primitives
// tests/calibration/primitives_osu018.csv -o src/cost/node_osu018.h
// from primitives between registers mapped to OSU 0.18 um and timed by OpenSTA
// (tests/calibration/primitives.py --liberty osu018). Do not edit: re-fit (src/cost/README.md).
// Per kind: um2 per proxy GE, and the delay c0 + per_x x + per_log2 log2 y + per_load loads
// (cost/node.h; x, y and loads as cost/builder.h passes them); the residuals are the fit's worst
// over its primitives (delays relative to the whole register-to-register path).
#pragma once

#include "cost/node.h"
#include "cost/node_lanes_osu018.h"

namespace glint {{

inline NodeConstants make_osu018() {{
  NodeConstants k;
  k.name = "osu018";
  k.library = "OSU 0.18 um standard cells (qflow-tech-osu018), abc -liberty, OpenSTA";
  k.reg_ns = {reg_ns:.4f};  // clock-to-Q + setup, register to register
{chr(10).join(body)}
  fit_lanes_osu018(k);  // what whole lanes add (node_fit.py --lanes)
  return k;
}}

}}  // namespace glint
"""
    open(out, "w").write(text)


# The lane fit. Mirrors CostBuilder::close (src/cost/builder.h): which factor a part of the chain
# takes.
OVERLAP = ("adder_before_multiplier", "adder_after", "comparator_after", "mux_after")


def path_ns(path, f):
    ns = path["ns"] - sum(a["counted_ns"] for a in path["chain"])  # the register overhead
    after, chain = False, path["chain"]
    for i, a in enumerate(chain):
        before = i + 1 < len(chain) and chain[i + 1]["kind"] == "multiplier"
        x = 1.0
        if a["kind"] == "adder" and before:
            x = f[0]
        elif after and a["kind"] in ("adder", "comparator", "mux"):
            x = f[1 + ("adder", "comparator", "mux").index(a["kind"])]
        ns += x * a["ns"]
        after = a["kind"] == "multiplier" or (after and x < 1)
    return ns


# Area groups: each takes one lane_area factor; parts in no group are kept as measured.
AREA_GROUPS = {"multiplier": ["multiplier"], "rom": ["rom"],
               "logic": ["adder", "comparator", "divider", "mux", "shifter", "lzd", "gates"]}


def lane_area(parts, g):
    return sum(um2 * next((g[k] for k, v in AREA_GROUPS.items() if part in v), 1.0)
               for part, um2 in parts.items())


def lanes(glint, path):
    rows = []
    for c in json.load(open(path))["configs"]:
        if not c.get("timing"):
            continue  # left out (a timeout) or a library OpenSTA could not time
        out = subprocess.run([glint, "sim", os.path.join(ROOT, c["vectors"]), "--unit", c["spec"],
                              "--node", "osu018", "--json"],
                             check=True, capture_output=True, text=True).stdout
        u = json.loads(out)["units"][0]
        rows.append({"spec": c["spec"], "unit": u["unit"], "um2": c["area_um2"],
                     "ns": c["timing"]["critical_path_ns"], "paths": u["node"]["paths"],
                     "parts": u["node"]["area_um2_unfitted_by_part"]})
    return rows


def ratios(rows, f, g):
    return ([lane_area(r["parts"], g) / r["um2"] for r in rows],
            [max(path_ns(p, f) for p in r["paths"]) / r["ns"] for r in rows])


def descend(cost, x, lo, hi):
    for _ in range(8):
        for i in range(len(x)):
            x[i] = min((cost(x[:i] + [v / 100] + x[i + 1:]), v / 100)
                       for v in range(lo, hi + 1))[1]
    return x


def lane_report(name, rows, f, g):
    area, path = ratios(rows, f, g)
    print(f"\n{name}: {len(rows)} lanes; area ratio {min(area):.3f}..{max(area):.3f} "
          f"({sum(abs(a - 1) > 0.10 for a in area)} outside +-10 %), path ratio "
          f"{min(path):.3f}..{max(path):.3f} ({sum(abs(p - 1) > 0.15 for p in path)} outside "
          f"+-15 %)")
    for unit in sorted({r["unit"] for r in rows}) + ["all"]:
        sel = [i for i, r in enumerate(rows) if unit in ("all", r["unit"])]
        print(f"  {unit:8} {len(sel):3} lanes  area {min(area[i] for i in sel):.3f}.."
              f"{max(area[i] for i in sel):.3f} Spearman "
              f"{spearman([area[i] * rows[i]['um2'] for i in sel], [rows[i]['um2'] for i in sel]):.3f}"
              f"  path {min(path[i] for i in sel):.3f}..{max(path[i] for i in sel):.3f} Spearman "
              f"{spearman([path[i] * rows[i]['ns'] for i in sel], [rows[i]['ns'] for i in sel]):.3f}")


def fit_lanes(glint, set_path, holdout, out):
    rows = lanes(glint, set_path)
    f = descend(lambda x: sum(math.log(max(path_ns(p, x) for p in r["paths"]) / r["ns"]) ** 2
                              for r in rows), [1.0] * len(OVERLAP), 0, 100)
    keys = list(AREA_GROUPS)
    gl = descend(lambda x: sum(math.log(lane_area(r["parts"], dict(zip(keys, x))) / r["um2"]) ** 2
                               for r in rows), [1.0] * len(keys), 50, 130)
    g = dict(zip(keys, gl))
    print("overlap: " + ", ".join(f"{k} {v:.2f}" for k, v in zip(OVERLAP, f)))
    print("lane area: " + ", ".join(f"{k} {v:.2f}" for k, v in g.items()))
    lane_report("fitted on", rows, f, g)
    if holdout:
        lane_report("hold-out", lanes(glint, holdout), f, g)
    if out:
        sets = "\n".join(f"  k.{part}.lane_area = {g[grp]:.2f};"
                         for grp, parts in AREA_GROUPS.items() for part in parts)
        open(out, "w").write(f"""// Generated by tests/calibration/node_fit.py --lanes build/glint
// tests/calibration/set_osu018.json -o src/cost/node_lanes_osu018.h from the calibration lanes
// mapped to OSU 0.18 um and timed by OpenSTA (synth_set.py --liberty osu018). Do not edit: re-fit
// (src/cost/README.md, "At a real node").
#pragma once

#include "cost/node.h"

namespace glint {{

// What whole lanes add to the primitives' constants (cost/node.h: NodeOverlap, lane_area).
inline void fit_lanes_osu018(NodeConstants& k) {{
  k.overlap = {{{f[0]:.2f}, {f[1]:.2f}, {f[2]:.2f}, {f[3]:.2f}}};
{sets}
}}

}}  // namespace glint
""")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--primitives", help="fit the per-part constants on this CSV "
                    "(primitives.py --liberty)")
    ap.add_argument("--lanes", nargs=2, metavar=("GLINT", "SET"),
                    help="fit the lane factors on this stored set (synth_set.py --liberty)")
    ap.add_argument("--holdout", help="with --lanes: also report this stored set")
    ap.add_argument("-o", "--output", help="write the C++ header here")
    args = ap.parse_args()
    if args.primitives:
        return fit_primitives(args.primitives, args.output)
    if args.lanes:
        return fit_lanes(args.lanes[0], args.lanes[1], args.holdout, args.output)
    ap.error("give --primitives CSV or --lanes GLINT SET")


if __name__ == "__main__":
    sys.exit(main())
