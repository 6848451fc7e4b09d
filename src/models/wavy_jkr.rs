//! The JKR theory of a wavy tip, Eq. (4.26) of section 4.5.1 (Guduru 2007, Kesari et al. 2010:
//! `[34]`, `[35]` of the dissertation): an elastic tip shaped as a paraboloid of radius R
//! carrying the axisymmetric undulation of (4.10), against a rigid flat, with a simply connected
//! contact of radius a and zero-range adhesion w. Its equilibrium curve, the stability of each
//! state under displacement control, and the displacement-controlled cycle with its
//! asperity-scale jumps, adhesive force and hysteresis.
//!
//! Variables (section 3.2.1): P̄ = P/(2E*R²) (compression positive), h̄ = h/R (indentation depth,
//! positive into contact, as in chapter 1; chapter 4's figures plot −h), ā = a/R, ℓ = πw/(E*R),
//! Ā = A/R, λ̄ = λ/R, and k = 2π/λ̄. The profile (4.10) is f(r) = r²/(2R) + A(1 − cos(2πr/λ)).
//!
//! Derivation. For an axisymmetric frictionless punch of profile f (f(0) = 0) with contact
//! radius a, Sneddon's solution without edge singularity gives the depth and force
//!
//! ```text
//! δ_H(a) = a ∫₀^a f'(x)/√(a²−x²) dx = a ∫₀^{π/2} f'(a sin θ) dθ
//! P_H(a) = 2E* ∫₀^a x² f'(x)/√(a²−x²) dx = 2E* a² ∫₀^{π/2} sin²θ f'(a sin θ) dθ
//! ```
//!
//! with dP_H/da = 2E*a dδ_H/da. JKR adds a flat-punch displacement Δ at fixed a, of stiffness
//! 2E*a, whose edge energy release rate G = E*Δ²/(2πa) must equal w: Δ = √(2πaw/E*), and
//! δ = δ_H − Δ, P = P_H − 2E*aΔ. For the undulation f' = Ak sin(kx), and with
//! ∫₀^{π/2} sin(z sin θ) dθ = (π/2)H₀(z), ∫₀^{π/2} cos²θ sin(z sin θ) dθ = (π/2)H₁(z)/z:
//!
//! ```text
//! δ_wave = (π/2) A k a H₀(ka),   P_wave = π E* A k a² H₀(ka) − π E* A a H₁(ka)
//! ```
//!
//! so that, in the variables above (ERRATA's reading of (4.26), with ℓ for the printed "χ"),
//!
//! ```text
//! P̄(ā) = 2ā³/3 − √(2ℓā³) + (π²Āā²/λ̄) H₀(2πā/λ̄) − (πĀā/2) H₁(2πā/λ̄)        (4.26a)
//! h̄(ā) = ā² − √(2ℓā) + (π²Āā/λ̄) H₀(2πā/λ̄)                                (4.26b)
//! ```
//!
//! The signs of the wavy terms follow: the undulation rises away from the apex, so it adds depth
//! and force (H₀ > 0 near the apex), and the H₁ term is the part of P_wave not proportional
//! to δ_wave. The tests check (4.26) against quadrature of the Sneddon integrals.
//!
//! Stability under displacement control. At fixed h, the energy Π(a) = U_el − πa²w has
//! ∂Π/∂a = E*(δ_H(a) − δ)² − 2πaw, i.e. in these variables
//!
//! ```text
//! ∂Π̄/∂ā = (h̄_H(ā) − h̄)²/2 − ℓā,     Π̄ = Π/(2E*R³)
//! ```
//!
//! which vanishes at Δ̄ = h̄_H − h̄ = √(2ℓā). There ∂²Π̄/∂ā² = Δ̄ h̄_H' − ℓ = Δ̄ (h̄_H' − Δ̄/(2ā))
//! = Δ̄ dh̄/dā along the curve, so for ℓ > 0 a state is stable iff dh̄/dā > 0. Since
//! dP̄/dā = ā dh̄/dā − Δ̄, the slope of the P̄-h̄ curve is dP̄/dh̄ = ā − Δ̄/(dh̄/dā): a state is
//! stable iff that slope is below the contact stiffness 2E*a (ā in these units), and the
//! displacement-controlled path jumps at the turning points dh̄/dā = 0 of h̄(ā). For ℓ = 0 the
//! criterion is taken as its limit.
//!
//! The displacement-controlled cycle. Approaching from a gap, the tip touches at h̄ = 0 and
//! jumps into contact (pull-in) at the smallest ā with h̄(ā) = 0. Loading follows ā upward while
//! h̄ rises; at a local maximum of h̄ (a fold) it jumps at fixed h̄ to the next ā where h̄ returns
//! to that value: the contact spreads across an asperity. Unloading from h̄_max follows ā
//! downward; at a local minimum of h̄ it jumps back to the previous ā at that h̄ (recession), or,
//! when there is none (the global minimum), out of contact (pull-off). The loop area
//! ∮ P̄ dh̄ is the energy lost, in units of 2E*R³.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::numerics::quadrature::integrate;
use crate::numerics::roots::brent;
use crate::numerics::special::struve_h0_h1;

/// Samples per wavelength (and per JKR length scale) of the marches that locate folds and
/// crossings in [`WavyJkr::cycle`]: two folds closer than 1/64 of a wavelength would be missed.
const CYCLE_SAMPLES_PER_WAVELENGTH: usize = 64;

