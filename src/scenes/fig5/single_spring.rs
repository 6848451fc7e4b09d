//! The single-spring model of section 5.3 (5.18): its energy landscape (Fig. 5.3), a
//! loading-unloading cycle (Fig. 5.4), and pull-in, pull-off and hysteresis against the
//! stiffness (Fig. 5.5).

use crate::error::Result;
use crate::figure::{Axis, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::fibril::{K_CR_BAR, SingleSpring, SpringState};
use crate::numerics::curve::{linspace, logspace};
use crate::params::{Range, require_below, require_non_empty};
use crate::scenes::{Scene, SceneHeader};

/// The equilibrium curve ū(d̄) of (5.18) over a gap range, split into stable and unstable runs.
fn equilibrium_runs(s: &SingleSpring, d_lo: f64, d_hi: f64, n: usize) -> Vec<(bool, Vec<SpringState>)> {
    let mut runs: Vec<(bool, Vec<SpringState>)> = Vec::new();
    // Insert the folds exactly so that stable and unstable runs meet there.
    let mut gaps = linspace(d_lo, d_hi, n);
    if let Some((a, b)) = s.fold_gaps() {
        gaps.extend([a, b].into_iter().filter(|g| (d_lo..=d_hi).contains(g)));
        gaps.sort_by(f64::total_cmp);
    }
    for d in gaps {
        let st = s.state_at_gap(d);
        let stable = s.curvature(d) >= -1e-12;
        match runs.last_mut() {
            Some((kind, pts)) if *kind == stable || s.curvature(d).abs() < 1e-12 => pts.push(st),
            _ => {
                // Start the new run at the previous run's last point so the curve is unbroken.
                let mut pts = Vec::new();
                if let Some((_, prev)) = runs.last() {
                    pts.extend(prev.last().copied());
                }
                pts.push(st);
                runs.push((stable, pts));
            }
        }
    }
    runs
}

crate::scene_params! {
    /// Parameters of scene fig5.3 (section 5.4.3). The dissertation does not list the
    /// displacements of its curves; these straddle the pull-in (1.791) and pull-off (2.043)
    /// displacements of k̄ = 0.5 k̄_cr.
    pub struct Fig5_3Params {
        /// Stiffness of the stable case, in units of k̄_cr = 0.3.
        stiff_ratio: f64 = 2.0, unit = "", range = Range::positive();
        /// Stiffness of the unstable case, in units of k̄_cr.
        soft_ratio: f64 = 0.5, unit = "", range = Range::positive();
        /// Displacements ū = u/σ of the curves.
        displacements: Vec<f64> = vec![1.6, 1.791, 1.9, 2.043, 2.2], unit = "", range = Range::positive();
        /// Smallest gap drawn, d̄ = d/σ.
        gap_min: f64 = 0.7, unit = "", range = Range::positive();
        /// Largest gap drawn.
        gap_max: f64 = 3.0, unit = "", range = Range::positive();
        /// Points per curve.
        points: usize = 300, unit = "", range = Range::between(10.0, 1.0e5);
    }
}

crate::scene! {
    /// Fig. 5.3: energy (5.16) and its first two derivatives (5.18), (5.20) against the gap.
    pub struct Fig5_3 {
        id: "fig5.3",
        chapter: "5",
        params: Fig5_3Params,
        title: "Single-spring energy landscape",
        caption: "Total energy (5.16), its first derivative (5.18) and second derivative (5.20) \
            against the gap d/sigma for several displacements u/sigma: (a)-(c) k = 2 k_cr, one minimizer, \
            always stable; (d)-(f) k = 0.5 k_cr, two minimizers between pull-in and pull-off.",
        results: &[
            ("soft_pull_in_u_norm", "pull-in displacement u/sigma of the soft case"),
            ("soft_pull_off_u_norm", "pull-off displacement u/sigma of the soft case"),
        ],
    }
}

impl Scene for Fig5_3 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below("gap_min", p.gap_min, "gap_max", p.gap_max)?;
        require_non_empty("displacements", &p.displacements)
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(40);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let gaps = linspace(p.gap_min, p.gap_max, p.points);
        let cases = [
            (p.stiff_ratio, ["(a)", "(b)", "(c)"]),
            (p.soft_ratio, ["(d)", "(e)", "(f)"]),
        ];
        for (ratio, labels) in cases {
            job.check()?;
            let s = SingleSpring::new(ratio * K_CR_BAR)?;
            let names = [
                ("Energy Π̄ = Π_tot/(cwA_e)", 0),
                ("∂Π̄/∂d̄, d̄ = d/σ", 1),
                ("∂²Π̄/∂d̄²", 2),
            ];
            for ((yname, which), label) in names.into_iter().zip(labels) {
                let mut panel = Panel::new(Axis::linear("Gap d/σ", ""), Axis::linear(yname, ""))
                    .titled(label, format!("k = {ratio} k_cr"));
                if which == 2 {
                    // (5.20) does not depend on u: the curves of every displacement are one,
                    // drawn once under one legend entry.
                    let pts = gaps.iter().map(|&d| (d, s.curvature(d))).collect();
                    panel.add(Series::new("every u/σ (coincide)", Style::Stable, pts).with_color(7));
                }
                for (c, &u) in p.displacements.iter().enumerate().filter(|_| which < 2) {
                    let pts = gaps
                        .iter()
                        .map(|&d| {
                            let y = if which == 0 {
                                s.energy(u, d)
                            } else {
                                s.residual(u, d)
                            };
                            (d, y)
                        })
                        .collect();
                    panel.add(Series::new(format!("u/σ = {u}"), Style::Stable, pts).with_color(c));
                    // Mark the equilibria at this displacement (roots of (5.18)).
                    let roots = crate::numerics::curve::all_roots(|d| s.residual(u, d), &gaps, 1e-12, 1e-12)?;
                    for d in roots {
                        let y = if which == 0 { s.energy(u, d) } else { 0.0 };
                        let shape = if s.curvature(d) > 0.0 {
                            MarkerShape::StableState
                        } else {
                            MarkerShape::UnstableState
                        };
                        panel.mark(Marker::new(format!("u/σ = {u}"), shape, d, y).with_color(c));
                    }
                }
                if which == 2 {
                    panel.add(
                        Series::new("zero", Style::Reference, vec![(p.gap_min, 0.0), (p.gap_max, 0.0)])
                            .with_color(7)
                            .without_legend(),
                    );
                }
                fig.panels.push(panel);
            }
            if let Some((u_in, u_off)) = s.bistable_range()
                && (ratio - p.soft_ratio).abs() < f64::EPSILON
            {
                fig.result("soft_pull_in_u_norm", u_in);
                fig.result("soft_pull_off_u_norm", u_off);
            }
        }
        fig.note("filled circles: stable equilibria (minimizers); open circles: unstable ones (maximizers)");
        fig.note(format!(
            "(c), (f): the second derivative (5.20) does not depend on the displacement, so the curves of all {} \
             displacements coincide; drawn once",
            p.displacements.len()
        ));
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.4 (section 5.4.3).
    pub struct Fig5_4Params {
        /// Stiffnesses in units of k̄_cr = 0.3.
        stiffness_ratios: Vec<f64> = vec![0.5, 1.0, 2.0], unit = "", range = Range::positive();
        /// Largest displacement ū = u/σ (start and end of the cycle).
        u_max: f64 = 3.0, unit = "", range = Range::positive();
        /// Smallest displacement ū reached on loading.
        u_min: f64 = 0.5, unit = "", range = Range::any();
        /// Displacement steps per phase.
        points: usize = 300, unit = "", range = Range::between(10.0, 1.0e6);
    }
}

