"""Drawing diagrams, sites and offsets with matplotlib (an optional dependency)."""

import json
import math
from typing import Any, Optional

import numpy as np


def _axes(ax):
    if ax is not None:
        return ax
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("Diagram.plot needs matplotlib: pip install matplotlib") from e
    _, ax = plt.subplots()
    return ax


def plot_diagram(
    diagram,
    ax: Optional[Any] = None,
    *,
    cells: bool = True,
    vertices: bool = True,
    sites: bool = True,
    edge_color: str = "tab:blue",
    site_color: str = "black",
    linewidth: float = 1.0,
):
    """Draws ``diagram`` into ``ax`` (new axes when None): filled cells, edges, vertices
    and the point sites; returns the axes."""
    from matplotlib.collections import LineCollection, PolyCollection

    ax = _axes(ax)
    if cells and len(diagram.cell_sites):
        outer = [rings[0] for _, rings in diagram.cells]
        colors = [f"C{site % 10}" for site, _ in diagram.cells]
        ax.add_collection(PolyCollection(outer, facecolors=colors, alpha=0.15, edgecolors="none"))
    ax.add_collection(LineCollection(diagram.edges, colors=edge_color, linewidths=linewidth))
    if vertices and len(diagram.vertices):
        v = diagram.vertices
        ax.plot(v[:, 0], v[:, 1], "o", color=edge_color, markersize=2)
    if sites:
        _plot_sites(diagram.scene, ax, site_color)
    x0, y0, x1, y1 = diagram.scene.domain
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    return ax


def _plot_sites(scene, ax, color):
    data = json.loads(scene.to_json())
    for s in data["sites"]:
        kind = s["kind"]
        if kind == "point":
            ax.plot(*s["at"], "o", color=color, markersize=3)
        elif kind == "segment":
            a, b = s["from"], s["to"]
            ax.plot([a[0], b[0]], [a[1], b[1]], color=color, linewidth=1.5)
        elif kind == "polyline":
            p = np.asarray(s["points"])
            ax.plot(p[:, 0], p[:, 1], color=color, linewidth=1.5)
        elif kind == "polygon":
            for ring in s["rings"]:
                r = np.asarray(ring + ring[:1])
                ax.plot(r[:, 0], r[:, 1], color=color, linewidth=1.5)
        elif kind in ("arc", "circle"):
            c, r = s["center"], s["radius"]
            a0, a1 = (s["start_angle"], s["end_angle"]) if kind == "arc" else (0, 2 * math.pi)
            if a1 <= a0:
                a1 += 2 * math.pi
            t = np.linspace(a0, a1, 64)
            ax.plot(c[0] + r * np.cos(t), c[1] + r * np.sin(t), color=color, linewidth=1.5)


def plot_offset(offset, ax: Optional[Any] = None, *, color: str = "tab:red", linewidth: float = 1.0):
    """Draws offset curves into ``ax`` (new axes when None); returns the axes."""
    ax = _axes(ax)
    for p in offset.polylines():
        ax.plot(p[:, 0], p[:, 1], color=color, linewidth=linewidth)
    ax.set_aspect("equal")
    return ax
