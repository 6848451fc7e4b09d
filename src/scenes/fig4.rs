//! Chapter 4 scenes: the Lennard-Jones contact of a smooth tip computed with the axisymmetric
//! surface model and charted against the Maugis-Dugdale theory (Fig. 4.5).
//!
//! The dissertation computes these figures with finite elements and a body force; for a rigid
//! flat substrate the body force integrated through a column is the plate traction, so the
//! surface model draws them (ERRATA on (4.19)). The scenes show the path a displacement-
//! controlled experiment measures: every drawn state is a certified stable equilibrium, and
//! the jumps between them are dashed; the unstable equilibria of the surface model are not
//! traced (the Maugis-Dugdale reference shows where its unstable branch lies).

mod accuracy;
pub mod criterion;
pub mod fe;
mod roughness;
mod study;
mod sweeps;

use std::f64::consts::PI;

use super::fig3::{draw_by_stability, draw_md};
use super::sweep::Swept;
use super::{Registered, Scene, SceneDyn, SceneHeader};
use crate::error::Result;
use crate::figure::{Axis, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::axisymmetric::cycle::{CycleOptions, TipCycle, TipState, run_cycle, run_cycle_watched};
use crate::models::axisymmetric::tip::{Tip, TipParams};
use crate::models::body_force_fe::tip::FeTip;
use crate::models::lennard_jones::LennardJones;
use crate::models::maugis_dugdale::MaugisDugdale;
use crate::models::wavy_jkr::{WavyJkr, WavyJkrParams};
use crate::params::{Range, require_below};
use crate::scenes::groups::{
    ContactCriterion, DepthPath, ElasticTip, FeMesh, Interaction, SurfaceModel, Waviness,
};

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[
    &Registered::<criterion::Fig4_3>::NEW,
    &Registered::<fe::Fig4_4>::NEW,
    &Registered::<Fig4_5>::NEW,
    &Registered::<accuracy::Fig4_5Accuracy>::NEW,
    &Registered::<fe::Fig4_5Models>::NEW,
    &Registered::<fe::Fig4_6>::NEW,
    &Registered::<Fig4_7>::NEW,
    &Registered::<Fig4_8>::NEW,
    &Registered::<roughness::Fig4_9a>::NEW,
    &Swept::<sweeps::Fig4_9b>::NEW,
    &Swept::<study::Fig4_9bModels>::NEW,
    &Swept::<sweeps::Fig4_10>::NEW,
    &Registered::<roughness::Fig4_11>::NEW,
    &Registered::<roughness::Fig4_12>::NEW,
];

crate::param_choice! {
    /// The model that computes a chapter 4 cycle: the axisymmetric surface model (seconds) or
    /// the dissertation's finite-element model with the body force (4.15) (minutes).
    pub enum TipModel { Surface = "surface", Fe = "fe" }
}

crate::scene_params! {
    /// Parameters of scene fig4.5 (section 4.4, the caption of Fig. 4.5). The maximum depth is
    /// not printed; −15 ζ0 (h/R ≈ −1.8e-3) presses the contact to about 1.8 times its
    /// pull-in radius.
    pub struct Fig4_5Params {
        /// The tip (R = 5 µm, E = 4.4 MPa, ν = 0.25).
        group tip: ElasticTip;
        /// The interaction (C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J).
        group lj: Interaction;
        /// The cycle.
        group path: DepthPath;
        /// The discretisation of the surface model.
        group surface: SurfaceModel help {
            ring_width: "Ring width (surface model) or width of the surface elements (finite elements) in units of b = ζ0²E*/w (surface model, 0.25 and below: the contact edge does not hop from ring to ring; the finite-element cycle hops at 0.25, not at 0.15).",
        };
        /// The contact threshold.
        group contact: ContactCriterion;
        /// Model of the tip: surface (the axisymmetric surface model, a few seconds) or fe (the dissertation's finite-element model with the body force (4.15): 15 112 unknowns at the defaults, 24 542 at ring_width 0.15, about a minute per cycle on 2 cores).
        model: TipModel = TipModel::Surface, unit = "", range = Range::any();
        /// The mesh of the finite-element model.
        group mesh: FeMesh;
    }
}

/// The interaction (4.1)-(4.7b) and the plane-strain modulus E* = E/(1 − ν²) of a scene.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the interaction parameter.
fn material(lj: &Interaction, tip: &ElasticTip) -> Result<(LennardJones, f64)> {
    Ok((lj.lennard_jones()?, tip.plane_strain_modulus()))
}

/// The surface model of a smooth or wavy tip (R = `radius` [m], E* = `modulus` [Pa], the
/// waviness `(amplitude, wavelength)` [m] of (4.10)) discretised by `surface`, with the fine
/// zone that covers the deepest depth `h_min` [m] ([`TipParams::fine_radius_for_depth`]).
///
/// # Errors
/// [`Error::InvalidParameter`] naming the parameter.
fn tip_for(
    lj: &LennardJones,
    (radius, modulus): (f64, f64),
    (amplitude, wavelength): (f64, f64),
    h_min: f64,
    surface: &SurfaceModel,
) -> Result<Tip> {
    let p = lj.params();
    let mut params = TipParams {
        radius,
        modulus,
        c6: p.c6,
        c12: p.c12,
        sigma: p.sigma,
        hamaker: p.hamaker,
        amplitude,
        wavelength,
        ring_width: surface.ring_width,
        fine_radius: 0.0,
        growth: 1.1,
        quadrature_points: surface.quadrature_points,
        reach: 30.0,
    };
    params.fine_radius = params.fine_radius_for_depth(h_min)?;
    Tip::new(&params)
}

/// The tip of a chapter 4 scene in the model its `model` parameter names.
enum SceneTip {
    /// The surface model.
    Surface(Box<Tip>),
    /// The finite-element model.
    Fe(Box<FeTip>),
}

/// The model a scene's `model` parameter names, with the mesh of the finite-element one.
#[derive(Debug, Clone)]
struct ModelChoice {
    model: TipModel,
    mesh: FeMesh,
}

impl SceneTip {
    /// The tip of a scene (`tip`, with the waviness `(amplitude, wavelength)` [m] of (4.10)):
    /// the surface model of [`tip_for`], or the finite-element model with the same fine zone,
    /// surface element width and Gauss points near the substrate.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the parameter.
    fn new(
        choice: &ModelChoice,
        lj: &LennardJones,
        tip: &ElasticTip,
        waviness: (f64, f64),
        h_min: f64,
        surface: &SurfaceModel,
    ) -> Result<Self> {
        let modulus = tip.plane_strain_modulus();
        let surface_tip = tip_for(lj, (tip.radius, modulus), waviness, h_min, surface)?;
        Ok(match choice.model {
            TipModel::Surface => Self::Surface(Box::new(surface_tip)),
            TipModel::Fe => Self::Fe(Box::new(fe::fe_wavy_tip(
                lj,
                tip,
                waviness,
                &fe::FeDiscretisation {
                    fine_radius: surface_tip.params().fine_radius,
                    element_width: surface.ring_width,
                    grading: choice.mesh.fe_grading,
                    size_over_radius: choice.mesh.fe_size_over_radius,
                    quadrature_points: surface.quadrature_points,
                },
            )?)),
        })
    }

    /// Run one cycle ([`run_cycle`]).
    ///
    /// # Errors
    /// As [`run_cycle`].
    fn cycle(&self, opts: &CycleOptions, progress: impl FnMut(f64) -> Result<()>) -> Result<TipCycle> {
        match self {
            Self::Surface(t) => run_cycle(t.as_ref(), opts, progress),
            Self::Fe(t) => run_cycle(t.as_ref(), opts, progress),
        }
    }

    /// Run one cycle, showing it as far as it goes to `on_state` after every accepted state
    /// ([`run_cycle_watched`]).
    ///
    /// # Errors
    /// As [`run_cycle`].
    fn cycle_watched(
        &self,
        opts: &CycleOptions,
        progress: impl FnMut(f64) -> Result<()>,
        on_state: impl FnMut(&TipCycle),
    ) -> Result<TipCycle> {
        match self {
            Self::Surface(t) => run_cycle_watched(t.as_ref(), opts, progress, on_state),
            Self::Fe(t) => run_cycle_watched(t.as_ref(), opts, progress, on_state),
        }
    }

    /// The name of the model's series.
    fn label(&self) -> &'static str {
        match self {
            Self::Surface(_) => "surface model (LJ)",
            Self::Fe(_) => "finite elements (LJ body force)",
        }
    }

    /// Unknowns: rings of the surface model, displacement unknowns of the finite elements.
    fn unknowns(&self) -> usize {
        match self {
            Self::Surface(t) => t.len(),
            Self::Fe(t) => t.len(),
        }
    }

    /// Radii [m] and gaps (normal units) of the surface points of a state at `depth` [m].
    fn profile(&self, depth: f64, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        match self {
            Self::Surface(t) => (t.radii(), t.gaps(t.approach(depth), u)),
            Self::Fe(t) => t.surface_gaps(t.approach(depth), u),
        }
    }

    /// The radial unit b = ζ0²E*/w [m].
    fn radial_unit(&self) -> f64 {
        match self {
            Self::Surface(t) => t.scales().radial,
            Self::Fe(t) => t.scales().radial,
        }
    }

    /// A note on the model's discretisation.
    fn describe(&self, width: f64, quadrature_points: usize) -> String {
        match self {
            Self::Surface(t) => format!(
                "Surface model: {} rings of {width:.2} b (b = ζ0²E*/w = {:.2} nm), {quadrature_points} Gauss points per interval",
                t.len(),
                self.radial_unit() * 1e9
            ),
            Self::Fe(t) => format!(
                "Finite elements: {} unknowns ({} triangles, surface elements of {width:.2} b, b = {:.2} nm, tip {:.0} R wide and high, bulk grading {})",
                t.len(),
                t.elements(),
                self.radial_unit() * 1e9,
                t.params().r0 / t.params().radius,
                t.params().grading
            ),
        }
    }
}

