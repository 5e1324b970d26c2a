#!/usr/bin/env python3
"""Checks glint's JSON report documentation against real outputs.

    check_schemas.py GLINT SOURCE_DIR [--synth]

The report schemas are documented in markdown files beside the code (src/*/*_report.md, ...;
the format is described in src/eval/sim_report.md, "How these files are written"). This script
parses them, runs GLINT in a temporary folder on the shipped traces and scene, and checks both
directions:

- every key of every real output is documented, with a matching type;
- every key documented as always present is in every object it belongs to, and every documented
  key (optional ones too) appears in at least one real output, so a key glint no longer writes
  cannot stay documented.

`--synth` adds `glint synth` (it needs yosys on PATH; ~3 s, ~10 s more with OpenSTA and osu018). Violations are printed as
`FILE.md: key 'PATH': message`; the exit status is 1 when there is any, 0 with a final
`PASS: N documents, M keys` line. Python 3 standard library only.
"""

import argparse
import csv
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The documentation files, relative to SOURCE_DIR.
DOC_FILES = [
    "src/eval/sim_report.md",
    "src/eval/eval_report.md",
    "src/eval/golden.md",
    "src/render/render_report.md",
    "src/sweep/sweep_report.md",
    "src/cli/synth_report.md",
]
SYNTH_DOC = "src/cli/synth_report.md"
OSU018 = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib"

# The sweep CSV's columns written only with --node.
NODE_COLUMNS = {"area_um2", "critical_path_ns", "max_clock_mhz", "energy_pj_per_request",
                "pareto_energy"}

BASE_TYPES = {"string", "integer", "number", "boolean", "null", "object", "array"}

# A schema section starts at a heading whose whole text is one backticked name: "## `errors`".
# Its name is also its GitHub anchor (#errors), which is what references link to.
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*$")
SECTION = re.compile(r"^`([a-z][a-z0-9_]*)`$")
# An entry: "- `key` type: meaning" or "- `key` type, only WHEN: meaning".
ENTRY = re.compile(r"^- `(?P<key>[^`]+)` (?P<type>[^\s,:]+)(?:, (?P<when>only [^:]+))?:(?: \S|$)")
KEY = re.compile(r"^(?:[A-Za-z0-9_$]+|\*)(?:\[\])*(?:\.(?:[A-Za-z0-9_$]+|\*)(?:\[\])*)*$")
LINK = re.compile(r"^\[([^\]]+)\]\(([^)#]*)#([a-z0-9_]+)\)$")
# "`glint_sim_report` version 3": the version a file documents, checked against the output.
VERSION = re.compile(r"`(glint_[a-z_]+)` version (\d+)")
FENCE = re.compile(r"^(```|~~~)")
# The sections a real output is checked against as a whole; keys of other sections are named
# with their section in messages (errors.max_abs).
ROOT_SECTIONS = {"glint_eval_report", "glint_sim_report", "golden", "scene_golden",
                 "glint_render_report",
                 "glint_sweep_report", "glint_size_report", "glint_synth_report"}


class Entry:
    """One documented key of a section."""

    def __init__(self, doc, section, key, types, ref, when, line):
        self.doc, self.section, self.key = doc, section, key
        self.types, self.ref, self.when, self.line = types, ref, when, line
        self.seen = False

    def label(self):
        # The key as the messages name it: qualified by its section unless it is a report's root.
        return self.key if self.section in ROOT_SECTIONS else f"{self.section}.{self.key}"


class Docs:
    """Every section of every documentation file: (doc, section) -> {key: Entry}."""

    def __init__(self):
        self.sections = {}
        self.versions = {}  # version key -> (doc, version)
        self.csv = {}  # doc -> [column] from a ```csv fenced block
        self.errors = []


def parent_key(key):
    if key.endswith("[]"):
        return key[:-2]
    return key.rsplit(".", 1)[0] if "." in key else ""


def parse_type(text, doc):
    """'number|null' -> ({'number', 'null'}, None); a link -> ({'object'}, (doc, section))."""
    types, ref = set(), None
    for member in text.split("|"):
        m = LINK.match(member)
        if m:
            # A reference to a section documented once elsewhere (or in this file: "#name").
            target = os.path.normpath(os.path.join(os.path.dirname(doc), m.group(2))) \
                if m.group(2) else doc
            ref = (target, m.group(3))
            types.add("object")
        elif member in BASE_TYPES:
            types.add(member)
        else:
            return None, None
    return types, ref


