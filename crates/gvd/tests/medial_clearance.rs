//! The clearance written at vertices and edge points in `complex` and `medial_axis`
//! modes, and the largest inscribed circle, against brute force: the least distance
//! from the point to every boundary segment of the scene, computed here.

mod common;

use common::{arc_dist, features, inside_polygon, seg_dist};
use gvd::geom::Point;
use gvd::scene::SiteKind;
use gvd::{compute, Options, Scene};

fn scene(name: &str) -> Scene {
    let path = format!("{}/tests/data/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The least distance from `q` to the sites' boundaries: to every corner and edge of
/// segments, polylines and polygons (a polygon's inside is not at distance 0 here), and
/// to arcs.
fn brute_clearance(sc: &Scene, q: Point) -> f64 {
    sc.sites()
        .iter()
        .map(|site| match site.kind {
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => arc_dist(q, center, radius, start_angle, end_angle),
            ref kind => {
                let (pts, edges) = features(kind);
                let corners = pts.iter().map(|p| q.dist(*p));
                let sides = edges.iter().map(|&(a, b)| seg_dist(q, pts[a], pts[b]));
                corners.chain(sides).fold(f64::INFINITY, f64::min)
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Asserts that every vertex's clearance and that of every `step`-th point of every
/// edge is `brute(scene, point)` within epsilon; returns how many were checked.
fn assert_clearances(
    name: &str,
    sc: &Scene,
    d: &gvd::VoronoiComplex,
    brute: fn(&Scene, Point) -> f64,
    step: usize,
) -> usize {
    let eps = sc.epsilon();
    let mut checked = 0;
    for v in &d.vertices {
        let r = v
            .clearance
            .unwrap_or_else(|| panic!("{name}: vertex without clearance"));
        let want = brute(sc, v.at);
        assert!(
            (r - want).abs() <= eps,
            "{name}: vertex {:?}: {r} vs {want}",
            v.at
        );
        checked += 1;
    }
    for e in &d.edges {
        assert_eq!(e.clearance.len(), e.points.len(), "{name}");
        for (&q, &r) in e.points.iter().zip(&e.clearance).step_by(step) {
            let want = brute(sc, q);
            assert!(
                (r - want).abs() <= eps,
                "{name}: edge point {q:?}: {r} vs {want}"
            );
            checked += 1;
        }
    }
    checked
}

#[test]
fn every_clearance_is_the_distance_to_the_boundary() {
    for name in [
        "polygon-bugtrap-medial_axis.json",
        "polygon-holes2-medial_axis.json",
        "polygon-star50-medial_axis.json",
        "polygon-bugtrap-complex.json",
        "polyline-zigzag-complex.json",
        "arcs-0030-points-0020-complex.json",
    ] {
        let sc = scene(name);
        let d = compute(&sc, &Options::default()).unwrap();
        let checked = assert_clearances(name, &sc, &d, brute_clearance, 1);
        assert!(checked > 20, "{name}: only {checked} points");
    }
}

#[test]
fn voronoi_mode_writes_no_clearance() {
    let sc = scene("polygons-convex5-voronoi.json");
    let d = compute(&sc, &Options::default()).unwrap();
    assert!(d.vertices.iter().all(|v| v.clearance.is_none()));
    assert!(d.edges.iter().all(|e| e.clearance.is_empty()));
    assert!(!d.stats.contains_key("max_inscribed_circle"));
}

/// A `w × h` rectangle (w > h) has the inscribed circle of radius h/2, anywhere on the
/// middle of its medial axis.
#[test]
fn rectangle_inscribed_circle_has_half_its_height() {
    let text = r#"{"domain":[-1,-1,5,3],"epsilon":1e-4,"mode":"medial_axis",
        "sites":[{"kind":"polygon","rings":[[[0,0],[4,0],[4,2],[0,2]]]}]}"#;
    let sc = Scene::from_json(text).unwrap();
    let d = compute(&sc, &Options::default()).unwrap();
    let (c, r) = d.max_inscribed_circle().unwrap();
    assert!((r - 1.0).abs() <= 1e-4, "{r}");
    assert!(
        (c.y - 1.0).abs() <= 1e-4 && (1.0 - 1e-4..=3.0 + 1e-4).contains(&c.x),
        "{c:?}"
    );
    let stat = &d.stats["max_inscribed_circle"];
    assert_eq!(stat["radius"].as_f64(), Some(r));
}

/// The largest inscribed circle is the maximum of the distance to the boundary over the
/// inside: no grid point inside does better, and the best grid point is close.
#[test]
fn inscribed_circle_is_the_maximum_over_a_grid() {
    for name in [
        "polygon-bugtrap-medial_axis.json",
        "polygon-holes2-medial_axis.json",
        "polygon-star50-medial_axis.json",
    ] {
        let sc = scene(name);
        let eps = sc.epsilon();
        let rings: Vec<Vec<Point>> = sc
            .sites()
            .iter()
            .flat_map(|s| match &s.kind {
                SiteKind::Polygon { rings } => rings.clone(),
                _ => Vec::new(),
            })
            .collect();
        let d = compute(&sc, &Options::default()).unwrap();
        let (c, r) = d.max_inscribed_circle().unwrap();
        assert!((brute_clearance(&sc, c) - r).abs() <= eps, "{name}");
        assert!(inside_polygon(c, &rings), "{name}: centre {c:?} outside");
        let b = sc.domain();
        let n = 300;
        let step = ((b.max.x - b.min.x) / n as f64).max((b.max.y - b.min.y) / n as f64);
        let mut best = 0.0f64;
        for i in 0..=n {
            for j in 0..=n {
                let q = Point::new(b.min.x + i as f64 * step, b.min.y + j as f64 * step);
                if inside_polygon(q, &rings) {
                    best = best.max(brute_clearance(&sc, q));
                }
            }
        }
        assert!(best <= r + eps, "{name}: grid {best} beats {r}");
        assert!(
            best >= r - step,
            "{name}: grid {best} far below {r} (step {step})"
        );
    }
}

/// The picture colours the axis by clearance (one `line` per polyline step, with a
/// legend) and, when asked, draws one disc per vertex off the boundary.
#[test]
fn the_picture_colours_the_axis_and_draws_the_discs() {
    use gvd::io::svg::{render_svg, SvgOptions};
    let sc = scene("polygon-bugtrap-medial_axis.json");
    let d = compute(&sc, &Options::default()).unwrap();
    let steps: usize = d.edges.iter().map(|e| e.points.len() - 1).sum();
    let plain = render_svg(&sc, &d, &SvgOptions::default());
    assert_eq!(plain.matches("<line ").count(), steps);
    assert!(plain.contains("clearance-legend"));
    assert!(!plain.contains("id=\"discs\""));
    let opts = SvgOptions {
        discs: true,
        ..Default::default()
    };
    let with_discs = render_svg(&sc, &d, &opts);
    let discs = &with_discs[with_discs.find("id=\"discs\"").unwrap()..];
    let discs = &discs[..discs.find("</g>").unwrap()];
    let inside = d
        .vertices
        .iter()
        .filter(|v| v.clearance > Some(0.0))
        .count();
    assert!(inside > 10);
    assert_eq!(discs.matches("<circle ").count(), inside);
}

/// The least distance from `q` to the scene's Bézier and B-spline curves.
fn brute_curve_distance(sc: &Scene, q: Point) -> f64 {
    sc.sites()
        .iter()
        .map(|site| q.dist(brute_curve_foot(&site.kind, q)))
        .fold(f64::INFINITY, f64::min)
}

/// The nearest point to `q` of a Bézier or B-spline curve, by dense sampling (2,000
/// points per control point) and a golden-section refinement about the best sample:
/// independent of the engine's certified foot-point search.
fn brute_curve_foot(kind: &SiteKind, q: Point) -> Point {
    use gvd::geom::bspline::RationalBspline;
    let curve = match kind {
        SiteKind::Bezier {
            control_points,
            weights,
        } => RationalBspline::bezier(control_points, weights.as_deref()),
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            ..
        } => RationalBspline::new(*degree, control_points, knots, weights.as_deref()),
        _ => panic!("free-form scenes only"),
    };
    let (lo, hi) = curve.domain();
    let n = 2000 * control_points_of(kind);
    let step = (hi - lo) / n as f64;
    let (mut at, mut d) = (lo, f64::INFINITY);
    for k in 0..=n {
        let t = lo + step * k as f64;
        let dk = curve.eval(t).dist(q);
        if dk < d {
            (at, d) = (t, dk);
        }
    }
    let (mut a, mut b) = ((at - step).max(lo), (at + step).min(hi));
    for _ in 0..60 {
        let (m1, m2) = (a + (b - a) * 0.382, a + (b - a) * 0.618);
        if curve.eval(m1).dist(q) < curve.eval(m2).dist(q) {
            b = m2;
        } else {
            a = m1;
        }
    }
    let refined = curve.eval(0.5 * (a + b));
    if refined.dist(q) < d {
        refined
    } else {
        curve.eval(at)
    }
}

fn control_points_of(kind: &SiteKind) -> usize {
    match kind {
        SiteKind::Bezier { control_points, .. } | SiteKind::Bspline { control_points, .. } => {
            control_points.len()
        }
        _ => 1,
    }
}

/// Free-form curves in `medial_axis` and `complex` modes: every vertex's and edge
/// point's clearance is the distance to the curves, by brute force.
#[test]
fn free_form_clearances_are_the_distance_to_the_curves() {
    for name in [
        "freeform-bezier4-medial_axis.json",
        "freeform-deep-concavity-medial_axis.json",
        "freeform-piecewise-c1-complex.json",
    ] {
        let path = format!("{}/tests/data/freeform/{name}", env!("CARGO_MANIFEST_DIR"));
        let sc = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
        let d = compute(&sc, &Options::default()).unwrap();
        let checked = assert_clearances(name, &sc, &d, brute_curve_distance, 3);
        assert!(checked > 10, "{name}: only {checked} points");
    }
}

/// Pruning a medial axis bounded by four Bézier curves at λ: where a corner branch is
/// cut, the cut end's two nearest curve points (by brute force) are 2λ apart.
#[test]
fn pruning_a_free_form_medial_axis_cuts_at_two_lambda() {
    let path = format!(
        "{}/tests/data/freeform/freeform-bezier4-medial_axis.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let sc = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let lambda = 0.2;
    let options = Options {
        prune: gvd::Pruning {
            lambda: Some(lambda),
            object_angle: None,
        },
        ..Default::default()
    };
    let d = compute(&sc, &options).unwrap();
    d.check_invariants().unwrap();
    assert_eq!(d.stats["pruning"]["cut_ends"], 4);
    let cut_ends: Vec<_> = d.vertices.iter().filter(|v| v.sites.len() == 2).collect();
    assert_eq!(cut_ends.len(), 4);
    for v in cut_ends {
        let [f1, f2] = [0, 1].map(|k| brute_curve_foot(&sc.sites()[v.sites[k].site()].kind, v.at));
        let gap = f1.dist(f2);
        assert!(
            gap >= 2.0 * lambda - 1e-6 && gap <= 2.0 * lambda + sc.epsilon(),
            "cut at {:?}: feet {gap} apart",
            v.at
        );
    }
}
