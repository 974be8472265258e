//! `gvd bench freeform`: the freeform engine (bisectors in parameter space, Hanniel,
//! Ramamurthy, Elber, Kim 2007) on scenes of Bézier and B-spline curves: the whole
//! diagram's time and the time per curve, beside the subdivision engine's on the same
//! scene, against the targets of the table.

use crate::bench::{best_run, Rng};
use gvd::scene::Scene;
use std::f64::consts::PI;
use std::fmt::Write as _;

/// The freeform scenes shipped for the bench: name, text.
const SHIPPED: [(&str, &str); 6] = [
    (
        "bezier4 (medial axis)",
        include_str!("../benches-data/freeform-bezier4-medial_axis.json"),
    ),
    (
        "closed6",
        include_str!("../benches-data/freeform-closed6-voronoi.json"),
    ),
    (
        "convex3",
        include_str!("../benches-data/freeform-convex3-voronoi.json"),
    ),
    (
        "deep concavity (medial axis)",
        include_str!("../benches-data/freeform-deep-concavity-medial_axis.json"),
    ),
    (
        "nonconvex2",
        include_str!("../benches-data/freeform-nonconvex2-voronoi.json"),
    ),
    (
        "piecewise C1 (complex)",
        include_str!("../benches-data/freeform-piecewise-c1-complex.json"),
    ),
];

/// Boxes a subdivision run may visit.
const SUBDIVISION_BOXES: usize = 1_000_000;

/// Targets: seconds per curve, whole diagram of the 5 cubics, whole glyph medial axis.
const PER_CURVE: f64 = 0.020;
const FIVE_CUBICS: f64 = 0.100;
const GLYPH: f64 = 0.200;

/// Which whole-diagram target a scene has besides the per-curve one.
#[derive(Clone, Copy, PartialEq)]
enum Whole {
    None,
    FiveCubics,
    Glyph,
}

fn point(s: &mut String, x: f64, y: f64) {
    let _ = write!(s, "[{x:.6},{y:.6}]");
}

fn points(ps: &[(f64, f64)]) -> String {
    let mut s = String::from("[");
    for (k, &(x, y)) in ps.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        point(&mut s, x, y);
    }
    s.push(']');
    s
}

fn scene_json(domain: [f64; 4], mode: &str, sites: &[String]) -> String {
    format!(
        r#"{{"domain":[{},{},{},{}],"epsilon":0.001,"mode":"{mode}","sites":[{}]}}"#,
        domain[0],
        domain[1],
        domain[2],
        domain[3],
        sites.join(",")
    )
}

