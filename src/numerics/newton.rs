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
//! Far from convergence a dense Hessian (and, where the caller asks, a sparse one) is
//! factorised in single precision for the direction only (half the cost; the direction's error
//! does not limit the iteration there), and a step
//! whose promised decrease lies below the energy's roundoff is taken in full rather than shrunk
//! to nothing by the line search. A caller may watch the iterations
//! ([`StableNewton::minimize_watched`]): to cancel a long minimisation, or to stop a trial as
//! soon as it meets an indefinite Hessian.
//! The energy, gradient and Hessian come from an [`Energy`]; nothing here knows about physics.
//!
//! Large systems ([`LinearSolver::Auto`] from [`ITERATIVE_MIN_UNKNOWNS`] unknowns) take the
//! iterative path instead: CG steps; instabilities resolved where they are (unknowns past
//! their own fold jump along their axis and the avalanche they start is relaxed locally;
//! unstable groups move along their own lowest mode, found on a small patch), so that a step
//! with hundreds of jumps costs a few global iterations; a localised diagonal modification
//! where nothing local applies; and a factorisation-free certificate of positive definiteness
//! for Hessians that are Z-matrices ([`crate::numerics::pcg::certify_z_matrix`]), with the
//! direct path as the fallback wherever the certificate is not found. The acceptance rule is
//! the same.
//!
//! The code follows the two paths. This file holds the public types, the set-up of
//! [`StableNewton`] (symbolic analysis), its stability test and the dispatch of
//! [`StableNewton::minimize`], the backtracking line search every path uses, and
//! [`plain_newton`]; `newton/direct.rs` the direct path (sparse Cholesky factorisations, chord
//! and shifted steps, negative curvature by inverse iteration); `newton/iterative.rs` the
//! iterative path (CG steps, the modified steps, the certificate, the hand-over to the direct
//! path); `newton/local.rs` the local moves the iterative path makes (coordinate jumps and the
//! avalanches they start, local relaxation of a region, patch escapes, one-dimensional
//! descents). Each file holds the unit tests of its code; the test energies they share (chains
//! of double wells) are in `newton/wells.rs`.

use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::numerics::pcg::{SymmetricPattern, inf_norm};
use crate::numerics::sparse_llt::SparseLlt;

mod direct;
mod iterative;
mod local;
#[cfg(test)]
mod wells;

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
    /// Optional: a key that tells this energy apart from the others a solver sees (two
    /// energies with the same key have the same Hessian at every state), such as the bits of
    /// the load parameter of a family of energies. Offering it lets [`StableNewton`] skip
    /// evaluating the Hessian again at the state where it evaluated it last (an accepted
    /// state's stability test, and the tangent solve of the next load step at that state). The
    /// default offers nothing.
    fn key(&self) -> Option<u64> {
        None
    }
    /// Optional: the energy as a function of unknown `i` alone, all others held at `x`,
    /// evaluated at x_i = `s`: (E, dE/ds, d²E/ds²), E up to a constant independent of s and
    /// `f64::INFINITY` outside the domain. Offering it (at a cost independent of `dim()`) lets
    /// the iterative path move an unknown that is unstable on its own straight to its next
    /// minimum. The default offers nothing.
    fn along_coordinate(&self, _x: &[f64], _i: usize, _s: f64) -> Option<(f64, f64, f64)> {
        None
    }
    /// Optional: the sum of the energy's terms that involve any unknown of `set` (sorted, no
    /// duplicates) at `x`, `f64::INFINITY` outside the domain, with the gradient components of
    /// those unknowns written into `grad` (length `set.len()`). Offering it (at a cost of the
    /// order of `set.len()`) lets the iterative path move a small unstable group of unknowns
    /// along its direction of negative curvature to the next minimum on that line. The
    /// default offers nothing.
    fn local_energy(&self, _x: &[f64], _set: &[usize], _grad: &mut [f64]) -> Option<f64> {
        None
    }
}

/// What [`StableNewton::minimize_watched`] calls during a minimisation with the report so far;
/// an error stops the minimisation.
pub type Watch<'a> = &'a mut dyn FnMut(&NewtonReport) -> Result<()>;

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
    /// How the linear systems are solved and definiteness is decided.
    pub linear: LinearSolver,
}