/// Largest number of samples [`WavyJkr::curve`] will produce.
const MAX_CURVE_SAMPLES: usize = 10_000_000;

/// Parameters of the wavy-tip JKR theory (4.26), non-dimensional.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavyJkrParams {
    /// Adhesion parameter ℓ = πw/(E*R) ≥ 0 [-], Eq. (4.25) (printed "χ" in (4.26)).
    pub ell: f64,
    /// Amplitude of the undulation Ā = A/R ≥ 0 [-].
    pub amplitude_bar: f64,
    /// Wavelength of the undulation λ̄ = λ/R > 0 [-].
    pub wavelength_bar: f64,
}

impl Default for WavyJkrParams {
    /// The theoretical curve of Figure 4.7b: ℓ = 2.26e-5 (printed as χ), A/R = 1.25e-4,
    /// λ/R = 1.25e-2.
    fn default() -> Self {
        Self {
            ell: 2.26e-5,
            amplitude_bar: 1.25e-4,
            wavelength_bar: 1.25e-2,
        }
    }
}

/// One equilibrium state of (4.26) (non-dimensional), or a state out of contact (ā = 0, P̄ = 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavyState {
    /// Contact radius ā = a/R.
    pub a: f64,
    /// Indentation depth h̄ = h/R.
    pub h: f64,
    /// Force P̄ = P/(2E*R²), compression positive.
    pub p: f64,
    /// Stable under displacement control (dh̄/dā > 0; out of contact: true).
    pub stable: bool,
}

/// What a jump of the displacement-controlled cycle does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JumpKind {
    /// Into contact at first touch (h̄ = 0).
    PullIn,
    /// Loading: the contact spreads across an asperity (ā jumps up).
    Advance,
    /// Unloading: the contact recedes across an asperity (ā jumps down).
    Recede,
    /// Out of contact.
    PullOff,
}

/// A jump at fixed depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavyJump {
    /// What it does.
    pub kind: JumpKind,
    /// State just before (a fold of h̄(ā), or the free state at h̄ = 0 for pull-in).
    pub from: WavyState,
    /// State just after (stable, or the free state for pull-off).
    pub to: WavyState,
}

/// The displacement-controlled cycle to a maximum depth.
#[derive(Debug, Clone, PartialEq)]
pub struct WavyCycle {
    /// Largest depth h̄_max = |h_min|/R of the cycle.
    pub h_max: f64,
    /// The jumps in order: pull-in, advances, recessions, pull-off.
    pub jumps: Vec<WavyJump>,
    /// The measured loading path from the pull-off depth at P̄ = 0 to h̄_max (a jump appears as
    /// two consecutive states at one depth).
    pub loading: Vec<WavyState>,
    /// The measured unloading path from h̄_max to the pull-off depth at P̄ = 0.
    pub unloading: Vec<WavyState>,
    /// Adhesive force −min P̄ over the measured cycle (positive when tensile), units 2E*R².
    pub adhesive_force: f64,
    /// Hysteresis ∮ P̄ dh̄, the loop area, units 2E*R³.
    pub hysteresis: f64,
}

/// The wavy-tip JKR theory at given (ℓ, Ā, λ̄).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavyJkr {
    ell: f64,
    amplitude_bar: f64,
    wavelength_bar: f64,
    /// k = 2π/λ̄.
    k: f64,
    /// π²Ā/λ̄, the coefficient of the H₀ terms.
    c: f64,
}

