//! Isotropic power spectra of random rough surfaces and their spectral moments (section 3.2.2,
//! appendices B.1 and C.1).
//!
//! ## Convention
//! Every PSD here is the isotropic C^iso(q) of (3.8), normalised so that
//! m0 = 2π ∫ q C^iso(q) dq = σ_rms². In terms of the autocorrelation R(δ) this is
//! C = (1/4π²) ∫ R(x) e^{-iq·x} d²x, the form of (C.1.3); (B.1.3)/(B.1.9) omit the 1/(4π²)
//! (see ERRATA). Other libraries differ by factors of 2 and (2π)².
//!
//! The moments are those of a profile in one direction, m_n = m_{n0} of (B.1.5):
//! m0 = σ_rms², m2 = ⟨(∂z/∂x)²⟩, m4 = ⟨(∂²z/∂x²)²⟩, from (3.8)
//! m_n = [2√π Γ((1+n)/2)/Γ(1+n/2)] ∫ q^{n+1} C^iso dq, i.e. the prefactors 2π, π, 3π/4.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::numerics::quadrature::{integrate, integrate_to_infinity};

/// Relative tolerance of the moment quadratures.
const MOMENT_REL_TOL: f64 = 1e-10;

/// The PSD (3.16) with the parameters (3.17) of section 3.3: the Si mold's surface
/// (σ_rms = 1.45 nm, L_c = 20.1 nm, n = 3.28, q_0 = 1e8 m⁻¹).
pub const PSD_3_17: Spectrum = Spectrum::Abc {
    rms: 1.45e-9,
    correlation_length: 20.1e-9,
    exponent: 3.28,
    cutoff: Some(1.0e8),
};

/// An isotropic PSD model, each scaled to its RMS height σ_rms [m].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Spectrum {
    /// Gaussian autocorrelation R = σ² e^{-δ²/L_c²}, PSD (C.1.3):
    /// C(q) = σ² L_c²/(4π) e^{-L_c² q²/4}.
    Gaussian {
        /// RMS height σ_rms [m].
        rms: f64,
        /// Correlation length L_c [m].
        correlation_length: f64,
    },
    /// The modified k-correlation (ABC) model (3.16):
    /// C(q) = σ² L_c² e^{-q/q0} / [C0 (1 + L_c² q²)^n],
    /// C0 = 2π ∫ e^{-q/q0} L_c² q (1 + L_c² q²)^{-n} dq.
    Abc {
        /// RMS height σ_rms [m].
        rms: f64,
        /// Correlation length L_c [m].
        correlation_length: f64,
        /// Power-law index n [-] (n > 1 without cut-off; m2 needs n > 2, m4 n > 3).
        exponent: f64,
        /// Cut-off wavenumber q0 [1/m]; `None` for the plain k-correlation model (q0 = ∞).
        cutoff: Option<f64>,
    },
    /// Self-affine spectrum with roll-off: C = K for q_low ≤ q < q_roll,
    /// K (q/q_roll)^{-2(1+H)} for q_roll ≤ q ≤ q_high, zero elsewhere.
    SelfAffine {
        /// RMS height σ_rms [m].
        rms: f64,
        /// Hurst exponent H [-], 0 < H < 1.
        hurst: f64,
        /// Lower cut-off wavenumber [1/m] (0 allowed).
        q_low: f64,
        /// Roll-off wavenumber [1/m].
        q_roll: f64,
        /// Upper (short-wavelength) cut-off wavenumber [1/m].
        q_high: f64,
    },
}

/// Spectral moments of an isotropic surface in the convention m0 = σ_rms² (3.8).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Moments {
    /// m0 = σ_rms² [m²].
    pub m0: f64,
    /// m2, the mean square slope in one direction [-].
    pub m2: f64,
    /// m4, the mean square curvature in one direction [1/m²].
    pub m4: f64,
}

impl Moments {
    /// RMS height √m0 [m].
    pub fn rms(&self) -> f64 {
        self.m0.sqrt()
    }

