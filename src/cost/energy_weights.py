#!/usr/bin/env python3
"""Per-part energy weights at a node, from the Liberty library itself (issue 26, item 3).

    python3 src/cost/energy_weights.py /usr/share/qflow/tech/osu018/osu018_stdcells.lib \\
        -o src/cost/energy_osu018.h

reads the library's internal_power tables, pin capacitances, nominal voltage and
cell_leakage_power and writes the C++ header glint's energy model uses (cost/energy.h): one energy
per toggle per part kind and a leakage density. First principles only: nothing here is fitted to
a gate-level power run (EnergyScale in cost/energy.h is where that fit will go).
The ctest `cost.energy_weights` re-runs this script and compares its output with the committed
header. Pure Python, no dependencies.

The model of one cell event: an input pin p of a cell toggles once. Its output then toggles with
probability P(p), the share of the other inputs' values for which the cell's function depends on
p (its Boolean difference, from the library's `function`, inputs independent and uniform). An
output toggle costs the internal energy of the arc p -> output (the mean of rise_power and
fall_power: rising and falling outputs equally often) plus the switching energy of the net it
drives, C_load V^2 / 2; the input pin's own internal energy (a passive table, if any) is added
whatever the output does. A part kind's weight is the energy of one bit of it when each input pin
of every cell of that bit toggles once: the part's energy is then its bits times its inputs'
toggle fraction times the weight (cost/energy.h says how glint counts bits per part).
"""
import argparse
import itertools
import re
import sys

# The operating point every table is read at: each table is interpolated (bilinear, clamped) at
# this output load and input transition.
#   load 0.025 pF: a fanout of two or three of these cells' input pins (0.009-0.06 pF each, most
#     0.013-0.03) and a short wire; the third load of every table (index_1: 0.005, 0.0125, 0.025,
#     0.075, 0.15), so no interpolation along the load;
#   slew 0.06 ns: what the cells' own transition tables give at that load (0.04-0.09 ns), the
#     first transition of every table (index_2: 0.06, ...). The clock pin is read at the same
#     slew: glint models no clock tree (its buffers' energy is left to the scale factor).
LOAD_PF = 0.025
SLEW_NS = 0.06

# The cells one bit of each part kind maps to: what `glint synth --liberty osu018`'s flow (Yosys
# synth, abc -liberty: abc skips the multi-output FAX1 and HAX1, so adders never use them) made of
# one primitive, in cells per bit, counted with
#   yosys -p "read_verilog P.v; synth -top P; abc -liberty LIB; stat -liberty LIB"
# on a 16-bit adder (a + b: 80 cells), an 8 x 8 unsigned multiplier (a * b: 317 cells over 64
# partial-product bits), a 16-bit comparator (a > b: 56 cells) and a 16-bit 2:1 mux (48 cells).
RECIPES = {
    "adder_bit": {  # 16-bit adder / 16
        "AND2X1": 7, "AOI21X1": 5, "INVX1": 1, "NAND2X1": 16, "NOR2X1": 15, "OAI21X1": 9,
        "OR2X1": 4, "XNOR2X1": 13, "XOR2X1": 10, "/": 16},
    "multiplier_bit": {  # 8 x 8 multiplier / 64 partial-product bits
        "AND2X1": 10, "AOI21X1": 21, "AOI22X1": 7, "INVX1": 21, "NAND2X1": 78, "NAND3X1": 13,
        "NOR2X1": 27, "OAI21X1": 34, "OAI22X1": 3, "OR2X1": 7, "XNOR2X1": 58, "XOR2X1": 38,
        "/": 64},
    "comparator_bit": {  # 16-bit comparator / 16
        "AND2X1": 3, "AOI21X1": 9, "AOI22X1": 4, "INVX1": 17, "NAND2X1": 3, "NOR2X1": 5,
        "OAI21X1": 9, "OAI22X1": 3, "XOR2X1": 3, "/": 16},
    # A 2:1 mux bit: abc maps s ? a : b to an inverter, a NAND2 and an OAI21 (not MUX2X1). A
    # shifter level and a ROM's decision-diagram node are such a mux too.
    "mux_bit": {"INVX1": 1, "NAND2X1": 1, "OAI21X1": 1, "/": 1},
    "table_bit": {"INVX1": 1, "NAND2X1": 1, "OAI21X1": 1, "/": 1},
    # Glue logic (the merge buffer's selects, leading-one chains): two-input AND/OR.
    "gate": {"AND2X1": 1, "/": 1},
}
# Flip-flops: dfflibmap maps every register bit to DFFPOSX1.
DFF = "DFFPOSX1"


# ---- a small Liberty reader: groups, simple and complex attributes ----

def tokens(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S).replace("\\\n", " ")
    for m in re.finditer(r'"[^"]*"|[A-Za-z0-9_.\-+!\']+|[(){}:;,]', text):
        yield m.group(0)


class Group:
    def __init__(self, kind, args):
        self.kind, self.args, self.attrs, self.groups = kind, args, {}, []

    def sub(self, kind):
        return [g for g in self.groups if g.kind == kind]