impl WavyJkr {
    /// Validate the parameters.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `ell` or `amplitude` unless ≥ 0 and finite, or
    /// `wavelength` unless positive and finite.
    pub fn new(params: &WavyJkrParams) -> Result<Self> {
        for (name, v) in [("ell", params.ell), ("amplitude_bar", params.amplitude_bar)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(name, v, "must be finite and not negative"));
            }
        }
        let lambda = params.wavelength_bar;
        if !(lambda.is_finite() && lambda > 0.0) {
            return Err(Error::invalid(
                "wavelength_bar",
                lambda,
                "must be positive and finite",
            ));
        }
        Ok(Self {
            ell: params.ell,
            amplitude_bar: params.amplitude_bar,
            wavelength_bar: lambda,
            k: 2.0 * PI / lambda,
            c: PI * PI * params.amplitude_bar / lambda,
        })
    }

    /// The parameters.
    pub fn params(&self) -> WavyJkrParams {
        WavyJkrParams {
            ell: self.ell,
            amplitude_bar: self.amplitude_bar,
            wavelength_bar: self.wavelength_bar,
        }
    }

    /// Non-adhesive (Sneddon) depth of the wavy profile h̄_H(ā) at contact radius `a` = ā.
    ///
    /// ```text
    /// h̄_H(ā) = ā² + (π²Āā/λ̄) H₀(2πā/λ̄)
    /// ```
    pub fn non_adhesive_depth(&self, a: f64) -> f64 {
        let (h0, _) = struve_h0_h1(self.k * a);
        a * a + self.c * a * h0
    }

    /// Non-adhesive (Sneddon) force P̄_H(ā).
    ///
    /// ```text
    /// P̄_H(ā) = 2ā³/3 + (π²Āā²/λ̄) H₀(2πā/λ̄) − (πĀā/2) H₁(2πā/λ̄)
    /// ```
    pub fn non_adhesive_force(&self, a: f64) -> f64 {
        let (h0, h1) = struve_h0_h1(self.k * a);
        2.0 / 3.0 * a.powi(3) + self.c * a * a * h0 - 0.5 * PI * self.amplitude_bar * a * h1
    }

    /// Indentation depth h̄ at contact radius `a` = ā ≥ 0.
    ///
    /// Implements Eq. (4.26b) (ERRATA reading):
    /// ```text
    /// h̄ = ā² − √(2ℓā) + (π²Āā/λ̄) H₀(2πā/λ̄)
    /// ```
    pub fn depth(&self, a: f64) -> f64 {
        self.non_adhesive_depth(a) - (2.0 * self.ell * a).sqrt()
    }

    /// Force P̄ at contact radius `a` = ā ≥ 0.
    ///
    /// Implements Eq. (4.26a) (ERRATA reading):
    /// ```text
    /// P̄ = 2ā³/3 − √(2ℓā³) + (π²Āā²/λ̄) H₀(2πā/λ̄) − (πĀā/2) H₁(2πā/λ̄)
    /// ```
    pub fn force(&self, a: f64) -> f64 {
        self.non_adhesive_force(a) - (2.0 * self.ell * a.powi(3)).sqrt()
    }

    /// dh̄/dā at `a` = ā > 0, with H₀' = 2/π − H₁:
    ///
    /// ```text
    /// dh̄/dā = 2ā − √(2ℓ)/(2√ā) + (π²Ā/λ̄) [ H₀(kā) + kā (2/π − H₁(kā)) ]
    /// ```
    pub fn depth_slope(&self, a: f64) -> f64 {
        let x = self.k * a;
        let (h0, h1) = struve_h0_h1(x);
        2.0 * a - 0.5 * (2.0 * self.ell / a).sqrt() + self.c * (h0 + x * (2.0 / PI - h1))
    }

    /// dP̄/dā at `a` = ā > 0, differentiated term by term (H₀' = 2/π − H₁, H₁' = H₀ − H₁/x):
    ///
    /// ```text
    /// dP̄/dā = 2ā² − (3/2)√(2ℓā) + (π²Ā/λ̄)[2āH₀ + kā²(2/π − H₁)] − (πĀ/2)[H₁ + kā H₀ − H₁]
    /// ```
    /// It equals ā dh̄/dā − √(2ℓā) (Sneddon's dP_H/dδ_H = 2E*a; the tests check it).
    pub fn force_slope(&self, a: f64) -> f64 {
        let x = self.k * a;
        let (h0, h1) = struve_h0_h1(x);
        2.0 * a * a - 1.5 * (2.0 * self.ell * a).sqrt() + self.c * (2.0 * a * h0 + x * a * (2.0 / PI - h1))
            - 0.5 * PI * self.amplitude_bar * x * h0
    }

    /// Slope of the P̄-h̄ curve at `a` = ā, dP̄/dh̄ = (dP̄/dā)/(dh̄/dā) (∞ at a fold).
    pub fn stiffness(&self, a: f64) -> f64 {
        self.force_slope(a) / self.depth_slope(a)
    }

    /// Whether the state at `a` = ā is stable under displacement control: dh̄/dā > 0, i.e.
    /// ∂²Π/∂a² > 0 at fixed h, equivalently dP̄/dh̄ < ā (module docs).
    pub fn is_stable(&self, a: f64) -> bool {
        self.depth_slope(a) > 0.0
    }

    /// The equilibrium state at contact radius `a` = ā > 0.
    pub fn state(&self, a: f64) -> WavyState {
        WavyState {
            a,
            h: self.depth(a),
            p: self.force(a),
            stable: self.is_stable(a),
        }
    }

    /// The equilibrium curve on ā ∈ (0, `a_max`]: `per_wavelength` samples per wavelength λ̄
    /// (and at least as many over `a_max`), 30 geometric samples from 1e-6 of that spacing up
    /// to it (the √ā end), and the turning points of h̄(ā), where stability changes, inserted
    /// exactly; in increasing ā.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `a_max` > 0 is finite and `per_wavelength` ≥ 4, or when
    /// more than 1e7 samples would be needed; root-finding failures (not expected).
    pub fn curve(&self, a_max: f64, per_wavelength: usize) -> Result<Vec<WavyState>> {
        if !(a_max.is_finite() && a_max > 0.0) {
            return Err(Error::invalid("a_max", a_max, "must be positive and finite"));
        }
        if per_wavelength < 4 {
            return Err(Error::invalid(
                "per_wavelength",
                per_wavelength,
                "must be at least 4",
            ));
        }
        let step = self.wavelength_bar.min(a_max) / per_wavelength as f64;
        let n = (a_max / step).ceil();
        if n > MAX_CURVE_SAMPLES as f64 {
            return Err(Error::invalid(
                "per_wavelength",
                per_wavelength,
                "needs more than 1e7 samples over a_max",
            ));
        }
        let n = n as usize;
        let mut grid: Vec<f64> = (0..30)
            .map(|i| step * 1e-6f64.powf(1.0 - i as f64 / 30.0))
            .collect();
        grid.extend((1..=n).map(|i| (i as f64 * step).min(a_max)));
        let mut out = Vec::with_capacity(grid.len() + 16);
        for w in grid.windows(2) {
            out.push(self.state(w[0]));
            let (s0, s1) = (self.depth_slope(w[0]), self.depth_slope(w[1]));
            if s0 != 0.0 && s1 != 0.0 && s0.signum() != s1.signum() {
                let fold = brent(|a| self.depth_slope(a), w[0], w[1], 1e-15 * w[1])?;
                out.push(WavyState {
                    stable: false,
                    ..self.state(fold)
                });
            }
        }
        if let Some(&last) = grid.last() {
            out.push(self.state(last));
        }
        Ok(out)
    }

    /// Spacing of the marches of [`Self::cycle`]: 1/64 of the smallest length of the problem
    /// (the wavelength, the JKR pull-in radius (2ℓ)^(1/3), the Hertz radius √h̄_max).
    fn march_step(&self, h_max: f64) -> f64 {
        let scale = self.wavelength_bar.min((2.0 * self.ell).cbrt()).min(h_max.sqrt());
        scale / CYCLE_SAMPLES_PER_WAVELENGTH as f64
    }

    /// The displacement-controlled cycle from first contact to the depth `h_max` = h̄_max > 0
    /// and back to pull-off: its jumps, measured path, adhesive force and hysteresis.
    ///
    /// Loading visits the states where h̄(ā) equals its running maximum from the pull-in state,
    /// unloading those where it equals its running minimum from ā_max (module docs). Folds and
    /// landing states are found by marching in ā at 1/64 of the smallest length scale and
    /// refining by Brent's method (to 1e-15 relative). The hysteresis is
    ///
    /// ```text
    /// ∮ P̄ dh̄ = Σ_segments ∫ P̄(ā) dh̄/dā dā        (jumps and the free approach add nothing)
    /// ```
    ///
    /// by adaptive Gauss-Kronrod quadrature along each followed segment (relative 1e-12).
    ///
    /// ```
    /// use adhesion::models::wavy_jkr::{JumpKind, WavyJkr, WavyJkrParams};
    /// // Figure 4.7b to |h_min|/R = 7e-4: asperity-scale jumps between pull-in and pull-off.
    /// let cycle = WavyJkr::new(&WavyJkrParams::default())?.cycle(7e-4)?;
    /// assert_eq!(cycle.jumps.first().map(|j| j.kind), Some(JumpKind::PullIn));
    /// assert_eq!(cycle.jumps.last().map(|j| j.kind), Some(JumpKind::PullOff));
    /// assert!(cycle.jumps.len() > 2 && cycle.hysteresis > 0.0);
    /// # Ok::<(), adhesion::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `h_max` > 0 and finite, or when ℓ = 0 (no pull-in:
    /// the contact radius at first touch is zero); [`Error::Unresolvable`] when a march does
    /// not end (not expected); root-finding and quadrature failures.
    pub fn cycle(&self, h_max: f64) -> Result<WavyCycle> {
        if !(h_max.is_finite() && h_max > 0.0) {
            return Err(Error::invalid("h_max", h_max, "must be positive and finite"));
        }
        if self.ell <= 0.0 {
            return Err(Error::invalid(
                "ell",
                self.ell,
                "the displacement-controlled cycle needs adhesion (ell > 0)",
            ));
        }
        let march = March::new(self, self.march_step(h_max));
        let mut jumps = Vec::new();
        // Pull-in: the first ā where h̄ reaches 0 from below (h̄ ~ −√(2ℓā) at small ā).
        let a_in = march
            .crossing(0.0, march.floor, Dir::Up)?
            .ok_or_else(|| unresolvable("no pull-in state"))?;
        let free = |h: f64| WavyState {
            a: 0.0,
            h,
            p: 0.0,
            stable: true,
        };
        jumps.push(WavyJump {
            kind: JumpKind::PullIn,
            from: free(0.0),
            to: self.state(a_in),
        });
        // Loading segments [from, to] in ā, increasing.
        let mut loading_segments = Vec::new();
        let mut start = a_in;
        let a_end = loop {
            let (end, fold) = march.follow(start, Dir::Up, h_max)?;
            loading_segments.push((start, end));
            if !fold {
                break end;
            }
            let level = self.depth(end);
            let beyond = march
                .extremum(end, Dir::Up)?
                .ok_or_else(|| unresolvable("no minimum after a fold"))?;
            let land = march
                .crossing(level, beyond, Dir::Up)?
                .ok_or_else(|| unresolvable("no landing state"))?;
            jumps.push(WavyJump {
                kind: JumpKind::Advance,
                from: self.state(end),
                to: self.state(land),
            });
            start = land;
        };
        // Unloading segments, ā decreasing, until pull-off.
        let mut unloading_segments = Vec::new();
        let mut start = a_end;
        let pull_off_depth = loop {
            let (end, _) = march.follow(start, Dir::Down, f64::NEG_INFINITY)?;
            unloading_segments.push((start, end));
            let level = self.depth(end);
            let land = match march.extremum(end, Dir::Down)? {
                Some(before) => march.crossing(level, before, Dir::Down)?,
                None => None,
            };
            match land {
                Some(land) => {
                    jumps.push(WavyJump {
                        kind: JumpKind::Recede,
                        from: self.state(end),
                        to: self.state(land),
                    });
                    start = land;
                }
                None => {
                    jumps.push(WavyJump {
                        kind: JumpKind::PullOff,
                        from: self.state(end),
                        to: free(level),
                    });
                    break level;
                }
            }
        };
        // Measured paths, the loop area and the largest tension.
        let mut loading = vec![free(pull_off_depth), free(0.0)];
        for &(a0, a1) in &loading_segments {
            loading.extend(march.samples(a0, a1));
        }
        let mut unloading = Vec::new();
        for &(a0, a1) in &unloading_segments {
            unloading.extend(march.samples(a0, a1));
        }
        unloading.push(free(pull_off_depth));
        let mut hysteresis = 0.0;
        let mut min_force: f64 = 0.0;
        for &(a0, a1) in loading_segments.iter().chain(&unloading_segments) {
            let r = integrate(
                |a| self.force(a) * self.depth_slope(a),
                a0,
                a1,
                1e-15 * self.ell.powf(5.0 / 3.0),
                1e-12,
            )?;
            hysteresis += r.value;
            min_force = min_force.min(march.min_force(a0, a1)?);
        }
        Ok(WavyCycle {
            h_max,
            jumps,
            loading,
            unloading,
            adhesive_force: -min_force,
            hysteresis,
        })
    }
}

