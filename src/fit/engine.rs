//! The fit of a contact model to a force-depth curve with the contact point and the force
//! baseline free, as AFM practice has it: the depth origin of a measured curve is never known
//! (every instrument file carries an offset), so the depth is δ = d − d_c with the contact point
//! d_c a fitted parameter, and the force is P(δ) + F₀ with the baseline F₀ fitted too.
//!
//! Models (spherical tip of radius R, plane-strain modulus ℰ = E/(1−ν²), work of adhesion w):
//! - **Hertz** (1.1): P = (4/3)ℰ√R δ^(3/2) for δ > 0, 0 otherwise, on every row (the curve
//!   leaves the baseline smoothly, as nanite fits it);
//! - **DMT** (1.3): P = (4/3)ℰ√R δ^(3/2) − 2πwR on the in-contact rows;
//! - **JKR** (1.2) = the contact relation (2.31b)-(2.32b) of the machine-stiffness model:
//!   P = P̂(ā³ − 2ā^(3/2)), δ = ĥ(ā² − (4/3)√ā) on the stable branch ā ≥ ā_D, on the
//!   in-contact rows.
//!
//! With adhesion the curve jumps into and out of contact, so which rows are in contact is read
//! from the data (the deviation from the baseline, [`super::detect_contact`]), not from the
//! model: out-of-contact rows are fitted by F₀ alone. This keeps the residuals continuous in
//! the parameters. For Hertz the contact point is found by profiling: for each trial d_c the
//! model is linear in (ℰ, F₀), solved in closed form; the best d_c on a scan and a golden-section
//! refinement start the joint Levenberg-Marquardt fit. JKR and DMT start from the shape of the
//! curve (the zero crossing, the deepest point and the force minimum) and keep the best of a
//! few starts.
//!
//! All parameters are reported with standard errors and their correlation matrix; warnings say
//! when a parameter is not determined (correlation above 0.99, standard error over half the
//! value, the contact point at the edge of the data, residuals far above the baseline noise).

use serde::Serialize;

use crate::error::{Error, Result};
use crate::models::machine_stiffness::{sphere_depth_minimum_radius, sphere_radius_at_depth};
use crate::numerics::least_squares::{LmOptions, LmSolution, levenberg_marquardt};

/// The contact model of a fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactModel {
    /// Hertz (1.1): no adhesion.
    Hertz,
    /// DMT (1.3): Hertz shifted by the pull-off force −2πwR.
    Dmt,
    /// JKR (1.2), the contact relation (2.31b)-(2.32b) of the machine-stiffness model.
    Jkr,
}

impl ContactModel {
    /// Whether the model has a work of adhesion.
    pub fn adhesive(self) -> bool {
        !matches!(self, ContactModel::Hertz)
    }

    /// The names of the fitted parameters, in the order of [`EngineFit::x`].
    pub fn parameter_names(self) -> &'static [&'static str] {
        match self {
            ContactModel::Hertz => &["plane_strain_modulus", "contact_point", "baseline"],
            _ => &[
                "work_of_adhesion",
                "plane_strain_modulus",
                "contact_point",
                "baseline",
            ],
        }
    }
}

/// The data of a fit: depth d (positive into the sample, arbitrary origin) and force P
/// (positive in compression) of each row, and which rows the data show in contact.
#[derive(Debug, Clone, Copy)]
pub struct FitData<'a> {
    /// Depth d [m], any origin.
    pub depth: &'a [f64],
    /// Force P [N].
    pub force: &'a [f64],
    /// Rows in contact as the data show them (used by the adhesive models).
    pub in_contact: &'a [bool],
    /// Noise level of the baseline [N] (0 if unknown).
    pub noise: f64,
}

/// The result of [`fit`], SI.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineFit {
    /// The model.
    pub model: ContactModel,
    /// Work of adhesion w [J/m²] (0 for Hertz).
    pub work_of_adhesion: f64,
    /// Plane-strain modulus ℰ [Pa].
    pub modulus: f64,
    /// Contact point d_c [m] in the data's depth origin.
    pub contact_point: f64,
    /// Baseline F₀ [N].
    pub baseline: f64,
    /// Standard errors in the order of [`ContactModel::parameter_names`] (SI).
    pub std_errors: Vec<f64>,
    /// Correlation matrix (row-major) in the same order.
    pub correlation: Vec<f64>,
    /// Root-mean-square force residual [N].
    pub rms_residual: f64,
    /// Levenberg-Marquardt iterations of the kept start.
    pub iterations: usize,
}

