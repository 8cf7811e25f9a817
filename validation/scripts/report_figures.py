#!/usr/bin/python3
"""Draws the figures of `attenuvis reproduce` from a JSON spec.

Usage: report_figures.py SPEC.json DIR

SPEC.json = {"figures": [FIG, ...], "processes": N?} (N processes draw, default 1); every FIG has
"id" (written as DIR/<id>.png), "kind" and kind-specific fields.  Data are either inline or in files of DIR
(the report's own tables and meshes), so the figure shows exactly the numbers of the run.

kinds
  lines      series=[{label, x[], y[], style?}], xlabel, ylabel, xlog?, ylog?, title?,
             hlines=[{y, label}]?, points=[{x, y, label}]? (published values, drawn as markers)
  node_maps  panels=[{title, csv, value, markers=[{x, y, label?, marker?}]?, boxes=[{x:[x0,x1], y:[y0,y1], label?}]?,
             xlim?, ylim?}], ncols?, common_scale?, vmin?, vmax?, cmap?, colorbar?, log?, zero?
             -- top-view heatmaps of node scores
  matrix     x[], ylabels[], z[[...]] (null = not computed), xlabel, ylabel, colorbar, zlog?, xlog?,
             threshold?, threshold_label? (a requirement, marked on the colour bar)
  scene3d    panels=[{obj, title}], ncols?, panel_size?, legend?, elev?, azim?
             -- triangle meshes (OBJ files beside the report) in an oblique 3D view

What the script derives so that every figure reads on its own, whatever the spec says:
  * every axis has a label with its unit (node maps: x [m], y [m]); every colour bar a label (from
    `colorbar`, else from the column name: degree, sum:* = S_S, avg:* = S_A, c:* = C);
  * multi-panel figures are at most ~11.5 in wide, with constrained layout: titles, tick labels and
    colour bars do not overlap at the report's width;
  * node maps show "no node" as white and, where the value is a contrast ratio to one point (`zero`
    given, or a column named c:*), nodes that do not see the point (C = 0) in grey, both in a legend;
  * curves of a lines figure that coincide with an earlier curve are drawn with hollow markers on top
    and say so in the legend ("coincides with ... for ..."); curves get distinct markers;
  * a marker-only series with one point per earlier curve, all at one x outside their range (e.g. a
    far-infrared value per fog), is drawn point by point in the colour of that curve;
  * missing matrix cells are hatched grey and named in a legend; log-x ticks fall on whole decades.

Any failure exits non-zero with a message on stderr; the report is then not written.
"""
import csv
import json
import math
import multiprocessing
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.colors import ListedColormap, LogNorm, Normalize  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402

MAX_WIDTH_IN = 11.5      # widest multi-panel figure: its text stays legible at the page's ~1100 px
NOT_VISIBLE = "#b4b4b4"  # nodes that do not see the chosen point
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "*"]

plt.rcParams.update({"font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "legend.fontsize": 8,
                     "xtick.labelsize": 8, "ytick.labelsize": 8})


_TABLES = {}


