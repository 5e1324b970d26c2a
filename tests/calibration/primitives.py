#!/usr/bin/env python3
"""Primitive sweeps through `glint synth`'s Yosys flow (yosys_flow.py): the data the cost proxy's
constants (src/cost/cost_model.h) are fitted on.

    python3 tests/calibration/primitives.py -o tests/calibration/primitives.csv

Each primitive is a combinational module from inputs to outputs (depth: gates from an input),
except registers and register arrays (depth into the flip-flops). Adders, subtractors,
comparators and restoring-divider rows of 4-41 bits; unsigned and signed rectangular multipliers of 8-41 bits; a multiplier by
a constant (what a one-entry table feeding a multiplier becomes); muxes; barrel shifters;
leading-one detectors; registers with and without enable; storage arrays of 1-257 entries as a case
ROM (random contents and smooth, monotone t^n-like contents: Yosys folds a constant table into
logic, so its size depends on what it holds) and as registers with a write port and a read mux.
Takes ~10 minutes on one core.
"""
import argparse
import csv
import os
import random
import sys

from node_flow import synthesize_node
from yosys_flow import synthesize

WIDTHS = [4, 8, 12, 17, 21, 25, 29, 33, 37, 41]
MULS = [(8, 8), (12, 6), (16, 4), (19, 19), (24, 12), (17, 17), (21, 17), (25, 17), (33, 17),
        (41, 17), (21, 21), (29, 21), (25, 25), (33, 25), (41, 25), (37, 29), (33, 33), (41, 33),
        (41, 41)]
ENTRIES = [1, 2, 3, 5, 9, 17, 33, 65, 129, 257]


class Module:
    """A primitive: its ports and body. str() is the combinational module `top` the generic flow
    synthesizes; node_flow registers its ports for the node's timing."""

    def __init__(self, ports, body):
        self.ports, self.body = ports, body

    def __str__(self):
        return f"module top({', '.join(self.ports)});\n{self.body}\nendmodule\n"


def comb(ports, body):
    return Module(ports, body)


def adder(w):
    return comb([f"input [{w-1}:0] a", f"input [{w-1}:0] b", f"output [{w}:0] y"],
                "assign y = a + b;")


def subtractor(w):
    return comb([f"input [{w-1}:0] a", f"input [{w-1}:0] b", f"output [{w}:0] y"],
                "assign y = {1'b0, a} - {1'b0, b};")


def comparator(w):
    return comb([f"input [{w-1}:0] a", f"input [{w-1}:0] b", "output y"], "assign y = a > b;")


def divider_row(w):
    # A restoring divider's row as schlick's RTL writes it: the w-bit partial remainder X minus the
    # (w - 1)-bit divisor in one subtractor whose borrow is the quotient bit, then the restore mux.
    return comb([f"input [{w-1}:0] x", f"input [{w-2}:0] d", "output q", f"output [{w-1}:0] r"],
                f"wire [{w}:0] df = {{1'b0, x}} - {{2'b0, d}};\nassign q = ~df[{w}];\n"
                f"assign r = q ? df[{w-1}:0] : x;")


def multiplier(a, b, signed):
    s = "signed " if signed else ""
    return comb([f"input {s}[{a-1}:0] a", f"input {s}[{b-1}:0] b", f"output {s}[{a+b-1}:0] y"],
                "assign y = a * b;")


def const_multiplier(a, k, kb):
    return comb([f"input [{a-1}:0] a", f"output [{a+kb-1}:0] y"], f"assign y = a * {kb}'d{k};")


def mux(w, k):
    sb = max(1, (k - 1).bit_length())
    ins = [f"input [{w-1}:0] d{i}" for i in range(k)]
    cases = "\n".join(f"    {i}: y = d{i};" for i in range(k - 1))
    body = (f"always @* begin\n  case (s)\n{cases}\n    default: y = d{k-1};\n  endcase\nend")
    return comb(ins + [f"input [{sb-1}:0] s", f"output reg [{w-1}:0] y"], body)