/// The options of a chapter 4 cycle at the equilibrium distance `zeta0` [m]: from `h_start` [m]
/// down to `h_min` [m] and back in steps of `step` [m], jumps located to 1e-3 ζ0, contact where
/// the gap is below `contact_gap` [m], the displacements kept at the jumps only.
fn cycle_options(zeta0: f64, (h_start, h_min, step): (f64, f64, f64), contact_gap: f64) -> CycleOptions {
    CycleOptions {
        h_start,
        h_min,
        step,
        refine_to: 1e-3 * zeta0,
        contact_gap,
        keep_profiles: false,
        unload_to: None,
    }
}

/// The largest contact radius [m] of a cycle's `states`.
fn largest_contact_radius<'a>(states: impl IntoIterator<Item = &'a TipState>) -> f64 {
    states.into_iter().map(|s| s.contact.radius()).fold(0.0, f64::max)
}

/// Draw a measured cycle into a P-h panel (h/R, P/(2E*R²)): loading and unloading solid,
/// jumps dashed, pull-in and pull-off marked. `scale` = (R, 2E*R²).
fn draw_cycle(panel: &mut Panel, cycle: &TipCycle, name: &str, color: usize, scale: (f64, f64)) {
    let pt = |s: &TipState| (s.depth / scale.0, s.force / scale.1);
    // Split each phase at its jumps so that a jump is not drawn as part of a branch.
    for (phase, states) in [(true, &cycle.loading), (false, &cycle.unloading)] {
        let mut run: Vec<(f64, f64)> = Vec::new();
        let jumps: Vec<&crate::models::axisymmetric::cycle::TipJump> =
            cycle.jumps.iter().filter(|j| j.loading == phase).collect();
        let mut next = jumps.iter().peekable();
        for s in states {
            if let Some(j) = next.peek()
                && j.after.depth == s.depth
                && j.after.force == s.force
            {
                if run.len() > 1 {
                    panel.add(
                        Series::new(name, Style::Stable, std::mem::take(&mut run))
                            .with_color(color)
                            .without_legend(),
                    );
                }
                run.clear();
                panel.add(
                    Series::new("jump", Style::Jump, vec![pt(&j.before), pt(&j.after)])
                        .with_color(color)
                        .without_legend(),
                );
                next.next();
            }
            run.push(pt(s));
        }
        if run.len() > 1 {
            panel.add(
                Series::new(name, Style::Stable, run)
                    .with_color(color)
                    .without_legend(),
            );
        }
    }
    if let Some(last) = panel.series.iter_mut().rev().find(|s| s.name == name) {
        last.legend = true;
    }
    if let Some(j) = cycle.jumps.first() {
        let (x, y) = pt(&j.before);
        panel.mark(Marker::new("pull-in", MarkerShape::PullIn, x, y).with_color(color));
    }
    if let Some(j) = cycle.jumps.iter().rfind(|j| !j.loading) {
        let (x, y) = pt(&j.before);
        panel.mark(Marker::new("pull-off", MarkerShape::PullOff, x, y).with_color(color));
    }
}

