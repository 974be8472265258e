//! Side-by-side benchmark of issue 4: gvd's incremental engine against spade and
//! boostvoronoi, in one run, on a directory of scene files made by
//! `shared/oracles/gen_scene.py`.
//!
//! ```text
//! python3 ../shared/oracles/gen_scene.py points 100000 --seed 1 -o /work/bench-scenes/points-100000.json
//! cargo run --release -p gvd --example bench_oracles -- /work/bench-scenes [--runs 3] [--big-runs 1]
//! ```
//!
//! Options: `--libs gvd,spade,boost,gvd-nocells` (a subset), `--timeout SECONDS` per
//! child (default 1800). The C++ oracles (CGAL, Boost.Polygon) cannot run in-process:
//! `scripts/bench_oracles.sh ORACLE_BUILD_DIR SCENE_DIR` times them on the same
//! scenes. `docs/BENCHMARKS.md` has the figures.
//!
//! Every `*.json` file of the directory is one case (its kind — points, segments or
//! mixed — and n are read from the scene). Each (case, library) pair runs in a child
//! process (this same program, re-run with `--child`), so that its peak memory is its
//! own:
//!
//! * **gvd**: `Scene::from_json` (timed apart, column "parse"), then
//!   `gvd::compute(&scene, &Options { engine: Engine::Incremental, .. })`: the
//!   clipped `VoronoiComplex` with its cells (`parallel` is left at its default,
//!   which the incremental engine does not use). An error (segments before the
//!   engine supports them) is printed with its message ("unsupported", "error"),
//!   not as a failure of the run.
//! * **gvd-nocells** (points only, an extra column): `gvd::internals::points_voronoi`,
//!   the same complex without the cells, to show what the cells cost.
//! * **spade** (points only): `DelaunayTriangulation::bulk_load` of the points.
//! * **boostvoronoi** (points and segments): `Builder::with_vertices`,
//!   `with_segments`, `build`. It takes integer input: every coordinate is multiplied by
//!   `BOOST_SCALE` = 2^20 (the default `--scale` of `oracle_boost`) and must then be
//!   an exact i32; on `gen_scene.py`'s 2^-20 grid it always is, so boostvoronoi sees
//!   exactly the scene. A coordinate that is not is rounded and counted ("rounded").
//!
//! Only the construction is timed: best of `--runs` (default 3) runs, or of
//! `--big-runs` (default 1) for n >= 10^6; every result is dropped before the next
//! run. The scene is parsed by gvd in every child; spade and boostvoronoi then keep
//! only their own input. Peak memory: the child resets its high-water mark
//! (`/proc/self/clear_refs`, "5") once its input is ready, and reports `VmHWM`
//! after the runs, i.e. the process's peak resident set during construction,
//! input included ("peak MB"), and that peak less the resident set at the reset
//! ("+MB", the construction's own memory). Linux only.
//!
//! "vertices" counts the Voronoi vertices in the closed domain, as a cross-check
//! (computed after timing): gvd's `complex.vertices`, the circumcentres of spade's
//! triangles that lie in the domain, boostvoronoi's diagram vertices in the scaled
//! domain (for segments, these include the points where a parabolic edge turns
//! straight, `oracle_boost`'s "breakpoints"). boostvoronoi's message column gives
//! all its diagram vertices, to compare with `oracle_boost --bench`'s
//! `stats.boost_vertices`. A child that panics or is killed is reported as "failed"
//! or "timeout" with its first lines of stderr; the other cases go on.

use boostvoronoi::prelude::{Builder, BvError};
use gvd::scene::{Metric, Scene, SiteKind};
use gvd::{compute, Engine, Options};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// boostvoronoi's integer input: coordinate * 2^20, as `oracle_boost --scale` by default.
const BOOST_SCALE: f64 = 1048576.0;

/// The libraries, in column order; "gvd-nocells" is `gvd::internals::points_voronoi`
/// (the clipped complex without the cells that `compute` adds), for points only.
const LIBS: [&str; 4] = ["gvd", "spade", "boost", "gvd-nocells"];

/// What one child reports.
#[derive(Clone, Debug, Default)]
struct Outcome {
    /// "ok", "unsupported", "n/a", "error", "failed" or "timeout".
    status: String,
    message: String,
    seconds: Option<f64>,
    parse_seconds: Option<f64>,
    peak_kb: Option<u64>,
    above_kb: Option<u64>,
    vertices: Option<usize>,
    edges: Option<usize>,
    runs: usize,
}

