//! The finite-element scenes of chapter 4 (sections 4.2.2-4.4): the dissertation's own model,
//! an axisymmetric tip with the Lennard-Jones body force (4.15)
//! ([`crate::models::body_force_fe`]). Fig. 4.4 checks it against Hertz without attraction;
//! fig4.5-models charts it against the surface model that draws the other chapter 4 figures:
//! the same cycle in both, the differences in P_adh, H and the jumps, the run time of each, and
//! how the finite-element result moves with the mesh and the tip's size.

use std::time::Instant;

use super::{cycle_options, draw_cycle, largest_contact_radius, material, tip_for};
use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::axisymmetric::cycle::{CycleModel, CycleOptions, TipCycle, run_convex_loading, run_cycle};
use crate::models::body_force_fe::body::FAR_POINTS;
use crate::models::body_force_fe::tip::{FeGeometry, FeTip, FeTipParams};
use crate::models::lennard_jones::LennardJones;
use crate::params::{Range, require_below};
use crate::scenes::groups::{ContactCriterion, DepthPath, ElasticTip, FeBulk, Interaction, SurfaceModel};
use crate::scenes::{Scene, SceneHeader};

/// The mesh of a scene's finite-element tip: the fine zone near the substrate, its surface
/// elements, the bulk and the modelled size of the tip.
#[derive(Debug, Clone, Copy)]
pub(super) struct FeDiscretisation {
    /// Radius of the fine zone [m].
    pub(super) fine_radius: f64,
    /// Width of the surface elements of the fine zone in units of b = ζ0²E*/w.
    pub(super) element_width: f64,
    /// Growth of the element size with the distance from the fine zone.
    pub(super) grading: f64,
    /// Radius and height of the modelled tip in units of R.
    pub(super) size_over_radius: f64,
    /// Gauss points in r per chord interval near the substrate.
    pub(super) quadrature_points: usize,
}

/// The finite-element tip of a smooth tip in a scene: its material, interaction and mesh.
fn fe_tip(lj: &LennardJones, tip: &ElasticTip, mesh: &FeDiscretisation) -> Result<FeTip> {
    fe_wavy_tip(lj, tip, (0.0, 1.0), mesh)
}

/// The finite-element tip of a scene with the waviness `(amplitude, wavelength)` [m] of (4.10).
pub(super) fn fe_wavy_tip(
    lj: &LennardJones,
    tip: &ElasticTip,
    (amplitude, wavelength): (f64, f64),
    mesh: &FeDiscretisation,
) -> Result<FeTip> {
    let p = lj.params();
    FeTip::new(&FeTipParams {
        radius: tip.radius,
        youngs_modulus: tip.youngs_modulus,
        poisson_ratio: tip.poisson_ratio,
        c6: p.c6,
        c12: p.c12,
        sigma: p.sigma,
        hamaker: p.hamaker,
        amplitude,
        wavelength,
        element_width: mesh.element_width,
        fine_radius: mesh.fine_radius,
        first_layer: 0.1,
        layer_growth: 1.3,
        grading: mesh.grading,
        r0: mesh.size_over_radius * tip.radius,
        h0: mesh.size_over_radius * tip.radius,
        quadrature_points: mesh.quadrature_points,
        far_quadrature_points: FAR_POINTS.min(mesh.quadrature_points),
        geometry: FeGeometry::HalfSpace,
    })
}

crate::scene_params! {
    /// Parameters of scene fig4.4 (section 4.4, the caption of Fig. 4.4: adhesionless contact,
    /// C6 = 0).
    pub struct Fig4_4Params {
        /// The tip (R = 10 µm, E = 1.1 MPa, ν = 0.25).
        group tip: ElasticTip { radius: 10.0e-6, youngs_modulus: 1.1e6 };
        from Interaction: c12: f64, help = "C12 of the potential (4.1) (C6 = 0: no attraction).";
        from Interaction: sigma: f64;
        from Interaction: hamaker: f64;
        /// Deepest penetration in units of σ.
        depth_over_sigma: f64 = 300.0, unit = "", range = Range::between(20.0, 2000.0);
        /// Depth step in units of σ (the states do not depend on it: one equilibrium per depth).
        step_over_sigma: f64 = 10.0, unit = "", range = Range::between(0.5, 100.0);
        /// Width of the surface elements over the contact zone [m].
        element_width: f64 = 3.3e-9, unit = "m", range = Range::between(1.0e-10, 1.0e-7);
        /// The bulk of the mesh.
        group bulk: FeBulk { grading: 0.07, size_over_radius: 128.0 } help {
            grading: "Growth of the element size with the distance from the contact zone (excess stiffness over Hertz 0.15 % at 0.07).",
            size_over_radius: "Radius and height of the tip in units of R (excess stiffness over Hertz of the held top about 17 % R/h0).",
        };
    }
}

