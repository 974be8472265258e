//! What `gvd verify` reports: the figures of each check, the problems found (at most a
//! few of each kind listed), and the verdict.

/// What the checker found.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The fraction of edge samples within tolerance of their bisector.
    pub sound: f64,
    /// The fraction of grid bisector crossings covered by an edge or vertex.
    pub complete: f64,
    /// `(good, total)` vertices.
    pub vertices_ok: (usize, usize),
    /// The largest edge sample error, in length units.
    pub worst_edge_error: f64,
    /// The worst offenders of each check, each naming the edge or vertex, its
    /// generators and a location.
    pub problems: Vec<String>,
    /// Findings that do not fail the diagram (unreferenced vertices, null ends on a site).
    pub warnings: Vec<String>,
    /// Whether all four checks passed.
    pub passed: bool,
}

impl Report {
    /// `sound=0.9993 complete=0.9981 vertices_ok=123/123 worst_edge_error=0.0012 PASS`,
    /// as the Python checker prints it.
    pub fn summary_line(&self) -> String {
        format!(
            "sound={:.4} complete={:.4} vertices_ok={}/{} worst_edge_error={} {}",
            self.sound,
            self.complete,
            self.vertices_ok.0,
            self.vertices_ok.1,
            fmt_g3(self.worst_edge_error),
            if self.passed { "PASS" } else { "FAIL" }
        )
    }
}

/// How many offenders each check lists.
pub(super) const MAX_LIST: usize = 5;

/// `x` with 3 significant digits, like Python's `{:.3g}`.
pub(super) fn fmt_g3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x.is_infinite() {
            "inf".into()
        } else {
            "0".into()
        };
    }
    let e = x.abs().log10().floor() as i32;
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if !(-4..3).contains(&e) {
        // Rust's exponent form rounds the mantissa (and carries it to the exponent),
        // subnormals included
        let text = format!("{x:.2e}");
        let (m, e) = text.split_once('e').unwrap_or((&text, "0"));
        let e: i32 = e.parse().unwrap_or(0);
        format!(
            "{}e{}{:02}",
            trim(m.to_string()),
            if e < 0 { '-' } else { '+' },
            e.abs()
        )
    } else {
        trim(format!("{:.*}", (2 - e).max(0) as usize, x))
    }
}