    /// Nayak's parameter α = m0 m4 / m2² (section 3.2.2); α ≥ 1.5 for any surface
    /// with a valid (3.7), 3 for a Gaussian autocorrelation.
    pub fn nayak_alpha(&self) -> f64 {
        self.m0 * self.m4 / (self.m2 * self.m2)
    }

    /// Nayak's C1 = α/(2α − 3) of (3.7).
    pub fn nayak_c1(&self) -> f64 {
        nayak_c1(self.nayak_alpha())
    }

    /// Nayak's C2 = C1 √(12/α) of (3.7).
    pub fn nayak_c2(&self) -> f64 {
        nayak_c2(self.nayak_alpha())
    }

    /// Asperity (summit) density η = m4 / (6π√3 m2) [1/m²], Eq. (3.9).
    pub fn asperity_density(&self) -> f64 {
        self.m4 / (6.0 * PI * 3f64.sqrt() * self.m2)
    }

    /// The moments of the surface scaled by k (z -> k z): each moment times k², Sec. 3.3.
    pub fn scaled(&self, k: f64) -> Moments {
        let k2 = k * k;
        Moments {
            m0: self.m0 * k2,
            m2: self.m2 * k2,
            m4: self.m4 * k2,
        }
    }
}

/// Nayak's C1 = α/(2α − 3), Eq. (3.7).
pub fn nayak_c1(alpha: f64) -> f64 {
    alpha / (2.0 * alpha - 3.0)
}

/// Nayak's C2 = C1 √(12/α), Eq. (3.7).
pub fn nayak_c2(alpha: f64) -> f64 {
    nayak_c1(alpha) * (12.0 / alpha).sqrt()
}

/// Prefactor 2√π Γ((1+n)/2)/Γ(1+n/2) of (3.8) for n = 0, 2, 4: 2π, π, 3π/4.
const MOMENT_PREFACTOR: [f64; 3] = [2.0 * PI, PI, 0.75 * PI];

fn positive(name: &str, v: f64) -> Result<()> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(name, v, "must be positive and finite"))
    }
}

impl Spectrum {
    /// Check the parameters (positive lengths, valid exponents, ordered wavenumbers).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first bad parameter.
    pub fn validate(&self) -> Result<()> {
        match *self {
            Spectrum::Gaussian {
                rms,
                correlation_length,
            } => {
                positive("rms", rms)?;
                positive("correlation-length", correlation_length)
            }
            Spectrum::Abc {
                rms,
                correlation_length,
                exponent,
                cutoff,
            } => {
                positive("rms", rms)?;
                positive("correlation-length", correlation_length)?;
                positive("exponent", exponent)?;
                match cutoff {
                    Some(q0) => positive("cutoff", q0),
                    None if exponent > 1.0 => Ok(()),
                    None => Err(Error::invalid(
                        "exponent",
                        exponent,
                        "must exceed 1 without a cut-off wavenumber (m0 diverges)",
                    )),
                }
            }
            Spectrum::SelfAffine {
                rms,
                hurst,
                q_low,
                q_roll,
                q_high,
            } => {
                positive("rms", rms)?;
                if !(hurst > 0.0 && hurst < 1.0) {
                    return Err(Error::invalid("hurst", hurst, "must lie in (0, 1)"));
                }
                if !(q_low >= 0.0 && q_low.is_finite()) {
                    return Err(Error::invalid("q-low", q_low, "must be non-negative and finite"));
                }
                positive("q-roll", q_roll)?;
                positive("q-high", q_high)?;
                if q_roll < q_low {
                    return Err(Error::invalid("q-roll", q_roll, "must not be below q-low"));
                }
                if q_high <= q_roll {
                    return Err(Error::invalid("q-high", q_high, "must exceed q-roll"));
                }
                Ok(())
            }
        }
    }

    /// RMS height σ_rms [m].
    pub fn rms(&self) -> f64 {
        match *self {
            Spectrum::Gaussian { rms, .. } | Spectrum::Abc { rms, .. } | Spectrum::SelfAffine { rms, .. } => {
                rms
            }
        }
    }

