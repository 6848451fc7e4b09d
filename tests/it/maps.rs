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
        let (size_factor, z_factor) = mnt_corrections(file, &m, e);
        let st_size: Vec<f64> = st_size.iter().zip(size_factor).map(|(s, c)| s * c).collect();
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
            match s[2].as_f64().map(|h| h * z_factor) {
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
            if let Some(st_rms) = e["rms_valid"].as_f64().map(|r| r * z_factor) {
                let valid: Vec<f64> = z.iter().copied().filter(|v| v.is_finite()).collect();
                let n = valid.len() as f64;
                let mean = valid.iter().sum::<f64>() / n;
                let rms = (valid.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
                assert!(rel(rms, st_rms) < tol, "{file} {channel}: rms {rms} vs {st_rms}");
                table.push(format!(
                    "| {file} | {channel} | {} x {} | {:.6e} x {:.6e} | {rms:.9e} (of {} valid) | {st_rms:.9e} | {:.1e} |",
                    m.info.nx,
                    m.info.ny,
                    ours[0] * f,
                    ours[1] * f,
                    valid.len(),
                    rel(rms, st_rms)
                ));
            }
            continue;
        }
        if m.info.ny == 1 {
            refusal("a line scan (1D profile)");
        }
        let n = z.len() as f64;
        let sum: f64 = z.iter().sum();
        let mean = sum / n;
        let rms = (z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
        let (st_sum, st_rms) = (
            e["sum"].as_f64().unwrap() * z_factor,
            e["rms"].as_f64().unwrap() * z_factor,
        );
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

/// Z steps [nm] of the `.mnt` documents compared: the generated fixtures' (their specs below)
/// and SurfaceTopography's examples' (their Z axes: 1e-4 nm and 0.2327 nm per count).
const MNT_Z_STEPS_NM: &[(&str, f64)] = &[
    ("mnt-small.mnt", 0.232732),
    ("mnt-masked.mnt", 1e-4),
    ("mnt-1.mnt", 1e-4),
    ("mnt-2.mnt", 0.23273157119750973),
];

/// Factors taking SurfaceTopography 1.25's reading of a Mountains `.mnt` document to the
/// document's own numbers, ones for other files. SurfaceTopography gives the extent of an
/// extracted profile, (points - 1) x step, as the physical size (points x step here), and scales
/// the stored integers by the fixed 10 nm of the document's pixel-scale entry (recorded as
/// `mnt_height_scale_m`) instead of the Z axis's step, so its heights are those here times a
/// constant: the check is that every height and the RMS are that same multiple, to 1e-6.
fn mnt_corrections(file: &str, m: &Measured, e: &serde_json::Value) -> ([f64; 2], f64) {
    if !file.ends_with(".mnt") {
        return ([1.0; 2], 1.0);
    }
    let step = MNT_Z_STEPS_NM
        .iter()
        .find(|(f, _)| *f == file)
        .unwrap_or_else(|| panic!("{file}: no Z step listed"))
        .1;
    let st_scale = e["mnt_height_scale_m"].as_f64().expect("mnt_height_scale_m");
    let (nx, ny) = (m.info.nx as f64, m.info.ny as f64);
    ([nx / (nx - 1.0), ny / (ny - 1.0)], step * 1e-9 / st_scale)
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

/// A Mountains `.mnt` document in the layout of SurfaceTopography's examples
/// (`adhesion::surface::formats`' `mnt` module): one surface of `nx` × `ny` int32 heights
/// `counts` (x fastest) with the steps in nanometres, stored in `blocks` zlib blocks written in
/// a shuffled order, the storage code `code` (12: zeros are missing points), SurfaceTopography's
/// fixed 10 nm pixel scale, and a third object holding the extent in millimetres where
/// SurfaceTopography reads it.
pub(crate) struct MntSpec<'a> {
    pub nx: u32,
    pub ny: u32,
    pub counts: &'a [i32],
    pub steps_nm: [f64; 3],
    pub blocks: usize,
    pub code: u8,
    /// Height data written instead of the blocks of `counts` (a corrupt or hostile file).
    pub blob: Option<Vec<u8>>,
}

fn tlv(tag: u16, data: &[u8]) -> Vec<u8> {
    let mut out = tag.to_le_bytes().to_vec();
    out.extend((data.len() as u64).to_le_bytes());
    out.extend_from_slice(data);
    out
}

fn mnt_text(s: &str) -> Vec<u8> {
    let mut out = vec![4u8];
    for u in s.encode_utf16() {
        out.extend(u.to_le_bytes());
    }
    out
}

fn mnt_axis(number: u32, name: &str, step_nm: f64) -> Vec<u8> {
    let id = [tlv(1, &number.to_le_bytes()), tlv(2, &mnt_text(name))].concat();
    let desc = [
        tlv(0xffff, &id),
        tlv(1, &step_nm.to_le_bytes()),
        tlv(2, &mnt_text("nm")),
        tlv(3, &mnt_text("µm")),
        tlv(4, &1000f64.to_le_bytes()),
        tlv(5, &0f64.to_le_bytes()),
        tlv(6, &1u32.to_le_bytes()),
    ]
    .concat();
    tlv(0xffff, &desc)
}

/// A height block: first point, points, compressed bytes and the zlib stream of `raw`.
fn mnt_block(first: u64, points: u32, raw: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    z.write_all(raw).unwrap();
    let packed = z.finish().unwrap();
    [
        first.to_le_bytes().to_vec(),
        points.to_le_bytes().to_vec(),
        (packed.len() as u32).to_le_bytes().to_vec(),
        packed,
    ]
    .concat()
}

/// The `ScopedContents` stream of the document `spec`.
pub(crate) fn mnt_stream(spec: &MntSpec) -> Vec<u8> {
    let (nx, ny) = (spec.nx, spec.ny);
    let n = spec.counts.len();
    // Blocks of equal size (SurfaceTopography groups them by their inflated size), in the order
    // 1, 3, 5, …, 0, 2, 4, …
    let per = n.div_ceil(spec.blocks.max(1));
    let starts: Vec<usize> = (0..n).step_by(per.max(1)).collect();
    let order: Vec<usize> = (0..starts.len())
        .filter(|k| k % 2 == 1)
        .chain((0..starts.len()).filter(|k| k % 2 == 0))
        .collect();
    let mut blob = ((n * 4) as u64).to_le_bytes().to_vec();
    for k in order {
        let (a, b) = (starts[k], (starts[k] + per).min(n));
        let raw: Vec<u8> = spec.counts[a..b].iter().flat_map(|c| c.to_le_bytes()).collect();
        blob.extend(mnt_block(a as u64, (b - a) as u32, &raw));
    }
    if let Some(b) = &spec.blob {
        blob.clone_from(b);
    }
    let (min, max) = (
        spec.counts.iter().copied().min().unwrap_or(0),
        spec.counts.iter().copied().max().unwrap_or(0),
    );
    // X and Y: {0xffff: descriptor, 1: points, 2: first index, 3: last index}.
    let lateral = |number: u32, name: &str, points: u32| {
        let axis = [
            mnt_axis(number, name, spec.steps_nm[number as usize - 1]),
            tlv(1, &points.to_le_bytes()),
            tlv(2, &0u32.to_le_bytes()),
            tlv(3, &(points - 1).to_le_bytes()),
        ];
        tlv(number as u16, &tlv(0xffff, &axis.concat()))
    };
    let (x, y) = (lateral(1, "X", nx), lateral(2, "Y", ny));
    let heights = tlv(
        1,
        &[
            tlv(1, &tlv(1, &9049u32.to_le_bytes())),
            tlv(2, &[tlv(1, &(n as u32).to_le_bytes()), tlv(2, &blob)].concat()),
        ]
        .concat(),
    );
    let z = tlv(
        2,
        &[
            mnt_axis(3, "Z", spec.steps_nm[2]),
            tlv(1, &min.to_le_bytes()),
            tlv(2, &max.to_le_bytes()),
        ]
        .concat(),
    );
    let kind = |k: u32| tlv(1, &tlv(1, &k.to_le_bytes()));
    let surface = [
        kind(9012),
        tlv(
            2,
            &[
                tlv(0xffff, &tlv(4, &mnt_text("1 : generated"))),
                tlv(1, &tlv(0xffff, &[x, y, heights, z].concat())),
            ]
            .concat(),
        ),
    ]
    .concat();
    // SurfaceTopography reads the grid and the extent (points - 1) x step [mm] of the third
    // object, six levels deep.
    let level6 = [
        tlv(7, &nx.to_le_bytes()),
        tlv(8, &ny.to_le_bytes()),
        tlv(9, &(f64::from(nx - 1) * spec.steps_nm[0] * 1e-6).to_le_bytes()),
        tlv(10, &(f64::from(ny - 1) * spec.steps_nm[1] * 1e-6).to_le_bytes()),
    ]
    .concat();
    let profile = [kind(9013), tlv(2, &tlv(1, &tlv(2, &tlv(2, &tlv(2, &level6)))))].concat();
    let mut objects = Vec::new();
    for object in [surface, kind(9010), profile] {
        let entry = tlv(1, &object);
        objects.extend((entry.len() as u64).to_le_bytes());
        objects.extend(entry);
    }
    let store = [tlv(1, &[spec.code]), tlv(2, &tlv(1, &objects))].concat();
    let scales: Vec<u8> = (1..=4).flat_map(|t| tlv(t, &10f64.to_le_bytes())).collect();
    let main = [tlv(6, &scales), tlv(0x2bd, &store)].concat();
    let top = [
        tlv(3, &[1]),
        tlv(2, &5u32.to_le_bytes()),
        tlv(4, &0x0001_0000u64.to_le_bytes()),
        tlv(5, &(spec.blocks as u64).to_le_bytes()),
        tlv(1, &main),
    ]
    .concat();
    [(top.len() as u64).to_le_bytes().to_vec(), top].concat()
}

/// An OLE compound file holding `scoped` as its `ScopedContents` stream (and an empty
/// `XmlHeader`, as Mountains writes it).
pub(crate) fn mnt_file(scoped: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut cf = cfb::CompoundFile::create(std::io::Cursor::new(Vec::new())).unwrap();
    cf.create_stream("ScopedContents")
        .unwrap()
        .write_all(scoped)
        .unwrap();
    cf.create_stream("XmlHeader").unwrap().write_all(b"").unwrap();
    cf.flush().unwrap();
    cf.into_inner().into_inner()
}

/// Heights of the generated `.mnt` fixtures: a tilted sinusoidal bump field of counts, zeros
/// in the lower left corner when `hole` (missing points under storage code 12) and one zero
/// inside otherwise (a valid height under code 39).
fn mnt_counts(nx: u32, ny: u32, hole: bool) -> Vec<i32> {
    let mut z = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (x, y) = (f64::from(i), f64::from(j));
            let v = 3000.0 * (x / 5.0).sin() * (y / 7.0).cos() + 40.0 * x - 25.0 * y + 700.0;
            let mut c = v.round() as i32;
            if c == 0 {
                c = 1;
            }
            if hole && i + j < 6 {
                c = 0;
            }
            z.push(c);
        }
    }
    if !hole {
        z[(nx + 3) as usize] = 0;
    }
    z
}

