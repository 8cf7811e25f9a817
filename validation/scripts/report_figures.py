#!/usr/bin/python3
"""Draws the figures of `attenuvis reproduce` from a JSON spec.

Usage: report_figures.py SPEC.json DIR

SPEC.json = {"figures": [FIG, ...]}; every FIG has "id" (written as DIR/<id>.png),
"kind" and kind-specific fields.  Data are either inline or in CSV files of DIR
(the report's own tables), so the figure shows exactly the numbers of the run.

kinds
  lines      series=[{label, x[], y[], style?}], xlabel, ylabel, xlog?, ylog?, title?,
             hlines=[{y, label}]?, points=[{x, y, label}]? (published values, drawn as markers)
  node_maps  panels=[{title, csv, value, markers=[{x, y, label}]?, xlim?, ylim?}], ncols?, common_scale?,
             vmin?, vmax?, cmap?, colorbar?, log?  -- top-view heatmaps of node scores
  matrix     x[], ylabels[], z[[...]] (null = missing), xlabel, ylabel, colorbar, zlog?, xlog?

Any failure exits non-zero with a message on stderr; the report is then not written.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402


def read_columns(path, names):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        idx = []
        for n in names:
            if n not in header:
                raise ValueError(f"{path}: no column '{n}' (columns: {header})")
            idx.append(header.index(n))
        cols = [[] for _ in names]
        for row in reader:
            for k, i in enumerate(idx):
                cols[k].append(float(row[i]))
    return [np.asarray(c) for c in cols]


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


def draw_lines(fig_spec, path):
    fig, ax = plt.subplots(figsize=fig_spec.get("size", (7, 4.5)))
    for s in fig_spec["series"]:
        x = np.asarray(s["x"], dtype=float)
        y = np.asarray([np.nan if v is None else v for v in s["y"]], dtype=float)
        ax.plot(x, y, s.get("style", "-"), label=s.get("label"), markersize=4)
    for p in fig_spec.get("points", []):
        ax.plot([p["x"]], [p["y"]], "k*", markersize=10)
        ax.annotate(p.get("label", ""), (p["x"], p["y"]), textcoords="offset points", xytext=(5, 5), fontsize=8)
    for h in fig_spec.get("hlines", []):
        ax.axhline(h["y"], color="gray", linestyle=":", linewidth=1)
        ax.annotate(h.get("label", ""), (ax.get_xlim()[0], h["y"]), fontsize=8, color="gray")
    if fig_spec.get("xlog"):
        ax.set_xscale("log")
    if fig_spec.get("ylog"):
        ax.set_yscale("log")
    ax.set_xlabel(fig_spec.get("xlabel", ""))
    ax.set_ylabel(fig_spec.get("ylabel", ""))
    if "title" in fig_spec:
        ax.set_title(fig_spec["title"], fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def draw_node_maps(fig_spec, base, path):
    panels = fig_spec["panels"]
    ncols = min(fig_spec.get("ncols", len(panels)), len(panels))
    nrows = math.ceil(len(panels) / ncols)
    size = fig_spec.get("panel_size", 3.2)
    data = []
    for p in panels:
        x, y, v = read_columns(os.path.join(base, p["csv"]), [p.get("x", "x"), p.get("y", "y"), p["value"]])
        data.append((x, y, v))
    common = fig_spec.get("common_scale", False)
    cmap = fig_spec.get("cmap", "viridis")
    log = fig_spec.get("log", False)
    gmin = fig_spec.get("vmin", min(float(np.nanmin(d[2])) for d in data))
    gmax = fig_spec.get("vmax", max(float(np.nanmax(d[2])) for d in data))
    fig, axes = plt.subplots(nrows, ncols, figsize=(size * ncols + (1.0 if common else 0.6 * ncols), size * nrows + 0.5),
                             squeeze=False)
    last = None
    for k, (p, (x, y, v)) in enumerate(zip(panels, data)):
        ax = axes[k // ncols][k % ncols]
        lo, hi = (gmin, gmax) if common else (p.get("vmin", float(np.nanmin(v))), p.get("vmax", float(np.nanmax(v))))
        if hi <= lo:
            hi = lo + (abs(lo) if lo else 1.0) * 1e-9 + 1e-300
        norm = LogNorm(vmin=max(lo, 1e-300), vmax=hi) if log else Normalize(vmin=lo, vmax=hi)
        g = grid_image(x, y, v)
        if g is not None:
            img, extent = g
            last = ax.imshow(img, origin="lower", extent=extent, cmap=cmap, norm=norm, interpolation="nearest")
        else:
            last = ax.scatter(x, y, c=v, s=2, cmap=cmap, norm=norm, marker="s", linewidths=0)
        for m in p.get("markers", []):
            ax.plot([m["x"]], [m["y"]], "o", markersize=7, markerfacecolor="none", markeredgecolor="red", markeredgewidth=1.5)
            ax.annotate(m.get("label", ""), (m["x"], m["y"]), textcoords="offset points", xytext=(6, 6),
                        color="red", fontsize=9, fontweight="bold")
        if "xlim" in p:
            ax.set_xlim(*p["xlim"])
        if "ylim" in p:
            ax.set_ylim(*p["ylim"])
        ax.set_aspect("equal")
        ax.set_title(p.get("title", ""), fontsize=9)
        ax.tick_params(labelsize=7)
        if not common:
            cb = fig.colorbar(last, ax=ax, fraction=0.046, pad=0.03)
            cb.ax.tick_params(labelsize=7)
    for k in range(len(panels), nrows * ncols):
        axes[k // ncols][k % ncols].axis("off")
    if common and last is not None:
        cb = fig.colorbar(last, ax=axes.ravel().tolist(), fraction=0.02, pad=0.02)
        cb.set_label(fig_spec.get("colorbar", ""))
    if "title" in fig_spec:
        fig.suptitle(fig_spec["title"], fontsize=10)
    fig.savefig(path, dpi=fig_spec.get("dpi", 110), bbox_inches="tight")
    plt.close(fig)


def draw_matrix(fig_spec, path):
    x = np.asarray(fig_spec["x"], dtype=float)
    ylabels = fig_spec["ylabels"]
    z = np.asarray([[np.nan if v is None else v for v in row] for row in fig_spec["z"]], dtype=float)
    fig, ax = plt.subplots(figsize=fig_spec.get("size", (9, 0.45 * len(ylabels) + 1.8)))
    finite = z[np.isfinite(z) & (z > 0)] if fig_spec.get("zlog") else z[np.isfinite(z)]
    if fig_spec.get("zlog"):
        lo = fig_spec.get("zmin", float(finite.min()) if finite.size else 1e-17)
        hi = fig_spec.get("zmax", float(finite.max()) if finite.size else 1.0)
        zz = np.where(z > 0, z, lo)
        norm = LogNorm(vmin=lo, vmax=max(hi, lo * 10))
    else:
        zz = z
        norm = Normalize()
    xs = np.log10(x) if fig_spec.get("xlog") else x
    im = ax.pcolormesh(np.arange(len(x) + 1), np.arange(len(ylabels) + 1), zz, cmap=fig_spec.get("cmap", "magma_r"),
                       norm=norm, shading="flat")
    step = max(1, len(x) // 13)
    ax.set_xticks(np.arange(0, len(x), step) + 0.5)
    ax.set_xticklabels([f"1e{v:.0f}" if fig_spec.get("xlog") else f"{v:g}" for v in xs[::step]], fontsize=7)
    ax.set_yticks(np.arange(len(ylabels)) + 0.5)
    ax.set_yticklabels(ylabels, fontsize=8)
    ax.set_xlabel(fig_spec.get("xlabel", ""))
    ax.set_ylabel(fig_spec.get("ylabel", ""))
    cb = fig.colorbar(im, ax=ax)
    cb.set_label(fig_spec.get("colorbar", ""))
    if "title" in fig_spec:
        ax.set_title(fig_spec["title"], fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: report_figures.py SPEC.json DIR")
    spec_path, base = sys.argv[1], sys.argv[2]
    with open(spec_path) as f:
        spec = json.load(f)
    for fig_spec in spec["figures"]:
        path = os.path.join(base, fig_spec["id"] + ".png")
        kind = fig_spec["kind"]
        try:
            if kind == "lines":
                draw_lines(fig_spec, path)
            elif kind == "node_maps":
                draw_node_maps(fig_spec, base, path)
            elif kind == "matrix":
                draw_matrix(fig_spec, path)
            else:
                raise ValueError(f"unknown figure kind '{kind}'")
        except Exception as e:  # name the figure that failed, then fail the job
            sys.stderr.write(f"report_figures.py: figure '{fig_spec['id']}' ({kind}): {type(e).__name__}: {e}\n")
            sys.exit(1)
        print(fig_spec["id"], flush=True)


if __name__ == "__main__":
    main()