crate::scene! {
    /// Fig. 4.4: the finite-element tip without attraction against Hertz.
    pub struct Fig4_4 {
        id: "fig4.4",
        chapter: "4",
        params: Fig4_4Params,
        title: "Adhesionless finite-element contact against Hertz",
        caption: "Finite-element model of the tip (axisymmetric linear triangles, the repulsive \
            body force of (4.15) with C6 = 0; R = 10 um, E = 1.1 MPa, nu = 0.25, C12 = 1, sigma = 1 nm, A_H = 2 × 10⁻²¹ J) \
            pressed against the rigid flat, against Hertz (3.3 with ell = chi = 0): (a) force against penetration, \
            (b) force against contact radius (gap below sigma, section 4.2.2). The soft repulsive wall has no sharp \
            surface: Hertz is drawn from one wall position fitted at the deepest state. No jump occurs.",
        results: &[
            ("hertz_deviation_norm", "largest |P - P_Hertz|/P over the deeper two thirds of the path"),
            ("wall_offset_norm", "fitted wall position / sigma (depth where Hertz starts)"),
            ("radius_deviation_norm", "largest |a - sqrt(R d)|/sqrt(R d) over the same states"),
            ("unknowns_count", "displacement unknowns of the mesh"),
            ("triangles_count", "triangles of the mesh"),
            ("jumps_count", "states reached from an unstable start (0: no instability; the adhesionless energy is convex)"),
            ("all_states_stable_count", "1 when every state was certified stable"),
            ("run_time_s", "wall-clock time of the loading path"),
        ],
        long: true,
    }
}

impl Scene for Fig4_4 {
    fn quick(p: &mut Self::Params) {
        p.depth_over_sigma = p.depth_over_sigma.min(60.0);
        p.step_over_sigma = p.step_over_sigma.max(6.0);
        p.bulk.coarsen(0.4, 6.0);
        p.element_width = p.element_width.max(8e-9);
    }

