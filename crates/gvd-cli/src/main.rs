//! `gvd`: generalized Voronoi diagrams from the command line.

mod bench;
mod bench_implicit;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use gvd::{Scene, VoronoiComplex};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
    Compute {
        /// The scene (JSON, see SCENE_FORMAT.md).
        scene: PathBuf,
        /// Write the diagram here (JSON).
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write a picture here (SVG).
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Draw the subdivision boxes in the picture.
        #[arg(long)]
        boxes: bool,
        /// Split boxes that hold two or more sites until no longer than this.
        #[arg(long)]
        max_box: Option<f64>,
        /// Worker threads (default: all cores; 1 = sequential).
        #[arg(long)]
        threads: Option<usize>,
        /// Algorithm family: `auto` takes the incremental engine for scenes of Euclidean
        /// points and the subdivision engine otherwise.
        #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
        engine: EngineArg,
        /// Give every edge of the incremental engine its exact bisector: `bisector`,
        /// pieces in Held's offset-parameter form with their clearance ranges.
        #[arg(long)]
        bisectors: bool,
    },
    /// Offset curves (lines and arcs) at a distance from the sites, derived from the
    /// diagram (in `complex` mode for a `voronoi` scene; inside the region in
    /// `medial_axis` mode: a pocket).
    Offset {
        /// The scene (JSON, see SCENE_FORMAT.md).
        scene: PathBuf,
        /// The offset distance (finite, > 0).
        #[arg(long, allow_negative_numbers = true)]
        distance: f64,
        /// Write the curves here (JSON, SCENE_FORMAT.md "Offsets").
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write a picture here (SVG): sites, faint diagram edges, offset curves.
        #[arg(long)]
        svg: Option<PathBuf>,
    },
    /// Check a diagram against its scene by brute force (independent of the engines).
    Verify {
        scene: PathBuf,
        diagram: PathBuf,
        /// Completeness grid size (N × N).
        #[arg(long, default_value_t = 512)]
        grid: usize,
        /// Tolerance as a multiple of the scene's epsilon.
        #[arg(long, default_value_t = 1.0)]
        slack: f64,
    },
    /// Reproduce a paper's table of timings and box counts.
    Bench {
        /// Which table: `emiris-table1`.
        table: String,
        /// Also run 10^4 and 10^5 Euclidean sites and the multi-core speed-up.
        #[arg(long)]
        large: bool,
        /// Repetitions per row (the best time is reported).
        #[arg(long, default_value_t = 3)]
        repeat: usize,
    },
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum EngineArg {
    Auto,
    Subdivision,
    Incremental,
}

