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
//! Three options make the location of jumps cheap where the jump measure alone decides them
//! (the tips of chapter 4): bisection trials beyond the fold stop at their first indefinite
//! Hessian ([`PathOptions::indefinite_trial_is_beyond`]) instead of running their iterations
//! out of the vanished basin; a step whose minimum lay a jump away is retried from the first
//! bisection state on the branch ([`PathOptions::retry_after_jump`]), so that a false alarm
//! on a fast branch costs two minimisations instead of a bisection to the tolerance; and the
//! landing after a jump may take more iterations than a trial
//! ([`PathOptions::landing_iterations`]: an avalanche of rings, each past its own fold). On
//! the smooth tip of Fig. 4.5 they cut a cycle's minimisations from 492 to 385 and its
//! factorisations from 4 866 to 3 024, 2 000 of them now in single precision (the directions
//! of [`StableNewton`]), along the same path: the same jumps, P_adh to 1e-10 and the loop area
//! to 2e-5.
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
    /// Largest number of Newton iterations of a landing, the minimisation from the last state
    /// on the branch just past its fold: a jump under way, which may need more iterations than
    /// a trial (an avalanche, ring after ring or spring after spring, each past its own
    /// fold), but just past the fold the way out of the vanished basin can be slow; a landing
    /// that needs more is tried again from further past the fold.
    pub landing_iterations: usize,
    /// Count a step whose start was unstable (the minimiser met an indefinite Hessian) as a
    /// jump even when the state moved little. Where the model's measure alone tells jumps
    /// apart, leave this off: a start just beyond a stable state can be slightly indefinite
    /// on a branch that goes on (a softening contact edge), and each such step would be
    /// bisected for nothing.
    pub unstable_start_is_jump: bool,
    /// Take a bisection trial whose minimiser meets an indefinite Hessian to lie beyond the
    /// fold at once, instead of letting it run its [`PathOptions::trial_iterations`] out of
    /// the vanished basin (most of a jump's cost). A trial on a branch that merely softens is
    /// then misjudged at the price of a little more bisection, never a wrong path: the state
    /// the bisection then lands on lies on the branch, and the walk goes on from there.
    pub indefinite_trial_is_beyond: bool,
    /// After a step whose minimum lay a jump away (a converged but distant state, a possible
    /// false alarm of the measure on a fast branch such as a receding contact edge), retry
    /// the rest of the step from the first bisection state on the branch before bisecting
    /// further: a false alarm then costs two minimisations instead of a bisection to
    /// [`PathOptions::refine_to`]. At most [`RETRIES`] retries per step; a real jump costs
    /// as many extra minimisations.
    pub retry_after_jump: bool,
}

/// Largest number of retries of the rest of a step ([`PathOptions::retry_after_jump`]).
pub const RETRIES: usize = 2;

/// What a minimisation of [`follow`] is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Trial {
    /// A step to the next target (or the rest of a step); with refinement it is capped and a
    /// jump it signals is bisected.
    Step,
    /// A bisection trial between the last state on the branch and a value beyond.
    Bisect,
    /// The jump from the last state on the branch, at the value the bisection found beyond
    /// it; capped unless that value is the target (`true`).
    Land(bool),
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
    /// Numeric factorisations of the Hessian (stability tests and tangents included).
    pub factorizations: usize,
    /// Jumps.
    pub jumps: usize,
    /// Whether every accepted state was certified stable.
    pub all_stable: bool,
}

/// The walk's current state and the trial just minimised.
struct Current<'a> {
    x: &'a mut Vec<f64>,
    trial: Vec<f64>,
    lambda: f64,
    stats: PathStats,
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
            x: &self.trial,
            jumped_from: jumped.then_some((self.lambda, self.x.as_slice())),
            stable,
            report,
            target,
        })?;
        std::mem::swap(self.x, &mut self.trial);
        self.lambda = at;
        Ok(())
    }
}

