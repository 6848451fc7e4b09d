//! Seeded mutation fuzzing of the input parsers: force-curve CSV, height-map CSV, .gsf,
//! peeling-profile CSV, presets, the point files of sharded sweeps, the merge (a point file,
//! its checksum forged after the mutation, assembled with the other points of its sweep), and
//! the instrument force-distance readers (JPK archives, also re-zipped from mutated entries so
//! that mutations reach the headers and channels past the zip's checksums; Asylum .ibw;
//! afmformats .h5; AFM Workshop CSV and zip; NT-MDT, Chiaro, afmformats .tab text), and the
//! height-map readers (`map …`: text matrix and xyz, .sdf, .x3p re-zipped from mutated entries,
//! .gwy, .sur, .ibw images, Nanoscope, .mi, .al3d, .nid, .plu, MetroPro .dat, .opd, .opdx,
//! Mountains .mnt whole and its document stream put back into a compound file).
//! Each parser
//! gets valid seeds mutated (bytes flipped, inserted, deleted, duplicated; numbers such as
//! 1e308, -0, nan spliced in) and must return `Ok` or `Err`, never panic. A short run is in CI;
//! `ADHESION_FUZZ_ITERATIONS` sets the count of the `#[ignore]`d long run (default one million
//! per parser), `ADHESION_FUZZ_PARSERS` a comma-separated list of the parsers it runs, and
//! `ADHESION_FUZZ_ONLY` a part of their names (e.g. `afm` for the force-distance readers).

use std::path::Path;

const SEED: u64 = 0x5eed_f022;

/// xorshift64*: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const TOKENS: &[&[u8]] = &[
    b",",
    b"\n",
    b"\r",
    b"\r\n",
    b"-",
    b"e",
    b"9",
    b"0",
    b".",
    b"\0",
    b"\xff",
    b"#",
    b"=",
    b"\"",
    b"[",
    b"]",
    b"1e308",
    b"-1e308",
    b"1e-320",
    b"-0",
    b"nan",
    b"inf",
    b"-inf",
    b"\xef\xbb\xbf",
    b"18446744073709551616",
    b"4294967297",
    b" ",
    b"\t",
    b"XRes = 65536",
    b"XReal = 1e-300",
    b"# adhesion height map: nx=2 ny=2 lx=1 ly=1",
    b"periodic=1",
    b"depth_nm,force_nN",
    b"{",
    b"}",
    b":",
    b"null",
    b"\"NaN\"",
    b"\"-1e300\"",
    b"-1e300",
    b"[]",
    b"\"values\":[]",
    b"\"point\":4",
];

/// The sweep of the point-file and merge fuzzing: fig4.9b in quick form (cheap to assemble),
/// its values, hash and point labels.
struct MergeCase {
    values: adhesion::params::ParamValues,
    hash: String,
    labels: Vec<String>,
}

static MERGE: std::sync::LazyLock<MergeCase> = std::sync::LazyLock::new(|| {
    let scene = adhesion::scenes::find("fig4.9b").unwrap();
    let values = scene.quick(&scene.defaults()).unwrap();
    let labels = scene.sweep().unwrap().points(&values).unwrap();
    MergeCase {
        hash: adhesion::headless::shard::params_hash(&values),
        values,
        labels,
    }
});

/// Mutated point files that passed every check and were assembled into the figure.
static ASSEMBLED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// The point the fuzzed point files stand for.
const POINT: usize = 4;

fn expected(case: &MergeCase) -> adhesion::headless::shard::Expected<'_> {
    adhesion::headless::shard::Expected {
        scene: "fig4.9b",
        point: POINT,
        params_hash: &case.hash,
        len: 2,
        nan_allowed: false,
    }
}

fn mutate(rng: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut b = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(b.len() + 1);
        match rng.below(5) {
            0 if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            1 => {
                let t = TOKENS[rng.below(TOKENS.len())];
                b.splice(at..at, t.iter().copied());
            }
            2 if !b.is_empty() => {
                let end = (at + 1 + rng.below(16)).min(b.len());
                let at = at.min(end);
                b.drain(at..end);
            }
            3 if !b.is_empty() => {
                let end = (at + 1 + rng.below(64)).min(b.len());
                let at = at.min(end);
                let chunk: Vec<u8> = b[at..end].to_vec();
                b.splice(at..at, chunk);
            }
            _ => b.truncate(at),
        }
    }
    b
}

fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let root = crate::common::root();
    let curve = std::fs::read(root.join("tests/fixtures/curves/synthetic_cycle.csv")).unwrap();
    let map = b"# adhesion height map: nx=3 ny=2 lx=3e-6 ly=2e-6 (SI units, rows are y)\n1e-9,2e-9,-1e-9\n0,3e-9,1e-9\n".to_vec();
    let mut gsf =
        b"Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\nXReal = 1e-6\nYReal = 1e-6\nXYUnits = m\n".to_vec();
    let pad = 4 - gsf.len() % 4;
    gsf.extend(std::iter::repeat_n(0u8, pad));
    for z in [1e-9f32, -1e-9, 2e-9, 0.0] {
        gsf.extend(z.to_le_bytes());
    }
    let profile = b"# x, y\n0,0\n0.1,0.01\n0.2,0.04\n0.3,0.09\n".to_vec();
    let preset = adhesion::headless::preset_text(adhesion::scenes::find("fig1.1").unwrap()).into_bytes();
    let case = &*MERGE;
    let point = adhesion::headless::shard::point_text(
        "fig4.9b",
        POINT,
        &case.labels[POINT],
        &case.hash,
        1.25,
        &[0.0123, 4.5e-3],
    )
    .into_bytes();
    let mut out = vec![
        ("force-curve CSV", curve),
        ("height-map CSV", map),
        (".gsf", gsf),
        ("profile CSV", profile),
        ("preset", preset),
        ("point file", point.clone()),
        ("merge", point),
    ];
    out.extend(afm_seeds());
    out.extend(map_seeds());
    out
}

/// The height-map readers' seeds: small fixtures (those of .nid, .plu, MetroPro, .opd and
/// .opdx written by benches/surfacetopography_reference.py), and small files built from the headers of
/// larger ones (a 4 x 4 Digital Surf object, a 4 x 4 Nanoscope image, a 4 x 4 .mi file of four
/// buffers, a 4 x 4 Alicona depth image).
fn map_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let dir = crate::common::root().join("tests/fixtures/maps");
    let read = |f: &str| std::fs::read(dir.join(f)).unwrap();
    let unpacked = |b: Vec<u8>| -> Vec<u8> {
        let mut z = zip::ZipArchive::new(std::io::Cursor::new(b)).unwrap();
        let mut out = Vec::new();
        for i in 0..z.len() {
            let mut f = z.by_index(i).unwrap();
            out.extend_from_slice(ENTRY);
            out.extend_from_slice(f.name().unwrap().as_bytes());
            out.push(b'\n');
            std::io::Read::read_to_end(&mut f, &mut out).unwrap();
        }
        out
    };
    let mut sur = read("sur-3.sur")[..512].to_vec();
    sur[108..112].copy_from_slice(&4i32.to_le_bytes());
    sur[112..116].copy_from_slice(&4i32.to_le_bytes());
    sur[116..120].copy_from_slice(&16u32.to_le_bytes());
    for k in 0..16i32 {
        sur.extend((k * 1000 - 7000).to_le_bytes());
    }
    let mut di = b"\\*File list\r\n\\Version: 0x09200201\r\n\\*Scanner list\r\n\\@Sens. Zsens: V 34.5 nm/V\r\n\\*Ciao image list\r\n\\Data offset: 512\r\n\\Data length: 32\r\n\\Bytes/pixel: 2\r\n\\Samps/line: 4\r\n\\Number of lines: 4\r\n\\Scan Size: 10 10 ~m\r\n\\@2:Image Data: S [Height] \"Height\"\r\n\\@2:Z scale: V [Sens. Zsens] (0.000375 V/LSB) 24.5 V\r\n\\*File list end\r\n\x1a".to_vec();
    di.resize(512, 0);
    for k in 0..16i16 {
        di.extend((k * 100 - 800).to_le_bytes());
    }
    let mi_full = read("mi-1.mi");
    let data = mi_full.windows(6).position(|w| w == b"\ndata ").unwrap();
    let end = data + 1 + mi_full[data + 1..].iter().position(|&b| b == b'\n').unwrap() + 1;
    let mut mi = String::from_utf8_lossy(&mi_full[..end])
        .replace("xPixels       256", "xPixels       4")
        .replace("yPixels       256", "yPixels       4")
        .into_bytes();
    for k in 0..64i32 {
        mi.extend((k * 3_000_000 - 90_000_000).to_le_bytes());
    }
    let mut al3d = read("al3d-1.al3d")[..1261].to_vec();
    for (key, value) in [(b"Cols".as_slice(), b"4".as_slice()), (b"Rows", b"4")] {
        let at = (0..al3d.len() - 20)
            .find(|&k| al3d[k..].starts_with(key) && al3d[k + key.len()] == 0)
            .unwrap();
        al3d[at + 20..at + 50].fill(0);
        al3d[at + 20..at + 20 + value.len()].copy_from_slice(value);
    }
    for k in 0..16 {
        al3d.extend((1e-6f32 * k as f32).to_le_bytes());
    }
    vec![
        ("map text", read("matrix-6.txt")),
        ("map xyz", read("xyz-2.txt")),
        ("map .sdf", read("sdf-1.sdf")),
        ("map .sdf binary", read("sdf-binary.sdf")),
        ("map .x3p entries", unpacked(read("x3p-u16.x3p"))),
        ("map .gwy", read("gwy-1.gwy")),
        ("map .sur", sur),
        ("map .ibw", read("10x10-one_channel_without_name.ibw")),
        ("map .di", di),
        ("map .mi", mi),
        ("map .al3d", al3d),
        ("map .nid", read("nid-small.nid")),
        ("map .plu", read("plu-small.plu")),
        ("map MetroPro .dat", read("metropro-small.dat")),
        ("map .opd", read("opd-small.opd")),
        ("map .opdx", read("opdx-small.opdx")),
        ("map .mnt", read("mnt-small.mnt")),
        (
            "map .mnt stream",
            crate::maps::mnt_stream_of(&read("mnt-masked.mnt")),
        ),
    ]
}

