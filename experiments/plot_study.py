#!/usr/bin/python3
"""Figures of the robustness study, read from the CSV files of a results folder only, and the page
that presents them.

    /usr/bin/python3 experiments/plot_study.py results/<name> [--out DIR] [--judged JUDGE_DIR]...

Writes PNG and PDF into results/<name>/figures/ (or DIR), each sized to fit a page:
  disagreement_<query>   false positives + false negatives per method and family (heat map)
  gap_rate_<query>       disagreement rate against the certified gap, one small panel per method
                         that gave a wrong answer (at most 16), separated and overlapping sides
  pareto                 median ns per query against disagreement rate, per query, every method,
                         on the instances of the query where every method ran (the slow types
                         run on a subset: paired, their count in the panel's title); only the
                         methods on the Pareto front are labelled
  pareto_compact         the same without sweeps and the extra MPFR precisions, colour by
                         algorithm, marker by number type, one key of each (legible at a page's
                         width), paired on
                         the instances where every method it shows ran
                         --judged JUDGE_DIR (repeatable): on both, the method of each results
                         folder of `certcyl judge` (its speed.csv) as a star with a black edge,
                         named, in the legend, for the queries it was judged on; its time is the
                         judge's mean per query (the exchange included), not a median per
                         instance, and it is kept out of the Pareto front
  gap_rate_overview      disagreement rate against |gap| for the methods in hardware precision,
                         line queries pooled, triangles, cylinder pairs
  error_by_k             error rate against k (the ulps off a family's degeneracy), binned (k = 0,
                         then four binades a bin), with 95% Wilson intervals, one panel per query:
                         the methods in hardware precision with most wrong answers, the Boolean
                         error (FP + FN) and, where it differs, the three-valued one (+ class)
  error_by_k.html        the same as a table for every method with a wrong answer (linked from
                         index.html)
  t_error                line queries: error of the entry parameter t in ulps, one panel per query,
                         on the instances where every method shown ran (paired)
                         (median, 90th and 99th percentiles, maximum)
  pareto_t_error         line queries: median ns against the 99th percentile of the t error (paired)
  map_<name>             failure maps: each method's answer on the ulp grid, wrong cells marked
                         (class mismatches, touching for overlapping or the reverse, apart), the
                         axes in ulps of the two perturbed coordinates; one image per panel, at
                         least a pixel per cell, every colour drawn named in the legend
  map_compact_<name>     the same with at most 8 panels (methods with identical answers on every
                         cell share a panel), legible at a page's width
  manifest.json          the SHA-256 of every file read (relative to the results folder) and of
                         every figure written, so a consumer (the paper) can tell whether a figure
                         comes from the study outputs it sits beside
and index.html, the page to start from: the summary table (summary.csv), then every figure with
a sentence on how to read it; static HTML, no script, no external resource. It is written to
results/<name>/index.html (with --out DIR: DIR/index.html), its links relative to it.
One line per figure on standard error as it is written.
Needs matplotlib and numpy (Debian python3-matplotlib, python3-numpy).
"""
import json
import math
import os
import re
import sys
import time
from collections import defaultdict
from html import escape

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import to_rgba, to_rgba_array  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import certcyl_results as cr  # noqa: E402
from certcyl_results import QUERY_TITLES, fnum, read_csv  # noqa: E402

KIND_COLOURS = {
    "certified": "black",
    "seed_as_written": "tab:red",
    "seed_corrected": "tab:blue",
    "robust": "tab:green",
    "sweep": "tab:purple",
    "peer": "tab:orange",
}

# A page: no figure is wider or taller than this (inches), so each prints on A4 or Letter.
PAGE_WIDTH, PAGE_HEIGHT = 7.8, 10.0

FIGURES = []  # (name, caption) of every figure written, in order
WRITTEN = []  # every file written
START = time.monotonic()


def save(fig, out, name, caption, rect=None, dpi=110, tight=True):
    """Writes name.png and name.pdf; `caption` is the sentence on how to read it (index.html)."""
    if tight:
        fig.tight_layout(rect=rect)
    width, height = fig.get_size_inches()
    assert width <= PAGE_WIDTH + 1e-9 and height <= PAGE_HEIGHT + 1e-9, f"{name}: {width:.1f} x {height:.1f} in"
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"{name}.{ext}")
        # A fixed creation date keeps the PDF a function of the data (matplotlib honours it).
        meta = {"CreationDate": None} if ext == "pdf" else None
        fig.savefig(path, dpi=dpi, metadata=meta)
        WRITTEN.append(path)
    plt.close(fig)
    FIGURES.append((name, caption))
    print(f"plot_study: {len(FIGURES)} figures, {name}.png and .pdf ({time.monotonic() - START:.1f} s)", file=sys.stderr, flush=True)


def front(points):
    """The Pareto front of (cost, error, ...) tuples: no other point is both cheaper and at most
    as wrong; sorted by cost."""
    return sorted(p for p in points if not any(o[0] < p[0] and o[1] <= p[1] for o in points if o is not p))


def pareto_axes(ax, query, ylabel):
    """Labels and grid of one Pareto panel (speed on x, an error measure on y)."""
    ax.set_xlabel("median ns per query", fontsize=6.5)
    ax.set_ylabel(ylabel, fontsize=6.5)
    ax.set_title(QUERY_TITLES.get(query, query), fontsize=7.5)
    ax.tick_params(labelsize=6)
    ax.grid(alpha=0.3)


def pareto_legend(fig, axes, used, title, kinds, lift=0):
    """Blanks the unused panels, and adds the legend of the method kinds drawn (`kinds`) and the
    front (`lift`, a fraction of the figure's height, above the bottom: the judged methods'
    legend below it), and the title."""
    for ax in list(axes.flat)[used:]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", ms=4, label=k) for k, c in KIND_COLOURS.items() if k in kinds]
    handles.append(plt.Line2D([], [], color="grey", lw=0.7, label="Pareto front (its methods named)"))
    bottom_legend(fig, handles, 6, lift)
    fig.suptitle(title, fontsize=8)


def bottom_legend(fig, handles, fontsize, lift):
    """The legend of `handles` at the bottom centre of the figure, seven to a line, `lift` (a
    fraction of the figure's height) above the bottom when the judged methods' legend is below."""
    anchor = {"bbox_to_anchor": (0.5, lift)} if lift else {}
    fig.legend(handles=handles, loc="lower center", ncol=7, fontsize=fontsize, frameon=False, **anchor)


def label_front(ax, pts, floor=None):
    """Names the points `pts` ((x, y, label) or (x, y, label, style), drawn at max(y, floor))
    beside them, to the right on the left part of the axes and to the left on the right part,
    one name per line from the highest point down (a name pushed below its point is joined to it
    by a thin line), so that no two names overlap; `style`, a dict, adds to the name's text
    properties. Call after the axes' scales and limits are final."""
    ax.get_xlim()
    ax.get_ylim()
    fig = ax.figure
    step = 7.0 / (ax.get_position().height * fig.get_size_inches()[1] * 72)  # a 5 pt line and a gap
    to_axes = ax.transAxes.inverted()
    items = []
    for x, y, label, *style in pts:
        y = y if floor is None else max(y, floor)
        fx, fy = to_axes.transform(ax.transData.transform((x, y)))
        items.append((fy, fx, x, y, label, style[0] if style else {}))
    last = None
    for fy, fx, x, y, label, style in sorted(items, key=lambda t: -t[0]):
        ty = fy + 0.03 if last is None else min(fy + 0.03, last - step)
        last = ty
        right = fx > 0.6
        ax.annotate(label, (x, y), xytext=(fx - 0.03 if right else fx + 0.03, ty), textcoords="axes fraction", fontsize=5,
                    ha="right" if right else "left", va="center", arrowprops={"arrowstyle": "-", "color": "grey", "lw": 0.4},
                    **style)


def wrap_name(name, width):
    """A method's name on lines of at most `width` characters where it can break: before a
    parameter list "[...]" and after a "/" (a longer piece keeps its own line)."""
    lines = [""]
    for piece in re.split(r"(?=\[)|(?<=/)", name):
        if lines[-1] and len(lines[-1]) + len(piece) > width:
            lines.append("")
        lines[-1] += piece
    return "\n".join(lines)


# A judged method (--judged): a star with a black edge, the first method red, the others in turn.
JUDGED_COLOURS = ("red", "magenta", "gold", "cyan", "lime")
JUDGED_NAME_CHARS = 30


