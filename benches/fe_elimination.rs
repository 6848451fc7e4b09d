//! Could another Newton method take the converged load steps of Fig. 4.5's finite-element
//! cycle for much less? (Issue 32, item 4: the cycle under 15 s.) A load step in contact
//! starts from the branch's tangent and spends its first iterations while the contact edge's
//! column of nodes settles on the steep repulsive wall (`benches/fe.rs`). This study takes
//! consecutive accepted states of the bench cycle in contact, one depth step (0.2 ζ0) apart,
//! and runs each step again from the tangent's prediction to the cycle's tolerance (largest
//! gradient component 10⁻⁷) by three methods, each with the same line search (Armijo):
//!
//! - **Newton**: a fresh double-precision factorisation at every iteration (shifted where the
//!   Hessian is indefinite);
//! - **eliminated**: nonlinear elimination of the unknowns out of balance at the prediction
//!   (|g| > 1 and their neighbours in the Hessian's graph: the contact edge's column), which are
//!   minimised with all others held (dense Newton) before the first global step and after
//!   each trial step, so that the global Newton step sees the wall only through its Schur
//!   complement; a fresh factorisation per global iteration;
//! - **eliminated, chord**: the same elimination with the global directions from the previous
//!   state's factorisation, refactorised where a step contracts the gradient by less than
//!   a quarter.
//!
//! The counts are priced with the unit costs measured in the same run (median of 15 each at a
//! state in contact); the local minimisations are priced at nothing, a bound in the
//! eliminations' favour. The cycle as it runs (`StableNewton` with chord steps, single-precision
//! directions and warm starts) takes 11.3 Newton iterations and 4.6 factorisations per
//! converged load step, 115 ms (`benches/fe.rs`).
//!
//! Run: `cargo bench --bench fe_elimination` (about 65 s on a quiet machine: the cycle 55 s,
//! the steps 10 s; `FE_ELIMINATION_STEPS` sets the number of steps, default 12). Each method's
//! converged state is checked to lie within 1e-8 of Newton's.
//!
//! Measured (bench mesh, 24 542 unknowns, quiet machine, 2 cores; 12 steps spread over
//! loading and unloading; 30 steps of the 15 112-unknown mesh of width 0.25 b give the same
//! counts):
//!
//! | method | iterations | factorisations | local iterations | priced per step | 279 steps |
//! |---|---|---|---|---|---|
//! | Newton | 7.0 (5-12) | 7.0 | | 128 ms | 35.8 s |
//! | eliminated | 4.2 (4-5) | 4.2 | 7.8 | 76 ms | 21.3 s |
//! | eliminated, chord | 9.7 (7-13) | 2.1 + 1 certifying | 21.8 | 85 ms | 23.7 s |
//! | as run (`benches/fe.rs`) | 11.3 | 4.6 | | 115 ms | 32.0 s |
//!
//! Unit costs of the same run: Hessian 1.46 ms, factorisation 9.02 ms in single and 12.54 ms
//! in double precision, solve 1.55 ms, energy 1.40 ms, gradient 1.38 ms. A larger eliminated
//! set (|g| > 0.05 and two rings of neighbours) takes 3.4 global iterations on the variant:
//! from an error of about 0.1 ζ0 to a gradient of 10⁻⁷ the quadratic convergence takes three
//! to four steps whatever the wall does. The eliminations would bring the 279 converged steps
//! of the cycle from 32 s to 21-24 s, still above 15 s before any jump (the jumps and the
//! contact-edge nodes peeling off in the unloading take 21 s as run). Even a floor of one
//! certifying factorisation and three iterations of a solve, a gradient and an energy per step
//! (27 ms: 7.5 s for the 279 steps) would leave 7.5 s for the jumps.
//!
//! Conclusion: under 15 s on this mesh, at this depth step and tolerance, on 2 cores, is out of
//! reach of a better nonlinear solver; it needs linear algebra several times cheaper than the
//! unit costs above and jumps three times cheaper. Not integrated: the elimination would save
//! at most a third of the converged steps' time at the price of a second solver path.

mod common;

use common::{fe_cycle_options, fig4_5_fe};
use std::borrow::Cow;
use std::collections::HashMap;
use std::time::Instant;

use adhesion::models::axisymmetric::cycle::{CycleOptions, TipState, run_cycle};
use adhesion::models::body_force_fe::tip::{FeEnergy, FeTip};
use adhesion::numerics::loading::Controlled;
use adhesion::numerics::newton::Energy;
use adhesion::numerics::pcg::inf_norm;
use adhesion::numerics::sparse_llt::SparseLlt;
use nalgebra::{DMatrix, DVector};

