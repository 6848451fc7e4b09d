//! The elastic half-space under axisymmetric surface pressure: the ring influence kernel and the
//! ring grid of the surface (boundary-element) model of section 4.2.
//!
//! A uniform pressure p on a disc of radius c displaces the surface of a half-space of
//! effective modulus E* normally by ([Johnson85, Eqs. 3.37-3.38], the Boussinesq point load
//! integrated over the disc)
//!
//! ```text
//! u(r) = (4 p c / (π E*)) E(r²/c²),                              r ≤ c,
//! u(r) = (4 p r / (π E*)) [E(c²/r²) − (1 − c²/r²) K(c²/r²)],      r > c,
//! ```
//!
//! with K, E the complete elliptic integrals of parameter m = k². A ring c₁ < r < c₂ is the
//! difference of two discs. Lengths here are in any unit, pressures in units of E*: the caller
//! scales.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::numerics::elliptic::complete_k_e;

/// E(m) − (1 − m) K(m) for small m without cancellation: Σ (e_n − k_n + k_{n−1}) mⁿ with
/// k_n = [(2n)!/(2^{2n} n!²)]² and e_n = −k_n/(2n − 1) the Maclaurin coefficients of
/// (2/π)K and (2/π)E.
fn e_minus_k_small(m: f64) -> f64 {
    let mut k_prev = 1.0; // k_0
    let mut sum = 0.0;
    let mut pow = 1.0;
    for n in 1..60 {
        let nf = n as f64;
        let ratio = (2.0 * nf - 1.0) / (2.0 * nf);
        let k_n = k_prev * ratio * ratio;
        let e_n = -k_n / (2.0 * nf - 1.0);
        pow *= m;
        let term = (e_n - k_n + k_prev) * pow;
        sum += term;
        k_prev = k_n;
        if term.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    0.5 * PI * sum
}

/// Normal surface displacement at radius `r` under unit pressure (p = E* = 1) on a disc of
/// radius `c`, [Johnson85, Eqs. 3.37-3.38] (formula in the module doc).
pub fn disc_displacement(r: f64, c: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    if r <= c {
        let (_, e) = complete_k_e((r / c) * (r / c));
        4.0 * c / PI * e
    } else {
        let m = (c / r) * (c / r);
        let bracket = if m < 0.1 {
            e_minus_k_small(m)
        } else {
            let (k, e) = complete_k_e(m);
            e - (1.0 - m) * k
        };
        4.0 * r / PI * bracket
    }
}

/// Normal surface displacement at `r` under unit pressure on the ring `inner` < ρ < `outer`.
pub fn ring_displacement(r: f64, inner: f64, outer: f64) -> f64 {
    disc_displacement(r, outer) - disc_displacement(r, inner)
}

/// The rings of the surface model: width `h` up to `r_fine`, then growing geometrically by
/// `growth` up to `r_max`. Tractions are constant on a ring; displacements and gaps are
/// collocated at the ring's mid-radius.
#[derive(Debug, Clone, PartialEq)]
pub struct RingGrid {
    /// Ring edges, 0 = e₀ < e₁ < … < e_N.
    pub edges: Vec<f64>,
    /// Collocation radii (mid-radius of each ring), length N.
    pub nodes: Vec<f64>,
    /// Ring areas π(e_{i+1}² − e_i²), length N.
    pub areas: Vec<f64>,
    /// Number of rings of the uniform (fine) zone.
    pub n_fine: usize,
}

impl RingGrid {
    /// Build the grid.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive width, `r_fine < h`, `growth ≤ 1` or a
    /// grid of more than `max_rings` rings.
    pub fn new(h: f64, r_fine: f64, growth: f64, r_max: f64, max_rings: usize) -> Result<Self> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(Error::invalid("ring_width", h, "must be positive"));
        }
        if !(growth > 1.0 && growth.is_finite()) {
            return Err(Error::invalid("ring_growth", growth, "must exceed 1"));
        }
        if !(r_fine >= h && r_fine.is_finite() && r_max.is_finite()) {
            return Err(Error::invalid(
                "fine_radius",
                r_fine,
                "must be at least one ring width",
            ));
        }
        let n_fine = (r_fine / h).ceil() as usize;
        if n_fine > max_rings {
            return Err(Error::invalid(
                "ring_width",
                h,
                format!(
                    "gives {} rings in the contact zone, more than {max_rings}: choose a wider ring",
                    crate::text::fmt_sig(n_fine as f64)
                ),
            ));
        }
        let mut edges: Vec<f64> = (0..=n_fine).map(|i| i as f64 * h).collect();
        let mut width = h;
        while *edges.last().unwrap_or(&0.0) < r_max {
            width *= growth;
            let next = edges.last().copied().unwrap_or(0.0) + width;
            edges.push(next);
            if edges.len() > max_rings + 1 {
                return Err(Error::invalid(
                    "ring_width",
                    h,
                    format!("gives more than {max_rings} rings: choose a wider ring"),
                ));
            }
        }
        let nodes = edges.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let areas = edges
            .windows(2)
            .map(|w| PI * (w[1] * w[1] - w[0] * w[0]))
            .collect();
        Ok(Self {
            edges,
            nodes,
            areas,
            n_fine,
        })
    }

    /// Number of rings.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the grid has no ring.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Collocation compliance: entry (i, j) is the displacement at node i under unit pressure
    /// on ring j (E* = 1). Row-major, N x N.
    pub fn compliance(&self) -> Vec<f64> {
        let n = self.len();
        let mut c = vec![0.0; n * n];
        for (i, &r) in self.nodes.iter().enumerate() {
            // Disc displacements at r for every edge, then differences.
            let discs: Vec<f64> = self.edges.iter().map(|&e| disc_displacement(r, e)).collect();
            for j in 0..n {
                c[i * n + j] = discs[j + 1] - discs[j];
            }
        }
        c
    }

    /// Symmetric stiffness of the rings: K = F⁻¹ with F the symmetric part of the flexibility
    /// F_ij = C_ij / A_j (displacement at node i per unit force on ring j; Maxwell-Betti
    /// reciprocity makes it symmetric up to the collocation error). K maps node displacements
    /// to ring forces, so that ½ uᵀ K u is the elastic energy of the loaded half-space. Returns
    /// K (row-major) and the largest relative asymmetry of F.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] if F is not positive definite (not expected for a valid grid).
    pub fn stiffness(&self) -> Result<(Vec<f64>, f64)> {
        let n = self.len();
        let c = self.compliance();
        let mut f = faer::Mat::<f64>::zeros(n, n);
        let mut asym: f64 = 0.0;
        for i in 0..n {
            for j in 0..n {
                let fij = c[i * n + j] / self.areas[j];
                let fji = c[j * n + i] / self.areas[i];
                f[(i, j)] = 0.5 * (fij + fji);
                if i != j {
                    let scale = (f64::abs(c[i * n + i] / self.areas[i])).max(c[j * n + j] / self.areas[j]);
                    asym = asym.max((fij - fji).abs() / scale);
                }
            }
        }
        // faer's blocked factorisation and inverse: about 1 s for 1 500 rings, where
        // unblocked triangular solves took minutes.
        use faer::linalg::solvers::DenseSolveCore;
        let k = f
            .llt(faer::Side::Lower)
            .map_err(|_| Error::Unresolvable {
                model: "ring stiffness",
                reason: "the ring flexibility is not positive definite".into(),
            })?
            .inverse();
        // K is symmetric: its column-major entries are its row-major ones.
        let k: Vec<f64> = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| k[(i, j)])
            .collect();
        Ok((k, asym))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::quadrature::integrate;
    use std::f64::consts::FRAC_1_SQRT_2;

    /// The displacement at r of unit pressure on the ring [c1, c2] by direct quadrature of the
    /// Boussinesq point-load solution u = 1/(π E* s) over the ring (E* = 1), no elliptic
    /// integrals: ∫ρ dρ ∫₀^π 2 dθ / (π s), s² = d² + 4rρ sin²(θ/2), d = |ρ − r|. The inner
    /// integral's peak at θ = 0 (width d/√(rρ)) is removed, where it is narrow, by
    /// t = sin(θ/2) = d sinh(v)/(2√(rρ)): ∫₀^π dθ/s = ∫₀^{v_max} dv / (√(rρ) √(1 − t²)),
    /// v_max = asinh(2√(rρ)/d), over θ < π/2; elsewhere θ is integrated as it is.
    fn brute_force(r: f64, c1: f64, c2: f64) -> f64 {
        let inner = |rho: f64| {
            let d = (rho - r).abs();
            let q = (r * rho).sqrt();
            let plain = |th: f64| 1.0 / (d * d + 4.0 * r * rho * (0.5 * th).sin().powi(2)).sqrt();
            let quad = |f: &dyn Fn(f64) -> f64, a: f64, b: f64| {
                integrate(f, a, b, 1e-14, 1e-12)
                    .unwrap_or_else(|e| panic!("inner quadrature at rho = {rho}, r = {r}: {e}"))
                    .value
            };
            let value = if d > 0.1 * q {
                quad(&plain, 0.0, PI)
            } else {
                // θ < π/2 through the peak-removing variable, the rest as it is.
                let v1 = (2.0 * q * FRAC_1_SQRT_2 / d).asinh();
                let sub = |v: f64| {
                    let t = d * v.sinh() / (2.0 * q);
                    1.0 / (q * (1.0 - t * t).sqrt())
                };
                quad(&sub, 0.0, v1) + quad(&plain, 0.5 * PI, PI)
            };
            2.0 / PI * value * rho
        };
        let mut total = 0.0;
        let cuts = if r > c1 && r < c2 {
            vec![c1, r, c2]
        } else {
            vec![c1, c2]
        };
        for w in cuts.windows(2) {
            total += integrate(inner, w[0], w[1], 1e-13, 1e-11)
                .expect("outer quadrature")
                .value;
        }
        total
    }

    #[test]
    fn ring_kernel_matches_boussinesq_quadrature() {
        // Inside, on and outside the ring, near and far.
        for (r, c1, c2) in [
            (0.3, 1.0, 1.2),
            (1.1, 1.0, 1.2),
            (1.05, 1.0, 1.2),
            (1.3, 1.0, 1.2),
            (5.0, 1.0, 1.2),
            (40.0, 2.0, 2.5),
            (0.5, 0.0, 1.0),
            (2.0, 0.0, 1.0),
        ] {
            let exact = ring_displacement(r, c1, c2);
            let brute = brute_force(r, c1, c2);
            assert!(
                (exact - brute).abs() < 1e-8 * brute.abs(),
                "r = {r}, ring [{c1}, {c2}]: {exact} vs {brute}"
            );
        }
    }

    #[test]
    fn disc_limits() {
        // Centre: u = 2pc/E*; edge: 4pc/(πE*); far: total force / (π E* r) = c²/r.
        assert!((disc_displacement(0.0, 1.5) - 3.0).abs() < 1e-14);
        assert!((disc_displacement(1.5, 1.5) - 6.0 / PI).abs() < 1e-14);
        // Far field: c²/r + c⁴/(8r³) + O(r⁻⁵) from the small-m series.
        let far = disc_displacement(1e3, 1.0);
        assert!((far - (1e-3 + 1.25e-10)).abs() < 1e-12 * 1e-3, "{far}");
        // The small-m series agrees with the AGM form where they meet (m = 0.1) and below.
        for m in [0.1, 0.05, 0.01] {
            let (k, e) = complete_k_e(m);
            let agm = e - (1.0 - m) * k;
            assert!((e_minus_k_small(m) - agm).abs() < 1e-13 * agm, "m = {m}");
        }
    }

    #[test]
    fn flexibility_is_nearly_symmetric_and_stiffness_reproduces_a_flat_punch() {
        let g = RingGrid::new(0.02, 1.0, 1.1, 3.0, 1000).expect("grid");
        let (k, asym) = g.stiffness().expect("stiffness");
        assert!(asym < 0.05, "asymmetry {asym}");
        // Rigid flat punch of radius 1 pressed by u = 1 on the rings inside r < 1, the rest
        // free: impose u on the inner rings and zero force outside; P = 2 E* a u (Sneddon).
        let n = g.len();
        let nf = g.n_fine;
        // Partition K: f_in = K_ii u_i + K_io u_o, 0 = K_oi u_i + K_oo u_o.
        let kk = nalgebra::DMatrix::from_row_slice(n, n, &k);
        let kii = kk.view((0, 0), (nf, nf));
        let kio = kk.view((0, nf), (nf, n - nf));
        let koi = kk.view((nf, 0), (n - nf, nf));
        let koo = kk.view((nf, nf), (n - nf, n - nf)).clone_owned();
        let ui = nalgebra::DVector::from_element(nf, 1.0);
        let uo = -koo.cholesky().expect("K_oo").solve(&(koi * &ui));
        let f = kii * &ui + kio * uo;
        let p: f64 = f.iter().sum();
        assert!((p - 2.0).abs() < 0.02, "punch force {p}");
    }
}
