//! Chapter 5 speed: the stable sparse Newton solve, coupled cycles, and the uncoupled paths
//! (exact spring by spring against binned), criterion medians. With `CH5_LONG=1` also the
//! complete Fig. 5.8 (6 stiffnesses x 10 roughnesses x 15 samples of 256 x 256 springs, median
//! of three runs) and one coupled 256 x 256 cycle of 1000 displacement steps per phase and of
//! 1000 in all (one run each),
//! too long for criterion's ten samples: `CH5_LONG=1 cargo bench --bench ch5 -- long`. The long
//! runs also time coupled cycles of 32 x 32 and 64 x 64 springs with the direct (Cholesky) and
//! the iterative (CG and certificate) linear algebra. In the coupled 256 x 256 cycle some 100
//! to 200 springs lose stability at each step of the contact range; the iterative path resolves
//! them locally (jumps, avalanches, patch modes, unbalanced springs relaxed with their
//! surroundings), some 15 global iterations per such step.

use std::hint::black_box;
use std::time::Instant;

use adhesion::job::Job;
use adhesion::models::fibril::{K_CR_BAR, SingleSpring};
use adhesion::models::spring_array::{BinnedBranches, SpringArray, coupled_cycle, uncoupled_cycle};
use adhesion::numerics::newton::{LinearSolver, NewtonOptions, StableNewton};
use adhesion::scenes::Scene;
use adhesion::scenes::fig5::{Fig5_8, Fig5_8Params};
use adhesion::surface::{Spectrum, generate};
use criterion::{BatchSize, Criterion};

/// Heights z̄ of a Gaussian-autocorrelation surface, σ̄_rms = `sigma`, L̄_c = 0.01.
fn heights(nx: usize, ny: usize, sigma: f64, seed: u64) -> Vec<f64> {
    let spectrum = Spectrum::Gaussian {
        rms: 1.0,
        correlation_length: 0.01,
    };
    let gy = ny.max(2);
    let map = generate(&spectrum, nx, gy, 1.0, gy as f64 / nx as f64, seed).expect("surface");
    let mut z = map.z;
    z.truncate(nx * ny);
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    z.iter().map(|v| sigma * (v - mean)).collect()
}

/// The cycle window of the scenes: 5 σ_rms beyond pull-off down to 4 σ_rms below pull-in.
fn window(k_e: f64, sigma: f64) -> (f64, f64) {
    let (u_in, u_off) = SingleSpring::new(k_e)
        .expect("spring")
        .bistable_range()
        .expect("soft");
    (u_off + 5.0 * sigma, u_in - 4.0 * sigma)
}

fn newton(c: &mut Criterion) {
    let mut group = c.benchmark_group("ch5 newton");
    group.sample_size(10);
    for (nx, ny) in [(256, 1), (128, 128)] {
        let k_e = K_CR_BAR * 2f64.powi(-10);
        let z = heights(nx, ny, 100.0, 1);
        let a = SpringArray::new(nx, ny, k_e, 2.0 * k_e, z).expect("array");
        let (u_max, u_min) = window(k_e, 100.0);
        // A state half-way down the loading path, then one step of Δū = 1.
        let cy_opts = NewtonOptions::default();
        let s = a.single().expect("spring");
        let mut d: Vec<f64> = a
            .heights()
            .iter()
            .map(|z| {
                s.gap(u_max - z, s.branch_on(u_max - z, true, false))
                    .expect("gap")
            })
            .collect();
        let mut solver = StableNewton::new(&a.energy_at(u_max)).expect("solver");
        let u_mid = 0.5 * (u_max + u_min);
        for u in adhesion::numerics::curve::linspace(u_max, u_mid, 200) {
            solver.minimize(&a.energy_at(u), &mut d, &cy_opts).expect("relax");
        }
        let e = a.energy_at(u_mid - 1.0);
        group.bench_function(format!("stable Newton, one step, {nx} x {ny} coupled"), |b| {
            b.iter_batched(
                || d.clone(),
                |mut x| black_box(solver.minimize(&e, &mut x, &cy_opts).expect("solve")),
                BatchSize::LargeInput,
            );
        });
    }
    group.finish();
}

