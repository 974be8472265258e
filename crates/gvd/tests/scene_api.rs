//! Scenes built in code go through the same checks as JSON: every invalid value is
//! refused with the site index and field, and a valid scene computes.

use gvd::scene::{Metric, Mode, SceneBuilder, Site};
use gvd::{Aabb, Error, Scene};

fn domain() -> Aabb {
    Aabb::from_array([-2.0, -2.0, 2.0, 2.0])
}

/// `(site, field)` of the refusal of a scene of a valid point then `site`.
fn refusal(site: Site) -> (usize, String) {
    let sites = vec![Site::point([1.5, 1.5]), site];
    match Scene::new(domain(), 1e-3, Mode::Voronoi, sites) {
        Err(Error::Site { site, field, .. }) => (site, field),
        other => panic!("expected a site refusal, got {other:?}"),
    }
}

#[test]
fn invalid_sites_built_in_code_are_refused_with_their_field() {
    let spd = |m| Metric::Anisotropic {
        matrix: m,
        weight: 0.0,
    };
    for (site, field) in [
        (Site::point([1.5, 1.5]), "at"), // duplicate of site 0
        (Site::point([f64::NAN, 0.0]), "at"),
        (
            Site::point_with([0.0, 0.0], Metric::Lp { p: 3 }),
            "metric.p",
        ),
        (
            Site::point_with([0.0, 0.0], Metric::Lp { p: 0 }),
            "metric.p",
        ),
        (
            Site::point_with([0.0, 0.0], spd([[1.0, 2.0], [2.0, 1.0]])),
            "metric.matrix",
        ),
        (
            Site::point_with(
                [0.0, 0.0],
                Metric::Moebius {
                    scale: 0.0,
                    weight: 0.0,
                },
            ),
            "metric.scale",
        ),
        (Site::segment([0.0, 0.0], [0.0, 0.0]), "to"),
        (Site::circle([0.0, 0.0], -1.0), "radius"),
        (Site::arc([0.0, 0.0], 0.0, 0.0, 1.0), "radius"),
        (Site::arc([0.0, 0.0], 1.0, 1.0, 1.0), "end_angle"),
        (Site::polyline(Vec::<[f64; 2]>::new()), "points"),
        (Site::polyline([[0.0, 0.0], [0.0, 0.0]]), "points"),
        (
            Site::polygon([[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]]),
            "rings",
        ),
        (Site::ellipse([0.0, 0.0], [1.0, 0.0], 0.0), "semi_axes"),
        (
            Site::bezier([[0.0, 0.0], [1.0, 1.0]], Some(vec![1.0, -1.0])),
            "weights",
        ),
        (
            Site::bspline(0, [[0.0, 0.0], [1.0, 1.0]], vec![0.0, 1.0], None, false),
            "degree",
        ),
        (
            Site::bspline(1, [[0.0, 0.0], [1.0, 1.0]], vec![0.0, 1.0], None, false),
            "knots",
        ),
    ] {
        let what = format!("{site:?}");
        assert_eq!(refusal(site), (1, field.to_string()), "{what}");
    }
}

#[test]
fn scene_level_values_are_refused() {
    for eps in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Scene::new(domain(), eps, Mode::Voronoi, vec![]),
            Err(Error::Scene { field, .. }) if field == "epsilon"
        ));
    }
    for d in [
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, f64::NAN, 1.0],
    ] {
        assert!(matches!(
            SceneBuilder::new(Aabb::from_array(d)),
            Err(Error::Scene { field, .. }) if field == "domain"
        ));
    }
    assert!(matches!(
        Site::algebraic("x^2 + * y", None),
        Err(Error::Scene { field, .. }) if field == "equation"
    ));
}

#[test]
fn code_and_json_build_the_same_scene() {
    let json = r#"{"domain": [-2, -2, 2, 2], "epsilon": 0.01, "mode": "complex", "sites": [
        {"kind": "point", "at": [1.5, 0]},
        {"kind": "polygon", "rings": [[[-1, -1], [0, -1], [0, 0], [-1, 0]]], "id": "square"},
        {"kind": "arc", "center": [1, 1], "radius": 0.5, "start_angle": 0, "end_angle": 2}
    ]}"#;
    let from_json = Scene::from_json(json).unwrap();
    let in_code = Scene::new(
        domain(),
        0.01,
        Mode::Complex,
        vec![
            Site::point([1.5, 0.0]),
            Site::polygon([[[-1.0, -1.0], [0.0, -1.0], [0.0, 0.0], [-1.0, 0.0]]]).with_id("square"),
            Site::arc([1.0, 1.0], 0.5, 0.0, 2.0),
        ],
    )
    .unwrap();
    assert_eq!(from_json, in_code);
    let diagram = gvd::compute(&in_code, &gvd::Options::default()).unwrap();
    assert!(!diagram.edges.is_empty());
    diagram.check_invariants().unwrap();
}

#[test]
fn tangent_circles_are_accepted_even_where_rounding_makes_them_overlap() {
    // |(-1, 0) − (0, −√3)| rounds to just below 2 = r + r
    let sites = vec![
        Site::circle([-1.0, 0.0], 1.0),
        Site::circle([0.0, -1.7320508075688772], 1.0),
    ];
    assert!(Scene::new(domain(), 1e-2, Mode::Voronoi, sites).is_ok());
    let overlapping = vec![
        Site::circle([-1.0, 0.0], 1.0),
        Site::circle([0.0, -1.7], 1.0),
    ];
    assert!(matches!(
        Scene::new(domain(), 1e-2, Mode::Voronoi, overlapping),
        Err(Error::Conflict {
            site: 1,
            other: 0,
            ..
        })
    ));
}

/// A scene that no engine computes is refused naming the site that is the real cause:
/// in `complex` mode, segments with curves or circles (in `voronoi` mode the subdivision
/// engine takes them all).
#[test]
fn refusals_of_mixed_scenes_name_the_real_cause() {
    let refused = |sites: Vec<Site>| {
        let voronoi = Scene::new(domain(), 1e-3, Mode::Voronoi, sites.clone()).unwrap();
        let d = gvd::compute(&voronoi, &gvd::Options::default()).unwrap();
        assert_eq!(d.stats["engine"], "subdivision");
        let scene = Scene::new(domain(), 1e-3, Mode::Complex, sites).unwrap();
        match gvd::compute(&scene, &gvd::Options::default()) {
            Err(Error::Unsupported {
                site,
                kind,
                message,
            }) => (site, kind, message),
            other => panic!("expected a refusal, got {:?}", other.map(|d| d.edges.len())),
        }
    };
    let bezier = Site::bezier([[0.5, 0.5], [1.0, 1.5], [1.5, 0.5]], None);
    // curves mix with the subdivision engine's kinds, segments with the incremental
    // engine's: in `complex` mode no engine takes the two
    let (site, kind, message) = refused(vec![Site::segment([-1.0, -1.0], [0.0, -1.0]), bezier]);
    assert_eq!((site, kind.as_str()), (0, "segment"), "{message}");
    assert!(message.contains("site 1 (kind 'bezier')"), "{message}");
    let (site, kind, message) = refused(vec![
        Site::segment([-1.0, -1.0], [0.0, -1.0]),
        Site::circle([1.0, 1.0], 0.5),
    ]);
    assert_eq!((site, kind.as_str()), (0, "segment"));
    assert!(message.contains("site 1 (kind 'circle')"), "{message}");
}
