//! The force-distance readers against afmformats: every fixture of tests/fixtures/afm/ (afmformats
//! 0.18.7's test files) read with `read_force_file` and compared with afmformats' readings in
//! reference.json (written by benches/afmformats_reference.py), column by column to 1e-6
//! relative; and the refusals: truncated files, headers claiming more than the file holds,
//! non-regular files, missing calibration values.

use adhesion::readers::{ForceFile, ReadOptions, Segment, read_force_file};
use serde_json::Value;
use std::path::{Path, PathBuf};

const TOL: f64 = 1e-6;

fn dir() -> PathBuf {
    crate::common::root().join("tests/fixtures/afm")
}

fn reference() -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir().join("reference.json")).unwrap()).unwrap()
}

fn opts_of(case: &Value) -> ReadOptions {
    ReadOptions {
        spring_constant: case["options"]["spring_constant"].as_f64(),
        sensitivity: case["options"]["sensitivity"].as_f64(),
    }
}

fn channel<'a>(s: &'a Segment, name: &str) -> Option<&'a [f64]> {
    match name {
        "force" => Some(&s.force),
        "height_measured" => s.height_measured.as_deref(),
        "height_piezo" => s.height_piezo.as_deref(),
        "time" => s.time.as_deref(),
        "tip_position" => s.tip_position.as_deref(),
        _ => None,
    }
}

/// Our segments matched to afmformats' (by its `segment` numbers); an Igor wave, one segment in
/// afmformats, is split by its note into approach and retract here and compared joined.
fn matched(file: &str, ours: &[Segment], n_ref: usize) -> Vec<Segment> {
    if ours.len() == n_ref {
        return ours.to_vec();
    }
    assert!(
        file.ends_with(".ibw") && n_ref == 1,
        "{file}: {} segments, afmformats has {n_ref}",
        ours.len()
    );
    let mut joined = Segment::default();
    for s in ours {
        joined.force.extend(&s.force);
        for (dst, src) in [
            (&mut joined.height_measured, &s.height_measured),
            (&mut joined.height_piezo, &s.height_piezo),
            (&mut joined.time, &s.time),
        ] {
            if let Some(src) = src {
                dst.get_or_insert_with(Vec::new).extend(src);
            }
        }
    }
    vec![joined]
}

