#!/usr/bin/python3
"""Checks the page a study writes, results/<name>/index.html, and its screenshots in Chromium.

    /usr/bin/python3 tests/report/check_report.py RESULTS_DIR SCREENSHOT.png

Fails (exit status 1, one line per problem) when
  - index.html holds a script, an external resource (http:, https:, //) or a link or image to a
    file that does not exist;
  - a PNG figure of RESULTS_DIR/figures/ is not shown on the page (<img>) with a caption, or a
    figure is larger than a page (8.5 x 11 inches at the DPI recorded in the PNG);
  - the page does not open on the summary table (a table before the first image), or the
    table's rows are not the rows of summary.csv (query and method), or a row's paired count and
    n are not those recounted here from instances.csv (the instances of the query on which every
    number type of the method's algorithm ran, and the method's certified rows among them);
  - the uniform sample's tables do not show exactly the rows of uniform.csv (query and method)
    with its decided, FP, FN and class counts;
  - the screenshot (the page in a tall window) is blank (almost only one colour), its top (a
    window's height) lacks the shading of a summary row with a wrong answer, or the rest shows no
    figure (no pixel of the heat maps' darkest red, of matplotlib's first line colour or of the
    failure maps' blue).
"""
import csv
import os
import re
import struct
import sys
from html.parser import HTMLParser


class Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.events = []  # ("table" | "img" | "script" | ..., attrs), in document order
        self.rows = []  # (query section, first cell) of every summary table body row
        self.cells = {}  # (query section, first cell) -> every cell of the row
        self.uniform = {}  # (query, method) -> every cell of a row of the uniform sample's tables
        self.section = None
        self.kind = None
        self.captions = []
        self._cell = None
        self._in_tbody = False
        self._in_caption = False
        self._text = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.events.append((tag, a))
        if tag == "h3":
            hid = a.get("id", "")
            self.kind, _, self.section = hid.partition("-") if hid.startswith(("summary-", "uniform-")) else (None, "", None)
        elif tag == "tbody":
            self._in_tbody = True
        elif tag == "tr" and self._in_tbody:
            self._cell = 0
            self._text = []
            self._row = []
        elif tag == "td" and self._cell is not None:
            self._cell += 1
            self._row.append("")
        elif tag == "figcaption":
            self._in_caption = True
            self._text = []

    def handle_endtag(self, tag):
        if tag == "tbody":
            self._in_tbody = False
        elif tag == "tr" and self._cell is not None:
            key = (self.section, "".join(self._text).strip())
            if self.kind == "summary":
                self.rows.append(key)
                self.cells[key] = [c.strip() for c in self._row]
            elif self.kind == "uniform":
                self.uniform[key] = [c.strip() for c in self._row]
            self._cell = None
        elif tag == "figcaption":
            self.captions.append("".join(self._text).strip())
            self._in_caption = False

    def handle_data(self, data):
        if (self._cell == 1) or self._in_caption:
            self._text.append(data)
        if self._cell:
            self._row[-1] += data