def parse_doc(docs, root, doc):
    path = os.path.join(root, doc)
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    section, fence, fence_lang, fence_body = None, False, "", []
    for n, line in enumerate(lines, 1):
        if FENCE.match(line):
            if not fence:
                fence, fence_lang, fence_body = True, line[3:].strip(), []
            else:
                fence = False
                if fence_lang == "csv":
                    # The sweep CSV's columns, documented as a comma-separated list.
                    text = " ".join(fence_body)
                    docs.csv[doc] = [c.strip() for c in text.split(",") if c.strip()]
            continue
        if fence:
            fence_body.append(line)
            continue
        for key, version in VERSION.findall(line):
            docs.versions.setdefault(key, (doc, int(version)))
        h = HEADING.match(line)
        if h:
            s = SECTION.match(h.group(2))
            section = s.group(1) if s else None
            if section:
                if (doc, section) in docs.sections:
                    docs.errors.append(f"{doc}:{n}: section `{section}` documented twice")
                docs.sections[(doc, section)] = {}
            continue
        if section is None or not line.startswith("- `"):
            continue
        m = ENTRY.match(line)
        types, ref = parse_type(m.group("type"), doc) if m else (None, None)
        if not m or types is None or not KEY.match(m.group("key")):
            docs.errors.append(
                f"{doc}:{n}: not an entry: expected '- `key` TYPE[, only WHEN]: meaning' with "
                f"TYPE of {sorted(BASE_TYPES)} or a [link](file.md#section), joined by |")
            continue
        key = m.group("key")
        entries = docs.sections[(doc, section)]
        if key in entries:
            docs.errors.append(f"{doc}:{n}: key '{key}' documented twice in `{section}`")
        entries[key] = Entry(doc, section, key, types, ref, m.group("when"), n)


def check_structure(docs):
    """Every entry's parent is documented as an object or array, every link resolves."""
    for (doc, section), entries in docs.sections.items():
        for key, e in entries.items():
            parent = parent_key(key)
            want = "array" if key.endswith("[]") else "object"
            if parent and (parent not in entries or want not in entries[parent].types):
                docs.errors.append(f"{doc}:{e.line}: key '{key}': its parent '{parent}' is not "
                                   f"documented as {want} in `{section}`")
            if e.ref and e.ref not in docs.sections:
                docs.errors.append(f"{doc}:{e.line}: key '{key}': no section `{e.ref[1]}` in "
                                   f"{e.ref[0]}")


# ---- Checking one real document ----------------------------------------------------------------

def json_type(value):
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "number"
    if isinstance(value, str):
        return "string"
    return "array" if isinstance(value, list) else "object"


def type_ok(value, types):
    t = json_type(value)
    # An integer is a number too: a float statistic that happens to be whole is still written
    # as 1.0 by glint, but documenting "number" must not depend on that.
    return t in types or (t == "integer" and "number" in types)


def child_key(key, name):
    return f"{key}.{name}" if key else name


