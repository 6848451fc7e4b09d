//! Does condensing the linear bulk of the finite-element tip onto its nonlinear surface layers
//! (a Schur complement) pay? (Issue 17, item 3.) Measured on the tip of Fig. 4.5 at its
//! defaults of then (`fig4_5_fe()`, 21 610 triangles, 22 266 unknowns, surface elements of
//! 0.155 b; it now has 23 817 triangles, 24 542 unknowns, surface elements of 0.1375 b).
//!
//! The Hessian is H = K + H_body, with K the constant stiffness and H_body the body force's
//! tangent, which couples the u_z dofs of each element only. Split the unknowns into s (the
//! u_z dofs where H_body matters) and b (every u_r dof and the other u_z dofs); with H_body
//! neglected on b, the Newton step H p = −g becomes
//!
//! ```text
//! (S + H_body,ss) p_s = −g_s + K_sb K_bb⁻¹ g_b,    p_b = −K_bb⁻¹ (g_b + K_bs p_s),
//! S = K_ss − K_sb K_bb⁻¹ K_bs (dense, once),
//! ```
//!
//! a dense Cholesky factorisation of size n_s and two sparse solves with the factor of K_bb
//! (once) per step, against the current step: a numeric sparse refactorisation (symbolic
//! analysis reused, faer's supernodal LLᵀ as `StableNewton` sets it up, sequential) and a
//! solve of the full Hessian.
//!
//! The body force acts on every element, so the condensation is exact only if its tangent on
//! b is dropped (a modified Newton step there: the gradient stays exact, so the equilibria do
//! not change, only the convergence rate and the stability test on b) or frozen into K_bb.
//! The bench takes the equilibrium at the deepest point of Fig. 4.5's cycle (h = −15 ζ0,
//! reached by `StableNewton` in steps of 1 ζ0 from the undeformed tip with its apex at ζ0),
//! and for several splits (the body tangent on the diagonal above a fraction of its largest
//! value, at that state and the undeformed one; above a fraction of the dof's own stiffness;
//! the u_z dofs of the fine zone below a height) reports n_s and the error of the step with
//! the tangent dropped outside s × s against the full Newton step (the first step of the next
//! load step, unloading by 0.2 ζ0). The smallest split whose step error is at most 1e-2
//! (`ADHESION_SCHUR_STEP_ERROR`) is condensed and timed; the condensed step is checked to
//! reproduce that error (the Schur code solves the dropped-tangent system exactly).
//!
//! Run: `cargo bench --bench fe_schur` (about 3.5 min: the deep state takes 15 s, S 4 s, a
//! condensed step 2.5 s).
//!
//! Measured (2 cores shared with two other heavy jobs, so the sparse step is 2x the 10.7 ms
//! of `SUPERNODAL_THRESHOLD`'s note; criterion medians):
//!
//! | split (u_z dofs)                   |   n_s | step error |
//! |------------------------------------|-------|------------|
//! | tangent > 1e-1 of its largest      |  1078 | 2.8        |
//! | tangent > 1e-3 of its largest      |  4022 | 0.40       |
//! | tangent > 1e-5 of its largest      |  6114 | 6.5e-3     |
//! | tangent > 1e-6 of its largest      |  7745 | 3.1e-4     |
//! | tangent > 1e-3 K_ii                |  3265 | 0.92       |
//! | fine zone, surface row only        |   554 | 0.96       |
//! | fine zone, z ≤ 3 ζ0                |  4986 | 0.24       |
//! | fine zone, z ≤ 10 ζ0               |  6371 | 8.4e-3     |
//! | every u_z (exact)                  | 11185 | 0          |
//!
//! - per Newton step now: sparse refactorisation + solve of H, 20.9 ms (Hessian values
//!   2.4 ms, common to both);
//! - condensed, n_s = 6114 (n_b = 16 152): one-off K_bb symbolic + numeric 22.5 ms, S
//!   3.92 s (6114 solves in blocks of 128); per step 2.70 s (dense LLᵀ of 6114 and two
//!   K_bb solves): 130 times the sparse step;
//! - dense LLᵀ alone: n = 512 2.16 ms, 768 6.00 ms, 1024 14.1 ms, 2048 111 ms (n³, about
//!   26 GFLOP/s): break-even with the sparse step at n_s ≈ 1100-1200;
//! - memory: sparse factor of H 9.4 MB; K_bb's 5.4 MB, S 299 MB and its factor 299 MB.
//!
//! Conclusion: it does not pay, by two orders of magnitude. The nonlinear zone is not a
//! surface but a band: for a step within 1e-2 of Newton's the body tangent must be kept
//! down to about 10 ζ0 into the tip (about 11 rows of the thin layers across the fine zone's
//! 554 surface nodes), n_s ≈ 6000, five times the break-even; the Schur complement of the 2-D
//! bulk onto a band is dense (n_s² = 37 M entries), while the sparse factor of the whole
//! Hessian (AMD ordering) holds 1.2 M entries, 53 per unknown: the sparse elimination already
//! condenses the bulk far more cheaply. n_s grows linearly with the fine zone's radius and the dense cost as its
//! cube, so a larger fine zone makes it worse; it would break even only for a fine zone about
//! a fifth of Fig. 4.5's (at best: the sparse step shrinks with it). Not integrated.

