"""A city OBJ, a node grid, four conditions, a heatmap, and the edge distances
of one node as a NumPy array.

    /usr/bin/python3 examples/city_weather.py OUTDIR [CITY.obj WALKABLE_GROUP]
(without an OBJ, a small block city is written to OUTDIR/city.obj and used)
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from attenuvis import visgraph as vg, weather as w


def block_city(path, blocks=4, size=20.0, street=10.0):
    """A ground plane (group "ground") and blocks x blocks boxes (group "building")."""
    extent = blocks * (size + street) + street
    v = [(0, 0, 0), (extent, 0, 0), (extent, extent, 0), (0, extent, 0)]
    faces = {"ground": [(1, 2, 3), (1, 3, 4)], "building": []}
    for bx in range(blocks):
        for by in range(blocks):
            x0, y0, h = street + bx * (size + street), street + by * (size + street), 10 + 5 * ((bx + by) % 3)
            base = len(v)
            v += [(x0 + dx, y0 + dy, z) for z in (0, h) for dx, dy in ((0, 0), (size, 0), (size, size), (0, size))]
            quads = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7), (4, 5, 6, 7)]
            for a, b, c, d in quads:
                faces["building"] += [(base + a + 1, base + b + 1, base + c + 1), (base + a + 1, base + c + 1, base + d + 1)]
    with open(path, "w") as f:
        f.writelines(f"v {x} {y} {z}\n" for x, y, z in v)
        for group, tris in faces.items():
            f.write(f"g {group}\n" + "".join(f"f {a} {b} {c}\n" for a, b, c in tris))


out = sys.argv[1]
if len(sys.argv) > 3:
    obj, walkable = sys.argv[2], [sys.argv[3]]
else:
    obj, walkable = f"{out}/city.obj", ["ground"]
    block_city(obj)
scene = vg.Scene.from_obj(obj)
eyes = vg.node_grid(scene, 2.0, walkable=walkable)
conditions = [w.Clear(), w.Rain(25), w.Fog(visibility=300, model="kim"), w.Snow(4, "dry")]
sigmas = [w.sigma(c, 550e-9).value for c in conditions]
result = vg.all_to_all(scene, eyes, sigmas, edges=True)
fig, axes = plt.subplots(1, 4, figsize=(16, 4))
for ax, c, s in zip(axes, conditions, result.sum):
    sc = ax.scatter(eyes[:, 0], eyes[:, 1], c=s, s=3, cmap="magma")
    ax.set_title(f"{c.text}: S_S", fontsize=9)
    ax.set_aspect("equal")
    fig.colorbar(sc, ax=ax, shrink=0.7)
fig.savefig(f"{out}/city_weather.png", dpi=80)
node = int(np.argmax(result.degree))
i, j, d = result.edges
distances = d[(i == node) | (j == node)]  # every line of sight of that node, metres
np.save(f"{out}/node_{node}_distances.npy", distances)
print(f"{len(eyes)} nodes; node {node} sees {len(distances)} others, median distance {np.median(distances):.1f} m")
