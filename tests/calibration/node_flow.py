# The node measure of a primitive, for primitives.py --liberty: the primitive between registers
# (every input and output a DFF of the library, as in a lane, where a part is driven by a
# register and drives one), mapped by `glint synth --liberty`'s flow (src/cli/cmd_synth.cpp,
# yosys_script; map_commands below) and timed by OpenSTA with a clock of 10 ns and no port
# delays (src/hdl/sdc.cpp). The area is the library's, less the wrapper's flip-flops; the delay is
# the worst register-to-register path, clock-to-Q and setup included.
import os
import re
import subprocess
import tempfile

OSU018 = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib"
PORT = re.compile(r"(input|output)\s+(?:reg\s+)?(signed\s+)?(?:\[(\d+):0\]\s+)?(\w+)")


def library(name):
    return OSU018 if name == "osu018" else name


def cell_area(lib_text, cell):
    m = re.search(r"cell\s*\(\s*" + cell + r"\s*\)\s*\{\s*area\s*:\s*([0-9.]+)", lib_text)
    return float(m.group(1))


def buffer_cell(lib_text):
    """The library's smallest buffer (one input pin, the output's function that pin, delay tables:
    abc buffers by them), the cell abc
    buffers high fan-out nets with; None when it has none. cost/liberty.cpp finds the same."""
    best = None
    for m in re.finditer(r"\bcell\s*\(\s*\"?(\w+)\"?\s*\)\s*\{", lib_text):
        nxt = re.compile(r"\bcell\s*\(").search(lib_text, m.end())
        body = lib_text[m.end():nxt.start() if nxt else len(lib_text)]
        if re.search(r"\b(ff|latch|statetable)\s*\(", body):
            continue
        ins = re.findall(r"\bpin\s*\(\s*\"?(\w+)\"?\s*\)\s*\{[^{}]*?direction\s*:\s*input", body)
        funcs = re.findall(r"function\s*:\s*\"\s*\(?\s*(\w+)\s*\)?\s*\"", body)
        area = re.search(r"\barea\s*:\s*([0-9.]+)", body)
        timed = "cell_rise" in body or "intrinsic_rise" in body
        if len(ins) == 1 and len(funcs) == 1 and funcs[0] == ins[0] and area and timed:
            if best is None or float(area.group(1)) < best[1]:
                best = (m.group(1), float(area.group(1)))
    return best[0] if best else None


def map_commands(lib, work, period_ns=10.0):
    """The Yosys commands that map a flattened design onto `lib` as glint synth does
    (src/cli/cmd_synth.cpp, yosys_script), then its statistics into work/stat.txt (read_stat):
    flip-flops by dfflibmap, logic by abc with the clock
    period as its delay target and, where the library has a buffer, abc's buffering and gate
    sizing (-constr: the buffer drives the inputs, outputs unloaded as in the lane's SDC).
    Without it abc leaves a register driving a hundred loads unbuffered, a path no real flow
    keeps (schlick's merge-buffer read: 13 ns unbuffered, 4.4 ns buffered)."""
    buf = buffer_cell(open(lib).read())
    abc = f"abc -D {round(period_ns * 1000)} -liberty {lib}"
    if buf:
        constr = os.path.join(work, "abc.constr")
        open(constr, "w").write(f"set_driving_cell {buf}\nset_load 0\n")
        abc = f"abc -D {round(period_ns * 1000)} -constr {constr} -liberty {lib}"
    return (f"dfflibmap -liberty {lib}\n{abc}\nopt_clean -purge\n"
            f"tee -q -o {os.path.join(work, 'stat.txt')} stat -liberty {lib}\n")


def read_stat(work):
    """(area_um2, cells, text) of the statistics map_commands wrote into `work`."""
    text = open(os.path.join(work, "stat.txt")).read()
    area = float(re.search(r"Chip area for (?:top )?module '[^']*':\s+([0-9.eE+-]+)",
                           text).group(1))
    return area, int(re.search(r"Number of cells:\s+([0-9]+)", text).group(1)), text


def registered(ports, body):
    """A module `top` whose every port but clk is registered around `core` (ports, body)."""
    core = f"module core({', '.join(ports)});\n{body}\nendmodule\n"
    decl, conn, regs, flops = ["input clk"], [], [], 0
    for p in ports:
        d, signed, hi, name = PORT.match(p).groups()
        if name == "clk":
            conn.append(".clk(clk)")
            continue
        w = int(hi) + 1 if hi is not None else 1
        rng = f"[{w - 1}:0] " if hi is not None else ""
        flops += w
        decl.append(f"{d} {rng}{name}_p")
        regs.append(f"reg {rng}{name}_q;")
        if d == "input":
            regs.append(f"always @(posedge clk) {name}_q <= {name}_p;")
        else:
            regs.append(f"wire {rng}{name}_w;\nalways @(posedge clk) {name}_q <= {name}_w;\n"
                        f"assign {name}_p = {name}_q;")
        conn.append(f".{name}({name}_{'q' if d == 'input' else 'w'})")
    top = (f"module top({', '.join(decl)});\n" + "\n".join(regs) +
           f"\ncore u(" + ", ".join(conn) + ");\nendmodule\n")
    return core + top, flops


def synthesize_node(ports, body, lib, own_flops=0):
    """dict(area_um2, ns, cells) of the primitive at the node (wrapper flip-flops left out;
    own_flops: the primitive's own, a register's or a RAM's)."""
    lib = library(lib)
    verilog, _ = registered(ports, body)
    with tempfile.TemporaryDirectory(prefix="glint-node.") as d:
        src = os.path.join(d, "top.v")
        net, sdc, tcl = (os.path.join(d, n) for n in ("net.v", "top.sdc", "sta.tcl"))
        open(src, "w").write(verilog)
        script = os.path.join(d, "synth.ys")
        open(script, "w").write(
            f"read_liberty -lib {lib}\nread_verilog {src}\nsynth -flatten -top top\n"
            f"{map_commands(lib, d)}setundef -zero\nsplitnets -ports\n"
            f"opt_clean\nrename -wire\n"
            f"write_verilog -noattr -noexpr -nohex -nodec -simple-lhs {net}\n")
        subprocess.run(["yosys", "-q", "-l", os.path.join(d, "log"), "-s", script], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        area, cells, text = read_stat(d)
        open(sdc, "w").write("create_clock -name clk -period 10 [get_ports clk]\n"
                             "set_input_delay 0 -clock clk [delete_from_list [all_inputs] "
                             "[get_ports clk]]\nset_output_delay 0 -clock clk [all_outputs]\n")
        open(tcl, "w").write(f"read_liberty {lib}\nread_verilog {net}\nlink_design top\n"
                             f"read_sdc {sdc}\nreport_checks -path_delay max -digits 4 "
                             f"-from [all_registers -clock_pins] -to [all_registers "
                             f"-data_pins]\n")
        rep = subprocess.run(["sta", "-no_splash", "-exit", tcl], check=True, cwd=d,
                             capture_output=True, text=True, stdin=subprocess.DEVNULL).stdout
    slack = float(re.search(r"(-?[0-9.]+)\s+slack", rep).group(1))
    dff = cell_area(open(lib).read(), "DFFPOSX1")
    # The wrapper's flip-flops that are left: Yosys removes those of constant or unused bits (a
    # ROM's constant output bits), so count the netlist's and keep the primitive's own.
    m = re.search(r"DFFPOSX1\s+([0-9]+)", text)
    left = (int(m.group(1)) if m else 0) - own_flops
    return {"area_um2": area - left * dff, "ns": 10.0 - slack, "cells": cells}
