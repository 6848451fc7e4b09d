//! Chapter 2 scenes: the machine-stiffness model for spherical and conical tips (Figs. 2.4-2.7),
//! the accuracy of the exact computation against its run time (fig2.5-accuracy), and the
//! comparison with the experiments of section 2.4 (Fig. 2.8).

use std::time::Instant;

use rayon::prelude::*;

mod experiments;

use self::experiments::XTOL;
pub use self::experiments::{Fig2_8, Fig2_8Fit, Fig2_8FitParams, Fig2_8Params, FitModelChoice, demo_cycle};
use super::{Registered, Scene, SceneDyn, SceneHeader};
use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::machine_stiffness::{Accuracy, MachineStiffness, State, SweepPoint, TipShape};
use crate::numerics::curve::{linspace, logspace};
use crate::params::{Range, require_below};

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[
    &Registered::<Fig2_4>::NEW,
    &Registered::<Fig2_5>::NEW,
    &Registered::<Fig2_5Accuracy>::NEW,
    &Registered::<Fig2_6>::NEW,
    &Registered::<Fig2_7>::NEW,
    &Registered::<Fig2_8>::NEW,
    &Registered::<Fig2_8Fit>::NEW,
];

// ---------------------------------------------------------------------------------------------
// Figs. 2.4 and 2.6: states vs stage displacement.

const BRANCH_RESULTS: &[(&str, &str)] = &[
    ("alpha_norm", "alpha = k_s / k_hat"),
    (
        "pull_in_radius_norm",
        "a_i / a_hat, stable contact radius at Delta = 0",
    ),
    ("pull_in_depth_norm", "h_i / h_hat, depth just after the pull-in"),
    ("pull_in_force_norm", "P_i / P_hat, force just after the pull-in"),
    ("pull_off_radius_norm", "a_o / a_hat, largest root of g-bar"),
    (
        "pull_off_depth_norm",
        "h_o / h_hat, depth just before the pull-off",
    ),
    (
        "pull_off_force_norm",
        "P_o / P_hat, force just before the pull-off",
    ),
    (
        "pull_off_stage_norm",
        "Delta_o / h_hat, stage displacement at the pull-off",
    ),
    ("pull_in_depth_jump_norm", "change of h / h_hat in the pull-in"),
    ("pull_off_depth_jump_norm", "change of h / h_hat in the pull-off"),
    (
        "hysteresis_norm",
        "energy loss by Eq. (2.38)/(2.48), chapter units",
    ),
    (
        "hysteresis_loop_norm",
        "energy loss as the area of the P-Delta loop, chapter units",
    ),
];

crate::param_group! {
    /// The stage displacements of a states-vs-stage-displacement figure (Figs. 2.4 and 2.6), in
    /// units of the tip's ĥ. Defaults: the spherical tip's figure.
    pub struct StagePath {
        /// Smallest stage displacement Δ/ĥ (below the pull-off).
        delta_min: f64 = -2.5, unit = "", range = Range::open(-1.0e9, 0.0);
        /// Largest stage displacement Δ/ĥ.
        delta_max: f64 = 1.5, unit = "", range = Range::open(0.0, 1.0e9);
        /// Samples per branch.
        points: usize = 400, unit = "", range = Range::between(20.0, 1.0e6);
        /// Stage displacements at which the stationary points are marked.
        markers: usize = 25, unit = "", range = Range::between(2.0, 1.0e4);
    }
}

impl StagePath {
    /// The quick form: 60 samples per branch, 8 markers.
    fn quick(&mut self) {
        self.points = self.points.min(60);
        self.markers = self.markers.min(8);
    }
}

