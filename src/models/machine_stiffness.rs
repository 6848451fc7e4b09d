//! Adhesive contact with machine stiffness (chapter 2): the variational model of section 2.2 for
//! spherical and conical tips, Eqs. (2.28)-(2.49), and appendix A.
//!
//! A rigid axisymmetric tip hangs from the stage by a spring of stiffness k_s and touches an
//! elastic half-space (plane-strain modulus ℰ = E/(1-ν²)) with JKR adhesion (work w). For a stage
//! displacement Δ the state is the contact radius a and the indentation depth h (positive into
//! the substrate). Its stationary points (a°, h°) satisfy h° = h(a°) and Δ = P(a°, h°)/k_s + h°,
//! (2.19)-(2.22), (2.26); they are solutions (stable) when g(a°) > 0, (2.23)-(2.24). For Δ < 0 the
//! out-of-contact state (0, Δ) is a solution too (appendix A.1).
//!
//! Non-dimensional form (the `_bar` quantities), with c = 4/3 for the sphere and 1 for the cone:
//!
//! ```text
//! sphere (2.34)-(2.36):  h̄ = ā² − (4/3)√ā,       P̄ = (3/2)ā h̄ − ā³/2,  ḡ = 3ā^(3/2) − 4ā/(2ā+α) − 1
//! cone   (2.44)-(2.46):  h̄ = ā/2 − √(2ā),        P̄ = 2ā h̄ − ā²/2,      ḡ = √(2ā)/2 − 4ā/(2ā+α) − 1
//! both   (2.35a)/(2.45a): Δ̄ = (c/α) P̄ + h̄
//! ```
//!
//! Along the branch h̄(ā), ḡ(ā) is a positive multiple of dΔ̄/dā, so the stable states are those
//! where the stage displacement grows with the contact radius, and the pull-off is the fold of
//! Δ̄(ā). Scales (SI): sphere â = (9πwR²/8ℰ)^(1/3), ĥ = â²/R, P̂ = 3πwR/2; cone
//! â = w/(πℰtan²θ), ĥ = w/(ℰtanθ), P̂ = w²/(πℰtan³θ); in both, α = k_s/(ℰâ).
//!
//! The hysteresis is returned in the chapter's energy units: (R⁴w⁵/ℰ²)^(1/3) for the sphere and
//! w³/(πℰ²tan⁴θ) = P̂ĥ for the cone. For the sphere P̂ĥ = (3π/2)(9π/8)^(2/3)(R⁴w⁵/ℰ²)^(1/3), the
//! factor (2.38) as printed lacks (see ERRATA).

use crate::error::{Error, Result};
use crate::numerics::curve::{Branch, PathPoint, all_roots, follow, linspace, logspace, stable_states_at};
use crate::numerics::quadrature::{GaussLegendre, polygon_area};
use crate::numerics::roots::{brent, expand_upward};

/// Tip shape of the non-dimensional problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TipShape {
    /// Spherical tip in the paraboloid approximation (2.30), the form the chapter uses.
    Sphere,
    /// Spherical tip with the exact profile, χ of Eq. (2.28), for a sphere of radius
    /// R = `radius_ratio` × â (â of the paraboloid's scaling). Stationary points: h̄(ā) =
    /// ρ ā atanh(ā/ρ) − (4/3)√ā, P̄ = (3/2)ā h̄ − (3ρ/4)(ā² − ρ²) atanh(ā/ρ) − (3/4)ρ² ā (from (2.19),
    /// (2.20), (2.25b) with (2.28)), ρ = R/â; it tends to [`TipShape::Sphere`] as ρ → ∞.
    SphereExact {
        /// ρ = R/â (> 1).
        radius_ratio: f64,
    },
    /// Conical tip, Eq. (2.40).
    Cone,
}

/// Sphere: asymptotic pull-in force P̄ᵢ as α → ∞, Sec. 2.3.1 (the JKR pull-in −4πwR/3 over P̂).
pub const SPHERE_PULL_IN_STIFF: f64 = -8.0 / 9.0;
/// Sphere: asymptotic pull-off force P̄ₒ as α → 0 (force control, −3πwR/2 over P̂).
pub const SPHERE_PULL_OFF_SOFT: f64 = -1.0;
/// Sphere: asymptotic pull-off force P̄ₒ as α → ∞ (JKR displacement control, −5πwR/6 over P̂).
pub const SPHERE_PULL_OFF_STIFF: f64 = -5.0 / 9.0;
/// Sphere: asymptotic hysteresis as α → ∞, (π^(5/3) + 3(2π)^(5/3))/10, Sec. 2.3.1.
pub const SPHERE_HYSTERESIS_STIFF: f64 = 7.092_195_971_863_96;
/// Cone: asymptotic pull-in force P̄ᵢ as α → ∞, Sec. 2.3.2.
pub const CONE_PULL_IN_STIFF: f64 = -32.0;
/// Cone: asymptotic pull-off force P̄ₒ as α → 0, Sec. 2.3.2.
pub const CONE_PULL_OFF_SOFT: f64 = -54.0;
/// Cone: asymptotic pull-off force P̄ₒ as α → ∞, Sec. 2.3.2.
pub const CONE_PULL_OFF_STIFF: f64 = -6.0;
/// Cone: asymptotic hysteresis as α → ∞, Sec. 2.3.2.
pub const CONE_HYSTERESIS_STIFF: f64 = 22.0;