impl EngineFit {
    /// The model force P(δ) + F₀ at depth `d` (data origin) for a row in contact or not.
    pub fn force_at(&self, radius: f64, d: f64, in_contact: bool) -> f64 {
        let p = Params {
            w: self.work_of_adhesion,
            e: self.modulus,
            dc: self.contact_point,
        };
        self.baseline + model_force(self.model, radius, &p, d, in_contact).0
    }
}

#[derive(Debug, Clone, Copy)]
struct Params {
    w: f64,
    e: f64,
    dc: f64,
}

/// The model force without baseline at depth `d` and its derivatives (∂P/∂ln w, ∂P/∂ln ℰ,
/// ∂P/∂d_c).
fn model_force(model: ContactModel, radius: f64, p: &Params, d: f64, in_contact: bool) -> (f64, [f64; 3]) {
    let delta = d - p.dc;
    match model {
        ContactModel::Hertz => {
            if delta <= 0.0 {
                return (0.0, [0.0; 3]);
            }
            let c = 4.0 / 3.0 * p.e * radius.sqrt();
            let f = c * delta.powf(1.5);
            (f, [0.0, f, -1.5 * c * delta.sqrt()])
        }
        ContactModel::Dmt => {
            if !in_contact {
                return (0.0, [0.0; 3]);
            }
            let adh = 2.0 * std::f64::consts::PI * p.w * radius;
            let dp = delta.max(0.0);
            let c = 4.0 / 3.0 * p.e * radius.sqrt();
            let f = c * dp.powf(1.5);
            (f - adh, [-adh, f, -1.5 * c * dp.sqrt()])
        }
        ContactModel::Jkr => {
            if !in_contact {
                return (0.0, [0.0; 3]);
            }
            // P̂ = 3πwR/2, â = (9πwR²/8ℰ)^(1/3), ĥ = â²/R (Sec. 2.3).
            let pi = std::f64::consts::PI;
            let p_hat = 1.5 * pi * p.w * radius;
            let a_hat = (9.0 * pi * p.w * radius * radius / (8.0 * p.e)).cbrt();
            let h_hat = a_hat * a_hat / radius;
            let hb = delta / h_hat;
            let a = sphere_radius_at_depth(hb);
            let pb = a.powi(3) - 2.0 * a.powf(1.5);
            // dP̄/dh̄ along the branch; zero where the depth is below the branch (clamped).
            let dh = 2.0 * a - 2.0 / (3.0 * a.sqrt());
            let slope = if a > sphere_depth_minimum_radius() && dh > 1e-12 {
                (3.0 * a * a - 3.0 * a.sqrt()) / dh
            } else {
                0.0
            };
            // P̂ ∝ w, ĥ ∝ (w/ℰ)^(2/3): ∂h̄/∂ln w = −(2/3)h̄ = −∂h̄/∂ln ℰ.
            let d_e = p_hat * slope * (2.0 / 3.0) * hb;
            (p_hat * pb, [p_hat * pb - d_e, d_e, -p_hat * slope / h_hat])
        }
    }
}

/// Scales that make the fitted parameters of order one.
#[derive(Debug, Clone, Copy)]
struct Scales {
    /// Depth scale L [m].
    length: f64,
    /// Force scale [N].
    force: f64,
}

fn unpack(model: ContactModel, x: &[f64], s: Scales) -> (Params, f64) {
    match model {
        ContactModel::Hertz => (
            Params {
                w: 0.0,
                e: x[0].exp(),
                dc: x[1] * s.length,
            },
            x[2] * s.force,
        ),
        _ => (
            Params {
                w: x[0].exp(),
                e: x[1].exp(),
                dc: x[2] * s.length,
            },
            x[3] * s.force,
        ),
    }
}

fn residuals(model: ContactModel, radius: f64, data: &FitData, s: Scales, x: &[f64]) -> Vec<f64> {
    let (p, f0) = unpack(model, x, s);
    data.depth
        .iter()
        .zip(data.force)
        .zip(data.in_contact)
        .map(|((&d, &f), &c)| (model_force(model, radius, &p, d, c).0 + f0 - f) / s.force)
        .collect()
}

