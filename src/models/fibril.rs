//! Fibril mechanics of chapter 5 (sections 5.3-5.4): tilted-fibril and seta-branch stiffness,
//! the Lennard-Jones fibril-substrate energy and the single-spring model, Eqs. (5.8)-(5.20).
//!
//! The single-spring model works in the variables of (5.16): gap d̄ = d/σ, displacement
//! ū = u/σ, stiffness k̄ = k_e σ²/(c w A_e), force P̄ = P σ/(c w A_e), energy Π̄ = Π/(c w A_e).
//!
//! Sign of the force: the dissertation's (5.19) writes P̄ = k̄(ū − d̄), which is positive in
//! tension, while section 5.5.2 and its figures call compression positive. The workbench
//! reports the contact force positive in compression, P̄ = k̄(d̄ − ū) = −g(d̄) at equilibrium,
//! with g of [`lj_traction`]; a tensile (adhesive) force is negative, as in Figs. 5.7-5.10.

use crate::error::{Error, Result};
use crate::numerics::roots::brent;

/// c = 16 (2/15)^(1/3) ≈ 8.174 of Eq. (5.14).
pub fn c_lj() -> f64 {
    16.0 * (2.0f64 / 15.0).cbrt()
}

/// Critical non-dimensional stiffness k̄_cr = 0.3 (section 5.4.3): the maximum over d̄ of
/// d̄⁻⁴/2 − d̄⁻¹⁰/5 in (5.20), reached at d̄ = 1.
pub const K_CR_BAR: f64 = 0.3;

/// Equilibrium separation of two LJ half-spaces relative to σ, Z₀/σ = (2/15)^(1/6) (section 5.3).
pub fn z0_over_sigma() -> f64 {
    (2.0f64 / 15.0).powf(1.0 / 6.0)
}

/// Dupré work of adhesion of two LJ half-spaces, Eq. (5.8): w = A/(16π Z₀²).
///
/// `hamaker` A [J], `z0` equilibrium distance Z₀ [m]; returns w [J/m²].
pub fn work_of_adhesion(hamaker: f64, z0: f64) -> f64 {
    hamaker / (16.0 * std::f64::consts::PI * z0 * z0)
}

/// Stiffness of a tilted fibril, Eq. (5.11):
///
/// ```text
/// k_f = π R_f² E / ( l_f sin²θ (1 + 4 l_f² cot²θ / (3 R_f²)) )
/// ```
///
/// `young` E [Pa], `radius` R_f [m], `length` l_f [m], `theta` θ [rad] between the fibril and
/// its backing; θ = π/2 is pure axial compression (stiffest), θ → 0 pure bending. Returns
/// k_f [N/m]. Written as F/δ from (5.10) so that θ = 0 (pure bending, 3EI/l³) is finite.
///
/// # Errors
/// [`Error::InvalidParameter`] for non-positive E, R_f, l_f or θ outside [0, π/2].
pub fn tilted_fibril_stiffness(young: f64, radius: f64, length: f64, theta: f64) -> Result<f64> {
    for (name, v) in [("young", young), ("radius", radius), ("length", length)] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(Error::invalid(name, v, "must be positive"));
        }
    }
    // Allow a rounding error above π/2 (grids computed as π/2 · i/n).
    if !(0.0..=std::f64::consts::FRAC_PI_2 * (1.0 + 1e-12)).contains(&theta) {
        return Err(Error::invalid("theta", theta, "must lie in [0, π/2]"));
    }
    let area = std::f64::consts::PI * radius * radius;
    let inertia = std::f64::consts::PI * radius.powi(4) / 4.0;
    // (5.10): δ/F = cos²θ l³/(3EI) + sin²θ l/(EA).
    let compliance = theta.cos().powi(2) * length.powi(3) / (3.0 * young * inertia)
        + theta.sin().powi(2) * length / (young * area);
    Ok(1.0 / compliance)
}

