//! Sparse Newton minimisation that only accepts stable equilibria.
//!
//! An equilibrium of a loaded elastic system is a stationary point of its total energy; it is
//! stable when the Hessian (tangent stiffness) is positive definite. Plain Newton solves
//! `H p = −g` and converges to whatever stationary point is near: on a non-convex energy that is
//! often a saddle or a maximum, an unstable state no experiment can observe.
//!
//! [`StableNewton`] minimises instead:
//! - the stability test is the sparse Cholesky factorisation `H = L Lᵀ` (faer): it succeeds
//!   exactly when `H` is positive definite, and fails with a non-positive pivot otherwise;
//! - with `H` positive definite it takes the Newton step, with a backtracking (Armijo) line
//!   search on the energy;
//! - with `H` indefinite it shifts, `(H + λI) p = −g` with the smallest λ (found by growing it
//!   geometrically) for which the factorisation succeeds, and backtracks along `p` for lower
//!   energy: a damped step that moves the unstable modes downhill while the stable parts of the
//!   system stay in their basins (the state an experiment reaches after the jump);
//! - at a stationary point that is not a minimum (gradient zero, `H` indefinite) it leaves
//!   along a direction of negative curvature found by inverse iteration with the shifted matrix.
//!
//! Every accepted state therefore has a small gradient, a small Newton correction (which rules
//! out the near-equilibria just past a fold, where the gradient is small but no equilibrium
//! exists) and a positive-definite Hessian (the last factorisation succeeded without shift). The symbolic factorisation (fill-reducing
//! ordering, elimination tree) is computed once for the fixed sparsity pattern and reused.
//! Numeric factorisations are reused too: while the gradient falls fast, steps solve with the
//! last positive-definite factor (chord steps, still with the line search on the energy), and
//! the factorisation of an accepted state serves both its stability test and the first step of
//! a continuation that restarts from it (identical Hessian values are detected, not assumed).
//! A continuation step therefore costs about one factorisation when no spring jumps.
//! The energy, gradient and Hessian come from an [`Energy`]; nothing here knows about physics.

use faer::Side;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use std::sync::Arc;

use crate::error::{Error, Result};

/// A smooth energy of `dim()` unknowns with a sparse Hessian of fixed pattern.
pub trait Energy {
    /// Number of unknowns.
    fn dim(&self) -> usize;
    /// Energy at `x`; `f64::INFINITY` outside the domain.
    fn energy(&self, x: &[f64]) -> f64;
    /// Gradient at `x` into `g` (length `dim()`).
    fn gradient(&self, x: &[f64], g: &mut [f64]);
    /// Positions (row, col) of the lower triangle of the Hessian, diagonal included; fixed.
    fn hessian_pattern(&self) -> Vec<(usize, usize)>;
    /// Hessian values at `x` in the order of [`Energy::hessian_pattern`].
    fn hessian_values(&self, x: &[f64], values: &mut [f64]);
}

/// Tolerances of the minimisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Converged when the largest gradient component is below this, the largest Newton
    /// correction below its square root, and `H` is positive definite.
    pub gradient_tol: f64,
    /// Or when the largest Newton correction is below this (and `H` is positive definite),
    /// the criterion of section 5.5.1.
    pub step_tol: f64,
    /// Largest number of iterations.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            gradient_tol: 1e-10,
            step_tol: 1e-12,
            max_iterations: 500,
        }
    }
}

/// How a minimisation went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonReport {
    /// Newton iterations taken.
    pub iterations: usize,
    /// Cholesky factorisations computed (failed attempts included, reused ones not).
    pub factorizations: usize,
    /// Iterations at which the Hessian was not positive definite (the state was unstable).
    pub indefinite_iterations: usize,
    /// Steps along a direction of negative curvature (leaving a saddle or maximum).
    pub negative_curvature_steps: usize,
    /// Largest gradient component at the accepted state.
    pub gradient_norm: f64,
    /// Energy at the accepted state.
    pub energy: f64,
}