/// The generated `.mnt` fixtures: (file, document).
fn mnt_fixtures() -> Vec<(&'static str, Vec<u8>)> {
    let (nx, ny) = (48u32, 40u32);
    let plain = mnt_counts(nx, ny, false);
    let holed = mnt_counts(nx, ny, true);
    vec![
        (
            "mnt-small.mnt",
            mnt_file(&mnt_stream(&MntSpec {
                nx,
                ny,
                counts: &plain,
                steps_nm: [74.8801903682761, 81.25, 0.232732],
                blocks: 5,
                code: 39,
                blob: None,
            })),
        ),
        (
            "mnt-masked.mnt",
            mnt_file(&mnt_stream(&MntSpec {
                nx,
                ny,
                counts: &holed,
                steps_nm: [1853.393117831074, 1854.5542570951588, 1e-4],
                blocks: 4,
                code: 12,
                blob: None,
            })),
        ),
    ]
}

/// Writes the generated `.mnt` fixtures (then run benches/surfacetopography_reference.py).
#[test]
#[ignore = "writes tests/fixtures/maps/mnt-*.mnt"]
fn write_mnt_fixtures() {
    for (file, bytes) in mnt_fixtures() {
        std::fs::write(maps().join(file), bytes).unwrap();
    }
}

/// The `ScopedContents` stream of the `.mnt` document `bytes`.
pub(crate) fn mnt_stream_of(bytes: &[u8]) -> Vec<u8> {
    let mut cf = cfb::CompoundFile::open(std::io::Cursor::new(bytes)).unwrap();
    let mut out = Vec::new();
    std::io::Read::read_to_end(&mut cf.open_stream("ScopedContents").unwrap(), &mut out).unwrap();
    out
}

