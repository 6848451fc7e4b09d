//! The iterative path of [`StableNewton::minimize`] ([`LinearSolver::Iterative`], and
//! [`LinearSolver::Auto`] from [`ITERATIVE_MIN_UNKNOWNS`] unknowns): Newton steps by
//! Jacobi-preconditioned conjugate gradients with the backtracking line search; the local moves
//! (`local.rs`) wherever the state is unstable; a localised diagonal modification where none of
//! them applies; and, for the accepted state, the factorisation-free certificate of positive
//! definiteness of a Hessian that is a Z-matrix ([`certify_z_matrix`]), which also bounds the
//! Newton correction. Wherever that certificate is not found the direct path takes over.
//!
//! [`LinearSolver::Iterative`]: super::LinearSolver::Iterative
//! [`LinearSolver::Auto`]: super::LinearSolver::Auto
//! [`ITERATIVE_MIN_UNKNOWNS`]: super::ITERATIVE_MIN_UNKNOWNS

use super::local::{
    Jumps, Tangent, descend_line, escape_around, escape_patches, jump_along_coordinates, settle,
};
use super::{Energy, NewtonOptions, NewtonReport, StableNewton, Watch, backtrack};
use crate::error::Result;
use crate::numerics::pcg::{Operator, PcgEnd, certify_z_matrix, dot, inf_norm, pcg, pcg_with_curvature};

/// Unknowns whose gradient component is at least this fraction of the largest are relaxed
/// locally when they are few (the iterative path of [`StableNewton::minimize`]).
const HOT_FRACTION: f64 = 0.1;

impl StableNewton {
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
    pub(super) fn certify(&mut self) -> (Option<bool>, f64) {
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
    ///
    /// [`LinearSolver::Iterative`]: super::LinearSolver::Iterative
    /// [`relax_region`]: super::local::relax_region
    pub(super) fn minimize_iterative(
        &mut self,
        energy: &impl Energy,
        x: &mut [f64],
        opts: &NewtonOptions,
        mut e0: f64,
        guess: Option<&[f64]>,
        watch: Watch<'_>,
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
        let hand_over = |this: &mut Self,
                         x: &mut [f64],
                         mut rep: NewtonReport,
                         watch: Watch<'_>|
         -> Result<NewtonReport> {
            let direct = this.minimize_inner(energy, x, opts, energy.energy(x), watch)?;
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
            watch(&rep)?;
            energy.gradient(x, &mut g);
            let gnorm = inf_norm(&g);
            self.loaded = None;
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
                    return hand_over(self, x, rep, watch);
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
                        return hand_over(self, x, rep, watch);
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
                        return hand_over(self, x, rep, watch);
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
                return hand_over(self, x, rep, watch);
            }
            let slope = dot(&g, &p);
            if slope >= 0.0 || slope.is_nan() {
                return hand_over(self, x, rep, watch);
            }
            match backtrack(energy, x, &p, e0, slope, &mut trial) {
                Some(e1) => e0 = e1,
                None => return hand_over(self, x, rep, watch),
            }
        }
        hand_over(self, x, rep, watch)
    }
}

#[cfg(test)]
mod tests {
    use crate::numerics::newton::wells::{Wells, WellsAlong, iterative};
    use crate::numerics::newton::{NewtonOptions, StableNewton};

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
