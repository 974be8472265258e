//! `gvd bench implicit`: circles (closed form and implicit path) and ellipses (implicit
//! bounds) beside Euclidean point scenes of the same size, one core and all cores.

use crate::bench::Rng;
use gvd::geom::{Aabb, Point};
use gvd::internals::SiteField;
use gvd::scene::{Metric, Mode, Scene, Site, SiteKind};
use gvd::FieldOptions;
use std::time::Instant;

fn scene(sites: Vec<SiteKind>) -> Scene {
    Scene::new(
        Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
        0.001,
        Mode::Voronoi,
        sites
            .into_iter()
            .map(|kind| Site { id: None, kind })
            .collect(),
    )
    .expect("a valid scene")
}

/// `n` disjoint shapes of reach `size(rng)` in [-2,2]² on a jittered grid (one per cell).
fn disjoint(n: usize, seed: u64, mut make: impl FnMut(Point, f64, &mut Rng) -> SiteKind) -> Scene {
    let mut rng = Rng(seed);
    let k = (n as f64).sqrt().ceil() as usize;
    let cell = 4.0 / k as f64;
    let mut cells: Vec<usize> = (0..k * k).collect();
    // a deterministic shuffle, then the first n cells
    for i in (1..cells.len()).rev() {
        let j = (rng.next_f64() * (i + 1) as f64) as usize;
        cells.swap(i, j.min(i));
    }
    let sites = cells[..n]
        .iter()
        .map(|&c| {
            let reach = cell * rng.range(0.1, 0.4);
            let slack = 0.5 * cell - reach;
            let centre = Point::new(
                -2.0 + cell * ((c % k) as f64 + 0.5) + rng.range(-slack, slack),
                -2.0 + cell * ((c / k) as f64 + 0.5) + rng.range(-slack, slack),
            );
            make(centre, reach, &mut rng)
        })
        .collect();
    scene(sites)
}

fn circles(n: usize, seed: u64) -> Scene {
    disjoint(n, seed, |center, reach, _| SiteKind::Circle {
        center,
        radius: reach,
    })
}

fn ellipses(n: usize, seed: u64) -> Scene {
    disjoint(n, seed, |center, reach, rng| SiteKind::Ellipse {
        center,
        semi_axes: [reach, reach * rng.range(0.3, 0.9)],
        rotation: rng.range(0.0, std::f64::consts::PI),
    })
}

fn points(n: usize, seed: u64) -> Scene {
    let mut rng = Rng(seed);
    scene(
        (0..n)
            .map(|_| SiteKind::Point {
                at: Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
                metric: Metric::Euclidean,
            })
            .collect(),
    )
}

/// Best seconds over `repeat` runs and the box count, through the subdivision engine.
fn time(scene: &Scene, fields: FieldOptions, parallel: bool, repeat: usize) -> (f64, u64) {
    let mut best = f64::INFINITY;
    let mut boxes = 0;
    for _ in 0..repeat {
        let t = Instant::now();
        let f = SiteField::for_scene_with(scene, &fields).expect("benchmark scenes are valid");
        let params =
            gvd::internals::SubdivisionParams::for_scene(scene, None, parallel, Default::default());
        let out = gvd::internals::subdivide(&f, &params).expect("benchmark scenes fit the limits");
        best = best.min(t.elapsed().as_secs_f64());
        boxes = out
            .complex
            .stats
            .get("boxes")
            .and_then(|v| v.as_u64())
            .unwrap_or(0);
    }
    (best, boxes)
}

pub fn implicit(large: bool, repeat: usize) {
    let threads = rayon::current_num_threads();
    println!("Implicit fields (Emiris et al. 2013, §3): random disjoint sites in [-2,2]^2, epsilon 0.001");
    println!(
        "seconds: best of {repeat} (1 for n >= 10000); 1 core vs {threads} threads; boxes = leaves with >= 2 sites"
    );
    println!(
        "{:<26} {:>6} | {:>9} {:>9} {:>7} | {:>8}",
        "scene", "n", "1 core s", "all s", "speedup", "boxes"
    );
    let closed = FieldOptions::default();
    let implicit_circles = FieldOptions {
        implicit_circles: true,
        ..Default::default()
    };
    let row = |name: &str, sc: &Scene, opts: FieldOptions, rep: usize| {
        let (t1, boxes) = time(sc, opts, false, rep);
        let (tn, _) = time(sc, opts, true, rep);
        println!(
            "{:<26} {:>6} | {:>9.3} {:>9.3} {:>6.2}x | {:>8}",
            name,
            sc.sites().len(),
            t1,
            tn,
            t1 / tn,
            boxes
        );
    };
    let mut sizes = vec![100, 1000];
    if large {
        sizes.push(10_000);
    }
    for n in sizes {
        let rep = if n >= 10_000 { 1 } else { repeat };
        let c = circles(n, 7 + n as u64);
        row("circles (closed form)", &c, closed, rep);
        row("circles (implicit path)", &c, implicit_circles, rep);
        row("points (Euclidean)", &points(n, 11 + n as u64), closed, rep);
    }
    for n in [20, 200] {
        row(
            "ellipses (implicit)",
            &ellipses(n, 13 + n as u64),
            closed,
            repeat,
        );
        row(
            "points (Euclidean)",
            &points(n, 17 + n as u64),
            closed,
            repeat,
        );
    }
    if !large {
        println!("(add --large for circles n = 10000)");
    }
}
