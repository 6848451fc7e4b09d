//! Fitting measured force-indentation curves (appendix A.4): the `--fit` command.
//!
//! A measured contact cycle (approach, contact, retract) of a spherical tip is read from CSV, its
//! in-contact part is found, and the work of adhesion w and the plane-strain modulus ℰ are fitted
//! by nonlinear least squares (Levenberg-Marquardt, [`crate::numerics::least_squares`]) to the
//! contact relation (2.31b)-(2.32b), which is the JKR relation (1.2):
//!
//! ```text
//! P(h) = P̂ (ā³ − 2ā^(3/2)),  h = ĥ (ā² − (4/3)√ā),  â = (9πwR²/8ℰ)^(1/3), ĥ = â²/R, P̂ = 3πwR/2
//! ```
//!
//! on the stable part ā ≥ ā_D, where h(ā) increases, so the force is a function of the depth.
//! Appendix A.4 fits the depth as a function of the force (A.4.1); that inverse is two-valued on
//! the part of the curve an experiment with a compliant cantilever reaches before the pull-off
//! (between the force minimum and the pull-off), so the residual here is the force at the measured
//! depth. The machine-stiffness model and JKR share this relation, so both give the same fitted
//! w and ℰ (as section 2.4 reports); they differ in where the jumps occur, which the report
//! predicts for both when the cantilever stiffness k_s is given.
//!
//! File format: a header naming the depth and force columns with their units (`depth_nm,force_nN`,
//! `depth_m,force_N`, `depth [um],force [uN]`, `h (nm); P (nN)` and the like; separators comma,
//! semicolon, tab), comment lines starting with `#`, then rows in acquisition order. Positive
//! depth is indentation, positive force is compression.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Series, Style};
use crate::models::machine_stiffness::{Experiment, Instability, TipGeometry};
pub mod engine;
pub mod instrument;
pub mod map;
pub mod predictions;

pub use engine::ContactModel;

pub use predictions::{JkrPredictions, Predictions, jkr_predictions, ph_panel, predictions};

/// Options of the `--fit` command (flattened into [`crate::cli::Cli`]).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FitArgs {
    /// Fit a measured force curve with --headless: a depth/force CSV, or an instrument file
    /// (JPK .jpk-force, .jpk-force-map, .jpk-qi-data/-series, Asylum .ibw, NT-MDT text, AFM
    /// Workshop CSV or map zip, Optics11 Chiaro text, afmformats .tab or .h5), the format read
    /// from the content. A file of many curves
    /// (a force map) is fitted curve by curve into maps.
    #[arg(long, value_name = "FILE")]
    pub fit: Option<PathBuf>,
    /// Tip radius R in metres (for --fit).
    #[arg(long, value_name = "METRES", requires = "fit")]
    pub tip_radius: Option<f64>,
    /// Cantilever (machine) stiffness k_s in N/m (for --fit): predicts the pull-in and pull-off;
    /// for an instrument file it overrides the file's value (and the run says so).
    #[arg(long, value_name = "N_PER_M", requires = "fit")]
    pub spring_constant: Option<f64>,
    /// Deflection sensitivity (InvOLS) in m/V, for instrument files that lack it (for --fit).
    #[arg(long, value_name = "M_PER_V", requires = "fit")]
    pub sensitivity: Option<f64>,
    /// Model (for --fit): hertz, dmt, jkr, maugis-dugdale, or machine-stiffness (needs a spring
    /// constant: the file's or --spring-constant). Default: machine-stiffness with a spring
    /// constant, else jkr.
    #[arg(long, value_enum, requires = "fit")]
    pub model: Option<FitModel>,
    /// Segment fitted (for --fit): approach, retract or both. Default: approach for hertz, retract
    /// for the adhesive models.
    #[arg(long, value_enum, requires = "fit")]
    pub segment: Option<SegmentChoice>,
    /// Poisson's ratio of the sample, to report Young's modulus E = E*(1 - nu^2) (for --fit).
    #[arg(long, value_name = "NU", requires = "fit")]
    pub poisson: Option<f64>,
    /// Fit only this curve of a multi-curve file (0-based index; for --fit).
    #[arg(long, value_name = "INDEX", requires = "fit")]
    pub curve: Option<usize>,
    /// Remove the baseline's slope as well as its offset in preprocessing (for --fit with an
    /// instrument file).
    #[arg(long, requires = "fit")]
    pub baseline_tilt: bool,
}

/// The model of a fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FitModel {
    /// Hertz (1.1): no adhesion (for comparison with Hertz-type AFM software).
    Hertz,
    /// DMT (1.3): Hertz shifted by the pull-off force −2πwR.
    Dmt,
    /// JKR (1.2): no machine stiffness.
    Jkr,
    /// The machine-stiffness model of chapter 2, (2.31)-(2.32): the JKR contact relation with
    /// the jumps of a cantilever of stiffness k_s.
    MachineStiffness,
    /// Maugis-Dugdale (3.3): w, ℰ and the range Z₀ of the Dugdale zone.
    MaugisDugdale,
}

impl FitModel {
    /// The contact relation fitted.
    pub fn contact_model(self) -> ContactModel {
        match self {
            FitModel::Hertz => ContactModel::Hertz,
            FitModel::Dmt => ContactModel::Dmt,
            FitModel::Jkr | FitModel::MachineStiffness => ContactModel::Jkr,
            FitModel::MaugisDugdale => ContactModel::MaugisDugdale,
        }
    }

    /// The segment fitted when the user does not choose one: the approach for Hertz (the
    /// elastic loading, as Hertz-type AFM analysis takes it), the retract for the adhesive
    /// models (where the pull-off is).
    pub fn default_segment(self) -> SegmentChoice {
        match self {
            FitModel::Hertz => SegmentChoice::Approach,
            _ => SegmentChoice::Retract,
        }
    }
}

/// The part of a cycle that is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SegmentChoice {
    /// The approach (loading) rows, up to the deepest row.
    Approach,
    /// The retract (unloading) rows after the deepest row, with the approach's out-of-contact
    /// rows for the baseline.
    Retract,
    /// Every row.
    Both,
}

/// A measured curve in SI units, in acquisition order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Curve {
    /// Indentation depth h [m] (positive into the substrate).
    pub depth: Vec<f64>,
    /// Contact force P [N] (positive in compression).
    pub force: Vec<f64>,
    /// 1-based line number of each row in the file.
    pub lines: Vec<usize>,
}

const LENGTH_UNITS: &[(&str, f64)] = &[
    ("m", 1.0),
    ("mm", 1e-3),
    ("um", 1e-6),
    ("µm", 1e-6),
    ("μm", 1e-6),
    ("micron", 1e-6),
    ("microns", 1e-6),
    ("nm", 1e-9),
    ("pm", 1e-12),
    ("a", 1e-10),
    ("å", 1e-10),
    ("angstrom", 1e-10),
];
const FORCE_UNITS: &[(&str, f64)] = &[
    ("n", 1.0),
    ("mn", 1e-3),
    ("un", 1e-6),
    ("µn", 1e-6),
    ("μn", 1e-6),
    ("nn", 1e-9),
    ("pn", 1e-12),
];
const DEPTH_NAMES: &[&str] = &["depth", "indentation", "h", "indentation_depth", "separation"];
const FORCE_NAMES: &[&str] = &["force", "load", "p", "contact_force"];

