//! Scene formats in (by extension or `--format`), outputs by extension (`-o`) and shell
//! completions.

use anyhow::{bail, Context, Result};
use gvd::io::Format;
use gvd::Scene;
use std::io::Read;
use std::path::Path;

/// A scene format named on the command line.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum FormatArg {
    Json,
    Geojson,
    Wkt,
    Dxf,
    Svg,
}

impl From<FormatArg> for Format {
    fn from(f: FormatArg) -> Format {
        match f {
            FormatArg::Json => Format::Json,
            FormatArg::Geojson => Format::GeoJson,
            FormatArg::Wkt => Format::Wkt,
            FormatArg::Dxf => Format::Dxf,
            FormatArg::Svg => Format::Svg,
        }
    }
}

/// The format of `path`: `--format`, else its extension, else (standard input, other
/// extensions) JSON.
fn format_of(path: &Path, given: Option<FormatArg>) -> Result<Format> {
    if let Some(f) = given {
        return Ok(f.into());
    }
    if path.as_os_str() == "-" {
        return Ok(Format::Json);
    }
    match Format::from_path(path) {
        Some(f) => Ok(f),
        None if path.extension().is_none() => Ok(Format::Json),
        None => bail!(
            "cannot tell the format of {} from its extension (.json, .geojson, .wkt, .dxf, .svg): give --format",
            path.display()
        ),
    }
}

/// Reads a scene in its format, warning on stderr about unknown fields and entities not
/// read; `mode` overrides the file's, `project` says how coordinates are taken.
pub fn read_scene_as(
    path: &Path,
    format: Option<FormatArg>,
    mode: Option<gvd::Mode>,
    project: ProjectArg,
) -> Result<Scene> {
    let format = format_of(path, format)?;
    let mut data = Vec::new();
    if path.as_os_str() == "-" {
        std::io::stdin()
            .read_to_end(&mut data)
            .context("cannot read standard input")?;
    } else {
        data = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    }
    let options = gvd::io::ReadOptions {
        mode,
        project: match project {
            ProjectArg::None => gvd::io::Projection::None,
            ProjectArg::Local => gvd::io::Projection::Local,
        },
        ..Default::default()
    };
    let (scene, warnings) = gvd::io::read_scene(&data, format, &options)
        .with_context(|| format!("{}", path.display()))?;
    for w in warnings {
        eprintln!("gvd: warning: {}: {w}", path.display());
    }
    Ok(scene)
}

/// How a scene's coordinates are taken (`--project`).
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ProjectArg {
    /// Planar, as they are.
    None,
    /// Longitude and latitude, projected about the data's centre.
    Local,
}

/// A mode named on the command line.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ModeArg {
    Voronoi,
    Complex,
    #[value(name = "medial_axis", alias = "medial-axis")]
    MedialAxis,
}

impl From<ModeArg> for gvd::Mode {
    fn from(m: ModeArg) -> gvd::Mode {
        match m {
            ModeArg::Voronoi => gvd::Mode::Voronoi,
            ModeArg::Complex => gvd::Mode::Complex,
            ModeArg::MedialAxis => gvd::Mode::MedialAxis,
        }
    }
}

/// What `gvd compute` writes to an `-o` path, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    Json,
    Svg,
    Png,
    GeoJson,
    Dxf,
}

/// The kind of an `-o` path: by its extension (`.json`, `.svg`, `.png`, `.geojson`,
/// `.dxf`, case ignored); `-` is JSON on standard output.
pub fn output_kind(path: &Path) -> Result<OutputKind> {
    if path.as_os_str() == "-" {
        return Ok(OutputKind::Json);
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    Ok(match ext.as_deref() {
        Some("json") => OutputKind::Json,
        Some("svg") => OutputKind::Svg,
        Some("png") => OutputKind::Png,
        Some("geojson") => OutputKind::GeoJson,
        Some("dxf") => OutputKind::Dxf,
        _ => bail!(
            "cannot tell what to write to {} from its extension (.json, .svg, .png, .geojson, .dxf): give --json, --svg, --png, --geojson or --dxf",
            path.display()
        ),
    })
}
