//! Coupled spring arrays (section 5.6): force-displacement cycles (Fig. 5.10), the contact
//! ratio over the cycle (Fig. 5.11), and the accuracy of the coupled solver against its run
//! time (Fig. 5.10-accuracy).

use super::ensemble::{cycle_window, k_bar_of_n};
use crate::error::Result;
use crate::figure::{Axis, Figure, Panel, Series, Style};
use crate::job::Job;
use crate::params::{Range, require_non_empty};
use crate::scenes::groups::{ArrayCycle, ArraySurface};
use crate::scenes::{Scene, SceneHeader};

crate::scene_params! {
    /// Parameters of scenes fig5.10 and fig5.11 (section 5.6).
    pub struct CouplingParams {
        /// Stiffness exponent n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponent: f64 = 10.0, unit = "", range = Range::open(0.0, 30.0);
        /// Coupling stiffnesses k_μ in units of k_e.
        couplings: Vec<f64> = vec![0.0, 2.0, 10.0], unit = "", range = Range::non_negative();
        /// The rough surface.
        group surface: ArraySurface;
        /// Springs N along ê₁.
        springs_x: usize = 256, unit = "", range = Range::between(1.0, 4096.0);
        /// Springs M along ê₂.
        springs_y: usize = 1, unit = "", range = Range::between(1.0, 4096.0);
        /// Seed of the surface.
        seed: u64 = 1, unit = "", range = Range::non_negative();
        /// The displacement cycle.
        group cycle: ArrayCycle;
        /// Newton tolerance on the largest gradient component.
        gradient_tol: f64 = 1e-10, unit = "", range = Range::positive();
    }
}

/// The coupled cycles of the coupling study (rayon over couplings).
fn coupling_study(
    p: &CouplingParams,
    job: &Job,
) -> Result<Vec<(f64, crate::models::spring_array::ArrayCycle)>> {
    use rayon::prelude::*;
    let k_e = k_bar_of_n(p.stiffness_exponent);
    let z = p.surface.heights(p.springs_x, p.springs_y, p.seed)?;
    let window = p.cycle.window(k_e, p.surface.roughness)?;
    // The iterative path at every size: it resolves avalanches locally (a chain of coupled
    // springs can have hundreds of generations in one step, one direct iteration each) and
    // ends jumps where the overdamped dynamics end them.
    let opts = crate::numerics::newton::NewtonOptions {
        gradient_tol: p.gradient_tol,
        linear: crate::numerics::newton::LinearSolver::Iterative,
        ..Default::default()
    };
    // Each coupling reports its fraction of steps; the run's progress is their mean, so the
    // gauge reaches 100 % only when the slowest (most strongly coupled) cycle is done.
    let fractions = std::sync::Mutex::new(vec![0.0; p.couplings.len()]);
    let n_couplings = p.couplings.len();
    p.couplings
        .par_iter()
        .enumerate()
        .map(|(slot, &mult)| {
            let a = crate::models::spring_array::SpringArray::new(
                p.springs_x,
                p.springs_y,
                k_e,
                mult * k_e,
                z.clone(),
            )?;
            let c = crate::models::spring_array::coupled_cycle(
                &a,
                window.0,
                window.1,
                p.cycle.steps,
                &opts,
                |f| {
                    job.check()?;
                    // Reported under the lock, so the means arrive in order.
                    let Ok(mut all) = fractions.lock() else {
                        // Another coupling panicked holding the lock; its error will surface.
                        return Ok(());
                    };
                    all[slot] = f;
                    let mean = all.iter().sum::<f64>() / n_couplings as f64;
                    let steps = (mean * (2 * p.cycle.steps * n_couplings) as f64).round();
                    // The figure is built after the last step: `done` brings the 1.
                    job.progress(
                        0.99 * mean,
                        &format!(
                            "coupled cycles: {steps:.0}/{} steps of {n_couplings} couplings",
                            2 * p.cycle.steps * n_couplings
                        ),
                    );
                    Ok(())
                },
            )?;
            Ok((mult, c))
        })
        .collect()
}

/// The checks, quick form and memory estimate of the coupling study, which Figs. 5.10 and 5.11
/// share (items of their `Scene` impls).
macro_rules! coupling_study_checks {
    () => {
        fn validate(p: &Self::Params) -> Result<()> {
            require_non_empty("couplings", &p.couplings)
        }

        fn quick(p: &mut Self::Params) {
            p.springs_x = p.springs_x.min(32);
            p.springs_y = p.springs_y.min(2);
            p.cycle.quick();
        }

        /// Peak memory of the coupling study: about 512 bytes per spring and coupling
        /// (heights, state, sparse tangent and the iterative solver's vectors; measured
        /// 450-490 bytes at 256² and 1024² springs with three couplings), all couplings at
        /// once, plus 64 MiB.
        fn memory_estimate(p: &Self::Params) -> Option<crate::scenes::MemoryEstimate> {
            let springs = p.springs_x as f64 * p.springs_y as f64;
            Some(crate::scenes::MemoryEstimate {
                bytes: 64.0 * 1024.0 * 1024.0 + 512.0 * springs * p.couplings.len().max(1) as f64,
                parameter: "springs_x x springs_y",
                value: format!("{} x {}", p.springs_x, p.springs_y),
            })
        }
    };
}

