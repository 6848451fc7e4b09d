//! Measured height maps read by content ([`adhesion::surface::formats`]), checked against
//! SurfaceTopography 1.25's readings of the same files (tests/fixtures/maps/reference.json,
//! written by benches/surfacetopography_reference.py): grid, physical size, heights, sum and RMS
//! about the mean to 1e-6 relative; missing points, line scans, truncated and corrupt files, and
//! headers claiming huge grids refused with one-line errors naming the file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use adhesion::surface::formats::{Measured, parse_bytes, read_measured};

fn maps() -> PathBuf {
    crate::common::root().join("tests/fixtures/maps")
}

/// Relative difference, 0 for two zeros.
fn rel(a: f64, b: f64) -> f64 {
    if a == b {
        0.0
    } else {
        (a - b).abs() / a.abs().max(b.abs())
    }
}

/// Our heights in metres where the file gives a length unit (else as stored).
fn metres(m: &Measured) -> Vec<f64> {
    let f = m.info.z_unit.metres.unwrap_or(1.0);
    m.z.iter().map(|v| v * f).collect()
}

#[test]
fn every_fixture_reads_as_surfacetopography_does() {
    compare_with_reference(&maps(), "reference.json", 15);
}

/// The example files too large to commit (SurfaceTopography's `test/file_format_examples`),
/// in the folder `ADHESION_MAPS_EXTRA` with the `reference-extra.json` that
/// `benches/surfacetopography_reference.py --extra DIR` writes there.
#[test]
#[ignore = "needs ADHESION_MAPS_EXTRA: a folder of example files and their reference-extra.json"]
fn extra_example_files_read_as_surfacetopography_does() {
    let dir = PathBuf::from(std::env::var("ADHESION_MAPS_EXTRA").expect("ADHESION_MAPS_EXTRA"));
    compare_with_reference(&dir, "reference-extra.json", 1);
}