impl NewtonReport {
    /// Whether the start state was unstable, so that the solver had to move to another
    /// stable state (an instability, a jump).
    pub fn left_unstable_state(&self) -> bool {
        self.indefinite_iterations > 0
    }
}

/// A numeric Cholesky factorisation, shared between the cache and its users.
type Factor = Arc<Llt<usize, f64>>;

/// Chord steps (an earlier factorisation reused) continue while each cuts the largest
/// gradient component by at least this factor; otherwise the Hessian is factorised again.
const CHORD_CONTRACTION: f64 = 0.25;

/// The sparse Hessian of an [`Energy`] with its symbolic Cholesky factorisation.
pub struct StableNewton {
    n: usize,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: faer::sparse::Argsort<usize>,
    llt: SymbolicLlt<usize>,
    /// Index in the values of each diagonal entry (for the shift).
    diagonal: Vec<usize>,
    /// Values in pattern order, then the diagonal shift slots appended.
    values: Vec<f64>,
    /// The last shift that worked, as the first guess for the next.
    last_shift: f64,
    /// The last unshifted factorisation (`None` inside: not positive definite) and the Hessian
    /// values it was computed from: a continuation that restarts from the state just accepted
    /// (and the stability test of that state) reuses it instead of factorising again.
    cache: Option<(Vec<f64>, Option<Factor>)>,
    /// Numeric factorisations computed so far (cache hits excluded).
    computed: usize,
}