crate::scene! {
    /// Fig. 5.4: gap and force over a loading-unloading cycle for several stiffnesses.
    pub struct Fig5_4 {
        id: "fig5.4",
        chapter: "5",
        params: Fig5_4Params,
        title: "Single-spring loading-unloading cycle",
        caption: "(a) Equilibrium gap d*/sigma and (b) force P sigma/(c w A_e) against the \
            displacement u/sigma, (5.18)-(5.20), for k = 0.5, 1, 2 k_cr: solid stable, dashed unstable; \
            the soft spring jumps in at pull-in (triangle) and out at pull-off (square). Force positive in compression.",
        results: &[
            ("pull_in_u_norm", "pull-in displacement of the first stiffness"),
            ("pull_off_u_norm", "pull-off displacement of the first stiffness"),
            ("pull_in_force_norm", "force just after pull-in, first stiffness"),
            ("pull_off_force_norm", "force just before pull-off, first stiffness"),
            ("hysteresis_norm", "energy lost over the cycle / (c w A_e), loop area, first stiffness"),
        ],
    }
}

impl Scene for Fig5_4 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below("u_min", p.u_min, "u_max", p.u_max)?;
        require_non_empty("stiffness_ratios", &p.stiffness_ratios)
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(40);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let mut gap = Panel::new(Axis::linear("Displacement u/σ", ""), Axis::linear("Gap d*/σ", ""))
            .titled("(a)", "equilibrium gap");
        let mut force = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear("Force Pσ/(c w A_e)", ""),
        )
        .titled("(b)", "equilibrium force");
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        for (c, &ratio) in p.stiffness_ratios.iter().enumerate() {
            job.check()?;
            let s = SingleSpring::new(ratio * K_CR_BAR)?;
            let name = format!("k = {ratio} k_cr");
            // All equilibria with ū in the window: gaps from the contact state at u_min to the
            // free state at u_max.
            // (A window that ends inside the bistable range, or that misses it, has only one
            // branch at an end: take the one that exists there.)
            use crate::models::fibril::SpringBranch::{Contact, Free};
            let d_lo = s.gap(p.u_min, Contact).or_else(|_| s.gap(p.u_min, Free))?;
            let d_hi = s.gap(p.u_max, Free).or_else(|_| s.gap(p.u_max, Contact))?;
            let (d_lo, d_hi) = (d_lo.min(d_hi), d_lo.max(d_hi));
            for (stable, run) in equilibrium_runs(&s, d_lo, d_hi, 4 * p.points) {
                let style = if stable { Style::Stable } else { Style::Unstable };
                gap.add(Series::new(&name, style, run.iter().map(|q| (q.u, q.d)).collect()).with_color(c));
                force.add(
                    Series::new(&name, style, run.iter().map(|q| (q.u, q.force)).collect()).with_color(c),
                );
            }
            let cycle = s.cycle(p.u_max, p.u_min, p.points)?;
            for j in &cycle.jumps {
                let shape = if j.after.d < j.before.d {
                    MarkerShape::PullIn
                } else {
                    MarkerShape::PullOff
                };
                for (panel, y0, y1) in [
                    (&mut gap, j.before.d, j.after.d),
                    (&mut force, j.before.force, j.after.force),
                ] {
                    panel.add(
                        Series::new("jump", Style::Jump, vec![(j.before.u, y0), (j.after.u, y1)])
                            .with_color(c)
                            .without_legend(),
                    );
                    panel.mark(Marker::new(&name, shape, j.before.u, y0).with_color(c));
                }
            }
            if c == 0 {
                if let Some(j) = s.pull_in()? {
                    fig.result("pull_in_u_norm", j.before.u);
                    fig.result("pull_in_force_norm", j.after.force);
                }
                if let Some(j) = s.pull_off()? {
                    fig.result("pull_off_u_norm", j.before.u);
                    fig.result("pull_off_force_norm", j.before.force);
                }
                fig.result("hysteresis_norm", cycle.loop_area());
            }
        }
        fig.panels.push(gap);
        fig.panels.push(force);
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.5 (section 5.4.3).
    pub struct Fig5_5Params {
        /// Smallest stiffness k̄.
        k_min: f64 = 0.01, unit = "", range = Range::positive();
        /// Largest stiffness k̄ (values at or above k̄_cr = 0.3 have no instability).
        k_max: f64 = 0.4, unit = "", range = Range::positive();
        /// Stiffness values.
        points: usize = 200, unit = "", range = Range::between(3.0, 1.0e5);
    }
}