impl Outcome {
    fn time_cell(&self) -> String {
        match (self.status.as_str(), self.seconds) {
            ("ok", Some(s)) => format!("{s:.3}"),
            (status, _) => status.to_string(),
        }
    }

    fn mem_cell(&self) -> String {
        match (self.status.as_str(), self.peak_kb, self.above_kb) {
            ("ok", Some(p), Some(a)) => format!("{:.0} (+{:.0})", mb(p), mb(a)),
            _ => "—".into(),
        }
    }
}

fn mb(kb: u64) -> f64 {
    kb as f64 / 1024.0
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--child") {
        std::process::exit(child(&args[1..]));
    }
    let mut dir = None;
    let mut runs = 3usize;
    let mut big_runs = 1usize;
    let mut timeout = 1800u64;
    let mut libs: Vec<String> = LIBS.iter().map(|s| s.to_string()).collect();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| -> String {
            it.next()
                .unwrap_or_else(|| usage(&format!("{name} needs a value")))
                .clone()
        };
        match a.as_str() {
            "--runs" => {
                runs = value("--runs")
                    .parse()
                    .unwrap_or_else(|_| usage("--runs N"))
            }
            "--big-runs" => {
                big_runs = value("--big-runs")
                    .parse()
                    .unwrap_or_else(|_| usage("--big-runs N"))
            }
            "--timeout" => {
                timeout = value("--timeout")
                    .parse()
                    .unwrap_or_else(|_| usage("--timeout SECONDS"))
            }
            "--libs" => libs = value("--libs").split(',').map(str::to_string).collect(),
            "-h" | "--help" => usage(""),
            s if s.starts_with('-') => usage(&format!("unknown option {s}")),
            s => dir = Some(PathBuf::from(s)),
        }
    }
    let dir = dir.unwrap_or_else(|| usage("a scene directory is needed"));
    if let Some(bad) = libs.iter().find(|l| !LIBS.contains(&l.as_str())) {
        usage(&format!("unknown library {bad} ({})", LIBS.join(", ")));
    }
    let mut cases = scan(&dir);
    if cases.is_empty() {
        usage(&format!("no *.json scene in {}", dir.display()));
    }
    cases.sort_by(|a, b| (a.kind, a.n, &a.path).cmp(&(b.kind, b.n, &b.path)));
    let exe = std::env::current_exe().expect("own path");

    println!(
        "bench_oracles: {} scenes in {}; best of {runs} runs (n < 10^6), {big_runs} (n >= 10^6); one child process per (scene, library)",
        cases.len(),
        dir.display()
    );
    println!(
        "{:<28} {:<11} {:>6} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  message",
        "scene", "lib", "runs", "parse s", "build s", "peak MB", "+MB", "vertices", "edges"
    );
    let mut results = Vec::new();
    for case in &cases {
        let r = if case.n >= 1_000_000 { big_runs } else { runs };
        let mut row = Vec::new();
        for lib in LIBS {
            let out = if !libs.iter().any(|l| l == lib) {
                Outcome {
                    status: "skipped".into(),
                    ..Default::default()
                }
            } else if (lib == "spade" || lib == "gvd-nocells") && case.kind != "points" {
                Outcome {
                    status: "n/a".into(),
                    message: format!("{lib}: points only"),
                    ..Default::default()
                }
            } else {
                run_child(&exe, lib, &case.path, r, Duration::from_secs(timeout))
            };
            let name = case.path.file_name().unwrap_or_default().to_string_lossy();
            let f = |v: Option<f64>, d: usize| v.map_or("—".into(), |v| format!("{v:.d$}"));
            println!(
                "{:<28} {:<11} {:>6} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  {}",
                name,
                lib,
                out.runs,
                f(out.parse_seconds, 3),
                if out.status == "ok" {
                    f(out.seconds, 3)
                } else {
                    out.status.clone()
                },
                f(out.peak_kb.map(mb), 0),
                f(out.above_kb.map(mb), 0),
                out.vertices.map_or("—".into(), |v| v.to_string()),
                out.edges.map_or("—".into(), |v| v.to_string()),
                out.message
            );
            row.push(out);
        }
        results.push(row);
    }

    println!();
    println!("| n | kind | gvd s | spade s | boostvoronoi s | gvd/spade | gvd/boostvoronoi | gvd w/o cells s | peak MB (+construction) gvd | spade | boostvoronoi | vertices gvd / spade / boostvoronoi |");
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for (case, row) in cases.iter().zip(&results) {
        let (ours, spade, boost, nocells) = (&row[0], &row[1], &row[2], &row[3]);
        let ratio = |a: &Outcome, b: &Outcome| match (a.status.as_str(), b.status.as_str()) {
            ("ok", "ok") => format!("{:.2}", a.seconds.unwrap_or(0.0) / b.seconds.unwrap_or(1.0)),
            _ => "—".into(),
        };
        let v = |o: &Outcome| o.vertices.map_or("—".into(), |v| v.to_string());
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} / {} |",
            case.n,
            case.kind,
            ours.time_cell(),
            spade.time_cell(),
            boost.time_cell(),
            ratio(ours, spade),
            ratio(ours, boost),
            nocells.time_cell(),
            ours.mem_cell(),
            spade.mem_cell(),
            boost.mem_cell(),
            v(ours),
            v(spade),
            v(boost)
        );
    }
    for (case, row) in cases.iter().zip(&results) {
        for (lib, out) in LIBS.iter().zip(row) {
            if !matches!(out.status.as_str(), "ok" | "n/a" | "skipped") {
                println!(
                    "{} {}: {}: {}",
                    case.path.display(),
                    lib,
                    out.status,
                    out.message
                );
            }
        }
    }
}

