//! Export speed: running and writing chapter 1's scenes in all four formats.

use std::hint::black_box;

use adhesion::headless::export_scene;
use adhesion::job::Job;
use adhesion::render::Format;
use adhesion::scenes;
use criterion::{Criterion, criterion_group, criterion_main};

fn chapter1_export(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let chapter1: Vec<_> = scenes::all()
        .into_iter()
        .filter(|s| s.info().chapter == "1")
        .collect();
    let mut group = c.benchmark_group("export");
    group.sample_size(20);
    for s in &chapter1 {
        let values = s.defaults();
        group.bench_function(format!("{} png+svg+csv+json", s.info().id), |b| {
            b.iter(|| {
                black_box(export_scene(*s, &values, dir.path(), &Format::ALL, &Job::quiet()).expect("export"))
            });
        });
        group.bench_function(format!("{} run only", s.info().id), |b| {
            b.iter(|| black_box(s.run(&values, &Job::quiet()).expect("run")));
        });
    }
    group.bench_function("all chapter 1 scenes, all formats", |b| {
        b.iter(|| {
            for s in &chapter1 {
                black_box(
                    export_scene(*s, &s.defaults(), dir.path(), &Format::ALL, &Job::quiet()).expect("export"),
                );
            }
        });
    });
    group.finish();
}

criterion_group!(benches, chapter1_export);
criterion_main!(benches);