    /// The same spectrum with RMS height `rms` (the shape is unchanged; C scales with rms²).
    pub fn with_rms(self, new: f64) -> Spectrum {
        match self {
            Spectrum::Gaussian {
                correlation_length, ..
            } => Spectrum::Gaussian {
                rms: new,
                correlation_length,
            },
            Spectrum::Abc {
                correlation_length,
                exponent,
                cutoff,
                ..
            } => Spectrum::Abc {
                rms: new,
                correlation_length,
                exponent,
                cutoff,
            },
            Spectrum::SelfAffine {
                hurst,
                q_low,
                q_roll,
                q_high,
                ..
            } => Spectrum::SelfAffine {
                rms: new,
                hurst,
                q_low,
                q_roll,
                q_high,
            },
        }
    }

    /// The PSD evaluated at many wavenumbers: validates once and precomputes the normalisation.
    ///
    /// # Errors
    /// As [`Spectrum::validate`], and a quadrature failure of the (3.16) normalisation C0.
    pub fn prepare(&self) -> Result<PreparedSpectrum> {
        self.validate()?;
        let amplitude = match *self {
            Spectrum::Gaussian {
                rms,
                correlation_length: lc,
            } => rms * rms * lc * lc / (4.0 * PI),
            Spectrum::Abc {
                rms,
                correlation_length: lc,
                exponent,
                cutoff,
            } => {
                // C0 = 2π J1 with J_k = ∫ s^k e^{-s/b} (1 + s²)^{-n} ds, s = L_c q, b = q0 L_c.
                rms * rms * lc * lc / (2.0 * PI * abc_integral(1, exponent, cutoff.map(|q0| q0 * lc))?)
            }
            Spectrum::SelfAffine {
                rms,
                hurst,
                q_low,
                q_roll,
                q_high,
            } => rms * rms / (2.0 * PI * self_affine_integral(1, hurst, q_low, q_roll, q_high)),
        };
        Ok(PreparedSpectrum {
            spectrum: *self,
            amplitude,
        })
    }

    /// C^iso(q) [m⁴] in the convention of (3.8); (C.1.3), (3.16) or the self-affine form.
    /// NaN for an invalid spectrum. Evaluates the (3.16) normalisation on every call: use
    /// [`Spectrum::prepare`] for many wavenumbers.
    pub fn psd(&self, q: f64) -> f64 {
        self.prepare().map_or(f64::NAN, |p| p.psd(q))
    }

    /// The spectral moments m0, m2, m4 of (3.8) over 0 ≤ q < ∞: closed forms for the Gaussian
    /// (m2 = 2σ²/L_c², m4 = 12σ²/L_c⁴), the self-affine model, and (3.16) without cut-off;
    /// adaptive quadrature for (3.16) with a cut-off.
    ///
    /// # Errors
    /// As [`Spectrum::validate`]; [`Error::Unresolvable`] when m2 or m4 diverge ((3.16)
    /// without cut-off and n ≤ 2 or n ≤ 3).
    pub fn moments(&self) -> Result<Moments> {
        self.validate()?;
        let s2 = self.rms() * self.rms();
        Ok(match *self {
            Spectrum::Gaussian {
                correlation_length: lc,
                ..
            } => Moments {
                m0: s2,
                m2: 2.0 * s2 / (lc * lc),
                m4: 12.0 * s2 / lc.powi(4),
            },
            Spectrum::Abc {
                correlation_length: lc,
                exponent,
                cutoff,
                ..
            } => {
                if cutoff.is_none() && exponent <= 3.0 {
                    return Err(Error::Unresolvable {
                        model: "k-correlation PSD (3.16)",
                        reason: format!("m4 diverges for n = {exponent} <= 3 without a cut-off wavenumber"),
                    });
                }
                let b = cutoff.map(|q0| q0 * lc);
                let j1 = abc_integral(1, exponent, b)?;
                let j3 = abc_integral(3, exponent, b)?;
                let j5 = abc_integral(5, exponent, b)?;
                // m_n = c_n K J_{n+1} / L_c^{n+2}, K = σ² L_c²/(2π J1).
                Moments {
                    m0: s2,
                    m2: s2 * j3 / (2.0 * j1 * lc * lc),
                    m4: 0.375 * s2 * j5 / (j1 * lc.powi(4)),
                }
            }
            Spectrum::SelfAffine {
                hurst,
                q_low,
                q_roll,
                q_high,
                ..
            } => {
                let i1 = self_affine_integral(1, hurst, q_low, q_roll, q_high);
                let k = s2 / (2.0 * PI * i1);
                Moments {
                    m0: s2,
                    m2: MOMENT_PREFACTOR[1] * k * self_affine_integral(3, hurst, q_low, q_roll, q_high),
                    m4: MOMENT_PREFACTOR[2] * k * self_affine_integral(5, hurst, q_low, q_roll, q_high),
                }
            }
        })
    }

