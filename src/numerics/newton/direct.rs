//! The direct path of [`StableNewton::minimize`] ([`LinearSolver::Direct`]): sparse Cholesky
//! factorisations `H = L Lᵀ` (faer), which are the step solve and the stability test in one.
//! A factorisation is reused for identical Hessian values (the cache that serves an accepted
//! state's stability test and the first step of a continuation restarting from it) and, while
//! the gradient falls fast, for chord steps. Where H is indefinite the step is shifted,
//! `(H + λI) p = −g` with the smallest λ found by growing it geometrically; at a stationary
//! point that is not a minimum the state leaves along a direction of negative curvature found
//! by inverse iteration. The iterative path hands over to this one wherever its certificate is
//! not found.
//!
//!
//! Hessians that are mostly full (a boundary-element kernel couples every unknown to every
//! other) are factorised as dense matrices, sequentially: the sparse supernodal factorisation
//! of a full matrix of a few hundred unknowns spends about a third of its time synchronising
//! threads, and a sweep already runs its points in parallel. While the gradient is far above
//! its tolerance, the direction of a dense Newton step comes from a single-precision
//! factorisation (half the flops; where it fails, the double-precision one decides); every
//! accepted state, every stability test and every cached factor rests on double precision.
//! Sparse Hessians take single-precision directions too where the caller asks for them
//! ([`StableNewton::set_single_precision_directions`]): the finite-element tip, whose
//! supernodal factor of about 10⁶ entries is bound by memory traffic, which single precision
//! halves.
//!
//! The line search cannot judge a step whose promised decrease lies below the roundoff of
//! the energy (terms that cancel): it would shrink the step until the state stops moving and
//! stall short of the gradient tolerance. With a positive-definite Hessian (or a chord step on
//! a positive-definite factor) such a step is taken in full, and the energy is not evaluated
//! there: the next gradient judges the step (a chord goes on only while the gradient falls by
//! [`CHORD_CONTRACTION`] per step), and the energy is evaluated again only where it is read
//! (a line search, the accepted state's report). On the finite-element cycles most of the
//! converging tail of a load step is such chord steps (the gradient from about 10⁻² to the
//! tolerance 10⁻⁷ at an energy of 10⁵): one energy evaluation fewer per step.
//!
//! [`LinearSolver::Direct`]: super::LinearSolver::Direct

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltParams, LltRegularization, cholesky_in_place};
use faer::linalg::cholesky::llt::solve::solve_in_place_with_conj;
use faer::{Conj, Par, Spec};
use std::sync::Arc;

use super::{Energy, Factor, NewtonOptions, NewtonReport, StableNewton, Watch, backtrack};
use crate::error::{Error, Result};
use crate::numerics::pcg::{dot, inf_norm};
use crate::numerics::sparse_llt::SparseLlt;

/// Chord steps (an earlier factorisation reused) continue while each cuts the largest
/// gradient component by at least this factor; otherwise the Hessian is factorised again.
pub(super) const CHORD_CONTRACTION: f64 = 0.25;

/// A Newton step that promises an energy decrease below this fraction of the energy is taken
/// without line search (the energy cannot resolve it).
const ENERGY_ROUNDOFF: f64 = 1e-12;

/// While the largest gradient component exceeds this multiple of the gradient tolerance, a
/// dense Hessian is factorised in single precision for the Newton direction (see
/// `StableNewton::factor_dense_single`).
const SINGLE_PRECISION_ABOVE: f64 = 1e4;

/// A numeric Cholesky factor `L` of `H = L Lᵀ`: sparse (faer's simplicial or supernodal
/// factorisation with the fill-reducing ordering of the symbolic analysis) or dense (lower triangle of a full
/// matrix, factorised in place).
pub(in crate::numerics) enum Cholesky {
    /// The factor's values in the layout of the symbolic analysis.
    Sparse(Arc<SparseLlt>, Vec<f64>),
    /// Column-major n × n, L in the lower triangle.
    Dense(Vec<f64>),
    /// As `Dense`, in single precision (a Newton direction far from convergence only).
    DenseSingle(Vec<f32>),
    /// As `Sparse`, in single precision (a Newton direction far from convergence only).
    SparseSingle(Arc<SparseLlt>, Vec<f32>),
}