def parse(text):
    toks = list(tokens(text))
    pos = 0

    def group(kind, args):
        nonlocal pos
        g = Group(kind, args)
        while pos < len(toks) and toks[pos] != "}":
            name = toks[pos]
            pos += 1
            if toks[pos] == ":":  # simple attribute: name : value ;
                value = toks[pos + 1]
                pos += 2
                while toks[pos] != ";":
                    value += " " + toks[pos]
                    pos += 1
                pos += 1
                g.attrs[name] = value.strip('"')
                continue
            assert toks[pos] == "(", f"expected ( after {name}"
            pos += 1
            a = []
            while toks[pos] != ")":
                if toks[pos] != ",":
                    a.append(toks[pos].strip('"'))
                pos += 1
            pos += 1
            if pos < len(toks) and toks[pos] == "{":
                pos += 1
                g.groups.append(group(name, a))
                pos += 1  # }
            else:  # complex attribute: name ( args ) ;
                if pos < len(toks) and toks[pos] == ";":
                    pos += 1
                g.attrs[name] = a
        return g

    top = group("", [])
    return top.groups[0]


def floats(attr):
    return [float(x) for x in ",".join(attr).replace(" ", "").split(",") if x]


def table_at(t, load, slew):
    """A rise_power/fall_power table at (load, slew): bilinear, clamped to its range."""
    vals = floats(t.attrs["values"])
    i1 = floats(t.attrs["index_1"])
    if "index_2" not in t.attrs:  # passive: indexed by the input transition alone
        return interp(i1, vals, slew)
    i2 = floats(t.attrs["index_2"])
    rows = [vals[r * len(i2):(r + 1) * len(i2)] for r in range(len(i1))]
    return interp(i1, [interp(i2, row, slew) for row in rows], load)


def interp(xs, ys, x):
    x = min(max(x, xs[0]), xs[-1])
    for k in range(len(xs) - 1):
        if x <= xs[k + 1]:
            f = (x - xs[k]) / (xs[k + 1] - xs[k])
            return ys[k] + f * (ys[k + 1] - ys[k])
    return ys[-1]


def mean_power(ip, load, slew):
    """The mean of an internal_power group's rise and fall energies (pJ)."""
    parts = [table_at(t, load, slew) for kind in ("rise_power", "fall_power")
             for t in ip.sub(kind)]
    return sum(parts) / len(parts) if parts else 0.0


def boolean(expr, inputs):
    """A Liberty function as a Python predicate over a dict of input values."""
    e = expr.replace("'", " ' ")
    e = re.sub(r"([A-Za-z_][A-Za-z0-9_]*)\s*'", r"(not \1)", e)  # postfix '
    e = e.replace("!", " not ").replace("+", " or ").replace("|", " or ")
    e = e.replace("^", " != ").replace("*", " and ").replace("&", " and ")
    # Juxtaposition is AND: between two operands (a name or a closing parenthesis, then a name,
    # 'not' or an opening parenthesis).
    for _ in range(4):
        e = re.sub(r"(\)|\b(?!not\b|and\b|or\b)[A-Za-z_][A-Za-z0-9_]*)\s+"
                   r"(?=\(|not\b|(?!and\b|or\b)[A-Za-z_])", r"\1 and ", e)
    code = compile(e, "<function>", "eval")
    return lambda v: bool(eval(code, {}, dict(v)))


def toggle_probability(fn, pin, inputs):
    others = [i for i in inputs if i != pin]
    hits = 0
    for values in itertools.product([False, True], repeat=len(others)):
        v = dict(zip(others, values))
        hits += fn({**v, pin: False}) != fn({**v, pin: True})
    return hits / 2 ** len(others)


