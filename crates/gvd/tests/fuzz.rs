//! Structured fuzzing (issue 15, docs/FUZZING.md): proptest drives the scene reader with
//! mutated JSON, `compute` with small random scenes of every kind and random options,
//! `verify` with mutated diagrams and `offset` with random distances. Every call must
//! end, in bounded time, with `Ok` or an `Error` (never a panic, a hang or an abort);
//! an `Error` of an engine must not be an `Internal` one unless the scene is hostile.
//!
//! `GVD_FUZZ_CASES` sets the number of cases of each target (default 48: some seconds
//! in `cargo test --release`), and `GVD_FUZZ_RUN_SEED` the runner's seed (default 1, so
//! that CI reruns the same cases; `random` draws a fresh one);
//! docs/FUZZING.md gives the long runs made by hand.

use gvd::verify::{verify, VerifyOptions};
use gvd::{
    compute, offset, Aabb, Control, Engine, Error, Limits, Metric, Mode, Options, Scene, Site,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use serde_json::Value;
use std::time::{Duration, Instant};

/// The longest any one call may take: the time limit given to `compute` plus the
/// phases that run after the engines' main loops, or `verify`'s capped sampling (some
/// 4 s for a few arcs at epsilon 1e-6), on a loaded machine.
const MAX_CALL: Duration = Duration::from_secs(20);

fn config() -> Config {
    let cases = std::env::var("GVD_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(48);
    let rng_seed = match std::env::var("GVD_FUZZ_RUN_SEED").as_deref() {
        Ok("random") => RngSeed::Random,
        Ok(seed) => RngSeed::Fixed(
            seed.parse()
                .expect("GVD_FUZZ_RUN_SEED: an integer or `random`"),
        ),
        Err(_) => RngSeed::Fixed(1),
    };
    eprintln!("GVD_FUZZ_RUN_SEED={rng_seed:?} GVD_FUZZ_CASES={cases}");
    Config {
        cases,
        rng_seed,
        // a failing case is reported as found: shrinking reruns slow scenes
        max_shrink_iters: 64,
        failure_persistence: None,
        ..Config::default()
    }
}

/// Numbers a hostile user tries.
const HOSTILE: [f64; 16] = [
    0.0, -0.0, 1e-300, -1e-300, 1e-150, 1e150, 1e300, -1e300, 1e308, -1e308, 5e-324, 1e15, 1e-15,
    4.0, -1.0, 0.5,
];

/// A small deterministic generator for the mutations (seeded by proptest).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 11
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        self.next() as f64 / (1u64 << 53) as f64
    }
}

/// One random change to `v`: a number scaled by 1e±150/1e±300 or replaced by a hostile
/// one, a key deleted or duplicated under another name, an array element deleted or
/// duplicated, a value given another type.
fn mutate(v: &mut Value, rng: &mut Rng) {
    match v {
        Value::Number(_) => {
            let x = v.as_f64().unwrap_or(0.0);
            let y = match rng.below(4) {
                0 => HOSTILE[rng.below(HOSTILE.len())],
                1 => x * [1e150, 1e-150, 1e300, 1e-300][rng.below(4)],
                2 => x + 1e15,
                _ => -x,
            };
            *v = serde_json::Number::from_f64(y).map_or(Value::Null, Value::Number);
        }
        Value::Array(a) if !a.is_empty() => {
            let i = rng.below(a.len());
            match rng.below(6) {
                0 => {
                    a.remove(i);
                }
                1 => {
                    let e = a[i].clone();
                    a.insert(i, e);
                }
                2 => a[i] = Value::String("x".into()),
                _ => mutate(&mut a[i], rng),
            }
        }
        Value::Object(o) if !o.is_empty() => {
            let keys: Vec<String> = o.keys().cloned().collect();
            let k = &keys[rng.below(keys.len())];
            match rng.below(6) {
                0 => {
                    o.remove(k);
                }
                1 => {
                    o.insert(k.clone(), Value::Null);
                }
                2 => {
                    o.insert(k.clone(), Value::Array(Vec::new()));
                }
                _ => {
                    if let Some(e) = o.get_mut(k) {
                        mutate(e, rng);
                    }
                }
            }
        }
        Value::String(s) => {
            *s = match rng.below(4) {
                0 => String::new(),
                1 => s.repeat(3),
                2 => "(x+y+1)^64".into(),
                _ => format!("{s}^2"),
            }
        }
        _ => *v = Value::from(HOSTILE[rng.below(HOSTILE.len())]),
    }
}

