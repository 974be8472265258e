"""Diagrams and offsets as shapely geometries (shapely >= 2, an optional dependency)."""

from typing import List, Optional


def _shapely():
    try:
        import shapely.geometry as g
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("this needs shapely: pip install shapely") from e
    return g


def cells(diagram) -> List["shapely.geometry.Polygon"]:
    """Every cell as a Polygon (its outer ring, then its holes), in ``cell_sites`` order."""
    g = _shapely()
    return [g.Polygon(rings[0], rings[1:]) for _, rings in diagram.cells]


def edges(diagram) -> "shapely.geometry.MultiLineString":
    """The diagram's edges as one MultiLineString."""
    g = _shapely()
    return g.MultiLineString([e for e in diagram.edges])


def offsets(offset, tolerance: Optional[float] = None) -> list:
    """The offset curves: LinearRings when closed, LineStrings otherwise."""
    g = _shapely()
    out = []
    for closed, pts in zip(offset.closed, offset.polylines(tolerance)):
        out.append(g.LinearRing(pts) if closed and len(pts) >= 4 else g.LineString(pts))
    return out
