//! Chapter 6 scenes: peel force along sinusoidal (Fig. 6.2) and zigzag (Fig. 6.4) substrates
//! with stability and the snap-throughs under load control, and the maps of the effective peel
//! force and work of adhesion over aspect ratio and peel angle (Figs. 6.3, 6.5) with their
//! extrema over θ and the optimum-angle fits (6.23), (6.27).
//!
//! Every scene takes an optional `profile_file`: a CSV of x, y over one period of the user's own
//! substrate, which then replaces the built-in profile (its shape is normalised to [−1, 1], the
//! aspect ratio A stays a parameter).

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use super::sweep::{Sweep, Swept};
use super::{Registered, Scene, SceneDyn, SceneHeader};
use crate::error::{Error, Result};
use crate::figure::{Axis, Field, FieldKind, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::models::peeling::{
    Profile, SampledProfile, Stability, WavyPeeling, kendall_force, sinusoid_optimum_angle_fit, steep_limits,
    zigzag_optimum_angle_fit,
};
use crate::numerics::curve::{golden_min, linspace, logspace};
use crate::params::{Range, require_below};

/// The chapter's scenes, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[
    &Registered::<Fig6_2>::NEW,
    &Swept::<Fig6_3>::NEW,
    &Registered::<Fig6_4>::NEW,
    &Swept::<Fig6_5>::NEW,
    &Registered::<Fig6Limits>::NEW,
];

/// Palette indices: black for the measured (load-path) lines, purple and yellow for the
/// minimum and maximum over θ as in the dissertation's contour plots.
const BLACK: usize = 7;
const PURPLE: usize = 3;
const YELLOW: usize = 4;

/// Read a substrate profile: a CSV (comma, semicolon, tab or space separated) of x, y over one
/// period, the last sample repeating the first height; `#` comments, blank lines and one header
/// line are skipped.
///
/// # Errors
/// [`Error::DataFile`] naming the file and line: unreadable file, a line without two numbers,
/// or a profile [`SampledProfile::new`] refuses (too few samples, x not increasing, not closing,
/// flat).
pub fn load_profile(path: &Path) -> Result<Profile> {
    let text = crate::input::read_text(path)?;
    let mut points = Vec::new();
    let mut header_seen = false;
    for (k, raw) in crate::params::normalise_line_ends(&text).lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line
            .split([',', ';', '\t', ' '])
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
        let nums: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        match nums {
            Some(v) if v.len() >= 2 => points.push((v[0], v[1])),
            _ if points.is_empty() && !header_seen => header_seen = true,
            _ => {
                return Err(Error::data_file(
                    path,
                    k + 1,
                    format!("expected two numbers x, y, got `{}`", raw.trim()),
                ));
            }
        }
    }
    SampledProfile::new(&points)
        .map(Profile::Sampled)
        .map_err(|e| match e {
            Error::Unresolvable { reason, .. } => Error::data_file(path, 0, reason),
            other => other,
        })
}

/// The profile of a scene: the user's file if given, else the built-in one.
fn profile_of(file: &str, builtin: &Profile) -> Result<Profile> {
    if file.trim().is_empty() {
        Ok(builtin.clone())
    } else {
        load_profile(Path::new(file.trim()))
    }
}

/// Notes describing a sampled profile.
fn profile_note(fig: &mut Figure, profile: &Profile, file: &str) {
    if let Profile::Sampled(s) = profile {
        let (lo, hi) = profile.slope_range();
        fig.note(format!(
            "profile from {}: {} samples per period, period {} (data units), own aspect ratio {:.5}, {} corner(s) detected, normalised slope range [{:.5}, {:.5}]",
            file.trim(),
            s.n_samples,
            s.period,
            s.aspect_ratio,
            profile.corners().len(),
            lo,
            hi
        ));
    }
}