    fn validate(p: &Self::Params) -> Result<()> {
        require_below(
            "step_over_sigma",
            p.step_over_sigma,
            "depth_over_sigma",
            p.depth_over_sigma,
        )
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let interaction = Interaction {
            c6: 0.0,
            c12: p.c12,
            sigma: p.sigma,
            hamaker: p.hamaker,
        };
        let (lj, modulus) = material(&interaction, &p.tip)?;
        let s = p.sigma;
        let fine = 1.3 * (p.tip.radius * p.depth_over_sigma * s).sqrt() + 20.0 * p.element_width;
        // The element width in the model's radial unit b.
        let mesh = FeDiscretisation {
            fine_radius: fine,
            element_width: 1.0,
            grading: 1.0,
            size_over_radius: 4.0,
            quadrature_points: 4,
        };
        let probe = fe_tip(&lj, &p.tip, &mesh)?;
        let b = probe.scales().radial;
        let tip = fe_tip(
            &lj,
            &p.tip,
            &FeDiscretisation {
                element_width: p.element_width / b,
                grading: p.bulk.grading,
                size_over_radius: p.bulk.size_over_radius,
                ..mesh
            },
        )?;
        let l = tip.length_unit();
        let opts = CycleOptions {
            h_start: 5.0 * l,
            h_min: -p.depth_over_sigma * s,
            step: p.step_over_sigma * s,
            refine_to: 1e-3 * l,
            contact_gap: s,
            keep_profiles: false,
            unload_to: None,
        };
        let start = Instant::now();
        // Without attraction the energy is convex: one equilibrium per depth, no jump to
        // locate, one minimisation per step.
        let cycle = run_convex_loading(&tip, &opts, |f| {
            job.progress(0.99 * f, "finite-element loading");
            job.check()
        })?;
        let run_time = start.elapsed().as_secs_f64();
        let k = 4.0 / 3.0 * modulus * p.tip.radius.sqrt();
        let deepest = cycle.loading.last().ok_or_else(|| Error::Unresolvable {
            model: "fig4.4",
            reason: "the loading path is empty".into(),
        })?;
        let wall = deepest.depth + (deepest.force.max(0.0) / k).powf(2.0 / 3.0);
        let deep: Vec<_> = cycle
            .loading
            .iter()
            .filter(|st| -st.depth > p.depth_over_sigma * s / 3.0)
            .collect();
        let (mut dev_p, mut dev_a) = (0.0f64, 0.0f64);
        for st in &deep {
            let d = wall - st.depth;
            dev_p = dev_p.max((st.force - k * d.powf(1.5)).abs() / st.force);
            let a_h = (p.tip.radius * d).sqrt();
            dev_a = dev_a.max((st.contact.radius() - a_h).abs() / a_h);
        }

        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut ph = Panel::new(
            Axis::linear("Penetration −h", "nm"),
            Axis::linear("Contact force P", "µN"),
        )
        .titled("(a)", format!("{} unknowns", tip.len()));
        let d_max = p.depth_over_sigma * s;
        let hertz: Vec<(f64, f64)> = (0..=200)
            .map(|i| {
                let h = -(wall - 0.05 * d_max) - (d_max * 1.05 + wall) * i as f64 / 200.0;
                (-h * 1e9, k * (wall - h).max(0.0).powf(1.5) * 1e6)
            })
            .collect();
        ph.add(Series::new("Hertz (3.3), ℓ = χ = 0", Style::Reference, hertz).with_color(7));
        ph.add(
            Series::new(
                "finite elements",
                Style::Scatter,
                cycle
                    .loading
                    .iter()
                    .map(|st| (-st.depth * 1e9, st.force * 1e6))
                    .collect(),
            )
            .with_color(0),
        );
        fig.panels.push(ph);
        let mut pa = Panel::new(
            Axis::linear("Contact radius a", "µm"),
            Axis::linear("Contact force P", "µN"),
        )
        .titled("(b)", "a: gap below σ");
        let a_max = largest_contact_radius(deep.iter().copied()) * 1.05;
        let hertz_a: Vec<(f64, f64)> = (0..=200)
            .map(|i| {
                let a = a_max * i as f64 / 200.0;
                (a * 1e6, k * (a * a / p.tip.radius).powf(1.5) * 1e6)
            })
            .collect();
        pa.add(Series::new("Hertz, a² = R d", Style::Reference, hertz_a).with_color(7));
        pa.add(
            Series::new(
                "finite elements",
                Style::Scatter,
                cycle
                    .loading
                    .iter()
                    .filter(|st| st.contact.radius() > 0.0)
                    .map(|st| (st.contact.radius() * 1e6, st.force * 1e6))
                    .collect(),
            )
            .with_color(0),
        );
        fig.panels.push(pa);
        fig.result("hertz_deviation_norm", dev_p);
        fig.result("wall_offset_norm", wall / s);
        fig.result("radius_deviation_norm", dev_a);
        fig.result("unknowns_count", tip.len() as f64);
        fig.result("triangles_count", tip.elements() as f64);
        fig.result("jumps_count", cycle.jumps.len() as f64);
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(cycle.stats.all_stable)),
        );
        fig.result("run_time_s", run_time);
        if a_max > 0.0 {
            fig.note(format!(
                "Force within {:.2} % of Hertz over the deeper two thirds of the path; contact radius within {:.2} % (the gap criterion a: g < sigma sits inside Hertz's hard edge).",
                100.0 * dev_p,
                100.0 * dev_a
            ));
        } else {
            // Under a low pressure the soft wall holds the surface more than σ away: the
            // criterion of section 4.2.2 finds no contact (radius_deviation_norm is then 1).
            fig.note(format!(
                "Force within {:.2} % of Hertz over the deeper two thirds of the path. No state has a gap below sigma (the soft wall's gap exceeds sigma at these pressures): the contact radius is not measured by the gap criterion; raise contact pressure (depth_over_sigma) or see panel (a).",
                100.0 * dev_p
            ));
            fig.panels[1].annotate("No gap below σ in any state: no contact by the criterion.");
        }
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig4.5-models (Fig. 4.5's smooth tip in both models).
    pub struct Fig4_5ModelsParams {
        /// The tip (R = 5 µm, E = 4.4 MPa, ν = 0.25).
        group tip: ElasticTip;
        /// The interaction (C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J).
        group lj: Interaction;
        /// The cycle.
        group path: DepthPath help {
            h_start_over_zeta0: "Start (and end) of the cycle in units of ζ0.",
        };
        /// Ring width of the surface model and element width of the finite-element model over the contact zone, in units of b = ζ0²E*/w (the finite-element cycle's receding contact edge hops from ring to ring at 0.25, not at 0.15).
        width: f64 = 0.15, unit = "", range = Range::between(0.05, 2.0);
        /// The bulk of the finite-element mesh.
        group bulk: FeBulk;
        /// Gradings of the mesh-convergence runs (shallow cycles to h = 0).
        convergence_gradings: Vec<f64> = vec![0.4, 0.3, 0.2, 0.15], unit = "", range = Range::between(0.05, 1.0);
        /// Tip sizes (over R) of the domain-convergence runs (shallow cycles to h = 0).
        convergence_sizes: Vec<f64> = vec![5.0, 10.0, 20.0, 40.0], unit = "", range = Range::between(2.0, 100.0);
        /// Run the convergence studies of panel (b): 1 yes, 0 no.
        convergence_study: usize = 1, unit = "", range = Range::between(0.0, 1.0);
        /// The contact threshold.
        group contact: ContactCriterion;
    }
}

/// What one model gave on one cycle.
struct ModelRun {
    cycle: TipCycle,
    seconds: f64,
    unknowns: usize,
}

