//! Stopping a run from outside (`Options::control`, issue 15): for every engine, a run
//! cancelled from another thread in the middle of its main loop ends promptly with
//! `Error::Cancelled`; a time limit ends a run with the "timed out" budget error; and
//! the progress callback sees increasing counts within each stage.

use gvd::{compute, Control, Engine, Error, Metric, Mode, Options, Progress, Scene, Site};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

fn domain() -> gvd::Aabb {
    gvd::Aabb::from_array([-1.0, -1.0, 1.0, 1.0])
}

/// A little linear congruential generator: the same scenes on every run.
fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 1.8 - 0.9
}

/// Euclidean points (the incremental point engine).
fn points(n: usize) -> Scene {
    let mut seed = 7;
    let sites = (0..n)
        .map(|_| Site::point([lcg(&mut seed), lcg(&mut seed)]))
        .collect();
    Scene::new(domain(), 1e-3, Mode::Voronoi, sites).unwrap()
}

/// Short horizontal segments on a grid, none touching (the incremental segment engine;
/// the soft-predicate engine with `Engine::Subdivision`).
fn segments(side: usize) -> Scene {
    let step = 1.8 / side as f64;
    let mut sites = Vec::new();
    for i in 0..side {
        for j in 0..side {
            let (x, y) = (-0.9 + step * i as f64, -0.9 + step * (j as f64 + 0.3));
            sites.push(Site::segment([x, y], [x + 0.6 * step, y + 0.1 * step]));
        }
    }
    Scene::new(domain(), 1e-4, Mode::Voronoi, sites).unwrap()
}

/// lp4 points (the distance-field subdivision engine).
fn lp_points(n: usize) -> Scene {
    let mut seed = 11;
    let sites = (0..n)
        .map(|_| Site::point_with([lcg(&mut seed), lcg(&mut seed)], Metric::Lp { p: 4 }))
        .collect();
    Scene::new(domain(), 1e-6, Mode::Voronoi, sites).unwrap()
}

/// Closed B-splines (the free-form engine).
fn freeform() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/freeform/freeform-closed6-voronoi.json");
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Runs `scene` with a progress callback that, at its first report of `stage` with
/// some work done, waits until another thread has set the cancel flag. Returns the
/// result, the time from the flag to the end of the run, and the reports seen.
fn cancel_mid_run(
    scene: &Scene,
    engine: Engine,
    stage: &'static str,
) -> (Result<gvd::VoronoiComplex, Error>, Duration, Vec<Progress>) {
    let flag = Arc::new(AtomicBool::new(false));
    let seen = Arc::new(Mutex::new(Vec::new()));
    let (ask, asked) = mpsc::channel::<()>();
    let (done, set) = mpsc::channel::<Instant>();
    let set = Mutex::new(set);
    let canceller = {
        let flag = flag.clone();
        std::thread::spawn(move || {
            if asked.recv().is_ok() {
                flag.store(true, Ordering::Relaxed);
                let _ = done.send(Instant::now());
            }
        })
    };
    let ask = Mutex::new(Some(ask));
    let record = seen.clone();
    let set_at = Arc::new(Mutex::new(None));
    let set_at2 = set_at.clone();
    let progress = move |p: &Progress| {
        record.lock().unwrap().push(*p);
        if p.stage == stage && p.done > 0 {
            if let Some(ask) = ask.lock().unwrap().take() {
                ask.send(()).unwrap();
                let at = set.lock().unwrap().recv().unwrap();
                *set_at2.lock().unwrap() = Some(at);
            }
        }
    };
    let options = Options {
        engine,
        control: Control {
            cancel: Some(flag),
            progress: Some(Arc::new(progress)),
            ..Default::default()
        },
        ..Default::default()
    };
    let result = compute(scene, &options);
    let end = Instant::now();
    drop(options);
    canceller.join().unwrap();
    let at = set_at.lock().unwrap().expect("the run reached the stage");
    let seen = seen.lock().unwrap().clone();
    (result, end - at, seen)
}

