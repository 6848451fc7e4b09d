//! The linear axisymmetric triangle (section 4.2.2): its stiffness from the constitutive law
//! (4.12) and the integration of the Lennard-Jones body force (4.15) over it.
//!
//! Stiffness: strains (ε_rr, ε_zz, ε_θθ, γ_rz) = (∂u_r/∂r, ∂u_z/∂z, u_r/r, ∂u_r/∂z + ∂u_z/∂r)
//! of the linear interpolation, K_e = ∫ Bᵀ D B 2πr dA with Radon's 7-point rule (ε_θθ is not
//! constant on the element).
//!
//! Body force: with linear u_z the height above the substrate d = δ + z + u_z is linear on the
//! element, so along a vertical chord the energy density, the force and the tangent have closed
//! antiderivatives in d (Ψ, ψ, ψ', ψ'' of [`Density`]). The element's integral is a
//! Gauss-Legendre rule in r over the chords ([`chords`]) of exact integrals in z: a column of
//! an undeformed flat tip carries exactly the plate traction p(g), Eq. (4.5), however thin or
//! thick its elements.

// Element code indexes small fixed arrays (nodes, strain components) by their local numbers,
// as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use crate::numerics::quadrature::{gauss_legendre, triangle_rule_7};

/// Isotropic elasticity in the order (rr, zz, θθ, rz), engineering shear strain (4.12).
pub fn elasticity_matrix(young: f64, nu: f64) -> [[f64; 4]; 4] {
    let f = young / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let (a, b) = (f * (1.0 - nu), f * nu);
    let g = young / (2.0 * (1.0 + nu));
    [[a, b, b, 0.0], [b, a, b, 0.0], [b, b, a, 0.0], [0.0, 0.0, 0.0, g]]
}

/// Linear shape functions of a triangle: N_k(r, z) = (α_k + β_k r + γ_k z) / (2A).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape {
    /// (α_k, β_k, γ_k) / (2A).
    pub coef: [[f64; 3]; 3],
    /// Area A.
    pub area: f64,
}

impl Shape {
    /// The shape functions of the triangle with vertices `p` (counter-clockwise).
    pub fn new(p: [[f64; 2]; 3]) -> Self {
        let two_a = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let mut coef = [[0.0; 3]; 3];
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            coef[k] = [
                (p[i][0] * p[j][1] - p[j][0] * p[i][1]) / two_a,
                (p[i][1] - p[j][1]) / two_a,
                (p[j][0] - p[i][0]) / two_a,
            ];
        }
        Self {
            coef,
            area: 0.5 * two_a,
        }
    }

    /// N_k at (r, z).
    pub fn at(&self, r: f64, z: f64) -> [f64; 3] {
        self.coef.map(|c| c[0] + c[1] * r + c[2] * z)
    }
}

/// Stiffness of a linear axisymmetric triangle, dofs (u_r0, u_z0, u_r1, u_z1, u_r2, u_z2):
/// K_e = ∫ Bᵀ D B 2πr dA (the strain energy ½ uᵀ K_e u of the ring the triangle sweeps).
pub fn triangle_stiffness(p: [[f64; 2]; 3], d: &[[f64; 4]; 4]) -> [[f64; 6]; 6] {
    let shape = Shape::new(p);
    let mut k = [[0.0; 6]; 6];
    for (bary, w) in triangle_rule_7() {
        let r: f64 = (0..3).map(|i| bary[i] * p[i][0]).sum();
        let weight = 2.0 * PI * r * w * shape.area;
        // B (4 × 6) at this point.
        let mut b = [[0.0; 6]; 4];
        for a in 0..3 {
            let [_, dr, dz] = shape.coef[a];
            b[0][2 * a] = dr;
            b[1][2 * a + 1] = dz;
            b[2][2 * a] = bary[a] / r;
            b[3][2 * a] = dz;
            b[3][2 * a + 1] = dr;
        }
        let mut db = [[0.0; 6]; 4];
        for i in 0..4 {
            for j in 0..6 {
                db[i][j] = (0..4).map(|m| d[i][m] * b[m][j]).sum();
            }
        }
        for i in 0..6 {
            for j in 0..6 {
                k[i][j] += weight * (0..4).map(|m| b[m][i] * db[m][j]).sum::<f64>();
            }
        }
    }
    k
}