def png_size_dpi(path):
    """(width, height, dots per inch or None) from a PNG's IHDR and pHYs chunks."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    width, height = struct.unpack(">II", data[16:24])
    dpi = None
    pos = 8
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"pHYs":
            ppu_x, _, unit = struct.unpack(">IIB", data[pos + 8:pos + 17])
            if unit == 1:
                dpi = ppu_x * 0.0254
        if kind == b"IDAT":
            break
        pos += 12 + length
    return width, height, dpi


def has_colour(rgb, want):
    """Whether the pixels rgb (an array of rows of RGB) hold one within 6 levels of a colour of
    `want`."""
    import numpy as np

    colours = np.unique(rgb.reshape(-1, 3), axis=0)
    return any(np.any(np.all(np.abs(colours - np.array(w)) <= 6, axis=1)) for w in want)


def check_screenshot(path, problems):
    """Not blank (more than a few colours, at least 1% of the pixels not white); the top
    (TOP_ROWS rows, a window's height) holds a shaded summary row, the rest a figure."""
    import matplotlib.image
    import numpy as np

    rgb = np.round(matplotlib.image.imread(path)[:, :, :3] * 255).astype(int)
    height, width = rgb.shape[:2]
    colours = np.unique(rgb.reshape(-1, 3), axis=0)
    share = float(np.mean(np.any(rgb != 255, axis=2)))
    print(f"check_report: {os.path.basename(path)}: {width}x{height}, {len(colours)} colours, {100 * share:.1f}% not white")
    if len(colours) < 20 or share < 0.01:
        problems.append(f"{path}: blank ({len(colours)} colours, {100 * share:.2f}% of the pixels not white)")
    if not has_colour(rgb[:TOP_ROWS], [SHADED_ROW]):
        problems.append(f"{path}: the top {TOP_ROWS} rows show no shaded summary row (#fde0e0)")
    if not has_colour(rgb[TOP_ROWS:], FIGURE_COLOURS):
        problems.append(f"{path}: below the top, no pixel of a figure (#67000d, #1f77b4 or #4c72b0)")


# The top of the page: the summary, with a row shaded for a wrong answer. Below: a figure, seen
# by the darkest red of the heat maps (#67000d), matplotlib's first line colour (tab:blue) or
# the failure maps' "separated" blue.
TOP_ROWS = 1600
SHADED_ROW = (0xfd, 0xe0, 0xe0)
FIGURE_COLOURS = [(0x67, 0x00, 0x0d), (0x1f, 0x77, 0xb4), (0x4c, 0x72, 0xb0)]


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    folder, shot = sys.argv[1:]
    index = os.path.join(folder, "index.html")
    problems = []
    if not os.path.exists(index):
        print(f"check_report: {index} is missing")
        return 1
    with open(index, encoding="utf-8") as f:
        text = f.read()
    page = Page()
    page.feed(text)

    images = []
    for tag, a in page.events:
        if tag in ("script", "iframe", "object", "embed"):
            problems.append(f"index.html holds a <{tag}>")
        for key in ("src", "href"):
            ref = a.get(key)
            if ref is None or ref.startswith("#"):
                continue
            if re.match(r"^([a-z]+:|//)", ref):
                problems.append(f"index.html refers to an external resource: {ref}")
                continue
            if not os.path.exists(os.path.join(folder, ref)):
                problems.append(f"index.html refers to a missing file: {ref}")
            if tag == "img":
                images.append(os.path.normpath(ref))
    if re.search(r"url\(|@import", text):
        problems.append("index.html's style loads a resource")

    figures = sorted(f for f in os.listdir(os.path.join(folder, "figures")) if f.endswith(".png"))
    if not figures:
        problems.append("no figures in figures/")
    for fig in figures:
        if os.path.join("figures", fig) not in images:
            problems.append(f"figures/{fig} is not shown on the page")
        width, height, dpi = png_size_dpi(os.path.join(folder, "figures", fig))
        if dpi is None:
            problems.append(f"figures/{fig}: no DPI recorded")
        elif width / dpi > 8.5 or height / dpi > 11:
            problems.append(f"figures/{fig}: {width / dpi:.1f} x {height / dpi:.1f} inches, larger than a page")
    if len(page.captions) != len(images) or any(len(c) < 40 for c in page.captions):
        problems.append(f"{len(images)} images but {len([c for c in page.captions if len(c) >= 40])} captions of a sentence")

    tags = [t for t, _ in page.events]
    if "table" not in tags or ("img" in tags and tags.index("table") > tags.index("img")):
        problems.append("the page does not open on the summary table")
    with open(os.path.join(folder, "summary.csv"), newline="") as f:
        expected = sorted((r["query"], r["method"]) for r in csv.DictReader(f))
    shown = sorted(page.rows)
    if shown != expected:
        missing = sorted(set(expected) - set(shown))[:3]
        extra = sorted(set(shown) - set(expected))[:3]
        problems.append(f"summary table: {len(shown)} rows for {len(expected)} in summary.csv (missing {missing}, unexpected {extra})")

    # Paired counts, recounted: per query and algorithm (the method's name before "/"), the
    # instances every one of its methods ran on; n: the method's certified rows among them.
    ran = {}
    with open(os.path.join(folder, "instances.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        ran.setdefault((r["query"], r["method"]), set()).add(r["instance"])
    common = {}
    for (q, m), ids in ran.items():
        key = (q, m.split("/")[0])
        common[key] = ids if key not in common else common[key] & ids
    n_on = {}
    for r in rows:
        if r["outcome"] != "uncertified" and r["instance"] in common[(r["query"], r["method"].split("/")[0])]:
            n_on[(r["query"], r["method"])] = n_on.get((r["query"], r["method"]), 0) + 1
    for (q, m), cells in page.cells.items():
        want = [str(len(common.get((q, m.split("/")[0]), ()))), str(n_on.get((q, m), 0))]
        if cells[2:4] != want:
            problems.append(f"summary table: {q} {m}: paired and n show {' '.join(cells[2:4])}, instances.csv gives {' '.join(want)}")
    upath = os.path.join(folder, "uniform.csv")
    uniform = {}
    if os.path.exists(upath):
        with open(upath, newline="") as f:
            uniform = {(r["query"], r["method"]): r for r in csv.DictReader(f)}
    if sorted(page.uniform) != sorted(uniform):
        problems.append(f"uniform sample: {len(page.uniform)} rows shown for {len(uniform)} in uniform.csv")
    for key, cells in page.uniform.items():
        r = uniform.get(key)
        want = [r[c] for c in ("decided", "false_positive", "false_negative", "class_mismatch")] if r else []
        if r and cells[2:6] != want:
            problems.append(f"uniform sample: {key[0]} {key[1]}: shows {' '.join(cells[2:6])}, uniform.csv gives {' '.join(want)}")

    check_screenshot(shot, problems)

    for p in problems:
        print(f"check_report: {p}")
    print(f"check_report: {len(figures)} figures, {len(shown)} summary rows, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