    /// The moments of the part of the spectrum inside the band q_min ≤ q ≤ q_max (what a grid
    /// resolves), by [`moments_of_psd`].
    ///
    /// # Errors
    /// As [`Spectrum::prepare`] and [`moments_of_psd`].
    pub fn moments_in_band(&self, q_min: f64, q_max: f64) -> Result<Moments> {
        let p = self.prepare()?;
        moments_of_psd(|q| p.psd(q), q_min, q_max)
    }
}

/// A validated spectrum with its normalisation precomputed (see [`Spectrum::prepare`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreparedSpectrum {
    spectrum: Spectrum,
    amplitude: f64,
}

impl PreparedSpectrum {
    /// The spectrum.
    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }

    /// C^iso(q) [m⁴] in the convention of (3.8): (C.1.3), (3.16), or the self-affine form.
    pub fn psd(&self, q: f64) -> f64 {
        let k = self.amplitude;
        match self.spectrum {
            Spectrum::Gaussian {
                correlation_length: lc,
                ..
            } => k * (-0.25 * lc * lc * q * q).exp(),
            Spectrum::Abc {
                correlation_length: lc,
                exponent,
                cutoff,
                ..
            } => {
                let damp = cutoff.map_or(1.0, |q0| (-q / q0).exp());
                k * damp * (1.0 + lc * lc * q * q).powf(-exponent)
            }
            Spectrum::SelfAffine { hurst, .. } => k * self.self_affine_shape(q, -2.0 * (1.0 + hurst)),
        }
    }

    /// The self-affine spectrum's shape at `q` against its plateau: 0 outside [q_low, q_high],
    /// 1 below the roll-off q_roll, (q/q_roll)^`power` above it (`power` = −2(1 + H) for the
    /// spectrum, −(1 + H) for its square root); 0 for the other spectra.
    fn self_affine_shape(&self, q: f64, power: f64) -> f64 {
        let Spectrum::SelfAffine {
            q_low,
            q_roll,
            q_high,
            ..
        } = self.spectrum
        else {
            return 0.0;
        };
        if q < q_low || q > q_high {
            0.0
        } else if q < q_roll {
            1.0
        } else {
            (q / q_roll).powf(power)
        }
    }

    /// √C^iso(q) [m²], the filter H of (C.1.12) that [`crate::surface::generate`] applies to white
    /// noise: [`PreparedSpectrum::psd`] with its square root taken inside the exponentials
    /// (one logarithm and one exponential per wavenumber for (3.16)).
    pub fn sqrt_psd(&self, q: f64) -> f64 {
        let k = self.amplitude.sqrt();
        match self.spectrum {
            Spectrum::Gaussian {
                correlation_length: lc,
                ..
            } => k * (-0.125 * lc * lc * q * q).exp(),
            Spectrum::Abc {
                correlation_length: lc,
                exponent,
                cutoff,
                ..
            } => {
                let damp = cutoff.map_or(0.0, |q0| -0.5 * q / q0);
                k * (damp - 0.5 * exponent * (lc * lc * q * q).ln_1p()).exp()
            }
            Spectrum::SelfAffine { hurst, .. } => k * self.self_affine_shape(q, -(1.0 + hurst)),
        }
    }
}