mod common;

use common::fig4_5_fe;
use std::hint::black_box;
use std::time::Instant;

use adhesion::models::body_force_fe::assembly::{FIXED, held_top_dofs};
use adhesion::models::body_force_fe::tip::FeTip;
use adhesion::numerics::loading::Controlled;
use adhesion::numerics::newton::{Energy, LinearSolver, NewtonOptions, StableNewton};
use adhesion::numerics::sparse_llt::SparseLlt;
use criterion::Criterion;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltParams, LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::cholesky::llt::solve::solve_in_place_with_conj;
use faer::{Conj, MatMut, MatRef, Par, Spec};

/// The conclusion of the measurement (printed at the end; numbers in the doc comment).
const CONCLUSION: &str = "Conclusion (fig4.5, 2 loaded cores): the condensation does not pay. \
A step within 1e-2 of Newton's needs the body tangent on n_s = 6114 u_z dofs (down to about \
10 zeta0 into the tip); its dense LLT costs about 130 times the sparse refactorisation of the \
full Hessian, which dense LLT matches only up to n_s of about 1100-1200.";

/// Columns per block of the multi-right-hand-side solve that forms S.
const BLOCK: usize = 128;

/// Dense Cholesky factorisation in place of the column-major n × n `a` (lower triangle).
fn dense_llt(a: &mut [f64], n: usize) {
    let params: Spec<LltParams, f64> = Default::default();
    let mut buf = MemBuffer::new(cholesky_in_place_scratch::<f64>(n, Par::Seq, params));
    cholesky_in_place(
        MatMut::from_column_major_slice_mut(a, n, n),
        LltRegularization::default(),
        Par::Seq,
        MemStack::new(&mut buf),
        params,
    )
    .expect("positive definite");
}

fn dense_solve(l: &[f64], n: usize, rhs: &mut [f64]) {
    let mut buf = MemBuffer::new(faer::dyn_stack::StackReq::EMPTY);
    solve_in_place_with_conj(
        MatRef::from_column_major_slice(l, n, n),
        Conj::No,
        MatMut::from_column_major_slice_mut(rhs, n, 1),
        Par::Seq,
        MemStack::new(&mut buf),
    );
}

/// The condensation of a split: the bulk's factor, the Schur complement and the couplings.
struct Condensed {
    /// Index of each unknown within s (`Ok`) or b (`Err`).
    place: Vec<Result<usize, usize>>,
    n_s: usize,
    n_b: usize,
    bulk: SparseLlt,
    bulk_factor: Vec<f64>,
    /// K_bs by s column: (b index, value).
    coupling: Vec<Vec<(usize, f64)>>,
    /// K_ss, column-major n_s × n_s, both triangles.
    k_ss: Vec<f64>,
    /// S, column-major n_s × n_s, both triangles (empty until formed).
    schur: Vec<f64>,
    /// K_bb: lower pattern and values.
    bb_pattern: Vec<(usize, usize)>,
    bb_values: Vec<f64>,
    /// Pattern positions of the body tangent within s × s: (position, column-major index).
    ss_slots: Vec<(usize, usize)>,
}

