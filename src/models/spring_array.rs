//! The multiple-spring model of section 5.5: an N x M array of springs of stiffness k_e above a
//! rigid rough substrate, each interacting with it through the LJ energy (5.26)-(5.27) and, when
//! k_μ > 0, with its four neighbours through coupling springs (5.24).
//!
//! Variables are those of the single-spring model (5.16): lengths in σ, stiffnesses in
//! c w A_e/σ², forces in c w A_e/σ, energies in c w A_e. The surface heights z̄_i = z_i/σ are
//! given as a slice in row-major order, spring i = ix + N·iy.
//!
//! Two paths compute a loading-unloading cycle:
//! - uncoupled (k_μ = 0): each spring's state depends only on ū − z̄_i and its history, so the
//!   array's force is a sum of the single-spring loading and unloading branches shifted by the
//!   heights ([`uncoupled_cycle`] exactly, spring by spring; [`uncoupled_cycle_binned`] by
//!   binning the heights on a grid aligned with the displacement steps, a discrete
//!   convolution whose cost does not grow with the number of springs);
//! - coupled (k_μ ≥ 0): the equilibrium equations (5.31)-(5.34) solved at every displacement
//!   step by [`crate::numerics::newton::StableNewton`], which follows the metastable state and
//!   never accepts an unstable one ([`coupled_cycle`]).
//!
//! Force convention: positive in compression (section 5.5.2), P̄ = Σ k̄_e(d̄_i − (ū − z̄_i)), the
//! negative of (5.35) written with the heights; since the heights have zero mean the two differ
//! only in sign. A spring counts as in contact when its gap is below σ (d̄_i < 1): every
//! contact-branch gap lies below it and every free-branch gap above it.

use crate::error::{Error, Result};
use crate::models::fibril::{
    SingleSpring, SpringBranch, lj_curvature, lj_energy, lj_traction, max_traction_gap,
};
use crate::numerics::curve::linspace;
use crate::numerics::loading::{Controlled, PathOptions, follow};
use crate::numerics::newton::{Energy, NewtonOptions, StableNewton};

/// Gap below which a spring counts as in contact (units of σ).
pub const CONTACT_GAP: f64 = 1.0;

/// An N x M spring array over a rough surface.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringArray {
    nx: usize,
    ny: usize,
    k_e: f64,
    k_mu: f64,
    heights: Vec<f64>,
}

impl SpringArray {
    /// An array of `nx` x `ny` springs (N along ê₁, M along ê₂) with stiffness k̄_e, coupling
    /// k̄_μ and surface heights z̄ (row-major, length N·M).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a wrong number of heights, non-positive k̄_e, negative
    /// k̄_μ or non-finite heights.
    pub fn new(nx: usize, ny: usize, k_e: f64, k_mu: f64, heights: Vec<f64>) -> Result<Self> {
        if nx == 0 || ny == 0 || heights.len() != nx * ny {
            return Err(Error::invalid(
                "heights",
                heights.len(),
                format!("must hold N x M = {} values", nx * ny),
            ));
        }
        if !(k_e > 0.0 && k_e.is_finite()) {
            return Err(Error::invalid("k_e", k_e, "must be positive"));
        }
        if !(k_mu >= 0.0 && k_mu.is_finite()) {
            return Err(Error::invalid("k_mu", k_mu, "must not be negative"));
        }
        if heights.iter().any(|z| !z.is_finite()) {
            return Err(Error::invalid("heights", "NaN", "must be finite"));
        }
        Ok(Self {
            nx,
            ny,
            k_e,
            k_mu,
            heights,
        })
    }

    /// Number of springs N·M.
    pub fn len(&self) -> usize {
        self.heights.len()
    }

    /// Whether the array is empty (never: the constructor requires N, M ≥ 1).
    pub fn is_empty(&self) -> bool {
        self.heights.is_empty()
    }

    /// Heights z̄_i.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The single spring of stiffness k̄_e.
    ///
    /// # Errors
    /// Not expected (k̄_e was validated).
    pub fn single(&self) -> Result<SingleSpring> {
        SingleSpring::new(self.k_e)
    }

    /// Calls `f(i, j)` for every neighbour pair i < j, the coupling springs of (5.24): first
    /// the pairs along ê₁ row by row, then those along ê₂; the order of the Hessian pattern.
    fn for_each_edge(&self, mut f: impl FnMut(usize, usize)) {
        let (nx, ny) = (self.nx, self.ny);
        for iy in 0..ny {
            let row = nx * iy;
            for i in row..row + nx - 1 {
                f(i, i + 1);
            }
        }
        for i in 0..nx * (ny - 1) {
            f(i, i + nx);
        }
    }