/// Split a header cell into (name, unit): `depth_nm`, `depth [nm]`, `depth (nm)`, `depth/nm`.
fn name_and_unit(cell: &str) -> (String, Option<String>) {
    let c = cell.trim().trim_matches('"').trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let (Some(i), Some(j)) = (c.find(open), c.rfind(close))
            && i < j
        {
            return (c[..i].trim().to_lowercase(), Some(c[i + 1..j].trim().to_string()));
        }
    }
    if let Some(i) = c.rfind('/') {
        return (c[..i].trim().to_lowercase(), Some(c[i + 1..].trim().to_string()));
    }
    if let Some(i) = c.rfind('_') {
        let (name, unit) = (&c[..i], &c[i + 1..]);
        let u = unit.to_lowercase();
        if LENGTH_UNITS.iter().chain(FORCE_UNITS).any(|(n, _)| *n == u) {
            return (name.trim().to_lowercase(), Some(unit.to_string()));
        }
        return (c.to_lowercase(), None);
    }
    (c.to_lowercase(), None)
}

fn split_row(line: &str) -> Vec<&str> {
    let sep = if line.contains(',') {
        ','
    } else if line.contains(';') {
        ';'
    } else {
        '\t'
    };
    if line.contains(sep) {
        line.split(sep).map(str::trim).collect()
    } else {
        line.split_whitespace().collect()
    }
}

/// Parse a measured curve from CSV text; `path` names the file in error messages.
///
/// # Errors
/// [`Error::DataFile`] naming the line: no header, a missing depth or force column, a missing or
/// unknown unit, a row with too few cells, a cell that is not a finite number, or no data rows.
pub fn parse_curve(text: &str, path: &Path) -> Result<Curve> {
    let err = |line: usize, msg: String| Error::data_file(path, line, msg);
    // Line ends: LF, CRLF or CR alone (old Mac exports); one line number per line in each.
    let text = crate::params::normalise_line_ends(text);
    let mut rows = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_start_matches('\u{feff}').trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = rows.next() else {
        return Err(err(
            0,
            "empty file: expected a header such as `depth_nm,force_nN`".into(),
        ));
    };
    let cells = split_row(header);
    let mut depth_col = None;
    let mut force_col = None;
    for (k, cell) in cells.iter().enumerate() {
        let (name, unit) = name_and_unit(cell);
        let is_depth = DEPTH_NAMES.contains(&name.as_str());
        let is_force = FORCE_NAMES.contains(&name.as_str());
        if !(is_depth || is_force) {
            continue;
        }
        let (units, what) = if is_depth {
            (LENGTH_UNITS, "length (m, mm, um, nm, pm, angstrom)")
        } else {
            (FORCE_UNITS, "force (N, mN, uN, nN, pN)")
        };
        let Some(unit) = unit else {
            return Err(err(
                header_line,
                format!(
                    "column `{}` has no unit: write e.g. `{name}_nm` or `{name} [nN]`",
                    cell.trim()
                ),
            ));
        };
        let Some(&(_, scale)) = units.iter().find(|(n, _)| *n == unit.to_lowercase()) else {
            return Err(err(
                header_line,
                format!(
                    "unknown unit `{unit}` in column `{}`: expected a {what}",
                    cell.trim()
                ),
            ));
        };
        let slot = if is_depth { &mut depth_col } else { &mut force_col };
        if slot.is_none() {
            *slot = Some((k, scale));
        }
    }
    let Some((dk, ds)) = depth_col else {
        return Err(err(
            header_line,
            format!("no depth column in header `{header}` (expected e.g. `depth_nm,force_nN`)"),
        ));
    };
    let Some((fk, fs)) = force_col else {
        return Err(err(
            header_line,
            format!("no force column in header `{header}` (expected e.g. `depth_nm,force_nN`)"),
        ));
    };
    let mut curve = Curve::default();
    for (line, row) in rows {
        let cells = split_row(row);
        let need = dk.max(fk) + 1;
        if cells.len() < need {
            return Err(err(
                line,
                format!(
                    "{} column(s), the header has {}",
                    cells.len(),
                    need.max(cells.len())
                ),
            ));
        }
        let num = |k: usize, what: &str| -> Result<f64> {
            let t = cells[k].trim_matches('"');
            match t.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(err(line, format!("{what} `{t}` is not a finite number"))),
            }
        };
        curve.depth.push(num(dk, "depth")? * ds);
        curve.force.push(num(fk, "force")? * fs);
        curve.lines.push(line);
    }
    if curve.depth.is_empty() {
        return Err(err(header_line, "no data rows after the header".into()));
    }
    Ok(curve)
}

/// Read a measured curve from a CSV file.
///
/// # Errors
/// As [`parse_curve`]; unreadable files.
pub fn read_curve(path: &Path) -> Result<Curve> {
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    let text = String::from_utf8(bytes).map_err(|_| Error::data_file(path, 0, "not UTF-8 text"))?;
    parse_curve(&text, path)
}

/// Fewest rows a baseline may have: shorter end segments are not taken as baselines.
pub const MIN_BASELINE_ROWS: usize = 10;

/// How the in-contact rows of a curve were found (written to `fit.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactDetection {
    /// The estimator, in words.
    pub method: String,
    /// Rows of the zero-force baseline found at the start of the file (0: none, the file starts
    /// in contact).
    pub baseline_rows_start: usize,
    /// Rows of the baseline found at the end of the file.
    pub baseline_rows_end: usize,
    /// Noise level σ of the baseline(s) [N] (0 without a baseline).
    pub noise_n: f64,
    /// A row between the baselines is in contact from the first to the last whose |P| exceeds
    /// this [N]: max(8σ, 1 % of the largest |P|).
    pub threshold_n: f64,
}

/// The in-contact part of a cycle ([`detect_contact`] without its description).
///
/// # Errors
/// As [`detect_contact`].
pub fn contact_range(curve: &Curve, path: &Path, min_points: usize) -> Result<std::ops::Range<usize>> {
    detect_contact(curve, path, min_points).map(|(r, _)| r)
}

