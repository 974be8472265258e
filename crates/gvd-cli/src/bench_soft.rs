//! `gvd bench soft`: the soft-predicate engine (Yap, Sharma, Lien 2012) on polygonal
//! scenes. Box counts and seconds with each filter of ¶25 on and off, beside the
//! paper's box counts (Figs. 7 and 8); then seconds on random non-crossing segments
//! beside the incremental engine's, timed in turn in the same run.

use crate::bench::Rng;
use anyhow::Context;
use gvd::geom::{Aabb, Point};
use gvd::io::{Format, ReadOptions};
use gvd::scene::{Mode, Scene, Site, SiteKind};
use gvd::SoftFilters;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::time::Instant;

/// The filter settings of the table: all on, then one switched off at a time.
const SETTINGS: [(&str, SoftFilters); 4] = [
    (
        "all on",
        SoftFilters {
            zone: true,
            oriented: true,
            two_edge: true,
        },
    ),
    (
        "no two-edge",
        SoftFilters {
            zone: true,
            oriented: true,
            two_edge: false,
        },
    ),
    (
        "no oriented",
        SoftFilters {
            zone: true,
            oriented: false,
            two_edge: true,
        },
    ),
    (
        "no zone",
        SoftFilters {
            zone: false,
            oriented: false,
            two_edge: true,
        },
    ),
];

/// The paper's box counts by filter setting (index into [`SETTINGS`]), with what
/// each shows: Fig. 7 (segments) with and without the two-edge filter of ¶25(a),
/// Fig. 8 with the oriented zones Z*(f), the zones Z(f) and no zone filter (¶25(b)).
const FIG7: [(usize, u64, &str); 2] = [
    (0, 169, "Fig. 7(b), new C1"),
    (1, 11_932, "Fig. 7(a), original C1"),
];
const FIG8: [(usize, u64, &str); 3] = [
    (0, 112, "Fig. 8(c), Z*(f)"),
    (2, 493, "Fig. 8(b), Z(f)"),
    (3, 13_777, "Fig. 8(a), no zones"),
];

/// The polygonal scenes shipped with the repository: name, text, format.
const SHIPPED: [(&str, &str, Format); 4] = [
    (
        "pocket (medial axis)",
        include_str!("../../../examples/scenes/pocket.json"),
        Format::Json,
    ),
    (
        "segments-0200",
        include_str!("../../../examples/scenes/segments-0200.json"),
        Format::Json,
    ),
    (
        "switzerland (medial axis)",
        include_str!("../../../examples/scenes/switzerland.geojson"),
        Format::GeoJson,
    ),
    (
        "bugtrap (medial axis)",
        include_str!("../../gvd/tests/data/scenes/polygon-bugtrap-medial_axis.json"),
        Format::Json,
    ),
];

/// A stand-in for Fig. 8's input (a "relatively simple" polygonal set, not given in
/// the text): the bugtrap polygon in `complex` mode, outside and inside.
const FIG8_SCENE: &str = include_str!("../../gvd/tests/data/scenes/polygon-bugtrap-complex.json");

/// Segments of the stand-in for Fig. 7's input (a few segments, not given in the text).
const FIG7_SEGMENTS: usize = 12;

/// Boxes a run of the filter table may visit (without the zone filter the counts grow
/// by two orders of magnitude).
const TABLE_BOXES: usize = 4_000_000;

/// `n` random non-crossing segments in [0,1]²: midpoints uniform, lengths uniform in [0.2, 1] / √n, directions uniform,
/// ends on the 2^-20 grid; a candidate that touches or crosses an earlier segment,
/// shares an end with one or leaves the square is drawn again. Default epsilon.
pub fn random_segments(n: usize, seed: u64) -> Scene {
    type Seg = [i64; 4];
    const G: i64 = 1 << 20;
    let mut rng = Rng(seed);
    let len = G as f64 / (n.max(1) as f64).sqrt();
    let cell = (len as i64).max(1);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut ends: HashSet<(i64, i64)> = HashSet::new();
    let mut segs: Vec<Seg> = Vec::with_capacity(n);
    while segs.len() < n {
        let (mx, my) = (rng.range(0.0, G as f64), rng.range(0.0, G as f64));
        let l = rng.range(0.2, 1.0) * len;
        let th = rng.range(0.0, std::f64::consts::PI);
        let (dx, dy) = (0.5 * l * th.cos(), 0.5 * l * th.sin());
        let s = [
            (mx - dx).round() as i64,
            (my - dy).round() as i64,
            (mx + dx).round() as i64,
            (my + dy).round() as i64,
        ];
        let (a, b) = ((s[0], s[1]), (s[2], s[3]));
        if a == b || s.iter().any(|&v| !(0..=G).contains(&v)) {
            continue;
        }
        if ends.contains(&a) || ends.contains(&b) {
            continue;
        }
        let cells: Vec<(i64, i64)> = (s[0].min(s[2]) / cell..=s[0].max(s[2]) / cell)
            .flat_map(|cx| (s[1].min(s[3]) / cell..=s[1].max(s[3]) / cell).map(move |cy| (cx, cy)))
            .collect();
        let touches = cells
            .iter()
            .filter_map(|c| grid.get(c))
            .flatten()
            .any(|&j| touch(&s, &segs[j]));
        if touches {
            continue;
        }
        for c in cells {
            grid.entry(c).or_default().push(segs.len());
        }
        ends.insert(a);
        ends.insert(b);
        segs.push(s);
    }
    let at = |x: i64, y: i64| Point::new(x as f64 / G as f64, y as f64 / G as f64);
    let domain = Aabb::from_array([0.0, 0.0, 1.0, 1.0]);
    let sites = segs
        .iter()
        .map(|s| {
            Site::new(SiteKind::Segment {
                from: at(s[0], s[1]),
                to: at(s[2], s[3]),
            })
        })
        .collect();
    Scene::new(
        domain,
        Scene::default_epsilon(&domain),
        Mode::Voronoi,
        sites,
    )
    .expect("random segments make a valid scene")
}