impl Condensed {
    /// Split the unknowns where `in_s`, factorise K_bb (timed: symbolic, numeric).
    fn bulk(pattern: &[(usize, usize)], k: &[f64], in_s: &[bool]) -> (Self, f64, f64) {
        let mut place = Vec::with_capacity(in_s.len());
        let (mut n_s, mut n_b) = (0, 0);
        for &s in in_s {
            if s {
                place.push(Ok(n_s));
                n_s += 1;
            } else {
                place.push(Err(n_b));
                n_b += 1;
            }
        }
        let mut bb_pattern = Vec::new();
        let mut bb_values = Vec::new();
        let mut coupling = vec![Vec::new(); n_s];
        let mut k_ss = vec![0.0; n_s * n_s];
        let mut ss_slots = Vec::new();
        for (at, (&(r, c), &v)) in pattern.iter().zip(k).enumerate() {
            match (place[r], place[c]) {
                (Err(i), Err(j)) => {
                    bb_pattern.push((i, j));
                    bb_values.push(v);
                }
                (Ok(i), Ok(j)) => {
                    k_ss[i + j * n_s] += v;
                    if i != j {
                        k_ss[j + i * n_s] += v;
                    }
                    ss_slots.push((at, i.max(j) + i.min(j) * n_s));
                }
                (Ok(i), Err(j)) | (Err(j), Ok(i)) => coupling[i].push((j, v)),
            }
        }
        let t = Instant::now();
        let bulk = SparseLlt::analyse(n_b, &bb_pattern).expect("pattern");
        let symbolic = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let bulk_factor = bulk
            .factorise(&bb_values, None)
            .expect("matrix")
            .expect("K_bb positive definite");
        let numeric = t.elapsed().as_secs_f64();
        (
            Self {
                place,
                n_s,
                n_b,
                bulk,
                bulk_factor,
                coupling,
                k_ss,
                schur: Vec::new(),
                bb_pattern,
                bb_values,
                ss_slots,
            },
            symbolic,
            numeric,
        )
    }

    /// S = K_ss − K_sb K_bb⁻¹ K_bs, by blocks of `BLOCK` right-hand sides.
    fn form_schur(&mut self) {
        let (n_s, n_b) = (self.n_s, self.n_b);
        self.schur.clear();
        self.schur.extend_from_slice(&self.k_ss);
        let mut x = vec![0.0; n_b * BLOCK];
        for j0 in (0..n_s).step_by(BLOCK) {
            let m = BLOCK.min(n_s - j0);
            let x = &mut x[..n_b * m];
            x.iter_mut().for_each(|v| *v = 0.0);
            for j in 0..m {
                for &(b, v) in &self.coupling[j0 + j] {
                    x[b + j * n_b] = v;
                }
            }
            self.bulk.solve(&self.bulk_factor, x);
            for j in 0..m {
                let col = &x[j * n_b..(j + 1) * n_b];
                for (i, row) in self.coupling.iter().enumerate() {
                    let dot: f64 = row.iter().map(|&(b, v)| v * col[b]).sum();
                    self.schur[i + (j0 + j) * n_s] -= dot;
                }
            }
        }
    }