    /// The (up to four) neighbours of spring i.
    fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> {
        let (nx, ny) = (self.nx, self.ny);
        let (ix, iy) = (i % nx, i / nx);
        [
            (ix > 0).then(|| i - 1),
            (ix + 1 < nx).then(|| i + 1),
            (iy > 0).then(|| i - nx),
            (iy + 1 < ny).then(|| i + nx),
        ]
        .into_iter()
        .flatten()
    }

    /// Total contact force P̄ at displacement ū with gaps d̄ (positive in compression), the
    /// negative of Eq. (5.35) with the heights included.
    pub fn force(&self, u: f64, d: &[f64]) -> f64 {
        self.heights
            .iter()
            .zip(d)
            .map(|(z, di)| self.k_e * (di - (u - z)))
            .sum()
    }

    /// Fraction of springs in contact (d̄_i < 1), the contact ratio of Fig. 5.11.
    pub fn contact_ratio(d: &[f64]) -> f64 {
        d.iter().filter(|&&x| x < CONTACT_GAP).count() as f64 / d.len() as f64
    }

    /// The total energy (5.29) at displacement ū as an [`Energy`] of the gaps.
    pub fn energy_at(&self, u: f64) -> ArrayEnergy<'_> {
        ArrayEnergy { array: self, u }
    }
}

/// The total energy (5.23)-(5.29) of a [`SpringArray`] at fixed displacement ū, a function of
/// the gaps d̄; its gradient is (5.31) and its Hessian the matrix 𝒜 of (5.33)-(5.34).
pub struct ArrayEnergy<'a> {
    array: &'a SpringArray,
    u: f64,
}

impl Energy for ArrayEnergy<'_> {
    fn dim(&self) -> usize {
        self.array.len()
    }

    /// Eq. (5.29): Σ k̄_e(ū − z̄_i − d̄_i)²/2 + Σ_edges k̄_μ(z̄_j + d̄_j − z̄_i − d̄_i)²/2 + Σ f(d̄_i).
    fn energy(&self, d: &[f64]) -> f64 {
        let a = self.array;
        let mut e = 0.0;
        for (z, &di) in a.heights.iter().zip(d) {
            if di <= 0.0 || di.is_nan() {
                return f64::INFINITY;
            }
            let r = self.u - z - di;
            e += 0.5 * a.k_e * r * r + lj_energy(di);
        }
        if a.k_mu > 0.0 {
            let mut c = 0.0;
            a.for_each_edge(|i, j| {
                let s = a.heights[j] + d[j] - a.heights[i] - d[i];
                c += s * s;
            });
            e += 0.5 * a.k_mu * c;
        }
        e
    }

    /// Eq. (5.31): −k̄_e(ū − z̄_i − d̄_i) + f′(d̄_i) + coupling terms.
    fn gradient(&self, d: &[f64], g: &mut [f64]) {
        let a = self.array;
        for ((gi, z), &di) in g.iter_mut().zip(&a.heights).zip(d) {
            *gi = -a.k_e * (self.u - z - di) + lj_traction(di);
        }
        if a.k_mu > 0.0 {
            a.for_each_edge(|i, j| {
                let s = a.k_mu * (a.heights[j] + d[j] - a.heights[i] - d[i]);
                g[i] -= s;
                g[j] += s;
            });
        }
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let a = self.array;
        let mut p: Vec<(usize, usize)> = (0..a.len()).map(|i| (i, i)).collect();
        if a.k_mu > 0.0 {
            a.for_each_edge(|i, j| p.push((j, i)));
        }
        p
    }

    /// Eq. (5.29) as a function of d̄_i alone, the neighbours held: the spring's own terms and
    /// its (up to four) coupling springs; slope and curvature are row i of (5.31) and (5.33).
    fn along_coordinate(&self, d: &[f64], i: usize, s: f64) -> Option<(f64, f64, f64)> {
        let a = self.array;
        if s <= 0.0 || s.is_nan() {
            return Some((f64::INFINITY, 0.0, 0.0));
        }
        let z = a.heights[i];
        let r = self.u - z - s;
        let (mut e, mut de, mut d2) = (
            0.5 * a.k_e * r * r + lj_energy(s),
            -a.k_e * r + lj_traction(s),
            a.k_e + lj_curvature(s),
        );
        if a.k_mu > 0.0 {
            for j in a.neighbours(i) {
                let t = a.heights[j] + d[j] - z - s;
                e += 0.5 * a.k_mu * t * t;
                de -= a.k_mu * t;
                d2 += a.k_mu;
            }
        }
        Some((e, de, d2))
    }

    /// The terms of Eq. (5.29) that involve any spring of `set`: their own terms and every
    /// coupling spring with at least one end in `set` (once), with the gradient (5.31) of those
    /// springs.
    fn local_energy(&self, d: &[f64], set: &[usize], grad: &mut [f64]) -> Option<f64> {
        let a = self.array;
        let mut e = 0.0;
        // The first member of `set` at or beyond i − nx (it only moves forward as i grows).
        let mut row_below = 0;
        for (k, (gi, &i)) in grad.iter_mut().zip(set).enumerate() {
            let di = d[i];
            if di <= 0.0 || di.is_nan() {
                return Some(f64::INFINITY);
            }
            let r = self.u - a.heights[i] - di;
            e += 0.5 * a.k_e * r * r + lj_energy(di);
            *gi = -a.k_e * r + lj_traction(di);
            if a.k_mu > 0.0 {
                while i >= a.nx && set[row_below] < i - a.nx {
                    row_below += 1;
                }
                for j in a.neighbours(i) {
                    let t = a.heights[j] + d[j] - a.heights[i] - di;
                    *gi -= a.k_mu * t;
                    // A pair inside the set is counted from its lower end only: a neighbour
                    // below i (i − 1 or i − nx) is in the set when it is the member before i,
                    // or the member `row_below` points at.
                    let below_in_set = j < i && (set[k.saturating_sub(1)] == j || set[row_below] == j);
                    if !below_in_set {
                        e += 0.5 * a.k_mu * t * t;
                    }
                }
            }
        }
        Some(e)
    }

    /// Eqs. (5.33)-(5.34): K + f″(d̄_i) δ_ij, K with k̄_e + (number of neighbours) k̄_μ on the
    /// diagonal and −k̄_μ for each neighbour pair.
    fn hessian_values(&self, d: &[f64], v: &mut [f64]) {
        let a = self.array;
        let n = a.len();
        for (vi, &di) in v[..n].iter_mut().zip(d) {
            *vi = a.k_e + lj_curvature(di);
        }
        if a.k_mu > 0.0 {
            let mut k = n;
            a.for_each_edge(|i, j| {
                v[i] += a.k_mu;
                v[j] += a.k_mu;
                v[k] = -a.k_mu;
                k += 1;
            });
        }
    }
}

