//! Depth-dependent hysteresis at large roughness, section 3.2.2 and appendix B.2: the mean
//! Maugis-Dugdale loss per asperity over Nayak's curvature distribution (3.11)-(3.14), the
//! asperity density (3.9), the nominal contact-area change from the JKR theory (B.2.1)-(B.2.3),
//! and the depth-dependent loss ΔE_D (3.15) and its per-area form (3.19).
//!
//! The surface enters only through its spectral moments m0, m2, m4 (convention m0 = σ_rms² of
//! (3.8); see [`crate::surface::spectrum`]): from a PSD model such as (3.16), from any other
//! PSD, or from a measured height map ([`crate::surface::moments_of_map`]). SI units throughout.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::models::maugis_dugdale::{empirical_loss, energy_loss, loss_table};
use crate::numerics::quadrature::integrate;
use crate::surface::{Moments, nayak_curvature_pdf};

/// How the normalised loss per asperity ΔĒ_md(χ, ℓ) is evaluated inside (3.13).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LossMethod {
    /// The exact loss (3.4) through the interpolated table (relative error below 1e-7).
    Table,
    /// The exact loss (3.4) by quadrature at every node (slow; the reference).
    Quadrature,
    /// The empirical function (3.6), as the dissertation does.
    Empirical,
}

/// The depth-dependent-hysteresis model of a smooth tip on a rough substrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ddh {
    /// Spectral moments of the substrate (already scaled by k² where section 3.3 scales it).
    pub moments: Moments,
    /// Tip radius R_t [m].
    pub tip_radius: f64,
    /// Effective modulus E* [Pa].
    pub modulus: f64,
    /// Work of adhesion w of the asperity contacts [J/m²].
    pub work_of_adhesion: f64,
    /// Range of the adhesive interaction Z₀ [m] (Dugdale), Eq. (3.2).
    pub range: f64,
}

/// The curvature variable t = −√(3/m4) k_m is integrated over [−T, 0]; the density (3.11) has
/// fallen below e^{−T²/4}·T² ≈ 1e-150 there.
const T_CUTOFF: f64 = 37.0;

impl Ddh {
    /// Validated model.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first non-positive or non-finite value, or a
    /// Nayak parameter α = m0 m4/m2² ≤ 1.5 (no valid summit statistics (3.7)).
    pub fn new(
        moments: Moments,
        tip_radius: f64,
        modulus: f64,
        work_of_adhesion: f64,
        range: f64,
    ) -> Result<Self> {
        for (name, v) in [
            ("m0", moments.m0),
            ("m2", moments.m2),
            ("m4", moments.m4),
            ("tip_radius", tip_radius),
            ("modulus", modulus),
            ("work_of_adhesion", work_of_adhesion),
            ("range", range),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be positive and finite"));
            }
        }
        let alpha = moments.nayak_alpha();
        if alpha <= 1.5 {
            return Err(Error::invalid(
                "nayak_alpha",
                alpha,
                "must exceed 1.5 for Nayak's summit statistics (3.7)",
            ));
        }
        Ok(Self {
            moments,
            tip_radius,
            modulus,
            work_of_adhesion,
            range,
        })
    }

    /// χ = w/(E*Z₀), Eq. (3.2).
    pub fn chi(&self) -> f64 {
        self.work_of_adhesion / (self.modulus * self.range)
    }

    /// Effective radius of an asperity of curvature variable t ≤ 0 against the tip.
    ///
    /// Implements Eq. (3.14b): `R(t) = (1/R_t − √(m4/3) t)^(−1)` [m].
    pub fn asperity_radius(&self, t: f64) -> f64 {
        1.0 / (1.0 / self.tip_radius - (self.moments.m4 / 3.0).sqrt() * t)
    }

    /// ℓ of an asperity, Eq. (3.14a): `ℓ(t) = πw/(E* R(t))`.
    pub fn ell(&self, t: f64) -> f64 {
        PI * self.work_of_adhesion / (self.modulus * self.asperity_radius(t))
    }

    /// Asperity density η [1/m²], Eq. (3.9): `η = m4/(6π√3 m2)`.
    pub fn asperity_density(&self) -> f64 {
        self.moments.asperity_density()
    }

    /// The mean loss per depth-dependent asperity ⟨ΔE_md⟩ [J].
    ///
    /// Implements Eqs. (3.12)-(3.13):
    /// ```text
    /// ⟨ΔE_md⟩ = 2E* ∫_{−∞}^0 ΔĒ_md(χ, ℓ(t)) p_κ(t) R³(t) dt
    /// ```
    /// with p_κ of (3.11) and ΔĒ_md exact (table or quadrature) or empirical (3.6).
    ///
    /// # Errors
    /// Quadrature failures; [`Error::Unresolvable`] from the MD model at extreme (χ, ℓ(t)).
    pub fn mean_loss(&self, method: LossMethod) -> Result<f64> {
        let chi = self.chi();
        let alpha = self.moments.nayak_alpha();
        let table = match method {
            LossMethod::Table => Some(loss_table()?),
            _ => None,
        };
        let err = std::cell::Cell::new(None);
        let integrand = |t: f64| {
            let r = self.asperity_radius(t);
            let ell = self.ell(t);
            let loss = match method {
                LossMethod::Table => table.map_or(f64::NAN, |tb| tb.loss(chi, ell)),
                LossMethod::Empirical => empirical_loss(chi, ell),
                LossMethod::Quadrature => match energy_loss(chi, ell) {
                    Ok(v) => v,
                    Err(e) => {
                        err.set(Some(e.to_string()));
                        f64::NAN
                    }
                },
            };
            loss * nayak_curvature_pdf(t, alpha) * r.powi(3)
        };
        let (rel, abs) = match method {
            LossMethod::Quadrature => (1e-7, 0.0),
            _ => (1e-10, 0.0),
        };
        let r = integrate(integrand, -T_CUTOFF, 0.0, abs, rel);
        if let Some(e) = err.take() {
            return Err(Error::Unresolvable {
                model: "depth-dependent hysteresis",
                reason: e,
            });
        }
        Ok(2.0 * self.modulus * r?.value)
    }

    /// Depth-dependent loss per unit nominal contact area, ΔE_D/ΔA_c = η⟨ΔE_md⟩ [J/m²]; with
    /// ΔA_c ≈ 4R_t|h_min| (B.2.3) this is (3.19), independent of the depth.
    ///
    /// # Errors
    /// As [`Ddh::mean_loss`].
    pub fn loss_per_area(&self, method: LossMethod) -> Result<f64> {
        Ok(self.asperity_density() * self.mean_loss(method)?)
    }

    /// Depth-dependent loss ΔE_D [J] for a nominal contact-area change ΔA_c [m²].
    ///
    /// Implements Eq. (3.15): `ΔE_D = η ΔA_c ⟨ΔE_md⟩`.
    ///
    /// # Errors
    /// As [`Ddh::mean_loss`].
    pub fn depth_dependent_loss(&self, area_change: f64, method: LossMethod) -> Result<f64> {
        Ok(area_change * self.loss_per_area(method)?)
    }
}

