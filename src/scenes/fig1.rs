//! Chapter 1 scenes: the classical P-h curves (Fig. 1.1) and the Fuller-Tabor force-separation
//! curves of a rough surface (Fig. 1.4b).

use super::{Registered, Scene, SceneDyn, SceneHeader};
use crate::error::Result;
use crate::figure::{Axis, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::classical::{
    DMT_ADHESIVE_FORCE_NORM, JKR_HYSTERESIS_CONSTANT, SphereContact, jkr_bar,
    jkr_hysteresis_constant_by_quadrature,
};
use crate::models::fuller_tabor::FullerTabor;
use crate::params::{Range, require_below};

/// The chapter's scenes, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[&Registered::<Fig1_1>::NEW, &Registered::<Fig1_4b>::NEW];

crate::param_choice! {
    /// Units of the axes of a P-h figure.
    pub enum PlotUnits { Normalized = "normalized", Si = "si" }
}

crate::scene_params! {
    /// Parameters of scene fig1.1. The dissertation's figure is generic (no parameters); the
    /// defaults describe a glass bead on PDMS of the kind measured in chapter 2.
    pub struct Fig1_1Params {
        /// Sphere radius R.
        radius: f64 = 10.0e-6, unit = "m", range = Range::positive();
        /// Effective modulus E* = E/(1-ν²) of the substrate (rigid sphere).
        modulus: f64 = 1.0e6, unit = "Pa", range = Range::positive();
        /// Work of adhesion w.
        work_of_adhesion: f64 = 0.05, unit = "J/m^2", range = Range::positive();
        /// Equilibrium separation ζ₀ for the Tabor parameter (1.8).
        equilibrium_separation: f64 = 0.3e-9, unit = "m", range = Range::positive();
        /// Largest indentation depth drawn, in units of h₀ = (π²Rw²/E*²)^(1/3).
        max_depth_norm: f64 = 2.5, unit = "", range = Range::open(0.0, 1.0e3);
        /// Axis units: normalized (P/πwR, h/h₀) or si.
        units: PlotUnits = PlotUnits::Normalized, unit = "", range = Range::any();
        /// Points per curve.
        points: usize = 400, unit = "", range = Range::between(10.0, 1.0e6);
    }
}

crate::scene! {
    /// Fig. 1.1: Hertz, JKR and DMT force-indentation curves with the JKR instabilities.
    pub struct Fig1_1 {
        id: "fig1.1",
        chapter: "1",
        params: Fig1_1Params,
        title: "Hertz, JKR and DMT force-indentation curves",
        caption: "Contact force vs indentation depth by Hertz (1.1), JKR (1.2) and DMT (1.7). \
            JKR pull-in A->B (1.3) and pull-off D->E (1.4) in displacement control; adhesive forces at C (JKR, 1.5) \
            and F (DMT). The shaded loop is the JKR hysteresis (1.6).",
        results: &[
            ("jkr_pull_in_radius_norm", "a_B / a0, a0 = (pi R^2 w/E*)^(1/3), Eq. (1.3)"),
            ("jkr_pull_in_depth_norm", "h_B / h0, h0 = (pi^2 R w^2/E*^2)^(1/3), Eq. (1.3)"),
            ("jkr_pull_in_force_norm", "P_B / (pi w R), Eq. (1.3)"),
            ("jkr_pull_off_radius_norm", "a_D / a0, Eq. (1.4)"),
            ("jkr_pull_off_depth_norm", "h_D / h0, Eq. (1.4)"),
            ("jkr_pull_off_force_norm", "P_D / (pi w R), Eq. (1.4)"),
            ("jkr_adhesive_force_radius_norm", "a_C / a0, Eq. (1.5)"),
            ("jkr_adhesive_force_depth_norm", "h_C / h0, Eq. (1.5)"),
            ("jkr_adhesive_force_norm", "P_C / (pi w R), Eq. (1.5)"),
            ("dmt_adhesive_force_norm", "P_F / (pi w R), Eq. (1.7)"),
            ("jkr_hysteresis_norm", "H / (R^4 w^5/E*^2)^(1/3), closed form of Eq. (1.6)"),
            ("jkr_hysteresis_loop_norm", "H / (R^4 w^5/E*^2)^(1/3), quadrature of the displacement-controlled loop"),
            ("jkr_pull_off_force_N", "P_D in newtons"),
            ("jkr_adhesive_force_N", "P_C in newtons"),
            ("jkr_pull_off_depth_m", "h_D in metres"),
            ("jkr_hysteresis_J", "H in joules, Eq. (1.6)"),
            ("tabor_parameter_norm", "mu_T of Eq. (1.8)"),
        ],
    }
}

impl Scene for Fig1_1 {
    fn validate(p: &Self::Params) -> Result<()> {
        SphereContact::new(p.radius, p.modulus, p.work_of_adhesion)?;
        Ok(())
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(60);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let c = SphereContact::new(p.radius, p.modulus, p.work_of_adhesion)?;
        let n = p.points;
        // Axis scaling: normalized, or SI with a readable prefix.
        let (h_unit, p_unit, h_scale, p_scale, x_label, y_label) = match p.units {
            PlotUnits::Normalized => (
                String::new(),
                String::new(),
                1.0,
                1.0,
                "Indentation depth h/h_0, h_0 = ∛(π²Rw²/E*²)",
                "Contact force P/(πwR)",
            ),
            PlotUnits::Si => {
                let (hs, hu) = super::engineering_unit("m", p.max_depth_norm * c.h0());
                let (ps, pu) = super::engineering_unit("N", 2.0 * c.p0());
                (
                    hu,
                    pu,
                    c.h0() / hs,
                    c.p0() / ps,
                    "Indentation depth h",
                    "Contact force P",
                )
            }
        };
        let pt = |h: f64, f: f64| (h * h_scale, f * p_scale);
        let h_max = p.max_depth_norm;
        // In the scales a0, h0, πwR: Hertz h = ā², P = (4/3)ā³; DMT P = (4/3)ā³ − 2.
        let a_max_hertz = h_max.sqrt();
        let a_max_jkr = jkr_bar::stable_radius_at_depth(h_max)?;
        let grid = |lo: f64, hi: f64| (0..n).map(move |i| lo + (hi - lo) * i as f64 / (n - 1) as f64);
        let hertz: Vec<_> = grid(0.0, a_max_hertz)
            .map(|a| pt(a * a, 4.0 / 3.0 * a.powi(3)))
            .collect();
        let dmt: Vec<_> = grid(0.0, a_max_hertz)
            .map(|a| pt(a * a, 4.0 / 3.0 * a.powi(3) - 2.0))
            .collect();
        let d = jkr_bar::PULL_OFF;
        // Cluster points near ā = 0 and ā_D where the curve turns.
        let jkr_unstable: Vec<_> = (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64;
                let a = d.a * t * t;
                pt(jkr_bar::depth(a), jkr_bar::force(a))
            })
            .collect();
        let jkr_stable: Vec<_> = (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64;
                let a = d.a + (a_max_jkr - d.a) * t * t;
                pt(jkr_bar::depth(a), jkr_bar::force(a))
            })
            .collect();
        job.check()?;

        let mut panel = Panel::new(Axis::linear(x_label, h_unit), Axis::linear(y_label, p_unit));
        panel.add(Series::new("Hertz", Style::Stable, hertz).with_color(7));
        panel.add(Series::new("JKR", Style::Stable, jkr_stable.clone()).with_color(1));
        panel.add(Series::new("JKR", Style::Unstable, jkr_unstable).with_color(1));
        panel.add(Series::new("DMT", Style::Stable, dmt).with_color(0));
        // The displacement-controlled loop: D -> B along the stable branch, closed by P = 0.
        let b = jkr_bar::PULL_IN;
        let mut loop_pts: Vec<_> = jkr_stable
            .iter()
            .copied()
            .filter(|&(h, _)| h <= b.h * h_scale + 1e-12)
            .collect();
        loop_pts.push(pt(b.h, b.p));
        loop_pts.push(pt(0.0, 0.0));
        loop_pts.push(pt(d.h, 0.0));
        panel.shade("JKR hysteresis", loop_pts, Some(1));
        panel.add(
            Series::new("jump", Style::Jump, vec![pt(0.0, 0.0), pt(b.h, b.p)])
                .with_color(1)
                .without_legend(),
        );
        panel.add(
            Series::new("jump", Style::Jump, vec![pt(d.h, d.p), pt(d.h, 0.0)])
                .with_color(1)
                .without_legend(),
        );
        let cpt = jkr_bar::ADHESIVE_FORCE;
        let (ax, ay) = pt(0.0, 0.0);
        let (bx, by) = pt(b.h, b.p);
        let (cx, cy) = pt(cpt.h, cpt.p);
        let (dx, dy) = pt(d.h, d.p);
        let (ex, ey) = pt(d.h, 0.0);
        let (fx, fy) = pt(0.0, -2.0);
        panel.mark(
            Marker::new("pull-in", MarkerShape::PullIn, ax, ay)
                .with_color(1)
                .with_label("A"),
        );
        panel.mark(
            Marker::new("stable state", MarkerShape::StableState, bx, by)
                .with_color(1)
                .with_label("B"),
        );
        panel.mark(
            Marker::new("adhesive force", MarkerShape::Point, cx, cy)
                .with_color(1)
                .with_label("C"),
        );
        panel.mark(
            Marker::new("pull-off", MarkerShape::PullOff, dx, dy)
                .with_color(1)
                .with_label("D"),
        );
        panel.mark(
            Marker::new("stable state", MarkerShape::StableState, ex, ey)
                .with_color(1)
                .with_label("E"),
        );
        panel.mark(
            Marker::new("adhesive force", MarkerShape::Point, fx, fy)
                .with_color(0)
                .with_label("F"),
        );

        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(panel);
        let results = [
            ("jkr_pull_in_radius_norm", b.a),
            ("jkr_pull_in_depth_norm", b.h),
            ("jkr_pull_in_force_norm", b.p),
            ("jkr_pull_off_radius_norm", d.a),
            ("jkr_pull_off_depth_norm", d.h),
            ("jkr_pull_off_force_norm", d.p),
            ("jkr_adhesive_force_radius_norm", cpt.a),
            ("jkr_adhesive_force_depth_norm", cpt.h),
            ("jkr_adhesive_force_norm", cpt.p),
            // Both in non-dimensional form, independent of the dimensional scales' range.
            ("dmt_adhesive_force_norm", DMT_ADHESIVE_FORCE_NORM),
            ("jkr_hysteresis_norm", JKR_HYSTERESIS_CONSTANT),
            (
                "jkr_hysteresis_loop_norm",
                jkr_hysteresis_constant_by_quadrature(1e-13)?,
            ),
            ("jkr_pull_off_force_N", c.jkr_pull_off().p),
            ("jkr_adhesive_force_N", c.jkr_adhesive_force().p),
            ("jkr_pull_off_depth_m", c.jkr_pull_off().h),
            ("jkr_hysteresis_J", c.jkr_hysteresis()),
            (
                "tabor_parameter_norm",
                c.tabor_parameter(p.equilibrium_separation)?,
            ),
        ];
        for (name, v) in results {
            fig.result(name, v);
        }
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig1.4b. The dissertation does not give its roughness values; these
    /// two show the reduction of adhesion with roughness (θ = σ_rms/h_o = 0.5: an adhesive
    /// loop close to the smooth JKR one; θ = 2: adhesion nearly gone).
    pub struct Fig1_4bParams {
        /// Smaller roughness θ₁ = σ_rms/h_o, with h_o = |h_D| = (27π²Rw²/64E*²)^(1/3).
        sigma1_over_ho: f64 = 0.5, unit = "", range = Range::open(0.0, 1.0e3);
        /// Larger roughness θ₂ = σ_rms/h_o.
        sigma2_over_ho: f64 = 2.0, unit = "", range = Range::open(0.0, 1.0e3);
        /// Separation d/h_o where the approach starts and the retraction ends, the same for both surfaces (far enough that every asperity of the rougher one has detached, about 3σ_rms + h_o).
        start_separation_ho: f64 = 8.0, unit = "", range = Range::open(-1.0e4, 1.0e4);
        /// Minimum separation d_min/h_o reached on loading, the same for both surfaces.
        min_separation_ho: f64 = -1.0, unit = "", range = Range::open(-1.0e4, 1.0e4);
        /// Separations per phase.
        points: usize = 241, unit = "", range = Range::between(10.0, 1.0e5);
    }
}

