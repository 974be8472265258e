#!/usr/bin/env python3
"""Makes gvd scenes from real outlines: glyphs of DejaVu Sans (the Debian package
fonts-dejavu-core, /usr/share/fonts/truetype/dejavu) flattened to polygons, and a
coastline of Natural Earth (public domain; the npm package world-atlas 2.0.2).

    python3 scripts/real_outlines.py glyph DejaVuSans.ttf g 4 complex > glyph-g.json
    python3 scripts/real_outlines.py country countries-10m.json Iceland 0.001 medial_axis > iceland.json

glyph FONT CHAR STEP MODE: the outline in font units, quadratic pieces cut into chords
of about STEP units (a long run of nearly flat corners), epsilon 0.5.
country TOPOJSON NAME EPSILON MODE: the country's rings in degrees scaled by the cosine
of its mean latitude (so near-isotropic), each ring a polygon.
"""

import json
import math
import sys


def glyph_rings(font_path, char, step):
    from fontTools.pens.basePen import BasePen
    from fontTools.ttLib import TTFont

    class Flatten(BasePen):
        def __init__(self, glyphs):
            super().__init__(glyphs)
            self.rings, self.ring = [], []

        def _moveTo(self, p):
            self.ring = [p]

        def _lineTo(self, p):
            self.ring.append(p)

        def _qCurveToOne(self, c, p):
            a = self.ring[-1]
            n = max(1, math.ceil((math.dist(a, c) + math.dist(c, p)) / step))
            for i in range(1, n + 1):
                t = i / n
                self.ring.append(tuple((1 - t) ** 2 * a[k] + 2 * t * (1 - t) * c[k] + t * t * p[k]
                                       for k in range(2)))

        def _closePath(self):
            ring = [[round(x, 6), round(y, 6)] for x, y in self.ring]
            if ring[0] == ring[-1]:
                ring.pop()
            dedup = [q for i, q in enumerate(ring) if q != ring[i - 1]]
            self.rings.append(dedup)

    font = TTFont(font_path)
    glyphs = font.getGlyphSet()
    pen = Flatten(glyphs)
    glyphs[font.getBestCmap()[ord(char)]].draw(pen)
    return pen.rings


def signed_area(ring):
    return sum(ring[i - 1][0] * ring[i][1] - ring[i][0] * ring[i - 1][1]
               for i in range(len(ring))) / 2


def glyph_scene(font_path, char, step, mode):
    rings = glyph_rings(font_path, char, float(step))
    # TrueType outlines: filled rings clockwise, holes anticlockwise; a hole belongs to
    # the filled ring that contains its first point
    outer = [r for r in rings if signed_area(r) < 0]
    holes = [r for r in rings if signed_area(r) > 0]
    polygons = [[o] for o in outer]
    for h in holes:
        owner = next(p for p in polygons if inside(h[0], p[0]))
        owner.append(h)
    sites = [{"kind": "polygon", "rings": p} for p in polygons]
    return scene(sites, 0.5, mode, f"DejaVu Sans '{char}', chords of {step} font units")


def inside(q, ring):
    odd = False
    for i in range(len(ring)):
        (x0, y0), (x1, y1) = ring[i - 1], ring[i]
        if (y0 > q[1]) != (y1 > q[1]) and q[0] < x0 + (q[1] - y0) * (x1 - x0) / (y1 - y0):
            odd = not odd
    return odd


def country_scene(path, name, epsilon, mode):
    topo = json.load(open(path))
    sx, sy = topo["transform"]["scale"]
    tx, ty = topo["transform"]["translate"]
    arcs = []
    for arc in topo["arcs"]:
        x = y = 0
        pts = []
        for dx, dy in arc:
            x, y = x + dx, y + dy
            pts.append((x * sx + tx, y * sy + ty))
        arcs.append(pts)
    for g in topo["objects"]["countries"]["geometries"]:
        if g["properties"].get("name") != name:
            continue
        polys = [g["arcs"]] if g["type"] == "Polygon" else g["arcs"]
        lat = sum(arcs[a if a >= 0 else ~a][0][1] for p in polys for r in p for a in r)
        lat /= sum(len(r) for p in polys for r in p)
        c = math.cos(math.radians(lat))
        sites = []
        for p in polys:
            rings = []
            for r in p:
                pts = []
                for a in r:
                    run = arcs[a] if a >= 0 else arcs[~a][::-1]
                    pts.extend(run if not pts else run[1:])
                ring = [[round(x * c, 9), round(y, 9)] for x, y in pts[:-1]]
                rings.append([q for i, q in enumerate(ring) if q != ring[i - 1]])
            sites.append({"kind": "polygon", "rings": rings})
        return scene(sites, float(epsilon), mode,
                     f"Natural Earth ({path.split('/')[-1]}) via world-atlas 2.0.2: {name}, "
                     f"longitude times cos {lat:.3f}")
    sys.exit(f"no country named {name}")


def scene(sites, epsilon, mode, source):
    xs = [q[0] for s in sites for r in s["rings"] for q in r]
    ys = [q[1] for s in sites for r in s["rings"] for q in r]
    pad = 0.1 * max(max(xs) - min(xs), max(ys) - min(ys))
    domain = [min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad]
    return {"domain": [round(v, 6) for v in domain], "epsilon": epsilon, "mode": mode,
            "source": source, "sites": sites}


def main():
    kind, *args = sys.argv[1:]
    make = {"glyph": glyph_scene, "country": country_scene}[kind]
    json.dump(make(*args), sys.stdout)
    print()


main()
