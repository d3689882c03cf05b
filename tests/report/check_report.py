#!/usr/bin/python3
"""Checks the page a study writes, results/<name>/index.html, and its screenshots in Chromium.

    /usr/bin/python3 tests/report/check_report.py RESULTS_DIR SCREENSHOT.png

Fails (exit status 1, one line per problem) when
  - index.html holds a script, an external resource (http:, https:, //) or a link or image to a
    file that does not exist;
  - a PNG figure of RESULTS_DIR/figures/ is not shown on the page (<img>) with a caption, or a
    figure is larger than a page (8.5 x 11 inches at the DPI recorded in the PNG);
  - the page does not open on the summary table (a table before the first image), or the
    table's rows are not the rows of summary.csv (query and method);
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
        self.rows = []  # (query section, first cell) of every table body row
        self.section = None
        self.captions = []
        self._cell = None
        self._in_tbody = False
        self._in_caption = False
        self._text = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.events.append((tag, a))
        if tag == "h3" and a.get("id", "").startswith("summary-"):
            self.section = a["id"][len("summary-"):]
        elif tag == "tbody":
            self._in_tbody = True
        elif tag == "tr" and self._in_tbody:
            self._cell = 0
            self._text = []
        elif tag == "td" and self._cell is not None:
            self._cell += 1
        elif tag == "figcaption":
            self._in_caption = True
            self._text = []

    def handle_endtag(self, tag):
        if tag == "tbody":
            self._in_tbody = False
        elif tag == "tr" and self._cell is not None:
            self.rows.append((self.section, "".join(self._text).strip()))
            self._cell = None
        elif tag == "figcaption":
            self.captions.append("".join(self._text).strip())
            self._in_caption = False

    def handle_data(self, data):
        if (self._cell == 1) or self._in_caption:
            self._text.append(data)


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

    check_screenshot(shot, problems)

    for p in problems:
        print(f"check_report: {p}")
    print(f"check_report: {len(figures)} figures, {len(shown)} summary rows, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