crate::scene! {
    /// Fig. 1.4b: Fuller-Tabor force-separation curves for two roughness values.
    pub struct Fig1_4b {
        id: "fig1.4b",
        chapter: "1",
        params: Fig1_4bParams,
        title: "Fuller-Tabor force-separation curves of rough surfaces",
        caption: "Total force vs separation of a Greenwood-Williamson rough surface with JKR \
            asperities (1.9)-(1.15), approach and retraction (arrows), for two roughness values: \
            the adhesive force and the energy loss fall as sigma_rms grows.",
        results: &[
            ("adhesive_force_1_norm", "most negative force on unloading, P/(N P_o), roughness 1"),
            ("adhesive_force_2_norm", "most negative force on unloading, P/(N P_o), roughness 2"),
            ("energy_loss_1_norm", "energy lost over the cycle / (N P_o h_o), roughness 1"),
            ("energy_loss_2_norm", "energy lost over the cycle / (N P_o h_o), roughness 2"),
            ("contact_fraction_1_norm", "fraction of asperities touched at d_min (1.10), roughness 1"),
            ("contact_fraction_2_norm", "fraction of asperities touched at d_min (1.10), roughness 2"),
        ],
    }
}

impl Scene for Fig1_4b {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below(
            "min_separation_ho",
            p.min_separation_ho,
            "start_separation_ho",
            p.start_separation_ho,
        )
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(40);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let mut panel = Panel::new(
            Axis::linear("Separation d/h_o", ""),
            Axis::linear("Total force P/(N P_o)", ""),
        );
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let sigmas = [p.sigma1_over_ho, p.sigma2_over_ho];
        for (k, &theta) in sigmas.iter().enumerate() {
            job.check()?;
            job.progress(k as f64 / 2.0, &format!("roughness {}/2", k + 1));
            let ft = FullerTabor::new(theta)?;
            // One separation axis and one d_min for both surfaces, as in the dissertation's
            // figure: scaling each curve by its own σ_rms would load both to the same
            // contact fraction and make their normalised losses equal.
            let cycle = ft.cycle(p.start_separation_ho, p.min_separation_ho, p.points)?;
            let name = format!("σ_rms/h_o = {theta}");
            let loading = cycle.loading.clone();
            let unloading = cycle.unloading.clone();
            // Arrows show the direction of travel: approach to the left, retraction to the right.
            // Both branches are stored in the order of travel.
            for branch in [&loading, &unloading] {
                let m = branch.len() / 5;
                panel.arrow(branch[m], branch[m + 1], Some(k));
            }
            panel.add(Series::new(&name, Style::Stable, loading).with_color(k));
            panel.add(Series::new(&name, Style::Stable, unloading).with_color(k));
            panel.mark(
                Marker::new(
                    "adhesive force",
                    MarkerShape::PullOff,
                    cycle.adhesive_force_separation,
                    cycle.adhesive_force,
                )
                .with_color(k),
            );
            fig.result(format!("adhesive_force_{}_norm", k + 1), cycle.adhesive_force);
            fig.result(format!("energy_loss_{}_norm", k + 1), cycle.energy_loss);
            fig.result(
                format!("contact_fraction_{}_norm", k + 1),
                ft.contact_fraction(p.min_separation_ho)?,
            );
            if job.wants_preview() {
                let mut preview = fig.clone();
                preview.panels = vec![panel.clone()];
                job.preview(&preview);
            }
        }
        fig.panels.push(panel);
        fig.note("each loop: approach with L = 0 (upper branch), retraction with L of Eq. (1.15) (lower branch); arrows give the direction; squares mark the adhesive force");
        job.progress(1.0, "done");
        Ok(fig)
    }
}
