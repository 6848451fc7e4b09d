//! Quasi-static loading paths: the states an experiment visits when a control parameter λ (a
//! displacement, a depth) is stepped, and the jumps between them.
//!
//! Under displacement control a system stays in the basin of the minimum it sits in until that
//! minimum ceases to exist (a fold of the equilibrium branch), then jumps to another stable
//! state. [`follow`] walks a sequence of control values, minimising the energy at each from the
//! previous state with [`StableNewton`] (which accepts only states with a positive-definite
//! Hessian, so a jump ends in a stable state and never on a saddle), and certifies each accepted
//! state.
//!
//! A step is a *jump* when the model's own measure of the change, [`Controlled::jump_measure`],
//! reaches 1 (for example, the largest displacement change in units of the interaction range),
//! or, where [`PathOptions::unstable_start_is_jump`] asks for it, when the solver had to leave
//! an unstable start (the previous state no longer was a minimum).
//! With [`PathOptions::refine_to`] a jump is located by bisection of the step: trial states
//! between the last accepted value and the target are minimised from the last accepted state;
//! those that stay on the branch are accepted (they lie on the path), until the last value on the
//! branch and the first beyond it differ by at most the tolerance. On a smooth branch the
//! change of state shrinks with the step, so a false alarm of the measure resolves into finer
//! steps without a jump; at a fold it does not, and the jump is reported there. Each jump costs
//! about log2(step/tolerance) extra minimisations.
//!
//! Where the model gives the rate of its gradient with the control ([`Controlled::gradient_rate`])
//! and the system is small enough for the direct solver, a step starts from the tangent of the
//! branch, `x + Δλ dx/dλ` with `H dx/dλ = −∂g/∂λ` solved with the factorisation that certified
//! the state (no extra factorisation): on a branch that moves (a contact pressed against a stiff
//! repulsive wall) Newton then converges in a few iterations instead of a line-searched descent
//! from the old state. The tangent is used when its step measures at most two jumps (it
//! diverges at a fold) and lowers the energy at the new control value below that of the plain
//! start. A step that started from the tangent is a jump when the minimum lies a jump away from
//! the prediction: a fast but smooth branch (a receding contact edge) follows its tangent and is
//! not bisected as a false alarm, while a jump leaves it.
//!
//! The driver stores nothing but the current state: every accepted state is handed to a
//! visitor, which records what its model needs (a force, a contact set, a profile), reports
//! progress, and may stop the walk with an error (cancellation).

use crate::error::{Error, Result};
use crate::numerics::newton::{Energy, NewtonOptions, NewtonReport, StableNewton};

/// A family of energies over a control parameter λ, with a measure of how far a step moved.
pub trait Controlled {
    /// The energy at one control value.
    type At<'a>: Energy
    where
        Self: 'a;
    /// The energy at control value `lambda`.
    fn at(&self, lambda: f64) -> Self::At<'_>;
    /// How far the state moved from `before` to `after`, in units where a jump moves at least
    /// about 1 and a smooth step of the path's size much less than 1.
    fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64;
    /// Adapt the start `x` (the state accepted at `from`) of a minimisation at `to`, e.g. so
    /// that it lies inside the energy's domain; by default it is left as it is.
    fn prepare_start(&self, _from: f64, _to: f64, _x: &mut [f64]) {}
    /// The rate ∂g/∂λ of the energy's gradient g at the state `x` and control value `lambda`,
    /// written into `out`; `false` (the default) where the model does not provide it. With it,
    /// a step starts from the branch's tangent (see [`follow`]).
    fn gradient_rate(&self, _lambda: f64, _x: &[f64], _out: &mut [f64]) -> bool {
        false
    }
}

/// A tangent predictor moves no unknown by more than this, in units of
/// [`Controlled::jump_measure`]; a larger tangent (near a fold, where it diverges) is not used.
const PREDICTOR_MAX_MEASURE: f64 = 2.0;