fn unresolvable(reason: &str) -> Error {
    Error::Unresolvable {
        model: "wavy JKR",
        reason: reason.into(),
    }
}

/// Direction of a march in ā.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Dir {
    Up,
    Down,
}

/// Marching in ā at a fixed spacing (geometric below it, towards ā → 0), for [`WavyJkr::cycle`].
struct March<'a> {
    model: &'a WavyJkr,
    step: f64,
    /// Smallest ā visited; below it h̄ ≈ −√(2ℓā) is monotone and no event can occur.
    floor: f64,
}

impl<'a> March<'a> {
    /// Upper limit on the number of steps of one march (the tip would have to cross 10⁶
    /// spacings without an event).
    const MAX_STEPS: usize = 1_000_000;

    fn new(model: &'a WavyJkr, step: f64) -> Self {
        Self {
            model,
            step,
            floor: step * 1e-9,
        }
    }

    /// The next sample after `a` in direction `dir` (`None` below the floor).
    fn next(&self, a: f64, dir: Dir) -> Option<f64> {
        match dir {
            Dir::Up if a < self.step => Some((2.0 * a).min(self.step)),
            Dir::Up => Some(a + self.step),
            Dir::Down if a > 2.0 * self.step => Some(a - self.step),
            Dir::Down => Some(0.5 * a).filter(|&b| b >= self.floor),
        }
    }