class Checker:
    def __init__(self, docs):
        self.docs = docs
        self.violations = {}  # message -> [where], in the order found
        self.keys_checked = 0

    def fail(self, message, origin=None):
        """Records a violation; the same one in several outputs is printed once, with the first
        output and how many more have it (a key missing from `errors` is missing everywhere)."""
        self.violations.setdefault(message, []).append(origin)

    def messages(self):
        for message, origins in self.violations.items():
            if origins[0] is None:
                yield message
                continue
            more = f"; and {len(origins) - 1} more places" if len(origins) > 1 else ""
            yield f"{message} ({origins[0]}{more})"

    def check(self, doc, section, value, origin):
        """Checks `value` (a whole output) against the section (doc, section)."""
        self.walk(value, [(doc, section, "")], "", origin)

    def lookup(self, scope, name):
        """The entries of `name` in a scope: a list of (doc, section, key) the value is at.

        A scope has several places when an entry is a link and also lists keys of its own
        beside the linked section's (skip.per_light_material[] in render_report.md)."""
        found = []
        for doc, section, key in scope:
            entries = self.docs.sections[(doc, section)]
            for k in (child_key(key, name), child_key(key, "*")):
                if k in entries:
                    found.append(entries[k])
                    break
        return found

    def descend(self, entries):
        scope = []
        for e in entries:
            scope.append((e.doc, e.section, e.key))
            if e.ref:
                scope.append((e.ref[0], e.ref[1], ""))
        return scope

    def walk(self, value, scope, path, origin):
        if isinstance(value, dict):
            for name, child in value.items():
                self.visit(child, scope, name, child_key(path, name), origin)
            self.require(value, scope, path, origin)
        elif isinstance(value, list):
            for child in value:
                self.visit(child, scope, "[]", path + "[]", origin, element=True)

    def visit(self, value, scope, name, path, origin, element=False):
        if element:
            entries = []
            for doc, section, key in scope:
                e = self.docs.sections[(doc, section)].get(key + "[]")
                if e:
                    entries.append(e)
        else:
            entries = self.lookup(scope, name)
        self.keys_checked += 1
        if not entries:
            doc, section, key = scope[-1]
            where = key + "[]" if element else child_key(key, name)
            label = where if section in ROOT_SECTIONS else f"{section}.{where}"
            self.fail(f"{doc}: key '{label}': glint writes it, but it is not documented",
                      f"{origin}: '{path}'")
            return
        for e in entries:
            e.seen = True
            if not type_ok(value, e.types):
                self.fail(f"{e.doc}: key '{e.label()}': documented as {'|'.join(sorted(e.types))}"
                          f", glint writes {json_type(value)}", f"{origin}: '{path}'")
        self.walk(value, self.descend(entries), path, origin)

    def require(self, obj, scope, path, origin):
        """Keys documented without `only ...` must be in every object of their parent."""
        for doc, section, key in scope:
            for e in self.docs.sections[(doc, section)].values():
                if e.when or "*" in e.key or e.key.endswith("[]") or parent_key(e.key) != key:
                    continue
                name = e.key.rsplit(".", 1)[-1]
                if name not in obj:
                    self.fail(f"{e.doc}: key '{e.label()}': documented as always present, "
                              f"but missing", f"{origin}: '{child_key(path, name)}'")

    def unseen(self, skip_docs):
        for (doc, section), entries in self.docs.sections.items():
            if doc in skip_docs:
                continue
            for e in entries.values():
                if not e.seen:
                    self.fail(f"{doc}: key '{e.label()}': documented, but in no real output")


# ---- Producing the real outputs -----------------------------------------------------------------