impl From<EngineArg> for gvd::Engine {
    fn from(e: EngineArg) -> Self {
        match e {
            EngineArg::Auto => gvd::Engine::Auto,
            EngineArg::Subdivision => gvd::Engine::Subdivision,
            EngineArg::Incremental => gvd::Engine::Incremental,
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("gvd: error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Compute {
            scene,
            json,
            svg,
            boxes,
            max_box,
            threads,
            engine,
            bisectors,
        } => {
            if json.is_none() && svg.is_none() {
                bail!("nothing to write: give --json OUT.json and/or --svg OUT.svg");
            }
            if let Some(n) = threads {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n.max(1))
                    .build_global()?;
            }
            let sc = read_scene(&scene)?;
            let options = gvd::Options {
                engine: engine.into(),
                parallel: threads != Some(1),
                subdivision: gvd::SubdivisionOptions {
                    max_box,
                    ..Default::default()
                },
                incremental: gvd::IncrementalOptions { bisectors },
            };
            let out = gvd::compute_with_boxes(&sc, &options)
                .with_context(|| format!("{}", scene.display()))?;
            let d = &out.complex;
            eprintln!(
                "{}: {} vertices, {} edges, {} boxes ({} uncertified) in {:.3} s",
                scene.display(),
                d.vertices.len(),
                d.edges.len(),
                stat(d, "boxes"),
                stat(d, "uncertified_boxes"),
                d.stats
                    .get("seconds")
                    .and_then(|v| v.as_f64())
                    .unwrap_or(0.0)
            );
            if let Some(path) = json {
                write_atomic_with(&path, |w| gvd::io::json::write_diagram_to(d, w))?;
            }
            if let Some(path) = svg {
                let opts = gvd::io::svg::SvgOptions {
                    boxes: if boxes { out.boxes.clone() } else { Vec::new() },
                    ..Default::default()
                };
                write_atomic(&path, &gvd::io::svg::render_svg(&sc, d, &opts))?;
            }
            // The process ends here: freeing millions of small vectors one by one
            // (0.5 s at 10^6 points) is slower than the kernel taking the pages back.
            std::mem::forget(out);
            std::mem::forget(sc);
            Ok(ExitCode::SUCCESS)
        }
        Command::Offset {
            scene,
            distance,
            json,
            svg,
        } => {
            if json.is_none() && svg.is_none() {
                bail!("nothing to write: give --json OUT.json and/or --svg OUT.svg");
            }
            gvd::offset::check_distance(distance)?;
            let sc = read_scene(&scene)?;
            let (off, diagram) = gvd::offset::offset_scene(&sc, distance, &Default::default())
                .with_context(|| format!("{}", scene.display()))?;
            eprintln!(
                "{}: offset at {distance}: {} curves ({} closed), {} primitives in {:.3} s",
                scene.display(),
                off.curves.len(),
                off.curves.iter().filter(|c| c.closed).count(),
                off.curves.iter().map(|c| c.primitives.len()).sum::<usize>(),
                off.stats
                    .get("seconds")
                    .and_then(|v| v.as_f64())
                    .unwrap_or(0.0)
            );
            if let Some(path) = json {
                write_atomic(&path, &off.to_json())?;
            }
            if let Some(path) = svg {
                let svg = gvd::io::svg::render_offset_svg(&sc, &diagram, &off, &Default::default());
                write_atomic(&path, &svg)?;
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Verify {
            scene,
            diagram,
            grid,
            slack,
        } => {
            let sc = read_scene(&scene)?;
            let text = std::fs::read_to_string(&diagram)
                .with_context(|| format!("cannot read {}", diagram.display()))?;
            let d: VoronoiComplex = gvd::io::json::read_diagram(&text)
                .with_context(|| format!("{}", diagram.display()))?;
            let opts = gvd::verify::VerifyOptions {
                grid,
                slack,
                ..Default::default()
            };
            let report = gvd::verify::verify(&sc, &d, &opts)?;
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
        Command::Bench {
            table,
            large,
            repeat,
        } => match table.as_str() {
            "emiris-table1" => {
                bench::emiris_table1(large, repeat.max(1));
                Ok(ExitCode::SUCCESS)
            }
            "implicit" => {
                bench_implicit::implicit(large, repeat.max(1));
                Ok(ExitCode::SUCCESS)
            }
            other => bail!("unknown table '{other}' (known: emiris-table1)"),
        },
    }
}

fn stat(d: &VoronoiComplex, key: &str) -> String {
    d.stats
        .get(key)
        .map(|v| v.to_string())
        .unwrap_or_else(|| "-".into())
}

fn read_scene(path: &Path) -> Result<Scene> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    Scene::from_json(&text).with_context(|| format!("{}", path.display()))
}

/// Writes through a temporary file in the same directory and renames it into place, so
/// that a failure never leaves a half-written output.
fn write_atomic(path: &Path, contents: &str) -> Result<()> {
    write_atomic_with(path, |w| w.write_all(contents.as_bytes()))
}

/// Writes a file through `write` (into a buffered temporary file, then renamed), so a
/// large output is never held whole in memory.
///
/// A symbolic link is followed, so the link stays and its target is replaced. A path
/// that is not a regular file (`/dev/stdout`, `/dev/null`, a FIFO) is written in place:
/// renaming over it would replace the device with a plain file.
fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> Result<()> {
    let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let in_place = std::fs::metadata(&target).is_ok_and(|m| !m.is_file());
    let tmp = if in_place {
        target.clone()
    } else {
        let dir = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let name = target.file_name().context("output path has no file name")?;
        dir.join(format!(".{}.tmp", name.to_string_lossy()))
    };
    let written = std::fs::File::create(&tmp).and_then(|file| {
        let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
        write(&mut w)?;
        w.flush()
    });
    if let Err(e) = written {
        if !in_place {
            let _ = std::fs::remove_file(&tmp);
        }
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    if !in_place {
        std::fs::rename(&tmp, &target)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}
