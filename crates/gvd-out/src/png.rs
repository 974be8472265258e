//! PNG pictures: the SVG picture of [`gvd::io::svg`] rendered by resvg, so the PNG is the
//! same picture as the SVG.

use anyhow::{Context, Result};

/// The SVG picture rendered to PNG at its own size (`width` and `height` in pixels).
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>> {
    use resvg::{tiny_skia, usvg};
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .context("cannot read the picture back for PNG")?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).context("the picture has no pixels")?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap.encode_png().context("cannot encode the PNG")
}
