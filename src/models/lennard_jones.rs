//! The generalized Lennard-Jones interaction of section 4.2.1 between an elastic tip and a rigid
//! flat substrate: the pair potential (4.1) summed over two half-spaces gives the plate energy
//! per unit area (4.4), its traction (4.5), the equilibrium separation ζ₀ (4.6), the work of
//! adhesion (4.7b) and the body force on the tip (4.15); from them the Dugdale equivalent of
//! section 4.4, the parameters ℓ, χ (4.25) and μ_T (1.8), and the estimate (4.19)-(4.23) of the
//! critical separation at which the tip jumps into or out of contact (section 4.3).
//!
//! Symbols: C₆, C₁₂ weight the attraction and repulsion of (4.1); σ [m] is its length scale,
//! A_H = 4π²ερ₁ρ₂σ⁶ [J] the Hamaker constant, g [m] the gap between the plates, s = ζ₀/g.
//!
//! Everything is written through A_H and σ, so that C₆ = 0 (the adhesionless runs of
//! Fig. 4.4: repulsion only) stays meaningful: then w = 0, ζ₀ = ∞ and the plate energy is the
//! pure C₁₂ term of (4.4), φ(g) = C₁₂ A_H σ⁶/(360π g⁸). For C₆ > 0 the same expressions are
//! the normalised forms of the module's functions, e.g. φ(g) = −(4w/3)[s² − s⁸/4].
//!
//! Sign convention: a traction or body force is positive when it attracts the tip towards the
//! substrate (as (4.5) and (4.15) are printed: F = dE/dζ).
//!
//! Errata used (ERRATA.md, chapter 4): (4.7a)'s factor is wrong, (4.7b) w = κA_H/ζ₀² with
//! κ = C₆/(16π) is used; (4.19) as printed vanishes at g⁶ = ζ₀⁶C₁₂/C₆, not at ζ₀, so the
//! traction of this module is the consistent p = dφ/dg = 8w/(3ζ₀)[s³ − s⁹]. The criterion
//! (4.23) with the printed coefficients 23.1 and 13.7 follows from the printed (4.19), not from
//! the consistent traction; [`TractionLaw`] offers both.

use std::f64::consts::{PI, SQRT_2};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::numerics::roots::brent;

/// ∫₀^∞ (1+t²)⁻⁹ dt / ∫₀^∞ (1+t²)⁻³ dt = (6435π/65536)/(3π/16) = 2145/4096, the ratio of the
/// repulsive to the attractive Boussinesq integral in (4.21).
const BOUSSINESQ_RATIO: f64 = 2145.0 / 4096.0;

/// Parameters of the generalized LJ interaction (4.1), (4.15).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LennardJonesParams {
    /// Weight C₆ ≥ 0 of the attractive term of (4.1) [-] (0: adhesionless, Fig. 4.4).
    pub c6: f64,
    /// Weight C₁₂ > 0 of the repulsive term of (4.1) [-].
    pub c12: f64,
    /// Length scale σ of (4.1) [m].
    pub sigma: f64,
    /// Hamaker constant A_H = 4π²ερ₁ρ₂σ⁶ [J].
    pub hamaker: f64,
}

impl Default for LennardJonesParams {
    /// The interaction of Figure 4.5: C₆ = 3, C₁₂ = 1, σ = 1 nm, A_H = 2e-21 J.
    fn default() -> Self {
        Self {
            c6: 3.0,
            c12: 1.0,
            sigma: 1e-9,
            hamaker: 2e-21,
        }
    }
}

/// The validated LJ plate interaction of section 4.2.1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LennardJones {
    params: LennardJonesParams,
    /// ζ₀ [m] (∞ when C₆ = 0).
    zeta0: f64,
    /// w [J/m²] (0 when C₆ = 0).
    work: f64,
}

