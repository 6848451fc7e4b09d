//! Scene fig4.3 (section 4.3): the critical separation at which a smooth tip jumps into
//! (pull-in) or out of (pull-off) contact, against the Tabor parameter μ_T.
//!
//! (a) The two roots of the estimate (4.23) (parabolic tip, Boussinesq point load: larger root
//! pull-in, smaller root pull-off, joined at the double root μ_T*), against the onsets the
//! surface model computes: for each μ_T a displacement-controlled cycle of the smooth tip, and
//! the gap at the apex, g(0)/ζ0, of the last state before the pull-in jump and before the
//! pull-off jump. μ_T is varied through the modulus E* at the fixed radius and interaction of
//! Fig. 4.5 (so ζ0 and w do not change), E* from (1.8). The surface model uses the consistent
//! traction (ERRATA on (4.19)); (4.23) is drawn with the printed traction (the dissertation's
//! curves) and, dotted, with the consistent one. (4.23) is an estimate (ERRATA): the difference
//! is charted, not tuned away.
//!
//! (b) The relative error (4.24) between the deformed gap profile of the last state before the
//! pull-in at one μ_T (5, as the text) and the parabola through its apex.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Legend, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::axisymmetric::cycle::{CycleOptions, TipCycle, TipState, run_cycle};
use crate::models::axisymmetric::tip::{Tip, TipParams};
use crate::models::lennard_jones::{InstabilityCriterion, LennardJones, TractionLaw};
use crate::params::Range;
use crate::scenes::groups::{ContactCriterion, DepthPath, ElasticTip, Interaction, SurfaceModel};
use crate::scenes::{Scene, SceneHeader};

/// The cycles start at h = (START_PER_TABOR μ_T + START_OFFSET) ζ0: beyond the JKR pull-off
/// separation of a displacement-controlled tip, (3/4)π^(2/3) μ_T ζ0 = 1.61 μ_T ζ0, and beyond
/// the pull-in (which (4.23) and the surface model put below μ_T ζ0 + 2 ζ0).
const START_PER_TABOR: f64 = 2.0;
/// See [`START_PER_TABOR`] [ζ0].
const START_OFFSET: f64 = 5.0;

/// Colour of the pull-in data (red in the dissertation's caption): palette vermillion.
const RED: usize = 1;
/// Colour of the pull-off data (blue in the caption).
const BLUE: usize = 0;

crate::scene_params! {
    /// Parameters of scene fig4.3 (section 4.3). The tip and interaction are those of Fig. 4.5
    /// (R = 5 µm, C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J); each μ_T sets E* through (1.8).
    pub struct Fig4_3Params {
        /// Tabor parameters μ_T of the surface-model cycles (E* from (1.8) at fixed R, w, ζ0; up to 8, where a cycle takes 10 s: rings grow as μ_T², its cost as μ_T⁶).
        tabor_parameters: Vec<f64> = vec![0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0], unit = "", range = Range::between(0.05, 8.0);
        /// μ_T of panel (b), the profile just before pull-in (the text: 5); also run in (a).
        error_tabor_parameter: f64 = 5.0, unit = "", range = Range::between(0.3, 8.0);
        /// Largest μ_T of the (4.23) curves.
        curve_tabor_max: f64 = 10.0, unit = "", range = Range::between(0.3, 100.0);
        from ElasticTip: radius: f64;
        /// The interaction (C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J).
        group lj: Interaction;
        from DepthPath: h_min_over_zeta0: f64 = -2.0,
            help = "Deepest depth of the cycles in units of ζ0 (shallow: a little past the pull-in).";
        from DepthPath: step_over_zeta0: f64;
        /// Jumps are located to this depth tolerance, in units of ζ0 (the gap before a jump is read there).
        refine_over_zeta0: f64 = 1.0e-4, unit = "", range = Range::between(1.0e-6, 0.1);
        from SurfaceModel: ring_width: f64,
            help = "Widest ring in units of b = ζ0²E*/w (0.25: the contact edge does not hop from ring to ring).";
        /// Least number of rings across √(2Rζ0), the width of the interaction zone of a stiff tip.
        rings_per_zone: usize = 20, unit = "", range = Range::between(2.0, 200.0);
        from SurfaceModel: quadrature_points: usize,
            help = "Gauss points per interval of the interaction energy.";
        /// The contact threshold.
        group contact: ContactCriterion;
        /// Cycles that bisect μ_T between the largest value without a jump and the smallest with one.
        onset_bisections: usize = 4, unit = "", range = Range::between(0.0, 20.0);
        /// Points of each (4.23) curve.
        curve_points: usize = 200, unit = "", range = Range::between(2.0, 10000.0);
    }
}

/// The interaction of a scene (4.1)-(4.7b).
///
/// # Errors
/// [`Error::InvalidParameter`] naming the interaction parameter.
fn interaction(p: &Fig4_3Params) -> Result<LennardJones> {
    p.lj.lennard_jones()
}