/// 5 open cubic Bézier curves, one per unit cell of a row, each an S (its inner
/// control points on either side of its chord, so not convex). SplitMix64 seed 5.
pub fn five_cubics() -> Scene {
    let mut rng = Rng(5);
    let sites: Vec<String> = (0..5)
        .map(|i| {
            let x = i as f64;
            let mut j = |c: f64| c + rng.range(-0.05, 0.05);
            let ps = [
                (x + j(0.15), j(0.5)),
                (x + j(0.4), j(0.85)),
                (x + j(0.6), j(0.15)),
                (x + j(0.85), j(0.5)),
            ];
            format!(r#"{{"kind":"bezier","control_points":{}}}"#, points(&ps))
        })
        .collect();
    Scene::from_json(&scene_json([-0.5, -0.5, 5.5, 1.5], "voronoi", &sites))
        .expect("the five cubics make a valid scene")
}

/// 3 open clamped B-splines of degree 5 with 7 control points, one per unit cell,
/// zigzags with seeded jitter. SplitMix64 seed 3.
pub fn three_quintics() -> Scene {
    let mut rng = Rng(3);
    let sites: Vec<String> = (0..3)
        .map(|i| {
            let x = i as f64;
            let ps: Vec<(f64, f64)> = (0..7)
                .map(|k| {
                    let t = k as f64 / 6.0;
                    let y = if k % 2 == 0 { 0.25 } else { 0.75 };
                    (
                        x + 0.1 + 0.8 * t + rng.range(-0.03, 0.03),
                        y + rng.range(-0.1, 0.1),
                    )
                })
                .collect();
            format!(
                r#"{{"kind":"bspline","degree":5,"control_points":{},"knots":[0,0,0,0,0,0,1,2,2,2,2,2,2]}}"#,
                points(&ps)
            )
        })
        .collect();
    Scene::from_json(&scene_json([-0.5, -0.5, 3.5, 1.5], "voronoi", &sites))
        .expect("the three quintics make a valid scene")
}

/// A closed glyph-like outline r(θ) = 1 + 0.3 cos 5θ of 20 cubic Bézier pieces joined
/// C1 (Hermite, tangents from the derivative), in medial_axis mode.
pub fn glyph() -> Scene {
    const N: usize = 20;
    let h = 2.0 * PI / N as f64;
    let at = |t: f64| {
        let r = 1.0 + 0.3 * (5.0 * t).cos();
        let dr = -1.5 * (5.0 * t).sin();
        let (c, s) = (t.cos(), t.sin());
        ((r * c, r * s), (dr * c - r * s, dr * s + r * c))
    };
    let sites: Vec<String> = (0..N)
        .map(|k| {
            let (p0, d0) = at(k as f64 * h);
            // the last piece ends exactly where the first starts
            let (p1, d1) = at(((k + 1) % N) as f64 * h);
            let ps = [
                p0,
                (p0.0 + h / 3.0 * d0.0, p0.1 + h / 3.0 * d0.1),
                (p1.0 - h / 3.0 * d1.0, p1.1 - h / 3.0 * d1.1),
                p1,
            ];
            format!(r#"{{"kind":"bezier","control_points":{}}}"#, points(&ps))
        })
        .collect();
    Scene::from_json(&scene_json([-2.0, -2.0, 2.0, 2.0], "medial_axis", &sites))
        .expect("the glyph makes a valid scene")
}

fn options(engine: gvd::Engine) -> gvd::Options {
    gvd::Options {
        engine,
        subdivision: gvd::SubdivisionOptions {
            limits: gvd::Limits {
                max_boxes: Some(SUBDIVISION_BOXES),
                ..Default::default()
            },
            ..Default::default()
        },
        parallel: false,
        ..Default::default()
    }
}

fn ms(seconds: f64) -> String {
    format!("{:.1}", seconds * 1e3)
}

/// One row; an error when the freeform engine fails or leaves the diagram empty.
fn row(name: &str, scene: &Scene, whole: Whole, repeat: usize) -> anyhow::Result<()> {
    let curves = scene.sites().len();
    let run = best_run(scene, &options(gvd::Engine::Freeform), repeat, |d| {
        (d.vertices.len(), d.edges.len())
    });
    let (seconds, (vertices, edges)) = match run {
        Ok(r) => r,
        Err(e) => {
            let e = e.to_string();
            println!(
                "{name:<30} {curves:>6} | failed: {} | target missed",
                e.chars().take(100).collect::<String>()
            );
            return Ok(());
        }
    };
    if vertices == 0 && edges == 0 {
        anyhow::bail!("{name}: the freeform engine's diagram is empty");
    }
    let per_curve = seconds / curves.max(1) as f64;
    let subdivision = match best_run(scene, &options(gvd::Engine::Subdivision), repeat, |_| ()) {
        Ok((s, ())) => format!("{} ms", ms(s)),
        Err(e) => {
            let e = e.to_string();
            format!("refused: {}", e.chars().take(40).collect::<String>())
        }
    };
    let verdict = |ok: bool| if ok { "met" } else { "missed" };
    let mut target = format!("<20 ms/curve {}", verdict(per_curve < PER_CURVE));
    match whole {
        Whole::None => {}
        Whole::FiveCubics => {
            let _ = write!(target, ", <100 ms whole {}", verdict(seconds < FIVE_CUBICS));
        }
        Whole::Glyph => {
            let _ = write!(target, ", <200 ms whole {}", verdict(seconds < GLYPH));
        }
    }
    println!(
        "{:<30} {:>6} | {:>10} {:>10} | {:>5} {:>5} | {:<52} | {}",
        name,
        curves,
        ms(seconds),
        ms(per_curve),
        vertices,
        edges,
        subdivision,
        target
    );
    Ok(())
}

/// The table; `quick` runs the shipped scenes only.
pub fn freeform_table(repeat: usize, quick: bool) -> anyhow::Result<()> {
    println!(
        "The freeform engine (bisectors in parameter space, HREK07) on Bézier and B-spline scenes"
    );
    println!(
        "ours: one core, best of {repeat}; per curve = whole diagram / curves (the library has no single-cell entry point);"
    );
    println!(
        "subdivision: the same scene, the same repeats, at most {SUBDIVISION_BOXES} boxes a run"
    );
    println!(
        "{:<30} {:>6} | {:>10} {:>10} | {:>5} {:>5} | {:<52} | target",
        "scene", "curves", "whole ms", "ms/curve", "verts", "edges", "subdivision"
    );
    for (name, text) in SHIPPED {
        let scene = Scene::from_json(text).expect("the shipped freeform scenes are valid");
        row(name, &scene, Whole::None, repeat)?;
    }
    if !quick {
        row(
            "5 cubic Beziers (seed 5)",
            &five_cubics(),
            Whole::FiveCubics,
            repeat,
        )?;
        row(
            "3 quintic B-splines (seed 3)",
            &three_quintics(),
            Whole::None,
            repeat,
        )?;
        row(
            "glyph, 20 cubics (medial axis)",
            &glyph(),
            Whole::Glyph,
            repeat,
        )?;
    }
    println!(
        "paper (Hanniel et al., IRIT on a Pentium 4): seconds to minutes per cell, around ten seconds per medial-axis cell"
    );
    Ok(())
}
