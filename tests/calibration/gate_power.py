#!/usr/bin/env python3
"""The gate-level energy reference at OSU 0.18 um (issue 26, item 4): a lane's energy per request
measured on the library-mapped netlist, simulated on the input's own requests.

Per lane (a unit SPEC and a vector file):
 1. `glint rtl SPEC --vectors FILE --no-sweep` writes the lane, its self-checking testbench (the
    file's requests in stream order, one offered a cycle, the sink always ready) and its SDC;
 2. Yosys maps the lane to the library as `glint synth --liberty` does (src/cli/cmd_synth.cpp:
    synth -flatten, dfflibmap, abc -liberty -D -constr), and the mapped netlist is kept;
 3. Icarus Verilog simulates that netlist with the library's own cell models
    (osu018_stdcells.v) under the same testbench, which must report PASS (the mapping is right),
    and dumps every net of the lane to a VCD; zero-delay: no glitches are counted;
 4. every net bit's transitions are counted over the stream and its drain (the edges from the
    first out of reset to the last result's, the `cycles` stored), and OpenSTA prices them with
    the library: the energy of a pin's transition (internal, from the library's tables at the
    pin's slew and load, and switching, C V^2 / 2 of its net) times the pin's transitions, plus
    leakage over the cycles.

OpenSTA 2.0.17 (Debian's opensta) cannot take per-pin activities: `set_power_activity -pins`
calls a procedure it does not define, and its activity propagation overwrites every pin's
activity before report_power reads it. So the flow runs report_power once at a global activity
and reads, from its `power` debug trace, each pin's energy per transition (the factor report_power
multiplies the activity by); the sum over pins of energy x simulated transitions is what
report_power computes for those activities. The script checks the reading: the pins' energies at
the global activity must add up to report_power's own internal and switching totals (within 1 %).
That version also has no use for a duty (its internal power sums the state-dependent `when`
groups whatever the state, and leakage is the cells' own), so none is passed.

    # one lane, its figures printed (and the work folder kept with --work)
    python3 tests/calibration/gate_power.py build/glint --lane hast traces/multi_light.vec
    # the stored reference (tests/calibration/power_set.txt, 28 lanes): 10 to 45 minutes on a shared
    # 2-core host, most of it Yosys's abc
    python3 tests/calibration/gate_power.py build/glint --timeout 900 \\
        -o tests/calibration/power_osu018.json
    # the short check of the normal suite: one small lane, 200 requests, skip on and off
    python3 tests/calibration/gate_power.py build/glint --smoke

Needs yosys, iverilog/vvp, sta (OpenSTA) and the library (Debian qflow-tech-osu018); --smoke exits
77 (ctest's SKIP_RETURN_CODE) naming what is missing. Run from the repository's top folder.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from node_flow import OSU018, map_commands, read_stat  # noqa: E402  (the library `--liberty osu018` names)

CELLS_V = os.path.join(os.path.dirname(OSU018), "osu018_stdcells.v")
PERIOD_NS = 10.0  # glint rtl's default clock (src/hdl/sdc.h), which the SDC states
SKIP = 77


def run(argv, cwd=None, timeout=None, merge=False):
    """stdout of argv (and its stderr with merge); raises with their end when it fails or after
    `timeout` seconds (its process group killed: Yosys runs abc as a child)."""
    p = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT if merge else subprocess.PIPE, text=True,
                         stdin=subprocess.DEVNULL, start_new_session=True)
    try:
        p.stdout, p.stderr = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, 9)
        p.communicate()
        raise RuntimeError(f"{' '.join(argv)}: gave up after {timeout:g} s")
    if p.returncode != 0:
        raise RuntimeError(
            f"{' '.join(argv)}: exit {p.returncode}:\n{(p.stdout + (p.stderr or ''))[-3000:]}")
    return p.stdout


def truncate_vectors(src, dst, requests):
    """A copy of vector file src with only its first `requests` rows."""
    out, rows, in_data = [], 0, False
    for line in open(src):
        body = line.split("#", 1)[0].strip()
        if in_data and body:
            if rows == requests:
                break
            rows += 1
        elif body == "data":
            in_data = True
        out.append(line)
    open(dst, "w").write("".join(out))


def glint_rtl(glint, spec, vectors, out):
    """dict(spec, unit, requests, cycles) of the lane glint rtl writes into `out`."""
    text = run([glint, "rtl", spec, "--vectors", vectors, "--no-sweep", "-o", out])
    m = re.match(r"(\w+): (\S+) \(", text)
    n = re.search(r"\((\d+) requests, (\d+) cycles\)", text)
    unit = m.group(1)
    rows = [ln.split() for ln in open(os.path.join(out, f"glint_{unit}_tb.vec"))
            if not ln.startswith("//") and ln.strip()]
    return {"unit": unit, "spec": m.group(2), "requests": int(n.group(1)),
            "cycles": int(n.group(2)), "computed": sum(1 for r in rows if int(r[2], 16) == 0)}


def map_lane(rtl, unit, lib, work, timeout):
    """The lane mapped to the library as glint synth maps it; wires and cells renamed _N_ alike
    in the Verilog (simulated, timed) and the JSON (read here). dict(area_um2, cells, seconds)."""
    top = f"glint_{unit}_lane"
    script = os.path.join(work, "map.ys")
    open(script, "w").write(
        f"read_liberty -lib {lib}\n"
        f"read_verilog {rtl}/{top}.v\nread_verilog {rtl}/glint_{unit}_datapath.v\n"
        f"synth -flatten -top {top}\n{map_commands(lib, work)}"
        # As glint synth writes it for OpenSTA; then every name but the ports' made short
        # (Icarus' VCD and OpenSTA then name the nets and instances as the JSON does).
        f"setundef -zero\nopt_clean\nrename -hide w:* c:*\nrename -enumerate\n"
        f"write_verilog -noattr -noexpr -nohex -nodec -simple-lhs {work}/netlist.v\n"
        f"write_json {work}/netlist.json\n")
    t0 = time.monotonic()
    run(["yosys", "-q", "-l", os.path.join(work, "yosys.log"), "-s", script], timeout=timeout)
    area, cells, _ = read_stat(work)
    return {"area_um2": area, "cells": cells, "yosys_seconds": round(time.monotonic() - t0, 1)}


def simulate(rtl, unit, work):
    """Icarus on the mapped netlist under glint's testbench; the cycles its PASS line reports."""
    tb = f"glint_{unit}_tb"
    dump = os.path.join(work, "dump.v")
    open(dump, "w").write(
        "`timescale 1ns / 1ps\nmodule gate_power_dump;\n  initial begin\n"
        f"    $dumpfile(\"{work}/gates.vcd\");\n    $dumpvars(1, {tb}.dut);\n  end\nendmodule\n")
    sim = os.path.join(work, "sim.vvp")
    run(["iverilog", "-o", sim, "-s", tb, "-s", "gate_power_dump", f"{rtl}/{tb}.v",
         f"{work}/netlist.v", CELLS_V, dump])
    argv = ["vvp", "-n", sim, f"+vectors={rtl}/{tb}.vec"]
    if os.path.exists(f"{rtl}/{tb}.cfg"):
        argv.append(f"+cfg={rtl}/{tb}.cfg")
    text = run(argv)
    m = re.search(r"^PASS (\d+) results, (\d+) cycles", text, re.M)
    if not m:
        raise RuntimeError(f"the gate-level testbench did not pass:\n{text[-2000:]}")
    return int(m.group(2))


