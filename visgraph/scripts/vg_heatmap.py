#!/usr/bin/python3
"""Top-view heatmap of one score column of an `attenuvis vg` CSV.

usage: vg_heatmap.py NODES.csv COLUMN OUT.png [--title TEXT]

Each node is drawn as a square of the grid pitch (estimated from the nodes'
x spacing) at its (x, y), coloured by COLUMN (viridis); nodes whose value is
nan are grey.  Needs Debian's /usr/bin/python3 with python3-matplotlib.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("column")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        if args.column not in header:
            sys.stderr.write(f"vg_heatmap: no column '{args.column}' in {args.csv} (have {', '.join(header)})\n")
            return 2
        ix, iy, ic = header.index("x"), header.index("y"), header.index(args.column)
        rows = [(float(r[ix]), float(r[iy]), float(r[ic])) for r in reader if r]
    if not rows:
        sys.stderr.write(f"vg_heatmap: {args.csv} has no nodes\n")
        return 2
    data = np.array(rows)
    x, y, v = data[:, 0], data[:, 1], data[:, 2]
    xs = np.unique(np.round(x, 6))
    pitch = float(np.min(np.diff(xs))) if len(xs) > 1 else 1.0
    span = max(float(np.ptp(x)), float(np.ptp(y)), pitch)
    fig, ax = plt.subplots(figsize=(7, 6), dpi=150)
    # Marker size in points^2 so that one square covers one grid cell.
    ax.set_xlim(x.min() - pitch, x.max() + pitch)
    ax.set_ylim(y.min() - pitch, y.max() + pitch)
    ax.set_aspect("equal")
    fig.canvas.draw()
    bbox = ax.get_window_extent()
    points_per_metre = bbox.width / fig.dpi * 72 / (span + 2 * pitch)
    size = (pitch * points_per_metre) ** 2
    finite = np.isfinite(v)
    if (~finite).any():
        ax.scatter(x[~finite], y[~finite], s=size, marker="s", c="0.7", linewidths=0)
    sc = ax.scatter(x[finite], y[finite], s=size, marker="s", c=v[finite], cmap="viridis", linewidths=0)
    fig.colorbar(sc, ax=ax, label=args.column)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(args.title or args.column)
    fig.savefig(args.out, format="png", bbox_inches="tight")
    return 0


if __name__ == "__main__":
    sys.exit(main())
