//! Section 4.5.2: the effect of roughness (the amplitude A of the waviness (4.10)) on adhesion
//! at a fixed maximum depth |h_min|/R = 6e-4 and σ = 1.5 nm: the P-h cycles of Fig. 4.9a, the
//! contact configurations at the adhesive force of Fig. 4.11 and the consecutive pull-off
//! configurations of Fig. 4.12, all with the axisymmetric surface model.
//!
//! The modulus: the caption of Fig. 4.9 gives the parameters of Fig. 4.7a (E = 2.2 MPa), at
//! which the printed smooth-tip adhesive force 1.54e-5 · 2E*R² exceeds the DMT bound 2πwR;
//! ERRATA reads E = 1.1 MPa as more likely. Fig. 4.9a draws both; Fig. 4.11 (whose caption
//! refers to Fig. 4.7a) uses 2.2 MPa, Fig. 4.12 (whose caption refers to Fig. 4.9a) 1.1 MPa.

use rayon::prelude::*;

use super::{ModelChoice, SceneTip, TipModel, draw_cycle};
use crate::error::{Error, Result};
use crate::figure::{Axis, Field, Figure, Panel, number};
use crate::job::Job;
use crate::models::axisymmetric::cycle::{CycleOptions, TipCycle, TipJump, TipState};
use crate::models::lennard_jones::LennardJones;
use crate::params::Range;
use crate::scenes::groups::{
    ContactCriterion, DepthPath, ElasticTip, FeMesh, Interaction, SurfaceModel, Waviness,
};
use crate::scenes::{Scene, SceneHeader};

