#!/usr/bin/env python3
"""The HTML pages of `glint render/sweep/size --html`, end to end.

usage: html_report.py GLINT SOURCE_DIR page|browser

Both modes make the three pages from small inputs with hostile names (a scene named with < > & " ',
an output folder and a vector file named so too) in a scratch folder, then:

page     parses each page with Python's html.parser: every element closed in order, the hostile
         names only as text (never as markup), the tables' rows and cells against the JSON
         reports, every embedded PNG byte for byte the file the render wrote, the command to
         reproduce splitting back into the argv that was run; merge's page of two shards holds
         the unsharded sweep's rows; a bad --html path writes nothing.
browser  opens each page in headless Chromium (ctest label `browser`): the page's own self-test
         (#selftest) reports in the dumped DOM that every table has its rows, a click sorts a
         table both ways and every image decoded; a screenshot of the render page shows the
         first image (its area is not the page's background). Exit 77 (ctest SKIP) when
         Chromium is not installed.
Prints PASS on success; any failure is an assertion naming what differs.
"""
import base64
import html.parser
import json
import os
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

GLINT, SOURCE, MODE = sys.argv[1], sys.argv[2], sys.argv[3]
HOSTILE = "<b>bold</b> & \"q\" 'a'"
VOID = {"meta", "img", "br", "hr", "input", "link", "col", "area", "base", "source", "wbr"}


class Page(html.parser.HTMLParser):
    """The elements of a page, checked for nesting as they are read."""

    def __init__(self, text):
        super().__init__(convert_charrefs=True)
        self.stack, self.errors = [], []
        self.tables = {}  # id -> list of rows, each a list of (text, data-v or None)
        self.images = []  # src of every <img>
        self.pre = {}  # id -> text
        self.texts = []  # every text node
        self.svgs = 0
        self._table = self._row = self._cell = self._pre = None
        self.feed(text)
        self.close()
        if self.stack:
            self.errors.append(f"unclosed at the end: {self.stack}")

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "svg":
            self.svgs += 1
        if tag == "img":
            self.images.append(a.get("src", ""))
        if tag == "table":
            self._table = self.tables.setdefault(a.get("id", f"#{len(self.tables)}"), [])
        if tag == "tr" and self._table is not None and "tbody" in self.stack:
            self._row = []
            self._table.append(self._row)
        if tag == "td" and self._row is not None:
            self._cell = ["", a.get("data-v")]
            self._row.append(self._cell)
        if tag == "pre":
            self._pre = a.get("id", "")
            self.pre[self._pre] = ""
        if tag not in VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in VOID:
            self.stack.pop()  # <circle ... /> in inline SVG: closed at once

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:] or 'nothing'}")
            return
        self.stack.pop()
        if tag == "table":
            self._table = None
        if tag == "tr":
            self._row = None
        if tag == "td":
            self._cell = None
        if tag == "pre":
            self._pre = None

    def handle_data(self, data):
        self.texts.append(data)
        if self._cell is not None:
            self._cell[0] += data
        if self._pre is not None:
            self.pre[self._pre] += data


def run(args, status=0):
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == status, f"{args}: exit {r.returncode}, expected {status}\n{r.stderr}"
    return r