impl StableNewton {
    /// Analyse the Hessian pattern of `energy` (lower triangle) once.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] if the pattern is out of bounds, lacks a diagonal entry, or the
    /// symbolic factorisation fails.
    pub fn new(energy: &impl Energy) -> Result<Self> {
        let n = energy.dim();
        let mut pattern = energy.hessian_pattern();
        let n_pattern = pattern.len();
        // The shift λI enters through extra diagonal entries (summed with the pattern's).
        pattern.extend((0..n).map(|i| (i, i)));
        let fail = |reason: String| Error::Unresolvable {
            model: "stable Newton",
            reason,
        };
        let mut has_diag = vec![false; n];
        for &(r, c) in &pattern[..n_pattern] {
            if r >= n || c >= n || r < c {
                return Err(fail(format!(
                    "Hessian entry ({r}, {c}) is outside the lower triangle of a {n} x {n} matrix"
                )));
            }
            if r == c {
                has_diag[r] = true;
            }
        }
        if let Some(i) = has_diag.iter().position(|&h| !h) {
            return Err(fail(format!(
                "Hessian pattern lacks the diagonal entry ({i}, {i})"
            )));
        }
        let pairs: Vec<Pair<usize, usize>> = pattern.iter().map(|&(r, c)| Pair::new(r, c)).collect();
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| fail(format!("sparsity pattern: {e:?}")))?;
        let llt = SymbolicLlt::try_new(symbolic.as_ref(), Side::Lower)
            .map_err(|e| fail(format!("symbolic factorisation: {e:?}")))?;
        Ok(Self {
            n,
            symbolic,
            argsort,
            llt,
            diagonal: (n_pattern..n_pattern + n).collect(),
            values: vec![0.0; n_pattern + n],
            last_shift: 0.0,
            cache: None,
            computed: 0,
        })
    }

    /// Factorise H + λI (values already in `self.values[..n_pattern]`); `None` if not
    /// positive definite. An unshifted factorisation of the same values as the last one is
    /// reused.
    fn factor(&mut self, shift: f64) -> Result<Option<Factor>> {
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
        let mat = SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, &self.values)
            .map_err(|e| Error::Unresolvable {
                model: "stable Newton",
                reason: format!("assembling the Hessian: {e:?}"),
            })?;
        let l = Llt::try_new_with_symbolic(self.llt.clone(), mat.as_ref(), Side::Lower)
            .ok()
            .map(Arc::new);
        if shift == 0.0 {
            let mut v = self.cache.take().map(|c| c.0).unwrap_or_default();
            v.clear();
            v.extend_from_slice(&self.values[..n_pattern]);
            self.cache = Some((v, l.clone()));
        }
        Ok(l)
    }

    fn solve(llt: &Llt<usize, f64>, rhs: &mut [f64]) {
        let n = rhs.len();
        let m = faer::MatMut::from_column_major_slice_mut(rhs, n, 1);
        llt.solve_in_place(m);
    }

    /// Whether the Hessian of `energy` at `x` is positive definite (the equilibrium is stable).
    ///
    /// # Errors
    /// Assembly failures (not expected).
    pub fn is_stable(&mut self, energy: &impl Energy, x: &[f64]) -> Result<bool> {
        let n_pattern = self.values.len() - self.n;
        energy.hessian_values(x, &mut self.values[..n_pattern]);
        Ok(self.factor(0.0)?.is_some())
    }

    /// Minimise `energy` from `x` (updated in place) to a stable equilibrium: small gradient
    /// and positive-definite Hessian. Never accepts a saddle or maximum.
    ///
    /// # Errors
    /// [`Error::NoConvergence`] after `max_iterations`; [`Error::Unresolvable`] if the start
    /// is outside the energy's domain.
    ///
    /// # Panics
    /// If `x.len() != energy.dim()`.
    pub fn minimize(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
    ) -> Result<NewtonReport> {
        let start = self.computed;
        let mut rep = self.minimize_inner(energy, x, opts)?;
        rep.factorizations = self.computed - start;
        Ok(rep)
    }

    fn minimize_inner(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
    ) -> Result<NewtonReport> {
        assert_eq!(x.len(), self.n, "state length must equal the energy's dimension");
        let n = self.n;
        let n_pattern = self.values.len() - n;
        let mut rep = NewtonReport::default();
        let mut g = vec![0.0; n];
        let mut p = vec![0.0; n];
        let mut trial = vec![0.0; n];
        let mut e0 = energy.energy(x);
        if !e0.is_finite() {
            return Err(Error::Unresolvable {
                model: "stable Newton",
                reason: "the start state is outside the energy's domain".into(),
            });
        }
        // A positive-definite factorisation from an earlier iterate and the gradient norm there:
        // while the gradient keeps falling fast, steps reuse it (chord steps) instead of
        // factorising again. Acceptance always factorises at the accepted state itself.
        let mut chord: Option<(Factor, f64)> = None;
        while rep.iterations < opts.max_iterations {
            rep.iterations += 1;
            energy.gradient(x, &mut g);
            let gnorm = inf_norm(&g);
            if let Some((f, g_prev)) = &chord
                && gnorm > opts.gradient_tol
                && gnorm <= CHORD_CONTRACTION * g_prev
            {
                for (pi, gi) in p.iter_mut().zip(&g) {
                    *pi = -gi;
                }
                Self::solve(f, &mut p);
                let slope = dot(&g, &p);
                let slack = 1e-14 * e0.abs().max(1.0);
                let mut t = 1.0;
                let mut accepted = false;
                while t >= 1e-20 {
                    for ((ti, xi), pi) in trial.iter_mut().zip(x.iter()).zip(&p) {
                        *ti = xi + t * pi;
                    }
                    let e1 = energy.energy(&trial);
                    if e1.is_finite() && e1 <= e0 + 1e-4 * t * slope + slack {
                        x.copy_from_slice(&trial);
                        e0 = e1;
                        accepted = true;
                        break;
                    }
                    t *= 0.5;
                }
                if accepted {
                    chord = chord.map(|(f, _)| (f, gnorm));
                } else {
                    chord = None;
                }
                continue;
            }
            chord = None;
            energy.hessian_values(x, &mut self.values[..n_pattern]);
            // Scale for the shift: the largest diagonal magnitude.
            let scale = inf_norm(&self.values[..n_pattern]).max(1e-300);
            let plain = self.factor(0.0)?;
            let (llt, definite) = match plain {
                Some(l) => (l, true),
                None => {
                    rep.indefinite_iterations += 1;
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
            Self::solve(&llt, &mut p);
            // A small gradient alone does not make an equilibrium: just past a fold none
            // exists, yet the gradient there is as small as the distance past the fold times
            // the stiffness, while the Hessian is still (barely) positive definite. The Newton
            // correction tells them apart: it is of the order of the gradient at a regular
            // minimum and large near the vanishing curvature of a fold. Accept only when it is
            // below √(gradient_tol) as well; otherwise keep descending (the jump, if any).
            if definite && gnorm <= opts.gradient_tol && inf_norm(&p) <= opts.gradient_tol.sqrt() {
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
            if definite && inf_norm(&p) <= opts.step_tol {
                rep.gradient_norm = gnorm;
                rep.energy = e0;
                x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
                rep.energy = energy.energy(x);
                return Ok(rep);
            }
            // Backtracking (Armijo) line search on the energy from the full step. No
            // extrapolation: a longer step could carry a metastable part of the system over
            // its energy barrier, and the state must follow the branch an experiment follows.
            let slack = 1e-14 * e0.abs().max(1.0);
            let armijo = |t: f64, e: f64| e <= e0 + 1e-4 * t * slope + slack;
            let eval = |t: f64, trial: &mut Vec<f64>| {
                for ((ti, xi), pi) in trial.iter_mut().zip(x.iter()).zip(&p) {
                    *ti = xi + t * pi;
                }
                energy.energy(trial)
            };
            let mut t = 1.0;
            let mut e1 = eval(t, &mut trial);
            while !(e1.is_finite() && armijo(t, e1)) {
                t *= 0.5;
                if t < 1e-20 {
                    break;
                }
                e1 = eval(t, &mut trial);
            }
            if t < 1e-20 {
                // No decrease along the step: at roundoff level already.
                if definite {
                    rep.gradient_norm = gnorm;
                    rep.energy = e0;
                    return Ok(rep);
                }
                return Err(Error::NoConvergence {
                    method: "stable Newton (line search)",
                    iterations: rep.iterations,
                    residual: gnorm,
                });
            }
            x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += t * pi);
            e0 = energy.energy(x);
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
    fn negative_curvature_direction(llt: &Llt<usize, f64>, v: &mut [f64]) -> Result<()> {
        // Deterministic start with components in every direction.
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = 1.0 + 0.5 * ((i as f64) * 0.618_033_988_75).fract();
        }
        for _ in 0..30 {
            Self::solve(llt, v);
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

/// Largest absolute value.
fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Plain Newton iteration on the gradient, `H p = −g` with a sparse LU factorisation and full
/// steps: converges to the nearest stationary point whatever its stability. Kept to show the
/// failure mode [`StableNewton`] avoids.
///
/// # Errors
/// [`Error::NoConvergence`] after `max_iterations` or on a singular Hessian.
pub fn plain_newton(energy: &impl Energy, x: &mut [f64], opts: &NewtonOptions) -> Result<NewtonReport> {
    let n = energy.dim();
    let pattern = energy.hessian_pattern();
    let n_lower = pattern.len();
    let mut lower = vec![0.0; n_lower];
    let mut g = vec![0.0; n];
    let mut rep = NewtonReport::default();
    while rep.iterations < opts.max_iterations {
        rep.iterations += 1;
        energy.gradient(x, &mut g);
        let gnorm = inf_norm(&g);
        if gnorm <= opts.gradient_tol {
            rep.gradient_norm = gnorm;
            rep.energy = energy.energy(x);
            return Ok(rep);
        }
        energy.hessian_values(x, &mut lower);
        // Full symmetric matrix: mirror the strictly lower entries.
        let mut triplets: Vec<faer::sparse::Triplet<usize, usize, f64>> = Vec::with_capacity(2 * n_lower);
        for (k, &(r, c)) in pattern.iter().enumerate() {
            triplets.push(faer::sparse::Triplet::new(r, c, lower[k]));
            if r != c {
                triplets.push(faer::sparse::Triplet::new(c, r, lower[k]));
            }
        }
        let mat = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).map_err(|e| {
            Error::Unresolvable {
                model: "plain Newton",
                reason: format!("assembling the Hessian: {e:?}"),
            }
        })?;
        rep.factorizations += 1;
        let lu = mat.sp_lu().map_err(|_| Error::NoConvergence {
            method: "plain Newton (singular Hessian)",
            iterations: rep.iterations,
            residual: gnorm,
        })?;
        let mut p: Vec<f64> = g.iter().map(|v| -v).collect();
        lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(&mut p, n, 1));
        if p.iter().any(|v| !v.is_finite()) {
            return Err(Error::NoConvergence {
                method: "plain Newton (singular Hessian)",
                iterations: rep.iterations,
                residual: gnorm,
            });
        }
        x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
        if inf_norm(&p) <= opts.step_tol {
            energy.gradient(x, &mut g);
            rep.gradient_norm = inf_norm(&g);
            rep.energy = energy.energy(x);
            return Ok(rep);
        }
    }
    Err(Error::NoConvergence {
        method: "plain Newton",
        iterations: rep.iterations,
        residual: inf_norm(&g),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of double wells w(x) = x⁴/4 − x²/2 coupled by springs c(x_{i+1} − x_i)²/2: the
    /// origin is a stationary point that is a maximum (c small), the minima are near ±1.
    struct Wells {
        n: usize,
        c: f64,
    }

    impl Energy for Wells {
        fn dim(&self) -> usize {
            self.n
        }
        fn energy(&self, x: &[f64]) -> f64 {
            let wells: f64 = x.iter().map(|v| v.powi(4) / 4.0 - v * v / 2.0).sum();
            let springs: f64 = x.windows(2).map(|w| 0.5 * self.c * (w[1] - w[0]).powi(2)).sum();
            wells + springs
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            for i in 0..self.n {
                g[i] = x[i].powi(3) - x[i];
                if i > 0 {
                    g[i] += self.c * (x[i] - x[i - 1]);
                }
                if i + 1 < self.n {
                    g[i] += self.c * (x[i] - x[i + 1]);
                }
            }
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            let mut p: Vec<(usize, usize)> = (0..self.n).map(|i| (i, i)).collect();
            p.extend((1..self.n).map(|i| (i, i - 1)));
            p
        }
        fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
            for i in 0..self.n {
                let deg = usize::from(i > 0) + usize::from(i + 1 < self.n);
                v[i] = 3.0 * x[i] * x[i] - 1.0 + self.c * deg as f64;
            }
            for k in 0..self.n.saturating_sub(1) {
                v[self.n + k] = -self.c;
            }
        }
    }

    #[test]
    fn plain_newton_accepts_the_maximum_the_stable_solver_does_not() {
        let e = Wells { n: 1, c: 0.0 };
        let opts = NewtonOptions::default();
        let mut x = vec![0.1];
        plain_newton(&e, &mut x, &opts).unwrap();
        assert!(x[0].abs() < 1e-10, "plain Newton converged to the maximum x = 0");
        let mut s = StableNewton::new(&e).unwrap();
        assert!(!s.is_stable(&e, &x).unwrap());
        let mut y = vec![0.1];
        let rep = s.minimize(&e, &mut y, &opts).unwrap();
        assert!((y[0].abs() - 1.0).abs() < 1e-10);
        assert!(rep.left_unstable_state());
        assert!(s.is_stable(&e, &y).unwrap());
    }

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

    #[test]
    fn a_pattern_without_diagonal_is_an_error() {
        struct NoDiag;
        impl Energy for NoDiag {
            fn dim(&self) -> usize {
                2
            }
            fn energy(&self, _: &[f64]) -> f64 {
                0.0
            }
            fn gradient(&self, _: &[f64], _: &mut [f64]) {}
            fn hessian_pattern(&self) -> Vec<(usize, usize)> {
                vec![(0, 0), (1, 0)]
            }
            fn hessian_values(&self, _: &[f64], _: &mut [f64]) {}
        }
        let err = StableNewton::new(&NoDiag).err().unwrap().to_string();
        assert!(err.contains("diagonal"), "{err}");
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
}
