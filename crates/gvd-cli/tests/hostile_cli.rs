//! Hostile options and output paths (issue 15): nonsense options refused at once with
//! exit 2, outputs written all or none through exclusive temporary files, never through
//! a symbolic link, over an input, over a read-only file, or twice.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Instant;

fn gvd() -> Command {
    Command::new(env!("CARGO_BIN_EXE_gvd"))
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A fresh directory for one test (files left behind show up in [`listing`]).
fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gvd-hostile-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn run(args: &[&std::ffi::OsStr]) -> Output {
    gvd().args(args).output().unwrap()
}

/// Asserts exit 2 within two seconds with `needle` in the message; returns the message.
fn refused_quickly(args: &[&std::ffi::OsStr], needle: &str) -> String {
    let start = Instant::now();
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(start.elapsed().as_secs_f64() < 2.0, "{args:?} took long");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

#[test]
fn nonsense_compute_options_are_refused_and_nothing_is_written() {
    let dir = scratch_dir("options");
    let scene = data("H11_lp4_two_points_for_maxbox0.json");
    let out = dir.join("out.json");
    for (option, needle) in [
        ("--max-box=0", "finite number > 0"),
        ("--max-box=-1", "finite number > 0"),
        ("--max-box=NaN", "finite number > 0"),
        ("--max-box=inf", "finite number > 0"),
        ("--max-box=1e-6", "boxes over the domain"),
        ("--threads=100000", "not in 1..=256"),
        ("--threads=0", "not in 1..=256"),
        ("--max-boxes=0", "--max-boxes"),
    ] {
        refused_quickly(
            &[
                "compute".as_ref(),
                scene.as_ref(),
                "--json".as_ref(),
                out.as_ref(),
                option.as_ref(),
            ],
            needle,
        );
    }
    assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
}

#[test]
fn verify_refuses_absurd_grids_and_slacks() {
    let (scene, diagram) = (data("V01_scene.json"), data("V01_diagram.json"));
    for option in [
        "--grid=18446744073709551615",
        "--grid=4294967296",
        "--grid=100000",
        "--grid=1",
        "--slack=NaN",
        "--slack=-1",
    ] {
        refused_quickly(
            &[
                "verify".as_ref(),
                scene.as_ref(),
                diagram.as_ref(),
                option.as_ref(),
            ],
            "invalid value",
        );
    }
    let ok = run(&[
        "verify".as_ref(),
        scene.as_ref(),
        diagram.as_ref(),
        "--grid=4096".as_ref(),
    ]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stdout)
    );
}

/// A planted link at any guessable temporary name redirects nothing: the temporary file
/// is created exclusively under a random name, and the output itself is not a link.
#[cfg(unix)]
#[test]
fn planted_links_redirect_nothing() {
    let dir = scratch_dir("planted");
    let secret = dir.join("secret");
    std::fs::write(&secret, "secret").unwrap();
    for name in [".out.json.tmp", "out.json.tmp", ".out.json"] {
        std::os::unix::fs::symlink(&secret, dir.join(name)).unwrap();
    }
    let out = dir.join("out.json");
    let scene = data("H12_three_points_for_threads.json");
    let ok = run(&[
        "compute".as_ref(),
        scene.as_ref(),
        "--json".as_ref(),
        out.as_ref(),
    ]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    assert_eq!(std::fs::read_to_string(&secret).unwrap(), "secret");
    assert!(std::fs::read_to_string(&out).unwrap().contains("\"edges\""));
    assert_eq!(
        listing(&dir),
        [
            ".out.json",
            ".out.json.tmp",
            "out.json",
            "out.json.tmp",
            "secret"
        ]
    );
}

#[test]
fn an_input_is_never_overwritten_nor_an_output_given_twice() {
    let dir = scratch_dir("clobber");
    let scene = dir.join("scene.json");
    std::fs::copy(data("H12_three_points_for_threads.json"), &scene).unwrap();
    let before = std::fs::read_to_string(&scene).unwrap();
    // the same file under another spelling is still the input
    let other_spelling = dir.join(".").join("scene.json");
    refused_quickly(
        &[
            "compute".as_ref(),
            scene.as_ref(),
            "--json".as_ref(),
            other_spelling.as_ref(),
        ],
        "is an input",
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), before);
    let out = dir.join("out");
    refused_quickly(
        &[
            "compute".as_ref(),
            scene.as_ref(),
            "--json".as_ref(),
            out.as_ref(),
            "--svg".as_ref(),
            out.as_ref(),
        ],
        "given twice",
    );
    assert_eq!(listing(&dir), ["scene.json"]);
}

#[cfg(unix)]
#[test]
fn a_read_only_output_is_kept() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch_dir("readonly");
    let out = dir.join("out.json");
    std::fs::write(&out, "mine").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    let scene = data("H12_three_points_for_threads.json");
    refused_quickly(
        &[
            "compute".as_ref(),
            scene.as_ref(),
            "--json".as_ref(),
            out.as_ref(),
        ],
        "read-only",
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "mine");
}

/// When one output cannot be written, none is: the SVG's directory is missing, so the
/// JSON (checked and written first) is not left behind either, and no temporary file.
#[test]
fn outputs_are_written_all_or_none() {
    let dir = scratch_dir("all-or-none");
    let json = dir.join("out.json");
    let svg = dir.join("missing-dir").join("out.svg");
    let scene = data("H12_three_points_for_threads.json");
    let out = run(&[
        "compute".as_ref(),
        scene.as_ref(),
        "--json".as_ref(),
        json.as_ref(),
        "--svg".as_ref(),
        svg.as_ref(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
    // a refused scene leaves nothing either, temporary files included
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"domain": [0, 0, 1, 1], "sites": [{"kind": "circle", "center": [0.5, 0.5], "radius": 0.1}, {"kind": "circle", "center": [0.5, 0.5], "radius": 0.1}]}"#).unwrap();
    refused_quickly(
        &[
            "compute".as_ref(),
            bad.as_ref(),
            "--json".as_ref(),
            json.as_ref(),
        ],
        "identical to site 0",
    );
    assert_eq!(listing(&dir), ["bad.json"]);
}

/// `-` is standard input for the scene and standard output for a result, never a file.
#[test]
fn dash_means_standard_input_and_output() {
    let dir = scratch_dir("dash");
    let scene = std::fs::read(data("H12_three_points_for_threads.json")).unwrap();
    let mut child = gvd()
        .args(["compute", "-", "--json", "-"])
        .current_dir(&dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(&scene).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let d: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(d["edges"].as_array().unwrap().len(), 3);
    assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
}

/// A refusal quotes at most a short excerpt of the input, however long the input.
#[test]
fn long_inputs_are_not_echoed_back() {
    let dir = scratch_dir("echo");
    let digits = "9".repeat(10_000);
    let scene = dir.join("long.json");
    std::fs::write(
        &scene,
        format!(r#"{{"domain": [0, 0, 1, 1], "sites": [{{"kind": "field", "equation": "x^2 + {digits}e999"}}]}}"#),
    )
    .unwrap();
    let json = dir.join("out.json");
    let err = refused_quickly(
        &[
            "compute".as_ref(),
            scene.as_ref(),
            "--json".as_ref(),
            json.as_ref(),
        ],
        "site 0",
    );
    assert!(err.len() < 1500, "{} characters", err.len());
}