/// Effective stiffness of the seta-branch system, Eq. (5.13):
/// k_e = (n_br/k_st + 1/k_br)⁻¹, as printed (the seta in series with one branch, the seta's
/// compliance shared by the n_br branches it carries).
///
/// # Errors
/// [`Error::InvalidParameter`] for non-positive stiffness or zero branches.
pub fn equivalent_stiffness(k_seta: f64, k_branch: f64, n_branches: usize) -> Result<f64> {
    if k_seta.is_nan() || k_seta <= 0.0 {
        return Err(Error::invalid("k_seta", k_seta, "must be positive"));
    }
    if k_branch.is_nan() || k_branch <= 0.0 {
        return Err(Error::invalid("k_branch", k_branch, "must be positive"));
    }
    if n_branches == 0 {
        return Err(Error::invalid("n_branches", 0, "must be at least 1"));
    }
    Ok(1.0 / (n_branches as f64 / k_seta + 1.0 / k_branch))
}

/// Critical stiffness in SI units, section 5.5.2 with the erratum of ERRATA.md:
/// k_cr = 0.3 c w π R_e² / σ².
///
/// `w` [J/m²], `radius` R_e [m], `sigma` σ [m]; returns [N/m].
pub fn critical_stiffness(w: f64, radius: f64, sigma: f64) -> f64 {
    K_CR_BAR * c_lj() * w * std::f64::consts::PI * radius * radius / (sigma * sigma)
}

/// Non-dimensional LJ energy per unit area, Eqs. (5.14), (5.27): f(d̄) = −d̄⁻²/12 + d̄⁻⁸/360.
pub fn lj_energy(d: f64) -> f64 {
    let d2 = 1.0 / (d * d);
    -d2 / 12.0 + d2.powi(4) / 360.0
}

/// Attractive LJ traction, the derivative of (5.27): g(d̄) = f′(d̄) = d̄⁻³/6 − d̄⁻⁹/45
/// (the terms of (5.18); positive = attraction towards the substrate).
pub fn lj_traction(d: f64) -> f64 {
    let i = 1.0 / d;
    let i3 = i * i * i;
    i3 / 6.0 - i3 * i3 * i3 / 45.0
}

/// Second derivative of (5.27): f″(d̄) = −d̄⁻⁴/2 + d̄⁻¹⁰/5 (the LJ part of (5.20)).
pub fn lj_curvature(d: f64) -> f64 {
    let i2 = 1.0 / (d * d);
    let i4 = i2 * i2;
    -i4 / 2.0 + i4 * i4 * i2 / 5.0
}

/// Gap d̄ where the attraction g(d̄) is largest (f″ = 0): d̄ = (2/5)^(1/6).
pub fn max_traction_gap() -> f64 {
    0.4f64.powf(1.0 / 6.0)
}

/// Which stable branch of the single spring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpringBranch {
    /// In contact: the small-gap branch, d̄ below the pull-off gap.
    Contact,
    /// Out of contact: the large-gap branch, d̄ above the pull-in gap.
    Free,
}

/// An equilibrium of the single spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringState {
    /// Displacement ū.
    pub u: f64,
    /// Gap d̄.
    pub d: f64,
    /// Contact force P̄, positive in compression.
    pub force: f64,
    /// Whether ∂²Π̄/∂d̄² > 0, Eq. (5.20).
    pub stable: bool,
}

/// An instability of the single spring: the state where stability is lost and the state it
/// jumps to at the same displacement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringJump {
    /// State before the jump (a fold: ∂²Π̄/∂d̄² = 0).
    pub before: SpringState,
    /// Stable state after the jump.
    pub after: SpringState,
    /// Energy released, Π̄(before) − Π̄(after) ≥ 0.
    pub energy_released: f64,
}

/// The single-spring model of Eqs. (5.15)-(5.20) at non-dimensional stiffness k̄.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleSpring {
    k: f64,
    /// (pull-off gap, pull-in gap) when k̄ < k̄_cr.
    folds: Option<(f64, f64)>,
}

