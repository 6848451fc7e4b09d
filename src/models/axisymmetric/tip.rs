//! The axisymmetric elastic tip against a rigid flat substrate with the Lennard-Jones surface
//! interaction: the surface (boundary-element) model of chapter 4.
//!
//! The tip is an elastic half-space with the profile (4.10),
//!
//! ```text
//! z_s(r) = δ + r²/(2R) + A [1 − cos(2π r/λ)],
//! ```
//!
//! δ the separation of the undeformed apex from the substrate (z0 of (4.10)) and f(r) the rest.
//! The surface displaces by u(r) towards the substrate, so the gap is g = δ + f(r) − u(r). For
//! a rigid flat
//! substrate the Lennard-Jones body force (4.15) integrated through a material column of the
//! tip is the plate traction (ERRATA on (4.19)), so the interaction energy per unit area of the
//! surface is the plate energy (4.4),
//!
//! ```text
//! φ(g) = −a₂/g² + a₈/g⁸,   a₂ = A_H C6/(12π),   a₈ = A_H C12 σ⁶/(360π),
//! ```
//!
//! which for C6 > 0 is φ(g) = −(4w/3)[(ζ0/g)² − ¼(ζ0/g)⁸] with φ(ζ0) = −w, Eqs. (4.6)-(4.7b).
//! The total energy of a state u (ring-wise constant tractions, displacements at the ring
//! mid-radii, [`RingGrid`]) is
//!
//! ```text
//! Π(u) = ½ uᵀ K u + Σ_i A_i φ(g_i),   g_i = δ + f(r_i) − u_i,
//! ```
//!
//! with K the ring stiffness of the half-space. Its gradient K u − A φ'(g) vanishes at an
//! equilibrium, and its Hessian K + diag(A_i φ''(g_i)) decides stability. The force on the tip
//! (compressive positive) is P = −Σ A_i φ'(g_i).
//!
//! Scaling: normal lengths in ζ0 (σ when C6 = 0), tractions in p_ref = w/ζ0 (the repulsive
//! scale a₈/σ⁹ when C6 = 0), radial lengths in b = ζ0 E*/p_ref = ζ0² E*/w, the width of the
//! zone over which the adhesive traction acts at a contact edge. Then E* = 1 and every term is
//! of order one.

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::models::axisymmetric::kernel::RingGrid;
use crate::models::lennard_jones::{LennardJones, LennardJonesParams};
use crate::numerics::loading::Controlled;
use crate::numerics::newton::Energy;
use crate::numerics::pcg::dot_lanes;

/// Largest number of rings a tip may have. A cycle costs about 3 000 dense factorisations of
/// N³/3 flops: 1.6 s of one core at 354 rings (Fig. 4.5), 8.9 s at 685, 31 s at 1 055; beyond
/// this, a cycle would take minutes and the grid is refused, naming `ring_width`.
pub const MAX_RINGS: usize = 1000;

/// Parameters of the surface model of a tip (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipParams {
    /// Radius of curvature R of the apex [m].
    pub radius: f64,
    /// Plane-strain modulus E* = E/(1 − ν²) [Pa].
    pub modulus: f64,
    /// C6 of the potential (4.1) [-]; 0 switches the attraction off.
    pub c6: f64,
    /// C12 of the potential (4.1) [-].
    pub c12: f64,
    /// Characteristic distance σ of the potential (4.1) [m].
    pub sigma: f64,
    /// Hamaker constant A_H [J].
    pub hamaker: f64,
    /// Amplitude A of the waviness (4.10) [m]; 0 for a smooth tip.
    pub amplitude: f64,
    /// Wavelength λ of the waviness (4.10) [m].
    pub wavelength: f64,
    /// Ring width h in units of b = ζ0² E*/w [-].
    pub ring_width: f64,
    /// Radius of the zone of uniform rings [m] (cover the largest contact radius and the
    /// interaction zone beyond it).
    pub fine_radius: f64,
    /// Growth factor of the ring widths outside the fine zone [-].
    pub growth: f64,
    /// Gauss points per interval between ring mid-radii for the interaction energy [-]: the
    /// displacement is interpolated linearly between mid-radii, so the energy varies smoothly
    /// as a contact edge crosses a ring (1 point per interval is collocation-like and lets the
    /// edge hop from ring to ring).
    pub quadrature_points: usize,
    /// Undeformed gap up to which the rings extend [in units of ζ0]: beyond it the traction is
    /// below (ζ0/g)³ of its scale and is neglected.
    pub reach: f64,
}