def shifter(w, levels):
    return comb([f"input [{w-1}:0] a", f"input [{levels-1}:0] s", f"output [{w-1}:0] y"],
                "assign y = a >> s;")


def lzd(w):
    # Position of the leading one (what pow's normalisation reads), as a priority loop.
    ob = max(1, w.bit_length())
    body = (f"integer i;\nalways @* begin\n  y = 0;\n  for (i = 0; i < {w}; i = i + 1)\n"
            f"    if (a[i]) y = i;\nend")
    return comb([f"input [{w-1}:0] a", f"output reg [{ob-1}:0] y"], body)


def register(w, enable):
    ports = ["input clk", f"input [{w-1}:0] d", f"output reg [{w-1}:0] q"]
    if enable:
        ports.insert(1, "input e")
    return comb(ports, f"always @(posedge clk) {'if (e) ' if enable else ''}q <= d;")


def rom_contents(entries, w, smooth, rng):
    if smooth:  # t^n at the nodes of [t0, 1], the shape of lut's and pow's tables
        n = rng.choice([4, 16, 50, 200])
        return [min((1 << w) - 1, round(((i / max(1, entries - 1)) ** n) * ((1 << w) - 1)))
                for i in range(entries)]
    return [rng.randrange(1 << w) for _ in range(entries)]


def rom(entries, w, values):
    ab = max(1, (entries - 1).bit_length())
    cases = "\n".join(f"    {ab}'d{i}: y = {w}'d{v};" for i, v in enumerate(values))
    body = f"always @* begin\n  case (a)\n{cases}\n    default: y = {w}'d0;\n  endcase\nend"
    return comb([f"input [{ab-1}:0] a", f"output reg [{w-1}:0] y"], body)


def ram(entries, w):
    ab = max(1, (entries - 1).bit_length())
    body = (f"reg [{w-1}:0] m [0:{entries-1}];\nalways @(posedge clk) if (we) m[wa] <= wd;\n"
            f"assign y = m[ra];")
    return comb(["input clk", "input we", f"input [{ab-1}:0] wa", f"input [{w-1}:0] wd",
                 f"input [{ab-1}:0] ra", f"output [{w-1}:0] y"], body)


def jobs(rng):
    for w in WIDTHS:
        yield "adder", w, 0, "", adder(w)
        yield "subtractor", w, 0, "", subtractor(w)
        yield "comparator", w, 0, "", comparator(w)
        yield "divider_row", w, 0, "", divider_row(w)
    for a, b in MULS:
        yield "multiplier", a, b, "unsigned", multiplier(a, b, False)
        yield "multiplier", a, b, "signed", multiplier(a, b, True)
    for a in [12, 17, 24]:
        for kb in [4, 8, 12, 16]:
            k = rng.randrange(1 << (kb - 1), 1 << kb) | 1
            yield "const_multiplier", a, kb, f"k={k} ones={bin(k).count('1')}", \
                const_multiplier(a, k, kb)
    for w in [8, 16, 32]:
        for k in [2, 3, 4, 8, 16]:
            yield "mux", w, k, "", mux(w, k)
        yield "register", w, 0, "", register(w, False)
        yield "register", w, 0, "enable", register(w, True)
    for w in [12, 16, 24]:
        for levels in [2, 3, 4, 5]:
            yield "shifter", w, levels, "", shifter(w, levels)
        yield "lzd", w, 0, "", lzd(w)
    for e in ENTRIES:
        for w in [8, 16]:
            for smooth in (False, True):
                yield "rom", e, w, "smooth" if smooth else "random", \
                    rom(e, w, rom_contents(e, w, smooth, rng))
            yield "ram", e, w, "write port", ram(e, w)


