//! Displacement-controlled loading-unloading cycles of a [`Tip`] (sections 4.3-4.5): the tip
//! approaches from far, is pressed to the maximum depth |h_min| and retracted, and every state
//! the experiment visits is a stable equilibrium reached from the previous one by
//! [`crate::numerics::loading::follow`], with each jump (pull-in, pull-off, the asperity-level
//! instabilities of a wavy tip) located by bisection of the step.
//!
//! Reported per cycle: the measured P-h path, the jumps with the states on both sides, the
//! adhesive force P_adh (the most tensile force of the path) and the hysteresis H (the area of
//! the loop, −∮ P dh, the energy lost in the cycle).

use std::cell::{Cell, RefCell};

use crate::error::{Error, Result};
use crate::models::axisymmetric::tip::{ContactSet, Tip};
use crate::numerics::loading::{Controlled, PathOptions, PathStats, follow};
use crate::numerics::newton::{LinearSolver, NewtonOptions, StableNewton};
use crate::numerics::quadrature::trapezoid;

/// One accepted state of a cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct TipState {
    /// Indentation depth h [m] (negative: pressed beyond the equilibrium distance).
    pub depth: f64,
    /// Force P [N], compressive positive.
    pub force: f64,
    /// Contact set (gap below the threshold).
    pub contact: ContactSet,
    /// Whether the state was certified stable (positive-definite Hessian).
    pub stable: bool,
    /// Ring displacements (normal units), kept for the states a figure draws; empty otherwise.
    pub displacement: Vec<f64>,
}

/// A jump of the cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct TipJump {
    /// Whether it happened on loading.
    pub loading: bool,
    /// The last state on the branch (depth within the refinement tolerance of the fold).
    pub before: TipState,
    /// The state after the jump.
    pub after: TipState,
}

impl TipJump {
    /// Whether the contact area grew (a pull-in, of the tip or of an asperity).
    pub fn is_pull_in(&self) -> bool {
        self.after.contact.area() > self.before.contact.area()
    }
}

/// A loading-unloading cycle.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TipCycle {
    /// Loading states, depth decreasing.
    pub loading: Vec<TipState>,
    /// Unloading states, depth increasing.
    pub unloading: Vec<TipState>,
    /// Jumps in the order they happened.
    pub jumps: Vec<TipJump>,
    /// Cost and certification of the walk.
    pub stats: PathStats,
}

impl TipCycle {
    /// Adhesive force P_adh: the most tensile force on the measured path [N] (negative).
    pub fn adhesive_force(&self) -> f64 {
        self.loading
            .iter()
            .chain(&self.unloading)
            .map(|s| s.force)
            .fold(0.0, f64::min)
    }

    /// Hysteresis H = −∮ P dh over the measured path [J]: the area between loading and
    /// unloading, with every jump vertical at its fold.
    ///
    /// The state after a jump lies where the minimiser found the way out, which may be up to
    /// one step past the fold (the energy just past a fold is flat and the way out slow). The
    /// stretch from the fold to that state lies on the new branch, so it is integrated with
    /// the force after the jump: an error of order (step)² · dP/dh. A trapezoid through the
    /// jump would add half the force jump times that stretch, an error of first order in
    /// the step (0.4 % of H between steps of 0.1 ζ0 and 0.05 ζ0 on the smooth tip of
    /// Fig. 4.5).
    pub fn hysteresis(&self) -> f64 {
        let path = |phase: bool, states: &mut dyn Iterator<Item = &TipState>| {
            let jumps: Vec<&TipJump> = self.jumps.iter().filter(|j| j.loading == phase).collect();
            let mut next = jumps.iter().peekable();
            let mut pts: Vec<(f64, f64)> = Vec::new();
            for s in states {
                if let Some(j) = next.peek()
                    && j.after.depth == s.depth
                    && j.after.force == s.force
                {
                    pts.push((j.before.depth, s.force));
                    next.next();
                }
                pts.push((s.depth, s.force));
            }
            pts
        };
        let load = path(true, &mut self.loading.iter());
        // Unloading starts where loading turned.
        let unload = path(false, &mut self.loading.last().into_iter().chain(&self.unloading));
        // Loading runs to decreasing depth: ∫ P dh there is negative of the area under it.
        -(trapezoid(&load) + trapezoid(&unload))
    }

