//! The classical theories of chapter 1: Hertz (1.1), JKR (1.2)-(1.6), DMT (1.7) and the Tabor
//! parameter (1.8), for a sphere of radius R on an elastic half-space.
//!
//! Sign conventions: the indentation depth h and the force P are positive in compression; the
//! contact radius a ≥ 0. E* is the effective modulus, 1/E* = (1-ν₁²)/E₁ + (1-ν₂²)/E₂.
//!
//! Non-dimensional JKR variables (`_bar`), the natural scales of the theory:
//!
//! ```text
//! a₀ = (π R² w / E*)^(1/3),  h₀ = (π² R w² / E*²)^(1/3) = a₀²/R,  P₀ = π w R,  E₀ = P₀ h₀
//! ā = a/a₀,  h̄ = h/h₀ = ā² − √(2ā),  P̄ = P/P₀ = (4/3) ā³ − √(8 ā³)      (1.2)
//! ```
//!
//! In these units the special points are ā_B = 2^(1/3), ā_C = (9/8)^(1/3), ā_D = 1/2,
//! h̄_C = −(3/64)^(1/3), h̄_D = −3/4, P̄_B = −4/3, P̄_C = −3/2, P̄_D = −5/6, and the hysteresis
//! (1.6) is (1 + 3·2^(5/3))/10 · E₀ = (π^(5/3) + 3 (2π)^(5/3))/10 · (R⁴w⁵/E*²)^(1/3).

use crate::error::{Error, Result};
/// Material and geometry of a sphere-on-flat contact, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereContact {
    /// Sphere radius R [m] (1/R = 1/R₁ + 1/R₂ for two spheres).
    pub radius: f64,
    /// Effective modulus E* [Pa].
    pub modulus: f64,
    /// Work of adhesion w [J/m²].
    pub work_of_adhesion: f64,
}

/// A contact state: contact radius a, indentation depth h, force P (SI or `_bar`, as stated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Contact radius a.
    pub a: f64,
    /// Indentation depth h (positive in compression).
    pub h: f64,
    /// Force P (positive in compression).
    pub p: f64,
}

impl SphereContact {
    /// Validated contact parameters.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless R > 0, E* > 0 and w ≥ 0 are finite.
    pub fn new(radius: f64, modulus: f64, work_of_adhesion: f64) -> Result<Self> {
        check_positive("radius", radius)?;
        check_positive("modulus", modulus)?;
        if !(work_of_adhesion.is_finite() && work_of_adhesion >= 0.0) {
            return Err(Error::invalid(
                "work_of_adhesion",
                work_of_adhesion,
                "must not be negative",
            ));
        }
        Ok(Self {
            radius,
            modulus,
            work_of_adhesion,
        })
    }

    /// Radius scale a₀ = (π R² w / E*)^(1/3) [m].
    pub fn a0(&self) -> f64 {
        // Cube roots first: the scale stays finite wherever it is a double (no R²w overflow).
        let (r, w, e) = self.cube_roots();
        std::f64::consts::PI.cbrt() * r * r * w / e
    }

    /// Depth scale h₀ = (π² R w² / E*²)^(1/3) [m].
    pub fn h0(&self) -> f64 {
        let (r, w, e) = self.cube_roots();
        std::f64::consts::PI.cbrt().powi(2) * r * (w / e).powi(2)
    }

    /// Force scale P₀ = π w R [N].
    pub fn p0(&self) -> f64 {
        std::f64::consts::PI * self.work_of_adhesion * self.radius
    }

    /// Energy scale of (1.6), (R⁴ w⁵ / E*²)^(1/3) [J].
    pub fn energy_scale_1_6(&self) -> f64 {
        let (r, w, e) = self.cube_roots();
        r.powi(4) * w * (w / e).powi(2) * w.powi(2)
    }

    /// (R^(1/3), w^(1/3), E*^(1/3)): the scales are products of these, computed without
    /// forming R⁴w⁵ (which leaves the double range long before the scale does).
    fn cube_roots(&self) -> (f64, f64, f64) {
        (
            self.radius.cbrt(),
            self.work_of_adhesion.cbrt(),
            self.modulus.cbrt(),
        )
    }

    /// Hertz depth and force at contact radius `a` [m].
    ///
    /// Implements Eq. (1.1):
    /// ```text
    /// h = a²/R,   P = 4E*a³/(3R)
    /// ```
    pub fn hertz(&self, a: f64) -> ContactState {
        ContactState {
            a,
            h: a * a / self.radius,
            p: 4.0 * self.modulus * a.powi(3) / (3.0 * self.radius),
        }
    }