def read_columns(path, names):
    """Columns of a CSV file of the report (each file parsed once: several figures read the same nodes)."""
    if path not in _TABLES:
        with open(path, newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = np.asarray([[float(v) for v in row] for row in reader], dtype=float).reshape(-1, len(header))
        _TABLES[path] = (header, rows)
    header, rows = _TABLES[path]
    for n in names:
        if n not in header:
            raise ValueError(f"{path}: no column '{n}' (columns: {header})")
    return [rows[:, header.index(n)] for n in names]


def value_label(column):
    """A colour-bar label for a node column, from the report's column names."""
    if column == "degree":
        return "degree (number of visible nodes)"
    if column.startswith("sum:"):
        return "S_S (sum of C over visible nodes)"
    if column.startswith("avg:"):
        return "S_A (mean C over visible nodes)"
    if column.startswith("c:"):
        return "C = exp(-sigma d) to the point"
    return column


def colorbar_label(fig_spec, column):
    """The spec's label, or the derived one where the spec gives only its first words ("C", "S_S")."""
    derived = value_label(column)
    given = fig_spec.get("colorbar")
    if not given or derived.startswith(given):
        return derived
    return given


def legend_below(fig, handles):
    """A figure legend just under the lowest axes (constrained layout may leave room below them)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes if ax.get_visible() and (ax.axison or ax.collections)]
    bottom = min(b.y0 for b in boxes if b is not None and b.height > 0)
    fig.legend(handles=handles, loc="upper center", ncol=len(handles), frameon=False,
               bbox_to_anchor=(0.5, bottom / fig.bbox.height), bbox_transform=fig.transFigure)


def grid_image(x, y, v):
    """Node values on a regular x-y grid as an image (NaN where no node), or None."""
    ux, uy = np.unique(np.round(x, 6)), np.unique(np.round(y, 6))
    if len(ux) < 2 or len(uy) < 2:
        return None
    h = min(np.min(np.diff(ux)), np.min(np.diff(uy)))
    ix = np.rint((x - ux[0]) / h).astype(int)
    iy = np.rint((y - uy[0]) / h).astype(int)
    if np.max(np.abs(ix * h + ux[0] - x)) > 1e-3 * h or np.max(np.abs(iy * h + uy[0] - y)) > 1e-3 * h:
        return None
    nx, ny = ix.max() + 1, iy.max() + 1
    if nx * ny > 16_000_000:
        return None
    img = np.full((ny, nx), np.nan)
    img[iy, ix] = v
    extent = (ux[0] - h / 2, ux[0] + (nx - 0.5) * h, uy[0] - h / 2, uy[0] + (ny - 0.5) * h)
    return img, extent


# ----------------------------------------------------------------------------- lines
def unit_of(label):
    m = re.search(r"\[([^\]]+)\]", label or "")
    return " " + m.group(1) if m else ""


def coincidence(series, fig_spec):
    """For each series: (depth, legend note) where it lies on earlier series, or None.

    Two curves coincide where they lie closer than 0.8 % of the plot's height (on a log axis: of
    its decades), i.e. within a marker's width; the note names each earlier curve, how close, and,
    unless it is the whole range, where."""
    out = [None] * len(series)
    ys = np.concatenate([s[1][np.isfinite(s[1])] for s in series])
    log = fig_spec.get("ylog") and ys.size and ys.min() > 0
    span = (np.log10(ys.max() / ys.min()) if log else ys.max() - ys.min()) if ys.size else 0.0
    xname = re.sub(r"\s*\[.*\]", "", fig_spec.get("xlabel", "x")) or "x"
    unit = unit_of(fig_spec.get("xlabel", ""))
    labels = [s[2] for s in series]
    for j, (xj, yj, _) in enumerate(series):
        notes, depth, covered = [], 0, np.zeros(len(xj), dtype=bool)
        for i in range(j):
            xi, yi, _ = series[i]
            if len(xi) != len(xj) or not np.allclose(xi, xj):
                continue
            ok = np.isfinite(yi) & np.isfinite(yj)
            rel = np.abs(yi - yj) / np.maximum(np.maximum(np.abs(yi), np.abs(yj)), 1e-300)
            with np.errstate(divide="ignore", invalid="ignore"):
                gap = np.abs(np.log10(yi / yj)) if log else np.abs(yi - yj)
            close = ok & (gap <= 0.008 * span)
            if close.sum() >= 2:   # drawn larger than every curve it lies on
                depth = max(depth, (out[i][0] if out[i] else 0) + 1)
            same = close & ~covered
            if same.sum() < 2:
                continue
            covered |= same
            how = "coincides with" if rel[same].max() <= 1e-9 else f"within {100 * rel[same].max():.2g} % of"
            where = "" if same.sum() == ok.sum() else f" for {xname} {xj[same].min():g}-{xj[same].max():g}{unit}"
            notes.append(f"{how} {labels[i]}{where}")
        if notes:
            out[j] = (depth, "; ".join(notes))
    return out


def draw_lines(fig_spec, path):
    raw = fig_spec["series"]
    series = [(np.asarray(s["x"], dtype=float), np.asarray([np.nan if v is None else v for v in s["y"]], dtype=float),
               s.get("label", "")) for s in raw]
    size = fig_spec.get("size", (7, 4.5))
    fig, ax = plt.subplots(figsize=(size[0], size[1]))
    same = coincidence(series, fig_spec)
    lines = []
    for k, (s, (x, y, _)) in enumerate(zip(raw, series)):
        style = s.get("style", "-")
        marker_only = not re.search(r"[-:]", style)
        has_marker = bool(re.search(r"[.,ov^<>1-4sp*hH+xXdD|_P]", style.replace("-", "")))
        # One point per earlier curve at a single x beyond them: colour each like its curve.
        if marker_only and k == len(lines) and len(x) == k and k > 0 and np.all(x == x[0]):
            for (lx, ly, line), px, py in zip([(a, b, c) for a, b, c in lines], x, y):
                ax.plot([px], [py], "*", color=line.get_color(), markersize=13, markeredgecolor="black",
                        markeredgewidth=0.6)
            ax.plot([], [], "*", color="white", markeredgecolor="black", markersize=11,
                    label=(s.get("label") or "") + " (star in the colour of its curve)")
            continue
        label = s.get("label")
        kw = {"markersize": 5}
        fmt = style
        if not has_marker and len(raw) > 3:
            fmt = style + MARKERS[k % len(MARKERS)]
        if same[k] is not None:
            depth, note = same[k]
            label = f"{label} ({note})"
            # Hollow and larger by depth, drawn on top: every coinciding curve stays visible.
            kw.update(markerfacecolor="none", markersize=min(5 + 3 * depth, 17), markeredgewidth=1.3, linewidth=1.0,
                      zorder=2 + depth)
        (line,) = ax.plot(x, y, fmt, label=label, **kw)
        if not marker_only:
            lines.append((x, y, line))
    for p in fig_spec.get("points", []):
        ax.plot([p["x"]], [p["y"]], "k*", markersize=10)
        ax.annotate(p.get("label", ""), (p["x"], p["y"]), textcoords="offset points", xytext=(5, 5), fontsize=8)
    if fig_spec.get("xlog"):
        ax.set_xscale("log")
    if fig_spec.get("ylog"):
        ax.set_yscale("log")
    for h in fig_spec.get("hlines", []):   # named in the legend: a label on the plot would sit on data
        ax.axhline(h["y"], color="dimgray", linestyle=":", linewidth=1.4, label=h.get("label") or f"{h['y']:g}")
    ax.set_xlabel(fig_spec.get("xlabel", ""))
    ax.set_ylabel(fig_spec.get("ylabel", ""))
    if "title" in fig_spec:
        ax.set_title(fig_spec["title"])
    ax.grid(True, which="both", alpha=0.3)
    # The legend goes under the plot, where it cannot cover a data point.
    labels = ax.get_legend_handles_labels()[1]
    longest = max((len(t) for t in labels), default=0)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), frameon=False,
              ncol=1 if longest > 45 else 2 if (longest > 22 or len(labels) > 6) else min(3, len(labels)))
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


# ----------------------------------------------------------------------------- node maps
def annotate_markers(ax, markers):
    """Each marker with its own symbol; labels pushed away from the group's centre with a leader line."""
    if not markers:
        return
    cx = np.mean([m["x"] for m in markers])
    cy = np.mean([m["y"] for m in markers])
    for k, m in enumerate(markers):
        ax.plot([m["x"]], [m["y"]], m.get("marker", "o"), markersize=9, markerfacecolor="white",
                markeredgecolor="black", markeredgewidth=1.6, zorder=5, clip_on=False)
        if not m.get("label"):
            continue
        dx, dy = m["x"] - cx, m["y"] - cy
        norm = math.hypot(dx, dy)
        if len(markers) == 1 or norm == 0:
            dx, dy = math.cos(0.6 + 2.1 * k), math.sin(0.6 + 2.1 * k)
        else:
            dx, dy = dx / norm, dy / norm
        ax.annotate(m["label"], (m["x"], m["y"]), textcoords="offset points", xytext=(26 * dx, 26 * dy),
                    ha="center", va="center", fontsize=9, fontweight="bold", zorder=6,
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="black", lw=0.8),
                    arrowprops=dict(arrowstyle="-", color="black", lw=1.0))