crate::scene! {
    /// Fig. 5.10: force-displacement cycles for several coupling stiffnesses.
    pub struct Fig5_10 {
        id: "fig5.10",
        chapter: "5",
        params: CouplingParams,
        title: "Coupled springs: force-displacement cycles",
        caption: "Total force P/(MN |P_m|) (positive in compression) against u/sigma for coupling \
            k_mu = 0, 2 k_e, 10 k_e; 256 x 1 springs, k_e = 2^-10 k_cr, sigma_rms/sigma = 100, L_c = 0.01; \
            equilibria (5.31)-(5.34) by the stable sparse Newton solver, every accepted state with a \
            positive-definite tangent.",
        results: &[
            ("efficiency_uncoupled_norm", "adhesion efficiency (5.36), first coupling"),
            ("efficiency_strongest_norm", "adhesion efficiency (5.36), last coupling"),
            ("hysteresis_uncoupled_norm", "energy lost over the cycle in units of MN |P_m| sigma, first coupling"),
            ("hysteresis_strongest_norm", "as above, last coupling"),
            ("jumps_uncoupled_count", "displacement steps with jumps, first coupling"),
            ("all_states_stable_count", "1 if every accepted state had a positive-definite tangent, else 0"),
        ],
    }
}

impl Scene for Fig5_10 {
    coupling_study_checks!();

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let cycles = coupling_study(p, job)?;
        let n = p.springs_x * p.springs_y;
        let norm = n as f64 * crate::models::spring_array::single_spring_adhesive_force().abs();
        let mut panel = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear("Force P/(MN |P_m|)", ""),
        );
        for (c, (mult, cy)) in cycles.iter().enumerate() {
            let name = format!("k_μ = {mult} k_e");
            for phase in [&cy.loading, &cy.unloading] {
                let pts: Vec<(f64, f64)> = phase.iter().map(|s| (s.u, s.force / norm)).collect();
                panel.add(Series::new(&name, Style::Stable, pts).with_color(c));
            }
        }
        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(panel);
        let first = &cycles[0].1;
        let last = &cycles[cycles.len() - 1].1;
        fig.result(
            "efficiency_uncoupled_norm",
            crate::models::spring_array::adhesion_efficiency(first, n),
        );
        fig.result(
            "efficiency_strongest_norm",
            crate::models::spring_array::adhesion_efficiency(last, n),
        );
        fig.result("hysteresis_uncoupled_norm", first.hysteresis() / norm);
        fig.result("hysteresis_strongest_norm", last.hysteresis() / norm);
        fig.result("jumps_uncoupled_count", first.jumps.len() as f64);
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(cycles.iter().all(|(_, c)| c.all_stable))),
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// Axis title of the contact ratio, with its definition: springs in contact over all.
const CONTACT_RATIO_LABEL: &str = "Contact ratio N_c/(MN)";

/// A direction mark on a curve given in the order of travel: a short arrow (the renderer gives
/// it a head of fixed size) at the point where the curve's value first crosses half its range,
/// pointing along the chord to the first point 4 % of the span of u further on (the average
/// direction over the steps of a stair-like curve). `None` for a curve without such points.
fn travel_arrow(pts: &[(f64, f64)]) -> Option<((f64, f64), (f64, f64))> {
    let (lo, hi) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let (u_lo, u_hi) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    if !(hi > lo && u_hi > u_lo) {
        return None;
    }
    let mid = 0.5 * (lo + hi);
    let k = pts
        .windows(2)
        .position(|w| (w[0].1 - mid) * (w[1].1 - mid) <= 0.0)?;
    let step = 0.04 * (u_hi - u_lo);
    let j = (k + 1..pts.len()).find(|&j| (pts[j].0 - pts[k].0).abs() >= step)?;
    let (a, b) = (pts[k], pts[j]);
    Some((a, (a.0 + 1e-3 * (b.0 - a.0), a.1 + 1e-3 * (b.1 - a.1))))
}

