//! Input that passes validation must not panic, abort, hang or leave files behind; errors name
//! the input. Peak statistics at extreme lengths, exports that fail half-way, concurrent
//! exports, conflicting options, non-physical fits, and the messages of bad input.

use std::path::Path;
use std::process::{Command, Output};

use adhesion::surface::{HeightMap, peak_statistics, peaks};

fn adhesion_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("binary runs")
}

/// One line on stderr, containing every needle; non-zero exit.
#[track_caller]
fn assert_one_line_error(o: &Output, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "succeeded; stderr: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "not one line:\n{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "`{n}` not in: {stderr}");
    }
}

/// Heights of a seeded pseudo-random `n × n` map.
fn random_heights(nx: usize, ny: usize, seed: u64) -> Vec<f64> {
    let mut s = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
    (0..nx * ny)
        .map(|_| {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e-9
        })
        .collect()
}

/// Mean nearest-peak distance by brute force over all pairs, in metres.
fn brute_force_mean_nearest(map: &HeightMap) -> f64 {
    let pk = peaks(map);
    let (dx, dy) = (map.dx(), map.dy());
    let s = dx.max(dy);
    let off = |d: usize, n: usize| if map.periodic { d.min(n - d) } else { d };
    let total: f64 = pk
        .iter()
        .enumerate()
        .map(|(k, &(i, j))| {
            pk.iter()
                .enumerate()
                .filter(|&(o, _)| o != k)
                .map(|(_, &(io, jo))| {
                    let di = off(io.abs_diff(i), map.nx) as f64 * (dx / s);
                    let dj = off(jo.abs_diff(j), map.ny) as f64 * (dy / s);
                    di.hypot(dj)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .sum();
    total / pk.len() as f64 * s
}

// Peak statistics (section B.4) at any physical lengths: the nearest-neighbour search on a cell
// list agrees with the all-pairs distance for square, elongated and extreme maps, periodic or
// not, and never allocates by the physical lengths (1e-9 m x 1e9 m aborted on a 115 GB
// allocation, a pixel of 1e-170 m indexed out of bounds).
#[test]
fn peak_statistics_agree_with_all_pairs_at_any_lengths() {
    let cases: &[(usize, usize, f64, f64)] = &[
        (64, 64, 1.0, 1.0),
        (64, 48, 1e-6, 3e-6),
        (48, 64, 1e-6, 1.0),
        (16, 16, 1e-9, 1e9),
        (16, 16, 1e9, 1e-9),
        (40, 24, 1e-6, 1e-1),
        (16, 16, 16e-170, 16e-170),
        (32, 32, 1e150, 1e150),
        (16, 64, 1e-300, 1e300),
    ];
    for (seed, &(nx, ny, lx, ly)) in cases.iter().enumerate() {
        for periodic in [false, true] {
            let map = HeightMap {
                nx,
                ny,
                lx,
                ly,
                z: random_heights(nx, ny, seed as u64),
                periodic,
            };
            let ps = peak_statistics(&map);
            assert_eq!(ps.count, peaks(&map).len());
            assert!(ps.count >= 2, "{nx}x{ny} {lx}x{ly}: {} peaks", ps.count);
            let expected = brute_force_mean_nearest(&map);
            let got = ps.mean_nearest_distance;
            assert!(
                (got - expected).abs() <= 1e-12 * expected,
                "{nx}x{ny} {lx:e}x{ly:e} periodic={periodic}: {got:e} vs all pairs {expected:e}"
            );
        }
    }
}

/// Write a Gwyddion simple field of `nx × ny` seeded heights with the given header values.
fn write_gsf(path: &Path, nx: usize, ny: usize, xreal: &str, yreal: &str, units: Option<&str>) {
    let mut h =
        format!("Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {xreal}\nYReal = {yreal}\n");
    if let Some(u) = units {
        h.push_str(&format!("XYUnits = {u}\n"));
    }
    let mut b = h.into_bytes();
    let pad = 4 - b.len() % 4;
    b.extend(std::iter::repeat_n(0u8, pad));
    for z in random_heights(nx, ny, 7) {
        b.extend((z as f32).to_le_bytes());
    }
    std::fs::write(path, b).unwrap();
}

fn write_csv_map(path: &Path, header: &str, n: usize) {
    let z = random_heights(n, n, 3);
    let mut t = String::from(header);
    for row in z.chunks(n) {
        let r: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
        t.push_str(&r.join(","));
        t.push('\n');
    }
    std::fs::write(path, t).unwrap();
}

// `--analyze-surface` at extreme lengths: elongated maps are analysed (same peak count as a
// unit square: peaks do not depend on lengths); lengths whose area or pixel leaves the f64
// range are a one-line error naming the field the user gave (pixel size, header, XReal/YReal).
#[test]
fn analyze_surface_at_extreme_lengths_is_analysed_or_names_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let count = |o: &Output| -> u64 {
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["peak_count"].as_u64().unwrap()
    };
    write_gsf(&d.join("unit.gsf"), 16, 16, "1", "1", None);
    let reference = count(&adhesion_in(d, &["--headless", "--analyze-surface", "unit.gsf"]));
    for (x, y) in [("1e-9", "1e9"), ("1e-6", "1"), ("1e-6", "1e5")] {
        write_gsf(&d.join("m.gsf"), 16, 16, x, y, None);
        let o = adhesion_in(d, &["--headless", "--analyze-surface", "m.gsf"]);
        assert_eq!(count(&o), reference, "XReal {x} YReal {y}");
    }
    write_gsf(&d.join("big.gsf"), 16, 16, "1e308", "1e308", Some("mm"));
    let o = adhesion_in(d, &["--headless", "--analyze-surface", "big.gsf"]);
    assert_one_line_error(&o, &["big.gsf", "XReal = 1e308", "f64 range"]);
    write_gsf(&d.join("tiny.gsf"), 16, 16, "1e-170", "1e-170", None);
    let o = adhesion_in(d, &["--headless", "--analyze-surface", "tiny.gsf"]);
    assert_one_line_error(&o, &["tiny.gsf", "XReal = 1e-170"]);
    write_csv_map(&d.join("plain.csv"), "", 16);
    let o = adhesion_in(
        d,
        &[
            "--headless",
            "--analyze-surface",
            "plain.csv",
            "--pixel-size",
            "1e-170",
        ],
    );
    assert_one_line_error(&o, &["plain.csv", "pixel size 1e-170"]);
    write_csv_map(
        &d.join("header.csv"),
        "# adhesion height map: nx=16 ny=16 lx=1e-200 ly=1e200 (SI units, rows are y)\n",
        16,
    );
    let o = adhesion_in(d, &["--headless", "--analyze-surface", "header.csv"]);
    assert_one_line_error(&o, &["header.csv", "header lx = 1e-200, ly = 1e200", "too small"]);
    write_csv_map(
        &d.join("huge.csv"),
        "# adhesion height map: nx=16 ny=16 lx=1e300 ly=1e300 (SI units, rows are y)\n",
        16,
    );
    let o = adhesion_in(d, &["--headless", "--analyze-surface", "huge.csv"]);
    assert_one_line_error(&o, &["huge.csv", "header lx = 1e300"]);
}

// fig3.7d at scan lengths whose area leaves the f64 range (1e300, 1e200 m: an index out of
// bounds on an empty PSD before) and at a pixel too small for its wavenumbers: one-line errors
// naming `length`.
#[test]
fn fig3_7d_at_extreme_lengths_names_the_length() {
    let dir = tempfile::tempdir().unwrap();
    for v in ["1e300", "1e200", "1e-80"] {
        let set = format!("length={v}");
        let o = adhesion_in(
            dir.path(),
            &[
                "--headless",
                "--quick",
                "--figure",
                "fig3.7d",
                "--set",
                &set,
                "--out",
                "o",
            ],
        );
        assert_one_line_error(&o, &["`length`", v]);
        assert!(!dir.path().join("o").join("fig3.7d.json").exists());
    }
}

// A scene whose memory grows with its parameters estimates it before it starts: fig5.10 with
// 4096 x 4096 springs (inside the declared range; it ran out of memory before) needs more than
// this machine has, and any size above a limit set in ADHESION_MEMORY_LIMIT is refused at once
// with the estimate and the limit.
#[test]
fn a_run_that_would_not_fit_in_memory_is_refused_before_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--headless",
        "--figure",
        "fig5.10",
        "--set",
        "springs_x=4096",
        "--set",
        "springs_y=4096",
        "--out",
        "o",
    ];
    let o = Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .current_dir(dir.path())
        .env("ADHESION_MEMORY_LIMIT", "16G")
        .args(args)
        .output()
        .unwrap();
    assert_one_line_error(
        &o,
        &["`springs_x x springs_y` = 4096 x 4096", "24.1 GiB", "16.0 GiB"],
    );
    let o = Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .current_dir(dir.path())
        .env("ADHESION_MEMORY_LIMIT", "100M")
        .args([
            "--headless",
            "--figure",
            "fig3.7d",
            "--set",
            "grid=2048",
            "--out",
            "o",
        ])
        .output()
        .unwrap();
    assert_one_line_error(&o, &["`grid` = 2048", "320 MiB", "100 MiB"]);
    assert!(!dir.path().join("o").exists());
}

fn adhesion(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

// An export whose last format cannot be written (a folder in the way of fig1.1.csv, fit.json)
// leaves none of its formats and no temporary file (it left the PNG and SVG before), and the
// error names the path and the operation.
#[test]
fn a_failed_export_leaves_no_format_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    std::fs::create_dir_all(out.join("fig1.1.csv")).unwrap();
    let o = adhesion(&["--headless", "--figure", "fig1.1", "--out", out.to_str().unwrap()]);
    assert_one_line_error(&o, &["writing", "fig1.1.csv", "folder"]);
    assert_eq!(files_in(&out), ["fig1.1.csv"]);
    std::fs::create_dir_all(out.join("fit.json")).unwrap();
    let curve = crate::common::root().join("tests/fixtures/curves/synthetic_cycle.csv");
    let o = adhesion(&[
        "--headless",
        "--fit",
        curve.to_str().unwrap(),
        "--tip-radius",
        "1e-6",
        "--spring-constant",
        "0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_one_line_error(&o, &["writing", "fit.json"]);
    assert_eq!(files_in(&out), ["fig1.1.csv", "fit.json"]);
}

// SIGTERM while an export writes its files (a 260 MB CSV): the process removes its temporaries
// and exits 128 + 15; the formats appear all together or not at all.
#[test]
fn a_signal_during_an_export_leaves_no_temporary_and_no_partial_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let mut child = Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .args(["--headless", "--figure", "fig1.1", "--set", "points=1000000"])
        .args(["--format", "csv,json", "--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    let mut signalled = false;
    while start.elapsed() < std::time::Duration::from_secs(60) {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if files_in(&out).iter().any(|f| f.ends_with(".tmp")) {
            let ok = Command::new("kill")
                .args(["-TERM", &child.id().to_string()])
                .status()
                .unwrap();
            assert!(ok.success());
            signalled = true;
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    let status = child.wait().unwrap();
    assert!(
        signalled,
        "no temporary file seen while the export ran ({status:?})"
    );
    assert_eq!(status.code(), Some(143), "{status:?}");
    let left = files_in(&out);
    assert!(
        left.is_empty() || left == ["fig1.1.csv", "fig1.1.json"],
        "left behind: {left:?}"
    );
}

// Two exports of one scene into one folder at once, with different parameters: the CSV and the
// JSON that remain always come from the same run (the sets are renamed under a folder lock).
#[test]
fn concurrent_exports_to_one_folder_leave_a_consistent_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    for _ in 0..4 {
        let spawn = |points: &str| {
            Command::new(env!("CARGO_BIN_EXE_adhesion"))
                .args([
                    "--headless",
                    "--figure",
                    "fig1.1",
                    "--set",
                    &format!("points={points}"),
                ])
                .args(["--format", "csv,json", "--out", out.to_str().unwrap()])
                .stdout(std::process::Stdio::null())
                .spawn()
                .unwrap()
        };
        let (mut a, mut b) = (spawn("20000"), spawn("30000"));
        assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("fig1.1.json")).unwrap()).unwrap();
        let points = json["parameters"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == "points")
            .and_then(|p| p["value"].as_u64())
            .expect("points in the JSON parameters");
        let csv = std::fs::read_to_string(out.join("fig1.1.csv")).unwrap();
        let hertz_rows = csv.lines().filter(|l| l.starts_with("1,Hertz,")).count() as u64;
        assert_eq!(hertz_rows, points, "CSV of one run beside the JSON of the other");
        assert_eq!(files_in(&out), ["fig1.1.csv", "fig1.1.json"]);
    }
}

// Options that the command does not use, or commands given together, are one-line errors (they
// were silently ignored: `--all --preset x.toml --set radius=-1` ran every scene with defaults).
#[test]
fn conflicting_or_unused_options_are_one_line_errors() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["--headless", "--all", "--preset", "x.toml", "--set", "radius=-1"],
            "--preset applies to --figure only",
        ),
        (
            &["--headless", "--all", "--surface", "missing.gsf"],
            "--surface applies to --figure only",
        ),
        (
            &["--headless", "--fit", "c.csv", "--figure", "fig1.1"],
            "--figure and --fit cannot be combined",
        ),
        (
            &["--headless", "--generate-surface", "--analyze-surface", "x.csv"],
            "--generate-surface and --analyze-surface cannot be combined",
        ),
        (
            &["--headless", "--figure", "fig1.1", "--pixel-size", "1e-9"],
            "--pixel-size applies to --analyze-surface only",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in cases {
        let mut all = args.to_vec();
        all.extend(["--out", "o"]);
        let o = adhesion_in(dir.path(), &all);
        assert_one_line_error(&o, &[needle]);
        assert!(files_in(dir.path()).is_empty(), "{args:?} wrote files");
    }
}

// Negative numbers in exponent form are values, not flags: the program's own range message in
// one line (clap's multi-line "unexpected argument '-1' found" before); clap's own errors are
// one line too.
#[test]
fn negative_numbers_are_values_and_command_line_errors_are_one_line() {
    let cases: &[(&[&str], &[&str])] = &[
        (
            &[
                "--headless",
                "--generate-surface",
                "--rms",
                "-1e-9",
                "--size",
                "8",
                "--length",
                "1e-6",
                "--correlation-length",
                "1e-7",
                "--out",
                "s.csv",
            ],
            &["`rms` = -1e-9", "positive"],
        ),
        (
            &["--headless", "--fit", "c.csv", "--tip-radius", "-1e-6"],
            &["c.csv"],
        ),
        (
            &[
                "--headless",
                "--analyze-surface",
                "m.csv",
                "--pixel-size",
                "-1e-8",
            ],
            &["m.csv"],
        ),
        (&["--headless", "--bogus"], &["--bogus", "--help"]),
        (&["--headless", "--figure"], &["--figure"]),
    ];
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.csv"), "1,2\n3,4\n").unwrap();
    for (args, needles) in cases {
        let o = adhesion_in(dir.path(), args);
        assert_one_line_error(&o, needles);
    }
    let o = adhesion_in(
        dir.path(),
        &[
            "--headless",
            "--analyze-surface",
            "m.csv",
            "--pixel-size",
            "-1e-8",
        ],
    );
    assert_one_line_error(&o, &["pixel size -1e-8 must be positive"]);
}

// Echoed input is escaped and cut: a 5 MB value with CR and NUL comes back as one short line;
// numbers in messages have at most 6 significant digits.
#[test]
fn echoed_input_is_escaped_and_truncated_and_numbers_are_short() {
    let dir = tempfile::tempdir().unwrap();
    let long = format!("units = \"{}\\r\\u0000x\"\n", "a".repeat(5_000_000));
    std::fs::write(dir.path().join("p.toml"), long).unwrap();
    let o = adhesion_in(
        dir.path(),
        &[
            "--headless",
            "--figure",
            "fig1.1",
            "--preset",
            "p.toml",
            "--out",
            "o",
        ],
    );
    assert_one_line_error(&o, &["p.toml"]);
    assert!(o.stderr.len() < 3000, "{} bytes echoed", o.stderr.len());
    assert!(!o.stderr.contains(&b'\r') && !o.stderr.contains(&0u8));
    let o = adhesion_in(
        dir.path(),
        &[
            "--headless",
            "--figure",
            "fig3.7d",
            "--set",
            "exponent=1e300",
            "--out",
            "o",
        ],
    );
    assert_one_line_error(&o, &["`exponent` = 1e300:"]);
}

// Item 9: a run inside the declared ranges ends with finite results or one line naming the
// parameter; non-dimensional results do not overflow with the dimensional scales.
#[test]
fn extreme_values_give_finite_results_or_name_the_parameter() {
    let dir = tempfile::tempdir().unwrap();
    for modulus in ["1e308", "1e-320"] {
        let set = format!("modulus={modulus}");
        let o = adhesion_in(
            dir.path(),
            &["--headless", "--figure", "fig1.1", "--set", &set, "--out", "o"],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/fig1.1.json")).unwrap())
                .unwrap();
        let results = json["results"].as_object().unwrap();
        for (name, v) in results {
            assert!(v.as_f64().is_some_and(f64::is_finite), "{modulus}: {name} = {v}");
        }
        assert_eq!(results["dmt_adhesive_force_norm"].as_f64(), Some(-2.0));
    }
    let o = adhesion_in(
        dir.path(),
        &[
            "--headless",
            "--quick",
            "--figure",
            "fig3.7d",
            "--set",
            "exponent=1e-300",
            "--out",
            "p",
        ],
    );
    assert_one_line_error(&o, &["`exponent` = 1e-300", "not finite"]);
    assert!(!dir.path().join("p").join("fig3.7d.json").exists());
}

// Item 13: a failure inside a model names the user's parameter and its value, and no number
// in the message has more than 6 significant digits.
#[test]
fn model_failures_name_the_parameter_with_short_numbers() {
    let dir = tempfile::tempdir().unwrap();
    for (fig, set, needle) in [
        (
            "fig3.8",
            "tip_radius=1e300",
            "`tip_radius` = 1e300 (default 2.5e-5)",
        ),
        ("fig3.8", "psd_rms=1e300", "`psd_rms` = 1e300"),
        ("fig5.4", "u_min=-1e300", "`u_min` = -1e300"),
        ("fig3.4", "chi_b=1e300", "`chi_b` = 1e300"),
    ] {
        let o = adhesion_in(
            dir.path(),
            &[
                "--headless",
                "--quick",
                "--figure",
                fig,
                "--set",
                set,
                "--out",
                "o",
            ],
        );
        assert_one_line_error(&o, &[needle]);
        let msg = String::from_utf8_lossy(&o.stderr);
        let longest = msg
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .map(|t| t.chars().filter(char::is_ascii_digit).count())
            .max()
            .unwrap_or(0);
        assert!(longest <= 7, "{fig} {set}: a number of {longest} digits in {msg}");
    }
}

// Issue 19, attribution in quick runs: a failure names only what the user changed (`--set`, a
// preset), measured from the defaults in quick form, never the resolution quick mode itself
// reduced (before: "`grid_points` = 6 (default 60), `points` = 7 (default 61)" for fig3.8).
#[test]
fn quick_run_failures_name_only_what_the_user_changed() {
    let dir = tempfile::tempdir().unwrap();
    for (fig, sets, needles, absent) in [
        (
            "fig3.8",
            &["tip_radius=1e300"][..],
            &["`tip_radius` = 1e300 (default 2.5e-5)"][..],
            &["`grid_points`", "`points`"][..],
        ),
        (
            "fig3.7d",
            &["exponent=1e-300"][..],
            &["`exponent` = 1e-300"][..],
            &["`grid`"][..],
        ),
        // A resolution the user set in a quick run is named, with its quick-form default.
        (
            "fig3.8",
            &["tip_radius=1e300", "points=5"][..],
            &["`tip_radius` = 1e300", "`points` = 5 (default 7)"][..],
            &["`grid_points`"][..],
        ),
    ] {
        let mut args = vec!["--headless", "--quick", "--figure", fig, "--out", "o"];
        for s in sets {
            args.extend(["--set", s]);
        }
        // The unsharded run and the merge of a sharded sweep attribute alike.
        let runs = if fig == "fig3.8" { 2 } else { 1 };
        for run in 0..runs {
            let mut args = args.clone();
            if run == 1 {
                let mut shard = args.clone();
                shard.extend(["--shard", "0/1"]);
                assert!(adhesion_in(dir.path(), &shard).status.success());
                args.push("--merge");
            }
            let o = adhesion_in(dir.path(), &args);
            assert_one_line_error(&o, needles);
            let msg = String::from_utf8_lossy(&o.stderr);
            for a in absent {
                assert!(!msg.contains(a), "{args:?}: `{a}` named in {msg}");
            }
        }
    }
}

// Item 16: preset syntax errors give the line and the key.
#[test]
fn preset_syntax_errors_give_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    for (text, needle) in [
        (
            "radius = 1e-6\nradius = 2e-6\n",
            "line 2 (`radius`): duplicate key",
        ),
        ("points = 400\nmodulus = 1e6x\n", "line 2 (`modulus`)"),
    ] {
        std::fs::write(dir.path().join("p.toml"), text).unwrap();
        let o = adhesion_in(
            dir.path(),
            &[
                "--headless",
                "--figure",
                "fig1.1",
                "--preset",
                "p.toml",
                "--out",
                "o",
            ],
        );
        assert_one_line_error(&o, &["p.toml", needle]);
    }
}

// Item 17: every text reader takes a byte-order mark and CR or CRLF line ends alike, and a
// blank file name is no file, for every file parameter.
#[test]
fn byte_order_marks_line_ends_and_blank_file_names_are_handled_alike() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    // A height map with a BOM and CR line ends.
    let mut map = String::from("\u{feff}# lx=1e-6 ly=1e-6\r");
    for (k, z) in random_heights(16, 16, 3).chunks(16).enumerate() {
        let row: Vec<String> = z.iter().map(|v| format!("{v:e}")).collect();
        map.push_str(&row.join(","));
        map.push(if k % 2 == 0 { '\r' } else { '\n' });
    }
    std::fs::write(p.join("map.csv"), &map).unwrap();
    let plain = adhesion_in(
        p,
        &[
            "--headless",
            "--analyze-surface",
            "map.csv",
            "--pixel-size",
            "1e-8",
        ],
    );
    assert!(
        plain.status.success(),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    // A preset with a BOM and CRLF.
    std::fs::write(p.join("b.toml"), "\u{feff}radius = 2e-5\r\npoints = 50\r\n").unwrap();
    let o = adhesion_in(
        p,
        &[
            "--headless",
            "--figure",
            "fig1.1",
            "--preset",
            "b.toml",
            "--out",
            "o",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A blank data file is the demonstration, as a blank profile file is the built-in profile.
    let o = adhesion_in(
        p,
        &[
            "--headless",
            "--quick",
            "--figure",
            "fig2.8-fit",
            "--set",
            "data_file=   ",
            "--out",
            "q",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json = std::fs::read_to_string(p.join("q/fig2.8-fit.json")).unwrap();
    assert!(json.contains("demonstration"), "{json}");
}