impl LennardJones {
    /// Validate the parameters and precompute ζ₀ and w.
    ///
    /// ```
    /// use adhesion::models::lennard_jones::{LennardJones, LennardJonesParams};
    /// // Figure 4.5: C₆ = 3, C₁₂ = 1, σ = 1 nm, A_H = 2e-21 J; R = 5 µm, E* = 4.4 MPa/(1 − 0.25²).
    /// let lj = LennardJones::new(&LennardJonesParams::default())?;
    /// let modulus = 4.4e6 / (1.0 - 0.25 * 0.25);
    /// assert!((lj.zeta0() - 0.5952e-9).abs() < 1e-13);
    /// assert!((lj.ell(5e-6, modulus) - 4.51e-5).abs() < 5e-8);
    /// assert!((lj.chi(modulus) - 0.124).abs() < 5e-4);
    /// # Ok::<(), adhesion::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `c6` unless C₆ ≥ 0, and `c12`, `sigma`, `hamaker`
    /// unless positive (all finite).
    pub fn new(params: &LennardJonesParams) -> Result<Self> {
        if !(params.c6.is_finite() && params.c6 >= 0.0) {
            return Err(Error::invalid("c6", params.c6, "must be finite and not negative"));
        }
        for (name, v) in [
            ("c12", params.c12),
            ("sigma", params.sigma),
            ("hamaker", params.hamaker),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be positive and finite"));
            }
        }
        // (4.6); C₆ = 0 gives +∞, and w = 0 below.
        let zeta0 = (2.0 * params.c12 / (15.0 * params.c6)).powf(1.0 / 6.0) * params.sigma;
        let work = if params.c6 > 0.0 {
            params.c6 / (16.0 * PI) * params.hamaker / (zeta0 * zeta0)
        } else {
            0.0
        };
        Ok(Self {
            params: *params,
            zeta0,
            work,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &LennardJonesParams {
        &self.params
    }

    /// Equilibrium separation of two half-spaces ζ₀ [m], where the traction (4.5) vanishes.
    ///
    /// Implements Eq. (4.6):
    /// ```text
    /// ζ₀ = (2C₁₂/(15C₆))^(1/6) σ
    /// ```
    /// +∞ when C₆ = 0 (repulsion alone has no equilibrium).
    pub fn zeta0(&self) -> f64 {
        self.zeta0
    }

    /// Dupré work of adhesion w = E(∞) − E(ζ₀) [J/m²].
    ///
    /// Implements Eq. (4.7b) (ERRATA: not the printed factor of (4.7a)):
    /// ```text
    /// w = κ A_H / ζ₀²,   κ = C₆/(16π)
    /// ```
    /// 0 when C₆ = 0.
    pub fn work_of_adhesion(&self) -> f64 {
        self.work
    }

    /// The energy scale of (4.4), 4περ₁ρ₂σ⁴ = A_H/(πσ²) [J/m²].
    pub fn energy_scale(&self) -> f64 {
        self.params.hamaker / (PI * self.params.sigma.powi(2))
    }

    /// Interaction energy per unit area of two half-spaces at gap `g` [m], φ(g) [J/m²].
    ///
    /// Implements Eq. (4.4):
    /// ```text
    /// φ(g) = (A_H/(πσ²)) [ −(C₆/12)(σ/g)² + (C₁₂/360)(σ/g)⁸ ]
    ///      = −(4w/3) [ (ζ₀/g)² − ¼(ζ₀/g)⁸ ]          (C₆ > 0)
    /// ```
    /// so that φ(ζ₀) = −w, φ(∞) = 0. For C₆ = 0, φ(g) = C₁₂ A_H σ⁶/(360π g⁸).
    pub fn plate_energy(&self, g: f64) -> f64 {
        let u = self.params.sigma / g;
        let u2 = u * u;
        self.energy_scale() * (-self.params.c6 / 12.0 * u2 + self.params.c12 / 360.0 * u2.powi(4))
    }

    /// Traction between the plates at gap `g` [m], p(g) = dφ/dg [Pa], positive = attractive.
    ///
    /// Implements Eq. (4.5), the consistent Derjaguin traction of ERRATA's (4.19):
    /// ```text
    /// p(g) = (A_H/(πσ³)) [ (C₆/6)(σ/g)³ − (C₁₂/45)(σ/g)⁹ ]
    ///      = (8w/(3ζ₀)) [ (ζ₀/g)³ − (ζ₀/g)⁹ ]          (C₆ > 0)
    /// ```
    pub fn traction(&self, g: f64) -> f64 {
        let sigma = self.params.sigma;
        let u = sigma / g;
        let u3 = u * u * u;
        self.energy_scale() / sigma * (self.params.c6 / 6.0 * u3 - self.params.c12 / 45.0 * u3.powi(3))
    }

    /// Slope of the traction, dp/dg = d²φ/dg² [Pa/m] (the plate-pair stiffness with its sign:
    /// negative where the attraction grows as the gap closes).
    ///
    /// ```text
    /// dp/dg = (A_H/(πσ⁴)) [ −(C₆/2)(σ/g)⁴ + (C₁₂/5)(σ/g)¹⁰ ] = −B_z(g)
    /// ```
    pub fn traction_slope(&self, g: f64) -> f64 {
        -self.body_force(g)
    }

    /// Body force per unit volume on the tip at height `z` [m] above the substrate, B_z [N/m³],
    /// positive = attractive.
    ///
    /// Implements Eq. (4.15) (with z standing for z + u_z, the deformed height):
    /// ```text
    /// B_z(z) = (A_H/(πσ⁴)) [ (C₆/2)(σ/z)⁴ − (C₁₂/5)(σ/z)¹⁰ ]
    /// ```
    /// A column of the tip above gap g carries ∫_g^∞ B_z dz = p(g), the traction (4.5).
    pub fn body_force(&self, z: f64) -> f64 {
        let sigma = self.params.sigma;
        let u = sigma / z;
        let u2 = u * u;
        let u4 = u2 * u2;
        self.params.hamaker / (PI * sigma.powi(4))
            * (self.params.c6 / 2.0 * u4 - self.params.c12 / 5.0 * u4 * u4 * u2)
    }

    /// Largest attractive traction σ₀ = max_g p(g) [Pa], at g = 3^(1/6) ζ₀.
    ///
    /// From (4.5): dp/dg = 0 at s⁶ = 1/3, where p = (8w/(3ζ₀))(2/(3√3)):
    /// ```text
    /// σ₀ = 16 w / (9√3 ζ₀)
    /// ```
    /// independent of C₆, C₁₂ in these variables. 0 when C₆ = 0.
    pub fn max_traction(&self) -> f64 {
        16.0 * self.work / (9.0 * 3f64.sqrt() * self.zeta0)
    }

    /// Gap of the largest attraction, 3^(1/6) ζ₀ [m].
    pub fn max_traction_gap(&self) -> f64 {
        3f64.powf(1.0 / 6.0) * self.zeta0
    }

    /// Range of the equivalent Dugdale cohesive zone δ₀ = w/σ₀ [m] (section 4.4).
    ///
    /// ```text
    /// δ₀ = c₃ ζ₀,   c₃ = 9√3/16 = 0.9743
    /// ```
    /// with σ₀ the maximum of the consistent traction ([`Self::max_traction`]); this is what
    /// reproduces χ = 0.124 of Figure 4.5. The section's general c₃ = 9√3 C₁₂^(5/6)/(16 C₆^(7/6))
    /// is the maximum of the printed (4.19) instead ([`c3_as_printed`]). +∞ when C₆ = 0.
    pub fn dugdale_range(&self) -> f64 {
        9.0 * 3f64.sqrt() / 16.0 * self.zeta0
    }

    /// Tabor parameter μ_T for a tip of radius `radius` R [m] and effective modulus `modulus`
    /// E* [Pa].
    ///
    /// Implements Eq. (1.8):
    /// ```text
    /// μ_T = ( R w² / (E*² ζ₀³) )^(1/3)
    /// ```
    /// 0 when C₆ = 0.
    pub fn tabor_parameter(&self, radius: f64, modulus: f64) -> f64 {
        (radius * self.work.powi(2) / (modulus.powi(2) * self.zeta0.powi(3))).cbrt()
    }

    /// Effective modulus E* [Pa] at which a tip of radius `radius` R [m] has the Tabor
    /// parameter `mu_t`: the inverse of [`Self::tabor_parameter`].
    ///
    /// Implements Eq. (1.8) solved for E*:
    /// ```text
    /// E* = ( R w² / (μ_T³ ζ₀³) )^(1/2)
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `mu_t` unless it is positive and finite, `radius`
    /// unless positive and finite, and `c6` when C₆ = 0 (no attraction: μ_T = 0 for every E*).
    pub fn modulus_for_tabor(&self, radius: f64, mu_t: f64) -> Result<f64> {
        if !(mu_t.is_finite() && mu_t > 0.0) {
            return Err(Error::invalid("mu_t", mu_t, "must be positive and finite"));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(Error::invalid("radius", radius, "must be positive and finite"));
        }
        if self.work <= 0.0 {
            return Err(Error::invalid(
                "c6",
                self.params.c6,
                "a Tabor parameter needs an attraction, C6 > 0",
            ));
        }
        Ok((radius * self.work.powi(2) / (mu_t.powi(3) * self.zeta0.powi(3))).sqrt())
    }

    /// Ratio of adhesive to elastic length χ = w/(E* δ₀) for `modulus` E* [Pa].
    ///
    /// Implements Eq. (4.25) (= (3.2) with Z₀ = δ₀ of [`Self::dugdale_range`]):
    /// ```text
    /// χ = w / (E* δ₀)
    /// ```
    pub fn chi(&self, modulus: f64) -> f64 {
        self.work / (modulus * self.dugdale_range())
    }

    /// Adhesion parameter ℓ = πw/(E*R) for `radius` R [m] and `modulus` E* [Pa].
    ///
    /// Implements Eq. (4.25) (= (3.1)):
    /// ```text
    /// ℓ = π w / (E* R)
    /// ```
    pub fn ell(&self, radius: f64, modulus: f64) -> f64 {
        PI * self.work / (modulus * radius)
    }

    /// Displacement Δz [m] of the apex of a parabolic tip (radius `radius` R [m], modulus
    /// `modulus` E* [Pa]) at gap `z0` [m], pulled by the Derjaguin traction `law`.
    ///
    /// Implements Eq. (4.21), derived from (4.20): with the Boussinesq point-load solution and
    /// z_s(r) = z₀ + r²/(2R),
    /// ```text
    /// Δz = ∫₀^∞ (1/(πE* r)) p(z_s(r)) 2πr dr = (2/E*) ∫₀^∞ p(z₀ + r²/(2R)) dr
    /// ∫₀^∞ (z₀ + r²/2R)⁻ⁿ dr = √(2R z₀) z₀⁻ⁿ ∫₀^∞ (1+t²)⁻ⁿ dt,   ∫(1+t²)⁻³ = 3π/16, ∫(1+t²)⁻⁹ = 6435π/65536
    /// ```
    /// and for a traction p = (8w/(3ζ₀)) k [α s³ − β s⁹], s = ζ₀/z_s (see [`TractionLaw`]):
    /// ```text
    /// Δz = π√2 k (w R^(1/2) ζ₀² / (E* z₀^(5/2))) [ α − (2145/4096) β (ζ₀/z₀)⁶ ]
    /// ```
    /// With the printed (4.19) (k = (C₆C₁₂)^(−1/3), α = C₆, β = C₁₂) this is (4.21) as
    /// printed, π(1−ν²)/(√2 (C₆C₁₂)^(1/3)) · (R^(1/2) w ζ₀²/(E z₀^(5/2))) [2C₆ − (2145C₁₂/2048)(ζ₀/z₀)⁶].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when C₆ = 0 (no attraction; (4.19) is undefined).
    pub fn apex_displacement(&self, z0: f64, radius: f64, modulus: f64, law: TractionLaw) -> Result<f64> {
        let (k, alpha, beta) = law.coefficients(self)?;
        let zeta0 = self.zeta0;
        Ok(
            PI * SQRT_2 * k * self.work * radius.sqrt() * zeta0 * zeta0 / (modulus * z0.powf(2.5))
                * (alpha - BOUSSINESQ_RATIO * beta * (zeta0 / z0).powi(6)),
        )
    }
}

/// c₃ of section 4.4 as printed, 9√3 C₁₂^(5/6)/(16 C₆^(7/6)).
///
/// It is σ₀ = max p with p the *printed* (4.19), whose maximum is 16w C₆^(7/6)/(9√3 C₁₂^(5/6) ζ₀);
/// for the consistent traction of ERRATA c₃ = 9√3/16 for every C₆, C₁₂. At C₆ = 3, C₁₂ = 1 the
/// printed form gives 0.2705 and χ = 0.446 for Figure 4.5, not the printed 0.124.
pub fn c3_as_printed(c6: f64, c12: f64) -> f64 {
    9.0 * 3f64.sqrt() * c12.powf(5.0 / 6.0) / (16.0 * c6.powf(7.0 / 6.0))
}

/// The Derjaguin traction used in the critical-separation estimate (4.19)-(4.23), written as
/// p = (8w/(3ζ₀)) k [α (ζ₀/g)³ − β (ζ₀/g)⁹].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TractionLaw {
    /// (4.19) as printed: k = (C₆C₁₂)^(−1/3), α = C₆, β = C₁₂. It vanishes at
    /// g = ζ₀ (C₁₂/C₆)^(1/6), not at ζ₀, unless C₆ = C₁₂; it is the law behind the printed
    /// coefficients 23.1 and 13.7 of (4.23).
    AsPrinted,
    /// The consistent traction of ERRATA, p = dφ/dg of (4.4): k = α = β = 1.
    Consistent,
}

impl TractionLaw {
    /// (k, α, β) for the interaction `lj`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when C₆ = 0.
    fn coefficients(self, lj: &LennardJones) -> Result<(f64, f64, f64)> {
        let LennardJonesParams { c6, c12, .. } = lj.params;
        if c6 <= 0.0 {
            return Err(Error::invalid(
                "c6",
                c6,
                "the critical-separation estimate (4.19)-(4.23) needs an attraction, C6 > 0",
            ));
        }
        Ok(match self {
            TractionLaw::AsPrinted => (1.0 / (c6 * c12).cbrt(), c6, c12),
            TractionLaw::Consistent => (1.0, 1.0, 1.0),
        })
    }