/// The in-contact part of a cycle, found as AFM software finds a contact point, by the deviation
/// from the baseline that is actually there, at each end of the file:
/// - a baseline starts with [`MIN_BASELINE_ROWS`] rows at an end whose median force is small
///   (below max(5σ, 2 % of the largest |P|), σ their noise level: the larger of the noise
///   about a robust line and of 1.4826 × the median deviation from their median, so that
///   correlated noise counts in full) and whose outermost
///   row is within the tolerance below: forces are taken as zero out of contact, as the
///   models assume; an end in contact has none;
/// - it grows row by row inwards while the force stays within max(6σ, 0.5 % of max |P|) of
///   that median, and ends before the first of three successive rows outside (a single noise
///   spike does not end it; the jump at pull-in or pull-off, or the onset of contact, does);
/// - the in-contact rows are those between the baselines from the first to the last whose
///   |P| exceeds max(8σ, 1 % of max |P|), with σ the smaller of the baselines' noise levels
///   (0 without a baseline: then the whole file is the contact part).
///
/// Baselines of 10 rows suffice; the jumps are never mistaken for noise, since σ comes from
/// the baseline rows alone.
///
/// # Errors
/// [`Error::DataFile`] when fewer than `min_points` rows are in contact.
pub fn detect_contact(
    curve: &Curve,
    path: &Path,
    min_points: usize,
) -> Result<(std::ops::Range<usize>, ContactDetection)> {
    let f = &curve.force;
    let n = f.len();
    let p_max = f.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let start = baseline(|k| f[k], n, p_max, true);
    let end = baseline(|k| f[n - 1 - k], n, p_max, true);
    // Baselines shorter than the minimum are not trusted (their σ would be noise itself).
    let start = start.filter(|b| b.0 >= MIN_BASELINE_ROWS);
    let end = end.filter(|b| b.0 >= MIN_BASELINE_ROWS);
    let (len_s, len_e) = (start.map_or(0, |b| b.0), end.map_or(0, |b| b.0));
    let noise = match (start, end) {
        (Some(a), Some(b)) => a.1.min(b.1),
        (Some(a), None) | (None, Some(a)) => a.1,
        (None, None) => 0.0,
    };
    let threshold = (8.0 * noise).max(0.01 * p_max);
    let inner = len_s..n.saturating_sub(len_e).max(len_s);
    let first = inner.clone().find(|&k| f[k].abs() > threshold);
    let last = inner.clone().rev().find(|&k| f[k].abs() > threshold);
    let range = match (first, last) {
        (Some(a), Some(b)) => a..b + 1,
        _ => 0..0,
    };
    let method = match (len_s > 0, len_e > 0) {
        (true, true) => "deviation from the zero-force baselines at both ends",
        (true, false) => "deviation from the zero-force baseline at the start (the file ends in contact)",
        (false, true) => "deviation from the zero-force baseline at the end (the file starts in contact)",
        (false, false) => "no baseline (the whole file in contact): force above 1 % of its largest |P|",
    };
    let detection = ContactDetection {
        method: method.into(),
        baseline_rows_start: len_s,
        baseline_rows_end: len_e,
        noise_n: noise,
        threshold_n: threshold,
    };
    if range.len() < min_points {
        let line = curve.lines.get(range.start).copied().unwrap_or(0);
        return Err(Error::data_file(
            path,
            line,
            format!(
                "only {} in-contact point(s) (force above {threshold:.3e} N; baselines of {len_s} rows at the start and {len_e} at the end); at least {min_points} are needed",
                range.len()
            ),
        ));
    }
    Ok((range, detection))
}

/// The zero-force baseline at one end of a curve: `f(k)` is the k-th force from that end
/// inwards, `n` the rows. Returns its length and noise level, or `None` if the end is in
/// contact (see [`detect_contact`]). With `zero_level` false the baseline may lie at any force
/// (an instrument's offset); `p_max` is then the force range.
pub(crate) fn baseline(
    f: impl Fn(usize) -> f64,
    n: usize,
    p_max: f64,
    zero_level: bool,
) -> Option<(usize, f64)> {
    if n < 2 * MIN_BASELINE_ROWS {
        return None;
    }
    let head: Vec<f64> = (0..MIN_BASELINE_ROWS).map(&f).collect();
    let mut sorted = head.clone();
    sorted.sort_by(f64::total_cmp);
    let level = sorted[sorted.len() / 2];
    // The larger of the noise about a robust line and of the spread about the median: on 10
    // rows, correlated noise (a drift, a sawtooth) looks like a line and only the second sees
    // it; for white noise both are σ.
    let mut deviations: Vec<f64> = head.iter().map(|x| (x - level).abs()).collect();
    deviations.sort_by(f64::total_cmp);
    let sigma = noise_level(&head).max(1.4826 * deviations[deviations.len() / 2]);
    if zero_level && level.abs() > (5.0 * sigma).max(0.02 * p_max) {
        return None;
    }
    // Rows that spread over more than a twentieth of the force range in two clusters are no
    // baseline: they straddle a jump (a file that ends two rows after the pull-off, with its
    // rows duplicated, gives 10 end rows of which four are at zero and six in contact). A
    // noisy baseline spreads as widely, without the gap (a JPK QI curve whose force rises
    // above the noise by only nine times its σ).
    if sigma > 0.05 * p_max && straddles_a_jump(&sorted) {
        return None;
    }
    let tol = (6.0 * sigma).max(0.005 * p_max);
    if (f(0) - level).abs() > tol {
        // The outermost row stands out: the file ends (or starts) in contact.
        return None;
    }
    let (mut len, mut outside) = (1, 0);
    for k in 1..n {
        if (f(k) - level).abs() > tol {
            outside += 1;
            if outside == 3 {
                break;
            }
        } else {
            len = k + 1;
            outside = 0;
        }
    }
    Some((len, sigma))
}

/// Whether sorted forces fall into two clusters of at least three rows each, separated by a gap
/// wider than half their whole range (white noise in ten rows leaves no such gap).
fn straddles_a_jump(sorted: &[f64]) -> bool {
    let n = sorted.len();
    let range = sorted[n - 1] - sorted[0];
    n >= 6 && (3..=n - 3).any(|i| sorted[i] - sorted[i - 1] > 0.5 * range)
}

/// Robust noise level of a segment that is a straight line plus noise: the larger of
/// median|ΔP|/(0.954·√2) of successive differences (right for white noise) and 1.4826 × the
/// median absolute residual of a robust straight line through the segment against the row index
/// (right for correlated noise too, where successive differences underestimate σ). A flat noisy
/// baseline gives its σ; a smooth curve, when a file holds only the contact part, nearly zero.
fn noise_level(seg: &[f64]) -> f64 {
    fn median(mut v: Vec<f64>) -> f64 {
        if v.is_empty() {
            return 0.0;
        }
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    }
    let n = seg.len();
    if n < 2 {
        return 0.0;
    }
    let from_diffs =
        median(seg.windows(2).map(|w| (w[1] - w[0]).abs()).collect()) / (0.954 * std::f64::consts::SQRT_2);
    // A robust straight line: the median of the slopes between rows half a segment apart, and
    // the median intercept (a few spikes or a jump at the end do not tilt it).
    let h = n / 2;
    let slope = median((0..n - h).map(|k| (seg[k + h] - seg[k]) / h as f64).collect());
    let intercept = median(
        seg.iter()
            .enumerate()
            .map(|(k, y)| y - slope * k as f64)
            .collect(),
    );
    let residuals = seg
        .iter()
        .enumerate()
        .map(|(k, y)| (y - intercept - slope * k as f64).abs())
        .collect();
    from_diffs.max(1.4826 * median(residuals))
}

/// A fitted parameter with its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// Value (SI).
    pub value: f64,
    /// Standard error from the Jacobian (SI).
    pub std_error: f64,
}

/// Predicted instabilities of one model, SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InstabilityReport {
    /// Force just after the pull-in [N].
    pub pull_in_force_n: f64,
    /// Change of indentation depth in the pull-in [m].
    pub pull_in_depth_jump_m: f64,
    /// Force just before the pull-off [N].
    pub pull_off_force_n: f64,
    /// Change of indentation depth in the pull-off [m].
    pub pull_off_depth_jump_m: f64,
    /// Depth just before the pull-off [m].
    pub pull_off_depth_m: f64,
}

/// The correlation matrix of the fitted parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Correlation {
    /// Parameter names, in the order of the rows and columns.
    pub parameters: Vec<String>,
    /// Rows of the matrix.
    pub matrix: Vec<Vec<f64>>,
}

