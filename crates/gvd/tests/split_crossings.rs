//! Segments that cross, overlap, repeat one another or touch another's inside, and
//! points on segments (issue 14): by default the segment engine cuts them into pieces
//! and computes; the diagram keeps the input's site indices and passes `gvd::verify`
//! (the library behind `gvd verify`, which shares no code with the engine) against the
//! original scene. `strict` and `medial_axis` mode keep the refusal, naming the sites;
//! near touches that are not exact stay refused.
//!
//! Scenes: `tests/data/crossings/` (an X, a T, a collinear overlap, repeats, a point on
//! a segment, a star of eight segments through one point whose crossings round
//! differently, a self-crossing polyline, a polygon crossed by a segment and touched by
//! another, a near T), and random sets of 100 short segments with such degeneracies
//! mixed in (the CI also runs 10,000 through the CLI and the shared checker, from
//! `scripts/gen_crossing_segments.py`).

use gvd::complex::{Generator, VoronoiComplex};
use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Error, IncrementalOptions, Options, Scene};
use serde_json::{json, Value};

fn text(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/crossings/{name}.json"));
    std::fs::read_to_string(path).unwrap()
}

fn in_mode(json: &str, mode: &str) -> Scene {
    let mut v: Value = serde_json::from_str(json).unwrap();
    v["mode"] = json!(mode);
    Scene::from_json(&v.to_string()).unwrap()
}

fn strict() -> Options {
    Options {
        incremental: IncrementalOptions {
            strict: true,
            ..Default::default()
        },
        ..Default::default()
    }
}

fn site_of(g: &Generator) -> usize {
    match *g {
        Generator::Site(s) => s,
        Generator::Feature { site, .. } => site,
    }
}

/// Computes `s` by default, checks it with `gvd::verify` and the labels (input sites,
/// no edge between one site and itself in `voronoi` mode); returns the diagram.
fn computed_and_verified(s: &Scene, what: &str) -> VoronoiComplex {
    let d = compute(s, &Options::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
    let report = verify(s, &d, &VerifyOptions::default()).unwrap();
    assert!(report.passed, "{what}: {}", report.summary_line());
    let n = s.sites().len();
    for e in &d.edges {
        assert!(
            e.sites.iter().all(|g| site_of(g) < n),
            "{what}: {:?}",
            e.sites
        );
        if s.mode() == gvd::Mode::Voronoi {
            assert_ne!(site_of(&e.sites[0]), site_of(&e.sites[1]), "{what}");
        }
    }
    d
}

fn counts(d: &VoronoiComplex) -> [u64; 3] {
    ["split_crossings", "split_touches", "merged_duplicates"]
        .map(|k| d.stats.get(k).and_then(Value::as_u64).unwrap_or(0))
}

#[test]
fn each_kind_of_contact_is_split_and_verified_in_voronoi_and_complex_modes() {
    // (scene, [crossing points, cuts at input points, merged pieces])
    let cases = [
        ("x", [1, 0, 0]),
        ("t", [0, 1, 0]),
        ("overlap", [0, 2, 1]),
        // sites 1 and 2 repeat site 0 (2 identically), site 3's first edge repeats it
        ("repeat", [0, 0, 3]),
        ("point-on", [0, 1, 0]),
        ("star", [1, 0, 0]),
        ("polyline-self-crossing", [1, 0, 0]),
        ("polygon-and-segment", [1, 1, 0]),
    ];
    for (name, want) in cases {
        for mode in ["voronoi", "complex"] {
            let s = in_mode(&text(name), mode);
            let d = computed_and_verified(&s, &format!("{name} ({mode})"));
            assert_eq!(counts(&d), want.map(|n| n as u64), "{name} ({mode})");
        }
    }
}

#[test]
fn a_star_is_one_vertex_at_its_centre() {
    let s = in_mode(&text("star"), "voronoi");
    let d = computed_and_verified(&s, "star");
    // the centre (a computed point within rounding of all eight lines) is one vertex of
    // degree 16 listing every site, not a cluster of vertices a few ulps apart
    let centre: Vec<_> = d
        .vertices
        .iter()
        .filter(|v| (v.at.x - 1.1).abs() < 1e-9 && (v.at.y - 1.3).abs() < 1e-9)
        .collect();
    assert_eq!(centre.len(), 1, "{centre:?}");
    assert_eq!(centre[0].sites.len(), 8);
}

#[test]
fn strict_refuses_naming_the_sites() {
    for (name, sites) in [
        ("x", (0, 1)),
        ("t", (0, 1)),
        ("overlap", (0, 1)),
        ("repeat", (0, 1)),
        ("point-on", (0, 1)),
    ] {
        let s = in_mode(&text(name), "voronoi");
        match compute(&s, &strict()) {
            Err(Error::Conflict {
                site,
                other,
                message,
            }) => {
                assert_eq!((site, other), sites, "{name}: {message}");
                assert!(message.contains("strict"), "{name}: {message}");
            }
            other => panic!("{name}: {:?}", other.map(|d| d.edges.len())),
        }
    }
}

#[test]
fn medial_axis_mode_refuses_crossings_naming_the_sites() {
    let s = in_mode(&text("polygon-and-segment"), "medial_axis");
    match compute(&s, &Options::default()) {
        Err(Error::Conflict {
            site,
            other,
            message,
        }) => {
            assert_eq!((site, other), (0, 1), "{message}");
            assert!(message.contains("medial_axis"), "{message}");
        }
        other => panic!("{:?}", other.map(|d| d.edges.len())),
    }
}

#[test]
fn near_touches_that_are_not_exact_stay_refused() {
    let s = in_mode(&text("near-t"), "voronoi");
    match compute(&s, &Options::default()) {
        Err(Error::Conflict {
            site,
            other,
            message,
        }) => {
            assert_eq!((site, other), (0, 1));
            assert!(message.contains("4e-12"), "{message}");
        }
        other => panic!("{:?}", other.map(|d| d.edges.len())),
    }
}

#[test]
fn scenes_without_contacts_have_no_split_stats() {
    let s = in_mode(
        r#"{"domain": [0, 0, 1, 1], "sites": [
            {"kind": "segment", "from": [0.1, 0.1], "to": [0.4, 0.5]},
            {"kind": "segment", "from": [0.4, 0.5], "to": [0.9, 0.2]},
            {"kind": "point", "at": [0.5, 0.9]}]}"#,
        "voronoi",
    );
    let d = compute(&s, &Options::default()).unwrap();
    assert!(!d.stats.contains_key("split_crossings"));
    assert!(!d.stats.contains_key("merged_duplicates"));
}

