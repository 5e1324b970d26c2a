#!/usr/bin/env python3
"""How well glint's cost proxy predicts a real node: the calibration set mapped to a Liberty
library and timed by OpenSTA (synth_set.py --liberty), against the proxy of the same lanes.

    python3 tests/calibration/node_fit.py build/glint tests/calibration/set_osu018.json \\
        [--holdout tests/calibration/holdout_osu018.json]

For every stored configuration the lane's proxy is read from `glint sim --json` (its area
inventory by part kind, in gate equivalents, and its critical path in gate levels). Two models
are fitted on the set alone and printed with their residuals on the set and the hold-out, per
unit: area in um2 as a non-negative sum over part kinds (um2 per GE of adders, multipliers,
registers, tables, ...; Lawson-Hanson on relative errors), and the worst path in ns as an affine
function of the proxy's levels. Issue 26's targets: area within +-10 %, path within +-15 %,
Spearman rank correlation >= 0.95, for every unit. Pure Python (no numpy): the fits are small.
"""
import argparse
import json
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint")
    ap.add_argument("set")
    ap.add_argument("--holdout")
    args = ap.parse_args()
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