impl TipParams {
    /// A fine zone that covers cycles to the depth `h_min` (negative: pressed): 1.15 times the
    /// JKR contact radius at |h_min| plus 10 b (the interaction zone beyond the contact edge),
    /// with the JKR radius from a²/R − √(2πwa/E*) = |h_min| (bisection on a) [m].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming an interaction parameter.
    pub fn fine_radius_for_depth(&self, h_min: f64) -> Result<f64> {
        let lj = LennardJones::new(&LennardJonesParams {
            c6: self.c6,
            c12: self.c12,
            sigma: self.sigma,
            hamaker: self.hamaker,
        })?;
        let (radius, modulus) = (self.radius, self.modulus);
        let w = lj.work_of_adhesion();
        let depth = |a: f64| a * a / radius - (2.0 * PI * w * a / modulus).sqrt();
        let (mut lo, mut hi) = (
            0.0,
            (radius * h_min.abs()).sqrt() + (4.0 * PI * w * radius * radius / modulus).cbrt(),
        );
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if depth(mid) < h_min.abs() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let b = lj.zeta0() * lj.zeta0() * modulus / w;
        Ok(1.15 * hi + 10.0 * b)
    }
}

impl Default for TipParams {
    /// The smooth tip of Fig. 4.5 (R = 5 µm, E = 4.4 MPa, ν = 0.25, C6 = 3, C12 = 1, σ = 1 nm,
    /// A_H = 2e-21 J) on the grid that keeps the contact edge from hopping (rings of 0.25 b, 4
    /// Gauss points per interval) over a fine zone of 250 nm (cycles to a few ζ0 deep).
    fn default() -> Self {
        Self {
            radius: 5e-6,
            modulus: 4.4e6 / (1.0 - 0.25 * 0.25),
            c6: 3.0,
            c12: 1.0,
            sigma: 1e-9,
            hamaker: 2e-21,
            amplitude: 0.0,
            wavelength: 1.25e-7,
            ring_width: 0.25,
            fine_radius: 2.5e-7,
            growth: 1.1,
            quadrature_points: 4,
            reach: 30.0,
        }
    }
}

/// The scales of the non-dimensional variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipScales {
    /// Normal length unit: ζ0 (4.6), or σ when C6 = 0 [m].
    pub length: f64,
    /// Traction unit p_ref: w/ζ0, or a₈/σ⁹ when C6 = 0 [Pa].
    pub traction: f64,
    /// Radial length unit b = length · E*/p_ref [m].
    pub radial: f64,
    /// Work of adhesion w (4.7b) [J/m²] (0 when C6 = 0).
    pub work_of_adhesion: f64,
}

impl TipScales {
    /// The scales of an interaction `law` and a plane-strain modulus E* [Pa].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `modulus` where the scales are not finite.
    pub fn new(law: &LennardJones, modulus: f64) -> Result<Self> {
        let p = law.params();
        let w = law.work_of_adhesion();
        let (length, traction) = if p.c6 > 0.0 {
            (law.zeta0(), w / law.zeta0())
        } else {
            // The repulsive term's own scale, C12 A_H/(360πσ³).
            (p.sigma, law.energy_scale() * p.c12 / (360.0 * p.sigma))
        };
        let radial = length * modulus / traction;
        if !(radial.is_finite() && radial > 0.0 && traction.is_finite()) {
            return Err(Error::invalid(
                "modulus",
                modulus,
                "gives a non-finite length scale with these interaction parameters",
            ));
        }
        Ok(Self {
            length,
            traction,
            radial,
            work_of_adhesion: w,
        })
    }

