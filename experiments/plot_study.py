#!/usr/bin/python3
"""Figures of the robustness study, read from the CSV files of a results folder only.

    /usr/bin/python3 experiments/plot_study.py results/<name> [--out DIR]

Writes PNG and PDF into results/<name>/figures/ (or DIR):
  disagreement_<query>   false positives + false negatives per method and family (heat map)
  gap_rate_<query>       disagreement rate against the certified signed gap, log-binned
  pareto                 median ns per query against disagreement rate, per query
  pareto_compact         the same without sweeps and the extra MPFR precisions, colour by
                         algorithm, marker by number type (legible at a page's width)
  gap_rate_overview      disagreement rate against |gap| for the methods in hardware precision,
                         line queries pooled, triangles, cylinder pairs
  t_error                line queries: error of the entry parameter t in ulps, per method
  pareto_t_error         line queries: median ns against the 99th percentile of the t error
  map_<name>             failure maps: each method's answer on the ulp grid, disagreements marked
  map_compact_<name>     the same with at most 8 panels (methods with identical answers on every
                         cell share a panel), legible at a page's width
  manifest.json          the SHA-256 of every file read (relative to the results folder) and of
                         every figure written, so a consumer (the paper) can tell whether a figure
                         comes from the study outputs it sits beside
Needs matplotlib and numpy (Debian python3-matplotlib, python3-numpy).
"""
import csv
import hashlib
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

KIND_COLOURS = {
    "certified": "black",
    "seed_as_written": "tab:red",
    "seed_corrected": "tab:blue",
    "robust": "tab:green",
    "sweep": "tab:purple",
    "peer": "tab:orange",
}


READ = []  # every input file read, for the manifest
WRITTEN = []  # every figure written


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def read_csv(path):
    READ.append(path)
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name, rect=None):
    fig.tight_layout(rect=rect)
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"{name}.{ext}")
        # A fixed creation date keeps the PDF a function of the data (matplotlib honours it).
        meta = {"CreationDate": None} if ext == "pdf" else None
        fig.savefig(path, dpi=110, metadata=meta)
        WRITTEN.append(path)
    plt.close(fig)


def write_manifest(folder, out):
    manifest = {
        "generator": "experiments/plot_study.py",
        "inputs": {os.path.relpath(p, folder): sha256(p) for p in sorted(set(READ))},
        "outputs": {os.path.relpath(p, out): sha256(p) for p in sorted(set(WRITTEN))},
    }
    with open(os.path.join(out, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1, sort_keys=True)
        f.write("\n")


def fnum(s):
    if s == "" or s is None:
        return math.nan
    return float(s)


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
        fig, ax = plt.subplots(figsize=(1.0 + 0.75 * len(fams), 0.8 + 0.26 * len(methods)))
        im = ax.imshow(rate, cmap="Reds", vmin=0, vmax=max(0.05, np.nanmax(rate) if np.isfinite(rate).any() else 1), aspect="auto")
        ax.set_xticks(range(len(fams)), fams, rotation=45, ha="right", fontsize=8)
        ax.set_yticks(range(len(methods)), methods, fontsize=7)
        for i in range(len(methods)):
            for j in range(len(fams)):
                if count[i, j]:
                    ax.text(j, i, str(count[i, j]), ha="center", va="center", fontsize=6)
        ax.set_title(f"{query}: false positives + false negatives (count; colour: rate)")
        fig.colorbar(im, ax=ax, shrink=0.6)
        save(fig, out, f"disagreement_{query}")


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
        wrong = [m for m, bins in methods.items() if any(c[1] for c in bins.values())]
        if not wrong:
            continue
        wrong.sort(key=lambda m: -sum(c[1] for c in methods[m].values()))
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
        for side, ax in zip((-1, 1), axes):
            for m in wrong[:14]:
                bins = methods[m]
                xs, ys = [], []
                for b, (n, bad) in sorted(bins.items()):
                    if b == 0 or (b > 0) != (side > 0) or n == 0:
                        continue
                    xs.append(abs(b) - 21)
                    ys.append(bad / n)
                if xs:
                    ax.plot(xs, ys, marker="o", ms=3, label=m)
            ax.set_xlabel("log10 of the certified lower bound of |gap| (upper edge of bin)")
            ax.set_title(("separated side (gap < 0)" if side < 0 else "overlapping side (gap > 0)"))
            ax.grid(alpha=0.3)
        axes[0].set_ylabel("disagreement rate (FP + FN)")
        axes[1].legend(fontsize=7, loc="upper right")
        fig.suptitle(f"{query}: disagreement rate against the certified signed gap")
        save(fig, out, f"gap_rate_{query}")


def pareto(summary, out):
    queries = sorted({r["query"] for r in summary})
    cols = 3
    rows_n = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(6 * cols, 4.6 * rows_n), squeeze=False)
    for ax, q in zip(axes.flat, queries):
        pts = []
        for r in summary:
            if r["query"] != q:
                continue
            ns, rate = fnum(r["median_ns"]), fnum(r["disagreement_rate"])
            if not (ns > 0):
                continue
            pts.append((ns, rate, r["method"], r["kind"]))
        floor = 1e-4
        for ns, rate, m, kind in pts:
            ax.scatter(ns, max(rate, floor), color=KIND_COLOURS.get(kind, "grey"), s=18)
            ax.annotate(m, (ns, max(rate, floor)), fontsize=5.5, xytext=(2, 2), textcoords="offset points")
        # Pareto front: no other method is both faster and at most as wrong.
        front = sorted(p for p in pts if not any(o[0] < p[0] and o[1] <= p[1] for o in pts if o is not p))
        if front:
            ax.step([p[0] for p in front], [max(p[1], floor) for p in front], where="post", color="grey", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("median ns per query")
        ax.set_ylabel(f"disagreement rate (0 drawn at {floor:g})")
        ax.set_title(q)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(queries):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=k) for k, c in KIND_COLOURS.items()]
    fig.legend(handles=handles, loc="lower right", fontsize=8)
    fig.suptitle("speed against error (per query, every method)")
    save(fig, out, "pareto")


