//! `gvd bench shou`: the four examples of Shou, Yuan, Miao and Wang 2011 (SYMW11) at
//! epsilon 1/256, 1/1024 and 1/4096, one core, beside the paper's CPU times and
//! subdivision counts.

use gvd::scene::Scene;

/// The paper's examples, as shipped in `examples/scenes/`, with its figures: CPU
/// seconds (Mathematica 5.0 on a 1.6 GHz Pentium T2330) and total subdivisions.
const EXAMPLES: [(&str, &str, f64, u64); 4] = [
    (
        "1 line, parabola",
        include_str!("../../../examples/scenes/shou-ex1-line-parabola.json"),
        2044.63,
        3301,
    ),
    (
        "2 astroid, circle",
        include_str!("../../../examples/scenes/shou-ex2-astroid-circle.json"),
        11094.1,
        6763,
    ),
    (
        "3 three circles",
        include_str!("../../../examples/scenes/shou-ex3-three-circles.json"),
        40181.2,
        14432,
    ),
    (
        "4 four circles",
        include_str!("../../../examples/scenes/shou-ex4-four-circles.json"),
        32607.9,
        21097,
    ),
];

/// The epsilons of the table: 1/256, 1/1024, 1/4096.
const EPSILONS: [u32; 3] = [256, 1024, 4096];

/// Boxes a run may visit unless `--large` (then the engine's default budget holds).
const QUICK_BOXES: usize = 1_000_000;

/// One timed run: best seconds over `repeat`, with the diagram's figures.
struct Row {
    seconds: f64,
    boxes: u64,
    uncertified: u64,
    vertices: usize,
    edges: usize,
}

fn run(scene: &Scene, options: &gvd::Options, repeat: usize) -> Result<Row, gvd::Error> {
    let (seconds, mut row) = crate::bench::best_run(scene, options, repeat, |d| {
        let stat = |k: &str| crate::bench::count_stat(d, k);
        Row {
            seconds: 0.0,
            boxes: stat("boxes"),
            uncertified: stat("uncertified_boxes"),
            vertices: d.vertices.len(),
            edges: d.edges.len(),
        }
    })?;
    row.seconds = seconds;
    Ok(row)
}

pub fn shou(large: bool, repeat: usize) {
    let options = gvd::Options {
        engine: gvd::Engine::Subdivision,
        subdivision: gvd::SubdivisionOptions {
            limits: gvd::Limits {
                max_boxes: (!large).then_some(QUICK_BOXES),
                ..Default::default()
            },
            ..Default::default()
        },
        parallel: false,
        ..Default::default()
    };
    println!("Shou, Yuan, Miao, Wang 2011: Voronoi diagrams of algebraic curves, examples 1-4");
    println!(
        "ours: one core, best of {repeat}{}; paper: Mathematica 5.0, Pentium T2330 1.6 GHz, its own pixel size",
        if large {
            String::new()
        } else {
            format!(", at most {QUICK_BOXES} boxes a run (--large lifts it)")
        }
    );
    println!(
        "{:<18} {:>6} | {:>9} {:>9} {:>9} | {:>8} {:>7} {:>7} | {:>5} {:>5}",
        "example",
        "1/eps",
        "ours s",
        "paper s",
        "speed-up",
        "boxes",
        "paper",
        "uncert",
        "verts",
        "edges"
    );
    for (name, text, paper_s, paper_boxes) in EXAMPLES {
        let shipped = Scene::from_json(text).expect("the shipped examples are valid");
        for inverse in EPSILONS {
            let scene = Scene::new(
                shipped.domain(),
                1.0 / f64::from(inverse),
                shipped.mode(),
                shipped.sites().to_vec(),
            )
            .expect("the examples are valid at every epsilon of the table");
            match run(&scene, &options, repeat) {
                Ok(r) => println!(
                    "{:<18} {:>6} | {:>9.3} {:>9.0} {:>8.0}x | {:>8} {:>7} {:>7} | {:>5} {:>5}",
                    name,
                    inverse,
                    r.seconds,
                    paper_s,
                    paper_s / r.seconds,
                    r.boxes,
                    paper_boxes,
                    r.uncertified,
                    r.vertices,
                    r.edges
                ),
                Err(e) => println!("{name:<18} {inverse:>6} | not finished: {e}"),
            }
        }
    }
}
