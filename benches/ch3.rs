//! Chapter 3 speed: the Maugis-Dugdale curve and cycle, the loss per asperity (3.4) exact
//! (quadrature, loop area) against the table and the empirical function (3.6), and the contour
//! of fig3.8c (loss per nominal area over (Z₀, σ_rms)) with each loss.

use std::hint::black_box;

use adhesion::job::Job;
use adhesion::models::ddh::LossMethod;
use adhesion::models::maugis_dugdale::{LossTable, MaugisDugdale, empirical_loss, energy_loss, loss_table};
use adhesion::numerics::curve::logspace;
use adhesion::scenes::fig3::Fig3_8Params;
use criterion::{Criterion, criterion_group, criterion_main};

/// (χ, ℓ) at the DMT end, in the transition (λ ≈ 1.0) and at the JKR end.
const CASES: [(&str, f64, f64); 3] = [("dmt", 0.01, 0.1), ("transition", 0.3, 0.1), ("jkr", 30.0, 0.1)];

fn md_engine(c: &mut Criterion) {
    let mut g = c.benchmark_group("md");
    for (name, chi, ell) in CASES {
        let md = MaugisDugdale::new(chi, ell).expect("model");
        let a_max = 3.0 * ell.cbrt().max(md.junction_radius());
        g.bench_function(format!("curve 2x200 points, {name}"), |b| {
            b.iter(|| black_box(md.curve(a_max, 200).expect("curve")));
        });
        g.bench_function(format!("cycle (jumps + loss), {name}"), |b| {
            b.iter(|| black_box(md.cycle().expect("cycle")));
        });
    }
    g.finish();
}

fn loss_per_asperity(c: &mut Criterion) {
    let table = loss_table().expect("table");
    let mut g = c.benchmark_group("loss per asperity");
    for (name, chi, ell) in CASES {
        g.bench_function(format!("exact, quadrature, {name}"), |b| {
            b.iter(|| black_box(energy_loss(black_box(chi), black_box(ell)).expect("loss")));
        });
        let md = MaugisDugdale::new(chi, ell).expect("model");
        g.bench_function(format!("exact, loop area n = 1000, {name}"), |b| {
            b.iter(|| black_box(md.energy_loss_by_loop_area(1000).expect("area")));
        });
    }
    // Lookups are timed over 1000 inputs spread over the whole range of s = χ³/ℓ.
    let chis = logspace(1e-3, 1e3, 1000);
    g.bench_function("table, 1000 evaluations", |b| {
        b.iter(|| chis.iter().map(|&x| table.loss(x, 0.1)).sum::<f64>());
    });
    g.bench_function("empirical (3.6), 1000 evaluations", |b| {
        b.iter(|| chis.iter().map(|&x| empirical_loss(x, 0.1)).sum::<f64>());
    });
    g.sample_size(10);
    g.bench_function("build the table, 40 nodes per unit ln s", |b| {
        b.iter(|| black_box(LossTable::new(40).expect("table")));
    });
    g.finish();
}

fn fig3_8c(c: &mut Criterion) {
    let p = Fig3_8Params::default();
    loss_table().expect("table");
    let mut g = c.benchmark_group("fig3.8c");
    g.sample_size(10);
    for (name, method) in [("table", LossMethod::Table), ("empirical", LossMethod::Empirical)] {
        g.bench_function(format!("60 x 60 grid, {name}"), |b| {
            b.iter(|| black_box(p.loss_grid(method, 60, &Job::quiet()).expect("grid")));
        });
    }
    g.bench_function("one point, quadrature at every node", |b| {
        b.iter(|| {
            black_box(
                p.model(24e-9, 12.2e-9)
                    .and_then(|m| m.loss_per_area(LossMethod::Quadrature))
                    .expect("point"),
            )
        });
    });
    g.finish();
}

criterion_group!(benches, md_engine, loss_per_asperity, fig3_8c);
criterion_main!(benches);