/// J_k = ∫_0^∞ s^k e^{-s/b} (1 + s²)^{-n} ds (b = q0 L_c; `None` for b = ∞), the dimensionless
/// integrals of the (3.16) normalisation and moments. Closed forms without cut-off:
/// J1 = 1/(2(n−1)), J3 = 1/(2(n−1)(n−2)), J5 = 1/((n−1)(n−2)(n−3)).
fn abc_integral(k: i32, n: f64, b: Option<f64>) -> Result<f64> {
    match b {
        None => {
            let v = match k {
                1 => 0.5 / (n - 1.0),
                3 => 0.5 / ((n - 1.0) * (n - 2.0)),
                5 => 1.0 / ((n - 1.0) * (n - 2.0) * (n - 3.0)),
                _ => f64::NAN,
            };
            Ok(v)
        }
        Some(b) => {
            let f = |s: f64| s.powi(k) * (-s / b).exp() * (1.0 + s * s).powf(-n);
            // The integrand changes on the scale min(1, b) near the origin and decays on b.
            let split = b.max(1.0);
            let head = integrate(f, 0.0, split, 0.0, MOMENT_REL_TOL)?;
            let tail = integrate_to_infinity(f, split, b.max(1.0), 0.0, MOMENT_REL_TOL)?;
            Ok(head.value + tail.value)
        }
    }
}

/// I_k = ∫ q^k C(q)/K dq of the self-affine model, in closed form.
fn self_affine_integral(k: i32, hurst: f64, q_low: f64, q_roll: f64, q_high: f64) -> f64 {
    let kp = f64::from(k + 1);
    let flat = (q_roll.powf(kp) - q_low.powf(kp)) / kp;
    let beta = 2.0 * (1.0 + hurst);
    let e = kp - beta;
    let tail = if e.abs() < 1e-12 {
        q_roll.powf(beta) * (q_high / q_roll).ln()
    } else {
        q_roll.powf(beta) * (q_high.powf(e) - q_roll.powf(e)) / e
    };
    flat + tail
}

/// The spectral moments (3.8) of an isotropic PSD `psd` [m⁴] over the band q_min ≤ q ≤ q_max
/// [1/m], by adaptive Gauss-Kronrod quadrature in ln q (the moments' integrands span decades).
/// `q_min` may be 0; `q_max` must be finite (truncate where the PSD is negligible, or use
/// [`Spectrum::moments`] for the full range).
///
/// # Errors
/// [`Error::InvalidParameter`] for a bad band, and a quadrature failure.
pub fn moments_of_psd(psd: impl Fn(f64) -> f64, q_min: f64, q_max: f64) -> Result<Moments> {
    if !(q_min >= 0.0 && q_min.is_finite()) {
        return Err(Error::invalid("q_min", q_min, "must be non-negative and finite"));
    }
    if !(q_max > q_min && q_max.is_finite()) {
        return Err(Error::invalid("q_max", q_max, "must be finite and exceed q_min"));
    }
    let lo = if q_min > 0.0 { q_min } else { q_max * 1e-9 };
    let mut m = [0.0; 3];
    for (idx, n) in [0, 2, 4].into_iter().enumerate() {
        // ∫ q^{n+1} C dq = ∫ q^{n+2} C d(ln q).
        let f = |u: f64| {
            let q = u.exp();
            q.powi(n + 2) * psd(q)
        };
        let mut v = integrate(f, lo.ln(), q_max.ln(), 0.0, MOMENT_REL_TOL)?.value;
        if q_min == 0.0 {
            v += integrate(|q: f64| q.powi(n + 1) * psd(q), 0.0, lo, 0.0, MOMENT_REL_TOL)?.value;
        }
        m[idx] = MOMENT_PREFACTOR[idx] * v;
    }
    Ok(Moments {
        m0: m[0],
        m2: m[1],
        m4: m[2],
    })
}