impl Controlled for SpringArray {
    type At<'a> = ArrayEnergy<'a>;

    fn at(&self, lambda: f64) -> ArrayEnergy<'_> {
        self.energy_at(lambda)
    }

    /// 1 when any spring changed contact state (gap across [`CONTACT_GAP`]), else 0.
    fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
        let changed = before
            .iter()
            .zip(after)
            .any(|(b, a)| (*b < CONTACT_GAP) != (*a < CONTACT_GAP));
        f64::from(u8::from(changed))
    }
}

/// One displacement step of a cycle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArrayStep {
    /// Displacement ū.
    pub u: f64,
    /// Total force P̄ (positive in compression).
    pub force: f64,
    /// Fraction of springs in contact.
    pub contact_ratio: f64,
}

/// A jump of the array at one displacement step: springs that changed contact state because
/// their previous equilibrium became unstable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrayJump {
    /// Displacement ū of the step.
    pub u: f64,
    /// Springs that came into contact.
    pub into_contact: usize,
    /// Springs that left contact.
    pub out_of_contact: usize,
    /// Force before the jump (the previous state's gaps at the new displacement).
    pub force_before: f64,
    /// Force after.
    pub force_after: f64,
}

/// A loading-unloading cycle of a spring array.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ArrayCycle {
    /// Loading steps, ū decreasing.
    pub loading: Vec<ArrayStep>,
    /// Unloading steps, ū increasing.
    pub unloading: Vec<ArrayStep>,
    /// Jumps (coupled path only; the uncoupled paths know them per spring).
    pub jumps: Vec<ArrayJump>,
    /// Whether every accepted state had a positive-definite Hessian (coupled path; the
    /// uncoupled paths sit on stable single-spring branches by construction).
    pub all_stable: bool,
    /// Newton iterations in total (coupled path).
    pub newton_iterations: usize,
}