/// The result of a fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReport {
    /// The data file.
    pub file: String,
    /// Tip radius R [m].
    pub tip_radius_m: f64,
    /// Model drawn and reported first.
    pub model: FitModel,
    /// The part of the cycle fitted.
    pub segment: SegmentChoice,
    /// Work of adhesion w [J/m²] (none for Hertz).
    pub work_of_adhesion_j_per_m2: Option<Estimate>,
    /// Plane-strain modulus ℰ = E/(1-ν²) [Pa].
    pub plane_strain_modulus_pa: Estimate,
    /// Hertz and DMT: the plane-strain moduli that fit within the noise with the contact point
    /// free, the 95 % profile interval over the contact point (wider than ±2 standard errors
    /// where the linearised error understates the uncertainty).
    pub plane_strain_modulus_interval_pa: Option<(f64, f64)>,
    /// Young's modulus E = ℰ(1 − ν²) [Pa], when Poisson's ratio ν is given.
    pub youngs_modulus_pa: Option<Estimate>,
    /// Poisson's ratio ν used for [`Self::youngs_modulus_pa`].
    pub poisson_ratio: Option<f64>,
    /// Contact point d_c [m], in the depth origin of the data: the fitted indentation is
    /// δ = d − d_c.
    pub contact_point_m: Estimate,
    /// Force baseline F₀ [N] fitted with the model (after any offset removed in
    /// preprocessing): the model force is P(δ) + F₀.
    pub baseline_n: Estimate,
    /// Range Z₀ of the Dugdale interaction [m] (Maugis-Dugdale).
    pub interaction_range_m: Option<Estimate>,
    /// Maugis parameter λ at the fitted values (Maugis-Dugdale).
    pub maugis_lambda: Option<f64>,
    /// Correlations of the fitted parameters.
    pub correlation: Correlation,
    /// Root-mean-square force residual [N].
    pub rms_residual_n: f64,
    /// Rows in the file.
    pub points_total: usize,
    /// Rows fitted (in and out of contact).
    pub points_used: usize,
    /// In-contact rows among them.
    pub points_in_contact: usize,
    /// First and last file line of the in-contact rows fitted.
    pub lines_used: (usize, usize),
    /// The rows in contact as the data show them (0-based, end exclusive), of the whole cycle.
    pub contact_rows: (usize, usize),
    /// The row where the approach turns into the retract ([`turning_row`]; 0-based).
    pub turning_row: usize,
    /// How the in-contact rows were found.
    pub contact_detection: ContactDetection,
    /// Why the fitted values may not mean what they seem (also printed on stderr), e.g. a
    /// standard error as large as the value.
    pub warnings: Vec<String>,
    /// Levenberg-Marquardt iterations.
    pub iterations: usize,
    /// Cantilever stiffness k_s [N/m], if given.
    pub spring_constant_n_per_m: Option<f64>,
    /// α = k_s/k̂ at the fitted parameters, if k_s is given.
    pub alpha: Option<f64>,
    /// Machine-stiffness predictions (with k_s and an adhesive model).
    pub machine_stiffness: Option<InstabilityReport>,
    /// JKR predictions (pull-in at h = 0, pull-off −5πwR/6, no depth change), for the
    /// adhesive models.
    pub jkr: Option<InstabilityReport>,
    /// Measured pull-off force: the minimum force of the retract rows, relative to the fitted
    /// baseline [N].
    pub measured_pull_off_force_n: f64,
    /// Measured most negative force of the whole cycle, relative to the fitted baseline [N].
    pub measured_min_force_n: f64,
}

impl FitReport {
    /// The work of adhesion, or an error for a model without one.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for Hertz.
    pub fn work_of_adhesion(&self) -> Result<Estimate> {
        self.work_of_adhesion_j_per_m2
            .ok_or_else(|| Error::invalid("model", "hertz", "has no work of adhesion"))
    }
}

/// The in-contact rows must be able to determine w and ℰ: the depth and the force vary, and
/// the deepest rows indent (positive depth) under compression (positive force), as every model
/// here has it (a sign flipped in one column breaks this).
///
/// # Errors
/// [`Error::DataFile`] naming the lines and what to check.
fn check_meaningful_data(h: &[f64], p: &[f64], path: &Path, lines: (usize, usize)) -> Result<()> {
    let span = |v: &[f64]| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        });
        hi - lo
    };
    let at = |what: String| {
        Error::data_file(
            path,
            lines.0,
            format!("in-contact lines {}-{}: {what}", lines.0, lines.1),
        )
    };
    if span(h) <= 0.0 {
        return Err(at("the depth does not vary, so no modulus can be fitted".into()));
    }
    if span(p) <= 0.0 {
        return Err(at("the force does not vary, so nothing can be fitted".into()));
    }
    // At the deepest tenth of the indentation span every model is in compression.
    let (h_lo, h_max) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(*x), b.max(*x))
    });
    let mut deep: Vec<f64> = h
        .iter()
        .zip(p)
        .filter(|(hh, _)| **hh >= h_max - 0.1 * (h_max - h_lo))
        .map(|(_, pp)| *pp)
        .collect();
    let mut all = p.to_vec();
    let (mid_deep, mid_all) = (deep.len() / 2, all.len() / 2);
    let deep_median = *deep.select_nth_unstable_by(mid_deep, f64::total_cmp).1;
    if deep_median <= *all.select_nth_unstable_by(mid_all, f64::total_cmp).1 {
        return Err(at(
            "the deepest rows are not in compression (positive depth is indentation, positive force compression): is the sign of one column flipped?"
                .into(),
        ));
    }
    Ok(())
}

/// The tip radii a fit accepts [m]: from a sharp AFM tip (0.1 nm) to a 10 cm indenter.
pub const TIP_RADIUS_RANGE: (f64, f64) = (1e-10, 0.1);
/// The spring constants a fit accepts [N/m]: the softest cantilevers to stiff indenter frames.
pub const SPRING_CONSTANT_RANGE: (f64, f64) = (1e-5, 1e7);

/// Options of a fit beside the data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// Tip radius R [m].
    pub radius: f64,
    /// Cantilever stiffness k_s [N/m], for the machine-stiffness predictions.
    pub spring_constant: Option<f64>,
    /// The model; `None`: machine-stiffness with a spring constant, else JKR.
    pub model: Option<FitModel>,
    /// The part of the cycle; `None`: the model's [`FitModel::default_segment`].
    pub segment: Option<SegmentChoice>,
    /// Poisson's ratio ν, to report Young's modulus E = ℰ(1 − ν²).
    pub poisson: Option<f64>,
}