/// The smooth tip of Tabor parameter `mu` (E* from (1.8)) on its grid.
///
/// The rings are `ring_width` b wide, or narrower where b (which grows with E*) is coarse
/// against √(2Rζ0), the radial width over which a stiff sphere feels the attraction. The fine
/// zone covers the contact at the deepest depth ([`TipParams::fine_radius_for_depth`]), but at
/// most twice the radius where the undeformed gap reaches the interaction's reach: the 10 b that
/// it adds beyond a JKR contact edge would be microns for a stiff tip, where the attraction acts
/// only within that radius. (Not `tip_for` of the parent module, which has no such cap.)
///
/// # Errors
/// [`Error::InvalidParameter`] naming the parameter (a grid of too many rings names
/// `ring_width`).
fn tip_at(lj: &LennardJones, p: &Fig4_3Params, mu: f64) -> Result<Tip> {
    let modulus = lj.modulus_for_tabor(p.radius, mu)?;
    let zeta0 = lj.zeta0();
    let b = zeta0 * zeta0 * modulus / lj.work_of_adhesion();
    let zone = (2.0 * p.radius * zeta0).sqrt();
    let by_zone = zone / (p.rings_per_zone as f64 * b);
    let i = lj.params();
    let mut params = TipParams {
        radius: p.radius,
        modulus,
        c6: i.c6,
        c12: i.c12,
        sigma: i.sigma,
        hamaker: i.hamaker,
        amplitude: 0.0,
        ring_width: p.ring_width.min(by_zone),
        quadrature_points: p.quadrature_points,
        ..TipParams::default()
    };
    let reach_radius = (2.0 * p.radius * params.reach * zeta0).sqrt();
    params.fine_radius = params
        .fine_radius_for_depth(p.h_min_over_zeta0 * zeta0)?
        .min(2.0 * reach_radius);
    // A grid of too many rings is named after the parameter that set its width.
    Tip::new(&params).map_err(|e| match e {
        Error::InvalidParameter { name, reason, .. } if name == "ring_width" && by_zone < p.ring_width => {
            Error::invalid(
                "rings_per_zone",
                p.rings_per_zone,
                reason.replace("a wider ring", "fewer rings"),
            )
        }
        e => e,
    })
}

/// A shallow cycle of the tip of Tabor parameter `mu`: from (2μ_T + 5) ζ0 apart to
/// `h_min_over_zeta0` and back. `progress(fraction)` may stop it with an error.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the parameter; minimiser failures; errors of `progress`.
fn cycle_at(
    lj: &LennardJones,
    p: &Fig4_3Params,
    mu: f64,
    progress: impl FnMut(f64) -> Result<()>,
) -> Result<(Tip, TipCycle)> {
    let tip = tip_at(lj, p, mu)?;
    let cycle = cycle_of(&tip, lj, p, mu, progress)?;
    Ok((tip, cycle))
}

/// The cycle of [`cycle_at`] on a tip already built by [`tip_at`].
fn cycle_of(
    tip: &Tip,
    lj: &LennardJones,
    p: &Fig4_3Params,
    mu: f64,
    progress: impl FnMut(f64) -> Result<()>,
) -> Result<TipCycle> {
    let zeta0 = lj.zeta0();
    let opts = CycleOptions {
        h_start: (START_PER_TABOR * mu + START_OFFSET) * zeta0,
        h_min: p.h_min_over_zeta0 * zeta0,
        step: p.step_over_zeta0 * zeta0,
        refine_to: p.refine_over_zeta0 * zeta0,
        contact_gap: p.contact.contact_gap,
        keep_profiles: false,
        unload_to: None,
    };
    run_cycle(tip, &opts, progress)
}

/// The gap at the apex g(0) of a state, in units of ζ0: the critical separation z_c of
/// section 4.3 when the state is the last before a jump.
///
/// The displacement is uniform inside the first ring mid-radius (the model's interpolation),
/// so g(0) = δ − u₀, with δ the approach of the state's depth ((4.10) with f(0) = 0).
///
/// # Panics
/// If the state kept no displacement (a cycle keeps those of the states on both sides of every
/// jump).
fn central_gap(tip: &Tip, state: &TipState) -> f64 {
    assert!(
        !state.displacement.is_empty(),
        "a jump state keeps its displacement"
    );
    tip.approach(state.depth) - state.displacement[0]
}

/// The last state before the pull-in: the first loading jump that enlarges the contact.
fn pull_in(cycle: &TipCycle) -> Option<&TipState> {
    cycle
        .jumps
        .iter()
        .find(|j| j.loading && j.is_pull_in())
        .map(|j| &j.before)
}

/// The last state before the pull-off: the last unloading jump that ends out of contact (or, if
/// none does, the last unloading jump).
fn pull_off(cycle: &TipCycle) -> Option<&TipState> {
    let unloading = || cycle.jumps.iter().filter(|j| !j.loading);
    unloading()
        .rfind(|j| j.after.contact.radius() == 0.0)
        .or_else(|| unloading().next_back())
        .map(|j| &j.before)
}

/// What one cycle says about the instabilities.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Onsets {
    /// Tabor parameter μ_T.
    tabor: f64,
    /// z_c/ζ0 before the pull-in, if there is one.
    pull_in: Option<f64>,
    /// z_c/ζ0 before the pull-off, if there is one.
    pull_off: Option<f64>,
    /// Jumps on the cycle.
    jumps: usize,
    /// Rings of the tip.
    rings: usize,
    /// Whether every state was certified stable.
    all_stable: bool,
}

/// The onsets of a cycle of the tip `tip` at Tabor parameter `tabor`.
fn onsets(tabor: f64, tip: &Tip, cycle: &TipCycle) -> Onsets {
    Onsets {
        tabor,
        pull_in: pull_in(cycle).map(|s| central_gap(tip, s)),
        pull_off: pull_off(cycle).map(|s| central_gap(tip, s)),
        jumps: cycle.jumps.len(),
        rings: tip.len(),
        all_stable: cycle.stats.all_stable,
    }
}

/// The deformed gap of a state against the parabola through its apex, Eq. (4.24).
#[derive(Debug, Clone, PartialEq)]
pub struct ParabolaError {
    /// Ring mid-radii r [m].
    pub radius: Vec<f64>,
    /// err(r) of (4.24) with z0 the deformed gap at the apex [-].
    pub error: Vec<f64>,
    /// err(r) with z0 read as the separation of the undeformed apex (the other reading of
    /// (4.24): the parabola the tip had before it deformed) [-].
    pub error_undeformed: Vec<f64>,
    /// The deformed gap at the apex z0 = g(0) [ζ0].
    pub central_gap: f64,
    /// Displacement of the apex towards the substrate u(0) [ζ0].
    pub apex_displacement: f64,
    /// √(2R z0) [m]: the radius where the parabola has doubled the apex gap.
    pub zone: f64,
}