/// P_adh, H, and the depths of the first pull-in and the last pull-off of a cycle.
fn summary(c: &TipCycle) -> (f64, f64, f64, f64) {
    let pull_in = c
        .jumps
        .iter()
        .find(|j| j.loading)
        .map_or(f64::NAN, |j| j.before.depth);
    let pull_off = c
        .jumps
        .iter()
        .rfind(|j| !j.loading)
        .map_or(f64::NAN, |j| j.before.depth);
    (c.adhesive_force(), c.hysteresis(), pull_in, pull_off)
}

crate::scene! {
    /// Fig. 4.5 in both models: the surface model against the finite-element model.
    pub struct Fig4_5Models {
        id: "fig4.5-models",
        chapter: "4",
        params: Fig4_5ModelsParams,
        title: "Smooth tip: finite-element model against the surface model",
        caption: "The cycle of Fig. 4.5 (R = 5 um, E = 4.4 MPa, nu = 0.25, C6 = 3, C12 = 1, sigma = 1 nm, \
            A_H = 2 × 10⁻²¹ J) computed with the dissertation's finite-element model (an axisymmetric tip with the body \
            force (4.15)) and with the surface model that draws the other chapter 4 figures (the body force \
            integrated through a column, the traction (4.19)). (a) P-h cycles of both; with convergence_study = 1 \
            (the default; not in the quick form, which draws (a) alone) the adhesive force of \
            shallow finite-element cycles (to h = 0) (b) against the number of unknowns as the bulk mesh is refined \
            (grading) and (c) against the tip's size r0 = h0, with the surface model's value for reference. The two \
            models differ only through the strain of the surface layer (order p/E) and the finite tip.",
        results: &[
            ("fe_adhesive_force_norm", "P_adh/(pi w R), finite elements"),
            ("surface_adhesive_force_norm", "P_adh/(pi w R), surface model"),
            ("fe_hysteresis_norm", "H/(2E* R^3), finite elements"),
            ("surface_hysteresis_norm", "H/(2E* R^3), surface model"),
            ("fe_pull_in_depth_nm", "depth of the pull-in, finite elements"),
            ("surface_pull_in_depth_nm", "depth of the pull-in, surface model"),
            ("fe_pull_off_depth_nm", "depth of the last pull-off, finite elements"),
            ("surface_pull_off_depth_nm", "depth of the last pull-off, surface model"),
            ("fe_jumps_count", "jumps of the finite-element cycle"),
            ("surface_jumps_count", "jumps of the surface-model cycle"),
            ("fe_unknowns_count", "unknowns of the finite-element model"),
            ("surface_unknowns_count", "rings of the surface model"),
            ("fe_time_s", "run time of the finite-element cycle"),
            ("surface_time_s", "run time of the surface-model cycle"),
            ("all_states_stable_count", "1 when every state of both cycles was certified stable"),
        ],
        sweep: true,
    }
}

impl Scene for Fig4_5Models {
    fn quick(p: &mut Self::Params) {
        p.path.h_min_over_zeta0 = p.path.h_min_over_zeta0.max(0.0);
        p.path.h_start_over_zeta0 = p.path.h_start_over_zeta0.min(9.0);
        p.path.step_over_zeta0 = p.path.step_over_zeta0.max(0.5);
        p.bulk.coarsen(0.5, 4.0);
        p.convergence_study = 0;
    }