/// Checks a run cancelled mid-way: `Error::Cancelled` within a second of the flag, and
/// increasing counts within each stage before.
fn assert_cancelled(scene: &Scene, engine: Engine, stage: &'static str) {
    let (result, after, seen) = cancel_mid_run(scene, engine, stage);
    assert_eq!(result.err(), Some(Error::Cancelled), "{engine:?}");
    assert!(after < Duration::from_secs(1), "{engine:?}: {after:?}");
    for w in seen.windows(2) {
        if w[0].stage == w[1].stage {
            assert!(w[0].done < w[1].done, "{engine:?}: {w:?}");
        }
    }
}

#[test]
fn incremental_points_are_cancelled_mid_run() {
    assert_cancelled(&points(100_000), Engine::Incremental, "points");
}

#[test]
fn incremental_segments_are_cancelled_mid_run() {
    assert_cancelled(&segments(60), Engine::Incremental, "segments and arcs");
}

#[test]
fn distance_field_subdivision_is_cancelled_mid_run() {
    assert_cancelled(&lp_points(400), Engine::Subdivision, "boxes");
}

#[test]
fn soft_predicate_subdivision_is_cancelled_mid_run() {
    assert_cancelled(&segments(30), Engine::Subdivision, "boxes");
}

#[test]
fn freeform_is_cancelled_mid_run() {
    assert_cancelled(&freeform(), Engine::Freeform, "pairs");
}

#[test]
fn a_flag_set_before_the_run_cancels_it_at_once() {
    let options = Options {
        control: Control {
            cancel: Some(Arc::new(AtomicBool::new(true))),
            ..Default::default()
        },
        ..Default::default()
    };
    for (scene, engine) in [
        (points(5000), Engine::Incremental),
        (segments(10), Engine::Incremental),
        (segments(10), Engine::Subdivision),
        (lp_points(20), Engine::Subdivision),
        (freeform(), Engine::Freeform),
    ] {
        let o = Options {
            engine,
            ..options.clone()
        };
        assert_eq!(
            compute(&scene, &o).err(),
            Some(Error::Cancelled),
            "{engine:?}"
        );
    }
}

#[test]
fn a_time_limit_ends_a_long_run_with_a_clear_error() {
    let options = Options {
        engine: Engine::Subdivision,
        control: Control {
            timeout: Some(Duration::from_millis(30)),
            ..Default::default()
        },
        ..Default::default()
    };
    let start = Instant::now();
    let e = compute(&lp_points(400), &options).unwrap_err();
    assert!(
        start.elapsed() < Duration::from_secs(2),
        "{:?}",
        start.elapsed()
    );
    match &e {
        Error::Budget { what, .. } => assert_eq!(what, "seconds"),
        other => panic!("expected the time budget, got {other:?}"),
    }
    assert!(
        e.to_string()
            .contains("timed out after 0.03 s; raise --timeout"),
        "{e}"
    );
    let zero = Options {
        control: Control {
            timeout: Some(Duration::ZERO),
            ..Default::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        compute(&points(3), &zero),
        Err(Error::InvalidOption { .. })
    ));
}

#[test]
fn progress_counts_increase_and_a_watched_run_gives_the_same_diagram() {
    let scene = points(20_000);
    let plain = compute(&scene, &Options::default()).unwrap();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let record = seen.clone();
    let options = Options {
        control: Control {
            progress: Some(Arc::new(move |p: &Progress| {
                record.lock().unwrap().push(*p)
            })),
            timeout: Some(Duration::from_secs(600)),
            ..Default::default()
        },
        ..Default::default()
    };
    let watched = compute(&scene, &options).unwrap();
    assert_eq!(plain.vertices.len(), watched.vertices.len());
    assert_eq!(plain.edges.len(), watched.edges.len());
    let seen = seen.lock().unwrap();
    let counts: Vec<u64> = seen
        .iter()
        .filter(|p| p.stage == "points")
        .map(|p| p.done)
        .collect();
    assert_eq!(seen[0].total, Some(20_000));
    assert!(counts.len() > 20, "{}", counts.len());
    assert!(counts.windows(2).all(|w| w[0] < w[1]));
    assert!(*counts.last().unwrap() <= 20_000);
}
