//! A small SVG writer: the domain frame, cells, edges, vertices and sites of a diagram
//! (and offset curves over them), with `y` pointing up. Numbers are printed with a
//! fixed number of decimals chosen from the domain size (about 6 significant digits,
//! never in exponent notation), so the output is byte-identical across runs and
//! platforms.

use crate::complex::VoronoiComplex;
use crate::geom::bezier::RationalBezier;
use crate::geom::bspline::RationalBspline;
use crate::geom::{Aabb, Point};
use crate::num::poly::Poly;
use crate::offset::model::{Curve, Offset, Primitive};
use crate::scene::{Scene, SiteKind};
use std::fmt::Write;

/// Drawing options.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgOptions {
    /// Subdivision boxes with their number of active sites, drawn as thin outlines
    /// coloured by the count, under everything else.
    pub boxes: Vec<(Aabb, usize)>,
    /// The picture's width in pixels (the height follows the domain's aspect).
    pub width_px: f64,
    /// Draw the maximal empty disc at each vertex that knows its clearance
    /// ([`crate::complex::Vertex::clearance`]), as a thin circle.
    pub discs: bool,
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions {
            boxes: Vec::new(),
            width_px: 800.0,
            discs: false,
        }
    }
}

/// Fixed-decimal number formatting and the flip `(x, y) ↦ (x, −y)`.
struct Fmt {
    decimals: usize,
}

impl Fmt {
    fn num(&self, v: f64) -> String {
        let s = format!("{:.*}", self.decimals, v);
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.')
        } else {
            &s
        };
        if s == "-0" {
            "0".into()
        } else {
            s.into()
        }
    }
    /// `x,y` in SVG coordinates.
    fn pt(&self, p: Point) -> String {
        format!("{},{}", self.num(p.x), self.num(-p.y))
    }
    /// The attributes of a `rect` covering `b`.
    fn rect(&self, b: Aabb) -> String {
        format!(
            "x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"",
            self.num(b.min.x),
            self.num(-b.max.y),
            self.num(b.width()),
            self.num(b.height())
        )
    }
    /// A path through `points`, closed with `Z` if `close`.
    fn path(&self, d: &mut String, points: &[Point], close: bool) {
        for (i, &p) in points.iter().enumerate() {
            d.push(if i == 0 { 'M' } else { 'L' });
            d.push_str(&self.pt(p));
        }
        if close && !points.is_empty() {
            d.push('Z');
        }
    }
}

