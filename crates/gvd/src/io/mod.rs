//! Writers and readers of diagrams. Writers never compute geometry: they print what the
//! model holds.

pub mod json;
pub mod svg;

pub use json::{read_diagram, write_diagram};
pub use svg::{render_svg, SvgOptions};