/// The nominal contact area of a smooth tip at the JKR level (appendix B.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrNominalArea {
    /// Tip radius R_t [m].
    pub tip_radius: f64,
    /// ℓ_JKR = πw/(E*R_t).
    pub ell: f64,
}

impl JkrNominalArea {
    /// The JKR estimate for a tip of radius R_t [m], modulus E* [Pa], work of adhesion w [J/m²].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for non-positive values.
    pub fn new(tip_radius: f64, modulus: f64, work_of_adhesion: f64) -> Result<Self> {
        for (name, v) in [
            ("tip_radius", tip_radius),
            ("modulus", modulus),
            ("jkr_work_of_adhesion", work_of_adhesion),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be positive and finite"));
            }
        }
        Ok(Self {
            tip_radius,
            ell: PI * work_of_adhesion / (modulus * tip_radius),
        })
    }

    /// Contact radius ā = a/R_t on the loading branch at depth h̄ = h/R_t ≤ 0 (indentation).
    ///
    /// Solves Eq. (B.2.1): `h̄ = −ā² + (2ℓ_JKR ā)^(1/2)` on its stable branch ā ≥ ā₀,
    /// ā₀ = (2ℓ_JKR)^(1/3) where h̄ = 0.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for h̄ > 0.
    pub fn radius(&self, h_bar: f64) -> Result<f64> {
        if !(h_bar <= 0.0 && h_bar.is_finite()) {
            return Err(Error::invalid("h_min", h_bar, "must be an indentation (h <= 0)"));
        }
        let a0 = (2.0 * self.ell).cbrt();
        let f = |a: f64| -a * a + (2.0 * self.ell * a).sqrt() - h_bar;
        let mut hi = a0 + (-h_bar).sqrt() + 1.0;
        while f(hi) > 0.0 {
            hi *= 2.0;
        }
        crate::numerics::roots::brent(f, a0, hi, 1e-15)
    }

    /// ΔA_c [m²] for the maximum depth |h_min| [m], exact.
    ///
    /// Implements Eq. (B.2.2):
    /// ```text
    /// ΔA_c = πR_t²|h̄_min| [1 + ((2ℓ ā_h)^(1/2) − (2ℓ)^(2/3)) / (ā_h² − (2ℓ ā_h)^(1/2))]
    /// ```
    /// which equals πR_t²(ā_h² − ā₀²).
    ///
    /// # Errors
    /// As [`JkrNominalArea::radius`].
    pub fn area_change(&self, depth: f64) -> Result<f64> {
        let h = -depth.abs() / self.tip_radius;
        if h == 0.0 {
            return Ok(0.0);
        }
        let a = self.radius(h)?;
        let root = (2.0 * self.ell * a).sqrt();
        let bracket = 1.0 + (root - (2.0 * self.ell).powf(2.0 / 3.0)) / (a * a - root);
        Ok(PI * self.tip_radius.powi(2) * h.abs() * bracket)
    }

    /// The bracket of (B.2.2) at depth |h_min| [m] (printed range 1.19 ... 1.33, taken as 1.26).
    ///
    /// # Errors
    /// As [`JkrNominalArea::radius`].
    pub fn area_bracket(&self, depth: f64) -> Result<f64> {
        Ok(self.area_change(depth)? / (PI * self.tip_radius * depth.abs()))
    }
}

/// ΔA_c ≈ 4R_t|h_min| [m²], Eq. (B.2.3) (the bracket of (B.2.2) taken as 1.26 ≈ 4/π).
pub fn area_change_approx(tip_radius: f64, depth: f64) -> f64 {
    4.0 * tip_radius * depth.abs()
}
