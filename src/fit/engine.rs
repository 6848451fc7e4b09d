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
use nalgebra::{DMatrix, DVector};

use crate::numerics::least_squares::{LeastSquares, LmOptions, LmSolution, levenberg_marquardt, minimize};

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
    /// Maugis-Dugdale (3.3): the stable contact branch of the Dugdale zone model, with the
    /// range Z₀ of the interaction fitted as well.
    MaugisDugdale,
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
            ContactModel::MaugisDugdale => &[
                "work_of_adhesion",
                "plane_strain_modulus",
                "contact_point",
                "baseline",
                "interaction_range",
            ],
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
    /// Range Z₀ of the Dugdale interaction [m] (Maugis-Dugdale only).
    pub interaction_range: Option<f64>,
    /// The deepest row's depth [m] (data origin): the Maugis-Dugdale branch is tabulated to it.
    pub deepest: f64,
    /// Standard errors in the order of [`ContactModel::parameter_names`] (SI).
    pub std_errors: Vec<f64>,
    /// Correlation matrix (row-major) in the same order.
    pub correlation: Vec<f64>,
    /// Root-mean-square force residual [N].
    pub rms_residual: f64,
    /// Levenberg-Marquardt iterations of the kept start.
    pub iterations: usize,
    /// For Hertz and DMT, the plane-strain moduli ℰ [Pa] that fit the data within the noise
    /// with the contact point anywhere ([`modulus_profile_interval`]); `None` for the others.
    pub modulus_interval: Option<(f64, f64)>,
}

impl EngineFit {
    /// The model force P(δ) + F₀ at depth `d` (data origin) for a row in contact or not.
    pub fn force_at(&self, radius: f64, d: f64, in_contact: bool) -> f64 {
        self.forces_at(radius, &[(d, in_contact)])[0]
    }

    /// The model forces P(δ) + F₀ of rows (depth in the data origin, in contact or not), the
    /// model (for Maugis-Dugdale its tabulated branch) built once for them all.
    pub fn forces_at(&self, radius: f64, rows: &[(f64, bool)]) -> Vec<f64> {
        let p = Params {
            w: self.work_of_adhesion,
            e: self.modulus,
            dc: self.contact_point,
            z0: self.interaction_range.unwrap_or(0.0),
        };
        let deepest = rows.iter().fold(self.deepest, |m, r| m.max(r.0));
        let m = Model::new(self.model, radius, &p, deepest - self.contact_point);
        rows.iter()
            .map(|&(d, c)| self.baseline + m.force(d, c).0)
            .collect()
    }
}

#[derive(Debug, Clone, Copy)]
struct Params {
    w: f64,
    e: f64,
    dc: f64,
    /// Range Z₀ of the Dugdale zone (Maugis-Dugdale).
    z0: f64,
}

/// The model at fixed parameters, its scales computed once per evaluation of the residuals.
#[derive(Debug, Clone)]
struct Model {
    model: ContactModel,
    /// Contact point d_c [m].
    dc: f64,
    /// Hertz factor (4/3)ℰ√R [N/m^(3/2)].
    hertz: f64,
    /// DMT adhesive force 2πwR [N].
    adhesion: f64,
    /// JKR force scale P̂ = 3πwR/2 [N].
    p_hat: f64,
    /// The inverse of the JKR depth scale ĥ = â²/R, â = (9πwR²/8ℰ)^(1/3) [1/m].
    inv_h_hat: f64,
    /// Maugis-Dugdale: the stable contact branch as (δ, P) with δ increasing [m, N].
    branch: Vec<(f64, f64)>,
    /// JKR: the branch's table, looked up once per model rather than per row.
    jkr: &'static JkrTable,
}

/// The stable branch of the Maugis-Dugdale curve (3.3) through deep contact, as (δ, P) in SI with
/// δ = −h the indentation, increasing: the zone branch (ā = 0) and the contact branch sampled
/// along their parameters (c̄, then τ = ln t from the junction to a contact radius past
/// `reach`), and the last stable run of them kept (where h̄ decreases into contact). Empty
/// where the model cannot be built at these parameters.
fn md_branch(radius: f64, p: &Params, reach: f64) -> Vec<(f64, f64)> {
    use crate::models::maugis_dugdale::MaugisDugdale;
    let pi = std::f64::consts::PI;
    let chi = p.w / (p.e * p.z0);
    let ell = pi * p.w / (p.e * radius);
    let Ok(md) = MaugisDugdale::new(chi, ell) else {
        return Vec::new();
    };
    // Past the deepest row: Hertz's ā² = δ/R with a margin for the adhesive part.
    let a_max = (2.0 * reach / radius)
        .sqrt()
        .max(4.0 * md.junction_radius())
        .max(1e-12);
    let Ok(deep) = md.contact_state(a_max) else {
        return Vec::new();
    };
    let mut states = Vec::with_capacity(2600);
    let c_star = md.junction_radius();
    for k in 0..100 {
        states.push(md.zone_state(c_star * k as f64 / 100.0));
    }
    let (tau_lo, tau_hi) = (deep.t.ln(), deep.t.ln().max(0.0) + 14.0);
    let n = 2400;
    for k in (0..=n).rev() {
        let tau = tau_lo + (tau_hi - tau_lo) * k as f64 / n as f64;
        states.push(md.contact_state_at_t(tau.exp()));
    }
    let end = states.len();
    let start = states
        .iter()
        .rposition(|s| !s.stable || !s.h.is_finite())
        .map_or(0, |i| i + 1);
    let (force, length) = (2.0 * p.e * radius * radius, radius);
    let mut out: Vec<(f64, f64)> = states[start..end]
        .iter()
        .filter(|s| s.h.is_finite() && s.p.is_finite())
        .map(|s| (-s.h * length, s.p * force))
        .collect();
    out.dedup_by(|a, b| a.0 <= b.0);
    out
}