/// What the strain energy of a triangle needs, in strain form: the constant strains
/// (ε_rr, ε_zz, γ_rz) from the shape functions' derivatives, and the integrals of the hoop
/// strain ε_θθ = Σ N_a u_ra / r. Computing ½ ∫ εᵀ D ε from the strains (rather than ½ uᵀ K u)
/// keeps the energy accurate where the displacements are large and nearly uniform, as under a
/// contact pressed deep: the line search compares energies that differ in their last digits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainForm {
    /// ∂N_a/∂r.
    pub dr: [f64; 3],
    /// ∂N_a/∂z.
    pub dz: [f64; 3],
    /// Volume of the ring ∫ 2πr dA.
    pub volume: f64,
    /// ∫ 2π N_a dA = 2πA/3 (the same for the three nodes).
    pub hoop: f64,
    /// ∫ 2π N_a N_b / r dA, in the order (0,0), (1,1), (2,2), (1,0), (2,0), (2,1).
    pub hoop2: [f64; 6],
}

impl StrainForm {
    /// The strain form of the triangle with vertices `p`.
    pub fn new(p: [[f64; 2]; 3]) -> Self {
        let shape = Shape::new(p);
        let mut hoop2 = [0.0; 6];
        let mut volume = 0.0;
        for (bary, w) in triangle_rule_7() {
            let r: f64 = (0..3).map(|i| bary[i] * p[i][0]).sum();
            let area = w * shape.area;
            volume += 2.0 * PI * r * area;
            for (m, (a, b)) in [(0, 0), (1, 1), (2, 2), (1, 0), (2, 0), (2, 1)]
                .into_iter()
                .enumerate()
            {
                hoop2[m] += 2.0 * PI * bary[a] * bary[b] / r * area;
            }
        }
        Self {
            dr: shape.coef.map(|c| c[1]),
            dz: shape.coef.map(|c| c[2]),
            volume,
            hoop: 2.0 * PI * shape.area / 3.0,
            hoop2,
        }
    }

    /// The stiffness ∂²/∂u² of [`StrainForm::energy`], dofs (u_r0, u_z0, u_r1, u_z1, u_r2,
    /// u_z2): the same matrix as [`triangle_stiffness`], from the strain form's integrals.
    pub fn stiffness(&self, d: &[[f64; 4]; 4]) -> [[f64; 6]; 6] {
        // Rows of the constant strains (rr, zz, rz) in the dofs.
        let mut c = [[0.0; 6]; 3];
        for a in 0..3 {
            c[0][2 * a] = self.dr[a];
            c[1][2 * a + 1] = self.dz[a];
            c[2][2 * a] = self.dz[a];
            c[2][2 * a + 1] = self.dr[a];
        }
        let d3 = [
            [d[0][0], d[0][1], 0.0],
            [d[1][0], d[1][1], 0.0],
            [0.0, 0.0, d[3][3]],
        ];
        // D_θ· times the constant strains, and the radial-dof indicator.
        let coupling: [f64; 6] = std::array::from_fn(|j| d[2][0] * c[0][j] + d[2][1] * c[1][j]);
        let radial: [f64; 6] = std::array::from_fn(|j| if j % 2 == 0 { 1.0 } else { 0.0 });
        let pairs = [(0, 0), (1, 1), (2, 2), (1, 0), (2, 0), (2, 1)];
        let mut k = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let mut v = 0.0;
                for m in 0..3 {
                    for n in 0..3 {
                        v += c[m][i] * d3[m][n] * c[n][j];
                    }
                }
                k[i][j] = self.volume * v + self.hoop * (coupling[i] * radial[j] + radial[i] * coupling[j]);
            }
        }
        for (m, &(a, b)) in pairs.iter().enumerate() {
            k[2 * a][2 * b] += d[2][2] * self.hoop2[m];
            if a != b {
                k[2 * b][2 * a] += d[2][2] * self.hoop2[m];
            }
        }
        k
    }

    /// ½ ∫ εᵀ D ε 2πr dA for nodal displacements `ur`, `uz`.
    pub fn energy(&self, d: &[[f64; 4]; 4], ur: [f64; 3], uz: [f64; 3]) -> f64 {
        let mut e = [0.0; 3];
        for a in 0..3 {
            e[0] += self.dr[a] * ur[a];
            e[1] += self.dz[a] * uz[a];
            e[2] += self.dz[a] * ur[a] + self.dr[a] * uz[a];
        }
        // Constant part (rr, zz, rz) of D.
        let constant = d[0][0] * e[0] * e[0]
            + 2.0 * d[0][1] * e[0] * e[1]
            + d[1][1] * e[1] * e[1]
            + d[3][3] * e[2] * e[2];
        // Coupling with the hoop strain: (D_θr ε_rr + D_θz ε_zz) ∫ 2πr ε_θθ.
        let coupling = (d[2][0] * e[0] + d[2][1] * e[1]) * self.hoop * (ur[0] + ur[1] + ur[2]);
        let h = &self.hoop2;
        let hoop = h[0] * ur[0] * ur[0]
            + h[1] * ur[1] * ur[1]
            + h[2] * ur[2] * ur[2]
            + 2.0 * (h[3] * ur[1] * ur[0] + h[4] * ur[2] * ur[0] + h[5] * ur[2] * ur[1]);
        0.5 * (self.volume * constant + 2.0 * coupling + d[2][2] * hoop)
    }
}