/// The sign of the turn `a → b → c` (exact on the integer grid).
fn orient(a: (i64, i64), b: (i64, i64), c: (i64, i64)) -> i64 {
    ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).signum()
}

/// Whether the closed segments `s` and `t` meet.
fn touch(s: &[i64; 4], t: &[i64; 4]) -> bool {
    let (a, b, c, d) = ((s[0], s[1]), (s[2], s[3]), (t[0], t[1]), (t[2], t[3]));
    let within = |p: (i64, i64), q: (i64, i64), r: (i64, i64)| {
        p.0.min(q.0) <= r.0 && r.0 <= p.0.max(q.0) && p.1.min(q.1) <= r.1 && r.1 <= p.1.max(q.1)
    };
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    (o1 != o2 && o3 != o4)
        || (o1 == 0 && within(a, b, c))
        || (o2 == 0 && within(a, b, d))
        || (o3 == 0 && within(c, d, a))
        || (o4 == 0 && within(c, d, b))
}

/// The figures of one run of the soft engine.
struct SoftRow {
    seconds: f64,
    subdivision_leaves: u64,
    leaves: u64,
    uncertified: u64,
    vertices: usize,
    edges: usize,
}

fn options(engine: gvd::Engine, filters: SoftFilters, max_boxes: Option<usize>) -> gvd::Options {
    gvd::Options {
        engine,
        subdivision: gvd::SubdivisionOptions {
            soft: filters,
            limits: gvd::Limits {
                max_boxes,
                ..Default::default()
            },
            ..Default::default()
        },
        parallel: false,
        ..Default::default()
    }
}

/// Seconds of one run and its diagram.
fn timed(scene: &Scene, options: &gvd::Options) -> Result<(f64, gvd::VoronoiComplex), gvd::Error> {
    let start = Instant::now();
    let d = gvd::compute(scene, options)?;
    Ok((start.elapsed().as_secs_f64(), d))
}

/// The soft engine with `filters`, best of `repeat`.
fn soft(scene: &Scene, filters: SoftFilters, repeat: usize) -> Result<SoftRow, gvd::Error> {
    let options = options(gvd::Engine::Subdivision, filters, Some(TABLE_BOXES));
    let (seconds, mut row) = crate::bench::best_run(scene, &options, repeat, |d| {
        let stat = |k: &str| crate::bench::count_stat(d, k);
        SoftRow {
            seconds: 0.0,
            subdivision_leaves: stat("leaves_after_subdivision"),
            leaves: stat("leaves"),
            uncertified: stat("uncertified_boxes"),
            vertices: d.vertices.len(),
            edges: d.edges.len(),
        }
    })?;
    row.seconds = seconds;
    Ok(row)
}

/// Prints the rows of one scene, one per filter setting, with the paper's counts
/// beside the settings they measured; returns the subdivision leaves per setting.
fn scene_rows(name: &str, scene: &Scene, paper: &[(usize, u64, &str)], repeat: usize) -> Vec<u64> {
    let mut counts = Vec::new();
    for (k, (setting, filters)) in SETTINGS.iter().enumerate() {
        let label = if k == 0 { name } else { "" };
        let beside = paper
            .iter()
            .find(|p| p.0 == k)
            .map(|p| format!("{:>7} {}", p.1, p.2))
            .unwrap_or_default();
        match soft(scene, *filters, repeat) {
            Ok(r) => {
                counts.push(r.subdivision_leaves);
                println!(
                    "{:<26} {:<11} | {:>8} {:>8} {:>6} | {:>5} {:>5} | {:>8.3} | {}",
                    label,
                    setting,
                    r.subdivision_leaves,
                    r.leaves,
                    r.uncertified,
                    r.vertices,
                    r.edges,
                    r.seconds,
                    beside
                );
            }
            Err(e) => {
                counts.push(0);
                println!("{label:<26} {setting:<11} | not finished: {e} | {beside}");
            }
        }
    }
    counts
}