/// Compare a file's reading with afmformats'; the largest relative difference of any compared
/// value (sample, min, max, sum) where the reference is not 0.
fn compare(case: &Value, ours: &ForceFile) -> f64 {
    let file = case["file"].as_str().unwrap();
    let curves = case["curves"].as_array().unwrap();
    assert_eq!(ours.curves.len(), curves.len(), "{file}: number of curves");
    let mut worst = 0.0f64;
    let mut check = |what: String, got: f64, want: f64, floor: f64| {
        let d = (got - want).abs();
        assert!(
            d <= TOL * want.abs() + floor,
            "{what}: got {got:.15e}, afmformats {want:.15e} (diff {d:.2e}, floor {floor:.2e})"
        );
        if want != 0.0 {
            worst = worst.max(d / want.abs());
        }
    };
    for (ci, (c, r)) in ours.curves.iter().zip(curves).enumerate() {
        let m = &r["meta"];
        for (name, got) in [
            ("spring_constant", c.meta.spring_constant),
            ("sensitivity", c.meta.sensitivity),
        ] {
            if let Some(want) = m[name].as_f64() {
                check(format!("{file} curve {ci} {name}"), got.unwrap(), want, 0.0);
            }
        }
        if let Some(p) = m["position"].as_array() {
            let got = c
                .meta
                .position
                .unwrap_or_else(|| panic!("{file} curve {ci}: no position"));
            for a in 0..2 {
                check(
                    format!("{file} curve {ci} position"),
                    got[a],
                    p[a].as_f64().unwrap(),
                    1e-15,
                );
            }
        }
        for (name, got) in [
            ("grid_index", c.meta.grid_index),
            ("grid_shape", c.meta.grid_shape),
        ] {
            if let Some(want) = m[name].as_array() {
                let want: Vec<usize> = want.iter().map(|v| v.as_u64().unwrap() as usize).collect();
                assert_eq!(got.map(|g| g.to_vec()), Some(want), "{file} curve {ci} {name}");
            }
        }
        if let Some(want) = m["grid_size"].as_array() {
            let got = c
                .meta
                .grid_size
                .unwrap_or_else(|| panic!("{file} curve {ci}: no grid size"));
            for a in 0..2 {
                check(
                    format!("{file} curve {ci} grid size"),
                    got[a],
                    want[a].as_f64().unwrap(),
                    0.0,
                );
            }
        }
        let rsegs = r["segments"].as_array().unwrap();
        let segs = matched(file, &c.segments, rsegs.len());
        for (si, (s, rs)) in segs.iter().zip(rsegs).enumerate() {
            let n = rs["len"].as_u64().unwrap() as usize;
            assert_eq!(s.len(), n, "{file} curve {ci} segment {si}: samples");
            for (name, stats) in rs["columns"].as_object().unwrap() {
                let what = format!("{file} curve {ci} segment {si} {name}");
                let v = channel(s, name).unwrap_or_else(|| panic!("{what}: missing"));
                assert_eq!(v.len(), n, "{what}: samples");
                if n == 0 {
                    continue;
                }
                let (min, max) = (stats["min"].as_f64().unwrap(), stats["max"].as_f64().unwrap());
                let scale = min.abs().max(max.abs());
                let floor = TOL * scale;
                check(
                    format!("{what} min"),
                    v.iter().copied().fold(f64::INFINITY, f64::min),
                    min,
                    floor,
                );
                check(
                    format!("{what} max"),
                    v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                    max,
                    floor,
                );
                check(
                    format!("{what} sum"),
                    v.iter().sum(),
                    stats["sum"].as_f64().unwrap(),
                    floor * n as f64,
                );
                for smp in stats["samples"].as_array().unwrap() {
                    let i = smp[0].as_u64().unwrap() as usize;
                    check(format!("{what}[{i}]"), v[i], smp[1].as_f64().unwrap(), floor);
                }
            }
        }
    }
    worst
}

#[test]
fn every_fixture_reads_as_afmformats_reads_it() {
    let reference = reference();
    let mut report = Vec::new();
    for case in reference["cases"].as_array().unwrap() {
        let file = case["file"].as_str().unwrap();
        let ours = read_force_file(&dir().join(file), &opts_of(case))
            .unwrap_or_else(|e| panic!("{file} {}: {e}", case["options"]));
        let worst = compare(case, &ours);
        report.push(format!(
            "{file} {}: {} curve(s), max rel. diff {worst:.2e}",
            case["options"],
            ours.curves.len()
        ));
    }
    println!("{}", report.join("\n"));
}

#[test]
fn chiaro_text_export_reads_unzipped_too() {
    let reference = reference();
    let case = reference["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["file"].as_str().unwrap().contains("chiaro"))
        .unwrap();
    let bytes = std::fs::read(dir().join(case["file"].as_str().unwrap())).unwrap();
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    let mut text = Vec::new();
    std::io::Read::read_to_end(&mut zip.by_index(0).unwrap(), &mut text).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("AEBP1_Indentation_002.txt");
    std::fs::write(&path, text).unwrap();
    let ours = read_force_file(&path, &ReadOptions::default()).unwrap();
    assert!(ours.format.contains("Chiaro"));
    compare(case, &ours);
    // The tip position is the file's: piezo height plus cantilever deflection.
    assert!(ours.curves[0].segments[0].tip_position.is_some());
}

/// The error's message: one line that names the file.
#[track_caller]
fn one_line_naming(e: &adhesion::Error, path: &Path) -> String {
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "not one line: {msg}");
    assert!(
        msg.contains(&path.display().to_string()),
        "does not name {}: {msg}",
        path.display()
    );
    msg
}