crate::scene! {
    /// Fig. 4.5: the smooth tip, surface model against Maugis-Dugdale.
    pub struct Fig4_5 {
        id: "fig4.5",
        chapter: "4",
        params: Fig4_5Params,
        title: "Smooth tip: Lennard-Jones surface model against Maugis-Dugdale",
        caption: "Displacement-controlled cycle of a smooth paraboloidal tip (R = 5 um, E = 4.4 MPa, \
            nu = 0.25) against a rigid flat with the Lennard-Jones interaction (C6 = 3, C12 = 1, sigma = 1 nm, \
            A_H = 2 × 10⁻²¹ J), computed with the axisymmetric surface model (the body force (4.15) integrated \
            through a column is the traction (4.19)) or, with model = fe, the dissertation's finite-element \
            model (section 4.2.2), against the Maugis-Dugdale curve (3.3) at the same \
            ell and chi (4.25): (a) P-h, (b) P-a with a the radius where the gap is below sigma. The model's \
            path is the measured one: stable states solid, jumps dashed; the MD reference shows its unstable \
            branch dashed and its loss shaded.",
        results: &[
            ("tabor_parameter_norm", "mu_T = (R w^2/(E*^2 zeta0^3))^(1/3), Eq. (1.8)"),
            ("ell_norm", "ell = pi w/(E* R), Eq. (4.25)"),
            ("chi_norm", "chi = w/(E* delta0), delta0 = (9 sqrt 3/16) zeta0, Eq. (4.25)"),
            ("adhesive_force_norm", "P_adh/(pi w R) of the surface model (JKR 1.5, DMT 2)"),
            ("md_adhesive_force_norm", "pull-off force of the MD theory / (pi w R)"),
            ("hysteresis_norm", "H/(2E* R^3), loop area of the surface model"),
            ("md_loss_norm", "loss of the MD theory (3.4) / (2E* R^3)"),
            ("pull_in_depth_norm", "h/R at the pull-in of the surface model"),
            ("pull_off_depth_norm", "h/R at the pull-off of the surface model"),
            ("jumps_count", "jumps on the cycle (2: one pull-in, one pull-off)"),
            ("rings_count", "rings of the surface model (0 with model = fe)"),
            ("unknowns_count", "unknowns of the model: rings (surface) or nodal displacements (fe)"),
            ("all_states_stable_count", "1 when every state was certified stable"),
        ],
    }
}