    /// The traction of this law at gap `g` [m] for the interaction `lj` [Pa].
    ///
    /// Implements Eq. (4.19) (as printed, or its consistent form):
    /// ```text
    /// p(g) = (8w/(3ζ₀)) k [ α (ζ₀/g)³ − β (ζ₀/g)⁹ ]
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when C₆ = 0.
    pub fn traction(self, lj: &LennardJones, g: f64) -> Result<f64> {
        let (k, alpha, beta) = self.coefficients(lj)?;
        let s = lj.zeta0 / g;
        let s3 = s * s * s;
        Ok(8.0 * lj.work / (3.0 * lj.zeta0) * k * (alpha * s3 - beta * s3.powi(3)))
    }
}

/// The critical separations of the two instabilities at one Tabor parameter (non-dimensional,
/// z̄ = z₀/ζ₀).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalSeparations {
    /// The smaller root of (4.23): the gap at the pull-off instability.
    pub pull_off: f64,
    /// The larger root of (4.23): the gap at the pull-in instability.
    pub pull_in: f64,
}

/// The critical-separation criterion (4.22)-(4.23) of section 4.3.
///
/// With z̄ = z₀/ζ₀ and (1.8), (4.21) reads Δz/ζ₀ = π√2 k μ_T^(3/2) [α z̄^(−5/2) − (2145/4096) β z̄^(−17/2)],
/// and the condition (4.22) d(Δz)/dz₀ = −1 becomes
/// ```text
/// μ_T^(3/2) ( c₁ z̄^(−7/2) − c₂ z̄^(−19/2) ) = 1                              (4.23)
/// c₁ = (5/2) π√2 k α,   c₂ = (17/2)(2145/4096) π√2 k β = (36465/8192) π√2 k β
/// ```
/// For the printed (4.19): c₁ = 5√2π C₆/(2(C₆C₁₂)^(1/3)) = 23.104 and
/// c₂ = 36465√2π C₁₂/(8192(C₆C₁₂)^(1/3)) = 109395√2π C₁₂/(24576(C₆C₁₂)^(1/3)) = 13.712 at C₆ = 3,
/// C₁₂ = 1 (the dissertation prints the two definitions swapped, ERRATA).
///
/// The left side f(z̄) = c₁ z̄^(−7/2) − c₂ z̄^(−19/2) has one maximum, at the double root
/// ```text
/// z̄* = (19 c₂ / (7 c₁))^(1/6),   f(z̄*) = (12/19) c₁ z̄*^(−7/2),   μ_T* = f(z̄*)^(−2/3)
/// ```
/// so (4.23) has no root for μ_T < μ_T*, one for μ_T = μ_T* and two for μ_T > μ_T*.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstabilityCriterion {
    c1: f64,
    c2: f64,
}