crate::scene_params! {
    /// Parameters of scenes fig6.2 and fig6.4 (Sec. 6.3). The dissertation gives w̄ = 0.005; the
    /// (A, θ) combinations of its figures are not printed, these show the same physics.
    pub struct PeelCurvesParams {
        /// Normalised work of adhesion w̄ = w/(Eh), Sec. 6.2.2.
        work_of_adhesion_norm: f64 = 0.005, unit = "", range = Range::positive();
        /// Peel angle θ of panel (a).
        peel_angle: f64 = 90.0, unit = "deg", range = Range::between(0.0, 180.0);
        /// Aspect ratios A of panel (a) (A = 0 is the flat substrate, Kendall's (6.11)).
        aspect_ratios: Vec<f64> = vec![0.0, 0.025, 0.05], unit = "", range = Range::between(0.0, 100.0);
        /// Aspect ratio A of panel (b).
        aspect_ratio: f64 = 0.05, unit = "", range = Range::between(0.0, 100.0);
        /// Peel angles θ of panel (b).
        peel_angles: Vec<f64> = vec![60.0, 90.0, 120.0], unit = "deg", range = Range::between(0.0, 180.0);
        /// Number of substrate periods drawn.
        periods: f64 = 3.0, unit = "", range = Range::between(1.0, 100.0);
        /// Samples per period (inflections and corners are added exactly).
        points_per_period: usize = 200, unit = "", range = Range::between(8.0, 1.0e5);
        /// Substrate profile file: CSV of x, y over one period, the last sample repeating the first height (empty: the built-in profile).
        profile_file: String = String::new(), unit = "", range = Range::any();
    }
}

crate::scene_params! {
    /// Parameters of scenes fig6.3 and fig6.5 (Sec. 6.3). The dissertation gives w̄ = 0.005; the
    /// plotted range of A is not printed, A ≤ 0.5 is our choice.
    pub struct PeelMapParams {
        /// Normalised work of adhesion w̄ = w/(Eh), Sec. 6.2.2.
        work_of_adhesion_norm: f64 = 0.005, unit = "", range = Range::positive();
        /// Largest aspect ratio A of the map.
        aspect_ratio_max: f64 = 0.5, unit = "", range = Range::open(0.0, 100.0);
        /// Grid points along A (from 0).
        aspect_ratio_points: usize = 101, unit = "", range = Range::between(3.0, 1.0e4);
        /// Grid points along θ (from 0 to π).
        angle_points: usize = 181, unit = "", range = Range::between(3.0, 1.0e4);
        /// Substrate profile file: CSV of x, y over one period, the last sample repeating the first height (empty: the built-in profile).
        profile_file: String = String::new(), unit = "", range = Range::any();
    }
}

/// Check every (A, θ) pair of a curves scene.
fn validate_curves(p: &PeelCurvesParams, builtin: &Profile) -> Result<()> {
    let profile = profile_of(&p.profile_file, builtin)?;
    for &a in &p.aspect_ratios {
        WavyPeeling::new(&profile, a, p.peel_angle.to_radians(), p.work_of_adhesion_norm)?;
    }
    for &theta in &p.peel_angles {
        WavyPeeling::new(
            &profile,
            p.aspect_ratio,
            theta.to_radians(),
            p.work_of_adhesion_norm,
        )?;
    }
    Ok(())
}

/// Result names of the curves scenes.
const CURVES_RESULTS: &[(&str, &str)] = &[
    (
        "kendall_force_norm",
        "Kendall's flat-substrate force F/(Ebh) at the panel (a) angle, Eq. (6.11)",
    ),
    (
        "max_force_norm",
        "effective peel force F_max/(Ebh), Eq. (6.17), largest A of panel (a)",
    ),
    (
        "max_force_path_norm",
        "largest force on the computed load path, same curve (equals (6.17))",
    ),
    ("min_force_norm", "smallest equilibrium force F/(Ebh), same curve"),
    (
        "max_force_position_norm",
        "front position x_p/lambda of the first snap-through (mod 1), same curve",
    ),
    (
        "first_jump_length_norm",
        "length of the first snap-through in periods, same curve",
    ),
    ("jumps_count", "snap-throughs on the drawn periods, same curve"),
    ("effective_work_ratio_norm", "w_e/w, Eq. (6.18), same curve"),
    (
        "force_enhancement_norm",
        "F_max/F_flat at the panel (a) angle, same curve",
    ),
];