/// A vertical chord of a triangle at a Gauss point in r: the element's body-force integrals are
/// sums over its chords of exact integrals in z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chord {
    /// Radius r of the chord.
    pub r: f64,
    /// Weight 2πr × the Gauss weight × the half-width of the r-interval.
    pub weight: f64,
    /// Reference height of the chord's lower end above the apex.
    pub z_lo: f64,
    /// Length of the chord.
    pub length: f64,
    /// Shape functions at the lower end.
    pub n_lo: [f64; 3],
    /// Their change along the chord, γ_k/(2A) × length.
    pub dn: [f64; 3],
}

/// The chords of a triangle: `points` Gauss points in r on each of the (at most two) intervals
/// between the r-coordinates of its vertices.
pub fn chords(p: [[f64; 2]; 3], points: usize, out: &mut Vec<Chord>) {
    let shape = Shape::new(p);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| p[a][0].total_cmp(&p[b][0]));
    let [a, b, c] = order.map(|k| p[k]);
    let on_edge = |u: [f64; 2], v: [f64; 2], r: f64| {
        if v[0] == u[0] {
            u[1]
        } else {
            u[1] + (v[1] - u[1]) * (r - u[0]) / (v[0] - u[0])
        }
    };
    let (x, w) = gauss_legendre(points);
    for (lo, hi, short) in [(a[0], b[0], (a, b)), (b[0], c[0], (b, c))] {
        if hi <= lo {
            continue;
        }
        let half = 0.5 * (hi - lo);
        for (xi, wi) in x.iter().zip(&w) {
            let r = lo + half * (xi + 1.0);
            let z1 = on_edge(a, c, r);
            let z2 = on_edge(short.0, short.1, r);
            let (z_lo, z_hi) = (z1.min(z2), z1.max(z2));
            let length = z_hi - z_lo;
            out.push(Chord {
                r,
                weight: 2.0 * PI * r * wi * half,
                z_lo,
                length,
                n_lo: shape.at(r, z_lo),
                dn: shape.coef.map(|c| c[2] * length),
            });
        }
    }
}