/// splitmix64: a seed-driven stream of uniform numbers in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` random segments of length about 1.5/√n in the unit square (about 0.7 crossings
/// each), a T, a collinear overlap and a point on an axis-parallel host, a reversed
/// repeat, and a star of eight segments through (0.5, 0.5), as scene JSON.
fn random_crossings(n: usize, seed: u64, mode: &str) -> String {
    let mut rng = Rng(seed);
    let len = 1.5 / (n as f64).sqrt();
    let seg = |a: [f64; 2], b: [f64; 2]| json!({"kind": "segment", "from": a, "to": b});
    let mut sites = Vec::new();
    let mut ends = Vec::new();
    for _ in 0..n {
        let c = [0.02 + 0.96 * rng.next(), 0.02 + 0.96 * rng.next()];
        let (ang, h) = (
            std::f64::consts::PI * rng.next(),
            0.5 * len * (0.5 + rng.next()),
        );
        let d = [h * ang.cos(), h * ang.sin()];
        ends.push(([c[0] - d[0], c[1] - d[1]], [c[0] + d[0], c[1] + d[1]]));
        sites.push(seg(ends[ends.len() - 1].0, ends[ends.len() - 1].1));
    }
    let (x0, y) = (
        0.05 + (0.9 - 1.5 * len) * rng.next(),
        0.05 + 0.9 * rng.next(),
    );
    sites.push(seg([x0, y], [x0 + len, y]));
    sites.push(seg([x0 + 0.5 * len, y], [x0 + 0.7 * len, y + 0.6 * len]));
    sites.push(seg([x0 + 0.75 * len, y], [x0 + 1.5 * len, y]));
    sites.push(json!({"kind": "point", "at": [x0 + 0.25 * len, y]}));
    let (a, b) = ends[(rng.next() * n as f64) as usize];
    sites.push(seg(b, a));
    for k in 0..8 {
        let ang = std::f64::consts::PI * k as f64 / 8.0 + 0.1;
        let d = [len * ang.cos(), len * ang.sin()];
        sites.push(seg([0.5 - d[0], 0.5 - d[1]], [0.5 + d[0], 0.5 + d[1]]));
    }
    json!({"domain": [0, 0, 1, 1], "epsilon": 1e-3, "mode": mode, "sites": sites}).to_string()
}

#[test]
fn random_crossing_sets_of_100_segments_pass_verify() {
    for seed in 1..=4 {
        for mode in ["voronoi", "complex"] {
            let s = Scene::from_json(&random_crossings(100, seed, mode)).unwrap();
            let d = computed_and_verified(&s, &format!("seed {seed} ({mode})"));
            let [crossings, touches, merged] = counts(&d);
            // about 0.7 crossings per segment, the star's centre among them; the T, the
            // overlap's two ends and the point; the repeat and the overlap's common piece
            assert!(crossings > 30, "seed {seed}: {crossings} crossings");
            assert!(touches >= 4, "seed {seed}: {touches} touches");
            assert!(merged >= 2, "seed {seed}: {merged} merged");
        }
    }
}