/// The parameters shared by the roughness scenes (those of Fig. 4.7a with σ = 1.5 nm and
/// |h_min|/R = 6e-4), with the scene's own amplitudes and extra fields appended.
/// The scenes of one model take `model` (surface or fe, after the discretisation); the study
/// of both models (`@fields`) takes the fields alone and names its model with `tip_model`.
macro_rules! rough_tip_params {
    // The scenes of this file: at one σ, the contact threshold σ (section 4.2.2).
    ($(#[$meta:meta])* $name:ident, youngs_modulus = $e:expr, sigma = $sigma:expr, { $($extra:tt)* }) => {
        rough_tip_params! { $(#[$meta])* $name, youngs_modulus = $e, {
            from Interaction: sigma: f64 = $sigma;
            /// The contact threshold (σ).
            group contact: ContactCriterion { contact_gap: $sigma };
            $($extra)*
        } }
    };
    ($(#[$meta:meta])* $name:ident, youngs_modulus = $e:expr, { $($extra:tt)* }) => {
        rough_tip_params! { @fields $(#[$meta])* $name, youngs_modulus = $e, {
            /// Model of the tip: surface (the axisymmetric surface model, seconds per cycle) or fe (the dissertation's finite-element model with the body force (4.15): 7 154 unknowns at σ = 1.5 nm and more at smaller σ, b growing as σ⁴; seconds to a minute per cycle, fig4.9a's six cycles 63 s on one core; quick form seconds per cycle).
            model: TipModel = TipModel::Surface, unit = "", range = Range::any();
            $($extra)*
        } }

        impl $name {
            /// The model of the cycles.
            fn tip_model(&self) -> TipModel {
                self.model
            }
        }
    };
    (@fields $(#[$meta:meta])* $name:ident, youngs_modulus = $e:expr, { $($extra:tt)* }) => {
        crate::scene_params! {
            $(#[$meta])*
            pub struct $name {
                /// The tip (R = 10 µm, ν = 0.25).
                group tip: ElasticTip { radius: 10.0e-6, youngs_modulus: $e } help {
                    youngs_modulus: "Young's modulus E of the tip [Pa] (see ERRATA on Fig. 4.9).",
                };
                from Interaction: c6: f64;
                from Interaction: c12: f64;
                from Interaction: hamaker: f64 = 1.0e-21;
                from Waviness: wavelength: f64;
                /// Maximum depth of the cycles |h_min|/R.
                depth_over_radius: f64 = 6.0e-4, unit = "", range = Range::between(1.0e-6, 1.0e-2);
                from DepthPath: h_start_over_zeta0: f64 = 25.0,
                    help = "Start (and end) of the cycles in units of ζ0; beyond every pull-off.";
                from DepthPath: step_over_zeta0: f64 = 0.25;
                /// The discretisation of the surface model.
                group surface: SurfaceModel help {
                    ring_width: "Ring width (surface model) or width of the surface elements (finite elements) in units of b = ζ0²E*/w.",
                    quadrature_points: "Gauss points per interval of the interaction energy (per chord interval in r near the substrate for finite elements).",
                };
                /// The mesh of the finite-element model.
                group mesh: FeMesh;
                $($extra)*
            }
        }

        impl $name {
            /// The quick form of the cycles: shallow (|h_min|/R at most 1e-4), started closer,
            /// in steps of at least 0.5 ζ0, on the quick finite-element mesh.
            #[allow(dead_code)]
            fn shallow_quick(&mut self) {
                self.depth_over_radius = self.depth_over_radius.min(1.0e-4);
                self.step_over_zeta0 = self.step_over_zeta0.max(0.5);
                self.h_start_over_zeta0 = self.h_start_over_zeta0.min(12.0);
                self.mesh.quick();
            }

            /// The material and cycle set-up at Young's modulus `youngs_modulus` [Pa], range
            /// `sigma` [m] of the potential and contact threshold `contact_gap` [m].
            fn setup(
                &self,
                youngs_modulus: f64,
                sigma: f64,
                contact_gap: f64,
            ) -> crate::error::Result<crate::scenes::fig4::roughness::Setup> {
                let interaction = crate::scenes::groups::Interaction {
                    c6: self.c6,
                    c12: self.c12,
                    sigma,
                    hamaker: self.hamaker,
                };
                let tip = crate::scenes::groups::ElasticTip {
                    youngs_modulus,
                    ..self.tip.clone()
                };
                let (lj, modulus) = crate::scenes::fig4::material(&interaction, &tip)?;
                Ok(crate::scenes::fig4::roughness::Setup {
                    lj,
                    modulus,
                    elastic: tip,
                    choice: crate::scenes::fig4::ModelChoice {
                        model: self.tip_model(),
                        mesh: self.mesh.clone(),
                    },
                    radius: self.tip.radius,
                    wavelength: self.wavelength,
                    depth: self.depth_over_radius * self.tip.radius,
                    h_start_over_zeta0: self.h_start_over_zeta0,
                    step_over_zeta0: self.step_over_zeta0,
                    surface: self.surface.clone(),
                    contact_gap,
                })
            }
        }
    };
}

pub(super) use rough_tip_params;

rough_tip_params! {
    /// Parameters of scene fig4.9a (section 4.5.2, the caption of Fig. 4.9: those of Fig. 4.7a
    /// with σ = 1.5 nm, |h_min|/R = 6e-4, A = 0, 0.9375 and 2.5 nm).
    Fig4_9aParams, youngs_modulus = 2.2e6, sigma = 1.5e-9, {
        /// Amplitude of the first cycle [m] (A/λ = 0).
        amplitude_1: f64 = 0.0, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of the second cycle [m] (A/λ = 0.0075).
        amplitude_2: f64 = 0.9375e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of the third cycle [m] (A/λ = 0.02).
        amplitude_3: f64 = 2.5e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Young's modulus of panel (b) [Pa] (ERRATA's reading of Fig. 4.9).
        youngs_modulus_b: f64 = 1.1e6, unit = "Pa", range = Range::between(1.0e4, 1.0e11);
    }
}

rough_tip_params! {
    /// Parameters of scene fig4.11 (the caption of Fig. 4.11: those of Fig. 4.7a with
    /// σ = 1.5 nm and A = 0, 1.25, 2.5, 3.75 nm; the depth of Fig. 4.9a).
    Fig4_11Params, youngs_modulus = 2.2e6, sigma = 1.5e-9, {
        /// Amplitude of configuration (a) [m].
        amplitude_1: f64 = 0.0, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of configuration (b) [m].
        amplitude_2: f64 = 1.25e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of configuration (c) [m].
        amplitude_3: f64 = 2.5e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of configuration (d) [m].
        amplitude_4: f64 = 3.75e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Grid points per side of the top views.
        map_points: usize = 121, unit = "", range = Range::between(11.0, 801.0);
    }
}

rough_tip_params! {
    /// Parameters of scene fig4.12 (the caption of Fig. 4.12: those of Fig. 4.9a with
    /// A = 1.25 nm and 3.125 nm, at ERRATA's E = 1.1 MPa for Fig. 4.9).
    Fig4_12Params, youngs_modulus = 1.1e6, sigma = 1.5e-9, {
        /// Amplitude of the small-roughness tip, configurations (a)-(c) [m].
        amplitude_1: f64 = 1.25e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Amplitude of the large-roughness tip, configurations (d)-(f) [m].
        amplitude_2: f64 = 3.125e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Grid points per side of the top views.
        map_points: usize = 121, unit = "", range = Range::between(11.0, 801.0);
    }
}

/// Material and cycle settings of one modulus.
pub(super) struct Setup {
    pub(super) lj: LennardJones,
    pub(super) modulus: f64,
    /// The tip's elastic constants (at the set modulus).
    pub(super) elastic: ElasticTip,
    /// The model of the cycles, with its finite-element mesh.
    pub(super) choice: ModelChoice,
    pub(super) radius: f64,
    pub(super) wavelength: f64,
    pub(super) depth: f64,
    pub(super) h_start_over_zeta0: f64,
    pub(super) step_over_zeta0: f64,
    pub(super) surface: SurfaceModel,
    pub(super) contact_gap: f64,
}

/// Largest surface-element width of the roughness sweeps (figs. 4.9b, 4.10) in units of the
/// wavelength λ: at λ/8 the waviness is resolved where 0.25 b (b ∝ σ⁴) is not (b = 79 nm at
/// σ = 2 nm, 400 nm at 3 nm against λ = 125 nm); the surface model at λ/8 is within 1.3 % of
/// λ/16 (fig4.9b-models).
pub(super) const MAX_WIDTH_OVER_WAVELENGTH: f64 = 0.125;

impl Setup {
    /// The radial unit b = ζ0²E*/w [m] of (4.6)-(4.7b).
    pub(super) fn radial_unit(&self) -> f64 {
        let zeta0 = self.lj.zeta0();
        zeta0 * zeta0 * self.modulus / self.lj.work_of_adhesion()
    }

    /// The surface-element width [m] of `width_b` b, at most `max_over_wavelength` λ, and
    /// whether that cap applied.
    pub(super) fn capped_width(&self, width_b: f64, max_over_wavelength: f64) -> (f64, bool) {
        let (width, cap) = (
            width_b * self.radial_unit(),
            max_over_wavelength * self.wavelength,
        );
        (width.min(cap), width > cap)
    }

    /// Cap the set-up's ring width at `max_over_wavelength` λ ([`Setup::capped_width`]);
    /// whether the cap applied (the width is unchanged where it did not).
    pub(super) fn cap_ring_width(&mut self, max_over_wavelength: f64) -> bool {
        let (width, capped) = self.capped_width(self.surface.ring_width, max_over_wavelength);
        if capped {
            self.surface.ring_width = width / self.radial_unit();
        }
        capped
    }

    /// (P, h) scales of the figures: (R, 2E*R²).
    pub(super) fn scale(&self) -> (f64, f64) {
        (self.radius, 2.0 * self.modulus * self.radius * self.radius)
    }

    /// The tip with amplitude `amplitude`, its rings set for the set depth.
    ///
    /// # Errors
    /// A ring grid the model refuses, naming the parameter that set it.
    pub(super) fn tip(&self, amplitude: f64) -> Result<SceneTip> {
        SceneTip::new(
            &self.choice,
            &self.lj,
            &self.elastic,
            (amplitude, self.wavelength),
            -self.depth,
            &self.surface,
        )
    }

    /// The tips of several amplitudes, in the order given: built before any cycle runs, so
    /// that a grid the model refuses fails at once, not after the other cycles.
    pub(super) fn tips(&self, amplitudes: &[f64]) -> Result<Vec<SceneTip>> {
        amplitudes.par_iter().map(|&a| self.tip(a)).collect()
    }

    /// One cycle of `tip` to the set depth.
    fn cycle_of(&self, tip: &SceneTip, keep_profiles: bool, job: &Job) -> Result<TipCycle> {
        let zeta0 = self.lj.zeta0();
        let opts = CycleOptions {
            keep_profiles,
            ..super::cycle_options(
                zeta0,
                (
                    self.h_start_over_zeta0 * zeta0,
                    -self.depth,
                    self.step_over_zeta0 * zeta0,
                ),
                self.contact_gap,
            )
        };
        tip.cycle(&opts, |f| {
            job.progress(f, "cycle");
            job.check()
        })
    }

    /// One cycle of the tip with amplitude `amplitude`, to the set depth.
    pub(super) fn cycle(
        &self,
        amplitude: f64,
        keep_profiles: bool,
        job: &Job,
    ) -> Result<(SceneTip, TipCycle)> {
        // The set-up of a finite-element tip takes seconds at small σ: the job is checked
        // before and after it, not only in the cycle.
        job.check()?;
        let tip = self.tip(amplitude)?;
        job.check()?;
        let cycle = self.cycle_of(&tip, keep_profiles, job)?;
        Ok((tip, cycle))
    }

    /// Cycles of several tips ([`Setup::tips`]) in parallel, in the order given; each fills an
    /// equal part of `job`'s progress step by step.
    fn cycles(
        &self,
        tips: Vec<SceneTip>,
        keep_profiles: bool,
        job: &Job,
        what: &str,
    ) -> Result<Vec<(SceneTip, TipCycle)>> {
        let weights = vec![1.0; tips.len()];
        let cycles = job.map_parallel_parts(&tips, &weights, what, (0.0, 1.0), |tip, part| {
            self.cycle_of(tip, keep_profiles, part)
        })?;
        Ok(tips.into_iter().zip(cycles).collect())
    }
}

/// A top view of the gap between a deformed tip and the substrate [nm], clipped at `clip`
/// (the contact region reads as the low plateau), with the contact threshold as the
/// highlighted contour: the axisymmetric contact set (a disc, or a disc and annuli) as the
/// dissertation's configuration snapshots show it.
fn top_view(
    (tip, zeta0): (&SceneTip, f64),
    state: &TipState,
    half_width: f64,
    points: usize,
    contact_gap: f64,
    clip: f64,
) -> Field {
    let (radii, gaps) = tip.profile(state.depth, &state.displacement);
    let gaps: Vec<f64> = gaps.iter().map(|g| g * zeta0 * 1e9).collect();
    // Linear interpolation in r between ring mid-radii (flat inside the first).
    let gap_at = |r: f64| -> f64 {
        let k = radii.partition_point(|&ri| ri < r);
        if k == 0 {
            return gaps[0];
        }
        if k >= radii.len() {
            return gaps[radii.len() - 1];
        }
        let t = (r - radii[k - 1]) / (radii[k] - radii[k - 1]);
        gaps[k - 1] + t * (gaps[k] - gaps[k - 1])
    };
    let coords: Vec<f64> = (0..points)
        .map(|i| (-1.0 + 2.0 * i as f64 / (points - 1) as f64) * half_width * 1e9)
        .collect();
    let mut values = Vec::with_capacity(points * points);
    for y in &coords {
        for x in &coords {
            values.push(gap_at(x.hypot(*y) * 1e-9).min(clip));
        }
    }
    let mut field = Field::heat("Gap g", "nm", coords.clone(), coords, values);
    // One colour scale for every configuration (a state out of contact included).
    field.color_range = Some((0.0, clip));
    field.highlight.push((contact_gap * 1e9, "contact edge".into()));
    field
}

/// The state of largest tension on a cycle (where the adhesive force is measured).
fn at_adhesive_force(cycle: &TipCycle) -> Option<&TipState> {
    cycle
        .loading
        .iter()
        .chain(&cycle.unloading)
        .min_by(|a, b| a.force.total_cmp(&b.force))
}

crate::scene! {
    /// Fig. 4.9a: P-h cycles of three amplitudes at the caption's modulus and at ERRATA's reading.
    pub struct Fig4_9a {
        id: "fig4.9a",
        chapter: "4",
        params: Fig4_9aParams,
        title: "Roughness and adhesion: P-h cycles of three amplitudes",
        caption: "Force against depth of a wavy tip (surface model, or with model = fe the dissertation's \
            finite-element model) cycled to |h_min|/R = 6 × 10⁻⁴ (the figure's notes give the depth that ran) for \
            A/lambda = 0, 0.0075 and 0.02 (A = 0, 0.9375, 2.5 nm; sigma = 1.5 nm, the other parameters of Fig. 4.7a). \
            (a) at the caption's E = 2.2 MPa, (b) at E = 1.1 MPa (ERRATA: the printed smooth-tip force exceeds the DMT \
            bound at 2.2 MPa). The dissertation: P_adh/(2E*R^2) = 1.54 × 10⁻⁵, 3.06 × 10⁻⁵, 1.93 × 10⁻⁵ and H/(2E*R^3) = 2.93 × 10⁻⁹, \
            12.43 × 10⁻⁹, 7.7 × 10⁻⁹: a small roughness raises both, a larger one lowers them again.",
        results: &[
            ("p_adh_1_norm", "P_adh/(2E*R^2), amplitude 1, panel (a)"),
            ("p_adh_2_norm", "P_adh/(2E*R^2), amplitude 2, panel (a)"),
            ("p_adh_3_norm", "P_adh/(2E*R^2), amplitude 3, panel (a)"),
            ("hysteresis_1_norm", "H/(2E*R^3), amplitude 1, panel (a)"),
            ("hysteresis_2_norm", "H/(2E*R^3), amplitude 2, panel (a)"),
            ("hysteresis_3_norm", "H/(2E*R^3), amplitude 3, panel (a)"),
            ("jumps_1_count", "jumps of cycle 1, panel (a)"),
            ("jumps_2_count", "jumps of cycle 2, panel (a)"),
            ("jumps_3_count", "jumps of cycle 3, panel (a)"),
            ("p_adh_1_b_norm", "P_adh/(2E*R^2), amplitude 1, panel (b)"),
            ("p_adh_2_b_norm", "P_adh/(2E*R^2), amplitude 2, panel (b)"),
            ("p_adh_3_b_norm", "P_adh/(2E*R^2), amplitude 3, panel (b)"),
            ("hysteresis_1_b_norm", "H/(2E*R^3), amplitude 1, panel (b)"),
            ("hysteresis_2_b_norm", "H/(2E*R^3), amplitude 2, panel (b)"),
            ("hysteresis_3_b_norm", "H/(2E*R^3), amplitude 3, panel (b)"),
            ("dmt_bound_norm", "DMT bound pi w/(E*R) on P_adh/(2E*R^2), panel (a)"),
        ],
    }
}

impl Scene for Fig4_9a {
    /// A shallow cycle (the loop and its jumps, not the caption's depth) with coarser steps.
    fn quick(p: &mut Self::Params) {
        p.shallow_quick();
    }

    fn validate(p: &Self::Params) -> Result<()> {
        p.setup(p.tip.youngs_modulus, p.sigma, p.contact.contact_gap)?;
        p.setup(p.youngs_modulus_b, p.sigma, p.contact.contact_gap)
            .map(|_| ())
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let amplitudes = [p.amplitude_1, p.amplitude_2, p.amplitude_3];
        let setups = [
            p.setup(p.tip.youngs_modulus, p.sigma, p.contact.contact_gap)?,
            p.setup(p.youngs_modulus_b, p.sigma, p.contact.contact_gap)?,
        ];
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let printed = [(1.54e-5, 2.93e-9), (3.06e-5, 12.43e-9), (1.93e-5, 7.7e-9)];
        // The softer tip's cycles cost more (at the defaults, half the modulus takes about five
        // times as long): the panels' parts of the progress go as E^-2.
        let parts = job.parts(
            &[p.tip.youngs_modulus.powi(-2), p.youngs_modulus_b.powi(-2)],
            0.0,
            0.99,
        );
        // Every tip of both panels first: a grid the model refuses is an error at once.
        let tips = setups
            .iter()
            .map(|s| s.tips(&amplitudes))
            .collect::<Result<Vec<_>>>()?;
        for (k, (setup, tips)) in setups.iter().zip(tips).enumerate() {
            let cycles = setup.cycles(
                tips,
                false,
                &parts[k],
                if k == 0 { "panel (a)" } else { "panel (b)" },
            )?;
            let (label, e) = if k == 0 {
                ("(a)", p.tip.youngs_modulus)
            } else {
                ("(b)", p.youngs_modulus_b)
            };
            // Depths from the deepest point to a quarter beyond the last pull-off (the flat
            // approach from h_start carries no information).
            let last_off = cycles
                .iter()
                .flat_map(|(_, c)| c.jumps.iter().map(|j| j.before.depth))
                .fold(0.0, f64::max);
            let (x_lo, x_hi) = (-1.05 * setup.depth / setup.radius, 1.25 * last_off / setup.radius);
            let x_axis = Axis::linear("Indentation depth h/R", "");
            let mut panel = Panel::new(
                if x_hi > 0.0 {
                    x_axis.with_range(x_lo, x_hi)
                } else {
                    x_axis
                },
                Axis::linear("Force P/(2E*R²)", ""),
            )
            .titled(label, format!("E = {:.2} MPa, {}", e * 1e-6, cycles[0].0.label()));
            if k == 0 {
                fig.note(format!(
                    "{}; cycles to |h_min|/R = {} in steps of {} ζ0.",
                    cycles[0]
                        .0
                        .describe(setup.surface.ring_width, setup.surface.quadrature_points),
                    number(setup.depth / setup.radius, 3),
                    setup.step_over_zeta0
                ));
            }
            let scale = setup.scale();
            let suffix = if k == 0 { "" } else { "_b" };
            let mut summary = Vec::new();
            for (i, ((_, cycle), a)) in cycles.iter().zip(amplitudes).enumerate() {
                let name = format!("A/λ = {}", crate::params::fmt_sig(a / p.wavelength));
                draw_cycle(&mut panel, cycle, &name, [0, 3, 2][i], scale);
                let padh = -cycle.adhesive_force() / scale.1;
                let h = cycle.hysteresis() / (scale.1 * setup.radius);
                fig.result(format!("p_adh_{}{suffix}_norm", i + 1), padh);
                fig.result(format!("hysteresis_{}{suffix}_norm", i + 1), h);
                if k == 0 {
                    fig.result(format!("jumps_{}_count", i + 1), cycle.jumps.len() as f64);
                }
                summary.push(format!(
                    "{name}: P_adh/(2E*R²) = {} (printed {}), H/(2E*R³) = {} (printed {}), {} jumps",
                    number(padh, 4),
                    number(printed[i].0, 3),
                    number(h, 4),
                    number(printed[i].1, 3),
                    cycle.jumps.len()
                ));
            }
            let w = setup.lj.work_of_adhesion();
            let dmt = std::f64::consts::PI * w / (setup.modulus * setup.radius);
            if k == 0 {
                fig.result("dmt_bound_norm", dmt);
            }
            fig.note(format!(
                "{label} E = {:.2} MPa (DMT bound on P_adh/(2E*R²): {}): {}.",
                e * 1e-6,
                number(dmt, 4),
                summary.join("; ")
            ));
            fig.panels.push(panel);
        }
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// The quick form and checks of the scenes with top views, Figs. 4.11 and 4.12 (items of
/// their `Scene` impls). The cycles are cheap at σ = 1.5 nm (a coarse ring grid): quick only
/// coarsens the maps (and the finite-element mesh).
macro_rules! top_view_checks {
    () => {
        fn quick(p: &mut Self::Params) {
            p.map_points = p.map_points.min(21);
            p.mesh.quick();
        }

        fn validate(p: &Self::Params) -> Result<()> {
            p.setup(p.tip.youngs_modulus, p.sigma, p.contact.contact_gap)
                .map(|_| ())
        }
    };
}

crate::scene! {
    /// Fig. 4.11: contact configurations at the adhesive force for four amplitudes.
    pub struct Fig4_11 {
        id: "fig4.11",
        chapter: "4",
        params: Fig4_11Params,
        title: "Roughness and the topology of the contact at the adhesive force",
        caption: "Top views of the gap (nm, clipped at 3 sigma) between the deformed wavy tip and the \
            substrate at the state of the adhesive force P_adh of a cycle to |h_min|/R = 6 × 10⁻⁴ (surface model, or with \
            model = fe the finite-element model), for \
            A = 0, 1.25, 2.5, 3.75 nm (sigma = 1.5 nm, the other parameters of Fig. 4.7a); the highlighted line is the \
            contact edge (gap = sigma). The dissertation: P_adh is largest at A/lambda = 0.01, where the contact is \
            still simply connected; beyond, the contact becomes multiply connected and the real contact area falls.",
        results: &[
            ("p_adh_1_norm", "P_adh/(2E*R^2), configuration (a)"),
            ("p_adh_2_norm", "P_adh/(2E*R^2), configuration (b)"),
            ("p_adh_3_norm", "P_adh/(2E*R^2), configuration (c)"),
            ("p_adh_4_norm", "P_adh/(2E*R^2), configuration (d)"),
            ("area_1_m2", "real contact area at P_adh, (a)"),
            ("area_2_m2", "real contact area at P_adh, (b)"),
            ("area_3_m2", "real contact area at P_adh, (c)"),
            ("area_4_m2", "real contact area at P_adh, (d)"),
            ("parts_1_count", "contact regions (disc + annuli) at P_adh, (a)"),
            ("parts_2_count", "contact regions (disc + annuli) at P_adh, (b)"),
            ("parts_3_count", "contact regions (disc + annuli) at P_adh, (c)"),
            ("parts_4_count", "contact regions (disc + annuli) at P_adh, (d)"),
        ],
    }
}

impl Scene for Fig4_11 {
    top_view_checks!();

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let amplitudes = [p.amplitude_1, p.amplitude_2, p.amplitude_3, p.amplitude_4];
        let setup = p.setup(p.tip.youngs_modulus, p.sigma, p.contact.contact_gap)?;
        let cycles = setup.cycles(setup.tips(&amplitudes)?, true, &job.part(0.0, 0.98), "cycles")?;
        let states: Vec<&TipState> = cycles
            .iter()
            .map(|(_, c)| at_adhesive_force(c).ok_or_else(|| no_states(Self::ID)))
            .collect::<Result<_>>()?;
        let half = 1.2
            * states
                .iter()
                .map(|s| s.contact.radius())
                .fold(p.wavelength, f64::max);
        let scale = setup.scale();
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        for (i, (((tip, cycle), state), a)) in cycles.iter().zip(&states).zip(amplitudes).enumerate() {
            let padh = -cycle.adhesive_force() / scale.1;
            let area = state.contact.area();
            let parts = state.contact.intervals.len();
            let mut panel = Panel::new(Axis::linear("x", "nm"), Axis::linear("y", "nm"))
                .titled(
                    ["(a)", "(b)", "(c)", "(d)"][i],
                    format!(
                        "A/λ = {:.3}: P_adh/(2E*R²) = {}",
                        a / p.wavelength,
                        number(padh, 3)
                    ),
                )
                .with_equal_aspect();
            panel.field = Some(top_view(
                (tip, setup.lj.zeta0()),
                state,
                half,
                p.map_points,
                p.contact.contact_gap,
                3.0 * p.sigma * 1e9,
            ));
            fig.panels.push(panel);
            fig.result(format!("p_adh_{}_norm", i + 1), padh);
            fig.result(format!("area_{}_m2", i + 1), area);
            fig.result(format!("parts_{}_count", i + 1), parts as f64);
        }
        let summary: Vec<String> = states
            .iter()
            .zip(amplitudes)
            .map(|(s, a)| {
                format!(
                    "A/λ = {:.3}: {} ({} region{}), area {:.4} µm²",
                    a / p.wavelength,
                    if s.contact.is_multiply_connected() {
                        "multiply connected"
                    } else {
                        "simply connected"
                    },
                    s.contact.intervals.len(),
                    if s.contact.intervals.len() == 1 { "" } else { "s" },
                    s.contact.area() * 1e12
                )
            })
            .collect();
        fig.note(format!("At P_adh: {}.", summary.join("; ")));
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// The error of a cycle without states (not expected: a cycle has at least its start).
fn no_states(id: &'static str) -> Error {
    Error::Unresolvable {
        model: id,
        reason: "the cycle has no states".into(),
    }
}

/// The pull-off jumps of the unloading phase (the contact area drops), the final one
/// included.
fn pull_offs(cycle: &TipCycle) -> Vec<&TipJump> {
    cycle
        .jumps
        .iter()
        .filter(|j| !j.loading && j.before.contact.area() > j.after.contact.area())
        .collect()
}

/// Asperity rings (wavelengths) a pull-off jump detaches: the drop of the contact radius in
/// wavelengths for a simply connected contact, or the number of contact regions lost,
/// whichever is larger (a jump that detaches two neighbours at once counts 2: a cascade).
fn rings_detached(jump: &TipJump, wavelength: f64) -> f64 {
    let (before, after) = (&jump.before.contact, &jump.after.contact);
    let by_radius = ((before.radius() - after.radius()) / wavelength).round();
    let by_parts = before.intervals.len() as f64 - after.intervals.len() as f64;
    by_radius.max(by_parts)
}

crate::scene! {
    /// Fig. 4.12: consecutive pull-off configurations of a small and a large roughness.
    pub struct Fig4_12 {
        id: "fig4.12",
        chapter: "4",
        params: Fig4_12Params,
        title: "Consecutive pull-off instabilities: cascade and one-by-one detachment",
        caption: "Top views of the gap (nm, clipped at 3 sigma) at two consecutive pull-off \
            instabilities on unloading, the last two that leave the tip in contact (surface model, or with model = fe \
            the finite-element model; parameters of Fig. 4.9a at E = 1.1 MPa: the caption refers to Fig. 4.9a, whose \
            printed smooth-tip force the caption's 2.2 MPa cannot give (ERRATA), while Fig. 4.11 refers to Fig. 4.7a, \
            whose 2.2 MPa Fig. 4.7 reproduces): (a)-(c) A = 1.25 nm, \
            (d)-(f) A = 3.125 nm; before the first of the two jumps, before the second, after the second. The \
            dissertation: at small roughness the detachment of an asperity triggers its neighbour at once (strong \
            coupling); at large roughness the asperities detach one by one (crack arrest and reinitiation).",
        results: &[
            ("pull_offs_1_count", "pull-off jumps on unloading, small roughness"),
            ("pull_offs_2_count", "pull-off jumps on unloading, large roughness"),
            ("rings_per_jump_1_count", "mean asperity rings detached per pull-off, small roughness"),
            ("rings_per_jump_2_count", "mean asperity rings detached per pull-off, large roughness"),
            ("cascades_1_count", "pull-offs detaching two or more rings at once, small roughness"),
            ("cascades_2_count", "pull-offs detaching two or more rings at once, large roughness"),
        ],
    }
}

impl Scene for Fig4_12 {
    top_view_checks!();

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let amplitudes = [p.amplitude_1, p.amplitude_2];
        let setup = p.setup(p.tip.youngs_modulus, p.sigma, p.contact.contact_gap)?;
        let cycles = setup.cycles(setup.tips(&amplitudes)?, true, &job.part(0.0, 0.98), "cycles")?;
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let labels = [["(a)", "(b)", "(c)"], ["(d)", "(e)", "(f)"]];
        let mut notes = Vec::new();
        for (k, ((tip, cycle), a)) in cycles.iter().zip(amplitudes).enumerate() {
            let offs = pull_offs(cycle);
            let rings: Vec<f64> = offs.iter().map(|j| rings_detached(j, p.wavelength)).collect();
            let mean = if rings.is_empty() {
                0.0
            } else {
                rings.iter().sum::<f64>() / rings.len() as f64
            };
            let cascades = rings.iter().filter(|&&r| r >= 2.0).count();
            fig.result(format!("pull_offs_{}_count", k + 1), offs.len() as f64);
            fig.result(format!("rings_per_jump_{}_count", k + 1), mean);
            fig.result(format!("cascades_{}_count", k + 1), cascades as f64);
            let list: Vec<String> = offs
                .iter()
                .zip(&rings)
                .map(|(j, r)| format!("{r:.0} at h/R = {}", number(j.before.depth / setup.radius, 3)))
                .collect();
            notes.push(format!(
                "A = {:.3} nm: {} pull-offs detaching {} ring(s)",
                a * 1e9,
                offs.len(),
                list.join(", ")
            ));
            // The last two consecutive pull-offs after which the tip is still in contact (the
            // final pull-off leaves no contact to draw); the last two when fewer remain.
            let in_contact: Vec<&TipJump> = offs
                .iter()
                .copied()
                .filter(|j| j.after.contact.area() > 0.0)
                .collect();
            let pair = if in_contact.len() >= 2 { &in_contact } else { &offs };
            if pair.len() < 2 {
                continue;
            }
            let (first, second) = (pair[pair.len() - 2], pair[pair.len() - 1]);
            let states = [&first.before, &second.before, &second.after];
            let half = 1.2 * first.before.contact.radius().max(p.wavelength);
            for (n, s) in states.iter().enumerate() {
                let mut panel = Panel::new(Axis::linear("x", "nm"), Axis::linear("y", "nm"))
                    .titled(
                        labels[k][n],
                        format!(
                            "A = {:.3} nm, h/R = {}, a = {:.0} nm",
                            a * 1e9,
                            number(s.depth / setup.radius, 3),
                            s.contact.radius() * 1e9
                        ),
                    )
                    .with_equal_aspect();
                panel.field = Some(top_view(
                    (tip, setup.lj.zeta0()),
                    s,
                    half,
                    p.map_points,
                    p.contact.contact_gap,
                    3.0 * p.sigma * 1e9,
                ));
                if s.contact.area() <= 0.0 {
                    let (_, gaps) = tip.profile(s.depth, &s.displacement);
                    let least = gaps.iter().copied().fold(f64::INFINITY, f64::min) * setup.lj.zeta0();
                    panel.annotate(format!(
                        "Out of contact: the final pull-off has detached the tip (least gap {:.1} nm, above the 3σ clip).",
                        least * 1e9
                    ));
                }
                fig.panels.push(panel);
            }
        }
        fig.note(format!("Pull-offs on unloading: {}.", notes.join("; ")));
        let r = |n: &str| fig.result_value(n).unwrap_or(0.0);
        let (small, large) = (r("rings_per_jump_1_count"), r("rings_per_jump_2_count"));
        fig.note(if small > large && r("pull_offs_2_count") > r("pull_offs_1_count") {
            format!(
                "As the text says: the small roughness detaches {small:.2} rings per pull-off (cascades), the large one \
                 {large:.2} in more, smaller steps; the large roughness's final pull-off still takes the centre and the \
                 last annulus together."
            )
        } else {
            format!(
                "Unlike the text: {small:.2} rings per pull-off at the small roughness, {large:.2} at the large one."
            )
        });
        job.progress(1.0, "done");
        Ok(fig)
    }
}