fn jacobian(
    model: ContactModel,
    radius: f64,
    data: &FitData,
    s: Scales,
    x: &[f64],
) -> nalgebra::DMatrix<f64> {
    let (p, _) = unpack(model, x, s);
    let n = model.parameter_names().len();
    let m = data.depth.len();
    let mut j = nalgebra::DMatrix::zeros(m, n);
    for (i, (&d, &c)) in data.depth.iter().zip(data.in_contact).enumerate() {
        let (_, g) = model_force(model, radius, &p, d, c);
        let row: [f64; 4] = [g[0], g[1], g[2] * s.length, s.force];
        let row = if model == ContactModel::Hertz {
            [row[1], row[2], row[3], 0.0]
        } else {
            row
        };
        for k in 0..n {
            j[(i, k)] = row[k] / s.force;
        }
    }
    j
}

fn cost(model: ContactModel, radius: f64, data: &FitData, s: Scales, x: &[f64]) -> f64 {
    let r = residuals(model, radius, data, s, x);
    if r.iter().all(|v| v.is_finite()) {
        r.iter().map(|v| v * v).sum()
    } else {
        f64::INFINITY
    }
}

/// The Hertz fit at a fixed contact point: P = K·max(δ, 0)^(3/2) + F₀ is linear in (K, F₀).
/// Returns (K, F₀, cost).
fn hertz_profile(data: &FitData, dc: f64) -> (f64, f64, f64) {
    let (mut sgg, mut sg, mut sgf, mut sf, mut sff) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let n = data.depth.len() as f64;
    for (&d, &f) in data.depth.iter().zip(data.force) {
        let g = (d - dc).max(0.0).powf(1.5);
        sgg += g * g;
        sg += g;
        sgf += g * f;
        sf += f;
        sff += f * f;
    }
    let det = n * sgg - sg * sg;
    if det.abs() <= 1e-300 || sgg <= 0.0 {
        let f0 = sf / n;
        return (0.0, f0, sff - 2.0 * f0 * sf + n * f0 * f0);
    }
    let k = (n * sgf - sg * sf) / det;
    let f0 = (sf - k * sg) / n;
    let c = sff + k * k * sgg + n * f0 * f0 - 2.0 * k * sgf - 2.0 * f0 * sf + 2.0 * k * f0 * sg;
    (k, f0, c.max(0.0))
}

/// The best contact point of the Hertz profile: a scan of `candidates` trial points between
/// the shallowest and the deepest rows, refined by golden sections. Returns (d_c, K, F₀).
fn hertz_start(data: &FitData, min_contact_rows: usize) -> (f64, f64, f64) {
    let mut sorted: Vec<f64> = data.depth.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    // The contact point leaves at least `min_contact_rows` rows in contact, with K > 0.
    let hi = sorted[n.saturating_sub(min_contact_rows.max(2)).min(n - 1)];
    let lo = sorted[0] - 0.1 * (sorted[n - 1] - sorted[0]);
    let eval = |dc: f64| {
        let (k, f0, c) = hertz_profile(data, dc);
        if k > 0.0 {
            (c, k, f0)
        } else {
            (f64::INFINITY, k, f0)
        }
    };
    let steps = 80;
    let at = |i: usize| lo + (hi - lo) * i as f64 / steps as f64;
    let (mut best_i, mut best) = (0, f64::INFINITY);
    for i in 0..=steps {
        let c = eval(at(i)).0;
        if c < best {
            best = c;
            best_i = i;
        }
    }
    let (mut a, mut b) = (at(best_i.saturating_sub(1)), at((best_i + 1).min(steps)));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (eval(x1).0, eval(x2).0);
    for _ in 0..40 {
        if f1 < f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = eval(x1).0;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = eval(x2).0;
        }
    }
    let dc = if f1 < f2 { x1 } else { x2 };
    let (_, k, f0) = eval(dc);
    if k > 0.0 {
        (dc, k, f0)
    } else {
        (at(best_i), eval(at(best_i)).1, eval(at(best_i)).2)
    }
}