impl ParabolaError {
    /// The largest err(r) of (4.24) and the radius [m] where it is.
    pub fn max(&self) -> (f64, f64) {
        self.error.iter().zip(&self.radius).fold(
            (0.0, 0.0),
            |best, (&e, &r)| if e > best.0 { (e, r) } else { best },
        )
    }
}

/// The relative error of the parabola approximation of the deformed gap of `state`.
///
/// Implements Eq. (4.24):
/// ```text
/// err(r) = | z0 + r²/(2R) − z(r) | / z(r)
/// ```
/// with z(r) the deformed gap at the ring mid-radii ([`Tip::gaps`]) and z0 = g(0)
/// ([`central_gap`]); also with z0 the undeformed apex separation δ.
///
/// # Panics
/// If the state kept no displacement.
fn parabola_error(tip: &Tip, state: &TipState) -> ParabolaError {
    let radius_of_curvature = tip.params().radius;
    let length = tip.scales().length;
    let delta = tip.approach(state.depth);
    let z0 = central_gap(tip, state);
    let gaps = tip.gaps(delta, &state.displacement);
    let radius = tip.radii();
    let parabola = |apex: f64, r: f64| apex + r * r / (2.0 * radius_of_curvature * length);
    let error = radius
        .iter()
        .zip(&gaps)
        .map(|(&r, &z)| (parabola(z0, r) - z).abs() / z)
        .collect();
    let error_undeformed = radius
        .iter()
        .zip(&gaps)
        .map(|(&r, &z)| (parabola(delta, r) - z).abs() / z)
        .collect();
    ParabolaError {
        radius,
        error,
        error_undeformed,
        central_gap: z0,
        apex_displacement: delta - z0,
        zone: (2.0 * radius_of_curvature * z0 * length).sqrt(),
    }
}

/// The parabola error (4.24) of the last state before the pull-in at μ_T =
/// `error_tabor_parameter` (one cycle), or `None` when that cycle has no pull-in.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the parameter; minimiser failures.
pub fn parabola_error_before_pull_in(p: &Fig4_3Params) -> Result<Option<ParabolaError>> {
    let lj = interaction(p)?;
    let (tip, cycle) = cycle_at(&lj, p, p.error_tabor_parameter, |_| Ok(()))?;
    Ok(pull_in(&cycle).map(|s| parabola_error(&tip, s)))
}

/// Points (x, y) of a curve.
type Curve = Vec<(f64, f64)>;

/// The two branches of (4.23), pull-in (larger root) and pull-off (smaller root), as (μ_T, z̄_c)
/// from the double root (μ_T*, z̄*) to `mu_max`, `n` points each, denser near μ_T* where the
/// roots separate like √(μ_T − μ_T*). Empty when `mu_max` ≤ μ_T*.
///
/// # Errors
/// Root-finding failures of [`InstabilityCriterion::critical_separations`].
fn criterion_branches(c: &InstabilityCriterion, mu_max: f64, n: usize) -> Result<(Curve, Curve)> {
    let (mu_star, z_star) = (c.critical_tabor(), c.double_root());
    let (mut pull_in, mut pull_off) = (Vec::new(), Vec::new());
    if mu_max <= mu_star {
        return Ok((pull_in, pull_off));
    }
    pull_in.push((mu_star, z_star));
    pull_off.push((mu_star, z_star));
    for k in 1..n.max(2) {
        let t = k as f64 / (n.max(2) - 1) as f64;
        let mu = mu_star + (mu_max - mu_star) * t * t;
        if let Some(roots) = c.critical_separations(mu)? {
            pull_in.push((mu, roots.pull_in));
            pull_off.push((mu, roots.pull_off));
        }
    }
    Ok((pull_in, pull_off))
}

/// Least-squares exponent p of y ∝ x^p through the points (ln x, ln y); `None` for fewer than
/// two distinct x.
fn power_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x.ln(), b + y.ln()));
    let (mx, my) = (sx / n, sy / n);
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        let dx = x.ln() - mx;
        (a + dx * (y.ln() - my), b + dx * dx)
    });
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Whether two Tabor parameters are the same value (as typed).
fn same_tabor(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs()
}

