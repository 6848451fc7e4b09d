//! Measured force curves from instrument files ([`crate::readers`]) prepared for the fit as AFM
//! practice has it (nanite's order of steps), each step and its values recorded:
//!
//! 1. **Force baseline**: the offset (and with `--baseline-tilt` the slope against the height)
//!    of the approach's out-of-contact rows, removed from every row. The baseline rows are found
//!    as [`super::detect_contact`] finds them: from the start of the approach while the force
//!    stays within the noise of its first rows.
//! 2. **Tip position** z_tip = z + F/k_s from the cantilever height z (the measured height where
//!    the file has one, else the piezo height) and the baseline-corrected force F, with the
//!    spring constant k_s of the file or of `--spring-constant`; the depth into the sample is
//!    d = −z_tip (its origin arbitrary: the contact point is fitted). nanite computes the tip
//!    position before removing the offset, which moves its contact point by F₀/k_s and changes
//!    nothing else; here the deflection is counted from the free cantilever.
//! 3. **Initial contact point**: the depth of the first approach row after the baseline.
//! 4. **Approach/retract split**: the approach rows, then the retract rows (pauses are left
//!    out); the fit takes the segment chosen by `--segment`.
//!
//! Then [`super::fit_with`] fits the model with the contact point and the baseline free.

use std::path::Path;

use rayon::prelude::*;
use serde::Serialize;

use super::{Curve, FitReport, FitSettings, fit_with};
use crate::error::{Error, Result};
use crate::readers::{ForceCurve, Segment, SegmentKind};

/// What the preprocessing did to one curve (written to the JSON).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Preprocessing {
    /// Spring constant used [N/m].
    pub spring_constant_n_per_m: f64,
    /// Where it came from: "file", or "--spring-constant (the file says X N/m)".
    pub spring_constant_source: String,
    /// The height channel of step 1: "height (measured)" or "height (piezo)".
    pub height_channel: String,
    /// Rows of the approach and of the retract taken (pauses are left out).
    pub approach_rows: usize,
    /// Rows of the retract taken.
    pub retract_rows: usize,
    /// Rows of the approach's baseline (step 2).
    pub baseline_rows: usize,
    /// Force offset removed [N] (the baseline's median).
    pub baseline_offset_n: f64,
    /// Baseline slope removed against the tip position [N/m] (with `--baseline-tilt`).
    pub baseline_tilt_n_per_m: Option<f64>,
    /// Noise level of the baseline [N].
    pub baseline_noise_n: f64,
    /// Initial contact point (step 3), as a depth d [m].
    pub initial_contact_point_m: Option<f64>,
}

/// Options of the preparation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PrepareOptions {
    /// Spring constant [N/m] overriding the file's.
    pub spring_constant: Option<f64>,
    /// Remove the baseline's slope as well as its offset.
    pub baseline_tilt: bool,
}

/// The segments of a curve as (approach, retract): the first approach segment and the first
/// retract segment after it. A segment without a kind is classed by its height's direction
/// (falling towards the sample: approach).
fn approach_and_retract(curve: &ForceCurve) -> (Option<&Segment>, Option<&Segment>) {
    let kind = |s: &Segment| -> Option<SegmentKind> {
        if let Some(k) = &s.kind {
            return Some(k.clone());
        }
        let h = s.height()?;
        let (first, last) = (*h.first()?, *h.last()?);
        if last < first {
            Some(SegmentKind::Approach)
        } else if last > first {
            Some(SegmentKind::Retract)
        } else {
            Some(SegmentKind::Pause)
        }
    };
    let ia = curve
        .segments
        .iter()
        .position(|s| kind(s) == Some(SegmentKind::Approach));
    let start = ia.map_or(0, |i| i + 1);
    let ir = curve.segments[start.min(curve.segments.len())..]
        .iter()
        .position(|s| kind(s) == Some(SegmentKind::Retract))
        .map(|i| i + start);
    (ia.map(|i| &curve.segments[i]), ir.map(|i| &curve.segments[i]))
}