/// Mountains `.mnt`: cut files and document streams, sizes off, a grid of 100 000² points, and
/// height blocks that inflate beyond their points, lie outside the grid or leave points
/// uncovered are refused with one line naming the file, before anything is allocated from the
/// claims.
#[test]
fn mnt_documents_truncated_corrupt_huge_or_inflating_are_refused() {
    let file = std::fs::read(maps().join("mnt-small.mnt")).unwrap();
    // (The compound file's last sector is padding: a file cut inside it still reads.)
    for cut in [file.len() / 2, file.len() * 3 / 4, 600, 100, 5] {
        let e = parse_bytes(&file[..cut], Path::new("cut.mnt"), None)
            .map(|_| ())
            .unwrap_err_or_else(|| panic!("cut at {cut} read"));
        assert!(e.contains("cut.mnt") && !e.contains('\n'), "{cut}: {e}");
    }
    let sc = mnt_stream_of(&file);
    for cut in [sc.len() / 2, sc.len() - 1, 40, 8, 3] {
        // As cut, and with the stream's own length mended (the entries then overrun it).
        let mut mended = sc[..cut].to_vec();
        if cut >= 8 {
            mended[..8].copy_from_slice(&(cut as u64 - 8).to_le_bytes());
        }
        for s in [&sc[..cut], &mended[..]] {
            let e = refused(&mnt_file(s), "cut.mnt", None);
            assert!(e.contains(".mnt"), "{cut}: {e}");
        }
    }
    let e = refused(&mnt_file(b"not a document"), "empty.mnt", None);
    assert!(e.contains("ScopedContents") || e.contains("corrupt"), "{e}");
    let spec = |nx: u32, ny: u32, counts: &[i32], blob: Option<Vec<u8>>| -> Vec<u8> {
        mnt_file(&mnt_stream(&MntSpec {
            nx,
            ny,
            counts,
            steps_nm: [10.0, 10.0, 1.0],
            blocks: 1,
            code: 39,
            blob,
        }))
    };
    let counts: Vec<i32> = (0..16).collect();
    // A grid of 100 000 x 100 000 points (and 16 heights).
    let e = refused(&spec(100_000, 100_000, &counts, None), "huge.mnt", None);
    assert!(e.contains("100000 x 100000") && e.contains("limit"), "{e}");
    let e = refused(&spec(4, 3, &counts, None), "count.mnt", None);
    assert!(e.contains("4 x 3 points on the axes but 16 heights"), "{e}");
    // Height data: byte count, then (first point, points, compressed bytes, zlib stream).
    let block = mnt_block;
    let head = 64u64.to_le_bytes().to_vec();
    // A decompression bomb: 16 points (64 bytes) whose stream inflates to 16 MiB.
    let bomb = [head.clone(), block(0, 16, &vec![0u8; 16 << 20])].concat();
    assert!(bomb.len() < 64 << 10);
    let e = refused(&spec(4, 4, &counts, Some(bomb)), "bomb.mnt", None);
    assert!(e.contains("inflates beyond its 64 bytes"), "{e}");
    let short = [head.clone(), block(0, 16, &[0u8; 60])].concat();
    let e = refused(&spec(4, 4, &counts, Some(short)), "short.mnt", None);
    assert!(
        e.contains("60 of 64 bytes") || e.contains("inflates to 60"),
        "{e}"
    );
    let outside = [head.clone(), block(8, 16, &[0u8; 64])].concat();
    let e = refused(&spec(4, 4, &counts, Some(outside)), "outside.mnt", None);
    assert!(e.contains("lies outside the 16 points"), "{e}");
    let gap = [head.clone(), block(0, 8, &[0u8; 32]), block(9, 7, &[0u8; 28])].concat();
    let e = refused(&spec(4, 4, &counts, Some(gap)), "gap.mnt", None);
    assert!(e.contains("uncovered"), "{e}");
    let wrong = [32u64.to_le_bytes().to_vec(), block(0, 16, &[0u8; 64])].concat();
    let e = refused(&spec(4, 4, &counts, Some(wrong)), "bytes.mnt", None);
    assert!(e.contains("declares 32 bytes"), "{e}");
}