impl SingleSpring {
    /// The model at k̄ = k_e σ²/(c w A_e).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if k̄ is not positive and finite.
    pub fn new(k_bar: f64) -> Result<Self> {
        if !(k_bar > 0.0 && k_bar.is_finite()) {
            return Err(Error::invalid("stiffness", k_bar, "must be positive"));
        }
        let folds = if k_bar < K_CR_BAR {
            // Roots of k̄ + f″(d̄) = 0 on either side of the maximum of −f″ at d̄ = 1.
            let h = |d: f64| k_bar + lj_curvature(d);
            let lo = brent(h, 0.5, 1.0, 1e-15)?;
            // −f″ < d̄⁻⁴/2, so k̄ + f″ > 0 beyond (1/(2k̄))^(1/4).
            let hi = brent(h, 1.0, (0.5 / k_bar).powf(0.25) + 1.0, 1e-15)?;
            Some((lo, hi))
        } else {
            None
        };
        Ok(Self { k: k_bar, folds })
    }

    /// The stiffness k̄.
    pub fn stiffness(&self) -> f64 {
        self.k
    }

    /// Whether the spring has instabilities (k̄ < k̄_cr = 0.3).
    pub fn has_instabilities(&self) -> bool {
        self.folds.is_some()
    }

    /// Total energy, Eq. (5.16): Π̄ = k̄(ū − d̄)²/2 − d̄⁻²/12 + d̄⁻⁸/360.
    pub fn energy(&self, u: f64, d: f64) -> f64 {
        0.5 * self.k * (u - d).powi(2) + lj_energy(d)
    }

    /// ∂Π̄/∂d̄, the left side of Eq. (5.18): −k̄(ū − d̄) + g(d̄).
    pub fn residual(&self, u: f64, d: f64) -> f64 {
        -self.k * (u - d) + lj_traction(d)
    }

    /// ∂²Π̄/∂d̄², Eq. (5.20): k̄ − d̄⁻⁴/2 + d̄⁻¹⁰/5.
    pub fn curvature(&self, d: f64) -> f64 {
        self.k + lj_curvature(d)
    }

    /// Displacement at which the gap d̄ is an equilibrium, Eq. (5.18) solved for ū:
    /// ū = d̄ + g(d̄)/k̄.
    pub fn displacement_at_gap(&self, d: f64) -> f64 {
        d + lj_traction(d) / self.k
    }

    /// Equilibrium state at gap d̄ (force by (5.19), positive in compression; stability by (5.20)).
    pub fn state_at_gap(&self, d: f64) -> SpringState {
        SpringState {
            u: self.displacement_at_gap(d),
            d,
            force: -lj_traction(d),
            stable: self.curvature(d) > 0.0,
        }
    }

    /// Gaps of the folds (pull-off, pull-in), where (5.20) vanishes; `None` if k̄ ≥ k̄_cr.
    pub fn fold_gaps(&self) -> Option<(f64, f64)> {
        self.folds
    }

    /// Range of ū over which the two stable branches coexist: (pull-in ū, pull-off ū).
    pub fn bistable_range(&self) -> Option<(f64, f64)> {
        self.folds
            .map(|(off, inn)| (self.displacement_at_gap(inn), self.displacement_at_gap(off)))
    }

    /// The stable equilibrium gap on `branch` at displacement ū, by Brent's method on (5.18).
    /// Without instabilities both branches are the single stable branch.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] when ū lies outside the branch's range (beyond its fold).
    pub fn gap(&self, u: f64, branch: SpringBranch) -> Result<f64> {
        let f = |d: f64| self.displacement_at_gap(d) - u;
        let (lo, hi) = match (self.folds, branch) {
            (None, _) => (self.lower_bracket(u, 1.0), u.max(1.0) + 1.0),
            (Some((off, _)), SpringBranch::Contact) => {
                if f(off) < 0.0 {
                    return Err(self.beyond_fold(u, "pull-off"));
                }
                (self.lower_bracket(u, off), off)
            }
            (Some((_, inn)), SpringBranch::Free) => {
                if f(inn) > 0.0 {
                    return Err(self.beyond_fold(u, "pull-in"));
                }
                (inn, u.max(inn) + 1.0)
            }
        };
        brent(f, lo, hi, 1e-14)
    }