/// The force on the sampled Maugis-Dugdale branch `b` at δ between samples `i − 1` and `i`: a
/// cubic Hermite interpolant with the slopes of the neighbouring samples (Catmull-Rom on the
/// uneven δ), so that the force is continuous with its slope in δ, and the cost of a fit
/// changes smoothly as the samples move past the data with the parameters (linear
/// interpolation puts a kink in the cost wherever a sample crosses a row, and the
/// difference-quotient Jacobian stalls on them).
fn md_branch_hermite(b: &[(f64, f64)], i: usize, delta: f64) -> f64 {
    let slope = |k: usize| {
        let (lo, hi) = (k.saturating_sub(1), (k + 1).min(b.len() - 1));
        (b[hi].1 - b[lo].1) / (b[hi].0 - b[lo].0)
    };
    let (l, r) = (b[i - 1], b[i]);
    let h = r.0 - l.0;
    let t = (delta - l.0) / h;
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * l.1
        + (t3 - 2.0 * t2 + t) * h * slope(i - 1)
        + (-2.0 * t3 + 3.0 * t2) * r.1
        + (t3 - t2) * h * slope(i)
}

impl Model {
    fn new(model: ContactModel, radius: f64, p: &Params, reach: f64) -> Self {
        let pi = std::f64::consts::PI;
        let (p_hat, inv_h_hat) = if model == ContactModel::Jkr {
            let a_hat = (9.0 * pi * p.w * radius * radius / (8.0 * p.e)).cbrt();
            (1.5 * pi * p.w * radius, radius / (a_hat * a_hat))
        } else {
            (0.0, 1.0)
        };
        Self {
            model,
            dc: p.dc,
            hertz: 4.0 / 3.0 * p.e * radius.sqrt(),
            adhesion: 2.0 * pi * p.w * radius,
            p_hat,
            inv_h_hat,
            branch: if model == ContactModel::MaugisDugdale {
                md_branch(radius, p, reach)
            } else {
                Vec::new()
            },
            jkr: JkrTable::get(),
        }
    }

    /// The model force without baseline at depth `d` and its derivatives (∂P/∂ln w,
    /// ∂P/∂ln ℰ, ∂P/∂d_c).
    #[inline(always)]
    fn force(&self, d: f64, in_contact: bool) -> (f64, [f64; 3]) {
        let delta = d - self.dc;
        match self.model {
            ContactModel::Hertz => {
                if delta <= 0.0 {
                    return (0.0, [0.0; 3]);
                }
                let root = delta.sqrt();
                let f = self.hertz * delta * root;
                (f, [0.0, f, -1.5 * self.hertz * root])
            }
            ContactModel::Dmt => {
                if !in_contact {
                    return (0.0, [0.0; 3]);
                }
                let dp = delta.max(0.0);
                let root = dp.sqrt();
                let f = self.hertz * dp * root;
                (f - self.adhesion, [-self.adhesion, f, -1.5 * self.hertz * root])
            }
            ContactModel::Jkr => {
                if !in_contact {
                    return (0.0, [0.0; 3]);
                }
                // P = P̂(ā³ − 2ā^(3/2)), δ = ĥ(ā² − (4/3)√ā) on the stable branch (Sec. 2.3),
                // in s = √ā: P̄ = s³(s³ − 2), h̄ = s⁴ − (4/3)s.
                let hb = delta * self.inv_h_hat;
                let root = self.jkr.root(hb);
                let s = root.s;
                let s3 = s * s * s;
                let pb = s3 * (s3 - 2.0);
                // dP̄/dh̄ = (dP̄/ds)(ds/dh̄) = 6s²(s³ − 1)·ds/dh̄ along the branch; zero where
                // the depth is below the branch (clamped at the fold, where it diverges).
                let slope = 6.0 * s * s * (s3 - 1.0) * root.ds_dh;
                // P̂ ∝ w, ĥ ∝ (w/ℰ)^(2/3): ∂h̄/∂ln w = −(2/3)h̄ = −∂h̄/∂ln ℰ.
                let p = self.p_hat * pb;
                let d_e = self.p_hat * slope * (2.0 / 3.0) * hb;
                (p, [p - d_e, d_e, -self.p_hat * slope * self.inv_h_hat])
            }
            ContactModel::MaugisDugdale => {
                // Interpolated on the stable branch (clamped at its ends); the derivatives are
                // taken by differences of whole evaluations.
                if !in_contact {
                    return (0.0, [0.0; 3]);
                }
                let b = &self.branch;
                if b.is_empty() {
                    return (f64::NAN, [0.0; 3]);
                }
                let i = b.partition_point(|q| q.0 < delta);
                let p = if i == 0 {
                    b[0].1
                } else if i == b.len() {
                    b[b.len() - 1].1
                } else {
                    md_branch_hermite(b, i, delta)
                };
                (p, [0.0; 3])
            }
        }
    }
}