impl Scene for Fig4_5 {
    fn quick(p: &mut Self::Params) {
        p.path.h_min_over_zeta0 = p.path.h_min_over_zeta0.max(-3.0);
        p.path.step_over_zeta0 = p.path.step_over_zeta0.max(0.25);
        p.mesh.quick();
    }

    fn validate(p: &Self::Params) -> Result<()> {
        p.path.validate()
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let (lj, modulus) = material(&p.lj, &p.tip)?;
        let zeta0 = lj.zeta0();
        let w = lj.work_of_adhesion();
        let choice = ModelChoice {
            model: p.model,
            mesh: p.mesh.clone(),
        };
        let h_min = p.path.h_min_over_zeta0 * zeta0;
        let tip = SceneTip::new(&choice, &lj, &p.tip, (0.0, 1.0), h_min, &p.surface)?;
        let opts = cycle_options(
            zeta0,
            (
                p.path.h_start_over_zeta0 * zeta0,
                h_min,
                p.path.step_over_zeta0 * zeta0,
            ),
            p.contact.contact_gap,
        );
        let scale = (p.tip.radius, 2.0 * modulus * p.tip.radius * p.tip.radius);
        let ph_axes = || {
            Panel::new(
                Axis::linear("Indentation depth h/R", ""),
                Axis::linear("Contact force P/(2E*R²)", ""),
            )
        };
        // The cycle is nearly all of the run (the Maugis-Dugdale curves follow); a listener
        // sees its P-h path grow, jumps included, on the axes of panel (a).
        let cycle = tip.cycle_watched(
            &opts,
            |f| {
                job.progress(0.98 * f, "cycle");
                job.check()
            },
            |so_far| {
                if job.wants_preview() {
                    let mut ph = ph_axes().titled("(a)", "the cycle so far");
                    draw_cycle(&mut ph, so_far, tip.label(), 0, scale);
                    job.preview(&Figure::new(Self::ID, Self::TITLE).with_panel(ph));
                }
            },
        )?;
        let (chi, ell) = (lj.chi(modulus), lj.ell(p.tip.radius, modulus));
        let md = MaugisDugdale::new(chi, ell)?;
        let a_max = largest_contact_radius(&cycle.loading) / p.tip.radius;

        let title = match tip {
            SceneTip::Surface(_) => Self::TITLE,
            SceneTip::Fe(_) => "Smooth tip: Lennard-Jones finite-element model against Maugis-Dugdale",
        };
        let mut fig = Figure::new(Self::ID, title);
        let mut ph = ph_axes().titled(
            "(a)",
            format!("μ_T = {:.3}", lj.tabor_parameter(p.tip.radius, modulus)),
        );
        let md_loss = draw_md(
            &mut ph,
            &md,
            &format!("MD (3.3), χ = {chi:.3}"),
            7,
            a_max.max(1e-6),
            300,
        )?;
        draw_cycle(&mut ph, &cycle, tip.label(), 0, scale);
        fig.panels.push(ph);

        let mut pa = Panel::new(
            Axis::linear("Contact radius a/R", ""),
            Axis::linear("Contact force P/(2E*R²)", ""),
        )
        .titled("(b)", "a: gap below σ (model), contact radius a (MD)");
        let md_curve = md.curve(a_max.max(1e-6), 300)?;
        // The MD contact branch (a > 0): stable solid, unstable dashed, as in panel (a).
        draw_by_stability(
            &mut pa,
            &format!("MD (3.3), χ = {chi:.3}"),
            7,
            md_curve
                .iter()
                .filter(|s| s.a > 0.0)
                .map(|s| (s.stable, (s.a, s.p))),
        );
        for (phase, states) in [("loading", &cycle.loading), ("unloading", &cycle.unloading)] {
            let pts: Vec<(f64, f64)> = states
                .iter()
                .filter(|s| s.contact.radius() > 0.0)
                .map(|s| (s.contact.radius() / p.tip.radius, s.force / scale.1))
                .collect();
            let model = match tip {
                SceneTip::Surface(_) => "surface model",
                SceneTip::Fe(_) => "finite elements",
            };
            pa.add(
                Series::new(format!("{model}, {phase}"), Style::Stable, pts)
                    .with_color(if phase == "loading" { 0 } else { 1 }),
            );
        }
        fig.panels.push(pa);

        let md_cycle = md.cycle()?;
        let pull_in = cycle.jumps.first();
        let pull_off = cycle.jumps.iter().rfind(|j| !j.loading);
        fig.result("tabor_parameter_norm", lj.tabor_parameter(p.tip.radius, modulus));
        fig.result("ell_norm", ell);
        fig.result("chi_norm", chi);
        fig.result(
            "adhesive_force_norm",
            -cycle.adhesive_force() / (PI * w * p.tip.radius),
        );
        // The most tensile force on the MD path an experiment follows (its stable states),
        // as P_adh of the model: not the force at the displacement-controlled fold.
        let md_adhesive = md_curve
            .iter()
            .filter(|s| s.stable)
            .map(|s| s.p)
            .fold(0.0, f64::min)
            .min(md_cycle.pull_off_from.p);
        fig.result(
            "md_adhesive_force_norm",
            -md_adhesive * scale.1 / (PI * w * p.tip.radius),
        );
        fig.result("hysteresis_norm", cycle.hysteresis() / (scale.1 * p.tip.radius));
        fig.result("md_loss_norm", md_loss);
        // Without instabilities (small μ_T) there is no pull-in or pull-off depth: 0, and a note.
        fig.result(
            "pull_in_depth_norm",
            pull_in.map_or(0.0, |j| j.before.depth / p.tip.radius),
        );
        fig.result(
            "pull_off_depth_norm",
            pull_off.map_or(0.0, |j| j.before.depth / p.tip.radius),
        );
        if cycle.jumps.is_empty() {
            fig.note("No instability on this cycle: the pull-in and pull-off depths are reported as 0.");
        }
        fig.result("jumps_count", cycle.jumps.len() as f64);
        let rings = match tip {
            SceneTip::Surface(_) => tip.unknowns(),
            SceneTip::Fe(_) => 0,
        };
        fig.result("rings_count", rings as f64);
        fig.result("unknowns_count", tip.unknowns() as f64);
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(cycle.stats.all_stable)),
        );
        fig.note(format!(
            "{}; {} states, jumps located to 10⁻³ ζ0; every state certified stable: {}.",
            tip.describe(p.surface.ring_width, p.surface.quadrature_points),
            cycle.stats.states,
            cycle.stats.all_stable
        ));
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig4.7 (section 4.5.1, the caption of Fig. 4.7).
    pub struct Fig4_7Params {
        /// The tip (R = 10 µm, E = 2.2 MPa, ν = 0.25).
        group tip: ElasticTip { radius: 10.0e-6, youngs_modulus: 2.2e6 };
        /// The interaction (C6 = 3, C12 = 1, σ = 1 nm, A_H = 1e-21 J).
        group lj: Interaction { hamaker: 1.0e-21 };
        /// The waviness (4.10) (A = 1.25 nm, λ = 0.125 µm).
        group wavy: Waviness;
        /// Maximum depth of the shallow cycle |h_min,1|/R.
        depth_1_over_radius: f64 = 1.5e-4, unit = "", range = Range::between(1.0e-6, 1.0e-2);
        /// Maximum depth of the deep cycle |h_min,2|/R.
        depth_2_over_radius: f64 = 7.0e-4, unit = "", range = Range::between(1.0e-6, 1.0e-2);
        from DepthPath: h_start_over_zeta0: f64 = 25.0,
            help = "Start (and end) of the cycles in units of ζ0; beyond every pull-off.";
        from DepthPath: step_over_zeta0: f64 = 0.25;
        /// The discretisation of the surface model.
        group surface: SurfaceModel;
        /// The contact threshold.
        group contact: ContactCriterion;
        /// Model of the tip: surface (the axisymmetric surface model, seconds) or fe (the dissertation's finite-element model with the body force (4.15): about 20 000 unknowns at the defaults and several minutes per figure on 2 cores).
        model: TipModel = TipModel::Surface, unit = "", range = Range::any();
        /// The mesh of the finite-element model.
        group mesh: FeMesh;
    }
}