def read_judged(paths):
    """The judged methods of the results folders `paths` of `certcyl judge` (or their speed.csv):
    one dict per row of each speed.csv (query, method, x = mean_ns, y = disagreement rate,
    source = the speed.csv, colour), a method's colour by its first appearance. ValueError
    naming the file when a speed.csv is missing or malformed."""
    judged, colours = [], {}
    for p in paths:
        path = p if os.path.isfile(p) else os.path.join(p, "speed.csv")
        if not os.path.isfile(path):
            raise ValueError(f"{path}: no such file (`certcyl judge` writes speed.csv for --plugin and --exec when "
                             "every case was answered)")
        for r in cr.read_judged_speed(path):
            colour = colours.setdefault(r["method"], JUDGED_COLOURS[len(colours) % len(JUDGED_COLOURS)])
            judged.append({"query": r["query"], "method": r["method"], "x": float(r["mean_ns"]),
                           "y": float(r["disagreement_rate"]), "source": path, "colour": colour})
    return judged


def judged_label(method):
    """A judged method's name on a figure: at most JUDGED_NAME_CHARS characters and an ellipsis,
    a dollar sign shown as itself (not as matplotlib's mathematics)."""
    name = method if len(method) <= JUDGED_NAME_CHARS else method[:JUDGED_NAME_CHARS] + "\u2026"
    return name.replace("$", r"\$")


def draw_judged(ax, judged, query, floor, size):
    """Draws the judged methods' points of `query` (at max(rate, floor)), kept out of any front;
    returns their (x, y, name, style) for label_front."""
    names = []
    for j in judged:
        if j["query"] != query:
            continue
        ax.scatter(j["x"], max(j["y"], floor), marker="*", s=size, color=j["colour"], edgecolors="black", linewidths=0.6,
                   zorder=5, gid="judged")
        names.append((j["x"], j["y"], judged_label(j["method"]), {"fontweight": "bold"}))
    return names


def judged_legend(fig, judged, fontsize):
    """The legend of the judged methods at the bottom of the figure, three to a line; returns the
    fraction of the figure's height it takes (0 without judged methods: no legend)."""
    seen = {}
    for j in judged:
        seen.setdefault(j["method"], j["colour"])
    if not seen:
        return 0
    handles = [plt.Line2D([], [], ls="", marker="*", ms=8, markerfacecolor=c, markeredgecolor="black", markeredgewidth=0.6,
                          label="judged: " + judged_label(m)) for m, c in seen.items()]
    fig.legend(handles=handles, loc="lower center", ncol=min(3, len(handles)), fontsize=fontsize, frameon=False,
               bbox_to_anchor=(0.5, 0))
    return (0.2 * math.ceil(len(handles) / 3) + 0.05) / fig.get_size_inches()[1]


def judged_caption(judged):
    """The sentences a Pareto figure's caption adds for the judged methods (none without)."""
    if not judged:
        return ""
    sources = {}
    for j in judged:
        sources.setdefault((j["method"], j["source"]), None)
    named = "; ".join(f"{m} ({s})" for m, s in sources)
    return (f" Stars with a black edge are methods judged by certcyl judge, named beside them and in the legend: {named}. "
            "A judged point's rate is the judge's disagreement rate (the study's definition), but its time is its mean per query "
            "over the judge's cases, a co-process or plugin exchange included, not the study's median per instance, so the x "
            "positions compare different statistics. Judged points are kept out of the Pareto front: the staircase joins the "
            "study's methods only.")


def disagreement_tables(families, out):
    by_query = defaultdict(list)
    for r in families:
        by_query[r["query"]].append(r)
    for query, rows in by_query.items():
        methods = sorted({r["method"] for r in rows}, key=lambda m: (m.split("/")[0], m))
        fams = sorted({r["family"] for r in rows})
        rate = np.full((len(methods), len(fams)), np.nan)
        count = np.zeros((len(methods), len(fams)), dtype=int)
        for r in rows:
            i, j = methods.index(r["method"]), fams.index(r["family"])
            n = int(r["n"]) - int(r["undecided"]) - int(r["error"])
            bad = int(r["false_positive"]) + int(r["false_negative"])
            count[i, j] = bad
            rate[i, j] = bad / n if n > 0 else np.nan
        width = min(PAGE_WIDTH, 2.6 + 0.42 * len(fams))
        height = min(PAGE_HEIGHT, 1.6 + 0.15 * len(methods))
        fig, ax = plt.subplots(figsize=(width, height))
        im = ax.imshow(rate, cmap="Reds", vmin=0, vmax=max(0.05, np.nanmax(rate) if np.isfinite(rate).any() else 1), aspect="auto")
        ax.set_xticks(range(len(fams)), fams, rotation=45, ha="right", fontsize=6)
        ax.set_yticks(range(len(methods)), methods, fontsize=5.5)
        for i in range(len(methods)):
            for j in range(len(fams)):
                if count[i, j]:
                    ax.text(j, i, str(count[i, j]), ha="center", va="center", fontsize=5)
        ax.set_title(f"{query}: false positives + false negatives\n(number in the cell: count; colour: rate)", fontsize=7)
        cb = fig.colorbar(im, ax=ax, shrink=0.6)
        cb.ax.tick_params(labelsize=6)
        save(fig, out, f"disagreement_{query}",
             f"One row per method and one column per hard-case family of the {QUERY_TITLES.get(query, query)} query: the number "
             "in a cell counts the answers that disagree with the certified one (false positives plus false negatives), the "
             "colour is that count's share of the decided answers; an empty white cell is a method without a wrong answer there.")


def gap_quantity(query):
    """What a query's signed gap is (src/study/gap.hpp): the depth margin G for the queries against
    one cylinder, the log growth factor log(phi*) for cylinder pairs (the labels of
    src/study/gap_quantity.hpp, whose names depth_margin and log_phi the command's output
    carries). Axes never pool the two."""
    return "$\\log\\varphi^*$" if query == "cylinder_cylinder" else "depth margin $G$"


def gap_bin(lo, hi):
    """Signed log10 bin of the certified gap's bound nearest zero: 0 when the enclosure contains 0
    (touching, or a gap not resolved from 0), +-(e + 21) for 10^(e-1) <= |gap| < 10^e."""
    if lo <= 0 <= hi:
        return 0
    g = lo if lo > 0 else hi
    if not math.isfinite(g):
        return 23 if g > 0 else -23
    e = max(-20, min(2, math.floor(math.log10(abs(g))) + 1))
    return e + 21 if g > 0 else -(e + 21)


def gap_rate(rows, out):
    by_query = defaultdict(lambda: defaultdict(lambda: defaultdict(lambda: [0, 0])))
    for r in rows:
        if r["outcome"] in ("uncertified", "undecided", "error", "invalid"):
            continue
        b = gap_bin(fnum(r["gap_lo"]), fnum(r["gap_hi"]))
        cell = by_query[r["query"]][r["method"]][b]
        cell[0] += 1
        cell[1] += r["outcome"] in ("false_positive", "false_negative")
    for query, methods in by_query.items():
        sides = ((-1, "tab:blue", "o", f"separated side ({gap_quantity(query)} < 0)"),
                 (1, "tab:orange", "s", f"overlapping side ({gap_quantity(query)} > 0)"))
        wrong = [m for m, bins in methods.items() if any(c[1] for c in bins.values())]
        if not wrong:
            continue
        wrong.sort(key=lambda m: (-sum(c[1] for c in methods[m].values()), m))
        shown = wrong[:16]
        cols = 4
        rn = math.ceil(len(shown) / cols)
        height = 1.45 * rn + 1.1
        fig, axes = plt.subplots(rn, cols, figsize=(PAGE_WIDTH, height), sharex=True, sharey=True, squeeze=False)
        fig.subplots_adjust(left=0.08, right=0.99, top=1 - 0.75 / height, bottom=0.45 / height, wspace=0.08, hspace=0.45)
        for ax, m in zip(axes.flat, shown):
            bins = methods[m]
            for side, colour, marker, label in sides:
                xs, ys = [], []
                for b, (n, bad) in sorted(bins.items()):
                    if b == 0 or (b > 0) != (side > 0) or n == 0:
                        continue
                    xs.append(abs(b) - 21)
                    ys.append(bad / n)
                if xs:
                    ax.plot(xs, ys, marker=marker, ms=2.5, lw=0.9, color=colour)
            ax.set_title(wrap_name(m, 36), fontsize=6, linespacing=1.05)
            ax.set_ylim(-0.05, 1.05)
            ax.set_xlim(-21, 3)
            ax.tick_params(labelsize=6)
            ax.grid(alpha=0.3)
        for k, ax in enumerate(axes.flat):
            if k >= len(shown):
                ax.axis("off")
            elif k + cols < len(shown):
                ax.tick_params(labelbottom=False)
            else:
                ax.tick_params(labelbottom=True)
        quantity = gap_quantity(query)
        fig.supxlabel(f"$\\log_{{10}}$ of the certified lower bound of $|${quantity}$|$, the signed gap (upper edge of bin)",
                      fontsize=7, y=0.01)
        fig.supylabel("disagreement rate (FP + FN)", fontsize=7)
        handles = [plt.Line2D([], [], color=c, marker=mk, ms=3, lw=0.9, label=label) for _, c, mk, label in sides]
        fig.legend(handles=handles, loc="upper center", ncol=2, fontsize=6.5, frameon=False, bbox_to_anchor=(0.5, 1 - 0.3 / height))
        more = f" (the {len(shown)} of {len(wrong)} with most wrong answers)" if len(wrong) > len(shown) else ""
        fig.suptitle(f"{query}: disagreement rate against the certified signed gap, per method with a wrong answer{more}",
                     fontsize=7.5, y=1 - 0.05 / height, va="top")
        save(fig, out, f"gap_rate_{query}",
             f"One panel per method that gave a wrong answer to the {QUERY_TITLES.get(query, query)} query (most wrong answers first): "
             "each point is the share of wrong answers among the instances whose certified signed gap (here "
             + ("log phi*, the log of the growth factor at which the two cylinders touch" if query == "cylinder_cylinder" else
                "the depth margin G, the offset of the cylinder at which the answer changes")
             + ") lies in a power-of-ten bin of its certified lower bound, blue on "
             "the separated side and orange on the overlapping side, so a method that fails only near a degeneracy has points only "
             "at the left; a bin with few instances jumps between 0 and 1.",
             tight=False)