impl Cholesky {
    /// Overwrite `rhs` with `H⁻¹ rhs`.
    pub(super) fn solve(&self, rhs: &mut [f64]) {
        match self {
            Self::Sparse(sparse, values) => sparse.solve(values, rhs),
            Self::Dense(l) => dense_solve(l, rhs),
            Self::SparseSingle(sparse, values) => in_single(rhs, |r| sparse.solve(values, r)),
            Self::DenseSingle(l) => in_single(rhs, |r| dense_solve(l, r)),
        }
    }
}

/// Overwrite `rhs` with `(L Lᵀ)⁻¹ rhs` for a dense column-major factor `L` (lower triangle).
fn dense_solve<T: faer::traits::RealField>(l: &[T], rhs: &mut [T]) {
    let n = rhs.len();
    let l = faer::MatRef::from_column_major_slice(l, n, n);
    let m = faer::MatMut::from_column_major_slice_mut(rhs, n, 1);
    let mut buf = MemBuffer::new(faer::dyn_stack::StackReq::EMPTY);
    solve_in_place_with_conj(l, Conj::No, m, Par::Seq, MemStack::new(&mut buf));
}

/// `solve` applied to `rhs` in single precision: rounded in, widened back.
fn in_single(rhs: &mut [f64], solve: impl FnOnce(&mut [f32])) {
    let mut single: Vec<f32> = rhs.iter().map(|&v| v as f32).collect();
    solve(&mut single);
    rhs.iter_mut().zip(&single).for_each(|(r, s)| *r = f64::from(*s));
}

/// Where a pattern is this full (stored lower-triangle entries over n(n+1)/2), the Hessian is
/// factorised as a dense matrix.
const DENSE_FILL: f64 = 0.5;
/// Dense factorisation only up to this many unknowns (8 bytes × n² of storage per factor).
const DENSE_MAX_UNKNOWNS: usize = 4000;

/// Column-major positions in an n × n matrix of the pattern entries (shift slots included),
/// when the pattern is full enough to be factorised densely.
pub(super) fn dense_layout(n: usize, pattern: &[(usize, usize)], n_pattern: usize) -> Option<Vec<usize>> {
    let lower = (n * (n + 1) / 2) as f64;
    if n > DENSE_MAX_UNKNOWNS || (n_pattern as f64) < DENSE_FILL * lower {
        return None;
    }
    Some(pattern.iter().map(|&(r, c)| r + c * n).collect())
}

/// Sum `values` into the lower triangle of the column-major n × n matrix `a` at the positions
/// `layout` (converted by `cast`) and factorise it in place, sequentially; whether it is
/// positive definite (in the precision of `T`).
fn dense_llt<T: faer::traits::RealField + Copy + std::ops::AddAssign>(
    a: &mut Vec<T>,
    n: usize,
    layout: &[usize],
    values: &[f64],
    cast: impl Fn(f64) -> T,
) -> bool {
    a.clear();
    a.resize(n * n, T::zero_impl());
    for (&k, &v) in layout.iter().zip(values) {
        a[k] += cast(v);
    }
    let par = Par::Seq;
    let params: Spec<LltParams, T> = Default::default();
    let mut buf =
        MemBuffer::new(faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<T>(n, par, params));
    cholesky_in_place(
        faer::MatMut::from_column_major_slice_mut(a, n, n),
        LltRegularization::default(),
        par,
        MemStack::new(&mut buf),
        params,
    )
    .is_ok()
}

impl StableNewton {
    /// Dense Cholesky factorisation of the values (pattern entries summed into the lower
    /// triangle); `None` if not positive definite.
    fn factor_dense(&mut self, layout: &[usize]) -> Option<Cholesky> {
        // The storage of a factor no longer in use, or fresh.
        let mut a = self.spare.take().unwrap_or_default();
        if dense_llt(&mut a, self.n, layout, &self.values, |v| v) {
            Some(Cholesky::Dense(a))
        } else {
            self.spare = Some(a);
            None
        }
    }