/// A text-level change: numbers JSON cannot hold as f64, cuts, stray bytes, nesting.
fn mutate_text(text: &str, rng: &mut Rng) -> String {
    let mut t = text.to_string();
    let at = |t: &str, rng: &mut Rng| {
        let mut i = rng.below(t.len() + 1);
        while !t.is_char_boundary(i) {
            i -= 1;
        }
        i
    };
    match rng.below(5) {
        0 => t.truncate(at(&t, rng)),
        1 => {
            let i = at(&t, rng);
            t.insert_str(
                i,
                ["1e400", "-1e999", "NaN", "\"", "[", "}", "\u{0}"][rng.below(7)],
            );
        }
        2 => t = t.replacen("0.", "1e-400", 1 + rng.below(3)),
        3 => t = format!("{}{t}{}", "[".repeat(200_000), "]".repeat(200_000)),
        _ => {}
    }
    t
}

/// The scenes the reader fuzzing starts from: one of each family of kinds.
const SEEDS: [&str; 8] = [
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"sites":[{"kind":"point","at":[0.5,0.1]},{"kind":"point","at":[-0.5,0.3],"metric":{"kind":"lp","p":4}},{"kind":"point","at":[0,-1],"metric":{"kind":"power","weight":0.2}}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"sites":[{"kind":"circle","center":[0.5,0.5],"radius":0.3},{"kind":"ellipse","center":[-0.7,-0.5],"semi_axes":[0.4,0.2],"rotation":0.3}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"mode":"complex","sites":[{"kind":"segment","from":[-1,-1],"to":[1,-1]},{"kind":"polyline","points":[[-1,0],[0,0.5],[1,0]]},{"kind":"arc","center":[0,1],"radius":0.4,"start_angle":0,"end_angle":3}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"mode":"medial_axis","sites":[{"kind":"polygon","rings":[[[-1,-1],[1,-1],[1,1],[-1,1]],[[-0.2,-0.2],[0.2,-0.2],[0,0.2]]]}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.0078125,"sites":[{"kind":"algebraic","equation":"(x^2 + y^2 - 1)^3 + 27*x^2*y^2"},{"kind":"point","at":[1.5,1.4]}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"sites":[{"kind":"field","equation":"(x-1)^2+y^2"},{"kind":"implicit_field","equation":"z^2-(x+1)^2-y^2"}]}"#,
    r#"{"domain":[-2,-2,2,2],"epsilon":0.001,"sites":[{"kind":"bezier","control_points":[[-1,-1],[0,1],[1,-1]]},{"kind":"bspline","degree":2,"control_points":[[-1,1.2],[0,1.8],[1,1.2],[1.5,1.5]],"knots":[0,0,0,0.5,1,1,1]}]}"#,
    r#"{"domain":[-1,-1,1,1],"epsilon":0.001,"sites":[{"kind":"point","at":[0.1,0.2],"metric":{"kind":"anisotropic","matrix":[[2,0.5],[0.5,1]],"weight":0}},{"kind":"point","at":[-0.3,0.1],"metric":{"kind":"moebius","scale":2,"weight":0.1}}]}"#,
];

/// Options for one run: any engine, odd box sizes and limits, with a time limit.
fn options(rng: &mut Rng) -> Options {
    let mut o = Options {
        engine: [
            Engine::Auto,
            Engine::Subdivision,
            Engine::Incremental,
            Engine::Freeform,
        ][rng.below(4)],
        parallel: rng.below(2) == 0,
        control: Control {
            timeout: Some(Duration::from_secs(2)),
            ..Default::default()
        },
        ..Default::default()
    };
    o.subdivision.max_box = [
        None,
        None,
        Some(0.25),
        Some(1e-7),
        Some(f64::NAN),
        Some(-1.0),
    ][rng.below(6)];
    o.subdivision.limits = Limits {
        max_boxes: [None, Some(1), Some(5000)][rng.below(3)],
        max_points: [None, Some(1), Some(5000)][rng.below(3)],
    };
    o.incremental.bisectors = rng.below(3) == 0;
    o
}

/// Runs `f`, which must end within [`MAX_CALL`] (else the failure shows `scene`).
fn timed<T>(what: &str, scene: Option<&Scene>, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let r = f();
    let t = start.elapsed();
    let shown = || scene.map(gvd::io::json::write_scene).unwrap_or_default();
    assert!(t < MAX_CALL, "{what} took {t:?} on {}", shown());
    r
}

/// Computes, verifies and offsets a scene that validation accepted: each step ends in
/// time with `Ok` or an `Error`.
fn exercise(scene: &Scene, rng: &mut Rng) {
    let opts = options(rng);
    if std::env::var_os("GVD_FUZZ_SHOW").is_some() {
        eprintln!("{opts:?}\n{}", gvd::io::json::write_scene(scene));
    }
    let Ok(d) = timed("compute", Some(scene), || compute(scene, &opts)) else {
        return;
    };
    let vo = VerifyOptions {
        grid: 8 + rng.below(40),
        slack: [1.0, 1e-300, 1e300, f64::NAN][rng.below(4)],
        ..Default::default()
    };
    // verify samples curved edges every epsilon/2 up to a cap: some seconds at a
    // relative epsilon of 1e-6 (docs/FUZZING.md), too slow for this loop
    if scene.epsilon() >= 1e-4 * scene.domain().longest_side() {
        let _ = timed("verify", Some(scene), || verify(scene, &d, &vo));
    }
    let distance = [0.1, 1e-300, 1e300, 0.0, -1.0, f64::NAN, 0.5][rng.below(7)];
    let _ = timed("offset", Some(scene), || offset(scene, &d, distance));
}

/// A random site of kind `k` around `c` at size `r`.
fn site(k: usize, c: [f64; 2], r: f64, rng: &mut Rng) -> Site {
    let p = |rng: &mut Rng| [c[0] + r * (rng.unit() - 0.5), c[1] + r * (rng.unit() - 0.5)];
    match k {
        0 => Site::point(p(rng)),
        1 => Site::point_with(
            p(rng),
            Metric::Lp {
                p: 2 * (1 + rng.below(3) as u32),
            },
        ),
        2 => Site::point_with(
            p(rng),
            Metric::Power {
                weight: r * rng.unit(),
            },
        ),
        3 => Site::circle(p(rng), 0.3 * r * rng.unit()),
        4 => Site::ellipse(
            p(rng),
            [0.3 * r * rng.unit(), 0.2 * r * rng.unit()],
            rng.unit(),
        ),
        5 => Site::segment(p(rng), p(rng)),
        6 => Site::arc(
            p(rng),
            0.3 * r * rng.unit(),
            6.0 * rng.unit(),
            6.0 * rng.unit(),
        ),
        7 => Site::polyline((0..2 + rng.below(4)).map(|_| p(rng)).collect::<Vec<_>>()),
        8 => Site::polygon([(0..3 + rng.below(4)).map(|_| p(rng)).collect::<Vec<_>>()]),
        9 => Site::bezier(
            (0..3 + rng.below(3)).map(|_| p(rng)).collect::<Vec<_>>(),
            None,
        ),
        _ => Site::field(&format!("(x-({:e}))^2+(y-({:e}))^2", c[0], c[1]))
            .unwrap_or_else(|_| Site::point(c)),
    }
}

/// A small random scene: sites of one kind (or mixed) in cells of a grid, at a random
/// scale, epsilon and mode.
fn random_scene(rng: &mut Rng) -> Result<Scene, Error> {
    let scale = [1.0, 1.0, 1e-150, 1e150, 1e-300, 1e300][rng.below(6)];
    let kind = rng.below(12);
    let n = 1 + rng.below(6);
    let mut sites = Vec::new();
    for i in 0..n {
        let c = [-0.75 + 0.5 * (i % 4) as f64, -0.75 + 0.5 * (i / 4) as f64];
        let k = if kind == 11 { rng.below(11) } else { kind };
        let c = [c[0] * scale, c[1] * scale];
        sites.push(site(k, c, 0.4 * scale, rng));
    }
    let domain = Aabb::from_array([-scale, -scale, scale, scale]);
    let epsilon = scale * [1e-3, 1e-2, 1e-6, 1e-12, 1e-17][rng.below(5)];
    let mode = [Mode::Voronoi, Mode::Complex, Mode::MedialAxis][rng.below(3)];
    Scene::new(domain, epsilon, mode, sites)
}

/// Replays one case of [`compute_takes_random_scenes`] (`GVD_FUZZ_SEED=s`, with
/// `GVD_FUZZ_SHOW=1` to print its scene and options).
#[test]
fn replay_one_case() {
    if let Some(s) = std::env::var("GVD_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        let mut rng = Rng(s);
        if let Ok(scene) = random_scene(&mut rng) {
            exercise(&scene, &mut rng);
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// The scene reader on mutated JSON: `Ok` or an `Error` with a short message; an
    /// accepted scene is computed, verified and offset.
    #[test]
    fn the_reader_takes_mutated_scenes(seed in 0usize..SEEDS.len(), s in any::<u64>(), n in 1usize..6) {
        let mut rng = Rng(s);
        let mut v: Value = serde_json::from_str(SEEDS[seed]).unwrap();
        for _ in 0..n {
            mutate(&mut v, &mut rng);
        }
        let text = mutate_text(&v.to_string(), &mut rng);
        match timed("from_json", None, || Scene::from_json(&text)) {
            Ok(scene) => exercise(&scene, &mut rng),
            Err(e) => {
                let m = e.to_string();
                prop_assert!(m.len() < 2000, "a message of {} characters", m.len());
            }
        }
    }

    /// `compute` (then `verify` and `offset`) on small random scenes of every kind at
    /// hostile scales, epsilons and options.
    #[test]
    fn compute_takes_random_scenes(s in any::<u64>()) {
        let mut rng = Rng(s);
        if let Ok(scene) = random_scene(&mut rng) {
            exercise(&scene, &mut rng);
        }
    }

    /// `verify` and `offset` on mutated diagrams of a valid scene (the diagram file is
    /// read back as `gvd verify` reads it).
    #[test]
    fn verify_takes_mutated_diagrams(seed in 0usize..4, s in any::<u64>(), n in 1usize..6) {
        let scene = Scene::from_json(SEEDS[seed]).unwrap();
        let d = compute(&scene, &Options::default()).unwrap();
        let mut v: Value = serde_json::from_str(&gvd::io::json::write_diagram(&d)).unwrap();
        let mut rng = Rng(s);
        for _ in 0..n {
            mutate(&mut v, &mut rng);
        }
        let text = mutate_text(&v.to_string(), &mut rng);
        if let Ok(d) = gvd::io::json::read_diagram(&text) {
            let vo = VerifyOptions { grid: 8 + rng.below(40), ..Default::default() };
            let _ = timed("verify", Some(&scene), || verify(&scene, &d, &vo));
            let distance = [0.1, 1e-300, 1e300, 0.5][rng.below(4)];
            let _ = timed("offset", Some(&scene), || offset(&scene, &d, distance));
        }
    }
}
