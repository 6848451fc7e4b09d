//! Chapter 5 scenes: fibril stiffness (Fig. 5.2b), the single-spring model (Figs. 5.3-5.5),
//! and the spring arrays on random rough surfaces (Figs. 5.7-5.11).

use super::sweep::{Sweep, Swept};
use super::{Registered, Scene, SceneDyn};
use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Legend, Marker, MarkerShape, Panel, Series, Style, number};
use crate::job::Job;
use crate::models::fibril::{K_CR_BAR, SingleSpring, SpringState, tilted_fibril_stiffness};
use crate::numerics::curve::{linspace, logspace};
use crate::params::{Range, fmt_sig};

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[
    &Registered::<Fig5_2b>::NEW,
    &Registered::<Fig5_3>::NEW,
    &Registered::<Fig5_4>::NEW,
    &Registered::<Fig5_5>::NEW,
    &Registered::<Fig5_7>::NEW,
    &Swept::<Fig5_8>::NEW,
    &Swept::<Fig5_9>::NEW,
    &Registered::<Fig5_10>::NEW,
    &Registered::<Fig5_11>::NEW,
    &Registered::<Fig5_10Accuracy>::NEW,
];

crate::scene_params! {
    /// Parameters of scene fig5.2b (section 5.4.1).
    pub struct Fig5_2bParams {
        /// Radius-to-length ratio R_f/l_f of the fibril (below 0.8: the half-stiffness angle exists).
        radius_over_length: f64 = 0.1, unit = "", range = Range::open(0.0, 0.8);
        /// Points on the curve.
        points: usize = 181, unit = "", range = Range::between(3.0, 1.0e5);
    }
}

/// Fig. 5.2b: stiffness of a tilted fibril against the tilt angle, Eq. (5.11).
pub struct Fig5_2b;

impl Scene for Fig5_2b {
    type Params = Fig5_2bParams;
    const ID: &'static str = "fig5.2b";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Stiffness of a tilted fibril";
    const CAPTION: &'static str = "Stiffness k_f of a fibril tilted at angle theta to its backing, Eq. (5.11), \
        in units of the axial stiffness pi R_f^2 E/l_f, for R_f/l_f = 1/10: pure bending at theta = 0, \
        pure compression (stiffest) at theta = pi/2.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "bending_stiffness_norm",
            "k_f(0) / (pi R_f^2 E / l_f) = 3 R_f^2 / (4 l_f^2)",
        ),
        ("compression_stiffness_norm", "k_f(pi/2) / (pi R_f^2 E / l_f) = 1"),
        (
            "half_stiffness_angle_deg",
            "angle where k_f is half the axial stiffness",
        ),
    ];

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(31);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let r = p.radius_over_length;
        let axial = std::f64::consts::PI * r * r;
        let norm = |theta: f64| Ok::<f64, Error>(tilted_fibril_stiffness(1.0, r, 1.0, theta)? / axial);
        let mut pts = Vec::with_capacity(p.points);
        for t in linspace(0.0, std::f64::consts::FRAC_PI_2, p.points) {
            pts.push((t.to_degrees(), norm(t)?));
        }
        job.check()?;
        let mut panel = Panel::new(
            Axis::linear("Tilt angle θ", "deg"),
            Axis::linear("Stiffness k_f l_f/(π R_f² E)", ""),
        )
        .titled("(b)", format!("R_f/l_f = {r}"));
        panel.add(Series::new("k_f, Eq. (5.11)", Style::Stable, pts).with_color(0));
        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(panel);
        fig.result("bending_stiffness_norm", norm(0.0)?);
        fig.result("compression_stiffness_norm", norm(std::f64::consts::FRAC_PI_2)?);
        let half = crate::numerics::roots::brent(
            |t| norm(t).unwrap_or(f64::NAN) - 0.5,
            0.0,
            std::f64::consts::FRAC_PI_2,
            1e-13,
        )?;
        fig.result("half_stiffness_angle_deg", half.to_degrees());
        job.progress(1.0, "done");
        Ok(fig)
    }
}

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

/// Fig. 5.3: energy (5.16) and its first two derivatives (5.18), (5.20) against the gap.
pub struct Fig5_3;