ALGO_COLOURS = {
    "certified": "black", "robust": "tab:green", "shene": "tab:blue", "gullotti": "tab:cyan",
    "gullotti_as_written": "tab:red", "eberly_triangle": "tab:purple", "eberly_cylinders": "tab:blue",
    "eberly_cylinders_as_written": "tab:red", "fcl": "tab:brown", "fcl_mesh": "tab:brown",
    "bullet": "tab:olive", "bullet_margin0": "goldenrod", "ode": "tab:pink", "ode_mesh": "tab:pink",
}
NT_MARKERS = {"exact": "X", "double": "o", "long_double": "s", "interval": "^", "gmpfr<113>": "D",
              "core_expr": "*", "float": "P"}
QUERY_TITLES = {"line_cylinder": "line", "ray_cylinder": "ray", "segment_cylinder": "segment",
                "line_elliptic_cylinder": "line, elliptic cylinder", "triangle_cylinder": "triangle",
                "cylinder_cylinder": "cylinder pair"}


def pareto_compact(summary, out):
    queries = [q for q in QUERY_TITLES if any(r["query"] == q for r in summary)]
    if not queries:
        return
    cols = 3
    rows_n = math.ceil(len(queries) / cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(7.6, 2.5 * rows_n + 0.9), squeeze=False)
    floor = 1e-4
    used_algos, used_nts = set(), set()
    for ax, q in zip(axes.flat, queries):
        pts = []
        for r in summary:
            base, _, nt = r["method"].partition("/")
            if r["query"] != q or r["kind"] == "sweep" or nt not in NT_MARKERS or base not in ALGO_COLOURS:
                continue
            ns, rate = fnum(r["median_ns"]), fnum(r["disagreement_rate"])
            if ns > 0:
                pts.append((ns, rate, base, nt))
        for ns, rate, base, nt in pts:
            hollow = base in ("bullet_margin0", "fcl_mesh", "ode_mesh")
            c = ALGO_COLOURS[base]
            ax.scatter(ns, max(rate, floor), marker=NT_MARKERS[nt], s=26, linewidths=0.9,
                       facecolors="none" if hollow else c, edgecolors=c)
            used_algos.add(base)
            used_nts.add(nt)
        front = sorted(p for p in pts if not any(o[0] < p[0] and o[1] <= p[1] for o in pts if o is not p))
        if front:
            ax.step([p[0] for p in front], [max(p[1], floor) for p in front], where="post", color="grey", lw=0.7, zorder=0)
        ax.axhline(floor, color="grey", lw=0.5, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 1)
        ax.set_title(QUERY_TITLES[q], fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("median ns per query", fontsize=7)
    for ax in axes[:, 0]:
        ax.set_ylabel("rate (0 at $10^{-4}$)", fontsize=7)
    for ax in list(axes.flat)[len(queries):]:
        ax.axis("off")
    algo_handles = [plt.Line2D([], [], color=ALGO_COLOURS[a], marker="o", ls="", ms=5,
                               markerfacecolor="none" if a in ("bullet_margin0", "fcl_mesh", "ode_mesh") else ALGO_COLOURS[a], label=a)
                    for a in ALGO_COLOURS if a in used_algos]
    nt_handles = [plt.Line2D([], [], color="grey", marker=m, ls="", ms=5, label=n) for n, m in NT_MARKERS.items() if n in used_nts]
    fig.legend(handles=algo_handles + nt_handles, loc="lower center", ncol=7, fontsize=6.2, frameon=False)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    name = "pareto_compact"
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"{name}.{ext}")
        fig.savefig(path, dpi=150, metadata={"CreationDate": None} if ext == "pdf" else None)
        WRITTEN.append(path)
    plt.close(fig)


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
    fig, axes = plt.subplots(1, 3, figsize=(7.6, 2.9), sharey=True)
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
        ax.set_xlabel("$\\log_{10}$ of $|$gap$|$ (bin upper edge)", fontsize=7)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=5.2, loc="upper right", frameon=False)
    axes[0].set_ylabel("disagreement rate (FP + FN)", fontsize=7)
    fig.tight_layout()
    name = "gap_rate_overview"
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"{name}.{ext}")
        fig.savefig(path, dpi=150, metadata={"CreationDate": None} if ext == "pdf" else None)
        WRITTEN.append(path)
    plt.close(fig)