/// The DMT fit at a fixed contact point, linear in (K, A, F₀): P = K·max(δ,0)^(3/2) − A on the
/// in-contact rows, 0 elsewhere, + F₀. Returns (K, A, F₀, cost).
fn dmt_profile(data: &FitData, dc: f64) -> Option<(f64, f64, f64, f64)> {
    let mut ata = nalgebra::Matrix3::<f64>::zeros();
    let mut atb = nalgebra::Vector3::<f64>::zeros();
    let mut bb = 0.0;
    for ((&d, &f), &c) in data.depth.iter().zip(data.force).zip(data.in_contact) {
        let row = if c {
            nalgebra::Vector3::new((d - dc).max(0.0).powf(1.5), -1.0, 1.0)
        } else {
            nalgebra::Vector3::new(0.0, 0.0, 1.0)
        };
        ata += row * row.transpose();
        atb += row * f;
        bb += f * f;
    }
    let sol = ata.cholesky()?.solve(&atb);
    let c = bb - 2.0 * sol.dot(&atb) + (sol.transpose() * ata * sol)[(0, 0)];
    Some((sol[0], sol[1], sol[2], c.max(0.0)))
}

/// The JKR start from the shape of the curve: the baseline from the out-of-contact rows, P̂
/// from the force minimum (−P̂ at the fixed-load pull-off, −(5/9)P̂ at the fixed-grip one; the
/// middle is taken), and ĥ, d_c from the depths of the zero crossing (h̄ = 2^(1/3)·(2/3)) and of
/// the deepest row. Returns (w, ℰ, d_c, F₀) or `None` where the shape gives no estimate.
fn jkr_start(data: &FitData, radius: f64) -> Option<(f64, f64, f64, f64)> {
    let pi = std::f64::consts::PI;
    let base: Vec<f64> = data
        .force
        .iter()
        .zip(data.in_contact)
        .filter(|(_, c)| !**c)
        .map(|(f, _)| *f)
        .collect();
    let f0 = if base.is_empty() { 0.0 } else { median(base) };
    let contact: Vec<(f64, f64)> = data
        .depth
        .iter()
        .zip(data.force)
        .zip(data.in_contact)
        .filter(|(_, c)| **c)
        .map(|((d, f), _)| (*d, *f - f0))
        .collect();
    let p_min = contact.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let (d_max, p_max) = contact
        .iter()
        .fold((f64::NEG_INFINITY, 0.0), |a, c| if c.0 > a.0 { *c } else { a });
    if !(p_min < 0.0 && p_max > 0.0) {
        return None;
    }
    let p_hat = -p_min / 0.78;
    let w = p_hat / (1.5 * pi * radius);
    // The deepest row: solve P̄ = ā³ − 2ā^(3/2) = p_max/P̂ for ā ≥ 1 (increasing there).
    let target = p_max / p_hat;
    let (mut lo, mut hi) = (1.0f64, 2.0f64);
    while hi.powi(3) - 2.0 * hi.powf(1.5) < target {
        hi *= 2.0;
        if hi > 1e12 {
            return None;
        }
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if mid.powi(3) - 2.0 * mid.powf(1.5) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a_max = 0.5 * (lo + hi);
    let hb_max = a_max * a_max - 4.0 / 3.0 * a_max.sqrt();
    // The zero crossing of the force on the in-contact rows nearest the deepest row's side.
    let hb_zero = 2f64.cbrt() * (2.0 / 3.0);
    let mut d_zero = None;
    for w2 in contact.windows(2) {
        if (w2[0].1 <= 0.0) != (w2[1].1 <= 0.0) {
            let t = w2[0].1 / (w2[0].1 - w2[1].1);
            d_zero = Some(w2[0].0 + t * (w2[1].0 - w2[0].0));
        }
    }
    let d_zero = d_zero?;
    let h_hat = (d_max - d_zero) / (hb_max - hb_zero);
    if !(h_hat > 0.0 && h_hat.is_finite()) {
        return None;
    }
    let dc = d_zero - hb_zero * h_hat;
    let a_hat = (h_hat * radius).sqrt();
    let e = 9.0 * pi * w * radius * radius / (8.0 * a_hat.powi(3));
    Some((w, e, dc, f0))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Fit `model` to `data` with the contact point and the baseline free (see the module doc).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `tip-radius` for a radius that is not positive;
/// [`Error::Unresolvable`] when the data give no start or no finite answer (too few rows in
/// contact, no adhesive force for an adhesive model) or the fit does not converge.
pub fn fit(model: ContactModel, radius: f64, data: &FitData) -> Result<EngineFit> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(Error::invalid("tip-radius", radius, "must be positive (metres)"));
    }
    let n = data.depth.len();
    let n_contact = data.in_contact.iter().filter(|c| **c).count();
    let n_params = model.parameter_names().len();
    if n < n_params + 2 {
        return Err(unresolvable(format!(
            "{n} rows, at least {} are needed for {n_params} parameters",
            n_params + 2
        )));
    }
    let (d_lo, d_hi) = data
        .depth
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
            (a.min(*d), b.max(*d))
        });
    let span = d_hi - d_lo;
    let p_scale = data.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    if !(span > 0.0 && p_scale > 0.0 && span.is_finite() && p_scale.is_finite()) {
        return Err(unresolvable("the depth or the force does not vary".into()));
    }
    let s = Scales {
        length: span,
        force: p_scale,
    };
    let starts: Vec<Vec<f64>> = match model {
        ContactModel::Hertz => {
            let (dc, k, f0) = hertz_start(data, 5);
            if k.is_nan() || k <= 0.0 {
                return Err(unresolvable(
                    "no part of the curve rises above its baseline".into(),
                ));
            }
            let e = k / (4.0 / 3.0 * radius.sqrt());
            vec![vec![e.ln(), dc / s.length, f0 / s.force]]
        }
        ContactModel::Dmt => {
            if n_contact < 5 {
                return Err(unresolvable(format!("only {n_contact} in-contact rows")));
            }
            // Profile over the contact point among the in-contact depths.
            let mut depths: Vec<f64> = data
                .depth
                .iter()
                .zip(data.in_contact)
                .filter(|(_, c)| **c)
                .map(|(d, _)| *d)
                .collect();
            depths.sort_by(f64::total_cmp);
            let (lo, hi) = (depths[0] - 0.2 * span, depths[depths.len().saturating_sub(4)]);
            let mut best: Option<(f64, (f64, f64, f64, f64))> = None;
            for i in 0..=80 {
                let dc = lo + (hi - lo) * i as f64 / 80.0;
                if let Some(p) = dmt_profile(data, dc)
                    && p.0 > 0.0
                    && p.1 > 0.0
                    && best.is_none_or(|b| p.3 < b.1.3)
                {
                    best = Some((dc, p));
                }
            }
            let Some((dc, (k, a, f0, _))) = best else {
                return Err(unresolvable(
                    "no adhesive force: the in-contact rows never pull (use --model hertz)".into(),
                ));
            };
            let e = k / (4.0 / 3.0 * radius.sqrt());
            let w = a / (2.0 * std::f64::consts::PI * radius);
            vec![vec![w.ln(), e.ln(), dc / s.length, f0 / s.force]]
        }
        ContactModel::Jkr => {
            if n_contact < 5 {
                return Err(unresolvable(format!("only {n_contact} in-contact rows")));
            }
            let Some((w, e, dc, f0)) = jkr_start(data, radius) else {
                return Err(unresolvable(
                    "no adhesive force: the in-contact rows never pull below the baseline, or never push above it (use --model hertz)"
                        .into(),
                ));
            };
            let mut v = Vec::new();
            for (fw, fe) in [(1.0, 1.0), (0.7, 1.0), (1.4, 1.0), (1.0, 0.5), (1.0, 2.0)] {
                v.push(vec![(w * fw).ln(), (e * fe).ln(), dc / s.length, f0 / s.force]);
            }
            v
        }
    };
    let res = |x: &[f64]| residuals(model, radius, data, s, x);
    let jac = |x: &[f64]| jacobian(model, radius, data, s, x);
    let opts = LmOptions {
        max_iterations: 300,
        ..LmOptions::default()
    };
    let mut best: Option<LmSolution> = None;
    for x0 in &starts {
        if !cost(model, radius, data, s, x0).is_finite() {
            continue;
        }
        if let Ok(sol) = levenberg_marquardt(&res, Some(&jac), x0, opts)
            && best.as_ref().is_none_or(|b| sol.residual_norm < b.residual_norm)
        {
            best = Some(sol);
        }
    }
    let Some(sol) = best else {
        return Err(unresolvable(
            "no start of the fit converged: the model does not describe these data".into(),
        ));
    };
    let (p, f0) = unpack(model, &sol.x, s);
    // Standard errors in SI: ln-parameters scale by the value, the others by their scale.
    let si_scale: Vec<f64> = match model {
        ContactModel::Hertz => vec![p.e, s.length, s.force],
        _ => vec![p.w, p.e, s.length, s.force],
    };
    let std_errors: Vec<f64> = sol.std_errors.iter().zip(&si_scale).map(|(e, k)| e * k).collect();
    let np = n_params;
    let correlation: Vec<f64> = (0..np * np)
        .map(|ij| {
            let (i, j) = (ij / np, ij % np);
            let c = sol.covariance[ij];
            let d = (sol.covariance[i * np + i] * sol.covariance[j * np + j]).sqrt();
            if i == j { 1.0 } else { c / d }
        })
        .collect();
    let rms = sol.residual_norm * s.force / (n as f64).sqrt();
    let values = [p.w, p.e, p.dc, f0, rms];
    if values
        .iter()
        .chain(&std_errors)
        .chain(&correlation)
        .any(|v| !v.is_finite())
    {
        return Err(unresolvable(format!(
            "no finite answer (w = {}, E* = {}, contact point {} m, standard errors {:?}): the data do not determine the parameters",
            crate::params::fmt_sig(p.w),
            crate::params::fmt_sig(p.e),
            crate::params::fmt_sig(p.dc),
            std_errors
                .iter()
                .map(|v| crate::params::fmt_sig(*v))
                .collect::<Vec<_>>()
        )));
    }
    Ok(EngineFit {
        model,
        work_of_adhesion: p.w,
        modulus: p.e,
        contact_point: p.dc,
        baseline: f0,
        std_errors,
        correlation,
        rms_residual: rms,
        iterations: sol.iterations,
    })
}