def pareto(rows, summary, out, judged=()):
    queries = sorted({r["query"] for r in summary})
    ran = cr.ran_on(rows)
    cols = 3
    rows_n = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(PAGE_WIDTH, 2.7 * rows_n + 0.8), squeeze=False)
    floor = 1e-4
    drawn = set()  # the kinds drawn
    for ax, q in zip(axes.flat, queries):
        kinds = {r["method"]: r["kind"] for r in summary if r["query"] == q}
        common, points = cr.paired_speed_error(rows, q, sorted(kinds), ran)
        pts = [(ns, rate, m, kinds[m]) for m, (ns, rate, decided) in points.items() if ns > 0 and decided]
        for ns, rate, m, kind in pts:
            ax.scatter(ns, max(rate, floor), color=KIND_COLOURS.get(kind, "grey"), s=9, linewidths=0)
            drawn.add(kind)
        names = draw_judged(ax, judged, q, floor, 90)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 1.5)
        # Pareto front: no other method is both faster and at most as wrong; only it is named
        # (the judged methods are named too, but kept out of it).
        best = front(pts)
        if best:
            ax.step([p[0] for p in best], [max(p[1], floor) for p in best], where="post", color="grey", lw=0.7, zorder=0)
        names = [(p[0], p[1], p[2]) for p in best] + names
        if names:
            label_front(ax, names, floor)
        ax.axhline(floor, color="grey", lw=0.5, ls=":")
        pareto_axes(ax, q, f"disagreement rate (0 drawn at {floor:g})")
        ax.set_title(f"{ax.get_title()} ({len(common)} paired)", fontsize=ax.title.get_fontsize())
    lift = judged_legend(fig, judged, 6)
    pareto_legend(fig, axes, len(queries), "speed against error (per query, every method)", drawn, lift)
    save(fig, out, "pareto",
         "One panel per query, one dot per method, coloured by kind, every method on the same instances: those of the query "
         "on which every method ran (the slow number types run on a pseudo-random subset; their count in the panel's title). "
         "Further left is faster, lower is right more often (a rate "
         "of 0 is drawn on the dotted line); the grey staircase joins the methods no other method beats on both speed and error, "
         "and only those are named. A rate pools every instance of the query, so it depends on the study's sampling "
         "design (k = 0 for one instance in eight, otherwise |k| log-uniform up to 2^41 ulps off a degeneracy): a point's "
         "height is the share of that design inside the method's precision band (error_by_k shows the error per k); the rate "
         "is the Boolean one, FP + FN, class mismatches aside. It says nothing of typical input: the uniform sample's rates, "
         "with their Wilson intervals, are in the table of that name on this page." + judged_caption(judged),
         rect=(0, 0.05 + lift, 1, 1))


ALGO_COLOURS = {
    "certified": "black", "robust": "tab:green", "shene": "tab:blue", "gullotti": "tab:cyan",
    "gullotti_as_written": "tab:red", "eberly_triangle": "tab:purple", "eberly_cylinders": "tab:blue",
    "eberly_cylinders_as_written": "tab:red", "fcl": "tab:brown", "fcl_mesh": "tab:brown",
    "bullet": "tab:olive", "bullet_margin0": "tab:olive", "ode": "tab:pink", "ode_mesh": "tab:pink",
}
# A peer library's variant, drawn hollow in its library's colour.
HOLLOW = ("bullet_margin0", "fcl_mesh", "ode_mesh")
NT_MARKERS = {"exact": "X", "double": "o", "long_double": "s", "interval": "^", "gmpfr<113>": "D",
              "core_expr": "*", "float": "P"}


def algo_nt_legends(fig, algos, nts, fontsize, lift):
    """Two keys at the bottom of the figure, `lift` (a fraction of its height) above it: colour =
    algorithm, one entry per colour (algorithms of one colour never share a query: named
    together; a peer's hollow variants in parentheses), and marker = number type."""
    by_colour = defaultdict(lambda: ([], []))
    for a in ALGO_COLOURS:
        if a in algos:
            by_colour[ALGO_COLOURS[a]][a in HOLLOW].append(a)
    algo_handles = []
    for c, (filled, hollow) in by_colour.items():
        label = ", ".join(filled) + (f" (hollow: {', '.join(hollow)})" if filled and hollow else ", ".join(hollow))
        algo_handles.append(plt.Line2D([], [], color=c, marker="o", ls="", ms=5, markerfacecolor=c if filled else "none",
                                       label=label))
    nt_handles = [plt.Line2D([], [], color="grey", marker=m, ls="", ms=5, label=n) for n, m in NT_MARKERS.items() if n in nts]
    keys = ((algo_handles, "colour: algorithm", "lower left", 0.01, 3), (nt_handles, "marker: number type", "lower right", 0.99, 2))
    for handles, title, loc, x, ncol in keys:
        if handles:
            fig.legend(handles=handles, title=title, title_fontsize=fontsize, loc=loc, ncol=ncol, fontsize=fontsize,
                       frameon=False, bbox_to_anchor=(x, lift), columnspacing=1.0, handletextpad=0.3)