def pool_max(img, k):
    """k x k blocks of a node image reduced to their largest value, so that thin rows of nodes
    (a sidewalk in a whole-city view) stay visible when the panel has fewer pixels than nodes."""
    ny, nx = img.shape
    pad = np.full((math.ceil(ny / k) * k, math.ceil(nx / k) * k), np.nan)
    pad[:ny, :nx] = img
    blocks = pad.reshape(pad.shape[0] // k, k, pad.shape[1] // k, k)
    with np.errstate(all="ignore"), np.testing.suppress_warnings() as sup:
        sup.filter(RuntimeWarning)
        return np.nanmax(np.nanmax(blocks, axis=3), axis=1)


def draw_node_maps(fig_spec, base, path):
    panels = fig_spec["panels"]
    ncols = min(fig_spec.get("ncols", len(panels)), len(panels))
    nrows = math.ceil(len(panels) / ncols)
    common = fig_spec.get("common_scale", False)
    size = min(fig_spec.get("panel_size", 3.2), MAX_WIDTH_IN / (ncols + (0.35 if common else 0)))
    data = []
    for p in panels:
        x, y, v = read_columns(os.path.join(base, p["csv"]), [p.get("x", "x"), p.get("y", "y"), p["value"]])
        data.append((x, y, v))
    cmap = plt.get_cmap(fig_spec.get("cmap", "viridis")).copy()
    cmap.set_bad(alpha=0)
    log = fig_spec.get("log", False)
    gmin = fig_spec.get("vmin", min(float(np.nanmin(d[2])) for d in data))
    gmax = fig_spec.get("vmax", max(float(np.nanmax(d[2])) for d in data))
    extra_h = 0.45 if common else 0.9   # a horizontal colour bar under every panel when scales differ
    fig, axes = plt.subplots(nrows, ncols, figsize=(size * ncols + (1.2 if common else 0.2), (size + extra_h) * nrows + 0.6),
                             squeeze=False, constrained_layout=True)
    last = None
    any_zero = False
    for k, (p, (x, y, v)) in enumerate(zip(panels, data)):
        ax = axes[k // ncols][k % ncols]
        zero = p.get("zero", fig_spec.get("zero", "does not see the point" if p["value"].startswith("c:") else None))
        hidden = (v == 0) if zero else np.zeros(len(v), dtype=bool)
        any_zero |= bool(hidden.any())
        shown = np.where(hidden, np.nan, v)
        lo, hi = (gmin, gmax) if common else (p.get("vmin", float(np.nanmin(v))), p.get("vmax", float(np.nanmax(v))))
        if hi <= lo:
            hi = lo + (abs(lo) if lo else 1.0) * 1e-9 + 1e-300
        norm = LogNorm(vmin=max(lo, 1e-300), vmax=hi) if log else Normalize(vmin=lo, vmax=hi)
        g = grid_image(x, y, shown)
        title = p.get("title", "")
        if g is not None:
            img, extent = g
            # Panel about 400 px wide: a window of many more nodes is max-pooled (and says so).
            cell = (extent[1] - extent[0]) / img.shape[1]
            window = max(np.ptp(p.get("xlim", extent[:2])), np.ptp(p.get("ylim", extent[2:]))) / cell
            pool = int(window // 450)
            hidden_img = grid_image(x, y, np.where(hidden, 1.0, np.nan))[0] if hidden.any() else None
            if pool >= 2:
                img = pool_max(img, pool)
                hidden_img = pool_max(hidden_img, pool) if hidden_img is not None else None
                size_m = pool * cell
                extent = (extent[0], extent[0] + img.shape[1] * size_m, extent[2], extent[2] + img.shape[0] * size_m)
                title += f"\n(each pixel: highest of {size_m:g} x {size_m:g} m)"
            if hidden_img is not None:
                ax.imshow(hidden_img, origin="lower", extent=extent, cmap=ListedColormap([NOT_VISIBLE]),
                          interpolation="nearest")
            last = ax.imshow(img, origin="lower", extent=extent, cmap=cmap, norm=norm, interpolation="nearest")
        else:
            if hidden.any():
                ax.scatter(x[hidden], y[hidden], c=NOT_VISIBLE, s=2, marker="s", linewidths=0)
            last = ax.scatter(x[~hidden], y[~hidden], c=v[~hidden], s=2, cmap=cmap, norm=norm, marker="s",
                              linewidths=0)
        for b in p.get("boxes", []):
            ax.add_patch(Rectangle((b["x"][0], b["y"][0]), b["x"][1] - b["x"][0], b["y"][1] - b["y"][0], fill=False,
                                   edgecolor="black", linewidth=1.4, linestyle="--", zorder=4))
            if b.get("label"):
                ax.annotate(b["label"], (b["x"][0], b["y"][1]), textcoords="offset points", xytext=(2, 3),
                            fontsize=8, zorder=6, bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none"))
        annotate_markers(ax, p.get("markers", []))
        if "xlim" in p:
            ax.set_xlim(*p["xlim"])
        if "ylim" in p:
            ax.set_ylim(*p["ylim"])
        ax.set_aspect("equal")
        ax.set_title(title)
        ax.tick_params(labelsize=7)
        ax.locator_params(nbins=4)
        if k // ncols == nrows - 1 or k + ncols >= len(panels):
            ax.set_xlabel("x [m]")
        if k % ncols == 0:
            ax.set_ylabel("y [m]")
        if not common:
            cb = fig.colorbar(last, ax=ax, orientation="horizontal", shrink=0.9, aspect=22, pad=0.02)
            cb.ax.tick_params(labelsize=7)
            cb.locator = matplotlib.ticker.MaxNLocator(4)
            cb.update_ticks()
            cb.set_label(colorbar_label(fig_spec, p["value"]), fontsize=7)
    for k in range(len(panels), nrows * ncols):
        axes[k // ncols][k % ncols].axis("off")
    if common and last is not None:
        cb = fig.colorbar(last, ax=axes.ravel().tolist(), shrink=min(1.0, 0.5 + 0.25 * nrows), aspect=30)
        cb.set_label(colorbar_label(fig_spec, panels[0]["value"]))
    legend = [Patch(facecolor="white", edgecolor="0.6", label="no node")]
    if any_zero:
        legend.append(Patch(facecolor=NOT_VISIBLE, label=fig_spec.get("zero", "does not see the point") + " (C = 0)"))
    legend_below(fig, legend)
    if "title" in fig_spec:
        fig.suptitle(fig_spec["title"])
    fig.savefig(path, dpi=fig_spec.get("dpi", 120), bbox_inches="tight", pad_inches=0.25)
    plt.close(fig)


# ----------------------------------------------------------------------------- matrix
def draw_matrix(fig_spec, path):
    x = np.asarray(fig_spec["x"], dtype=float)
    ylabels = fig_spec["ylabels"]
    z = np.asarray([[np.nan if v is None else v for v in row] for row in fig_spec["z"]], dtype=float)
    fig, ax = plt.subplots(figsize=fig_spec.get("size", (9, 0.42 * len(ylabels) + 2.0)), constrained_layout=True)
    finite = z[np.isfinite(z) & (z > 0)] if fig_spec.get("zlog") else z[np.isfinite(z)]
    if fig_spec.get("zlog"):
        lo = fig_spec.get("zmin", float(finite.min()) if finite.size else 1e-17)
        hi = fig_spec.get("zmax", float(finite.max()) if finite.size else 1.0)
        zz = np.where(z > 0, z, lo)
        norm = LogNorm(vmin=lo, vmax=max(hi, lo * 10))
    else:
        zz = z
        norm = Normalize()
    zz = np.ma.masked_invalid(zz)
    im = ax.pcolormesh(np.arange(len(x) + 1), np.arange(len(ylabels) + 1), zz, cmap=fig_spec.get("cmap", "magma_r"),
                       norm=norm, shading="flat")
    missing = np.argwhere(~np.isfinite(z))
    for iy, ix in missing:
        ax.add_patch(Rectangle((ix, iy), 1, 1, facecolor="#e4e4e4", edgecolor="#888888", hatch="////", linewidth=0.5))
    if fig_spec.get("xlog"):
        lx = np.log10(x)
        decades = [i for i, v in enumerate(lx) if abs(v - round(v)) < 1e-9]
        step = max(1, math.ceil(len(decades) / 13))
        ticks = decades[::step]
        ax.set_xticks(np.asarray(ticks) + 0.5)
        ax.set_xticklabels([f"$10^{{{int(round(lx[i]))}}}$" for i in ticks])
    else:
        step = max(1, math.ceil(len(x) / 13))
        ax.set_xticks(np.arange(0, len(x), step) + 0.5)
        ax.set_xticklabels([f"{v:g}" for v in x[::step]])
    ax.set_yticks(np.arange(len(ylabels)) + 0.5)
    ax.set_yticklabels(ylabels)
    ax.set_xlabel(fig_spec.get("xlabel", ""))
    ax.set_ylabel(fig_spec.get("ylabel", ""))
    cb = fig.colorbar(im, ax=ax)
    label = fig_spec.get("colorbar", "")
    if "threshold" in fig_spec:   # the requirement, marked on the colour scale
        cb.ax.axhline(fig_spec["threshold"], color="cyan", linewidth=2.5)
        label += f"\ncyan line: {fig_spec.get('threshold_label', 'threshold')} {fig_spec['threshold']:g}"
    cb.set_label(label)
    if len(missing):
        ax.legend(handles=[Patch(facecolor="#e4e4e4", edgecolor="#888888", hatch="////", label="not computed")],
                  loc="upper left", bbox_to_anchor=(0.0, -0.16), frameon=False)
    if "title" in fig_spec:
        ax.set_title(fig_spec["title"])
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- 3D scenes
GROUP_COLOURS = {"floor": "#d8d8d8", "obstacle": "#9a9ca3", "building": "#c9b8a2", "road": "#6b6b6b",
                 "sidewalk": "#ececec", "crosswalk": "#f2d64b", "ground": "#9fc38c", "terrain": "#b5c99a"}
GROUP_LABELS = {"building": "buildings", "road": "roads", "sidewalk": "sidewalks", "crosswalk": "crosswalks",
                "ground": "lots and parks", "terrain": "terrain", "floor": "floor", "obstacle": "obstacles"}
GROUND_LAYER = {"terrain": 0, "ground": 1, "floor": 1, "road": 2, "sidewalk": 3, "crosswalk": 3}


def read_obj(path):
    """Vertices, triangles (fan-triangulated) and the group name of each triangle."""
    verts, tris, groups = [], [], []
    group = "default"
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                idx = []
                for t in line.split()[1:]:
                    i = int(t.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for a in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[a], idx[a + 1]))
                    groups.append(group)
            elif line.startswith("g ") or line.startswith("usemtl "):
                group = line.split(maxsplit=1)[1].strip() if len(line.split()) > 1 else "default"
    if not tris:
        raise ValueError(f"{path}: no faces")
    return np.asarray(verts), np.asarray(tris), groups


def draw_scene(ax, path, elev, azim):
    """Orthographic view from (elev, azim), flat-shaded triangles in painter's order."""
    v, t, groups = read_obj(path)
    v = v - v.mean(axis=0)
    e, a = math.radians(elev), math.radians(azim)
    d = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])  # towards the viewer
    right = np.cross([0.0, 0.0, 1.0], d)
    right /= np.linalg.norm(right)
    up = np.cross(d, right)
    light = d + 0.6 * right + 0.8 * up
    light /= np.linalg.norm(light)
    p = v[t]                                       # (n, 3, 3)
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    layer = np.array([GROUND_LAYER.get(g, 10) for g in groups])
    # Solids (obstacles, buildings) are closed and wound outwards: faces turned away from the
    # viewer are hidden behind the front ones and are left out (the painter's order alone
    # misorders a long roof triangle against the walls under it).
    facing = n @ d
    keep = (layer < 10) | (facing > 0)
    n *= np.where(facing < 0, -1.0, 1.0)[:, None]
    shade = 0.45 + 0.55 * np.clip(n @ light, 0, 1)
    depth = p.mean(axis=1) @ d
    # Flat ground first (lowest layer first), then solids back to front.
    order = np.lexsort((depth, layer))
    order = order[keep[order]]
    base = np.array([matplotlib.colors.to_rgb(GROUP_COLOURS.get(g, "#bbbbbb")) for g in groups])
    colours = np.clip(base * shade[:, None], 0, 1)
    xy = np.stack([p @ right, p @ up], axis=-1)    # (n, 3, 2)
    ax.add_collection(PolyCollection(xy[order], facecolors=colours[order], edgecolors=colours[order], linewidths=0.15))
    # Frame the built area: the natural terrain around it only fills the corners.
    built = np.array([g != "terrain" for g in groups])
    fx, fy = xy[built][..., 0], xy[built][..., 1]
    pad = 0.03 * max(fx.max() - fx.min(), fy.max() - fy.min())
    ax.set_xlim(fx.min() - pad, fx.max() + pad)
    ax.set_ylim(fy.min() - pad, fy.max() + pad)
    ax.set_aspect("equal")
    ax.axis("off")
    return sorted(set(groups))


def draw_scene3d(fig_spec, base, path):
    panels = fig_spec["panels"]
    ncols = min(fig_spec.get("ncols", len(panels)), len(panels))
    nrows = math.ceil(len(panels) / ncols)
    size = min(fig_spec.get("panel_size", 3.0), MAX_WIDTH_IN / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(size * ncols, size * 0.8 * nrows + 0.4), squeeze=False,
                             constrained_layout=True)
    seen = set()
    for k, p in enumerate(panels):
        ax = axes[k // ncols][k % ncols]
        seen |= set(draw_scene(ax, os.path.join(base, p["obj"]), fig_spec.get("elev", 35), fig_spec.get("azim", -60)))
        ax.set_title(p.get("title", ""))
    for k in range(len(panels), nrows * ncols):
        axes[k // ncols][k % ncols].axis("off")
    if fig_spec.get("legend"):
        legend_below(fig, [Patch(facecolor=GROUP_COLOURS[g], edgecolor="0.5", label=GROUP_LABELS.get(g, g))
                           for g in GROUP_COLOURS if g in seen])
    fig.savefig(path, dpi=fig_spec.get("dpi", 130), bbox_inches="tight")
    plt.close(fig)


DRAW = {"lines": lambda f, base, path: draw_lines(f, path),
        "node_maps": draw_node_maps,
        "matrix": lambda f, base, path: draw_matrix(f, path),
        "scene3d": draw_scene3d}


def draw(job):
    """Draws one figure; returns None, or the message that names it and what failed."""
    fig_spec, base = job
    kind = fig_spec["kind"]
    try:
        if kind not in DRAW:
            raise ValueError(f"unknown figure kind '{kind}'")
        DRAW[kind](fig_spec, base, os.path.join(base, fig_spec["id"] + ".png"))
    except Exception as e:  # name the figure that failed, then fail the job
        return f"report_figures.py: figure '{fig_spec['id']}' ({kind}): {type(e).__name__}: {e}"
    finally:
        plt.close("all")
    return None


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: report_figures.py SPEC.json DIR")
    spec_path, base = sys.argv[1], sys.argv[2]
    with open(spec_path) as f:
        spec = json.load(f)
    # Maps of many nodes and 3-D scenes take seconds each, line plots a fraction
    # of one: the dear kinds go first, so that the processes end together.
    order = {"node_maps": 0, "scene3d": 0, "matrix": 1, "lines": 2}
    jobs = sorted(((f, base) for f in spec["figures"]), key=lambda j: order.get(j[0]["kind"], 0))
    processes = max(1, min(int(spec.get("processes", 1)), len(jobs)))
    if processes == 1:
        failures = [m for m in map(draw, jobs) if m is not None]
    else:
        # Forked after matplotlib's import (a second), so each process starts drawing at once.
        with multiprocessing.get_context("fork").Pool(processes) as pool:
            failures = [m for m in pool.imap_unordered(draw, jobs, chunksize=1) if m is not None]
    if failures:
        sys.stderr.write("\n".join(failures) + "\n")
        sys.exit(1)


if __name__ == "__main__":
    main()