/// Walk the control values `targets` from the stable state `x` (updated in place to the last
/// state), handing every accepted state to `visit`. `interrupt` is called at every Newton
/// iteration of every minimisation; an error it returns (cancellation) stops the walk at once,
/// however long a minimisation runs.
///
/// # Errors
/// Minimiser failures ([`crate::error::Error::NoConvergence`]), and whatever `interrupt` or
/// `visit` returns.
///
/// # Panics
/// If `x.len()` differs from the energy's dimension.
// Eight inputs of distinct roles: the model and its solver, the start (λ, x), the targets,
// the options, and the two callbacks (every Newton iteration, every accepted state).
#[allow(clippy::too_many_arguments)]
pub fn follow<C: Controlled>(
    model: &C,
    solver: &mut StableNewton,
    x: &mut Vec<f64>,
    lambda_start: f64,
    targets: &[f64],
    opts: &PathOptions,
    interrupt: &mut dyn FnMut() -> Result<()>,
    mut visit: impl FnMut(&Visit<'_>) -> Result<()>,
) -> Result<PathStats> {
    let factorizations_before = solver.factorizations();
    let n = x.len();
    let mut walk = Current {
        trial: x.clone(),
        x,
        lambda: lambda_start,
        stats: PathStats {
            all_stable: true,
            ..PathStats::default()
        },
    };
    let trial_opts = NewtonOptions {
        max_iterations: opts.trial_iterations.min(opts.newton.max_iterations),
        ..opts.newton
    };
    let landing_opts = NewtonOptions {
        max_iterations: opts.landing_iterations.min(opts.newton.max_iterations),
        ..opts.newton
    };
    // Minimise from the walk's state at `at` into its trial: Some((report, jumped, stable)), or None when a
    // capped trial ran out of iterations (a jump under way) or, with
    // `indefinite_trial_is_beyond`, a bisection trial met an indefinite Hessian.
    let mut rate = vec![0.0; n];
    let mut predicted = Vec::with_capacity(n);
    let mut attempt =
        |w: &mut Current<'_>, at: f64, kind: Trial| -> Result<Option<(NewtonReport, bool, bool)>> {
            let (x, trial, from, stats) = (&*w.x, &mut w.trial, w.lambda, &mut w.stats);
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
            let capped = match kind {
                Trial::Step => opts.refine_to.is_some_and(|tol| (at - from).abs() > tol),
                Trial::Bisect => true,
                Trial::Land(at_target) => !at_target,
            };
            let newton = match kind {
                Trial::Land(false) => &landing_opts,
                _ if capped => &trial_opts,
                _ => &opts.newton,
            };
            let leave_on_indefinite = kind == Trial::Bisect && opts.indefinite_trial_is_beyond;
            let mut watch = |rep: &NewtonReport| {
                interrupt()?;
                if leave_on_indefinite && rep.left_unstable_state() {
                    Err(Error::NoConvergence {
                        method: "bisection trial (indefinite Hessian: beyond the fold)",
                        iterations: rep.iterations,
                        residual: f64::NAN,
                    })
                } else {
                    Ok(())
                }
            };
            // A bisection trial's verdict is its first Hessian: no warm start there.
            let warm = solver.warm_start();
            solver.set_warm_start(warm && kind != Trial::Bisect);
            let result = solver.minimize_watched(&e, trial, newton, &mut watch);
            solver.set_warm_start(warm);
            let rep = match result {
                Ok(rep) => rep,
                Err(Error::NoConvergence { iterations, .. }) if capped => {
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
        'step: loop {
            let refine = opts.refine_to.filter(|&tol| (target - walk.lambda).abs() > tol);
            let first = attempt(&mut walk, target, Trial::Step)?;
            if let Some((rep, jumped, stable)) = first
                && (!jumped || refine.is_none())
            {
                walk.accept(&mut visit, target, (rep, jumped, stable), k)?;
                break;
            }
            // A converged state a jump away may be a false alarm of the measure: retry the
            // rest of the step from the first bisection state on the branch.
            let mut retries = if opts.retry_after_jump && first.is_some() {
                RETRIES
            } else {
                0
            };
            // Bisect towards the fold: accept trial states that stay on the branch.
            let tol = refine.unwrap_or(0.0);
            let mut hi = target;
            while (hi - walk.lambda).abs() > tol {
                let mid = 0.5 * (walk.lambda + hi);
                match attempt(&mut walk, mid, Trial::Bisect)? {
                    Some((rep, false, stable)) => {
                        walk.accept(&mut visit, mid, (rep, false, stable), k)?;
                        if retries > 0 {
                            retries -= 1;
                            match attempt(&mut walk, hi, Trial::Step)? {
                                Some((rep, false, stable)) => {
                                    walk.accept(&mut visit, hi, (rep, false, stable), k)?;
                                    if hi == target {
                                        break 'step;
                                    }
                                    continue 'step;
                                }
                                Some(_) => {}
                                None => retries = 0,
                            }
                        }
                    }
                    _ => hi = mid,
                }
            }
            // `hi` is within the tolerance of the last state on the branch: jump there (or,
            // when the bisection found no jump after all, go on from here). Just past a fold
            // the way out is slowest; where the minimiser does not find it, the jump is taken
            // from further past the fold (doubling the distance, at most to the target).
            let mut at = hi;
            let (rep, jumped, stable) = loop {
                let full = (at - target).abs() <= f64::EPSILON * target.abs().max(1.0);
                match attempt(&mut walk, at, Trial::Land(full))? {
                    Some(found) => break found,
                    None => {
                        let further = walk.lambda + 2.0 * (at - walk.lambda);
                        at = if (further - walk.lambda).abs() >= (target - walk.lambda).abs() {
                            target
                        } else {
                            further
                        };
                    }
                }
            };
            walk.accept(&mut visit, at, (rep, jumped, stable), k)?;
            if at == target {
                break;
            }
        }
    }
    walk.stats.factorizations = solver.factorizations() - factorizations_before;
    Ok(walk.stats)
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
        walk_with(model, &options(refine))
    }

    /// The options of the walks: refinement to `refine`, the plain bisection.
    fn options(refine: Option<f64>) -> PathOptions {
        PathOptions {
            newton: NewtonOptions::default(),
            refine_to: refine,
            trial_iterations: 50,
            landing_iterations: 50,
            unstable_start_is_jump: true,
            indefinite_trial_is_beyond: false,
            retry_after_jump: false,
        }
    }

    fn walk_with<C: Controlled>(model: &C, opts: &PathOptions) -> Walk {
        let mut solver = StableNewton::new(&WellAt(0.0)).expect("1x1 pattern");
        // Start in the left well at λ = -0.1 and tilt to the right until it vanishes.
        let mut x = vec![-1.0];
        let targets = targets();
        let mut states = Vec::new();
        let mut jumps = Vec::new();
        let stats = follow(
            model,
            &mut solver,
            &mut x,
            -0.2,
            &targets,
            opts,
            &mut || Ok(()),
            |v| {
                states.push((v.lambda, v.x[0]));
                if let Some((l0, x0)) = v.jumped_from {
                    jumps.push((l0, v.lambda, x0[0]));
                }
                Ok(())
            },
        )
        .expect("walk");
        (states, jumps, stats)
    }

    // Bisection trials past the fold stop at their first indefinite Hessian instead of running
    // their iterations out of the vanished basin: the same fold, the same landing, fewer
    // Newton iterations. (Jumps decided by the measure alone, as for the tips of chapter 4.)
    #[test]
    fn bisection_trials_past_the_fold_stop_at_the_first_indefinite_hessian() {
        let slow = PathOptions {
            unstable_start_is_jump: false,
            ..options(Some(1e-9))
        };
        let fast = PathOptions {
            indefinite_trial_is_beyond: true,
            ..slow
        };
        let (states_slow, jumps_slow, stats_slow) = walk_with(&Well, &slow);
        let (states_fast, jumps_fast, stats_fast) = walk_with(&Well, &fast);
        assert_eq!((jumps_slow.len(), jumps_fast.len()), (1, 1));
        let fold = 2.0 / (3.0 * 3f64.sqrt());
        for j in [jumps_slow[0], jumps_fast[0]] {
            assert!((j.0 - fold).abs() < 1e-8 && j.1 > fold, "{j:?}");
        }
        let landed = |s: &[(f64, f64)], l: f64| s.iter().find(|p| p.0 == l).expect("landing").1;
        assert!((landed(&states_slow, jumps_slow[0].1) - landed(&states_fast, jumps_fast[0].1)).abs() < 1e-8);
        assert!(stats_fast.all_stable);
        assert!(
            stats_fast.newton_iterations < stats_slow.newton_iterations,
            "{} vs {}",
            stats_fast.newton_iterations,
            stats_slow.newton_iterations
        );
    }

    /// A branch that moves fast but smoothly: E = ½(x − 10λ)², so every step of 0.06 moves
    /// x by 0.6, beyond the jump measure's threshold of 0.5 (a false alarm).
    struct Fast;
    struct FastAt(f64);
    impl Energy for FastAt {
        fn dim(&self) -> usize {
            1
        }
        fn energy(&self, x: &[f64]) -> f64 {
            0.5 * (x[0] - 10.0 * self.0).powi(2)
        }
        fn gradient(&self, x: &[f64], g: &mut [f64]) {
            g[0] = x[0] - 10.0 * self.0;
        }
        fn hessian_pattern(&self) -> Vec<(usize, usize)> {
            vec![(0, 0)]
        }
        fn hessian_values(&self, _: &[f64], v: &mut [f64]) {
            v[0] = 1.0;
        }
    }
    impl Controlled for Fast {
        type At<'a> = FastAt;
        fn at(&self, lambda: f64) -> FastAt {
            FastAt(lambda)
        }
        fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
            Well.jump_measure(before, after)
        }
    }

    // A false alarm of the measure on a fast smooth branch: retrying the rest of the step from
    // the first bisection state on the branch walks the same path (no jump, the same final
    // state) in a fraction of the minimisations a bisection to the tolerance takes.
    #[test]
    fn a_false_alarm_is_resolved_by_retrying_the_rest_of_the_step() {
        let plain = PathOptions {
            unstable_start_is_jump: false,
            ..options(Some(1e-9))
        };
        let retry = PathOptions {
            retry_after_jump: true,
            ..plain
        };
        let run = |opts: &PathOptions| {
            let mut solver = StableNewton::new(&FastAt(0.0)).expect("1x1 pattern");
            let mut x = vec![-2.0];
            let mut last = (0.0, 0.0);
            let stats = follow(
                &Fast,
                &mut solver,
                &mut x,
                -0.2,
                &targets(),
                opts,
                &mut || Ok(()),
                |v| {
                    assert!(v.jumped_from.is_none(), "no jump on a smooth branch");
                    last = (v.lambda, v.x[0]);
                    Ok(())
                },
            )
            .expect("walk");
            (stats, last)
        };
        let (stats_plain, last_plain) = run(&plain);
        let (stats_retry, last_retry) = run(&retry);
        assert_eq!((stats_plain.jumps, stats_retry.jumps), (0, 0));
        assert_eq!(last_plain.0, 0.5);
        assert_eq!(last_retry.0, 0.5);
        assert!((last_plain.1 - 5.0).abs() < 1e-9 && (last_retry.1 - 5.0).abs() < 1e-9);
        assert!(
            4 * stats_retry.minimisations < stats_plain.minimisations,
            "{} vs {}",
            stats_retry.minimisations,
            stats_plain.minimisations
        );
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

    #[test]
    fn without_refinement_the_jump_is_reported_at_its_step() {
        let (_, jumps, stats) = walk(None);
        assert_eq!(jumps.len(), 1);
        assert!((jumps[0].1 - 0.44).abs() < 1e-12, "{:?}", jumps[0]);
        assert_eq!(stats.states, 11);
    }
}