class Library:
    def __init__(self, path):
        with open(path) as f:
            self.lib = parse(f.read())
        self.cells = {c.args[0]: c for c in self.lib.sub("cell")}
        self.voltage = float(self.lib.attrs.get("nom_voltage", "0"))
        if self.voltage <= 0:
            sys.exit(f"{path}: no nom_voltage")

    def cell(self, name):
        if name not in self.cells:
            sys.exit(f"library has no cell {name}")
        return self.cells[name]

    def pins(self, cell):
        return {p.args[0]: p for p in cell.sub("pin")}

    def switching(self):
        """C_load V^2 / 2: a net's energy per toggle (pJ with pF and V)."""
        return LOAD_PF * self.voltage ** 2 / 2

    def event(self, name):
        """Energy of one cell per toggle of each of its inputs once (pJ), and the detail."""
        cell = self.cell(name)
        pins = self.pins(cell)
        inputs = [n for n, p in pins.items() if p.attrs.get("direction") == "input"]
        outputs = [p for p in pins.values() if p.attrs.get("direction") == "output"]
        total = 0.0
        for pin in inputs:
            for ip in pins[pin].sub("internal_power"):  # the pin's own (passive) energy
                total += mean_power(ip, LOAD_PF, SLEW_NS)
            for out in outputs:
                fn = boolean(out.attrs["function"], inputs)
                p = toggle_probability(fn, pin, inputs)
                arcs = [ip for ip in out.sub("internal_power")
                        if ip.attrs.get("related_pin") == pin]
                internal = sum(mean_power(ip, LOAD_PF, SLEW_NS) for ip in arcs) / max(len(arcs), 1)
                total += p * (internal + self.switching())
        return total

    def register_bit(self):
        """A data toggle of a flip-flop: D's internal energy, Q's arc from CLK, Q's net."""
        pins = self.pins(self.cell(DFF))
        d = sum(mean_power(ip, LOAD_PF, SLEW_NS) for ip in pins["D"].sub("internal_power"))
        q = [ip for ip in pins["Q"].sub("internal_power") if ip.attrs.get("related_pin") == "CLK"]
        return d + sum(mean_power(ip, LOAD_PF, SLEW_NS) for ip in q) / len(q) + self.switching()

    def clock_bit(self):
        """A clock cycle of a flip-flop: its CLK pin's internal energy on the rising and the
        falling edge (both tables, summed: every cycle has one of each), and the pin's capacitance
        charged and discharged, C V^2."""
        clk = self.pins(self.cell(DFF))["CLK"]
        e = 0.0
        for ip in clk.sub("internal_power"):
            e += sum(table_at(t, LOAD_PF, SLEW_NS) for kind in ("rise_power", "fall_power")
                     for t in ip.sub(kind))
        return e + float(clk.attrs["capacitance"]) * self.voltage ** 2

    def recipe(self, kind):
        r = dict(RECIPES[kind])
        per = r.pop("/")
        return sum(n * self.event(c) for c, n in r.items()) / per

    def leakage_density(self):
        """nW per um2: every cell's cell_leakage_power over its area, summed over the library."""
        leak = sum(float(c.attrs.get("cell_leakage_power", 0)) for c in self.cells.values())
        area = sum(float(c.attrs.get("area", 0)) for c in self.cells.values())
        return leak / area


def header(lib, path, out):
    w = {
        "register_bit": lib.register_bit(),
        "clock_bit": lib.clock_bit(),
        "adder_bit": lib.recipe("adder_bit"),
        "multiplier_bit": lib.recipe("multiplier_bit"),
        "comparator_bit": lib.recipe("comparator_bit"),
        "mux_bit": lib.recipe("mux_bit"),
        "table_bit": lib.recipe("table_bit"),
        "gate": lib.recipe("gate"),
    }
    why = {
        "register_bit": f"{DFF}: D pin + Q arc from CLK + C_load V^2 / 2, per data toggle",
        "clock_bit": f"{DFF}: CLK pin rise + fall + C_clk V^2, per clocked bit per cycle",
        "adder_bit": "16-bit adder's cells / 16, each input toggling once",
        "multiplier_bit": "8 x 8 multiplier's cells / 64 partial-product bits",
        "comparator_bit": "16-bit comparator's cells / 16",
        "mux_bit": "a 2:1 mux bit: INVX1 + NAND2X1 + OAI21X1",
        "table_bit": "a ROM decision node (a 2:1 mux bit) on a read's path",
        "gate": "a two-input glue gate: AND2X1",
    }
    lines = [
        "// Generated by src/cost/energy_weights.py " + path,
        "// -o " + out + " from the library's internal_power tables, pin capacitances, nominal",
        "// voltage and cell_leakage_power (first principles, not fitted: cost/energy.h's",
        "// EnergyScale is where a fit goes).",
        "// Do not edit: re-run the script (src/cost/README.md, \"Energy\").",
        f"// Every table is read at an output load of {LOAD_PF} pF and an input transition of",
        f"// {SLEW_NS} ns (the script's comment says why). Energies in pJ, leakage in nW per um2.",
        "#pragma once",
        "",
        '#include "cost/energy.h"',
        "",
        "namespace glint {",
        "",
        "inline EnergyWeights make_energy_osu018() {",
        "  EnergyWeights w;",
        '  w.node = "osu018";',
        f"  w.voltage = {lib.voltage:g};",
        f"  w.load_pf = {LOAD_PF:g};",
        f"  w.slew_ns = {SLEW_NS:g};",
    ]
    for k, v in w.items():
        lines += [f"  // {why[k]}", f"  w.{k} = {v:.6f};"]
    lines += [
        "  // every cell's cell_leakage_power over its area, summed over the library",
        f"  w.leakage_nw_per_um2 = {lib.leakage_density():.6e};",
        "  return w;",
        "}",
        "",
        "}  // namespace glint",
        "",
    ]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("liberty")
    ap.add_argument("-o", "--output", default="-")
    ap.add_argument("--name", default="src/cost/energy_osu018.h",
                    help="the output's name in the header's first lines")
    a = ap.parse_args()
    text = header(Library(a.liberty), a.liberty, a.name)
    if a.output == "-":
        sys.stdout.write(text)
    else:
        with open(a.output, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