/// The row where the approach turns into the retract, for a cycle whose contact starts at row
/// `contact_start`: the row farthest from the contact point in the plane of indentation and
/// force, each scaled to its largest value (the rule of nanite's approach/retract split).
/// Where the stage has reversed but the cantilever lags, the deepest row is a retract row whose
/// force has already dropped; counting it to the approach bends a Hertz fit of a noisy curve
/// with few rows in contact (a JPK QI curve of 15 such rows gave half the modulus).
/// Forces are taken relative to the mean of the rows before the contact; without such rows,
/// relative to zero. On an ideal cycle (deepest row, largest force) this is the deepest row.
pub fn turning_row(curve: &Curve, contact_start: usize) -> usize {
    let (d, f) = (&curve.depth, &curve.force);
    let n = d.len().min(f.len());
    if n == 0 {
        return 0;
    }
    let c = contact_start.min(n - 1);
    let base = if c > 0 {
        f[..c].iter().sum::<f64>() / c as f64
    } else {
        0.0
    };
    let spread = if c > 1 {
        (f[..c].iter().map(|v| (v - base).powi(2)).sum::<f64>() / c as f64).sqrt()
    } else {
        0.0
    };
    let x_max = d[..n].iter().map(|v| v - d[c]).fold(0.0f64, f64::max);
    let y_max = f[..n].iter().map(|v| v - base).fold(0.0f64, f64::max);
    // Each scaled to its largest value (0 where that is not positive), by the reciprocal.
    let inverse = |m: f64| if m > 0.0 { 1.0 / m } else { 0.0 };
    let (x_inv, y_inv) = (inverse(x_max), inverse(y_max));
    let mut best = (0, f64::NEG_INFINITY);
    for k in 0..n {
        let x = ((d[k] - d[c]) * x_inv).max(0.0);
        let y_raw = f[k] - base;
        // Forces within the baseline's spread count as zero.
        let y = if y_raw < spread {
            0.0
        } else {
            (y_raw * y_inv).max(0.0)
        };
        let r = x * x + y * y;
        if r > best.1 {
            best = (k, r);
        }
    }
    best.0
}

/// The rows a fit of `segment` takes, of a curve of `n` rows turning at row `turn` whose contact
/// starts at row `contact_start`: every row, the approach before the turn (the turning row
/// counts to the retract, as in nanite's split), or the retract from the turn with the
/// approach's out-of-contact rows before the contact (for the baseline).
fn fitted_rows(n: usize, segment: SegmentChoice, turn: usize, contact_start: usize) -> Vec<usize> {
    match segment {
        SegmentChoice::Both => (0..n).collect(),
        SegmentChoice::Approach => (0..turn.max(1)).collect(),
        SegmentChoice::Retract => (0..contact_start.min(turn)).chain(turn..n).collect(),
    }
}

/// Fit w and ℰ to the in-contact rows of a curve (appendix A.4), with the contact point and
/// the baseline free; see [`fit_with`].
///
/// # Errors
/// As [`fit_with`].
pub fn fit_curve(
    curve: &Curve,
    path: &Path,
    radius: f64,
    spring_constant: Option<f64>,
    model: Option<FitModel>,
) -> Result<FitReport> {
    fit_with(
        curve,
        path,
        &FitSettings {
            radius,
            spring_constant,
            model,
            segment: None,
            poisson: None,
        },
    )
}