crate::scene! {
    /// Fig. 5.11: contact ratio over the cycle for several coupling stiffnesses.
    pub struct Fig5_11 {
        id: "fig5.11",
        chapter: "5",
        params: CouplingParams,
        title: "Coupled springs: contact ratio over the cycle",
        caption: "Contact ratio N_c/(MN), the fraction of springs in contact (gap below \
            sigma), against u/sigma on loading (a) and unloading (b) for coupling k_mu = 0, 2 k_e, 10 k_e; the \
            cycles of Fig. 5.10. Arrows give the direction of travel: u decreases on loading, increases on \
            unloading.",
        results: &[
            ("max_contact_ratio_uncoupled_norm", "largest contact ratio over the cycle, first coupling"),
            ("max_contact_ratio_strongest_norm", "largest contact ratio over the cycle, last coupling"),
        ],
    }
}

impl Scene for Fig5_11 {
    coupling_study_checks!();

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let cycles = coupling_study(p, job)?;
        let mut load = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear(CONTACT_RATIO_LABEL, ""),
        )
        .titled("(a)", "loading (u decreasing)");
        let mut unload = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear(CONTACT_RATIO_LABEL, ""),
        )
        .titled("(b)", "unloading (u increasing)");
        let max_ratio = |c: &crate::models::spring_array::ArrayCycle| {
            c.loading
                .iter()
                .chain(&c.unloading)
                .map(|s| s.contact_ratio)
                .fold(0.0, f64::max)
        };
        for (c, (mult, cy)) in cycles.iter().enumerate() {
            let name = format!("k_μ = {mult} k_e");
            for (panel, phase) in [(&mut load, &cy.loading), (&mut unload, &cy.unloading)] {
                let pts: Vec<(f64, f64)> = phase.iter().map(|s| (s.u, s.contact_ratio)).collect();
                if let Some((from, to)) = travel_arrow(&pts) {
                    panel.arrow(from, to, Some(c));
                }
                panel.add(Series::new(&name, Style::Stable, pts).with_color(c));
            }
        }
        let mut fig = Figure::new(Self::ID, Self::TITLE)
            .with_panel(load)
            .with_panel(unload);
        fig.result("max_contact_ratio_uncoupled_norm", max_ratio(&cycles[0].1));
        fig.result(
            "max_contact_ratio_strongest_norm",
            max_ratio(&cycles[cycles.len() - 1].1),
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.10-accuracy: the coupled cycle of Fig. 5.10 (one coupling) at
    /// several displacement steps and Newton tolerances, against a fine reference.
    pub struct Fig5_10AccuracyParams {
        /// Stiffness exponent n.
        stiffness_exponent: f64 = 10.0, unit = "", range = Range::open(0.0, 30.0);
        /// Coupling k_μ in units of k_e.
        coupling: f64 = 2.0, unit = "", range = Range::non_negative();
        /// The rough surface.
        group surface: ArraySurface;
        /// Springs N along ê₁ (M = 1).
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Seed of the surface.
        seed: u64 = 1, unit = "", range = Range::non_negative();
        /// Displacement steps per phase of the runs compared.
        steps: Vec<f64> = vec![50.0, 100.0, 200.0, 400.0, 800.0, 1600.0], unit = "", range = Range::between(10.0, 1.0e6);
        /// Newton gradient tolerances of the runs compared.
        tolerances: Vec<f64> = vec![1e-3, 1e-6, 1e-10], unit = "", range = Range::positive();
        /// Steps per phase of the reference run (tolerance 1e-12).
        reference_steps: usize = 6400, unit = "", range = Range::between(10.0, 1.0e7);
        from ArrayCycle: depth_sigmas: f64;
        from ArrayCycle: end_sigmas: f64;
        /// Horizontal axis: measured run time (true) or the deterministic count of Newton iterations (false, for reproducible snapshots).
        wall_clock: bool = true, unit = "", range = Range::any();
    }
}

crate::scene! {
    /// Fig. 5.10-accuracy: error of the adhesive force against run time.
    pub struct Fig5_10Accuracy {
        id: "fig5.10-accuracy",
        chapter: "5",
        params: Fig5_10AccuracyParams,
        title: "Coupled springs: accuracy against run time",
        caption: "Relative error of the adhesive force P_max (5.36) and of the hysteresis of the \
            coupled cycle of Fig. 5.10 (k_mu = 2 k_e) against run time, over the displacement step (points along a \
            line) and the Newton tolerance (one line each), relative to a fine reference run.",
        results: &[
            ("reference_time_s", "run time of the reference"),
            ("reference_adhesive_force_norm", "P_max/(MN |P_m|) of the reference"),
            ("coarsest_error_norm", "relative P_max error of the coarsest step at the tightest tolerance"),
            ("finest_error_norm", "relative P_max error of the finest step at the tightest tolerance"),
        ],
    }
}

