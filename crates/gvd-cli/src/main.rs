//! `gvd`: generalized Voronoi diagrams from the command line.

mod bench;
mod bench_algebraic;
mod bench_freeform;
mod bench_implicit;
mod bench_soft;
mod formats;
mod output;
mod progress;

use anyhow::{bail, Context, Result};
use clap::{Args, CommandFactory, Parser, Subcommand};
use formats::{output_kind, read_scene_as, FormatArg, ModeArg, OutputKind, ProjectArg};
use gvd::VoronoiComplex;
use output::Outputs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Most worker threads `--threads` accepts.
const MAX_THREADS: usize = 256;
/// Most characters of an error message printed (a message may quote the input).
const MAX_MESSAGE: usize = 1000;

#[derive(Parser)]
#[command(
    name = "gvd",
    version,
    about = "Generalized Voronoi diagrams in the plane"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Compute the diagram of a scene; write it as JSON and/or SVG.
    Compute(ComputeArgs),
    /// Offset curves (lines and arcs) at a distance from the sites, derived from the
    /// diagram (in `complex` mode for a `voronoi` scene; inside the region in
    /// `medial_axis` mode: a pocket).
    Offset(OffsetArgs),
    /// Check a diagram against its scene by brute force (independent of the engines).
    Verify(VerifyArgs),
    /// Reproduce a paper's table of timings and box counts.
    Bench(BenchArgs),
    /// Print a shell completion script (e.g. `gvd completions bash >
    /// /etc/bash_completion.d/gvd`).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
}

#[derive(Args)]
struct ComputeArgs {
    /// The scene: JSON (SCENE_FORMAT.md), GeoJSON, WKT, DXF or SVG by its extension (`-`
    /// reads standard input: JSON, or the format given by `--format`).
    scene: PathBuf,
    /// The scene's format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
    /// The mode, instead of the scene's (a GeoJSON file's top-level `mode`; WKT, DXF and
    /// SVG have none: voronoi).
    #[arg(long, value_enum)]
    mode: Option<ModeArg>,
    /// GeoJSON in longitude and latitude (degrees): `local` projects them to metres
    /// (azimuthal equidistant about the data's centre) and GeoJSON outputs back.
    #[arg(long, value_enum, default_value = "none")]
    project: ProjectArg,
    /// Write the diagram here (JSON; `-` for standard output).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write the diagram here as GeoJSON: vertices, edges and cells as features.
    #[arg(long)]
    geojson: Option<PathBuf>,
    /// Write the edges (the medial axis in medial_axis mode) here as DXF LINEs.
    #[arg(long)]
    dxf: Option<PathBuf>,
    /// Write a picture here (SVG; `-` for standard output).
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Write the same picture here as PNG.
    #[arg(long)]
    png: Option<PathBuf>,
    /// Write here, in the format of the extension (.json, .svg, .png, .geojson, .dxf;
    /// `-`: JSON on standard output); repeatable.
    #[arg(short = 'o', long = "output")]
    output: Vec<PathBuf>,
    /// Draw the subdivision boxes in the picture.
    #[arg(long)]
    boxes: bool,
    /// Draw the maximal empty disc at every vertex in the picture (complex and
    /// medial_axis modes, where vertices carry their clearance).
    #[arg(long)]
    svg_discs: bool,
    /// Split boxes that hold two or more sites until no longer than this (finite, > 0).
    #[arg(long, value_parser = positive_length)]
    max_box: Option<f64>,
    /// Most boxes the subdivision engine may visit (default: 2097152 + 64 per site).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    max_boxes: Option<u64>,
    /// Most polyline points the subdivision engine (and the incremental engine on
    /// curved edges) may write (default: 524288 + 256
    /// per site).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    max_points: Option<u64>,
    /// Worker threads (default: all cores; 1 = sequential; at most 256).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=MAX_THREADS as u64))]
    threads: Option<u64>,
    /// Algorithm family: `auto` takes the incremental engine for scenes of Euclidean
    /// points, the freeform engine for scenes of bezier/bspline curves, and the
    /// subdivision engine otherwise.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    engine: EngineArg,
    /// Give every edge of the incremental engine its exact bisector: `bisector`,
    /// pieces in Held's offset-parameter form with their clearance ranges.
    #[arg(long)]
    bisectors: bool,
    /// Refuse segments that cross, overlap, repeat or touch another's inside, and
    /// points on segments (naming the sites), instead of splitting them there.
    #[arg(long)]
    strict: bool,
    /// Prune the medial axis to its λ-medial axis: keep the points whose two nearest
    /// boundary points are at least 2λ apart (a length of the scene).
    #[arg(long, value_name = "LAMBDA", value_parser = positive_length)]
    prune_lambda: Option<f64>,
    /// Prune the medial axis by the object angle: keep the points whose two nearest
    /// boundary points subtend at least this angle there (degrees, in (0, 180]).
    #[arg(long, value_name = "DEGREES", value_parser = object_angle_degrees)]
    prune_angle: Option<f64>,
    /// Soft-predicate engine (segments, polylines, polygons with `--engine
    /// subdivision`): no zone filter, every feature within reach belongs to a box.
    #[arg(long)]
    no_zone_filter: bool,
    /// Soft-predicate engine: zones Z(f) instead of the oriented zones Z*(f).
    #[arg(long)]
    no_oriented_zones: bool,
    /// Soft-predicate engine: no two-edge filter in C1 (Yap et al. ¶25(a)).
    #[arg(long)]
    no_two_edge_filter: bool,
    #[command(flatten)]
    run: progress::RunArgs,
}

