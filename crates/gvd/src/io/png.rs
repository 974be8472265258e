//! PNG pictures (feature `png`): the SVG picture of [`super::svg`] rasterised by resvg,
//! so the PNG is the same picture as the SVG, pixel for pixel at the SVG's own size.

use crate::{Scene, VoronoiComplex};
use resvg::{tiny_skia, usvg};

/// Why a picture could not be made into PNG.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct PngError(String);

/// The SVG picture rendered to PNG at its own size (`width` and `height` in pixels).
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, PngError> {
    let fail = |what: &str, e: &dyn std::fmt::Display| PngError(format!("{what}: {e}"));
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| fail("cannot read the picture back for PNG", &e))?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| PngError("the picture has no pixels".into()))?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap
        .encode_png()
        .map_err(|e| fail("cannot encode the PNG", &e))
}

/// The picture of [`super::svg::render_svg`] as PNG.
pub fn render_png(
    scene: &Scene,
    diagram: &VoronoiComplex,
    opts: &super::SvgOptions,
) -> Result<Vec<u8>, PngError> {
    svg_to_png(&super::render_svg(scene, diagram, opts))
}