/// How [`StableNewton`] solves its linear systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LinearSolver {
    /// [`LinearSolver::Iterative`] from [`ITERATIVE_MIN_UNKNOWNS`] unknowns, otherwise
    /// [`LinearSolver::Direct`].
    #[default]
    Auto,
    /// Sparse Cholesky factorisations: the step solves and the stability test in one.
    Direct,
    /// Jacobi-preconditioned conjugate gradients for the steps, a localised diagonal
    /// modification where the Hessian is indefinite, and the factorisation-free certificate of
    /// [`crate::numerics::pcg::certify_z_matrix`] for the stability of accepted states
    /// (Cholesky only where that certificate does not apply or is not found).
    Iterative,
}

/// Systems from this many unknowns use the iterative path under [`LinearSolver::Auto`].
pub const ITERATIVE_MIN_UNKNOWNS: usize = 4096;

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            gradient_tol: 1e-10,
            step_tol: 1e-12,
            max_iterations: 500,
            linear: LinearSolver::Auto,
        }
    }
}

/// How a minimisation went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonReport {
    /// Newton iterations taken.
    pub iterations: usize,
    /// Cholesky factorisations computed (failed attempts and single-precision ones included,
    /// reused ones not).
    pub factorizations: usize,
    /// Iterations at which the Hessian was not positive definite (the state was unstable).
    pub indefinite_iterations: usize,
    /// Steps along a direction of negative curvature (leaving a saddle or maximum).
    pub negative_curvature_steps: usize,
    /// Largest gradient component at the accepted state.
    pub gradient_norm: f64,
    /// Energy at the accepted state.
    pub energy: f64,
    /// Times the iterative path handed over to the direct one (a stability certificate not
    /// found, a failed line search); zero on the direct path.
    pub direct_fallbacks: usize,
    /// Unknowns moved to their next minimum along their own axis (iterative path).
    pub coordinate_jumps: usize,
    /// Unstable groups of unknowns moved along their own negative-curvature mode (iterative
    /// path).
    pub patch_escapes: usize,
}

impl NewtonReport {
    /// Whether the start state was unstable, so that the solver had to move to another
    /// stable state (an instability, a jump).
    pub fn left_unstable_state(&self) -> bool {
        self.indefinite_iterations > 0
    }
}

/// A numeric Cholesky factorisation, shared between the cache and its users.
type Factor = Arc<direct::Cholesky>;