/// Marker between the entries of a JPK archive unpacked into one seed.
const ENTRY: &[u8] = b"\n@@entry@@ ";

/// The force-distance readers' seeds: small fixtures (text ones cut to their first lines).
fn afm_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let dir = crate::common::root().join("tests/fixtures/afm");
    let read = |f: &str| std::fs::read(dir.join(f)).unwrap();
    let head = |b: Vec<u8>, lines: usize| -> Vec<u8> {
        let mut n = 0;
        let end = b.iter().position(|&c| {
            n += usize::from(c == b'\n');
            n == lines
        });
        b[..end.map_or(b.len(), |e| e + 1)].to_vec()
    };
    let unzip = |b: Vec<u8>| -> Vec<(String, Vec<u8>)> {
        let mut z = zip::ZipArchive::new(std::io::Cursor::new(b)).unwrap();
        (0..z.len())
            .map(|i| {
                let mut f = z.by_index(i).unwrap();
                let name = f.name().unwrap().into_owned();
                let mut data = Vec::new();
                std::io::Read::read_to_end(&mut f, &mut data).unwrap();
                (name, data)
            })
            .collect()
    };
    let unpacked = |b: Vec<u8>| -> Vec<u8> {
        let mut out = Vec::new();
        for (name, data) in unzip(b) {
            out.extend_from_slice(ENTRY);
            out.extend_from_slice(name.as_bytes());
            out.push(b'\n');
            out.extend(data);
        }
        out
    };
    let chiaro = unzip(read("fmt-chiaro-txt_AEBP1_Indentation_002.zip"))
        .remove(0)
        .1;
    vec![
        ("afm .jpk-force", read("fmt-jpk-fd_spot3-0192.jpk-force")),
        (
            "afm .jpk-force entries",
            unpacked(read("fmt-jpk-fd_spot3-0192.jpk-force")),
        ),
        (
            "afm .jpk-qi-data entries",
            unpacked(read("fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data")),
        ),
        ("afm .ibw", read("fmt-igor-fd_SiN_FD_plot.ibw")),
        (
            "afm Workshop .csv",
            head(read("fmt-afm-workshop-fd_single_2021-01-15.csv"), 60),
        ),
        (
            "afm Workshop .zip",
            read("fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip"),
        ),
        (
            "afm NT-MDT .txt",
            // Whole: the constant padding that the reader crops spans its first 180 rows.
            read("fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt"),
        ),
        ("afm Chiaro .txt", head(chiaro, 90)),
        ("afm .tab", head(read("fmt-tab-fd_version_0.13.3.tab"), 60)),
        ("afm .h5", read("fmt-hdf5-fd_version_0.13.3.h5")),
    ]
}

