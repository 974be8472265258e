"""GeoJSON, WKT, DXF and SVG in and out, read back by independent libraries."""

import json
import math

import numpy as np
import pytest

import gvd


def test_geojson_round_trip_through_shapely():
    shapely = pytest.importorskip("shapely")
    from shapely.geometry import mapping, shape

    outline = shapely.Polygon([(0, 0), (10, 0), (10, 6), (4, 8), (0, 6)], [[(2, 2), (2, 4), (4, 4), (4, 2)]])
    towns = shapely.MultiPoint([(12, 2), (13, 4), (12, 7)])  # outside the land: a polygon is solid
    fc = {"type": "FeatureCollection", "mode": "voronoi",
          "features": [{"type": "Feature", "id": "land", "properties": {}, "geometry": mapping(outline)},
                       {"type": "Feature", "properties": {"id": "towns"}, "geometry": mapping(towns)}]}
    scene = gvd.Scene.from_geojson(json.dumps(fc))
    assert scene.kinds() == ["polygon", "point", "point", "point"]
    sites = json.loads(scene.to_json())["sites"]
    assert shapely.Polygon(sites[0]["rings"][0], sites[0]["rings"][1:]).equals(outline)
    d = gvd.compute(scene)
    out = json.loads(d.to_geojson())
    assert out["type"] == "FeatureCollection"
    kinds = [f["properties"]["type"] for f in out["features"]]
    assert kinds.count("vertex") == len(d.vertices)
    assert kinds.count("edge") == len(d.edge_sites)
    assert kinds.count("cell") == len(d.cell_sites)
    for f in out["features"]:
        g = shape(f["geometry"])
        assert g.is_valid
        p = f["properties"]
        if p["type"] == "vertex":
            assert np.allclose(g.coords[0], d.vertices[p["index"]])
            assert math.isclose(p["clearance"], d.clearances[p["index"]])
        elif p["type"] == "edge":
            assert np.allclose(np.asarray(g.coords), d.edges[p["index"]])
        else:
            # each cell holds its site, and names its id
            site = p["site"]
            assert p["site_id"] == ("land" if site == 0 else "towns")
            if site > 0:
                assert g.contains(shapely.Point(sites[site]["at"]))
    # from shapely directly, and back as shapely geometries
    again = gvd.Scene.from_shapely(outline, mode="medial_axis")
    axis = gvd.compute(again)
    assert axis.verify(grid=128)
    assert outline.buffer(1e-9).contains(axis.shapely_edges())


def test_wkt_in_and_out():
    shapely = pytest.importorskip("shapely")
    import shapely.wkt

    text = "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))\nPOINT (6 1.5)\nLINESTRING (5 -1, 7 -1)\n"
    scene = gvd.Scene.from_wkt(text, domain=[-1, -2, 8, 4])
    assert scene.domain == (-1, -2, 8, 4) and scene.kinds() == ["polygon", "point", "polyline"]
    d = gvd.compute(scene)
    points, edges, cells = [shapely.wkt.loads(line) for line in d.to_wkt().splitlines()]
    assert len(points.geoms) == len(d.vertices)
    assert len(edges.geoms) == len(d.edge_sites)
    assert len(cells.geoms) == len(d.cell_sites)
    # cells (the engine of points writes them): they tile the domain
    pts = gvd.Scene.from_wkt("MULTIPOINT ((0 0), (4 0), (4 3), (1 2))", domain=[-1, -2, 8, 4])
    _, _, cells = [shapely.wkt.loads(line) for line in gvd.compute(pts).to_wkt().splitlines()]
    assert len(cells.geoms) == 4 and abs(sum(c.area for c in cells.geoms) - 9 * 6) < 1e-9