def pareto_compact(rows, summary, out, judged=()):
    queries = [q for q in QUERY_TITLES if any(r["query"] == q for r in summary)]
    ran = cr.ran_on(rows)
    if not queries:
        return
    cols = 3
    rows_n = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(7.6, 2.5 * rows_n + 0.9), squeeze=False)
    floor = 1e-4
    used_algos, used_nts = set(), set()
    for ax, q in zip(axes.flat, queries):
        shown = sorted(r["method"] for r in summary if r["query"] == q and r["kind"] != "sweep"
                       and r["method"].partition("/")[2] in NT_MARKERS and r["method"].partition("/")[0] in ALGO_COLOURS)
        common, points = cr.paired_speed_error(rows, q, shown, ran)
        pts = [(ns, rate) + tuple(m.split("/", 1)) for m, (ns, rate, decided) in points.items() if ns > 0 and decided]
        for ns, rate, base, nt in pts:
            hollow = base in HOLLOW
            c = ALGO_COLOURS[base]
            ax.scatter(ns, max(rate, floor), marker=NT_MARKERS[nt], s=26, linewidths=0.9,
                       facecolors="none" if hollow else c, edgecolors=c)
            used_algos.add(base)
            used_nts.add(nt)
        names = draw_judged(ax, judged, q, floor, 110)
        front = sorted(p for p in pts if not any(o[0] < p[0] and o[1] <= p[1] for o in pts if o is not p))
        if front:
            ax.step([p[0] for p in front], [max(p[1], floor) for p in front], where="post", color="grey", lw=0.7, zorder=0)
        ax.axhline(floor, color="grey", lw=0.5, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 1)
        if names:
            label_front(ax, names, floor)
        ax.set_title(f"{QUERY_TITLES[q]} ({len(common)} paired)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("median ns per query", fontsize=7)
    for ax in axes[:, 0]:
        ax.set_ylabel("rate (0 at $10^{-4}$)", fontsize=7)
    for ax in list(axes.flat)[len(queries):]:
        ax.axis("off")
    lift = judged_legend(fig, judged, 6.2)
    algo_nt_legends(fig, used_algos, used_nts, 6.2, lift)
    save(fig, out, "pareto_compact",
         "The same speed against error without the sweeps and the extra MPFR precisions: colour is the algorithm, marker the "
         "number type (hollow: a peer library's variant), so the cost of each number type reads along a colour; each panel on "
         "the instances where every method it shows ran (their count in its title). As on "
         "pareto, the rate (Boolean, FP + FN) depends on the study's sampling design of k (error_by_k); typical-case rates "
         "come from the uniform sample alone."
         + judged_caption(judged),
         rect=(0, 0.1 + lift, 1, 1), dpi=150)


def gap_rate_overview(rows, out):
    groups = [("line queries", ("line_cylinder", "ray_cylinder", "segment_cylinder", "line_elliptic_cylinder")),
              ("triangle", ("triangle_cylinder",)), ("cylinder pair", ("cylinder_cylinder",))]
    hardware = ("double", "long_double", "float")
    data = defaultdict(lambda: defaultdict(lambda: defaultdict(lambda: [0, 0])))
    for r in rows:
        if r["outcome"] in ("uncertified", "undecided", "error", "invalid") or r["kind"] in ("sweep", "certified"):
            continue
        base, _, nt = r["method"].partition("/")
        if nt not in hardware:
            continue
        lo, hi = fnum(r["gap_lo"]), fnum(r["gap_hi"])
        if lo <= 0 <= hi:
            continue
        g = lo if lo > 0 else hi
        if not math.isfinite(g):
            continue
        e = max(-18, min(1, math.floor(math.log10(abs(g))) + 1))
        for gi, (_, qs) in enumerate(groups):
            if r["query"] in qs:
                cell = data[gi][r["method"]][e]
                cell[0] += 1
                cell[1] += r["outcome"] in ("false_positive", "false_negative")
    fig, axes = plt.subplots(1, 3, figsize=(7.6, 3.9), sharey=True)
    for gi, (title, _) in enumerate(groups):
        ax = axes[gi]
        methods = data[gi]
        wrong = sorted((m for m, b in methods.items() if any(c[1] for c in b.values())),
                       key=lambda m: -sum(c[1] for c in methods[m].values()))[:8]
        for m in wrong:
            xs, ys = [], []
            for e, (n, bad) in sorted(methods[m].items()):
                if n:
                    xs.append(e)
                    ys.append(bad / n)
            base, _, nt = m.partition("/")
            ax.plot(xs, ys, marker=NT_MARKERS.get(nt, "o"), ms=3.5, lw=0.9, color=ALGO_COLOURS.get(base, "grey"),
                    ls="-" if nt != "long_double" else "--", label=m.replace("_as_written", " (as written)"))
        ax.set_title(title, fontsize=8)
        quantity = gap_quantity(groups[gi][1][0])
        ax.set_xlabel(f"$\\log_{{10}}$ of $|${quantity}$|$ (bin upper edge)", fontsize=7)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
        if wrong:  # below the panel, off the data
            ax.legend(fontsize=5.5, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=1, frameon=False, borderaxespad=0)
    axes[0].set_ylabel("disagreement rate (FP + FN)", fontsize=7)
    save(fig, out, "gap_rate_overview",
         "The methods in hardware precision (double, long double, float) with wrong answers, at most 8 per panel: the share of "
         "wrong answers against the certified lower bound of the signed gap's size in powers of ten, both sides pooled: the depth "
         "margin G (the offset of the cylinder that changes the answer) for lines and triangles, log phi* (the log growth factor "
         "at which the cylinders touch) for cylinder pairs, each panel on its own axis; a method's line falls to 0 "
         "once the input is far enough from a degeneracy for its precision.",
         dpi=150)


ERROR_BY_K_METHODS = 4  # per panel of error_by_k
ERROR_BY_K_NTS = ("double", "long_double", "float")


def error_by_k_methods(by_k, kinds, query):
    """The methods of error_by_k's panel for `query`: in hardware precision (ERROR_BY_K_NTS), not
    certified, no sweep and no seed as written (whose slips are algorithmic, wrong at every k),
    with a wrong answer (Boolean or three-valued) on the hard-case families, the
    ERROR_BY_K_METHODS with most wrong answers (three-valued) first."""
    cand = []
    for (q, m), bins in by_k.items():
        base, nt = cr.split_method(m)
        if q != query or nt not in ERROR_BY_K_NTS or kinds.get(m) in ("certified", "sweep", "seed_as_written"):
            continue
        wrong3 = sum(b.wrong3 for b in bins)
        if wrong3:
            cand.append((-wrong3, m))
    return [m for _, m in sorted(cand)[:ERROR_BY_K_METHODS]]


def k_tick(b):
    lo, hi = cr.K_BINS[b]
    return "0" if lo is None else (f"$2^{{{lo}}}$+" if hi is None else f"$2^{{{lo}}}$")


def error_by_k(rows, out):
    """Error rate against k, the ulps an instance was moved off its family's degeneracy, with
    95% Wilson intervals: one panel per query."""
    by_k = cr.errors_by_k(rows)
    boolean = cr.boolean_methods(rows)
    kinds = {r["method"]: r["kind"] for r in rows}
    queries = [q for q in QUERY_TITLES if any(k[0] == q for k in by_k)]
    if not queries:
        return by_k, boolean
    cols = 2 if len(queries) > 1 else 1
    rn = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rn, cols, figsize=(PAGE_WIDTH, 2.15 * rn + 0.6), sharey=True, squeeze=False)
    nb = len(cr.K_BINS)
    for ax, q in zip(axes.flat, queries):
        methods = error_by_k_methods(by_k, kinds, q)
        for i, m in enumerate(methods):
            colour = plt.get_cmap("tab10")(i % 10)
            shift = (i - (len(methods) - 1) / 2) * 0.12
            bins = by_k[(q, m)]
            series = [(False, "-", "o", colour)]
            if m not in boolean and any(b.cls for b in bins):
                series.append((True, "--", "s", "none"))
            for three, ls, marker, face in series:
                xs, ys, lo, hi = [], [], [], []
                for b, e in enumerate(bins):
                    if not e.decided:
                        continue
                    r = e.rate3 if three else e.rate
                    a, z = e.interval(three)
                    xs.append(b + shift + (0.045 if three else 0))
                    ys.append(r)
                    lo.append(max(0.0, r - a))  # the Wilson interval holds r, up to rounding
                    hi.append(max(0.0, z - r))
                if xs:
                    ax.errorbar(xs, ys, yerr=[lo, hi], color=colour, ls=ls, lw=0.7, marker=marker, ms=3, mfc=face,
                                elinewidth=0.6, capsize=1.5, alpha=0.85,
                                label=cr.method_label(m) + (" (three-valued)" if three else ""))
        ax.set_xticks(range(nb), [k_tick(b) for b in range(nb)], fontsize=6)
        ax.set_xlim(-0.5, nb - 0.5)
        ax.set_ylim(-0.03, 1.03)
        ax.set_title(QUERY_TITLES[q], fontsize=7.5)
        ax.tick_params(axis="y", labelsize=6)
        ax.grid(alpha=0.3)
        if methods:
            ax.legend(fontsize=5.5, loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False, borderaxespad=0.3)
        else:
            ax.text(0.5, 0.5, "no wrong answer in hardware precision", transform=ax.transAxes, ha="center", fontsize=6)
    for ax in list(axes.flat)[len(queries):]:
        ax.axis("off")
    for ax in axes[:, 0]:
        ax.set_ylabel("error rate", fontsize=7)
    fig.supxlabel("|k|, ulps off the family's degeneracy (bin: from the power shown to the next one shown)", fontsize=7)
    save(fig, out, "error_by_k",
         "One panel per query: the error rate of the methods in hardware precision with most wrong answers (at most "
         f"{ERROR_BY_K_METHODS}; seeds as written, sweeps and the certified query left out) against |k|, the ulps the hard-case instance was moved off its family's degeneracy, in bins of "
         "k = 0 and four binades (the last from 2^36 up), with 95% Wilson intervals; solid: the Boolean error (FP + FN) over "
         "the decided answers; dashed with hollow markers, for a three-valued method with class mismatches: the three-valued "
         "error (FP + FN + class mismatches). The study draws k = 0 for one instance in eight and |k| log-uniform up to 2^41, "
         "so a single rate over all instances is this curve averaged over that design. Uniform random instances are left "
         "out; the table of every method is error_by_k.html.",
         rect=(0, 0.02, 1, 1), dpi=150)
    return by_k, boolean


T_ERROR_MARKS = (("median", 50, "tab:blue", "o"), ("90th percentile", 90, "tab:green", "^"),
                 ("99th percentile", 99, "tab:orange", "s"), ("maximum", 100, "tab:red", "x"))