def vcd_toggles(path, cycles):
    """Transitions of every bit of the lane's nets, {(name, bit): count}, over the cycles edges
    from the first out of reset: from the time `rst` falls (the testbench's negative edge before
    edge 0) to that time plus cycles periods."""
    ids, scale = {}, 1.0
    units = {"s": 1e9, "ms": 1e6, "us": 1e3, "ns": 1.0, "ps": 1e-3, "fs": 1e-6}
    f = open(path)
    header = []
    for line in f:
        header.append(line)
        if line.startswith("$enddefinitions"):
            break
    text = " ".join(header)
    m = re.search(r"\$timescale\s+(\d+)\s*(\w+)\s+\$end", text)
    scale = int(m.group(1)) * units[m.group(2)]  # ns per VCD time unit
    for m in re.finditer(r"\$var\s+\w+\s+(\d+)\s+(\S+)\s+(\S+)(?:\s+\[(\d+)(?::(\d+))?\])?\s+\$end",
                         text):
        width, code, name = int(m.group(1)), m.group(2), m.group(3)
        lsb = int(m.group(5) if m.group(5) is not None else (m.group(4) or 0))
        ids.setdefault(code, []).append((name, lsb, width))
    rst = next(c for c, v in ids.items() if any(n == "rst" for n, _, _ in v))
    value = {c: 0 for c in ids}
    toggles = {c: [0] * ids[c][0][2] for c in ids}
    t, t0, t_end = 0.0, None, None
    for line in f:
        c0 = line[0]
        if c0 == "#":
            t = int(line[1:]) * scale
            if t_end is not None and t > t_end:
                break
            continue
        if c0 == "b":
            bits, code = line[1:].split()
        elif c0 in "01xzXZ":
            bits, code = c0, line[1:].strip()
        else:
            continue
        new = int(bits.replace("x", "0").replace("z", "0").replace("X", "0").replace("Z", "0"), 2)
        if code == rst and t0 is None and new == 0 and value[code] == 1 and t > 0:
            t0, t_end = t, t + cycles * PERIOD_NS
        if t0 is not None:
            diff = value[code] ^ new
            tg = toggles[code]
            while diff:
                low = diff & -diff
                tg[low.bit_length() - 1] += 1
                diff ^= low
        value[code] = new
    if t0 is None:
        raise RuntimeError(f"{path}: rst never falls")
    out = {}
    for code, names in ids.items():
        for name, lsb, width in names:
            for b in range(width):
                out[(name, lsb + b)] = toggles[code][b]
    return out