/// (3π/2)(9π/8)^(2/3): P̂ĥ of the sphere in units of (R⁴w⁵/ℰ²)^(1/3), the factor (2.38) lacks.
pub fn sphere_energy_factor() -> f64 {
    1.5 * std::f64::consts::PI * (9.0 * std::f64::consts::PI / 8.0).powf(2.0 / 3.0)
}

/// A state of the tip (non-dimensional or SI, as stated where it is returned).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Contact radius a (0 out of contact).
    pub a: f64,
    /// Indentation depth h (positive into the substrate).
    pub h: f64,
    /// Contact force P (positive in compression).
    pub force: f64,
    /// Stage displacement Δ.
    pub delta: f64,
    /// Whether the state is a solution (local minimum of the energy), (2.24) / appendix A.1.
    pub stable: bool,
}

/// An instability: the state just before the jump and the state just after, at the same Δ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instability {
    /// State just before the jump.
    pub before: State,
    /// State just after the jump.
    pub after: State,
}

impl Instability {
    /// Change of the indentation depth in the jump, h_after − h_before.
    pub fn depth_jump(&self) -> f64 {
        self.after.h - self.before.h
    }

    /// The state on the contact branch (after a pull-in, before a pull-off).
    pub fn contact(&self) -> State {
        if self.after.a > 0.0 {
            self.after
        } else {
            self.before
        }
    }
}

/// A displacement-controlled cycle: loading from Δ_min to Δ_max and unloading back.
#[derive(Debug, Clone, PartialEq)]
pub struct Cycle {
    /// States visited on loading, in order.
    pub loading: Vec<State>,
    /// States visited on unloading, in order.
    pub unloading: Vec<State>,
    /// Jumps on loading (the pull-in).
    pub loading_jumps: Vec<Instability>,
    /// Jumps on unloading (the pull-off).
    pub unloading_jumps: Vec<Instability>,
}

impl Cycle {
    /// Energy lost in the cycle: the area enclosed by the force vs stage-displacement loop,
    /// ∮ P dΔ (shoelace formula over the visited states; clockwise loops count positive).
    pub fn loop_area(&self) -> f64 {
        let pts: Vec<(f64, f64)> = self
            .loading
            .iter()
            .chain(&self.unloading)
            .map(|s| (s.delta, s.force))
            .collect();
        -polygon_area(&pts)
    }
}

/// The non-dimensional machine-stiffness model for one tip shape and stiffness ratio α.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MachineStiffness {
    /// Tip shape.
    pub tip: TipShape,
    /// α = k_s/k̂, the machine stiffness over the contact's characteristic stiffness, (2.35a)/(2.45a).
    pub alpha: f64,
}

/// Accuracy settings of the exact computation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    /// Absolute tolerance on ā of the root finder (Brent).
    pub xtol: f64,
    /// Order of the Gauss-Legendre rule for the hysteresis integral (2.38)/(2.48).
    pub order: usize,
}

impl Default for Accuracy {
    fn default() -> Self {
        Self {
            xtol: 1e-14,
            order: 40,
        }
    }
}