/// Fit a contact model to a measured cycle with the contact point and the force baseline free
/// ([`engine::fit`]): the in-contact rows are found from the deviation from the baseline
/// ([`detect_contact`]), the chosen segment's rows are fitted (the retract with the approach's
/// out-of-contact rows, the approach, or both), and the instabilities of JKR and of the
/// machine-stiffness model are predicted at the fitted values (Sec. 2.4).
///
/// # Errors
/// [`Error::DataFile`] for too few in-contact points or data that cannot be fitted (naming the
/// file); [`Error::InvalidParameter`] for a bad radius, spring constant, Poisson's ratio or
/// model choice.
pub fn fit_with(curve: &Curve, path: &Path, settings: &FitSettings) -> Result<FitReport> {
    let radius = settings.radius;
    if !(radius.is_finite() && (TIP_RADIUS_RANGE.0..=TIP_RADIUS_RANGE.1).contains(&radius)) {
        return Err(Error::invalid(
            "tip-radius",
            crate::params::fmt_sig(radius),
            format!(
                "must lie in [{}, {}] m",
                crate::params::fmt_sig(TIP_RADIUS_RANGE.0),
                crate::params::fmt_sig(TIP_RADIUS_RANGE.1)
            ),
        ));
    }
    if let Some(k) = settings.spring_constant
        && !(k.is_finite() && (SPRING_CONSTANT_RANGE.0..=SPRING_CONSTANT_RANGE.1).contains(&k))
    {
        return Err(Error::invalid(
            "spring-constant",
            crate::params::fmt_sig(k),
            format!(
                "must lie in [{}, {}] N/m",
                crate::params::fmt_sig(SPRING_CONSTANT_RANGE.0),
                crate::params::fmt_sig(SPRING_CONSTANT_RANGE.1)
            ),
        ));
    }
    if let Some(nu) = settings.poisson
        && !(nu.is_finite() && (-1.0..0.5 + 1e-12).contains(&nu))
    {
        return Err(Error::invalid("poisson", nu, "must lie in [-1, 0.5]"));
    }
    let model = match (settings.model, settings.spring_constant) {
        (Some(FitModel::MachineStiffness), None) => {
            return Err(Error::invalid(
                "model",
                "machine-stiffness",
                "needs --spring-constant (N/m)",
            ));
        }
        (Some(m), _) => m,
        (None, Some(_)) => FitModel::MachineStiffness,
        (None, None) => FitModel::Jkr,
    };
    let segment = settings.segment.unwrap_or(model.default_segment());
    // Hertz's contact is where its fitted contact point puts it: the detection (which needs the
    // force 8σ above the baseline) only supplies the noise level and the turning row, so a noisy
    // curve whose force rises little above its noise is fitted, with the warnings that say how
    // well (a JPK QI curve of 15 rows in contact and a force 10σ at most).
    let adhesive = model.contact_model().adhesive();
    let (range, contact_detection) = detect_contact(curve, path, if adhesive { 10 } else { 0 })?;
    let turn = turning_row(curve, range.start);
    // Rows fitted: (row, in contact).
    let rows = fitted_rows(curve.depth.len(), segment, turn, range.start);
    let depth: Vec<f64> = rows.iter().map(|&k| curve.depth[k]).collect();
    let force: Vec<f64> = rows.iter().map(|&k| curve.force[k]).collect();
    let in_contact: Vec<bool> = rows.iter().map(|k| range.contains(k)).collect();
    let used_contact: Vec<usize> = rows.iter().copied().filter(|k| range.contains(k)).collect();
    // The fitted segment's in-contact rows must be able to determine the model (the other
    // segment may hold what this fit does not use, such as a retract baseline that drifted).
    if let (Some(&a), Some(&b)) = (used_contact.first(), used_contact.last()) {
        let (h, p): (Vec<f64>, Vec<f64>) = used_contact
            .iter()
            .map(|&k| (curve.depth[k], curve.force[k]))
            .unzip();
        check_meaningful_data(&h, &p, path, (curve.lines[a], curve.lines[b]))?;
    }
    if adhesive && used_contact.len() < 5 {
        return Err(Error::data_file(
            path,
            curve.lines[range.start],
            format!(
                "only {} in-contact row(s) in the {} segment: choose another with --segment",
                used_contact.len(),
                serde_json::to_value(segment)
                    .ok()
                    .and_then(|v| v.as_str().map(String::from))
                    .unwrap_or_default()
            ),
        ));
    }
    let first_line = used_contact
        .first()
        .or(rows.first())
        .map_or(0, |&k| curve.lines[k]);
    let data = engine::FitData {
        depth: &depth,
        force: &force,
        in_contact: &in_contact,
        noise: contact_detection.noise_n,
    };
    let fit = engine::fit(model.contact_model(), radius, &data).map_err(|e| match e {
        Error::Unresolvable { reason, .. } => Error::data_file(path, first_line, reason),
        other => other,
    })?;
    // Hertz's rows in contact are those past its fitted contact point.
    let used_contact: Vec<usize> = if !adhesive {
        rows.iter()
            .copied()
            .filter(|&k| curve.depth[k] > fit.contact_point)
            .collect()
    } else {
        used_contact
    };
    let lines_used = match (used_contact.first(), used_contact.last()) {
        (Some(&a), Some(&b)) => (curve.lines[a], curve.lines[b]),
        _ => (first_line, first_line),
    };
    let warnings = engine::warnings(&fit, &data);
    let (w, e) = (fit.work_of_adhesion, fit.modulus);
    let se = &fit.std_errors;
    let (w_est, e_est, dc_est, f0_est) = if adhesive {
        (
            Some(Estimate {
                value: w,
                std_error: se[0],
            }),
            Estimate {
                value: e,
                std_error: se[1],
            },
            Estimate {
                value: fit.contact_point,
                std_error: se[2],
            },
            Estimate {
                value: fit.baseline,
                std_error: se[3],
            },
        )
    } else {
        (
            None,
            Estimate {
                value: e,
                std_error: se[0],
            },
            Estimate {
                value: fit.contact_point,
                std_error: se[1],
            },
            Estimate {
                value: fit.baseline,
                std_error: se[2],
            },
        )
    };
    let names = model.contact_model().parameter_names();
    let np = names.len();
    let correlation = Correlation {
        parameters: names.iter().map(|s| s.to_string()).collect(),
        matrix: (0..np)
            .map(|i| fit.correlation[i * np..(i + 1) * np].to_vec())
            .collect(),
    };
    let (jkr, alpha, machine) = if adhesive {
        let x_for = |k: f64| Experiment::new(TipGeometry::Sphere { radius }, e, w, k);
        let jkr_pred = jkr_predictions(&x_for(1.0)?)?;
        let jkr = InstabilityReport {
            pull_in_force_n: jkr_pred.pull_in_force,
            pull_in_depth_jump_m: 0.0,
            pull_off_force_n: jkr_pred.pull_off_force,
            pull_off_depth_jump_m: 0.0,
            pull_off_depth_m: jkr_pred.pull_off_depth,
        };
        let (alpha, machine) = match settings.spring_constant {
            Some(k) if matches!(model, FitModel::Jkr | FitModel::MachineStiffness) => {
                let x = x_for(k)?;
                let (pull_in, pull_off) = x.instabilities()?;
                let rep = |i: &Instability, o: &Instability| InstabilityReport {
                    pull_in_force_n: i.after.force,
                    pull_in_depth_jump_m: i.depth_jump(),
                    pull_off_force_n: o.before.force,
                    pull_off_depth_jump_m: o.depth_jump(),
                    pull_off_depth_m: o.before.h,
                };
                (Some(x.alpha()), Some(rep(&pull_in, &pull_off)))
            }
            _ => (None, None),
        };
        (Some(jkr), alpha, machine)
    } else {
        (None, None, None)
    };
    let min_of = |it: &mut dyn Iterator<Item = &f64>| it.copied().fold(f64::INFINITY, f64::min);
    let measured_pull_off = min_of(&mut curve.force[turn..].iter()) - fit.baseline;
    let measured_min = min_of(&mut curve.force.iter()) - fit.baseline;
    let young = settings.poisson.map(|nu| Estimate {
        value: e * (1.0 - nu * nu),
        std_error: e_est.std_error * (1.0 - nu * nu),
    });
    Ok(FitReport {
        file: path.display().to_string(),
        tip_radius_m: radius,
        model,
        segment,
        work_of_adhesion_j_per_m2: w_est,
        plane_strain_modulus_pa: e_est,
        plane_strain_modulus_interval_pa: fit.modulus_interval,
        youngs_modulus_pa: young,
        poisson_ratio: settings.poisson,
        contact_point_m: dc_est,
        baseline_n: f0_est,
        interaction_range_m: fit.interaction_range.map(|z| Estimate {
            value: z,
            std_error: se[4],
        }),
        maugis_lambda: fit.interaction_range.map(|z| {
            let pi = std::f64::consts::PI;
            crate::models::maugis_dugdale::maugis_lambda(w / (e * z), pi * w / (e * radius))
        }),
        correlation,
        rms_residual_n: fit.rms_residual,
        points_total: curve.depth.len(),
        points_used: rows.len(),
        points_in_contact: used_contact.len(),
        lines_used,
        contact_rows: (range.start, range.end),
        turning_row: turn,
        contact_detection,
        warnings,
        iterations: fit.iterations,
        spring_constant_n_per_m: settings.spring_constant,
        alpha,
        machine_stiffness: machine,
        jkr,
        measured_pull_off_force_n: measured_pull_off,
        measured_min_force_n: measured_min,
    })
}