impl Scene for Fig5_3 {
    type Params = Fig5_3Params;
    const ID: &'static str = "fig5.3";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Single-spring energy landscape";
    const CAPTION: &'static str = "Total energy (5.16), its first derivative (5.18) and second derivative (5.20) \
        against the gap d/sigma for several displacements u/sigma: (a)-(c) k = 2 k_cr, one minimizer, \
        always stable; (d)-(f) k = 0.5 k_cr, two minimizers between pull-in and pull-off.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "soft_pull_in_u_norm",
            "pull-in displacement u/sigma of the soft case",
        ),
        (
            "soft_pull_off_u_norm",
            "pull-off displacement u/sigma of the soft case",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.gap_min >= p.gap_max {
            return Err(Error::invalid("gap_min", p.gap_min, "must be below gap_max"));
        }
        if p.displacements.is_empty() {
            return Err(Error::invalid("displacements", "[]", "must not be empty"));
        }
        Ok(())
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
                for (c, &u) in p.displacements.iter().enumerate() {
                    let pts = gaps
                        .iter()
                        .map(|&d| {
                            let y = match which {
                                0 => s.energy(u, d),
                                1 => s.residual(u, d),
                                _ => s.curvature(d),
                            };
                            (d, y)
                        })
                        .collect();
                    panel.add(Series::new(format!("u/σ = {u}"), Style::Stable, pts).with_color(c));
                    if which < 2 {
                        // Mark the equilibria at this displacement (roots of (5.18)).
                        let roots =
                            crate::numerics::curve::all_roots(|d| s.residual(u, d), &gaps, 1e-12, 1e-12)?;
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

/// Fig. 5.4: gap and force over a loading-unloading cycle for several stiffnesses.
pub struct Fig5_4;

impl Scene for Fig5_4 {
    type Params = Fig5_4Params;
    const ID: &'static str = "fig5.4";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Single-spring loading-unloading cycle";
    const CAPTION: &'static str = "(a) Equilibrium gap d*/sigma and (b) force P sigma/(c w A_e) against the \
        displacement u/sigma, (5.18)-(5.20), for k = 0.5, 1, 2 k_cr: solid stable, dashed unstable; \
        the soft spring jumps in at pull-in (triangle) and out at pull-off (square). Force positive in compression.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        ("pull_in_u_norm", "pull-in displacement of the first stiffness"),
        ("pull_off_u_norm", "pull-off displacement of the first stiffness"),
        ("pull_in_force_norm", "force just after pull-in, first stiffness"),
        (
            "pull_off_force_norm",
            "force just before pull-off, first stiffness",
        ),
        (
            "hysteresis_norm",
            "energy lost over the cycle / (c w A_e), loop area, first stiffness",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.u_min >= p.u_max {
            return Err(Error::invalid("u_min", p.u_min, "must be below u_max"));
        }
        if p.stiffness_ratios.is_empty() {
            return Err(Error::invalid("stiffness_ratios", "[]", "must not be empty"));
        }
        Ok(())
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

/// Fig. 5.5: pull-in and pull-off forces and the hysteresis against the stiffness.
pub struct Fig5_5;

impl Scene for Fig5_5 {
    type Params = Fig5_5Params;
    const ID: &'static str = "fig5.5";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Single-spring pull-in, pull-off and hysteresis vs stiffness";
    const CAPTION: &'static str = "(a) Pull-in force (just after the jump in) and pull-off force (just before \
        the jump out), force positive in compression, and (b) the hysteretic energy loss, against the \
        stiffness k; no instability and no loss for k >= k_cr = 0.3.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "max_pull_in_force_magnitude_norm",
            "largest |pull-in force| over the stiffness range",
        ),
        (
            "max_pull_in_force_stiffness_norm",
            "stiffness k where |pull-in force| is largest",
        ),
        ("critical_stiffness_norm", "k_cr, maximum of -f''(d) in (5.20)"),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.k_min >= p.k_max {
            return Err(Error::invalid("k_min", p.k_min, "must be below k_max"));
        }
        Ok(())
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

/// Heights z̄ = z/σ of sample `seed`: a Gaussian-autocorrelation surface (appendix C) of
/// N x M points with σ_rms = 1 on a box of length 1 along ê₁ (so L_c is L̄_c = L_c/(100 µm)),
/// to be scaled by σ̄_rms. A single row (M = 1) is the first row of an N x 2 surface, shifted
/// to zero mean and scaled to unit RMS (its autocorrelation along ê₁ is the same Gaussian).
fn unit_surface(nx: usize, ny: usize, lc_bar: f64, seed: u64) -> Result<Vec<f64>> {
    let spectrum = crate::surface::Spectrum::Gaussian {
        rms: 1.0,
        correlation_length: lc_bar,
    };
    let gy = ny.max(2);
    let map = crate::surface::generate(&spectrum, nx, gy, 1.0, gy as f64 / nx as f64, seed)?;
    let mut z = map.z;
    if gy != ny {
        z.truncate(nx * ny);
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        z.iter_mut().for_each(|v| *v -= mean);
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64).sqrt();
        if rms > 0.0 {
            z.iter_mut().for_each(|v| *v /= rms);
        }
    }
    Ok(z)
}

/// The displacement window of a cycle over a surface of roughness σ̄_rms: from `c_max` σ̄_rms
/// beyond the pull-off displacement (every spring detached) down to `c_min` σ̄_rms below the
/// pull-in displacement (every spring within that many σ_rms of the mean plane touched). Both
/// ends keep a margin of at least half the bistable width u_off − u_in (and 1 in ū), so that a
/// nearly flat surface (σ̄_rms far below the displacement step) is still fully loaded and
/// unloaded, and the last step before each fold does not end a hair past it.
fn cycle_window(k_e: f64, sigma_bar: f64, c_min: f64, c_max: f64) -> Result<(f64, f64)> {
    let s = SingleSpring::new(k_e)?;
    let (u_in, u_off) = s.bistable_range().unwrap_or((1.0, 1.0));
    let margin = (0.5 * (u_off - u_in)).max(1.0);
    Ok((
        u_off + (c_max * sigma_bar).max(margin),
        u_in - (c_min * sigma_bar).max(margin),
    ))
}

/// k̄_e of k̂_e = k_e/k_cr = 2⁻ⁿ (section 5.5.2).
fn k_bar_of_n(n: f64) -> f64 {
    K_CR_BAR * 2f64.powf(-n)
}

/// Mean and sample standard deviation.
fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    (mean, var.sqrt())
}

/// Unit-RMS surfaces of samples `seed .. seed + samples` (rayon over samples).
fn unit_surfaces(
    nx: usize,
    ny: usize,
    lc_bar: f64,
    samples: usize,
    seed: u64,
    job: &Job,
) -> Result<Vec<Vec<f64>>> {
    use rayon::prelude::*;
    let done = job.ticker(samples, "surfaces", 0.0, 1.0);
    (0..samples)
        .into_par_iter()
        .map(|k| {
            job.check()?;
            let surface = unit_surface(nx, ny, lc_bar, seed + k as u64);
            done.tick();
            surface
        })
        .collect()
}

/// Uncoupled cycles over unit surfaces scaled by σ̄_rms (binned path, tables shared by the
/// samples, rayon over samples).
fn uncoupled_samples(
    unit: &[Vec<f64>],
    sigma_bar: f64,
    k_e: f64,
    steps: usize,
    oversample: usize,
    window: (f64, f64),
    job: &Job,
) -> Result<Vec<crate::models::spring_array::ArrayCycle>> {
    use rayon::prelude::*;
    let (lo, hi) = unit
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let tables = crate::models::spring_array::BinnedBranches::new(
        k_e,
        window.0,
        window.1,
        steps,
        oversample,
        (sigma_bar * lo, sigma_bar * hi),
    )?;
    let done = job.ticker(unit.len(), "samples", 0.0, 1.0);
    unit.par_iter()
        .map(|u| {
            job.check()?;
            let z: Vec<f64> = u.iter().map(|v| v * sigma_bar).collect();
            let cycle = tables.cycle(&z);
            done.tick();
            cycle
        })
        .collect()
}

crate::param_choice! {
    /// Path for uncoupled arrays.
    pub enum UncoupledPath { Binned = "binned", Exact = "exact" }
}

crate::scene_params! {
    /// Parameters of scene fig5.7 (section 5.5.2).
    pub struct Fig5_7Params {
        /// Stiffness exponent n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponent: f64 = 7.0, unit = "", range = Range::open(0.0, 30.0);
        /// Normalized roughnesses σ̄_rms = σ_rms/σ of the curves.
        roughness: Vec<f64> = vec![10.0, 25.0, 50.0, 100.0], unit = "", range = Range::positive();
        /// Normalized correlation length L̄_c = L_c/(100 µm).
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// Springs along each side (N = M).
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Surface samples averaged.
        samples: usize = 15, unit = "", range = Range::between(1.0, 1000.0);
        /// Seed of the first sample (sample k uses seed + k).
        seed: u64 = 1, unit = "", range = Range::any();
        /// Displacement steps per phase.
        steps: usize = 1000, unit = "", range = Range::between(10.0, 1.0e6);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
        /// Height bins per displacement step of the binned path.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
        /// Uncoupled path: binned (convolution) or exact (spring by spring).
        path: UncoupledPath = UncoupledPath::Binned, unit = "", range = Range::any();
    }
}

/// Panel (b) of Fig. 5.7: the cycles of `full` framed on their tensile part. Forces from 15 %
/// below the most negative one to as far above zero; displacements over the points in that
/// band whose force is not yet (or no longer) negligible (|P| above 2 % of the most negative
/// force), so the range ends where the slowest decay reaches zero. One arrow per branch, at the
/// middle of its part inside the frame, gives the direction of travel.
fn adhesive_window(full: &Panel) -> Panel {
    let mut zoom = full.clone().titled("(b)", "tensile part, where the loops lie");
    zoom.arrows.clear();
    zoom.legend = Legend::Hidden;
    let y_min = full
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(0.0f64, f64::min);
    if y_min >= 0.0 {
        return zoom;
    }
    let (y_lo, y_hi) = (1.15 * y_min, -y_min);
    let inside = |p: &(f64, f64)| p.1 >= y_lo && p.1 <= y_hi && p.1.abs() >= 0.02 * -y_min;
    let (x_lo, x_hi) = full
        .series
        .iter()
        .flat_map(|s| s.points.iter().filter(|p| inside(p)).map(|p| p.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if x_hi <= x_lo {
        return zoom;
    }
    let dx = 0.05 * (x_hi - x_lo);
    zoom.x = zoom.x.clone().with_range(x_lo - dx, x_hi + dx);
    zoom.y = zoom.y.clone().with_range(y_lo, y_hi);
    for s in &full.series {
        let idx: Vec<usize> = (0..s.points.len().saturating_sub(1))
            .filter(|&i| inside(&s.points[i]) && s.points[i].0 >= x_lo && s.points[i].0 <= x_hi)
            .collect();
        if let Some(&k) = idx.get(idx.len() / 2) {
            zoom.arrow(s.points[k], s.points[k + 1], s.color);
        }
    }
    zoom
}

/// Fig. 5.7: force-displacement cycles of uncoupled spring arrays on rough surfaces.
pub struct Fig5_7;

impl Scene for Fig5_7 {
    type Params = Fig5_7Params;
    const ID: &'static str = "fig5.7";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Spring-array force-displacement cycles on rough surfaces";
    const CAPTION: &'static str = "Total force P/(MN |P_m|) (positive in compression) against the displacement \
        u/sigma over a loading-unloading cycle of 256 x 256 uncoupled springs, k_e = 2^-7 k_cr, on Gaussian \
        rough surfaces of several sigma_rms/sigma, averaged over the samples: the sum of shifted single-spring \
        branches (5.35). (a) The whole cycles (the roughest surface sets the range); (b) the tensile part, \
        where the smoother surfaces' loops lie. Arrows: loading to the left, unloading to the right.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "efficiency_first_norm",
            "adhesion efficiency (5.36) of the first roughness, sample mean",
        ),
        (
            "efficiency_last_norm",
            "adhesion efficiency (5.36) of the last roughness, sample mean",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.roughness.is_empty() {
            return Err(Error::invalid("roughness", "[]", "must not be empty"));
        }
        Ok(())
    }

    fn quick(p: &mut Self::Params) {
        p.springs = p.springs.min(32);
        p.samples = p.samples.min(2);
        p.steps = p.steps.min(100);
        p.roughness.truncate(2);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let k_e = k_bar_of_n(p.stiffness_exponent);
        let n = p.springs;
        let norm = (n * n) as f64 * crate::models::spring_array::single_spring_adhesive_force().abs();
        let mut panel = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear("Force P/(MN |P_m|)", ""),
        )
        .titled(
            "(a)",
            format!("whole cycles, k_e = 2^-{} k_cr", p.stiffness_exponent),
        );
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut effs = Vec::new();
        // Progress: the surfaces (about 4 % of a run at the defaults), then each roughness's
        // cycles sample by sample.
        let unit = unit_surfaces(
            n,
            n,
            p.correlation_length,
            p.samples,
            p.seed,
            &job.part(0.0, 0.04),
        )?;
        let stages = job.parts(&vec![1.0; p.roughness.len()], 0.04, 0.99);
        for ((c, &sigma), stage) in p.roughness.iter().enumerate().zip(&stages) {
            job.check()?;
            stage.progress(0.0, &format!("σ_rms/σ = {sigma}"));
            let window = cycle_window(k_e, sigma, p.depth_sigmas, p.end_sigmas)?;
            let cycles = match p.path {
                UncoupledPath::Binned => {
                    uncoupled_samples(&unit, sigma, k_e, p.steps, p.oversample, window, stage)?
                }
                UncoupledPath::Exact => {
                    use rayon::prelude::*;
                    let done = stage.ticker(p.samples, "samples", 0.0, 1.0);
                    (0..p.samples)
                        .into_par_iter()
                        .map(|k| {
                            job.check()?;
                            let z: Vec<f64> = unit[k].iter().map(|v| v * sigma).collect();
                            let a = crate::models::spring_array::SpringArray::new(n, n, k_e, 0.0, z)?;
                            let cycle =
                                crate::models::spring_array::uncoupled_cycle(&a, window.0, window.1, p.steps);
                            done.tick();
                            cycle
                        })
                        .collect::<Result<Vec<_>>>()?
                }
            };
            let m = cycles.len() as f64;
            let avg = |sel: fn(
                &crate::models::spring_array::ArrayCycle,
            ) -> &Vec<crate::models::spring_array::ArrayStep>| {
                let first = sel(&cycles[0]);
                (0..first.len())
                    .map(|i| {
                        let f = cycles.iter().map(|cy| sel(cy)[i].force).sum::<f64>() / m;
                        (first[i].u, f / norm)
                    })
                    .collect::<Vec<_>>()
            };
            let name = format!("σ_rms/σ = {sigma}");
            let load = avg(|c| &c.loading);
            let unload = avg(|c| &c.unloading);
            let k = load.len() / 3;
            panel.arrow(load[k], load[k + 1], Some(c));
            panel.arrow(unload[k], unload[k + 1], Some(c));
            panel.add(Series::new(&name, Style::Stable, load).with_color(c));
            panel.add(Series::new(&name, Style::Stable, unload).with_color(c));
            let e: Vec<f64> = cycles
                .iter()
                .map(|cy| crate::models::spring_array::adhesion_efficiency(cy, n * n))
                .collect();
            effs.push(mean_std(&e).0);
        }
        let zoom = adhesive_window(&panel);
        fig.panels.push(panel);
        fig.panels.push(zoom);
        fig.result("efficiency_first_norm", effs[0]);
        fig.result("efficiency_last_norm", *effs.last().unwrap_or(&f64::NAN));
        fig.note("arrows give the direction of travel: loading to the left, unloading to the right");
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.8 (section 5.5.2).
    pub struct Fig5_8Params {
        /// Stiffness exponents n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponents: Vec<f64> = vec![6.0, 7.0, 8.0, 9.0, 10.0, 11.0], unit = "", range = Range::open(0.0, 30.0);
        /// Smallest normalized roughness σ̄_rms.
        roughness_min: f64 = 10.0, unit = "", range = Range::positive();
        /// Largest normalized roughness σ̄_rms.
        roughness_max: f64 = 1500.0, unit = "", range = Range::positive();
        /// Roughness values (log-spaced).
        roughness_points: usize = 10, unit = "", range = Range::between(2.0, 1000.0);
        /// Normalized correlation length L̄_c.
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// Springs along each side (N = M).
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Surface samples averaged.
        samples: usize = 15, unit = "", range = Range::between(1.0, 1000.0);
        /// Seed of the first sample.
        seed: u64 = 1, unit = "", range = Range::any();
        /// Displacement steps per phase.
        steps: usize = 1000, unit = "", range = Range::between(10.0, 1.0e6);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
        /// Height bins per displacement step.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
    }
}

/// Axis title of the adhesion efficiency, with its definition (5.36).
const EFFICIENCY_LABEL: &str = "Adhesion efficiency α_F = P_max/(MN P_m)";

/// RMS deviation of the simulated efficiency from (5.37) up to which the fit counts as matching
/// the data: 5 % of the efficiency's range [0, 1], three times the spread of the sample means.
const FIT_MATCH_RMS: f64 = 0.05;

/// What Fig. 5.8 finds about (5.37), against the text (section 5.5.2), which finds that it
/// matches for n = 6-8 and deviates for n = 9-11: the stiffness exponents whose RMS deviation
/// exceeds [`FIT_MATCH_RMS`], or that it fits every one, with the deviations' range.
fn fit_verdict(exponents: &[f64], deviations: &[f64]) -> String {
    let (lo, hi) = deviations
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &d| {
            (a.min(d), b.max(d))
        });
    let off: Vec<String> = exponents
        .iter()
        .zip(deviations)
        .filter(|(_, d)| **d > FIT_MATCH_RMS)
        .map(|(n, _)| fmt_sig(*n))
        .collect();
    let range = format!("RMS deviation {}-{}", number(lo, 2), number(hi, 2));
    if off.is_empty() {
        format!("(5.37) fits every n here ({range}); the text finds deviations for n = 9-11")
    } else {
        format!(
            "(5.37) deviates here for n = {} ({range}); the text finds deviations for n = 9-11",
            off.join(", ")
        )
    }
}

/// Fig. 5.8: adhesion efficiency against roughness for several stiffnesses, with (5.37).
pub struct Fig5_8;

impl Scene for Fig5_8 {
    type Params = Fig5_8Params;
    const ID: &'static str = "fig5.8";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Adhesion efficiency vs roughness and stiffness";
    const CAPTION: &'static str = "Adhesion efficiency alpha_F = P_max/(MN P_m) (5.36) against sigma_rms/sigma for \
        k_e/k_cr = 2^-n, n = 6..11, 256 x 256 uncoupled springs, mean and standard deviation over 15 surfaces \
        (symbols, error bars) and the empirical fit exp(-4 sigma_rms/(sigma 2^n)) (5.37) (lines).";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "fit_rms_deviation_first_norm",
            "RMS over the roughness range of the simulated mean efficiency minus (5.37), first stiffness exponent",
        ),
        ("fit_rms_deviation_last_norm", "as above, last stiffness exponent"),
        (
            "fit_rms_deviation_max_norm",
            "largest of these over the stiffness exponents",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.roughness_min >= p.roughness_max {
            return Err(Error::invalid(
                "roughness_min",
                p.roughness_min,
                "must be below roughness_max",
            ));
        }
        if p.stiffness_exponents.is_empty() {
            return Err(Error::invalid("stiffness_exponents", "[]", "must not be empty"));
        }
        Ok(())
    }

    fn quick(p: &mut Self::Params) {
        p.springs = p.springs.min(32);
        p.samples = p.samples.min(2);
        p.steps = p.steps.min(100);
        p.roughness_points = p.roughness_points.min(3);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        super::sweep::run::<Self>(p, job)
    }
}

/// Fig. 5.8 is a sweep over (stiffness exponent, roughness): point `c·R + i` is exponent `c`
/// and roughness `i` (R roughness values), averaged over the samples of the unit surfaces
/// `seed .. seed + samples`, the same surfaces at every point (common random numbers, as in
/// Sec. 5.5.2). A point's result is the adhesion efficiency of each sample.
impl Sweep for Fig5_8 {
    type Context = Vec<Vec<f64>>;

    fn point_len(p: &Self::Params, _id: usize) -> usize {
        p.samples
    }

    fn context(p: &Self::Params, job: &Job) -> Result<Self::Context> {
        unit_surfaces(p.springs, p.springs, p.correlation_length, p.samples, p.seed, job)
    }

    fn points(p: &Self::Params) -> Vec<String> {
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        p.stiffness_exponents
            .iter()
            .flat_map(|ne| {
                sigmas
                    .iter()
                    .map(move |s| format!("n = {ne}, σ_rms/σ = {}", fmt_sig(*s)))
            })
            .collect()
    }

    fn run_point(p: &Self::Params, unit: &Self::Context, id: usize, job: &Job) -> Result<Vec<f64>> {
        let n = p.springs;
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        let (ne, sigma) = (
            p.stiffness_exponents[id / sigmas.len()],
            sigmas[id % sigmas.len()],
        );
        let k_e = k_bar_of_n(ne);
        let window = cycle_window(k_e, sigma, p.depth_sigmas, p.end_sigmas)?;
        let cycles = uncoupled_samples(unit, sigma, k_e, p.steps, p.oversample, window, job)?;
        Ok(cycles
            .iter()
            .map(|cy| crate::models::spring_array::adhesion_efficiency(cy, n * n))
            .collect())
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        let mut panel = Panel::new(
            Axis::log("Roughness σ_rms/σ", ""),
            Axis::linear(EFFICIENCY_LABEL, ""),
        );
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut deviations = Vec::with_capacity(p.stiffness_exponents.len());
        for (c, &ne) in p.stiffness_exponents.iter().enumerate() {
            let mut pts = Vec::new();
            let mut bars = Vec::new();
            let mut dev2 = 0.0;
            for (i, &sigma) in sigmas.iter().enumerate() {
                let (m, sd) = mean_std(&points[c * sigmas.len() + i]);
                pts.push((sigma, m));
                bars.push((sigma, m - sd));
                bars.push((sigma, m + sd));
                dev2 += (m - crate::models::spring_array::efficiency_fit(sigma, ne)).powi(2);
            }
            let name = format!("n = {ne}");
            panel.add(Series::new(&name, Style::Scatter, pts).with_color(c));
            panel.add(
                Series::new(&name, Style::ErrorBar, bars)
                    .with_color(c)
                    .without_legend(),
            );
            let fit: Vec<(f64, f64)> = logspace(p.roughness_min, p.roughness_max, 100)
                .into_iter()
                .map(|s| (s, crate::models::spring_array::efficiency_fit(s, ne)))
                .collect();
            panel.add(
                Series::new(&name, Style::Stable, fit)
                    .with_color(c)
                    .without_legend(),
            );
            deviations.push((dev2 / sigmas.len() as f64).sqrt());
        }
        fig.result("fit_rms_deviation_first_norm", deviations[0]);
        fig.result("fit_rms_deviation_last_norm", deviations[deviations.len() - 1]);
        fig.result(
            "fit_rms_deviation_max_norm",
            deviations.iter().copied().fold(0.0, f64::max),
        );
        panel.annotate(format!(
            "symbols: simulation, mean ± 1 s.d. over {} surfaces; lines: (5.37)",
            p.samples
        ));
        panel.annotate(fit_verdict(&p.stiffness_exponents, &deviations));
        fig.panels.push(panel);
        fig.note(
            "symbols: simulation mean over the samples, bars: one standard deviation; lines: Eq. (5.37)",
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.9 (section 5.5.2).
    pub struct Fig5_9Params {
        /// Stiffness exponent n.
        stiffness_exponent: f64 = 6.0, unit = "", range = Range::open(0.0, 30.0);
        /// Normalized roughnesses σ̄_rms of the two panels.
        roughness: Vec<f64> = vec![10.0, 50.0], unit = "", range = Range::positive();
        /// Normalized correlation lengths L̄_c.
        correlation_lengths: Vec<f64> = vec![0.01, 0.02, 0.04, 0.06, 0.08, 0.1], unit = "", range = Range::open(0.0, 1.0);
        /// Springs along each side.
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Surface samples.
        samples: usize = 15, unit = "", range = Range::between(1.0, 1000.0);
        /// Seed of the first sample.
        seed: u64 = 1, unit = "", range = Range::any();
        /// Displacement steps per phase.
        steps: usize = 1000, unit = "", range = Range::between(10.0, 1.0e6);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
        /// Height bins per displacement step.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
    }
}

/// The top of an efficiency axis that starts at zero: the first of 0.1, 0.12, 0.15, 0.2, 0.25,
/// 0.3, 0.4, 0.5, 0.6, 0.8, 1 (times a power of ten) at least 30 % above `top`, and at most 1
/// (the efficiency's bound).
fn efficiency_axis_top(top: f64) -> f64 {
    const STEPS: [f64; 11] = [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0];
    let want = 1.3 * top;
    if !(want > 0.0 && want.is_finite()) {
        return 1.0;
    }
    let decade = 10f64.powf(want.log10().floor());
    let nice = STEPS
        .iter()
        .map(|s| s * decade)
        .find(|v| *v >= want * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade);
    nice.min(1.0)
}

/// Fig. 5.9: adhesion efficiency against correlation length.
pub struct Fig5_9;

impl Scene for Fig5_9 {
    type Params = Fig5_9Params;
    const ID: &'static str = "fig5.9";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Adhesion efficiency vs correlation length";
    const CAPTION: &'static str = "Adhesion efficiency (5.36) against L_c/(100 um) for sigma_rms/sigma = 10 (a) and 50 \
        (b), k_e = 2^-6 k_cr, 256 x 256 uncoupled springs; mean and standard deviation over 15 surfaces.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[(
        "max_relative_spread_norm",
        "largest (max - min)/mean of the mean efficiency over the correlation lengths, over the panels",
    )];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.roughness.is_empty() || p.correlation_lengths.is_empty() {
            return Err(Error::invalid(
                "roughness",
                "[]",
                "roughness and correlation_lengths must not be empty",
            ));
        }
        Ok(())
    }

    fn quick(p: &mut Self::Params) {
        p.springs = p.springs.min(32);
        p.samples = p.samples.min(2);
        p.steps = p.steps.min(100);
        p.correlation_lengths.truncate(2);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        super::sweep::run::<Self>(p, job)
    }
}

/// Fig. 5.9 is a sweep over (roughness, correlation length): point `c·L + l` is roughness `c`
/// and correlation length `l` (L lengths), on the unit surfaces of seeds `seed .. seed + samples`
/// at that length. A point's result is the adhesion efficiency of each sample.
impl Sweep for Fig5_9 {
    type Context = ();

    fn point_len(p: &Self::Params, _id: usize) -> usize {
        p.samples
    }

    fn context(_p: &Self::Params, _job: &Job) -> Result<()> {
        Ok(())
    }

    fn points(p: &Self::Params) -> Vec<String> {
        p.roughness
            .iter()
            .flat_map(|s| {
                p.correlation_lengths
                    .iter()
                    .map(move |lc| format!("σ_rms/σ = {s}, L_c/(100 µm) = {lc}"))
            })
            .collect()
    }

    fn run_point(p: &Self::Params, _context: &(), id: usize, job: &Job) -> Result<Vec<f64>> {
        let n = p.springs;
        let k_e = k_bar_of_n(p.stiffness_exponent);
        let nl = p.correlation_lengths.len();
        let (sigma, lc) = (p.roughness[id / nl], p.correlation_lengths[id % nl]);
        let window = cycle_window(k_e, sigma, p.depth_sigmas, p.end_sigmas)?;
        let unit = unit_surfaces(n, n, lc, p.samples, p.seed, &job.part(0.0, 0.5))?;
        let cycles = uncoupled_samples(
            &unit,
            sigma,
            k_e,
            p.steps,
            p.oversample,
            window,
            &job.part(0.5, 1.0),
        )?;
        Ok(cycles
            .iter()
            .map(|cy| crate::models::spring_array::adhesion_efficiency(cy, n * n))
            .collect())
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut spread = 0.0f64;
        let labels = ["(a)", "(b)", "(c)", "(d)"];
        let nl = p.correlation_lengths.len();
        for (c, &sigma) in p.roughness.iter().enumerate() {
            let mut pts = Vec::new();
            let mut bars = Vec::new();
            for (l, &lc) in p.correlation_lengths.iter().enumerate() {
                let (m, sd) = mean_std(&points[c * nl + l]);
                pts.push((lc, m));
                bars.push((lc, m - sd));
                bars.push((lc, m + sd));
            }
            let ms: Vec<f64> = pts.iter().map(|q| q.1).collect();
            let sds: Vec<f64> = (0..nl).map(|l| mean_std(&points[c * nl + l]).1).collect();
            let (lo, hi) = ms.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
            let mean = mean_std(&ms).0;
            spread = spread.max((hi - lo) / mean);
            let mut panel = Panel::new(
                Axis::linear("Correlation length L_c/(100 µm)", ""),
                Axis::linear(EFFICIENCY_LABEL, ""),
            )
            .titled(labels[c.min(3)], format!("σ_rms/σ = {sigma}"));
            // From zero, to a round value above the largest error bar: the figure is about
            // whether the efficiency depends on L_c, which a range fitted to the means'
            // scatter would exaggerate into a trend.
            let top = bars.iter().map(|b| b.1).fold(0.0, f64::max);
            panel.y = panel.y.clone().with_range(0.0, efficiency_axis_top(top));
            let (first, last) = (p.correlation_lengths[0], p.correlation_lengths[nl - 1]);
            panel.add(
                Series::new(
                    "mean over all L_c",
                    Style::Reference,
                    vec![(first, mean), (last, mean)],
                )
                .with_color(7),
            );
            panel.add(
                Series::new(
                    format!("simulation: mean of {} surfaces", p.samples),
                    Style::Scatter,
                    pts,
                )
                .with_color(c),
            );
            panel.add(Series::new("± 1 s.d. over the surfaces", Style::ErrorBar, bars).with_color(c));
            // The text (section 5.5.2): no appreciable dependence on L_c, the uncertainty
            // growing with L_c. Compare the spread of the means with their standard errors.
            let sem_max = sds.iter().fold(0.0f64, |a, &v| a.max(v)) / (p.samples.max(1) as f64).sqrt();
            panel.annotate(format!(
                "s.d. over the surfaces {} at L_c = {} to {} at {}",
                number(sds[0], 2),
                fmt_sig(first),
                number(sds[nl - 1], 2),
                fmt_sig(last)
            ));
            panel.annotate(format!(
                "means {}-{} ({} % of their mean), standard errors ≤ {}: {}",
                number(lo, 3),
                number(hi, 3),
                number(100.0 * (hi - lo) / mean, 2),
                number(sem_max, 2),
                if hi - lo <= 2.0 * sem_max {
                    "no dependence on L_c beyond the scatter, as the text finds"
                } else {
                    "they vary by more than the scatter, a dependence on L_c the text does not report"
                }
            ));
            fig.panels.push(panel);
        }
        fig.result("max_relative_spread_norm", spread);
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scenes fig5.10 and fig5.11 (section 5.6).
    pub struct CouplingParams {
        /// Stiffness exponent n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponent: f64 = 10.0, unit = "", range = Range::open(0.0, 30.0);
        /// Coupling stiffnesses k_μ in units of k_e.
        couplings: Vec<f64> = vec![0.0, 2.0, 10.0], unit = "", range = Range::non_negative();
        /// Normalized roughness σ̄_rms.
        roughness: f64 = 100.0, unit = "", range = Range::positive();
        /// Normalized correlation length L̄_c.
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// Springs N along ê₁.
        springs_x: usize = 256, unit = "", range = Range::between(1.0, 4096.0);
        /// Springs M along ê₂.
        springs_y: usize = 1, unit = "", range = Range::between(1.0, 4096.0);
        /// Seed of the surface.
        seed: u64 = 1, unit = "", range = Range::any();
        /// Displacement steps per phase.
        steps: usize = 1000, unit = "", range = Range::between(10.0, 1.0e6);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
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
    let mut z = unit_surface(p.springs_x, p.springs_y, p.correlation_length, p.seed)?;
    z.iter_mut().for_each(|v| *v *= p.roughness);
    let window = cycle_window(k_e, p.roughness, p.depth_sigmas, p.end_sigmas)?;
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
            let c =
                crate::models::spring_array::coupled_cycle(&a, window.0, window.1, p.steps, &opts, |f| {
                    job.check()?;
                    // Reported under the lock, so the means arrive in order.
                    let Ok(mut all) = fractions.lock() else {
                        // Another coupling panicked holding the lock; its error will surface.
                        return Ok(());
                    };
                    all[slot] = f;
                    let mean = all.iter().sum::<f64>() / n_couplings as f64;
                    let steps = (mean * (2 * p.steps * n_couplings) as f64).round();
                    // The figure is built after the last step: `done` brings the 1.
                    job.progress(
                        0.99 * mean,
                        &format!(
                            "coupled cycles: {steps:.0}/{} steps of {n_couplings} couplings",
                            2 * p.steps * n_couplings
                        ),
                    );
                    Ok(())
                })?;
            Ok((mult, c))
        })
        .collect()
}

fn coupling_validate(p: &CouplingParams) -> Result<()> {
    if p.couplings.is_empty() {
        return Err(Error::invalid("couplings", "[]", "must not be empty"));
    }
    Ok(())
}

/// Peak memory of the coupling study: about 512 bytes per spring and coupling (heights, state,
/// sparse tangent and the iterative solver's vectors; measured 450-490 bytes at 256² and
/// 1024² springs with three couplings), all couplings at once, plus 64 MiB.
fn coupling_memory(p: &CouplingParams) -> crate::scenes::MemoryEstimate {
    let springs = p.springs_x as f64 * p.springs_y as f64;
    crate::scenes::MemoryEstimate {
        bytes: 64.0 * 1024.0 * 1024.0 + 512.0 * springs * p.couplings.len().max(1) as f64,
        parameter: "springs_x x springs_y",
        value: format!("{} x {}", p.springs_x, p.springs_y),
    }
}

fn coupling_quick(p: &mut CouplingParams) {
    p.springs_x = p.springs_x.min(32);
    p.springs_y = p.springs_y.min(2);
    p.steps = p.steps.min(100);
}

/// Fig. 5.10: force-displacement cycles for several coupling stiffnesses.
pub struct Fig5_10;

impl Scene for Fig5_10 {
    type Params = CouplingParams;
    const ID: &'static str = "fig5.10";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Coupled springs: force-displacement cycles";
    const CAPTION: &'static str = "Total force P/(MN |P_m|) (positive in compression) against u/sigma for coupling \
        k_mu = 0, 2 k_e, 10 k_e; 256 x 1 springs, k_e = 2^-10 k_cr, sigma_rms/sigma = 100, L_c = 0.01; \
        equilibria (5.31)-(5.34) by the stable sparse Newton solver, every accepted state with a \
        positive-definite tangent.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "efficiency_uncoupled_norm",
            "adhesion efficiency (5.36), first coupling",
        ),
        (
            "efficiency_strongest_norm",
            "adhesion efficiency (5.36), last coupling",
        ),
        (
            "hysteresis_uncoupled_norm",
            "energy lost over the cycle in units of MN |P_m| sigma, first coupling",
        ),
        ("hysteresis_strongest_norm", "as above, last coupling"),
        (
            "jumps_uncoupled_count",
            "displacement steps with jumps, first coupling",
        ),
        (
            "all_states_stable_count",
            "1 if every accepted state had a positive-definite tangent, else 0",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        coupling_validate(p)
    }

    fn quick(p: &mut Self::Params) {
        coupling_quick(p);
    }

    fn memory_estimate(p: &Self::Params) -> Option<crate::scenes::MemoryEstimate> {
        Some(coupling_memory(p))
    }

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

/// Fig. 5.11: contact ratio over the cycle for several coupling stiffnesses.
pub struct Fig5_11;

impl Scene for Fig5_11 {
    type Params = CouplingParams;
    const ID: &'static str = "fig5.11";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Coupled springs: contact ratio over the cycle";
    const CAPTION: &'static str = "Contact ratio N_c/(MN), the fraction of springs in contact (gap below \
        sigma), against u/sigma on loading (a) and unloading (b) for coupling k_mu = 0, 2 k_e, 10 k_e; the \
        cycles of Fig. 5.10. Arrows give the direction of travel: u decreases on loading, increases on \
        unloading.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        (
            "max_contact_ratio_uncoupled_norm",
            "largest contact ratio over the cycle, first coupling",
        ),
        (
            "max_contact_ratio_strongest_norm",
            "largest contact ratio over the cycle, last coupling",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        coupling_validate(p)
    }

    fn quick(p: &mut Self::Params) {
        coupling_quick(p);
    }

    fn memory_estimate(p: &Self::Params) -> Option<crate::scenes::MemoryEstimate> {
        Some(coupling_memory(p))
    }

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
        /// Normalized roughness σ̄_rms.
        roughness: f64 = 100.0, unit = "", range = Range::positive();
        /// Normalized correlation length L̄_c.
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// Springs N along ê₁ (M = 1).
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Seed of the surface.
        seed: u64 = 1, unit = "", range = Range::any();
        /// Displacement steps per phase of the runs compared.
        steps: Vec<f64> = vec![50.0, 100.0, 200.0, 400.0, 800.0, 1600.0], unit = "", range = Range::between(10.0, 1.0e6);
        /// Newton gradient tolerances of the runs compared.
        tolerances: Vec<f64> = vec![1e-3, 1e-6, 1e-10], unit = "", range = Range::positive();
        /// Steps per phase of the reference run (tolerance 1e-12).
        reference_steps: usize = 6400, unit = "", range = Range::between(10.0, 1.0e7);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
        /// Horizontal axis: measured run time (true) or the deterministic count of Newton iterations (false, for reproducible snapshots).
        wall_clock: bool = true, unit = "", range = Range::any();
    }
}