impl MachineStiffness {
    /// The model for a tip shape and α > 0.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless α is positive and finite.
    pub fn new(tip: TipShape, alpha: f64) -> Result<Self> {
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(Error::invalid("alpha", alpha, "must be positive and finite"));
        }
        if let TipShape::SphereExact { radius_ratio } = tip
            && !(radius_ratio.is_finite() && radius_ratio > 1.0)
        {
            return Err(Error::invalid(
                "radius_ratio",
                radius_ratio,
                "R/a_hat must exceed 1 (the contact radius stays below R)",
            ));
        }
        Ok(Self { tip, alpha })
    }

    /// c/α in Δ̄ = (c/α)P̄ + h̄: 4/(3α) for the sphere (2.35a), 1/α for the cone (2.45a).
    pub fn compliance(&self) -> f64 {
        match self.tip {
            TipShape::Sphere | TipShape::SphereExact { .. } => 4.0 / (3.0 * self.alpha),
            TipShape::Cone => 1.0 / self.alpha,
        }
    }

    /// Indentation depth of the stationary point, h̄(ā): Eq. (2.34b) / (2.44b).
    pub fn depth(&self, a: f64) -> f64 {
        match self.tip {
            TipShape::Sphere => a * a - 4.0 / 3.0 * a.sqrt(),
            TipShape::SphereExact { radius_ratio: r } => r * a * (a / r).atanh() - 4.0 / 3.0 * a.sqrt(),
            TipShape::Cone => 0.5 * a - (2.0 * a).sqrt(),
        }
    }

    /// dh̄/dā of Eq. (2.34b) / (2.44b).
    pub fn depth_slope(&self, a: f64) -> f64 {
        match self.tip {
            TipShape::Sphere => 2.0 * a - 2.0 / (3.0 * a.sqrt()),
            TipShape::SphereExact { radius_ratio: r } => {
                r * (a / r).atanh() + a / (1.0 - (a / r).powi(2)) - 2.0 / (3.0 * a.sqrt())
            }
            TipShape::Cone => 0.5 - 1.0 / (2.0 * a).sqrt(),
        }
    }

    /// Contact force P̄(ā, h̄): Eq. (2.35b) / (2.45b).
    pub fn force(&self, a: f64, h: f64) -> f64 {
        match self.tip {
            TipShape::Sphere => 1.5 * a * h - 0.5 * a.powi(3),
            TipShape::SphereExact { radius_ratio: r } => {
                1.5 * a * h - 0.75 * r * (a * a - r * r) * (a / r).atanh() - 0.75 * r * r * a
            }
            TipShape::Cone => 2.0 * a * h - 0.5 * a * a,
        }
    }

    /// Partial derivatives (∂P̄/∂ā, ∂P̄/∂h̄) of Eq. (2.35b) / (2.45b).
    pub fn force_partials(&self, a: f64, h: f64) -> (f64, f64) {
        match self.tip {
            TipShape::Sphere => (1.5 * h - 1.5 * a * a, 1.5 * a),
            TipShape::SphereExact { radius_ratio: r } => (1.5 * h - 1.5 * r * a * (a / r).atanh(), 1.5 * a),
            TipShape::Cone => (2.0 * h - a, 2.0 * a),
        }
    }

    /// Force at the stationary point of radius ā, P̄(ā, h̄(ā)): Eqs. (2.34)-(2.35) / (2.44)-(2.45).
    pub fn branch_force(&self, a: f64) -> f64 {
        self.force(a, self.depth(a))
    }

    /// Stage displacement of the stationary point of radius ā: Eq. (2.35a) / (2.45a).
    pub fn stage_displacement(&self, a: f64) -> f64 {
        self.compliance() * self.branch_force(a) + self.depth(a)
    }

    /// dΔ̄/dā along the branch, from (2.35a) / (2.45a) with the chain rule.
    pub fn stage_slope(&self, a: f64) -> f64 {
        let h = self.depth(a);
        let hp = self.depth_slope(a);
        let (p1, p2) = self.force_partials(a, h);
        self.compliance() * (p1 + p2 * hp) + hp
    }

    /// The stability function ḡ(ā): Eq. (2.36) / (2.46); a stationary point is a solution when
    /// it is positive, (2.24).
    pub fn g(&self, a: f64) -> f64 {
        let spring = 4.0 * a / (2.0 * a + self.alpha);
        match self.tip {
            TipShape::Sphere => 3.0 * a.powf(1.5) - spring - 1.0,
            // (2.23) in the sphere's scales: (3/2)√ā h̄'(ā) − 4ā/(2ā + α).
            TipShape::SphereExact { .. } => 1.5 * a.sqrt() * self.depth_slope(a) - spring,
            TipShape::Cone => (2.0 * a).sqrt() / 2.0 - spring - 1.0,
        }
    }

    /// An ā above which ḡ > 0 for every α (the fold radii lie below it): sphere 3ā^(3/2) > 3,
    /// cone √(2ā)/2 > 3.
    fn fold_bound(&self) -> f64 {
        match self.tip {
            TipShape::Sphere => 1.0,
            // The exact profile is steeper than the paraboloid, so ḡ is larger there; the grid
            // of `folds` (up to 1.001 × this bound) must stay below ā = ρ, where h̄ diverges.
            TipShape::SphereExact { radius_ratio: r } => (r * (1.0 - 1e-12) / 1.001).min(1.0),
            TipShape::Cone => 18.0,
        }
    }

    /// A bracket [lo, hi] of the root of an increasing `f` above `lo`: doubling, or, for the exact
    /// sphere, the whole range below ā = ρ (where the depth diverges).
    fn upward_bracket(&self, f: impl Fn(f64) -> f64, lo: f64) -> Result<(f64, f64)> {
        match self.tip {
            TipShape::SphereExact { radius_ratio: r } => {
                let hi = r * (1.0 - 1e-12);
                if f(hi) < 0.0 {
                    return Err(Error::invalid(
                        "delta",
                        "",
                        "beyond the reach of the sphere (contact radius would exceed R)",
                    ));
                }
                Ok((lo, hi))
            }
            _ => expand_upward(f, lo, lo.max(1.0) * 2.0, 200),
        }
    }

    /// The folds of Δ̄(ā) (roots of ḡ), in increasing order. The largest is the pull-off radius
    /// āₒ, Sec. 2.3.1.
    ///
    /// # Errors
    /// Root-finding failures (not expected).
    pub fn folds(&self, xtol: f64) -> Result<Vec<f64>> {
        let grid = logspace(1e-12, self.fold_bound() * 1.001, 160);
        all_roots(|a| self.g(a), &grid, xtol, 0.0)
    }

    /// The state on the branch at radius ā (interior stationary point), with its stability.
    pub fn state(&self, a: f64) -> State {
        let h = self.depth(a);
        State {
            a,
            h,
            force: self.force(a, h),
            delta: self.compliance() * self.force(a, h) + h,
            stable: self.g(a) > 0.0,
        }
    }

    /// The out-of-contact state (0, Δ̄), a solution for Δ̄ < 0 (appendix A.1.2).
    pub fn free_state(delta: f64) -> State {
        State {
            a: 0.0,
            h: delta,
            force: 0.0,
            delta,
            stable: delta < 0.0,
        }
    }

    /// All interior stationary points at stage displacement Δ̄, in increasing ā, classified by
    /// (2.24): the roots of Δ̄(ā) = Δ̄, Eqs. (2.34)-(2.35) / (2.44)-(2.45). Δ̄(ā) is monotone
    /// between the folds, so each piece holds at most one root, found by Brent's method.
    ///
    /// # Errors
    /// Root-finding failures (not expected for finite Δ̄).
    pub fn stationary_points(&self, delta: f64, xtol: f64) -> Result<Vec<State>> {
        self.stationary_points_between(delta, xtol, &self.folds(xtol)?)
    }

    /// [`Self::stationary_points`] with the folds already found.
    fn stationary_points_between(&self, delta: f64, xtol: f64, folds: &[f64]) -> Result<Vec<State>> {
        if !delta.is_finite() {
            return Err(Error::invalid("delta", delta, "must be finite"));
        }
        let f = |a: f64| self.stage_displacement(a) - delta;
        let mut ends = vec![0.0];
        ends.extend(folds);
        let mut roots = Vec::new();
        for w in ends.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            if f(lo) * f(hi) < 0.0 || (f(hi) == 0.0 && hi > 0.0) {
                roots.push(brent(f, lo, hi, xtol)?);
            }
        }
        // Beyond the last fold Δ̄(ā) grows without bound.
        let last = *ends.last().expect("ends holds 0");
        if f(last) < 0.0 {
            let (lo, hi) = self.upward_bracket(f, last)?;
            roots.push(brent(f, lo, hi, xtol)?);
        }
        Ok(roots
            .into_iter()
            .filter(|&a| a > 0.0)
            .map(|a| self.state(a))
            .collect())
    }

    /// The solution points at Δ̄: the stable stationary points and, for Δ̄ < 0, the
    /// out-of-contact state (0, Δ̄) (appendix A.1), in increasing ā.
    ///
    /// # Errors
    /// As [`Self::stationary_points`].
    pub fn solution_points(&self, delta: f64, xtol: f64) -> Result<Vec<State>> {
        self.solution_points_between(delta, xtol, &self.folds(xtol)?)
    }

    /// [`Self::solution_points`] with the folds already found.
    fn solution_points_between(&self, delta: f64, xtol: f64, folds: &[f64]) -> Result<Vec<State>> {
        let mut out = Vec::new();
        if delta < 0.0 {
            out.push(Self::free_state(delta));
        }
        out.extend(
            self.stationary_points_between(delta, xtol, folds)?
                .into_iter()
                .filter(|s| s.stable),
        );
        Ok(out)
    }

    /// The pull-in at Δ̄ = 0 (Sec. 2.3.1): from the out-of-contact state (0, 0) to the stable
    /// stationary point of smallest radius āᵢ at Δ̄ = 0.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] if there is no stable contact state at Δ̄ = 0 (not expected).
    pub fn pull_in(&self, xtol: f64) -> Result<Instability> {
        self.pull_in_between(xtol, &self.folds(xtol)?)
    }

    /// Both instabilities, (pull-in, pull-off), the folds found once for the two.
    ///
    /// # Errors
    /// As [`Self::pull_in`], [`Self::pull_off`].
    pub fn instabilities(&self, xtol: f64) -> Result<(Instability, Instability)> {
        let folds = self.folds(xtol)?;
        Ok((
            self.pull_in_between(xtol, &folds)?,
            self.pull_off_between(xtol, &folds)?,
        ))
    }

    /// [`Self::pull_in`] with the folds already found.
    fn pull_in_between(&self, xtol: f64, folds: &[f64]) -> Result<Instability> {
        let after = self
            .stationary_points_between(0.0, xtol, folds)?
            .into_iter()
            .find(|s| s.stable)
            .ok_or_else(|| Error::Unresolvable {
                model: "machine stiffness",
                reason: format!(
                    "no stable contact state at zero stage displacement (alpha = {})",
                    self.alpha
                ),
            })?;
        Ok(Instability {
            before: State {
                stable: true,
                ..Self::free_state(0.0)
            },
            after: State { delta: 0.0, ..after },
        })
    }

    /// The pull-off (Sec. 2.3.1): unloading along the stable branch ends at the fold
    /// āₒ = inf{ā : ḡ(ā) > 0 on [ā, ∞)} (the largest root of ḡ) and jumps at Δ̄ₒ = Δ̄(āₒ) to the
    /// nearest solution below: out of contact, (0, Δ̄ₒ), when Δ̄ₒ < 0.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] if ḡ has no root or no solution exists after the jump.
    pub fn pull_off(&self, xtol: f64) -> Result<Instability> {
        self.pull_off_between(xtol, &self.folds(xtol)?)
    }

    /// [`Self::pull_off`] with the folds already found.
    fn pull_off_between(&self, xtol: f64, folds: &[f64]) -> Result<Instability> {
        let &a_o = folds.last().ok_or_else(|| Error::Unresolvable {
            model: "machine stiffness",
            reason: format!("no pull-off fold (alpha = {})", self.alpha),
        })?;
        let before = State {
            stable: true,
            ..self.state(a_o)
        };
        let after = self
            .solution_points_between(before.delta, xtol, folds)?
            .into_iter()
            .rfind(|s| s.a < a_o - 10.0 * xtol)
            .ok_or_else(|| Error::Unresolvable {
                model: "machine stiffness",
                reason: format!("no state to jump to at the pull-off (alpha = {})", self.alpha),
            })?;
        Ok(Instability { before, after })
    }

    /// Hysteretic energy loss of a cycle through both instabilities, by Eq. (2.38) / (2.48)
    /// (with the constant factor and sign of ERRATA.md), integrated by Gauss-Legendre of the given
    /// order, in the chapter's energy units (see the module docs).
    ///
    /// # Errors
    /// As [`Self::pull_in`], [`Self::pull_off`].
    pub fn hysteresis(&self, acc: Accuracy) -> Result<f64> {
        let a_i = self.pull_in(acc.xtol)?.after.a;
        let a_o = self.pull_off(acc.xtol)?.before.a;
        let c = self.compliance();
        let integrand = |a: f64| {
            let h = self.depth(a);
            let hp = self.depth_slope(a);
            let (p1, p2) = self.force_partials(a, h);
            // Eq. (2.38): (c/α) P̄ [P̄,₁ + P̄,₂ h̄' + (α/c) h̄'], c = 4/3 (sphere) or 1 (cone).
            c * self.force(a, h) * (p1 + p2 * hp + hp / c)
        };
        let area = -GaussLegendre::new(acc.order.max(1)).integrate(integrand, a_o, a_i);
        Ok(area * self.energy_factor())
    }

    /// P̂ĥ in the chapter's energy units: (3π/2)(9π/8)^(2/3) for the sphere, 1 for the cone.
    pub fn energy_factor(&self) -> f64 {
        match self.tip {
            TipShape::Sphere | TipShape::SphereExact { .. } => sphere_energy_factor(),
            TipShape::Cone => 1.0,
        }
    }

    /// The displacement-controlled cycle from Δ̄_min (< Δ̄ₒ, out of contact) to Δ̄_max (> 0) and
    /// back, followed with [`crate::numerics::curve::follow`] on two sampled branches: the
    /// out-of-contact states (0, Δ̄) and the contact branch ā ↦ (h̄, P̄, Δ̄) sampled with
    /// `samples` radii, the exact pull-in and pull-off radii among them. The jumps are those the
    /// stability test (2.24) dictates; no jump location is imposed.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a range that does not contain the loop; root-finding
    /// failures.
    pub fn cycle(&self, delta_min: f64, delta_max: f64, samples: usize, xtol: f64) -> Result<Cycle> {
        let pull_off = self.pull_off(xtol)?;
        let pull_in = self.pull_in(xtol)?;
        let (a_o, a_i) = (pull_off.before.a, pull_in.after.a);
        if delta_min.is_nan() || delta_min >= pull_off.before.delta {
            return Err(Error::invalid(
                "delta_min",
                delta_min,
                format!(
                    "must lie below the pull-off stage displacement {}",
                    crate::text::fmt_sig(pull_off.before.delta)
                ),
            ));
        }
        if !(delta_max > 0.0 && delta_max.is_finite()) {
            return Err(Error::invalid(
                "delta_max",
                delta_max,
                "must be positive and finite",
            ));
        }
        let n = samples.max(20);
        let f = |a: f64| self.stage_displacement(a) - delta_max;
        let (lo, hi) = self.upward_bracket(f, a_i)?;
        let a_max = brent(f, lo, hi, xtol)? * 1.000_001;
        // Unstable part: clustered towards ā = 0; stable part: uniform, with āₒ and āᵢ exact.
        let mut radii: Vec<f64> = (1..n / 4)
            .map(|k| a_o * (k as f64 / (n / 4) as f64).powi(2))
            .collect();
        radii.extend(linspace(a_o, a_max, n));
        radii.push(a_i);
        radii.sort_by(f64::total_cmp);
        radii.dedup();
        let contact = Branch {
            control: radii.iter().map(|&a| self.stage_displacement(a)).collect(),
            stable: radii.iter().map(|&a| a >= a_o).collect(),
            state: radii,
        };
        let free_controls = linspace(delta_min, 0.0, n);
        let free = Branch {
            state: vec![0.0; n],
            stable: vec![true; n],
            control: free_controls,
        };
        let branches = [free, contact];
        let to_state = |p: &PathPoint| -> State {
            if p.branch == 0 {
                Self::free_state(p.control)
            } else {
                State {
                    delta: p.control,
                    ..self.state(p.state)
                }
            }
        };
        let start = stable_states_at(&branches, delta_min)
            .into_iter()
            .find(|p| p.branch == 0)
            .ok_or_else(|| Error::invalid("delta_min", delta_min, "no out-of-contact state there"))?;
        let up = follow(&branches, start, delta_max);
        let top = *up.points.last().expect("a path has its start");
        let down = follow(&branches, top, delta_min);
        let jumps = |path: &crate::numerics::curve::Path| -> Vec<Instability> {
            path.jumps
                .iter()
                .map(|j| Instability {
                    before: to_state(&j.from),
                    after: to_state(&j.to),
                })
                .collect()
        };
        Ok(Cycle {
            loading: up.points.iter().map(to_state).collect(),
            unloading: down.points.iter().map(to_state).collect(),
            loading_jumps: jumps(&up),
            unloading_jumps: jumps(&down),
        })
    }

    /// Pull-in force approximation P̄ᵢ*(α): Eq. (2.37a) / (2.47a).
    pub fn pull_in_force_fit(&self) -> f64 {
        let al = self.alpha;
        match self.tip {
            TipShape::Sphere | TipShape::SphereExact { .. } => {
                -8.0 / 9.0 * (1.0 - 1.0 / (1.0 + 0.83 * al.powf(1.12)))
            }
            TipShape::Cone => {
                -32.0 * (1.0 - (-0.12 * al).exp()) * (1.0 + 2.05 * (-0.123 * al.powf(0.665)).exp())
            }
        }
    }

    /// Pull-off force approximation P̄ₒ*(α): Eq. (2.37b) / (2.47b).
    pub fn pull_off_force_fit(&self) -> f64 {
        let al = self.alpha;
        match self.tip {
            TipShape::Sphere | TipShape::SphereExact { .. } => {
                -(5.0 + 4.0 / (1.0 + 0.21 * al.powf(1.32))) / 9.0
            }
            TipShape::Cone => -6.0 - 48.0 / (1.0 + 0.00158 * al.powf(2.285)),
        }
    }

    /// Hysteresis approximation H̄(α): Eq. (2.39) / (2.49).
    pub fn hysteresis_fit(&self) -> f64 {
        let al = self.alpha;
        match self.tip {
            TipShape::Sphere | TipShape::SphereExact { .. } => 7.092 + 7.657 / al.powf(0.99),
            TipShape::Cone => 22.0 + 4383.87 / al.powf(1.4478),
        }
    }

    /// The exact pull-in force, pull-off force and hysteresis at this α (one sweep point).
    ///
    /// # Errors
    /// As [`Self::hysteresis`].
    pub fn sweep_point(&self, acc: Accuracy) -> Result<SweepPoint> {
        Ok(SweepPoint {
            alpha: self.alpha,
            pull_in_force: self.pull_in(acc.xtol)?.after.force,
            pull_off_force: self.pull_off(acc.xtol)?.before.force,
            hysteresis: self.hysteresis(acc)?,
        })
    }
}