impl ArrayCycle {
    /// Most negative force on unloading, P_max of Eq. (5.36).
    pub fn max_tensile_force(&self) -> f64 {
        self.unloading
            .iter()
            .map(|s| s.force)
            .fold(f64::INFINITY, f64::min)
    }

    /// Energy lost over the cycle, −∮ P̄ dū (area of the loop, trapezoid rule).
    pub fn hysteresis(&self) -> f64 {
        let load: Vec<(f64, f64)> = self.loading.iter().map(|s| (s.u, s.force)).collect();
        let unload: Vec<(f64, f64)> = self.unloading.iter().map(|s| (s.u, s.force)).collect();
        -(crate::numerics::quadrature::trapezoid(&load) + crate::numerics::quadrature::trapezoid(&unload))
    }
}

/// The displacement grid of a cycle: `n` values from `u_max` down to `u_min`.
///
/// # Errors
/// [`Error::InvalidParameter`] for `u_min ≥ u_max` or `n < 2`.
pub fn cycle_grid(u_max: f64, u_min: f64, n: usize) -> Result<Vec<f64>> {
    if u_min.is_nan() || u_max.is_nan() || u_min >= u_max {
        return Err(Error::invalid("u_min", u_min, "must be below u_max"));
    }
    if n < 2 {
        return Err(Error::invalid("steps", n, "must be at least 2"));
    }
    Ok(linspace(u_max, u_min, n))
}

/// Adhesive force of the single spring P_m of Eq. (5.36): the most negative force on unloading,
/// −g at the gap of largest attraction (the contact branch passes it for every k̄).
pub fn single_spring_adhesive_force() -> f64 {
    -lj_traction(max_traction_gap())
}

/// Adhesion efficiency α_F = P_max/(MN P_m), Eq. (5.36).
pub fn adhesion_efficiency(cycle: &ArrayCycle, n_springs: usize) -> f64 {
    cycle.max_tensile_force() / (n_springs as f64 * single_spring_adhesive_force())
}

/// Empirical fit (5.37): α_F = exp(−4 σ̄_rms / 2ⁿ).
pub fn efficiency_fit(sigma_rms_bar: f64, n: f64) -> f64 {
    (-4.0 * sigma_rms_bar / 2f64.powf(n)).exp()
}

/// Uncoupled cycle (k̄_μ = 0), exact: every spring on its single-spring branch at ū − z̄_i,
/// solved by Brent's method. Cost O(N·M·steps); the reference for the cheaper paths.
///
/// # Errors
/// Grid errors; root-finding failures (not expected).
pub fn uncoupled_cycle(array: &SpringArray, u_max: f64, u_min: f64, n: usize) -> Result<ArrayCycle> {
    let grid = cycle_grid(u_max, u_min, n)?;
    let s = array.single()?;
    let touched: Vec<bool> = array
        .heights
        .iter()
        .map(|z| s.branch_on(u_min - z, true, true) == SpringBranch::Contact)
        .collect();
    let step = |u: f64, loading: bool| -> Result<ArrayStep> {
        let mut force = 0.0;
        let mut contact = 0usize;
        for (z, &t) in array.heights.iter().zip(&touched) {
            let b = s.branch_on(u - z, loading, t);
            let d = s.gap(u - z, b)?;
            force += array.k_e * (d - (u - z));
            contact += usize::from(d < CONTACT_GAP);
        }
        Ok(ArrayStep {
            u,
            force,
            contact_ratio: contact as f64 / array.len() as f64,
        })
    };
    let mut out = ArrayCycle {
        all_stable: true,
        ..ArrayCycle::default()
    };
    for &u in &grid {
        out.loading.push(step(u, true)?);
    }
    for &u in grid.iter().rev() {
        out.unloading.push(step(u, false)?);
    }
    Ok(out)
}

/// Uncoupled cycle (k̄_μ = 0) by binning: the heights are spread onto a grid of spacing
/// δ = Δū/`oversample` aligned with the displacement steps (linear weights to the two nearest
/// nodes), so that ū_j − z̄ always falls on a multiple of δ, where the single-spring branches
/// are tabulated once. The force at each step is then a discrete convolution of the height
/// histogram with the tabulated branch. Cost O(steps · (range of z̄)/δ), independent of N·M.
/// Exact for a force linear in ū between nodes; the error comes from the curvature of the
/// branches and from smearing each spring's jump over one bin.
///
/// # Errors
/// Grid errors; [`Error::InvalidParameter`] for `oversample` = 0 or no heights.
pub fn uncoupled_cycle_binned(
    heights: &[f64],
    k_e: f64,
    u_max: f64,
    u_min: f64,
    n: usize,
    oversample: usize,
) -> Result<ArrayCycle> {
    let (lo, hi) = heights
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    BinnedBranches::new(k_e, u_max, u_min, n, oversample, (lo, hi))?.cycle(heights)
}

