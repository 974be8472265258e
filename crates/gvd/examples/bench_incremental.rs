//! Times the topology-oriented incremental Voronoi diagram of random points against
//! spade's bulk-loaded Delaunay triangulation, in one run.
//!
//! ```text
//! cargo run --release -p gvd --example bench_incremental [max_exponent=6]
//! ```
//!
//! Uniform random points in the unit square (fixed seed), n = 10^4 .. 10^max, then a
//! square grid of about 10^max points (every Voronoi vertex has four sites). Columns:
//! our graph only (`PointDiagram::new`), the conversion alone (`to_complex`), the
//! conversion with the cells traced from the faces (`to_complex_with_cells`, what
//! `gvd compute` does after the graph), graph + clipped `VoronoiComplex`
//! (`points_voronoi`), the diagram with cells as JSON (`write_diagram_to` into a
//! buffer), spade's `bulk_load`, and the ratios to spade. Best of three runs below
//! 10^6, one run at 10^6 and above.

use gvd::geom::{Aabb, Point};
use gvd::internals::{points_voronoi, PointDiagram};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::time::Instant;

fn random_points(n: usize, seed: u64) -> Vec<Point> {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| Point::new(next(), next())).collect()
}

fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("at least one run"))
}

fn main() {
    let max_exp: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(6);
    let domain = Aabb::from_array([0.0, 0.0, 1.0, 1.0]);
    println!(
        "{:>12} {:>10} {:>10} {:>10} {:>13} {:>10} {:>10} {:>11} {:>12} {:>10} {:>10}",
        "n",
        "graph s",
        "output s",
        "+cells s",
        "graph+out s",
        "json s",
        "spade s",
        "graph/spade",
        "total/spade",
        "vertices",
        "edges"
    );
    let mut cases: Vec<(String, Vec<Point>, Aabb)> = (4..=max_exp)
        .map(|e| {
            let n = 10usize.pow(e);
            (
                n.to_string(),
                random_points(n, 0x5EED + u64::from(e)),
                domain,
            )
        })
        .collect();
    // A degenerate input of the largest size: a square grid (cocircular quadruples).
    let k = 10usize.pow(max_exp).isqrt();
    let grid = (0..k * k)
        .map(|i| Point::new((i % k) as f64, (i / k) as f64))
        .collect();
    let side = k as f64 - 1.0;
    cases.push((
        format!("grid {k}^2"),
        grid,
        Aabb::from_array([0.0, 0.0, side, side]),
    ));
    for &(ref name, ref pts, domain) in &cases {
        let n = pts.len();
        let runs = if n >= 1_000_000 { 1 } else { 3 };
        let (t_graph, d) = best_of(runs, || {
            PointDiagram::new(pts, domain).expect("valid input")
        });
        assert_eq!(d.topology_counts().0, 0);
        let (t_out, out) = best_of(runs, || d.to_complex());
        drop(out);
        let (t_cells, (with_cells, traced)) = best_of(runs, || d.to_complex_with_cells());
        assert!(traced);
        drop(d);
        let (t_json, bytes) = best_of(runs, || {
            let mut buf = Vec::new();
            gvd::io::json::write_diagram_to(&with_cells, &mut buf).expect("in memory");
            buf.len()
        });
        assert!(bytes > 0);
        drop(with_cells);
        let (t_total, out) = best_of(runs, || points_voronoi(pts, domain).expect("valid input"));
        let sp: Vec<Point2<f64>> = pts.iter().map(|p| Point2::new(p.x, p.y)).collect();
        let (t_spade, t) = best_of(runs, || {
            DelaunayTriangulation::<Point2<f64>>::bulk_load(sp.clone()).expect("spade")
        });
        assert_eq!(t.num_vertices(), n);
        println!(
            "{:>12} {:>10.3} {:>10.3} {:>10.3} {:>13.3} {:>10.3} {:>10.3} {:>11.2} {:>12.2} {:>10} {:>10}",
            name,
            t_graph,
            t_out,
            t_cells,
            t_total,
            t_json,
            t_spade,
            t_graph / t_spade,
            t_total / t_spade,
            out.vertices.len(),
            out.edges.len()
        );
    }
    println!("reference (issue 4, 10^6 points, same machine kind): CGAL Delaunay 1.50 s, Boost.Polygon Voronoi 4.1 s");
}