/// The body-force energy density of the tip's material at height d above the substrate and
/// its derivatives, in the units of the caller (Eqs. (4.2), (4.15)):
///
/// ```text
/// ψ(d)  = −a3/d³ + a9/d⁹        (energy per unit volume; ψ = −p, p the traction (4.5))
/// ψ'(d) = 3a3/d⁴ − 9a9/d¹⁰      (= B_z, the body force (4.15), attractive positive)
/// Ψ(d)  = a3/(2d²) − a9/(8d⁸)   (Ψ' = ψ, Ψ(∞) = 0; Ψ = −φ, φ the plate energy (4.4))
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Density {
    /// Coefficient of the attraction, a3 = A_H C6 / (6π).
    pub a3: f64,
    /// Coefficient of the repulsion, a9 = A_H C12 σ⁶ / (45π).
    pub a9: f64,
}

/// Values of Ψ, ψ, ψ', ψ'' at one height.
#[derive(Debug, Clone, Copy)]
struct Values {
    big_psi: f64,
    psi: f64,
    d1: f64,
    d2: f64,
}

/// Below this relative change ε of d along a chord the chord integrals use a 4-point Gauss rule
/// in z, where the antiderivative differences would cancel: the closed form of the third
/// tangent moment loses about ε⁻³ ulp (3e-11 relative at ε = 0.02), the Gauss rule's error
/// is about (11)₈ ε⁸ (4!)⁴/(9 (8!)³) ≈ ε⁸ (3e-14 relative at ε = 0.02, for the steepest
/// integrand d⁻¹¹).
const SHORT_CHORD: f64 = 0.02;

impl Density {
    fn values(&self, d: f64) -> Values {
        let u = 1.0 / d;
        let u2 = u * u;
        let u3 = u2 * u;
        let u8 = u2 * u2 * u2 * u2;
        let u9 = u8 * u;
        Values {
            big_psi: 0.5 * self.a3 * u2 - 0.125 * self.a9 * u8,
            psi: -self.a3 * u3 + self.a9 * u9,
            d1: 3.0 * self.a3 * u3 * u - 9.0 * self.a9 * u9 * u,
            d2: -12.0 * self.a3 * u3 * u2 + 90.0 * self.a9 * u9 * u2,
        }
    }

    /// ψ(d).
    pub fn psi(&self, d: f64) -> f64 {
        self.values(d).psi
    }

    /// ψ'(d) = B_z(d).
    pub fn psi_prime(&self, d: f64) -> f64 {
        self.values(d).d1
    }

    /// ∫ ψ dz along a chord from height `d_lo` to `d_lo + dd` of length `length` (d linear).
    pub fn energy_on_chord(&self, d_lo: f64, dd: f64, length: f64) -> f64 {
        if dd.abs() < SHORT_CHORD * d_lo {
            return length * self.gauss_z(d_lo, dd, |v| v.psi)[0];
        }
        let (lo, hi) = (self.values(d_lo), self.values(d_lo + dd));
        length * (hi.big_psi - lo.big_psi) / dd
    }

    /// Moments ∫₀¹ ψ'(d_lo + τ dd) τ^m dτ, m = 0, 1.
    pub fn force_moments(&self, d_lo: f64, dd: f64) -> [f64; 2] {
        if dd.abs() < SHORT_CHORD * d_lo {
            let m = self.gauss_z(d_lo, dd, |v| v.d1);
            return [m[0], m[1]];
        }
        let (lo, hi) = (self.values(d_lo), self.values(d_lo + dd));
        let i0 = (hi.psi - lo.psi) / dd;
        let i1 = (dd * hi.psi - (hi.big_psi - lo.big_psi)) / (dd * dd);
        [i0, i1]
    }

    /// Moments ∫₀¹ ψ''(d_lo + τ dd) τ^m dτ, m = 0, 1, 2.
    pub fn tangent_moments(&self, d_lo: f64, dd: f64) -> [f64; 3] {
        if dd.abs() < SHORT_CHORD * d_lo {
            return self.gauss_z(d_lo, dd, |v| v.d2);
        }
        let (lo, hi) = (self.values(d_lo), self.values(d_lo + dd));
        let i0 = (hi.d1 - lo.d1) / dd;
        let i1 = (dd * hi.d1 - (hi.psi - lo.psi)) / (dd * dd);
        let i2 = (dd * dd * hi.d1 - 2.0 * dd * hi.psi + 2.0 * (hi.big_psi - lo.big_psi)) / (dd * dd * dd);
        [i0, i1, i2]
    }