/// A stored (uncompressed) zip of the entries of an unpacked seed.
fn rezip(bytes: &[u8]) -> Vec<u8> {
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let stored = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let mut rest = bytes;
    let mut seen = std::collections::HashSet::new();
    while let Some(at) = rest.windows(ENTRY.len()).position(|w| w == ENTRY) {
        rest = &rest[at + ENTRY.len()..];
        let nl = rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len());
        let name = String::from_utf8_lossy(&rest[..nl]).into_owned();
        rest = &rest[(nl + 1).min(rest.len())..];
        let end = rest
            .windows(ENTRY.len())
            .position(|w| w == ENTRY)
            .unwrap_or(rest.len());
        if !seen.insert(name.clone()) {
            continue;
        }
        if name.ends_with('/') {
            let _ = out.add_directory(name, stored);
        } else if out.start_file(name, stored).is_ok() {
            let _ = std::io::Write::write_all(&mut out, &rest[..end]);
        }
    }
    out.finish().map(|c| c.into_inner()).unwrap_or_default()
}

/// Run one parser on `bytes`; true when it panicked.
fn panics(kind: &str, bytes: &[u8], dir: &Path) -> bool {
    let path = dir.join("input");
    if let Some(format) = kind.strip_prefix("afm ") {
        // Zips are built before the parser runs: a panic of the zip writer is not the reader's.
        let bytes = if format.ends_with(" entries") {
            rezip(bytes)
        } else {
            bytes.to_vec()
        };
        let name = match format.split(' ').next().unwrap_or("") {
            "Workshop" | "NT-MDT" | "Chiaro" => format!("input{}", &format[format.rfind('.').unwrap_or(0)..]),
            ext => format!("input{ext}"),
        };
        let opts = adhesion::readers::ReadOptions {
            spring_constant: Some(0.1),
            sensitivity: Some(5e-8),
        };
        return std::panic::catch_unwind(|| {
            let _ = adhesion::readers::parse_force_bytes(&bytes, Path::new(&name), &opts);
        })
        .is_err();
    }
    if kind.starts_with("map ") {
        // Mutated .mnt streams are put back into a compound file before the reader runs, so that
        // mutations reach the document past the container.
        let bytes = if kind.ends_with(" entries") {
            rezip(bytes)
        } else if kind.ends_with(" stream") {
            crate::maps::mnt_file(bytes)
        } else {
            bytes.to_vec()
        };
        return std::panic::catch_unwind(|| {
            let p = Path::new("m");
            let _ = adhesion::surface::formats::list_bytes(&bytes, p);
            if let Ok(m) = adhesion::surface::formats::parse_bytes(&bytes, p, None)
                && let Ok(map) = m.into_height_map(p, Some(1e-8), true)
            {
                let _ = adhesion::surface::command::report(&map, adhesion::surface::Cutoff::None);
            }
        })
        .is_err();
    }
    std::panic::catch_unwind(|| match kind {
        "force-curve CSV" => {
            let _ = adhesion::fit::parse_curve(&String::from_utf8_lossy(bytes), Path::new("c.csv"));
        }
        "height-map CSV" => {
            if let Ok(m) =
                adhesion::surface::io::parse_csv(&String::from_utf8_lossy(bytes), Path::new("m.csv"), None)
            {
                let _ = adhesion::surface::command::report(&m, adhesion::surface::Cutoff::None);
            }
        }
        ".gsf" => {
            if let Ok(m) = adhesion::surface::io::parse_gsf(bytes, Path::new("m.gsf")) {
                let _ = adhesion::surface::command::report(&m, adhesion::surface::Cutoff::None);
            }
        }
        "point file" => {
            use adhesion::headless::shard::{parse_point, reseal};
            let text = String::from_utf8_lossy(bytes);
            let case = &*MERGE;
            let _ = parse_point(&text, &expected(case));
            if let Some(forged) = reseal(&text) {
                let _ = parse_point(&forged, &expected(case));
            }
        }
        "merge" => {
            use adhesion::headless::shard::{parse_point, point_text, reseal};
            let case = &*MERGE;
            let text = String::from_utf8_lossy(bytes);
            // The mutant with its checksum forged, and a well-formed point file of the numbers
            // in the mutant (its last two, or one or three: wrong counts), so that odd values
            // (1e308, -0, subnormals, NaN) reach the checks and the assembly.
            let numbers: Vec<f64> = text
                .split(|c: char| c.is_whitespace() || ",\":[]{}".contains(c))
                .filter_map(|t| t.parse::<f64>().ok())
                .collect();
            let count = [2, 2, 2, 1, 3][bytes.len() % 5].min(numbers.len());
            let seconds = numbers.first().copied().unwrap_or(0.0);
            let rebuilt = point_text(
                "fig4.9b",
                POINT,
                &case.labels[POINT],
                &case.hash,
                seconds,
                &numbers[numbers.len() - count..],
            );
            for forged in reseal(&text).into_iter().chain([rebuilt]) {
                if let Ok((values, _)) = parse_point(&forged, &expected(case)) {
                    let mut points = vec![vec![0.01, 0.002]; case.labels.len()];
                    points[POINT] = values;
                    let sweep = adhesion::scenes::find("fig4.9b").unwrap().sweep().unwrap();
                    let _ = sweep.assemble(&case.values, &points, &adhesion::job::Job::quiet());
                    ASSEMBLED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                }
            }
        }
        "profile CSV" => {
            std::fs::write(&path, bytes).unwrap();
            let _ = adhesion::scenes::fig6::load_profile(&path);
        }
        _ => {
            std::fs::write(&path, bytes).unwrap();
            let mut v = adhesion::scenes::find("fig1.1").unwrap().defaults();
            let _ = v.apply_preset_file(&path);
        }
    })
    .is_err()
}

