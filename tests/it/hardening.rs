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
