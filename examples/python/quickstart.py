import numpy as np
import gvd

rng = np.random.default_rng(0)
pts = rng.uniform([0.5, 0.5], [9.5, 5.5], size=(60, 2))
pts = pts[np.hypot(*(pts - [5, 3]).T) > 1.6]          # keep clear of the island

scene = gvd.Scene([0, 0, 10, 6])                        # domain; mode="voronoi"
scene.add_points(pts)
scene.add_polygon([[[4, 2], [6, 2.2], [5.2, 4]]], id="island")
scene.add_arc([5, 3], 1.5, 3.5, 5.5)                   # radians, counter-clockwise
d = gvd.compute(scene)                                  # GIL released while it runs
print(d)
print(d.vertices.shape, d.edge_points.shape, d.edge_offsets.shape, d.clearances.max())
assert d.verify()                                       # the independent checker

ax = d.plot()                                           # matplotlib
ax.figure.savefig("quickstart.png", dpi=80, bbox_inches="tight")
