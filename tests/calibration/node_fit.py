#!/usr/bin/env python3
"""The cost proxy at a real node: its per-part constants, and an earlier whole-lane fit.

    python3 tests/calibration/node_fit.py --primitives tests/calibration/primitives_osu018.csv \\
        -o src/cost/node_osu018.h

fits the constants glint uses (src/cost/node_osu018.h, cost/node.h) on the primitives mapped to
the library and timed by OpenSTA (primitives.py --liberty osu018): per kind, um2 per GE and the
delay's terms, printed with their residuals and written as the C++ header. The lanes' check is
calibration_report on set_osu018.json (src/cost/README.md, "At a real node").

    python3 tests/calibration/node_fit.py build/glint tests/calibration/set_osu018.json \\
        [--holdout tests/calibration/holdout_osu018.json]

is the earlier whole-lane fit, kept for comparison:

For every stored configuration the lane's proxy is read from `glint sim --json` (its area
inventory by part kind, in gate equivalents, and its critical path in gate levels). Two models
are fitted on the set alone and printed with their residuals on the set and the hold-out, per
unit: area in um2 as a non-negative sum over part kinds (um2 per GE of adders, multipliers,
registers, tables, ...; Lawson-Hanson on relative errors), and the worst path in ns as an affine
function of the proxy's levels. Issue 26's targets: area within +-10 %, path within +-15 %,
Spearman rank correlation >= 0.95, for every unit. Pure Python (no numpy): the fits are small.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def proxy(glint, spec, vectors):
    out = subprocess.run([glint, "sim", "--json", "--unit", spec, os.path.join(ROOT, vectors)],
                         check=True, capture_output=True, text=True).stdout
    u = json.loads(out)["units"][0]
    kinds = {}
    for part in u["area"]["inventory"]:
        kinds[part["kind"]] = kinds.get(part["kind"], 0.0) + part["ge"]
    return {"unit": u["unit"], "ge": u["area"]["ge"], "kinds": kinds,
            "levels": u["critical_path"]["delay"], "stage": u["critical_path"]["stage"]}


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


def load(glint, path):
    rows = []
    for c in json.load(open(path))["configs"]:
        if "error" in c:
            print(f"  left out: {c['spec']} ({c['error']})", file=sys.stderr)
            continue
        rows.append({**c, "proxy": proxy(glint, c["spec"], c["vectors"])})
    return rows


def report(name, rows, kinds, area_c, path_c):
    area = [sum(area_c[k] * r["proxy"]["kinds"].get(kind, 0.0) for k, kind in enumerate(kinds))
            for r in rows]
    path = [path_c[0] + path_c[1] * r["proxy"]["levels"] for r in rows]
    print(f"\n{name}: {len(rows)} configurations")
    print(f"{'unit':9} {'n':>3} {'area residuals':>18} {'rho':>5} {'path residuals':>18} {'rho':>5}")
    units = sorted({r["proxy"]["unit"] for r in rows}) + ["all"]
    for u in units:
        idx = [i for i, r in enumerate(rows) if u == "all" or r["proxy"]["unit"] == u]
        ra = [area[i] / rows[i]["area_um2"] - 1 for i in idx]
        rt = [path[i] / rows[i]["timing"]["critical_path_ns"] - 1 for i in idx]
        sa = spearman([area[i] for i in idx], [rows[i]["area_um2"] for i in idx])
        st = spearman([rows[i]["proxy"]["levels"] for i in idx],
                      [rows[i]["timing"]["critical_path_ns"] for i in idx])
        print(f"{u:9} {len(idx):>3} {min(ra):+8.1%}..{max(ra):+7.1%} {sa:5.2f} "
              f"{min(rt):+8.1%}..{max(rt):+7.1%} {st:5.2f}")


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

namespace glint {{

inline NodeConstants make_osu018() {{
  NodeConstants k;
  k.name = "osu018";
  k.library = "OSU 0.18 um standard cells (qflow-tech-osu018), abc -liberty, OpenSTA";
  k.reg_ns = {reg_ns:.4f};  // clock-to-Q + setup, register to register
{chr(10).join(body)}
  return k;
}}

}}  // namespace glint
"""
    open(out, "w").write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint", nargs="?")
    ap.add_argument("set", nargs="?")
    ap.add_argument("--holdout")
    ap.add_argument("--primitives", help="fit the per-part constants on this CSV "
                    "(primitives.py --liberty) instead")
    ap.add_argument("-o", "--output", help="with --primitives: write the C++ header here")
    args = ap.parse_args()
    if args.primitives:
        return fit_primitives(args.primitives, args.output)
    if not args.glint or not args.set:
        ap.error("give GLINT SET (the whole-lane fit) or --primitives CSV")
    fit = load(args.glint, args.set)
    kinds = sorted({k for r in fit for k in r["proxy"]["kinds"]})
    # Relative errors: each row divided by its library area.
    a = [[r["proxy"]["kinds"].get(k, 0.0) / r["area_um2"] for k in kinds] for r in fit]
    area_c = nnls(a, [1.0] * len(fit))
    lv = [[1.0 / r["timing"]["critical_path_ns"], r["proxy"]["levels"] /
           r["timing"]["critical_path_ns"]] for r in fit]
    path_c = solve(lv, [1.0] * len(fit))
    print("area: um2 per proxy GE, by part kind: " +
          ", ".join(f"{k} {c:.3f}" for k, c in zip(kinds, area_c)))
    print(f"path: ns = {path_c[0]:.3f} + {path_c[1]:.4f} x proxy levels")
    report("fitted on", fit, kinds, area_c, path_c)
    if args.holdout:
        report("hold-out", load(args.glint, args.holdout), kinds, area_c, path_c)
    return 0


if __name__ == "__main__":
    sys.exit(main())
