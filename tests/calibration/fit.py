#!/usr/bin/env python3
"""Fits the cost proxy's constants (src/cost/cost_model.h) to the primitive sweeps and prints each
with what it was fitted on and its residual (the error budget beside the constants).

    python3 tests/calibration/fit.py tests/calibration/primitives.csv
"""
import csv
import math
import sys


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]


def lsq(xs, ys):
    """Least squares y ~ sum_i c_i x_i (xs: list of feature tuples); returns the c_i."""
    n = len(xs[0])
    a = [[sum(x[i] * x[j] for x in xs) for j in range(n)] for i in range(n)]
    b = [sum(x[i] * y for x, y in zip(xs, ys)) for i in range(n)]
    for i in range(n):  # Gauss-Jordan, n is 1-3
        p = a[i][i]
        for j in range(n):
            a[i][j] /= p
        b[i] /= p
        for k in range(n):
            if k != i:
                f = a[k][i]
                for j in range(n):
                    a[k][j] -= f * a[i][j]
                b[k] -= f * b[i]
    return b


def report(name, feats, ys, label):
    c = lsq(feats, ys)
    pred = [sum(ci * xi for ci, xi in zip(c, x)) for x in feats]
    res = [(p - y) / y for p, y in zip(pred, ys) if y]
    worst = max(res, key=abs) if res else 0
    med = sorted(abs(r) for r in res)[len(res) // 2] if res else 0
    print(f"{name}: {' '.join(f'{v:.4g}' for v in c)}  ({label}; {len(ys)} points, worst "
          f"{100 * worst:+.1f} %, median |{100 * med:.1f}| %)")
    return c


def rom_nodes(words, width):
    """Decision-diagram nodes of a case ROM, as cost_model.cpp's rom_ge counts them."""
    if len(words) <= 2:
        return 0
    ab = (len(words) - 1).bit_length()
    n = 1 << ab
    total = 0
    for bit in range(width):
        f = [(words[i] >> bit) & 1 if i < len(words) else 0 for i in range(n)]
        seen = set()
        size = n
        while size >= 2:
            for i in range(0, n, size):
                lo, hi = f[i:i + size // 2], f[i + size // 2:i + size]
                if lo == hi or (len(set(lo)) == 1 and len(set(hi)) == 1):
                    continue
                seen.add(tuple(f[i:i + size]))
            size //= 2
        total += len(seen)
    return total


def rom_words():
    """The ROMs' contents, replayed from primitives.py's generator (its fixed seed)."""
    import random
    import re
    import primitives
    out = {}
    for kind, a, b, variant, verilog in primitives.jobs(random.Random(10)):
        if kind == "rom":
            out[(a, b, variant)] = [int(x) for x in re.findall(r"'d(\d+);", verilog)][:a]
    return out


def main():
    data = rows(sys.argv[1])
    by = {}
    for r in data:
        by.setdefault((r["kind"], r["variant"]), []).append(r)

    def pts(kind, variant=""):
        return [(int(r["a"]), int(r["b"]), float(r["ge"]), int(r["depth"]))
                for r in by.get((kind, variant), [])]

    print("# area (GE)")
    add = [p for p in pts("adder") + pts("subtractor") if p[0] >= 8]
    report("adder GE per bit", [(a,) for a, _, _, _ in add], [g for _, _, g, _ in add],
           "adders and subtractors of 8-41 bits")
    cmp_ = [p for p in pts("comparator") if p[0] >= 8]
    report("comparator GE per bit", [(a,) for a, _, _, _ in cmp_], [g for _, _, g, _ in cmp_],
           "comparators of 8-41 bits")
    mu = pts("multiplier", "unsigned")
    report("unsigned multiplier GE per a b, per (a + b)", [(a * b, a + b) for a, b, _, _ in mu],
           [g for _, _, g, _ in mu], "8x8 .. 41x41")
    ms = pts("multiplier", "signed")
    report("signed multiplier GE per a b, per (a + b)", [(a * b, a + b) for a, b, _, _ in ms],
           [g for _, _, g, _ in ms], "8x8 .. 41x41")
    mx = pts("mux")
    report("mux GE per bit and input", [(a * (b - 1),) for a, b, _, _ in mx],
           [g for _, _, g, _ in mx], "8-32 bits x 2-16 inputs")
    report("register GE per bit", [(a,) for a, _, _, _ in pts("register")],
           [g for _, _, g, _ in pts("register")], "plain")
    report("register with enable GE per bit", [(a,) for a, _, _, _ in pts("register", "enable")],
           [g for _, _, g, _ in pts("register", "enable")], "enable")
    sh = pts("shifter")
    report("shifter GE per bit and level", [(a * b,) for a, b, _, _ in sh], [g for _, _, g, _ in sh],
           "12-24 bits x 2-5 levels")
    lz = pts("lzd")
    report("lzd GE per bit", [(a,) for a, _, _, _ in lz], [g for _, _, g, _ in lz], "12-24 bits")
    for v in ("random", "smooth"):
        ro = [p for p in pts("rom", v) if p[0] > 1]
        report(f"rom ({v}) GE per bit", [(a * b,) for a, b, _, _ in ro], [g for _, _, g, _ in ro],
               "2-257 entries x 8, 16 bits")
    words = rom_words()
    ro = [(a, b, g, v) for v in ("random", "smooth") for a, b, g, _ in pts("rom", v) if a >= 9]
    report("rom GE per decision-diagram node", [(rom_nodes(words[(a, b, v)], b),) for a, b, _, v in ro],
           [g for _, _, g, _ in ro], "ROMs of 9-257 entries x 8, 16 bits, random and t^n")
    ra = pts("ram", "write port")
    report("ram GE per bit, per bit of the read mux", [(a * b, (a - 1) * b) for a, b, _, _ in ra],
           [g for _, _, g, _ in ra], "1-257 entries x 8, 16 bits")
    print("# depth (gates)")
    report("adder depth: const, per log2 W", [(1, math.log2(a)) for a, _, _, _ in add],
           [d for _, _, _, d in add], "adders and subtractors")
    report("comparator depth: const, per log2 W", [(1, math.log2(a)) for a, _, _, _ in cmp_],
           [d for _, _, _, d in cmp_], "comparators")
    allm = mu + ms
    report("multiplier depth: const, per log2 min(a,b), per log2(a+b)",
           [(1, math.log2(min(a, b)), math.log2(a + b)) for a, b, _, _ in allm],
           [d for _, _, _, d in allm], "all multipliers")
    report("mux depth: const, per log2 K", [(1, math.log2(b)) for a, b, _, _ in mx],
           [d for _, _, _, d in mx], "muxes")
    report("shifter depth per level", [(b,) for a, b, _, _ in sh], [d for _, _, _, d in sh], "")
    for v in ("random", "smooth"):
        ro = [p for p in pts("rom", v) if p[0] > 1]
        report(f"rom ({v}) depth: const, per log2 E", [(1, math.log2(a)) for a, _, _, _ in ro],
               [d for _, _, _, d in ro], "")


if __name__ == "__main__":
    main()