#[derive(Args)]
struct OffsetArgs {
    /// The scene: JSON (SCENE_FORMAT.md), GeoJSON, WKT, DXF or SVG by its extension (`-`
    /// reads standard input: JSON, or the format given by `--format`).
    scene: PathBuf,
    /// The scene's format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
    /// The mode, instead of the scene's (medial_axis: the offsets of a pocket).
    #[arg(long, value_enum)]
    mode: Option<ModeArg>,
    /// GeoJSON in longitude and latitude (degrees): `local` projects them to metres
    /// (azimuthal equidistant about the data's centre) and GeoJSON outputs back.
    #[arg(long, value_enum, default_value = "none")]
    project: ProjectArg,
    /// Write the curves here as DXF LINE and ARC entities.
    #[arg(long)]
    dxf: Option<PathBuf>,
    /// Write the curves here as GeoJSON LineStrings (arcs as chords within epsilon).
    #[arg(long)]
    geojson: Option<PathBuf>,
    /// The offset distance (finite, > 0).
    #[arg(long, allow_negative_numbers = true)]
    distance: f64,
    /// Write the curves here (JSON, SCENE_FORMAT.md "Offsets"; `-` for standard output).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write a picture here (SVG): sites, faint diagram edges, offset curves.
    #[arg(long)]
    svg: Option<PathBuf>,
    #[command(flatten)]
    run: progress::RunArgs,
}

#[derive(Args)]
struct VerifyArgs {
    scene: PathBuf,
    diagram: PathBuf,
    /// The scene's format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
    /// The mode, instead of the scene's (as given to `gvd compute`).
    #[arg(long, value_enum)]
    mode: Option<ModeArg>,
    /// GeoJSON in longitude and latitude (degrees): `local` projects them to metres
    /// (azimuthal equidistant about the data's centre) and GeoJSON outputs back.
    #[arg(long, value_enum, default_value = "none")]
    project: ProjectArg,
    /// Completeness grid size (N × N, 2 ≤ N ≤ 4096).
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u64).range(2..=gvd::verify::MAX_GRID as u64))]
    grid: u64,
    /// Tolerance as a multiple of the scene's epsilon (finite, > 0).
    #[arg(long, default_value_t = 1.0, value_parser = positive_length)]
    slack: f64,
}

#[derive(Args)]
struct BenchArgs {
    /// Which table: `emiris-table1`, `implicit`, `shou`, `soft` or `freeform`.
    table: String,
    /// Larger runs: 10^4 and 10^5 Euclidean sites and the multi-core speed-up
    /// (`emiris-table1`, `implicit`), no box cap per run (`shou`).
    #[arg(long)]
    large: bool,
    /// Repetitions per row (the best time is reported).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=1000))]
    repeat: u64,
    /// Only the shipped scenes (`freeform`), for tests.
    #[arg(long, hide = true)]
    quick: bool,
    /// Only the random-segments rows (`soft`).
    #[arg(long)]
    random_only: bool,
    /// Also write the random-segment scenes timed to this directory as
    /// `random-segments-N.json` (`soft`).
    #[arg(long, value_name = "DIR")]
    save_scenes: Option<PathBuf>,
}