fn usage(problem: &str) -> ! {
    if !problem.is_empty() {
        eprintln!("bench_oracles: {problem}");
    }
    eprintln!("usage: bench_oracles SCENE_DIR [--runs 3] [--big-runs 1] [--timeout 1800] [--libs gvd,spade,boost,gvd-nocells]");
    std::process::exit(2)
}

struct Case {
    path: PathBuf,
    kind: &'static str,
    n: usize,
}

/// The scenes of a directory, with their kind and size (parsed once, here).
fn scan(dir: &Path) -> Vec<Case> {
    let entries = std::fs::read_dir(dir)
        .unwrap_or_else(|e| usage(&format!("cannot read {}: {e}", dir.display())));
    let mut cases = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let scene = match std::fs::read_to_string(&path)
            .map_err(|e| e.to_string())
            .and_then(|t| Scene::from_json(&t).map_err(|e| e.to_string()))
        {
            Ok(s) => s,
            Err(e) => {
                eprintln!("bench_oracles: skipping {}: {e}", path.display());
                continue;
            }
        };
        let points = scene
            .sites()
            .iter()
            .filter(|s| matches!(s.kind, SiteKind::Point { .. }))
            .count();
        let kind = if points == scene.sites().len() {
            "points"
        } else if points == 0 {
            "segments"
        } else {
            "mixed"
        };
        cases.push(Case {
            path,
            kind,
            n: scene.sites().len(),
        });
    }
    cases
}

/// Runs one (scene, library) pair in a child process and reads its report.
fn run_child(exe: &Path, lib: &str, scene: &Path, runs: usize, timeout: Duration) -> Outcome {
    let mut child = match Command::new(exe)
        .arg("--child")
        .arg(lib)
        .arg(scene)
        .arg(runs.to_string())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => {
            return Outcome {
                status: "failed".into(),
                message: format!("cannot start the child: {e}"),
                ..Default::default()
            }
        }
    };
    let mut pipe_out = child.stdout.take().expect("piped");
    let mut pipe_err = child.stderr.take().expect("piped");
    let read_out = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = pipe_out.read_to_string(&mut s);
        s
    });
    let read_err = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = pipe_err.read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if start.elapsed() > timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(_) => break None,
        }
    };
    let stdout = read_out.join().unwrap_or_default();
    let stderr = read_err.join().unwrap_or_default();
    let Some(status) = status else {
        return Outcome {
            status: "timeout".into(),
            message: format!("killed after {} s", timeout.as_secs()),
            runs,
            ..Default::default()
        };
    };
    match stdout.lines().find_map(|l| l.strip_prefix("RESULT ")) {
        Some(line) if status.success() => parse_report(line),
        _ => Outcome {
            status: "failed".into(),
            message: format!(
                "child exited with {status}: {}",
                stderr
                    .lines()
                    .filter(|l| !l.trim().is_empty())
                    .take(2)
                    .collect::<Vec<_>>()
                    .join(" / ")
            ),
            runs,
            ..Default::default()
        },
    }
}