fn unresolvable(reason: String) -> Error {
    Error::Unresolvable { model: "fit", reason }
}

/// Warnings on a fit whose parameters the data may not determine: correlations above 0.99,
/// standard errors above half the value, the contact point at the edge of the data (outside
/// the depths, or with fewer than 3 % of the rows on one side), residuals far above the
/// baseline noise (rms over 3 σ).
pub fn warnings(fit: &EngineFit, data: &FitData) -> Vec<String> {
    let names = fit.model.parameter_names();
    let np = names.len();
    let mut out = Vec::new();
    for i in 0..np {
        for j in i + 1..np {
            let r = fit.correlation[i * np + j];
            if r.abs() > 0.99 {
                out.push(format!(
                    "{} and {} are not determined separately: their correlation is {}",
                    names[i].replace('_', " "),
                    names[j].replace('_', " "),
                    crate::params::fmt_sig((r * 1000.0).round() / 1000.0)
                ));
            }
        }
    }
    let values: Vec<(&str, f64, f64)> = match fit.model {
        ContactModel::Hertz => vec![("modulus", fit.modulus, fit.std_errors[0])],
        _ => vec![
            ("work of adhesion", fit.work_of_adhesion, fit.std_errors[0]),
            ("modulus", fit.modulus, fit.std_errors[1]),
        ],
    };
    for (name, v, e) in values {
        if e > 0.5 * v {
            out.push(format!(
                "the {name} is not determined by these data: its standard error is {} % of its value",
                crate::params::fmt_sig((100.0 * e / v).round())
            ));
        }
    }
    let n = data.depth.len();
    let below = data.depth.iter().filter(|d| **d < fit.contact_point).count();
    let edge = (n as f64 * 0.03).ceil() as usize;
    if below < edge.max(1) || n - below < edge.max(1) {
        out.push(format!(
            "the contact point lies at the edge of the data ({below} of {n} rows before it): it is not determined"
        ));
    }
    if data.noise > 0.0 && fit.rms_residual > 3.0 * data.noise {
        out.push(format!(
            "the model does not describe these data within their noise: the rms force residual is {} times the baseline noise",
            crate::params::fmt_sig((10.0 * fit.rms_residual / data.noise).round() / 10.0)
        ));
    }
    out
}
