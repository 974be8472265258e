"""Scenes built in Python, read from every input form, and refused with the site and field."""

import _thread
import json
import math
import random
import re
import threading
import time

import numpy as np
import pytest

import gvd


def bad_cases(data):
    """(file, site, field) from the table of data/bad/README.md (copied from the corpus)."""
    rows = []
    for line in (data / "bad" / "README.md").read_text().splitlines():
        m = re.match(r"\|\s*`([^`]+\.json)`\s*\|[^|]*\|\s*(\d*)\s*\|\s*`?([^`|]*)`?\s*\|", line)
        if m:
            rows.append((m.group(1), int(m.group(2)) if m.group(2) else None, m.group(3).strip() or None))
    return rows


def test_the_bad_table_is_read(data):
    cases = bad_cases(data)
    assert len(cases) == len(list((data / "bad").glob("*.json"))) == 16


@pytest.mark.parametrize("case", range(16))
def test_bad_inputs_raise_scene_error_with_site_and_field(data, case):
    name, site, field = bad_cases(data)[case]
    path = data / "bad" / name
    for source in (path, str(path), path.read_text()):
        with pytest.raises(gvd.SceneError) as e:
            gvd.compute(source)
        assert e.value.site == site, (name, str(e.value))
        assert e.value.field == field, (name, str(e.value))
        assert isinstance(e.value, ValueError)


def test_every_kind_through_the_builder():
    s = gvd.Scene([-4, -4, 4, 4], epsilon=1e-3)
    assert s.add_point([0.1, 0.2], id="p") == 0
    s.add_point((3, 3), "lp", p=4)
    s.add_point([-3, 3], "anisotropic", matrix=[[2, 0.5], [0.5, 1]], weight=0.1)
    s.add_point([3, -3], "power", weight=0.3)
    s.add_point([-3.5, -3.5], "moebius", scale=2, weight=0.1)
    s.add_circle([2, 0], 0.3)
    s.add_ellipse([-2, 0], [0.5, 0.2], 0.3)
    s.add_segment([0, -3], [1, -2.5])
    s.add_arc([0, 2.5], 0.4, 0, math.pi / 2)
    s.add_polyline(np.array([[1, 1], [1.5, 1.5], [2, 1]]))
    s.add_polygon([[[-1, -1], [-0.5, -1], [-0.5, -0.5]]])
    s.add_algebraic("x^2 + y^2 - 0.01", clip=[-3, 1, -2, 2])
    s.add_bezier([[2.5, 2], [3, 2.5], [3.5, 2]])
    s.add_bspline(2, [[-3, -2], [-2.5, -1.5], [-2, -2], [-1.5, -1.5]], [0, 0, 0, 0.5, 1, 1, 1])
    s.add_field("(x - 1)^2 + (y + 1)^2")
    s.add_implicit_field("(x + 1)^2 + (y - 1)^2 - (z + 0.1)^2")
    assert len(s) == 16
    assert s.kinds() == ["point"] * 5 + ["circle", "ellipse", "segment", "arc", "polyline", "polygon",
                                         "algebraic", "bezier", "bspline", "field", "implicit_field"]
    back = gvd.Scene.from_json(s.to_json())
    assert back.to_json() == s.to_json()
    assert json.loads(s.to_json())["sites"][0]["id"] == "p"


@pytest.mark.parametrize(
    "add,site,field",
    [
        (lambda s: s.add_point([0.5, float("nan")]), 1, "at"),
        (lambda s: s.add_point([0.5, 0.5], "lp", p=3), 1, "metric.p"),
        (lambda s: s.add_point([0.5, 0.5], "lp"), 1, "metric.p"),
        (lambda s: s.add_point([0.5, 0.5], "lp", p=-2), 1, "metric.p"),
        (lambda s: s.add_point([0.5, 0.5], "anisotropic", matrix=[[1, 0], [0, -1]]), 1, "metric.matrix"),
        (lambda s: s.add_point([0.5, 0.5], "taxicab"), 1, "metric.kind"),
        (lambda s: s.add_point("here"), 1, "at"),
        (lambda s: s.add_segment([0.2, 0.2], [0.2, 0.2]), 1, "to"),
        (lambda s: s.add_polygon([[[0, 0], [1, 1]]]), 1, "rings"),
        (lambda s: s.add_polygon([[[0, 0, 0], [1, 1, 1]]]), 1, "rings[0]"),
        (lambda s: s.add_polyline([[0, 0]]), 1, "points"),
        (lambda s: s.add_circle([0.5, 0.5], -1), 1, "radius"),
        (lambda s: s.add_algebraic("x^^2"), 1, "equation"),
        (lambda s: s.add_field("x +* y"), 1, "equation"),
    ],
)
def test_builder_refusals_name_site_and_field(add, site, field):
    s = gvd.Scene([0, 0, 1, 1])
    s.add_point([0.9, 0.9])
    with pytest.raises(gvd.SceneError) as e:
        add(s)
    assert (e.value.site, e.value.field) == (site, field), str(e.value)
    assert str(e.value).startswith(f"site {site} field '{field}'")
    assert len(s) == 1  # the refused site was not added


def test_scene_level_refusals():
    for args, field in [(([0, 0, -1, 1],), "domain"), (([0, 0, 1, 1], 0.0), "epsilon"),
                        (([0, 0, 1, 1], None, "median"), "mode"), ((["a", 0, 1, 1],), "domain")]:
        with pytest.raises(gvd.SceneError) as e:
            gvd.Scene(*args)
        assert e.value.site is None and e.value.field == field