class Runner:
    """Runs glint in a temporary folder; collects (doc, section, json, origin) to check."""

    def __init__(self, glint, source, work):
        self.glint, self.source, self.work = glint, source, work
        self.outputs = []
        self.csvs = []  # (origin, header columns, scene?)
        self.failures = []

    def src(self, rel):
        return os.path.join(self.source, rel)

    def run(self, args, ok=(0,)):
        """Runs glint ARGS; returns its stdout, or None (recorded as a failure)."""
        cmd = [self.glint] + args
        p = subprocess.run(cmd, cwd=self.work, capture_output=True, text=True)
        if p.returncode not in ok:
            self.failures.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
            return None
        return p.stdout

    def json_stdout(self, doc, section, args, origin, ok=(0,)):
        out = self.run(args, ok)
        if out is not None:
            self.outputs.append((doc, section, json.loads(out), origin))

    def json_file(self, doc, section, path, origin):
        with open(path, encoding="utf-8") as f:
            self.outputs.append((doc, section, json.load(f), origin))

    def csv_header(self, path, origin, scene, node=False):
        with open(path, newline="", encoding="utf-8") as f:
            self.csvs.append((origin, next(csv.reader(f)), scene, node))

    def all(self, synth):
        eval_doc, sim_doc = "src/eval/eval_report.md", "src/eval/sim_report.md"
        # eval: many lights and colours, the contract edge cases (always-skipped slots, bound and
        # none contracts), a Gaussian lobe.
        for trace in ("eight_lights.vec", "contract_cases.vec", "gaussian.vec"):
            self.json_stdout(eval_doc, "glint_eval_report",
                             ["eval", self.src("traces/" + trace), "--json"], "glint eval " + trace)
        # eval with a chip capacity, units whose config has non-default keys (a horner that keeps
        # Sollya's fits: sup_norm) and the units outside the default set (sfu, pwp).
        self.json_stdout(eval_doc, "glint_eval_report",
                         ["eval", self.src("traces/phong_basic.vec"), "--chip", "ram:materials=4,slots=4", "--unit",
                          "hast:match=minimax,tables=ram", "--unit", "hast:root=0.9", "--unit", "sfu", "--unit", "pwp",
                          "--unit", "pwp:domain=log",
                          "--unit", "horner:degree=6,guard=2", "--json"],
                         "glint eval --chip ram:materials=4,slots=4 phong_basic.vec")
        # sim: fast (JSON on stdout), clocked (--report), and a chip of fixed capacity.
        self.json_stdout(sim_doc, "glint_sim_report",
                         ["sim", self.src("traces/phong_basic.vec"), "--json"],
                         "glint sim phong_basic.vec")
        if self.run(["sim", self.src("traces/hard_cases.vec"), "--mode", "clocked",
                     "--sink-ready", "0.7", "--report", "sim.json"]) is not None:
            self.json_file(sim_doc, "glint_sim_report", os.path.join(self.work, "sim.json"),
                           "glint sim --mode clocked --report hard_cases.vec")
        self.json_stdout(sim_doc, "glint_sim_report",
                         ["sim", self.src("traces/multi_light.vec"), "--chip", "ram:materials=16,slots=16",
                          "--activity", "clock", "--json"],
                         "glint sim --chip ram:materials=16,slots=16 --activity clock multi_light.vec")
        self.json_stdout(sim_doc, "glint_sim_report",
                         ["sim", self.src("traces/multi_light.vec"), "--node", "osu018",
                          "--activity", "operand", "--json"],
                         "glint sim --node osu018 --activity operand multi_light.vec")
        # sweep: a vector file with a refused configuration (schlick match=width cannot hold the
        # Gaussian lobe's n'), a scene (image errors), and one shard of a fixed-capacity sweep.
        sweep_doc = "src/sweep/sweep_report.md"
        runs = [
            ("vectors", [self.src("traces/contract_cases.vec"), "--grid",
                         "schlick:match=none|width", "--grid", "lut:bits=4..5", "--grid", "pow"]),
            ("scene", ["--scene", self.src("traces/scenes/small.json"), "--grid",
                       "lut:bits=4..5", "--grid", "hast", "--node", "osu018"]),
            ("shard", [self.src("traces/phong_basic.vec"), "--grid", "lut:bits=4..7",
                       "--shard", "1/2", "--chip", "ram:materials=4,slots=4"]),
        ]
        for name, args in runs:
            out_json, out_csv = f"sweep_{name}.json", f"sweep_{name}.csv"
            if self.run(["sweep"] + args + ["-o", out_json, "--csv", out_csv]) is None:
                continue
            origin = f"glint sweep ({name})"
            self.json_file(sweep_doc, "glint_sweep_report", os.path.join(self.work, out_json),
                           origin)
            self.csv_header(os.path.join(self.work, out_csv), origin, name == "scene",
                            "--node" in args)
        # size: one family meets the budget, one does not (spec null); exit 1 would be none.
        self.json_stdout(sweep_doc, "glint_size_report",
                         ["size", "--budget", "lsb8<=1", "--grid", "lut:bits=6..7", "--grid",
                          "hast:d=2", self.src("traces/phong_basic.vec"), "--json", "--node",
                          "osu018"],
                         "glint size", ok=(0, 1))
        # size with nothing meeting a bound budget on the grids as given (widening would meet it):
        # the closest configurations at their grid's end.
        self.json_stdout(sweep_doc, "glint_size_report",
                         ["size", "--budget", "bound_lsb<=0.5", "--grid", "lut:bits=4..5",
                          "--grid", "hast:d=2..3", self.src("traces/phong_basic.vec"), "--json",
                          "--no-widen"],
                         "glint size (none meets)", ok=(1,))
        # render: the small scene's report.json (with --float: its float_images object).
        render_doc = "src/render/render_report.md"
        if self.run(["render", self.src("traces/scenes/small.json"), "-o", "render",
                     "--float", "pfm", "--node", "osu018"]) is not None:
            self.json_file(render_doc, "glint_render_report",
                           os.path.join(self.work, "render", "report.json"), "glint render")
        # The teapot reproduces a paper's figure (reproduces.*); one unit keeps it quick.
        if self.run(["render", self.src("traces/scenes/teapot.json"), "-o", "teapot", "--unit",
                     "lut"]) is not None:
            self.json_file(render_doc, "glint_render_report",
                           os.path.join(self.work, "teapot", "report.json"),
                           "glint render (teapot)")
        # render: a tiny scene of meshes, for meshes[] (normals from the file, generated with a
        # crease angle, and from patches).
        with open(os.path.join(self.work, "tet.stl"), "w", encoding="utf-8") as f:
            f.write("solid t\n" + "".join(
                "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {v}\n" for v in tri) +
                "endloop\nendfacet\n" for tri in (("0 0 0", "0 1 0", "1 0 0"),
                                                    ("0 0 0", "0 0 1", "0 1 0"),
                                                    ("0 0 0", "1 0 0", "0 0 1"),
                                                    ("1 0 0", "0 1 0", "0 0 1"))) + "endsolid t\n")
        with open(os.path.join(self.work, "meshes.json"), "w", encoding="utf-8") as f:
            json.dump({"glint_scene": 1,
                       "camera": {"position": [0, 2, 6], "look_at": [0, 0, 0], "fov_y": 40,
                                  "resolution": [16, 12]},
                       "lights": [{"name": "l", "type": "point", "position": [2, 4, 3]}],
                       "materials": [{"name": "m", "specular": [1, 1, 1], "lobe": "phong",
                                      "shininess": 20}],
                       "objects": [
                           {"type": "mesh", "file": self.src("traces/scenes/torus.obj"),
                            "material": "m"},
                           {"type": "mesh", "file": "tet.stl", "material": "m",
                            "crease_angle": 80, "translate": [-2, 0, 0]},
                           {"type": "bezier", "file": self.src("traces/scenes/teapot.bpt"),
                            "subdivisions": 1, "material": "m", "scale": 0.3,
                            "translate": [2, 0, 0]}]}, f)
        if self.run(["render", "meshes.json", "-o", "render_meshes", "--unit", "pow"]) is not None:
            self.json_file(render_doc, "glint_render_report",
                           os.path.join(self.work, "render_meshes", "report.json"),
                           "glint render (meshes)")
        # The shipped goldens, as glint regress reads them.
        for path in sorted(glob.glob(self.src("traces/golden/*.json"))):
            self.json_file("src/eval/golden.md", "golden", path,
                           "traces/golden/" + os.path.basename(path))
        for path in sorted(glob.glob(self.src("traces/golden/scenes/*.json"))):
            self.json_file("src/eval/golden.md", "scene_golden", path,
                           "traces/golden/scenes/" + os.path.basename(path))
        # A trace's golden with the optional keys, as glint regress --update writes it from the
        # settings alone.
        regress = os.path.join(self.work, "regress")
        os.makedirs(os.path.join(regress, "golden"))
        shutil.copy(self.src("traces/phong_basic.vec"), regress)
        made = os.path.join(regress, "golden", "phong_basic.json")
        with open(made, "w", encoding="utf-8") as f:
            json.dump({"trace": "phong_basic.vec", "units": ["lut", "hast"], "sink_ready": 1,
                       "seed": 1, "chip": "ram:materials=4,slots=4", "budgets": {"lut": "lsb8<=1,area_ge<=100000"}}, f)
        if self.run(["regress", "--traces", regress, "--update"]) is not None:
            self.json_file("src/eval/golden.md", "golden", made, "glint regress --update")
        scene_golden = self.src("traces/golden/scenes/small/report.json")
        if os.path.exists(scene_golden):
            self.json_file(render_doc, "glint_render_report", scene_golden,
                           "traces/golden/scenes/small/report.json")
        if synth:
            # Yosys' generic flow and a liberty library (the four-cell one the rtl tests use).
            spec = ["synth", "lut:in=uq1.10", "--vectors", self.src("traces/phong_basic.vec")]
            self.json_stdout(SYNTH_DOC, "glint_synth_report", spec + ["--json"], "glint synth")
            self.json_stdout(SYNTH_DOC, "glint_synth_report",
                             spec + ["--liberty", self.src("tests/rtl/tiny.lib"), "--json"],
                             "glint synth --liberty")
            # The built-in node, timed by OpenSTA (when both are installed: .ci/bootstrap).
            if shutil.which("sta") and os.path.exists(OSU018):
                self.json_stdout(SYNTH_DOC, "glint_synth_report",
                                 spec + ["--liberty", "osu018", "--json"],
                                 "glint synth --liberty osu018")