/// How many times fewer boxes setting `with` leaves than `without`, ours and the paper's.
fn reduction(what: &str, ours: &[u64], paper: &[(usize, u64, &str)], without: usize, with: usize) {
    let count = |p: &[(usize, u64, &str)], k: usize| p.iter().find(|x| x.0 == k).map(|x| x.1);
    let (Some(pw), Some(pv)) = (count(paper, without), count(paper, with)) else {
        return;
    };
    let ratio = |a: u64, b: u64| a as f64 / b.max(1) as f64;
    println!(
        "  {what}: ours {:.1}x fewer subdivision leaves, the paper's {:.1}x",
        ratio(ours[without], ours[with]),
        ratio(pw, pv)
    );
}

/// The table; `random_only` skips the filter rows, `save_scenes` is where the
/// random-segment scenes are written. Everything runs on a pool of one thread: the
/// engines' `parallel: false` keeps the distance-field subdivision sequential, but the
/// incremental engine's and the cells' parallel maps take the global pool (all cores).
pub fn soft_table(
    repeat: usize,
    random_only: bool,
    save_scenes: Option<&Path>,
) -> anyhow::Result<()> {
    let one_core = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .context("cannot start the benchmark's thread")?;
    one_core.install(|| {
        if !random_only {
            filter_table(repeat);
            println!();
        }
        random_rows(repeat, save_scenes)
    })
}

/// The rows of each scene with each filter setting, and the reductions.
fn filter_table(repeat: usize) {
    println!(
        "Yap, Sharma, Lien 2012, ¶25: the soft-predicate subdivision with each filter on and off"
    );
    println!(
        "ours: one core, best of {repeat}, at most {TABLE_BOXES} boxes a run; subdiv = leaves when the subdivision phase stops"
    );
    println!(
        "(the paper's count of subdivision boxes), leaves = after balancing and construction;"
    );
    println!(
        "paper: its C++ implementation on its own inputs (not given in the text), here stand-ins"
    );
    println!(
        "{:<26} {:<11} | {:>8} {:>8} {:>6} | {:>5} {:>5} | {:>8} | paper",
        "scene", "filters", "subdiv", "leaves", "uncert", "verts", "edges", "seconds"
    );
    for (name, text, format) in SHIPPED {
        let (scene, _) = gvd::io::read_scene(text.as_bytes(), format, &ReadOptions::default())
            .expect("the shipped scenes are valid");
        scene_rows(name, &scene, &[], repeat);
    }
    let fig7 = random_segments(FIG7_SEGMENTS, 7);
    let name7 = format!("Fig. 7-like: {FIG7_SEGMENTS} segments");
    let ours7 = scene_rows(&name7, &fig7, &FIG7, repeat);
    let fig8 = Scene::from_json(FIG8_SCENE).expect("the bugtrap scene is valid");
    let ours8 = scene_rows("Fig. 8-like: bugtrap", &fig8, &FIG8, repeat);
    println!("reductions by the filters:");
    reduction("two-edge filter (Fig. 7)", &ours7, &FIG7, 1, 0);
    reduction("zone filter Z(f) (Fig. 8)", &ours8, &FIG8, 3, 2);
    reduction(
        "oriented zones Z*(f) over Z(f) (Fig. 8)",
        &ours8,
        &FIG8,
        2,
        0,
    );
}

/// Both engines on random non-crossing segments, timed in turn.
fn random_rows(repeat: usize, save_scenes: Option<&Path>) -> anyhow::Result<()> {
    println!("Random non-crossing segments in [0,1]^2: lengths in [0.2, 1]/sqrt(n), SplitMix64 seed 1, epsilon 0.001;");
    println!("one core, best of {repeat}, the two engines timed in turn on the same scene");
    println!(
        "{:>6} | {:>9} {:>13} {:>6} | {:>10} {:>10}",
        "n", "soft s", "incremental s", "ratio", "soft verts", "incr verts"
    );
    for n in [1_000usize, 10_000] {
        let scene = random_segments(n, 1);
        if let Some(dir) = save_scenes {
            let path = dir.join(format!("random-segments-{n}.json"));
            gvd::io::write_file(&path, gvd::io::json::write_scene(&scene).as_bytes())
                .with_context(|| format!("writing {}", path.display()))?;
        }
        let soft = options(gvd::Engine::Subdivision, SoftFilters::default(), None);
        let incremental = options(gvd::Engine::Incremental, SoftFilters::default(), None);
        let (mut best_soft, mut best_incremental) = (f64::INFINITY, f64::INFINITY);
        let (mut soft_vertices, mut incremental_vertices) = (0, 0);
        for _ in 0..repeat {
            let (s, d) = timed(&scene, &soft).expect("random segments fit the default limits");
            best_soft = best_soft.min(s);
            soft_vertices = d.vertices.len();
            let (s, d) = timed(&scene, &incremental).expect("random segments are valid");
            best_incremental = best_incremental.min(s);
            incremental_vertices = d.vertices.len();
        }
        println!(
            "{:>6} | {:>9.3} {:>13.3} {:>5.1}x | {:>10} {:>10}",
            n,
            best_soft,
            best_incremental,
            best_soft / best_incremental,
            soft_vertices,
            incremental_vertices
        );
    }
    Ok(())
}