/// Options of [`follow`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathOptions {
    /// Tolerances of the minimiser.
    pub newton: NewtonOptions,
    /// Locate each jump by bisection until the last value on the branch and the first beyond
    /// it differ by at most this (in units of λ); `None`: jumps are reported at the step where
    /// they were met.
    pub refine_to: Option<f64>,
    /// Largest number of Newton iterations of a bisection trial: a trial that needs more is
    /// on its way to another state (near a fold the way out of the vanished basin is slow),
    /// and counts as a jump.
    pub trial_iterations: usize,
    /// Count a step whose start was unstable (the minimiser met an indefinite Hessian) as a
    /// jump even when the state moved little. Where the model's measure alone tells jumps
    /// apart, leave this off: a start just beyond a stable state can be slightly indefinite
    /// on a branch that goes on (a softening contact edge), and each such step would be
    /// bisected for nothing.
    pub unstable_start_is_jump: bool,
    /// Largest number of Newton iterations of the minimisation that takes a located jump
    /// (from the first value past the fold); where it needs more, the jump is taken from
    /// further past the fold. Equal to [`PathOptions::trial_iterations`] unless the model's
    /// jumps are long descents (a contact zipping up node by node in a finite-element mesh),
    /// which would otherwise be retried from ever further past the fold.
    pub jump_iterations: usize,
    /// After the first state a bisection accepts, try the target again from it (once per
    /// target): a false alarm of the jump measure (a fast but smooth branch, whose tangent's
    /// error over the full step reaches the measure while half the step's does not) then costs
    /// two more minimisations instead of about log2(step/tolerance).
    pub retry_target: bool,
}

/// One accepted state of the path, as handed to the visitor.
#[derive(Debug)]
pub struct Visit<'a> {
    /// Control value.
    pub lambda: f64,
    /// The equilibrium state.
    pub x: &'a [f64],
    /// The previous accepted state when this state was reached by a jump, `None` on the branch.
    pub jumped_from: Option<(f64, &'a [f64])>,
    /// Whether the Hessian of the state is positive definite (always, unless the minimiser's
    /// acceptance rule failed; recorded so that callers can assert it).
    pub stable: bool,
    /// The minimiser's report for this state.
    pub report: NewtonReport,
    /// Index of the target value being walked towards (bisection states share it).
    pub target: usize,
}

/// What a walk cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PathStats {
    /// States accepted (targets plus bisection states).
    pub states: usize,
    /// Minimisations run (rejected bisection trials included).
    pub minimisations: usize,
    /// Newton iterations in all minimisations.
    pub newton_iterations: usize,
    /// Jumps.
    pub jumps: usize,
    /// Whether every accepted state was certified stable.
    pub all_stable: bool,
}

/// The walk's current state and the trial just minimised.
struct Current<'a> {
    x: &'a mut Vec<f64>,
    trial: &'a mut Vec<f64>,
    lambda: &'a mut f64,
    stats: &'a mut PathStats,
}

impl Current<'_> {
    /// Hand the trial state at `at` (with its report, whether it jumped and whether it is
    /// stable) to the visitor and make it the current state.
    fn accept(
        &mut self,
        visit: &mut impl FnMut(&Visit<'_>) -> Result<()>,
        at: f64,
        (report, jumped, stable): (NewtonReport, bool, bool),
        target: usize,
    ) -> Result<()> {
        self.stats.states += 1;
        self.stats.jumps += usize::from(jumped);
        self.stats.all_stable &= stable;
        visit(&Visit {
            lambda: at,
            x: self.trial,
            jumped_from: jumped.then_some((*self.lambda, self.x.as_slice())),
            stable,
            report,
            target,
        })?;
        std::mem::swap(self.x, self.trial);
        *self.lambda = at;
        Ok(())
    }
}