/// The single-spring branches tabulated at the nodes of the binned path, for every height in a
/// range: build once, then run [`BinnedBranches::cycle`] for many surfaces (samples).
#[derive(Debug, Clone)]
pub struct BinnedBranches {
    spring: SingleSpring,
    k_e: f64,
    grid: Vec<f64>,
    u_max: f64,
    delta: f64,
    r: i64,
    m_lo: i64,
    m_hi: i64,
    q_lo: i64,
    contact_force: Vec<f64>,
    free_force: Vec<f64>,
}

impl BinnedBranches {
    /// Tabulate the branches for a cycle from `u_max` down to `u_min` in `n` steps, bins of
    /// Δū/`oversample`, and heights within `height_range`.
    ///
    /// # Errors
    /// Grid errors; [`Error::InvalidParameter`] for `oversample` = 0 or an empty height range.
    pub fn new(
        k_e: f64,
        u_max: f64,
        u_min: f64,
        n: usize,
        oversample: usize,
        height_range: (f64, f64),
    ) -> Result<Self> {
        let grid = cycle_grid(u_max, u_min, n)?;
        if oversample == 0 {
            return Err(Error::invalid("oversample", 0, "must be at least 1"));
        }
        let (z_lo, z_hi) = height_range;
        if !(z_lo <= z_hi && z_lo.is_finite() && z_hi.is_finite()) {
            return Err(Error::invalid(
                "heights",
                format!("[{z_lo}, {z_hi}]"),
                "must be a finite range",
            ));
        }
        let spring = SingleSpring::new(k_e)?;
        let r = oversample as i64;
        let du = (u_max - u_min) / (n - 1) as f64;
        let delta = du / oversample as f64;
        // Bin coordinate of a height: s = (u_max − z)/δ, so ū_j − z = δ (s − j r).
        let m_lo = ((u_max - z_hi) / delta).floor() as i64;
        let m_hi = ((u_max - z_lo) / delta).floor() as i64 + 1;
        let j_max = (n - 1) as i64;
        let q_lo = m_lo - j_max * r;
        let n_q = (m_hi - q_lo + 1) as usize;
        let (u_in, u_off) = spring
            .bistable_range()
            .unwrap_or((f64::NEG_INFINITY, f64::NEG_INFINITY));
        let mut contact_force = vec![f64::NAN; n_q];
        let mut free_force = vec![f64::NAN; n_q];
        for q in 0..n_q {
            let u = delta * (q as i64 + q_lo) as f64;
            let has_instab = spring.has_instabilities();
            if !has_instab || u < u_off {
                contact_force[q] = k_e * (spring.gap(u, SpringBranch::Contact)? - u);
            }
            if !has_instab || u > u_in {
                free_force[q] = k_e * (spring.gap(u, SpringBranch::Free)? - u);
            }
        }
        Ok(Self {
            spring,
            k_e,
            grid,
            u_max,
            delta,
            r,
            m_lo,
            m_hi,
            q_lo,
            contact_force,
            free_force,
        })
    }

