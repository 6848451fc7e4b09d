//! Measured force curves: one fit with the contact point and the baseline free of a 2000-point
//! instrument curve (JKR/machine-stiffness on the retract, Hertz on the approach), the
//! preprocessing alone, the JKR fit alone of the prepared curve (as nanite's fit is timed), and
//! a 128 × 128 force map (16 384 curves) fitted in parallel.
//!
//! The curves are made by the machine-stiffness model (R = 1 µm, ℰ = 2 MPa, w = 40 mJ/m²,
//! k_s = 0.5 N/m) as an instrument records them: height and force with offsets and 1 % noise.
//! `benches/nanite_compare.py` times nanite's Hertz fit of the same curve (written by
//! `FORCE_CURVE_BENCH_WRITE=path`) back to back.

use std::hint::black_box;
use std::path::Path;

use adhesion::fit::instrument::{PrepareOptions, Synthetic, fit_all, fit_curve, prepare, synthetic_curve};
use adhesion::fit::{FitModel, FitSettings, fit_with};
use adhesion::models::machine_stiffness::{Experiment, TipGeometry};
use adhesion::readers::ForceCurve;
use criterion::{Criterion, criterion_group, criterion_main};

fn curve(modulus: f64, seed: u64) -> ForceCurve {
    let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, modulus, 0.04, 0.5).unwrap();
    let d_o = x.pull_off().unwrap().before.delta;
    let s = Synthetic {
        delta_min: 1.5 * d_o,
        delta_max: 3.0 * x.scales().h,
        samples: 1000,
        depth_offset: 3.2e-6,
        force_offset: 5e-9,
        noise: 3e-9,
        seed,
    };
    synthetic_curve(&x, &s).unwrap()
}

fn settings(model: FitModel) -> FitSettings {
    FitSettings {
        radius: 1e-6,
        spring_constant: None,
        model: Some(model),
        segment: None,
        poisson: None,
    }
}

fn force_curves(c: &mut Criterion) {
    let one = curve(2.0e6, 1);
    let rows: usize = one.segments.iter().map(|s| s.len()).sum();
    if let Some(path) = std::env::var_os("FORCE_CURVE_BENCH_WRITE") {
        let mut t = String::from("segment,height_m,force_n\n");
        for (k, s) in one.segments.iter().enumerate() {
            for (z, f) in s.height_measured.as_ref().unwrap().iter().zip(&s.force) {
                t.push_str(&format!("{k},{z:e},{f:e}\n"));
            }
        }
        std::fs::write(path, t).unwrap();
    }
    let opts = PrepareOptions::default();
    let path = Path::new("bench");
    let mut group = c.benchmark_group("force_curves");
    group.sample_size(50);
    group.bench_function(format!("preprocess a {rows}-point curve"), |b| {
        b.iter(|| black_box(prepare(&one, path, &opts).unwrap()));
    });
    for model in [
        FitModel::MachineStiffness,
        FitModel::Jkr,
        FitModel::Dmt,
        FitModel::Hertz,
    ] {
        let s = settings(model);
        group.bench_function(
            format!("{model:?} fit, contact point free, {rows}-point curve"),
            |b| {
                b.iter(|| black_box(fit_curve(&one, path, &opts, &s).unwrap()));
            },
        );
    }
    // The fit alone of the prepared curve, as nanite's `fit_model` is timed (its preprocessing
    // apart): the like-for-like figure for `benches/nanite_compare.py`.
    let (prepared, pre) = prepare(&one, path, &opts).unwrap();
    let s = FitSettings {
        spring_constant: Some(pre.spring_constant_n_per_m),
        ..settings(FitModel::Jkr)
    };
    group.bench_function(format!("Jkr fit of the prepared {rows}-point curve"), |b| {
        b.iter(|| black_box(fit_with(&prepared, path, &s).unwrap()));
    });
    group.finish();
    // A 128 × 128 map: 64 distinct curves (moduli 1-3 MPa, noise seeds) repeated over the grid.
    let distinct: Vec<ForceCurve> = (0..64)
        .map(|k| curve(1.0e6 + 2.0e6 * k as f64 / 63.0, k))
        .collect();
    let map: Vec<ForceCurve> = (0..128 * 128)
        .map(|k| {
            let mut c = distinct[k % 64].clone();
            c.index = k;
            c.meta.grid_index = Some([k % 128, k / 128]);
            c.meta.grid_shape = Some([128, 128]);
            c
        })
        .collect();
    let mut group = c.benchmark_group("force_map");
    group.sample_size(10);
    let s = settings(FitModel::MachineStiffness);
    group.bench_function("128 x 128 map, machine-stiffness fits, rayon", |b| {
        b.iter(|| {
            let fits = fit_all(&map, path, &opts, &s);
            assert!(fits.iter().all(|f| f.is_ok()));
            black_box(fits)
        });
    });
    group.finish();
}

criterion_group!(benches, force_curves);
criterion_main!(benches);