/// The figure of a fit: (a) the measured points (the fitted in-contact rows highlighted) in the
/// fitted frame (indentation δ = d − d_c, force P − F₀) over the model's P-δ curve at the fitted
/// parameters (for the adhesive models, JKR and, with k_s, the machine-stiffness model with their
/// jumps); (b) the force residuals of the fitted rows, in nm and nN.
///
/// # Errors
/// Model errors.
pub fn fit_figure(curve: &Curve, report: &FitReport) -> Result<Figure> {
    let radius = report.tip_radius_m;
    let e = report.plane_strain_modulus_pa.value;
    let dc = report.contact_point_m.value;
    let f0 = report.baseline_n.value;
    let h_max = curve.depth.iter().copied().fold(f64::NEG_INFINITY, f64::max) - dc;
    let mut panel = match report.work_of_adhesion_j_per_m2 {
        Some(w) if matches!(report.model, FitModel::Jkr | FitModel::MachineStiffness) => {
            let k = report.spring_constant_n_per_m.unwrap_or(1.0);
            let x = Experiment::new(TipGeometry::Sphere { radius }, e, w.value, k)?;
            let depth_norm = (h_max / x.scales().h).max(1.0) * 1.05;
            let mut panel = ph_panel(&x, "(a)", "fit of the measured curve", depth_norm, 300)?;
            if report.spring_constant_n_per_m.is_none() {
                // Without k_s the machine-stiffness jumps are not known: keep JKR only.
                panel.series.retain(|s| s.name.starts_with("JKR"));
                panel.markers.retain(|m| m.name.contains("JKR"));
            }
            panel
        }
        _ => {
            // The model in the figure's frame: depth from the contact point, force less F₀.
            let fit = engine::EngineFit {
                contact_point: 0.0,
                baseline: 0.0,
                deepest: h_max,
                ..fitted_model(curve, report)
            };
            let n = 300;
            let depths: Vec<(f64, bool)> = (0..=n)
                .map(|i| (h_max.max(0.0) * 1.05 * i as f64 / n as f64, true))
                .collect();
            let pts = depths
                .iter()
                .zip(fit.forces_at(radius, &depths))
                .map(|(&(d, _), p)| (d * 1e9, p * 1e9))
                .collect();
            let name = match report.model {
                FitModel::Hertz => "Hertz",
                FitModel::Dmt => "DMT",
                _ => "Maugis-Dugdale",
            };
            let mut panel = crate::figure::Panel::new(
                Axis::linear("Indentation depth h", "nm"),
                Axis::linear("Force P", "nN"),
            )
            .titled("(a)", "fit of the measured curve");
            panel.add(Series::new(name, Style::Stable, pts));
            panel
        }
    };
    let pts: Vec<(f64, f64)> = curve
        .depth
        .iter()
        .zip(&curve.force)
        .map(|(h, p)| ((h - dc) * 1e9, (p - f0) * 1e9))
        .collect();
    let used = report.lines_used;
    let in_contact: Vec<(f64, f64)> = curve
        .lines
        .iter()
        .zip(&pts)
        .filter(|(l, _)| **l >= used.0 && **l <= used.1)
        .map(|(_, p)| *p)
        .collect();
    panel
        .series
        .insert(0, Series::new("measured", Style::Scatter, pts).with_color(7));
    panel.series.insert(
        1,
        Series::new("measured, fitted in contact", Style::Scatter, in_contact).with_color(2),
    );
    panel.x = Axis::linear("Indentation depth h = d − d_c", "nm");
    panel.y = Axis::linear("Force P − F_0", "nN");
    // Both models share the P-h relation in contact: the JKR curve lies on the model's.
    panel.mark_coinciding(crate::figure::COINCIDENCE_TOL);
    let residual_panel = residual_panel(curve, report)?;
    let mut fig = Figure::new("fit", "Fit of a measured force-indentation curve")
        .with_panel(panel)
        .with_panel(residual_panel);
    record_results(&mut fig, report);
    let n = crate::figure::number;
    let modulus = format!(
        "plane-strain modulus = {} ± {} Pa, contact point {} ± {} nm",
        n(e, 5),
        n(report.plane_strain_modulus_pa.std_error, 3),
        n(dc * 1e9, 3),
        n(report.contact_point_m.std_error * 1e9, 2),
    );
    fig.note(match report.work_of_adhesion_j_per_m2 {
        Some(w) => format!(
            "w = {} ± {} J/m², {modulus}, {} rows fitted, {} in contact",
            n(w.value, 5),
            n(w.std_error, 3),
            report.points_used,
            report.points_in_contact
        ),
        None => format!("{modulus}, {} rows fitted", report.points_used),
    });
    fig.note(format!(
        "in-contact rows found by {}",
        report.contact_detection.method
    ));
    for w in &report.warnings {
        fig.note(format!("warning: {w}"));
    }
    Ok(fig)
}

/// The named results of a fit recorded on its figure (SI, names ending in their unit).
fn record_results(fig: &mut Figure, report: &FitReport) {
    if let Some(w) = report.work_of_adhesion_j_per_m2 {
        fig.result("work_of_adhesion_J_per_m2", w.value);
        fig.result("work_of_adhesion_std_error_J_per_m2", w.std_error);
    }
    fig.result("plane_strain_modulus_Pa", report.plane_strain_modulus_pa.value);
    fig.result(
        "plane_strain_modulus_std_error_Pa",
        report.plane_strain_modulus_pa.std_error,
    );
    fig.result("contact_point_m", report.contact_point_m.value);
    fig.result("contact_point_std_error_m", report.contact_point_m.std_error);
    fig.result("baseline_N", report.baseline_n.value);
    fig.result("rms_residual_N", report.rms_residual_n);
    fig.result("measured_pull_off_force_N", report.measured_pull_off_force_n);
    fig.result("points_used_count", report.points_used as f64);
}

/// The fitted model of a report in the data's depth origin, as [`engine::fit`] returned it (less
/// its statistics).
fn fitted_model(curve: &Curve, report: &FitReport) -> engine::EngineFit {
    engine::EngineFit {
        model: report.model.contact_model(),
        work_of_adhesion: report.work_of_adhesion_j_per_m2.map_or(0.0, |w| w.value),
        modulus: report.plane_strain_modulus_pa.value,
        contact_point: report.contact_point_m.value,
        baseline: report.baseline_n.value,
        interaction_range: report.interaction_range_m.map(|z| z.value),
        deepest: curve.depth.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        std_errors: Vec::new(),
        correlation: Vec::new(),
        rms_residual: 0.0,
        iterations: 0,
        modulus_interval: None,
    }
}

/// Panel (b) of [`fit_figure`]: the force residual (model − measured) of every fitted row
/// against its indentation.
fn residual_panel(curve: &Curve, report: &FitReport) -> Result<crate::figure::Panel> {
    let fit = fitted_model(curve, report);
    let (c0, c1) = report.contact_rows;
    let rows = fitted_rows(curve.depth.len(), report.segment, report.turning_row, c0);
    let at: Vec<(f64, bool)> = rows
        .iter()
        .map(|&k| (curve.depth[k], (c0..c1).contains(&k)))
        .collect();
    let model = fit.forces_at(report.tip_radius_m, &at);
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .zip(&at)
        .zip(model)
        .map(|((&k, &(d, _)), p)| ((d - fit.contact_point) * 1e9, (p - curve.force[k]) * 1e9))
        .collect();
    let mut panel = crate::figure::Panel::new(
        Axis::linear("Indentation depth h = d − d_c", "nm"),
        Axis::linear("Residual, model − measured", "nN"),
    )
    .titled("(b)", "residuals of the fitted rows");
    panel.add(Series::new("residual", Style::Scatter, pts).with_color(2));
    Ok(panel)
}

/// A noise-free cycle in displacement control as an experiment records it (approach, contact,
/// retract), from the machine-stiffness model (Sec. 2.3.1): the states followed from stage
/// displacement `delta_min` to `delta_max` [m] and back, as (depth, force) rows with `samples`
/// samples per branch. Useful to test fits and as a template of the input format.
///
/// # Errors
/// Model errors; a range that does not contain the loop.
pub fn simulate_cycle(x: &Experiment, delta_min: f64, delta_max: f64, samples: usize) -> Result<Curve> {
    let m = x.model()?;
    let sc = x.scales();
    let cycle = m.cycle(delta_min / sc.h, delta_max / sc.h, samples, 1e-14)?;
    let mut curve = Curve::default();
    for s in cycle.loading.iter().chain(&cycle.unloading) {
        let si = x.to_si(*s);
        curve.depth.push(si.h);
        curve.force.push(si.force);
        curve.lines.push(curve.lines.len() + 2);
    }
    Ok(curve)
}

/// Whether a file's bytes are a depth/force CSV of [`parse_curve`]'s format: UTF-8 text whose
/// first line that is neither empty nor a comment names a depth and a force column.
pub fn looks_like_curve_csv(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1 << 16)];
    let text = match std::str::from_utf8(head) {
        Ok(t) => t,
        Err(e) if e.error_len().is_none() => std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or(""),
        Err(_) => return false,
    };
    let text = crate::params::normalise_line_ends(text);
    let Some(header) = text
        .lines()
        .map(|l| l.trim_start_matches('\u{feff}').trim())
        .find(|l| !l.is_empty() && !l.starts_with('#'))
    else {
        return false;
    };
    let names: Vec<String> = split_row(header).iter().map(|c| name_and_unit(c).0).collect();
    names.iter().any(|n| DEPTH_NAMES.contains(&n.as_str()))
        && names.iter().any(|n| FORCE_NAMES.contains(&n.as_str()))
}