def t_error(rows, out):
    errs = defaultdict(list)
    for r in rows:
        t = fnum(r["t_error_ulps"])
        if math.isfinite(t):
            errs[(r["query"], r["method"])].append(t)
    if not errs:
        return
    keys = sorted(errs)
    fig, ax = plt.subplots(figsize=(8, 0.25 * len(keys) + 1))
    for i, k in enumerate(keys):
        v = np.array(errs[k]) + 1
        ax.scatter(np.percentile(v, [50, 90, 99, 100]), [i] * 4, c=["tab:blue", "tab:green", "tab:orange", "tab:red"], s=12)
    ax.set_yticks(range(len(keys)), [f"{q}: {m}" for q, m in keys], fontsize=6)
    ax.set_xscale("log")
    ax.set_xlabel("1 + |t - t*| in ulps of max(|t*|, 1) (median, p90, p99, max)")
    ax.grid(alpha=0.3)
    save(fig, out, "t_error")

    # Speed against the error of t: median ns per query against the 99th percentile of the
    # t error, per line query and method.
    ns = defaultdict(list)
    kinds = {}
    for r in rows:
        if (r["query"], r["method"]) in errs:
            ns[(r["query"], r["method"])].append(fnum(r["ns"]))
            kinds[r["method"]] = r["kind"]
    queries = sorted({q for q, _ in keys})
    fig, axes = plt.subplots(1, len(queries), figsize=(5.5 * len(queries), 4.5), squeeze=False)
    for ax, q in zip(axes.flat, queries):
        for (qq, m) in keys:
            if qq != q:
                continue
            x = float(np.median(ns[(qq, m)]))
            y = float(np.percentile(np.array(errs[(qq, m)]) + 1, 99))
            ax.scatter(x, y, color=KIND_COLOURS.get(kinds.get(m), "grey"), s=16)
            ax.annotate(m, (x, y), fontsize=5.5, xytext=(2, 2), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("median ns per query")
        ax.set_ylabel("99th percentile of 1 + t error (ulps)")
        ax.set_title(q)
        ax.grid(alpha=0.3)
    fig.suptitle("speed against the error of the entry parameter t (line queries)")
    save(fig, out, "pareto_t_error")


CODES = "stoiue"
CODE_COLOURS = ["#4c72b0", "#f2c14e", "#dd8452", "#c44e52", "#bbbbbb", "#000000"]


def meets(c):
    return c in "toi"


def failure_maps(folder, out):
    mapdir = os.path.join(folder, "failure_maps")
    if not os.path.isdir(mapdir):
        return
    code_index = {c: k for k, c in enumerate(CODES)}
    meets_code = np.array([meets(c) for c in CODES])
    for name in sorted(os.listdir(mapdir)):
        if not name.endswith(".csv"):
            continue
        rows = read_csv(os.path.join(mapdir, name))
        meta = {}
        jpath = os.path.join(mapdir, name[:-4] + ".json")
        if os.path.exists(jpath):
            READ.append(jpath)
            with open(jpath) as f:
                meta = json.load(f)
        strides = meta.get("map_strides", {})
        n = max(int(r["i"]) for r in rows) + 1
        ii = np.array([int(r["i"]) for r in rows])
        jj = np.array([int(r["j"]) for r in rows])
        methods = ["certified"] + [k for k in rows[0] if k not in ("i", "j", "d0_ulps", "d1_ulps", "certified", "gap_lo", "gap_hi")]
        cert = np.full((n, n), -1)
        cert[jj, ii] = [code_index[r["certified"]] for r in rows]
        cols = 6
        rn = math.ceil(len(methods) / cols)
        fig, axes = plt.subplots(rn, cols, figsize=(2.6 * cols, 2.75 * rn + 0.6), squeeze=False)
        cmap = ListedColormap(CODE_COLOURS)
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
            bad = evaluated & (sub != code_index["u"]) & (sub != code_index["e"]) & (meets_code[np.clip(sub, 0, None)] != meets_code[sub_cert])
            if m == "certified":
                bad[:] = False
            lo = np.nonzero(sel)[0]
            extent = (lo[0] - s / 2, lo[-1] + s / 2, lo[0] - s / 2, lo[-1] + s / 2)
            ax.imshow(np.ma.masked_where(~evaluated, sub), cmap=cmap, vmin=-0.5, vmax=len(CODES) - 0.5, origin="lower",
                      interpolation="nearest", extent=extent)
            if bad.any():
                overlay = np.ma.masked_where(~bad, np.ones(bad.shape))
                ax.imshow(overlay, cmap=ListedColormap(["magenta"]), alpha=0.55, origin="lower", interpolation="nearest", extent=extent)
            ax.set_xlim(-0.5, n - 0.5)
            ax.set_ylim(-0.5, n - 0.5)
            cells = int(evaluated.sum())
            every = "" if s == 1 else f", rows/cols step {s}"
            ax.set_title(f"{m}\n{int(bad.sum())} of {cells} wrong{every}", fontsize=6)
            ax.set_xticks([])
            ax.set_yticks([])
        for ax in list(axes.flat)[len(methods):]:
            ax.axis("off")
        handles = [plt.Line2D([], [], color=c, marker="s", ls="", label=l) for c, l in zip(CODE_COLOURS, ["separated", "touching", "overlapping", "intersecting", "undecided", "error"])]
        handles.append(plt.Line2D([], [], color="magenta", marker="s", ls="", label="disagrees with certified"))
        fig.legend(handles=handles, loc="lower center", ncol=7, fontsize=7)
        step = meta.get("ulps_per_cell", 1)
        fig.suptitle(f"{meta.get('description', name)}: {n}x{n} cells, {step} ulp per cell", fontsize=9)
        save(fig, out, "map_" + name[:-4], rect=(0, 0.03, 1, 0.97))
        map_compact(rows, [m for m in methods if int(strides.get(m, 1)) == 1], n, name[:-4], out)


def map_compact(rows, methods, n, name, out):
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
    fig, axes = plt.subplots(rn, cols, figsize=(7.6, 2.35 * rn + 0.4), squeeze=False)
    cmap = ListedColormap(CODE_COLOURS)
    for ax, p in zip(axes.flat, panels):
        m = p[0]
        img = np.zeros((n, n))
        bad = np.zeros((n, n), dtype=bool)
        for r in rows:
            i, j = int(r["i"]), int(r["j"])
            c = r[m]
            img[j, i] = CODES.index(c)
            if m != "certified" and c not in "ue" and meets(c) != meets(r["certified"]):
                bad[j, i] = True
        ax.imshow(img, cmap=cmap, vmin=-0.5, vmax=len(CODES) - 0.5, origin="lower", interpolation="nearest")
        if bad.any():
            overlay = np.ma.masked_where(~bad, np.ones((n, n)))
            ax.imshow(overlay, cmap=ListedColormap(["magenta"]), alpha=0.6, origin="lower", interpolation="nearest")
        label = "\n".join(p[:2]) + (f" (+{len(p) - 2})" if len(p) > 2 else "")
        ax.set_title(label + ("" if m == "certified" else f"\n{int(bad.sum())} wrong"), fontsize=6.5)
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=c, marker="s", ls="", label=l) for c, l in zip(CODE_COLOURS, ["separated", "touching", "overlapping", "intersecting", "undecided", "error"])]
    handles.append(plt.Line2D([], [], color="magenta", marker="s", ls="", label="wrong"))
    fig.legend(handles=handles, loc="lower center", ncol=7, fontsize=6.5, frameon=False)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"map_compact_{name}.{ext}")
        fig.savefig(path, dpi=150, metadata={"CreationDate": None} if ext == "pdf" else None)
        WRITTEN.append(path)
    plt.close(fig)


def main():
    args = sys.argv[1:]
    out = None
    if len(args) == 3 and args[1] == "--out":
        out = args[2]
    elif len(args) != 1:
        print(__doc__)
        return 2
    folder = args[0]
    if out is None:
        out = os.path.join(folder, "figures")
    os.makedirs(out, exist_ok=True)
    rows = read_csv(os.path.join(folder, "instances.csv"))
    summary = read_csv(os.path.join(folder, "summary.csv"))
    families = read_csv(os.path.join(folder, "summary_families.csv"))
    disagreement_tables(families, out)
    gap_rate(rows, out)
    pareto(summary, out)
    pareto_compact(summary, out)
    gap_rate_overview(rows, out)
    t_error(rows, out)
    failure_maps(folder, out)
    write_manifest(folder, out)
    print(f"figures written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