crate::scene! {
    /// Fig. 4.3: critical separation against the Tabor parameter; the parabola error before
    /// pull-in.
    pub struct Fig4_3 {
        id: "fig4.3",
        chapter: "4",
        params: Fig4_3Params,
        title: "Critical separation of the instabilities against the Tabor parameter",
        caption: "(a) Dimensionless critical separation z_c/zeta0 against the Tabor parameter mu_T: \
            the roots of (4.23) (parabolic tip, Boussinesq point load; pull-in red, pull-off blue; solid with the \
            printed traction (4.19), dotted with the consistent one) and, as circles, the gap at the apex of the last \
            state before the pull-in and pull-off jumps of displacement-controlled cycles of the smooth tip of Fig. 4.5 \
            (R = 5 um, C6 = 3, C12 = 1, sigma = 1 nm, A_H = 2 × 10⁻²¹ J) with the axisymmetric surface model, mu_T set \
            through E* by (1.8). (b) Relative error (4.24) between the deformed gap profile just before the pull-in \
            at mu_T = 5 and the parabola through its apex.",
        results: &[
            ("critical_tabor_norm", "mu_T* of (4.23), printed traction, unrounded coefficients"),
            ("double_root_norm", "z_c/zeta0 at mu_T* (the double root of (4.23))"),
            ("critical_tabor_consistent_norm", "mu_T* of (4.23) with the consistent traction (ERRATA (4.19))"),
            ("double_root_consistent_norm", "z_c/zeta0 at mu_T* with the consistent traction"),
            ("onset_tabor_low_norm", "surface model: largest mu_T found without a jump below the first with one (0: none)"),
            ("onset_tabor_high_norm", "surface model: smallest mu_T found with a jump (0: none)"),
            ("cycles_count", "surface-model cycles of panel (a) (bisection not counted)"),
            ("cycles_with_jumps_count", "of them, cycles with at least one jump"),
            ("pull_in_ratio_min_norm", "smallest z_c(model)/z_c(4.23) at pull-in, printed traction"),
            ("pull_in_ratio_max_norm", "largest z_c(model)/z_c(4.23) at pull-in, printed traction"),
            ("pull_in_consistent_ratio_min_norm", "smallest z_c(model)/z_c(4.23) at pull-in, consistent traction"),
            ("pull_in_consistent_ratio_max_norm", "largest z_c(model)/z_c(4.23) at pull-in, consistent traction"),
            ("pull_in_exponent_norm", "p of a fit z_c ~ mu_T^p to the model's pull-in separations (0: fewer than 2)"),
            ("pull_in_exponent_criterion_norm", "p of the same fit to the pull-in roots of (4.23) at the same mu_T"),
            ("pull_off_gap_min_norm", "smallest z_c/zeta0 at pull-off (model)"),
            ("pull_off_gap_max_norm", "largest z_c/zeta0 at pull-off (model)"),
            ("pull_in_gap_norm", "z_c/zeta0 before pull-in at the mu_T of panel (b) (model; 0: no pull-in)"),
            ("criterion_pull_in_gap_norm", "pull-in root of (4.23) at the mu_T of panel (b), printed traction"),
            ("error_max_norm", "largest err(r) of (4.24), z0 the deformed apex gap (text: below 0.05, at the centre)"),
            ("error_max_radius_nm", "radius of the largest err(r)"),
            ("error_max_radius_norm", "radius of the largest err(r) / sqrt(2 R z_c)"),
            ("apex_displacement_norm", "u(0)/z_c before pull-in: err(0) when z0 is the undeformed apex gap"),
            ("all_states_stable_count", "1 when every state of every cycle was certified stable"),
        ],
        sweep: true,
    }
}

impl Scene for Fig4_3 {
    fn quick(p: &mut Self::Params) {
        p.tabor_parameters = vec![0.5, 2.0];
        p.ring_width = p.ring_width.max(0.5);
        p.refine_over_zeta0 = p.refine_over_zeta0.max(1e-3);
        p.step_over_zeta0 = p.step_over_zeta0.max(0.25);
        p.onset_bisections = p.onset_bisections.min(1);
        p.curve_points = p.curve_points.min(50);
    }