/// Prepare one curve of an instrument file for the fit (steps 1-4 of the module doc). The
/// rows' "lines" are their 1-based sample numbers in the curve (approach first).
///
/// # Errors
/// [`Error::DataFile`] naming the file and curve: no spring constant (naming
/// `--spring-constant`), no height channel, no approach and no retract segment, channels of
/// unequal length, non-finite samples.
pub fn prepare(curve: &ForceCurve, path: &Path, opts: &PrepareOptions) -> Result<(Curve, Preprocessing)> {
    let at = |msg: String| Error::data_file(path, 0, format!("curve {}: {msg}", curve.index));
    let (k, source) = match (opts.spring_constant, curve.meta.spring_constant) {
        (Some(k), None) => (k, "--spring-constant (the file has none)".to_string()),
        (Some(k), Some(f)) => (
            k,
            format!(
                "--spring-constant (the file says {} N/m)",
                crate::params::fmt_sig(f)
            ),
        ),
        (None, Some(f)) => (f, "file".to_string()),
        (None, None) => {
            return Err(at(
                "the file gives no spring constant: give it with --spring-constant (N/m)".into(),
            ));
        }
    };
    if !(k.is_finite() && k > 0.0) {
        return Err(Error::invalid("spring-constant", k, "must be positive (N/m)"));
    }
    let (approach, retract) = approach_and_retract(curve);
    let segs: Vec<&Segment> = [approach, retract].into_iter().flatten().collect();
    if segs.is_empty() {
        return Err(at("no approach or retract segment".into()));
    }
    let measured = segs.iter().all(|s| s.height_measured.is_some());
    let channel = if measured {
        "height (measured)"
    } else {
        "height (piezo)"
    };
    let samples: usize = segs.iter().map(|s| s.force.len()).sum();
    let mut height = Vec::with_capacity(samples);
    let mut force = Vec::with_capacity(samples);
    for s in &segs {
        let h = if measured {
            s.height_measured.as_deref()
        } else {
            s.height_piezo.as_deref()
        };
        let Some(h) = h else {
            return Err(at("a segment has no height channel".into()));
        };
        if h.len() != s.force.len() {
            return Err(at(format!(
                "the height channel has {} samples and the force {}",
                h.len(),
                s.force.len()
            )));
        }
        for (&z, &f) in h.iter().zip(&s.force) {
            if !(z.is_finite() && f.is_finite()) {
                return Err(at(format!(
                    "sample {} is not a finite number (height {z}, force {f})",
                    height.len() + 1
                )));
            }
            height.push(z);
            force.push(f);
        }
    }
    let approach_rows = approach.map_or(0, Segment::len);
    let retract_rows = retract.map_or(0, Segment::len);
    // Step 1: the approach's baseline, its offset (and slope against the height) removed, so
    // that the force is the cantilever's deflection from its free state times k_s. With a tilt
    // the baseline is found again on the detilted force (a tilted baseline leaves the band of a
    // level one early), three times.
    let (lo, hi) = force
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| {
            (a.min(*f), b.max(*f))
        });
    let p_max = hi - lo;
    let find = |force: &[f64]| {
        let head = &force[..approach_rows];
        super::baseline(|i| head[i], head.len(), p_max, false)
            .filter(|b| b.0 >= super::MIN_BASELINE_ROWS)
            .unwrap_or((0, 0.0))
    };
    let (mut baseline_rows, mut noise) = find(&force);
    let mut offset = 0.0;
    let mut tilt = None;
    if baseline_rows > 0 && opts.baseline_tilt {
        let raw = force.clone();
        for _ in 0..3 {
            // Least-squares line F = a + b·z over the baseline rows but their last tenth (where
            // a smooth onset of contact, as Hertz's, already bends the curve); out of contact the
            // tip follows the base, so the slope against z is the slope against the tip position.
            let used = (baseline_rows * 9 / 10).max(super::MIN_BASELINE_ROWS.min(baseline_rows));
            let (z, rows) = (&height[..used], &raw[..used]);
            let n = used as f64;
            let (mz, mf) = (z.iter().sum::<f64>() / n, rows.iter().sum::<f64>() / n);
            let szz: f64 = z.iter().map(|x| (x - mz) * (x - mz)).sum();
            let szf: f64 = z.iter().zip(rows).map(|(x, y)| (x - mz) * (y - mf)).sum();
            if szz <= 0.0 {
                break;
            }
            let b = szf / szz;
            tilt = Some(b);
            for ((f, r), z) in force.iter_mut().zip(&raw).zip(&height) {
                *f = r - b * z;
            }
            let (rows_now, noise_now) = find(&force);
            if rows_now <= baseline_rows {
                break;
            }
            (baseline_rows, noise) = (rows_now, noise_now);
        }
    }
    if baseline_rows > 0 {
        let mut rows = force[..baseline_rows].to_vec();
        offset += *rows.select_nth_unstable_by(baseline_rows / 2, f64::total_cmp).1;
    }
    for f in &mut force {
        *f -= offset;
    }
    // Step 2: tip position z + F/k_s; the depth into the sample is its negative.
    let depth: Vec<f64> = height.iter().zip(&force).map(|(z, f)| -(z + f / k)).collect();
    let initial_contact_point =
        (baseline_rows > 0 && baseline_rows < approach_rows).then(|| depth[baseline_rows]);
    let lines = (1..=depth.len()).collect();
    Ok((
        Curve { depth, force, lines },
        Preprocessing {
            spring_constant_n_per_m: k,
            spring_constant_source: source,
            height_channel: channel.into(),
            approach_rows,
            retract_rows,
            baseline_rows,
            baseline_offset_n: offset,
            baseline_tilt_n_per_m: tilt,
            baseline_noise_n: noise,
            initial_contact_point_m: initial_contact_point,
        },
    ))
}