def read_page(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    page = Page(text)
    assert not page.errors, f"{path}: not well formed: {page.errors[:5]}"
    return text, page


def check_reproduce(page, argv, path):
    words = shlex.split(page.pre["command"])
    assert words[:3] == ["cd", os.getcwd(), "&&"], f"{path}: {words[:3]}"
    assert words[3:] == argv, f"{path}: the command splits into {words[3:]}, ran {argv}"


def make_pages(work):
    """Runs the three commands; returns {name: (page path, argv, json report)}."""
    with open(os.path.join(SOURCE, "traces/scenes/small.json")) as f:
        scene = json.load(f)
    scene["name"] = HOSTILE
    scene_path = os.path.join(work, "hostile.json")
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    out = os.path.join(work, "out <'&\">")
    os.mkdir(out)
    pages = {}
    render = [GLINT, "render", scene_path, "-o", os.path.join(out, "r"), "--unit", "hast",
              "--unit", "lut", "--threads", "2", "--html"]
    run(render)
    with open(os.path.join(out, "r", "report.json")) as f:
        pages["render"] = (os.path.join(out, "r", "report.html"), render, json.load(f))
    vectors = os.path.join(out, "v<&>'\".vec")
    shutil.copy(os.path.join(SOURCE, "traces/phong_basic.vec"), vectors)
    sweep = [GLINT, "sweep", vectors, "--grid", "lut:bits=4..7", "--grid", "horner:degree=2..3",
             "-o", os.path.join(out, "sweep.json"), "--html", os.path.join(out, "sweep.html")]
    run(sweep)
    with open(os.path.join(out, "sweep.json")) as f:
        pages["sweep"] = (os.path.join(out, "sweep.html"), sweep, json.load(f))
    size = [GLINT, "size", "--budget", "lsb8<=1", "--grid", "lut:bits=5..8", "--grid",
            "horner:degree=2..4", "--no-widen", "--chip", "rom", vectors, "--html",
            os.path.join(out, "size.html"), "--json"]
    pages["size"] = (os.path.join(out, "size.html"), size, json.loads(run(size).stdout))
    return pages, out


def check_pages(pages, out):
    # Render: the hostile name is text, the images are the files, the table is the report's.
    path, argv, report = pages["render"]
    text, page = read_page(path)
    assert HOSTILE not in text and "<b>bold" not in text, "the scene name was not escaped"
    assert any(HOSTILE in t for t in page.texts), "the scene name is not shown as text"
    check_reproduce(page, argv, path)
    pngs = [f for f in report["files"] if f.endswith(".png")]
    assert len(page.images) == len(pngs), f"{len(page.images)} images, {len(pngs)} PNGs written"
    for name, src in zip(pngs, page.images):
        prefix = "data:image/png;base64,"
        assert src.startswith(prefix), f"{name}: not a data: URI"
        with open(os.path.join(os.path.dirname(path), name), "rb") as f:
            assert base64.b64decode(src[len(prefix):]) == f.read(), f"{name}: not the file"
    units = page.tables["units"]
    assert "skipped % (light x pixel pairs)" in page.texts, "the units' skip column"
    assert len(units) == len(report["units"]), f"units table: {len(units)} rows"
    for row, u in zip(units, report["units"]):
        assert row[0][0] == u["unit"], f"{row[0][0]} != {u['unit']}"
        assert float(row[1][1]) == u["image_error"]["max_lsb"], f"{u['unit']}: max_lsb"
        assert row[-1][0] == u["spec"]
        skip = 7  # the column after core_ratio
        assert float(row[skip][1]) == u["skipped_fraction"], f"{u['unit']}: skipped_fraction"
        assert row[skip][0] == f"{100 * u['skipped_fraction']:.1f} %", row[skip][0]
    assert len(page.tables["skips"]) == len(report["skip"]["per_light_material"])
    assert len(page.tables["slots"]) == len(report["slots"])
    assert json.loads(page.pre[""]) == report, "the page's report.json is not the file"

    # Sweep: plots inline, fronts and configurations as the report flags them.
    path, argv, report = pages["sweep"]
    text, page = read_page(path)
    assert "v<&>'\"" not in text, "the vector file's name was not escaped"
    check_reproduce(page, argv, path)
    assert page.svgs == 2, f"{page.svgs} plots"
    assert len(page.tables["configurations"]) == len(report["results"])
    for name in ("area", "throughput", "area_latency"):
        flagged = sum(r["pareto"][name] for r in report["results"])
        assert len(page.tables["front_" + name]) == flagged, f"front {name}"

    # Merge: the page of two shards joined holds the unsharded sweep's rows.
    shards = []
    for k in range(2):
        shards.append(os.path.join(out, f"shard{k}.json"))
        run(argv[:argv.index("-o")] + ["--shard", f"{k}/2", "-o", shards[-1]])
    merged = os.path.join(out, "merged.html")
    run([GLINT, "merge"] + shards + ["--html", merged])
    _, merged_page = read_page(merged)
    assert merged_page.tables["configurations"] == page.tables["configurations"], "merge page"

    # Size: a row per family, the fronts of its input.
    path, argv, doc = pages["size"]
    text, page = read_page(path)
    check_reproduce(page, argv, path)
    assert len(page.tables["families"]) == len(doc["families"])
    for row, fam in zip(page.tables["families"], doc["families"]):
        if fam.get("spec"):
            assert row[2][0] == fam["spec"]
    assert page.svgs == 2, f"{page.svgs} plots"

    # All or nothing: an --html path that cannot be written refuses the run before any work,
    # and the report asked for beside it is not written either.
    bad = os.path.join(out, "no such folder", "x.html")
    json_out = os.path.join(out, "refused.json")
    r = run([GLINT, "sweep", os.path.join(SOURCE, "traces/phong_basic.vec"), "--grid", "lut",
             "-o", json_out, "--html", bad], status=2)
    assert "--html" in r.stderr, r.stderr
    assert not os.path.exists(json_out), "a refused run wrote its report"


def decode_png(path):
    """(width, height, rows of RGB(A) bytes): 8-bit truecolour, non-interlaced (Chromium's)."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unexpected PNG format"
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, rows, prev = zlib.decompress(idat), [], bytearray(w * bpp)
    stride = w * bpp
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows


def check_browser(pages, work):
    expected = {
        "render": (pages["render"][2], lambda r: {"units": len(r["units"])}),
        "sweep": (pages["sweep"][2], lambda r: {"configurations": len(r["results"])}),
        "size": (pages["size"][2], lambda d: {"families": len(d["families"])}),
    }
    shot = os.path.join(work, "render.png")
    # Every Chromium at once (own profiles): the test's time is about one browser start.
    procs = {}
    for name, (path, _, _) in pages.items():
        procs[name] = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu",
             "--user-data-dir=" + os.path.join(work, "profile_" + name),
             "--virtual-time-budget=5000", "--dump-dom", "file://" + path + "#selftest"],
            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    procs["shot"] = subprocess.Popen(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--force-device-scale-factor=1", "--window-size=1280,1600",
         "--user-data-dir=" + os.path.join(work, "profile_shot"), "--screenshot=" + shot,
         "file://" + pages["render"][0]],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    dumps = {name: p.communicate(timeout=120)[0] for name, p in procs.items()}
    image0 = None
    for name, (report, counts) in expected.items():
        page = Page(dumps[name])
        lines = page.pre.get("selftest", "").splitlines()
        assert lines, f"{name}: the self-test did not run in Chromium"
        assert lines[-1] == "selftest pass", f"{name}: {lines}"
        for table, rows in counts(report).items():
            assert f"table {table} rows {rows}" in lines, f"{name}: {table} not {rows} rows: {lines}"
            assert len(page.tables[table]) == rows, f"{name}: the DOM's {table}"
        sorts = [l for l in lines if l.startswith("sort ")]
        assert sorts and sorts[0].endswith("ascending ok descending ok"), f"{name}: {sorts}"
        n = len([f for f in report.get("files", []) if f.endswith(".png")])
        assert f"images {n} decoded {n}" in lines, f"{name}: {lines}"
        if name != "render":
            assert "svgs 2" in lines or "svgs 4" in lines, f"{name}: plots {lines}"
        else:
            image0 = [int(v) for v in next(l for l in lines if l.startswith("image0 ")).split()[1:]]
    # The screenshot: the page's background at its corner, the first image where the page says
    # it is, and there the picture (many colours, mostly not the background).
    assert os.path.exists(shot), "Chromium wrote no screenshot"
    w, h, bpp, rows = decode_png(shot)
    background = bytes(rows[2][2 * bpp:2 * bpp + 3])
    x, y, iw, ih = image0
    assert x + iw <= w and y + ih <= h, f"the first image {image0} is outside the {w}x{h} shot"
    colours, differ, seen = set(), 0, 0
    for yy in range(y + 2, y + ih - 2, 3):
        for xx in range(x + 2, x + iw - 2, 3):
            px = bytes(rows[yy][xx * bpp:xx * bpp + 3])
            colours.add(px)
            differ += px != background
            seen += 1
    assert len(colours) > 8, f"the image area has {len(colours)} colours: blank"
    assert differ > seen // 2, f"{differ} of {seen} pixels differ from the background"


def main():
    if MODE == "browser" and not shutil.which("chromium"):
        print("SKIP: chromium is not installed (Debian package chromium)")
        return 77
    work = tempfile.mkdtemp(prefix="glint_html_")
    try:
        os.chdir(work)
        pages, out = make_pages(work)
        if MODE == "page":
            check_pages(pages, out)
        else:
            check_browser(pages, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"PASS: html {MODE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
