//! Writers and readers of scenes and diagrams. Writers never compute geometry: they
//! print what the model holds. Readers of every format build a validated scene through
//! [`crate::SceneBuilder`], with the checks and messages of JSON input.

pub mod dxf;
pub mod file;
pub mod geojson;
pub mod json;
#[cfg(feature = "png")]
pub mod png;
pub mod project;
mod read;
pub mod svg;
pub mod svg_in;
pub mod wkt;

pub use file::write_file;
pub use json::{read_diagram, write_diagram, write_scene};
pub use project::{LocalProjection, Projection};
pub use read::{read_scene, Format, ReadOptions};
pub use svg::{render_svg, SvgOptions};
