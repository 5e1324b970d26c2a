# The measure `glint synth` takes of a netlist, for the calibration scripts: the same Yosys flow
# (src/cli/cmd_synth.cpp, yosys_script), gate equivalents priced as there (cmd_synth.cpp,
# register_transistors: Yosys' `stat -tech cmos` plus the flip-flops it leaves unpriced) and the
# logic depth as there (analyse_netlist: every combinational cell one level from a register, an
# input or a constant).
import json
import os
import re
import subprocess
import tempfile


def register_transistors(cell_type):
    """Transistors of a flip-flop Yosys' cmos estimate leaves out (0 for those it prices).

    $_DFF_P_/$_DFF_N_ are 16 in Yosys' table; a flip-flop with an enable is that plus the 2:1 mux
    it absorbed (12), with a reset or set one more AND (6) for each."""
    if not cell_type.startswith("$_") or ("DFF" not in cell_type and "LATCH" not in cell_type):
        return 0
    if cell_type in ("$_DFF_P_", "$_DFF_N_"):
        return 0
    name = cell_type[2:].rstrip("_")
    kind, _, pins = name.partition("_")
    t = 16
    if kind.endswith("E"):  # DFFE, SDFFE, SDFFCE, DFFSRE, ALDFFE, DLATCHE? (enable)
        t += 12
    if kind.startswith("SDFF") or kind.startswith("ALDFF"):
        t += 6
    elif kind.startswith("DFFSR") or kind.startswith("DLATCHSR"):
        t += 12
    elif re.fullmatch(r"[NP]{2}[01][NP]?", pins):  # asynchronous reset: $_DFF_PP0_, $_DFFE_PN1P_
        t += 6
    return t


def synthesize(verilog, top):
    """Runs the flow on `verilog` (a string); returns dict(ge, transistors, cells, flip_flops,
    depth, cell_types)."""
    with tempfile.TemporaryDirectory(prefix="glint-cal.") as d:
        src = os.path.join(d, "top.v")
        with open(src, "w") as f:
            f.write(verilog)
        stat = os.path.join(d, "stat.txt")
        netlist = os.path.join(d, "netlist.json")
        script = os.path.join(d, "synth.ys")
        with open(script, "w") as f:
            f.write(f"read_verilog {src}\nsynth -flatten -top {top}\nopt_clean -purge\n"
                    f"tee -q -o {stat} stat -tech cmos\nwrite_json {netlist}\n")
        subprocess.run(["yosys", "-q", "-l", os.path.join(d, "log"), "-s", script], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        text = open(stat).read()
        m = re.search(r"Estimated number of transistors:\s+([0-9]+)", text)
        transistors = int(m.group(1)) if m else 0
        nl = json.load(open(netlist))
    mod = nl["modules"][top]
    cells = []
    driver = {}
    types = {}
    for c in mod["cells"].values():
        t = c["type"]
        types[t] = types.get(t, 0) + 1
        reg = t.startswith("$_") and ("DFF" in t or "LATCH" in t)
        ins, outs = [], []
        for port, bits in c["connections"].items():
            out = c["port_directions"][port] == "output"
            for b in bits:
                if isinstance(b, int):
                    (outs if out else ins).append(b)
        if not reg:
            for b in outs:
                driver[b] = len(cells)
        cells.append((reg, ins, outs))
    depth = {}

    def depth_of(bit):
        stack = [(bit, False)]
        while stack:
            b, expanded = stack.pop()
            if b in depth:
                continue
            if b not in driver:
                depth[b] = 0
                continue
            reg, ins, outs = cells[driver[b]]
            if not expanded:
                stack.append((b, True))
                stack.extend((i, False) for i in ins if i not in depth)
                continue
            d = max((depth.get(i, 0) for i in ins), default=0)
            for o in outs:
                depth[o] = d + 1
        return depth[bit]

    deepest = 0
    for reg, ins, outs in cells:
        if reg:
            deepest = max([deepest] + [depth_of(i) for i in ins])
    for port in mod["ports"].values():
        if port["direction"] == "output":
            deepest = max([deepest] + [depth_of(b) for b in port["bits"] if isinstance(b, int)])
    extra = sum(register_transistors(t) * n for t, n in types.items())
    return {
        "transistors": transistors,
        "ge": (transistors + extra) / 4,
        "cells": sum(types.values()),
        "flip_flops": sum(n for t, n in types.items() if "DFF" in t or "LATCH" in t),
        "depth": deepest,
        "cell_types": types,
    }