    fn validate(p: &Self::Params) -> Result<()> {
        // The start depth of the smallest μ_T must lie above the deepest depth.
        if p.h_min_over_zeta0 + p.step_over_zeta0 >= START_OFFSET {
            return Err(Error::invalid(
                "h_min_over_zeta0",
                p.h_min_over_zeta0,
                "must lie at least one step below the start of the cycles",
            ));
        }
        Ok(())
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let lj = interaction(p)?;
        let printed = InstabilityCriterion::new(&lj, TractionLaw::AsPrinted)?;
        let consistent = InstabilityCriterion::new(&lj, TractionLaw::Consistent)?;
        let mut sweep = sweep(&lj, p, job)?;
        let onset = onset_bracket(&lj, p, &mut sweep, job)?;
        let summary = Summary::new(&sweep.points, &printed, &consistent, p.error_tabor_parameter)?;
        let analysis = Analysis {
            p,
            lj: &lj,
            printed: &printed,
            consistent: &consistent,
            sweep: &sweep,
            onset,
            summary: &summary,
        };
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        fig.panels.push(analysis.panel_a()?);
        fig.panels.push(analysis.panel_b());
        analysis.results(&mut fig);
        analysis.notes(&mut fig)?;
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// Whether a failed cycle is noted on the figure (its minimiser failed) rather than ending the
/// scene (cancellation, invalid parameters).
fn noted(e: &Error) -> bool {
    matches!(e, Error::NoConvergence { .. } | Error::Unresolvable { .. })
}

/// The cycles of panel (a) and the profile of panel (b).
#[derive(Debug, Clone, PartialEq)]
struct Sweep {
    /// One per Tabor parameter whose cycle ran, μ_T increasing.
    points: Vec<Onsets>,
    /// The parabola error before the pull-in at `error_tabor_parameter`.
    profile: Option<ParabolaError>,
    /// Cycles whose minimiser failed, as text for the notes.
    failed: Vec<String>,
}

/// Run the cycles of `tabor_parameters` and `error_tabor_parameter` in parallel (largest μ_T
/// first: its cycle costs most, rings ∝ μ_T² and a factorisation ∝ rings³); each cycle fills a
/// part of the progress ∝ μ_T³ step by step (at the defaults the five cycles up to μ_T = 2 take
/// a tenth of the time, μ_T = 5 and 6 most of it), the parts spanning 0 to 0.97.
///
/// # Errors
/// [`Error::Cancelled`]; [`Error::InvalidParameter`] naming the parameter.
fn sweep(lj: &LennardJones, p: &Fig4_3Params, job: &Job) -> Result<Sweep> {
    let mut mus = p.tabor_parameters.clone();
    mus.push(p.error_tabor_parameter);
    mus.sort_by(f64::total_cmp);
    mus.dedup_by(|a, b| same_tabor(*a, *b));
    let weights: Vec<f64> = mus.iter().map(|mu| mu.powi(3)).collect();
    let parts = job.parts(&weights, 0.0, 0.97);
    // Every tip first: a grid the model refuses (too many rings at the largest μ_T) is an
    // error at once, not after the other cycles have run.
    let tips: Vec<Tip> = mus
        .par_iter()
        .map(|&mu| tip_at(lj, p, mu))
        .collect::<Result<_>>()?;
    let mut runs: Vec<Result<(Onsets, Option<ParabolaError>)>> = mus
        .par_iter()
        .zip(&tips)
        .enumerate()
        .rev()
        .map(|(k, (&mu, tip))| {
            job.check()?;
            let cycle = cycle_of(tip, lj, p, mu, |f| {
                parts[k].progress(f, &format!("cycle at μ_T = {mu}"));
                job.check()
            })?;
            let profile = same_tabor(mu, p.error_tabor_parameter)
                .then(|| pull_in(&cycle).map(|s| parabola_error(tip, s)))
                .flatten();
            Ok((onsets(mu, tip, &cycle), profile))
        })
        .collect();
    runs.reverse();
    let mut sweep = Sweep {
        points: Vec::new(),
        profile: None,
        failed: Vec::new(),
    };
    for (mu, run) in mus.iter().zip(runs) {
        match run {
            Ok((o, profile)) => {
                sweep.points.push(o);
                sweep.profile = sweep.profile.take().or(profile);
            }
            Err(e) if noted(&e) => sweep.failed.push(format!("μ_T = {mu}: {e}")),
            Err(e) => return Err(e),
        }
    }
    Ok(sweep)
}

/// Where the surface model starts to jump: the largest μ_T found without a jump below the
/// smallest found with one, each `None` when there is none.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Onset {
    low: Option<f64>,
    high: Option<f64>,
}

/// The onset of the jumps: from the sweep, then `onset_bisections` cycles bisecting between the
/// largest μ_T without a jump and the smallest with one (a cycle jumps when any state moved by
/// the driver's jump measure, ζ0/2).
///
/// # Errors
/// [`Error::Cancelled`]; [`Error::InvalidParameter`]. A failed minimiser ends the bisection and
/// is noted in `sweep.failed`.
fn onset_bracket(lj: &LennardJones, p: &Fig4_3Params, sweep: &mut Sweep, job: &Job) -> Result<Onset> {
    let high = sweep.points.iter().find(|o| o.jumps > 0).map(|o| o.tabor);
    let low = high.and_then(|h| {
        sweep
            .points
            .iter()
            .filter(|o| o.tabor < h && o.jumps == 0)
            .map(|o| o.tabor)
            .reduce(f64::max)
    });
    let (Some(mut l), Some(mut h)) = (low, high) else {
        return Ok(Onset { low, high });
    };
    let n = p.onset_bisections as f64;
    for i in 0..p.onset_bisections {
        job.check()?;
        let mid = 0.5 * (l + h);
        let cycle = cycle_at(lj, p, mid, |f| {
            job.progress(0.97 + 0.02 * (i as f64 + f) / n, "onset bisection");
            job.check()
        });
        match cycle {
            Ok((_, c)) if c.jumps.is_empty() => l = mid,
            Ok(_) => h = mid,
            Err(e) if noted(&e) => {
                sweep.failed.push(format!("onset bisection at μ_T = {mid}: {e}"));
                break;
            }
            Err(e) => return Err(e),
        }
    }
    Ok(Onset {
        low: Some(l),
        high: Some(h),
    })
}

/// Smallest value, 0 for none.
fn min_of(v: &[f64]) -> f64 {
    v.iter().copied().reduce(f64::min).unwrap_or(0.0)
}

/// Largest value, 0 for none.
fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().reduce(f64::max).unwrap_or(0.0)
}

/// The model's critical separations against the roots of (4.23).
#[derive(Debug, Clone, PartialEq)]
struct Summary {
    /// (μ_T, z_c/ζ0) of the model's pull-ins.
    model_pull_in: Curve,
    /// (μ_T, pull-in root of (4.23), printed traction) at the same μ_T.
    criterion_pull_in: Curve,
    /// Model over (4.23), printed traction, at pull-in.
    ratios: Vec<f64>,
    /// Model over (4.23), consistent traction, at pull-in.
    consistent_ratios: Vec<f64>,
    /// The model's pull-off separations.
    pull_offs: Vec<f64>,
    /// Pull-off roots of (4.23) at the μ_T of the model's pull-offs: printed, consistent.
    criterion_pull_offs: (Vec<f64>, Vec<f64>),
    /// The model's pull-in separation at `error_tabor_parameter`.
    model_b: Option<f64>,
    /// The pull-in root of (4.23) (printed traction) at `error_tabor_parameter`.
    criterion_b: Option<f64>,
}

impl Summary {
    /// Compare the sweep's `points` with the criteria; `mu_b` is the μ_T of panel (b).
    ///
    /// # Errors
    /// Root-finding failures of (4.23).
    fn new(
        points: &[Onsets],
        printed: &InstabilityCriterion,
        consistent: &InstabilityCriterion,
        mu_b: f64,
    ) -> Result<Self> {
        let mut s = Summary {
            model_pull_in: Vec::new(),
            criterion_pull_in: Vec::new(),
            ratios: Vec::new(),
            consistent_ratios: Vec::new(),
            pull_offs: Vec::new(),
            criterion_pull_offs: (Vec::new(), Vec::new()),
            model_b: None,
            criterion_b: printed.critical_separations(mu_b)?.map(|r| r.pull_in),
        };
        for o in points {
            let roots = printed.critical_separations(o.tabor)?;
            let consistent_roots = consistent.critical_separations(o.tabor)?;
            if let Some(z) = o.pull_in {
                s.model_pull_in.push((o.tabor, z));
                if let Some(r) = roots {
                    s.ratios.push(z / r.pull_in);
                    s.criterion_pull_in.push((o.tabor, r.pull_in));
                }
                if let Some(r) = consistent_roots {
                    s.consistent_ratios.push(z / r.pull_in);
                }
                if same_tabor(o.tabor, mu_b) {
                    s.model_b = Some(z);
                }
            }
            if let Some(z) = o.pull_off {
                s.pull_offs.push(z);
                s.criterion_pull_offs.0.extend(roots.map(|r| r.pull_off));
                s.criterion_pull_offs
                    .1
                    .extend(consistent_roots.map(|r| r.pull_off));
            }
        }
        Ok(s)
    }
}