    /// The cycle over one surface.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for no heights or heights outside the tabulated range.
    pub fn cycle(&self, heights: &[f64]) -> Result<ArrayCycle> {
        if heights.is_empty() {
            return Err(Error::invalid("heights", 0, "must not be empty"));
        }
        let n_bins = (self.m_hi - self.m_lo + 1) as usize;
        let mut weight = vec![0.0; n_bins];
        for &z in heights {
            let c = (self.u_max - z) / self.delta;
            let m = c.floor();
            let phi = c - m;
            let b = m as i64 - self.m_lo;
            if b < 0 || b + 1 >= n_bins as i64 {
                return Err(Error::invalid("heights", z, "outside the tabulated height range"));
            }
            weight[b as usize] += 1.0 - phi;
            weight[b as usize + 1] += phi;
        }
        let s = &self.spring;
        let (u_in, u_off) = s
            .bistable_range()
            .unwrap_or((f64::NEG_INFINITY, f64::NEG_INFINITY));
        let j_max = (self.grid.len() - 1) as i64;
        let total: f64 = weight.iter().sum();
        let step = |j: i64, loading: bool| -> ArrayStep {
            let mut force = 0.0;
            let mut contact = 0.0;
            for (b, &w) in weight.iter().enumerate() {
                if w == 0.0 {
                    continue;
                }
                let m = b as i64 + self.m_lo;
                let q = (m - j * self.r - self.q_lo) as usize;
                let u = self.delta * (m - j * self.r) as f64;
                let (f, in_contact) = if s.has_instabilities() {
                    // Touched on loading: ū at the lowest step reached the pull-in displacement.
                    let touched = self.delta * (m - j_max * self.r) as f64 <= u_in;
                    let c = if loading { u <= u_in } else { touched && u < u_off };
                    (
                        if c {
                            self.contact_force[q]
                        } else {
                            self.free_force[q]
                        },
                        c,
                    )
                } else {
                    let f = self.free_force[q];
                    (f, f / self.k_e + u < CONTACT_GAP)
                };
                force += w * f;
                if in_contact {
                    contact += w;
                }
            }
            ArrayStep {
                u: self.grid[j as usize],
                force,
                contact_ratio: contact / total,
            }
        };
        let mut out = ArrayCycle {
            all_stable: true,
            ..ArrayCycle::default()
        };
        out.loading = (0..=j_max).map(|j| step(j, true)).collect();
        out.unloading = (0..=j_max).rev().map(|j| step(j, false)).collect();
        Ok(out)
    }
}

/// Coupled cycle, Eqs. (5.31)-(5.34): at each displacement step the gaps are found by
/// [`StableNewton`] from the previous step's equilibrium, so the array stays on the metastable
/// branch until it loses stability and then moves to the next stable state. Jumps are the steps
/// at which the previous state had become unstable or springs changed contact state.
///
/// `on_step(fraction)` is called after each step and may return an error to stop (cancellation).
///
/// # Errors
/// Grid errors, [`crate::error::Error::NoConvergence`] from the solver, errors of `on_step`.
pub fn coupled_cycle(
    array: &SpringArray,
    u_max: f64,
    u_min: f64,
    n: usize,
    opts: &NewtonOptions,
    mut on_step: impl FnMut(f64) -> Result<()>,
) -> Result<ArrayCycle> {
    let grid = cycle_grid(u_max, u_min, n)?;
    let s = array.single()?;
    // Start: every spring on its free branch at ū_max − z̄_i (or the only branch), then relax.
    let mut d: Vec<f64> = array
        .heights
        .iter()
        .map(|z| {
            let b = s.branch_on(u_max - z, true, false);
            s.gap(u_max - z, b)
        })
        .collect::<Result<_>>()?;
    let mut solver = StableNewton::new(&array.energy_at(u_max))?;
    let mut out = ArrayCycle {
        all_stable: true,
        ..ArrayCycle::default()
    };
    // The shared loading-path driver, without refinement: a step is a jump when the previous
    // state became unstable (the solver met an indefinite tangent) or springs changed contact
    // state within it (for k̄_e < k̄_cr only possible through an instability; a Newton step may
    // carry a spring past its vanished branch at once).
    let path = PathOptions {
        newton: *opts,
        refine_to: None,
        trial_iterations: opts.max_iterations,
        unstable_start_is_jump: true,
        jump_iterations: opts.max_iterations,
        retry_target: false,
    };
    let unloading: Vec<f64> = grid.iter().rev().copied().collect();
    let total = 2 * grid.len();
    let mut done = 0;
    let mut start = u_max;
    for (loading, targets) in [(true, &grid), (false, &unloading)] {
        let stats = follow(array, &mut solver, &mut d, start, targets, &path, |v| {
            let u = v.lambda;
            let step = ArrayStep {
                u,
                force: array.force(u, v.x),
                contact_ratio: SpringArray::contact_ratio(v.x),
            };
            if let Some((_, before)) = v.jumped_from {
                let changed = |into: bool| {
                    before
                        .iter()
                        .zip(v.x)
                        .filter(|(b, x)| (**b < CONTACT_GAP) != into && (**x < CONTACT_GAP) == into)
                        .count()
                };
                out.jumps.push(ArrayJump {
                    u,
                    into_contact: changed(true),
                    out_of_contact: changed(false),
                    force_before: array.force(u, before),
                    force_after: step.force,
                });
            }
            if loading {
                out.loading.push(step);
            } else {
                out.unloading.push(step);
            }
            done += 1;
            on_step(done as f64 / total as f64)
        })?;
        out.newton_iterations += stats.newton_iterations;
        out.all_stable &= stats.all_stable;
        start = *targets.last().unwrap_or(&start);
    }
    Ok(out)
}