    /// Stable state on `branch` at ū.
    ///
    /// # Errors
    /// As [`Self::gap`].
    pub fn state(&self, u: f64, branch: SpringBranch) -> Result<SpringState> {
        let d = self.gap(u, branch)?;
        Ok(SpringState {
            u,
            ..self.state_at_gap(d)
        })
    }

    /// A gap below the contact-branch solution at ū: ū(d̄) → −∞ as d̄ → 0.
    fn lower_bracket(&self, u: f64, start: f64) -> f64 {
        let mut d = start;
        while self.displacement_at_gap(d) > u && d > 1e-3 {
            d *= 0.8;
        }
        d
    }

    fn beyond_fold(&self, u: f64, which: &str) -> Error {
        Error::Unresolvable {
            model: "single spring",
            reason: format!(
                "displacement {u} is beyond the {which} fold at stiffness {}",
                self.k
            ),
        }
    }

    /// Pull-in instability on approach (section 5.4.3): the free branch ends at its fold
    /// (larger root of (5.20) = 0) and the spring jumps into contact at the same ū.
    /// `None` if k̄ ≥ k̄_cr.
    ///
    /// # Errors
    /// Root-finding failures (not expected).
    pub fn pull_in(&self) -> Result<Option<SpringJump>> {
        let Some((_, inn)) = self.folds else {
            return Ok(None);
        };
        let before = self.state_at_gap(inn);
        let after = self.state(before.u, SpringBranch::Contact)?;
        Ok(Some(self.jump(before, after)))
    }

    /// Pull-off instability on retraction (section 5.4.3): the contact branch ends at its fold
    /// (smaller root of (5.20) = 0) and the spring jumps out of contact. `None` if k̄ ≥ k̄_cr.
    ///
    /// # Errors
    /// Root-finding failures (not expected).
    pub fn pull_off(&self) -> Result<Option<SpringJump>> {
        let Some((off, _)) = self.folds else {
            return Ok(None);
        };
        let before = self.state_at_gap(off);
        let after = self.state(before.u, SpringBranch::Free)?;
        Ok(Some(self.jump(before, after)))
    }

    fn jump(&self, before: SpringState, after: SpringState) -> SpringJump {
        SpringJump {
            before,
            after,
            energy_released: self.energy(before.u, before.d) - self.energy(after.u, after.d),
        }
    }

    /// Hysteretic energy loss of a cycle that reaches past both folds, ΔĒ_s of Fig. 5.5b: the
    /// energy released at the pull-in and pull-off jumps (zero for k̄ ≥ k̄_cr).
    ///
    /// # Errors
    /// Root-finding failures (not expected).
    pub fn hysteresis(&self) -> Result<f64> {
        let a = self.pull_in()?.map_or(0.0, |j| j.energy_released);
        let b = self.pull_off()?.map_or(0.0, |j| j.energy_released);
        Ok(a + b)
    }

    /// Stable branch the spring is on at ū after a history: on loading (ū decreasing) it is in
    /// contact once ū has passed the pull-in displacement; on unloading it stays in contact
    /// until the pull-off displacement.
    pub fn branch_on(&self, u: f64, loading: bool, touched: bool) -> SpringBranch {
        match self.bistable_range() {
            None => SpringBranch::Contact,
            Some((u_in, u_off)) => {
                let in_contact = if loading { u <= u_in } else { touched && u < u_off };
                if in_contact {
                    SpringBranch::Contact
                } else {
                    SpringBranch::Free
                }
            }
        }
    }