/// Where to cut each fixture so that what is left is broken: binary formats in the middle, text
/// formats inside a data row (after its first separator) or inside their header.
fn cut(name: &str, bytes: &[u8]) -> usize {
    let half = bytes.len() / 2;
    let text_row_cut = |sep: u8| {
        let line = half + bytes[half..].iter().position(|&b| b == b'\n').unwrap() + 1;
        line + bytes[line..].iter().position(|&b| b == sep).unwrap() + 1
    };
    if name.ends_with(".csv") {
        text_row_cut(b',')
    } else if name.ends_with(".txt") {
        text_row_cut(b'\t')
    } else if name.ends_with(".tab") {
        // Inside the metadata block.
        bytes.windows(8).position(|w| w == b"\"enum\": ").unwrap()
    } else {
        half
    }
}

#[test]
fn truncated_files_are_refused_in_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = reference();
    let opts = ReadOptions {
        spring_constant: Some(0.1),
        sensitivity: Some(5e-8),
    };
    let mut seen = std::collections::BTreeSet::new();
    for case in reference["cases"].as_array().unwrap() {
        let name = case["file"].as_str().unwrap();
        if !seen.insert(name) {
            continue;
        }
        let bytes = std::fs::read(dir().join(name)).unwrap();
        let path = tmp.path().join(name);
        std::fs::write(&path, &bytes[..cut(name, &bytes)]).unwrap();
        let e = read_force_file(&path, &opts).expect_err(name);
        one_line_naming(&e, &path);
        // Nothing at all.
        std::fs::write(&path, b"").unwrap();
        one_line_naming(&read_force_file(&path, &opts).expect_err(name), &path);
    }
}

/// An Igor binary wave v5 header (little-endian) claiming `npnts` float32 points, with `data`
/// bytes of data after it.
fn igor(npnts: i32, rows: i32, data: usize) -> Vec<u8> {
    let mut b = vec![0u8; 64 + 320];
    b[0..2].copy_from_slice(&5i16.to_le_bytes());
    let wfm = (320i64 + 4 * i64::from(npnts)).min(i64::from(i32::MAX)) as i32;
    b[4..8].copy_from_slice(&wfm.to_le_bytes());
    b[64 + 12..64 + 16].copy_from_slice(&npnts.to_le_bytes());
    b[64 + 16..64 + 18].copy_from_slice(&2i16.to_le_bytes());
    b[64 + 68..64 + 72].copy_from_slice(&rows.to_le_bytes());
    b.extend(std::iter::repeat_n(0u8, data));
    b
}

#[test]
fn headers_claiming_more_than_the_file_holds_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("claim.ibw");
    // 2^31 − 1 points claimed (8 GiB of data), 16 bytes present.
    std::fs::write(&path, igor(i32::MAX, i32::MAX, 16)).unwrap();
    let msg = one_line_naming(
        &read_force_file(&path, &ReadOptions::default()).unwrap_err(),
        &path,
    );
    assert!(msg.contains("Igor"), "{msg}");

    // A JPK segment header claiming 10^12 points over a channel of a few thousand.
    let src = std::fs::read(dir().join("fmt-jpk-fd_spot3-0192.jpk-force")).unwrap();
    let mut zin = zip::ZipArchive::new(std::io::Cursor::new(src)).unwrap();
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let stored = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for i in 0..zin.len() {
        let mut f = zin.by_index(i).unwrap();
        let name = f.name().unwrap().into_owned();
        let mut data = Vec::new();
        std::io::Read::read_to_end(&mut f, &mut data).unwrap();
        if name.ends_with("segment-header.properties") {
            let text = String::from_utf8_lossy(&data).into_owned();
            let text: String = text
                .lines()
                .map(|l| {
                    if l.starts_with("force-segment-header.num-points=") {
                        "force-segment-header.num-points=1000000000000".to_owned()
                    } else {
                        l.to_owned()
                    }
                })
                .collect::<Vec<_>>()
                .join("\n");
            data = text.into_bytes();
        }
        if name.ends_with('/') {
            out.add_directory(name, stored).unwrap();
        } else {
            out.start_file(name, stored).unwrap();
            std::io::Write::write_all(&mut out, &data).unwrap();
        }
    }
    let path = tmp.path().join("claim.jpk-force");
    std::fs::write(&path, out.finish().unwrap().into_inner()).unwrap();
    let msg = one_line_naming(
        &read_force_file(&path, &ReadOptions::default()).unwrap_err(),
        &path,
    );
    assert!(msg.contains("1000000000000"), "{msg}");
}