/// The JSON of the fit of one curve of an instrument file: the fit's report with the file's
/// format, the curve's place and the preprocessing.
#[derive(Debug, Serialize)]
struct InstrumentFitJson<'a> {
    format: &'a str,
    #[serde(flatten)]
    curve: &'a instrument::CurveFit,
}

/// The JSON of a force map's fits.
#[derive(Debug, Serialize)]
struct MapJson<'a> {
    file: String,
    format: &'a str,
    model: FitModel,
    tip_radius_m: f64,
    curves: usize,
    fitted: usize,
    failed: Vec<map::Failure>,
    layout: map::Layout,
    fits: Vec<&'a instrument::CurveFit>,
}

/// The `--fit` command: read, fit, and write `DIR/fit.json`, `fit.png`, `fit.svg`, `fit.csv`
/// (one curve), or `DIR/fit-map.json`, `.png`, `.svg`, `.csv` (a file of many curves: the maps,
/// and one CSV row per curve). Everything is computed and rendered before the first file is
/// written.
///
/// # Errors
/// Bad input (one line naming the file and line or curve), fit failures (of a single curve),
/// I/O.
pub fn command(args: &FitArgs, out: &Path) -> Result<Vec<PathBuf>> {
    let path = args
        .fit
        .as_deref()
        .ok_or_else(|| Error::invalid("fit", "", "give the file of a measured curve"))?;
    let radius = args
        .tip_radius
        .ok_or_else(|| Error::invalid("tip-radius", "", "--fit needs --tip-radius (metres)"))?;
    let settings = FitSettings {
        radius,
        spring_constant: args.spring_constant,
        model: args.model,
        segment: args.segment,
        poisson: args.poisson,
    };
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    let files: Vec<(PathBuf, Vec<u8>)> = if looks_like_curve_csv(&bytes) {
        if args.curve.is_some() || args.baseline_tilt || args.sensitivity.is_some() {
            return Err(Error::Usage(
                "--curve, --baseline-tilt and --sensitivity apply to instrument files, not to a depth/force CSV".into(),
            ));
        }
        let text = String::from_utf8(bytes).map_err(|_| Error::data_file(path, 0, "not UTF-8 text"))?;
        let curve = parse_curve(&text, path)?;
        let report = fit_with(&curve, path, &settings)?;
        for w in &report.warnings {
            eprintln!("warning: {}: {w}", path.display());
        }
        let fig = fit_figure(&curve, &report)?;
        let json =
            serde_json::to_string_pretty(&report).expect("the report has finite numbers and string keys");
        fit_files(out, "fit", &fig, json)?
    } else {
        let file = crate::readers::parse_force_bytes(
            &bytes,
            path,
            &crate::readers::ReadOptions {
                spring_constant: args.spring_constant,
                sensitivity: args.sensitivity,
            },
        )?;
        if let Some(k) = args.spring_constant {
            eprintln!(
                "note: {}: spring constant {} N/m from --spring-constant, not the file's",
                path.display(),
                crate::params::fmt_sig(k)
            );
        }
        let opts = instrument::PrepareOptions {
            spring_constant: None,
            baseline_tilt: args.baseline_tilt,
        };
        let curves: Vec<crate::readers::ForceCurve> = match args.curve {
            Some(i) => match file.curves.get(i) {
                Some(c) => vec![c.clone()],
                None => {
                    return Err(Error::invalid(
                        "curve",
                        i,
                        format!("the file holds {} curve(s), indexed from 0", file.curves.len()),
                    ));
                }
            },
            None => file.curves.clone(),
        };
        if curves.is_empty() {
            return Err(Error::data_file(path, 0, "the file holds no curve"));
        }
        if curves.len() == 1 {
            let (curve, fit) = instrument::fit_curve(&curves[0], path, &opts, &settings)?;
            for w in &fit.fit.warnings {
                eprintln!("warning: {} (curve {}): {w}", path.display(), fit.curve);
            }
            let mut fig = fit_figure(&curve, &fit.fit)?;
            fig.note(format!("{}, curve {}", file.format, fit.curve));
            let json = serde_json::to_string_pretty(&InstrumentFitJson {
                format: &file.format,
                curve: &fit,
            })
            .expect("the report has finite numbers and string keys");
            fit_files(out, "fit", &fig, json)?
        } else {
            let fits = instrument::fit_all(&curves, path, &opts, &settings);
            let mut failed = Vec::new();
            for (c, f) in curves.iter().zip(&fits) {
                match f {
                    Err(e) => {
                        eprintln!("error: {}: curve {} not fitted: {e}", path.display(), c.index);
                        failed.push(map::Failure {
                            curve: c.index,
                            grid_index: c.meta.grid_index,
                            reason: e.to_string(),
                        });
                    }
                    Ok(f) if !f.fit.warnings.is_empty() => {
                        eprintln!(
                            "warning: {} (curve {}): {}",
                            path.display(),
                            c.index,
                            f.fit.warnings.join("; ")
                        );
                    }
                    Ok(_) => {}
                }
            }
            let title = format!("Fits of a force map ({}, {} curves)", file.format, curves.len());
            let lay = map::layout(&curves);
            let fig = map::map_figure(&lay, &fits, &title)?;
            let ok: Vec<&instrument::CurveFit> = fits.iter().filter_map(|f| f.as_ref().ok()).collect();
            let model = ok
                .first()
                .map_or(settings.model.unwrap_or(FitModel::MachineStiffness), |f| {
                    f.fit.model
                });
            let json = serde_json::to_string_pretty(&MapJson {
                file: path.display().to_string(),
                format: &file.format,
                model,
                tip_radius_m: radius,
                curves: curves.len(),
                fitted: ok.len(),
                failed,
                layout: lay.clone(),
                fits: ok,
            })
            .expect("the report has finite numbers and string keys");
            let mut files = vec![
                (out.join("fit-map.png"), crate::render::plot::png_bytes(&fig)?),
                (
                    out.join("fit-map.svg"),
                    crate::render::plot::svg_string(&fig)?.into_bytes(),
                ),
                (
                    out.join("fit-map.csv"),
                    map::table_csv(&curves, &lay, &fits).into_bytes(),
                ),
            ];
            files.push((out.join("fit-map.json"), json.into_bytes()));
            files
        }
    };
    std::fs::create_dir_all(out).map_err(Error::file("creating the folder", out))?;
    crate::render::write_set(&files)?;
    Ok(files.into_iter().map(|(p, _)| p).collect())
}

/// The rendered files of one fit's figure: `<stem>.png`, `.svg`, `.csv` and `.json`.
fn fit_files(out: &Path, stem: &str, fig: &Figure, json: String) -> Result<Vec<(PathBuf, Vec<u8>)>> {
    Ok(vec![
        (
            out.join(format!("{stem}.png")),
            crate::render::plot::png_bytes(fig)?,
        ),
        (
            out.join(format!("{stem}.svg")),
            crate::render::plot::svg_string(fig)?.into_bytes(),
        ),
        (
            out.join(format!("{stem}.csv")),
            crate::render::data::csv(fig).into_bytes(),
        ),
        (out.join(format!("{stem}.json")), json.into_bytes()),
    ])
}
