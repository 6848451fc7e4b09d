//! Chapter 2 speed: the fig2.5 sweep (100 α values, exact pull-in, pull-off and hysteresis) on
//! one core and in parallel, the followed cycle of one α, and a fit of a 2000-point cycle.

use std::hint::black_box;
use std::path::Path;

use adhesion::fit::{fit_curve, simulate_cycle};
use adhesion::job::Job;
use adhesion::models::machine_stiffness::{Accuracy, Experiment, MachineStiffness, TipGeometry, TipShape};
use adhesion::numerics::curve::logspace;
use adhesion::scenes::fig2::sweep;
use criterion::{Criterion, criterion_group, criterion_main};

fn chapter2(c: &mut Criterion) {
    let alphas = logspace(1e-2, 1e3, 100);
    let mut group = c.benchmark_group("ch2");
    group.sample_size(20);
    for tip in [TipShape::Sphere, TipShape::Cone] {
        group.bench_function(format!("{tip:?} sweep, 100 alpha, one core"), |b| {
            b.iter(|| {
                let v: Vec<_> = alphas
                    .iter()
                    .map(|&a| {
                        MachineStiffness::new(tip, a)
                            .unwrap()
                            .sweep_point(Accuracy::default())
                            .unwrap()
                    })
                    .collect();
                black_box(v)
            });
        });
        group.bench_function(format!("{tip:?} sweep, 100 alpha, rayon"), |b| {
            b.iter(|| black_box(sweep(tip, &alphas, Accuracy::default(), &Job::quiet()).unwrap()));
        });
    }
    let m = MachineStiffness::new(TipShape::Sphere, 1.0).unwrap();
    let d_o = m.pull_off(1e-14).unwrap().before.delta;
    group.bench_function("sphere cycle, 2000 samples per branch", |b| {
        b.iter(|| black_box(m.cycle(1.5 * d_o, 2.0, 2000, 1e-14).unwrap()));
    });
    // A 2000-row cycle (approach, contact, retract) with 1 % deterministic force noise.
    let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, 2.0e6, 0.04, 0.5).unwrap();
    let d_o = x.pull_off().unwrap().before.delta;
    let mut curve = simulate_cycle(&x, 1.5 * d_o, 3.0 * x.scales().h, 870).unwrap();
    let p_max = curve.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    for (k, p) in curve.force.iter_mut().enumerate() {
        *p += 0.01 * p_max * (((k * 7919) % 1000) as f64 / 500.0 - 1.0) * 1.732;
    }
    let n = curve.force.len();
    group.bench_function(format!("fit of a {n}-point cycle"), |b| {
        b.iter(|| black_box(fit_curve(&curve, Path::new("bench.csv"), 1e-6, Some(0.5), None).unwrap()));
    });
    group.finish();
}

criterion_group!(benches, chapter2);
criterion_main!(benches);