impl Fig4_7Params {
    /// The model and its finite-element mesh.
    fn model_choice(&self) -> ModelChoice {
        ModelChoice {
            model: self.model,
            mesh: self.mesh.clone(),
        }
    }
}

/// The states A-D of Figs. 4.7a and 4.8 on a (deep) cycle: A, B before and after the loading
/// jump in contact nearest h/R = −4e-4; C, D the loading and unloading states nearest
/// h/R = 6e-5 (two metastable states at one depth).
fn marked_states(cycle: &TipCycle, radius: f64) -> [Option<TipState>; 4] {
    let off = |s: &TipState, at: f64| (s.depth / radius - at).abs();
    let jump = cycle
        .jumps
        .iter()
        .filter(|j| j.loading && j.before.contact.radius() > 0.0)
        .min_by(|a, b| off(&a.before, -4e-4).total_cmp(&off(&b.before, -4e-4)));
    let nearest = |states: &[TipState]| {
        states
            .iter()
            .min_by(|a, b| off(a, 6e-5).total_cmp(&off(b, 6e-5)))
            .cloned()
    };
    [
        jump.map(|j| j.before.clone()),
        jump.map(|j| j.after.clone()),
        nearest(&cycle.loading),
        nearest(&cycle.unloading),
    ]
}