    fn validate(p: &Self::Params) -> Result<()> {
        p.path.validate()
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let (lj, modulus) = material(&p.lj, &p.tip)?;
        let (zeta0, w) = (lj.zeta0(), lj.work_of_adhesion());
        let h_min = p.path.h_min_over_zeta0 * zeta0;
        let discretisation = SurfaceModel {
            ring_width: p.width,
            quadrature_points: 4,
        };
        let surface = tip_for(&lj, (p.tip.radius, modulus), (0.0, 1.0), h_min, &discretisation)?;
        let fine = surface.params().fine_radius;
        let fe_at = |grading: f64, size: f64| {
            fe_tip(
                &lj,
                &p.tip,
                &FeDiscretisation {
                    fine_radius: fine,
                    element_width: p.width,
                    grading,
                    size_over_radius: size,
                    quadrature_points: 4,
                },
            )
        };
        let opts = |h_min: f64| {
            cycle_options(
                zeta0,
                (
                    p.path.h_start_over_zeta0 * zeta0,
                    h_min,
                    p.path.step_over_zeta0 * zeta0,
                ),
                p.contact.contact_gap,
            )
        };
        let fe_tip = fe_at(p.bulk.grading, p.bulk.size_over_radius)?;
        // Progress: the full finite-element cycle, the surface model's, the shallow
        // finite-element cycles of the convergence study, the surface model's shallow cycle, by
        // their estimated costs. Measured: 3 788 unknowns took 7.6 times the surface model's
        // 277 rings (quick form, 30.5 s and 4.0 s), the finite-element cost grows as about
        // unknowns^1.4, the surface model's as rings²; the study took about 1.2 times the full
        // cycle at the defaults.
        let fe_cost = 7.6 * (fe_tip.len() as f64 / 3788.0).powf(1.4);
        let surface_cost = (surface.len() as f64 / 277.0).powi(2);
        let study = if p.convergence_study == 1 {
            1.2 * fe_cost
        } else {
            0.0
        };
        let stages = job.parts(&[fe_cost, surface_cost, study, 0.5 * surface_cost], 0.0, 0.99);
        let start = Instant::now();
        let fe_cycle = run_cycle(&fe_tip, &opts(h_min), |f| {
            stages[0].progress(f, "finite-element cycle");
            job.check()
        })?;
        let fe = ModelRun {
            cycle: fe_cycle,
            seconds: start.elapsed().as_secs_f64(),
            unknowns: fe_tip.len(),
        };
        let start = Instant::now();
        let surface_cycle = run_cycle(&surface, &opts(h_min), |f| {
            stages[1].progress(f, "surface-model cycle");
            job.check()
        })?;
        let bem = ModelRun {
            cycle: surface_cycle,
            seconds: start.elapsed().as_secs_f64(),
            unknowns: surface.len(),
        };
        // Convergence: shallow cycles (to h = 0) of the finite-element model.
        let mut variants: Vec<(bool, f64)> = Vec::new();
        if p.convergence_study == 1 {
            variants.extend(p.convergence_gradings.iter().map(|&g| (true, g)));
            variants.extend(p.convergence_sizes.iter().map(|&s| (false, s)));
        }
        let shallow = opts(0.0_f64.max(h_min));
        let weights = vec![1.0; variants.len()];
        let studies = stages[2].map_parallel_parts(
            &variants,
            &weights,
            "convergence cycles",
            (0.0, 1.0),
            |&(by_grading, v), part| {
                let tip = if by_grading {
                    fe_at(v, p.bulk.size_over_radius)?
                } else {
                    fe_at(p.bulk.grading, v)?
                };
                let c = run_cycle(&tip, &shallow, |f| {
                    part.progress(f, "convergence cycle");
                    job.check()
                })?;
                Ok((by_grading, v, tip.len(), c.adhesive_force()))
            },
        )?;
        let reference_shallow = if variants.is_empty() {
            None
        } else {
            let c = run_cycle(&surface, &shallow, |f| {
                stages[3].progress(f, "surface-model shallow cycle");
                job.check()
            })?;
            Some(c.adhesive_force())
        };

        let force_scale = std::f64::consts::PI * w * p.tip.radius;
        let scale = (p.tip.radius, 2.0 * modulus * p.tip.radius * p.tip.radius);
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut ph = Panel::new(
            Axis::linear("Indentation depth h/R", ""),
            Axis::linear("Contact force P/(2E*R²)", ""),
        )
        .titled("(a)", "same cycle, both models");
        draw_cycle(&mut ph, &bem.cycle, "surface model", 7, scale);
        draw_cycle(&mut ph, &fe.cycle, "finite elements", 0, scale);
        fig.panels.push(ph);
        // (b) against the unknowns as the bulk mesh is refined, (c) against the tip's size
        // (which adds few unknowns: the mesh grows logarithmically with it).
        for (by_grading, label, title, axis, color) in [
            (
                true,
                "(b)",
                "bulk mesh refined (grading marked)",
                "Unknowns of the finite-element model",
                0,
            ),
            (false, "(c)", "tip grown (r0 = h0)", "Tip size r0/R = h0/R", 1),
        ] {
            let mut pts: Vec<(f64, f64, f64)> = studies
                .iter()
                .filter(|s| s.0 == by_grading)
                .map(|s| (if by_grading { s.2 as f64 } else { s.1 }, -s.3 / force_scale, s.1))
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut pc = Panel::new(
                Axis::log(axis, ""),
                Axis::linear("Adhesive force P_adh/(πwR), cycle to h = 0", ""),
            )
            .titled(label, title);
            pc.add(
                Series::new(
                    "finite elements",
                    Style::Stable,
                    pts.iter().map(|q| (q.0, q.1)).collect(),
                )
                .with_color(color),
            );
            for q in &pts {
                let text = if by_grading {
                    format!("{}", q.2)
                } else {
                    format!("{}R", q.2)
                };
                pc.mark(
                    Marker::new(text.clone(), MarkerShape::Point, q.0, q.1)
                        .with_color(color)
                        .with_label(text),
                );
            }
            if let Some(f) = reference_shallow {
                let (lo, hi) = (pts[0].0, pts[pts.len() - 1].0);
                pc.add(
                    Series::new(
                        "surface model",
                        Style::Reference,
                        vec![(lo, -f / force_scale), (hi, -f / force_scale)],
                    )
                    .with_color(7),
                );
            }
            fig.panels.push(pc);
        }
        let (fa, fh, fi, fo) = summary(&fe.cycle);
        let (sa, sh, si, so) = summary(&bem.cycle);
        let loss_scale = scale.1 * p.tip.radius;
        fig.result("fe_adhesive_force_norm", -fa / force_scale);
        fig.result("surface_adhesive_force_norm", -sa / force_scale);
        fig.result("fe_hysteresis_norm", fh / loss_scale);
        fig.result("surface_hysteresis_norm", sh / loss_scale);
        for (name, v) in [
            ("fe_pull_in_depth_nm", fi),
            ("surface_pull_in_depth_nm", si),
            ("fe_pull_off_depth_nm", fo),
            ("surface_pull_off_depth_nm", so),
        ] {
            if v.is_finite() {
                fig.result(name, v * 1e9);
            }
        }
        fig.result("fe_jumps_count", fe.cycle.jumps.len() as f64);
        fig.result("surface_jumps_count", bem.cycle.jumps.len() as f64);
        fig.result("fe_unknowns_count", fe.unknowns as f64);
        fig.result("surface_unknowns_count", bem.unknowns as f64);
        fig.result("fe_time_s", fe.seconds);
        fig.result("surface_time_s", bem.seconds);
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(fe.cycle.stats.all_stable && bem.cycle.stats.all_stable)),
        );
        fig.note(format!(
            "P_adh/(pi w R): finite elements {:.4}, surface model {:.4} ({} %); H: {} %; run time {:.1} s against {:.1} s.",
            -fa / force_scale,
            -sa / force_scale,
            signed_percent(100.0 * (fa / sa - 1.0)),
            signed_percent(100.0 * (fh / sh - 1.0)),
            fe.seconds,
            bem.seconds
        ));
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig4.6 (Fig. 4.5's smooth tip, the fields after the pull-in).
    pub struct Fig4_6Params {
        /// The tip (R = 5 µm, E = 4.4 MPa, ν = 0.25).
        group tip: ElasticTip;
        /// The interaction (C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J).
        group lj: Interaction;
        /// Depth of the state shown, in units of ζ0 (after the pull-in, which happens near +4 ζ0 at the defaults).
        depth_over_zeta0: f64 = 0.0, unit = "", range = Range::between(-20.0, 20.0);
        from DepthPath: step_over_zeta0: f64 = 0.25, help = "Depth step of the loading in units of ζ0.";
        /// Element width over the contact zone in units of b = ζ0²E*/w (that of fig4.5-models, whose finite-element cycle hops from ring to ring on unloading at 0.25, not at 0.15).
        width: f64 = 0.15, unit = "", range = Range::between(0.05, 2.0);
        /// The bulk of the mesh.
        group bulk: FeBulk help {
            size_over_radius: "Radius and height of the tip in units of R.",
        };
        /// Depth below the surface at which σ_zz is drawn, in units of ζ0 (below the interaction layer the column carries the whole traction).
        stress_depth_over_zeta0: f64 = 3.0, unit = "", range = Range::between(0.1, 50.0);
    }
}