    /// A single-precision dense factorisation of the Hessian values (no shift) for a Newton
    /// direction far from convergence, where the direction's accuracy (about 10⁻⁷ times the
    /// condition number) does not limit the iteration and the factorisation costs half of a
    /// double-precision one; `None` if it fails (not positive definite, or too ill-conditioned
    /// for single precision). Never a stability test, and never cached as one.
    fn factor_dense_single(&mut self) -> Option<Factor> {
        let layout = self.dense.as_ref()?;
        let n_pattern = self.values.len() - self.n;
        let mut a = self.spare_single.take().unwrap_or_default();
        self.computed += 1;
        // The shift slots (after the pattern) are not part of H.
        if dense_llt(
            &mut a,
            self.n,
            &layout[..n_pattern],
            &self.values[..n_pattern],
            |v| v as f32,
        ) {
            Some(Arc::new(Cholesky::DenseSingle(a)))
        } else {
            self.spare_single = Some(a);
            None
        }
    }

    /// A single-precision factorisation of the Hessian values for a Newton direction far from
    /// convergence: dense where the Hessian is factorised densely
    /// ([`Self::factor_dense_single`]), sparse where the caller asked for it
    /// ([`StableNewton::set_single_precision_directions`]); `None` otherwise or where it fails.
    fn factor_single(&mut self) -> Option<Factor> {
        if self.dense.is_some() {
            return self.factor_dense_single();
        }
        if !self.single_sparse {
            return None;
        }
        let n_pattern = self.values.len() - self.n;
        let mut single: Vec<f32> = self.values[..n_pattern].iter().map(|&v| v as f32).collect();
        // The shift slots (after the pattern) are not part of H.
        single.resize(self.values.len(), 0.0);
        self.computed += 1;
        let spare = self.spare_single.take();
        match self.sparse.factorise(&single, spare).ok()? {
            Ok(values) => Some(Arc::new(Cholesky::SparseSingle(self.sparse.clone(), values))),
            Err(storage) => {
                self.spare_single = Some(storage);
                None
            }
        }
    }

    /// Factorise H + λI (values already in `self.values[..n_pattern]`); `None` if not
    /// positive definite. An unshifted factorisation of the same values as the last one is
    /// reused.
    pub(super) fn factor(&mut self, shift: f64) -> Result<Option<Factor>> {
        let n_pattern = self.values.len() - self.n;
        if shift == 0.0
            && let Some((v, l)) = &self.cache
            && v[..] == self.values[..n_pattern]
        {
            return Ok(l.clone());
        }
        self.computed += 1;
        for &k in &self.diagonal {
            self.values[k] = shift;
        }
        let l = if let Some(layout) = self.dense.take() {
            let l = self.factor_dense(&layout).map(Arc::new);
            self.dense = Some(layout);
            l
        } else {
            let spare = self.spare.take();
            match self
                .sparse
                .factorise(&self.values, spare)
                .map_err(|reason| Error::Unresolvable {
                    model: "stable Newton",
                    reason,
                })? {
                Ok(values) => Some(Arc::new(Cholesky::Sparse(self.sparse.clone(), values))),
                Err(storage) => {
                    self.spare = Some(storage);
                    None
                }
            }
        };
        if shift == 0.0 {
            let (mut v, old) = self.cache.take().unwrap_or_default();
            // The replaced factor's storage serves the next dense factorisation when nothing
            // else holds it.
            if let Some(Ok(Cholesky::Dense(a) | Cholesky::Sparse(_, a))) = old.map(Arc::try_unwrap) {
                self.spare = Some(a);
            }
            v.clear();
            v.extend_from_slice(&self.values[..n_pattern]);
            self.cache = Some((v, l.clone()));
        }
        Ok(l)
    }