def node_jobs(rng):
    """A smaller sweep for the node (each primitive through both flows): the shapes the lanes use."""
    yield "wire", 1, 0, "", comb(["input a", "output y"], "assign y = a;")
    for w in [4, 8, 12, 17, 25, 33, 41]:
        yield "adder", w, 0, "", adder(w)
        yield "comparator", w, 0, "", comparator(w)
    for w in [8, 17, 25, 33]:
        yield "divider_row", w, 0, "", divider_row(w)
    for a, b in [(8, 8), (12, 6), (16, 4), (17, 17), (24, 12), (25, 17), (33, 17), (33, 25),
                 (41, 33)]:
        yield "multiplier", a, b, "unsigned", multiplier(a, b, False)
    for a, b in [(12, 6), (17, 17), (33, 25)]:
        yield "multiplier", a, b, "signed", multiplier(a, b, True)
    for a in [12, 24]:
        for kb in [8, 16]:
            k = rng.randrange(1 << (kb - 1), 1 << kb) | 1
            yield "const_multiplier", a, kb, f"k={k} ones={bin(k).count('1')}", \
                const_multiplier(a, k, kb)
    for w in [8, 16, 32]:
        for k in [2, 3, 5, 8, 16]:
            yield "mux", w, k, "", mux(w, k)
        yield "register", w, 0, "", register(w, False)
        yield "register", w, 0, "enable", register(w, True)
    for w in [16, 24]:
        for levels in [3, 5]:
            yield "shifter", w, levels, "", shifter(w, levels)
        yield "lzd", w, 0, "", lzd(w)
    for e in [5, 17, 65, 257]:
        for smooth in (False, True):
            yield "rom", e, 16, "smooth" if smooth else "random", \
                rom(e, 16, rom_contents(e, 16, smooth, rng))
    for e in [2, 5, 17, 65, 257]:
        for w in [8, 16, 24]:
            yield "ram", e, w, "write port", ram(e, w)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--only", help="one kind (adder, multiplier, rom, ...)")
    ap.add_argument("--liberty", help="also map each primitive to this library (osu018 or a "
                    "file) and time it with OpenSTA: area_um2 and ns beside GE and depth")
    args = ap.parse_args()
    rng = random.Random(10)  # fixed contents: the same modules every run
    if args.liberty:
        return node_main(args, rng)
    rows = []
    for kind, a, b, variant, verilog in jobs(rng):
        if args.only and kind != args.only:
            continue
        r = synthesize(str(verilog), "top")
        rows.append([kind, a, b, variant, r["ge"], r["depth"], r["cells"], r["flip_flops"]])
        print(f"{kind} {a} {b} {variant}: {r['ge']:.1f} GE depth {r['depth']}", file=sys.stderr,
              flush=True)
    with open(args.output, "w", newline="") as f:
        f.write("# Primitive sweeps through glint synth's Yosys flow (GE as glint synth prices "
                "them, depth in gates).\n# Regenerate: python3 tests/calibration/primitives.py -o "
                "tests/calibration/primitives.csv\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["kind", "a", "b", "variant", "ge", "depth", "cells", "flip_flops"])
        w.writerows(rows)


def node_main(args, rng):
    rows = []
    for kind, a, b, variant, m in node_jobs(rng):
        if args.only and kind != args.only:
            continue
        g = synthesize(str(m), "top")
        own = a * b if kind == "ram" else a if kind == "register" else 0
        n = synthesize_node(m.ports, m.body, args.liberty, own)
        rows.append([kind, a, b, variant, g["ge"], g["depth"], round(n["area_um2"], 1),
                     round(n["ns"], 4), n["cells"]])
        print(f"{kind} {a} {b} {variant}: {g['ge']:.1f} GE depth {g['depth']}, "
              f"{n['area_um2']:.0f} um2 {n['ns']:.3f} ns", file=sys.stderr, flush=True)
    with open(args.output, "w", newline="") as f:
        f.write(f"# Primitives between registers at the node: GE and depth of glint synth's generic "
                f"flow, area (less the wrapper's flip-flops) and register-to-register ns of "
                f"--liberty {args.liberty} (node_flow.py).\n# Regenerate: python3 "
                f"tests/calibration/primitives.py --liberty {args.liberty} -o "
                f"tests/calibration/primitives_{os.path.basename(args.liberty)}.csv\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["kind", "a", "b", "variant", "ge", "depth", "area_um2", "ns", "cells"])
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