crate::scene! {
    /// Fig. 4.6: u_z in the tip and σ_zz along the interface after the pull-in.
    pub struct Fig4_6 {
        id: "fig4.6",
        chapter: "4",
        params: Fig4_6Params,
        title: "Fields in the tip after the pull-in (finite elements)",
        caption: "The smooth tip of Fig. 4.5 (finite-element model) loaded past its pull-in: (a) the \
            vertical displacement u_z in the tip near the contact (the neck-like profile of the contact zone), \
            (b) the normal stress sigma_zz along the interface, taken just above the interaction layer (the tip's \
            bottom face is traction free; the body force builds sigma_zz up through the layer): compressive in the \
            centre, tensile with a concentration at the contact edge, as in the classical adhesive contact; (c) the \
            gap of the deformed surface near the contact against the undeformed tip's at the same depth: the \
            neck-like profile (also drawn in (a)).",
        results: &[
            ("contact_radius_m", "radius where the gap is below sigma"),
            ("depth_m", "depth h of the state"),
            ("force_N", "force P of the state (compressive positive)"),
            ("peak_tension_MPa", "largest tensile sigma_zz on the line of panel (b)"),
            ("peak_tension_radius_m", "its radius"),
            ("centre_stress_MPa", "sigma_zz at the axis on that line"),
            ("unknowns_count", "displacement unknowns of the mesh"),
        ],
        long: true,
    }
}