/// Exact pull-in, pull-off and hysteresis at one α (Figs. 2.5, 2.7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepPoint {
    /// α.
    pub alpha: f64,
    /// P̄ᵢ.
    pub pull_in_force: f64,
    /// P̄ₒ.
    pub pull_off_force: f64,
    /// H̄ in the chapter's energy units.
    pub hysteresis: f64,
}

/// Tip geometry in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TipGeometry {
    /// Sphere of radius R [m].
    Sphere {
        /// Radius R [m].
        radius: f64,
    },
    /// Cone with profile f(r) = −r tanθ; θ [rad] is the angle between the cone's surface and
    /// the substrate, in (0, π/2), Eq. (2.40).
    Cone {
        /// θ [rad].
        angle: f64,
    },
}

/// The model in SI units: tip, plane-strain modulus ℰ, work of adhesion w, machine stiffness k_s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Experiment {
    /// Tip geometry.
    pub tip: TipGeometry,
    /// Plane-strain modulus ℰ = E/(1-ν²) [Pa].
    pub modulus: f64,
    /// Work of adhesion w [J/m²].
    pub work_of_adhesion: f64,
    /// Machine stiffness k_s [N/m].
    pub spring_constant: f64,
}

/// The scales of the non-dimensional variables, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// â [m].
    pub a: f64,
    /// ĥ [m].
    pub h: f64,
    /// P̂ [N].
    pub force: f64,
    /// k̂ = ℰâ [N/m].
    pub stiffness: f64,
    /// The chapter's energy unit [J]: (R⁴w⁵/ℰ²)^(1/3) (sphere), w³/(πℰ²tan⁴θ) (cone).
    pub energy: f64,
}