/// A point of the stable JKR branch found from its depth: s = √ā, ds/dh̄ there, and whether
/// the depth lies past the fold (else s is clamped at the fold s_D and ds/dh̄ = 0).
#[derive(Debug, Clone, Copy, PartialEq)]
struct JkrRoot {
    s: f64,
    ds_dh: f64,
    on_branch: bool,
}

/// The table of [`JkrTable::root`]: on each interval [k·du, (k+1)·du] of u the
/// Hermite cubic of s through s and ds/du at its ends, as the coefficients of
/// s = c₀ + c₁r + c₂r² + c₃r³ in r = u/du − k (Horner's form: six operations for s and ds/dr).
#[derive(Debug)]
struct JkrTable {
    h_d: f64,
    s_d: f64,
    /// 1/(2·du): ds/dh̄ = (ds/dr)/(2u·du).
    half_inv_du: f64,
    inv_du: f64,
    u_max: f64,
    cubic: Vec<[f64; 4]>,
}

impl JkrTable {
    /// The table, built on first use.
    fn get() -> &'static Self {
        static TABLE: std::sync::OnceLock<JkrTable> = std::sync::OnceLock::new();
        TABLE.get_or_init(JkrTable::new)
    }

    fn new() -> Self {
        let s_d = sphere_depth_minimum_radius().sqrt();
        let h_d = s_d.powi(4) - 4.0 / 3.0 * s_d;
        let n = 2049;
        let u_max = 64.0;
        let du = u_max / (n - 1) as f64;
        // s and its slope in r (ds/du·du) at the nodes.
        let nodes: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let u = k as f64 * du;
                if k == 0 {
                    // h̄ − h̄_D ≈ 6s_D²(s − s_D)² at the fold.
                    (s_d, du / (6f64.sqrt() * s_d))
                } else {
                    let si = sphere_radius_at_depth(h_d + u * u).sqrt();
                    (si, du * 2.0 * u / (4.0 * si.powi(3) - 4.0 / 3.0))
                }
            })
            .collect();
        let cubic = nodes
            .windows(2)
            .map(|w| {
                let ((s0, m0), (s1, m1)) = (w[0], w[1]);
                [s0, m0, 3.0 * (s1 - s0) - 2.0 * m0 - m1, 2.0 * (s0 - s1) + m0 + m1]
            })
            .collect();
        Self {
            h_d,
            s_d,
            half_inv_du: 0.5 / du,
            inv_du: 1.0 / du,
            u_max,
            cubic,
        }
    }

    /// s = √ā on the stable JKR branch at normalised depth h̄ = ā² − (4/3)√ā (Sec. 2.3.1), with
    /// ds/dh̄; as [`sphere_radius_at_depth`] but fast: s and ds/du from a cubic Hermite table in
    /// u = √(h̄ − h̄_D) (where s is smooth: s − s_D ∝ u at the fold), then one Newton step on
    /// s⁴ − (4/3)s = h̄ with the tabulated ds/dh̄ = (ds/du)/(2u) as the inverse slope (its error,
    /// about 1e-6 relative, multiplies the table's 1e-9: one division per depth, not three); beyond
    /// the table from s⁴ ≈ h̄ + (4/3)h̄^(1/4) and two exact Newton steps. Depths at or below the
    /// fold h̄_D give s_D = √ā_D (the clamp of the residuals). Agrees with
    /// [`sphere_radius_at_depth`] to 1e-13 relative away from the fold, where the depth's
    /// round-off dominates both (unit test).
    #[inline(always)]
    fn root(&self, hb: f64) -> JkrRoot {
        let f = |s: f64| s * s * s * s - 4.0 / 3.0 * s - hb;
        let dh = hb - self.h_d;
        if dh.is_nan() || dh <= 0.0 {
            return JkrRoot {
                s: self.s_d,
                ds_dh: 0.0,
                on_branch: false,
            };
        }
        let u = dh.sqrt();
        let (s, ds_dh) = if u < self.u_max {
            let x = u * self.inv_du;
            let i = (x as usize).min(self.cubic.len() - 1);
            let r = x - i as f64;
            let [c0, c1, c2, c3] = self.cubic[i];
            let s = c0 + r * (c1 + r * (c2 + r * c3));
            let ds_dr = c1 + r * (2.0 * c2 + r * 3.0 * c3);
            let ds_dh = ds_dr * self.half_inv_du / u;
            (s - f(s) * ds_dh, ds_dh)
        } else {
            let df = |s: f64| 4.0 * s * s * s - 4.0 / 3.0;
            let mut s = (hb + 4.0 / 3.0 * hb.powf(0.25)).powf(0.25);
            s -= f(s) / df(s);
            s -= f(s) / df(s);
            (s, 1.0 / df(s))
        };
        if s > self.s_d {
            JkrRoot {
                s,
                ds_dh,
                on_branch: true,
            }
        } else {
            JkrRoot {
                s: self.s_d,
                ds_dh: 0.0,
                on_branch: false,
            }
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
    /// The deepest row's depth [m] (data origin).
    reach: f64,
}

fn unpack(model: ContactModel, x: &[f64], s: Scales) -> (Params, f64) {
    match model {
        ContactModel::Hertz => (
            Params {
                w: 0.0,
                e: x[0].exp(),
                dc: x[1] * s.length,
                z0: 0.0,
            },
            x[2] * s.force,
        ),
        _ => (
            Params {
                w: x[0].exp(),
                e: x[1].exp(),
                dc: x[2] * s.length,
                z0: x.get(4).map_or(0.0, |v| v.exp()),
            },
            x[3] * s.force,
        ),
    }
}

/// The model at `x` and its baseline F₀ [N].
fn model_at(model: ContactModel, radius: f64, s: Scales, x: &[f64]) -> (Model, f64) {
    let (p, f0) = unpack(model, x, s);
    (Model::new(model, radius, &p, s.reach - p.dc), f0)
}

/// A row's residual (model − measured)/force scale with the model's derivatives of the row
/// (∂P/∂ln w, ∂P/∂ln ℰ, ∂P/∂d_c): the one residual formula of the fit. `inv` is 1/F.
#[inline(always)]
fn row(m: &Model, f0: f64, inv: f64, (d, f, in_contact): (f64, f64, bool)) -> (f64, [f64; 3]) {
    let (force, grad) = m.force(d, in_contact);
    ((force + f0 - f) * inv, grad)
}

fn residuals(model: ContactModel, radius: f64, data: &FitData, s: Scales, x: &[f64]) -> Vec<f64> {
    let (m, f0) = model_at(model, radius, s, x);
    let inv = 1.0 / s.force;
    data.depth
        .iter()
        .zip(data.force)
        .zip(data.in_contact)
        .map(|((&d, &f), &c)| row(&m, f0, inv, (d, f, c)).0)
        .collect()
}

/// About the number of rows of the coarse stage and of the ranking of starts: every k-th row,
/// k = ⌊n/250⌋, leaves 250 to 499 rows (a pass over them costs a fraction of one over all
/// rows). Over ten noise seeds of the force-curve bench (2 006 rows) the fit on all rows then
/// took 3.3 passes on average (3 or 4) from the coarse minimum, as from every fourth row
/// (3.2); from every 15th row it took 4 on the first seed. (Means of runs of rows in place of
/// every k-th row gave 3 passes on every seed, but as many more coarse ones: no gain.)
const COARSE_TARGET_ROWS: usize = 250;

/// The stride that leaves about [`COARSE_TARGET_ROWS`] of `n` rows; curves of fewer than
/// twice as many rows are fitted on all rows at once.
fn coarse_stride(n: usize) -> usize {
    (n / COARSE_TARGET_ROWS).max(1)
}

/// The fit of a model whose rows give their derivatives in closed form (Hertz, DMT, JKR) as
/// [`LeastSquares`] over every `stride`-th row: one pass over the rows gives the cost and the
/// normal equations together, the m × n Jacobian never formed. The normal equations of the
/// last cost are kept.
///
/// The adhesive models' rows out of contact carry no model force (their residual is
/// (F₀ − f)/F and their derivatives vanish, as [`Model::force`] gives them to [`row`]): they
/// enter every pass through their count, mean and spread, summed once, and the pass runs over
/// the rows in contact only.
struct ClosedForm {
    model: ContactModel,
    radius: f64,
    s: Scales,
    /// The rows the pass runs over, (depth [m], force [N], in contact).
    rows: Vec<(f64, f64, bool)>,
    /// The rows out of contact summed once (adhesive models; zero for Hertz).
    free: FreeRows,
    /// The number of rows m.
    m: usize,
    last: Option<(Vec<f64>, DMatrix<f64>, DVector<f64>)>,
}

/// Rows out of contact of an adhesive model: their count, the mean of f/F and
/// Σ(f/F − mean)², so that Σ(F₀/F − f/F)² = count·(F₀/F − mean)² + spread.
#[derive(Debug, Clone, Copy, Default)]
struct FreeRows {
    count: f64,
    mean: f64,
    spread: f64,
}

impl ClosedForm {
    fn new(model: ContactModel, radius: f64, data: &FitData, s: Scales, stride: usize) -> Self {
        let m = data.depth.len().div_ceil(stride.max(1));
        let all = data
            .depth
            .iter()
            .zip(data.force)
            .zip(data.in_contact)
            .step_by(stride.max(1))
            .map(|((&d, &f), &c)| (d, f, c));
        if !model.adhesive() {
            return Self {
                model,
                radius,
                s,
                rows: all.collect(),
                free: FreeRows::default(),
                m,
                last: None,
            };
        }
        let inv = 1.0 / s.force;
        let mut rows = Vec::with_capacity(m);
        let mut free = Vec::with_capacity(m);
        for r in all {
            if r.2 {
                rows.push(r);
            } else {
                free.push(r.1 * inv);
            }
        }
        let count = free.len() as f64;
        let mean = free.iter().sum::<f64>() / count.max(1.0);
        let spread = free.iter().map(|f| (f - mean).powi(2)).sum();
        Self {
            model,
            radius,
            s,
            rows,
            free: FreeRows { count, mean, spread },
            m,
            last: None,
        }
    }

    /// ½Σr², JᵀJ and Jᵀr at `x` in the fitted parameters (ln w, ln ℰ, d_c/L, F₀/F, or without
    /// ln w for Hertz).
    fn evaluate(&self, x: &[f64]) -> (f64, DMatrix<f64>, DVector<f64>) {
        let (m, f0) = model_at(self.model, self.radius, self.s, x);
        let s = self.s;
        let inv = 1.0 / s.force;
        let scale = [inv, inv, s.length * inv];
        // Rows of the Jacobian: (g₀, g₁, g₂)·scale, and 1 for the baseline F₀/F.
        let (mut a, mut b, mut sum_j) = ([0.0f64; 6], [0.0f64; 3], [0.0f64; 3]);
        let (mut rr, mut sum_r) = (0.0, 0.0);
        for &data_row in &self.rows {
            let (r, g) = row(&m, f0, inv, data_row);
            let j = [g[0] * scale[0], g[1] * scale[1], g[2] * scale[2]];
            rr += r * r;
            sum_r += r;
            a[0] += j[0] * j[0];
            a[1] += j[0] * j[1];
            a[2] += j[0] * j[2];
            a[3] += j[1] * j[1];
            a[4] += j[1] * j[2];
            a[5] += j[2] * j[2];
            for k in 0..3 {
                b[k] += j[k] * r;
                sum_j[k] += j[k];
            }
        }
        let free = self.free;
        let offset = f0 * inv - free.mean;
        rr += free.count * offset * offset + free.spread;
        sum_r += free.count * offset;
        let full = [
            [a[0], a[1], a[2], sum_j[0]],
            [a[1], a[3], a[4], sum_j[1]],
            [a[2], a[4], a[5], sum_j[2]],
            [sum_j[0], sum_j[1], sum_j[2], self.m as f64],
        ];
        let full_b = [b[0], b[1], b[2], sum_r];
        // Hertz has no ln w: its parameters are the last three.
        let first = usize::from(self.model == ContactModel::Hertz);
        let n = 4 - first;
        let jtj = DMatrix::from_fn(n, n, |i, k| full[i + first][k + first]);
        let jtr = DVector::from_fn(n, |i, _| full_b[i + first]);
        (0.5 * rr, jtj, jtr)
    }
}

impl LeastSquares for ClosedForm {
    fn rows(&self) -> usize {
        self.m
    }

    fn cost(&mut self, x: &[f64]) -> Option<f64> {
        let (c, jtj, jtr) = self.evaluate(x);
        self.last = Some((x.to_vec(), jtj, jtr));
        c.is_finite().then_some(c)
    }

    fn normal(&mut self, x: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
        match self.last.take() {
            Some((at, jtj, jtr)) if at == x => (jtj, jtr),
            _ => {
                let (_, jtj, jtr) = self.evaluate(x);
                (jtj, jtr)
            }
        }
    }
}

/// Central differences of the residuals in the (order-one) fitted parameters, with an absolute
/// step: the Maugis-Dugdale branch is a table, whose derivatives are not in closed form.
fn fd_jacobian(f: &dyn Fn(&[f64]) -> Vec<f64>, x: &[f64]) -> nalgebra::DMatrix<f64> {
    let h = 1e-6;
    let mut xp = x.to_vec();
    let cols: Vec<Vec<f64>> = (0..x.len())
        .map(|j| {
            xp[j] = x[j] + h;
            let rp = f(&xp);
            xp[j] = x[j] - h;
            let rm = f(&xp);
            xp[j] = x[j];
            rp.iter().zip(&rm).map(|(a, b)| (a - b) / (2.0 * h)).collect()
        })
        .collect();
    nalgebra::DMatrix::from_fn(cols[0].len(), x.len(), |i, j| cols[j][i])
}

/// The Hertz fit at a fixed contact point: P = K·max(δ, 0)^(3/2) + F₀ is linear in (K, F₀).
/// Returns (K, F₀, cost).
fn hertz_profile(data: &FitData, dc: f64) -> (f64, f64, f64) {
    let (mut sgg, mut sg, mut sgf, mut sf, mut sff) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let n = data.depth.len() as f64;
    for (&d, &f) in data.depth.iter().zip(data.force) {
        let x = (d - dc).max(0.0);
        let g = x * x.sqrt();
        sgg += g * g;
        sg += g;
        sgf += g * f;
        sf += f;
        sff += f * f;
    }
    hertz_solve(n, [sgg, sg, sgf, sf, sff])
}

/// The least-squares (K, F₀) of P = K·g + F₀ over `n` rows from the sums Σg², Σg, Σg·P, ΣP and
/// ΣP², and the cost there: K = 0 and F₀ the mean force where no row is in contact.
fn hertz_solve(n: f64, sums: [f64; 5]) -> (f64, f64, f64) {
    let [sgg, sg, sgf, sf, sff] = sums;
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

/// [`hertz_profile`] from rows sorted deepest first, with the sums of the forces and of their
/// squares over all rows given. Returns (K, cost).
fn hertz_profile_sorted(rows: &[(f64, f64)], dc: f64, sf: f64, sff: f64) -> (f64, f64) {
    let n = rows.len() as f64;
    let (mut sgg, mut sg, mut sgf) = (0.0, 0.0, 0.0);
    for &(d, f) in rows.iter().take_while(|r| r.0 > dc) {
        let x = d - dc;
        let g = x * x.sqrt();
        sgg += g * g;
        sg += g;
        sgf += g * f;
    }
    let (k, _, c) = hertz_solve(n, [sgg, sg, sgf, sf, sff]);
    (k, c)
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
    let steps = 40;
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
    for _ in 0..30 {
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
            nalgebra::Vector3::new((d - dc).max(0.0) * (d - dc).max(0.0).sqrt(), -1.0, 1.0)
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
    // The deepest row: P̄ = ā³ − 2ā^(3/2) = p_max/P̂ for ā ≥ 1, a quadratic in t = ā^(3/2):
    // t² − 2t = p_max/P̂, t = 1 + √(1 + p_max/P̂).
    let t = 1.0 + (1.0 + p_max / p_hat).sqrt();
    let a_max = t.powf(2.0 / 3.0);
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
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Fit `model` to `data` with the contact point and the baseline free (see the module doc).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `tip-radius` for a radius that is not positive;
/// [`Error::Unresolvable`] when the data give no start or no finite answer (too few rows in
/// contact, no adhesive force for an adhesive model) or the fit does not converge.
pub fn fit(model: ContactModel, radius: f64, data: &FitData) -> Result<EngineFit> {
    // A relative decrease of the cost below 1e-10 moves the parameters by less than a
    // thousandth of their standard error on noisy data (δx ≈ σ_x·√(2·10⁻¹⁰·n)); the default
    // 1e-14 took 51 iterations of slow, linear convergence on a JPK curve of 3 900 rows.
    // Noiseless data converge quadratically and stop on the step instead. Maugis-Dugdale,
    // whose Jacobian is by differences of a tabulated branch, keeps the default, and so does
    // the JKR fit it starts from: its long valley in Z₀ is crossed by small decreases, and its
    // fit ended 2 % above the cost of the true parameters from a JKR start 1e-10 converged
    // (measured with the branch interpolated linearly, before `md_branch_hermite`).
    let cost_tol = if model == ContactModel::MaugisDugdale {
        LmOptions::default().cost_tol
    } else {
        1e-10
    };
    fit_to(model, radius, data, cost_tol)
}

fn fit_to(model: ContactModel, radius: f64, data: &FitData, cost_tol: f64) -> Result<EngineFit> {
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
        reach: d_hi,
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
            for (fw, fe) in [(1.0, 1.0), (0.7, 1.0), (1.4, 1.0)] {
                v.push(vec![(w * fw).ln(), (e * fe).ln(), dc / s.length, f0 / s.force]);
            }
            v
        }
        ContactModel::MaugisDugdale => {
            // From the JKR fit, with the range Z₀ that gives Maugis parameters λ = 0.3 to 10
            // (λ = (9/2)^(1/3) χ ℓ^(−1/3), χ = w/(ℰZ₀), ℓ = πw/(ℰR)).
            let j = fit_to(ContactModel::Jkr, radius, data, cost_tol)?;
            let (w, e) = (j.work_of_adhesion, j.modulus);
            let ell = std::f64::consts::PI * w / (e * radius);
            [0.3, 1.0, 3.0, 10.0]
                .iter()
                .map(|lambda| {
                    let chi = lambda * ell.cbrt() / 4.5f64.cbrt();
                    let z0 = w / (e * chi);
                    vec![
                        w.ln(),
                        e.ln(),
                        j.contact_point / s.length,
                        j.baseline / s.force,
                        z0.ln(),
                    ]
                })
                .collect()
        }
    };
    let opts = LmOptions {
        max_iterations: 300,
        cost_tol,
        ..LmOptions::default()
    };
    // Coarse to fine: on a long curve the steps far from the minimum are taken on about 250
    // rows ([`coarse_stride`]), and the fit on all rows starts at that minimum, where it needs
    // a step or two. The answer is the fit on all rows. Hertz starts at the exact profile over
    // the contact point, a step or two from its minimum: it gains nothing from the coarse
    // stage. The coarse rows also rank the starts (enough for starts that differ by tens of
    // percent): the fit runs from the best, and from the next only where it fails.
    let closed_form = model != ContactModel::MaugisDugdale;
    let stride = coarse_stride(n);
    let coarse_stage = stride > 1 && model != ContactModel::Hertz;
    let mut coarse_rows = (closed_form && (starts.len() > 1 || coarse_stage))
        .then(|| ClosedForm::new(model, radius, data, s, stride));
    let mut all_rows = closed_form.then(|| ClosedForm::new(model, radius, data, s, 1));
    let mut ranked: Vec<(f64, &Vec<f64>)> = starts.iter().map(|x0| (0.0, x0)).collect();
    if let (Some(p), true) = (coarse_rows.as_mut(), starts.len() > 1) {
        for (c, x0) in &mut ranked {
            *c = p.cost(x0).unwrap_or(f64::INFINITY);
        }
        ranked.retain(|(c, _)| c.is_finite());
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    // Maugis-Dugdale's cost has local minima in Z₀ (a JKR-like small range against the true
    // one): every start is run to its end and the lowest kept.
    let every_start = model == ContactModel::MaugisDugdale;
    let mut best: Option<LmSolution> = None;
    for (_, x0) in ranked {
        let solved = match (coarse_rows.as_mut(), all_rows.as_mut()) {
            (_, None) => {
                // The branch is a table: its derivatives are taken by differences.
                let res = |x: &[f64]| residuals(model, radius, data, s, x);
                let jac = |x: &[f64]| fd_jacobian(&res, x);
                levenberg_marquardt(&res, Some(&jac), x0, opts)
            }
            (coarse_rows, Some(all_rows)) => {
                let coarse = coarse_rows.filter(|_| coarse_stage).and_then(|p| {
                    let loose = LmOptions {
                        cost_tol: 1e-6,
                        ..opts
                    };
                    minimize(p, x0, loose).ok()
                });
                let fine = coarse.as_ref().map_or(x0.as_slice(), |c| c.x.as_slice());
                minimize(all_rows, fine, opts).or_else(|e| match coarse {
                    Some(_) => minimize(all_rows, x0, opts),
                    None => Err(e),
                })
            }
        };
        if let Ok(sol) = solved
            && best.as_ref().is_none_or(|b| sol.residual_norm < b.residual_norm)
        {
            best = Some(sol);
            if !every_start {
                break;
            }
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
        ContactModel::MaugisDugdale => vec![p.w, p.e, s.length, s.force, p.z0],
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
    let dc_se = std_errors[if model == ContactModel::Hertz { 1 } else { 2 }];
    let modulus_interval = modulus_profile_interval(model, radius, data, (p.e, p.dc, dc_se), rms);
    Ok(EngineFit {
        model,
        work_of_adhesion: p.w,
        modulus: p.e,
        contact_point: p.dc,
        baseline: f0,
        interaction_range: (model == ContactModel::MaugisDugdale).then_some(p.z0),
        deepest: d_hi,
        std_errors,
        correlation,
        rms_residual: rms,
        iterations: sol.iterations,
        modulus_interval,
    })
}

/// Δ(cost)/σ² of the 95 % profile interval of one parameter (χ² with one degree of freedom).
const PROFILE_CHI2_95: f64 = 3.84;

/// The 95 % profile-likelihood interval of the modulus over the contact point, for the models
/// linear in their other parameters at a fixed contact point (Hertz: P = K·δ^(3/2) + F₀; DMT
/// with its adhesive force): at contact points that leave 3, 4, ... rows in contact, growing by
/// 8 % up to every row (about 80 points for 1 000 rows: as fine where few rows indent as where
/// many do), and at the fitted contact point ± 0.25, 0.5, ... 4 of its standard errors, the
/// best (K, F₀) is solved exactly, and the moduli of those whose cost lies within
/// [`PROFILE_CHI2_95`]·σ² of the fitted cost, σ² = n·rms²/(n − p), bound the interval (the
/// fitted modulus inside it). `fitted` is (ℰ, d_c, standard error of d_c). Where the cost has several valleys, or one long and curved
/// valley, the linearised standard error understates the uncertainty, and this shows it: a noisy
/// curve whose force rises ten times its noise over its last rows fits within the noise from
/// ℰ = 25 Pa to 5 kPa. `None` for JKR and Maugis-Dugdale.
fn modulus_profile_interval(
    model: ContactModel,
    radius: f64,
    data: &FitData,
    fitted: (f64, f64, f64),
    rms: f64,
) -> Option<(f64, f64)> {
    let (e, dc_fit, dc_se) = fitted;
    let n = data.depth.len();
    let np = model.parameter_names().len();
    if !matches!(model, ContactModel::Hertz | ContactModel::Dmt) || n <= np + 3 {
        return None;
    }
    let mut sorted = data.depth.to_vec();
    sorted.sort_by(f64::total_cmp);
    let sigma2 = n as f64 * rms * rms / (n - np) as f64;
    let limit = n as f64 * rms * rms + PROFILE_CHI2_95 * sigma2;
    let to_e = 1.0 / (4.0 / 3.0 * radius.sqrt());
    let (mut e_lo, mut e_hi) = (e, e);
    let mut points: Vec<f64> = (-16..=16)
        .filter(|i| *i != 0 && dc_se.is_finite())
        .map(|i| dc_fit + 0.25 * f64::from(i) * dc_se)
        .collect();
    let (mut m, mut rows) = (3.0f64, 3usize);
    while rows < n {
        // The contact point at the depth of the (rows + 1)-th deepest row leaves `rows` in
        // contact.
        points.push(sorted[n - 1 - rows]);
        m *= 1.08;
        rows = (m as usize).max(rows + 1);
    }
    // Hertz's sums over the rows in contact, the rows sorted deepest first: a contact point
    // visits only the rows past it (about 14 n rows in all, not 110 n).
    let mut by_depth: Vec<(f64, f64)> = data
        .depth
        .iter()
        .copied()
        .zip(data.force.iter().copied())
        .collect();
    by_depth.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (sf, sff) = data.force.iter().fold((0.0, 0.0), |(a, b), f| (a + f, b + f * f));
    for dc in points {
        let (k, cost) = match model {
            ContactModel::Hertz => hertz_profile_sorted(&by_depth, dc, sf, sff),
            _ => match dmt_profile(data, dc) {
                Some((k, a, _, c)) if a > 0.0 => (k, c),
                _ => (0.0, f64::INFINITY),
            },
        };
        if k > 0.0 && cost <= limit {
            e_lo = e_lo.min(k * to_e);
            e_hi = e_hi.max(k * to_e);
        }
    }
    Some((e_lo, e_hi))
}

fn unresolvable(reason: String) -> Error {
    Error::Unresolvable { model: "fit", reason }
}

/// Fewest rows on either side of the contact point for it to be determined.
pub const EDGE_ROWS: usize = 10;

/// Warnings on a fit whose parameters the data may not determine: correlations above 0.99,
/// standard errors above half the value, the contact point at the edge of the data (fewer
/// than [`EDGE_ROWS`] rows on one side), residuals far above the baseline noise (rms over 3 σ).
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
        ContactModel::MaugisDugdale => vec![
            ("work of adhesion", fit.work_of_adhesion, fit.std_errors[0]),
            ("modulus", fit.modulus, fit.std_errors[1]),
            (
                "interaction range",
                fit.interaction_range.unwrap_or(0.0),
                fit.std_errors[4],
            ),
        ],
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
    if let Some((lo, hi)) = fit.modulus_interval
        && (hi > 2.0 * fit.modulus || lo < 0.5 * fit.modulus)
    {
        out.push(format!(
            "the modulus is not determined by these data: with the contact point elsewhere, plane-strain moduli from {} to {} Pa fit within the noise (95 % profile)",
            crate::render::labels::fmt_sig(lo, 2),
            crate::render::labels::fmt_sig(hi, 2)
        ));
    }
    if fit.model == ContactModel::MaugisDugdale {
        // Z₀ is the last parameter; its valley in the cost is long and curved where it is
        // strongly correlated with another, and the linearised error then understates it.
        let k = np - 1;
        if let Some((j, r)) = (0..k)
            .map(|j| (j, fit.correlation[k * np + j]))
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            && r.abs() > 0.9
        {
            out.push(format!(
                "the interaction range is weakly determined (correlation {} with the {}): its standard error, from the linearised fit, understates its uncertainty",
                crate::params::fmt_sig((r * 1000.0).round() / 1000.0),
                names[j].replace('_', " ")
            ));
        }
    }
    let n = data.depth.len();
    let below = data.depth.iter().filter(|d| **d < fit.contact_point).count();
    let edge = EDGE_ROWS.min(n / 4).max(1);
    if below < edge || n - below < edge {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hertz profile from rows sorted by depth equals the plain one.
    #[test]
    fn sorted_hertz_profile_matches() {
        let depth: Vec<f64> = (0..200).map(|k| ((k * 37) % 200) as f64 * 1e-9).collect();
        let force: Vec<f64> = depth
            .iter()
            .map(|d| 3.0 * (d - 80e-9).max(0.0).powf(1.5) + 1e-12 * ((d * 1e9).sin()))
            .collect();
        let contact = vec![true; depth.len()];
        let data = FitData {
            depth: &depth,
            force: &force,
            in_contact: &contact,
            noise: 0.0,
        };
        let mut rows: Vec<(f64, f64)> = depth.iter().copied().zip(force.iter().copied()).collect();
        rows.sort_by(|a, b| b.0.total_cmp(&a.0));
        let (sf, sff) = force.iter().fold((0.0, 0.0), |(a, b), f| (a + f, b + f * f));
        for dc in [-1e-9, 50e-9, 80e-9, 150e-9, 198.5e-9, 300e-9] {
            let (k, _, c) = hertz_profile(&data, dc);
            let (k2, c2) = hertz_profile_sorted(&rows, dc, sf, sff);
            assert!((k - k2).abs() <= 1e-9 * k.abs().max(1e-30), "{dc}: {k} {k2}");
            assert!((c - c2).abs() <= 1e-9 * c.abs() + 1e-40, "{dc}: {c} {c2}");
        }
    }

    /// The fast inversion agrees with the Newton iteration of the model everywhere on the
    /// branch, at the fold, in the table and beyond it.
    #[test]
    fn fast_jkr_inversion_matches_the_model() {
        let s_d = sphere_depth_minimum_radius().sqrt();
        let h_d = s_d.powi(4) - 4.0 / 3.0 * s_d;
        let mut worst = (0.0f64, 0.0);
        for k in 0..20000 {
            let hb = h_d + 1e-12 * 1.0019f64.powi(k);
            if hb > 1e8 {
                break;
            }
            let root = JkrTable::get().root(hb);
            assert!(root.on_branch, "h̄ − h̄_D = {}", hb - h_d);
            let (a, b) = (root.s * root.s, sphere_radius_at_depth(hb));
            // ds/dh̄ = 1/(4s³ − 4/3), to the table's accuracy and, near the fold, to the
            // round-off of h̄ − h̄_D (1e-16 of h̄_D, relative to h̄ − h̄_D).
            let exact = 1.0 / (4.0 * root.s.powi(3) - 4.0 / 3.0);
            let slope_tol = 1e-5 + 2e-16 / (hb - h_d);
            assert!(
                (root.ds_dh - exact).abs() <= slope_tol * exact,
                "ds/dh̄ at h̄ − h̄_D = {}: {} against {exact}",
                hb - h_d,
                root.ds_dh
            );
            // Near the fold the depth's round-off (1e-16 of h̄_D) moves ā by about
            // 1e-16/√(h̄ − h̄_D) in either method (the slope of h̄(s) vanishes there).
            let tol = 1e-13 + 1e-15 / (hb - h_d).sqrt();
            if (a - b).abs() / b / tol > worst.0 {
                worst = ((a - b).abs() / b / tol, hb - h_d);
            }
        }
        assert!(worst.0 < 1.0, "{worst:?}");
        for below in [h_d - 1.0, h_d, f64::NAN] {
            let root = JkrTable::get().root(below);
            assert_eq!((root.s, root.ds_dh, root.on_branch), (s_d, 0.0, false), "{below}");
        }
    }
}