    /// One condensed Newton step: factorise S + H_body,ss (the body tangent of `h` − `k` on
    /// s × s) into `a` and solve H p = −g with the body tangent on b dropped.
    fn step(&self, h: &[f64], k: &[f64], g: &[f64], a: &mut Vec<f64>, p: &mut [f64]) {
        let (n_s, n_b) = (self.n_s, self.n_b);
        a.clear();
        a.extend_from_slice(&self.schur);
        for &(at, ij) in &self.ss_slots {
            a[ij] += h[at] - k[at];
        }
        dense_llt(a, n_s);
        let (mut gs, mut gb) = (vec![0.0; n_s], vec![0.0; n_b]);
        for (i, place) in self.place.iter().enumerate() {
            match *place {
                Ok(j) => gs[j] = g[i],
                Err(j) => gb[j] = g[i],
            }
        }
        // t = K_bb⁻¹ g_b; r_s = −g_s + K_sb t.
        let mut t = gb.clone();
        self.bulk.solve(&self.bulk_factor, &mut t);
        let mut ps: Vec<f64> = gs.iter().map(|v| -v).collect();
        for (pi, row) in ps.iter_mut().zip(&self.coupling) {
            *pi += row.iter().map(|&(b, v)| v * t[b]).sum::<f64>();
        }
        dense_solve(a, n_s, &mut ps);
        // p_b = −K_bb⁻¹ (g_b + K_bs p_s).
        for (row, &pi) in self.coupling.iter().zip(&ps) {
            for &(b, v) in row {
                gb[b] += v * pi;
            }
        }
        self.bulk.solve(&self.bulk_factor, &mut gb);
        for (i, place) in self.place.iter().enumerate() {
            p[i] = match *place {
                Ok(j) => ps[j],
                Err(j) => -gb[j],
            };
        }
    }
}