/// Everything the figure shows.
struct Analysis<'a> {
    p: &'a Fig4_3Params,
    lj: &'a LennardJones,
    printed: &'a InstabilityCriterion,
    consistent: &'a InstabilityCriterion,
    sweep: &'a Sweep,
    onset: Onset,
    summary: &'a Summary,
}

impl Analysis<'_> {
    /// The largest err(r) and its radius [m], with √(2R z_c) [m].
    fn worst(&self) -> Option<(f64, f64, f64)> {
        self.sweep.profile.as_ref().map(|e| {
            let (err, at) = e.max();
            (err, at, e.zone)
        })
    }

    /// Panel (a): z_c/ζ0 against μ_T.
    ///
    /// # Errors
    /// Root-finding failures of (4.23).
    fn panel_a(&self) -> Result<Panel> {
        let (p, printed) = (self.p, self.printed);
        let onset_text = match (self.onset.low, self.onset.high) {
            (Some(l), Some(h)) => format!("model's first jump at μ_T = {l:.3}-{h:.3}"),
            (None, Some(h)) => format!("model: jumps from μ_T ≤ {h:.3}"),
            _ => "model: no jump".to_string(),
        };
        let (pin, poff) = criterion_branches(printed, p.curve_tabor_max, p.curve_points)?;
        let (cin, coff) = criterion_branches(self.consistent, p.curve_tabor_max, p.curve_points)?;
        let z_top = pin.iter().map(|q| q.1).fold(2.0, f64::max);
        // Head room for the legend in the upper left, above the curves.
        let mut a = Panel::new(
            Axis::linear("Tabor parameter μ_T", ""),
            Axis::linear("Critical separation z_c/ζ0", "").with_range(0.0, 1.45 * z_top),
        )
        .titled("(a)", format!("(4.23) and surface model; {onset_text}"));
        a.legend = Legend::UpperLeft;
        a.add(Series::new("z_c = μ_T ζ0", Style::Reference, vec![(0.0, 0.0), (z_top, z_top)]).with_color(8));
        a.add(Series::new("(4.23) pull-in", Style::Stable, pin).with_color(RED));
        a.add(Series::new("(4.23) pull-off", Style::Stable, poff).with_color(BLUE));
        a.add(Series::new("(4.23), consistent traction", Style::Reference, cin).with_color(RED));
        a.add(
            Series::new("(4.23), consistent traction, pull-off", Style::Reference, coff)
                .with_color(BLUE)
                .without_legend(),
        );
        if let Some(h) = self.onset.high {
            let x = self.onset.low.map_or(h, |l| 0.5 * (l + h));
            a.add(
                Series::new(
                    "surface model: first jump",
                    Style::Reference,
                    vec![(x, 0.0), (x, 0.9 * z_top)],
                )
                .with_color(2),
            );
        }
        a.mark(
            Marker::new(
                "μ_T* of (4.23)",
                MarkerShape::Point,
                printed.critical_tabor(),
                printed.double_root(),
            )
            .with_color(7),
        );
        for o in &self.sweep.points {
            if let Some(z) = o.pull_in {
                a.mark(
                    Marker::new("surface model, pull-in", MarkerShape::StableState, o.tabor, z)
                        .with_color(RED),
                );
            }
            if let Some(z) = o.pull_off {
                a.mark(
                    Marker::new("surface model, pull-off", MarkerShape::StableState, o.tabor, z)
                        .with_color(BLUE),
                );
            }
        }
        Ok(a)
    }

    /// Panel (b): err(r) of (4.24) just before the pull-in, out to 3√(2R z_c).
    fn panel_b(&self) -> Panel {
        let mu_b = self.p.error_tabor_parameter;
        let b = Panel::new(Axis::linear("Radius r", "nm"), Axis::linear("err(r), (4.24)", ""));
        let (Some(e), Some((err_max, r_max, zone))) = (&self.sweep.profile, self.worst()) else {
            return b.titled("(b)", format!("μ_T = {mu_b}: no pull-in, no profile"));
        };
        let mut b = b.titled(
            "(b)",
            format!(
                "μ_T = {mu_b}, just before pull-in: largest err {:.1} % at r = {:.0} nm",
                100.0 * err_max,
                r_max * 1e9
            ),
        );
        let shown = |values: &[f64]| -> Curve {
            e.radius
                .iter()
                .zip(values)
                .take_while(|(r, _)| **r <= 3.0 * zone)
                .map(|(r, v)| (r * 1e9, *v))
                .collect()
        };
        b.add(Series::new("(4.24), z0 = deformed apex gap", Style::Stable, shown(&e.error)).with_color(RED));
        b.add(
            Series::new(
                "z0 read as the undeformed apex gap",
                Style::Dashed,
                shown(&e.error_undeformed),
            )
            .with_color(7),
        );
        b.add(
            Series::new(
                "the text: below 5 %",
                Style::Reference,
                vec![(0.0, 0.05), (3.0 * zone * 1e9, 0.05)],
            )
            .with_color(8),
        );
        b.mark(
            Marker::new("largest err(r)", MarkerShape::Point, r_max * 1e9, err_max)
                .with_color(RED)
                .with_label(format!("{:.1} %", 100.0 * err_max)),
        );
        b
    }

    /// The scalar results.
    fn results(&self, fig: &mut Figure) {
        let (s, points) = (self.summary, &self.sweep.points);
        let (printed, consistent) = (self.printed, self.consistent);
        let worst = self.worst();
        fig.result("critical_tabor_norm", printed.critical_tabor());
        fig.result("double_root_norm", printed.double_root());
        fig.result("critical_tabor_consistent_norm", consistent.critical_tabor());
        fig.result("double_root_consistent_norm", consistent.double_root());
        fig.result("onset_tabor_low_norm", self.onset.low.unwrap_or(0.0));
        fig.result("onset_tabor_high_norm", self.onset.high.unwrap_or(0.0));
        fig.result("cycles_count", points.len() as f64);
        fig.result(
            "cycles_with_jumps_count",
            points.iter().filter(|o| o.jumps > 0).count() as f64,
        );
        fig.result("pull_in_ratio_min_norm", min_of(&s.ratios));
        fig.result("pull_in_ratio_max_norm", max_of(&s.ratios));
        fig.result("pull_in_consistent_ratio_min_norm", min_of(&s.consistent_ratios));
        fig.result("pull_in_consistent_ratio_max_norm", max_of(&s.consistent_ratios));
        fig.result(
            "pull_in_exponent_norm",
            power_exponent(&s.model_pull_in).unwrap_or(0.0),
        );
        fig.result(
            "pull_in_exponent_criterion_norm",
            power_exponent(&s.criterion_pull_in).unwrap_or(0.0),
        );
        fig.result("pull_off_gap_min_norm", min_of(&s.pull_offs));
        fig.result("pull_off_gap_max_norm", max_of(&s.pull_offs));
        fig.result("pull_in_gap_norm", s.model_b.unwrap_or(0.0));
        fig.result("criterion_pull_in_gap_norm", s.criterion_b.unwrap_or(0.0));
        fig.result("error_max_norm", worst.map_or(0.0, |w| w.0));
        fig.result("error_max_radius_nm", worst.map_or(0.0, |w| w.1 * 1e9));
        fig.result("error_max_radius_norm", worst.map_or(0.0, |w| w.1 / w.2));
        fig.result(
            "apex_displacement_norm",
            self.sweep
                .profile
                .as_ref()
                .map_or(0.0, |e| e.apex_displacement / e.central_gap),
        );
        fig.result(
            "all_states_stable_count",
            f64::from(u8::from(points.iter().all(|o| o.all_stable))),
        );
    }

    /// The notes: the method, then what the workbench finds on each claim of the text.
    ///
    /// # Errors
    /// Invalid parameters of the apex-displacement estimate (4.21) (not expected after
    /// validation).
    fn notes(&self, fig: &mut Figure) -> Result<()> {
        let (p, s, points) = (self.p, self.summary, &self.sweep.points);
        let (printed, consistent) = (self.printed, self.consistent);
        let zeta0 = self.lj.zeta0();
        let rings = points.iter().map(|o| o.rings);
        fig.note(format!(
            "Surface model, smooth tip of Fig. 4.5 (R = {} µm); μ_T set through E* = (R w^2/(μ_T^3 ζ0^3))^(1/2), \
             (1.8), at fixed w and ζ0 = {:.3} nm; cycles from (2 μ_T + 5) ζ0 apart to {} ζ0, steps of {} ζ0, \
             jumps located to {} ζ0; {}-{} rings (at most {} b, at least {} across √(2Rζ0)). z_c is the gap \
             at the apex of the last state before the jump.",
            p.radius * 1e6,
            zeta0 * 1e9,
            crate::figure::exact_number(p.h_min_over_zeta0),
            p.step_over_zeta0,
            crate::figure::exact_number(p.refine_over_zeta0),
            rings.clone().min().unwrap_or(0),
            rings.max().unwrap_or(0),
            p.ring_width,
            p.rings_per_zone,
        ));
        let no_jump: Vec<String> = points
            .iter()
            .filter(|o| o.jumps == 0)
            .map(|o| format!("{}", o.tabor))
            .collect();
        if !no_jump.is_empty() {
            fig.note(format!(
                "No jump on the cycle at μ_T = {}: the model's path is single-valued there (no marker).",
                no_jump.join(", ")
            ));
        }
        if let Some(h) = self.onset.high {
            let bracket = self.onset.low.map_or_else(
                || format!("at or below {h:.3}"),
                |l| format!("between {l:.3} and {h:.3}"),
            );
            fig.note(format!(
                "Onset: the surface model first jumps at μ_T {bracket}; (4.23) predicts μ_T* = {:.6} (z* = {:.6}) with the \
                 printed traction and {:.4} (z* = {:.4}) with the consistent one the model uses. A jump counts when some \
                 ring moves by ζ0/2 or more, so the fold itself may start a little below the bracket. (4.23) is an \
                 estimate (ERRATA): the onset is charted, not fitted.",
                printed.critical_tabor(),
                printed.double_root(),
                consistent.critical_tabor(),
                consistent.double_root(),
            ));
        } else {
            fig.note("Onset: no cycle of the sweep jumps; raise the Tabor parameters.");
        }
        if let (Some(first), Some(last)) = (s.model_pull_in.first(), s.model_pull_in.last()) {
            fig.note(format!(
                "Pull-in: the model's z_c is {:.2}-{:.2} of the root of (4.23) with the printed traction ({:.2}-{:.2} with \
                 the consistent one): the difference grows with μ_T in absolute terms (the text), the ratio stays nearly \
                 constant. 'z_c ≈ μ_T': z_c/(μ_T ζ0) falls from {:.2} at μ_T = {} to {:.2} at {}; z_c grows like \
                 μ_T^{:.2} (fit; (4.23): μ_T^{:.2}, tending to 3/7), so z_c ≈ μ_T holds only near μ_T ≈ {:.1}.",
                min_of(&s.ratios),
                max_of(&s.ratios),
                min_of(&s.consistent_ratios),
                max_of(&s.consistent_ratios),
                first.1 / first.0,
                first.0,
                last.1 / last.0,
                last.0,
                power_exponent(&s.model_pull_in).unwrap_or(0.0),
                power_exponent(&s.criterion_pull_in).unwrap_or(0.0),
                crossing(&s.model_pull_in),
            ));
        }
        if !s.pull_offs.is_empty() {
            let (pr, co) = &s.criterion_pull_offs;
            fig.note(format!(
                "Pull-off: the model's z_c = {:.3}-{:.3} ζ0, close to 1 as the text says (the apex sits near the \
                 equilibrium distance until the contact lets go); (4.23) gives {:.3}-{:.3} (printed traction, whose zero \
                 is at (C12/C6)^(1/6) ζ0) and {:.3}-{:.3} (consistent).",
                min_of(&s.pull_offs),
                max_of(&s.pull_offs),
                min_of(pr),
                max_of(pr),
                min_of(co),
                max_of(co),
            ));
        }
        if let (Some(e), Some((err_max, r_max, zone))) = (&self.sweep.profile, self.worst()) {
            // The apex displacement (4.21) at the pull-in root of (4.23), relative to the root.
            let estimate = match s.criterion_b {
                Some(z) => {
                    let modulus = self.lj.modulus_for_tabor(p.radius, p.error_tabor_parameter)?;
                    self.lj
                        .apex_displacement(z * zeta0, p.radius, modulus, TractionLaw::AsPrinted)?
                        / (z * zeta0)
                }
                None => 0.0,
            };
            fig.note(format!(
                "(b) With z0 the deformed apex gap, err(0) = 0 by construction, so its maximum cannot lie at the centre: the \
                 workbench finds {:.1} % at r = {:.0} nm ({:.2} √(2Rz_c)), not below 5 % at the centre as the text says. \
                 Read with z0 the undeformed apex gap, the maximum is at the centre but is u(0)/z_c = {:.0} %: before the \
                 pull-in the apex has moved {:.2} ζ0 towards the substrate, at z_c = {:.2} ζ0, so the deformation is \
                 not small against the gap. The estimate itself says so: (4.21) at the pull-in root of (4.23) gives \
                 u(0)/z_c = {:.2} (its attractive term alone, Δz ∝ z0^(−5/2) with dΔz/dz0 = −1 (4.22), gives 2/5).",
                100.0 * err_max,
                r_max * 1e9,
                r_max / zone,
                100.0 * e.apex_displacement / e.central_gap,
                e.apex_displacement,
                e.central_gap,
                estimate,
            ));
        }
        for f in &self.sweep.failed {
            fig.note(format!("Not computed: {f}."));
        }
        Ok(())
    }
}