def test_dxf_part_with_arcs_and_bulges_read_and_offsets_written(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    # a slot-shaped part written by an independent DXF library: a closed LWPOLYLINE
    # with two bulges of 1 (half circles), a LINE, an ARC and a CIRCLE outside it
    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0, 0, 0, 0), (4, 0, 0, 0, 1), (4, 2, 0, 0, 0), (0, 2, 0, 0, 1)],
                       format="xyseb", close=True)
    msp.add_line((0, 4), (4, 4))
    msp.add_arc((8, 1), 1, 90, 270)
    msp.add_circle((8, 5), 0.5)
    msp.add_text("not a site")
    path = tmp_path / "part.dxf"
    doc.saveas(path)
    with pytest.warns(UserWarning, match="TEXT"):
        scene = gvd.read(path, mode="complex")
    assert scene.kinds() == ["polyline", "arc", "polyline", "arc", "segment", "arc", "arc", "arc"]
    sites = json.loads(scene.to_json())["sites"]
    arcs = [s for s in sites if s["kind"] == "arc" and math.isclose(s["radius"], 1) and s["center"][0] < 6]
    assert sorted(round(a["center"][0], 12) for a in arcs) == [0, 4]
    for mode in ("voronoi", "complex"):
        d = gvd.compute(scene.with_mode(mode))
        assert d.stats["engine"] == "incremental"
        report = d.verify(grid=256)
        assert report, report
    # offsets of a pocket: the slot outline as a closed polygon-like chain, read back
    pocket = gvd.Scene([-2, -2, 6, 4], mode="medial_axis")
    pocket.add_polygon([[[0, 0], [4, 0], [4, 2], [0, 2]]])
    off = gvd.offset(pocket, 0.5)
    out = tmp_path / "offset.dxf"
    out.write_text(off.to_dxf())
    back = ezdxf.readfile(out)
    entities = list(back.modelspace())
    prims = [p for c in off.curves for p in c["primitives"]]
    assert len(entities) == len(prims) > 0
    assert all(e.dxftype() == "LINE" for e in entities)  # a square pocket: straight offsets
    ring = off.to_shapely()[0]
    assert abs(shapely_area(ring) - 3 * 1) < 1e-9


def shapely_area(ring):
    import shapely

    return shapely.Polygon(ring).area