    pub(super) fn minimize_inner(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
        mut e0: f64,
        watch: Watch<'_>,
    ) -> Result<NewtonReport> {
        let n = self.n;
        let n_pattern = self.values.len() - n;
        let mut rep = NewtonReport::default();
        let mut g = vec![0.0; n];
        let mut p = vec![0.0; n];
        let mut trial = vec![0.0; n];
        // Whether `e0` lags behind `x`: a step below the energy's roundoff is taken without
        // evaluating the energy, which is evaluated again only where it is read.
        let mut stale = false;
        let refresh = |e0: &mut f64, stale: &mut bool, x: &[f64]| {
            if std::mem::take(stale) {
                *e0 = energy.energy(x);
            }
        };
        // A positive-definite factorisation from an earlier iterate and the gradient norm there:
        // while the gradient keeps falling fast, steps reuse it (chord steps) instead of
        // factorising again. Acceptance always factorises at the accepted state itself. A warm
        // start takes the last positive-definite factorisation, of an earlier state, for the
        // first chord step.
        let mut chord: Option<(Factor, f64)> = if self.warm {
            self.cache
                .as_ref()
                .and_then(|(_, l)| l.clone())
                .map(|l| (l, f64::INFINITY))
        } else {
            None
        };
        while rep.iterations < opts.max_iterations {
            rep.iterations += 1;
            watch(&rep)?;
            energy.gradient(x, &mut g);
            let gnorm = inf_norm(&g);
            if let Some((f, g_prev)) = &chord
                && gnorm > opts.gradient_tol
                && gnorm <= CHORD_CONTRACTION * g_prev
            {
                for (pi, gi) in p.iter_mut().zip(&g) {
                    *pi = -gi;
                }
                f.solve(&mut p);
                let slope = dot(&g, &p);
                if slope < 0.0 && -slope <= ENERGY_ROUNDOFF * e0.abs().max(1.0) {
                    // The decrease this chord step promises lies below what the energy
                    // resolves: a line search would judge roundoff. The step is taken in full,
                    // and the next gradient judges it (the chord goes on only while the
                    // gradient falls by CHORD_CONTRACTION per step).
                    x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
                    stale = true;
                    chord = chord.map(|(f, _)| (f, gnorm));
                    continue;
                }
                refresh(&mut e0, &mut stale, x);
                let accepted = match backtrack(energy, x, &p, e0, slope, &mut trial) {
                    Some(e1) => {
                        e0 = e1;
                        true
                    }
                    None => false,
                };
                if accepted {
                    chord = chord.map(|(f, _)| (f, gnorm));
                } else {
                    chord = None;
                }
                continue;
            }
            chord = None;
            self.load_hessian(energy, x);
            // Far from convergence a single-precision factorisation serves the direction
            // (dense Hessians, and sparse ones where the caller asked); the acceptance below
            // always rests on a double-precision one.
            let single = if gnorm > SINGLE_PRECISION_ABOVE * opts.gradient_tol {
                self.factor_single()
            } else {
                None
            };
            let exact = single.is_none();
            let plain = match single {
                Some(l) => Some(l),
                None => self.factor(0.0)?,
            };
            let (llt, definite) = match plain {
                Some(l) => (l, true),
                None => {
                    // Scale for the shift: the largest Hessian entry's magnitude.
                    let scale = inf_norm(&self.values[..n_pattern]).max(1e-300);
                    rep.indefinite_iterations += 1;
                    watch(&rep)?;
                    let mut shift = if self.last_shift > 0.0 {
                        0.25 * self.last_shift
                    } else {
                        1e-6 * scale
                    };
                    loop {
                        if let Some(l) = self.factor(shift)? {
                            self.last_shift = shift;
                            break (l, false);
                        }
                        shift *= 4.0;
                        if shift > 1e12 * scale {
                            return Err(Error::Unresolvable {
                                model: "stable Newton",
                                reason: format!(
                                    "no shift up to {shift:.3e} makes the Hessian positive definite"
                                ),
                            });
                        }
                    }
                }
            };
            for (pi, gi) in p.iter_mut().zip(&g) {
                *pi = -gi;
            }
            llt.solve(&mut p);
            // A small gradient alone does not make an equilibrium: just past a fold none
            // exists, yet the gradient there is as small as the distance past the fold times
            // the stiffness, while the Hessian is still (barely) positive definite. The Newton
            // correction tells them apart: it is of the order of the gradient at a regular
            // minimum and large near the vanishing curvature of a fold. Accept only when it is
            // below √(gradient_tol) as well; otherwise keep descending (the jump, if any).
            if definite && exact && gnorm <= opts.gradient_tol && inf_norm(&p) <= opts.gradient_tol.sqrt() {
                refresh(&mut e0, &mut stale, x);
                rep.gradient_norm = gnorm;
                rep.energy = e0;
                return Ok(rep);
            }
            if definite {
                chord = Some((llt.clone(), gnorm));
            }
            let mut slope = dot(&g, &p);
            if !definite && (gnorm <= opts.gradient_tol || slope > -1e-300) {
                // A stationary point that is not a minimum: leave along negative curvature.
                Self::negative_curvature_direction(&llt, &mut p)?;
                rep.negative_curvature_steps += 1;
                if dot(&g, &p) > 0.0 {
                    p.iter_mut().for_each(|v| *v = -*v);
                }
                slope = dot(&g, &p).min(0.0);
            }
            if definite && exact && inf_norm(&p) <= opts.step_tol {
                rep.gradient_norm = gnorm;
                rep.energy = e0;
                x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
                rep.energy = energy.energy(x);
                return Ok(rep);
            }
            if definite && exact && -slope <= ENERGY_ROUNDOFF * e0.abs().max(1.0) {
                // The decrease this step promises is below what the energy resolves (its
                // terms cancel to roundoff): the line search cannot judge it and would shrink
                // it to nothing. Near a minimum with a positive-definite Hessian the full
                // Newton step is safe; take it.
                x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
                stale = true;
                continue;
            }
            refresh(&mut e0, &mut stale, x);
            match backtrack(energy, x, &p, e0, slope, &mut trial) {
                Some(e1) => e0 = e1,
                None if definite => {
                    // No decrease along the step: at roundoff level already.
                    rep.gradient_norm = gnorm;
                    rep.energy = e0;
                    return Ok(rep);
                }
                None => {
                    return Err(Error::NoConvergence {
                        method: "stable Newton (line search)",
                        iterations: rep.iterations,
                        residual: gnorm,
                    });
                }
            }
        }
        energy.gradient(x, &mut g);
        Err(Error::NoConvergence {
            method: "stable Newton",
            iterations: rep.iterations,
            residual: inf_norm(&g),
        })
    }