impl Scene for Fig5_10Accuracy {
    fn validate(p: &Self::Params) -> Result<()> {
        require_non_empty("steps", &p.steps)?;
        require_non_empty("tolerances", &p.tolerances)
    }

    fn quick(p: &mut Self::Params) {
        p.springs = p.springs.min(24);
        p.steps = vec![20.0, 40.0];
        p.tolerances.truncate(2);
        p.reference_steps = p.reference_steps.min(160);
        p.wall_clock = false;
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        use crate::models::spring_array::{SpringArray, coupled_cycle};
        use crate::numerics::newton::NewtonOptions;
        let k_e = k_bar_of_n(p.stiffness_exponent);
        let z = p.surface.heights(p.springs, 1, p.seed)?;
        let a = SpringArray::new(p.springs, 1, k_e, p.coupling * k_e, z)?;
        let window = cycle_window(k_e, p.surface.roughness, p.depth_sigmas, p.end_sigmas)?;
        let norm = p.springs as f64 * crate::models::spring_array::single_spring_adhesive_force().abs();
        let run = |steps: usize,
                   tol: f64,
                   part: &Job,
                   what: &str|
         -> Result<(crate::models::spring_array::ArrayCycle, f64, usize)> {
            let opts = NewtonOptions {
                gradient_tol: tol,
                linear: crate::numerics::newton::LinearSolver::Iterative,
                ..Default::default()
            };
            let t0 = std::time::Instant::now();
            let c = coupled_cycle(&a, window.0, window.1, steps, &opts, |f| {
                part.progress(f, what);
                job.check()
            })?;
            let iterations = c.newton_iterations;
            Ok((c, t0.elapsed().as_secs_f64(), iterations))
        };
        // Each cycle's part of the progress by its cost: its steps, a little more per step for
        // a tighter tolerance (the reference takes about 45 % of a run at the defaults).
        let cost = |steps: f64, tol: f64| steps * (1.0 + 0.1 * (1.0 / tol).log10().max(0.0));
        let mut weights = vec![cost(p.reference_steps as f64, 1e-12)];
        for &tol in &p.tolerances {
            weights.extend(p.steps.iter().map(|&steps| cost(steps, tol)));
        }
        let parts = job.parts(&weights, 0.0, 0.99);
        let (reference, ref_time, _) = run(p.reference_steps, 1e-12, &parts[0], "reference")?;
        let p_ref = reference.max_tensile_force();
        let h_ref = reference.hysteresis();
        let x_label = if p.wall_clock {
            Axis::log("Run time", "s")
        } else {
            Axis::log("Cost: Newton iterations", "")
        };
        let mut force_panel = Panel::new(x_label.clone(), Axis::log("Relative error of P_max", ""))
            .titled("(a)", "adhesive force");
        let mut hyst_panel = Panel::new(x_label, Axis::log("Relative error of the hysteresis", ""))
            .titled("(b)", "hysteresis");
        let mut coarsest = f64::NAN;
        let mut finest = f64::NAN;
        for (c, &tol) in p.tolerances.iter().enumerate() {
            let mut fp = Vec::new();
            let mut hp = Vec::new();
            for (k, &steps) in p.steps.iter().enumerate() {
                job.check()?;
                let what = format!("tolerance {}, {steps} steps", crate::figure::exact_number(tol));
                let (cy, time, iters) = run(steps as usize, tol, &parts[1 + c * p.steps.len() + k], &what)?;
                let x = if p.wall_clock { time } else { iters as f64 };
                let ef = ((cy.max_tensile_force() - p_ref) / p_ref).abs().max(1e-16);
                let eh = ((cy.hysteresis() - h_ref) / h_ref).abs().max(1e-16);
                fp.push((x, ef));
                hp.push((x, eh));
                if c + 1 == p.tolerances.len() {
                    if k == 0 {
                        coarsest = ef;
                    }
                    finest = ef;
                }
            }
            let name = format!("tolerance {}", crate::figure::exact_number(tol));
            force_panel.add(Series::new(&name, Style::Stable, fp).with_color(c));
            hyst_panel.add(Series::new(&name, Style::Stable, hp).with_color(c));
        }
        let mut fig = Figure::new(Self::ID, Self::TITLE)
            .with_panel(force_panel)
            .with_panel(hyst_panel);
        fig.result("reference_time_s", ref_time);
        fig.result("reference_adhesive_force_norm", p_ref / norm);
        fig.result("coarsest_error_norm", coarsest);
        fig.result("finest_error_norm", finest);
        fig.note("points along a line: displacement steps per phase, coarse (left) to fine (right)");
        fig.note(
            "the error need not fall monotonically with the step: a jump of a group of coupled springs \
             triggered one step earlier or later puts the array on a neighbouring metastable branch",
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}