/// Fig. 5.10-accuracy: error of the adhesive force against run time.
pub struct Fig5_10Accuracy;

impl Scene for Fig5_10Accuracy {
    type Params = Fig5_10AccuracyParams;
    const ID: &'static str = "fig5.10-accuracy";
    const CHAPTER: &'static str = "5";
    const TITLE: &'static str = "Coupled springs: accuracy against run time";
    const CAPTION: &'static str = "Relative error of the adhesive force P_max (5.36) and of the hysteresis of the \
        coupled cycle of Fig. 5.10 (k_mu = 2 k_e) against run time, over the displacement step (points along a \
        line) and the Newton tolerance (one line each), relative to a fine reference run.";
    const RESULTS: &'static [(&'static str, &'static str)] = &[
        ("reference_time_s", "run time of the reference"),
        (
            "reference_adhesive_force_norm",
            "P_max/(MN |P_m|) of the reference",
        ),
        (
            "coarsest_error_norm",
            "relative P_max error of the coarsest step at the tightest tolerance",
        ),
        (
            "finest_error_norm",
            "relative P_max error of the finest step at the tightest tolerance",
        ),
    ];

    fn validate(p: &Self::Params) -> Result<()> {
        if p.steps.is_empty() || p.tolerances.is_empty() {
            return Err(Error::invalid(
                "steps",
                "[]",
                "steps and tolerances must not be empty",
            ));
        }
        Ok(())
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
        let mut z = unit_surface(p.springs, 1, p.correlation_length, p.seed)?;
        z.iter_mut().for_each(|v| *v *= p.roughness);
        let a = SpringArray::new(p.springs, 1, k_e, p.coupling * k_e, z)?;
        let window = cycle_window(k_e, p.roughness, p.depth_sigmas, p.end_sigmas)?;
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
                let what = format!("tolerance {tol:e}, {steps} steps");
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
            let name = format!("tolerance {tol:e}");
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
