//! Site ids are echoed in every output: the JSON diagram (`site_ids`, read back), the
//! GeoJSON properties and the SVG titles, for the point and the segment engines.

use gvd::io::{geojson, json, svg};
use gvd::{compute, Aabb, Mode, Options, Scene, Site};

fn scenes() -> Vec<Scene> {
    let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
    let points = Scene::new(
        domain,
        1e-3,
        Mode::Voronoi,
        vec![
            Site::point([-1.0, 0.1]).with_id("well <A> & \"B\""),
            Site::point([1.0, -0.2]),
            Site::point([0.2, 1.3]).with_id("c"),
        ],
    )
    .unwrap();
    let segments = Scene::new(
        domain,
        1e-3,
        Mode::Voronoi,
        vec![
            Site::segment([-1.5, -1.0], [-0.5, 1.0]).with_id("well <A> & \"B\""),
            Site::polyline([[0.5, -1.0], [1.0, 0.0], [0.5, 1.0]]),
            Site::point([0.0, -1.5]).with_id("c"),
        ],
    )
    .unwrap();
    vec![points, segments]
}

#[test]
fn ids_reach_json_geojson_and_svg() {
    for scene in scenes() {
        let d = compute(&scene, &Options::default()).unwrap();
        let want = vec![Some("well <A> & \"B\"".to_string()), None, Some("c".into())];
        assert_eq!(d.site_ids, want);

        let text = json::write_diagram(&d);
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(
            v["site_ids"],
            serde_json::json!(["well <A> & \"B\"", null, "c"])
        );
        assert_eq!(json::read_diagram(&text).unwrap().site_ids, want);
        let mut streamed = Vec::new();
        json::write_diagram_to(&d, &mut streamed).unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), text);

        let g: serde_json::Value =
            serde_json::from_str(&geojson::write_diagram(&scene, &d)).unwrap();
        let features = g["features"].as_array().unwrap();
        let edge = features
            .iter()
            .find(|f| f["properties"]["type"] == "edge" && f["properties"]["generators"][0] == 0)
            .expect("an edge of site 0");
        assert_eq!(edge["properties"]["site_ids"][0], "well <A> & \"B\"");
        let cell = features
            .iter()
            .find(|f| f["properties"]["type"] == "cell" && f["properties"]["site"] == 2)
            .expect("the cell of site 2");
        assert_eq!(cell["properties"]["site_id"], "c");

        let picture = svg::render_svg(&scene, &d, &svg::SvgOptions::default());
        let escaped = "<title>well &lt;A&gt; &amp; &quot;B&quot;</title>";
        // the site's group and its cell
        assert_eq!(picture.matches(escaped).count(), 2, "{picture}");
        assert_eq!(picture.matches("<title>c</title>").count(), 2);
        assert_eq!(picture.matches("<title>").count(), 4);
    }
}

#[test]
fn no_ids_no_field() {
    let scene = Scene::new(
        Aabb::from_array([0.0, 0.0, 1.0, 1.0]),
        1e-3,
        Mode::Voronoi,
        vec![Site::point([0.2, 0.2]), Site::point([0.7, 0.6])],
    )
    .unwrap();
    let d = compute(&scene, &Options::default()).unwrap();
    assert!(d.site_ids.is_empty());
    assert!(!json::write_diagram(&d).contains("site_ids"));
}
