//! Chapter 6 speed: running and exporting the peeling scenes (figs. 6.2-6.5) at their default
//! resolution, and the cost of the model pieces (equilibrium curve + load path, a sampled
//! profile's construction, one map point).

use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

use adhesion::headless::export_scene;
use adhesion::job::Job;
use adhesion::models::peeling::{Profile, SampledProfile, WavyPeeling};
use adhesion::render::Format;
use adhesion::scenes;
use criterion::{Criterion, criterion_group, criterion_main};

fn chapter6(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let chapter: Vec<_> = scenes::all()
        .into_iter()
        .filter(|s| s.info().chapter == "6")
        .collect();
    let mut group = c.benchmark_group("ch6");
    group.sample_size(20);
    for s in &chapter {
        let values = s.defaults();
        group.bench_function(format!("{} run only", s.info().id), |b| {
            b.iter(|| black_box(s.run(&values, &Job::quiet()).expect("run")));
        });
    }
    group.bench_function("all chapter 6 scenes, png+svg+csv+json", |b| {
        b.iter(|| {
            for s in &chapter {
                black_box(
                    export_scene(*s, &s.defaults(), dir.path(), &Format::ALL, &Job::quiet()).expect("export"),
                );
            }
        });
    });
    let sine: Vec<(f64, f64)> = (0..=200)
        .map(|i| {
            let x = f64::from(i) / 200.0;
            (x, -(2.0 * std::f64::consts::PI * x).cos())
        })
        .collect();
    group.bench_function("sampled profile, 200 samples", |b| {
        b.iter(|| black_box(SampledProfile::new(&sine).expect("profile")));
    });
    let profile = Profile::Sinusoid;
    let peel = WavyPeeling::new(&profile, 0.05, FRAC_PI_2, 0.005).expect("peeling");
    group.bench_function("equilibrium curve + load path, 3 periods x 200", |b| {
        b.iter(|| {
            let curve = peel.equilibrium_curve(0.0, 3.0, 200);
            black_box(peel.load_path(&curve).expect("path"))
        });
    });
    group.finish();
}

criterion_group!(benches, chapter6);
criterion_main!(benches);