    /// ∫₀¹ f(d_lo + τ dd) τ^m dτ for m = 0, 1, 2 by the 4-point Gauss-Legendre rule, f picked
    /// from the values (for a chord along which d changes by less than [`SHORT_CHORD`]: the
    /// rule's error is below 1e-13 relative there).
    fn gauss_z(&self, d_lo: f64, dd: f64, pick: impl Fn(&Values) -> f64) -> [f64; 3] {
        // Nodes (1 ± x_k)/2 and weights w_k/2 of the Gauss-Legendre rule on [−1, 1], mapped to [0, 1].
        const X: [f64; 4] = [
            0.069_431_844_202_973_71,
            0.330_009_478_207_571_9,
            0.669_990_521_792_428_1,
            0.930_568_155_797_026_3,
        ];
        const W: [f64; 4] = [
            0.173_927_422_568_726_93,
            0.326_072_577_431_273_07,
            0.326_072_577_431_273_07,
            0.173_927_422_568_726_93,
        ];
        let mut out = [0.0; 3];
        for (t, w) in X.iter().zip(&W) {
            let f = pick(&self.values(d_lo + t * dd));
            out[0] += w * f;
            out[1] += w * f * t;
            out[2] += w * f * t * t;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn density() -> Density {
        Density { a3: 1.3, a9: 0.7 }
    }

    /// The chord integrals against a fine composite Gauss quadrature, for long chords (closed
    /// forms) and short ones (the Gauss rule in z).
    #[test]
    fn chord_integrals_match_a_fine_quadrature() {
        let rho = density();
        let fine = |f: &dyn Fn(f64) -> f64, m: i32, d_lo: f64, dd: f64| {
            let (x, w) = gauss_legendre(20);
            let n = 200;
            let mut s = 0.0;
            for k in 0..n {
                let (a, b) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                for (xi, wi) in x.iter().zip(&w) {
                    let t = a + 0.5 * (b - a) * (xi + 1.0);
                    s += 0.5 * (b - a) * wi * f(d_lo + t * dd) * t.powi(m);
                }
            }
            s
        };
        let psi = |d: f64| rho.psi(d);
        let d1 = |d: f64| rho.psi_prime(d);
        let d2 = |d: f64| rho.values(d).d2;
        for (d_lo, dd) in [
            (0.8, 3.0),
            (1.0, 0.3),
            (2.0, -0.5),
            (1.0, 0.01),
            // Either side of the switch to the Gauss rule.
            (1.0, 0.0199),
            (1.0, 0.0201),
            (3.0, -0.0601),
            (5.0, 1e-6),
            (0.9, 40.0),
        ] {
            let e = rho.energy_on_chord(d_lo, dd, 2.0);
            let f = rho.force_moments(d_lo, dd);
            let t = rho.tangent_moments(d_lo, dd);
            let want = [
                2.0 * fine(&psi, 0, d_lo, dd),
                fine(&d1, 0, d_lo, dd),
                fine(&d1, 1, d_lo, dd),
                fine(&d2, 0, d_lo, dd),
                fine(&d2, 1, d_lo, dd),
                fine(&d2, 2, d_lo, dd),
            ];
            let got = [e, f[0], f[1], t[0], t[1], t[2]];
            for (g, w) in got.iter().zip(&want) {
                let scale = w.abs().max(1e-3 * rho.values(d_lo).d2.abs());
                assert!(
                    (g - w).abs() < 1e-10 * scale,
                    "d_lo {d_lo}, dd {dd}: {got:?} vs {want:?}"
                );
            }
        }
    }

    /// The stiffness of a triangle is symmetric, has the rigid translation along z as a null
    /// vector (a translation along r strains the hoop direction) and is positive semi-definite
    /// on the element's deformations.
    #[test]
    fn triangle_stiffness_is_symmetric_with_the_axial_translation_free() {
        let p = [[1.0, 0.0], [2.0, 0.2], [1.2, 1.0]];
        let k = triangle_stiffness(p, &elasticity_matrix(3.0, 0.3));
        for i in 0..6 {
            for j in 0..6 {
                assert!((k[i][j] - k[j][i]).abs() < 1e-12 * k[i][i].abs());
            }
            let axial: f64 = (0..3).map(|a| k[i][2 * a + 1]).sum();
            assert!(axial.abs() < 1e-12 * k[i][i].abs(), "row {i}: {axial}");
        }
        // A uniform radial expansion u_r = ε r strains ε_rr = ε_θθ = ε: energy ½ (2(λ+2G)+2λ)... as
        // the exact ∫ σ:ε over the ring.
        let (e, nu) = (3.0, 0.3);
        let u: Vec<f64> = (0..3).flat_map(|a| [1e-3 * p[a][0], 0.0]).collect();
        let energy: f64 = 0.5
            * (0..6)
                .map(|i| (0..6).map(|j| u[i] * k[i][j] * u[j]).sum::<f64>())
                .sum::<f64>();
        let d = elasticity_matrix(e, nu);
        let strain = [1e-3, 0.0, 1e-3, 0.0];
        let density: f64 = 0.5
            * (0..4)
                .map(|i| (0..4).map(|j| strain[i] * d[i][j] * strain[j]).sum::<f64>())
                .sum::<f64>();
        let shape = Shape::new(p);
        let centroid_r = (p[0][0] + p[1][0] + p[2][0]) / 3.0;
        let volume = 2.0 * PI * centroid_r * shape.area;
        assert!(
            (energy - density * volume).abs() < 1e-12 * energy,
            "{energy} vs {}",
            density * volume
        );
    }

    /// The strain form gives the energy ½ uᵀ K u of the stiffness.
    #[test]
    fn strain_form_energy_is_the_stiffness_quadratic_form() {
        let p = [[1.0, 0.0], [2.0, 0.2], [1.2, 1.0]];
        let d = elasticity_matrix(3.0, 0.3);
        let k = triangle_stiffness(p, &d);
        let u = [0.3, -0.2, 0.5, 0.1, -0.4, 0.7];
        let quadratic: f64 = 0.5
            * (0..6)
                .map(|i| (0..6).map(|j| u[i] * k[i][j] * u[j]).sum::<f64>())
                .sum::<f64>();
        let form = StrainForm::new(p);
        let e = form.energy(&d, [u[0], u[2], u[4]], [u[1], u[3], u[5]]);
        assert!((e - quadratic).abs() < 1e-12 * quadratic, "{e} vs {quadratic}");
        let k2 = form.stiffness(&d);
        for i in 0..6 {
            for j in 0..6 {
                assert!((k[i][j] - k2[i][j]).abs() < 1e-12 * k[i][i].abs(), "({i}, {j})");
            }
        }
    }

    /// The chords of a triangle integrate r·(polynomial of degree ≤ 2 in z) exactly.
    #[test]
    fn chords_cover_the_triangle() {
        let p = [[1.0, 0.0], [2.0, 0.2], [1.2, 1.0]];
        let mut c = Vec::new();
        chords(p, 4, &mut c);
        let area: f64 = c.iter().map(|c| c.weight * c.length).sum();
        let shape = Shape::new(p);
        let centroid_r = (p[0][0] + p[1][0] + p[2][0]) / 3.0;
        assert!((area - 2.0 * PI * centroid_r * shape.area).abs() < 1e-12);
        // Shape functions at the chord ends sum to one, and the chord's top end is on the
        // triangle.
        for ch in &c {
            assert!((ch.n_lo.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(ch.dn.iter().sum::<f64>().abs() < 1e-12);
            assert!(
                ch.n_lo
                    .iter()
                    .zip(&ch.dn)
                    .all(|(n, d)| n + d > -1e-12 && *n > -1e-12)
            );
        }
    }
}