/// A quantity of a state drawn against the stage displacement: panel title, axis label and
/// accessor.
type Quantity = (&'static str, String, fn(&State) -> f64);

/// The scales of chapter 2's non-dimensional variables for a tip, as the axes write them
/// (sphere: Sec. 2.3.1, Eqs. (2.31)-(2.38); cone: Sec. 2.3.2, Eqs. (2.44)-(2.48)).
struct Scales {
    /// The contact radius â.
    a: &'static str,
    /// The depth ĥ.
    h: &'static str,
    /// The force P̂.
    p: &'static str,
    /// The interface stiffness k̂_s of α = k_s/k̂_s.
    k: &'static str,
    /// The non-dimensional hysteresis H̄.
    hysteresis: &'static str,
}

/// The scales of [`Scales`] for `tip`.
fn scales(tip: TipShape) -> Scales {
    match tip {
        TipShape::Sphere | TipShape::SphereExact { .. } => Scales {
            a: "â = ∛(9πwR²/8ℰ)",
            h: "ĥ = â²/R",
            p: "P̂ = 3πwR/2",
            k: "k̂_s = ∛(9πwℰ²R²/8)",
            hysteresis: "H̄ = ΔE/∛(R⁴w⁵/ℰ²)",
        },
        TipShape::Cone => Scales {
            a: "â = w/(πℰ tan²θ)",
            h: "ĥ = w/(ℰ tan θ)",
            p: "P̂ = w²/(πℰ tan³θ)",
            k: "k̂_s = w/(π tan²θ)",
            hysteresis: "H̄ = πℰ²tan⁴θ ΔE/w³",
        },
    }
}

/// The states of a tip under machine stiffness α along the stage displacements `path`.
fn branch_figure(
    (id, title): (&str, &str),
    tip: TipShape,
    alpha: f64,
    path: &StagePath,
    job: &Job,
) -> Result<Figure> {
    let StagePath {
        delta_min,
        delta_max,
        points,
        markers,
    } = *path;
    let m = MachineStiffness::new(tip, alpha)?;
    let pull_in = m.pull_in(XTOL)?;
    let pull_off = m.pull_off(XTOL)?;
    // The cycle refuses a `delta_min` that does not reach below the pull-off.
    let cycle = m.cycle(delta_min, delta_max, points, XTOL)?;
    job.check()?;
    let a_o = pull_off.before.a;
    let a_max = cycle.loading.iter().map(|s| s.a).fold(0.0, f64::max);
    let stable: Vec<State> = linspace(a_o, a_max, points)
        .into_iter()
        .map(|a| m.state(a))
        .collect();
    let unstable: Vec<State> = (0..points)
        .map(|k| a_o * (k as f64 / (points - 1) as f64).powi(2))
        .map(|a| m.state(a))
        .collect();
    let free: Vec<State> = linspace(delta_min, 0.0, 2)
        .into_iter()
        .map(MachineStiffness::free_state)
        .collect();
    // Stationary and solution points at a sample of stage displacements (circles and dots).
    let mut stationary = Vec::new();
    let mut solutions = Vec::new();
    for d in linspace(delta_min, delta_max, markers.max(2)) {
        stationary.extend(m.stationary_points(d, XTOL)?);
        solutions.extend(m.solution_points(d, XTOL)?);
    }
    job.check()?;
    let sc = scales(tip);
    let quantities: [Quantity; 3] = [
        ("contact radius", format!("Contact radius a/â, {}", sc.a), |s| {
            s.a
        }),
        (
            "indentation depth",
            format!("Indentation depth h/ĥ, {}", sc.h),
            |s| s.h,
        ),
        ("contact force", format!("Contact force P/P̂, {}", sc.p), |s| {
            s.force
        }),
    ];
    let mut fig = Figure::new(id, title);
    for (k, (heading, label, q)) in quantities.iter().enumerate() {
        let pts = |v: &[State]| v.iter().map(|s| (s.delta, q(s))).collect::<Vec<_>>();
        let mut panel = Panel::new(
            Axis::linear("Stage displacement Δ/ĥ", ""),
            Axis::linear(label.clone(), ""),
        )
        .titled(["(b)", "(c)", "(d)"][k], *heading);
        panel.add(Series::new("solution (in contact)", Style::Stable, pts(&stable)).with_color(0));
        panel.add(Series::new("stationary, unstable", Style::Unstable, pts(&unstable)).with_color(0));
        panel.add(Series::new("solution (out of contact)", Style::Stable, pts(&free)).with_color(1));
        panel.add(Series::new("stationary points", Style::Scatter, pts(&stationary)).with_color(2));
        panel.add(Series::new("solution points", Style::Scatter, pts(&solutions)).with_color(3));
        for (name, j) in [("pull-in", pull_in), ("pull-off", pull_off)] {
            panel.add(
                Series::new(
                    name,
                    Style::Jump,
                    vec![(j.before.delta, q(&j.before)), (j.after.delta, q(&j.after))],
                )
                .with_color(1)
                .without_legend(),
            );
        }
        let (ci, co) = (pull_in.after, pull_off.before);
        panel.mark(Marker::new("after pull-in", MarkerShape::PullIn, ci.delta, q(&ci)).with_color(1));
        panel.mark(Marker::new("before pull-off", MarkerShape::PullOff, co.delta, q(&co)).with_color(1));
        if k == 2 {
            // Loading (right) on the out-of-contact line, unloading (left) on the contact branch.
            panel.arrow((delta_min * 0.6, 0.0), (delta_min * 0.4, 0.0), Some(1));
            let s1 = m.state(a_o + 0.55 * (pull_in.after.a - a_o));
            let s0 = m.state(a_o + 0.6 * (pull_in.after.a - a_o));
            panel.arrow((s0.delta, s0.force), (s1.delta, s1.force), Some(0));
        }
        fig.panels.push(panel);
    }
    let loop_area = cycle.loop_area() * m.energy_factor();
    let results = [
        ("alpha_norm", alpha),
        ("pull_in_radius_norm", pull_in.after.a),
        ("pull_in_depth_norm", pull_in.after.h),
        ("pull_in_force_norm", pull_in.after.force),
        ("pull_off_radius_norm", pull_off.before.a),
        ("pull_off_depth_norm", pull_off.before.h),
        ("pull_off_force_norm", pull_off.before.force),
        ("pull_off_stage_norm", pull_off.before.delta),
        ("pull_in_depth_jump_norm", pull_in.depth_jump()),
        ("pull_off_depth_jump_norm", pull_off.depth_jump()),
        ("hysteresis_norm", m.hysteresis(Accuracy::default())?),
        ("hysteresis_loop_norm", loop_area),
    ];
    for (name, v) in results {
        fig.result(name, v);
    }
    fig.note("solid: solution points (stable, g > 0); dashed: unstable stationary points; triangles: just after the pull-in; squares: just before the pull-off");
    job.progress(1.0, "done");
    Ok(fig)
}

crate::scene_params! {
    /// Parameters of scene fig2.4. The dissertation does not state the α of its figure; α = 1
    /// shows both branches and both jumps clearly.
    pub struct Fig2_4Params {
        /// Stiffness ratio α = k_s/k̂, k̂ = (9πwℰ²R²/8)^(1/3), Eq. (2.35a).
        alpha: f64 = 1.0, unit = "", range = Range::positive();
        /// The stage displacements.
        group path: StagePath;
    }
}

crate::scene! {
    /// Fig. 2.4: spherical tip, contact radius, depth and force vs stage displacement.
    pub struct Fig2_4 {
        id: "fig2.4",
        chapter: "2",
        params: Fig2_4Params,
        title: "Spherical tip with machine stiffness: states vs stage displacement",
        caption: "Contact radius (a), indentation depth (b) and force (c) vs stage displacement \
            (the dissertation's panels (b)-(d); its geometry sketch (a) is not drawn) for a spherical tip, Eqs. (2.34)-(2.36): stationary points (circles), solution points (dots), \
            the pull-in at zero stage displacement (triangles) and the pull-off at the fold a_o (squares).",
        results: BRANCH_RESULTS,
    }
}

impl Scene for Fig2_4 {
    fn quick(p: &mut Self::Params) {
        p.path.quick();
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        branch_figure((Self::ID, Self::TITLE), TipShape::Sphere, p.alpha, &p.path, job)
    }
}

crate::scene_params! {
    /// Parameters of scene fig2.6. The dissertation does not state the α of its figure; α = 10
    /// shows both branches and both jumps on one scale.
    pub struct Fig2_6Params {
        /// Stiffness ratio α = k_s/k̂, k̂ = w/(π tan²θ), Eq. (2.45a).
        alpha: f64 = 10.0, unit = "", range = Range::positive();
        /// The stage displacements (the cone's jumps are longer in ĥ).
        group path: StagePath { delta_min: -5.0, delta_max: 3.0 };
    }
}

crate::scene! {
    /// Fig. 2.6: conical tip, as Fig. 2.4.
    pub struct Fig2_6 {
        id: "fig2.6",
        chapter: "2",
        params: Fig2_6Params,
        title: "Conical tip with machine stiffness: states vs stage displacement",
        caption: "Contact radius (a), indentation depth (b) and force (c) vs stage displacement \
            (the dissertation's panels (b)-(d); its geometry sketch (a) is not drawn) for a conical tip, Eqs. (2.44)-(2.46): stationary points (circles), solution points (dots), \
            the pull-in (triangles) and the pull-off (squares).",
        results: BRANCH_RESULTS,
    }
}

impl Scene for Fig2_6 {
    fn quick(p: &mut Self::Params) {
        p.path.quick();
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        branch_figure((Self::ID, Self::TITLE), TipShape::Cone, p.alpha, &p.path, job)
    }
}

// ---------------------------------------------------------------------------------------------
// Figs. 2.5 and 2.7: α sweeps.

/// Exact sweep points at the given α values, in parallel; cancellable.
///
/// # Errors
/// Model errors; [`Error::Cancelled`].
pub fn sweep(tip: TipShape, alphas: &[f64], acc: Accuracy, job: &Job) -> Result<Vec<SweepPoint>> {
    alphas
        .par_iter()
        .map(|&a| {
            job.check()?;
            MachineStiffness::new(tip, a)?.sweep_point(acc)
        })
        .collect()
}

/// Largest relative errors of the approximations over a sweep: (pull-in, pull-off, hysteresis).
pub fn fit_errors(tip: TipShape, points: &[SweepPoint]) -> Result<(f64, f64, f64)> {
    let mut e = (0.0f64, 0.0f64, 0.0f64);
    for s in points {
        let m = MachineStiffness::new(tip, s.alpha)?;
        let rel = |fit: f64, exact: f64| ((fit - exact) / exact).abs();
        e.0 = e.0.max(rel(m.pull_in_force_fit(), s.pull_in_force));
        e.1 = e.1.max(rel(m.pull_off_force_fit(), s.pull_off_force));
        e.2 = e.2.max(rel(m.hysteresis_fit(), s.hysteresis));
    }
    Ok(e)
}

const SWEEP_RESULTS: &[(&str, &str)] = &[
    (
        "pull_in_force_at_alpha_min_norm",
        "P_i / P_hat at the smallest alpha",
    ),
    (
        "pull_off_force_at_alpha_min_norm",
        "P_o / P_hat at the smallest alpha",
    ),
    (
        "pull_in_force_at_alpha_max_norm",
        "P_i / P_hat at the largest alpha",
    ),
    (
        "pull_off_force_at_alpha_max_norm",
        "P_o / P_hat at the largest alpha",
    ),
    (
        "hysteresis_at_alpha_max_norm",
        "H at the largest alpha, chapter units",
    ),
    (
        "pull_in_fit_max_rel_error_norm",
        "largest |fit/exact - 1| of the pull-in fit over the alpha range",
    ),
    (
        "pull_off_fit_max_rel_error_norm",
        "largest |fit/exact - 1| of the pull-off fit over the alpha range",
    ),
    (
        "hysteresis_fit_max_rel_error_norm",
        "largest |fit/exact - 1| of the hysteresis fit over the alpha range",
    ),
];

fn sweep_figure(
    id: &str,
    title: &str,
    tip: TipShape,
    (alpha_min, alpha_max): (f64, f64),
    points: usize,
    fit_names: (&str, &str),
    job: &Job,
) -> Result<Figure> {
    if alpha_min >= alpha_max {
        return Err(Error::invalid("alpha_min", alpha_min, "must be below alpha_max"));
    }
    let alphas = logspace(alpha_min, alpha_max, points);
    job.progress(0.0, "sweeping alpha");
    let exact = sweep(tip, &alphas, Accuracy::default(), job)?;
    let fine = logspace(alpha_min, alpha_max, 400);
    let fits: Vec<MachineStiffness> = fine
        .iter()
        .map(|&a| MachineStiffness::new(tip, a))
        .collect::<Result<_>>()?;
    let sc = scales(tip);
    let alpha_axis = || Axis::log(format!("Stiffness ratio α = k_s/k̂_s, {}", sc.k), "");
    let mut forces = Panel::new(alpha_axis(), Axis::linear(format!("Force |P|/P̂, {}", sc.p), ""))
        .titled("(a)", "pull-in and pull-off forces");
    forces.add(
        Series::new(
            "|P_i| exact",
            Style::Scatter,
            exact.iter().map(|s| (s.alpha, s.pull_in_force.abs())).collect(),
        )
        .with_color(0),
    );
    forces.add(
        Series::new(
            "|P_o| exact",
            Style::Scatter,
            exact.iter().map(|s| (s.alpha, s.pull_off_force.abs())).collect(),
        )
        .with_color(1),
    );
    forces.add(
        Series::new(
            format!("|P_i| fit {}", fit_names.0),
            Style::Stable,
            fits.iter()
                .map(|m| (m.alpha, m.pull_in_force_fit().abs()))
                .collect(),
        )
        .with_color(0),
    );
    forces.add(
        Series::new(
            format!("|P_o| fit {}", fit_names.0),
            Style::Stable,
            fits.iter()
                .map(|m| (m.alpha, m.pull_off_force_fit().abs()))
                .collect(),
        )
        .with_color(1),
    );
    let mut hyst = Panel::new(
        alpha_axis(),
        Axis::log(format!("Hysteresis {}", sc.hysteresis), ""),
    )
    .titled("(b)", "hysteretic energy loss");
    // The exact hysteresis is (2.38) for the sphere and (2.48) for the cone.
    let exact_eq = if tip == TipShape::Cone { "(2.48)" } else { "(2.38)" };
    hyst.add(
        Series::new(
            format!("H exact {exact_eq}"),
            Style::Scatter,
            exact.iter().map(|s| (s.alpha, s.hysteresis)).collect(),
        )
        .with_color(2),
    );
    // Where the fit fails, say so on the figure: the ratio at the smallest α.
    let fit_note = match (exact.first(), fits.first()) {
        (Some(e), Some(f)) if e.hysteresis > 0.0 => {
            let r = f.hysteresis_fit() / e.hysteresis;
            if !(0.5..=2.0).contains(&r) {
                let a = format!("{:.4}", e.alpha);
                let a = a.trim_end_matches('0').trim_end_matches('.');
                format!(", {r:.0}x the exact at α = {a}")
            } else {
                String::new()
            }
        }
        _ => String::new(),
    };
    hyst.add(
        Series::new(
            format!("H fit {}{fit_note}", fit_names.1),
            Style::Stable,
            fits.iter().map(|m| (m.alpha, m.hysteresis_fit())).collect(),
        )
        .with_color(2),
    );
    let (first, last) = (exact[0], exact[exact.len() - 1]);
    let (e_in, e_off, e_h) = fit_errors(tip, &exact)?;
    let mut fig = Figure::new(id, title).with_panel(forces).with_panel(hyst);
    let results = [
        ("pull_in_force_at_alpha_min_norm", first.pull_in_force),
        ("pull_off_force_at_alpha_min_norm", first.pull_off_force),
        ("pull_in_force_at_alpha_max_norm", last.pull_in_force),
        ("pull_off_force_at_alpha_max_norm", last.pull_off_force),
        ("hysteresis_at_alpha_max_norm", last.hysteresis),
        ("pull_in_fit_max_rel_error_norm", e_in),
        ("pull_off_fit_max_rel_error_norm", e_off),
        ("hysteresis_fit_max_rel_error_norm", e_h),
    ];
    for (name, v) in results {
        fig.result(name, v);
    }
    fig.note(format!(
        "largest relative error of the fits over alpha in [{alpha_min}, {alpha_max}]: pull-in {:.1} %, pull-off {:.1} %, hysteresis {:.1} %",
        100.0 * e_in,
        100.0 * e_off,
        100.0 * e_h
    ));
    job.progress(1.0, "done");
    Ok(fig)
}

crate::scene_params! {
    /// Parameters of the α sweeps, scenes fig2.5 (Sec. 2.3.1) and fig2.7 (Sec. 2.3.2).
    pub struct AlphaSweepParams {
        /// Smallest stiffness ratio α.
        alpha_min: f64 = 1.0e-2, unit = "", range = Range::positive();
        /// Largest stiffness ratio α.
        alpha_max: f64 = 1.0e3, unit = "", range = Range::positive();
        /// Number of α values (log-spaced) solved exactly.
        points: usize = 100, unit = "", range = Range::between(2.0, 1.0e5);
    }
}

/// Figs. 2.5 and 2.7: the α sweep of one tip shape ([`sweep_figure`]), with the equations of
/// its fits.
macro_rules! alpha_sweep_scene {
    (
        $(#[$doc:meta])*
        $name:ident, id = $id:literal, shape = $shape:expr, fits = $fits:expr,
        title = $title:literal, caption = $caption:literal
    ) => {
        crate::scene! {
            $(#[$doc])*
            pub struct $name {
                id: $id,
                chapter: "2",
                params: AlphaSweepParams,
                title: $title,
                caption: $caption,
                results: SWEEP_RESULTS,
            }
        }

        impl Scene for $name {
            fn quick(p: &mut Self::Params) {
                p.points = p.points.min(12);
            }

            fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
                sweep_figure(
                    Self::ID,
                    Self::TITLE,
                    $shape,
                    (p.alpha_min, p.alpha_max),
                    p.points,
                    $fits,
                    job,
                )
            }
        }
    };
}

alpha_sweep_scene! {
    /// Fig. 2.5: sphere, pull-in and pull-off forces and hysteresis vs α, exact and (2.37), (2.39).
    Fig2_5, id = "fig2.5", shape = TipShape::Sphere, fits = ("(2.37)", "(2.39)"),
    title = "Spherical tip: pull-in, pull-off and hysteresis vs machine stiffness",
    caption = "Spherical tip. (a) Exact (circles) and approximate (lines, Eq. (2.37)) |P_i| and \
        |P_o| vs alpha. (b) Exact hysteresis (Eq. (2.38), circles) and its approximation (2.39)."
}

alpha_sweep_scene! {
    /// Fig. 2.7: cone, as Fig. 2.5 with the fits (2.47), (2.49).
    Fig2_7, id = "fig2.7", shape = TipShape::Cone, fits = ("(2.47)", "(2.49)"),
    title = "Conical tip: pull-in, pull-off and hysteresis vs machine stiffness",
    caption = "Conical tip. (a) Exact (circles) and approximate (lines, Eq. (2.47)) |P_i| and \
        |P_o| vs alpha. (b) Exact hysteresis (Eq. (2.48), circles) and its approximation (2.49)."
}

// ---------------------------------------------------------------------------------------------
// fig2.5-accuracy: error of the exact computation against its cost.

crate::scene_params! {
    /// Parameters of scene fig2.5-accuracy.
    pub struct Fig2_5AccuracyParams {
        /// Smallest stiffness ratio α of the test set.
        alpha_min: f64 = 1.0e-2, unit = "", range = Range::positive();
        /// Largest stiffness ratio α of the test set.
        alpha_max: f64 = 1.0e3, unit = "", range = Range::positive();
        /// Number of α values (log-spaced) in the test set.
        points: usize = 20, unit = "", range = Range::between(2.0, 1.0e4);
        /// Repetitions of each timed run (the time is the mean).
        repeats: usize = 20, unit = "", range = Range::between(1.0, 1.0e6);
        /// Measure run times (panel (b)); off, only the error against the setting is drawn.
        time_runs: bool = true, unit = "", range = Range::any();
    }
}

/// A family of method settings: its name, the quantity its setting is (an axis title), and
/// each setting's value with the method it stands for.
type Family = (&'static str, &'static str, Vec<(f64, Method)>);

/// One method setting: its label and accuracy, or loop sampling.
#[derive(Clone, Copy)]
enum Method {
    Exact(Accuracy),
    Loop(usize),
    Fits,
}

/// Largest relative errors (pull-off force, hysteresis) over the α set, against the reference.
fn method_errors(
    method: Method,
    models: &[MachineStiffness],
    reference: &[SweepPoint],
) -> Result<(f64, f64)> {
    let mut e = (0.0f64, 0.0f64);
    for (m, r) in models.iter().zip(reference) {
        let (p_off, h) = run_method(method, m)?;
        e.0 = e.0.max(((p_off - r.pull_off_force) / r.pull_off_force).abs());
        e.1 = e.1.max(((h - r.hysteresis) / r.hysteresis).abs());
    }
    Ok(e)
}

fn run_method(method: Method, m: &MachineStiffness) -> Result<(f64, f64)> {
    Ok(match method {
        Method::Exact(acc) => (m.pull_off(acc.xtol)?.before.force, m.hysteresis(acc)?),
        Method::Loop(n) => {
            let po = m.pull_off(1e-10)?;
            let c = m.cycle(1.1 * po.before.delta - 0.1, 0.1, n, 1e-10)?;
            (po.before.force, c.loop_area() * m.energy_factor())
        }
        Method::Fits => (m.pull_off_force_fit(), m.hysteresis_fit()),
    })
}

crate::scene! {
    /// fig2.5-accuracy: error of the pull-off force and the hysteresis against run time, as the
    /// root-finding tolerance, the Gauss-Legendre order and the loop sampling vary; the fits (2.37),
    /// (2.39) as the cheapest method.
    pub struct Fig2_5Accuracy {
        id: "fig2.5-accuracy",
        chapter: "2",
        params: Fig2_5AccuracyParams,
        title: "Spherical tip: accuracy against run time of the pull-off force and hysteresis",
        caption: "Largest relative error over a set of alpha values of the pull-off force and the \
            hysteresis (2.38) of the sphere, as the root-finding tolerance (Brent), the Gauss-Legendre order, \
            or the sampling of the loop-area method vary, against each setting (a)-(c) and the run time (d); \
            the fits (2.37), (2.39) are the cheapest method.",
        results: &[
            ("reference_time_s", "run time of the reference computation for the whole alpha set"),
            ("fits_pull_off_max_rel_error_norm", "largest relative error of (2.37b)"),
            ("fits_hysteresis_max_rel_error_norm", "largest relative error of (2.39)"),
            ("tolerance_1e-8_pull_off_max_rel_error_norm", "pull-off error with xtol = 1e-8"),
            ("order_8_hysteresis_max_rel_error_norm", "hysteresis error with 8 Gauss-Legendre points"),
        ],
    }
}

impl Scene for Fig2_5Accuracy {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below("alpha_min", p.alpha_min, "alpha_max", p.alpha_max)
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(4);
        p.repeats = 1;
        p.time_runs = false;
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let models: Vec<MachineStiffness> = logspace(p.alpha_min, p.alpha_max, p.points)
            .into_iter()
            .map(|a| MachineStiffness::new(TipShape::Sphere, a))
            .collect::<Result<_>>()?;
        let reference_acc = Accuracy {
            xtol: 1e-15,
            order: 100,
        };
        let t0 = Instant::now();
        let reference: Vec<SweepPoint> = models
            .iter()
            .map(|m| m.sweep_point(reference_acc))
            .collect::<Result<_>>()?;
        let reference_time = t0.elapsed().as_secs_f64();
        let tolerances = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14];
        let orders = [2usize, 3, 4, 6, 8, 12, 16, 24, 40];
        let samples = [50usize, 100, 200, 400, 800, 1600, 3200];
        // Each family against its own setting, one quantity per axis: (name, axis, settings).
        let families: Vec<Family> = vec![
            (
                "Brent tolerance (40-point rule)",
                "Root-finding tolerance x_tol",
                tolerances
                    .iter()
                    .map(|&t| (t, Method::Exact(Accuracy { xtol: t, order: 40 })))
                    .collect(),
            ),
            (
                "Gauss-Legendre order (tolerance 10⁻¹⁴)",
                "Gauss-Legendre order n",
                orders
                    .iter()
                    .map(|&n| {
                        (
                            n as f64,
                            Method::Exact(Accuracy {
                                xtol: 1e-14,
                                order: n,
                            }),
                        )
                    })
                    .collect(),
            ),
            (
                "loop area, samples per branch",
                "Samples per branch of the loop",
                samples.iter().map(|&n| (n as f64, Method::Loop(n))).collect(),
            ),
            ("fits (2.37), (2.39)", "", vec![(1.0, Method::Fits)]),
        ];
        let floor = 1e-17;
        let letters = ["(a)", "(b)", "(c)"];
        let mut by_time = Panel::new(Axis::log("Run time", "s"), Axis::log("Max relative error", ""));
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        // Progress: the reference above, then setting by setting.
        let n_settings: usize = families.iter().map(|(_, _, s)| s.len()).sum();
        let mut done = 0;
        job.progress(0.05, "reference computed");
        for (k, (name, axis, settings)) in families.into_iter().enumerate() {
            job.check()?;
            let mut off_pts = Vec::new();
            let mut h_pts = Vec::new();
            let mut off_t = Vec::new();
            let mut h_t = Vec::new();
            for (x, method) in settings {
                job.progress(0.05 + 0.94 * done as f64 / n_settings as f64, name);
                done += 1;
                let (e_off, e_h) = method_errors(method, &models, &reference)?;
                let (e_off, e_h) = (e_off.max(floor), e_h.max(floor));
                if let Method::Fits = method {
                    fig.result("fits_pull_off_max_rel_error_norm", e_off);
                    fig.result("fits_hysteresis_max_rel_error_norm", e_h);
                }
                if let Method::Exact(acc) = method {
                    if acc.xtol == 1e-8 && acc.order == 40 {
                        fig.result("tolerance_1e-8_pull_off_max_rel_error_norm", e_off);
                    }
                    if acc.xtol == 1e-14 && acc.order == 8 {
                        fig.result("order_8_hysteresis_max_rel_error_norm", e_h);
                    }
                }
                if !matches!(method, Method::Fits) {
                    off_pts.push((x, e_off));
                    h_pts.push((x, e_h));
                }
                if p.time_runs {
                    let t = Instant::now();
                    for _ in 0..p.repeats {
                        for m in &models {
                            std::hint::black_box(run_method(method, m)?);
                        }
                    }
                    let dt = t.elapsed().as_secs_f64() / p.repeats as f64;
                    off_t.push((dt, e_off));
                    h_t.push((dt, e_h));
                }
            }
            if !off_pts.is_empty() {
                let mut by_setting = Panel::new(Axis::log(axis, ""), Axis::log("Max relative error", ""))
                    .titled(letters[k.min(2)], name);
                by_setting
                    .add(Series::new(format!("pull-off, {name}"), Style::Stable, off_pts).with_color(k));
                by_setting
                    .add(Series::new(format!("hysteresis, {name}"), Style::Dashed, h_pts).with_color(k));
                fig.panels.push(by_setting);
            }
            if p.time_runs {
                let style = if off_t.len() == 1 {
                    Style::Scatter
                } else {
                    Style::Stable
                };
                by_time.add(Series::new(format!("pull-off, {name}"), style, off_t).with_color(k));
                let style = if h_t.len() == 1 {
                    Style::Scatter
                } else {
                    Style::Dashed
                };
                by_time.add(Series::new(format!("hysteresis, {name}"), style, h_t).with_color(k));
            }
        }
        if p.time_runs {
            fig.panels.push(by_time.titled("(d)", "error against run time"));
        }
        fig.result("reference_time_s", if p.time_runs { reference_time } else { 0.0 });
        let floor = crate::figure::exact_number(floor);
        fig.note(format!(
            "reference: Brent to 10⁻¹⁵ and a 100-point Gauss-Legendre rule; errors below {floor} are drawn at {floor}"
        ));
        job.progress(1.0, "done");
        Ok(fig)
    }
}