impl Scene for Fig4_6 {
    fn quick(p: &mut Self::Params) {
        p.step_over_zeta0 = p.step_over_zeta0.max(0.5);
        p.width = p.width.max(0.5);
        p.bulk.coarsen(0.4, 5.0);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let (lj, modulus) = material(&p.lj, &p.tip)?;
        let zeta0 = lj.zeta0();
        let h = p.depth_over_zeta0 * zeta0;
        let discretisation = SurfaceModel {
            ring_width: p.width,
            quadrature_points: 4,
        };
        let surface = tip_for(
            &lj,
            (p.tip.radius, modulus),
            (0.0, 1.0),
            h.min(0.0),
            &discretisation,
        )?;
        let tip = fe_tip(
            &lj,
            &p.tip,
            &FeDiscretisation {
                fine_radius: surface.params().fine_radius,
                element_width: p.width,
                grading: p.bulk.grading,
                size_over_radius: p.bulk.size_over_radius,
                quadrature_points: 4,
            },
        )?;
        let start = (h + 2.0 * zeta0).max(8.0 * zeta0);
        let opts = CycleOptions {
            h_start: start,
            h_min: h,
            step: p.step_over_zeta0 * zeta0,
            refine_to: 1e-2 * zeta0,
            contact_gap: p.lj.sigma,
            keep_profiles: true,
            unload_to: Some(h + 0.5 * p.step_over_zeta0 * zeta0),
        };
        let cycle = run_cycle(&tip, &opts, |f| {
            job.progress(0.99 * f, "finite-element loading");
            job.check()
        })?;
        let state = cycle.loading.last().ok_or_else(|| Error::Unresolvable {
            model: "fig4.6",
            reason: "the loading path is empty".into(),
        })?;
        let u = &state.displacement;
        let l = tip.length_unit();
        let a = state.contact.radius().max(10.0 * l);
        let mesh = tip.mesh();

        // (a) u_z on a grid of the window r ≤ 1.6 a, z ≤ 0.8 a (mesh units ℓ).
        let (nx, ny) = (96usize, 48usize);
        let (w_r, w_z) = (1.6 * a / l, 0.8 * a / l);
        let xs: Vec<f64> = (0..nx).map(|i| w_r * i as f64 / (nx - 1) as f64).collect();
        let ys: Vec<f64> = (0..ny).map(|j| w_z * j as f64 / (ny - 1) as f64).collect();
        let mut values = vec![f64::NAN; nx * ny];
        for tri in &mesh.triangles {
            let pts = tri.map(|k| mesh.nodes[k]);
            let (r_lo, r_hi) = (
                pts.iter().map(|q| q[0]).fold(f64::INFINITY, f64::min),
                pts.iter().map(|q| q[0]).fold(0.0, f64::max),
            );
            let (z_lo, z_hi) = (
                pts.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min),
                pts.iter().map(|q| q[1]).fold(f64::NEG_INFINITY, f64::max),
            );
            if r_lo > w_r || z_lo > w_z {
                continue;
            }
            let shape = crate::models::body_force_fe::element::Shape::new(pts);
            let uz = tri.map(|k| tip.node_displacement(u, k)[1]);
            let i0 = xs.partition_point(|&x| x < r_lo);
            let j0 = ys.partition_point(|&y| y < z_lo);
            for j in j0..ny {
                if ys[j] > z_hi {
                    break;
                }
                for i in i0..nx {
                    if xs[i] > r_hi {
                        break;
                    }
                    let n = shape.at(xs[i], ys[j]);
                    if n.iter().all(|&v| v >= -1e-9) {
                        values[j * nx + i] = (0..3).map(|k| n[k] * uz[k]).sum::<f64>() * l * 1e9;
                    }
                }
            }
        }
        // Grid points outside the mesh (none in this window): the nearest value in the row.
        for j in 0..ny {
            for i in 0..nx {
                if values[j * nx + i].is_nan() {
                    values[j * nx + i] = (0..nx)
                        .map(|k| values[j * nx + k])
                        .find(|v| v.is_finite())
                        .unwrap_or(0.0);
                }
            }
        }
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut pf = Panel::new(
            Axis::linear("Radius r", "nm"),
            Axis::linear("Height z above the apex", "nm"),
        )
        .titled("(a)", format!("u_z at h = {:.2} nm", state.depth * 1e9));
        pf.field = Some(crate::figure::Field::heat(
            "u_z",
            "nm",
            xs.iter().map(|x| x * l * 1e9).collect(),
            ys.iter().map(|y| y * l * 1e9).collect(),
            values,
        ));
        // The deformed surface (nodes moved by (u_r, u_z)) over the field.
        let surface_nodes: Vec<usize> = mesh
            .surface
            .iter()
            .copied()
            .filter(|&k| mesh.nodes[k][0] <= w_r)
            .collect();
        let deformed: Vec<(f64, f64)> = surface_nodes
            .iter()
            .map(|&k| {
                let [ur, uz] = tip.node_displacement(u, k);
                (
                    (mesh.nodes[k][0] + ur) * l * 1e9,
                    (mesh.nodes[k][1] + uz) * l * 1e9,
                )
            })
            .collect();
        pf.add(Series::new("deformed surface", Style::Stable, deformed).with_color(0));
        fig.panels.push(pf);
        // (c) The neck: the gap of the deformed surface near the contact against the rigid
        // tip's at the same depth.
        let delta = tip.approach(state.depth);
        let zero = vec![0.0; u.len()];
        let window = |(r, g): (Vec<f64>, Vec<f64>)| -> Vec<(f64, f64)> {
            r.iter()
                .zip(g)
                .filter(|(r, _)| **r <= 1.6 * a)
                .map(|(r, g)| (r * 1e9, g * l * 1e9))
                .collect()
        };
        let mut pn = Panel::new(Axis::linear("Radius r", "nm"), Axis::linear("Gap g", "nm"))
            .titled("(c)", "deformed surface near the contact: the neck");
        pn.add(Series::new("deformed tip", Style::Stable, window(tip.surface_gaps(delta, u))).with_color(0));
        pn.add(
            Series::new(
                "undeformed tip, same depth",
                Style::Reference,
                window(tip.surface_gaps(delta, &zero)),
            )
            .with_color(7),
        );
        pn.add(
            Series::new(
                "contact threshold σ",
                Style::Reference,
                vec![(0.0, p.lj.sigma * 1e9), (1.6 * a * 1e9, p.lj.sigma * 1e9)],
            )
            .with_color(1),
        );