/// `key=value` fields separated by spaces; `message=` takes the rest of the line.
fn parse_report(line: &str) -> Outcome {
    let (fields, message) = match line.split_once("message=") {
        Some((f, m)) => (f, m.to_string()),
        None => (line, String::new()),
    };
    let mut o = Outcome {
        message,
        ..Default::default()
    };
    for kv in fields.split_whitespace() {
        let Some((k, v)) = kv.split_once('=') else {
            continue;
        };
        match k {
            "status" => o.status = v.to_string(),
            "seconds" => o.seconds = v.parse().ok(),
            "parse" => o.parse_seconds = v.parse().ok(),
            "peak_kb" => o.peak_kb = v.parse().ok(),
            "above_kb" => o.above_kb = v.parse().ok(),
            "vertices" => o.vertices = v.parse().ok(),
            "edges" => o.edges = v.parse().ok(),
            "runs" => o.runs = v.parse().unwrap_or(0),
            _ => {}
        }
    }
    o
}

/// `VmHWM` and `VmRSS` of this process, in kB.
fn memory_kb() -> (Option<u64>, Option<u64>) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|v| v.parse().ok())
    };
    (field("VmHWM:"), field("VmRSS:"))
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
extern "C" {
    /// glibc: gives the heap's free memory back to the system.
    fn malloc_trim(pad: usize) -> i32;
}

/// Returns the memory freed after parsing to the system (glibc keeps it resident
/// otherwise, and a construction could reuse it unseen), sets the high-water mark to
/// the current resident set (Linux >= 4.0), and returns that set.
fn reset_peak() -> Option<u64> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only releases free heap pages; no pointer is involved.
    unsafe {
        malloc_trim(0);
    }
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    memory_kb().1
}

/// Runs `build` `runs` times, dropping each result before the next run; returns the
/// best time and `count` of the last result (evaluated after timing).
fn best_of<T>(
    runs: usize,
    mut build: impl FnMut() -> Result<T, String>,
    count: impl Fn(&T) -> (usize, usize, String),
) -> Result<(f64, (usize, usize, String)), String> {
    let mut best = f64::INFINITY;
    let mut counts = (0, 0, String::new());
    for k in 0..runs.max(1) {
        let t = Instant::now();
        let r = build()?;
        best = best.min(t.elapsed().as_secs_f64());
        if k + 1 == runs.max(1) {
            counts = count(&r);
        }
        drop(r);
    }
    Ok((best, counts))
}