/// Each file of `dir` listed in its `reference` JSON, as SurfaceTopography read it, to 1e-6
/// relative; prints the table of RMS heights.
fn compare_with_reference(dir: &Path, reference: &str, at_least: usize) {
    let text = std::fs::read_to_string(dir.join(reference)).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let tol = 1e-6;
    let mut table = vec![
        "| file | channel | grid | physical size [m] | RMS ours [m] | RMS SurfaceTopography [m] | rel. diff. |".to_string(),
        "|---|---|---|---|---|---|---|".to_string(),
    ];
    let entries = doc["maps"].as_array().unwrap();
    assert!(entries.len() >= at_least);
    for e in entries {
        let file = e["file"].as_str().unwrap();
        let channel = e["channel"].as_str().unwrap();
        let path = dir.join(file);
        let m = read_measured(&path, Some(channel)).unwrap_or_else(|err| panic!("{file}: {err}"));
        let grid: Vec<usize> = e["nb_grid_pts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(
            (m.info.nx, m.info.ny),
            (grid[0], grid[1]),
            "{file} {channel}: grid"
        );
        // Physical size: in metres where SurfaceTopography knows the unit, else as stored.
        let st_size: Vec<f64> = e["physical_sizes_m"]
            .as_array()
            .or(e["physical_sizes"].as_array())
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let ours = m.info.size.unwrap();
        let f = m.info.xy_unit.metres.unwrap_or(1.0);
        // A line scan has its length only.
        for k in 0..st_size.len() {
            assert!(
                rel(ours[k] * f, st_size[k]) < tol,
                "{file} {channel}: size {} vs {}",
                ours[k] * f,
                st_size[k]
            );
        }
        let z = metres(&m);
        let missing = z.iter().filter(|v| !v.is_finite()).count();
        assert_eq!(
            missing as u64,
            e["missing"].as_u64().unwrap(),
            "{file} {channel}: missing points"
        );
        for s in e["samples"].as_array().unwrap() {
            let (i, j) = (s[0].as_u64().unwrap() as usize, s[1].as_u64().unwrap() as usize);
            let ours = z[j * m.info.nx + i];
            match s[2].as_f64() {
                Some(h) => assert!(
                    rel(ours, h) < tol,
                    "{file} {channel}: height at ({i}, {j}) {ours} vs {h}"
                ),
                None => assert!(ours.is_nan(), "{file} {channel}: ({i}, {j}) should be missing"),
            }
        }
        // Missing points and line scans read as SurfaceTopography reads them, and are refused as
        // height maps with one line naming the file and why.
        let refusal = |why: &str| {
            let err = m
                .clone()
                .into_height_map(&path, None, false)
                .unwrap_err()
                .to_string();
            assert!(
                err.contains(why) && err.contains(file) && !err.contains('\n'),
                "{err}"
            );
        };
        if missing > 0 {
            refusal(&format!("{missing} of"));
            continue;
        }
        if m.info.ny == 1 {
            refusal("a line scan (1D profile)");
        }
        let n = z.len() as f64;
        let sum: f64 = z.iter().sum();
        let mean = sum / n;
        let rms = (z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
        let (st_sum, st_rms) = (e["sum"].as_f64().unwrap(), e["rms"].as_f64().unwrap());
        // A sum near zero (heights about a zero mean) compares relative to the sum of |z|.
        let scale = z.iter().map(|v| v.abs()).sum::<f64>();
        assert!(
            (sum - st_sum).abs() <= tol * scale,
            "{file} {channel}: sum {sum} vs {st_sum}"
        );
        assert!(rel(rms, st_rms) < tol, "{file} {channel}: rms {rms} vs {st_rms}");
        table.push(format!(
            "| {file} | {channel} | {} x {} | {:.6e} x {:.6e} | {rms:.9e} | {st_rms:.9e} | {:.1e} |",
            m.info.nx,
            m.info.ny,
            ours[0] * f,
            ours[1] * f,
            rel(rms, st_rms)
        ));
    }
    println!("{}", table.join("\n"));
}

/// The fixtures whose lengths and heights are in length units become height maps in metres.
#[test]
fn fixtures_with_units_become_height_maps() {
    for (file, channel) in [
        ("sdf-1.sdf", None),
        ("sdf-binary.sdf", None),
        ("matrix-6.txt", None),
        ("x3p-f32.x3p", None),
        ("x3p-u16.x3p", None),
        ("gwy-1.gwy", Some("Height")),
        ("sur-3.sur", None),
        ("di-3.di", Some("Height")),
        ("xyz-1.txt", None),
        ("mi-1.mi", Some("Topography")),
        ("al3d-1.al3d", None),
        ("nid-small.nid", None),
        ("plu-small.plu", Some("layer0")),
        ("metropro-small.dat", None),
        ("opd-small.opd", Some("OPD")),
        ("opdx-small.opdx", None),
    ] {
        let path = maps().join(file);
        let m = read_measured(&path, channel).unwrap();
        let (nx, ny) = (m.info.nx, m.info.ny);
        let map = m
            .into_height_map(&path, None, file.ends_with(".txt"))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((map.nx, map.ny), (nx, ny));
        assert!(map.lx > 0.0 && map.rms() >= 0.0, "{file}");
    }
}

#[test]
fn channels_are_chosen_by_name_and_listed() {
    let path = maps().join("gwy-1.gwy");
    let m = read_measured(&path, None).unwrap();
    assert_eq!(m.info.name, "Height");
    let e = read_measured(&path, Some("Topography")).unwrap_err().to_string();
    assert!(
        e.contains("`Height`") && e.contains("`Phase`") && e.contains("`Height masked`"),
        "{e}"
    );
    // Phase is in degrees: not a height channel.
    let e = read_measured(&path, Some("phase"))
        .unwrap()
        .into_height_map(&path, None, false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("`deg`") && e.contains("not a height channel"), "{e}");
    let list = adhesion::surface::formats::list_channels(&path).unwrap();
    assert_eq!(list.lines().count(), 4, "{list}");
    assert!(
        list.contains("Height: 48 x 32 points, 5e-6 x 3.33333e-6 m, heights in m"),
        "{list}"
    );
    // FILE#CHANNEL reads a channel where a scene takes only a path.
    let p = PathBuf::from(format!("{}#Height masked", path.display()));
    let e = adhesion::surface::read_height_map(&p, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("3 of 320 points are missing") && e.contains("x index 5, y index 3"),
        "{e}"
    );
}

fn adhesion(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .args(args)
        .output()
        .expect("binary runs")
}

#[test]
fn analyze_surface_reads_instrument_files() {
    let gwy = maps().join("gwy-1.gwy");
    let o = adhesion(&[
        "--headless",
        "--analyze-surface",
        gwy.to_str().unwrap(),
        "--channel",
        "Height",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rms = r.to_string();
    assert!(rms.contains("rms"), "{rms}");
    let o = adhesion(&[
        "--headless",
        "--analyze-surface",
        gwy.to_str().unwrap(),
        "--list-channels",
    ]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("Height masked"));
    let o = adhesion(&[
        "--headless",
        "--analyze-surface",
        gwy.to_str().unwrap(),
        "--channel",
        "Nope",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.trim().lines().count() == 1 && err.contains("no channel `Nope`"),
        "{err}"
    );
    let o = adhesion(&[
        "--headless",
        "--analyze-surface",
        gwy.to_str().unwrap(),
        "--pixel-size",
        "1e-8",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--pixel-size does not apply"),
        "{err}"
    );
    // A scene's surface parameter takes the new formats without change.
    let sur = maps().join("x3p-f32.x3p");
    let o = adhesion(&["--headless", "--analyze-surface", sur.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn line_scans_and_non_uniform_grids_are_refused() {
    let path = maps().join("xy-3.txt");
    let e = adhesion::surface::read_height_map(&path, Some(1e-6))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line scan (1D profile) of 11 points") && e.contains("xy-3.txt"),
        "{e}"
    );
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("nonuniform.txt");
    std::fs::write(&p, "0 0 1\n1 0 1\n3 0 1\n0 1 1\n1 1 1\n3 1 1\n").unwrap();
    let e = adhesion::surface::read_height_map(&p, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("non-uniform grid in x"), "{e}");
}

/// Every prefix and corrupted header of the binary fixtures gives a one-line error naming the
/// file (or, for a corruption the format cannot see, a reading), never a panic.
#[test]
fn truncated_and_corrupt_files_give_one_line_errors() {
    for file in [
        "sdf-binary.sdf",
        "x3p-f32.x3p",
        "gwy-1.gwy",
        "sur-3.sur",
        "10x10-one_channel_without_name.ibw",
        "di-3.di",
        "sdf-1.sdf",
        "mi-1.mi",
        "al3d-1.al3d",
        "nid-small.nid",
        "plu-small.plu",
        "metropro-small.dat",
        "opd-small.opd",
        "opdx-small.opdx",
        "opdx-3.opdx",
    ] {
        let bytes = std::fs::read(maps().join(file)).unwrap();
        let path = Path::new(file);
        // A text file cut after its data (in its trailer) still reads; the Alicona file's
        // depth image (1 261 + 296 rows of 800 bytes) is followed by its texture image.
        let last = match file {
            "sdf-1.sdf" => 100,
            "al3d-1.al3d" => 1261 + 296 * 800 - 1,
            // The Dektak file's item tree ends 3 bytes before its end (a terminator's type and
            // two bytes).
            "opdx-3.opdx" => bytes.len() - 3,
            _ => bytes.len() - 1,
        };
        let cuts = [bytes.len() / 2, last, 100.min(bytes.len() - 1), 20, 5];
        for cut in cuts {
            let e = parse_bytes(&bytes[..cut], path, None)
                .map(|_| ())
                .unwrap_err_or_else(|| panic!("{file} cut at {cut} read"));
            assert!(e.contains(file) && !e.contains('\n'), "{file} at {cut}: {e}");
        }
    }
    // Corrupt: sizes in headers off.
    let mut sur = std::fs::read(maps().join("sur-3.sur")).unwrap();
    sur[116..120].copy_from_slice(&7u32.to_le_bytes());
    let e = refused(&sur, "c.sur", None);
    assert!(e.contains("point count of 7"), "{e}");
    let mut ibw = std::fs::read(maps().join("10x10-one_channel_without_name.ibw")).unwrap();
    ibw[64 + 12..64 + 16].copy_from_slice(&99i32.to_le_bytes());
    let e = refused(&ibw, "c.ibw", None);
    assert!(e.contains("99 points"), "{e}");
}

trait ErrText {
    fn unwrap_err_or_else(self, f: impl FnOnce()) -> String;
}

impl ErrText for adhesion::error::Result<()> {
    fn unwrap_err_or_else(self, f: impl FnOnce()) -> String {
        match self {
            Ok(()) => {
                f();
                String::new()
            }
            Err(e) => e.to_string(),
        }
    }
}

/// The one-line error naming the file `file` that reading `bytes` gives.
fn refused(bytes: &[u8], file: &str, channel: Option<&str>) -> String {
    let e = parse_bytes(bytes, Path::new(file), channel)
        .unwrap_err()
        .to_string();
    assert!(e.contains(file) && !e.contains('\n'), "{e}");
    e
}

/// [`refused`] for a text header (read as Latin-1) whose lines `keys` (each a key and its
/// number) are given the number 100000.
fn refused_edited(text: &[u8], file: &str, keys: &[&str]) -> String {
    let mut s: String = text.iter().map(|&b| b as char).collect();
    for key in keys {
        let to = format!("{}100000", key.trim_end_matches(|c: char| c.is_ascii_digit()));
        s = s.replace(key, &to);
    }
    let bytes: Vec<u8> = s.chars().map(|c| c as u32 as u8).collect();
    refused(&bytes, file, None)
}

/// Headers claiming a 100 000² map are refused before anything is allocated from them.
#[test]
fn a_header_claiming_a_huge_map_is_refused() {
    // .sur: 100000 x 100000 points.
    let mut sur = std::fs::read(maps().join("sur-3.sur")).unwrap();
    sur[108..112].copy_from_slice(&100_000i32.to_le_bytes());
    sur[112..116].copy_from_slice(&100_000i32.to_le_bytes());
    sur[116..120].copy_from_slice(&(100_000u32.wrapping_mul(100_000)).to_le_bytes());
    let e = refused(&sur, "huge.sur", None);
    assert!(e.contains("100000"), "{e}");
    // .x3p: SizeX = SizeY = 100000 in main.xml.
    let x3p = std::fs::read(maps().join("x3p-f32.x3p")).unwrap();
    let mut z = zip::ZipArchive::new(std::io::Cursor::new(&x3p)).unwrap();
    let mut xml = String::new();
    std::io::Read::read_to_string(&mut z.by_name("main.xml").unwrap(), &mut xml).unwrap();
    let xml = xml
        .replace("<SizeX>40</SizeX>", "<SizeX>100000</SizeX>")
        .replace("<SizeY>30</SizeY>", "<SizeY>100000</SizeY>");
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    out.start_file("main.xml", zip::write::SimpleFileOptions::default())
        .unwrap();
    std::io::Write::write_all(&mut out, xml.as_bytes()).unwrap();
    out.start_file("bindata/data.bin", zip::write::SimpleFileOptions::default())
        .unwrap();
    std::io::Write::write_all(&mut out, &[0u8; 64]).unwrap();
    let bytes = out.finish().unwrap().into_inner();
    let e = refused(&bytes, "huge.x3p", None);
    assert!(e.contains("100000 x 100000"), "{e}");
    // Text headers: Nanoscope (Samps/line, Number of lines), .mi (xPixels, yPixels) and .nid
    // (Points, Lines) claiming 100000 x 100000 points.
    for (file, head, keys, claim) in [
        (
            "di-3.di",
            40960,
            ["\\Samps/line: 256", "\\Number of lines: 256"],
            "100000",
        ),
        (
            "mi-1.mi",
            8192,
            ["xPixels       256", "yPixels       256"],
            "100000 x 100000",
        ),
        (
            "nid-small.nid",
            5083,
            ["Points=24", "Lines=16"],
            "100000 x 100000",
        ),
    ] {
        let bytes = std::fs::read(maps().join(file)).unwrap();
        let e = refused_edited(&bytes[..head], &format!("huge-{file}"), &keys);
        assert!(e.contains(claim), "{e}");
    }
    // .al3d: Cols = Rows = 100000.
    let mut al3d = std::fs::read(maps().join("al3d-1.al3d")).unwrap();
    for key in [b"Cols".as_slice(), b"Rows"] {
        let at = (0..1261).find(|&k| al3d[k..].starts_with(key)).unwrap();
        al3d[at + 20..at + 26].copy_from_slice(b"100000");
    }
    let e = refused(&al3d, "huge.al3d", None);
    assert!(e.contains("100000 x 100000"), "{e}");
    // .plu: 100000 x 100000 points in the calibration and the layer.
    let mut plu = std::fs::read(maps().join("plu-small.plu")).unwrap();
    for at in [388, 392, 500, 504] {
        plu[at..at + 4].copy_from_slice(&100_000u32.to_le_bytes());
    }
    let e = refused(&plu, "huge.plu", None);
    assert!(e.contains("100000 x 100000"), "{e}");
    // MetroPro and .opd count points in u16: 65535 x 65535 is above the limit.
    let mut dat = std::fs::read(maps().join("metropro-small.dat")).unwrap();
    dat[68..72].copy_from_slice(&[0xff; 4]);
    let e = refused(&dat, "huge.dat", None);
    assert!(e.contains("65535 x 65535"), "{e}");
    let mut opd = std::fs::read(maps().join("opd-small.opd")).unwrap();
    let raw = opd_raster(&opd, "Raw");
    opd[raw..raw + 4].copy_from_slice(&[0xff; 4]);
    let e = parse_bytes(&opd, Path::new("huge.opd"), Some("Raw"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("huge.opd") && e.contains("65535 x 65535"), "{e}");
    // .opdx: Dimension1Points = Dimension2Points = 100000.
    let mut opdx = std::fs::read(maps().join("opdx-small.opdx")).unwrap();
    for key in [b"Dimension1Points".as_slice(), b"Dimension2Points"] {
        let at = opdx.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 1;
        opdx[at..at + 4].copy_from_slice(&100_000u32.to_le_bytes());
    }
    let e = refused(&opdx, "huge.opdx", None);
    assert!(e.contains("100000 x 100000"), "{e}");
    // .gsf: XRes = YRes = 100000.
    let gsf = b"Gwyddion Simple Field 1.0\nXRes = 100000\nYRes = 100000\nXReal = 1\nYReal = 1\n\0\0\0";
    let e = refused(gsf, "huge.gsf", None);
    assert!(e.contains("100000"), "{e}");
}

/// Offset of the raster block `name` in a Wyko .opd file (its points in x, y and item size).
fn opd_raster(opd: &[u8], name: &str) -> usize {
    let entry = |k: usize| {
        let e = &opd[2 + 24 * k..2 + 24 * (k + 1)];
        let n = e[..16].iter().position(|&b| b == 0).unwrap_or(16);
        (
            String::from_utf8_lossy(&e[..n]).into_owned(),
            i32::from_le_bytes(e[18..22].try_into().unwrap()) as usize,
        )
    };
    let (_, dir) = entry(0);
    let mut at = 2 + dir;
    for k in 1..dir / 24 {
        let (n, len) = entry(k);
        if n == name {
            return at;
        }
        at += len;
    }
    panic!("no block {name}")
}

/// Why the channel of a file's bytes that reads is not a height map.
fn height_map_error(bytes: &[u8], file: &str, channel: Option<&str>) -> String {
    let path = Path::new(file);
    parse_bytes(bytes, path, channel)
        .unwrap()
        .into_height_map(path, None, false)
        .unwrap_err()
        .to_string()
}

/// Points not measured in the new instrument formats become missing points, refused with
/// their count; a Sensofar profile is refused as a line scan; the channels of a Nanosurf file
/// are listed with their units.
#[test]
fn instrument_markers_of_points_not_measured_are_missing() {
    // MetroPro: a phase of 2147483647 at x index 3, y index 1 (20 points per row).
    let mut dat = std::fs::read(maps().join("metropro-small.dat")).unwrap();
    let at = 834 + 2 * 4 * 3 + 4 * (20 + 3);
    dat[at..at + 4].copy_from_slice(&i32::MAX.to_be_bytes());
    let e = height_map_error(&dat, "bad.dat", None);
    assert!(
        e.contains("1 of 280 points are missing") && e.contains("x index 3, y index 1"),
        "{e}"
    );
    // .opd: an f32 of 1e38 in the raster "Raw" (y fastest, from the top: stored index 0 is x
    // index 0 at the last row, y index 9).
    let mut opd = std::fs::read(maps().join("opd-small.opd")).unwrap();
    let at = opd_raster(&opd, "Raw") + 6;
    opd[at..at + 4].copy_from_slice(&1e38f32.to_le_bytes());
    let e = height_map_error(&opd, "bad.opd", Some("Raw"));
    assert!(
        e.contains("1 of 180 points are missing") && e.contains("x index 0, y index 9"),
        "{e}"
    );
    // Sensofar: measurement type 1, a profile.
    let mut plu = std::fs::read(maps().join("plu-small.plu")).unwrap();
    plu[428..432].copy_from_slice(&1u32.to_le_bytes());
    let e = refused(&plu, "profile.plu", None);
    assert!(e.contains("line scan"), "{e}");
    // Nanosurf: every data set listed, the deflection in newtons.
    let list = adhesion::surface::formats::list_channels(&maps().join("nid-small.nid")).unwrap();
    assert!(
        list.contains("Scan forward (Deflection): 24 x 16 points, 5e-6 x 3.33333e-6 m, heights in N")
            && list.contains("Scan forward (Z-Axis)")
            && list.contains("Scan backward (Z-Axis)"),
        "{list}"
    );
}