/// μ_T where the model's pull-in separation z_c/ζ0 crosses μ_T (linear interpolation of
/// z/μ − 1 between the points; the nearest point's μ_T when it does not cross).
fn crossing(points: &[(f64, f64)]) -> f64 {
    let f = |q: &(f64, f64)| q.1 / q.0 - 1.0;
    for w in points.windows(2) {
        let (f0, f1) = (f(&w[0]), f(&w[1]));
        if f0 >= 0.0 && f1 < 0.0 {
            return w[0].0 + f0 / (f0 - f1) * (w[1].0 - w[0].0);
        }
    }
    points
        .iter()
        .min_by(|a, b| f(a).abs().total_cmp(&f(b).abs()))
        .map_or(0.0, |q| q.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_exponent_recovers_a_power_law() {
        let pts: Vec<(f64, f64)> = [0.5, 1.0, 3.0, 8.0]
            .iter()
            .map(|&x: &f64| (x, 2.0 * x.powf(3.0 / 7.0)))
            .collect();
        assert!((power_exponent(&pts).unwrap() - 3.0 / 7.0).abs() < 1e-12);
        assert!(power_exponent(&pts[..1]).is_none());
    }

    #[test]
    fn branches_start_at_the_double_root_and_satisfy_4_23() {
        let lj = LennardJones::new(&crate::models::lennard_jones::LennardJonesParams::default()).unwrap();
        let c = InstabilityCriterion::new(&lj, TractionLaw::AsPrinted).unwrap();
        let (pin, poff) = criterion_branches(&c, 10.0, 20).unwrap();
        assert_eq!(pin.len(), 20);
        assert_eq!(pin[0], (c.critical_tabor(), c.double_root()));
        for (a, b) in pin.iter().zip(&poff).skip(1) {
            assert!(a.1 > b.1);
            assert!(c.residual(a.1, a.0).abs() < 1e-10 && c.residual(b.1, b.0).abs() < 1e-10);
        }
        assert!((pin.last().unwrap().0 - 10.0).abs() < 1e-12);
        assert!(criterion_branches(&c, 0.1, 20).unwrap().0.is_empty());
    }

    #[test]
    fn crossing_interpolates_z_over_mu() {
        // z/μ − 1 = 0.5 at μ = 1 and −0.5 at μ = 3: crosses at 2.
        assert!((crossing(&[(1.0, 1.5), (3.0, 1.5)]) - 2.0).abs() < 1e-12);
    }
}
