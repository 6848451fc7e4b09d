//! Rough surfaces: generation (FFT filtering of white noise), isotropic PSD with the spectral
//! moments (one transform), peak statistics and the (3.16) fit, on 256² and 1024² grids with the
//! Si mold's spectrum (3.16), (3.17) on a 2 µm scan; the whole pipeline also on 4096² (time per
//! point against 1024²). `benches/surface_numpy.py` runs the same pipeline in numpy.
//! Reading a 512² height map from the bytes of a file (`read 512x512 FORMAT`): Gwyddion simple
//! field, Digital Surf, Nanosurf, Sensofar, Zygo MetroPro and Bruker Wyko, the files built here
//! from the headers of the small fixtures in tests/fixtures/maps; and a 4096² map as `.gsf`,
//! `.sur` and `.gwy` (`read 4096x4096 .FORMAT`).

use std::hint::black_box;

use adhesion::surface::formats::parse_bytes;
use adhesion::surface::{Cutoff, Spectrum, fit_abc, generate, peak_statistics, radial_psd_and_moments};
use criterion::{Criterion, criterion_group, criterion_main};

fn mold() -> Spectrum {
    adhesion::surface::spectrum::PSD_3_17
}

fn surface(c: &mut Criterion) {
    let s = mold();
    let mut group = c.benchmark_group("surface");
    group.sample_size(10);
    for n in [256usize, 1024] {
        let map = generate(&s, n, n, 2e-6, 2e-6, 1).expect("generate");
        group.bench_function(format!("generate {n}x{n}"), |b| {
            b.iter(|| black_box(generate(&s, n, n, 2e-6, 2e-6, 1).expect("generate")));
        });
        group.bench_function(format!("radial PSD + moments {n}x{n}"), |b| {
            b.iter(|| black_box(radial_psd_and_moments(&map)));
        });
        group.bench_function(format!("generate + radial PSD + moments {n}x{n}"), |b| {
            b.iter(|| {
                let m = generate(&s, n, n, 2e-6, 2e-6, 1).expect("generate");
                black_box(radial_psd_and_moments(&m))
            });
        });
        group.bench_function(format!("peak statistics {n}x{n}"), |b| {
            b.iter(|| black_box(peak_statistics(&map)));
        });
        let (psd, _) = radial_psd_and_moments(&map);
        group.bench_function(format!("fit (3.16) to the radial PSD of {n}x{n}"), |b| {
            b.iter(|| black_box(fit_abc(&psd, Cutoff::Fixed(1.0e8)).expect("fit")));
        });
    }
    // The pipeline at 4096² (16.8 M points): the time per point against 1024².
    let n = 4096;
    group.bench_function(format!("generate + radial PSD + moments {n}x{n}"), |b| {
        b.iter(|| {
            let m = generate(&s, n, n, 2e-6, 2e-6, 1).expect("generate");
            black_box(radial_psd_and_moments(&m))
        });
    });
    group.finish();
}

/// The points of the maps read.
const N: usize = 512;

mod maps;
use maps::{fixture, stored};

/// 512² maps in six formats, as file bytes.
fn map_files() -> Vec<(&'static str, Vec<u8>)> {
    let n = N * N;
    let (gsf, sur) = (maps::gsf(N), maps::sur(N));
    let nid_text = String::from_utf8_lossy(&fixture("nid-small.nid")).into_owned();
    let header = &nid_text[..nid_text.find("#!").expect("data marker")];
    let mut nid = header
        .replace("Points=24", &format!("Points={N}"))
        .replace("Lines=16", &format!("Lines={N}"))
        .replace("SaveBits=16", "SaveBits=32")
        .replace("SaveSign=Unsigned", "SaveSign=Signed")
        .into_bytes();
    nid.extend_from_slice(b"#!");
    nid.extend((0..3 * n).flat_map(|k| stored(k).to_le_bytes()));
    let mut plu = fixture("plu-small.plu")[..500].to_vec();
    plu[489] = 1;
    for at in [388, 392, 500, 504] {
        plu.resize(plu.len().max(at + 4), 0);
        plu[at..at + 4].copy_from_slice(&(N as u32).to_le_bytes());
    }
    plu.extend((0..n).flat_map(|k| (stored(k) as f32 * 1e-3).to_le_bytes()));
    plu.extend([0u8; 8]);
    let mut dat = fixture("metropro-small.dat")[..834].to_vec();
    dat[52..58].fill(0);
    dat[68..70].copy_from_slice(&(N as u16).to_be_bytes());
    dat[70..72].copy_from_slice(&(N as u16).to_be_bytes());
    dat.extend((0..n).flat_map(|k| stored(k).to_be_bytes()));
    let mut opd = vec![0u8, 0];
    let entry = |name: &str, kind: i16, length: usize| {
        let mut e = [0u8; 24];
        e[..name.len()].copy_from_slice(name.as_bytes());
        e[16..18].copy_from_slice(&kind.to_le_bytes());
        e[18..22].copy_from_slice(&(length as i32).to_le_bytes());
        e
    };
    opd.extend(entry("Directory", 1, 24 * 4));
    opd.extend(entry("Wavelength", 7, 4));
    opd.extend(entry("Pixel_size", 7, 4));
    opd.extend(entry("Raw", 3, 6 + 4 * n));
    opd.extend(632.8f32.to_le_bytes());
    opd.extend(2e-5f32.to_le_bytes());
    for v in [N as u16, N as u16, 4] {
        opd.extend(v.to_le_bytes());
    }
    opd.extend((0..n).flat_map(|k| (stored(k) as f32 * 1e-3).to_le_bytes()));
    vec![
        ("Gwyddion simple field", gsf),
        ("Digital Surf", sur),
        ("Nanosurf", nid),
        ("Sensofar", plu),
        ("MetroPro", dat),
        ("Wyko", opd),
    ]
}

fn read_maps(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface");
    group.sample_size(20);
    for (format, bytes) in map_files() {
        let path = std::path::Path::new("map");
        let m = parse_bytes(&bytes, path, None).expect(format);
        assert_eq!((m.info.nx, m.info.ny), (N, N), "{format}");
        group.bench_function(format!("read {N}x{N} {format}"), |b| {
            b.iter(|| black_box(parse_bytes(black_box(&bytes), path, None).expect("read")));
        });
    }
    group.finish();
}

/// Reading a 4096² map (16.8 M points) as `.gsf` (f32), `.sur` (int32) and `.gwy` (f64): the
/// native formats against the simple field. Peak memory of the same readings:
/// `examples/read_map.rs`.
fn read_big_maps(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface");
    group.sample_size(10);
    let n = 4096;
    for (format, bytes) in [
        ("gsf", maps::gsf(n)),
        ("sur", maps::sur(n)),
        ("gwy", maps::gwy(n)),
    ] {
        let path = std::path::Path::new("map");
        let m = parse_bytes(&bytes, path, None).expect(format);
        assert_eq!((m.info.nx, m.info.ny), (n, n), "{format}");
        drop(m);
        group.bench_function(format!("read {n}x{n} .{format}"), |b| {
            b.iter(|| black_box(parse_bytes(black_box(&bytes), path, None).expect("read")));
        });
    }
    group.finish();
}

criterion_group!(benches, surface, read_maps, read_big_maps);
criterion_main!(benches);
