//! Cells of the segment engine (points, segments, arcs, polylines, polygons in
//! `voronoi` mode) and of the soft-predicate engine (segments, polylines, polygons):
//! they tile the domain, and a sampled point lies in the cell of the
//! site nearest to it by an independent brute force (`common::dist`).

mod common;

use gvd::complex::{Cell, Generator};
use gvd::geom::ring::{even_odd_contains, signed_area};
use gvd::{compute, Aabb, Engine, Mode, Options, Point, Scene, Site};

fn area(c: &Cell) -> f64 {
    c.rings.iter().map(|r| signed_area(r)).sum()
}

fn scene_file(name: &str) -> Scene {
    let path = format!(
        "{}/../../examples/scenes/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A square polygon with a square hole, a point site in the hole, a segment and an arc
/// outside: the point's cell is a hole of the polygon's cell.
fn polygon_with_a_hole() -> Scene {
    Scene::new(
        Aabb::from_array([-3.0, -3.0, 3.0, 3.0]),
        1e-4,
        Mode::Voronoi,
        vec![
            Site::polygon([
                vec![[-2.0, -2.0], [1.0, -2.0], [1.0, 1.0], [-2.0, 1.0]],
                vec![[-1.0, -1.0], [-1.0, 0.2], [0.3, 0.2], [0.3, -1.0]],
            ]),
            Site::point([-0.3, -0.5]),
            Site::segment([2.0, -2.5], [2.5, 2.0]),
            Site::arc([-1.0, 2.0], 0.6, 0.3, 2.8),
            Site::polyline([[1.5, 2.8], [2.0, 2.2], [2.8, 2.6]]),
        ],
    )
    .unwrap()
}

/// Checks the cells of `scene`'s diagram by the default engine: one per site with a positive area, areas
/// summing to the domain's, and each of `n × n` sampled points in exactly one cell, the
/// one of its nearest site (samples within `tie` of a tie skipped). Returns the number of
/// samples checked.
fn check_cells(scene: &Scene, n: usize) -> usize {
    check_cells_of(scene, Engine::Auto, n)
}

/// [`check_cells`] of the diagram by `engine`.
fn check_cells_of(scene: &Scene, engine: Engine, n: usize) -> usize {
    let options = Options {
        engine,
        ..Options::default()
    };
    let d = compute(scene, &options).unwrap();
    let domain = scene.domain();
    let whole = domain.width() * domain.height();
    let total: f64 = d.cells.iter().map(area).sum();
    assert!(
        (total - whole).abs() < 1e-9 * whole,
        "cells cover {total} of {whole}"
    );
    assert!(d.cells.windows(2).all(|w| w[0].site < w[1].site));
    for c in &d.cells {
        assert!(signed_area(&c.rings[0]) > 0.0, "cell {}", c.site);
        assert!(area(c) > 0.0, "cell {}", c.site);
    }
    let tie = 10.0 * scene.epsilon();
    let mut checked = 0;
    for i in 0..n {
        for j in 0..n {
            let q = domain.at((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let mut ds: Vec<(f64, usize)> = (0..scene.sites().len())
                .map(|s| (common::dist(scene, &Generator::Site(s), q), s))
                .collect();
            ds.sort_by(|a, b| a.0.total_cmp(&b.0));
            if ds.len() > 1 && ds[1].0 - ds[0].0 < tie {
                continue;
            }
            let holders: Vec<usize> = d
                .cells
                .iter()
                .filter(|c| c.rings.iter().filter(|r| even_odd_contains(r, q)).count() % 2 == 1)
                .map(|c| c.site)
                .collect();
            assert_eq!(holders, [ds[0].1], "sample {q:?}");
            checked += 1;
        }
    }
    checked
}

/// Segments cut from real data that share endpoints (a road network with junctions of
/// degree four, a coastline): every site has its cell. Where a site names a shared end,
/// the other's cell is bounded by its own zone boundary there, and a spur left where a
/// vertex was merged within epsilon must not turn the edges around a vertex.
#[test]
fn segments_sharing_endpoints_each_get_their_cell() {
    for name in [
        "shared-endpoint-84segments.json",
        "shared-endpoint-labels-3segments.json",
        "shared-endpoint-4segments.json",
    ] {
        let path = format!(
            "{}/tests/data/scenes/regressions/{name}",
            env!("CARGO_MANIFEST_DIR")
        );
        let scene = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
        let d = compute(&scene, &Options::default()).unwrap();
        let sites: Vec<usize> = d.cells.iter().map(|c| c.site).collect();
        assert_eq!(
            sites,
            (0..scene.sites().len()).collect::<Vec<_>>(),
            "{name}"
        );
        let checked = check_cells(&scene, 60);
        assert!(checked > 400, "{name}: {checked} samples");
    }
}

#[test]
fn segments_tile_the_domain() {
    assert!(check_cells(&scene_file("segments-0200.json"), 60) > 3000);
}

#[test]
fn arcs_and_points_tile_the_domain() {
    assert!(check_cells(&scene_file("arcs-0030-points-0020.json"), 60) > 3000);
}

#[test]
fn rounded_rectangle_with_a_slot() {
    assert!(check_cells(&scene_file("rounded-rect-slot.json"), 60) > 3000);
}

#[test]
fn a_cell_inside_a_polygon_is_its_hole() {
    let scene = polygon_with_a_hole();
    assert!(check_cells(&scene, 60) > 3000);
    let d = compute(&scene, &Options::default()).unwrap();
    let polygon = &d.cells[0];
    assert_eq!(polygon.site, 0);
    assert_eq!(polygon.rings.len(), 2, "the outer ring and one hole");
    let hole = &polygon.rings[1];
    assert!(signed_area(hole) < 0.0);
    // The hole is the point's cell, which lies inside the polygon's hole (1.3 × 1.2)
    // away from the polygon's boundary.
    let point = d.cells.iter().find(|c| c.site == 1).unwrap();
    assert!(
        (area(point) + signed_area(hole)).abs() < 1e-12,
        "{}",
        area(point)
    );
    assert!(area(point) > 0.1 && area(point) < 1.56);
    assert!(even_odd_contains(hole, Point::new(-0.3, -0.5)));
}

/// The soft-predicate engine (`Engine::Subdivision` on segments, polylines and
/// polygons) gives every site its cell too, a polygon's with the hole where another
/// polygon lies inside it.
#[test]
fn the_soft_engine_tiles_the_domain() {
    assert!(check_cells_of(&scene_file("segments-0200.json"), Engine::Subdivision, 60) > 3000);
    // the polygon with a hole, a triangle in the hole instead of the point, no arc
    let holed = polygon_with_a_hole();
    let mut sites = holed.sites().to_vec();
    sites[1] = Site::polygon([vec![[-0.5, -0.6], [-0.1, -0.6], [-0.3, -0.3]]]);
    sites.remove(3);
    let nested = Scene::new(holed.domain(), holed.epsilon(), Mode::Voronoi, sites).unwrap();
    assert!(check_cells_of(&nested, Engine::Subdivision, 60) > 3000);
}