    /// Follow the stable segment from `a` in direction `dir` (h̄ rising for `Up`, falling for
    /// `Down`) until h̄ reaches `target` (returns (ā there, false)) or a fold (ā of the fold,
    /// true), whichever comes first.
    fn follow(&self, a: f64, dir: Dir, target: f64) -> Result<(f64, bool)> {
        let m = self.model;
        let mut a0 = a;
        for _ in 0..Self::MAX_STEPS {
            let a1 = self
                .next(a0, dir)
                .ok_or_else(|| unresolvable("a stable segment reaches a = 0"))?;
            if m.depth_slope(a1) <= 0.0 {
                let fold = brent(|a| m.depth_slope(a), a0, a1, 1e-15 * a0.max(a1))?;
                if dir == Dir::Up && m.depth(fold) >= target {
                    return Ok((brent(|a| m.depth(a) - target, a0, fold, 1e-15 * fold)?, false));
                }
                return Ok((fold, true));
            }
            if dir == Dir::Up && m.depth(a1) >= target {
                return Ok((brent(|a| m.depth(a) - target, a0, a1, 1e-15 * a1)?, false));
            }
            a0 = a1;
        }
        Err(unresolvable("a stable segment does not end"))
    }

    /// From a fold at `a`, the next extremum of h̄ in direction `dir`, where the curve turns
    /// stable again (`None` when the march reaches ā → 0 first).
    fn extremum(&self, a: f64, dir: Dir) -> Result<Option<f64>> {
        let m = self.model;
        // The last sample on the unstable stretch (dh̄/dā < 0); at the fold itself the sign of
        // dh̄/dā is rounding noise, so it does not count.
        let mut unstable: Option<f64> = None;
        let mut a0 = a;
        for _ in 0..Self::MAX_STEPS {
            let Some(a1) = self.next(a0, dir) else {
                return Ok(None);
            };
            if m.depth_slope(a1) > 0.0 {
                // A stretch narrower than one spacing: look for it between the fold and a1.
                let lo = match unstable {
                    Some(x) => x,
                    None => (1..=40)
                        .map(|j| a + (a1 - a) * 0.5f64.powi(j))
                        .find(|&x| m.depth_slope(x) < 0.0)
                        .ok_or_else(|| unresolvable("no unstable stretch after a fold"))?,
                };
                return Ok(Some(brent(|a| m.depth_slope(a), lo, a1, 1e-15 * lo.max(a1))?));
            }
            unstable = Some(a1);
            a0 = a1;
        }
        Err(unresolvable("no turning point after a fold"))
    }

    /// The first ā after `a` in direction `dir` where h̄ crosses `level` (upwards for `Up`,
    /// downwards for `Down`); `None` when the march reaches ā → 0 first.
    fn crossing(&self, level: f64, a: f64, dir: Dir) -> Result<Option<f64>> {
        let m = self.model;
        let mut a0 = a;
        for _ in 0..Self::MAX_STEPS {
            let Some(a1) = self.next(a0, dir) else {
                return Ok(None);
            };
            let h1 = m.depth(a1);
            let crossed = match dir {
                Dir::Up => h1 >= level,
                Dir::Down => h1 <= level,
            };
            if crossed {
                let x = brent(|a| m.depth(a) - level, a0, a1, 1e-15 * a0.max(a1))?;
                return Ok(Some(x));
            }
            a0 = a1;
        }
        Err(unresolvable("no crossing of the depth level"))
    }