#[cfg(unix)]
#[test]
fn fifos_and_folders_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("curve.jpk-force");
    let ok = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    if ok {
        let msg = one_line_naming(
            &read_force_file(&fifo, &ReadOptions::default()).unwrap_err(),
            &fifo,
        );
        assert!(msg.contains("not a regular file"), "{msg}");
    }
    let msg = one_line_naming(
        &read_force_file(tmp.path(), &ReadOptions::default()).unwrap_err(),
        tmp.path(),
    );
    assert!(msg.contains("folder"), "{msg}");
}

#[test]
fn missing_calibration_values_name_the_option() {
    let none = ReadOptions::default();
    for (file, option) in [
        (
            "fmt-afm-workshop-fd_single_2018-08-01_13.06.09.csv",
            "--spring-constant N/m",
        ),
        (
            "fmt-afm-workshop-fd_single_2018-08-01_13.06.09.csv",
            "--sensitivity m/V",
        ),
        (
            "fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip",
            "--spring-constant N/m",
        ),
        (
            "fmt-jpk-fd_single-modified_2023.jpk-force",
            "--spring-constant N/m",
        ),
        (
            "fmt-jpk-cl_calibration_force-save-2015.02.04-11.25.21.294.jpk-force",
            "--sensitivity m/V",
        ),
        (
            "fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt",
            "--spring-constant N/m",
        ),
    ] {
        let path = dir().join(file);
        let msg = one_line_naming(&read_force_file(&path, &none).unwrap_err(), &path);
        assert!(msg.contains(option), "{file}: {msg}");
    }
    // The sensitivity alone is not enough for a curve in volts.
    let path = dir().join("fmt-afm-workshop-fd_single_2018-08-01_13.06.09.csv");
    let msg = read_force_file(
        &path,
        &ReadOptions {
            sensitivity: Some(1e-8),
            ..none
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        msg.contains("--spring-constant N/m") && !msg.contains("--sensitivity"),
        "{msg}"
    );
}

#[test]
fn segments_have_kinds_and_maps_their_grid() {
    let read = |f: &str| read_force_file(&dir().join(f), &ReadOptions::default()).unwrap();
    use adhesion::readers::SegmentKind::{Approach, Pause, Retract};
    let kinds = |f: &ForceFile| {
        f.curves[0]
            .segments
            .iter()
            .map(|s| s.kind.clone().unwrap())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        kinds(&read("fmt-jpk-fd_spot3-0192.jpk-force")),
        [Approach, Retract]
    );
    assert_eq!(
        kinds(&read("fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force")),
        [Approach, Pause, Retract]
    );
    assert_eq!(kinds(&read("fmt-igor-fd_U3_3_p10004.ibw")), [Approach, Retract]);
    let map = read("fmt-jpk-fd_map2x2_extracted.jpk-force-map");
    assert!(map.format.contains("map"));
    assert!(
        map.curves
            .iter()
            .all(|c| c.meta.grid_shape.is_some() && c.meta.grid_index.is_some())
    );
    // The approach decreases in height (towards the sample), as afmformats' convention has it.
    let s = &read("fmt-jpk-fd_spot3-0192.jpk-force").curves[0].segments[0];
    let h = s.height().unwrap();
    assert!(h[h.len() - 1] < h[0]);
}

#[test]
fn zip_bombs_are_refused() {
    // 40 MiB of zeros deflate to about 40 kB: past the budget of max(64 × size, 16 MiB).
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let deflated =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    out.start_file("header.properties", deflated).unwrap();
    let zeros = vec![b'0'; 1 << 20];
    for _ in 0..40 {
        std::io::Write::write_all(&mut out, &zeros).unwrap();
    }
    let bytes = out.finish().unwrap().into_inner();
    assert!(bytes.len() < 1 << 20, "{}", bytes.len());
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("bomb.jpk-force");
    std::fs::write(&path, bytes).unwrap();
    let msg = one_line_naming(
        &read_force_file(&path, &ReadOptions::default()).unwrap_err(),
        &path,
    );
    assert!(msg.contains("budget"), "{msg}");
}
