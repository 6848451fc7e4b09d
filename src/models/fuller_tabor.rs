//! The Fuller-Tabor model of adhesion of a rough surface, Eqs. (1.9)-(1.15): Greenwood-Williamson
//! asperities of equal radius and Gaussian heights, each obeying the JKR theory.
//!
//! Everything is non-dimensional: heights, separations and depths in units of
//! h_o = |h_D| = (27π²Rw²/64E*²)^(1/3) (the magnitude of the JKR pull-off depth, see ERRATA for
//! (1.11)-(1.14)), forces per asperity in units of P_o = |P_C| = (3/2)πwR. The roughness enters
//! through the single number θ = σ_rms/h_o (Fuller and Tabor's adhesion parameter).
//!
//! The JKR curve of one asperity is parametrised by its contact radius ā (in units of
//! a₀ = (πR²w/E*)^(1/3)): h/h_o = (4/3) h̄(ā), P/P_o = (2/3) P̄(ā) with h̄, P̄ of
//! [`crate::models::classical::jkr_bar`]. Integrating (1.14) over ā instead of h removes the
//! square-root singularity of dP/dh at the pull-off point D and needs no root solve per
//! quadrature node.

use crate::error::{Error, Result};
use crate::models::classical::jkr_bar;
use crate::numerics::quadrature::integrate;

/// Ratio h₀/h_o between the JKR depth scale and |h_D|: h_o = (3/4) h₀.
const H0_OVER_HO: f64 = 4.0 / 3.0;
/// Ratio P₀/P_o between πwR and |P_C| = (3/2)πwR.
const P0_OVER_PO: f64 = 2.0 / 3.0;
/// Heights beyond this many σ above the mean carry no asperities in double precision
/// (the Gaussian density there is below 1e-17 of its peak).
const TAIL_SIGMAS: f64 = 9.0;

/// Phase of a contact cycle, which fixes the lower limit L of (1.14) by (1.15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// Approach: asperities touch when their height exceeds the separation, L = 0.
    Loading,
    /// Retraction after reaching the minimum separation `d_min`: asperities that touched stay
    /// in contact until stretched to −h_o, L = max(−1, d_min − d).
    Unloading {
        /// Minimum separation reached during loading [h_o].
        d_min: f64,
    },
}

/// A loading-unloading cycle in separation control.
#[derive(Debug, Clone, PartialEq)]
pub struct FtCycle {
    /// (d, P/(N P_o)) on approach, d decreasing.
    pub loading: Vec<(f64, f64)>,
    /// (d, P/(N P_o)) on retraction, d increasing.
    pub unloading: Vec<(f64, f64)>,
    /// Most negative force on retraction (the adhesive force) [N P_o].
    pub adhesive_force: f64,
    /// Separation at the adhesive force [h_o].
    pub adhesive_force_separation: f64,
    /// Energy lost over the cycle, ∫(P_loading − P_unloading) dd [N P_o h_o].
    pub energy_loss: f64,
}

/// The Fuller-Tabor model for one roughness θ = σ_rms/h_o.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullerTabor {
    theta: f64,
}

impl FullerTabor {
    /// The model for θ = σ_rms/h_o.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless θ > 0 is finite.
    pub fn new(sigma_over_ho: f64) -> Result<Self> {
        if sigma_over_ho.is_finite() && sigma_over_ho > 0.0 {
            Ok(Self { theta: sigma_over_ho })
        } else {
            Err(Error::invalid("sigma_over_ho", sigma_over_ho, "must be positive"))
        }
    }

    /// θ = σ_rms/h_o.
    pub fn theta(&self) -> f64 {
        self.theta
    }

    /// Gaussian height density φ(z) of (1.9), z in units of h_o.
    ///
    /// Implements Eq. (1.9): `φ(z) = exp(−z²/2σ²) / (√(2π) σ)`.
    pub fn height_density(&self, z: f64) -> f64 {
        let t = self.theta;
        (-0.5 * (z / t).powi(2)).exp() / ((2.0 * std::f64::consts::PI).sqrt() * t)
    }

    /// Fraction of asperities in contact at separation d on loading, n/N of (1.10):
    /// `∫_d^∞ φ(z) dz = erfc(d/(√2 σ))/2`.
    ///
    /// # Errors
    /// If the quadrature fails.
    pub fn contact_fraction(&self, d: f64) -> Result<f64> {
        let hi = TAIL_SIGMAS * self.theta;
        if d >= hi {
            return Ok(0.0);
        }
        let lo = d.max(-TAIL_SIGMAS * self.theta);
        Ok(integrate(|z| self.height_density(z), lo, hi, 1e-14, 1e-12)?.value)
    }