    /// A displacement-controlled loading-unloading cycle: ū from `u_max` down to `u_min` and
    /// back, `n` equally spaced values per phase, following the stable branch an experiment
    /// follows (Fig. 5.4), with the jumps that occur.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `u_min ≥ u_max` or `n < 2`.
    pub fn cycle(&self, u_max: f64, u_min: f64, n: usize) -> Result<SpringCycle> {
        if u_min.is_nan() || u_max.is_nan() || u_min >= u_max {
            return Err(Error::invalid("u_min", u_min, "must be below u_max"));
        }
        if n < 2 {
            return Err(Error::invalid("points", n, "must be at least 2"));
        }
        let mut out = SpringCycle::default();
        let grid = crate::numerics::curve::linspace(u_max, u_min, n);
        let range = self.bistable_range();
        let touched = range.is_none_or(|(u_in, _)| u_min <= u_in);
        for &u in &grid {
            let b = self.branch_on(u, true, touched);
            out.loading.push(self.state(u, b)?);
        }
        if let (Some(j), Some((u_in, _))) = (self.pull_in()?, range)
            && u_min <= u_in
            && u_in <= u_max
        {
            out.jumps.push(j);
        }
        for &u in grid.iter().rev() {
            let b = self.branch_on(u, false, touched);
            out.unloading.push(self.state(u, b)?);
        }
        if let (Some(j), Some((u_in, u_off))) = (self.pull_off()?, range)
            && u_min <= u_in
            && u_off <= u_max
        {
            out.jumps.push(j);
        }
        Ok(out)
    }
}

/// A loading-unloading cycle of the single spring.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpringCycle {
    /// States on approach, ū decreasing.
    pub loading: Vec<SpringState>,
    /// States on retraction, ū increasing.
    pub unloading: Vec<SpringState>,
    /// Pull-in and pull-off jumps that occurred, in order.
    pub jumps: Vec<SpringJump>,
}

impl SpringCycle {
    /// Energy dissipated over the cycle as the area of the force-displacement loop,
    /// −∮ P̄ dū: the work the driver does on approach minus what it recovers on retraction,
    /// by the trapezoid rule on the sampled curves with the jumps inserted as vertical edges.
    pub fn loop_area(&self) -> f64 {
        // Force along each phase as a function of ū, with the jump as a vertical segment.
        let mut load: Vec<(f64, f64)> = Vec::new();
        let mut prev: Option<SpringState> = None;
        for s in &self.loading {
            if let Some(p) = prev
                && let Some(j) = self
                    .jumps
                    .iter()
                    .find(|j| j.before.d > j.after.d && j.before.u <= p.u && j.before.u >= s.u)
            {
                load.push((j.before.u, j.before.force));
                load.push((j.after.u, j.after.force));
            }
            load.push((s.u, s.force));
            prev = Some(*s);
        }
        let mut unload: Vec<(f64, f64)> = Vec::new();
        prev = None;
        for s in &self.unloading {
            if let Some(p) = prev
                && let Some(j) = self
                    .jumps
                    .iter()
                    .find(|j| j.before.d < j.after.d && j.before.u >= p.u && j.before.u <= s.u)
            {
                unload.push((j.before.u, j.before.force));
                unload.push((j.after.u, j.after.force));
            }
            unload.push((s.u, s.force));
            prev = Some(*s);
        }
        // Work the driver does on the spring: dW = ∂Π̄/∂ū dū = k̄(ū − d̄) dū = −P̄ dū. Loading
        // runs ū downwards, unloading upwards: the sum over both phases is the loop integral.
        -(crate::numerics::quadrature::trapezoid(&load) + crate::numerics::quadrature::trapezoid(&unload))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        for d in [0.7, 0.9, 1.3, 2.5] {
            let h = 1e-6;
            let fd = (lj_energy(d + h) - lj_energy(d - h)) / (2.0 * h);
            assert!((fd - lj_traction(d)).abs() < 1e-8);
            let fd2 = (lj_traction(d + h) - lj_traction(d - h)) / (2.0 * h);
            assert!((fd2 - lj_curvature(d)).abs() < 1e-7);
        }
    }

    #[test]
    fn traction_vanishes_at_the_equilibrium_separation() {
        assert!(lj_traction(z0_over_sigma()).abs() < 1e-14);
    }
}