        // (b) σ_zz at the element centroids nearest to the chosen depth below the surface.
        let stresses = tip.centroid_stresses(u);
        let target = p.stress_depth_over_zeta0 * zeta0 / l;
        let mut line: Vec<(f64, f64, f64)> = mesh
            .triangles
            .iter()
            .zip(&stresses)
            .filter_map(|(tri, s)| {
                let r = tri.iter().map(|&k| mesh.nodes[k][0]).sum::<f64>() / 3.0;
                let z = tri.iter().map(|&k| mesh.nodes[k][1]).sum::<f64>() / 3.0;
                (r <= 2.0 * a / l).then_some((r, (z - target).abs(), s[1]))
            })
            .collect();
        line.sort_by(|x, y| x.0.total_cmp(&y.0));
        // One value per radius bin of two element widths: the mean over the elements whose
        // centroid lies within one ζ0 of the target depth (the stress of a linear triangle is
        // constant on it; the mean over a patch smooths the two orientations of the cut squares).
        let bin = 2.0 * tip.mesh().width;
        let band = zeta0 / l;
        let mut pts: Vec<(f64, f64)> = Vec::new();
        let mut k = 0;
        while k < line.len() {
            let r0 = line[k].0;
            let group: Vec<&(f64, f64, f64)> = line[k..].iter().take_while(|q| q.0 < r0 + bin).collect();
            let near: Vec<&&(f64, f64, f64)> = group.iter().filter(|q| q.1 <= band).collect();
            if !near.is_empty() {
                let r = near.iter().map(|q| q.0).sum::<f64>() / near.len() as f64;
                let s = near.iter().map(|q| q.2).sum::<f64>() / near.len() as f64;
                pts.push((r * l * 1e9, s * 1e-6));
            }
            k += group.len();
        }
        let (peak_r, peak) = pts
            .iter()
            .copied()
            .fold((0.0, f64::NEG_INFINITY), |m, q| if q.1 > m.1 { q } else { m });
        let centre = pts.first().map_or(0.0, |q| q.1);
        let mut ps = Panel::new(
            Axis::linear("Radius r", "nm"),
            Axis::linear("Normal stress σ_zz", "MPa"),
        )
        .titled(
            "(b)",
            format!(
                "{:.1} ζ0 above the surface; tension positive",
                p.stress_depth_over_zeta0
            ),
        );
        ps.add(Series::new("finite elements", Style::Stable, pts).with_color(0));
        ps.mark(
            Marker::new(
                "contact edge",
                MarkerShape::Cross,
                state.contact.radius() * 1e9,
                0.0,
            )
            .with_label("a"),
        );
        fig.panels.push(ps);
        fig.panels.push(pn);
        fig.result("contact_radius_m", state.contact.radius());
        fig.result("depth_m", state.depth);
        fig.result("force_N", state.force);
        fig.result("peak_tension_MPa", peak);
        fig.result("peak_tension_radius_m", peak_r * 1e-9);
        fig.result("centre_stress_MPa", centre);
        fig.result("unknowns_count", tip.len() as f64);
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// A signed percentage with two decimals and a true minus sign ("+3.05", "−0.22").
fn signed_percent(v: f64) -> String {
    format!("{v:+.2}").replace('-', "−")
}
