#!/usr/bin/python3
"""Top-view heatmap of score columns of an `attenuvis vg` CSV.

usage: vg_heatmap.py NODES.csv OUT.png COLUMN [COLUMN ...] [--title TEXT]
                     [--footprints CELLS.csv] [--crs NAME]

One panel per COLUMN (e.g. sum:clear, sum:fog:advection), all on one colour
scale (viridis, one labelled colour bar), so that panels compare directly.
Each node is a square of the grid pitch (estimated from the nodes' x
spacing) at its (x, y).  Nodes that see no other node (degree 0, or a sum of
exactly 0 when the degree is not in the file) are drawn as red crosses, so
they are not mistaken for nodes whose lines of sight are all long (C near 0).
Nodes whose value is nan are light grey.  --footprints draws the grid cells
covered by buildings (x,y of their centres) in dark grey.  Needs Debian's
/usr/bin/python3 with python3-matplotlib.
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = [r for r in reader if r]
    return header, rows


def column(header, rows, name):
    i = header.index(name)
    return np.array([float(r[i]) for r in rows])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("out")
    parser.add_argument("columns", nargs="+")
    parser.add_argument("--title", default="")
    parser.add_argument("--footprints", default="")
    parser.add_argument("--crs", default="")
    args = parser.parse_args()
    header, rows = read_csv(args.csv)
    for name in args.columns:
        if name not in header:
            sys.stderr.write(f"vg_heatmap: no column '{name}' in {args.csv} (have {', '.join(header)})\n")
            return 2
    if not rows:
        sys.stderr.write(f"vg_heatmap: {args.csv} has no nodes\n")
        return 2
    x, y = column(header, rows, "x"), column(header, rows, "y")
    values = [column(header, rows, name) for name in args.columns]
    degree = column(header, rows, "degree") if "degree" in header else None
    covered = np.empty((0, 2))
    if args.footprints:
        _, cells = read_csv(args.footprints)
        if cells:
            covered = np.array([[float(r[0]), float(r[1])] for r in cells])

    xs = np.unique(np.round(x, 6))
    pitch = float(np.min(np.diff(xs))) if len(xs) > 1 else 1.0
    all_x = np.concatenate([x, covered[:, 0]]) if len(covered) else x
    all_y = np.concatenate([y, covered[:, 1]]) if len(covered) else y
    finite = np.concatenate([v[np.isfinite(v)] for v in values])
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if hi <= lo:
        hi = lo + 1.0
    n = len(values)
    cols = min(n, 2)
    panel_rows = math.ceil(n / cols)
    fig, axes = plt.subplots(panel_rows, cols, figsize=(6.5 * cols, 5.5 * panel_rows), dpi=150, squeeze=False,
                             constrained_layout=True)
    # Coordinates relative to the lower-left corner keep tick labels short
    # (UTM-sized numbers otherwise); the offset is in the axis label.
    x0, y0 = float(np.floor(all_x.min())), float(np.floor(all_y.min()))
    unit = "m" + (f", {args.crs}" if args.crs else "")
    # Grid nodes (the usual case) are drawn as an image of cells, one pixel
    # per cell; scattered nodes (--nodes) as dots.
    gx0, gy0 = all_x.min(), all_y.min()
    ix = np.rint((x - gx0) / pitch).astype(int)
    iy = np.rint((y - gy0) / pitch).astype(int)
    on_grid = np.allclose(x, gx0 + ix * pitch, atol=1e-3 * pitch) and np.allclose(y, gy0 + iy * pitch, atol=1e-3 * pitch)
    nx = int(np.rint((all_x.max() - gx0) / pitch)) + 1
    ny = int(np.rint((all_y.max() - gy0) / pitch)) + 1
    extent = (gx0 - x0 - pitch / 2, gx0 - x0 + (nx - 0.5) * pitch, gy0 - y0 - pitch / 2, gy0 - y0 + (ny - 0.5) * pitch)
    mappable = None
    for k, (name, v) in enumerate(zip(args.columns, values)):
        ax = axes[k // cols][k % cols]
        blind = (degree == 0) if degree is not None else (v == 0)
        nan = ~np.isfinite(v) & ~blind
        shown = np.isfinite(v) & ~blind
        if on_grid:
            # Background: white = no node; dark grey = covered; light grey = no value.
            rgb = np.ones((ny, nx, 3))
            if len(covered):
                cx = np.rint((covered[:, 0] - gx0) / pitch).astype(int)
                cy = np.rint((covered[:, 1] - gy0) / pitch).astype(int)
                ok = (cx >= 0) & (cx < nx) & (cy >= 0) & (cy < ny)
                rgb[cy[ok], cx[ok]] = 0.3
            rgb[iy[nan], ix[nan]] = 0.85
            ax.imshow(rgb, origin="lower", extent=extent, interpolation="nearest")
            image = np.full((ny, nx), np.nan)
            image[iy[shown], ix[shown]] = v[shown]
            mappable = ax.imshow(np.ma.masked_invalid(image), origin="lower", extent=extent, cmap="viridis",
                                 vmin=lo, vmax=hi, interpolation="nearest")
        else:
            if len(covered):
                ax.scatter(covered[:, 0] - x0, covered[:, 1] - y0, s=4, marker="s", c="0.3", linewidths=0)
            ax.scatter(x[nan] - x0, y[nan] - y0, s=6, c="0.85", linewidths=0)
            mappable = ax.scatter(x[shown] - x0, y[shown] - y0, s=6, c=v[shown], cmap="viridis", vmin=lo, vmax=hi,
                                  linewidths=0)
        if blind.any():
            ax.scatter(x[blind] - x0, y[blind] - y0, s=12, marker="x", c="red", linewidths=0.8,
                       label=f"sees no node ({int(blind.sum())})")
        if len(covered):
            ax.scatter([], [], s=20, marker="s", c="0.3", label="covered (buildings)")
        ax.set_aspect("equal")
        # Shown relative to the scene's corner only where it is not the origin (UTM-sized data).
        ax.set_xlabel(f"x - {x0:.0f} ({unit})" if x0 else f"x ({unit})")
        ax.set_ylabel(f"y - {y0:.0f} ({unit})" if y0 else f"y ({unit})")
        ax.set_title(name)
        if len(covered) or blind.any():
            ax.legend(loc="upper right", fontsize=7, framealpha=0.8)
    for k in range(n, panel_rows * cols):
        axes[k // cols][k % cols].axis("off")
    first = args.columns[0]
    if all(c.startswith("sum:") for c in args.columns):
        label = "sum score $S_S = \\sum \\exp(-\\sigma d)$ over the nodes seen"
    elif all(c.startswith("avg:") for c in args.columns):
        label = "average score $S_A = S_S$ / degree"
    elif first == "degree":
        label = "degree (nodes seen)"
    else:
        label = first
    fig.colorbar(mappable, ax=axes.ravel().tolist(), label=label, shrink=0.8)
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.out, format="png", bbox_inches="tight")
    return 0


if __name__ == "__main__":
    sys.exit(main())