/// The cycle's gradient tolerance.
const GRADIENT_TOL: f64 = 1e-7;
/// Unknowns out of balance above this gradient at the prediction are eliminated.
const OUT_OF_BALANCE: f64 = 1.0;
/// The eliminated unknowns are minimised to this gradient.
const LOCAL_TOL: f64 = 1e-3;
/// A chord step that contracts the gradient by less than this refactorises.
const CHORD_CONTRACTION: f64 = 0.25;
/// Iterations before a method is taken to have failed (none does).
const MAX_ITERATIONS: usize = 80;

/// The next shift of a factorisation that failed with `shift`: 10⁻⁶ of `scale` (the largest
/// diagonal entry), then ten times the last.
fn next_shift(shift: f64, scale: f64) -> f64 {
    if shift == 0.0 { 1e-6 * scale } else { 10.0 * shift }
}

/// The methods compared.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Method {
    Newton,
    Eliminated,
    EliminatedChord,
}

/// What a step cost.
#[derive(Default, Clone, Copy)]
struct Counts {
    iterations: usize,
    factorisations: usize,
    local: usize,
}

/// One load step's energy at the new depth and the tip's sparse analysis.
struct Step<'a> {
    energy: FeEnergy<'a>,
    llt: &'a SparseLlt,
    pattern: &'a [(usize, usize)],
    diagonal: &'a [usize],
    counts: Counts,
}

impl Step<'_> {
    /// The factor of the Hessian at `u`, shifted by the smallest μ of 10⁻⁶, 10⁻⁵, … times its
    /// largest diagonal entry that factorises where it is indefinite.
    fn factor(&mut self, u: &[f64]) -> Vec<f64> {
        let mut values = vec![0.0; self.pattern.len()];
        self.energy.hessian_values(u, &mut values);
        let scale = self.diagonal.iter().fold(0.0f64, |m, &k| m.max(values[k].abs()));
        let mut shift = 0.0;
        let mut storage = None;
        loop {
            let mut shifted = values.clone();
            self.diagonal.iter().for_each(|&k| shifted[k] += shift);
            self.counts.factorisations += 1;
            match self
                .llt
                .factorise::<f64>(&shifted, storage.take())
                .expect("pattern")
            {
                Ok(factor) => return factor,
                Err(s) => storage = Some(s),
            }
            shift = next_shift(shift, scale);
        }
    }

    /// Minimise over the unknowns `set` with all others held (dense Newton with the Armijo
    /// search) to a largest gradient component below `LOCAL_TOL`; nothing moves (and no
    /// energy is evaluated) where `set` is in balance already.
    fn minimise_locally(&mut self, u: &mut [f64], set: &[usize]) {
        let place: HashMap<usize, usize> = set.iter().enumerate().map(|(a, &i)| (i, a)).collect();
        let (n, m) = (u.len(), set.len());
        let mut g = vec![0.0; n];
        let mut values = vec![0.0; self.pattern.len()];
        let mut e = None;
        for _ in 0..MAX_ITERATIONS {
            self.energy.gradient(u, &mut g);
            let g_set: Vec<f64> = set.iter().map(|&i| g[i]).collect();
            if inf_norm(&g_set) < LOCAL_TOL {
                return;
            }
            self.counts.local += 1;
            self.energy.hessian_values(u, &mut values);
            let mut h = DMatrix::<f64>::zeros(m, m);
            for (k, &(r, c)) in self.pattern.iter().enumerate() {
                if let (Some(&a), Some(&b)) = (place.get(&r), place.get(&c)) {
                    h[(a, b)] = values[k];
                    h[(b, a)] = values[k];
                }
            }
            let scale = (0..m).fold(0.0f64, |x, a| x.max(h[(a, a)].abs()));
            let rhs = DVector::from_iterator(m, g_set.iter().map(|x| -x));
            let mut shift = 0.0;
            let p = loop {
                let mut shifted = h.clone();
                (0..m).for_each(|a| shifted[(a, a)] += shift);
                if let Some(ch) = shifted.cholesky() {
                    break ch.solve(&rhs);
                }
                shift = next_shift(shift, scale);
            };
            let mut full = vec![0.0; n];
            set.iter().zip(p.iter()).for_each(|(&i, &pi)| full[i] = pi);
            let before = *e.get_or_insert_with(|| self.energy.energy(u));
            e = Some(self.line_search(u, &full, &g, before, None));
        }
    }

    /// Move `u` along `p` by the first t of 1, 1/2, … that satisfies Armijo's condition on
    /// the energy (after minimising the eliminated unknowns `set` at the trial state), or whose
    /// promised decrease lies below the energy's roundoff; the new energy.
    fn line_search(&mut self, u: &mut [f64], p: &[f64], g: &[f64], e: f64, set: Option<&[usize]>) -> f64 {
        let slope: f64 = p.iter().zip(g).map(|(a, b)| a * b).sum();
        let mut t = 1.0;
        let mut trial = vec![0.0; u.len()];
        loop {
            trial
                .iter_mut()
                .zip(u.iter().zip(p))
                .for_each(|(x, (a, b))| *x = a + t * b);
            if let Some(set) = set {
                self.minimise_locally(&mut trial, set);
            }
            let e_trial = self.energy.energy(&trial);
            if e_trial <= e + 1e-4 * t * slope || (t * slope).abs() < 1e-13 * e.abs() || t < 1e-8 {
                u.copy_from_slice(&trial);
                return e_trial;
            }
            t *= 0.5;
        }
    }

    /// Converge from `u` by `method`; `previous` is the factor of the state before the step.
    fn converge(
        &mut self,
        u: &mut [f64],
        method: Method,
        previous: &[f64],
        neighbours: &[Vec<usize>],
    ) -> Counts {
        let n = u.len();
        let mut g = vec![0.0; n];
        self.energy.gradient(u, &mut g);
        let set = (method != Method::Newton).then(|| {
            let mut set: Vec<usize> = (0..n).filter(|&i| g[i].abs() > OUT_OF_BALANCE).collect();
            let ring: Vec<usize> = set.iter().flat_map(|&i| neighbours[i].iter().copied()).collect();
            set.extend(ring);
            set.sort_unstable();
            set.dedup();
            set
        });
        if let Some(set) = &set {
            self.minimise_locally(u, set);
        }
        let mut e = self.energy.energy(u);
        let mut factor = Cow::Borrowed(previous);
        let mut last = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            self.energy.gradient(u, &mut g);
            let norm = inf_norm(&g);
            if norm < GRADIENT_TOL {
                break;
            }
            if method != Method::EliminatedChord || norm > CHORD_CONTRACTION * last {
                factor = Cow::Owned(self.factor(u));
            }
            last = norm;
            self.counts.iterations += 1;
            let mut p: Vec<f64> = g.iter().map(|x| -x).collect();
            self.llt.solve(&factor, &mut p);
            e = self.line_search(u, &p, &g, e, set.as_deref());
        }
        self.counts
    }
}