crate::scene! {
    /// Fig. 4.7: depth-dependent hysteresis of a wavy tip, surface model against (4.26).
    pub struct Fig4_7 {
        id: "fig4.7",
        chapter: "4",
        params: Fig4_7Params,
        title: "Wavy tip: depth-dependent hysteresis",
        caption: "Displacement-controlled cycles of a wavy tip (4.10) (R = 10 um, E = 2.2 MPa, nu = 0.25, \
            A = 1.25 nm, lambda = 0.125 um; C6 = 3, C12 = 1, sigma = 1 nm, A_H = 10⁻²¹ J) with the axisymmetric \
            surface model (model = fe: the dissertation's finite-element model): (a) cycles to |h_min|/R = 1.5 × 10⁻⁴ (thin) and 7 × 10⁻⁴ (thick): more asperity-level \
            instabilities and more loss for the deeper cycle (DDH); A, B: the states before and after the pull-in \
            nearest h/R = −4 × 10⁻⁴; C, D: the loading and unloading states at h/R = 6 × 10⁻⁵; (b) the deep cycle against \
            the wavy JKR theory (4.26) (ERRATA reading, ell printed as chi), stable solid, unstable dashed.",
        results: &[
            ("adhesive_force_1_norm", "P_adh/(2E*R^2) of the shallow cycle"),
            ("adhesive_force_2_norm", "P_adh/(2E*R^2) of the deep cycle"),
            ("hysteresis_1_norm", "H/(2E*R^3) of the shallow cycle"),
            ("hysteresis_2_norm", "H/(2E*R^3) of the deep cycle"),
            ("jumps_1_count", "jumps of the shallow cycle"),
            ("jumps_2_count", "jumps of the deep cycle"),
            ("theory_adhesive_force_2_norm", "P_adh/(2E*R^2) of (4.26) to the deep depth"),
            ("theory_hysteresis_1_norm", "loop area of (4.26) to the shallow depth / (2E*R^3)"),
            ("theory_hysteresis_2_norm", "loop area of (4.26) to the deep depth / (2E*R^3)"),
            ("theory_jumps_2_count", "jumps of (4.26) to the deep depth"),
            ("ell_norm", "ell = pi w/(E* R) (printed as chi in the caption)"),
            ("asperity_radius_ratio_norm", "R_a/R = lambda^2/(4 pi^2 A R), section 4.5.1"),
            ("all_states_stable_count", "1 when every state of both cycles was certified stable"),
        ],
    }
}

impl Scene for Fig4_7 {
    fn quick(p: &mut Self::Params) {
        p.depth_1_over_radius = p.depth_1_over_radius.min(5.0e-5);
        p.depth_2_over_radius = p.depth_2_over_radius.min(1.5e-4);
        p.step_over_zeta0 = p.step_over_zeta0.max(0.5);
        p.h_start_over_zeta0 = p.h_start_over_zeta0.min(20.0);
        p.mesh.quick();
    }