def t_error(rows, out):
    # The methods with an error of t per query, compared on the instances where all of them ran
    # (the slow number types run on a subset): the errors of the rows of those instances only.
    shown = defaultdict(set)
    for r in rows:
        if math.isfinite(fnum(r["t_error_ulps"])):
            shown[r["query"]].add(r["method"])
    ran = cr.ran_on(rows)
    common = {q: cr.paired(rows, q, sorted(ms), ran) for q, ms in shown.items()}
    errs = defaultdict(list)
    for r in rows:
        t = fnum(r["t_error_ulps"])
        if math.isfinite(t) and r["instance"] in common[r["query"]]:
            errs[(r["query"], r["method"])].append(t)
    if not errs:
        return
    keys = sorted(errs)
    queries = [q for q in QUERY_TITLES if any(k[0] == q for k in keys)] + sorted({q for q, _ in keys} - set(QUERY_TITLES))
    cols = 2 if len(queries) > 1 else 1
    rn = math.ceil(len(queries) / cols)
    per_row = [max(sum(1 for k in keys if k[0] == q) for q in queries[r * cols:(r + 1) * cols]) for r in range(rn)]
    height = min(PAGE_HEIGHT, 0.095 * sum(per_row) + 0.75 * rn + 0.8)
    fig, axes = plt.subplots(rn, cols, figsize=(PAGE_WIDTH, height), squeeze=False, gridspec_kw={"height_ratios": [n + 6 for n in per_row]})
    for ax, q in zip(axes.flat, queries):
        methods = [m for qq, m in keys if qq == q]
        for i, m in enumerate(methods):
            v = np.percentile(np.array(errs[(q, m)]) + 1, [p for _, p, _, _ in T_ERROR_MARKS])
            ax.plot([v[0], v[-1]], [i, i], color="lightgrey", lw=0.8, zorder=0)
            for (_, _, colour, marker), x in zip(T_ERROR_MARKS, v):
                ax.scatter(x, i, color=colour, marker=marker, s=9, linewidths=0.8)
        ax.set_yticks(range(len(methods)), methods, fontsize=5)
        ax.set_ylim(len(methods) - 0.5, -0.5)
        ax.set_xscale("log")
        ax.set_title(f"{QUERY_TITLES.get(q, q)} ({len(common[q])} paired instances)", fontsize=7)
        ax.tick_params(axis="x", labelsize=6)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(queries):]:
        ax.axis("off")
    fig.supxlabel("1 + |t - t*| in ulps of max(|t*|, 1), t* the exact entry parameter", fontsize=7)
    handles = [plt.Line2D([], [], color=c, marker=mk, ls="", ms=4, label=label) for label, _, c, mk in T_ERROR_MARKS]
    fig.legend(handles=handles, loc="upper center", ncol=4, fontsize=6.5, frameon=False, bbox_to_anchor=(0.5, 1.0))
    save(fig, out, "t_error",
         "One panel per line query, one row per method: the error of the entry parameter t it reports, in ulps of the exact "
         "value, over the instances on which it reported one among those every method shown ran on (the slow number types run "
         "on a subset: paired, their count in the title); the markers are its median, 90th and 99th percentiles and maximum "
         "(1 means exact), so a long grey bar is a method that is usually accurate but sometimes far off.",
         rect=(0, 0, 1, 0.96))

    # Speed against the error of t: median ns per query against the 99th percentile of the
    # t error, per line query and method, on the same paired instances.
    ns = defaultdict(list)
    kinds = {}
    for r in rows:
        if (r["query"], r["method"]) in errs and r["instance"] in common[r["query"]] and r["answer"] != "process_ended":
            ns[(r["query"], r["method"])].append(fnum(r["ns"]))
            kinds[r["method"]] = r["kind"]
    cols = 2 if len(queries) > 1 else 1
    rn = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rn, cols, figsize=(PAGE_WIDTH, 2.9 * rn + 0.8), squeeze=False)
    drawn = set()  # the kinds drawn
    for ax, q in zip(axes.flat, queries):
        pts = []
        for (qq, m) in keys:
            if qq != q:
                continue
            x = float(np.median(ns[(qq, m)]))
            y = float(np.percentile(np.array(errs[(qq, m)]) + 1, 99))
            ax.scatter(x, y, color=KIND_COLOURS.get(kinds.get(m), "grey"), s=9, linewidths=0)
            pts.append((x, y, m))
            drawn.add(kinds.get(m))
        ax.set_xscale("log")
        ax.set_yscale("log")
        best = front(pts)
        if best:
            ax.step([p[0] for p in best], [p[1] for p in best], where="post", color="grey", lw=0.7, zorder=0)
            label_front(ax, best)
        pareto_axes(ax, q, "99th percentile of 1 + t error (ulps)")
        ax.set_title(f"{ax.get_title()} ({len(common[q])} paired)", fontsize=ax.title.get_fontsize())
    pareto_legend(fig, axes, len(queries), "speed against the error of the entry parameter t (line queries)", drawn)
    save(fig, out, "pareto_t_error",
         "One panel per line query, one dot per method, coloured by kind, every method on the instances of the query on which "
         "all of them ran (their count in the title): further left is faster, lower has a smaller 99th "
         "percentile of the t error; the grey staircase joins the methods no other beats on both, and only those are named.",
         rect=(0, 0.05, 1, 1))


CODES = "stoiuecx"
CODE_COLOURS = ["#4c72b0", "#f2c14e", "#dd8452", "#c44e52", "#bbbbbb", "#000000", "#8fbf8f", "#2f6f2f"]
CODE_NAMES = ["separated", "touching", "overlapping", "intersecting", "undecided", "error", "as its contract (differs from solid)",
              "not as its contract"]
# A wrong cell is drawn opaque in this one colour, whatever the method answered there.
WRONG_COLOUR = "#ff00ff"
WRONG_LABEL = "wrong: meets where the certified answer is separated, or the reverse"
# A class mismatch (a three-valued method says touching where the certified answer is
# overlapping, or the reverse) in its own colour: right as a Boolean answer, wrong as a
# three-valued one.
CLASS_COLOUR = "#00d8d8"
CLASS_LABEL = "class mismatch: touching for overlapping, or the reverse"


def meets(c):
    return c in "toi"


NOT_EVALUATED_LABEL = "not evaluated (a slow method's skipped rows and columns)"


def map_legend(fig, fontsize, used, bottom=0.0):
    """The legend of the colours `used` (indices into CODES, "wrong", "class", "unevaluated"):
    exactly the colours the maps show, wrong cells and class mismatches always named."""
    handles = [plt.Line2D([], [], color=c, marker="s", ls="", label=l)
               for k, (c, l) in enumerate(zip(CODE_COLOURS, CODE_NAMES)) if k in used]
    if "unevaluated" in used:
        handles.append(plt.Line2D([], [], color="white", markeredgecolor="grey", marker="s", ls="", label=NOT_EVALUATED_LABEL))
    marks = [plt.Line2D([], [], color=c, marker="s", ls="", label=l) for c, l in ((WRONG_COLOUR, WRONG_LABEL),
                                                                                   (CLASS_COLOUR, CLASS_LABEL))]
    # Two keys side by side: the answers, two to a line, and the marks on wrong cells.
    fig.legend(handles=handles, loc="lower left", ncol=2, fontsize=fontsize, frameon=False, bbox_to_anchor=(0.01, bottom))
    fig.legend(handles=marks, loc="lower right", ncol=1, fontsize=fontsize, frameon=False, bbox_to_anchor=(0.99, bottom))
    return max(math.ceil(len(handles) / 2), len(marks))


def draw_map(ax, code, bad, extent=None, cls=None):
    """An answer per cell (code: index into CODES, negative or masked where not evaluated) as one
    RGBA image: wrong cells opaque in WRONG_COLOUR, class mismatches (cls) in CLASS_COLOUR, cells
    not evaluated transparent; no interpolation, so no cell takes a colour outside the legend.
    Returns the colours used (map_legend's keys)."""
    code = np.ma.filled(np.ma.asarray(code), -1)
    valid = code >= 0
    rgba = np.zeros(code.shape + (4,))
    rgba[valid] = to_rgba_array(CODE_COLOURS)[code[valid]]
    shown = valid.copy()  # the cells drawn in their answer's colour
    used = set()
    for mask, colour, key in ((bad, WRONG_COLOUR, "wrong"), (cls, CLASS_COLOUR, "class")):
        if mask is not None and (mask & valid).any():
            rgba[mask & valid] = to_rgba(colour)
            shown &= ~mask
            used.add(key)
    used |= set(np.unique(code[shown]).tolist())
    ax.imshow(rgba, origin="lower", interpolation="none", extent=extent)
    ax.set_xticks([])
    ax.set_yticks([])
    return used


def map_offsets(rows):
    """The two perturbed coordinates' offsets in ulps by column i and row j of a map's CSV."""
    return ({int(r["i"]): int(float(r["d0_ulps"])) for r in rows}, {int(r["j"]): int(float(r["d1_ulps"])) for r in rows})