    /// JKR depth and force at contact radius `a` [m].
    ///
    /// Implements Eq. (1.2):
    /// ```text
    /// h = a²/R − √(2πaw/E*),   P = 4E*a³/(3R) − √(8πa³wE*)
    /// ```
    pub fn jkr(&self, a: f64) -> ContactState {
        let pi = std::f64::consts::PI;
        let w = self.work_of_adhesion;
        ContactState {
            a,
            h: a * a / self.radius - (2.0 * pi * a * w / self.modulus).sqrt(),
            p: 4.0 * self.modulus * a.powi(3) / (3.0 * self.radius)
                - (8.0 * pi * a.powi(3) * w * self.modulus).sqrt(),
        }
    }

    /// DMT depth and force at contact radius `a` [m], the adhesive force added to Hertz.
    ///
    /// Implements Eq. (1.7):
    /// ```text
    /// h = a²/R,   P = 4E*a³/(3R) − 2πwR
    /// ```
    pub fn dmt(&self, a: f64) -> ContactState {
        let hertz = self.hertz(a);
        ContactState {
            p: hertz.p - 2.0 * std::f64::consts::PI * self.work_of_adhesion * self.radius,
            ..hertz
        }
    }

    /// JKR state just after the pull-in instability (point B of Fig. 1.1).
    ///
    /// Implements Eq. (1.3): `a_B = (2πR²w/E*)^(1/3), h_B = 0, P_B = −(4/3)πwR`.
    pub fn jkr_pull_in(&self) -> ContactState {
        self.scale(jkr_bar::PULL_IN)
    }

    /// JKR state at the pull-off instability in displacement control (point D of Fig. 1.1).
    ///
    /// Implements Eq. (1.4): `a_D = (πR²w/8E*)^(1/3), h_D = −(27π²Rw²/64E*²)^(1/3),
    /// P_D = −(5/6)πwR`.
    pub fn jkr_pull_off(&self) -> ContactState {
        self.scale(jkr_bar::PULL_OFF)
    }

    /// JKR adhesive-force point, the most negative force (point C of Fig. 1.1).
    ///
    /// Implements Eq. (1.5): `a_C = (9πR²w/8E*)^(1/3), h_C = −(3π²Rw²/64E*²)^(1/3),
    /// P_C = −(3/2)πwR`.
    pub fn jkr_adhesive_force(&self) -> ContactState {
        self.scale(jkr_bar::ADHESIVE_FORCE)
    }

    /// DMT adhesive force, at zero contact radius (point F of Fig. 1.1): `P_F = −2πwR` (1.7).
    pub fn dmt_adhesive_force(&self) -> ContactState {
        self.dmt(0.0)
    }

    /// JKR hysteretic energy loss of a displacement-controlled cycle [J], closed form.
    ///
    /// Implements Eq. (1.6): `H = 7.092 (R⁴w⁵/E*²)^(1/3)`, with the exact constant
    /// (π^(5/3) + 3(2π)^(5/3))/10.
    pub fn jkr_hysteresis(&self) -> f64 {
        JKR_HYSTERESIS_CONSTANT * self.energy_scale_1_6()
    }

    /// Tabor parameter μ_T for an equilibrium separation ζ₀ [m].
    ///
    /// Implements Eq. (1.8): `μ_T = (R w² / (E*² ζ₀³))^(1/3)`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless ζ₀ > 0.
    pub fn tabor_parameter(&self, zeta0: f64) -> Result<f64> {
        check_positive("equilibrium_separation", zeta0)?;
        let (r, w, e) = self.cube_roots();
        Ok(r * (w / e).powi(2) / zeta0)
    }

    /// Convert a non-dimensional JKR state to SI.
    pub fn scale(&self, s: ContactState) -> ContactState {
        ContactState {
            a: s.a * self.a0(),
            h: s.h * self.h0(),
            p: s.p * self.p0(),
        }
    }
}

/// DMT adhesive force in units of πwR: P_F = −2πwR at a = 0, Eq. (1.7).
pub const DMT_ADHESIVE_FORCE_NORM: f64 = -2.0;

/// The constant of (1.6), exact: (π^(5/3) + 3(2π)^(5/3))/10 = 7.0924...
pub const JKR_HYSTERESIS_CONSTANT: f64 = 7.092_195_971_863_96;

fn check_positive(name: &str, v: f64) -> Result<()> {
    Error::require_positive(name, v)
}

/// The JKR theory in its non-dimensional form (scales a₀, h₀, P₀ = πwR; see the module docs).
pub mod jkr_bar {
    use super::ContactState;
    use crate::error::Result;
    use crate::numerics::quadrature::integrate;
    use crate::numerics::roots::{brent, expand_upward};

