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

use faer::Side;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use nalgebra::DMatrix;

use super::envelope::Envelope;
use std::collections::VecDeque;
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::numerics::pcg::{
    Operator, PcgEnd, SymmetricPattern, certify_z_matrix, dot, inf_norm, pcg, pcg_with_curvature,
};

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
    /// Row structure of the Hessian for the iterative path.
    rows: SymmetricPattern,
    /// The Hessian values of the last state certified positive definite without factorisation,
    /// and the certificate (see [`certify_z_matrix`]); the certificate is kept as the start for
    /// the next one.
    certified: Option<(Vec<f64>, f64)>,
    certificate: Vec<f64>,
    /// The Hessian values in row order (see [`SymmetricPattern::gather`]).
    row_values: Vec<f64>,
    /// The state the last iterative minimisation accepted and how far it moved from its start:
    /// where a continuation restarts from that state, the first CG solve starts from that move
    /// (see [`StableNewton::minimize`]).
    last_move: Option<(Vec<f64>, Vec<f64>)>,
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
            rows,
            certified: None,
            certificate: Vec::new(),
            row_values: Vec::new(),
            last_move: None,
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
        if let Some((v, _)) = &self.certified
            && v[..] == self.values[..n_pattern]
        {
            return Ok(true);
        }
        if self.n >= ITERATIVE_MIN_UNKNOWNS
            && let (Some(definite), _) = self.certify()
        {
            return Ok(definite);
        }
        Ok(self.factor(0.0)?.is_some())
    }

    /// The iteration's Hessian (gathered into row order) with its diagonal and off-diagonal
    /// sums, for the local moves.
    fn tangent<'a>(&'a self, diag: &'a [f64], off: &'a [f64]) -> Tangent<'a> {
        Tangent {
            pattern: &self.rows,
            rows: &self.row_values,
            diag,
            off,
        }
    }

    /// Decide the definiteness of the Hessian in `self.values` without factorising when it is
    /// a Z-matrix ([`certify_z_matrix`]); `None` when undecided or not a Z-matrix. With
    /// `Some(true)` comes a bound on ‖H⁻¹‖∞.
    fn certify(&mut self) -> (Option<bool>, f64) {
        let n_pattern = self.values.len() - self.n;
        self.rows.gather(&self.values[..n_pattern], &mut self.row_values);
        let mut diag = vec![0.0; self.n];
        let mut off = vec![0.0; self.n];
        let z_matrix = self
            .rows
            .diagonal_and_off_sums(&self.row_values, &mut diag, &mut off);
        self.certify_gathered(&diag, z_matrix)
    }

    /// [`StableNewton::certify`] with the values already spread into row order and their
    /// diagonal and Z-matrix property at hand (as the iterative path has them each iteration).
    fn certify_gathered(&mut self, diag: &[f64], z_matrix: bool) -> (Option<bool>, f64) {
        let n_pattern = self.values.len() - self.n;
        let values = &self.values[..n_pattern];
        if let Some((v, bound)) = &self.certified
            && v[..] == values[..]
        {
            return (Some(true), *bound);
        }
        if !z_matrix {
            return (None, f64::INFINITY);
        }
        let (found, bound) =
            certify_z_matrix(&self.rows, &self.row_values, diag, &mut self.certificate, 2000);
        if found == Some(true) {
            let mut v = self.certified.take().map(|c| c.0).unwrap_or_default();
            v.clear();
            v.extend_from_slice(values);
            self.certified = Some((v, bound));
        }
        (found, bound)
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
        assert_eq!(x.len(), self.n, "state length must equal the energy's dimension");
        let e0 = energy.energy(x);
        if !e0.is_finite() {
            return Err(Error::Unresolvable {
                model: "stable Newton",
                reason: "the start state is outside the energy's domain".into(),
            });
        }
        let start = self.computed;
        let iterative = match opts.linear {
            LinearSolver::Auto => self.n >= ITERATIVE_MIN_UNKNOWNS,
            LinearSolver::Direct => false,
            LinearSolver::Iterative => true,
        };
        let mut rep = if iterative {
            let previous = self
                .last_move
                .take()
                .filter(|(end, _)| end.as_slice() == &*x)
                .map(|(_, delta)| delta);
            let start_x = x.to_vec();
            let rep = self.minimize_iterative(energy, x, opts, e0, previous.as_deref())?;
            let delta = x.iter().zip(&start_x).map(|(a, b)| a - b).collect();
            self.last_move = Some((x.to_vec(), delta));
            rep
        } else {
            self.minimize_inner(energy, x, opts, e0)?
        };
        rep.factorizations = self.computed - start;
        Ok(rep)
    }

    /// The iterative path ([`LinearSolver::Iterative`]). Each iteration, in this order:
    /// - jumps: the unknowns whose rows are not diagonally dominant (only these can be near a
    ///   fold) are descended along their own axes, others held ([`Energy::along_coordinate`]);
    ///   those whose descent crosses non-positive curvature have no minimum left nearby and
    ///   move to their next one, and the jump spreads to their neighbours as it does in the
    ///   system (an avalanche, resolved locally: [`settle`] relaxes the region around it with
    ///   a small stable Newton, [`relax_region`]);
    /// - collective instabilities (every unknown stable on its own axis, the group not): the
    ///   group's lowest mode is found on a small patch of the Hessian and the patch moves
    ///   along it to the next minimum ([`escape_patches`], [`escape_around`]); where no patch
    ///   shows it, the state moves down the line of negative curvature CG met;
    /// - a few unknowns far out of balance (at least [`HOT_FRACTION`] of the largest gradient
    ///   component, at most n/256 + 16 of them) are relaxed locally with their surroundings
    ///   ([`settle`]), not in two iterations running nor in the first;
    /// - otherwise a Newton step by Jacobi-preconditioned CG, with a backtracking line search
    ///   on the energy (the first CG solve of a continuation starts from the last step's move,
    ///   `guess`, scaled to the minimum of the quadratic model along it);
    /// - where H is indefinite and none of the above applies, the rows that are not diagonally
    ///   dominant get their net diagonal h_ii − Σ_{j≠i}|h_ij| replaced by its magnitude (a
    ///   strictly diagonally dominant, positive-definite modification): the unstable unknowns
    ///   move downhill, damped, while the rest takes its Newton step.
    ///
    /// The local moves need [`Energy::along_coordinate`] and [`Energy::local_energy`]; without
    /// them the path still works, by the modified steps alone (slowly near many folds).
    ///
    /// A state is accepted with a small gradient, a certificate of positive definiteness
    /// ([`certify_z_matrix`]) and a Newton correction bounded by ‖H⁻¹‖∞·‖g‖∞ (from the same
    /// certificate) below √gradient_tol. Where no certificate is found (or H is not a
    /// Z-matrix) the direct path takes over from the current state and decides by
    /// factorisation.
    fn minimize_iterative(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
        mut e0: f64,
        guess: Option<&[f64]>,
    ) -> Result<NewtonReport> {
        let n = self.n;
        let n_pattern = self.values.len() - n;
        let mut rep = NewtonReport::default();
        let mut g = vec![0.0; n];
        let mut rhs = vec![0.0; n];
        let mut p = vec![0.0; n];
        let mut trial = vec![0.0; n];
        let mut diag = vec![0.0; n];
        let mut off = vec![0.0; n];
        let mut inv = vec![0.0; n];
        let mut extra = vec![0.0; n];
        let mut direction = vec![0.0; n];
        let mut line_gradient = vec![0.0; n];
        let mut local_moves = false;
        let mut hot_settled = false;
        let max_cg = 2000.min(10 * n.max(10));
        let hand_over = |this: &mut Self, x: &mut [f64], mut rep: NewtonReport| -> Result<NewtonReport> {
            let direct = this.minimize_inner(energy, x, opts, energy.energy(x))?;
            rep.iterations += direct.iterations;
            rep.indefinite_iterations += direct.indefinite_iterations;
            rep.negative_curvature_steps += direct.negative_curvature_steps;
            rep.gradient_norm = direct.gradient_norm;
            rep.energy = direct.energy;
            rep.direct_fallbacks += 1;
            Ok(rep)
        };
        while rep.iterations < opts.max_iterations {
            rep.iterations += 1;
            energy.gradient(x, &mut g);
            let gnorm = inf_norm(&g);
            energy.hessian_values(x, &mut self.values[..n_pattern]);
            self.rows.gather(&self.values[..n_pattern], &mut self.row_values);
            let z_matrix = self
                .rows
                .diagonal_and_off_sums(&self.row_values, &mut diag, &mut off);
            if gnorm <= opts.gradient_tol {
                // Converged if certified definite with a small Newton correction.
                let (definite, bound) = self.certify_gathered(&diag, z_matrix);
                if definite == Some(true) && gnorm * bound <= opts.gradient_tol.sqrt() {
                    rep.gradient_norm = gnorm;
                    rep.energy = e0;
                    return Ok(rep);
                }
                if definite.is_none() {
                    return hand_over(self, x, rep);
                }
            }
            let mut definite = diag.iter().all(|&d| d > 0.0);
            // A few unknowns far out of balance while the rest is nearly balanced (never in the
            // first iteration: its step is the smooth response to the load, which decides
            // what follows; never twice running, so that the global steps go on; not near
            // convergence, where the Newton steps converge fast).
            let mut hot = Vec::new();
            if rep.iterations > 1 && !hot_settled && gnorm > 1e4 * opts.gradient_tol {
                hot.extend((0..n).filter(|&i| g[i].abs() >= HOT_FRACTION * gnorm));
                if hot.len() > n / 256 + 16 {
                    hot.clear();
                }
            }
            hot_settled = false;
            // Unknowns past their own fold jump first (with the avalanche they start), the
            // unbalanced ones among the candidates. From a stable start the first step is
            // Newton's: the smooth response moves the neighbours too, and a spring's fold is
            // judged against where they go.
            let jumps = if rep.iterations > 1 || !definite {
                jump_along_coordinates(energy, x, &self.tangent(&diag, &off), &g, &hot, &mut rep)
            } else {
                Jumps::default()
            };
            if jumps.moved {
                rep.indefinite_iterations += 1;
                local_moves = true;
                e0 = energy.energy(x);
                continue;
            }
            if !definite {
                rep.indefinite_iterations += 1;
                if escape_patches(energy, x, &self.tangent(&diag, &off), &mut rep) {
                    local_moves = true;
                    e0 = energy.energy(x);
                    continue;
                }
            }
            // The unbalanced ones, stable on their axes: typically pushed by the last step deep
            // into a steep, strongly curved part of their potential (a repulsive wall), from
            // where each Newton step covers only a fraction of the way back. Relaxed locally
            // with their surroundings ([`settle`]), at the cost of their region instead of a
            // global iteration per fraction.
            if !hot.is_empty() && !jumps.held && settle(energy, x, &self.tangent(&diag, &off), hot, &mut rep)
            {
                hot_settled = true;
                local_moves = true;
                e0 = energy.energy(x);
                continue;
            }
            // Inexact Newton: while local moves keep reshaping the state, a rough solve serves.
            let forcing = if local_moves { 1e-2 } else { 1e-4 };
            local_moves = false;
            let target = (forcing * gnorm).max(0.2 * opts.gradient_tol);
            rhs.iter_mut().zip(&g).for_each(|(r, gi)| *r = -gi);
            p.fill(0.0);
            if definite {
                inv.iter_mut().zip(&diag).for_each(|(m, d)| *m = 1.0 / d);
                let op = Operator {
                    pattern: &self.rows,
                    values: &self.row_values,
                    extra_diagonal: &[],
                };
                // The first step of a continuation starts CG from the last accepted move,
                // scaled to the minimum of the quadratic model along it: the smooth response
                // to a load step changes little from one step to the next.
                if let (1, Some(p0)) = (rep.iterations, guess) {
                    let curvature = op.apply_dot(p0, &mut direction);
                    let alpha = -dot(&g, p0) / curvature;
                    if curvature > 0.0 && alpha > 0.0 && alpha.is_finite() {
                        p.iter_mut().zip(p0).for_each(|(pi, qi)| *pi = alpha * qi);
                    }
                }
                // A direction of non-positive curvature shows H indefinite: modified step below.
                definite = pcg_with_curvature(&op, &inv, &rhs, &mut p, target, max_cg, &mut direction).0
                    != PcgEnd::NegativeCurvature;
                if !definite {
                    rep.indefinite_iterations += 1;
                    // A local unstable mode, or else down the line of negative curvature CG
                    // met (a direction d with dᵀHd ≤ 0, spread over the system).
                    if escape_patches(energy, x, &self.tangent(&diag, &off), &mut rep)
                        || escape_around(energy, x, &self.tangent(&diag, &off), &direction, &mut rep)
                        || descend_line(energy, x, &mut direction, &mut trial, &mut line_gradient)
                    {
                        rep.negative_curvature_steps += 1;
                        local_moves = true;
                        e0 = energy.energy(x);
                        continue;
                    }
                }
            }
            if definite {
                if inf_norm(&p) <= opts.step_tol {
                    if self.certify_gathered(&diag, z_matrix).0 != Some(true) {
                        // A stationary point that is not a minimum: leave it along a local
                        // unstable mode if one is found, else decide by factorisation.
                        if escape_patches(energy, x, &self.tangent(&diag, &off), &mut rep) {
                            rep.indefinite_iterations += 1;
                            e0 = energy.energy(x);
                            continue;
                        }
                        return hand_over(self, x, rep);
                    }
                    x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += pi);
                    rep.gradient_norm = gnorm;
                    rep.energy = energy.energy(x);
                    return Ok(rep);
                }
                match backtrack(energy, x, &p, e0, dot(&g, &p), &mut trial) {
                    Some(e1) => e0 = e1,
                    None => {
                        // No decrease along the step: at roundoff level already.
                        if self.certify_gathered(&diag, z_matrix).0 == Some(true) {
                            rep.gradient_norm = gnorm;
                            rep.energy = e0;
                            return Ok(rep);
                        }
                        return hand_over(self, x, rep);
                    }
                }
                continue;
            }
            let floor = 1e-8 * inf_norm(&diag).max(1e-300);
            for i in 0..n {
                let net = diag[i] - off[i];
                extra[i] = if net > 0.0 {
                    0.0
                } else {
                    off[i] + (-net).max(floor) - diag[i]
                };
                inv[i] = 1.0 / (diag[i] + extra[i]);
            }
            let op = Operator {
                pattern: &self.rows,
                values: &self.row_values,
                extra_diagonal: &extra,
            };
            p.fill(0.0);
            if pcg(&op, &inv, &rhs, &mut p, target, max_cg).0 == PcgEnd::NegativeCurvature {
                return hand_over(self, x, rep);
            }
            let slope = dot(&g, &p);
            if slope >= 0.0 || slope.is_nan() {
                return hand_over(self, x, rep);
            }
            match backtrack(energy, x, &p, e0, slope, &mut trial) {
                Some(e1) => e0 = e1,
                None => return hand_over(self, x, rep),
            }
        }
        hand_over(self, x, rep)
    }

    fn minimize_inner(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
        mut e0: f64,
    ) -> Result<NewtonReport> {
        let n = self.n;
        let n_pattern = self.values.len() - n;
        let mut rep = NewtonReport::default();
        let mut g = vec![0.0; n];
        let mut p = vec![0.0; n];
        let mut trial = vec![0.0; n];
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
                let accepted = match backtrack(energy, x, &p, e0, dot(&g, &p), &mut trial) {
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

/// Move every unknown past its own fold downhill along its axis to its next minimum, one after
/// the other (coordinate descent; each move lowers the energy and stops at the first minimum
/// met, so no barrier is crossed). The candidates are the rows that are not diagonally
/// dominant and the `unbalanced` unknowns; one jumps when its descent crosses non-positive
/// curvature. The jump spreads as it
/// does in the system: the neighbours (in the Hessian's pattern) of an unknown that jumped are
/// relaxed along their axes in turn, and pass the jump on when they jumped as well. An
/// avalanche thus costs work in proportion to the unknowns it moves, not one global iteration
/// per generation; [`settle`] then relaxes its surroundings. Returns what happened
/// ([`Jumps`]): nothing also when the energy does not offer [`Energy::along_coordinate`].
fn jump_along_coordinates(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    g: &[f64],
    unbalanced: &[usize],
    rep: &mut NewtonReport,
) -> Jumps {
    let Tangent {
        pattern, diag, off, ..
    } = *h;
    let n = x.len();
    let mut out = Jumps::default();
    if n == 0 || energy.along_coordinate(x, 0, x[0]).is_none() {
        return out;
    }
    // Candidates: the rows that are not diagonally dominant (h_ii ≤ Σ|h_ij|), among them every
    // row with h_ii ≤ 0: the unknowns near a fold. One whose minimum is taken away by its
    // neighbours while its row is still dominant enters this set within a step or two, or at
    // once when it is among the `unbalanced` (its gradient component far above the rest's).
    let mut queued = vec![false; n];
    let mut queue: VecDeque<usize> = (0..n).filter(|&i| diag[i] <= off[i]).collect();
    queue.iter().for_each(|&i| queued[i] = true);
    let fold_seeds = queue.len();
    for &i in unbalanced {
        if !queued[i] {
            queued[i] = true;
            queue.push_back(i);
        }
    }
    if queue.is_empty() {
        return out;
    }
    let seeds = queue.len();
    // Each unknown may move a few times as its neighbours settle; beyond that the global
    // iteration takes over.
    let mut budget = 4 * n + 64;
    let mut jumped_set = Vec::new();
    let mut popped = 0;
    while let Some(i) = queue.pop_front() {
        queued[i] = false;
        popped += 1;
        if budget == 0 {
            break;
        }
        budget -= 1;
        let Some((to, jumped)) = descend_1d(|s| energy.along_coordinate(x, i, s), x[i]) else {
            continue;
        };
        let seed = popped <= seeds;
        // A candidate still stable on its axis jumps only when no neighbour has overshot its
        // own balance against the move (g_j pushing it back): such a neighbour would, at
        // equilibrium, pull less, and the spring might keep a minimum. Newton settles those
        // first. (From a state every unknown wants to leave in the same sense, as after a
        // uniform load step, a jump found with the neighbours held is a jump at equilibrium
        // too: the neighbours only follow.)
        if jumped && seed && diag[i] > 0.0 {
            let sense = -g[i].signum();
            if pattern
                .columns(i)
                .any(|j| j != i && g[j] * sense > 1e-3 * g[i].abs())
            {
                out.held |= popped > fold_seeds;
                continue;
            }
        }
        // A candidate that only settles stays for the Newton step; a neighbour of a jump moves.
        if jumped || !seed {
            x[i] = to;
        }
        if jumped {
            rep.coordinate_jumps += 1;
            jumped_set.push(i);
            for j in pattern.columns(i) {
                if j != i && !queued[j] {
                    queued[j] = true;
                    queue.push_back(j);
                }
            }
        }
    }
    out.moved = !jumped_set.is_empty();
    settle(energy, x, h, jumped_set, rep);
    out
}

/// What [`jump_along_coordinates`] did.
#[derive(Debug, Default, Clone, Copy)]
struct Jumps {
    /// Some unknown jumped.
    moved: bool,
    /// Some unbalanced candidate past its own fold was held back for the Newton step (a
    /// neighbour out of balance against its move).
    held: bool,
}

/// The Hessian of one iteration of the iterative path, as the local moves read it: its
/// pattern, its values in row order, its diagonal and its off-diagonal absolute row sums
/// Σ_{j≠i} |h_ij|.
#[derive(Clone, Copy)]
struct Tangent<'a> {
    pattern: &'a SymmetricPattern,
    rows: &'a [f64],
    diag: &'a [f64],
    off: &'a [f64],
}

/// Unknowns whose gradient component is at least this fraction of the largest are relaxed
/// locally when they are few (the iterative path of [`StableNewton::minimize`]).
const HOT_FRACTION: f64 = 0.1;

/// Rings of neighbours around moved unknowns that [`settle`] relaxes.
const SETTLE_RINGS: usize = 4;

/// Largest connected region that [`settle`] relaxes.
const MAX_REGION: usize = 400;

/// Newton iterations per region in [`settle`] at most.
const SETTLE_ITERATIONS: usize = 40;

/// Let the surroundings of unknowns that just moved (jumped, or escaped an instability) settle
/// before the next global step: each connected region of the unknowns within [`SETTLE_RINGS`]
/// of them is relaxed on its own with the rest of the system held ([`relax_region`]). The
/// nonlinear part of the response to a jump is local (the neighbours follow, and some of them
/// lose stability and jump in turn: an avalanche); resolving it here costs work in proportion
/// to the region, where every global step costs work in proportion to the whole system. The
/// global Newton step that follows corrects the smooth remainder. Returns whether anything
/// moved.
fn settle(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    moved: Vec<usize>,
    rep: &mut NewtonReport,
) -> bool {
    let pattern = h.pattern;
    if moved.is_empty() || energy.local_energy(x, &moved[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut relaxed = false;
    let n = x.len();
    let mut mark = vec![false; n];
    let mut region = Vec::new();
    for i in moved {
        if !mark[i] {
            mark[i] = true;
            region.push(i);
        }
    }
    for _ in 0..SETTLE_RINGS {
        add_ring(pattern, &mut region, &mut mark);
    }
    let mut seen = vec![false; n];
    for &s0 in &region {
        if seen[s0] {
            continue;
        }
        let mut comp = component(pattern, s0, &mark, &mut seen, usize::MAX);
        if comp.len() <= MAX_REGION {
            comp.sort_unstable();
            relaxed |= relax_region(energy, x, h, &comp, rep);
        }
    }
    relaxed
}

/// The unknowns connected to `s0` through the pattern within `member` (breadth first, `s0`
/// included), marked in `seen`, stopping once more than `cap` are found.
fn component(
    pattern: &SymmetricPattern,
    s0: usize,
    member: &[bool],
    seen: &mut [bool],
    cap: usize,
) -> Vec<usize> {
    seen[s0] = true;
    let mut comp = vec![s0];
    let mut k = 0;
    while k < comp.len() && comp.len() <= cap {
        let i = comp[k];
        k += 1;
        for j in pattern.columns(i) {
            if member[j] && !seen[j] {
                seen[j] = true;
                comp.push(j);
            }
        }
    }
    comp
}

/// Add to `set` the neighbours of its unknowns not yet in `seen` (one ring), marking them.
/// Returns whether any was added.
fn add_ring(pattern: &SymmetricPattern, set: &mut Vec<usize>, seen: &mut [bool]) -> bool {
    let ring: Vec<usize> = set
        .iter()
        .flat_map(|&i| pattern.columns(i))
        .filter(|&j| !seen[j])
        .collect();
    let before = set.len();
    for j in ring {
        if !seen[j] {
            seen[j] = true;
            set.push(j);
        }
    }
    set.len() > before
}

/// Grow `patch` ring by ring (up to [`PATCH_RINGS`] rings, at most [`MAX_PATCH`] unknowns)
/// until its principal submatrix of H shows negative curvature ([`negative_mode`]), and then
/// move it along that mode to the next minimum ([`descend_along`]); the unknowns moved are
/// appended to `escaped`. A group's unstable mode reaches into the stable unknowns around it
/// (the Schur complement of the rest subtracts from the group's block), hence the growth.
fn escape_patch(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    mut patch: Vec<usize>,
    seen: &mut [bool],
    escaped: &mut Vec<usize>,
    rep: &mut NewtonReport,
) {
    if patch.len() > MAX_PATCH {
        return;
    }
    // Rings up to the largest patch within the size limit, each unknown with its ring.
    let mut ring_of = vec![0; patch.len()];
    let mut testable = patch.len();
    for ring in 1..=PATCH_RINGS {
        if !add_ring(h.pattern, &mut patch, seen) {
            break;
        }
        ring_of.resize(patch.len(), ring);
        if patch.len() > MAX_PATCH {
            break;
        }
        testable = patch.len();
    }
    // A principal submatrix of a positive-definite block is positive definite: one
    // factorisation of the largest patch rules out all the smaller ones.
    let mut largest = patch[..testable].to_vec();
    largest.sort_unstable();
    if Envelope::principal_block(h.pattern, h.rows, &largest)
        .cholesky()
        .is_some()
    {
        return;
    }
    let last_ring = ring_of[testable - 1];
    for ring in 0..=last_ring {
        let mut set: Vec<usize> = (0..testable)
            .filter(|&k| ring_of[k] <= ring)
            .map(|k| patch[k])
            .collect();
        set.sort_unstable();
        let scale = set.iter().fold(0.0f64, |s, &i| s.max(h.diag[i].abs()));
        if let Some((lambda, v)) = negative_mode(h, &set, scale) {
            if descend_along(energy, x, &set, v, lambda) != 0.0 {
                rep.patch_escapes += 1;
                escaped.extend_from_slice(&set);
            }
            // The rings beyond this one were not reached.
            (0..patch.len())
                .filter(|&k| ring_of[k] > ring)
                .for_each(|k| seen[patch[k]] = false);
            return;
        }
    }
}

/// Stable Newton on the unknowns `set` (sorted) alone, all others held at `x`: the energy and
/// gradient from [`Energy::local_energy`], the Hessian block with its diagonal from
/// [`Energy::along_coordinate`] and its off-diagonal entries from `h` (the last global
/// Hessian; exact for couplings that are quadratic, as in the spring arrays, otherwise a chord
/// approximation). Where the Cholesky factorisation of the block (within its
/// envelope, [`Envelope`]) fails, the region is unstable on its own and moves along its lowest
/// mode to the next minimum on that line ([`descend_along`]); otherwise it takes Newton steps
/// with backtracking. Stops when the region's largest gradient component
/// has fallen by 10³ (the global iteration finishes). Returns whether anything moved.
fn relax_region(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    set: &[usize],
    rep: &mut NewtonReport,
) -> bool {
    let m = set.len();
    let mut grad = vec![0.0; m];
    let mut moved = false;
    let Some(mut e) = energy.local_energy(x, set, &mut grad) else {
        return false;
    };
    if !e.is_finite() {
        return false;
    }
    let tol = 1e-3 * inf_norm(&grad);
    // Off-diagonal entries from the global Hessian; the diagonal is set at every iteration.
    let mut block = Envelope::principal_block(h.pattern, h.rows, set);
    if !block.all_finite() {
        return false;
    }
    let mut trial_grad = vec![0.0; m];
    let mut p = vec![0.0; m];
    for _ in 0..SETTLE_ITERATIONS {
        if inf_norm(&grad) <= tol {
            break;
        }
        for (r, &i) in set.iter().enumerate() {
            let d = energy.along_coordinate(x, i, x[i]).map_or(f64::NAN, |t| t.2);
            if !d.is_finite() {
                return moved;
            }
            block.set_diagonal(r, d);
        }
        let Some(chol) = block.cholesky() else {
            let (lambda, v) = lowest_mode(&block);
            if lambda.is_nan() || lambda >= 0.0 || descend_along(energy, x, set, v, lambda) == 0.0 {
                return moved;
            }
            rep.patch_escapes += 1;
            moved = true;
            match energy.local_energy(x, set, &mut grad) {
                Some(e1) if e1.is_finite() => e = e1,
                _ => return true,
            }
            continue;
        };
        p.iter_mut().zip(&grad).for_each(|(pi, g)| *pi = -g);
        chol.solve(&mut p);
        let slope: f64 = p.iter().zip(&grad).map(|(a, b)| a * b).sum();
        if slope.is_nan() || slope >= 0.0 {
            return moved;
        }
        let start: Vec<f64> = set.iter().map(|&i| x[i]).collect();
        let accepted = armijo(e, slope, 1e-12, |t| {
            for ((&i, s0), pi) in set.iter().zip(&start).zip(p.iter()) {
                x[i] = s0 + t * pi;
            }
            energy
                .local_energy(x, set, &mut trial_grad)
                .unwrap_or(f64::INFINITY)
        });
        // On acceptance x and the trial gradient are those of the accepted step.
        match accepted {
            Some(e1) => {
                moved = true;
                e = e1;
                grad.copy_from_slice(&trial_grad);
            }
            None => {
                for (&i, s0) in set.iter().zip(&start) {
                    x[i] = *s0;
                }
                return moved;
            }
        }
    }
    moved
}

/// Leave an instability whose mode CG met as the direction `dir` (dᵀHd ≤ 0): the unknowns
/// where |d_i| is at least a tenth of its largest component fall into connected groups; each
/// group, with up to [`PATCH_RINGS`] rings of neighbours, forms a patch, and when the patch's
/// principal submatrix of H has a negative eigenvalue, the patch moves along that eigenvector
/// to the next minimum ([`descend_along`], then [`settle`]). Returns whether any moved.
fn escape_around(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    dir: &[f64],
    rep: &mut NewtonReport,
) -> bool {
    let largest = inf_norm(dir);
    if !(largest > 0.0 && largest.is_finite()) {
        return false;
    }
    let n = x.len();
    let strong: Vec<usize> = (0..n).filter(|&i| dir[i].abs() >= 0.1 * largest).collect();
    if strong.is_empty() || energy.local_energy(x, &strong[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut in_strong = vec![false; n];
    strong.iter().for_each(|&i| in_strong[i] = true);
    let mut mark = vec![false; n];
    let mut escaped = Vec::new();
    for &s0 in &strong {
        if mark[s0] {
            continue;
        }
        let patch = component(h.pattern, s0, &in_strong, &mut mark, MAX_PATCH);
        escape_patch(energy, x, h, patch, &mut mark, &mut escaped, rep);
    }
    let moved = !escaped.is_empty();
    settle(energy, x, h, escaped, rep);
    moved
}

/// Move `x` along the direction `dir` (either sense, downhill) to the first minimum of the
/// energy on that line ([`descend_1d`], whole-system evaluations into the scratch vectors
/// `point` and `grad`). Returns whether it moved.
fn descend_line(
    energy: &impl Energy,
    x: &mut [f64],
    dir: &mut [f64],
    point: &mut [f64],
    grad: &mut [f64],
) -> bool {
    let norm = inf_norm(dir);
    if !(norm > 0.0 && norm.is_finite()) {
        return false;
    }
    dir.iter_mut().for_each(|v| *v /= norm);
    let line = |t: f64| -> Option<(f64, f64, f64)> {
        for ((pi, xi), di) in point.iter_mut().zip(x.iter()).zip(dir.iter()) {
            *pi = xi + t * di;
        }
        let e = energy.energy(point);
        if !e.is_finite() {
            return Some((e, 0.0, 0.0));
        }
        energy.gradient(point, grad);
        Some((e, dot(grad, dir), if t == 0.0 { -1.0 } else { f64::NAN }))
    };
    let Some((t, _)) = descend_1d(line, 0.0) else {
        return false;
    };
    x.iter_mut().zip(dir.iter()).for_each(|(xi, di)| *xi += t * di);
    t != 0.0
}

/// The lowest eigenvalue of a symmetric matrix with its unit eigenvector: by shift and invert
/// within the envelope ([`Envelope::lowest_eigenpair`]), else by the dense eigenproblem.
fn lowest_mode(a: &Envelope) -> (f64, Vec<f64>) {
    if let Some(pair) = a.lowest_eigenpair() {
        return pair;
    }
    let eig = DMatrix::from_fn(a.order(), a.order(), |r, c| a.get(r.max(c), r.min(c))).symmetric_eigen();
    match eig
        .eigenvalues
        .iter()
        .copied()
        .enumerate()
        .min_by(|p, q| p.1.total_cmp(&q.1))
    {
        Some((k, lambda)) => (lambda, eig.eigenvectors.column(k).iter().copied().collect()),
        None => (f64::INFINITY, Vec::new()),
    }
}

/// Move the unknowns `set` (sorted) along the direction `v` of curvature `lambda` < 0, downhill,
/// to the first minimum of the energy on that line ([`descend_1d`] on
/// [`Energy::local_energy`]). Returns the step taken along v (0 if none).
fn descend_along(energy: &impl Energy, x: &mut [f64], set: &[usize], mut v: Vec<f64>, lambda: f64) -> f64 {
    let m = set.len();
    let mut grad = vec![0.0; m];
    match energy.local_energy(x, set, &mut grad) {
        Some(e) if e.is_finite() => {}
        _ => return 0.0,
    }
    if dot(&grad, &v) > 0.0 {
        v.iter_mut().for_each(|vi| *vi = -*vi);
    }
    let base: Vec<f64> = set.iter().map(|&i| x[i]).collect();
    let line = |t: f64| -> Option<(f64, f64, f64)> {
        for ((&i, b), vi) in set.iter().zip(&base).zip(&v) {
            x[i] = b + t * vi;
        }
        let e = energy.local_energy(x, set, &mut grad)?;
        Some((e, dot(&grad, &v), if t == 0.0 { lambda } else { f64::NAN }))
    };
    let t = descend_1d(line, 0.0).map_or(0.0, |(t, _)| t);
    for ((&i, b), vi) in set.iter().zip(&base).zip(&v) {
        x[i] = b + t * vi;
    }
    t
}

/// Largest group of unknowns that [`escape_patches`] treats as one patch.
const MAX_PATCH: usize = 256;

/// Rings of neighbours by which [`escape_patch`] grows a patch at most.
const PATCH_RINGS: usize = 4;

/// Leave a collective instability locally. Negative curvature needs rows of H that are not
/// diagonally dominant (h_ii ≤ Σ_{j≠i} |h_ij|): the principal submatrix of the other rows is
/// strictly diagonally dominant, hence positive definite. Each connected group of such rows
/// with their neighbours, grown ring by ring ([`escape_patch`]), whose principal submatrix of
/// H has a negative eigenvalue λ is moved along the eigenvector v (padded with zeros,
/// vᵀHv = λ|v|² < 0 for the whole H), downhill, to the first minimum of the energy on that
/// line, evaluated locally ([`Energy::local_energy`]). This is the unstable group's own mode,
/// taken in one move instead of being crept along by damped steps. Returns whether any patch
/// moved; `false` also when the energy does not offer [`Energy::local_energy`].
fn escape_patches(energy: &impl Energy, x: &mut [f64], h: &Tangent<'_>, rep: &mut NewtonReport) -> bool {
    let Tangent {
        pattern, diag, off, ..
    } = *h;
    let n = x.len();
    let seeds: Vec<usize> = (0..n).filter(|&i| diag[i] - off[i] <= 0.0).collect();
    if seeds.is_empty() || energy.local_energy(x, &seeds[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut in_patch = vec![false; n];
    for &i in &seeds {
        pattern.columns(i).for_each(|j| in_patch[j] = true);
    }
    let mut seen = vec![false; n];
    let mut escaped = Vec::new();
    for &s0 in &seeds {
        if seen[s0] {
            continue;
        }
        let comp = component(pattern, s0, &in_patch, &mut seen, usize::MAX);
        escape_patch(energy, x, h, comp, &mut seen, &mut escaped, rep);
    }
    let moved = !escaped.is_empty();
    settle(energy, x, h, escaped, rep);
    moved
}

/// A direction of negative curvature of the principal submatrix of H (the iteration's `h`) on
/// the sorted unknowns `set`: its lowest eigenvalue, when below −1e-12·`scale`, with the unit
/// eigenvector ([`lowest_mode`]). A successful Cholesky factorisation rules it out first, at a
/// fraction of the cost of the eigenproblem.
fn negative_mode(h: &Tangent<'_>, set: &[usize], scale: f64) -> Option<(f64, Vec<f64>)> {
    let a = Envelope::principal_block(h.pattern, h.rows, set);
    if a.cholesky().is_some() {
        return None;
    }
    let (lambda, v) = lowest_mode(&a);
    (lambda < -1e-12 * scale).then_some((lambda, v))
}

/// From `s0`, go downhill on the one-variable energy `f` (value, slope, curvature) to the first
/// local minimum: steps doubling from the local length scale until the energy stops falling
/// (slope turned, energy risen, or the domain left), then bisection inside that bracket.
/// Returns the minimum and whether the way down met non-positive curvature (the start past a
/// fold: a jump rather than a settling). `None` if `f` is not offered, the start is outside the
/// domain or no lower point is found.
fn descend_1d(mut f: impl FnMut(f64) -> Option<(f64, f64, f64)>, s0: f64) -> Option<(f64, bool)> {
    let (e0, d0, c0) = f(s0)?;
    if !e0.is_finite() {
        return None;
    }
    let dir = if d0 > 0.0 { -1.0 } else { 1.0 };
    // Still going down (in `dir`) at s, and not above the energy at the bracket's low end.
    let descending = |e: f64, d: f64, e_ref: f64| e.is_finite() && e <= e_ref && dir * d < 0.0;
    let floor = 1e-12 * (1.0 + s0.abs());
    let mut h = if c0 != 0.0 && d0 != 0.0 && c0.is_finite() {
        (d0 / c0).abs()
    } else {
        0.0
    }
    .max(1e-6 * (1.0 + s0.abs()));
    let mut unstable = c0 <= 0.0;
    let (mut a, mut ea, mut da, mut ca) = (s0, e0, d0, c0);
    let mut b = None;
    for _ in 0..400 {
        // Where the curvature is positive a minimum may be near: never step further than half
        // again the Newton step to it, or a doubled step could cross it and the barrier
        // beyond into another basin (a jump the system does not make).
        if ca > 0.0 {
            h = h.min(1.5 * (da / ca).abs()).max(floor);
        }
        let t = a + dir * h;
        let (et, dt, ct) = f(t)?;
        if descending(et, dt, ea) {
            // Curvature where `f` does not give it (NaN): the secant of the slopes.
            let ct = if ct.is_nan() { (dt - da) / (t - a) } else { ct };
            (a, ea, da, ca) = (t, et, dt, ct);
            unstable |= ct <= 0.0;
            h *= 2.0;
        } else {
            b = Some(t);
            break;
        }
    }
    let mut b = b?;
    // The minimum to a 10⁻⁸ of the bracket (or to roundoff): the local Newton iterations that
    // follow every move polish it.
    let width = 1e-8 * (b - a).abs();
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m == a || m == b || (b - a).abs() <= width {
            break;
        }
        let (em, dm, cm) = f(m)?;
        if descending(em, dm, ea) {
            (a, ea) = (m, em);
            unstable |= cm <= 0.0;
        } else {
            b = m;
        }
    }
    (ea < e0).then_some((a, unstable))
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

    /// The chain of wells with its one-coordinate energy offered.
    struct WellsAlong(Wells);

    impl Energy for WellsAlong {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn energy(&self, x: &[f64]) -> f64 {
            self.0.energy(x)
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            self.0.gradient(x, g);
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            self.0.hessian_pattern()
        }
        fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
            self.0.hessian_values(x, v);
        }
        fn along_coordinate(&self, x: &[f64], i: usize, s: f64) -> Option<(f64, f64, f64)> {
            let c = self.0.c;
            let (mut e, mut d, mut h) = (s.powi(4) / 4.0 - s * s / 2.0, s.powi(3) - s, 3.0 * s * s - 1.0);
            for j in [i.checked_sub(1), (i + 1 < self.0.n).then_some(i + 1)]
                .into_iter()
                .flatten()
            {
                e += 0.5 * c * (s - x[j]).powi(2);
                d += c * (s - x[j]);
                h += c;
            }
            Some((e, d, h))
        }
    }

    /// Double wells w(x) = x⁴/4 − x²/2 in a uniform field b (energy −b·x each), coupled in a
    /// chain by springs c(x_{i+1} − x_i)²/2, offering both local evaluations.
    struct FieldWells {
        n: usize,
        c: f64,
        b: f64,
    }

    impl FieldWells {
        fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> {
            [i.checked_sub(1), (i + 1 < self.n).then_some(i + 1)]
                .into_iter()
                .flatten()
        }
    }

    impl Energy for FieldWells {
        fn dim(&self) -> usize {
            self.n
        }
        fn energy(&self, x: &[f64]) -> f64 {
            let wells: f64 = x.iter().map(|v| v.powi(4) / 4.0 - v * v / 2.0 - self.b * v).sum();
            let springs: f64 = x.windows(2).map(|w| 0.5 * self.c * (w[1] - w[0]).powi(2)).sum();
            wells + springs
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            for i in 0..self.n {
                g[i] = x[i].powi(3) - x[i] - self.b;
                for j in self.neighbours(i) {
                    g[i] += self.c * (x[i] - x[j]);
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
                v[i] = 3.0 * x[i] * x[i] - 1.0 + self.c * self.neighbours(i).count() as f64;
            }
            for k in 0..self.n.saturating_sub(1) {
                v[self.n + k] = -self.c;
            }
        }
        fn along_coordinate(&self, x: &[f64], i: usize, s: f64) -> Option<(f64, f64, f64)> {
            let (mut e, mut d, mut h) = (
                s.powi(4) / 4.0 - s * s / 2.0 - self.b * s,
                s.powi(3) - s - self.b,
                3.0 * s * s - 1.0,
            );
            for j in self.neighbours(i) {
                e += 0.5 * self.c * (s - x[j]).powi(2);
                d += self.c * (s - x[j]);
                h += self.c;
            }
            Some((e, d, h))
        }
        fn local_energy(&self, x: &[f64], set: &[usize], grad: &mut [f64]) -> Option<f64> {
            let mut e = 0.0;
            for (gi, &i) in grad.iter_mut().zip(set) {
                let s = x[i];
                e += s.powi(4) / 4.0 - s * s / 2.0 - self.b * s;
                *gi = s.powi(3) - s - self.b;
                for j in self.neighbours(i) {
                    *gi += self.c * (s - x[j]);
                    if j > i || set.binary_search(&j).is_err() {
                        e += 0.5 * self.c * (s - x[j]).powi(2);
                    }
                }
            }
            Some(e)
        }
    }

    // Two wells coupled strongly (c = 2) at the stationary point x = (0, 0): each is stable
    // along its own axis (curvature −1 + 2 = 1), the pair is not (eigenvalue −1 along (1, 1)).
    // No coordinate move lowers the energy; the local unstable mode does, in one move, and
    // the pair ends in a common well without factorisation.
    #[test]
    fn a_collective_saddle_is_left_along_its_local_mode() {
        let e = FieldWells { n: 2, c: 2.0, b: 0.0 };
        let mut s = StableNewton::new(&e).unwrap();
        let mut x = vec![0.0, 0.0];
        let rep = s.minimize(&e, &mut x, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 0);
        assert_eq!(rep.coordinate_jumps, 0);
        assert!(rep.patch_escapes >= 1);
        assert!(
            (x[0] - x[1]).abs() < 1e-9 && (x[0].abs() - 1.0).abs() < 1e-9,
            "x = {x:?}"
        );
        let mut check = StableNewton::new(&e).unwrap();
        assert!(check.is_stable(&e, &x).unwrap());
    }

    // A front in a chain of 400 bistable wells in a field: the first ten sit in the right
    // well, the rest in the left one, where each is metastable on its own (b = 0.2 is below
    // the fold field 2/√27 = 0.385) but not next to a neighbour in the right well: the pull
    // 2c = 0.5 exceeds the fold field of its own-axis energy x⁴/4 − (1 − 2c)x²/2 − bx, 0.136.
    // Every well jumps, one after the other: an avalanche of 390 generations. The iterative
    // path resolves it locally, in a few global iterations (not one per generation), and
    // ends where the direct path ends.
    #[test]
    fn an_avalanche_is_resolved_locally() {
        let n = 400;
        let e = FieldWells { n, c: 0.25, b: 0.2 };
        let start: Vec<f64> = (0..n).map(|i| if i < 10 { 1.0 } else { -1.0 }).collect();
        let mut s = StableNewton::new(&e).unwrap();
        let (mut a, mut b) = (start.clone(), start);
        // The direct path meets the generations one at a time, a few iterations each.
        let direct = NewtonOptions {
            max_iterations: 20_000,
            ..NewtonOptions::default()
        };
        let slow = s.minimize(&e, &mut a, &direct).unwrap();
        assert!(slow.iterations > n, "{} direct iterations", slow.iterations);
        let rep = s.minimize(&e, &mut b, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 0);
        // Each well leaves by a local move: along its own axis, or with a few neighbours
        // along their common lowest mode.
        assert!(rep.coordinate_jumps + rep.patch_escapes >= n - 10, "{rep:?}");
        assert!(rep.iterations <= 20, "{} global iterations", rep.iterations);
        assert!(b.iter().all(|&v| v > 0.9), "every well jumped");
        assert!(a.iter().zip(&b).all(|(p, q)| (p - q).abs() < 1e-8));
        let mut check = StableNewton::new(&e).unwrap();
        assert!(check.is_stable(&e, &b).unwrap());
    }

    // A tilted double well E = s⁴/4 − s²/2 + 0.3 s, entered from s = 3: the first minimum
    // downhill is the shallow one near 0.79 (s³ − s + 0.3 = 0), behind which lie the barrier
    // at 0.34 and the deep well at −1.13. Doubling steps alone land past the barrier (at 0.21,
    // lower and still going down); the descent must stop in the shallow well and report no
    // instability on the way.
    #[test]
    fn a_one_dimensional_descent_does_not_cross_a_barrier() {
        let f = |s: f64| {
            Some((
                s.powi(4) / 4.0 - s * s / 2.0 + 0.3 * s,
                s.powi(3) - s + 0.3,
                3.0 * s * s - 1.0,
            ))
        };
        let (to, unstable) = descend_1d(f, 3.0).unwrap();
        assert!(
            (to.powi(3) - to + 0.3).abs() < 1e-9 && to > 0.75 && to < 0.9,
            "to = {to}"
        );
        assert!(!unstable);
        // From just past the barrier top the way down runs through negative curvature.
        let (to, unstable) = descend_1d(f, 0.3).unwrap();
        assert!(to < -1.0 && unstable, "to = {to}");
    }

    fn iterative() -> NewtonOptions {
        NewtonOptions {
            linear: LinearSolver::Iterative,
            ..NewtonOptions::default()
        }
    }

    // The iterative path leaves the maximum like the direct one; its accepted state passes the
    // factorisation test of a separate (direct) solver.
    #[test]
    fn the_iterative_path_leaves_the_maximum_too() {
        let e = Wells { n: 1, c: 0.0 };
        let mut s = StableNewton::new(&e).unwrap();
        let mut y = vec![0.1];
        let rep = s.minimize(&e, &mut y, &iterative()).unwrap();
        assert!((y[0] - 1.0).abs() < 1e-10, "x = {}", y[0]);
        assert!(rep.left_unstable_state());
        assert_eq!(rep.direct_fallbacks, 0);
        let mut check = StableNewton::new(&e).unwrap();
        assert!(check.is_stable(&e, &y).unwrap());
    }

    // At the stationary saddle x = 0 of the coupled chain: without the one-coordinate energy
    // the iterative path has no descent direction (gradient zero) and hands over to the direct
    // path, which leaves along negative curvature; with it, the unstable unknowns jump along
    // their axes. Both end at a minimum the factorisation confirms.
    #[test]
    fn the_iterative_path_leaves_a_stationary_saddle() {
        let plain = Wells { n: 50, c: 0.1 };
        let mut x = vec![0.0; 50];
        let mut s = StableNewton::new(&plain).unwrap();
        let rep = s.minimize(&plain, &mut x, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 1);
        assert!(rep.energy < -0.2 * 50.0);
        let along = WellsAlong(Wells { n: 50, c: 0.1 });
        let mut y = vec![0.0; 50];
        let rep = s.minimize(&along, &mut y, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 0);
        assert!(rep.coordinate_jumps >= 1);
        assert!(rep.gradient_norm <= 1e-10);
        assert!(rep.energy < -0.2 * 50.0, "E = {}", rep.energy);
        let mut check = StableNewton::new(&along).unwrap();
        assert!(check.is_stable(&along, &x).unwrap() && check.is_stable(&along, &y).unwrap());
    }

    // From a stable start the two paths reach the same minimum.
    #[test]
    fn the_paths_agree_from_a_stable_start() {
        let e = Wells { n: 40, c: 0.3 };
        let start: Vec<f64> = (0..40).map(|i| 0.7 + 0.01 * i as f64).collect();
        let (mut a, mut b) = (start.clone(), start);
        let mut s = StableNewton::new(&e).unwrap();
        s.minimize(&e, &mut a, &NewtonOptions::default()).unwrap();
        let rep = s.minimize(&e, &mut b, &iterative()).unwrap();
        assert_eq!((rep.indefinite_iterations, rep.direct_fallbacks), (0, 0));
        assert!(a.iter().zip(&b).all(|(p, q)| (p - q).abs() < 1e-9));
    }
}
