//! `gvd compute` and `gvd offset` on GeoJSON, WKT and DXF inputs, and their GeoJSON and
//! DXF outputs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn gvd(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gvd"))
        .args(args)
        .output()
        .unwrap()
}

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gvd-formats-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn ok(out: &Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{err}");
    err
}

#[test]
fn a_dxf_part_computes_verifies_and_writes_geojson_and_dxf() {
    let part = repo("examples/scenes/plate-bulges.dxf");
    let (json, geojson, dxf) = (
        scratch("plate.json"),
        scratch("plate.geojson"),
        scratch("plate.dxf"),
    );
    let err = ok(&gvd(&[
        "compute".as_ref(),
        part.as_ref(),
        "--json".as_ref(),
        json.as_ref(),
        "--geojson".as_ref(),
        geojson.as_ref(),
        "--dxf".as_ref(),
        dxf.as_ref(),
    ]));
    assert!(err.contains("entities not read: TEXT ×1"), "{err}");
    // the diagram passes the independent checker against the scene read from the DXF
    let out = gvd(&["verify".as_ref(), part.as_ref(), json.as_ref()]);
    ok(&out);
    assert!(String::from_utf8_lossy(&out.stdout).contains("PASS"));
    let gj: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&geojson).unwrap()).unwrap();
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let edges = d["edges"].as_array().unwrap();
    let features = gj["features"].as_array().unwrap();
    let n_edges = features
        .iter()
        .filter(|f| f["properties"]["type"] == "edge")
        .count();
    assert_eq!(n_edges, edges.len());
    let lines = std::fs::read_to_string(&dxf)
        .unwrap()
        .lines()
        .filter(|l| *l == "LINE")
        .count();
    let segments: usize = edges
        .iter()
        .map(|e| e["points"].as_array().unwrap().len() - 1)
        .sum();
    assert_eq!(lines, segments);
}

#[test]
fn offsets_of_a_wkt_pocket_as_dxf_arcs_and_lines() {
    let wkt = scratch("pocket.wkt");
    std::fs::write(&wkt, "POLYGON ((0 0, 4 0, 4 3, 2 1.5, 0 3, 0 0))\n").unwrap();
    let dxf = scratch("pocket-offset.dxf");
    ok(&gvd(&[
        "offset".as_ref(),
        wkt.as_ref(),
        "--mode".as_ref(),
        "medial-axis".as_ref(),
        "--distance".as_ref(),
        "0.3".as_ref(),
        "--dxf".as_ref(),
        dxf.as_ref(),
    ]));
    let text = std::fs::read_to_string(&dxf).unwrap();
    // the reflex corner of the pocket rounds its offset with an arc
    assert!(
        text.contains("\nLINE\n") && text.contains("\nARC\n"),
        "{text}"
    );
    assert!(text.ends_with("0\nENDSEC\n0\nEOF\n"));
}

#[test]
fn the_format_comes_from_the_extension_or_the_flag() {
    let txt = scratch("points.txt");
    std::fs::write(
        &txt,
        r#"{"type": "MultiPoint", "coordinates": [[0, 0], [1, 0], [0, 1]]}"#,
    )
    .unwrap();
    let out = scratch("points.json");
    let refused = gvd(&[
        "compute".as_ref(),
        txt.as_ref(),
        "--json".as_ref(),
        out.as_ref(),
    ]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--format"));
    assert!(!out.exists());
    ok(&gvd(&[
        "compute".as_ref(),
        txt.as_ref(),
        "--format".as_ref(),
        "geojson".as_ref(),
        "--json".as_ref(),
        out.as_ref(),
    ]));
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(d["vertices"].as_array().unwrap().len(), 1);
    // a refused site names the site, the field and the feature it came from
    let bad = scratch("bad.geojson");
    std::fs::write(
        &bad,
        r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": null,
            "geometry": {"type": "LineString", "coordinates": [[0, 0], [0, 0]]}}]}"#,
    )
    .unwrap();
    let refused = gvd(&[
        "compute".as_ref(),
        bad.as_ref(),
        "--json".as_ref(),
        out.as_ref(),
    ]);
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success()
            && err.contains("site 0 field 'points'")
            && err.contains("(feature 0)"),
        "{err}"
    );
}