    /// A direction of most negative curvature of H, by inverse iteration with the shifted
    /// factor (H + λI)⁻¹, whose dominant eigenvector is H's lowest. Written into `v`.
    fn negative_curvature_direction(llt: &Cholesky, v: &mut [f64]) -> Result<()> {
        // Deterministic start with components in every direction.
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = 1.0 + 0.5 * ((i as f64) * 0.618_033_988_75).fract();
        }
        for _ in 0..30 {
            llt.solve(v);
            let norm = dot(v, v).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return Err(Error::Unresolvable {
                    model: "stable Newton",
                    reason: "inverse iteration for a negative-curvature direction failed".into(),
                });
            }
            v.iter_mut().for_each(|vi| *vi /= norm);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::numerics::newton::wells::Wells;
    use crate::numerics::newton::{Energy, NewtonOptions, StableNewton};
    use crate::numerics::pcg::inf_norm;

    #[test]
    fn a_stationary_saddle_is_left_along_negative_curvature() {
        // Start exactly at the stationary point x = 0 of a coupled chain: gradient zero.
        let e = Wells { n: 50, c: 0.1 };
        let mut x = vec![0.0; 50];
        let mut s = StableNewton::new(&e).unwrap();
        let rep = s.minimize(&e, &mut x, &NewtonOptions::default()).unwrap();
        assert!(rep.negative_curvature_steps >= 1);
        assert!(s.is_stable(&e, &x).unwrap());
        assert!(rep.gradient_norm <= 1e-10);
        assert!(
            rep.energy < -0.2 * 50.0,
            "a minimum well below the start, E = {}",
            rep.energy
        );
    }

    // Single-precision directions on a sparse Hessian reach the same minimum, certified in
    // double precision, and cost single-precision factorisations only while the gradient is
    // large.
    #[test]
    fn sparse_single_precision_directions_reach_the_same_minimum() {
        let e = Wells { n: 400, c: 0.3 };
        let opts = NewtonOptions::default();
        let start: Vec<f64> = (0..400).map(|i| 1.0 + 0.3 * ((i as f64) * 0.37).sin()).collect();
        let mut runs = Vec::new();
        for single in [false, true] {
            let mut s = StableNewton::new(&e).unwrap();
            assert!(s.dense.is_none(), "a sparse Hessian");
            s.set_single_precision_directions(single);
            let mut x = start.clone();
            let rep = s.minimize(&e, &mut x, &opts).unwrap();
            assert!(rep.gradient_norm <= opts.gradient_tol);
            assert!(s.is_stable(&e, &x).unwrap());
            runs.push((x, rep));
        }
        let (plain, single) = (&runs[0], &runs[1]);
        let gap = plain
            .0
            .iter()
            .zip(&single.0)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(gap < 1e-8, "minima differ by {gap:e}");
        assert!((plain.1.energy - single.1.energy).abs() <= 1e-12 * plain.1.energy.abs().max(1.0));
    }