def map_scale(axes, count, cols, n, offsets, coordinates, fontsize):
    """The ulp scale of a grid of map panels (the first `count` of `axes`, `cols` to a row): ticks
    at the grid's ends and centre on every panel, labelled with the offsets in ulps on the left
    column and on the lowest panel of each column, with the coordinates' names."""
    d0, d1 = offsets
    ticks = [0, n // 2, n - 1]
    for k, ax in enumerate(list(axes)[:count]):
        ax.set_xticks(ticks, [str(d0.get(t, "")) for t in ticks] if k + cols >= count else [], fontsize=fontsize)
        ax.set_yticks(ticks, [str(d1.get(t, "")) for t in ticks] if k % cols == 0 else [], fontsize=fontsize)
        if k % cols == 0:
            ax.set_ylabel(f"{coordinates[1]} (ulps)", fontsize=fontsize + 0.5, labelpad=1)
        if k + cols >= count:
            ax.set_xlabel(f"{coordinates[0]} (ulps)", fontsize=fontsize + 0.5, labelpad=1)
        ax.tick_params(length=1.5, pad=1, width=0.5)
        # The end labels inside the panel's width, clear of the neighbours'.
        for label, ha in zip(ax.get_xticklabels(), ("left", "center", "right")):
            label.set_horizontalalignment(ha)


def map_coordinates(meta):
    """The names of a map's two perturbed coordinates on its axes: their indices in the input."""
    c = meta.get("perturbed_coordinates")
    return (f"input[{c[0]}]", f"input[{c[1]}]") if c and len(c) == 2 else ("1st coordinate", "2nd coordinate")


def map_dpi(fig, axes, n, least):
    """The PNG resolution that gives each of the n x n cells of the smallest panel at least one
    pixel (no cell dropped by the resampling), and at least `least`."""
    width, height = fig.get_size_inches()
    side = min(min(ax.get_position().width * width, ax.get_position().height * height) for ax in axes)
    return max(least, math.ceil(n / side))


def wrong_counts(sub, sub_cert, evaluated):
    """False positives (the method meets, the certified answer is separated), false negatives
    (the reverse) and class mismatches (the method answers touching where the certified answer
    is overlapping, or the reverse; a Boolean method's `intersecting` is none) among the
    evaluated cells, undecided and error cells aside: three boolean masks."""
    meets_code = np.array([meets(c) for c in CODES])
    # A cell answered as the method's contract says where it differs from the solid answer ("c")
    # is not wrong; one answered against it there ("x") is a false positive under the contract.
    contract, against = sub == CODES.index("c"), sub == CODES.index("x")
    decided = evaluated & (sub != CODES.index("u")) & (sub != CODES.index("e")) & ~contract
    m = meets_code[np.clip(sub, 0, None)]
    c = meets_code[np.clip(sub_cert, 0, None)]
    t, o = CODES.index("t"), CODES.index("o")
    cls = decided & (((sub == t) & (sub_cert == o)) | ((sub == o) & (sub_cert == t)))
    return (decided & m & ~c) | (decided & against), decided & ~m & c & ~against, cls


def failure_maps(folder, out):
    mapdir = os.path.join(folder, "failure_maps")
    if not os.path.isdir(mapdir):
        return
    code_index = {c: k for k, c in enumerate(CODES)}
    for name in sorted(os.listdir(mapdir)):
        if not name.endswith(".csv"):
            continue
        rows = read_csv(os.path.join(mapdir, name))
        meta = {}
        jpath = os.path.join(mapdir, name[:-4] + ".json")
        if os.path.exists(jpath):
            cr.note_read(jpath)
            with open(jpath) as f:
                meta = json.load(f)
        strides = meta.get("map_strides", {})
        n = max(int(r["i"]) for r in rows) + 1
        ii = np.array([int(r["i"]) for r in rows])
        jj = np.array([int(r["j"]) for r in rows])
        methods = ["certified"] + [k for k in rows[0] if k not in ("i", "j", "d0_ulps", "d1_ulps", "certified", "gap_lo", "gap_hi")]
        cert = np.full((n, n), -1)
        cert[jj, ii] = [code_index[r["certified"]] for r in rows]
        cols = 8
        rn = math.ceil(len(methods) / cols)
        legend_rows = 5  # at most 10 answers' entries, two to a line
        height = min(PAGE_HEIGHT, 1.4 * rn + 0.75 + 0.13 * legend_rows)
        fig, axes = plt.subplots(rn, cols, figsize=(PAGE_WIDTH, height), squeeze=False)
        fig.subplots_adjust(left=0.075, right=0.995, top=1 - 0.42 / height, bottom=(0.42 + 0.13 * legend_rows) / height,
                            wspace=0.12, hspace=0.62)
        used = set()
        for ax, m in zip(axes.flat, methods):
            s = int(strides.get(m, 1))
            # A slow method ran on every s-th row and column through the centre only: draw
            # each evaluated cell as an s x s block around it.
            code = np.full((n, n), -1)
            code[jj, ii] = [code_index.get(r[m], -1) for r in rows]
            sel = (np.arange(n) - n // 2) % s == 0
            sub = code[np.ix_(sel, sel)]
            sub_cert = cert[np.ix_(sel, sel)]
            evaluated = sub >= 0
            fp, fn, cls = wrong_counts(sub, sub_cert, evaluated)
            if m == "certified":
                fp[:] = False
                fn[:] = False
                cls[:] = False
            lo = np.nonzero(sel)[0]
            extent = (lo[0] - s / 2, lo[-1] + s / 2, lo[0] - s / 2, lo[-1] + s / 2)
            used |= draw_map(ax, np.where(evaluated, sub, -1), fp | fn, extent, cls)
            if not evaluated.all() or extent != (-0.5, n - 0.5, -0.5, n - 0.5):
                used.add("unevaluated")
            ax.set_xlim(-0.5, n - 0.5)
            ax.set_ylim(-0.5, n - 0.5)
            base, _, nt = m.partition("/")
            every = "" if s == 1 else f", step {s}"
            # A Boolean method (it answers intersecting) has no class mismatch to count.
            classes = "" if (sub == CODES.index("i")).any() else f", {int(cls.sum())} cl."
            counts = "" if m == "certified" else f"\n{int(fp.sum())} FP, {int(fn.sum())} FN{classes}"
            ax.set_title(f"{wrap_name(base, 26)}\n{nt}{every}{counts}", fontsize=4.8, linespacing=1.05, pad=2)
        for ax in list(axes.flat)[len(methods):]:
            ax.axis("off")
        coords = map_coordinates(meta)
        map_scale(axes.flat, len(methods), cols, n, map_offsets(rows), coords, 4.5)
        map_legend(fig, 6, used, 0.005)
        step = meta.get("ulps_per_cell", 1)
        fig.suptitle(f"{meta.get('description', name)}: {n}x{n} cells, {step} ulp per cell (step s: every s-th row and column evaluated)",
                     fontsize=7, y=1 - 0.04 / height, va="top")
        desc = meta.get("description", name[:-4])
        save(fig, out, "map_" + name[:-4],
             f"Failure map around one degenerate configuration ({desc}): each panel is a method's answer on a grid of inputs "
             f"{step} ulp apart in two coordinates ({coords[0]} and {coords[1]}, the perturbed numbers of the base input in the "
             "map's .json; the axes give their offsets in ulps), coloured by answer as the certified panel (first) is; magenta "
             "cells are wrong (the method says the sets meet where the certified answer is separated, or the reverse) and the "
             "title counts them as false positives (FP) and false negatives (FN); cyan cells are class mismatches (touching "
             "answered where the certified answer is overlapping, or the reverse: right as a Boolean answer, wrong as a "
             "three-valued one), counted as cl. (not for a Boolean method, which answers intersecting); white cells were not "
             "evaluated (a slow number type runs on every s-th row and column, step s in the title). Every cell is drawn in "
             "one colour of the legend, at least one pixel a cell.",
             tight=False, dpi=map_dpi(fig, list(axes.flat)[:len(methods)], n, 110))
        map_compact(rows, [m for m in methods if int(strides.get(m, 1)) == 1], n, name[:-4], desc, coords, out)


def map_compact(rows, methods, n, name, desc, coordinates, out):
    """At most 8 panels: the certified answer, then the methods in the order double, float,
    long double, interval, other; methods whose answers agree on every cell share a panel. Only
    methods evaluated on every cell (the caller leaves out the slow types run on a sub-grid)."""
    nt_rank = {"double": 0, "float": 1, "long_double": 2, "interval": 3}
    others = sorted((m for m in methods if m != "certified"), key=lambda m: (nt_rank.get(m.partition("/")[2], 9), m))
    panels = [["certified"]]
    columns = {"certified": tuple(r["certified"] for r in rows)}
    for m in others:
        col = tuple(r[m] for r in rows)
        for p in panels:
            if columns[p[0]] == col and p[0] != "certified":
                p.append(m)
                break
        else:
            columns[m] = col
            panels.append([m])
    panels = panels[:8]
    cols = 4
    rn = math.ceil(len(panels) / cols)
    fig, axes = plt.subplots(rn, cols, figsize=(7.6, 2.35 * rn + 0.7), squeeze=False)
    ii = np.array([int(r["i"]) for r in rows])
    jj = np.array([int(r["j"]) for r in rows])
    cert = np.zeros((n, n), dtype=int)
    cert[jj, ii] = [CODES.index(r["certified"]) for r in rows]
    used = set()
    for ax, p in zip(axes.flat, panels):
        m = p[0]
        img = np.zeros((n, n), dtype=int)
        img[jj, ii] = [CODES.index(c) for c in columns[m]]
        fp, fn, cls = wrong_counts(img, cert, np.ones((n, n), dtype=bool))
        if m == "certified":
            fp[:] = False
            fn[:] = False
            cls[:] = False
        used |= draw_map(ax, img, fp | fn, cls=cls)
        label = "\n".join(wrap_name(m, 34) for m in p[:2]) + (f" (+{len(p) - 2})" if len(p) > 2 else "")
        classes = "" if (img == CODES.index("i")).any() else f", {int(cls.sum())} class"  # none for a Boolean method
        ax.set_title(label + ("" if m == "certified" else f"\n{int(fp.sum())} FP, {int(fn.sum())} FN{classes}"), fontsize=6.5)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    map_scale(axes.flat, len(panels), cols, n, map_offsets(rows), coordinates, 5)
    legend_rows = map_legend(fig, 6.5, used)
    fig.tight_layout(rect=(0, (0.05 + 0.14 * legend_rows) / fig.get_size_inches()[1], 1, 1))
    save(fig, out, f"map_compact_{name}",
         f"The failure map of {desc} in at most 8 panels: the certified answer first, then one panel per distinct answer "
         "pattern (methods with the same answer on every cell share a panel, the title names the first two); magenta cells are "
         "wrong, counted in the title as false positives (FP) and false negatives (FN); cyan cells are class mismatches "
         "(touching for overlapping or the reverse), counted as class for a three-valued method. The axes give the two "
         f"perturbed coordinates' offsets in ulps ({coordinates[0]} and {coordinates[1]}, numbers of the base input in the map's "
         ".json). Every cell is drawn in one colour of the legend, at least one pixel a cell.",
         tight=False, dpi=map_dpi(fig, list(axes.flat)[:len(panels)], n, 150))


# ---- index.html ----------------------------------------------------------------------------

STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 70em; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; } h3 { font-size: 1.05em; }
table { border-collapse: collapse; font-size: 0.8em; margin: 0.5em 0 1em; }
th, td { border: 1px solid #ccc; padding: 0.15em 0.5em; text-align: left; }
th { background: #eee; } td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.wrong td { background: #fde0e0; } tr.mismatch td { background: #dff4f4; } tr.certified td { font-weight: bold; }
figure { margin: 1.5em 0; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { max-width: 50em; font-size: 0.9em; } pre { font-size: 0.75em; overflow-x: auto; background: #f6f6f6; padding: 0.5em; }
.note { color: #555; font-size: 0.9em; }
"""

SUMMARY_COLUMNS = ("method", "kind", "paired", "n", "FP", "FN", "class", "undecided", "error", "invalid", "rate", "3-val. rate",
                   "median ns")


def summary_cells(method, kind, t, boolean):
    """The cells of the summary row of `method` from its PairedTally t (cr.paired_by_algorithm):
    the Boolean rate (FP + FN) / decided and the three-valued one (FP + FN + class) / decided (a
    dash for a Boolean method, or when nothing was decided), and the median time, all on the
    paired instances."""
    e = t.errors
    rate = f"{e.rate:.2e}" if e.decided else "--"
    rate3 = "--" if method in boolean or not e.decided else f"{e.rate3:.2e}"
    ns = "--" if not t.ns else f"{t.median_ns:.0f}"
    return [method, kind, t.paired, t.n, e.fp, e.fn, e.cls, t.undecided, t.error, t.invalid, rate, rate3, ns]


def uniform_cells(r):
    """The cells of a row of uniform.csv: its counts and the Boolean and three-valued error in
    percent with the 95% Wilson interval (a dash for a Boolean method)."""
    e = cr.uniform_errors(r)
    cell = (lambda three: f"{cr.percent_text(e.rate3 if three else e.rate)} "
            f"[{cr.percent_text(e.interval(three)[0])}, {cr.percent_text(e.interval(three)[1])}]")
    return [r["method"], r["kind"], e.decided, e.fp, e.fn, e.cls, cr.uniform_not_decided(r),
            cell(False) if e.decided else "--", cell(True) if e.decided and not cr.uniform_boolean(r) else "--"]


def k_cell(e, three_valued=False):
    """A bin of the error-by-k table: wrong / decided and the 95% Wilson interval in percent."""
    if not e.decided:
        return ""
    lo, hi = e.interval(three_valued)
    return f"{e.wrong3 if three_valued else e.wrong}/{e.decided} [{cr.percent_text(lo)}, {cr.percent_text(hi)}]%"


def write_error_by_k(out, by_k, boolean, kinds):
    """error_by_k.html beside the figures: per query, every method with a wrong answer on the
    hard-case families, its errors per bin of k with their Wilson intervals (the Boolean error,
    and for a three-valued method with class mismatches the three-valued error on a second row).
    Returns its path."""
    path = os.path.join(out, "error_by_k.html")
    header = ["method", "error"] + [cr.k_bin_label(b) for b in range(len(cr.K_BINS))] + ["all k"]
    html = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">', "<title>certcyl study: errors against k</title>",
            f"<style>{STYLE}</style>", "</head>", "<body>", "<h1>Errors against k</h1>",
            "<p>Each hard-case instance is a degenerate configuration with one input coordinate moved by k ulps; the study draws "
            "k = 0 for one instance in eight and otherwise &plusmn;(2<sup>e</sup> + j), e uniform in 0..40, so a method's single "
            "error rate (summary.csv) is mostly the share of that design inside its precision band. Here the errors per bin of "
            "|k| (k = 0, then four binades a bin, the last open): wrong answers / decided answers and the 95% Wilson interval of "
            "the rate in percent. Boolean: false positives + false negatives; three-valued (second row, for a three-valued method "
            "with class mismatches): false positives + false negatives + class mismatches (touching answered for overlapping, or "
            "the reverse). Uniform random instances are left out; methods without a wrong answer on the families are left out "
            "(every bin 0/n), and so are the certified query and the sweeps.</p>"]
    queries = [q for q in QUERY_TITLES if any(k[0] == q for k in by_k)] + sorted({q for q, _ in by_k} - set(QUERY_TITLES))
    numeric = tuple(header[2:])
    for q in queries:
        rows, classes = [], []
        methods = sorted((m for qq, m in by_k if qq == q and kinds.get(m) not in ("certified", "sweep")),
                         key=lambda m: (m.split("/")[0], m))
        for m in methods:
            bins = by_k[(q, m)]
            total = cr.Errors.pooled(bins)
            if not total.wrong3:
                continue
            rows.append([m, "Boolean"] + [k_cell(e) for e in bins] + [k_cell(total)])
            classes.append("wrong" if total.wrong else "")
            if total.cls and m not in boolean:
                rows.append([m, "three-valued"] + [k_cell(e, True) for e in bins] + [k_cell(total, True)])
                classes.append("mismatch")
        html.append(f'<h2 id="k-{escape(q, quote=True)}">{escape(q)} ({escape(QUERY_TITLES.get(q, q))})</h2>')
        html.append(cr.html_table(header, rows, classes, numeric) if rows else "<p>No method made a wrong answer.</p>")
    html += ["</body>", "</html>", ""]
    with open(path, "w") as f:
        f.write("\n".join(html))
    WRITTEN.append(path)
    return path


def write_index(folder, out, summary, rows, boolean=frozenset(), error_by_k_page=None):
    """index.html: the summary table (paired, from `rows` of instances.csv), the uniform sample,
    then every figure written, each with its caption; links to error_by_k_page (the errors per
    bin of k) when given. `boolean`: the methods whose three-valued rate is undefined
    (cr.boolean_methods)."""
    path = os.path.join(folder, "index.html") if os.path.normpath(out) == os.path.normpath(os.path.join(folder, "figures")) \
        else os.path.join(out, "index.html")
    here = os.path.dirname(os.path.abspath(path))

    def link(p):
        return escape(os.path.relpath(os.path.abspath(p), here).replace(os.sep, "/"), quote=True)

    machine = {}
    mpath = os.path.join(folder, "machine.json")
    if os.path.exists(mpath):
        cr.note_read(mpath)
        with open(mpath) as f:
            machine = json.load(f)
    options = machine.get("options", {})
    name = options.get("name") or os.path.basename(os.path.abspath(folder))
    html = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">', f"<title>certcyl study: {escape(name)}</title>",
            f"<style>{STYLE}</style>", "</head>", "<body>", f"<h1>certcyl study: {escape(name)}</h1>"]
    facts = [f"size {options['size']}" if "size" in options else "", f"seed {options['seed']}" if "seed" in options else "",
             f"commit {machine['commit']}" if "commit" in machine else "", f"{machine['date']}" if "date" in machine else "",
             f"{machine['merged_shards']} shards merged" if "merged_shards" in machine else ""]
    html.append(f'<p class="note">{escape(", ".join(f for f in facts if f))}</p>')
    html.append('<p>Contents: <a href="#summary">summary</a>, <a href="#uniform">uniform sample</a>, <a href="#figures">figures</a> (' +
                ", ".join(f'<a href="#{escape(n, quote=True)}">{escape(n)}</a>' for n, _ in FIGURES) +
                '), <a href="#files">files</a>.</p>')

    html.append('<h2 id="summary">Summary</h2>')
    html.append("<p>One row per query and method, each algorithm's number types <em>paired</em>: counted on the instances of "
                "the query on which every number type of the algorithm ran (paired: how many; the slow number types run on a "
                "pseudo-random share of each family only, so an unpaired comparison would judge them on other inputs), as the "
                "paper's tables do. On those instances: the rows judged (n), the answers that disagree with the certified one "
                "(FP: says the sets meet, they are separated; FN: the reverse), touching and overlapping confused (class), "
                "undecided answers, errors and invalid values (a reported value not finite), the disagreement rate (FP + FN) / "
                "decided answers (the Boolean error), the three-valued error rate (FP + FN + class) / decided answers (a dash "
                "for a Boolean method, which never answers touching or overlapping), and the median time per call. Every "
                "instance of every method is counted in <code>summary.csv</code>. Rows with a false positive or a false "
                "negative are shaded red, rows with class mismatches only cyan. Each rate pools the query's hard-case families "
                "and its few uniform instances, and the study's design (k = 0 for one instance in eight, otherwise |k| "
                "log-uniform up to 2^41 ulps off a degeneracy) sets how many fall inside a method's precision band: the rate is "
                "a property of that design, not of the method alone, and says nothing of typical input (the "
                '<a href="#uniform">uniform sample</a> below does).</p>')
    if error_by_k_page:
        html.append(f'<p>The errors per bin of k, with 95% Wilson intervals, for every method with a wrong answer: '
                    f'<a href="{link(error_by_k_page)}">error_by_k.html</a> (figure <a href="#error_by_k">error_by_k</a>).</p>')
    tallies = cr.paired_by_algorithm(rows)
    kinds = {r["method"]: r["kind"] for r in summary}
    order = [q for q in QUERY_TITLES if any(k[0] == q for k in tallies)] + sorted({q for q, _ in tallies} - set(QUERY_TITLES))
    numeric = ("paired", "n", "FP", "FN", "class", "undecided", "error", "invalid", "rate", "3-val. rate", "median ns")
    for q in order:
        ms = sorted((m for qq, m in tallies if qq == q), key=lambda m: (cr.split_method(m)[0], m))
        html.append(f'<h3 id="summary-{escape(q, quote=True)}">{escape(q)} ({escape(QUERY_TITLES.get(q, q))})</h3>')
        cells = [summary_cells(m, kinds.get(m, ""), tallies[(q, m)], boolean) for m in ms]
        classes = ["certified" if kinds.get(m) == "certified" else "wrong" if tallies[(q, m)].errors.wrong
                   else "mismatch" if tallies[(q, m)].errors.cls else "" for m in ms]
        html.append(cr.html_table(list(SUMMARY_COLUMNS), cells, classes, numeric))

    usample = cr.uniform_sample(folder)
    html.append('<h2 id="uniform">Uniform sample: typical input</h2>')
    if usample:
        html.append("<p>The study's uniform sample (<code>uniform.csv</code>): per query, random instances drawn as the "
                    "uniform family draws them (in [-2, 2]^3), each certified and answered by every method that runs on every "
                    "instance (the slow number types, Gmpfr and CORE::Expr, are not in it). Decided answers, FP, FN and class "
                    "mismatches, answers not decided (undecided, error or invalid), and the Boolean and three-valued error in "
                    "percent with the 95% Wilson interval: the typical-case rates of this distribution.</p>")
        header = ["method", "kind", "decided", "FP", "FN", "class", "not decided", "Boolean error %", "three-valued error %"]
        by_q = defaultdict(list)
        for r in usample:
            by_q[r["query"]].append(r)
        for q in [q for q in QUERY_TITLES if q in by_q] + sorted(set(by_q) - set(QUERY_TITLES)):
            r0 = by_q[q][0]
            html.append(f'<h3 id="uniform-{escape(q, quote=True)}">{escape(q)} ({escape(QUERY_TITLES.get(q, q))}): '
                        f'{int(r0["instances"])} instances, certified {r0["separated"]} separated, {r0["touching"]} touching, '
                        f'{r0["overlapping"]} overlapping, {r0["uncertified"]} undecided</h3>')
            cells = [uniform_cells(r) for r in by_q[q]]
            classes = ["wrong" if cr.uniform_errors(r).wrong else "mismatch" if cr.uniform_errors(r).cls else "" for r in by_q[q]]
            html.append(cr.html_table(header, cells, classes, ("decided", "FP", "FN", "class", "not decided")))
    else:
        html.append("<p>This study has no uniform sample (its configuration leaves out the uniform family, or its size is 0).</p>")
    tpath = os.path.join(folder, "summary.txt")
    if os.path.exists(tpath):
        cr.note_read(tpath)
        with open(tpath) as f:
            text = f.read()
        html.append(f'<p>The same per method over all queries, the checks of the instances, CORE::Expr\'s warnings and the '
                    f'stages that decided the cylinder pairs (<a href="{link(tpath)}">summary.txt</a>):</p>')
        html.append(f"<pre>{escape(text)}</pre>")

    html.append('<h2 id="figures">Figures</h2>')
    html.append("<p>Each figure links to its full-size PNG; a PDF of each sits beside it.</p>")
    for n, caption in FIGURES:
        png, pdf = os.path.join(out, n + ".png"), os.path.join(out, n + ".pdf")
        html.append(f'<figure id="{escape(n, quote=True)}">')
        html.append(f'<a href="{link(png)}"><img src="{link(png)}" alt="{escape(n, quote=True)}"></a>')
        html.append(f'<figcaption><b>{escape(n)}</b> (<a href="{link(pdf)}">PDF</a>): {escape(caption)}</figcaption>')
        html.append("</figure>")

    html.append('<h2 id="files">Files</h2><ul>')
    for f, what in (("instances.csv", "one row per instance and method"), ("inputs.csv", "one row per instance, its input in hexfloats"),
                    ("summary.csv", "every instance of every method, per query (the table above counts the paired ones)"),
                    ("summary_families.csv", "the same per family"), ("uniform.csv", "the uniform sample's counts per query and method"),
                    ("stages.csv", "how the certified cylinder-pair answers were decided"),
                    ("hunt.csv", "the worst input found per method"), ("machine.json", "compiler, flags, CPU, commit, options"),
                    ("manifest.json", "size, rows and SHA-256 of every data file"), ("Core_Diagnostics", "CORE::Expr's warnings")):
        if os.path.exists(os.path.join(folder, f)):
            html.append(f'<li><a href="{link(os.path.join(folder, f))}">{escape(f)}</a>: {escape(what)}</li>')
    html.append("</ul>")
    html += ["</body>", "</html>", ""]
    with open(path, "w") as f:
        f.write("\n".join(html))
    print(f"plot_study: index {path}", file=sys.stderr, flush=True)


def main():
    args = sys.argv[1:]
    out = None
    positional, judged_dirs = [], []
    while args:
        a = args.pop(0)
        if a == "--judged" and args:
            judged_dirs.append(args.pop(0))
        elif a == "--out" and args and out is None:
            out = args.pop(0)
        elif a.startswith("--"):  # unknown, without its value, or --out twice
            positional = None
            break
        else:
            positional.append(a)
    if positional is None or len(positional) != 1:
        print(__doc__)
        return 2
    folder = positional[0]
    try:
        judged = read_judged(judged_dirs)
    except ValueError as e:
        print(f"plot_study: --judged: {e}", file=sys.stderr)
        return 1
    if out is None:
        out = os.path.join(folder, "figures")
    os.makedirs(out, exist_ok=True)
    rows = read_csv(os.path.join(folder, "instances.csv"))
    summary = read_csv(os.path.join(folder, "summary.csv"))
    families = read_csv(os.path.join(folder, "summary_families.csv"))
    studied = {r["query"] for r in summary}
    for j in judged:
        if j["query"] not in studied:
            print(f"plot_study: --judged: {j['source']}: query {j['query']} is not in the study's summary.csv, "
                  f"{j['method']} not drawn for it", file=sys.stderr)
    disagreement_tables(families, out)
    gap_rate(rows, out)
    pareto(rows, summary, out, judged)
    pareto_compact(rows, summary, out, judged)
    gap_rate_overview(rows, out)
    by_k, boolean = error_by_k(rows, out)
    t_error(rows, out)
    failure_maps(folder, out)
    page = write_error_by_k(out, by_k, boolean, {r["method"]: r["kind"] for r in rows})
    write_index(folder, out, summary, rows, boolean, page)
    cr.write_manifest("experiments/plot_study.py", folder, out, WRITTEN)
    print(f"figures written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