fn check_positive(name: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(name, v, "must be positive and finite"))
    }
}

impl Experiment {
    /// Validated SI parameters.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive radius, modulus, work of adhesion or spring
    /// constant, or a cone angle outside (0, π/2).
    pub fn new(tip: TipGeometry, modulus: f64, work_of_adhesion: f64, spring_constant: f64) -> Result<Self> {
        match tip {
            TipGeometry::Sphere { radius } => check_positive("radius", radius)?,
            TipGeometry::Cone { angle } => {
                if !(angle > 0.0 && angle < std::f64::consts::FRAC_PI_2) {
                    return Err(Error::invalid("angle", angle, "must lie in (0, pi/2) rad"));
                }
            }
        }
        check_positive("modulus", modulus)?;
        check_positive("work_of_adhesion", work_of_adhesion)?;
        check_positive("spring_constant", spring_constant)?;
        Ok(Self {
            tip,
            modulus,
            work_of_adhesion,
            spring_constant,
        })
    }

    /// The scales: sphere Sec. 2.3.1 (above (2.34)), cone Sec. 2.3.2 (above (2.44)).
    pub fn scales(&self) -> Scales {
        let (e, w) = (self.modulus, self.work_of_adhesion);
        let pi = std::f64::consts::PI;
        match self.tip {
            TipGeometry::Sphere { radius: r } => {
                let a = (9.0 * pi * w * r * r / (8.0 * e)).cbrt();
                Scales {
                    a,
                    h: a * a / r,
                    force: 1.5 * pi * w * r,
                    stiffness: e * a,
                    energy: (r.powi(4) * w.powi(5) / (e * e)).cbrt(),
                }
            }
            TipGeometry::Cone { angle } => {
                let t = angle.tan();
                let a = w / (pi * e * t * t);
                Scales {
                    a,
                    h: w / (e * t),
                    force: w * w / (pi * e * t.powi(3)),
                    stiffness: e * a,
                    energy: w.powi(3) / (pi * e * e * t.powi(4)),
                }
            }
        }
    }