    /// Number of jumps on loading and on unloading.
    pub fn jump_counts(&self) -> (usize, usize) {
        let l = self.jumps.iter().filter(|j| j.loading).count();
        (l, self.jumps.len() - l)
    }
}

/// How a cycle is run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleOptions {
    /// Depth at the start and end of the cycle [m] (positive: apart).
    pub h_start: f64,
    /// Deepest depth h_min [m] (negative).
    pub h_min: f64,
    /// Depth step [m].
    pub step: f64,
    /// Jumps are located to this depth tolerance [m].
    pub refine_to: f64,
    /// Contact threshold of the gap [m] (σ in section 4.2.2).
    pub contact_gap: f64,
    /// Keep the ring displacements of every state (for profiles); otherwise of jump states
    /// only.
    pub keep_profiles: bool,
    /// Stop unloading at this depth [m] instead of returning to the start (a figure that needs
    /// only part of the unloading path); `None`: the whole cycle.
    pub unload_to: Option<f64>,
}

/// A model of a tip that a cycle can drive: the surface model [`Tip`] and the finite-element
/// model [`crate::models::body_force_fe::tip::FeTip`]. The control value is the approach δ of
/// the undeformed apex in the model's normal length unit.
pub trait CycleModel: Controlled {
    /// Number of unknowns.
    fn unknowns(&self) -> usize;
    /// The normal length unit [m].
    fn length_unit(&self) -> f64;
    /// Indentation depth h [m] of approach `delta`.
    fn depth(&self, delta: f64) -> f64;
    /// Approach of depth `h` [m], the inverse of [`CycleModel::depth`].
    fn approach(&self, h: f64) -> f64;
    /// Force on the tip, compressive positive [N].
    fn force(&self, delta: f64, u: &[f64]) -> f64;
    /// The contact set with the gap threshold `threshold` [m].
    fn contact(&self, delta: f64, u: &[f64], threshold: f64) -> ContactSet;
    /// How the minimiser solves its linear systems.
    fn linear_solver(&self) -> LinearSolver {
        LinearSolver::Auto
    }
    /// Adapt how the path is followed (see [`PathOptions`]); by default nothing changes.
    fn tune_path(&self, _path: &mut PathOptions) {}
    /// Whether the minimiser starts each load step warm, with chord steps on the last
    /// accepted state's factorisation ([`StableNewton::set_warm_start`]); by default not.
    fn warm_start(&self) -> bool {
        false
    }
    /// Whether Newton directions far from convergence come from single-precision sparse
    /// factorisations ([`StableNewton::set_single_precision_directions`]); by default not.
    fn single_precision_directions(&self) -> bool {
        false
    }
    /// Seconds of one core an accepted state of a cycle costs, about; `None` where no
    /// estimate is known. [`run_cycle`] refuses a cycle estimated above
    /// [`MAX_CYCLE_SECONDS`].
    fn seconds_per_state(&self) -> Option<f64> {
        None
    }
}

/// Longest cycle [`run_cycle`] starts, in estimated seconds of one core: a run of hours at a
/// fine depth step over a deep cycle is refused at once rather than left running.
pub const MAX_CYCLE_SECONDS: f64 = 3600.0;

/// Seconds of one core per accepted state and per ring³ of the surface model (its dense
/// factorisations): Fig. 4.5's smooth cycle, 354 rings and 270 states, takes 1.52 s (median
/// of `cargo bench --bench ch4`), Fig. 4.7's deep wavy cycle 3.1 s for 505 rings and 264
/// states (this constant predicts 4.3 s).
const SECONDS_PER_STATE_AND_RING3: f64 = 1.3e-10;

impl CycleModel for Tip {
    fn unknowns(&self) -> usize {
        self.len()
    }
    fn length_unit(&self) -> f64 {
        self.scales().length
    }
    fn depth(&self, delta: f64) -> f64 {
        Tip::depth(self, delta)
    }
    fn approach(&self, h: f64) -> f64 {
        Tip::approach(self, h)
    }
    fn force(&self, delta: f64, u: &[f64]) -> f64 {
        Tip::force(self, delta, u)
    }
    fn contact(&self, delta: f64, u: &[f64], threshold: f64) -> ContactSet {
        Tip::contact(self, delta, u, threshold)
    }
    fn seconds_per_state(&self) -> Option<f64> {
        Some(SECONDS_PER_STATE_AND_RING3 * (self.len() as f64).powi(3))
    }
}

