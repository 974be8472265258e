"""gvd: generalized Voronoi diagrams in the plane.

Points under many metrics, circles, ellipses, segments, arcs, polylines, polygons with
holes, algebraic curves and distance fields; Voronoi diagrams, Voronoi complexes and
medial axes; offsets; an independent checker.

>>> import gvd
>>> d = gvd.compute({"domain": [0, 0, 1, 1], "sites": [
...     {"kind": "point", "at": [0.25, 0.25]}, {"kind": "point", "at": [0.75, 0.5]},
...     {"kind": "point", "at": [0.4, 0.8]}]})
>>> d.vertices.shape
(1, 2)
"""

import json as _json
import os as _os
from typing import Any, Optional, Union

from . import errors
from ._gvd import Diagram, Offset, Report, Scene, __version__
from ._gvd import compute as _compute
from ._gvd import offset as _offset
from ._gvd import read_diagram as _read_diagram
from ._gvd import verify as _verify
from .errors import (
    BudgetError,
    DiagramError,
    Error,
    InternalError,
    OptionError,
    SceneError,
    UnsupportedError,
)

__all__ = [
    "Scene",
    "Diagram",
    "Offset",
    "Report",
    "compute",
    "offset",
    "verify",
    "read",
    "read_diagram",
    "Error",
    "SceneError",
    "UnsupportedError",
    "BudgetError",
    "OptionError",
    "DiagramError",
    "InternalError",
    "errors",
    "__version__",
]

SceneLike = Union[Scene, dict, str, "_os.PathLike[str]", Any]


def read(
    path: Union[str, "_os.PathLike[str]"],
    format: Optional[str] = None,
    *,
    domain=None,
    epsilon: Optional[float] = None,
    mode: Optional[str] = None,
    project: Optional[str] = None,
) -> Scene:
    """Reads a scene file; the format from ``format`` or the extension (``.json``,
    ``.geojson``, ``.wkt``, ``.dxf``, ``.svg``). ``domain``, ``epsilon`` and ``mode`` override the
    file's. ``project="local"`` takes GeoJSON coordinates as longitude and latitude in
    degrees, projected to metres about the data's centre; the diagram's GeoJSON outputs
    come back in longitude and latitude."""
    return Scene.read(_os.fspath(path), format, domain=domain, epsilon=epsilon, mode=mode,
                      project=project)


def as_scene(scene: SceneLike) -> Scene:
    """A ``Scene`` from a ``Scene``, a dict or JSON text of the scene format, a path to a
    scene file, or a shapely geometry (anything with ``__geo_interface__``)."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return Scene.from_json(_json.dumps(scene))
    if isinstance(scene, str):
        if scene.lstrip().startswith("{"):
            return Scene.from_json(scene)
        return read(scene)
    if isinstance(scene, _os.PathLike):
        return read(scene)
    if hasattr(scene, "__geo_interface__"):
        return Scene.from_shapely(scene)
    raise TypeError(
        "expected a gvd.Scene, a dict, JSON text, a path or a shapely geometry, "
        f"found {type(scene).__name__}"
    )


def compute(
    scene: SceneLike,
    engine: str = "auto",
    *,
    parallel: bool = True,
    max_box: Optional[float] = None,
    max_boxes: Optional[int] = None,
    max_points: Optional[int] = None,
    bisectors: bool = False,
    strict: bool = False,
    timeout: Optional[float] = None,
    prune_lambda: Optional[float] = None,
    prune_angle: Optional[float] = None,
) -> Diagram:
    """Computes the Voronoi diagram (or complex, or medial axis: the scene's ``mode``).

    ``scene``: a ``gvd.Scene``, a dict or JSON text in the scene format, a path, or a
    shapely geometry. ``engine``: ``"auto"`` (the incremental engine where it applies),
    ``"incremental"`` (Euclidean points, segments, arcs, polylines, polygons),
    ``"subdivision"`` (every site kind but free-form curves) or ``"freeform"`` (Bézier
    and B-spline curves). ``max_box``, ``max_boxes`` and ``max_points``
    tune the subdivision engine; ``bisectors`` gives the incremental engine's edges
    their exact bisectors. Segments that cross, overlap or touch are cut into pieces
    that keep their site's index; ``strict=True`` refuses them instead, naming both
    sites. ``timeout`` (seconds) bounds the run. The GIL is released while it
    computes, and Ctrl-C stops it (``KeyboardInterrupt``).

    ``prune_lambda`` (a length) and ``prune_angle`` (degrees) prune the medial axis: a
    point stays when its two nearest boundary points are at least ``2 * prune_lambda``
    apart (the λ-medial axis) and subtend at least ``prune_angle`` there (the object
    angle). Cut branches end at vertices of degree one; vertices of degree two are
    merged away.

    Raises ``SceneError`` (with ``.site`` and ``.field``) for refused scenes,
    ``UnsupportedError``, ``BudgetError`` (also when ``timeout`` runs out, with
    ``what == "seconds"``) and ``OptionError``.
    """
    return _compute(
        as_scene(scene),
        engine,
        parallel=parallel,
        max_box=max_box,
        max_boxes=max_boxes,
        max_points=max_points,
        bisectors=bisectors,
        strict=strict,
        timeout=timeout,
        prune_lambda=prune_lambda,
        prune_angle=prune_angle,
    )


def offset(scene: SceneLike, distance: float) -> Offset:
    """Offset curves (exact lines and arcs) at ``distance`` from the sites, derived from
    the diagram (in ``complex`` mode for a ``voronoi`` scene; in ``medial_axis`` mode,
    the offsets of a pocket). Euclidean points, segments, arcs, polylines and polygons.
    """
    return _offset(as_scene(scene), distance)


def verify(scene: SceneLike, diagram: Union[Diagram, str], grid: int = 512, slack: float = 1.0) -> Report:
    """Checks ``diagram`` (a ``Diagram``, or JSON text of one) against ``scene`` by brute
    force, independently of the engines: soundness of every edge sample, completeness
    on a ``grid`` × ``grid`` lattice, the vertices, within ``slack`` × epsilon."""
    scene = as_scene(scene)
    if isinstance(diagram, str):
        diagram = _read_diagram(scene, diagram)
    return _verify(scene, diagram, grid, slack)


def read_diagram(scene: SceneLike, text: str) -> Diagram:
    """A diagram from JSON text (``Diagram.to_json()`` or ``gvd compute --json``), paired
    with its scene."""
    return _read_diagram(as_scene(scene), text)