/// The generated `.mnt` fixtures are the documents [`mnt_fixtures`] writes, and read back as
/// written: the stored integers times the Z step, x fastest, zeros missing under code 12 only.
#[test]
fn mnt_fixtures_read_as_written() {
    for (file, bytes) in mnt_fixtures() {
        let m = read_measured(&maps().join(file), None).unwrap();
        let again = parse_bytes(&bytes, Path::new(file), None).unwrap();
        assert_eq!(m.z.len(), again.z.len(), "{file}");
        assert!(
            m.z.iter()
                .zip(&again.z)
                .all(|(a, b)| a == b || (a.is_nan() && b.is_nan())),
            "{file}: the committed fixture differs from the generator's document"
        );
        let (nx, ny) = (m.info.nx, m.info.ny);
        assert_eq!((nx, ny), (48, 40), "{file}");
        let hole = file.contains("masked");
        let counts = mnt_counts(48, 40, hole);
        let step = MNT_Z_STEPS_NM.iter().find(|(f, _)| *f == file).unwrap().1;
        assert_eq!(m.info.z_unit.name, "nm");
        for (k, (&c, &z)) in counts.iter().zip(&m.z).enumerate() {
            if hole && c == 0 {
                assert!(z.is_nan(), "{file}: point {k} should be missing");
            } else {
                assert!(
                    rel(z, f64::from(c) * step) < 1e-15,
                    "{file}: point {k}: {z} vs {c}"
                );
            }
        }
        let missing = m.z.iter().filter(|z| z.is_nan()).count();
        assert_eq!(missing, if hole { 21 } else { 0 }, "{file}");
    }
}