/// Run one cycle. `progress(fraction)` is called after every accepted state, and with the last
/// fraction at every Newton iteration in between; it may return an error to stop
/// (cancellation), which a long minimisation then honours at its next iteration.
///
/// # Errors
/// [`Error::InvalidParameter`] for an empty or reversed depth range, a non-positive step or a
/// cycle estimated above [`MAX_CYCLE_SECONDS`]; minimiser failures; errors of `progress`.
pub fn run_cycle<M: CycleModel>(
    tip: &M,
    opts: &CycleOptions,
    progress: impl FnMut(f64) -> Result<()>,
) -> Result<TipCycle> {
    walk(tip, opts, false, progress, |_| {})
}

/// [`run_cycle`], showing the cycle as far as it goes to `on_state` after every accepted state
/// (its jumps included), for a live figure.
///
/// # Errors
/// As [`run_cycle`].
pub fn run_cycle_watched<M: CycleModel>(
    tip: &M,
    opts: &CycleOptions,
    progress: impl FnMut(f64) -> Result<()>,
    on_state: impl FnMut(&TipCycle),
) -> Result<TipCycle> {
    walk(tip, opts, false, progress, on_state)
}

/// Press a tip whose energy is convex in its unknowns at every depth, such as a tip without
/// attraction (C6 = 0: the repulsive ψ(d) ∝ d⁻⁸ of the body force (4.15) and the strain energy
/// are convex), from `opts.h_start` to `opts.h_min` in steps of about `opts.step`: the loading
/// half of [`run_cycle`], with no unloading (`opts.unload_to` is not used).
///
/// A convex energy has one equilibrium at each depth, which the stable minimiser reaches from
/// any start in its domain, so the path has no jump to locate: each step is one minimisation
/// from the previous state, however far it moves (no bisection of the steps that
/// [`Controlled::jump_measure`] would take for jumps: on the adhesionless tip of Fig. 4.4
/// pressed to 300 σ, 18 312 unknowns, 76 steps of 4 σ cost 1 497 Newton iterations and 14 s,
/// 16 steps of 20 σ 317 and 3.2 s, 4 steps of 100 σ 95 and 1.3 s, with the same deviation from
/// Hertz to four digits, where [`run_cycle`] took 12 minutes for two such paths of 76 states,
/// of 18 312 and 32 215 unknowns, most of it bisecting steps that moved the contact by more
/// than the jump measure's unit). A state whose minimisation
/// started from an indefinite Hessian (impossible for a convex energy: it would show that the
/// model is not) is recorded as a jump, and every state is certified stable as in
/// [`run_cycle`].
///
/// # Errors
/// As [`run_cycle`].
pub fn run_convex_loading<M: CycleModel>(
    tip: &M,
    opts: &CycleOptions,
    progress: impl FnMut(f64) -> Result<()>,
) -> Result<TipCycle> {
    walk(tip, opts, true, progress, |_| {})
}