/// The sparse Hessian of an [`Energy`] with its symbolic Cholesky factorisation.
pub struct StableNewton {
    n: usize,
    /// The symbolic analysis of the Hessian's pattern (shift slots included).
    sparse: Arc<SparseLlt>,
    /// For a mostly full pattern: each value's column-major position in a dense n × n matrix
    /// (the direct path then factorises densely, see `newton/direct.rs`).
    dense: Option<Vec<usize>>,
    /// Storage of a dense factor no longer in use, for the next one.
    spare: Option<Vec<f64>>,
    /// Storage of a single-precision dense factor no longer in use.
    spare_single: Option<Vec<f32>>,
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
    /// Row structure of the Hessian for the iterative path.
    rows: SymmetricPattern,
    /// The Hessian values of the last state certified positive definite without factorisation,
    /// and the certificate (see [`certify_z_matrix`]); the certificate is kept as the start for
    /// the next one.
    ///
    /// [`certify_z_matrix`]: crate::numerics::pcg::certify_z_matrix
    certified: Option<(Vec<f64>, f64)>,
    certificate: Vec<f64>,
    /// The Hessian values in row order (see [`SymmetricPattern::gather`]).
    row_values: Vec<f64>,
    /// The state the last iterative minimisation accepted and how far it moved from its start:
    /// where a continuation restarts from that state, the first CG solve starts from that move
    /// (see [`StableNewton::minimize`]).
    last_move: Option<(Vec<f64>, Vec<f64>)>,
    /// How [`StableNewton::is_stable`] and [`StableNewton::solve_at`] decide (the
    /// minimisation takes its own from [`NewtonOptions`]).
    linear: LinearSolver,
    /// The key ([`Energy::key`]) of the energy and the state whose Hessian the values hold,
    /// where known.
    loaded: Option<(u64, Vec<f64>)>,
    /// Whether a minimisation on the direct path starts with chord steps on the last
    /// positive-definite factorisation (see [`StableNewton::set_warm_start`]).
    warm: bool,
    /// Whether Newton directions far from convergence come from single-precision sparse
    /// factorisations (see [`StableNewton::set_single_precision_directions`]).
    single_sparse: bool,
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
        let rows = SymmetricPattern::from_lower(n, &pattern[..n_pattern]);
        let sparse = Arc::new(SparseLlt::analyse(n, &pattern).map_err(fail)?);
        let dense = direct::dense_layout(n, &pattern, n_pattern);
        Ok(Self {
            n,
            sparse,
            dense,
            spare: None,
            spare_single: None,
            diagonal: (n_pattern..n_pattern + n).collect(),
            values: vec![0.0; n_pattern + n],
            last_shift: 0.0,
            cache: None,
            computed: 0,
            rows,
            certified: None,
            certificate: Vec::new(),
            row_values: Vec::new(),
            last_move: None,
            linear: LinearSolver::Auto,
            loaded: None,
            warm: false,
            single_sparse: false,
        })
    }

    /// Decide stability and solve at a state ([`Self::is_stable`], [`Self::solve_at`]) as
    /// `linear` says: [`LinearSolver::Direct`] for a system whose Hessian is not a Z-matrix
    /// (the iterative path's certificate never applies), however large.
    pub fn set_linear(&mut self, linear: LinearSolver) {
        self.linear = linear;
    }

    /// Whether a minimisation on the direct path starts with chord steps on the last
    /// positive-definite factorisation, computed at an earlier state (the one accepted last,
    /// on a path that follows a load), instead of factorising at its start. The chord steps
    /// go on while each cuts the gradient by [`direct::CHORD_CONTRACTION`]; acceptance still
    /// factorises the Hessian at the accepted state itself, so that only the cost changes:
    /// one factorisation fewer per load step where the step converges on the old factor.
    /// Off by default. A caller that reads the first iterations for a verdict (a bisection
    /// trial that stops at the first indefinite Hessian) turns it off for that minimisation:
    /// chord steps would postpone the first look at the Hessian.
    pub fn set_warm_start(&mut self, on: bool) {
        self.warm = on;
    }

    /// Whether the direct path takes the Newton directions far from convergence (largest
    /// gradient component above 10⁴ times its tolerance) from a single-precision sparse
    /// factorisation: half the memory traffic of the double-precision one. The acceptance,
    /// every stability test and every cached factor still rest on double precision, so only
    /// the iterates before convergence change. Off by default (dense Hessians always do it).
    pub fn set_single_precision_directions(&mut self, on: bool) {
        self.single_sparse = on;
    }

    /// Whether minimisations start warm ([`Self::set_warm_start`]).
    pub fn warm_start(&self) -> bool {
        self.warm
    }

    /// Put the Hessian of `energy` at `x` into the values, unless they hold it already (the
    /// same energy by [`Energy::key`] at the same state).
    fn load_hessian(&mut self, energy: &impl Energy, x: &[f64]) {
        let key = energy.key();
        if let (Some(key), Some((loaded, at))) = (key, &self.loaded)
            && key == *loaded
            && at[..] == *x
        {
            return;
        }
        let n_pattern = self.values.len() - self.n;
        energy.hessian_values(x, &mut self.values[..n_pattern]);
        let (_, mut at) = self.loaded.take().unwrap_or_default();
        if let Some(key) = key {
            at.clear();
            at.extend_from_slice(x);
            self.loaded = Some((key, at));
        }
    }

    /// Numeric factorisations computed so far (single-precision ones included, reused ones
    /// not).
    pub fn factorizations(&self) -> usize {
        self.computed
    }

    /// Whether the iterative path serves this system.
    fn iterative(&self, linear: LinearSolver) -> bool {
        match linear {
            LinearSolver::Auto => self.n >= ITERATIVE_MIN_UNKNOWNS,
            LinearSolver::Direct => false,
            LinearSolver::Iterative => true,
        }
    }

    /// Whether the Hessian of `energy` at `x` is positive definite (the equilibrium is stable).
    ///
    /// # Errors
    /// Assembly failures (not expected).
    pub fn is_stable(&mut self, energy: &impl Energy, x: &[f64]) -> Result<bool> {
        let n_pattern = self.values.len() - self.n;
        self.load_hessian(energy, x);
        if let Some((v, _)) = &self.certified
            && v[..] == self.values[..n_pattern]
        {
            return Ok(true);
        }
        if self.iterative(self.linear)
            && let (Some(definite), _) = self.certify()
        {
            return Ok(definite);
        }
        Ok(self.factor(0.0)?.is_some())
    }

    /// Solve `H(x) y = rhs` in place (the Hessian of `energy` at `x`) with the direct path's
    /// factorisation, when the direct path serves this system and `H(x)` is positive definite;
    /// otherwise `false` and `rhs` unchanged. At a state just certified by [`Self::is_stable`]
    /// the factorisation is the cached one: the solve costs no factorisation.
    ///
    /// # Errors
    /// Assembly failures (not expected).
    pub fn solve_at(&mut self, energy: &impl Energy, x: &[f64], rhs: &mut [f64]) -> Result<bool> {
        if self.iterative(self.linear) {
            return Ok(false);
        }
        self.load_hessian(energy, x);
        match self.factor(0.0)? {
            Some(l) => {
                l.solve(rhs);
                Ok(true)
            }
            None => Ok(false),
        }
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
        self.minimize_watched(energy, x, opts, &mut |_| Ok(()))
    }

    /// [`Self::minimize`] with a watcher: `watch` sees the report at the start of every
    /// iteration and right after an iteration found the Hessian indefinite, and stops the
    /// minimisation (`x` left at the current iterate) by returning an error, which is passed
    /// on: cancellation inside a long minimisation, or a caller that only wants to know
    /// whether a stable state lies near the start.
    ///
    /// # Errors
    /// As [`Self::minimize`], and whatever `watch` returns.
    ///
    /// # Panics
    /// If `x.len() != energy.dim()`.
    pub fn minimize_watched(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
        watch: Watch<'_>,
    ) -> Result<NewtonReport> {
        assert_eq!(x.len(), self.n, "state length must equal the energy's dimension");
        let e0 = energy.energy(x);
        if !e0.is_finite() {
            return Err(Error::Unresolvable {
                model: "stable Newton",
                reason: "the start state is outside the energy's domain".into(),
            });
        }
        let start = self.computed;
        let iterative = self.iterative(opts.linear);
        let mut rep = if iterative {
            let previous = self
                .last_move
                .take()
                .filter(|(end, _)| end.as_slice() == &*x)
                .map(|(_, delta)| delta);
            let start_x = x.to_vec();
            let rep = self.minimize_iterative(energy, x, opts, e0, previous.as_deref(), watch)?;
            let delta = x.iter().zip(&start_x).map(|(a, b)| a - b).collect();
            self.last_move = Some((x.to_vec(), delta));
            rep
        } else {
            self.minimize_inner(energy, x, opts, e0, watch)?
        };
        rep.factorizations = self.computed - start;
        Ok(rep)
    }
}

