//! Rough surfaces: generation (FFT filtering of white noise), isotropic PSD with the spectral
//! moments (one transform), peak statistics and the (3.16) fit, on 256² and 1024² grids with the
//! Si mold's spectrum (3.16), (3.17) on a 2 µm scan; the whole pipeline also on 4096² (time per
//! point against 1024²). `benches/surface_numpy.py` runs the same pipeline in numpy.

use std::hint::black_box;

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

criterion_group!(benches, surface);
criterion_main!(benches);