/// Walk the control values `targets` from the stable state `x` (updated in place to the last
/// state), handing every accepted state to `visit`.
///
/// # Errors
/// Minimiser failures ([`crate::error::Error::NoConvergence`]), and whatever `visit` returns.
///
/// # Panics
/// If `x.len()` differs from the energy's dimension.
pub fn follow<C: Controlled>(
    model: &C,
    solver: &mut StableNewton,
    x: &mut Vec<f64>,
    lambda_start: f64,
    targets: &[f64],
    opts: &PathOptions,
    mut visit: impl FnMut(&Visit<'_>) -> Result<()>,
) -> Result<PathStats> {
    let mut stats = PathStats {
        all_stable: true,
        ..PathStats::default()
    };
    let mut lambda = lambda_start;
    let mut trial = x.clone();
    // Minimise from `x` at `at` into `trial`: Some((report, jumped, stable)), or None when a
    // trial capped at `cap` iterations ran out of them (a jump under way).
    let mut rate = vec![0.0; x.len()];
    let mut predicted = Vec::with_capacity(x.len());
    let mut attempt = |x: &[f64],
                       trial: &mut Vec<f64>,
                       from: f64,
                       at: f64,
                       cap: Option<usize>,
                       stats: &mut PathStats|
     -> Result<Option<(NewtonReport, bool, bool)>> {
        trial.clear();
        trial.extend_from_slice(x);
        model.prepare_start(from, at, trial);
        let e = model.at(at);
        let mut on_tangent = false;
        if model.gradient_rate(from, x, &mut rate[..])
            && solver.solve_at(&model.at(from), x, &mut rate[..])?
        {
            // `rate` now holds −dx/dλ.
            predicted.clear();
            predicted.extend(x.iter().zip(rate.iter()).map(|(xi, ri)| xi - (at - from) * ri));
            if model.jump_measure(x, &predicted[..]) <= PREDICTOR_MAX_MEASURE
                && e.energy(&predicted[..]) < e.energy(trial)
            {
                trial.copy_from_slice(&predicted);
                on_tangent = true;
            }
        }
        stats.minimisations += 1;
        let newton = NewtonOptions {
            max_iterations: cap.map_or(opts.newton.max_iterations, |c| c.min(opts.newton.max_iterations)),
            ..opts.newton
        };
        let rep = match solver.minimize(&e, trial, &newton) {
            Ok(rep) => rep,
            Err(Error::NoConvergence { iterations, .. }) if cap.is_some() => {
                stats.newton_iterations += iterations;
                return Ok(None);
            }
            Err(e) => return Err(e),
        };
        stats.newton_iterations += rep.iterations;
        // A jump leaves the branch: measured from the tangent's prediction where it was used
        // (a fast but smooth branch, a receding contact edge, is not a jump), else from the
        // previous state.
        let origin: &[f64] = if on_tangent { &predicted } else { x };
        let jumped = (opts.unstable_start_is_jump && rep.left_unstable_state())
            || model.jump_measure(origin, trial) >= 1.0;
        let stable = solver.is_stable(&e, trial)?;
        Ok(Some((rep, jumped, stable)))
    };
    for (k, &target) in targets.iter().enumerate() {
        loop {
            let refine = opts.refine_to.filter(|&tol| (target - lambda).abs() > tol);
            let trial_cap = Some(opts.trial_iterations);
            let first = attempt(x, &mut trial, lambda, target, refine.and(trial_cap), &mut stats)?;
            if let Some((rep, jumped, stable)) = first
                && (!jumped || refine.is_none())
            {
                let mut current = Current {
                    x,
                    trial: &mut trial,
                    lambda: &mut lambda,
                    stats: &mut stats,
                };
                current.accept(&mut visit, target, (rep, jumped, stable), k)?;
                break;
            }
            // Bisect towards the fold: accept trial states that stay on the branch.
            let tol = refine.unwrap_or(0.0);
            let mut hi = target;
            let mut retry = opts.retry_target;
            let mut reached = false;
            while (hi - lambda).abs() > tol {
                let mid = 0.5 * (lambda + hi);
                match attempt(x, &mut trial, lambda, mid, trial_cap, &mut stats)? {
                    Some((rep, false, stable)) => {
                        let mut current = Current {
                            x,
                            trial: &mut trial,
                            lambda: &mut lambda,
                            stats: &mut stats,
                        };
                        current.accept(&mut visit, mid, (rep, false, stable), k)?;
                        if retry && hi == target {
                            retry = false;
                            if let Some((rep, false, stable)) =
                                attempt(x, &mut trial, lambda, target, trial_cap, &mut stats)?
                            {
                                let mut current = Current {
                                    x,
                                    trial: &mut trial,
                                    lambda: &mut lambda,
                                    stats: &mut stats,
                                };
                                current.accept(&mut visit, target, (rep, false, stable), k)?;
                                reached = true;
                                break;
                            }
                        }
                    }
                    _ => hi = mid,
                }
            }
            if reached {
                break;
            }
            // `hi` is within the tolerance of the last state on the branch: jump there (or,
            // when the bisection found no jump after all, go on from here). Just past a fold
            // the way out is slowest; where the minimiser does not find it, the jump is taken
            // from further past the fold (doubling the distance, at most to the target).
            let mut at = hi;
            let (rep, jumped, stable) = loop {
                let full = (at - target).abs() <= f64::EPSILON * target.abs().max(1.0);
                let cap = (!full).then_some(opts.jump_iterations);
                match attempt(x, &mut trial, lambda, at, cap, &mut stats)? {
                    Some(found) => break found,
                    None => {
                        let further = lambda + 2.0 * (at - lambda);
                        at = if (further - lambda).abs() >= (target - lambda).abs() {
                            target
                        } else {
                            further
                        };
                    }
                }
            };
            let mut current = Current {
                x,
                trial: &mut trial,
                lambda: &mut lambda,
                stats: &mut stats,
            };
            current.accept(&mut visit, at, (rep, jumped, stable), k)?;
            if at == target {
                break;
            }
        }
    }
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One unknown x in the tilted double well E = x⁴/4 − x²/2 − λx: folds at
    /// λ = ±2/(3√3), where the outer minimum on the side of the tilt vanishes.
    struct Well;
    struct WellAt(f64);
    impl Energy for WellAt {
        fn dim(&self) -> usize {
            1
        }
        fn energy(&self, x: &[f64]) -> f64 {
            x[0].powi(4) / 4.0 - x[0] * x[0] / 2.0 - self.0 * x[0]
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            g[0] = x[0].powi(3) - x[0] - self.0;
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            vec![(0, 0)]
        }
        fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
            v[0] = 3.0 * x[0] * x[0] - 1.0;
        }
    }
    impl Controlled for Well {
        type At<'a> = WellAt;
        fn at(&self, lambda: f64) -> WellAt {
            WellAt(lambda)
        }
        fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
            (after[0] - before[0]).abs() / 0.5
        }
    }

    /// The same well with its gradient rate ∂g/∂λ = −1: steps start from the tangent.
    struct WellWithRate;
    impl Controlled for WellWithRate {
        type At<'a> = WellAt;
        fn at(&self, lambda: f64) -> WellAt {
            WellAt(lambda)
        }
        fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
            Well.jump_measure(before, after)
        }
        fn gradient_rate(&self, _: f64, _: &[f64], out: &mut [f64]) -> bool {
            out[0] = -1.0;
            true
        }
    }

    // The tangent predictor changes where steps start, not the path: the same fold, the same
    // landing state, fewer Newton iterations.
    #[test]
    fn the_tangent_predictor_follows_the_same_path_in_fewer_iterations() {
        let (states, jumps, stats) = walk(Some(1e-9));
        let targets = targets();
        let (with, jumps_with, stats_with) = walk_model(&WellWithRate, Some(1e-9));
        assert_eq!(jumps_with.len(), 1);
        assert!((jumps_with[0].0 - jumps[0].0).abs() < 1e-9);
        let at = |s: &[(f64, f64)], l: f64| s.iter().find(|p| p.0 == l).map(|p| p.1);
        for &(l, x) in states.iter().filter(|p| targets.contains(&p.0)) {
            let y = at(&with, l).expect("every target visited");
            assert!((x - y).abs() < 1e-8, "at λ = {l}: {x} vs {y}");
        }
        assert!(
            stats_with.newton_iterations < stats.newton_iterations,
            "{} vs {}",
            stats_with.newton_iterations,
            stats.newton_iterations
        );
    }

    /// (λ, x) of every state, (λ before, λ after, x before) of every jump, the statistics.
    type Walk = (Vec<(f64, f64)>, Vec<(f64, f64, f64)>, PathStats);

    /// The control values of the walks: λ = −0.1 ... 0.5.
    fn targets() -> Vec<f64> {
        (0..=10).map(|i| -0.1 + 0.06 * i as f64).collect()
    }

    fn walk(refine: Option<f64>) -> Walk {
        walk_model(&Well, refine)
    }

    fn walk_model<C: Controlled>(model: &C, refine: Option<f64>) -> Walk {
        walk_with(
            model,
            &PathOptions {
                newton: NewtonOptions::default(),
                refine_to: refine,
                trial_iterations: 50,
                unstable_start_is_jump: true,
                jump_iterations: 50,
                retry_target: false,
            },
        )
    }

    fn walk_with<C: Controlled>(model: &C, opts: &PathOptions) -> Walk {
        let mut solver = StableNewton::new(&WellAt(0.0)).expect("1x1 pattern");
        // Start in the left well at λ = -0.1 and tilt to the right until it vanishes.
        let mut x = vec![-1.0];
        let targets = targets();
        let mut states = Vec::new();
        let mut jumps = Vec::new();
        let stats = follow(model, &mut solver, &mut x, -0.2, &targets, opts, |v| {
            states.push((v.lambda, v.x[0]));
            if let Some((l0, x0)) = v.jumped_from {
                jumps.push((l0, v.lambda, x0[0]));
            }
            Ok(())
        })
        .expect("walk");
        (states, jumps, stats)
    }

    #[test]
    fn jump_is_located_at_the_fold_by_bisection() {
        let fold = 2.0 / (3.0 * 3f64.sqrt());
        let (states, jumps, stats) = walk(Some(1e-9));
        assert_eq!(jumps.len(), 1);
        let (before, after, x0) = jumps[0];
        // The last state on the branch is within the minimiser's gradient tolerance (1e-10)
        // of the fold: past it by less than that, a near-equilibrium is still accepted.
        assert!((before - fold).abs() < 1e-9 && after > fold, "{before} {after}");
        assert!(after - before <= 1e-9);
        // Just before the fold the left minimum sits at x = -1/√3; the jump lands in the right
        // well (x³ − x = λ at x > 1).
        assert!((x0 + 1.0 / 3f64.sqrt()).abs() < 1e-4, "{x0}");
        let landed = states.iter().find(|s| s.0 == after).expect("after state").1;
        assert!(landed > 1.0);
        assert!(stats.all_stable && stats.jumps == 1);
        // The states are visited in increasing λ.
        assert!(states.windows(2).all(|w| w[1].0 > w[0].0));
    }

    // A jump whose descent takes more iterations than a bisection trial may: with
    // `jump_iterations` at the trial cap it is taken from further past the fold (the state
    // after it lies beyond the tolerance), with a larger `jump_iterations` from the first value
    // past the fold.
    #[test]
    fn a_long_jump_is_taken_from_the_first_value_past_the_fold() {
        let fold = 2.0 / (3.0 * 3f64.sqrt());
        let opts = |jump_iterations| PathOptions {
            newton: NewtonOptions::default(),
            refine_to: Some(1e-9),
            trial_iterations: 4,
            unstable_start_is_jump: true,
            jump_iterations,
            retry_target: false,
        };
        let (_, capped, _) = walk_with(&Well, &opts(4));
        let (_, long, stats) = walk_with(&Well, &opts(100));
        assert_eq!((capped.len(), long.len()), (1, 1));
        assert!(capped[0].1 - fold > 1e-8, "{:?}", capped[0]);
        assert!((long[0].1 - fold).abs() < 2e-9, "{:?}", long[0]);
        assert!(stats.all_stable);
    }

    /// One unknown in the moving well E = ½ (x − 8λ²)², with its gradient rate: the minimum
    /// moves smoothly but turns fast, so from λ = 0 the tangent's error over a step of 0.3 is
    /// 8 × 0.3² = 0.72, more than half the jump measure's unit, while over half the step it is
    /// 0.18.
    struct Moving;
    struct MovingAt(f64);
    impl Energy for MovingAt {
        fn dim(&self) -> usize {
            1
        }
        fn energy(&self, x: &[f64]) -> f64 {
            0.5 * (x[0] - 8.0 * self.0 * self.0).powi(2)
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            g[0] = x[0] - 8.0 * self.0 * self.0;
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            vec![(0, 0)]
        }
        fn hessian_values(&self, _: &[f64], v: &mut [f64]) {
            v[0] = 1.0;
        }
    }
    impl Controlled for Moving {
        type At<'a> = MovingAt;
        fn at(&self, lambda: f64) -> MovingAt {
            MovingAt(lambda)
        }
        fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
            (after[0] - before[0]).abs() / 0.5
        }
        fn gradient_rate(&self, lambda: f64, _: &[f64], out: &mut [f64]) -> bool {
            out[0] = -16.0 * lambda;
            true
        }
    }

    // A false alarm of the jump measure on a fast smooth branch: the bisection finds no jump
    // either way, and with `retry_target` the false alarm costs three minimisations (the full
    // step, half of it, the rest) instead of one per halving down to the tolerance; the next
    // step (0.15, from a tangent that turns with the branch) raises none.
    #[test]
    fn retrying_the_target_resolves_a_false_alarm_in_three_minimisations() {
        let targets = [0.3, 0.45];
        let run = |retry_target| {
            let mut solver = StableNewton::new(&MovingAt(0.0)).expect("1x1 pattern");
            let mut x = vec![0.0];
            let opts = PathOptions {
                newton: NewtonOptions::default(),
                refine_to: Some(1e-6),
                trial_iterations: 50,
                unstable_start_is_jump: false,
                jump_iterations: 50,
                retry_target,
            };
            let mut at_targets = Vec::new();
            let stats = follow(&Moving, &mut solver, &mut x, 0.0, &targets, &opts, |v| {
                if targets.contains(&v.lambda) {
                    at_targets.push((v.lambda, v.x[0]));
                }
                Ok(())
            })
            .expect("walk");
            (at_targets, stats)
        };
        let (plain, plain_stats) = run(false);
        let (retried, stats) = run(true);
        assert_eq!((plain_stats.jumps, stats.jumps), (0, 0));
        assert_eq!(plain.len(), targets.len());
        for ((l, x), (l2, y)) in plain.iter().zip(&retried) {
            assert_eq!(l, l2);
            assert!((x - 8.0 * l * l).abs() < 1e-9 && (y - 8.0 * l * l).abs() < 1e-9);
        }
        assert_eq!(stats.minimisations, 4, "{stats:?}");
        assert!(plain_stats.minimisations > 16, "{plain_stats:?}");
    }

    #[test]
    fn without_refinement_the_jump_is_reported_at_its_step() {
        let (_, jumps, stats) = walk(None);
        assert_eq!(jumps.len(), 1);
        assert!((jumps[0].1 - 0.44).abs() < 1e-12, "{:?}", jumps[0]);
        assert_eq!(stats.states, 11);
    }
}
