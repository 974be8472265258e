"""Point diagrams against scipy.spatial.Voronoi (Qhull), an independent implementation."""

import threading
import time

import numpy as np
import pytest

import gvd

scipy_spatial = pytest.importorskip("scipy.spatial")


def random_scene(n, seed):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(-1.0, 1.0, size=(n, 2))
    s = gvd.Scene([-1.5, -1.5, 1.5, 1.5], epsilon=1e-6)
    s.add_points(pts)
    return s, pts


@pytest.mark.parametrize(
    "n,seed,engine",
    [(50, 1, "incremental"), (400, 2, "incremental"), (2000, 3, "incremental"),
     (50, 1, "subdivision"), (400, 2, "subdivision")],
)
def test_interior_vertices_match_scipy(n, seed, engine):
    scene, pts = random_scene(n, seed)
    d = gvd.compute(scene, engine=engine)
    vor = scipy_spatial.Voronoi(pts)
    x0, y0, x1, y1 = scene.domain
    # Qhull's vertices inside the domain, away from its boundary (vertices on the
    # boundary are where gvd clips edges; vertices outside are not in gvd's diagram)
    margin = 1e-3
    theirs = vor.vertices[
        (vor.vertices[:, 0] > x0 + margin) & (vor.vertices[:, 0] < x1 - margin)
        & (vor.vertices[:, 1] > y0 + margin) & (vor.vertices[:, 1] < y1 - margin)
    ]
    ours = d.vertices
    inside = (ours[:, 0] > x0 + margin) & (ours[:, 0] < x1 - margin) & (ours[:, 1] > y0 + margin) & (ours[:, 1] < y1 - margin)
    ours = ours[inside]
    assert len(ours) == len(theirs)
    tol = 10 * scene.epsilon if engine == "subdivision" else 1e-9
    dist, _ = scipy_spatial.cKDTree(theirs).query(ours)
    assert dist.max() < tol
    dist, _ = scipy_spatial.cKDTree(ours).query(theirs)
    assert dist.max() < tol


def test_arrays_are_consistent_with_the_points():
    scene, pts = random_scene(300, 7)
    d = gvd.compute(scene)
    tree = scipy_spatial.cKDTree(pts)
    # clearance: the distance to the nearest site, which the vertex's generators share
    near, _ = tree.query(d.vertices, k=3)
    assert np.allclose(d.clearances, near[:, 0], atol=1e-12)
    assert np.allclose(near[:, 2], near[:, 0], atol=1e-9)
    for k in range(len(d.vertices)):
        gens = d.vertex_generators[d.vertex_offsets[k]:d.vertex_offsets[k + 1]]
        assert len(gens) >= 3 and (gens[:, 1] == 0).all()
        assert np.allclose(np.linalg.norm(pts[gens[:, 0]] - d.vertices[k], axis=1), d.clearances[k])
    # CSR layout: edges' points in one array
    assert d.edge_offsets[0] == 0 and d.edge_offsets[-1] == len(d.edge_points)
    assert len(d.edge_offsets) == len(d.edge_sites) + 1
    for e in (0, len(d.edge_sites) // 2, len(d.edge_sites) - 1):
        a, b = d.edge_offsets[e], d.edge_offsets[e + 1]
        assert np.array_equal(d.edge_points[a:b], d.edges[e])
        mid = d.edge_points[a:b].mean(axis=0)
        i, j = d.edge_sites[e]
        assert abs(np.linalg.norm(pts[i] - mid) - np.linalg.norm(pts[j] - mid)) < 1e-9
    ends = d.edge_ends
    assert ((ends >= -1) & (ends < len(d.vertices))).all()
    # a cell per site, each holding its site
    assert sorted(d.cell_sites.tolist()) == list(range(300))
    assert len(d.cell_offsets) == len(d.cell_sites) + 1
    # arrays are shared and read-only
    assert d.vertices is d.vertices and not d.vertices.flags.writeable


def test_cells_hold_their_sites():
    shapely = pytest.importorskip("shapely")
    scene, pts = random_scene(100, 11)
    d = gvd.compute(scene)
    polys = d.shapely_cells()
    for site, poly in zip(d.cell_sites, polys):
        assert poly.is_valid and poly.contains(shapely.Point(pts[site]))
    total = sum(p.area for p in polys)
    assert abs(total - 9.0) < 1e-9  # the cells tile the 3 × 3 domain


def test_the_gil_is_released_while_computing():
    scene, _ = random_scene(200_000, 5)
    done = threading.Event()

    def work():
        gvd.compute(scene)
        done.set()

    t = threading.Thread(target=work)
    start = time.perf_counter()
    t.start()
    stamps = []
    while not done.is_set():
        stamps.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    duration = time.perf_counter() - start
    gaps = np.diff(stamps) if len(stamps) > 1 else np.array([duration])
    # with the GIL held, this thread would stall for the whole computation
    assert duration > 0.1 and gaps.max() < duration / 3, (duration, gaps.max())