/// Median of `runs` timings of `f`, in ms.
fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            1e3 * start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn main() {
    let steps: usize = std::env::var("FE_ELIMINATION_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12);
    let tip = FeTip::new(&fig4_5_fe()).expect("tip");
    let z = tip.scales().length;
    let opts = fe_cycle_options(z, -15.0, 0.2);
    let start = Instant::now();
    let cycle = run_cycle(
        &tip,
        &CycleOptions {
            keep_profiles: true,
            ..opts
        },
        |_| Ok(()),
    )
    .expect("cycle");
    println!(
        "fe/fig4.5 cycle ({} unknowns): {:.1} s, P_adh {:.12e} N",
        tip.len(),
        start.elapsed().as_secs_f64(),
        cycle.adhesive_force()
    );
    // Consecutive target states in contact, one depth step apart (no bisection between).
    let in_contact = |s: &TipState| s.contact.area() > 0.0;
    let pairs: Vec<(&TipState, &TipState)> = [&cycle.loading, &cycle.unloading]
        .into_iter()
        .flat_map(|states| states.windows(2).map(|w| (&w[0], &w[1])))
        .filter(|(a, b)| {
            ((b.depth - a.depth).abs() - opts.step).abs() < 1e-6 * opts.step && in_contact(a) && in_contact(b)
        })
        .collect();
    let stride = (pairs.len() / steps.max(1)).max(1);

    let pattern = tip.energy_at(0.0).hessian_pattern();
    let diagonal: Vec<usize> = (0..pattern.len())
        .filter(|&k| pattern[k].0 == pattern[k].1)
        .collect();
    let n = tip.len();
    let llt = SparseLlt::analyse(n, &pattern).expect("analysis");
    let mut neighbours = vec![Vec::new(); n];
    for &(r, c) in pattern.iter().filter(|(r, c)| r != c) {
        neighbours[r].push(c);
        neighbours[c].push(r);
    }

    let methods = [Method::Newton, Method::Eliminated, Method::EliminatedChord];
    let mut totals = [Counts::default(); 3];
    let mut counted = 0;
    for (before, after) in pairs.iter().step_by(stride).take(steps) {
        let (from, to) = (tip.approach(before.depth), tip.approach(after.depth));
        let u0 = &before.displacement;
        // The tangent's prediction, from the factor of the state before the step.
        let mut first = Step {
            energy: tip.energy_at(from),
            llt: &llt,
            pattern: &pattern,
            diagonal: &diagonal,
            counts: Counts::default(),
        };
        let previous = first.factor(u0);
        let mut rate = vec![0.0; n];
        tip.gradient_rate(from, u0, &mut rate);
        llt.solve(&previous, &mut rate);
        let predicted: Vec<f64> = u0.iter().zip(&rate).map(|(x, r)| x - (to - from) * r).collect();
        let mut line = format!("h {:+7.3} -> {:+7.3} ζ0:", before.depth / z, after.depth / z);
        let mut reference: Option<Vec<f64>> = None;
        for (method, total) in methods.iter().zip(totals.iter_mut()) {
            let mut step = Step {
                energy: tip.energy_at(to),
                counts: Counts::default(),
                ..first
            };
            let mut u = predicted.clone();
            let c = step.converge(&mut u, *method, &previous, &neighbours);
            let apart = reference
                .get_or_insert_with(|| u.clone())
                .iter()
                .zip(&u)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                apart < 1e-8,
                "{method:?} converged {apart:e} away from Newton's state"
            );
            line += &format!(
                " {method:?} {} its {} facts {} local |",
                c.iterations, c.factorisations, c.local
            );
            total.iterations += c.iterations;
            total.factorisations += c.factorisations;
            total.local += c.local;
        }
        println!("{line}");
        counted += 1;
    }

    // Unit costs at the deepest loading state.
    let deep = cycle.loading.last().expect("loading states");
    let (delta, u) = (tip.approach(deep.depth), &deep.displacement);
    let e = tip.energy_at(delta);
    let mut values = vec![0.0; pattern.len()];
    let hessian = median_ms(15, || e.hessian_values(u, &mut values));
    let single_values: Vec<f32> = values.iter().map(|&v| v as f32).collect();
    let single = median_ms(15, || {
        llt.factorise::<f32>(&single_values, None)
            .expect("pattern")
            .expect("positive definite");
    });
    let mut factor = Vec::new();
    let double = median_ms(15, || {
        factor = llt
            .factorise::<f64>(&values, None)
            .expect("pattern")
            .expect("positive definite");
    });
    let mut rhs = vec![1.0; n];
    let solve = median_ms(15, || llt.solve(&factor, &mut rhs));
    let energy = median_ms(15, || {
        std::hint::black_box(e.energy(u));
    });
    let mut g = vec![0.0; n];
    let gradient = median_ms(15, || e.gradient(u, &mut g));
    println!(
        "unit costs (ms): Hessian {hessian:.2}, factorisation {single:.2} (single) {double:.2} (double), solve {solve:.2}, energy {energy:.2}, gradient {gradient:.2}"
    );
    let k = counted as f64;
    for (method, t) in methods.iter().zip(&totals) {
        let (its, facts) = (t.iterations as f64 / k, t.factorisations as f64 / k);
        // Every iteration: a solve, a gradient and an energy; every factorisation: a Hessian.
        // The chord method adds the accepted state's certifying factorisation.
        let certify = if *method == Method::EliminatedChord {
            hessian + double
        } else {
            0.0
        };
        let ms = its * (solve + gradient + energy) + facts * (hessian + double) + certify;
        println!(
            "{method:?}: {its:.2} iterations, {facts:.2} factorisations, {:.2} local iterations per step; priced {ms:.0} ms per step, {:.1} s for 279 steps",
            t.local as f64 / k,
            279.0 * ms / 1e3
        );
    }
    let floor = hessian + double + 3.0 * (solve + gradient + energy);
    println!(
        "floor (one certifying factorisation, three iterations): {floor:.0} ms per step, {:.1} s for 279 steps",
        279.0 * floor / 1e3
    );
}