    // Reuse: restarting from the state just accepted (same Hessian values) and testing its
    // stability compute no new factorisation; a restart from elsewhere does.
    #[test]
    fn the_factorisation_of_the_accepted_state_is_reused() {
        let e = Wells { n: 20, c: 0.3 };
        let mut x: Vec<f64> = (0..20).map(|i| 0.5 + 0.02 * i as f64).collect();
        let mut s = StableNewton::new(&e).unwrap();
        let opts = NewtonOptions::default();
        let first = s.minimize(&e, &mut x, &opts).unwrap();
        assert!(first.factorizations >= 1);
        let again = s.minimize(&e, &mut x, &opts).unwrap();
        assert_eq!((again.iterations, again.factorizations), (1, 0));
        assert!(s.is_stable(&e, &x).unwrap());
        let mut y = vec![1.3; 20];
        let other = s.minimize(&e, &mut y, &opts).unwrap();
        assert!(other.factorizations >= 1);
        assert!(y.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-8));
    }

    // A warm start (chord steps on the factorisation of the state accepted before) reaches the
    // same minimum from a start near it with fewer factorisations, and still certifies it by
    // a factorisation at the minimum itself.
    #[test]
    fn a_warm_start_saves_the_first_factorisation() {
        let e = Wells { n: 30, c: 0.3 };
        let opts = NewtonOptions::default();
        let mut runs = Vec::new();
        for warm in [false, true] {
            let mut s = StableNewton::new(&e).unwrap();
            s.set_warm_start(warm);
            let mut x: Vec<f64> = (0..30).map(|i| 0.8 + 0.01 * i as f64).collect();
            s.minimize(&e, &mut x, &opts).unwrap();
            // Near the minimum, as after a small load step.
            let mut y: Vec<f64> = x
                .iter()
                .enumerate()
                .map(|(i, v)| v + 1e-3 * (i as f64).cos())
                .collect();
            let rep = s.minimize(&e, &mut y, &opts).unwrap();
            assert!(rep.gradient_norm <= opts.gradient_tol);
            assert!(s.is_stable(&e, &y).unwrap());
            assert!(y.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-8));
            runs.push(rep.factorizations);
        }
        assert!(
            runs[1] < runs[0] && runs[1] >= 1,
            "cold {} warm {}",
            runs[0],
            runs[1]
        );
    }

    /// A chain of wells raised by a constant (an energy of large magnitude, whose roundoff
    /// hides the decrease of a small step), counting its energy evaluations.
    struct Raised {
        wells: Wells,
        offset: f64,
        energies: std::cell::Cell<usize>,
    }

    impl Energy for Raised {
        fn dim(&self) -> usize {
            self.wells.dim()
        }
        fn energy(&self, x: &[f64]) -> f64 {
            self.energies.set(self.energies.get() + 1);
            self.offset + self.wells.energy(x)
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            self.wells.gradient(x, g)
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            self.wells.hessian_pattern()
        }
        fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
            self.wells.hessian_values(x, v)
        }
    }

    // Warm chord steps whose promised decrease lies below the energy's roundoff (1e-12 of
    // 1e8) are taken without evaluating the energy: fewer energy evaluations than iterations,
    // the minimum of a cold minimisation to 1e-9, and the reported energy that of the
    // accepted state (evaluated again where a step left it behind).
    #[test]
    fn chord_steps_below_the_energy_roundoff_skip_the_energy() {
        let e = Raised {
            wells: Wells { n: 30, c: 0.3 },
            offset: 1e8,
            energies: std::cell::Cell::new(0),
        };
        let opts = NewtonOptions::default();
        let mut s = StableNewton::new(&e).unwrap();
        s.set_warm_start(true);
        let mut x: Vec<f64> = (0..30).map(|i| 0.8 + 0.01 * i as f64).collect();
        s.minimize(&e, &mut x, &opts).unwrap();
        let start: Vec<f64> = x
            .iter()
            .enumerate()
            .map(|(i, v)| v + 1e-3 * (i as f64).cos())
            .collect();
        let mut y = start.clone();
        e.energies.set(0);
        let rep = s.minimize(&e, &mut y, &opts).unwrap();
        let evaluations = e.energies.get();
        assert!(
            rep.iterations >= 2 && evaluations < rep.iterations,
            "{evaluations} energies in {} iterations",
            rep.iterations
        );
        assert_eq!(rep.energy, e.energy(&y));
        let mut cold = StableNewton::new(&e).unwrap();
        let mut z = start;
        cold.minimize(&e, &mut z, &opts).unwrap();
        assert!(y.iter().zip(&z).all(|(a, b)| (a - b).abs() < 1e-9));
        assert!(s.is_stable(&e, &y).unwrap());
    }

    /// ½|x|² plus an offset of 10⁻⁹ everywhere but at the start `x0`: an energy whose
    /// evaluation cannot resolve the decrease of a small Newton step (as when its terms cancel
    /// to roundoff), with the exact gradient x and Hessian I.
    struct Unresolved {
        x0: f64,
    }

    impl Energy for Unresolved {
        fn dim(&self) -> usize {
            1
        }
        fn energy(&self, x: &[f64]) -> f64 {
            0.5 * x[0] * x[0] + if x[0] == self.x0 { 0.0 } else { 1e-9 }
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            g[0] = x[0];
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            vec![(0, 0)]
        }
        fn hessian_values(&self, _: &[f64], v: &mut [f64]) {
            v[0] = 1.0;
        }
    }

    // The line search cannot see the 1.25e-13 a Newton step from x = 5e-7 gains under the
    // offset: it would shrink the step until x stops moving and stall there, short of the
    // gradient tolerance. A step below the energy's resolution is taken in full instead.
    #[test]
    fn a_step_below_the_energy_roundoff_is_taken_in_full() {
        let e = Unresolved { x0: 5e-7 };
        let mut s = StableNewton::new(&e).unwrap();
        let mut x = vec![e.x0];
        let rep = s.minimize(&e, &mut x, &NewtonOptions::default()).unwrap();
        assert!(x[0].abs() <= 1e-10, "{x:?}");
        assert!(rep.iterations <= 3, "{rep:?}");
    }

    // Far from convergence a dense Hessian is factorised in single precision for the
    // direction. At a condition number single precision cannot handle (1e12) the minimiser
    // still reaches the minimum to the gradient tolerance (double precision where single
    // fails or stalls), and every accepted state rests on a double-precision factorisation.
    #[test]
    fn single_precision_directions_reach_the_double_precision_minimum() {
        for ratio in [1e2, 1e12] {
            let e = Full {
                n: 60,
                site: Site::Quadratic { ratio },
                c: 0.5,
            };
            let mut s = StableNewton::new(&e).unwrap();
            let mut x = vec![100.0; 60];
            let opts = NewtonOptions::default();
            s.minimize(&e, &mut x, &opts).unwrap();
            let mut g = vec![0.0; 60];
            e.gradient(&x, &mut g);
            assert!(
                inf_norm(&g) <= opts.gradient_tol,
                "ratio {ratio}: {}",
                inf_norm(&g)
            );
            assert!(s.is_stable(&e, &x).unwrap());
            // The accepted state's double-precision factorisation is the cached one.
            assert!(s.cache.as_ref().is_some_and(|(_, l)| l.is_some()));
        }
    }

    /// The energy of each unknown alone in [`Full`].
    #[derive(Clone, Copy)]
    enum Site {
        /// x⁴/4 − s x²/2 − 0.01 i x: a double well, tilted more for later unknowns.
        Quartic { s: f64 },
        /// d_i x²/2 − x with d_i from 1 to `ratio` (geometric): a quadratic of condition
        /// about `ratio`.
        Quadratic { ratio: f64 },
    }

    /// E = Σ site_i(x_i) + ½ c (Σ x_i)²: every unknown coupled to every other, so the Hessian
    /// diag(site_i'') + c 11ᵀ is full and the dense path serves it.
    struct Full {
        n: usize,
        site: Site,
        c: f64,
    }

    impl Full {
        /// (site_i, site_i', site_i'') at x.
        fn site(&self, i: usize, x: f64) -> (f64, f64, f64) {
            match self.site {
                Site::Quartic { s } => {
                    let b = 0.01 * i as f64;
                    (
                        x.powi(4) / 4.0 - s * x * x / 2.0 - b * x,
                        x.powi(3) - s * x - b,
                        3.0 * x * x - s,
                    )
                }
                Site::Quadratic { ratio } => {
                    let d = ratio.powf(i as f64 / (self.n - 1) as f64);
                    (0.5 * d * x * x - x, d * x - 1.0, d)
                }
            }
        }
    }

    impl Energy for Full {
        fn dim(&self) -> usize {
            self.n
        }
        fn energy(&self, x: &[f64]) -> f64 {
            let sum: f64 = x.iter().sum();
            x.iter().enumerate().map(|(i, &v)| self.site(i, v).0).sum::<f64>() + 0.5 * self.c * sum * sum
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            let sum: f64 = x.iter().sum();
            for (i, (gi, &v)) in g.iter_mut().zip(x).enumerate() {
                *gi = self.site(i, v).1 + self.c * sum;
            }
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            (0..self.n).flat_map(|i| (0..=i).map(move |j| (i, j))).collect()
        }
        fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
            let mut k = 0;
            for (i, &xi) in x.iter().enumerate() {
                for j in 0..=i {
                    v[k] = self.c + if i == j { self.site(i, xi).2 } else { 0.0 };
                    k += 1;
                }
            }
        }
    }

    // A full Hessian is factorised densely: the minimiser converges to a stable state with a
    // small gradient, and the stability test rejects the unstable stationary point x = 0 of
    // the symmetric double wells (Hessian c 11ᵀ − s I, indefinite).
    #[test]
    fn a_full_hessian_takes_the_dense_factorisation() {
        let e = Full {
            n: 40,
            site: Site::Quartic { s: 1.0 },
            c: 0.05,
        };
        let mut s = StableNewton::new(&e).unwrap();
        assert!(s.dense.is_some(), "a full pattern is factorised densely");
        assert!(
            !s.is_stable(
                &Full {
                    n: 40,
                    site: Site::Quartic { s: 1.0 },
                    c: 0.05
                },
                &[0.0; 40]
            )
            .unwrap()
        );
        let mut x: Vec<f64> = (0..40).map(|i| 0.1 * (i as f64 - 20.0)).collect();
        let rep = s.minimize(&e, &mut x, &NewtonOptions::default()).unwrap();
        assert!(s.is_stable(&e, &x).unwrap());
        let mut g = vec![0.0; 40];
        e.gradient(&x, &mut g);
        assert!(inf_norm(&g) <= 1e-9, "{rep:?}");
        // The same minimum as the sparse factorisation of the same matrix reaches.
        let mut sparse = StableNewton::new(&e).unwrap();
        sparse.dense = None;
        let mut y: Vec<f64> = (0..40).map(|i| 0.1 * (i as f64 - 20.0)).collect();
        sparse.minimize(&e, &mut y, &NewtonOptions::default()).unwrap();
        assert!(x.iter().zip(&y).all(|(a, b)| (a - b).abs() < 1e-9));
        // A solve with the dense factor of a positive-definite Hessian inverts it.
        let mut rhs: Vec<f64> = (0..40).map(|i| (i as f64).sin()).collect();
        let b = rhs.clone();
        assert!(s.solve_at(&e, &x, &mut rhs).unwrap());
        let mut hv = vec![0.0; 40 * 41 / 2];
        e.hessian_values(&x, &mut hv);
        for i in 0..40 {
            let row: f64 = (0..40)
                .map(|j| {
                    hv[if j <= i {
                        i * (i + 1) / 2 + j
                    } else {
                        j * (j + 1) / 2 + i
                    }] * rhs[j]
                })
                .sum();
            assert!((row - b[i]).abs() < 1e-10, "row {i}: {row} vs {}", b[i]);
        }
    }
}
