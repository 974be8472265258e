//! The `gvd` binary end to end: outputs written and checked, bad input refused with
//! nothing written.

use std::path::{Path, PathBuf};
use std::process::Command;

fn gvd() -> Command {
    Command::new(env!("CARGO_BIN_EXE_gvd"))
}

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gvd-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn compute_writes_a_diagram_that_verifies() {
    let scene = repo("examples/scenes/points-mixed-0030.json");
    let (json, svg) = (scratch("mixed.json"), scratch("mixed.svg"));
    let out = gvd()
        .args([
            "compute",
            scene.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(d["edges"].as_array().unwrap().len() > 30);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let v = gvd()
        .args(["verify", scene.to_str().unwrap(), json.to_str().unwrap()])
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&v.stdout);
    assert!(v.status.success() && report.contains("PASS"), "{report}");
}

#[test]
fn bad_scenes_are_refused_and_nothing_is_written() {
    let dir = repo("crates/gvd/tests/data/bad");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        seen += 1;
        let target = scratch(&format!(
            "bad-{}",
            path.file_name().unwrap().to_string_lossy()
        ));
        let out = gvd()
            .args([
                "compute",
                path.to_str().unwrap(),
                "--json",
                target.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{} was not refused: {err}",
            path.display()
        );
        assert!(err.contains("error"), "{}: {err}", path.display());
        assert!(!target.exists(), "{} left an output file", path.display());
    }
    assert!(seen >= 10, "only {seen} bad scenes found");
}

#[test]
fn refusal_names_the_site_and_field() {
    let scene = scratch("odd-p.json");
    std::fs::write(
        &scene,
        r#"{"domain": [0, 0, 1, 1], "sites": [{"kind": "point", "at": [0.2, 0.2]},
            {"kind": "point", "at": [0.7, 0.4], "metric": {"kind": "lp", "p": 3}}]}"#,
    )
    .unwrap();
    let out = gvd()
        .args(["compute", scene.to_str().unwrap(), "--json", "/dev/null"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("site 1") && err.contains("metric.p"), "{err}");
}