impl InstabilityCriterion {
    /// The criterion for the interaction `lj` with the traction `law`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when C₆ = 0.
    pub fn new(lj: &LennardJones, law: TractionLaw) -> Result<Self> {
        let (k, alpha, beta) = law.coefficients(lj)?;
        Ok(Self {
            c1: 2.5 * PI * SQRT_2 * k * alpha,
            c2: 8.5 * BOUSSINESQ_RATIO * PI * SQRT_2 * k * beta,
        })
    }

    /// The criterion with given coefficients (e.g. the printed, rounded 23.1 and 13.7).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless both are positive and finite.
    pub fn from_coefficients(c1: f64, c2: f64) -> Result<Self> {
        for (name, v) in [("c1", c1), ("c2", c2)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be positive and finite"));
            }
        }
        Ok(Self { c1, c2 })
    }

    /// Coefficient c₁ of z̄^(−7/2) in (4.23).
    pub fn c1(&self) -> f64 {
        self.c1
    }

    /// Coefficient c₂ of z̄^(−19/2) in (4.23).
    pub fn c2(&self) -> f64 {
        self.c2
    }

    /// The left side of (4.23) without μ_T, f(z̄) = c₁ z̄^(−7/2) − c₂ z̄^(−19/2) = −(1/μ_T^(3/2)) d(Δz/ζ₀)/dz̄.
    pub fn slope_factor(&self, z_bar: f64) -> f64 {
        self.c1 * z_bar.powf(-3.5) - self.c2 * z_bar.powf(-9.5)
    }

    /// Residual of (4.23) at gap `z_bar` and Tabor parameter `mu_t`: μ_T^(3/2) f(z̄) − 1.
    pub fn residual(&self, z_bar: f64, mu_t: f64) -> f64 {
        mu_t.powf(1.5) * self.slope_factor(z_bar) - 1.0
    }

    /// The double root z̄* = (19c₂/(7c₁))^(1/6), where f is largest.
    pub fn double_root(&self) -> f64 {
        (19.0 * self.c2 / (7.0 * self.c1)).powf(1.0 / 6.0)
    }

    /// The critical Tabor parameter μ_T* = f(z̄*)^(−2/3), below which (4.23) has no root (no
    /// instability).
    pub fn critical_tabor(&self) -> f64 {
        let z = self.double_root();
        (12.0 / 19.0 * self.c1 * z.powf(-3.5)).powf(-2.0 / 3.0)
    }

    /// Both roots of (4.23) at Tabor parameter `mu_t`, or `None` below μ_T*.
    ///
    /// The pull-off root lies between the zero of f, (c₂/c₁)^(1/6), and z̄*; the pull-in root
    /// between z̄* and (c₁ μ_T^(3/2))^(2/7), beyond which μ_T^(3/2) f < μ_T^(3/2) c₁ z̄^(−7/2) ≤ 1.
    /// At μ_T = μ_T* (to rounding) both are z̄*.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `mu_t` is positive and finite; root-finding failures
    /// (not expected: the brackets hold by construction).
    pub fn critical_separations(&self, mu_t: f64) -> Result<Option<CriticalSeparations>> {
        if !(mu_t.is_finite() && mu_t > 0.0) {
            return Err(Error::invalid("mu_t", mu_t, "must be positive and finite"));
        }
        let z_star = self.double_root();
        let peak = self.residual(z_star, mu_t);
        if peak < 0.0 {
            return Ok(None);
        }
        if peak == 0.0 {
            return Ok(Some(CriticalSeparations {
                pull_off: z_star,
                pull_in: z_star,
            }));
        }
        let f = |z: f64| self.residual(z, mu_t);
        let z_zero = (self.c2 / self.c1).powf(1.0 / 6.0);
        let z_far = (self.c1 * mu_t.powf(1.5)).powf(2.0 / 7.0).max(z_star);
        let xtol = 1e-15 * z_star;
        let pull_off = brent(f, z_zero, z_star, xtol)?;
        let pull_in = brent(f, z_star, z_far, xtol)?;
        Ok(Some(CriticalSeparations { pull_off, pull_in }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::quadrature::{integrate, integrate_to_infinity};

    fn fig4_5() -> LennardJones {
        LennardJones::new(&LennardJonesParams::default()).unwrap()
    }

    /// The potential at (C₆, C₁₂) = (3, 1), (1, 1) and (2, 5), σ and A_H of Fig. 4.5.
    fn several_exponent_pairs() -> impl Iterator<Item = LennardJones> {
        [(3.0, 1.0), (1.0, 1.0), (2.0, 5.0)].into_iter().map(|(c6, c12)| {
            LennardJones::new(&LennardJonesParams {
                c6,
                c12,
                ..LennardJonesParams::default()
            })
            .unwrap()
        })
    }

    #[test]
    fn invalid_parameters_are_named() {
        let bad = |p: LennardJonesParams, name: &str| {
            let e = LennardJones::new(&p).unwrap_err().to_string();
            assert!(e.contains(&format!("`{name}`")), "{e}");
        };
        let d = LennardJonesParams::default();
        bad(LennardJonesParams { c6: -1.0, ..d }, "c6");
        bad(LennardJonesParams { c12: 0.0, ..d }, "c12");
        bad(LennardJonesParams { sigma: f64::NAN, ..d }, "sigma");
        bad(LennardJonesParams { hamaker: -2e-21, ..d }, "hamaker");
    }

    #[test]
    fn plate_energy_is_minus_w_at_zeta0_with_zero_traction_and_matches_the_zeta0_form() {
        // The A_H, σ form of (4.4) against the normalised form −(4w/3)[s² − s⁸/4], and the
        // definitions of ζ₀ (4.6) and w (4.7b); closed forms, so 1e-13 relative.
        for lj in several_exponent_pairs() {
            let (z0, w) = (lj.zeta0(), lj.work_of_adhesion());
            assert!((lj.plate_energy(z0) + w).abs() < 1e-13 * w);
            assert!(lj.traction(z0).abs() < 1e-13 * w / z0);
            for s in [0.7, 1.0, 1.3, 3.0] {
                let g = z0 / s;
                let normalised = -4.0 * w / 3.0 * (s * s - 0.25 * s.powi(8));
                let tol = 1e-13 * (normalised.abs() + w);
                assert!((lj.plate_energy(g) - normalised).abs() < tol, "{s}");
                let p = 8.0 * w / (3.0 * z0) * (s.powi(3) - s.powi(9));
                assert!((lj.traction(g) - p).abs() < 1e-13 * (p.abs() + w / z0), "{s}");
            }
            // φ(∞) = 0: at g = 1e4 ζ₀ the energy is −(4/3)·1e-8 w.
            assert!(lj.plate_energy(1e4 * z0).abs() < 2e-8 * w);
        }
    }

    #[test]
    fn traction_and_slope_are_derivatives_of_the_plate_energy() {
        // Central differences of step 1e-6 g. Relative to the size of the derivative (plus its
        // scale w/ζ₀ resp. w/ζ₀², for the zero at s = 1), truncation d²/6 · (third derivative)
        // and rounding ε f/d are of order 1e-10 (measured worst 9.7e-11, dφ/dg at s = 2);
        // tolerance 1e-9.
        let lj = fig4_5();
        let z0 = lj.zeta0();
        let scale = lj.work_of_adhesion() / z0;
        for s in [0.8, 1.0, 1.2, 2.0] {
            let g = z0 / s;
            let d = 1e-6 * g;
            let dphi = (lj.plate_energy(g + d) - lj.plate_energy(g - d)) / (2.0 * d);
            let p = lj.traction(g);
            assert!((dphi - p).abs() < 1e-9 * (p.abs() + scale), "{s}");
            let dp = (lj.traction(g + d) - lj.traction(g - d)) / (2.0 * d);
            let slope = lj.traction_slope(g);
            assert!((dp - slope).abs() < 1e-9 * (slope.abs() + scale / z0), "{s}");
        }
    }

    #[test]
    fn body_force_column_integrates_to_the_traction() {
        // ∫_g^∞ B_z dz = p(g) (4.15) vs (4.5), adaptive Gauss-Kronrod to 1e-13 relative; the
        // test allows 1e-10 of the traction scale 8w/(3ζ₀).
        for c6 in [3.0, 0.0] {
            let lj = LennardJones::new(&LennardJonesParams {
                c6,
                ..LennardJonesParams::default()
            })
            .unwrap();
            let sigma = lj.params().sigma;
            let scale = lj.params().hamaker / (PI * sigma.powi(3));
            for g in [0.5 * sigma, 0.6 * sigma, sigma, 3.0 * sigma] {
                let column = integrate_to_infinity(|z| lj.body_force(z), g, g, 0.0, 1e-13).unwrap();
                assert!(
                    (column.value - lj.traction(g)).abs() < 1e-10 * scale,
                    "C6 = {c6}, g = {g}: {} vs {}",
                    column.value,
                    lj.traction(g)
                );
            }
        }
    }

    #[test]
    fn adhesionless_interaction_is_the_repulsive_term_of_4_4() {
        // C₆ = 0 (Fig. 4.4): w = 0, ζ₀ = ∞, φ = C₁₂ A_H σ⁶/(360π g⁸) > 0, repulsive traction.
        let lj = LennardJones::new(&LennardJonesParams {
            c6: 0.0,
            ..LennardJonesParams::default()
        })
        .unwrap();
        let p = lj.params();
        assert_eq!(lj.work_of_adhesion(), 0.0);
        assert!(lj.zeta0().is_infinite());
        let g = 0.8 * p.sigma;
        let expected = p.c12 * p.hamaker * p.sigma.powi(6) / (360.0 * PI * g.powi(8));
        assert!((lj.plate_energy(g) - expected).abs() < 1e-14 * expected);
        assert!(lj.traction(g) < 0.0);
        assert_eq!(lj.chi(1e6), 0.0);
        assert_eq!(lj.tabor_parameter(1e-5, 1e6), 0.0);
        assert!(InstabilityCriterion::new(&lj, TractionLaw::AsPrinted).is_err());
    }

    #[test]
    fn dugdale_range_is_w_over_the_largest_traction() {
        // σ₀ by golden-section search on the consistent traction vs 16w/(9√3ζ₀), for several
        // (C₆, C₁₂): the location is found to ~1e-8, the maximum value to ~1e-15 relative.
        for lj in several_exponent_pairs() {
            let z0 = lj.zeta0();
            let g = crate::numerics::curve::golden_min(|g| -lj.traction(g), 0.9 * z0, 2.0 * z0, 1e-14 * z0);
            assert!((g - lj.max_traction_gap()).abs() < 1e-7 * z0);
            assert!((lj.traction(g) - lj.max_traction()).abs() < 1e-12 * lj.max_traction());
            let delta0 = lj.work_of_adhesion() / lj.traction(g);
            assert!((delta0 - lj.dugdale_range()).abs() < 1e-12 * z0);
            // The printed c₃ is w/(ζ₀ max p) for the printed (4.19), not for the consistent one.
            let gp = crate::numerics::curve::golden_min(
                |g| -TractionLaw::AsPrinted.traction(&lj, g).unwrap(),
                0.5 * z0,
                3.0 * z0,
                1e-14 * z0,
            );
            let printed_max = TractionLaw::AsPrinted.traction(&lj, gp).unwrap();
            let c3 = lj.work_of_adhesion() / (z0 * printed_max);
            let (c6, c12) = (lj.params().c6, lj.params().c12);
            assert!((c3 - c3_as_printed(c6, c12)).abs() < 1e-12 * c3, "{c6} {c12}");
        }
    }

    #[test]
    fn figure_4_5_parameters_give_the_printed_ell_chi_and_a_tabor_parameter_near_5() {
        // R = 5 µm, E = 4.4 MPa, ν = 0.25: ℓ = 4.51e-5, χ = 0.124 (caption); μ_T ≈ 5 is the
        // "μ = 5" of Fig. 4.3b. Printed precision: half a unit of the last digit.
        let lj = fig4_5();
        let modulus = 4.4e6 / (1.0 - 0.25 * 0.25);
        let radius = 5e-6;
        assert!((lj.ell(radius, modulus) - 4.51e-5).abs() < 0.005e-5);
        assert!((lj.chi(modulus) - 0.124).abs() < 0.0005);
        assert!((lj.tabor_parameter(radius, modulus) - 5.0).abs() < 0.05);
    }

    #[test]
    fn modulus_for_tabor_inverts_1_8() {
        // Round trip through (1.8) at μ_T = 0.5, 5, 10 (closed forms: 1e-13 relative); the
        // modulus of Fig. 4.5 (E = 4.4 MPa, ν = 0.25) is that of μ_T ≈ 5.
        let lj = fig4_5();
        for mu in [0.5, 5.0, 10.0] {
            let e = lj.modulus_for_tabor(5e-6, mu).unwrap();
            assert!((lj.tabor_parameter(5e-6, e) - mu).abs() < 1e-13 * mu, "{mu}");
        }
        let e5 = lj.modulus_for_tabor(5e-6, 5.0).unwrap();
        assert!((e5 / (4.4e6 / 0.9375) - 1.0).abs() < 0.02);
        assert!(
            lj.modulus_for_tabor(5e-6, 0.0)
                .unwrap_err()
                .to_string()
                .contains("`mu_t`")
        );
        let none = LennardJones::new(&LennardJonesParams {
            c6: 0.0,
            ..LennardJonesParams::default()
        })
        .unwrap();
        assert!(
            none.modulus_for_tabor(5e-6, 1.0)
                .unwrap_err()
                .to_string()
                .contains("`c6`")
        );
    }

    #[test]
    fn apex_displacement_4_21_matches_quadrature_of_the_boussinesq_integral_4_20() {
        // Δz = (2/E*) ∫₀^∞ p(z₀ + r²/2R) dr by adaptive Gauss-Kronrod (1e-13 relative) against
        // the closed form, both traction laws, gaps on both sides of the traction's zero.
        let lj = fig4_5();
        let (radius, modulus) = (5e-6, 4.4e6 / 0.9375);
        let z0 = lj.zeta0();
        for law in [TractionLaw::AsPrinted, TractionLaw::Consistent] {
            for z_bar in [0.9, 1.0, 1.08, 1.5, 4.0] {
                let gap = z_bar * z0;
                let scale = (2.0 * radius * gap).sqrt();
                let quad = integrate_to_infinity(
                    |r| law.traction(&lj, gap + r * r / (2.0 * radius)).unwrap(),
                    0.0,
                    scale,
                    0.0,
                    1e-13,
                )
                .unwrap();
                let numeric = 2.0 / modulus * quad.value;
                let closed = lj.apex_displacement(gap, radius, modulus, law).unwrap();
                // Relative to the attractive part alone, so a near-cancellation is not a zero.
                let size = PI * SQRT_2 * lj.work_of_adhesion() * radius.sqrt() * z0 * z0
                    / (modulus * gap.powf(2.5))
                    * 3.0;
                assert!(
                    (numeric - closed).abs() < 1e-9 * size,
                    "{law:?} z = {z_bar}: {numeric} vs {closed}"
                );
            }
        }
    }

    #[test]
    fn criterion_is_the_derivative_condition_4_22_of_4_21() {
        // −d(Δz/ζ₀)/dz̄ = μ_T^(3/2) f(z̄): central difference of the SI closed form (step 1e-6
        // z̄: truncation ~1e-12, rounding ~1e-10 relative).
        let lj = fig4_5();
        let (radius, modulus) = (5e-6, 4.4e6 / 0.9375);
        let mu = lj.tabor_parameter(radius, modulus);
        let z0 = lj.zeta0();
        for law in [TractionLaw::AsPrinted, TractionLaw::Consistent] {
            let crit = InstabilityCriterion::new(&lj, law).unwrap();
            for z_bar in [0.95, 1.1, 2.0, 5.0] {
                let d = 1e-6;
                let dz = |zb: f64| lj.apex_displacement(zb * z0, radius, modulus, law).unwrap() / z0;
                let fd = -(dz(z_bar + d) - dz(z_bar - d)) / (2.0 * d);
                let f = mu.powf(1.5) * crit.slope_factor(z_bar);
                let size = mu.powf(1.5) * crit.c1() * z_bar.powf(-3.5);
                assert!((fd - f).abs() < 1e-8 * size, "{law:?} {z_bar}: {fd} vs {f}");
            }
        }
    }

    #[test]
    fn coefficients_of_4_23_agree_with_the_printed_23_1_and_13_7_with_definitions_swapped() {
        let crit = InstabilityCriterion::new(&fig4_5(), TractionLaw::AsPrinted).unwrap();
        // Printed precision ±0.05.
        assert!((crit.c1() - 23.1).abs() < 0.05, "{}", crit.c1());
        assert!((crit.c2() - 13.7).abs() < 0.05, "{}", crit.c2());
        // The printed definitions, evaluated: "c₁" = 109395√2πC₁₂/(24576(C₆C₁₂)^(1/3)) is the
        // value printed for c₂, and "c₂" = 5√2πC₆/(2(C₆C₁₂)^(1/3)) the one printed for c₁.
        let k = 3f64.cbrt();
        let printed_c1_definition = 109395.0 * SQRT_2 * PI / (24576.0 * k);
        let printed_c2_definition = 5.0 * SQRT_2 * PI * 3.0 / (2.0 * k);
        assert!((printed_c1_definition - crit.c2()).abs() < 1e-13 * crit.c2());
        assert!((printed_c2_definition - crit.c1()).abs() < 1e-13 * crit.c1());
    }

    #[test]
    fn double_root_and_both_roots_at_mu_1_satisfy_4_23() {
        for law in [TractionLaw::AsPrinted, TractionLaw::Consistent] {
            let crit = InstabilityCriterion::new(&fig4_5(), law).unwrap();
            let (z, mu) = (crit.double_root(), crit.critical_tabor());
            // At the double root the residual and its z̄-derivative (analytic, relative to the
            // size of its two terms) vanish, to 1e-10.
            assert!(crit.residual(z, mu).abs() < 1e-10);
            let (t1, t2) = (3.5 * crit.c1() * z.powf(-4.5), 9.5 * crit.c2() * z.powf(-10.5));
            assert!((t2 - t1).abs() < 1e-10 * t1, "{t1} {t2}");
            let roots = crit.critical_separations(1.0).unwrap().unwrap();
            assert!(roots.pull_off < z && z < roots.pull_in);
            assert!(crit.residual(roots.pull_off, 1.0).abs() < 1e-10);
            assert!(crit.residual(roots.pull_in, 1.0).abs() < 1e-10);
            // None below μ_T*, and pull-in grows with μ_T while pull-off stays near 1.
            assert!(crit.critical_separations(0.99 * mu).unwrap().is_none());
            let big = crit.critical_separations(5.0).unwrap().unwrap();
            assert!(big.pull_in > roots.pull_in && big.pull_off < roots.pull_off);
        }
    }

    #[test]
    fn printed_mu_star_and_z_star_follow_from_the_rounded_coefficients() {
        // ERRATA: 0.20155 and 1.08258 come from c₁ = 23.1, c₂ = 13.7; the unrounded
        // coefficients give 0.201584 and 1.082713 (outside the printed precision).
        let rounded = InstabilityCriterion::from_coefficients(23.1, 13.7).unwrap();
        assert!((rounded.critical_tabor() - 0.20155).abs() < 0.5e-5);
        assert!((rounded.double_root() - 1.08258).abs() < 0.5e-5);
        let exact = InstabilityCriterion::new(&fig4_5(), TractionLaw::AsPrinted).unwrap();
        assert!((exact.critical_tabor() - 0.20155).abs() > 0.5e-5);
        assert!((exact.double_root() - 1.08258).abs() > 0.5e-5);
    }

    #[test]
    fn consistent_traction_needs_a_larger_tabor_parameter_for_an_instability() {
        // With p = 8w/(3ζ₀)[s³ − s⁹] (k = α = β = 1) the coefficients are independent of C₆,
        // C₁₂: c₁ = 5π/√2, c₂ = 36465√2π/8192; closed forms, 1e-13.
        let crit = InstabilityCriterion::new(&fig4_5(), TractionLaw::Consistent).unwrap();
        assert!((crit.c1() - 5.0 * PI / SQRT_2).abs() < 1e-13 * crit.c1());
        assert!((crit.c2() - 36465.0 * SQRT_2 * PI / 8192.0).abs() < 1e-13 * crit.c2());
        let printed = InstabilityCriterion::new(&fig4_5(), TractionLaw::AsPrinted).unwrap();
        assert!(crit.critical_tabor() > 2.0 * printed.critical_tabor());
        // The Boussinesq ratio is (6435π/65536)/(3π/16).
        let i9 = integrate(|t: f64| (1.0 + t * t).powi(-9), 0.0, 50.0, 0.0, 1e-14).unwrap();
        assert!((i9.value / (3.0 * PI / 16.0) - BOUSSINESQ_RATIO).abs() < 1e-12);
    }
}