/// Executions and panics per parser.
fn fuzz(iterations: usize) -> Vec<(&'static str, usize, usize)> {
    let dir = tempfile::tempdir().unwrap();
    let mut out = Vec::new();
    // ADHESION_FUZZ_PARSERS="point file,merge" limits a run to some parsers,
    // ADHESION_FUZZ_ONLY=afm to those whose names contain it.
    let only = std::env::var("ADHESION_FUZZ_PARSERS").ok();
    let part = std::env::var("ADHESION_FUZZ_ONLY").unwrap_or_default();
    for (k, (kind, seed)) in seeds().into_iter().enumerate() {
        if !kind.contains(part.as_str())
            || only
                .as_deref()
                .is_some_and(|o| !o.split(',').any(|p| p.trim() == kind))
        {
            continue;
        }
        let mut rng = Rng(SEED + k as u64);
        let mut corpus = vec![seed];
        let mut crashes = 0;
        for i in 0..iterations {
            let parent = &corpus[rng.below(corpus.len())];
            let input = mutate(&mut rng, parent);
            if panics(kind, &input, dir.path()) {
                crashes += 1;
                eprintln!("{kind}: panic on {:?}", String::from_utf8_lossy(&input));
            }
            // Keep some mutants as parents so that mutations stack up.
            if i % 64 == 0 && corpus.len() < 256 && input.len() < 1 << 16 {
                corpus.push(input);
            }
        }
        out.push((kind, iterations, crashes));
    }
    out
}

#[test]
fn parsers_survive_mutated_input() {
    for (kind, n, crashes) in fuzz(500) {
        assert_eq!(crashes, 0, "{kind}: {crashes} of {n} inputs panicked");
    }
}

#[test]
#[ignore = "long fuzzing run: ADHESION_FUZZ_ITERATIONS per parser (default 1e6)"]
fn parsers_survive_a_million_mutated_inputs() {
    let n = std::env::var("ADHESION_FUZZ_ITERATIONS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1_000_000);
    let results = fuzz(n);
    for (kind, n, crashes) in &results {
        println!("{kind}: {n} executions, {crashes} panics");
    }
    println!(
        "merge: {} mutated point files passed the checks and were assembled",
        ASSEMBLED.load(std::sync::atomic::Ordering::Relaxed)
    );
    assert!(results.iter().all(|r| r.2 == 0));
}

#[test]
fn height_map_seeds_read_unmutated() {
    for (kind, seed) in map_seeds() {
        let bytes = if kind.ends_with(" entries") {
            rezip(&seed)
        } else if kind.ends_with(" stream") {
            crate::maps::mnt_file(&seed)
        } else {
            seed
        };
        let m = adhesion::surface::formats::parse_bytes(&bytes, Path::new("m"), None)
            .unwrap_or_else(|e| panic!("{kind}: {e}"));
        assert!(m.info.nx >= 4 && m.info.ny >= 3, "{kind}");
    }
}

#[test]
fn force_distance_seeds_read_unmutated() {
    let opts = adhesion::readers::ReadOptions {
        spring_constant: Some(0.1),
        sensitivity: Some(5e-8),
    };
    for (kind, seed) in afm_seeds() {
        let format = kind.trim_start_matches("afm ");
        let bytes = if format.ends_with(" entries") {
            rezip(&seed)
        } else {
            seed
        };
        let name = match format.split(' ').next().unwrap() {
            "Workshop" | "NT-MDT" | "Chiaro" => format!("input{}", &format[format.rfind('.').unwrap()..]),
            ext => format!("input{ext}"),
        };
        let file = adhesion::readers::parse_force_bytes(&bytes, Path::new(&name), &opts)
            .unwrap_or_else(|e| panic!("{kind}: {e}"));
        assert!(!file.curves.is_empty(), "{kind}");
    }
}
