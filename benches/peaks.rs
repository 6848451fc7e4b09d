//! Peak statistics (section B.4) of one 512 x 512 map at different physical lengths: the cost
//! of the nearest-neighbour search depends on the grid and the peaks only.

use std::hint::black_box;

use adhesion::surface::{HeightMap, generate, peak_statistics};
use criterion::{Criterion, criterion_group, criterion_main};

fn peaks_at_any_length(c: &mut Criterion) {
    let n = 512;
    let base = generate(&adhesion::surface::spectrum::PSD_3_17, n, n, 2e-6, 2e-6, 1).expect("generate");
    let mut group = c.benchmark_group("peak statistics 512x512");
    group.sample_size(10);
    for (name, lx, ly) in [
        ("2 um x 2 um", 2e-6, 2e-6),
        ("1e150 m x 1e150 m", 1e150, 1e150),
        ("aspect 1e4 (1e-6 m x 1e-2 m)", 1e-6, 1e-2),
        ("aspect 1e18 (1e-9 m x 1e9 m)", 1e-9, 1e9),
    ] {
        let map = HeightMap {
            lx,
            ly,
            periodic: false,
            ..base.clone()
        };
        group.bench_function(name, |b| b.iter(|| black_box(peak_statistics(&map))));
    }
    group.finish();
}

criterion_group!(benches, peaks_at_any_length);
criterion_main!(benches);