    /// α = k_s/k̂.
    pub fn alpha(&self) -> f64 {
        self.spring_constant / self.scales().stiffness
    }

    /// The non-dimensional model with the exact spherical profile (2.28) instead of the
    /// paraboloid (2.30): [`TipShape::SphereExact`] with ρ = R/â.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a cone, or R/â ≤ 1.
    pub fn model_exact_sphere(&self) -> Result<MachineStiffness> {
        let TipGeometry::Sphere { radius } = self.tip else {
            return Err(Error::invalid("tip", "cone", "the exact profile is for a sphere"));
        };
        MachineStiffness::new(
            TipShape::SphereExact {
                radius_ratio: radius / self.scales().a,
            },
            self.alpha(),
        )
    }

    /// The non-dimensional model.
    ///
    /// # Errors
    /// Not expected after validation (α is positive).
    pub fn model(&self) -> Result<MachineStiffness> {
        let shape = match self.tip {
            TipGeometry::Sphere { .. } => TipShape::Sphere,
            TipGeometry::Cone { .. } => TipShape::Cone,
        };
        MachineStiffness::new(shape, self.alpha())
    }

    /// A non-dimensional state in SI units.
    pub fn to_si(&self, s: State) -> State {
        let sc = self.scales();
        State {
            a: s.a * sc.a,
            h: s.h * sc.h,
            force: s.force * sc.force,
            delta: s.delta * sc.h,
            stable: s.stable,
        }
    }