    /// States from `a0` to `a1` (either order) at the march spacing, both ends included.
    fn samples(&self, a0: f64, a1: f64) -> Vec<WavyState> {
        let n = ((a1 - a0).abs() / self.step).ceil().max(1.0) as usize;
        (0..=n)
            .map(|i| self.model.state(a0 + (a1 - a0) * i as f64 / n as f64))
            .collect()
    }

    /// Smallest P̄ on [a0, a1] (either order): the ends and every interior minimum (a sign
    /// change of dP̄/dā from − to + between samples, refined by Brent's method).
    fn min_force(&self, a0: f64, a1: f64) -> Result<f64> {
        let m = self.model;
        let (lo, hi) = (a0.min(a1), a0.max(a1));
        let mut best = m.force(lo).min(m.force(hi));
        let n = ((hi - lo) / self.step).ceil().max(1.0) as usize;
        let mut x0 = lo;
        let mut s0 = m.force_slope(lo);
        for i in 1..=n {
            let x1 = lo + (hi - lo) * i as f64 / n as f64;
            let s1 = m.force_slope(x1);
            if s0 < 0.0 && s1 > 0.0 {
                let x = brent(|a| m.force_slope(a), x0, x1, 1e-15 * x1)?;
                best = best.min(m.force(x));
            }
            x0 = x1;
            s0 = s1;
        }
        Ok(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::classical::SphereContact;
    use crate::models::maugis_dugdale::jkr_loss_constant;
    use crate::numerics::quadrature::polygon_area;

    fn fig4_7() -> WavyJkr {
        WavyJkr::new(&WavyJkrParams::default()).unwrap()
    }

    /// Sneddon's integrals for the profile (4.10) by adaptive quadrature in θ (x = ā sin θ
    /// removes the endpoint singularity), to 1e-13 relative: (h̄_H, P̄_H).
    fn sneddon(model: &WavyJkr, a: f64) -> (f64, f64) {
        let p = model.params();
        let k = 2.0 * PI / p.wavelength_bar;
        let slope = |x: f64| x + p.amplitude_bar * k * (k * x).sin();
        let depth = integrate(|t: f64| slope(a * t.sin()), 0.0, PI / 2.0, 0.0, 1e-13).unwrap();
        let force = integrate(
            |t: f64| t.sin().powi(2) * slope(a * t.sin()),
            0.0,
            PI / 2.0,
            0.0,
            1e-13,
        )
        .unwrap();
        (a * depth.value, a * a * force.value)
    }

    #[test]
    fn equation_4_26_matches_quadrature_of_the_sneddon_integrals() {
        // ā from inside the first wavelength to 8 wavelengths (kā = 50); with the JKR terms
        // added. The wavy parts are compared relative to their own scale (they pass through
        // zero), the totals relative to |value| + that scale; 1e-9 (quadrature 1e-13, Struve
        // 1e-15).
        let m = fig4_7();
        let p = m.params();
        for a in [1e-3, 5e-3, 1.2e-2, 2.6e-2, 4.1e-2, 0.1] {
            let (h_q, p_q) = sneddon(&m, a);
            let wave_scale = p.amplitude_bar * (1.0 + a / p.wavelength_bar);
            let h_model = m.non_adhesive_depth(a);
            let p_model = m.non_adhesive_force(a);
            assert!(
                (h_model - h_q).abs() < 1e-9 * (h_q.abs() + wave_scale),
                "h at {a}"
            );
            assert!(
                (p_model - p_q).abs() < 1e-9 * (p_q.abs() + wave_scale * a),
                "P at {a}"
            );
            // Total with the JKR flat-punch terms.
            let h_total = h_q - (2.0 * p.ell * a).sqrt();
            let p_total = p_q - (2.0 * p.ell * a.powi(3)).sqrt();
            assert!((m.depth(a) - h_total).abs() < 1e-9 * (h_total.abs() + wave_scale));
            assert!((m.force(a) - p_total).abs() < 1e-9 * (p_total.abs() + wave_scale * a));
        }
    }

    #[test]
    fn smooth_tip_is_the_jkr_theory_1_2() {
        // Ā = 0: (4.26) is (1.2) in the units of 3.2.1, exactly (closed forms; 1e-12).
        let (radius, modulus, w) = (10e-6, 2.2e6 / 0.9375, 1.688e-4);
        let jkr = SphereContact::new(radius, modulus, w).unwrap();
        let ell = PI * w / (modulus * radius);
        let m = WavyJkr::new(&WavyJkrParams {
            ell,
            amplitude_bar: 0.0,
            wavelength_bar: 1e-2,
        })
        .unwrap();
        for a in [1e-4, 3e-3, 1e-2, 5e-2] {
            let s = jkr.jkr(a * radius);
            let (h, p) = (s.h / radius, s.p / (2.0 * modulus * radius * radius));
            assert!((m.depth(a) - h).abs() < 1e-12 * h.abs(), "{a}");
            assert!((m.force(a) - p).abs() < 1e-12 * p.abs(), "{a}");
        }
    }

    #[test]
    fn vanishing_amplitude_tends_to_jkr_linearly() {
        // (4.26) is linear in Ā: at Ā = 1e-18 the difference from JKR is below 1e-12 of the
        // values (the wavy terms carry π²/λ̄ ≈ 790), and the difference quotient is the same at
        // Ā = 1e-6 and 1e-3.
        let base = WavyJkrParams::default();
        let jkr = WavyJkr::new(&WavyJkrParams {
            amplitude_bar: 0.0,
            ..base
        })
        .unwrap();
        let tiny = WavyJkr::new(&WavyJkrParams {
            amplitude_bar: 1e-18,
            ..base
        })
        .unwrap();
        for a in [5e-3, 2e-2, 6e-2] {
            assert!((tiny.depth(a) - jkr.depth(a)).abs() < 1e-12 * jkr.depth(a).abs());
            assert!((tiny.force(a) - jkr.force(a)).abs() < 1e-12 * jkr.force(a).abs());
            let q = |amp: f64| {
                let m = WavyJkr::new(&WavyJkrParams {
                    amplitude_bar: amp,
                    ..base
                })
                .unwrap();
                (m.depth(a) - jkr.depth(a)) / amp
            };
            assert!((q(1e-6) - q(1e-3)).abs() < 1e-8 * q(1e-3).abs());
        }
    }

    #[test]
    fn long_wavelength_adds_the_curvature_of_the_undulation() {
        // For ā ≪ λ̄, A(1 − cos kr) ≈ A k² r²/2: a paraboloid of curvature 1/R + Ak²; Hertz
        // depth ā²(1 + Āk²) to O((kā)²) relative.
        let m = WavyJkr::new(&WavyJkrParams {
            ell: 0.0,
            amplitude_bar: 1e-3,
            wavelength_bar: 10.0,
        })
        .unwrap();
        let k = 2.0 * PI / 10.0;
        for a in [1e-3, 1e-2] {
            let hertz = a * a * (1.0 + 1e-3 * k * k);
            assert!((m.depth(a) - hertz).abs() < (k * a).powi(2) * hertz, "{a}");
        }
    }

    #[test]
    fn slopes_match_finite_differences_and_sneddons_stiffness_identity() {
        // Central differences, step 1e-6 ā (truncation ~1e-12 relative, rounding ~1e-10 of the
        // derivative's scale); the identity dP̄/dā = ā dh̄/dā − √(2ℓā) to 1e-13.
        let m = fig4_7();
        for a in [2e-3, 1e-2, 1.9e-2, 3.3e-2, 0.1] {
            let d = 1e-6 * a;
            let dh = (m.depth(a + d) - m.depth(a - d)) / (2.0 * d);
            let dp = (m.force(a + d) - m.force(a - d)) / (2.0 * d);
            let (sh, sp) = (m.depth_slope(a), m.force_slope(a));
            let hscale = 2.0 * a + (m.params().ell / a).sqrt() + m.c * (1.0 + m.k * a);
            assert!((dh - sh).abs() < 1e-8 * hscale, "dh at {a}: {dh} vs {sh}");
            assert!((dp - sp).abs() < 1e-8 * hscale * a, "dP at {a}: {dp} vs {sp}");
            let identity = a * sh - (2.0 * m.params().ell * a).sqrt();
            assert!((sp - identity).abs() < 1e-13 * hscale * a, "identity at {a}");
        }
    }

    #[test]
    fn stability_flag_is_the_sign_of_the_second_variation_of_the_energy() {
        // ∂Π̄/∂ā|_h̄ = (h̄_H(ā) − h̄)²/2 − ℓā, differentiated numerically at each equilibrium
        // (h̄ = h̄(ā)): the sign of ∂²Π̄/∂ā² must be the flag, and its value Δ̄ dh̄/dā.
        let m = fig4_7();
        let ell = m.params().ell;
        let curve = m.curve(0.05, 32).unwrap();
        let mut n_unstable = 0;
        for s in curve.iter().filter(|s| s.a > 1e-4) {
            let energy_slope = |a: f64| 0.5 * (m.non_adhesive_depth(a) - s.h).powi(2) - ell * a;
            assert!(energy_slope(s.a).abs() < 1e-12 * ell * s.a.max(1e-3), "{}", s.a);
            let d = 1e-5 * s.a;
            let second = (energy_slope(s.a + d) - energy_slope(s.a - d)) / (2.0 * d);
            let expected = (2.0 * ell * s.a).sqrt() * m.depth_slope(s.a);
            assert!(
                (second - expected).abs() < 1e-6 * (ell + expected.abs()),
                "{}",
                s.a
            );
            if expected.abs() > 1e-6 * ell {
                assert_eq!(s.stable, second > 0.0, "{}", s.a);
            }
            n_unstable += usize::from(!s.stable);
            // Stable iff the P̄-h̄ slope is below the contact stiffness ā (away from folds).
            if m.depth_slope(s.a).abs() > 1e-3 {
                assert_eq!(s.stable, m.stiffness(s.a) < s.a, "{}", s.a);
            }
        }
        assert!(n_unstable > 0, "the Fig. 4.7 curve has unstable stretches");
    }

    #[test]
    fn curve_inserts_every_turning_point_and_resolves_each_wavelength() {
        let m = fig4_7();
        let curve = m.curve(0.05, 64).unwrap();
        assert!(curve.len() >= 64 * 4);
        // Between consecutive samples the stability flag changes only at an inserted fold.
        let is_fold = |s: &WavyState| m.depth_slope(s.a).abs() < 1e-10;
        for w in curve.windows(2) {
            if w[0].stable != w[1].stable {
                assert!(
                    is_fold(&w[0]) || is_fold(&w[1]),
                    "between {} and {}",
                    w[0].a,
                    w[1].a
                );
            }
        }
        let folds: Vec<_> = curve
            .iter()
            .filter(|s| m.depth_slope(s.a).abs() < 1e-10)
            .collect();
        assert!(folds.len() >= 3, "{}", folds.len());
    }

    #[test]
    fn smooth_tip_cycle_is_the_jkr_cycle_1_3_to_1_6() {
        // Ā = 0: pull-in at h̄ = 0 to ā_B = (2ℓ)^(1/3) (1.3), pull-off at ā_D = (ℓ/8)^(1/3)
        // (1.4), adhesive force 3ℓ/4 (P_C = 3πwR/2, (1.5)), loss 0.52622 ℓ^(5/3) ((1.6), (3.5a)).
        // Closed forms vs root finding to 1e-15 and quadrature to 1e-12: tolerance 1e-10.
        let ell = 2.26e-5;
        let m = WavyJkr::new(&WavyJkrParams {
            ell,
            amplitude_bar: 0.0,
            wavelength_bar: 1.25e-2,
        })
        .unwrap();
        let cycle = m.cycle(7e-4).unwrap();
        let kinds: Vec<_> = cycle.jumps.iter().map(|j| j.kind).collect();
        assert_eq!(kinds, [JumpKind::PullIn, JumpKind::PullOff]);
        let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
        assert!(rel(cycle.jumps[0].to.a, (2.0 * ell).cbrt()) < 1e-10);
        assert!(rel(cycle.jumps[1].from.a, (ell / 8.0).cbrt()) < 1e-10);
        assert!(rel(cycle.adhesive_force, 0.75 * ell) < 1e-10);
        assert!(rel(cycle.hysteresis, jkr_loss_constant() * ell.powf(5.0 / 3.0)) < 1e-10);
    }

    #[test]
    fn wavy_cycle_jumps_at_folds_to_stable_states_and_its_loop_area_is_the_hysteresis() {
        // Fig. 4.7b: h̄_max = 7e-4 (|h_min,2|/R of Fig. 4.7a).
        let m = fig4_7();
        let cycle = m.cycle(7e-4).unwrap();
        let n = cycle.jumps.len();
        assert!(n > 4, "asperity-scale jumps expected, got {n}");
        assert_eq!(cycle.jumps[0].kind, JumpKind::PullIn);
        assert_eq!(cycle.jumps[n - 1].kind, JumpKind::PullOff);
        for j in &cycle.jumps[1..n - 1] {
            // From a fold (dh̄/dā = 0) to a stable state at the same depth.
            assert!(m.depth_slope(j.from.a).abs() < 1e-9, "{j:?}");
            assert!(j.to.stable && (j.to.h - j.from.h).abs() < 1e-15);
            match j.kind {
                JumpKind::Advance => assert!(j.to.a > j.from.a),
                JumpKind::Recede => assert!(j.to.a < j.from.a),
                _ => panic!("{j:?}"),
            }
        }
        // The loading path never decreases in depth, the unloading path never increases.
        assert!(cycle.loading.windows(2).all(|w| w[1].h >= w[0].h - 1e-15));
        assert!(cycle.unloading.windows(2).all(|w| w[1].h <= w[0].h + 1e-15));
        // The shoelace area of the sampled loop converges to the quadrature at second order in
        // the sample spacing (λ̄/64): 1e-3 relative.
        let polygon: Vec<(f64, f64)> = cycle
            .loading
            .iter()
            .chain(&cycle.unloading)
            .map(|s| (s.h, s.p))
            .collect();
        let area = polygon_area(&polygon).abs();
        assert!(
            (area - cycle.hysteresis).abs() < 1e-3 * cycle.hysteresis,
            "{area} vs {}",
            cycle.hysteresis
        );
    }

    #[test]
    fn hysteresis_grows_with_the_maximum_depth() {
        // Depth-dependent hysteresis (Fig. 4.7a): |h_min,1|/R = 1.5e-4 and |h_min,2|/R = 7e-4.
        let m = fig4_7();
        let shallow = m.cycle(1.5e-4).unwrap();
        let deep = m.cycle(7e-4).unwrap();
        assert!(deep.jumps.len() > shallow.jumps.len());
        assert!(deep.hysteresis > shallow.hysteresis);
    }

    #[test]
    fn invalid_parameters_are_named() {
        let d = WavyJkrParams::default();
        for (p, name) in [
            (WavyJkrParams { ell: -1.0, ..d }, "ell"),
            (
                WavyJkrParams {
                    amplitude_bar: f64::NAN,
                    ..d
                },
                "amplitude_bar",
            ),
            (
                WavyJkrParams {
                    wavelength_bar: 0.0,
                    ..d
                },
                "wavelength_bar",
            ),
        ] {
            let e = WavyJkr::new(&p).unwrap_err().to_string();
            assert!(e.contains(&format!("`{name}`")), "{e}");
        }
        assert!(fig4_7().cycle(-1e-4).is_err());
        let no_adhesion = WavyJkr::new(&WavyJkrParams { ell: 0.0, ..d }).unwrap();
        assert!(no_adhesion.cycle(1e-4).is_err());
    }
}