    /// Point B, after pull-in, Eq. (1.3).
    pub const PULL_IN: ContactState = ContactState {
        a: 1.259_921_049_894_873_2, // 2^(1/3)
        h: 0.0,
        p: -4.0 / 3.0,
    };
    /// Point D, pull-off in displacement control, Eq. (1.4).
    pub const PULL_OFF: ContactState = ContactState {
        a: 0.5,
        h: -0.75,
        p: -5.0 / 6.0,
    };
    /// Point C, adhesive force, Eq. (1.5).
    pub const ADHESIVE_FORCE: ContactState = ContactState {
        a: 1.040_041_911_525_952,    // (9/8)^(1/3)
        h: -0.360_562_392_576_852_1, // -(3/64)^(1/3)
        p: -1.5,
    };

    /// h̄(ā) = ā² − √(2ā), Eq. (1.2) in the scales a₀, h₀.
    pub fn depth(a: f64) -> f64 {
        a * a - (2.0 * a).sqrt()
    }

    /// dh̄/dā = 2ā − 1/√(2ā).
    pub fn depth_slope(a: f64) -> f64 {
        2.0 * a - 1.0 / (2.0 * a).sqrt()
    }

    /// P̄(ā) = (4/3)ā³ − √(8ā³), Eq. (1.2) in the scales a₀, P₀.
    pub fn force(a: f64) -> f64 {
        4.0 / 3.0 * a.powi(3) - (8.0 * a.powi(3)).sqrt()
    }

    /// State at ā.
    pub fn state(a: f64) -> ContactState {
        ContactState {
            a,
            h: depth(a),
            p: force(a),
        }
    }

    /// Contact radius on the displacement-stable branch (ā ≥ 1/2) at depth h̄ ≥ h̄_D = −3/4.
    ///
    /// # Errors
    /// [`crate::error::Error::NoBracket`] for h̄ < −3/4 (no contact possible).
    pub fn stable_radius_at_depth(h: f64) -> Result<f64> {
        // At and (by rounding) just below h̄_D the stable branch ends at ā_D.
        if (PULL_OFF.h - 1e-12..=PULL_OFF.h).contains(&h) {
            return Ok(PULL_OFF.a);
        }
        let f = |a: f64| depth(a) - h;
        let (lo, hi) = expand_upward(f, PULL_OFF.a, 2.0, 200)?;
        brent(f, lo, hi, 1e-15)
    }

    /// Hysteresis of the displacement-controlled cycle in units of P₀h₀, by quadrature of
    /// −∮P dh = −∫_{ā_D}^{ā_B} P̄(ā) h̄'(ā) dā (the loop between the pull-off point D and the
    /// pull-in point B, closed by the zero-force approach at h̄ ∈ [h̄_D, 0]).
    ///
    /// # Errors
    /// If the quadrature fails (it does not for these smooth integrands).
    pub fn hysteresis_by_quadrature(tol: f64) -> Result<f64> {
        let r = integrate(|a| -force(a) * depth_slope(a), PULL_OFF.a, PULL_IN.a, tol, tol)?;
        Ok(r.value)
    }
}

/// JKR hysteresis (1.6) computed by quadrature of the displacement-controlled loop, in units of
/// (R⁴w⁵/E*²)^(1/3); equals [`JKR_HYSTERESIS_CONSTANT`].
///
/// # Errors
/// If the quadrature fails.
pub fn jkr_hysteresis_constant_by_quadrature(tol: f64) -> Result<f64> {
    let in_p0h0 = jkr_bar::hysteresis_by_quadrature(tol)?;
    // P₀ h₀ = π^(5/3) (R⁴w⁵/E*²)^(1/3).
    Ok(in_p0h0 * std::f64::consts::PI.powf(5.0 / 3.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_points_lie_on_the_jkr_curve_and_are_its_extrema() {
        for s in [jkr_bar::PULL_IN, jkr_bar::PULL_OFF, jkr_bar::ADHESIVE_FORCE] {
            assert!((jkr_bar::depth(s.a) - s.h).abs() < 1e-14);
            assert!((jkr_bar::force(s.a) - s.p).abs() < 1e-14);
        }
        // D is the minimum of h̄(ā): dh̄/dā = 0 there.
        assert!(jkr_bar::depth_slope(0.5).abs() < 1e-15);
    }

    #[test]
    fn the_hysteresis_constant_is_the_closed_form() {
        let pi = std::f64::consts::PI;
        let c = (pi.powf(5.0 / 3.0) + 3.0 * (2.0 * pi).powf(5.0 / 3.0)) / 10.0;
        assert!((c - JKR_HYSTERESIS_CONSTANT).abs() < 1e-14);
    }
}
