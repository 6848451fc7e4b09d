//! Fit of the PSD model (3.16) to an isotropic PSD by nonlinear least squares in log space
//! (section 3.3, appendix B.1): parameters σ_rms, L_c, n, with the cut-off q0 fixed (as in
//! (3.17)) or free.

use serde::Serialize;

use super::analysis::RadialPsd;
use super::spectrum::Spectrum;
use crate::error::{Error, Result};
use crate::numerics::least_squares::{LmOptions, levenberg_marquardt};

/// The cut-off wavenumber q0 of (3.16) in a fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Cutoff {
    /// Held at this value [1/m] (the dissertation fixes q0 = 1.0e8 1/m before fitting).
    Fixed(f64),
    /// Fitted, starting from this value [1/m].
    Free(f64),
    /// No cut-off (q0 = ∞, the plain k-correlation model).
    None,
}

/// Fitted (3.16) parameters and their standard errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AbcFit {
    /// σ_rms [m].
    pub rms: f64,
    /// Standard error of σ_rms [m].
    pub rms_error: f64,
    /// L_c [m].
    pub correlation_length: f64,
    /// Standard error of L_c [m].
    pub correlation_length_error: f64,
    /// Power-law index n [-].
    pub exponent: f64,
    /// Standard error of n [-].
    pub exponent_error: f64,
    /// q0 [1/m] (infinite without cut-off).
    pub cutoff: f64,
    /// Standard error of q0 [1/m] (0 when held fixed).
    pub cutoff_error: f64,
    /// RMS of the residuals ln C_model − ln C_data.
    pub log_residual_rms: f64,
    /// Number of PSD points fitted.
    pub points: usize,
}

impl AbcFit {
    /// The fitted spectrum.
    pub fn spectrum(&self) -> Spectrum {
        Spectrum::Abc {
            rms: self.rms,
            correlation_length: self.correlation_length,
            exponent: self.exponent,
            cutoff: self.cutoff.is_finite().then_some(self.cutoff),
        }
    }
}

/// Fit (3.16) to the isotropic PSD `psd` (points with C > 0), minimising Σ (ln C_model − ln C)²
/// over ln σ_rms, ln L_c, n (and ln q0 when free) by Levenberg-Marquardt.
///
/// # Errors
/// [`Error::InvalidParameter`] with fewer usable points than parameters or a bad cut-off;
/// [`Error::NoConvergence`] when the fit does not converge; [`Error::Unresolvable`] when the
/// fit is degenerate: a standard error undefined, L_c outside 0.1/q_max to 10/q_min of the
/// fitted points, or n not positive.
pub fn fit_abc(psd: &RadialPsd, cutoff: Cutoff) -> Result<AbcFit> {
    let pts: Vec<(f64, f64)> = psd
        .q
        .iter()
        .zip(&psd.c)
        .filter(|(q, c)| **q > 0.0 && **c > 0.0 && c.is_finite())
        .map(|(q, c)| (*q, *c))
        .collect();
    let n_par = if matches!(cutoff, Cutoff::Free(_)) { 4 } else { 3 };
    if pts.len() < n_par + 1 {
        return Err(Error::invalid(
            "psd",
            pts.len(),
            format!("need more than {n_par} positive PSD points to fit (3.16)"),
        ));
    }
    if let Cutoff::Fixed(q0) | Cutoff::Free(q0) = cutoff
        && !(q0 > 0.0 && q0.is_finite())
    {
        return Err(Error::invalid("cutoff", q0, "must be positive and finite"));
    }
    // Start: σ from m0 = 2π ∫ q C dq (trapezoid), L_c from the half-plateau wavenumber.
    let m0: f64 = pts
        .windows(2)
        .map(|w| std::f64::consts::PI * (w[1].0 - w[0].0) * (w[0].0 * w[0].1 + w[1].0 * w[1].1))
        .sum();
    let plateau = pts.iter().take(3).map(|p| p.1).sum::<f64>() / pts.len().min(3) as f64;
    let q_half = pts
        .iter()
        .find(|p| p.1 < 0.5 * plateau)
        .map_or(pts[pts.len() / 2].0, |p| p.0);
    let mut x0 = vec![m0.max(f64::MIN_POSITIVE).sqrt().ln(), (1.0 / q_half).ln(), 2.0];
    if let Cutoff::Free(q0) = cutoff {
        x0.push(q0.ln());
    }
    let model = |x: &[f64]| -> Option<Spectrum> {
        let q0 = match cutoff {
            Cutoff::Fixed(q0) => Some(q0),
            Cutoff::Free(_) => Some(x[3].exp()),
            Cutoff::None => None,
        };
        Some(Spectrum::Abc {
            rms: x[0].exp(),
            correlation_length: x[1].exp(),
            exponent: x[2],
            cutoff: q0,
        })
    };
    let residuals = |x: &[f64]| -> Vec<f64> {
        match model(x).and_then(|s| s.prepare().ok()) {
            Some(p) => pts.iter().map(|&(q, c)| p.psd(q).ln() - c.ln()).collect(),
            None => vec![f64::NAN; pts.len()],
        }
    };
    let sol = levenberg_marquardt(&residuals, None, &x0, LmOptions::default())?;
    let x = &sol.x;
    let se = &sol.std_errors;
    let (cut, cut_err) = match cutoff {
        Cutoff::Fixed(q0) => (q0, 0.0),
        Cutoff::Free(_) => (x[3].exp(), x[3].exp() * se[3]),
        Cutoff::None => (f64::INFINITY, 0.0),
    };
    let (q_min, q_max) = (pts[0].0, pts[pts.len() - 1].0);
    let degenerate = |reason: String| Error::Unresolvable {
        model: "fit of (3.16)",
        reason: format!("degenerate, not reported: {reason}"),
    };
    if let Some(k) = se.iter().take(n_par).position(|e| !e.is_finite()) {
        let name = ["sigma_rms", "L_c", "n", "q0"][k];
        return Err(degenerate(format!(
            "the standard error of {name} is undefined (the PSD does not determine the parameters; \
             check the pixel size)"
        )));
    }
    let lc = x[1].exp();
    if !(lc >= 0.1 / q_max && lc <= 10.0 / q_min) {
        return Err(degenerate(format!(
            "L_c = {} m is outside the lengths the map resolves ({} to {} m; check the pixel size)",
            crate::params::fmt_sig(lc),
            crate::params::fmt_sig(0.1 / q_max),
            crate::params::fmt_sig(10.0 / q_min)
        )));
    }
    if x[2].is_nan() || x[2] <= 0.0 {
        return Err(degenerate(format!(
            "n = {} is not positive",
            crate::params::fmt_sig(x[2])
        )));
    }
    Ok(AbcFit {
        rms: x[0].exp(),
        rms_error: x[0].exp() * se[0],
        correlation_length: x[1].exp(),
        correlation_length_error: x[1].exp() * se[1],
        exponent: x[2],
        exponent_error: se[2],
        cutoff: cut,
        cutoff_error: cut_err,
        log_residual_rms: sol.residual_norm / (pts.len() as f64).sqrt(),
        points: pts.len(),
    })
}