    fn validate(p: &Self::Params) -> Result<()> {
        require_below(
            "depth_1_over_radius",
            p.depth_1_over_radius,
            "depth_2_over_radius",
            p.depth_2_over_radius,
        )
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let (lj, modulus) = material(&p.lj, &p.tip)?;
        let zeta0 = lj.zeta0();
        let depths = [
            p.depth_1_over_radius * p.tip.radius,
            p.depth_2_over_radius * p.tip.radius,
        ];
        let tip = SceneTip::new(
            &p.model_choice(),
            &lj,
            &p.tip,
            (p.wavy.amplitude, p.wavy.wavelength),
            -depths[1],
            &p.surface,
        )?;
        let opts = |h: f64, keep: bool| CycleOptions {
            keep_profiles: keep,
            ..cycle_options(
                zeta0,
                (p.h_start_over_zeta0 * zeta0, -h, p.step_over_zeta0 * zeta0),
                p.contact.contact_gap,
            )
        };
        // The two cycles in parallel, each with its part of the progress by its steps (the
        // depth travelled from the start, twice).
        let parts = job.parts(
            &[
                p.h_start_over_zeta0 * zeta0 + depths[0],
                p.h_start_over_zeta0 * zeta0 + depths[1],
            ],
            0.0,
            0.98,
        );
        let (shallow, deep) = rayon::join(
            || {
                tip.cycle(&opts(depths[0], false), |f| {
                    parts[0].progress(f, "shallow cycle");
                    job.check()
                })
            },
            || {
                tip.cycle(&opts(depths[1], false), |f| {
                    parts[1].progress(f, "deep cycle");
                    job.check()
                })
            },
        );
        let (shallow, deep) = (shallow?, deep?);
        let scale = (p.tip.radius, 2.0 * modulus * p.tip.radius * p.tip.radius);
        let ell = lj.ell(p.tip.radius, modulus);
        let theory = WavyJkr::new(&WavyJkrParams {
            ell,
            amplitude_bar: p.wavy.amplitude / p.tip.radius,
            wavelength_bar: p.wavy.wavelength / p.tip.radius,
        })?;

        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let axes = || {
            (
                Axis::linear("Indentation depth h/R", ""),
                Axis::linear("Contact force P/(2E*R²)", ""),
            )
        };
        let (x, y) = axes();
        let model = match tip {
            SceneTip::Surface(_) => "surface model",
            SceneTip::Fe(_) => "finite elements",
        };
        let mut a = Panel::new(x, y).titled("(a)", format!("{model}, two maximum depths"));
        // The deep cycle first: where the shallow one visits the same states it is drawn on top.
        for (cycle, depth, color) in [
            (&deep, p.depth_2_over_radius, 3),
            (&shallow, p.depth_1_over_radius, 8),
        ] {
            draw_cycle(&mut a, cycle, &format!("|h_min|/R = {depth}"), color, scale);
        }
        let pt = |s: &TipState| (s.depth / scale.0, s.force / scale.1);
        for (label, s) in ["A", "B", "C", "D"]
            .iter()
            .zip(marked_states(&deep, p.tip.radius))
        {
            if let Some(s) = s {
                let (x, y) = pt(&s);
                a.mark(
                    Marker::new(*label, MarkerShape::Point, x, y)
                        .with_label(*label)
                        .with_color(3),
                );
            }
        }
        fig.panels.push(a);

        let (x, y) = axes();
        let mut b = Panel::new(x, y).titled("(b)", "deep cycle against the wavy JKR theory (4.26)");
        let a_max = largest_contact_radius(&deep.loading) / p.tip.radius;
        let curve = theory.curve(1.2 * a_max.max(1e-6), 64)?;
        // (4.26) counts h̄ positive into contact; here h < 0 is pressed.
        let mut run: Vec<(f64, f64)> = Vec::new();
        let mut stable = curve.first().is_none_or(|s| s.stable);
        for s in &curve {
            if s.stable != stable && run.len() > 1 {
                let last = *run.last().expect("non-empty run");
                let style = if stable { Style::Stable } else { Style::Unstable };
                b.add(
                    Series::new("(4.26)", style, std::mem::take(&mut run))
                        .with_color(7)
                        .without_legend(),
                );
                run.push(last);
                stable = s.stable;
            }
            run.push((-s.h, s.p));
        }
        if run.len() > 1 {
            let style = if stable { Style::Stable } else { Style::Unstable };
            b.add(Series::new("wavy JKR (4.26)", style, run).with_color(7));
        }
        draw_cycle(&mut b, &deep, tip.label(), 3, scale);
        fig.panels.push(b);

        let theory_1 = theory.cycle(p.depth_1_over_radius)?;
        let theory_2 = theory.cycle(p.depth_2_over_radius)?;
        let e_scale = scale.1 * p.tip.radius;
        fig.result("adhesive_force_1_norm", -shallow.adhesive_force() / scale.1);
        fig.result("adhesive_force_2_norm", -deep.adhesive_force() / scale.1);
        fig.result("hysteresis_1_norm", shallow.hysteresis() / e_scale);
        fig.result("hysteresis_2_norm", deep.hysteresis() / e_scale);
        fig.result("jumps_1_count", shallow.jumps.len() as f64);
        fig.result("jumps_2_count", deep.jumps.len() as f64);
        fig.result("theory_adhesive_force_2_norm", theory_2.adhesive_force);
        fig.result("theory_hysteresis_1_norm", theory_1.hysteresis);
        fig.result("theory_hysteresis_2_norm", theory_2.hysteresis);
        fig.result("theory_jumps_2_count", theory_2.jumps.len() as f64);
        fig.result("ell_norm", ell);
        fig.result(
            "asperity_radius_ratio_norm",
            p.wavy.wavelength * p.wavy.wavelength
                / (4.0 * PI * PI * p.wavy.amplitude.max(f64::MIN_POSITIVE) * p.tip.radius),
        );
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(shallow.stats.all_stable && deep.stats.all_stable)),
        );
        let discretisation = match &tip {
            SceneTip::Surface(t) => format!(
                "Surface model: {} rings of {:.2} b",
                t.len(),
                p.surface.ring_width
            ),
            SceneTip::Fe(_) => tip.describe(p.surface.ring_width, p.surface.quadrature_points),
        };
        fig.note(format!(
            "{discretisation}; the tip's adhesive force and loss are below those of (4.26) \
             and its instabilities come earlier, as section 4.5.1 finds for its finite-element model \
             (finite interaction range against the JKR limit)."
        ));
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene! {
    /// Fig. 4.8: the deformed surface at the states A-D of Fig. 4.7a.
    pub struct Fig4_8 {
        id: "fig4.8",
        chapter: "4",
        params: Fig4_7Params,
        title: "Wavy tip: surface profiles at the states A-D",
        caption: "Gap between the deformed wavy tip and the substrate against the radius at the states \
            of Fig. 4.7a on the deep cycle (surface model, or the finite-element model with model = fe; only the \
            deep cycle's |h_min| is used): (a) A and B \
            just before and after a pull-in near h/R = −4 × 10⁻⁴, the contact grows across an asperity by a finite \
            amount; (b) C (loading) and D (unloading) at the same depth h/R = 6 × 10⁻⁵, two metastable states with \
            different contact regions. The dotted line is the contact threshold sigma (section 4.2.2).",
        results: &[
            ("contact_radius_a_nm", "contact radius at A"),
            ("contact_radius_b_nm", "contact radius at B"),
            ("contact_radius_c_nm", "contact radius at C"),
            ("contact_radius_d_nm", "contact radius at D"),
            ("depth_ab_norm", "h/R of the jump A -> B"),
            ("depth_cd_norm", "h/R of the states C and D"),
        ],
    }
}

