#!/usr/bin/env python3
"""Cuts one country out of a world-atlas TopoJSON file (Natural Earth, public domain)
into a GeoJSON FeatureCollection gvd reads (the medial axis mode as a foreign member).

    python3 scripts/topojson_country.py countries-50m.json Switzerland > examples/scenes/switzerland.geojson
"""

import json
import sys


def decode_arcs(topo):
    sx, sy = topo["transform"]["scale"]
    tx, ty = topo["transform"]["translate"]
    arcs = []
    for arc in topo["arcs"]:
        x = y = 0
        pts = []
        for dx, dy in arc:
            x += dx
            y += dy
            pts.append([round(x * sx + tx, 10), round(y * sy + ty, 10)])
        arcs.append(pts)
    return arcs


def ring(arcs, indices):
    out = []
    for i in indices:
        pts = arcs[i] if i >= 0 else arcs[~i][::-1]
        out.extend(pts if not out else pts[1:])
    return out


def main():
    path, name = sys.argv[1], sys.argv[2]
    topo = json.load(open(path))
    arcs = decode_arcs(topo)
    for g in topo["objects"]["countries"]["geometries"]:
        if g["properties"].get("name") != name:
            continue
        polys = [g["arcs"]] if g["type"] == "Polygon" else g["arcs"]
        coords = [[ring(arcs, r) for r in p] for p in polys]
        geometry = {"type": "MultiPolygon", "coordinates": coords}
        json.dump({"type": "FeatureCollection", "mode": "medial_axis",
                   "features": [{"type": "Feature", "id": name,
                                 "properties": {"source": "Natural Earth 1:50m via world-atlas 2.0.2"},
                                 "geometry": geometry}]}, sys.stdout)
        return
    sys.exit(f"no country named {name}")


main()