#[test]
fn an_svg_drawing_computes_to_png_json_and_geojson_by_extension() {
    let drawing = repo("examples/scenes/bracket.svg");
    let (png, json, svg, geojson) = (
        scratch("bracket.png"),
        scratch("bracket.json"),
        scratch("bracket.svg"),
        scratch("bracket.geojson"),
    );
    ok(&gvd(&[
        "compute".as_ref(),
        drawing.as_ref(),
        "-o".as_ref(),
        png.as_ref(),
        "-o".as_ref(),
        json.as_ref(),
        "--output".as_ref(),
        svg.as_ref(),
        "-o".as_ref(),
        geojson.as_ref(),
    ]));
    let out = gvd(&["verify".as_ref(), drawing.as_ref(), json.as_ref()]);
    ok(&out);
    assert!(String::from_utf8_lossy(&out.stdout).contains("PASS"));
    // the ids of the drawing's elements reach the JSON diagram
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(d["site_ids"]
        .as_array()
        .unwrap()
        .contains(&serde_json::json!("hole-left")));
    assert!(!d["cells"].as_array().unwrap().is_empty());
    // the PNG decodes, at the SVG picture's size, and is not blank
    let picture = std::fs::read_to_string(&svg).unwrap();
    let attr = |name: &str| -> u32 {
        let at = picture.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        picture[at..].split('"').next().unwrap().parse().unwrap()
    };
    let decoder = png::Decoder::new(std::fs::File::open(&png).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (attr("width"), attr("height")));
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(4).collect();
    let white = pixels.iter().filter(|p| p[..3] == [255, 255, 255]).count();
    let mut colours: Vec<&[u8]> = pixels.clone();
    colours.sort();
    colours.dedup();
    assert!(
        white < pixels.len() / 2,
        "{white} of {} white",
        pixels.len()
    );
    assert!(colours.len() > 20, "{} colours", colours.len());
    // an output of unknown extension is refused before any work
    let bad = gvd(&[
        "compute".as_ref(),
        drawing.as_ref(),
        "-o".as_ref(),
        scratch("x.bmp").as_ref(),
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("from its extension"));
}

#[test]
fn completions_for_every_shell() {
    for shell in ["bash", "zsh", "fish"] {
        let out = gvd(&["completions".as_ref(), shell.as_ref()]);
        ok(&out);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            text.contains("compute") && text.contains("geojson") && text.contains("output"),
            "{shell}"
        );
    }
}

#[test]
fn longitude_and_latitude_projected_and_back() {
    let input = scratch("lonlat.geojson");
    std::fs::write(
        &input,
        r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": null,
            "geometry": {"type": "MultiPoint", "coordinates": [[5.0, 52.0], [5.6, 52.3], [5.2, 52.5]]}}]}"#,
    )
    .unwrap();
    let (planar, projected) = (
        scratch("lonlat-planar.geojson"),
        scratch("lonlat-out.geojson"),
    );
    let vertex = |out: &Path| -> (Vec<f64>, f64) {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
        let f = &v["features"][0];
        assert_eq!(f["properties"]["type"], "vertex");
        let at = f["geometry"]["coordinates"].as_array().unwrap();
        let at = at.iter().map(|c| c.as_f64().unwrap()).collect();
        (at, f["properties"]["clearance"].as_f64().unwrap())
    };
    ok(&gvd(&[
        "compute".as_ref(),
        input.as_os_str(),
        "--geojson".as_ref(),
        planar.as_os_str(),
    ]));
    ok(&gvd(&[
        "compute".as_ref(),
        input.as_os_str(),
        "--project".as_ref(),
        "local".as_ref(),
        "--geojson".as_ref(),
        projected.as_os_str(),
    ]));
    let (p, planar_clearance) = vertex(&planar);
    let (q, clearance) = vertex(&projected);
    // both in degrees among the sites, apart: the plane of degrees is not the sphere's
    for v in [&p, &q] {
        assert!(
            (5.0..5.6).contains(&v[0]) && (52.0..52.5).contains(&v[1]),
            "{v:?}"
        );
    }
    assert!(
        (p[0] - q[0]).abs().max((p[1] - q[1]).abs()) > 0.05,
        "{p:?} {q:?}"
    );
    assert!(planar_clearance < 1.0, "{planar_clearance}");
    assert!((clearance - 29_213.77).abs() < 1.0, "{clearance}");
    let wkt = repo("examples/scenes/pocket.json");
    let out = gvd(&[
        "compute".as_ref(),
        wkt.as_os_str(),
        "--project".as_ref(),
        "local".as_ref(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("GeoJSON only"));
}

/// `-` reads any format from standard input when `--format` names it, and a GeoJSON
/// diagram goes to standard output with `--geojson -`.
#[test]
fn standard_input_in_the_format_given() {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_gvd"))
        .args(["compute", "-", "--format", "wkt", "--geojson", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"MULTIPOINT ((0 0), (1 0), (0 1))\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    ok(&out);
    let d: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let kinds: Vec<&str> = d["features"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["properties"]["type"].as_str().unwrap())
        .collect();
    assert_eq!(kinds.iter().filter(|&&k| k == "vertex").count(), 1);
    assert_eq!(kinds.iter().filter(|&&k| k == "cell").count(), 3);
}