    /// Total force at separation d, P/(N P_o).
    ///
    /// Implements Eqs. (1.14)-(1.15):
    /// ```text
    /// P(d) = N P_o ∫_L^∞ F(h/h_o) φ(h + d) dh,   L = 0 (loading),  L = max(−h_o, d_min − d) (unloading)
    /// ```
    /// with F the asperity's JKR force, evaluated as an integral over the asperity contact
    /// radius.
    ///
    /// # Errors
    /// If the quadrature fails to converge.
    pub fn force(&self, d: f64, phase: Phase) -> Result<f64> {
        let lower = match phase {
            Phase::Loading => 0.0,
            Phase::Unloading { d_min } => (d_min - d).max(-1.0),
        };
        let upper = TAIL_SIGMAS * self.theta - d;
        if upper <= lower {
            return Ok(0.0);
        }
        let a_lo = jkr_bar::stable_radius_at_depth(lower / H0_OVER_HO)?;
        let a_hi = jkr_bar::stable_radius_at_depth(upper / H0_OVER_HO)?;
        let integrand = |a: f64| {
            let h = H0_OVER_HO * jkr_bar::depth(a);
            let dh = H0_OVER_HO * jkr_bar::depth_slope(a);
            P0_OVER_PO * jkr_bar::force(a) * self.height_density(h + d) * dh
        };
        Ok(integrate(integrand, a_lo, a_hi, 1e-13, 1e-10)?.value)
    }

    /// A cycle from `d_start` down to `d_min` and back, `n` separations per phase.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless d_min < d_start and n ≥ 2; quadrature failures.
    pub fn cycle(&self, d_start: f64, d_min: f64, n: usize) -> Result<FtCycle> {
        if d_min.partial_cmp(&d_start) != Some(std::cmp::Ordering::Less) {
            return Err(Error::invalid(
                "d_min",
                d_min,
                "must be below the starting separation",
            ));
        }
        if n < 2 {
            return Err(Error::invalid("points", n, "must be at least 2"));
        }
        let step = (d_start - d_min) / (n - 1) as f64;
        let ds: Vec<f64> = (0..n).map(|i| d_min + step * i as f64).collect();
        let loading: Vec<(f64, f64)> = ds
            .iter()
            .rev()
            .map(|&d| Ok((d, self.force(d, Phase::Loading)?)))
            .collect::<Result<_>>()?;
        let unloading: Vec<(f64, f64)> = ds
            .iter()
            .map(|&d| Ok((d, self.force(d, Phase::Unloading { d_min })?)))
            .collect::<Result<_>>()?;
        let (adhesive_force_separation, adhesive_force) = unloading
            .iter()
            .copied()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("n >= 2 points");
        // Loss by the trapezoid rule on the common grid.
        let energy_loss = loading
            .iter()
            .rev()
            .zip(&unloading)
            .map(|(l, u)| l.1 - u.1)
            .collect::<Vec<_>>()
            .windows(2)
            .map(|w| 0.5 * step * (w[0] + w[1]))
            .sum();
        Ok(FtCycle {
            loading,
            unloading,
            adhesive_force,
            adhesive_force_separation,
            energy_loss,
        })
    }
}

/// The asperity depth as a function of χ = (1 + P/P_o)^(1/2), Eq. (1.11), on its two branches.
///
/// Implements Eq. (1.11):
/// ```text
/// h/h_o = (3χ − 1) [(1 + χ)/9]^(1/3),    χ ≥ 0          (large contact, ā ≥ ā_C)
/// h/h_o = −(3χ + 1) [(1 − χ)/9]^(1/3),   0 ≤ χ ≤ 2/3    (small contact, ā_D ≤ ā ≤ ā_C)
/// ```
/// `large_branch` selects the first line. Returns `None` outside the branch's χ range.
pub fn asperity_depth_from_chi(chi: f64, large_branch: bool) -> Option<f64> {
    if large_branch {
        (chi >= 0.0).then(|| (3.0 * chi - 1.0) * ((1.0 + chi) / 9.0).cbrt())
    } else {
        (0.0..=2.0 / 3.0)
            .contains(&chi)
            .then(|| -(3.0 * chi + 1.0) * ((1.0 - chi) / 9.0).cbrt())
    }
}

/// The asperity force F(h/h_o) = P/P_o of (1.13) on the displacement-stable JKR branch, for
/// h/h_o ≥ −1; `None` below (the asperity has detached).
///
/// Implements Eq. (1.13) by solving (1.2) for the contact radius.
pub fn asperity_force(h_over_ho: f64) -> Option<f64> {
    if h_over_ho < -1.0 {
        return None;
    }
    let a = jkr_bar::stable_radius_at_depth(h_over_ho / H0_OVER_HO).ok()?;
    Some(P0_OVER_PO * jkr_bar::force(a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq_1_11_agrees_with_the_jkr_curve_on_both_branches() {
        for k in 0..=60 {
            let chi = k as f64 / 60.0 * 2.0;
            if let Some(h) = asperity_depth_from_chi(chi, true) {
                let f = asperity_force(h).unwrap();
                assert!((f - (chi * chi - 1.0)).abs() < 1e-10, "chi {chi}: {f}");
            }
            if let Some(h) = asperity_depth_from_chi(chi, false) {
                let f = asperity_force(h).unwrap();
                assert!((f - (chi * chi - 1.0)).abs() < 1e-9, "chi {chi}: {f}");
            }
        }
        // The ends of the small-contact branch are C (χ = 0) and D (χ = 2/3, h = −h_o).
        assert!((asperity_depth_from_chi(2.0 / 3.0, false).unwrap() + 1.0).abs() < 1e-14);
    }
}
