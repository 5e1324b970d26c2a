#!/usr/bin/env python3
"""`glint synth --liberty osu018` (ctest rtl.synth_node): the lane mapped onto OSU's 0.18 um cells
and timed by OpenSTA under the SDC `glint rtl` writes. Checks that the report's figures agree with
each other and with the library, not the figures themselves (those are the calibration's):
  - the area in NAND2 equivalents is the area over the library's NAND2X1 (24 um2, its LEF 2.4 x 10);
  - the critical path is the clock period less the slack, the arrival plus the setup time at a
    register, and the maximum clock its inverse;
  - the path's end points are RTL names in the unit's stages (or the lane's);
  - `glint rtl --clock-period` writes that clock into glint_<unit>_lane.sdc.
Usage: synth_node.py GLINT"""
import json
import subprocess
import sys
import tempfile

glint = sys.argv[1]
args = ["lut:bits=4", "--material", "m shininess=50", "--liberty", "osu018", "--json"]


def synth(extra):
    out = subprocess.run([glint, "synth", *args, *extra], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"FAIL: glint synth {' '.join(extra)}: exit {out.returncode}: {out.stderr}")
    return json.loads(out.stdout)


def close(a, b, what):
    if abs(a - b) > 1e-6 * max(1.0, abs(a), abs(b)):
        sys.exit(f"FAIL: {what}: {a} != {b}")


r = synth([])
if r["glint_synth_report"] != 2 or r["flow"] != "liberty":
    sys.exit(f"FAIL: report version or flow: {r}")
if r["nand2_cell"] != "NAND2X1" or r["nand2_area_um2"] != 24:
    sys.exit(f"FAIL: osu018's NAND2: {r['nand2_cell']} {r['nand2_area_um2']}")
close(r["nand2_equivalents"], r["area_um2"] / 24, "NAND2 equivalents")
t = r["timing"]
close(t["critical_path_ns"], t["clock_period_ns"] - t["slack_ns"], "critical path vs slack")
close(t["max_clock_mhz"], 1000 / t["critical_path_ns"], "maximum clock")
if t["clock_period_ns"] != 10 or not 0 < t["critical_path_ns"] < 10:
    sys.exit(f"FAIL: a lut lane at osu018 is timed within the default 10 ns clock: {t}")
end = t["endpoint"]
stages = {s["stage"] for s in r["stages"]} | {"lane", "lane outputs", "lane inputs"}
for point in (t["startpoint"], end):
    if point["stage"] not in stages or not point["name"]:
        sys.exit(f"FAIL: path point outside the stages {sorted(stages)}: {point}")
if end["kind"] == "register":
    close(t["critical_path_ns"], t["arrival_ns"] + t["setup_ns"], "arrival + setup")
    if not t["setup_ns"] > 0:
        sys.exit(f"FAIL: no setup time at a register end point: {t}")

with tempfile.TemporaryDirectory() as d:
    out = subprocess.run([glint, "rtl", "lut:bits=4", "--material", "m shininess=50", "-o", d,
                          "--clock-period", "4", "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"FAIL: glint rtl: {out.stderr}")
    sdc = open(f"{d}/glint_lut_lane.sdc").read()
    if "create_clock -name clk -period 4.000 [get_ports clk]" not in sdc:
        sys.exit(f"FAIL: the SDC's clock: {sdc}")
    if f"{d}/glint_lut_lane.sdc" not in json.loads(out.stdout)["files"]:
        sys.exit("FAIL: glint rtl does not list its SDC")
print(f"PASS: glint synth at osu018: {r['area_um2']:.0f} um2 = {r['nand2_equivalents']:.0f} "
      f"NAND2X1, critical path {t['critical_path_ns']:.3f} ns ({t['max_clock_mhz']:.0f} MHz), "
      f"{t['startpoint']['name']} -> {end['name']}")