fn cycles(c: &mut Criterion) {
    let mut group = c.benchmark_group("ch5 cycles");
    group.sample_size(10);
    let k_e = K_CR_BAR * 2f64.powi(-10);
    let z = heights(256, 1, 100.0, 1);
    let (u_max, u_min) = window(k_e, 100.0);
    for mult in [0.0, 2.0, 10.0] {
        let a = SpringArray::new(256, 1, k_e, mult * k_e, z.clone()).expect("array");
        group.bench_function(
            format!("coupled cycle 256 x 1, 1000 steps, k_mu = {mult} k_e"),
            |b| {
                b.iter(|| {
                    black_box(
                        coupled_cycle(&a, u_max, u_min, 1000, &NewtonOptions::default(), |_| Ok(()))
                            .expect("cycle"),
                    )
                });
            },
        );
    }
    let k_e = K_CR_BAR * 2f64.powi(-7);
    let (u_max, u_min) = window(k_e, 50.0);
    for n in [64, 256] {
        let z = heights(n, n, 50.0, 1);
        let a = SpringArray::new(n, n, k_e, 0.0, z.clone()).expect("array");
        if n == 64 {
            group.bench_function("uncoupled exact, 64 x 64, 1000 steps", |b| {
                b.iter(|| black_box(uncoupled_cycle(&a, u_max, u_min, 1000).expect("cycle")));
            });
        }
        let (lo, hi) = z.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
        group.bench_function(
            format!("uncoupled binned (tables + cycle), {n} x {n}, 1000 steps"),
            |b| {
                b.iter(|| {
                    let t = BinnedBranches::new(k_e, u_max, u_min, 1000, 4, (lo, hi)).expect("tables");
                    black_box(t.cycle(&z).expect("cycle"))
                });
            },
        );
        let t = BinnedBranches::new(k_e, u_max, u_min, 1000, 4, (lo, hi)).expect("tables");
        group.bench_function(
            format!("uncoupled binned (cycle only), {n} x {n}, 1000 steps"),
            |b| {
                b.iter(|| black_box(t.cycle(&z).expect("cycle")));
            },
        );
    }
    group.finish();
}

/// Median of `runs` timed runs, seconds.
fn median_of(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn long_runs() {
    let t = median_of(3, || {
        black_box(Fig5_8::run(&Fig5_8Params::default(), &Job::quiet()).expect("fig5.8"));
    });
    println!("ch5 long/fig5.8 complete (6 x 10 x 15 samples, 256 x 256): median of 3 runs {t:.2} s");
    let k_e = K_CR_BAR * 2f64.powi(-10);
    let (u_max, u_min) = window(k_e, 100.0);
    for n in [32, 64] {
        let a = SpringArray::new(n, n, k_e, 2.0 * k_e, heights(n, n, 100.0, 1)).expect("array");
        for linear in [LinearSolver::Direct, LinearSolver::Iterative] {
            let opts = NewtonOptions {
                linear,
                ..NewtonOptions::default()
            };
            let t = median_of(1, || {
                black_box(coupled_cycle(&a, u_max, u_min, 1000, &opts, |_| Ok(())).expect("cycle"));
            });
            println!(
                "ch5 long/coupled cycle {n} x {n}, k_mu = 2 k_e, 1000 steps, {linear:?}: one run {t:.2} s"
            );
        }
    }
    let a = SpringArray::new(256, 256, k_e, 2.0 * k_e, heights(256, 256, 100.0, 1)).expect("array");
    // 1000 displacement steps per phase, and 1000 in all (500 per phase).
    for steps in [1000, 500] {
        let t = median_of(1, || {
            black_box(
                coupled_cycle(&a, u_max, u_min, steps, &NewtonOptions::default(), |_| Ok(())).expect("cycle"),
            );
        });
        println!("ch5 long/coupled cycle 256 x 256, k_mu = 2 k_e, {steps} steps per phase: one run {t:.2} s");
    }
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    newton(&mut c);
    cycles(&mut c);
    c.final_summary();
    if std::env::var_os("CH5_LONG").is_some() {
        long_runs();
    }
}