/// Backtracking (Armijo) line search on the energy from the full step `p` at `x` (energy
/// `e0`, directional derivative `slope` < 0): halves the step until the energy falls enough,
/// then moves `x` and returns the new energy; `None` (x unchanged) when no step down to 1e-20
/// of `p` lowers it (roundoff level). No extrapolation: a longer step could carry a metastable
/// part of the system over its energy barrier, and the state must follow the branch an
/// experiment follows.
fn backtrack(
    energy: &impl Energy,
    x: &mut [f64],
    p: &[f64],
    e0: f64,
    slope: f64,
    trial: &mut [f64],
) -> Option<f64> {
    let e1 = armijo(e0, slope, 1e-20, |t| {
        for ((ti, xi), pi) in trial.iter_mut().zip(x.iter()).zip(p) {
            *ti = xi + t * pi;
        }
        energy.energy(trial)
    })?;
    x.copy_from_slice(trial);
    Some(e1)
}

/// The Armijo rule: tries the steps t = 1, 1/2, 1/4, … down to `smallest`, evaluating
/// `energy_at(t)` (which sets up the trial state), and returns the energy of the first that
/// lies below e0 + 10⁻⁴·t·`slope` (with a roundoff slack of 10⁻¹⁴·max(|e0|, 1)); `None` when
/// none does. The last call of `energy_at` is the accepted step.
fn armijo(e0: f64, slope: f64, smallest: f64, mut energy_at: impl FnMut(f64) -> f64) -> Option<f64> {
    let slack = 1e-14 * e0.abs().max(1.0);
    let mut t = 1.0;
    while t >= smallest {
        let e1 = energy_at(t);
        if e1.is_finite() && e1 <= e0 + 1e-4 * t * slope + slack {
            return Some(e1);
        }
        t *= 0.5;
    }
    None
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
    use super::wells::Wells;
    use super::*;

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
}