/// Pressed in steps of 1 ζ0 from the undeformed tip with its apex at ζ0 (δ = 1) to
/// h = −15 ζ0 (δ = −14): the deepest state of Fig. 4.5's cycle.
fn deep_state(tip: &FeTip) -> Vec<f64> {
    let t = Instant::now();
    let mut u = vec![0.0; tip.len()];
    let mut newton = StableNewton::new(&tip.energy_at(1.0)).expect("analysis");
    newton.set_linear(LinearSolver::Direct);
    let opts = NewtonOptions {
        linear: LinearSolver::Direct,
        max_iterations: 5000,
        ..NewtonOptions::default()
    };
    let mut from = 1.0;
    let mut iterations = 0;
    for step in 0..=15 {
        let delta = 1.0 - step as f64;
        tip.prepare_start(from, delta, &mut u);
        let rep = newton
            .minimize(&tip.energy_at(delta), &mut u, &opts)
            .expect("equilibrium");
        iterations += rep.iterations;
        from = delta;
    }
    let (r, gaps) = tip.surface_gaps(from, &u);
    let contact = r
        .iter()
        .zip(&gaps)
        .filter(|(_, g)| **g < 1.5)
        .map(|(r, _)| *r)
        .fold(0.0, f64::max);
    println!(
        "deep state h = -15 zeta0: {iterations} Newton iterations, {} factorisations, {:.1} s; \
         contact radius (gap < 1.5 zeta0) {:.1} nm, fine zone {:.1} nm",
        newton.factorizations(),
        t.elapsed().as_secs_f64(),
        contact * 1e9,
        tip.params().fine_radius * 1e9
    );
    u
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let tolerance: f64 = std::env::var("ADHESION_SCHUR_STEP_ERROR")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1e-2);
    let tip = FeTip::new(&fig4_5_fe()).expect("tip");
    let n = tip.len();
    let far = tip.energy_at(1e8);
    let pattern = far.hessian_pattern();
    let zero = vec![0.0; n];
    // K: the Hessian where the body force's tangent vanishes (δ = 1e8 ζ0).
    let mut k = vec![0.0; pattern.len()];
    far.hessian_values(&zero, &mut k);
    let deep = deep_state(&tip);
    let states = [(1.0, zero.clone()), (-14.0, deep.clone())];
    let mut h_deep = vec![0.0; pattern.len()];
    tip.energy_at(-14.0).hessian_values(&deep, &mut h_deep);
    // The u_z dofs: those with a body tangent on the diagonal somewhere.
    let mut z_dofs = vec![false; n];
    for d in held_top_dofs(tip.mesh()).0 {
        if d[1] != FIXED {
            z_dofs[d[1]] = true;
        }
    }

    let full = SparseLlt::analyse(n, &pattern).expect("pattern");
    let mut full_factor = full
        .factorise(&h_deep, None)
        .expect("matrix")
        .expect("positive definite");
    // The right-hand side: the gradient of the deep state at the next load step (unloading
    // by 0.2 zeta0, the cycle's step), the first Newton step's.
    let mut g = vec![0.0; n];
    tip.energy_at(-13.8).gradient(&deep, &mut g);
    let mut p_full: Vec<f64> = g.iter().map(|v| -v).collect();
    full.solve(&full_factor, &mut p_full);
    println!(
        "tip: {} triangles, {n} unknowns ({} u_z), {} Hessian entries (lower)",
        tip.elements(),
        z_dofs.iter().filter(|&&z| z).count(),
        pattern.len()
    );
    // The error of the step with the body tangent dropped outside s x s (what the
    // condensation solves), by a sparse factorisation of that Hessian.
    let step_error = |in_s: &[bool]| -> f64 {
        let dropped: Vec<f64> = pattern
            .iter()
            .enumerate()
            .map(|(at, &(r, c))| if in_s[r] && in_s[c] { h_deep[at] } else { k[at] })
            .collect();
        let Ok(factor) = full.factorise(&dropped, None).expect("matrix") else {
            return f64::INFINITY;
        };
        let mut p: Vec<f64> = g.iter().map(|v| -v).collect();
        full.solve(&factor, &mut p);
        max_diff(&p, &p_full) / inf_norm(&p_full)
    };
    let mut splits: Vec<(String, Vec<bool>)> = Vec::new();
    // By the body tangent on the diagonal relative to its largest value, at the two states.
    let mut tangent = vec![0.0f64; n];
    for (delta, u) in &states {
        let mut h = vec![0.0; pattern.len()];
        tip.energy_at(*delta).hessian_values(u, &mut h);
        for (at, &(r, c)) in pattern.iter().enumerate() {
            if r == c {
                tangent[r] = tangent[r].max((h[at] - k[at]).abs());
            }
        }
    }
    let top = inf_norm(&tangent);
    for e in [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8] {
        splits.push((
            format!("|H_body,ii| > {e:.0e} max"),
            tangent.iter().map(|&t| t > e * top).collect(),
        ));
    }
    // By the body tangent relative to the dof's own stiffness (thin layers: K_ii is large).
    for e in [1e-2, 1e-3, 1e-4] {
        splits.push((
            format!("|H_body,ii| > {e:.0e} K_ii"),
            pattern
                .iter()
                .zip(&k)
                .filter(|((r, c), _)| r == c)
                .map(|(&(r, _), &kd)| tangent[r] > e * kd)
                .collect(),
        ));
    }
    // Geometric bands: the u_z dofs of the fine zone's nodes below a height above the bottom.
    let (dofs, _) = held_top_dofs(tip.mesh());
    let l = tip.scales().length;
    let fine = tip.params().fine_radius / l;
    for band in [0.0, 1.0, 3.0, 10.0, 30.0] {
        let mut in_s = vec![false; n];
        for ([r, z], d) in tip.mesh().nodes.iter().zip(&dofs) {
            if *r <= fine && *z <= band && d[1] != FIXED {
                in_s[d[1]] = true;
            }
        }
        splits.push((format!("u_z, r <= r_f, z <= {band} zeta0"), in_s));
    }
    splits.push(("every u_z (exact)".into(), z_dofs.clone()));
    let mut chosen: Option<(usize, usize)> = None;
    for (k_split, (name, in_s)) in splits.iter().enumerate() {
        let n_s = in_s.iter().filter(|&&s| s).count();
        let err = step_error(in_s);
        println!(
            "split {name}: n_s = {n_s}, n_b = {}, step error {err:.2e}",
            n - n_s
        );
        if err <= tolerance && chosen.is_none_or(|(_, m)| n_s < m) {
            chosen = Some((k_split, n_s));
        }
    }
    let (k_split, _) = chosen.expect("the exact split");
    let (name, in_s) = &splits[k_split];
    println!("chosen (smallest n_s with step error <= {tolerance:.0e}): {name}");
    let in_s = in_s.clone();

    let (mut cond, t_sym, t_num) = Condensed::bulk(&pattern, &k, &in_s);
    let t = Instant::now();
    cond.form_schur();
    let t_schur = t.elapsed().as_secs_f64();
    let (n_s, n_b) = (cond.n_s, cond.n_b);
    let mut a = Vec::new();
    let mut p = vec![0.0; n];
    let t = Instant::now();
    cond.step(&h_deep, &k, &g, &mut a, &mut p);
    let t_step = t.elapsed().as_secs_f64();
    println!(
        "condensed: n_s = {n_s}, n_b = {n_b}; K_bb symbolic {:.1} ms, numeric {:.1} ms, \
         S (n_s solves in blocks of {BLOCK}) {:.2} s; one step {:.3} s; its error against the \
         full step {:.2e} (the split's: {:.2e})",
        t_sym * 1e3,
        t_num * 1e3,
        t_schur,
        t_step,
        max_diff(&p, &p_full) / inf_norm(&p_full),
        step_error(&in_s),
    );
    println!(
        "memory: full factor {:.1} MB, K_bb factor {:.1} MB, S {:.1} MB (+ its factor {:.1} MB)",
        full.factor_len() as f64 * 8e-6,
        cond.bulk.factor_len() as f64 * 8e-6,
        (n_s * n_s) as f64 * 8e-6,
        (n_s * n_s) as f64 * 8e-6,
    );

    let mut group = c.benchmark_group("fe-schur");
    group.bench_function(format!("full Hessian values ({n} unknowns)"), |b| {
        let mut h = vec![0.0; pattern.len()];
        b.iter(|| tip.energy_at(-14.0).hessian_values(black_box(&deep), &mut h))
    });
    group.bench_function(format!("full sparse refactorise + solve ({n} unknowns)"), |b| {
        b.iter(|| {
            full_factor = full
                .factorise(black_box(&h_deep), Some(std::mem::take(&mut full_factor)))
                .expect("matrix")
                .expect("positive definite");
            let mut p: Vec<f64> = g.iter().map(|v| -v).collect();
            full.solve(&full_factor, &mut p);
            black_box(p)
        })
    });
    group.bench_function(
        format!("condensed step: S + H_body,ss, dense llt + solve, 2 K_bb solves (n_s = {n_s})"),
        |b| b.iter(|| cond.step(black_box(&h_deep), &k, &g, &mut a, &mut p)),
    );
    group.bench_function(format!("K_bb factorise, symbolic + numeric (n_b = {n_b})"), |b| {
        let mut factor = Vec::new();
        b.iter(|| {
            let bulk = SparseLlt::analyse(n_b, &cond.bb_pattern).expect("pattern");
            factor = bulk
                .factorise(&cond.bb_values, Some(std::mem::take(&mut factor)))
                .expect("matrix")
                .expect("positive definite");
            black_box(&factor);
        })
    });
    group.bench_function(format!("form S, {n_s} solves with K_bb"), |b| {
        b.iter(|| cond.form_schur())
    });
    for m in [128, 256, 384, 512, 768, 1024, 2048] {
        // A symmetric positive-definite m × m matrix: S's leading block where S is that large.
        let mut spd = vec![0.0; m * m];
        for j in 0..m {
            for i in 0..m {
                spd[i + j * m] = if i < n_s && j < n_s {
                    cond.schur[i + j * n_s]
                } else if i == j {
                    1.0
                } else {
                    0.0
                };
            }
        }
        group.bench_function(format!("dense llt, n = {m}"), |b| {
            let mut work = Vec::new();
            b.iter(|| {
                work.clear();
                work.extend_from_slice(&spd);
                dense_llt(&mut work, m);
                black_box(&work);
            })
        });
    }
    group.finish();
    c.final_summary();
    println!("{CONCLUSION}");
}