crate::scene! {
    /// Fig. 5.5: pull-in and pull-off forces and the hysteresis against the stiffness.
    pub struct Fig5_5 {
        id: "fig5.5",
        chapter: "5",
        params: Fig5_5Params,
        title: "Single-spring pull-in, pull-off and hysteresis vs stiffness",
        caption: "(a) Pull-in force (just after the jump in) and pull-off force (just before \
            the jump out), force positive in compression, and (b) the hysteretic energy loss, against the \
            stiffness k; no instability and no loss for k >= k_cr = 0.3.",
        results: &[
            ("max_pull_in_force_magnitude_norm", "largest |pull-in force| over the stiffness range"),
            ("max_pull_in_force_stiffness_norm", "stiffness k where |pull-in force| is largest"),
            ("critical_stiffness_norm", "k_cr, maximum of -f''(d) in (5.20)"),
        ],
    }
}

impl Scene for Fig5_5 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below("k_min", p.k_min, "k_max", p.k_max)
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(30);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let mut pin = Vec::new();
        let mut poff = Vec::new();
        let mut hys = Vec::new();
        for k in logspace(p.k_min, p.k_max, p.points) {
            job.check()?;
            let s = SingleSpring::new(k)?;
            if let (Some(a), Some(b)) = (s.pull_in()?, s.pull_off()?) {
                pin.push((k, a.after.force));
                poff.push((k, b.before.force));
            }
            hys.push((k, s.hysteresis()?));
        }
        let mut forces = Panel::new(
            Axis::linear("Stiffness k̄_e = k_eσ²/(cwA_e)", ""),
            Axis::linear("Force Pσ/(c w A_e)", ""),
        )
        .titled("(a)", "pull-in and pull-off forces");
        forces.add(Series::new("pull-in", Style::Stable, pin.clone()).with_color(0));
        forces.add(Series::new("pull-off", Style::Stable, poff).with_color(1));
        let mut loss = Panel::new(
            Axis::linear("Stiffness k̄_e = k_eσ²/(cwA_e)", ""),
            Axis::linear("Hysteresis ΔE_s/(c w A_e)", ""),
        )
        .titled("(b)", "hysteretic energy loss");
        loss.add(Series::new("ΔE_s", Style::Stable, hys).with_color(0));
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        fig.panels.push(forces);
        fig.panels.push(loss);
        if let Some(&(k, f)) = pin.iter().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs())) {
            fig.result("max_pull_in_force_magnitude_norm", f.abs());
            fig.result("max_pull_in_force_stiffness_norm", k);
        }
        let d_cr = crate::numerics::curve::golden_min(crate::models::fibril::lj_curvature, 0.5, 2.0, 1e-10);
        fig.result(
            "critical_stiffness_norm",
            -crate::models::fibril::lj_curvature(d_cr),
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}

// ---------------------------------------------------------------------------------------------
// Spring arrays on random rough surfaces (section 5.5).