/// Nayak's joint PDF of asperity heights and curvatures, Eq. (3.7):
/// p(ξ, t) = √(3C1)/(2π) e^{-C1 ξ²} (t² − 2 + 2e^{-t²/2}) e^{-(C1 t² + C2 t ξ)/2},
/// with ξ = height/σ_rms, t = −√(3/m4) k_m ≤ 0. Normalised over ξ ∈ ℝ, t ≤ 0. Needs α > 1.5.
pub fn nayak_joint_pdf(xi: f64, t: f64, alpha: f64) -> f64 {
    let c1 = nayak_c1(alpha);
    let c2 = nayak_c2(alpha);
    // One exponential: the two factors of (3.7) can under- and overflow separately.
    (3.0 * c1).sqrt() / (2.0 * PI)
        * (t * t - 2.0 + 2.0 * (-0.5 * t * t).exp())
        * (-c1 * xi * xi - 0.5 * (c1 * t * t + c2 * t * xi)).exp()
}

/// Nayak's PDF of asperity curvatures, Eq. (3.11), the marginal of (3.7) over heights (ERRATA:
/// its c1, c2 are (3.7)'s C1, C2):
/// p_κ(t) = √(3/4π) (t² − 2 + 2e^{-t²/2}) e^{-(8C1² − C2²) t²/(16 C1)}.
/// Since 8C1² − C2² = 4C1, the exponent is −t²/4 for every α: the curvature distribution in
/// the variable t does not depend on Nayak's parameter. Normalised over t ≤ 0.
pub fn nayak_curvature_pdf(t: f64, alpha: f64) -> f64 {
    let c1 = nayak_c1(alpha);
    let c2 = nayak_c2(alpha);
    (3.0 / (4.0 * PI)).sqrt()
        * (t * t - 2.0 + 2.0 * (-0.5 * t * t).exp())
        * (-(8.0 * c1 * c1 - c2 * c2) * t * t / (16.0 * c1)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sqrt_psd_is_the_square_root_of_the_psd() {
        for s in [
            Spectrum::Gaussian {
                rms: 2.0,
                correlation_length: 0.3,
            },
            PSD_3_17,
            Spectrum::Abc {
                rms: 1.0,
                correlation_length: 1.0,
                exponent: 3.5,
                cutoff: None,
            },
            Spectrum::SelfAffine {
                rms: 1.0e-9,
                hurst: 0.8,
                q_low: 1.0e5,
                q_roll: 1.0e6,
                q_high: 1.0e9,
            },
        ] {
            let p = s.prepare().unwrap();
            for q in [0.0, 3.0e4, 2.0e5, 1.0, 7.5, 1.0e6, 4.0e7, 1.0e8, 9.0e8, 2.0e9] {
                let (a, b) = (p.sqrt_psd(q), p.psd(q).sqrt());
                assert!((a - b).abs() <= 1e-13 * b, "{s:?} at q = {q}: {a:e} vs {b:e}");
            }
        }
    }

    #[test]
    fn each_spectrum_integrates_to_its_rms_squared() {
        let cases = [
            (
                Spectrum::Gaussian {
                    rms: 2.0,
                    correlation_length: 0.3,
                },
                200.0,
            ),
            (
                Spectrum::Abc {
                    rms: 1.45e-9,
                    correlation_length: 20.1e-9,
                    exponent: 3.28,
                    cutoff: Some(1.0e8),
                },
                1.0e11,
            ),
            (
                Spectrum::SelfAffine {
                    rms: 1.0e-9,
                    hurst: 0.8,
                    q_low: 1.0e5,
                    q_roll: 1.0e6,
                    q_high: 1.0e9,
                },
                1.0e9,
            ),
        ];
        for (s, q_max) in cases {
            let m = s.moments_in_band(0.0, q_max).unwrap();
            let rel = (m.m0 / (s.rms() * s.rms()) - 1.0).abs();
            assert!(rel < 1e-7, "{s:?}: m0 off by {rel:e}");
        }
    }
}