def test_dxf_offset_arcs_read_back_by_ezdxf(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    s = gvd.Scene([-3, -3, 3, 3])
    s.add_segment([-1, 0], [1, 0])
    off = gvd.offset(s, 0.5)
    path = tmp_path / "o.dxf"
    path.write_text(off.to_dxf())
    kinds = sorted(e.dxftype() for e in ezdxf.readfile(path).modelspace())
    assert kinds == ["ARC", "ARC", "LINE", "LINE"]
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "ARC":
            assert math.isclose(e.dxf.radius, 0.5)
            assert math.isclose((e.dxf.end_angle - e.dxf.start_angle) % 360, 180)
    edges = tmp_path / "e.dxf"
    d = gvd.compute(s.with_mode("complex"))
    edges.write_text(d.to_dxf())
    lines = list(ezdxf.readfile(edges).modelspace())
    assert len(lines) == sum(len(e) - 1 for e in d.edges)


def test_svg_and_plot():
    s = gvd.Scene([0, 0, 1, 1])
    s.add_points([[0.2, 0.2], [0.8, 0.3], [0.5, 0.9]])
    d = gvd.compute(s)
    assert d.to_svg(width=300).startswith("<svg") and 'width="300"' in d.to_svg(width=300)
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    ax = d.plot()
    assert len(ax.collections) >= 2 and ax.get_xlim() == (0, 1)


def test_offset_against_shapely_buffer():
    shapely = pytest.importorskip("shapely")
    s = gvd.Scene([-3, -3, 3, 3])
    s.add_segment([-1, 0], [1, 0])
    s.add_point([0, 2])
    off = gvd.offset(s, 0.4)
    ours = shapely.unary_union([shapely.Polygon(r) for r in off.to_shapely(1e-6) if r.is_ring])
    theirs = shapely.union(shapely.LineString([(-1, 0), (1, 0)]).buffer(0.4, 256), shapely.Point(0, 2).buffer(0.4, 256))
    assert ours.symmetric_difference(theirs).area < 1e-3
    assert len(off) == 2 and all(off.closed)


def test_a_country_outline_medial_axis(repo):
    """The shipped GeoJSON country (Natural Earth): its medial axis verifies, and every
    edge lies inside the outline, read back through shapely."""
    shapely = pytest.importorskip("shapely")
    from shapely.geometry import shape

    path = repo / "examples" / "scenes" / "switzerland.geojson"
    scene = gvd.read(path)
    assert scene.mode == "medial_axis" and scene.kinds() == ["polygon"]
    d = gvd.compute(scene)
    assert d.verify(grid=256)
    outline = shape(json.loads(path.read_text())["features"][0]["geometry"])
    edges = [shape(f["geometry"]) for f in json.loads(d.to_geojson())["features"]
             if f["properties"]["type"] == "edge"]
    assert len(edges) == len(d.edge_sites) > 100
    assert all(outline.buffer(1e-9).contains(e) for e in edges)
    # the deepest point of the axis is its largest inscribed circle's centre
    k = int(np.argmax(d.clearances))
    centre = shapely.Point(d.vertices[k])
    assert abs(outline.boundary.distance(centre) - d.clearances[k]) < 1e-9


def test_docstring_example():
    import doctest

    failures, tried = doctest.testmod(gvd)
    assert tried > 0 and failures == 0


def test_segment_cells_site_ids_and_an_svg_drawing():
    shapely = pytest.importorskip("shapely")
    import pathlib

    scene = gvd.Scene([0, 0, 4, 3])
    scene.add_segment([0.5, 0.5], [1.5, 2.5], id="wall")
    scene.add_polygon([[[2.5, 0.5], [3.5, 0.5], [3.5, 1.5]]], id="pillar")
    scene.add_arc([2.5, 2.2], 0.4, 0.0, 2.0)
    d = gvd.compute(scene)
    assert json.loads(d.to_json())["site_ids"] == ["wall", "pillar", None]
    assert d.site_ids == ["wall", "pillar", None]
    # the segment engine's cells tile the domain, each holding its site
    cells = d.shapely_cells()
    assert sorted(d.cell_sites.tolist()) == [0, 1, 2]
    assert abs(sum(c.area for c in cells) - 12.0) < 1e-9
    pillar = cells[d.cell_sites.tolist().index(1)]
    assert pillar.contains(shapely.Polygon([[2.5, 0.5], [3.5, 0.5], [3.5, 1.5]]).buffer(-1e-6))
    assert "<title>wall</title>" in d.to_svg()
    # an SVG drawing read by its extension
    drawing = pathlib.Path(__file__).resolve().parents[2] / "examples" / "scenes" / "bracket.svg"
    bracket = gvd.compute(str(drawing))
    assert "hole-left" in bracket.site_ids
    assert bracket.verify(grid=128)


def test_png_bytes_and_file_are_the_svg_picture(tmp_path):
    import re
    import struct
    import zlib

    d = gvd.compute({"domain": [0, 0, 4, 2], "epsilon": 0.01,
                     "sites": [{"kind": "point", "at": [1, 1]}, {"kind": "point", "at": [3, 1]}]})
    png = d.to_png(width=200)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height, depth, colour = struct.unpack(">IIBB", png[16:26])
    svg_size = re.search(r'<svg [^>]*width="(\d+)" height="(\d+)"', d.to_svg(width=200))
    assert (width, height) == (200, int(svg_size.group(2)))  # the SVG's size (and margin)
    assert (depth, colour) == (8, 6)  # 8-bit RGBA
    chunks, i = {}, 8
    while i < len(png):
        (n,) = struct.unpack(">I", png[i:i + 4])
        chunks.setdefault(png[i + 4:i + 8], b"")
        chunks[png[i + 4:i + 8]] += png[i + 8:i + 8 + n]
        i += 12 + n
    raw = zlib.decompress(chunks[b"IDAT"])
    assert len(raw) == height * (1 + 4 * width)
    assert len(set(raw)) > 2  # not a blank picture
    out = tmp_path / "d.png"
    assert d.to_png(out, width=200) is None
    assert out.read_bytes() == png
    with pytest.raises(OSError, match="directory"):
        d.to_png(tmp_path)
    link = tmp_path / "link.png"
    link.symlink_to(out)
    with pytest.raises(OSError, match="symbolic link"):
        d.to_png(link, width=100)
    assert out.read_bytes() == png
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.png", "link.png"]


def test_longitude_and_latitude_projected_and_back(tmp_path):
    sites = [(5.0, 52.0), (5.6, 52.3), (5.2, 52.5)]
    text = json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": None,
         "geometry": {"type": "MultiPoint", "coordinates": sites}}]})
    path = tmp_path / "three.geojson"
    path.write_text(text)

    def haversine(a, b):
        r = 6371008.8
        p1, p2 = math.radians(a[1]), math.radians(b[1])
        dl = math.radians(b[0] - a[0])
        h = math.sin((p2 - p1) / 2) ** 2 + math.cos(p1) * math.cos(p2) * math.sin(dl / 2) ** 2
        return 2 * r * math.asin(math.sqrt(h))

    for scene in (gvd.read(path, project="local"), gvd.Scene.from_geojson(text, project="local")):
        d = gvd.compute(scene)
        out = json.loads(d.to_geojson())
        (vertex,) = [f for f in out["features"]
                     if f["properties"]["type"] == "vertex" and len(f["properties"]["generators"]) == 3]
        at = vertex["geometry"]["coordinates"]
        dist = [haversine(at, s) for s in sites]
        # the projection's distortion within 29 km of the centre bounds the spread: 0.1 m
        assert max(dist) - min(dist) < 0.1, dist
        assert abs(vertex["properties"]["clearance"] - max(dist)) < 0.1
        edges = [f for f in out["features"] if f["properties"]["type"] == "edge"]
        for e in edges:
            for x, y in e["geometry"]["coordinates"]:
                assert 4.8 < x < 5.8 and 51.9 < y < 52.6
        offset = json.loads(d.offset(1000.0).to_geojson())  # metres
        for f in offset["features"]:
            for x, y in f["geometry"]["coordinates"]:
                assert 4.9 < x < 5.7 and 51.9 < y < 52.6
    with pytest.raises(gvd.OptionError, match="project"):
        gvd.read(path, project="utm")


def test_sites_added_to_a_projected_scene_keep_its_projection():
    shapely = pytest.importorskip("shapely")
    text = json.dumps({"type": "MultiPoint", "coordinates": [(5.0, 52.0), (5.6, 52.3), (5.2, 52.5)]})
    scene = gvd.Scene.from_geojson(text, project="local")
    # the scene's coordinates are metres about the data's centre, (5.3, 52.25)
    site = scene.add_point([0.0, 0.0])
    out = json.loads(gvd.compute(scene).to_geojson())

    def coordinates(geometry):
        if geometry["type"] == "Point":
            return [geometry["coordinates"]]
        if geometry["type"] == "LineString":
            return geometry["coordinates"]
        return [p for ring in geometry["coordinates"] for p in ring]

    for f in out["features"]:
        for x, y in coordinates(f["geometry"]):
            assert 4.8 < x < 5.8 and 51.9 < y < 52.6, (f["properties"], x, y)
    (cell,) = [f for f in out["features"]
               if f["properties"]["type"] == "cell" and f["properties"]["site"] == site]
    assert shapely.geometry.shape(cell["geometry"]).contains(shapely.Point(5.3, 52.25))
