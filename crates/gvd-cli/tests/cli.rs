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

/// Runs `gvd compute SCENE ARGS...` (a scene of `examples/scenes`) and asserts success.
fn compute_ok(scene: &str, args: &[&std::ffi::OsStr]) {
    let scene = repo("examples/scenes").join(scene);
    let out = gvd()
        .arg("compute")
        .arg(&scene)
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn compute_writes_a_diagram_that_verifies() {
    let scene = repo("examples/scenes/points-mixed-0030.json");
    let (json, svg) = (scratch("mixed.json"), scratch("mixed.svg"));
    compute_ok(
        "points-mixed-0030.json",
        &[
            "--json".as_ref(),
            json.as_ref(),
            "--svg".as_ref(),
            svg.as_ref(),
        ],
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
fn compute_without_outputs_prints_the_summary() {
    let out = gvd()
        .arg("compute")
        .arg(repo("examples/scenes/segments-0200.json"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let edges: usize = stdout
        .split(" edges")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no edge count in {stdout}"));
    assert!(edges > 200, "{stdout}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("nothing written"));
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

#[test]
fn offset_writes_curves_and_a_picture() {
    let scene = repo("examples/scenes/points-euclidean-0200.json");
    let (json, svg) = (scratch("offset.json"), scratch("offset.svg"));
    let out = gvd()
        .args(["offset", scene.to_str().unwrap(), "--distance", "0.1"])
        .args([
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
    let off: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(off["distance"], 0.1);
    let curves = off["curves"].as_array().unwrap();
    assert!(!curves.is_empty());
    for c in curves {
        assert!(c["closed"].is_boolean());
        for p in c["primitives"].as_array().unwrap() {
            match p["kind"].as_str().unwrap() {
                "arc" => assert_eq!(p["radius"], 0.1),
                "line" => assert!(p["from"].is_array() && p["to"].is_array()),
                other => panic!("{other}"),
            }
        }
    }
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.contains("<g id=\"offsets\"") && picture.contains(" 0 0 0 "));
}

#[test]
fn offset_refuses_bad_distances_and_writes_nothing() {
    let scene = repo("examples/scenes/points-euclidean-0200.json");
    for d in ["0", "-0.5", "nan", "inf"] {
        let target = scratch(&format!("offset-bad-{d}.json"));
        let out = gvd()
            .args(["offset", scene.to_str().unwrap(), "--distance", d])
            .args(["--json", target.to_str().unwrap()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{d}: {err}");
        assert!(err.contains("distance"), "{d}: {err}");
        assert!(!target.exists(), "{d} left an output file");
    }
}

/// An output path that is not a regular file (a FIFO here, like `/dev/stdout` in a pipe)
/// is written in place, never replaced by a plain file.
#[cfg(unix)]
#[test]
fn output_into_a_fifo_keeps_the_fifo() {
    use std::os::unix::fs::FileTypeExt;
    let fifo = scratch("diagram.fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    compute_ok(
        "points-mixed-0030.json",
        &["--json".as_ref(), fifo.as_ref()],
    );
    // Checked before joining: a reader left on a replaced FIFO would wait forever.
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    let text = reader.join().unwrap();
    let d: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(d["edges"].as_array().unwrap().len() > 30);
    std::fs::remove_file(&fifo).unwrap();
}

/// A symbolic link is never written through: refused, the link and its target kept.
#[cfg(unix)]
#[test]
fn output_through_a_symlink_is_refused() {
    let (target, link) = (scratch("linked-target.svg"), scratch("link.svg"));
    let _ = std::fs::remove_file(&link);
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let scene = repo("examples/scenes/points-mixed-0030.json");
    let out = gvd()
        .arg("compute")
        .arg(&scene)
        .arg("--svg")
        .arg(&link)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("symbolic link"));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
}

/// `--bisectors` adds each edge's exact bisector to the JSON (and only when asked).
#[test]
fn bisectors_flag_adds_offset_forms() {
    let json = scratch("slot-bisectors.json");
    for (flag, expected) in [(None, false), (Some("--bisectors"), true)] {
        let mut args = vec!["--json".as_ref(), json.as_os_str()];
        args.extend(flag.map(std::ffi::OsStr::new));
        compute_ok("slot-pocket.json", &args);
        let d: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let with = d["edges"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e.get("bisector").is_some())
            .count();
        assert_eq!(with > 0, expected, "{flag:?}: {with} edges with a bisector");
    }
}

#[test]
fn unknown_fields_are_warned_about_and_ignored() {
    let scene = scratch("unknown-fields-scene.json");
    let written = scratch("unknown-fields-out.json");
    std::fs::write(
        &scene,
        r#"{"domain": [0, 0, 1, 1], "epsilion": 0.01, "source": "test",
            "sites": [{"kind": "point", "at": [0.2, 0.2], "radius": 1},
                      {"kind": "point", "at": [0.7, 0.6]}]}"#,
    )
    .unwrap();
    let out = gvd()
        .arg("compute")
        .arg(&scene)
        .arg("--json")
        .arg(&written)
        .output()
        .unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("unknown field 'epsilion' (ignored; did you mean 'epsilon'?)"),
        "{err}"
    );
    assert!(
        err.contains("site 0: unknown field 'radius' (ignored)"),
        "{err}"
    );
    assert!(err.contains("unknown field 'source' (ignored)"), "{err}");
    assert!(written.exists());
}

/// `gvd bench freeform --quick` (the shipped scenes only: the full table takes longer
/// than a test should) prints a row per scene and no empty diagram.
#[test]
fn bench_freeform_quick_rows() {
    let out = gvd()
        .args(["bench", "freeform", "--repeat", "1", "--quick"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for scene in [
        "bezier4",
        "closed6",
        "convex3",
        "deep concavity",
        "nonconvex2",
        "piecewise C1",
    ] {
        assert!(
            text.lines()
                .any(|l| l.starts_with(scene) && l.contains('|')),
            "no row for {scene}:\n{text}"
        );
    }
    assert!(!text.contains("empty"), "{text}");
    assert!(text.contains("Hanniel"), "{text}");
}

#[test]
fn compute_prunes_the_medial_axis() {
    let json = scratch("serrated-pruned.json");
    compute_ok(
        "serrated-pocket.json",
        &[
            "--prune-lambda".as_ref(),
            "0.1".as_ref(),
            "--json".as_ref(),
            json.as_ref(),
        ],
    );
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let pruning = &d["stats"]["pruning"];
    assert_eq!(pruning["lambda"], 0.1);
    let edges = d["edges"].as_array().unwrap().len();
    assert!(edges * 4 < pruning["edges_before"].as_u64().unwrap() as usize);
    assert!(d["edges"]
        .as_array()
        .unwrap()
        .iter()
        .any(|e| e.get("sites_along").is_some()));
    for bad in ["0", "181", "nan"] {
        let out = gvd()
            .arg("compute")
            .arg(repo("examples/scenes/serrated-pocket.json"))
            .args(["--prune-angle", bad, "--json"])
            .arg(scratch("refused.json"))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "--prune-angle {bad}");
        assert!(!scratch("refused.json").exists());
    }
}