/// Run a curves scene (Fig. 6.2 or 6.4).
fn run_curves(p: &PeelCurvesParams, builtin: &Profile, job: &Job) -> Result<Figure> {
    let profile = profile_of(&p.profile_file, builtin)?;
    let w = p.work_of_adhesion_norm;
    let x_axis = || Axis::linear("Peel-front position x_p/λ", "");
    let y_axis = || Axis::linear("Peel force F/(Ebh)", "");
    let mut panel_a = Panel::new(x_axis(), y_axis()).titled("(a)", format!("θ = {}°", p.peel_angle));
    let mut panel_b = Panel::new(x_axis(), y_axis()).titled("(b)", format!("A = {}", p.aspect_ratio));
    let cases: Vec<(usize, f64, f64)> = p
        .aspect_ratios
        .iter()
        .map(|&a| (0, a, p.peel_angle))
        .chain(p.peel_angles.iter().map(|&t| (1, p.aspect_ratio, t)))
        .collect();
    let mut fig = Figure::new("", "");
    let reference = p.aspect_ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let n_cases = cases.len();
    for (k, (panel_index, a, theta_deg)) in cases.into_iter().enumerate() {
        job.check()?;
        job.progress(k as f64 / n_cases as f64, &format!("curve {}/{}", k + 1, n_cases));
        let peel = WavyPeeling::new(&profile, a, theta_deg.to_radians(), w)?;
        let curve = peel.equilibrium_curve(0.0, p.periods, p.points_per_period);
        let path = peel.load_path(&curve)?;
        let color = if panel_index == 0 {
            k
        } else {
            k - p.aspect_ratios.len()
        };
        let name = if panel_index == 0 {
            format!("A = {a}")
        } else {
            format!("θ = {theta_deg}°")
        };
        let panel = if panel_index == 0 {
            &mut panel_a
        } else {
            &mut panel_b
        };
        // Runs of equal stability: stable and neutral solid, unstable dashed (solid runs
        // first, so that the legend shows the solid line).
        let mut runs: Vec<(Style, Vec<(f64, f64)>)> = Vec::new();
        let mut run_start = 0;
        for s in 1..=curve.segments.len() {
            if s == curve.segments.len() || curve.segments[s] != curve.segments[run_start] {
                let style = if curve.segments[run_start] == Stability::Unstable {
                    Style::Unstable
                } else {
                    Style::Stable
                };
                runs.push((style, curve.points[run_start..=s].to_vec()));
                run_start = s;
            }
        }
        runs.sort_by_key(|(style, _)| *style == Style::Unstable);
        for (style, points) in runs {
            panel.add(Series::new(&name, style, points).with_color(color));
        }
        for j in &path.jumps {
            panel.add(
                Series::new(
                    "snap-through",
                    Style::Jump,
                    vec![(j.from, j.force), (j.to, j.force)],
                )
                .with_color(BLACK)
                .without_legend(),
            );
            panel.arrow((j.from, j.force), (j.to, j.force), Some(BLACK));
        }
        if let Some(j) = path.jumps.first() {
            panel.mark(Marker::new("F_max", MarkerShape::Point, j.from, j.force).with_color(color));
        }
        if panel_index == 0 && a == reference {
            let kendall = kendall_force(theta_deg.to_radians(), w);
            let path_max = path.points.iter().map(|q| q.1).fold(0.0, f64::max);
            fig.result("kendall_force_norm", kendall);
            fig.result("max_force_norm", peel.max_force());
            fig.result("max_force_path_norm", path_max);
            fig.result("min_force_norm", peel.min_force());
            fig.result(
                "max_force_position_norm",
                path.jumps.first().map_or(0.0, |j| j.from.rem_euclid(1.0)),
            );
            fig.result(
                "first_jump_length_norm",
                path.jumps.first().map_or(0.0, |j| j.to - j.from),
            );
            fig.result("jumps_count", path.jumps.len() as f64);
            fig.result("effective_work_ratio_norm", peel.effective_work() / w);
            fig.result("force_enhancement_norm", peel.max_force() / kendall);
        }
    }
    fig.panels = vec![panel_a, panel_b];
    fig.note("solid: stable (or neutral) equilibria, dashed: unstable; thin black arrows: snap-throughs of the front under a slowly rising load, which starts at the smallest equilibrium force and peels the film off completely once it reaches F_max (6.17)");
    fig.note("peel force from (6.9) with the square root over ((cos θ_e − 1)² + 2w̄) only, see ERRATA");
    profile_note(&mut fig, &profile, &p.profile_file);
    job.progress(1.0, "done");
    Ok(fig)
}