/// [`run_cycle`], or with `convex` [`run_convex_loading`].
fn walk<M: CycleModel>(
    tip: &M,
    opts: &CycleOptions,
    convex: bool,
    progress: impl FnMut(f64) -> Result<()>,
    mut on_state: impl FnMut(&TipCycle),
) -> Result<TipCycle> {
    if !(opts.h_min < opts.h_start && opts.h_min.is_finite() && opts.h_start.is_finite()) {
        return Err(Error::invalid(
            "h_min",
            opts.h_min,
            "must be below the start depth",
        ));
    }
    if !(opts.step > 0.0 && opts.step.is_finite()) {
        return Err(Error::invalid("step", opts.step, "must be positive"));
    }
    let n_steps = ((opts.h_start - opts.h_min) / opts.step).ceil() as usize;
    if n_steps > 1_000_000 {
        return Err(Error::invalid(
            "step",
            opts.step,
            format!("gives {n_steps} steps per phase, more than 1e6"),
        ));
    }
    let depths: Vec<f64> = (0..=n_steps)
        .map(|k| opts.h_start - (opts.h_start - opts.h_min) * k as f64 / n_steps as f64)
        .collect();
    let approach = |h: f64| tip.approach(h);
    let loading: Vec<f64> = depths.iter().skip(1).map(|&h| approach(h)).collect();
    let unloading: Vec<f64> = if convex {
        Vec::new()
    } else {
        depths
            .iter()
            .rev()
            .skip(1)
            .take_while(|&&h| opts.unload_to.is_none_or(|end| h <= end))
            .map(|&h| approach(h))
            .collect()
    };
    if let Some(per_state) = tip.seconds_per_state() {
        let states = loading.len() + unloading.len();
        let seconds = per_state * states as f64;
        if seconds > MAX_CYCLE_SECONDS {
            return Err(Error::invalid(
                "step",
                opts.step,
                format!(
                    "a cycle of {} depth steps on {} unknowns would take about {:.0} min of one core \
                     (at most {:.0} min): take larger depth steps, a shallower cycle or wider rings",
                    states,
                    tip.unknowns(),
                    seconds / 60.0,
                    MAX_CYCLE_SECONDS / 60.0
                ),
            ));
        }
    }
    let newton = NewtonOptions {
        gradient_tol: 1e-7,
        step_tol: 1e-6,
        max_iterations: 1000,
        linear: tip.linear_solver(),
    };
    let mut path = PathOptions {
        newton,
        refine_to: Some(opts.refine_to / tip.length_unit()),
        trial_iterations: 40,
        landing_iterations: 160,
        unstable_start_is_jump: false,
        indefinite_trial_is_beyond: true,
        retry_after_jump: true,
    };
    tip.tune_path(&mut path);
    if convex {
        // One minimisation per step, run to the minimiser's limit: no jump to locate.
        path.refine_to = None;
        path.retry_after_jump = false;
        path.indefinite_trial_is_beyond = false;
    }
    let start = approach(opts.h_start);
    let start_energy = tip.at(start);
    let mut solver = StableNewton::new(&start_energy)?;
    solver.set_linear(newton.linear);
    solver.set_warm_start(tip.warm_start());
    solver.set_single_precision_directions(tip.single_precision_directions());
    let mut u = vec![0.0; tip.unknowns()];
    let progress = RefCell::new(progress);
    let reported = Cell::new(0.0);
    let mut interrupt = || progress.borrow_mut()(reported.get());
    // Relax at the start depth.
    solver.minimize_watched(&start_energy, &mut u, &newton, &mut |_| interrupt())?;
    let state = |delta: f64, u: &[f64], stable: bool, keep: bool| TipState {
        depth: tip.depth(delta),
        force: tip.force(delta, u),
        contact: tip.contact(delta, u, opts.contact_gap),
        stable,
        displacement: if keep { u.to_vec() } else { Vec::new() },
    };
    let start_stable = solver.is_stable(&start_energy, &u)?;
    let mut cycle = TipCycle::default();
    cycle.stats.all_stable = start_stable;
    cycle
        .loading
        .push(state(start, &u, start_stable, opts.keep_profiles));
    let total = (loading.len() + unloading.len()) as f64;
    let mut done = 0usize;
    let mut last_delta = start;
    for (phase, targets) in [(true, &loading), (false, &unloading)] {
        let stats = follow(
            tip,
            &mut solver,
            &mut u,
            last_delta,
            targets,
            &path,
            &mut interrupt,
            |v| {
                let s = state(
                    v.lambda,
                    v.x,
                    v.stable,
                    opts.keep_profiles || (!convex && v.jumped_from.is_some()),
                );
                if convex {
                    // A convex energy's step moves far without jumping: its only sign of an
                    // instability is an unstable start (the state before is the last one
                    // recorded, with its displacements only where profiles are kept).
                    if v.report.left_unstable_state() {
                        let before = if phase {
                            cycle.loading.last()
                        } else {
                            cycle.unloading.last()
                        };
                        if let Some(before) = before.cloned() {
                            cycle.jumps.push(TipJump {
                                loading: phase,
                                before,
                                after: s.clone(),
                            });
                        }
                    }
                } else if let Some((l0, x0)) = v.jumped_from {
                    cycle.jumps.push(TipJump {
                        loading: phase,
                        before: state(l0, x0, true, true),
                        after: s.clone(),
                    });
                }
                if phase {
                    cycle.loading.push(s);
                } else {
                    cycle.unloading.push(s);
                }
                on_state(&cycle);
                done = done.max(v.target + 1 + if phase { 0 } else { loading.len() });
                reported.set(done as f64 / total);
                progress.borrow_mut()(reported.get())
            },
        )?;
        last_delta = *targets.last().unwrap_or(&last_delta);
        cycle.stats.states += stats.states;
        cycle.stats.minimisations += stats.minimisations;
        cycle.stats.newton_iterations += stats.newton_iterations;
        cycle.stats.factorizations += stats.factorizations;
        cycle.stats.jumps += stats.jumps;
        cycle.stats.all_stable &= stats.all_stable;
    }
    if convex {
        // The walk's steps move far without jumping: only unstable starts count (see above).
        cycle.stats.jumps = cycle.jumps.len();
    }
    Ok(cycle)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(depth: f64, force: f64) -> TipState {
        TipState {
            depth,
            force,
            contact: ContactSet::default(),
            stable: true,
            displacement: Vec::new(),
        }
    }

    /// A loop with a free branch (P = 0) and a contact branch (P = −1): pull-in at the fold
    /// h = 1, pull-off at the fold h = 1.5, and each state after a jump found one step past its
    /// fold (h = 0 and h = 2). With vertical jumps the loop spans 1 ≤ h ≤ 1.5 between the
    /// branches: H = 0.5 exactly (a trapezoid through the jumps gives 0.75).
    #[test]
    fn jumps_are_vertical_at_their_folds_in_the_loop_area() {
        let loading = vec![
            state(2.0, 0.0),
            state(1.0, 0.0),
            state(0.0, -1.0),
            state(-1.0, -1.0),
        ];
        let unloading = vec![
            state(0.0, -1.0),
            state(1.0, -1.0),
            state(1.5, -1.0),
            state(2.0, 0.0),
        ];
        let jumps = vec![
            TipJump {
                loading: true,
                before: loading[1].clone(),
                after: loading[2].clone(),
            },
            TipJump {
                loading: false,
                before: unloading[2].clone(),
                after: unloading[3].clone(),
            },
        ];
        let cycle = TipCycle {
            loading,
            unloading,
            jumps,
            stats: PathStats::default(),
        };
        assert!((cycle.hysteresis() - 0.5).abs() < 1e-15, "{}", cycle.hysteresis());
    }

    /// A cycle estimated at 1.5 hours (Fig. 4.5's tip in steps of about 1e-4 ζ0) is refused at
    /// once with the estimate, before any minimisation; Fig. 4.5's default cycle is not.
    #[test]
    fn a_cycle_of_hours_is_refused_before_it_starts() {
        use crate::models::axisymmetric::tip::TipParams;
        // Fig. 4.5's tip with the benchmark's fine zone: 354 rings.
        let tip = Tip::new(&TipParams {
            fine_radius: 4e-7,
            ..TipParams::default()
        })
        .expect("tip");
        let z = tip.scales().length;
        let per_state = tip.seconds_per_state().expect("an estimate");
        let opts = |step: f64| CycleOptions {
            h_start: 12.0 * z,
            h_min: -15.0 * z,
            step: step * z,
            refine_to: 1e-3 * z,
            contact_gap: 1e-9,
            keep_profiles: false,
            unload_to: None,
        };
        let fine = MAX_CYCLE_SECONDS / per_state / 2.0 * 1.5;
        let step = 27.0 / fine;
        let started = std::time::Instant::now();
        let err = run_cycle(&tip, &opts(step), |_| Ok(())).expect_err("refused");
        assert!(started.elapsed().as_secs_f64() < 1.0);
        let msg = err.to_string();
        assert!(msg.contains("min of one core") && !msg.contains('\n'), "{msg}");
        assert!(
            per_state * 2.0 * (27.0 / 0.2) < 10.0,
            "the default cycle is estimated in seconds"
        );
    }
}