def check_versions(docs, checker, outputs):
    """The version key of each output equals the version its file says it documents."""
    for doc, section, value, origin in outputs:
        for key, (vdoc, version) in docs.versions.items():
            if isinstance(value, dict) and key in value and value[key] != version:
                checker.fail(f"{vdoc}: key '{key}': documents version {version}, glint writes "
                             f"{value[key]}", origin)
            # Goldens hold a sim report one level down.
            report = value.get("report") if isinstance(value, dict) else None
            if isinstance(report, dict) and key in report and report[key] != version:
                checker.fail(f"{vdoc}: key '{key}': documents version {version}, the golden has "
                             f"{report[key]}", origin)


def check_csv(docs, checker, csvs):
    """The sweep CSV's header is the documented column list (image.* only for a scene, the
    energy's columns only with --node)."""
    doc = "src/sweep/sweep_report.md"
    columns = docs.csv.get(doc)
    if columns is None:
        checker.fail(f"{doc}: no ```csv block listing the CSV columns")
        return
    for origin, header, scene, node in csvs:
        want = [c for c in columns if (scene or not c.startswith("image."))
                and (node or c not in NODE_COLUMNS)]
        for c in header:
            if c not in want:
                checker.fail(f"{doc}: CSV column '{c}': glint writes it, but it is not documented",
                             origin)
        for c in want:
            if c not in header:
                checker.fail(f"{doc}: CSV column '{c}': documented, but missing", origin)
        if set(header) == set(want) and header != want:
            checker.fail(f"{doc}: CSV columns: glint writes them in another order", origin)
        checker.keys_checked += len(header)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("glint", help="the glint binary")
    ap.add_argument("source", help="the source folder (traces/, src/)")
    ap.add_argument("--synth", action="store_true",
                    help="also check glint synth (needs yosys on PATH)")
    args = ap.parse_args()
    glint = os.path.abspath(args.glint)
    source = os.path.abspath(args.source)
    if args.synth and shutil.which("yosys") is None:
        sys.exit("check_schemas.py: --synth needs yosys on PATH")

    docs = Docs()
    for doc in DOC_FILES:
        parse_doc(docs, source, doc)
    check_structure(docs)
    if docs.errors:
        for e in docs.errors:
            print(e)
        sys.exit(1)

    with tempfile.TemporaryDirectory(prefix="glint_schemas_") as work:
        runner = Runner(glint, source, work)
        runner.all(args.synth)
    if runner.failures:
        for f in runner.failures:
            print("glint failed:", f)
        sys.exit(1)

    checker = Checker(docs)
    for doc, section, value, origin in runner.outputs:
        checker.check(doc, section, value, origin)
    check_versions(docs, checker, runner.outputs)
    check_csv(docs, checker, runner.csvs)
    # Without --synth nothing exercises synth_report.md: its keys cannot be required to appear.
    checker.unseen(set() if args.synth else {SYNTH_DOC})

    for message in checker.messages():
        print(message)
    if checker.violations:
        print(f"FAIL: {len(checker.violations)} violations")
        sys.exit(1)
    skipped = set() if args.synth else {SYNTH_DOC}
    documented = sum(len(e) for (doc, _), e in docs.sections.items() if doc not in skipped)
    print(f"PASS: {len(runner.outputs)} documents, {documented} keys "
          f"({checker.keys_checked} values checked)")


if __name__ == "__main__":
    main()