/// Extremum of `f` over [lo, hi]: a grid scan of `n` points refined by golden-section search.
fn extremum_over(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize, maximize: bool) -> (f64, f64) {
    let sign = if maximize { -1.0 } else { 1.0 };
    let g = |t: f64| sign * f(t);
    let grid = linspace(lo, hi, n.max(3));
    let k = (0..grid.len())
        .min_by(|&a, &b| g(grid[a]).total_cmp(&g(grid[b])))
        .unwrap_or(0);
    let (a, b) = (grid[k.saturating_sub(1)], grid[(k + 1).min(grid.len() - 1)]);
    let t = golden_min(g, a, b, 1e-12);
    let (t, v) = [(t, f(t)), (grid[k], f(grid[k]))]
        .into_iter()
        .min_by(|x, y| (sign * x.1).total_cmp(&(sign * y.1)))
        .unwrap_or((t, f(t)));
    (t, v)
}

/// About `n` round contour levels strictly inside (lo, hi): multiples of 1, 2 or 5 × 10^k.
fn nice_levels(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return Vec::new();
    }
    let raw = (hi - lo) / n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).floor() as i64 + 1;
    (first..)
        .map(|k| k as f64 * step)
        .take_while(|&v| v < hi)
        .filter(|&v| v > lo)
        .collect()
}

/// Result names of the map scenes.
const MAP_RESULTS: &[(&str, &str)] = &[
    (
        "max_deviation_fit_rad",
        "largest |theta_opt - theta_fit| over the A grid (A > 0), fit (6.23) or (6.27)",
    ),
    (
        "max_deviation_aspect_ratio_norm",
        "A at which that largest deviation occurs",
    ),
    (
        "optimum_angle_at_max_aspect_ratio_rad",
        "numerically optimal theta for w_e at the largest A",
    ),
    (
        "fit_angle_at_max_aspect_ratio_rad",
        "theta of the fit (6.23) or (6.27) at the largest A",
    ),
    (
        "max_work_ratio_norm",
        "w_e/w at the optimal angle and the largest A",
    ),
    ("max_force_norm", "largest F_max/(Ebh) on the map"),
    (
        "max_force_boundary_deviation_rad",
        "largest |argmax_theta F_max - atan(A|min rho'|)| over A (0: the maximum is at the lower admissible angle)",
    ),
    (
        "min_force_boundary_deviation_rad",
        "largest |argmin_theta F_max - (pi - atan(A max rho'))| over A",
    ),
    (
        "min_work_boundary_deviation_rad",
        "largest |argmin_theta w_e - (pi - atan(A max rho'))| over A",
    ),
];

/// One point of a map scene (Fig. 6.3 or 6.5): the column of aspect ratio number `i` of both
/// maps (F_max/(Ebh), then w_e/w, at every angle of the grid; NaN at inadmissible angles), then
/// the extrema over θ at that A: θ and value of the largest and smallest F_max, θ of the
/// smallest w_e, θ and value of the largest w_e (the three w_e entries NaN at A = 0).
fn map_point(p: &PeelMapParams, profile: &Profile, i: usize, job: &Job) -> Result<Vec<f64>> {
    let w = p.work_of_adhesion_norm;
    let a = linspace(0.0, p.aspect_ratio_max, p.aspect_ratio_points)[i];
    let t_grid = linspace(0.0, std::f64::consts::PI, p.angle_points);
    let ny = t_grid.len();
    let mut out = vec![f64::NAN; 2 * ny + 7];
    let force = |a: f64, t: f64| WavyPeeling::new(profile, a, t, w).map(|q| q.max_force());
    let work = |a: f64, t: f64| WavyPeeling::new(profile, a, t, w).map(|q| q.effective_work() / w);
    let (lo, hi) = profile.admissible_angles(a);
    for (j, &t) in t_grid.iter().enumerate() {
        if t >= lo && t <= hi {
            out[j] = force(a, t)?;
            out[ny + j] = work(a, t)?;
        }
    }
    job.check()?;
    let fa = |t: f64| force(a, t.clamp(lo, hi)).unwrap_or(f64::NAN);
    let wa = |t: f64| work(a, t.clamp(lo, hi)).unwrap_or(f64::NAN);
    let (t_fmax, v_fmax) = extremum_over(fa, lo, hi, p.angle_points, true);
    let (t_fmin, v_fmin) = extremum_over(fa, lo, hi, p.angle_points, false);
    out[2 * ny..2 * ny + 4].copy_from_slice(&[t_fmax, v_fmax, t_fmin, v_fmin]);
    // At A = 0 the effective work is w for every angle: no extremum to draw.
    if a > 0.0 {
        let (t_wmin, _) = extremum_over(wa, lo, hi, p.angle_points, false);
        let (t_wmax, v_wmax) = extremum_over(wa, lo, hi, p.angle_points, true);
        out[2 * ny + 4..].copy_from_slice(&[t_wmin, t_wmax, v_wmax]);
    }
    Ok(out)
}