/// `text` with the five XML special characters escaped, for element content and
/// attribute values.
fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// A light pastel colour for site `i` (hues spaced by the golden ratio).
fn pastel(i: usize) -> String {
    let h = (i as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let (s, l) = (0.55, 0.85);
    let c = (1.0 - (2.0 * l - 1.0f64).abs()) * s;
    let x = c * (1.0 - (h % 2.0 - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = l - c / 2.0;
    let byte = |v: f64| ((v + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b))
}

/// The outline colour of a subdivision box with `n` active sites.
fn box_colour(n: usize) -> &'static str {
    match n {
        0 => "#bdbdbd",
        1 => "#43a047",
        2 => "#1e88e5",
        3 => "#fb8c00",
        _ => "#e53935",
    }
}

/// Renders the diagram of `scene` as an SVG document.
pub fn render_svg(scene: &Scene, diagram: &VoronoiComplex, opts: &SvgOptions) -> String {
    let (mut s, f, size) = open_svg(scene, opts);
    let sw = |k: f64| f.num(k * size);
    if !opts.boxes.is_empty() {
        let _ = writeln!(
            s,
            "<g id=\"boxes\" fill=\"none\" stroke-width=\"{}\">",
            sw(0.0008)
        );
        for &(b, n) in &opts.boxes {
            let _ = writeln!(s, "<rect {} stroke=\"{}\"/>", f.rect(b), box_colour(n));
        }
        s.push_str("</g>\n");
    }
    if !diagram.cells.is_empty() {
        s.push_str("<g id=\"cells\" stroke=\"none\" fill-opacity=\"0.7\" fill-rule=\"evenodd\">\n");
        for c in &diagram.cells {
            let mut d = String::new();
            for ring in &c.rings {
                f.path(&mut d, ring, true);
            }
            // A cell of a site with an id carries its title (a tooltip in viewers).
            let end = match scene.sites().get(c.site).and_then(|x| x.id.as_deref()) {
                Some(id) => format!("><title>{}</title></path>", xml_escape(id)),
                None => "/>".into(),
            };
            let _ = writeln!(s, "<path d=\"{d}\" fill=\"{}\"{end}", pastel(c.site));
        }
        s.push_str("</g>\n");
    }
    write_domain(&mut s, scene, &f, size);
    // Sites under the edges: a polygon's fill would hide its medial axis.
    write_sites(&mut s, scene, &f, size);
    let t_max = write_edges(&mut s, diagram, &f, "#2b6cb0", &sw(0.0025));
    if t_max > 0.0 {
        write_clearance_legend(&mut s, scene.domain(), &f, t_max);
    }
    if opts.discs {
        let _ = writeln!(
            s,
            "<g id=\"discs\" fill=\"none\" stroke=\"#d32f2f\" stroke-opacity=\"0.5\" stroke-width=\"{}\">",
            sw(0.001)
        );
        for v in &diagram.vertices {
            if let Some(r) = v.clearance.filter(|r| *r > 0.0) {
                let _ = writeln!(
                    s,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                    f.num(v.at.x),
                    f.num(-v.at.y),
                    f.num(r)
                );
            }
        }
        s.push_str("</g>\n");
    }
    let _ = writeln!(s, "<g id=\"vertices\" fill=\"#d32f2f\">");
    for v in &diagram.vertices {
        let _ = writeln!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
            f.num(v.at.x),
            f.num(-v.at.y),
            sw(0.003)
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// Renders offset curves over their scene: the sites, the diagram's edges drawn thin
/// and grey over them, and the curves as SVG lines and arcs (`A` commands, so arcs stay
/// exact at any zoom); `opts.boxes` is not drawn.
pub fn render_offset_svg(
    scene: &Scene,
    diagram: &VoronoiComplex,
    offset: &Offset,
    opts: &SvgOptions,
) -> String {
    let (mut s, f, size) = open_svg(scene, opts);
    write_domain(&mut s, scene, &f, size);
    // sites first: a polygon's fill would hide the edges inside it
    write_sites(&mut s, scene, &f, size);
    write_edges(&mut s, diagram, &f, "#9a9aa6", &f.num(0.0012 * size));
    let _ = writeln!(
        s,
        "<g id=\"offsets\" fill=\"none\" stroke=\"#d81b60\" stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\">",
        f.num(0.003 * size)
    );
    for curve in &offset.curves {
        let _ = writeln!(s, "<path d=\"{}\"/>", curve_path(&f, curve));
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// An offset curve as path data: `M` at its start, `L` per line, `A` per arc (split into
/// halves of at most a half turn, so that no arc's ends coincide), `Z` if closed.
fn curve_path(f: &Fmt, curve: &Curve) -> String {
    let mut d = String::new();
    if let Some(first) = curve.primitives.first() {
        d.push('M');
        d.push_str(&f.pt(first.start()));
    }
    for prim in &curve.primitives {
        match *prim {
            Primitive::Line { to, .. } => {
                d.push('L');
                d.push_str(&f.pt(to));
            }
            Primitive::Arc {
                start_angle,
                end_angle,
                radius,
                ..
            } => {
                let halves = if (end_angle - start_angle).abs() > std::f64::consts::PI {
                    2
                } else {
                    1
                };
                // y is flipped, so counter-clockwise is the negative-angle sweep (0)
                let sweep = u8::from(end_angle < start_angle);
                for k in 1..=halves {
                    let r = f.num(radius);
                    let end = prim.point_at(k as f64 / halves as f64);
                    let _ = write!(d, "A{r},{r} 0 0 {sweep} {}", f.pt(end));
                }
            }
        }
    }
    if curve.closed {
        d.push('Z');
    }
    d
}

/// The SVG element with its view box, and the white background; the number format and
/// the domain's longest side (line widths are fractions of it).
fn open_svg(scene: &Scene, opts: &SvgOptions) -> (String, Fmt, f64) {
    let dom = scene.domain();
    let size = dom.longest_side();
    let f = Fmt {
        decimals: (5 - size.log10().floor() as i64).clamp(0, 15) as usize,
    };
    let margin = 0.03 * size;
    let (vw, vh) = (dom.width() + 2.0 * margin, dom.height() + 2.0 * margin);
    let (x0, y0) = (dom.min.x - margin, -(dom.max.y + margin));
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"{} {} {} {}\">",
        opts.width_px.round(),
        (opts.width_px * vh / vw).round(),
        f.num(x0),
        f.num(y0),
        f.num(vw),
        f.num(vh)
    );
    let _ = writeln!(
        s,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>",
        f.num(x0),
        f.num(y0),
        f.num(vw),
        f.num(vh)
    );
    (s, f, size)
}

/// The domain's frame.
fn write_domain(s: &mut String, scene: &Scene, f: &Fmt, size: f64) {
    let _ = writeln!(
        s,
        "<rect id=\"domain\" {} fill=\"none\" stroke=\"#555555\" stroke-width=\"{}\"/>",
        f.rect(scene.domain()),
        f.num(0.002 * size)
    );
}

/// The diagram's edges as polylines of the given colour and width, or coloured by
/// clearance where known: from their exact bisectors, else from their points'
/// clearances ([`crate::complex::Edge::clearance`]). Returns the largest clearance drawn
/// (0 if none), for the legend of the colours.
fn write_edges(
    s: &mut String,
    diagram: &VoronoiComplex,
    f: &Fmt,
    colour: &str,
    width: &str,
) -> f64 {
    let _ = writeln!(
        s,
        "<g id=\"edges\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{width}\" stroke-linejoin=\"round\" stroke-linecap=\"round\">"
    );
    let t_max = diagram
        .edges
        .iter()
        .flat_map(|e| {
            let exact = e.bisector.iter().flat_map(|p| p.t);
            exact.chain(e.clearance.iter().copied())
        })
        .filter(|t| t.is_finite())
        .fold(0.0f64, f64::max);
    let line = |s: &mut String, a: Point, b: Point, t: f64| {
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\"/>",
            f.num(a.x),
            f.num(-a.y),
            f.num(b.x),
            f.num(-b.y),
            viridis(t / t_max)
        );
    };
    for e in &diagram.edges {
        if t_max > 0.0 && e.bisector.is_empty() && !e.clearance.is_empty() {
            for (p, r) in e.points.windows(2).zip(e.clearance.windows(2)) {
                line(s, p[0], p[1], 0.5 * (r[0] + r[1]));
            }
            continue;
        }
        if e.bisector.is_empty() || t_max <= 0.0 {
            let pts: Vec<String> = e.points.iter().map(|&p| f.pt(p)).collect();
            let _ = writeln!(s, "<polyline points=\"{}\"/>", pts.join(" "));
            continue;
        }
        const STEPS: usize = 8;
        for piece in &e.bisector {
            let t = |k: usize| piece.t[0] + (piece.t[1] - piece.t[0]) * k as f64 / STEPS as f64;
            for k in 0..STEPS {
                line(
                    s,
                    piece.at(t(k)),
                    piece.at(t(k + 1)),
                    0.5 * (t(k) + t(k + 1)),
                );
            }
        }
    }
    s.push_str("</g>\n");
    t_max
}

/// The colour of `x ∈ [0, 1]` on the viridis scale (five stops, linear between).
fn viridis(x: f64) -> String {
    const STOPS: [[f64; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let x = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    } * 4.0;
    let k = (x.floor() as usize).min(3);
    let w = x - k as f64;
    let c = |i: usize| (STOPS[k][i] * (1.0 - w) + STOPS[k + 1][i] * w).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(0), c(1), c(2))
}

/// A bar of the clearance colours along the domain's bottom edge, labelled 0 and
/// `t_max`.
fn write_clearance_legend(s: &mut String, domain: Aabb, f: &Fmt, t_max: f64) {
    let (lo, hi) = (domain.min, domain.max);
    let (w, h) = (hi.x - lo.x, hi.y - lo.y);
    let size = w.max(h);
    let (x0, y0, bar_w, bar_h) = (lo.x + 0.02 * w, lo.y + 0.02 * h, 0.3 * w, 0.015 * size);
    let _ = writeln!(s, "<g id=\"clearance-legend\" stroke=\"none\">");
    s.push_str("<linearGradient id=\"clearance-scale\">");
    for k in 0..=4 {
        let x = k as f64 / 4.0;
        let _ = write!(s, "<stop offset=\"{x}\" stop-color=\"{}\"/>", viridis(x));
    }
    s.push_str("</linearGradient>\n");
    let _ = writeln!(
        s,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"url(#clearance-scale)\"/>",
        f.num(x0),
        f.num(-(y0 + bar_h)),
        f.num(bar_w),
        f.num(bar_h)
    );
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" font-size=\"{}\" font-family=\"sans-serif\" fill=\"#000000\">clearance 0 … {}</text>",
        f.num(x0 + bar_w * 1.03),
        f.num(-(y0 + 0.1 * bar_h)),
        f.num(1.2 * bar_h),
        fmt_len(t_max)
    );
    s.push_str("</g>\n");
}

/// A length with 3 significant digits.
fn fmt_len(x: f64) -> String {
    format!("{x:.3e}")
        .parse::<f64>()
        .map_or_else(|_| x.to_string(), |v| v.to_string())
}

/// The sites: points as dots, circles and ellipses as outlines, curves as strokes;
/// field sites are not drawn.
fn write_sites(s: &mut String, scene: &Scene, f: &Fmt, size: f64) {
    let _ = writeln!(
        s,
        "<g id=\"sites\" fill=\"none\" stroke=\"#000000\" stroke-width=\"{}\">",
        f.num(0.002 * size)
    );
    let stroke = |s: &mut String, pts: &[Point], close: bool, extra: &str| {
        let mut d = String::new();
        f.path(&mut d, pts, close);
        let _ = writeln!(s, "<path d=\"{d}\"{extra}/>");
    };
    for site in scene.sites() {
        // A site with an id is a group whose title names it (a tooltip in viewers).
        if let Some(id) = &site.id {
            let _ = writeln!(s, "<g><title>{}</title>", xml_escape(id));
        }
        match &site.kind {
            SiteKind::Point { at, .. } => {
                let _ = writeln!(
                    s,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#000000\" stroke=\"none\"/>",
                    f.num(at.x),
                    f.num(-at.y),
                    f.num(0.004 * size)
                );
            }
            SiteKind::Circle { center, radius } => {
                let _ = writeln!(
                    s,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                    f.num(center.x),
                    f.num(-center.y),
                    f.num(*radius)
                );
            }
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => {
                let (cx, cy) = (f.num(center.x), f.num(-center.y));
                let _ = writeln!(
                    s,
                    "<ellipse cx=\"{cx}\" cy=\"{cy}\" rx=\"{}\" ry=\"{}\" transform=\"rotate({} {cx} {cy})\"/>",
                    f.num(semi_axes[0]),
                    f.num(semi_axes[1]),
                    f.num(-rotation.to_degrees())
                );
            }
            SiteKind::Segment { from, to } => stroke(s, &[*from, *to], false, ""),
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                let sweep = crate::geom::arc::sweep(*start_angle, *end_angle);
                let pts: Vec<Point> = (0..=64)
                    .map(|k| {
                        let a = start_angle + sweep * k as f64 / 64.0;
                        *center + Point::new(a.cos(), a.sin()) * *radius
                    })
                    .collect();
                stroke(s, &pts, false, "");
            }
            SiteKind::Polyline { points } => stroke(s, points, false, ""),
            SiteKind::Polygon { rings } => {
                let mut d = String::new();
                for r in rings {
                    f.path(&mut d, r, true);
                }
                let _ = writeln!(
                    s,
                    "<path d=\"{d}\" fill=\"#e0e0e0\" fill-rule=\"evenodd\"/>"
                );
            }
            SiteKind::Bezier {
                control_points,
                weights,
            } => stroke(
                s,
                &RationalBezier::new(control_points, weights.as_deref()).sample(64),
                false,
                "",
            ),
            SiteKind::Bspline {
                degree,
                control_points,
                knots,
                weights,
                ..
            } => stroke(
                s,
                &RationalBspline::new(*degree, control_points, knots, weights.as_deref())
                    .sample(32),
                false,
                "",
            ),
            SiteKind::Algebraic { equation, clip } => {
                let window = clip.unwrap_or(scene.domain()).intersection(&scene.domain());
                if let Some(window) = window {
                    let mut d = String::new();
                    for [a, b] in zero_contour(equation.poly(), &window, CONTOUR_CELLS) {
                        f.path(&mut d, &[a, b], false);
                    }
                    let _ = writeln!(s, "<path d=\"{d}\"/>");
                }
            }
            SiteKind::Field { .. } | SiteKind::ImplicitField { .. } => {}
        }
        if site.id.is_some() {
            s.push_str("</g>\n");
        }
    }
    s.push_str("</g>\n");
}

/// Grid cells per side for drawing an algebraic curve.
const CONTOUR_CELLS: usize = 400;

/// The zero set of `f(x, y)` over `window` for drawing: marching squares on an `n × n`
/// grid, each crossing placed by linear interpolation of `f` along the cell side; a
/// cell with crossings on all four sides (a saddle) is joined by the asymptotic decider.
/// A picture, not a certificate: features below the grid's spacing may be lost.
fn zero_contour(f: &Poly, window: &Aabb, n: usize) -> Vec<[Point; 2]> {
    let at = |i: usize, j: usize| window.at(i as f64 / n as f64, j as f64 / n as f64);
    let value = |p: Point| f.eval(p.x, p.y, 0.0);
    let values: Vec<f64> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| (i, j)))
        .map(|(i, j)| value(at(i, j)))
        .collect();
    let v = |i: usize, j: usize| values[j * (n + 1) + i];
    let cross = |p: Point, q: Point, fp: f64, fq: f64| {
        let t = if fp == fq { 0.5 } else { fp / (fp - fq) };
        p + (q - p) * t
    };
    let mut segments = Vec::new();
    for j in 0..n {
        for i in 0..n {
            // corners counter-clockwise from the lower left; side k joins corner k to k+1
            let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let fs = corners.map(|(a, b)| v(a, b));
            let ps = corners.map(|(a, b)| at(a, b));
            let mut hits: Vec<(usize, Point)> = Vec::with_capacity(4);
            for k in 0..4 {
                let (fa, fb) = (fs[k], fs[(k + 1) % 4]);
                if (fa < 0.0) != (fb < 0.0) {
                    hits.push((k, cross(ps[k], ps[(k + 1) % 4], fa, fb)));
                }
            }
            match hits.len() {
                2 => segments.push([hits[0].1, hits[1].1]),
                4 => {
                    // a saddle, decided by the bilinear interpolant's value at its own
                    // saddle point: where that has the sign of corners 0 and 2 they are
                    // joined, and the curve cuts off corners 1 and 3 (sides 0–1, 2–3)
                    let saddle = (fs[0] * fs[2] - fs[1] * fs[3]) / (fs[0] + fs[2] - fs[1] - fs[3]);
                    let skip = usize::from((saddle < 0.0) != (fs[0] < 0.0));
                    segments.push([hits[skip].1, hits[skip + 1].1]);
                    segments.push([hits[(skip + 2) % 4].1, hits[(skip + 3) % 4].1]);
                }
                _ => {}
            }
        }
    }
    segments
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_contour_follows_the_curve() {
        let circle = Poly::parse("x^2 + y^2 - 1", &['x', 'y']).unwrap();
        let window = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        let segments = zero_contour(&circle, &window, 64);
        let length: f64 = segments.iter().map(|[a, b]| a.dist(*b)).sum();
        assert!((length - std::f64::consts::TAU).abs() < 0.01 * std::f64::consts::TAU);
        let h = 4.0 / 64.0;
        for [a, b] in &segments {
            assert!((a.norm() - 1.0).abs() < h * h && (b.norm() - 1.0).abs() < h * h);
        }
        // a hyperbola whose two branches pass through one cell (a saddle): a wrong
        // pairing there joins a point of one branch (x < 1/128) to the other (x > 1/128)
        let hyperbola = Poly::parse("(x - 1/128) * (y - 1/128) - 1/100000", &['x', 'y']).unwrap();
        let window = Aabb::from_array([-1.0, -1.0, 1.0, 1.0]);
        for [a, b] in zero_contour(&hyperbola, &window, 64) {
            assert_eq!(a.x < 1.0 / 128.0, b.x < 1.0 / 128.0, "{a:?} to {b:?}");
        }
    }
    use crate::complex::{smallvec, Cell, Edge, Generator, Vertex};
    use crate::scene::{Metric, Mode, Site};

    /// Every opened tag is closed in order (a simple well-formedness check).
    fn balanced(svg: &str) -> bool {
        let mut stack: Vec<&str> = Vec::new();
        let mut rest = svg;
        while let Some(i) = rest.find('<') {
            let Some(j) = rest[i..].find('>') else {
                return false;
            };
            let tag = &rest[i + 1..i + j];
            rest = &rest[i + j + 1..];
            if tag.contains('<') || tag.matches('"').count() % 2 != 0 {
                return false;
            }
            if let Some(name) = tag.strip_prefix('/') {
                if stack.pop() != Some(name) {
                    return false;
                }
            } else if !tag.ends_with('/') {
                stack.push(tag.split_whitespace().next().unwrap_or(""));
            }
        }
        stack.is_empty()
    }

    /// A B-spline is drawn as its curve, not its control polygon: the drawn path passes
    /// through points of the curve, and not through its outer control points.
    #[test]
    fn a_bspline_is_drawn_as_its_curve() {
        let p = |x, y| Point::new(x, y);
        let control = vec![
            p(-1.0, 0.0),
            p(-0.5, 0.9),
            p(0.0, -0.9),
            p(0.5, 0.9),
            p(1.0, 0.0),
        ];
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let kind = SiteKind::Bspline {
            degree: 3,
            control_points: control.clone(),
            knots: knots.clone(),
            weights: None,
            closed: false,
        };
        let scene = Scene::new(
            Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
            1e-3,
            Mode::Voronoi,
            vec![Site { id: None, kind }],
        )
        .expect("a valid scene");
        let svg = render_svg(&scene, &VoronoiComplex::default(), &SvgOptions::default());
        let sites = &svg[svg.find("<g id=\"sites\"").unwrap()..];
        let d = &sites[sites.find(" d=\"").unwrap() + 4..];
        let d = &d[..d.find('"').unwrap()];
        let numbers: Vec<f64> = d
            .split(|c: char| c.is_ascii_alphabetic() || c == ' ' || c == ',')
            .filter(|t| !t.is_empty())
            .map(|t| t.parse().unwrap())
            .collect();
        let drawn: Vec<Point> = numbers.chunks(2).map(|c| p(c[0], -c[1])).collect();
        assert!(drawn.len() > 50, "{} points", drawn.len());
        let curve = RationalBspline::new(3, &control, &knots, None);
        for t in [0.1, 0.37, 0.5, 0.81] {
            let on = curve.eval(t);
            let nearest = drawn
                .iter()
                .map(|q| q.dist(on))
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 0.05, "C({t}) is {nearest} from the drawing");
        }
        for c in &control[1..4] {
            assert!(
                drawn.iter().all(|q| q.dist(*c) > 0.1),
                "control point {c:?} drawn"
            );
        }
    }

    #[test]
    fn well_formed_and_deterministic() {
        let site = |kind| Site { id: None, kind };
        let p = |x, y| Point::new(x, y);
        let scene = Scene::new(
            Aabb::from_array([-2.0, -1.0, 2.0, 1.0]),
            1e-3,
            Mode::Voronoi,
            vec![
                site(SiteKind::Point {
                    at: p(-1.0, 0.0),
                    metric: Metric::Euclidean,
                }),
                site(SiteKind::Circle {
                    center: p(1.0, 0.0),
                    radius: 0.25,
                }),
                site(SiteKind::Ellipse {
                    center: p(0.0, 0.5),
                    semi_axes: [0.3, 0.1],
                    rotation: 0.5,
                }),
                site(SiteKind::Arc {
                    center: p(0.0, -0.5),
                    radius: 0.2,
                    start_angle: 0.0,
                    end_angle: 3.0,
                }),
                site(SiteKind::Bezier {
                    control_points: vec![p(1.0, 0.5), p(1.5, 0.9), p(1.9, 0.5)],
                    weights: None,
                }),
            ],
        )
        .expect("a valid scene");
        let g = Generator::Site;
        let diagram = VoronoiComplex {
            vertices: vec![Vertex {
                clearance: None,
                at: p(0.0, 0.0),
                sites: smallvec![g(0), g(1), g(2)],
            }],
            edges: vec![
                Edge {
                    clearance: Vec::new(),
                    sites_along: Vec::new(),
                    sites: [g(0), g(1)],
                    from: Some(0),
                    bisector: Vec::new(),
                    parametric: Vec::new(),
                    to: None,
                    points: smallvec![p(0.0, 0.0), p(0.1, -0.5), p(0.0, -1.0)],
                },
                Edge {
                    clearance: Vec::new(),
                    sites_along: Vec::new(),
                    sites: [g(0), g(2)],
                    from: Some(0),
                    bisector: Vec::new(),
                    parametric: Vec::new(),
                    to: None,
                    points: smallvec![p(0.0, 0.0), p(-2.0, 1.0)],
                },
            ],
            cells: vec![Cell {
                site: 0,
                rings: smallvec![vec![p(-2.0, -1.0), p(0.0, 0.0), p(-2.0, 1.0)]],
            }],
            ..Default::default()
        };
        let opts = SvgOptions {
            boxes: vec![(Aabb::from_array([-2.0, -1.0, 0.0, 0.0]), 3)],
            ..Default::default()
        };
        let a = render_svg(&scene, &diagram, &opts);
        let b = render_svg(&scene, &diagram, &opts);
        assert_eq!(a, b);
        assert!(balanced(&a), "{a}");
        assert_eq!(a.matches("<polyline").count(), diagram.edges.len());
        assert!(a.contains("viewBox=\"-2.12 -1.12 4.24 2.24\""), "{a}");
        assert!(a.contains("<polyline points=\"0,0 0.1,0.5 0,1\"/>"), "{a}");
        // no exponent notation, no non-finite numbers
        for value in a
            .split('"')
            .skip(1)
            .step_by(2)
            .filter(|v| !v.starts_with('#'))
        {
            let b = value.as_bytes();
            assert!(
                !(1..b.len()).any(|i| b[i] == b'e' && b[i - 1].is_ascii_digit()),
                "{value}"
            );
        }
        assert!(!a.contains("NaN") && !a.contains("inf"));
        assert!(!balanced("<svg><g></svg>"));
    }
}