    /// Force unit p_ref b² [N].
    pub fn force(&self) -> f64 {
        self.traction * self.radial * self.radial
    }

    /// Energy unit p_ref · length · b² [J].
    pub fn energy(&self) -> f64 {
        self.force() * self.length
    }
}

/// A validated tip with its ring grid and stiffness.
#[derive(Debug, Clone)]
pub struct Tip {
    params: TipParams,
    scales: TipScales,
    grid: RingGrid,
    /// Quadrature points of the interaction (see [`QuadPoint`]).
    points: Vec<QuadPoint>,
    /// Non-dimensional profile f(r_i) (in the normal unit).
    profile: Vec<f64>,
    /// Stiffness K (row-major, non-dimensional).
    stiffness: Vec<f64>,
    /// The plate interaction (4.4)-(4.5) in SI units; the non-dimensional φ̂ is read from it.
    law: LennardJones,
    /// Largest relative asymmetry of the collocation flexibility.
    asymmetry: f64,
}

impl Tip {
    /// Validate the parameters, build the grid and the stiffness.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the parameter; grid errors.
    pub fn new(p: &TipParams) -> Result<Self> {
        let positive = Error::require_positive;
        positive("radius", p.radius)?;
        positive("modulus", p.modulus)?;
        positive("wavelength", p.wavelength)?;
        positive("ring_width", p.ring_width)?;
        positive("fine_radius", p.fine_radius)?;
        positive("reach", p.reach)?;
        if !(p.amplitude >= 0.0 && p.amplitude.is_finite()) {
            return Err(Error::invalid(
                "amplitude",
                p.amplitude,
                "must be zero or positive",
            ));
        }
        // Validates C6, C12, σ, A_H, naming them.
        let law = LennardJones::new(&LennardJonesParams {
            c6: p.c6,
            c12: p.c12,
            sigma: p.sigma,
            hamaker: p.hamaker,
        })?;
        let scales = TipScales::new(&law, p.modulus)?;
        let (length, radial) = (scales.length, scales.radial);
        // The rings reach to where the undeformed gap is `reach` normal units.
        let r_reach = (2.0 * p.radius * p.reach * length).sqrt();
        let r_max = r_reach.max(p.fine_radius * 1.5);
        // The grid is built in radial units b. Its stiffness (E* = 1) maps displacements in b
        // to forces in E* b²; with u in the normal unit and forces in p_ref b², the factor is
        // E* · length / p_ref = b, i.e. one: K̂ is the grid's stiffness as it is.
        let grid = RingGrid::new(
            p.ring_width,
            (p.fine_radius / radial).max(p.ring_width),
            p.growth,
            r_max / radial,
            MAX_RINGS,
        )?;
        let (stiffness, asymmetry) = grid.stiffness()?;
        let shape = |rb: f64| {
            let r = rb * radial;
            let wavy = p.amplitude * (1.0 - (2.0 * PI * r / p.wavelength).cos());
            (r * r / (2.0 * p.radius) + wavy) / length
        };
        let profile = grid.nodes.iter().map(|&rb| shape(rb)).collect();
        let points = quadrature_points(&grid, p.quadrature_points, shape)?;
        Ok(Self {
            params: *p,
            scales,
            grid,
            points,
            profile,
            stiffness,
            law,
            asymmetry,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &TipParams {
        &self.params
    }

    /// The scales of the non-dimensional variables.
    pub fn scales(&self) -> &TipScales {
        &self.scales
    }

    /// The ring grid (radii in the radial unit b).
    pub fn grid(&self) -> &RingGrid {
        &self.grid
    }

    /// Ring mid-radii [m].
    pub fn radii(&self) -> Vec<f64> {
        self.grid.nodes.iter().map(|r| r * self.scales.radial).collect()
    }

    /// Number of unknowns (rings).
    pub fn len(&self) -> usize {
        self.profile.len()
    }

    /// Whether the tip has no ring (never, after [`Tip::new`]).
    pub fn is_empty(&self) -> bool {
        self.profile.is_empty()
    }

    /// Largest relative asymmetry of the collocation flexibility (a discretisation measure).
    pub fn asymmetry(&self) -> f64 {
        self.asymmetry
    }

    /// Plate energy per unit area φ̂(ĝ) = φ(ĝ ℓ)/(p_ref ℓ), Eq. (4.4), ℓ the normal unit.
    pub fn phi(&self, g: f64) -> f64 {
        let s = &self.scales;
        self.law.plate_energy(g * s.length) / (s.traction * s.length)
    }

    /// φ̂'(ĝ): the traction over p_ref, positive when attractive, Eqs. (4.5), (4.19) (ERRATA).
    pub fn phi_prime(&self, g: f64) -> f64 {
        let s = &self.scales;
        self.law.traction(g * s.length) / s.traction
    }

    /// φ̂''(ĝ): the traction's slope in normal units.
    pub fn phi_second(&self, g: f64) -> f64 {
        let s = &self.scales;
        self.law.traction_slope(g * s.length) * s.length / s.traction
    }

    /// Gap at ring i for approach `delta` (normal units).
    fn gap(&self, delta: f64, u: &[f64], i: usize) -> f64 {
        delta + self.profile[i] - u[i]
    }

    /// Gaps at the ring mid-radii (normal units).
    pub fn gaps(&self, delta: f64, u: &[f64]) -> Vec<f64> {
        (0..self.len()).map(|i| self.gap(delta, u, i)).collect()
    }

    /// Gap at a quadrature point.
    fn point_gap(&self, delta: f64, u: &[f64], q: &QuadPoint) -> f64 {
        delta + q.profile - q.shape_a * u[q.a] - q.shape_b * u[q.b]
    }

    /// Force on the tip P = −∫ φ'(g) dA, compressive positive [N].
    pub fn force(&self, delta: f64, u: &[f64]) -> f64 {
        let p: f64 = self
            .points
            .iter()
            .map(|q| -q.weight * self.phi_prime(self.point_gap(delta, u, q)))
            .sum();
        p * self.scales.force()
    }

    /// Traction on the tip at each ring, compressive positive [Pa].
    pub fn tractions(&self, delta: f64, u: &[f64]) -> Vec<f64> {
        (0..self.len())
            .map(|i| -self.phi_prime(self.gap(delta, u, i)) * self.scales.traction)
            .collect()
    }

    /// Indentation depth h = δ − ζ0 [m] of approach `delta` (normal units): h < 0 when the
    /// apex is pressed closer than the equilibrium distance, the sign convention of (3.3).
    pub fn depth(&self, delta: f64) -> f64 {
        (delta - 1.0) * self.scales.length
    }

    /// Approach δ̂ (normal units) of indentation depth `h` [m], the inverse of [`Tip::depth`].
    pub fn approach(&self, h: f64) -> f64 {
        h / self.scales.length + 1.0
    }

    /// The contact set: the radial intervals [m] where the gap is below `threshold` [m] (the
    /// definition of section 4.2.2 with threshold σ), with edges interpolated linearly between
    /// ring mid-radii. Several intervals mean a multiply connected (annular) contact.
    pub fn contact(&self, delta: f64, u: &[f64], threshold: f64) -> ContactSet {
        ContactSet::from_gaps(
            &self.radii(),
            &self.gaps(delta, u),
            threshold / self.scales.length,
        )
    }

    /// The energy at approach `delta` (normal units), as an [`Energy`] of the ring
    /// displacements.
    pub fn energy_at(&self, delta: f64) -> TipEnergy<'_> {
        TipEnergy { tip: self, delta }
    }
}

/// A quadrature point of the interaction energy ∫ φ(g) dA: the displacement there is
/// interpolated linearly between the ring mid-radii `a` and `b` (constant inside the first
/// mid-radius, where the surface is flat by symmetry, and beyond the last).
#[derive(Debug, Clone, Copy, PartialEq)]
struct QuadPoint {
    /// Weight: 2πr × the Gauss weight × the interval's length (in b²).
    weight: f64,
    /// Profile f(r) (normal units).
    profile: f64,
    a: usize,
    b: usize,
    shape_a: f64,
    shape_b: f64,
}

/// The quadrature points of a grid: `n` Gauss points on each interval between mid-radii, on
/// [0, r_0] and on [r_{N−1}, e_N].
fn quadrature_points(grid: &RingGrid, n: usize, shape: impl Fn(f64) -> f64) -> Result<Vec<QuadPoint>> {
    if n == 0 || n > 16 {
        return Err(Error::invalid("quadrature_points", n, "must be between 1 and 16"));
    }
    let (x, w) = crate::numerics::quadrature::gauss_legendre(n);
    let nodes = &grid.nodes;
    let last = nodes.len() - 1;
    let outer = *grid.edges.last().unwrap_or(&nodes[last]);
    let mut intervals = vec![(0.0, nodes[0], 0, 0)];
    intervals.extend((0..last).map(|i| (nodes[i], nodes[i + 1], i, i + 1)));
    intervals.push((nodes[last], outer, last, last));
    let mut out = Vec::with_capacity(intervals.len() * n);
    for (lo, hi, a, b) in intervals {
        let half = 0.5 * (hi - lo);
        for (xi, wi) in x.iter().zip(&w) {
            let r = lo + half * (xi + 1.0);
            let t = if a == b { 0.0 } else { (r - lo) / (hi - lo) };
            out.push(QuadPoint {
                weight: 2.0 * PI * r * wi * half,
                profile: shape(r),
                a,
                b,
                shape_a: if a == b { 1.0 } else { 1.0 - t },
                shape_b: if a == b { 0.0 } else { t },
            });
        }
    }
    Ok(out)
}

/// How far a point at gap `gap` must start moved away from the substrate when the next step
/// closes gaps by `closing`, so that its gap shrinks to no less than half: 0 where the step
/// leaves more than half (shared by the surface and the finite-element models' starts).
pub fn start_shift(gap: f64, closing: f64) -> f64 {
    (0.5 * gap - (gap - closing)).max(0.0)
}

/// The contact set of a state.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactSet {
    /// Radial intervals (inner, outer) [m], increasing; the first starts at 0 for a contact
    /// that includes the apex.
    pub intervals: Vec<(f64, f64)>,
}

impl ContactSet {
    /// The intervals where the gap `g` (at increasing radii `r` [m]) is below `threshold` (in
    /// the unit of `g`), with edges interpolated linearly between the radii (section 4.2.2).
    pub fn from_gaps(r: &[f64], g: &[f64], threshold: f64) -> Self {
        let t = threshold;
        let mut intervals = Vec::new();
        let mut start: Option<f64> = None;
        for i in 0..g.len() {
            let inside = g[i] < t;
            let edge = |k: usize| {
                // Linear crossing between nodes k-1 and k.
                let (g0, g1) = (g[k - 1], g[k]);
                r[k - 1] + (t - g0) / (g1 - g0) * (r[k] - r[k - 1])
            };
            match (inside, start) {
                (true, None) => start = Some(if i == 0 { 0.0 } else { edge(i) }),
                (false, Some(s)) => {
                    intervals.push((s, edge(i)));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = start {
            intervals.push((s, *r.last().unwrap_or(&s)));
        }
        Self { intervals }
    }

    /// Contact radius a: the outer edge of the outermost interval [m] (0 out of contact).
    pub fn radius(&self) -> f64 {
        self.intervals.last().map_or(0.0, |i| i.1)
    }

    /// Real contact area Σ π(r_out² − r_in²) [m²].
    pub fn area(&self) -> f64 {
        self.intervals.iter().map(|(a, b)| PI * (b * b - a * a)).sum()
    }

    /// Whether the contact is multiply connected (more than one interval).
    pub fn is_multiply_connected(&self) -> bool {
        self.intervals.len() > 1
    }
}

/// The total energy of a [`Tip`] at one approach.
#[derive(Debug, Clone, Copy)]
pub struct TipEnergy<'a> {
    tip: &'a Tip,
    delta: f64,
}

impl Energy for TipEnergy<'_> {
    fn dim(&self) -> usize {
        self.tip.len()
    }

    fn energy(&self, u: &[f64]) -> f64 {
        let t = self.tip;
        let n = t.len();
        let mut elastic = 0.0;
        for i in 0..n {
            let row = &t.stiffness[i * n..(i + 1) * n];
            elastic += u[i] * dot_lanes(row, u);
        }
        let mut adhesive = 0.0;
        for q in &t.points {
            let g = t.point_gap(self.delta, u, q);
            if g <= 0.0 {
                return f64::INFINITY;
            }
            adhesive += q.weight * t.phi(g);
        }
        0.5 * elastic + adhesive
    }

    fn gradient(&self, u: &[f64], g: &mut [f64]) {
        let t = self.tip;
        let n = t.len();
        for (gi, row) in g.iter_mut().zip(t.stiffness.chunks_exact(n)) {
            *gi = dot_lanes(row, u);
        }
        for q in &t.points {
            let f = q.weight * t.phi_prime(t.point_gap(self.delta, u, q));
            g[q.a] -= f * q.shape_a;
            g[q.b] -= f * q.shape_b;
        }
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let n = self.tip.len();
        (0..n).flat_map(|i| (0..=i).map(move |j| (i, j))).collect()
    }

    fn hessian_values(&self, u: &[f64], values: &mut [f64]) {
        let t = self.tip;
        let n = t.len();
        let mut k = 0;
        for i in 0..n {
            values[k..k + i + 1].copy_from_slice(&t.stiffness[i * n..i * n + i + 1]);
            k += i + 1;
        }
        // Entry (i, j ≤ i) of the lower triangle sits at i(i+1)/2 + j.
        let at = |i: usize, j: usize| i * (i + 1) / 2 + j;
        for q in &t.points {
            let c = q.weight * t.phi_second(t.point_gap(self.delta, u, q));
            values[at(q.a, q.a)] += c * q.shape_a * q.shape_a;
            values[at(q.b, q.b)] += c * q.shape_b * q.shape_b;
            if q.a != q.b {
                let (hi, lo) = if q.a > q.b { (q.a, q.b) } else { (q.b, q.a) };
                values[at(hi, lo)] += c * q.shape_a * q.shape_b;
            }
        }
    }
}

impl Controlled for Tip {
    type At<'a> = TipEnergy<'a>;

    fn at(&self, lambda: f64) -> TipEnergy<'_> {
        self.energy_at(lambda)
    }

    /// Where pressing from `from` to `to` would close a gap to less than half its value (a
    /// step larger than the gap at the repulsive wall, outside the energy's domain when it
    /// closes it altogether), the ring starts moved with the tip by the difference.
    fn prepare_start(&self, from: f64, to: f64, u: &mut [f64]) {
        let closing = from - to;
        if closing <= 0.0 {
            return;
        }
        for (i, ui) in u.iter_mut().enumerate() {
            *ui -= start_shift(from + self.profile[i] - *ui, closing);
        }
    }

    /// ∂g/∂δ: the gap g = δ + f − u grows with δ, so the gradient's adhesive part changes at
    /// −Σ_q w_q φ''(g_q) N_i(q) (the elastic part does not depend on δ).
    fn gradient_rate(&self, delta: f64, u: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        for q in &self.points {
            let c = q.weight * self.phi_second(self.point_gap(delta, u, q));
            out[q.a] -= c * q.shape_a;
            out[q.b] -= c * q.shape_b;
        }
        true
    }

    /// The largest change of a ring displacement in units of half the interaction range.
    fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
        before
            .iter()
            .zip(after)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / 0.5
    }
}
