#!/usr/bin/env python3
"""Random segment scenes with crossings, for the segment engine's splitting (issue 14).

usage: gen_crossing_segments.py N SEED OUT.json [--no-crossings]

N segments of random direction in the unit square, of length about 1.5/sqrt(N) (so
that each crosses about 0.7 others), plus a few exact degeneracies: T junctions (an
end exactly in the middle of an axis-parallel segment), collinear overlaps, repeats
(reversed), points on segments and a star of 8 segments through one point. With
--no-crossings the same number of segments, one inside each cell of a jittered
sqrt(N) x sqrt(N) grid, so none touches another: the baseline for timing.
"""
import json, math, random, sys


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 3:
        sys.exit(__doc__.split("\n\n")[1])
    n, seed, out = int(args[0]), int(args[1]), args[2]
    plain = "--no-crossings" in sys.argv
    rng = random.Random(seed)
    length = 1.5 / math.sqrt(n)
    segs = []
    if plain:
        m = math.ceil(math.sqrt(n))
        w = 1.0 / m
        for k in range(n):
            i, j = k % m, k // m
            c = ((i + 0.5) * w, (j + 0.5) * w)
            ang = rng.uniform(0, math.pi)
            h = 0.45 * w * rng.uniform(0.5, 1.0)
            d = (h * math.cos(ang), h * math.sin(ang))
            segs.append(((c[0] - d[0], c[1] - d[1]), (c[0] + d[0], c[1] + d[1])))
    while len(segs) < n:
        c = (rng.uniform(0.02, 0.98), rng.uniform(0.02, 0.98))
        ang = rng.uniform(0, math.pi)
        h = 0.5 * length * rng.uniform(0.5, 1.5)
        d = (h * math.cos(ang), h * math.sin(ang))
        segs.append(((c[0] - d[0], c[1] - d[1]), (c[0] + d[0], c[1] + d[1])))
    sites = [{"kind": "segment", "from": list(a), "to": list(b)} for a, b in segs]
    if not plain:
        k = max(1, n // 50)
        for _ in range(k):
            # a T on an axis-parallel host (its middle lies exactly on it)
            y = rng.uniform(0.05, 0.95)
            x0 = rng.uniform(0.05, 0.95 - 1.5 * length)
            host = ((x0, y), (x0 + length, y))
            foot = (x0 + 0.5 * length, y)
            up = rng.choice([-1, 1]) * 0.6 * length
            sites.append({"kind": "segment", "from": list(host[0]), "to": list(host[1])})
            sites.append({"kind": "segment", "from": list(foot), "to": [foot[0] + 0.3 * up, y + up]})
            # an overlap on the same line, and a point on the host
            sites.append({"kind": "segment", "from": [x0 + 0.75 * length, y], "to": [x0 + 1.5 * length, y]})
            sites.append({"kind": "point", "at": [x0 + 0.25 * length, y]})
        for r in rng.sample(range(n), k):
            a, b = segs[r]
            sites.append({"kind": "segment", "from": list(b), "to": list(a)})  # a repeat
        # a star: 8 segments through one centre
        c = (0.5, 0.5)
        for j in range(8):
            ang = math.pi * j / 8 + 0.1
            d = (length * math.cos(ang), length * math.sin(ang))
            sites.append({"kind": "segment", "from": [c[0] - d[0], c[1] - d[1]],
                          "to": [c[0] + d[0], c[1] + d[1]]})
    scene = {"domain": [0, 0, 1, 1], "epsilon": 1e-3,
             "mode": "voronoi", "sites": sites,
             "source": f"scripts/gen_crossing_segments.py {n} {seed}" + (" --no-crossings" if plain else "")}
    json.dump(scene, open(out, "w"))


main()