PIN = re.compile(r"^power: internal (\S+)/(\S+) \((\S+)\)")
SWITCHING = re.compile(r"^power: switching (\S+)/(\S+) activity = (\S+) volt = \S+ (\S+)")
GROUP = re.compile(r"^power:\s+\S+ -> (\S+) .*?(\S+) (\S+)\s+(\S+)\s+(\S+) (no pg_pin|\S+)$")


def sta_pin_energies(lib, netlist, top, sdc, work):
    """Per pin (instance, pin): (internal, switching, averaged internal) J per transition, OpenSTA's leakage (W),
    and its report_power totals at the global activity (checked against the pins' sum)."""
    tcl = os.path.join(work, "power.tcl")
    open(tcl, "w").write(
        f"read_liberty {lib}\nread_verilog {netlist}\nlink_design {top}\nread_sdc {sdc}\n"
        "set_power_activity -global -activity 1 -duty 0.5\nsta::set_debug power 2\n"
        "report_power -digits 8\n")
    # (its debug trace goes to stderr)
    text = run(["sta", "-no_splash", "-exit", tcl], cwd=work, merge=True)
    pins, pin, switching, groups, unclocked = {}, None, None, [], []
    check = [0.0, 0.0]  # internal, switching at the global activity, rebuilt from the pins

    def close():
        nonlocal switching
        if pin is None:
            return
        # What report_power 2.0.17 sums for an output pin: over its internal-power groups (one
        # per related pin and state), the energies of a rise and a fall, times the pin's
        # transitions. Its later source halves that and averages the groups per supply, the
        # energy of one transition: kept beside, as `internal_averaged`.
        supplies = {}
        for energy, act, supply in groups:
            supplies.setdefault(supply, []).append(energy)
            check[0] += energy * act
        e_int = sum(e for e, _, _ in groups)
        e_avg = sum(sum(g) / len(g) / 2 for g in supplies.values())
        # The switching line comes before its pin's own (cell/port: the instance is the next).
        e_sw = 0.0
        if switching and switching[:2] == (pin[2], pin[1]):
            if float(switching[2]) > 0:
                e_sw = float(switching[3]) / float(switching[2])
            else:
                unclocked.append(f"{pin[0]}/{pin[1]}")
            check[1] += float(switching[3])
            switching = None
        pins[(pin[0], pin[1])] = (e_int, e_sw, e_avg)

    for line in text.splitlines():
        m = PIN.match(line)
        if m:
            close()
            pin, groups = (m.group(1), m.group(2), m.group(3)), []
            continue
        m = SWITCHING.match(line)
        if m:
            close()
            pin = None
            switching = (m.group(1), m.group(2), m.group(3), m.group(4))
            continue
        m = GROUP.match(line)
        if m and pin is not None:
            act, energy = float(m.group(2)) * 1e9, float(m.group(4))
            groups.append((energy, act, m.group(6)))
            continue
        if line.startswith("power: leakage") and pin is not None:
            close()
            pin, switching = None, None
    close()
    total = re.search(r"^Total\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
    internal, switch, leakage = (float(total.group(i)) for i in (1, 2, 3))
    for got, want, what in ((check[0], internal, "internal"), (check[1], switch, "switching")):
        if abs(got - want) > 0.01 * want:
            raise RuntimeError(f"OpenSTA's {what} power {want:.6e} W, the pins' sum {got:.6e} W: "
                               "its debug trace is not the one this script reads")
    return pins, leakage, unclocked


def sequential_cells(lib):
    """Cells of the library with a flip-flop or latch group (OpenSTA's `Sequential`)."""
    seq, cell = set(), None
    for line in open(lib):
        m = re.match(r"\s*cell\s*\(\s*\"?(\w+)", line)
        if m:
            cell = m.group(1)
        elif cell and re.match(r"\s*(ff|latch)\s*\(", line):
            seq.add(cell)
    return seq


def lane(glint, spec, vectors, lib=OSU018, work=None, requests=None, timeout=None):
    """The reference of one lane: a dict as power_osu018.json stores it."""
    own = work is None
    work = work or tempfile.mkdtemp(prefix="glint-gate-power.")
    work = os.path.abspath(work)
    os.makedirs(work, exist_ok=True)
    try:
        t0 = time.monotonic()
        source = vectors
        if requests:
            source = os.path.join(work, "requests.vec")
            truncate_vectors(vectors, source, requests)
        rtl = os.path.join(work, "rtl")
        r = glint_rtl(glint, spec, source, rtl)
        unit, top = r["unit"], f"glint_{r['unit']}_lane"
        mapped = map_lane(rtl, unit, lib, work, timeout)
        cycles = simulate(rtl, unit, work)
        if cycles != r["cycles"]:
            raise RuntimeError(f"{spec}: the gate-level run took {cycles} cycles, glint rtl says "
                               f"{r['cycles']}")
        toggles = vcd_toggles(os.path.join(work, "gates.vcd"), cycles)
        os.remove(os.path.join(work, "gates.vcd"))  # (megabytes; the counts are what is kept)
        pins, leakage_w, unclocked = sta_pin_energies(lib, os.path.join(work, "netlist.v"), top,
                                           os.path.join(rtl, f"{top}.sdc"), work)
        net = json.load(open(os.path.join(work, "netlist.json")))["modules"][top]
        bit_name = {}
        for name, n in net["netnames"].items():
            for i, b in enumerate(n["bits"]):
                if isinstance(b, int) and (name, i) in toggles:
                    bit_name.setdefault(b, (name, i))
        seq = sequential_cells(lib)
        clk = net["ports"]["clk"]["bits"][0]
        energy = {"internal": 0.0, "switching": 0.0, "internal_averaged": 0.0}
        split = {"registers": 0.0, "combinational": 0.0}
        reg_toggles, missing = 0, []
        for cname, c in net["cells"].items():
            for port, bits in c["connections"].items():
                b = bits[0]
                if not isinstance(b, int):
                    continue  # a constant input: no transition
                if b not in bit_name:
                    missing.append(f"{cname}/{port}")
                    continue
                n = toggles[bit_name[b]]
                e_int, e_sw, e_avg = pins.get((cname, port), (0.0, 0.0, 0.0))
                energy["internal"] += e_int * n
                energy["internal_averaged"] += e_avg * n
                energy["switching"] += e_sw * n
                split["registers" if c["type"] in seq else "combinational"] += (e_int + e_sw) * n
                if c["type"] in seq and c["port_directions"][port] == "output":
                    reg_toggles += n
        # Pins OpenSTA found no clock for get no activity, so their switching energy cannot be
        # read: none may toggle.
        silent = [p for p in unclocked if toggles.get(bit_name.get(
            net["cells"][p.split("/")[0]]["connections"][p.split("/")[1]][0]), 0)]
        if silent:
            raise RuntimeError(f"{spec}: toggling pins OpenSTA has no clock for: {silent[:5]}")
        if missing:
            raise RuntimeError(f"{spec}: pins whose net the VCD lacks: {missing[:5]}")
        all_nets = sum(toggles[v] for b, v in bit_name.items() if b != clk)
        seconds = cycles * PERIOD_NS * 1e-9
        energy["leakage"] = leakage_w * seconds
        energy["total"] = energy["internal"] + energy["switching"] + energy["leakage"]
        pj = 1e12 / r["requests"]
        result = {
            "spec": r["spec"], "requests": r["requests"], "computed": r["computed"],
            "cycles": cycles, "cells": mapped["cells"], "area_um2": mapped["area_um2"],
            "energy_pj_per_request": {k: round(energy[k] * pj, 4)
                                      for k in ("total", "internal", "switching", "leakage")},
            "energy_pj_by_group": {k: round(v * pj, 4) for k, v in split.items()},
            "internal_averaged_pj_per_request": round(energy["internal_averaged"] * pj, 4),
            "toggles": {"registers": reg_toggles, "all_nets": all_nets},
            "average_power_mw": round((energy["total"] / seconds) * 1e3, 4),
            "seconds": round(time.monotonic() - t0, 1), "yosys_seconds": mapped["yosys_seconds"]}
        if not all(math.isfinite(v) and v >= 0 for v in result["energy_pj_per_request"].values()):
            raise RuntimeError(f"{spec}: energy not finite: {result['energy_pj_per_request']}")
        return result
    finally:
        if own:
            shutil.rmtree(work, ignore_errors=True)


def read_set(path):
    """power_set.txt: SPEC VECTORS SET a line (SET: calibration or holdout), # comments."""
    lanes = []
    for line in open(path):
        line = line.split("#", 1)[0].split()
        if line:
            lanes.append({"spec": line[0], "vectors": line[1], "set": line[2]})
    return lanes


def missing_tools():
    gone = [t for t in ("yosys", "iverilog", "vvp", "sta") if shutil.which(t) is None]
    gone += [f for f in (OSU018, CELLS_V) if not os.path.exists(f)]
    return gone


def describe(e):
    p = e["energy_pj_per_request"]
    return (f"{p['total']:.3f} pJ/request (internal {p['internal']:.3f}, switching "
            f"{p['switching']:.3f}, leakage {p['leakage']:.5f}), {e['requests']} requests, "
            f"{e['computed']} computed, {e['cycles']} cycles, {e['cells']} cells, register "
            f"toggles {e['toggles']['registers']}, net toggles {e['toggles']['all_nets']}, "
            f"{e['seconds']} s")


def smoke(glint, requests):
    """One small lane, skip on and off, on the first requests of multi_light (some skipped):
    the gate-level testbench passes, the energy is positive and finite, the skip saves."""
    spec = "hast:d=2,in=uq1.10"
    vectors = os.path.join(ROOT, "traces/multi_light.vec")
    on = lane(glint, spec + ",skip=on", vectors, requests=requests)
    off = lane(glint, spec + ",skip=off", vectors, requests=requests)
    for e in (on, off):
        print(f"{e['spec']}: {describe(e)}")
    failures = []
    if not on["computed"] < on["requests"]:
        failures.append("no request skipped: the check of the skip's saving proves nothing")
    if off["computed"] != off["requests"]:
        failures.append("skip=off skipped a request")
    for e in (on, off):
        if not e["energy_pj_per_request"]["total"] > 0:
            failures.append(f"{e['spec']}: energy not positive")
        if not e["toggles"]["registers"] > 0:
            failures.append(f"{e['spec']}: no register toggled")
    if not on["energy_pj_per_request"]["total"] < off["energy_pj_per_request"]["total"]:
        failures.append("skip=on does not use less energy than skip=off")
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print("PASS: gate-level energy of one lane, skip on "
          f"{on['energy_pj_per_request']['total']:.3f} < off "
          f"{off['energy_pj_per_request']['total']:.3f} pJ/request")
    return 0


DEFAULT_UNITS = ("lut", "hast", "horner", "pow", "schlick")


def check_stored(path, min_lanes, min_holdout):
    """The stored reference as the energy fit and its normal-suite test read it (no tool run):
    enough lanes and hold-out, every unit of the default set with the skip on and off, each
    lane's figures consistent. 0 when it holds."""
    doc = json.load(open(path))
    lanes, failures = doc["lanes"], []
    holdout = [e for e in lanes if e["set"] == "holdout"]
    if len(lanes) < min_lanes or len(holdout) < min_holdout:
        failures.append(f"{len(lanes)} lanes, {len(holdout)} in the hold-out: want at least "
                        f"{min_lanes} and {min_holdout}")
    for unit in DEFAULT_UNITS:
        for skip in ("on", "off"):
            if not any(e["spec"].startswith(unit + ":") and f"skip={skip}" in e["spec"]
                       for e in lanes):
                failures.append(f"no {unit} lane with skip={skip}")
    for e in lanes:
        name = f"{e['spec']} {e['input']}"
        p = e["energy_pj_per_request"]
        parts = p["internal"] + p["switching"] + p["leakage"]
        if not (all(math.isfinite(v) for v in p.values()) and p["total"] > 0 and
                abs(parts - p["total"]) <= 1e-3 * p["total"] + 2e-4):
            failures.append(f"{name}: energy {p} not positive or not the sum of its parts")
        if not 0 < e["computed"] <= e["requests"] <= e["cycles"]:
            failures.append(f"{name}: requests {e['requests']}, computed {e['computed']}, "
                            f"cycles {e['cycles']}")
        if "skip=off" in e["spec"] and e["computed"] != e["requests"]:
            failures.append(f"{name}: skip=off but {e['requests'] - e['computed']} skipped")
        vectors = e["input"].split()[1]
        if not os.path.exists(os.path.join(ROOT, vectors)):
            failures.append(f"{name}: {vectors} is not in the repository")
        if e["set"] not in ("calibration", "holdout"):
            failures.append(f"{name}: set {e['set']}")
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print(f"PASS: {len(lanes)} lanes ({len(holdout)} in the hold-out), every default unit with "
          "the skip on and off")
    return 0


def compare(fresh, stored, tolerance):
    """The re-derived reference against the stored one, lane by lane: the same lanes, requests,
    cycles and cells, every energy within `tolerance` (relative). 0 when they agree."""
    new = {(e["spec"], e["input"]): e for e in json.load(open(fresh))["lanes"]}
    old = json.load(open(stored))["lanes"]
    failed = 0
    for s in old:
        key = (s["spec"], s["input"])
        n = new.get(key)
        ok = n is not None and all(n[k] == s[k] for k in ("requests", "computed", "cycles",
                                                          "cells")) and all(
            abs(n["energy_pj_per_request"][k] - v) <= tolerance * abs(v) + 1e-4
            for k, v in s["energy_pj_per_request"].items())
        failed += not ok
        got = n["energy_pj_per_request"]["total"] if n else "missing"
        print(f"{'ok  ' if ok else 'FAIL'} {s['spec']} {s['input']}: {got} pJ/request (stored "
              f"{s['energy_pj_per_request']['total']})")
    if len(new) != len(old):
        print(f"FAIL: {len(new)} lanes re-derived, {len(old)} stored")
        failed += 1
    print("PASS: the gate-level reference re-derived as stored" if not failed else
          f"FAIL: {failed} lanes differ from the stored reference")
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint")
    ap.add_argument("-o", "--output", help="write the reference of the set here")
    ap.add_argument("--set", default=os.path.join(HERE, "power_set.txt"))
    ap.add_argument("--lane", nargs=2, metavar=("SPEC", "VECTORS"), help="one lane, printed")
    ap.add_argument("--requests", type=int, help="only the first N requests of the vectors")
    ap.add_argument("--work", help="keep the lane's files here (--lane)")
    ap.add_argument("--timeout", type=float, default=1800, help="seconds of Yosys per lane")
    ap.add_argument("--smoke", action="store_true", help="the normal suite's short check")
    ap.add_argument("--check-stored", metavar="FILE", help="check a stored reference's shape")
    ap.add_argument("--compare", metavar="STORED",
                    help="after writing -o, compare it with this stored reference")
    ap.add_argument("--tolerance", type=float, default=0.005)
    args = ap.parse_args()
    if args.check_stored:
        return check_stored(args.check_stored, 20, 6)
    gone = missing_tools()
    if gone:
        print(f"SKIP: the gate-level flow needs {', '.join(gone)} (Debian yosys, iverilog, "
              "opensta, qflow-tech-osu018)")
        return SKIP
    if args.smoke:
        return smoke(args.glint, args.requests or 200)
    if args.lane:
        e = lane(args.glint, args.lane[0], args.lane[1], work=args.work, requests=args.requests,
                 timeout=args.timeout)
        print(json.dumps(e, indent=1))
        print(f"{e['spec']}: {describe(e)}", file=sys.stderr)
        return 0
    if not args.output:
        ap.error("-o FILE, --lane or --smoke")
    lanes, failed, t0 = [], [], time.monotonic()
    sta = run(["sta", "-version"]).strip()
    rel = os.path.relpath(os.path.abspath(args.set), ROOT)
    out = os.path.relpath(os.path.abspath(args.output), ROOT)
    for c in read_set(args.set):
        try:
            e = lane(args.glint, c["spec"], os.path.join(ROOT, c["vectors"]),
                     timeout=args.timeout, requests=args.requests)
        except RuntimeError as err:
            # Stored as left out (a lane abc does not map in the time given), not silently.
            print(f"{c['spec']} {c['vectors']}: {err}", file=sys.stderr, flush=True)
            failed.append({"spec": c["spec"], "input": f"--vectors {c['vectors']}",
                           "error": str(err).splitlines()[-1][:300]})
            continue
        e = {"spec": e["spec"], "input": f"--vectors {c['vectors']}", "set": c["set"], **{
            k: v for k, v in e.items() if k != "spec"}}
        print(f"{c['spec']} {c['vectors']}: {describe(e)}", file=sys.stderr, flush=True)
        lanes.append(e)
        # Written after every lane: a run cut short keeps what it measured.
        doc = {"node": "osu018", "liberty": OSU018, "opensta": sta,
               "yosys": run(["yosys", "-V"]).strip(),
               "iverilog": run(["iverilog", "-V"]).splitlines()[0],
               "clock_period_ns": PERIOD_NS,
               "command": f"python3 tests/calibration/gate_power.py build/glint --set {rel}"
                          f" --timeout {args.timeout:g} -o {out}",
               "cycles": "the testbench's edges from the first out of reset to the last "
                         "result's retire: the stream plus the pipeline's drain",
               "simulation": "zero-delay (Icarus, the library's cell models): no glitches",
               "seconds": round(time.monotonic() - t0), "lanes": lanes, "left_out": failed}
        with open(args.output, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
    if not lanes:
        return 1
    return compare(args.output, args.compare, args.tolerance) if args.compare else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
