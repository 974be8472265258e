#!/usr/bin/env python3
"""Checks the exact bisectors of a diagram written by `gvd compute --bisectors`.

usage: scripts/check_bisectors.py SCENE.json DIAGRAM.json

For every edge with a `bisector`, each piece is sampled at 9 clearances in its range,
evaluated by Held's offset-parameter form (docs/SCENE_FORMAT.md) and measured against
the edge's polyline: every sample must lie within the scene's epsilon of it, and the
pieces must join. Edges without a bisector are counted. Prints one line ending in PASS
or FAIL; exit status 1 on FAIL. Needs numpy.
"""
import json
import math
import sys

import numpy as np


def at(piece, t):
    def coord(c):
        u, w = c[4] + c[5] * t, c[6] + c[7] * t
        return c[0] - c[1] - c[2] * t + piece["sign"] * c[3] * math.sqrt(max(0.0, u * u - w * w))

    return np.array([coord(piece["x"]), coord(piece["y"])])


def polyline_dist(q, pts):
    a, b = pts[:-1], pts[1:]
    ab = b - a
    den = (ab * ab).sum(1)
    den[den == 0] = 1.0
    s = np.clip(((q - a) * ab).sum(1) / den, 0.0, 1.0)
    return float(np.sqrt((((a + ab * s[:, None]) - q) ** 2).sum(1)).min())


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    scene = json.load(open(sys.argv[1]))
    diagram = json.load(open(sys.argv[2]))
    x0, y0, x1, y1 = scene["domain"]
    eps = scene.get("epsilon", 1e-3 * max(x1 - x0, y1 - y0))
    worst, off, without, unjoined = 0.0, 0, 0, 0
    for e in diagram["edges"]:
        pieces, pts = e.get("bisector"), np.array(e["points"], dtype=float)
        if not pieces:
            without += 1
            continue
        for p, q in zip(pieces, pieces[1:]):
            if np.linalg.norm(at(p, p["t"][1]) - at(q, q["t"][0])) > eps:
                unjoined += 1
        for p in pieces:
            for i in range(9):
                t = p["t"][0] + (p["t"][1] - p["t"][0]) * i / 8
                d = polyline_dist(at(p, t), pts)
                worst = max(worst, d)
                off += d > eps
    ok = off == 0 and unjoined == 0 and without < len(diagram["edges"])
    print(
        f"edges={len(diagram['edges'])} without_bisector={without} samples_off={off} "
        f"unjoined={unjoined} worst={worst:.3g} epsilon={eps:.3g} {'PASS' if ok else 'FAIL'}"
    )
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
