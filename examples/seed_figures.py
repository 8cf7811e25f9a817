"""The seed paper's S_S heatmaps: the five classic layouts under clear air,
rain 8 mm/h, heavy advection fog and dry snow 4 mm/h (550 nm).

    /usr/bin/python3 examples/seed_figures.py OUTDIR [SPACING_M]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from attenuvis import visgraph as vg, weather as w

out, spacing = sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
conditions = {"clear": w.Clear(), "rain 8 mm/h": w.Rain(8), "advection fog": w.Fog("advection"),
              "dry snow 4 mm/h": w.Snow(4, "dry")}
sigmas = [w.sigma(c, 550e-9, convention="seed").value for c in conditions.values()]
fig, axes = plt.subplots(len(conditions), 5, figsize=(15, 12), squeeze=False)
for col, name in enumerate(vg.classic_layout_names()):
    scene = vg.Scene.layout(col)
    eyes = vg.node_grid(scene, spacing)
    scores = vg.all_to_all(scene, eyes, sigmas).sum
    np.save(f"{out}/layout{col}_sum.npy", scores)
    for row, label in enumerate(conditions):
        ax = axes[row, col]
        sc = ax.scatter(eyes[:, 0], eyes[:, 1], c=scores[row], s=4, marker="s", cmap="viridis")
        ax.set_aspect("equal")
        ax.set_title(f"{name}\n{label}", fontsize=8)
        fig.colorbar(sc, ax=ax, shrink=0.7)
fig.suptitle("S_S = sum of exp(-sigma d) over visible nodes")
fig.savefig(f"{out}/seed_heatmaps.png", dpi=80)
print(f"wrote {out}/seed_heatmaps.png")