/// The child: `--child LIB SCENE RUNS`; prints one `RESULT ...` line.
fn child(args: &[String]) -> i32 {
    let [lib, path, runs] = args else {
        eprintln!("bench_oracles --child LIB SCENE RUNS");
        return 2;
    };
    let runs: usize = runs.parse().unwrap_or(1);
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{path}: {e}");
            return 2;
        }
    };
    let t = Instant::now();
    let scene = match Scene::from_json(&text) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{path}: {e}");
            return 2;
        }
    };
    let parse = t.elapsed().as_secs_f64();
    drop(text);
    let domain = scene.domain();
    let (result, base) = match lib.as_str() {
        "gvd" => {
            let options = Options {
                engine: Engine::Incremental,
                ..Default::default()
            };
            let base = reset_peak();
            let r = best_of(
                runs,
                || {
                    compute(&scene, &options).map_err(|e| match e {
                        gvd::Error::Unsupported { .. } => format!("unsupported: {e}"),
                        e => format!("{e}"),
                    })
                },
                |c| (c.vertices.len(), c.edges.len(), String::new()),
            );
            (r, base)
        }
        "gvd-nocells" => {
            let points: Option<Vec<gvd::geom::Point>> = scene
                .sites()
                .iter()
                .map(|s| match s.kind {
                    SiteKind::Point {
                        at,
                        metric: Metric::Euclidean,
                    } => Some(at),
                    _ => None,
                })
                .collect();
            drop(scene);
            match points {
                None => (Err("unsupported: points only".into()), None),
                Some(points) => {
                    let base = reset_peak();
                    let r = best_of(
                        runs,
                        || {
                            gvd::internals::points_voronoi(&points, domain)
                                .map_err(|e| format!("{e}"))
                        },
                        |c| (c.vertices.len(), c.edges.len(), String::new()),
                    );
                    (r, base)
                }
            }
        }
        "spade" => {
            let points: Result<Vec<Point2<f64>>, String> = scene
                .sites()
                .iter()
                .enumerate()
                .map(|(i, s)| match s.kind {
                    SiteKind::Point {
                        at,
                        metric: Metric::Euclidean,
                    } => Ok(Point2::new(at.x, at.y)),
                    ref k => Err(format!(
                        "unsupported: sites[{i}]: spade takes points only, not {}",
                        k.name()
                    )),
                })
                .collect();
            drop(scene);
            match points {
                Err(e) => (Err(e), None),
                Ok(points) => {
                    let base = reset_peak();
                    let r = best_of(
                        runs,
                        || {
                            DelaunayTriangulation::<Point2<f64>>::bulk_load(points.clone())
                                .map_err(|e| format!("spade: {e:?}"))
                        },
                        |t| {
                            let inside = t
                                .inner_faces()
                                .filter(|f| {
                                    let c = f.circumcenter();
                                    c.x >= domain.min.x
                                        && c.x <= domain.max.x
                                        && c.y >= domain.min.y
                                        && c.y <= domain.max.y
                                })
                                .count();
                            (inside, t.num_undirected_edges(), String::new())
                        },
                    );
                    (r, base)
                }
            }
        }
        "boost" => match boost_input(&scene) {
            Err(e) => (Err(e), None),
            Ok((points, segments, rounded)) => {
                drop(scene);
                if rounded > 0 {
                    eprintln!("boost: {rounded} coordinates rounded to the 2^-20 grid");
                }
                let (lo, hi) = (
                    [domain.min.x * BOOST_SCALE, domain.min.y * BOOST_SCALE],
                    [domain.max.x * BOOST_SCALE, domain.max.y * BOOST_SCALE],
                );
                let base = reset_peak();
                let r = best_of(
                    runs,
                    || {
                        Builder::<i32>::default()
                            .with_vertices(points.iter())
                            .and_then(|b| b.with_segments(segments.iter()))
                            .and_then(|b| b.build())
                            .map_err(|e: BvError| format!("boostvoronoi: {e}"))
                    },
                    |d| {
                        let inside = d
                            .vertices()
                            .iter()
                            .filter(|v| {
                                v.x() >= lo[0] && v.x() <= hi[0] && v.y() >= lo[1] && v.y() <= hi[1]
                            })
                            .count();
                        let all = d.vertices().len();
                        (
                            inside,
                            d.edges().len() / 2,
                            format!("{all} diagram vertices in all"),
                        )
                    },
                );
                (r, base)
            }
        },
        other => {
            eprintln!("unknown library {other}");
            return 2;
        }
    };
    let (hwm, _) = memory_kb();
    let mem = match (hwm, base) {
        (Some(h), Some(b)) => format!("peak_kb={h} above_kb={}", h.saturating_sub(b)),
        (Some(h), None) => format!("peak_kb={h}"),
        _ => String::new(),
    };
    match result {
        Ok((seconds, (vertices, edges, note))) => println!(
            "RESULT status=ok runs={runs} parse={parse} seconds={seconds} vertices={vertices} edges={edges} {mem} message={note}"
        ),
        Err(e) => {
            let (status, message) = match e.strip_prefix("unsupported: ") {
                Some(m) => ("unsupported", m),
                None => ("error", e.as_str()),
            };
            println!(
                "RESULT status={status} runs={runs} parse={parse} message={}",
                message.replace('\n', " ")
            )
        }
    }
    0
}

type BoostInput = (Vec<[i32; 2]>, Vec<[i32; 4]>, usize);

/// The scene as boostvoronoi's integer points and segments (scaled by `BOOST_SCALE`),
/// with the number of coordinates that had to be rounded.
fn boost_input(scene: &Scene) -> Result<BoostInput, String> {
    let mut rounded = 0;
    let mut int = |v: f64, i: usize| -> Result<i32, String> {
        let s = v * BOOST_SCALE;
        let r = s.round();
        if r != s {
            rounded += 1;
        }
        if r.abs() > i32::MAX as f64 {
            return Err(format!("sites[{i}]: {v} * 2^20 overflows i32"));
        }
        Ok(r as i32)
    };
    let (mut points, mut segments) = (Vec::new(), Vec::new());
    for (i, s) in scene.sites().iter().enumerate() {
        match s.kind {
            SiteKind::Point {
                at,
                metric: Metric::Euclidean,
            } => points.push([int(at.x, i)?, int(at.y, i)?]),
            SiteKind::Segment { from, to } => segments.push([
                int(from.x, i)?,
                int(from.y, i)?,
                int(to.x, i)?,
                int(to.y, i)?,
            ]),
            ref k => {
                return Err(format!(
                    "unsupported: sites[{i}]: kind '{}' is not supported by boostvoronoi",
                    k.name()
                ))
            }
        }
    }
    Ok((points, segments, rounded))
}