    /// An instability in SI units.
    pub fn instability_to_si(&self, i: Instability) -> Instability {
        Instability {
            before: self.to_si(i.before),
            after: self.to_si(i.after),
        }
    }

    /// Pull-in in SI units (Sec. 2.3).
    ///
    /// # Errors
    /// As [`MachineStiffness::pull_in`].
    pub fn pull_in(&self) -> Result<Instability> {
        Ok(self.instability_to_si(self.model()?.pull_in(1e-14)?))
    }

    /// Pull-off in SI units (Sec. 2.3).
    ///
    /// # Errors
    /// As [`MachineStiffness::pull_off`].
    pub fn pull_off(&self) -> Result<Instability> {
        Ok(self.instability_to_si(self.model()?.pull_off(1e-14)?))
    }

    /// Pull-in and pull-off in SI units, the folds found once for both.
    ///
    /// # Errors
    /// As [`MachineStiffness::instabilities`].
    pub fn instabilities(&self) -> Result<(Instability, Instability)> {
        let (i, o) = self.model()?.instabilities(1e-14)?;
        Ok((self.instability_to_si(i), self.instability_to_si(o)))
    }

    /// Hysteretic energy loss [J], Eq. (2.38) / (2.48).
    ///
    /// # Errors
    /// As [`MachineStiffness::hysteresis`].
    pub fn hysteresis(&self) -> Result<f64> {
        Ok(self.model()?.hysteresis(Accuracy::default())? * self.scales().energy)
    }