/// A finite number > 0 (NaN, infinities, zero and negatives are refused).
fn positive_length(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(x) => Err(format!("must be a finite number > 0, found {x}")),
        Err(e) => Err(e.to_string()),
    }
}

/// An angle in degrees in (0, 180].
fn object_angle_degrees(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x <= 180.0 => Ok(x),
        Ok(x) => Err(format!("must be an angle in (0, 180] degrees, found {x}")),
        Err(e) => Err(e.to_string()),
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum EngineArg {
    Auto,
    Subdivision,
    Incremental,
    Freeform,
}

impl From<EngineArg> for gvd::Engine {
    fn from(e: EngineArg) -> Self {
        match e {
            EngineArg::Auto => gvd::Engine::Auto,
            EngineArg::Subdivision => gvd::Engine::Subdivision,
            EngineArg::Incremental => gvd::Engine::Incremental,
            EngineArg::Freeform => gvd::Engine::Freeform,
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("gvd: error: {}", clip(&format!("{e:#}")));
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Compute(args) => compute(args),
        Command::Offset(args) => offset(args),
        Command::Verify(args) => verify(args),
        Command::Bench(args) => bench(args),
        Command::Completions { shell } => {
            clap_complete::generate(shell, &mut Cli::command(), "gvd", &mut std::io::stdout());
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// `gvd compute`: the diagram, written as JSON and/or SVG.
fn compute(mut args: ComputeArgs) -> Result<ExitCode> {
    for path in std::mem::take(&mut args.output) {
        let slot = match output_kind(&path)? {
            OutputKind::Json => &mut args.json,
            OutputKind::Svg => &mut args.svg,
            OutputKind::Png => &mut args.png,
            OutputKind::GeoJson => &mut args.geojson,
            OutputKind::Dxf => &mut args.dxf,
        };
        let shown = path.display().to_string();
        if let Some(before) = slot.replace(path) {
            bail!(
                "two outputs in one format: {} and {shown}",
                before.display()
            );
        }
    }
    let paths = [&args.json, &args.svg, &args.png, &args.geojson, &args.dxf];
    let summary_only = paths.iter().all(|p| p.is_none());
    let mut outputs = outputs_for(&args.scene, &paths, false)?;
    if let Some(n) = args.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n as usize)
            .build_global()
            .context("cannot start the worker threads")?;
    }
    let sc = read_scene_as(
        &args.scene,
        args.format,
        args.mode.map(Into::into),
        args.project,
    )?;
    let (control, bar) = args.run.control();
    let options = gvd::Options {
        engine: args.engine.into(),
        parallel: args.threads != Some(1),
        subdivision: gvd::SubdivisionOptions {
            max_box: args.max_box,
            limits: gvd::Limits {
                max_boxes: args.max_boxes.map(saturating_usize),
                max_points: args.max_points.map(saturating_usize),
            },
            soft: gvd::SoftFilters {
                zone: !args.no_zone_filter,
                oriented: !args.no_oriented_zones,
                two_edge: !args.no_two_edge_filter,
            },
            ..Default::default()
        },
        incremental: gvd::IncrementalOptions {
            bisectors: args.bisectors,
            strict: args.strict,
        },
        control,
        prune: gvd::Pruning {
            lambda: args.prune_lambda,
            object_angle: args.prune_angle.map(f64::to_radians),
        },
    };
    let out = gvd::compute_with_boxes(&sc, &options);
    progress::finish(bar);
    let out = out.with_context(|| format!("{}", args.scene.display()))?;
    let d = &out.complex;
    let seconds = d.stats.get("seconds").and_then(|v| v.as_f64());
    let boxes = match d.stats.get("boxes") {
        Some(n) => format!(", {n} boxes ({} uncertified)", stat(d, "uncertified_boxes")),
        None => String::new(),
    };
    let summary = format!(
        "{}: {} vertices, {} edges{boxes} in {:.3} s",
        args.scene.display(),
        d.vertices.len(),
        d.edges.len(),
        seconds.unwrap_or(0.0)
    );
    if summary_only {
        // with nothing to write, the summary is the output
        println!("{summary}");
        eprintln!("gvd: nothing written; to keep the diagram, {OUTPUT_HINT}");
    } else {
        eprintln!("{summary}");
    }
    if let Some((c, r)) = d
        .max_inscribed_circle()
        .filter(|_| sc.mode() == gvd::Mode::MedialAxis)
    {
        match sc.projection() {
            Some(p) => {
                let c = p.inverse(c);
                eprintln!(
                    "gvd: largest inscribed circle: centre (longitude {}, latitude {}), radius {r} m",
                    c.x, c.y
                )
            }
            None => eprintln!(
                "gvd: largest inscribed circle: centre ({}, {}), radius {r}",
                c.x, c.y
            ),
        }
    }
    if let Some(p) = d.stats.get("pruning") {
        eprintln!(
            "gvd: pruned from {} vertices and {} edges ({} branch ends cut, {} vertices of degree two merged)",
            p["vertices_before"], p["edges_before"], p["cut_ends"], p["merged_vertices"]
        );
    }
    if let Some(cuts) = split_summary(d) {
        eprintln!("gvd: {cuts} (--strict refuses such input)");
    }
    if let Some(asked) = d.stats.get("epsilon_floored_from").and_then(|v| v.as_f64()) {
        eprintln!(
            "gvd: warning: epsilon {asked:e} is finer than f64 resolves in this domain; the diagram is at resolution {}",
            stat(d, "resolution")
        );
    }
    if let Some(path) = &args.json {
        outputs.write(path, |w| gvd::io::json::write_diagram_to(d, &mut &mut *w))?;
    }
    if args.svg.is_some() || args.png.is_some() {
        let opts = gvd::io::svg::SvgOptions {
            boxes: if args.boxes {
                out.boxes.clone()
            } else {
                Vec::new()
            },
            discs: args.svg_discs,
            ..Default::default()
        };
        let svg = gvd::io::svg::render_svg(&sc, d, &opts);
        if let Some(path) = &args.png {
            let png = gvd::io::png::svg_to_png(&svg)?;
            outputs.write(path, |w| w.write_all(&png))?;
        }
        if let Some(path) = &args.svg {
            outputs.write(path, |w| w.write_all(svg.as_bytes()))?;
        }
    }
    if let Some(path) = &args.geojson {
        let text = gvd::io::geojson::write_diagram(&sc, d);
        outputs.write(path, |w| w.write_all(text.as_bytes()))?;
    }
    if let Some(path) = &args.dxf {
        let text = gvd::io::dxf::write_diagram(d);
        outputs.write(path, |w| w.write_all(text.as_bytes()))?;
    }
    outputs.commit()?;
    // The process ends here: freeing millions of small vectors one by one
    // (0.5 s at 10^6 points) is slower than the kernel taking the pages back.
    std::mem::forget(out);
    std::mem::forget(sc);
    Ok(ExitCode::SUCCESS)
}

/// `gvd offset`: offset curves from the diagram, written as JSON and/or SVG.
fn offset(args: OffsetArgs) -> Result<ExitCode> {
    let mut outputs = outputs_for(
        &args.scene,
        &[&args.json, &args.svg, &args.dxf, &args.geojson],
        true,
    )?;
    gvd::offset::check_distance(args.distance)?;
    let sc = read_scene_as(
        &args.scene,
        args.format,
        args.mode.map(Into::into),
        args.project,
    )?;
    let (control, bar) = args.run.control();
    let options = gvd::Options {
        control,
        ..Default::default()
    };
    let off = gvd::offset::offset_scene(&sc, args.distance, &options);
    progress::finish(bar);
    let (off, diagram) = off.with_context(|| format!("{}", args.scene.display()))?;
    eprintln!(
        "{}: offset at {}: {} curves ({} closed), {} primitives in {:.3} s",
        args.scene.display(),
        args.distance,
        off.curves.len(),
        off.curves.iter().filter(|c| c.closed).count(),
        off.curves.iter().map(|c| c.primitives.len()).sum::<usize>(),
        off.stats
            .get("seconds")
            .and_then(|v| v.as_f64())
            .unwrap_or(0.0)
    );
    if let Some(path) = &args.json {
        let json = off.to_json();
        outputs.write(path, |w| w.write_all(json.as_bytes()))?;
    }
    if let Some(path) = &args.svg {
        let svg = gvd::io::svg::render_offset_svg(&sc, &diagram, &off, &Default::default());
        outputs.write(path, |w| w.write_all(svg.as_bytes()))?;
    }
    if let Some(path) = &args.dxf {
        let text = gvd::io::dxf::write_offset(&off);
        outputs.write(path, |w| w.write_all(text.as_bytes()))?;
    }
    if let Some(path) = &args.geojson {
        let text = gvd::io::geojson::write_offset(&sc, &off, sc.epsilon());
        outputs.write(path, |w| w.write_all(text.as_bytes()))?;
    }
    outputs.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// `gvd verify`: the brute-force check; exit 1 when the diagram fails it.
fn verify(args: VerifyArgs) -> Result<ExitCode> {
    let sc = read_scene_as(
        &args.scene,
        args.format,
        args.mode.map(Into::into),
        args.project,
    )?;
    let text = read_text(&args.diagram)?;
    let d: VoronoiComplex = gvd::io::json::read_diagram(&text)
        .with_context(|| format!("{}", args.diagram.display()))?;
    let opts = gvd::verify::VerifyOptions {
        grid: saturating_usize(args.grid),
        slack: args.slack,
        ..Default::default()
    };
    let report = gvd::verify::verify(&sc, &d, &opts)?;
    for w in &report.warnings {
        eprintln!("gvd: warning: {w}");
    }
    for p in &report.problems {
        println!("  {p}");
    }
    println!("{}", report.summary_line());
    Ok(if report.passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// `gvd bench`: a paper's table.
fn bench(args: BenchArgs) -> Result<ExitCode> {
    let repeat = saturating_usize(args.repeat);
    match args.table.as_str() {
        "emiris-table1" => bench::emiris_table1(args.large, repeat),
        "implicit" => bench_implicit::implicit(args.large, repeat),
        "shou" => bench_algebraic::shou(args.large, repeat),
        "soft" => bench_soft::soft_table(repeat, args.random_only, args.save_scenes.as_deref())?,
        "freeform" => bench_freeform::freeform_table(repeat, args.quick)?,
        other => bail!(
            "unknown table '{}' (known: emiris-table1, implicit, shou, soft, freeform)",
            clip(other)
        ),
    }
    Ok(ExitCode::SUCCESS)
}

/// How to ask for outputs, for messages.
const OUTPUT_HINT: &str =
    "give -o OUT (.json, .svg, .png, .geojson, .dxf), or --json, --svg, --png, --geojson or --dxf OUT";

/// The outputs of a command reading `scene`, each checked (see [`output`]) before any
/// work; at least one is required when `required`.
fn outputs_for(scene: &Path, paths: &[&Option<PathBuf>], required: bool) -> Result<Outputs> {
    let mut outputs = Outputs::new(&[scene]);
    let mut any = false;
    for path in paths.iter().copied().flatten() {
        outputs.claim(path)?;
        any = true;
    }
    if required && !any {
        bail!("nothing to write: {OUTPUT_HINT}");
    }
    Ok(outputs)
}

fn saturating_usize(n: u64) -> usize {
    usize::try_from(n).unwrap_or(usize::MAX)
}

/// At most [`MAX_MESSAGE`] characters of `s`.
fn clip(s: &str) -> String {
    match s.char_indices().nth(MAX_MESSAGE) {
        Some((k, _)) => format!("{}… ({} characters cut)", &s[..k], s[k..].chars().count()),
        None => s.to_string(),
    }
}

/// "split 12 crossings, 3 touches, merged 2 repeated segment pieces" from the stats of
/// the segment engine's cuts, if it made any.
fn split_summary(d: &VoronoiComplex) -> Option<String> {
    let n = |key: &str| d.stats.get(key).and_then(|v| v.as_u64());
    let (c, t, m) = (
        n("split_crossings")?,
        n("split_touches")?,
        n("merged_duplicates")?,
    );
    Some(format!(
        "split segments at {c} crossings and {t} touches, merged {m} repeated segment pieces"
    ))
}

fn stat(d: &VoronoiComplex, key: &str) -> String {
    d.stats
        .get(key)
        .map(|v| v.to_string())
        .unwrap_or_else(|| "-".into())
}

/// The text of `path`, or of standard input for `-`.
fn read_text(path: &Path) -> Result<String> {
    if path.as_os_str() == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .context("cannot read standard input")?;
        return Ok(text);
    }
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}