def test_conflicts_and_options():
    s = gvd.Scene([-2, -2, 2, 2])
    s.add_segment([-1, -1], [1, 1])
    s.add_segment([-1, 1], [1, -1])
    crossed = gvd.compute(s)
    assert crossed.stats["split_crossings"] == 1
    with pytest.raises(gvd.SceneError) as e:
        gvd.compute(s, strict=True)
    assert e.value.site == 0 and e.value.other == 1 and e.value.field is None
    ok = gvd.Scene([0, 0, 1, 1])
    ok.add_point([0.5, 0.5])
    with pytest.raises(gvd.OptionError) as e:
        gvd.compute(ok, engine="fast")
    assert e.value.option == "engine"
    with pytest.raises(gvd.SceneError) as e:
        gvd.offset(ok, -1.0)
    assert e.value.field == "distance"
    with pytest.raises(TypeError):
        gvd.compute(42)


def test_unsupported_and_budget():
    s = gvd.Scene([-2, -2, 2, 2])
    s.add_circle([0, 0], 0.5)
    s.add_point([1.5, 1.5])
    with pytest.raises(gvd.UnsupportedError) as e:
        gvd.compute(s, engine="incremental")
    assert e.value.site == 0 and e.value.kind == "circle"
    with pytest.raises(gvd.BudgetError) as e:
        gvd.compute(s, engine="subdivision", max_boxes=10)
    assert e.value.what == "boxes" and e.value.limit == 10


def test_inputs_dict_text_path(tmp_path):
    scene = {"domain": [0, 0, 1, 1], "sites": [{"kind": "point", "at": [0.2, 0.3]},
                                              {"kind": "point", "at": [0.7, 0.6]},
                                              {"kind": "point", "at": [0.3, 0.9]}]}
    p = tmp_path / "s.json"
    p.write_text(json.dumps(scene))
    outs = [gvd.compute(x).to_json() for x in (scene, json.dumps(scene), p, str(p), gvd.read(p))]
    assert all(json.loads(o)["vertices"] == json.loads(outs[0])["vertices"] for o in outs)
    with pytest.warns(UserWarning, match="unknown field .metrc."):
        gvd.compute({"domain": [0, 0, 1, 1], "sites": [{"kind": "point", "at": [0.5, 0.5], "metrc": 1}]})
    with pytest.raises(gvd.OptionError):
        gvd.read(tmp_path / "s.txt")
    with pytest.raises(OSError):
        gvd.read(tmp_path / "missing.json")


def test_mode_and_repr():
    s = gvd.Scene([-2, -2, 2, 2], mode="medial_axis")
    s.add_polygon([[[-1, -1], [1, -1], [1, 1], [-1, 1]]], id="square")
    d = gvd.compute(s)
    assert "medial_axis" in repr(d) and "1 sites" in repr(s)
    assert d.site_ids == ["square"]
    # the medial axis of a square: its two diagonals, clearance 1 at the centre
    assert np.isclose(d.clearances.max(), 1.0)
    assert d.verify(grid=128)
    assert gvd.compute(s.with_mode("voronoi")).stats["engine"] == "incremental"


def _slow_scene():
    """8,000 lp points at epsilon 1e-6: seconds in the subdivision engine."""
    rng = random.Random(1)
    s = gvd.Scene([0, 0, 1, 1], 1e-6)
    for _ in range(8000):
        s.add_point([rng.random(), rng.random()], "lp", p=4)
    return s


def test_timeout_stops_the_run():
    s = _slow_scene()
    start = time.monotonic()
    with pytest.raises(gvd.BudgetError) as e:
        gvd.compute(s, engine="subdivision", timeout=0.01)
    assert e.value.what == "seconds"
    # the whole run takes seconds; a stop within 2 s, on a loaded 2-core machine too
    assert time.monotonic() - start < 2.0
    with pytest.raises(gvd.OptionError) as e:
        gvd.compute(s, timeout=0.0)
    assert e.value.option == "timeout"


def test_ctrl_c_stops_the_run():
    s = _slow_scene()
    threading.Timer(0.02, _thread.interrupt_main).start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        gvd.compute(s, engine="subdivision")
    # the signal also raises once the run is over: only a stop well before its end shows
    # that the run itself was cancelled
    assert time.monotonic() - start < 1.0


def test_pruning_the_medial_axis():
    # a square with a small slot in one side: the slot's branch goes at lambda 0.1
    s = gvd.Scene([-2, -2, 2, 2], mode="medial_axis")
    s.add_polygon([[[-1, -1], [-0.05, -1], [-0.05, -1.1], [0.05, -1.1], [0.05, -1], [1, -1], [1, 1], [-1, 1]]])
    whole = gvd.compute(s)
    pruned = gvd.compute(s, prune_lambda=0.1)
    assert pruned.stats["pruning"]["edges_before"] == len(whole.edges)
    assert len(pruned.edge_offsets) < len(whole.edge_offsets)
    assert (pruned.edge_points[:, 1] > -1 + 1e-9).all()
    assert (whole.edge_points[:, 1] < -1).any()
    with pytest.raises(gvd.OptionError):
        gvd.compute(s, prune_angle=0.0)