    /// Contact force [N] of the stable contact branch at indentation depth h [m], the relation
    /// (2.31b)-(2.32b) (the JKR relation (1.2)) inverted on ā ≥ ā_D, where h̄(ā) increases.
    /// Depths below the branch's minimum h̄(ā_D) give the force at ā_D. Sphere only.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a cone tip.
    pub fn force_at_depth(&self, h: f64) -> Result<f64> {
        let TipGeometry::Sphere { .. } = self.tip else {
            return Err(Error::invalid(
                "tip",
                "cone",
                "force_at_depth is implemented for the sphere",
            ));
        };
        let sc = self.scales();
        let a = sphere_radius_at_depth(h / sc.h);
        Ok(sc.force * (a.powi(3) - 2.0 * a.powf(1.5)))
    }
}

/// ā_D = (1/3)^(2/3): the minimum of the sphere's h̄(ā) of (2.34b) (the JKR pull-off in depth control).
pub fn sphere_depth_minimum_radius() -> f64 {
    (1.0f64 / 3.0).powf(2.0 / 3.0)
}

/// The radius ā ≥ ā_D at which the sphere's h̄(ā) = ā² − (4/3)√ā of (2.34b) equals `h`; ā_D when
/// `h` is below the minimum. Newton's method on s = √ā from an upper starting point (h̄ is convex
/// in s there, so the iteration decreases monotonically to the root).
pub fn sphere_radius_at_depth(h: f64) -> f64 {
    let s_d = sphere_depth_minimum_radius().sqrt();
    let hs = |s: f64| s.powi(4) - 4.0 / 3.0 * s;
    if h.is_nan() || h <= hs(s_d) {
        return sphere_depth_minimum_radius();
    }
    // Start above the root: at s = (h + 2)^(1/4) + 0.5, s⁴ − (4/3)s exceeds h.
    let mut s = (h.max(0.0) + 2.0).powf(0.25).max(s_d) + 0.5;
    for _ in 0..100 {
        let f = hs(s) - h;
        let d = 4.0 * s.powi(3) - 4.0 / 3.0;
        let step = f / d;
        s -= step;
        if s < s_d {
            s = s_d;
        }
        if step.abs() <= 1e-15 * s {
            break;
        }
    }
    s * s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn g_is_a_positive_multiple_of_the_stage_slope() {
        let exact = TipShape::SphereExact { radius_ratio: 35.0 };
        for tip in [TipShape::Sphere, TipShape::Cone, exact] {
            for alpha in [1e-2, 0.3, 1.0, 7.0, 1e3] {
                let m = MachineStiffness::new(tip, alpha).unwrap();
                for a in logspace(1e-3, 30.0, 50) {
                    let (g, d) = (m.g(a), m.stage_slope(a));
                    assert_eq!(g > 0.0, d > 0.0, "{tip:?} alpha {alpha} a {a}: g {g}, dD {d}");
                }
            }
        }
    }

    #[test]
    fn radius_at_depth_inverts_the_branch() {
        for a in [0.5, 0.8, 1.0, 2.0, 10.0] {
            let h = a * a - 4.0 / 3.0 * f64::sqrt(a);
            assert!((sphere_radius_at_depth(h) - a).abs() < 1e-12 * a, "{a}");
        }
        assert_eq!(sphere_radius_at_depth(-5.0), sphere_depth_minimum_radius());
    }
}