/// The labels of the points of a map scene: one per aspect ratio.
fn map_points(p: &PeelMapParams) -> Vec<String> {
    linspace(0.0, p.aspect_ratio_max, p.aspect_ratio_points)
        .iter()
        .map(|a| format!("A = {}", crate::text::fmt_sig(*a)))
        .collect()
}

/// Assemble a map scene (Fig. 6.3 or 6.5) from its points ([`map_point`]).
fn assemble_map(
    p: &PeelMapParams,
    builtin: &Profile,
    fit: fn(f64) -> f64,
    fit_eq: &str,
    points: &[Vec<f64>],
    job: &Job,
) -> Result<Figure> {
    let profile = profile_of(&p.profile_file, builtin)?;
    let a_grid = linspace(0.0, p.aspect_ratio_max, p.aspect_ratio_points);
    let t_grid = linspace(0.0, std::f64::consts::PI, p.angle_points);
    let (nx, ny) = (a_grid.len(), t_grid.len());
    let mut fmax = vec![f64::NAN; nx * ny];
    let mut wratio = vec![f64::NAN; nx * ny];
    for (i, point) in points.iter().enumerate() {
        for j in 0..ny {
            fmax[j * nx + i] = point[j];
            wratio[j * nx + i] = point[ny + j];
        }
    }
    job.check()?;
    job.progress(0.3, "extrema over θ");
    let mut lines: [Vec<(f64, f64)>; 5] = Default::default(); // F max, F min, w max, w min, fit
    let (mut dev_fit, mut dev_a) = (0.0f64, 0.0);
    let (mut dev_fmax, mut dev_fmin, mut dev_wmin) = (0.0f64, 0.0f64, 0.0f64);
    let (mut opt_last, mut fit_last, mut wmax_last, mut fmax_all) = (0.0, 0.0, 0.0, 0.0f64);
    let mut table = Vec::new();
    for (&a, point) in a_grid.iter().zip(points) {
        let (lo, hi) = profile.admissible_angles(a);
        let [t_fmax, v_fmax, t_fmin, v_fmin, t_wmin, t_wmax, v_wmax] =
            [0, 1, 2, 3, 4, 5, 6].map(|k| point[2 * ny + k]);
        lines[0].push((a, t_fmax));
        lines[1].push((a, t_fmin));
        fmax_all = fmax_all.max(v_fmax).max(v_fmin);
        if a > 0.0 {
            lines[3].push((a, t_wmin));
            dev_fmax = dev_fmax.max((t_fmax - lo).abs());
            dev_fmin = dev_fmin.max((t_fmin - hi).abs());
            dev_wmin = dev_wmin.max((t_wmin - hi).abs());
            lines[2].push((a, t_wmax));
            let t_fit = fit(a);
            lines[4].push((a, t_fit));
            if (t_wmax - t_fit).abs() > dev_fit {
                dev_fit = (t_wmax - t_fit).abs();
                dev_a = a;
            }
            (opt_last, fit_last, wmax_last) = (t_wmax, t_fit, v_wmax);
            table.push((a, t_wmax, t_fit));
        }
    }
    let levels = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        nice_levels(lo, hi, 8)
    };
    let x_axis = || Axis::linear("Aspect ratio A = amplitude/λ", "");
    let y_axis = || Axis::linear("Peel angle θ", "rad");
    let mut pa = Panel::new(x_axis(), y_axis()).titled("(a)", "effective peel force F_max/(Ebh)");
    let mut field = Field::heat("F_max/(Ebh)", "", a_grid.clone(), t_grid.clone(), fmax);
    field.kind = FieldKind::Contour {
        levels: levels(&field.values),
        filled: true,
    };
    pa.field = Some(field);
    pa.add(Series::new("max over θ", Style::Dashed, lines[0].clone()).with_color(YELLOW));
    pa.add(Series::new("min over θ", Style::Dashed, lines[1].clone()).with_color(PURPLE));
    let mut pb = Panel::new(x_axis(), y_axis()).titled("(b)", "effective work of adhesion w_e/w");
    let mut field = Field::heat("w_e/w", "", a_grid, t_grid, wratio);
    field.kind = FieldKind::Contour {
        levels: levels(&field.values),
        filled: true,
    };
    pb.field = Some(field);
    pb.add(Series::new("max over θ", Style::Dashed, lines[2].clone()).with_color(YELLOW));
    pb.add(Series::new("min over θ", Style::Dashed, lines[3].clone()).with_color(PURPLE));
    pb.add(Series::new(format!("fit {fit_eq}"), Style::Reference, lines[4].clone()).with_color(BLACK));
    let mut fig = Figure::new("", "");
    fig.panels = vec![pa, pb];
    for (name, v) in [
        ("max_deviation_fit_rad", dev_fit),
        ("max_deviation_aspect_ratio_norm", dev_a),
        ("optimum_angle_at_max_aspect_ratio_rad", opt_last),
        ("fit_angle_at_max_aspect_ratio_rad", fit_last),
        ("max_work_ratio_norm", wmax_last),
        ("max_force_norm", fmax_all),
        ("max_force_boundary_deviation_rad", dev_fmax),
        ("min_force_boundary_deviation_rad", dev_fmin),
        ("min_work_boundary_deviation_rad", dev_wmin),
    ] {
        fig.result(name, v);
    }
    let step = (table.len() / 10).max(1);
    let rows: Vec<String> = table
        .iter()
        .enumerate()
        .filter(|(k, _)| (k + 1) % step == 0 || *k + 1 == table.len())
        .map(|(_, (a, t, f))| format!("A = {a:.3}: {t:.4} ({f:.4})"))
        .collect();
    fig.note(format!(
        "optimum peel angle of w_e [rad], numerical (fit {fit_eq}): {}",
        rows.join("; ")
    ));
    fig.note(format!(
        "the fit {fit_eq} is read with a negative exponent, θ ≈ 0.5π exp[−1/(...)] (ERRATA); blank region: angles excluded by the comparability condition"
    ));
    profile_note(&mut fig, &profile, &p.profile_file);
    job.progress(1.0, "done");
    Ok(fig)
}

