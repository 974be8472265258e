//! What gvd's front ends (the `gvd` CLI and the Python package) share to write outputs:
//! files written all or none ([`Outputs`]) and PNG pictures ([`svg_to_png`]).

mod output;
mod png;

pub use output::Outputs;
pub use png::svg_to_png;
