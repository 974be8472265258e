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
        let eps = sc.epsilon();
        let d = compute(&sc, &Options::default()).unwrap();
        let mut checked = 0;
        for v in &d.vertices {
            let r = v
                .clearance
                .unwrap_or_else(|| panic!("{name}: vertex without clearance"));
            let want = brute_clearance(&sc, v.at);
            assert!(
                (r - want).abs() <= eps,
                "{name}: vertex {:?}: {r} vs {want}",
                v.at
            );
            checked += 1;
        }
        for e in &d.edges {
            assert_eq!(e.clearance.len(), e.points.len(), "{name}");
            for (&q, &r) in e.points.iter().zip(&e.clearance) {
                let want = brute_clearance(&sc, q);
                assert!(
                    (r - want).abs() <= eps,
                    "{name}: edge point {q:?}: {r} vs {want}"
                );
                checked += 1;
            }
        }
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