/// A peel-force scene along one substrate profile: the curves of [`run_curves`].
macro_rules! peel_curves_scene {
    ($(#[$doc:meta])* $name:ident, $id:literal, $profile:expr, $title:literal, $caption:literal) => {
        crate::scene! {
            $(#[$doc])*
            pub struct $name {
                id: $id,
                chapter: "6",
                params: PeelCurvesParams,
                title: $title,
                caption: $caption,
                results: CURVES_RESULTS,
            }
        }

        impl Scene for $name {
            fn validate(p: &Self::Params) -> Result<()> {
                validate_curves(p, &$profile)
            }

            fn quick(p: &mut Self::Params) {
                p.points_per_period = p.points_per_period.min(40);
                p.periods = p.periods.min(2.0);
            }

            fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
                let mut fig = run_curves(p, &$profile, job)?;
                fig.title = Self::TITLE.into();
                Ok(fig)
            }
        }
    };
}

/// A map scene of the effective peel force and work of adhesion over one substrate profile: a
/// sweep over the aspect ratio, point `i` the column of A number `i` ([`map_point`]), with the
/// profile's optimum-angle fit `$fit` (equation `$fit_eq`).
macro_rules! peel_map_scene {
    ($(#[$doc:meta])* $name:ident, $id:literal, $profile:expr, $fit:path, $fit_eq:literal, $title:literal, $caption:literal) => {
        crate::scene! {
            $(#[$doc])*
            pub struct $name {
                id: $id,
                chapter: "6",
                params: PeelMapParams,
                title: $title,
                caption: $caption,
                results: MAP_RESULTS,
            }
        }

        impl Scene for $name {
            fn validate(p: &Self::Params) -> Result<()> {
                profile_of(&p.profile_file, &$profile).map(|_| ())
            }

            fn quick(p: &mut Self::Params) {
                p.aspect_ratio_points = p.aspect_ratio_points.min(21);
                p.angle_points = p.angle_points.min(37);
            }

            fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
                super::sweep::run::<Self>(p, job)
            }
        }

        impl Sweep for $name {
            type Context = Profile;

            fn context(p: &Self::Params, _job: &Job) -> Result<Profile> {
                profile_of(&p.profile_file, &$profile)
            }

            /// The column's forces and works at every angle, then its extrema ([`map_point`]);
            /// NaN where an angle is not admissible.
            fn point_len(p: &Self::Params, _id: usize) -> usize {
                2 * p.angle_points + 7
            }

            const NAN_VALUES: bool = true;

            fn points(p: &Self::Params) -> Vec<String> {
                map_points(p)
            }

            fn run_point(p: &Self::Params, profile: &Profile, id: usize, job: &Job) -> Result<Vec<f64>> {
                map_point(p, profile, id, job)
            }

            fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
                let mut fig = assemble_map(p, &$profile, $fit, $fit_eq, points, job)?;
                fig.title = Self::TITLE.into();
                Ok(fig)
            }
        }
    };
}

peel_curves_scene!(
    /// Fig. 6.2: peel force along a sinusoidal substrate.
    Fig6_2,
    "fig6.2",
    Profile::Sinusoid,
    "Peel force along a sinusoidal substrate",
    "Peel force F/(Ebh) vs peel-front position x_p/λ on the sinusoid (6.20) for several A and θ, \
        w = 0.005: (6.9)-(6.10), stable (solid) and unstable (dashed) by (6.15); thin black arrows: snap-throughs under load \
        control up to F_max (6.17), which lies at the steepest descent x_p = 3/4 + n."
);

peel_map_scene!(
    /// Fig. 6.3: maps of the effective peel force and work of adhesion, sinusoid.
    Fig6_3,
    "fig6.3",
    Profile::Sinusoid,
    sinusoid_optimum_angle_fit,
    "(6.23)",
    "Effective peel force and work of adhesion, sinusoidal substrate",
    "Contours of (a) F_max/(Ebh), (6.21), and (b) w_e/w, (6.22), over aspect ratio A and peel \
        angle θ (admissible angles only), w = 0.005; yellow/purple: maximum/minimum over θ at each A; dotted: the \
        optimum-angle fit (6.23)."
);

peel_curves_scene!(
    /// Fig. 6.4: peel force along a zigzag substrate.
    Fig6_4,
    "fig6.4",
    Profile::Zigzag,
    "Peel force along a zigzag substrate",
    "Peel force F/(Ebh) vs peel-front position x_p/λ on the zigzag (6.24) for several A and θ, \
        w = 0.005: neutral equilibrium on the flanks, the front rests at the crests; thin black arrows: snap-throughs \
        from each valley to the next crest once the load reaches F_max (6.25)."
);

peel_map_scene!(
    /// Fig. 6.5: maps of the effective peel force and work of adhesion, zigzag.
    Fig6_5,
    "fig6.5",
    Profile::Zigzag,
    zigzag_optimum_angle_fit,
    "(6.27)",
    "Effective peel force and work of adhesion, zigzag substrate",
    "Contours of (a) F_max/(Ebh), (6.25), and (b) w_e/w, (6.26), over aspect ratio A and peel \
        angle θ (admissible angles only), w = 0.005; yellow/purple: maximum/minimum over θ at each A; dotted: the \
        optimum-angle fit (6.27)."
);

crate::scene_params! {
    /// Parameters of scene fig6.3-limits (Sec. 6.4): the approach of (6.17)-(6.18) to the flat
    /// and steep limits (6.28)-(6.31) at θ = π/2. The first w̄ is the section's example (0.1),
    /// the second the figures' (0.005).
    pub struct LimitsParams {
        /// Normalised works of adhesion w̄ = w/(Eh); results are reported for the first.
        work_of_adhesion_norms: Vec<f64> = vec![0.1, 0.005], unit = "", range = Range::open(0.0, 1.0e3);
        /// Smallest aspect ratio A.
        aspect_ratio_min: f64 = 1.0e-3, unit = "", range = Range::open(0.0, 1.0e6);
        /// Largest aspect ratio A.
        aspect_ratio_max: f64 = 1.0e3, unit = "", range = Range::open(0.0, 1.0e9);
        /// Points along A (log-spaced).
        points: usize = 200, unit = "", range = Range::between(3.0, 1.0e5);
        /// Substrate profile file replacing the zigzag: CSV of x, y over one period, the last sample repeating the first height (empty: sinusoid and zigzag).
        profile_file: String = String::new(), unit = "", range = Range::any();
    }
}

crate::scene! {
    /// Beyond the dissertation's figures: the limits of Sec. 6.4 reached from (6.17)-(6.18).
    pub struct Fig6Limits {
        id: "fig6.3-limits",
        chapter: "6",
        params: LimitsParams,
        title: "Flat and steep limits of the peel-force and adhesion enhancement",
        caption: "Enhancement of (a) the effective peel force F_max/F_flat, (6.17)/(6.11), and (b) the \
            effective work w_e/w, (6.18), vs aspect ratio A at θ = π/2 for the sinusoid and the zigzag (or a profile file); dotted: the steep \
            limits α (6.29) and β (6.31) approached as A grows, and 1 as A → 0 (6.28a), (6.30a).",
        results: &[
            ("alpha_norm", "alpha = F_max,steep/F_max,flat, Eq. (6.29), first w"),
            ("alpha_approx_norm", "the small-w approximation sqrt(2/w) of (6.29)"),
            ("beta_norm", "beta = w_e,steep/w_e,flat = 1 + sqrt(2/w), Eq. (6.31)"),
            ("sinusoid_force_ratio_at_max_aspect_ratio_norm", "F_max/F_flat of (6.17) on the sinusoid at the largest A"),
            ("sinusoid_work_ratio_at_max_aspect_ratio_norm", "w_e/w of (6.18) on the sinusoid at the largest A"),
            ("zigzag_force_ratio_at_max_aspect_ratio_norm", "F_max/F_flat on the zigzag (or the profile file) at the largest A"),
            ("zigzag_work_ratio_at_max_aspect_ratio_norm", "w_e/w on the zigzag (or the profile file) at the largest A"),
        ],
    }
}

impl Scene for Fig6Limits {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below(
            "aspect_ratio_min",
            p.aspect_ratio_min,
            "aspect_ratio_max",
            p.aspect_ratio_max,
        )?;
        profile_of(&p.profile_file, &Profile::Zigzag).map(|_| ())
    }

    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(40);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let second = profile_of(&p.profile_file, &Profile::Zigzag)?;
        let profiles = [Profile::Sinusoid, second];
        let a_grid = logspace(p.aspect_ratio_min, p.aspect_ratio_max, p.points);
        let x_axis = || Axis::log("Aspect ratio A = amplitude/λ", "");
        let mut pa =
            Panel::new(x_axis(), Axis::linear("F_max/F_flat", "")).titled("(a)", "peel force, θ = 90°");
        let mut pb =
            Panel::new(x_axis(), Axis::linear("w_e/w", "")).titled("(b)", "work of adhesion, θ = 90°");
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let (a_lo, a_hi) = (a_grid[0], a_grid[a_grid.len() - 1]);
        for (k, &w) in p.work_of_adhesion_norms.iter().enumerate() {
            job.check()?;
            let limits = steep_limits(w);
            for (m, profile) in profiles.iter().enumerate() {
                let mut force = Vec::with_capacity(a_grid.len());
                let mut work = Vec::with_capacity(a_grid.len());
                for &a in &a_grid {
                    let peel = WavyPeeling::new(profile, a, FRAC_PI_2, w)?;
                    force.push((a, peel.max_force() / limits.force_flat));
                    work.push((a, peel.effective_work() / w));
                }
                let name = format!("{}, w = {w}", profile.name());
                if k == 0 {
                    let key = if m == 0 { "sinusoid" } else { "zigzag" };
                    fig.result(
                        format!("{key}_force_ratio_at_max_aspect_ratio_norm"),
                        force[force.len() - 1].1,
                    );
                    fig.result(
                        format!("{key}_work_ratio_at_max_aspect_ratio_norm"),
                        work[work.len() - 1].1,
                    );
                }
                pa.add(Series::new(&name, Style::Stable, force).with_color(2 * k + m));
                pb.add(Series::new(&name, Style::Stable, work).with_color(2 * k + m));
            }
            pa.add(
                Series::new(
                    format!("α (6.29), w = {w}"),
                    Style::Reference,
                    vec![(a_lo, limits.alpha), (a_hi, limits.alpha)],
                )
                .with_color(BLACK),
            );
            pb.add(
                Series::new(
                    format!("β (6.31), w = {w}"),
                    Style::Reference,
                    vec![(a_lo, limits.beta), (a_hi, limits.beta)],
                )
                .with_color(BLACK),
            );
            if k == 0 {
                fig.result("alpha_norm", limits.alpha);
                fig.result("alpha_approx_norm", limits.alpha_approx);
                fig.result("beta_norm", limits.beta);
            }
        }
        fig.panels = vec![pa, pb];
        fig.note("for w = 0.1 the text prints alpha = 4.68 (4.6856 by (6.29)) and beta = 5.68, which is 1 + alpha rather than (6.31) = 5.472 (ERRATA)");
        profile_note(&mut fig, &profiles[1], &p.profile_file);
        job.progress(1.0, "done");
        Ok(fig)
    }
}