impl Scene for Fig4_8 {
    fn quick(p: &mut Self::Params) {
        Fig4_7::quick(p);
    }

    fn validate(p: &Self::Params) -> Result<()> {
        Fig4_7::validate(p)
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let (lj, _) = material(&p.lj, &p.tip)?;
        let zeta0 = lj.zeta0();
        let depth = p.depth_2_over_radius * p.tip.radius;
        let tip = SceneTip::new(
            &p.model_choice(),
            &lj,
            &p.tip,
            (p.wavy.amplitude, p.wavy.wavelength),
            -depth,
            &p.surface,
        )?;
        let opts = CycleOptions {
            keep_profiles: true,
            // D lies at h/R = 6e-5 on unloading: the rest of the cycle (the pull-off and its
            // recessions) is not drawn here.
            unload_to: Some(1.5e-4 * p.tip.radius),
            ..cycle_options(
                zeta0,
                (p.h_start_over_zeta0 * zeta0, -depth, p.step_over_zeta0 * zeta0),
                p.contact.contact_gap,
            )
        };
        let deep = tip.cycle(&opts, |f| {
            job.progress(0.99 * f, "deep cycle");
            job.check()
        })?;
        let states = marked_states(&deep, p.tip.radius);
        let r_max = 1.3
            * deep
                .loading
                .iter()
                .map(|s| s.contact.radius())
                .fold(p.wavy.wavelength, f64::max);
        let profile = |s: &TipState| -> Vec<(f64, f64)> {
            let (radii, gaps) = tip.profile(s.depth, &s.displacement);
            radii
                .iter()
                .zip(gaps)
                .take_while(|(r, _)| **r <= r_max)
                .map(|(r, g)| (r * 1e9, g * zeta0 * 1e9))
                .collect()
        };
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let titles = [
            ("(a)", "A, B: before and after a pull-in"),
            ("(b)", "C (loading), D (unloading): same depth"),
        ];
        let labels = ["A", "B", "C", "D"];
        for (k, (label, title)) in titles.iter().enumerate() {
            let mut panel = Panel::new(
                Axis::linear("Radius r", "nm"),
                Axis::linear("Gap g", "nm").with_range(0.0, 8.0),
            )
            .titled(*label, *title);
            for i in 0..2 {
                let n = 2 * k + i;
                let Some(s) = &states[n] else { continue };
                panel.add(
                    Series::new(
                        format!(
                            "{} (h/R = {}, a = {:.0} nm)",
                            labels[n],
                            crate::figure::number(s.depth / p.tip.radius, 3),
                            s.contact.radius() * 1e9
                        ),
                        Style::Stable,
                        profile(s),
                    )
                    .with_color(n),
                );
            }
            panel.add(
                Series::new(
                    "contact threshold σ",
                    Style::Reference,
                    vec![
                        (0.0, p.contact.contact_gap * 1e9),
                        (r_max * 1e9, p.contact.contact_gap * 1e9),
                    ],
                )
                .with_color(7),
            );
            fig.panels.push(panel);
        }
        for (n, name) in ["a", "b", "c", "d"].iter().enumerate() {
            let a = states[n].as_ref().map_or(0.0, |s| s.contact.radius());
            fig.result(format!("contact_radius_{name}_nm"), a * 1e9);
        }
        fig.result(
            "depth_ab_norm",
            states[0].as_ref().map_or(0.0, |s| s.depth / p.tip.radius),
        );
        fig.result(
            "depth_cd_norm",
            states[2].as_ref().map_or(0.0, |s| s.depth / p.tip.radius),
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}
