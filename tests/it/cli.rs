//! The command line, run as a process: exports write the four files; bad input gives a one-line
//! error naming the problem, a non-zero exit, and writes nothing.

use std::path::Path;
use std::process::{Command, Output};

fn adhesion(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default()
}

/// Run with bad input: assert failure, one line on stderr containing `needle`, no files.
#[track_caller]
fn assert_rejected(args: &[&str], needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut all: Vec<&str> = args.to_vec();
    let out_s = out.to_str().unwrap();
    all.extend(["--out", out_s]);
    let o = adhesion(&all);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "{args:?}: stderr is not one line:\n{stderr}"
    );
    assert!(stderr.contains(needle), "{args:?}: `{needle}` not in: {stderr}");
    assert!(files_in(&out).is_empty(), "{args:?} wrote {:?}", files_in(&out));
}

#[test]
fn headless_export_writes_the_four_formats() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let o = adhesion(&["--headless", "--figure", "fig1.1", "--out", out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for ext in ["png", "svg", "csv", "json"] {
        let p = dir.path().join(format!("fig1.1.{ext}"));
        let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        assert!(len > 1000, "{} is {len} bytes", p.display());
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("fig1.1.json")).unwrap()).unwrap();
    assert_eq!(json["scene"], "fig1.1");
    assert_eq!(json["version"], env!("CARGO_PKG_VERSION"));
    assert!(json["run_time_s"].as_f64().unwrap() >= 0.0);
    let radius = json["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "radius")
        .unwrap();
    assert_eq!(radius["unit"], "m");
    let h = json["results"]["jkr_hysteresis_loop_norm"].as_f64().unwrap();
    assert!((h - 7.092_195_971_863_96).abs() < 1e-6);
    // No temporary files are left behind.
    assert!(files_in(dir.path()).iter().all(|f| !f.contains(".tmp-")));
}

#[test]
fn format_selection_and_set_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let o = adhesion(&[
        "--headless",
        "--figure",
        "fig1.1",
        "--set",
        "units=si",
        "--set",
        "radius=5e-6",
        "--format",
        "csv,json",
        "--out",
        out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut files = files_in(dir.path());
    files.sort();
    assert_eq!(files, vec!["fig1.1.csv", "fig1.1.json"]);
}

#[test]
fn unknown_scene_is_rejected() {
    assert_rejected(&["--headless", "--figure", "fig9.9"], "unknown scene `fig9.9`");
    assert_rejected(&["--headless", "--figure", "fig1.2"], "did you mean");
}

#[test]
fn unknown_or_misspelled_preset_key_is_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.toml");
    std::fs::write(&p, "radus = 1e-6\n").unwrap();
    assert_rejected(
        &[
            "--headless",
            "--figure",
            "fig1.1",
            "--preset",
            p.to_str().unwrap(),
        ],
        "unknown parameter `radus` for scene fig1.1 (did you mean `radius`?)",
    );
    std::fs::write(&p, "colour = 3\n").unwrap();
    assert_rejected(
        &[
            "--headless",
            "--figure",
            "fig1.1",
            "--preset",
            p.to_str().unwrap(),
        ],
        "unknown parameter `colour`",
    );
    std::fs::write(&p, "radius = \n").unwrap();
    assert_rejected(
        &[
            "--headless",
            "--figure",
            "fig1.1",
            "--preset",
            p.to_str().unwrap(),
        ],
        "p.toml",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--set", "radus=1"],
        "did you mean `radius`",
    );
}

#[test]
fn invalid_values_are_rejected_with_the_parameter_named() {
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--set", "modulus=-1e6"],
        "invalid parameter `modulus` = -1000000: must be positive",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--set", "radius=abc"],
        "parameter `radius` expects a number, got `abc`",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--set", "radius=NaN"],
        "invalid parameter `radius` = NaN: must be a finite number",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--set", "units=cgs"],
        "expects one of normalized, si",
    );
    assert_rejected(
        &[
            "--headless",
            "--figure",
            "fig1.4b",
            "--set",
            "min_separation_ho=9",
        ],
        "must be below",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--format", "tiff"],
        "unknown format `tiff`",
    );
    assert_rejected(
        &["--headless", "--figure", "fig1.1", "--width-mm", "10"],
        "a figure is 40-500 mm wide",
    );
    assert_rejected(&["--headless", "--figure", "fig1.1", "--dpi", "0"], "--dpi");
}

#[test]
fn list_and_describe() {
    let o = adhesion(&["--list"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && s.contains("fig1.1") && s.contains("fig1.4b"));
    let o = adhesion(&["--describe", "fig1.1"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    for needle in ["radius", "1e-5", "Pa", "(0, inf)", "jkr_hysteresis_norm"] {
        assert!(s.contains(needle), "`{needle}` missing from --describe");
    }
    let o = adhesion(&["--describe", "nope"]);
    assert!(!o.status.success());
}

#[test]
fn reproduce_writes_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let o = adhesion(&["--headless", "--reproduce", "--out", dir.path().to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("reproduction.md")).unwrap();
    assert!(md.contains("ch1.jkr_hysteresis_constant") && md.contains("Reproduced"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("reproduction.json")).unwrap())
            .unwrap();
    assert!(json.as_array().unwrap().len() >= 10);
}