/// The fit of one curve of an instrument file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveFit {
    /// Index of the curve in its file.
    pub curve: usize,
    /// Grid index (x, y) in its map, where the file gives one.
    pub grid_index: Option<[usize; 2]>,
    /// Lateral position [m], where the file gives one.
    pub position_m: Option<[f64; 2]>,
    /// The preprocessing steps.
    pub preprocessing: Preprocessing,
    /// The fit.
    pub fit: FitReport,
}

/// Prepare and fit one curve; `settings.spring_constant` is set to the spring constant used.
///
/// # Errors
/// As [`prepare`] and [`fit_with`].
pub fn fit_curve(
    curve: &ForceCurve,
    path: &Path,
    opts: &PrepareOptions,
    settings: &FitSettings,
) -> Result<(Curve, CurveFit)> {
    let (data, pre) = prepare(curve, path, opts)?;
    let settings = FitSettings {
        spring_constant: Some(pre.spring_constant_n_per_m),
        ..*settings
    };
    let fit = fit_with(&data, path, &settings).map_err(|e| match e {
        Error::DataFile { path, line, message } if line > 0 => Error::DataFile {
            path,
            line: 0,
            message: format!("curve {}, sample {line}: {message}", curve.index),
        },
        Error::DataFile { path, line, message } => Error::DataFile {
            path,
            line,
            message: format!("curve {}: {message}", curve.index),
        },
        other => other,
    })?;
    Ok((
        data,
        CurveFit {
            curve: curve.index,
            grid_index: curve.meta.grid_index,
            position_m: curve.meta.position,
            preprocessing: pre,
            fit,
        },
    ))
}

/// Fit every curve of a file in parallel (rayon); each curve's result or its error, in file
/// order.
pub fn fit_all(
    curves: &[ForceCurve],
    path: &Path,
    opts: &PrepareOptions,
    settings: &FitSettings,
) -> Vec<Result<CurveFit>> {
    curves
        .par_iter()
        .map(|c| fit_curve(c, path, opts, settings).map(|(_, f)| f))
        .collect()
}

/// How [`synthetic_curve`] records a cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Synthetic {
    /// Stage displacement where the cycle starts and ends [m] (negative: out of contact).
    pub delta_min: f64,
    /// Deepest stage displacement [m].
    pub delta_max: f64,
    /// Samples per branch.
    pub samples: usize,
    /// The instrument's height offset: the contact point is at height −`depth_offset` [m].
    pub depth_offset: f64,
    /// The instrument's force offset [N].
    pub force_offset: f64,
    /// Standard deviation of the Gaussian force noise [N].
    pub noise: f64,
    /// Seed of the noise.
    pub seed: u64,
}

/// A force curve as an instrument records it, made by the machine-stiffness model (Sec. 2.3.1)
/// for tests, benchmarks and demonstrations: the cycle of [`super::simulate_cycle`] (see
/// [`Synthetic`]), written as the cantilever height z = −d − F/k_s − `depth_offset` and the
/// force plus `force_offset` and seeded Gaussian noise, split at the deepest row into an
/// approach and a retract segment.
///
/// # Errors
/// Model errors; a negative noise level.
pub fn synthetic_curve(
    x: &crate::models::machine_stiffness::Experiment,
    s: &Synthetic,
) -> Result<ForceCurve> {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let c = super::simulate_cycle(x, s.delta_min, s.delta_max, s.samples)?;
    let turn = super::turning_row(&c, 0);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(s.seed);
    let normal = Normal::new(0.0, s.noise).map_err(|e| Error::invalid("noise", s.noise, e.to_string()))?;
    let k = x.spring_constant;
    let mut segs = [Segment::default(), Segment::default()];
    for (i, (d, f)) in c.depth.iter().zip(&c.force).enumerate() {
        let seg = &mut segs[usize::from(i > turn)];
        seg.force.push(f + s.force_offset + normal.sample(&mut rng));
        seg.height_measured
            .get_or_insert_with(Vec::new)
            .push(-d - f / k - s.depth_offset);
    }
    let [mut a, mut r] = segs;
    a.kind = Some(SegmentKind::Approach);
    r.kind = Some(SegmentKind::Retract);
    Ok(ForceCurve {
        index: 0,
        segments: vec![a, r],
        meta: crate::readers::CurveMeta {
            spring_constant: Some(k),
            instrument: Some("synthetic (machine-stiffness model)".into()),
            ..Default::default()
        },
    })
}
