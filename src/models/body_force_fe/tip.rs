//! The finite-element model of the tip (sections 4.2.2, 4.4): axisymmetric linear elasticity
//! (4.11)-(4.14) of a tip of radius r0 and height h0 with the Lennard-Jones body force (4.15) of
//! the rigid substrate, its top held (u_r = 0, u_z = 0) while the substrate approaches. The
//! profile (4.10) either shapes the bottom face (the body B0 of (4.8),
//! [`FeGeometry::Profiled`]) or enters the height above the substrate of a flat-bottomed
//! cylinder ([`FeGeometry::HalfSpace`], the default: the idealisation of the half-space
//! theories the chapter compares with, which converges as the tip grows; a paraboloidal body's
//! compliance grows like ln h0, so B0's results depend on its unstated size).
//!
//! The total energy of the nodal displacements u (linear triangles, [`Mesh`]) at approach δ
//! (the gap of the undeformed apex) is
//!
//! ```text
//! Π(u) = ½ uᵀ K u + ∫ ψ(δ + Z + u_z) dV,   ψ(d) = −p(d),
//! ```
//!
//! with Z the reference height above the plane of the undeformed apex (z, plus z_s(r) for the
//! half-space geometry), the weak form (4.16)-(4.18) being its stationarity; ψ'(d) = B_z(d). Its Hessian K + ∫ ψ''
//! N Nᵀ dV decides stability, and [`StableNewton`](crate::numerics::newton::StableNewton)
//! minimises it with a sparse Cholesky factorisation (symbolic analysis once). The force on the
//! tip (compressive positive) is P = −∂Π/∂δ = −∫ B_z dV, which at equilibrium is the reaction of
//! the top face. Moving the substrate by δ instead of the top by h_t is the same loading: the
//! depth is h = δ − ζ0 as in the surface model, so that both models share one axis.
//!
//! Units: lengths in ℓ (ζ0, or σ when C6 = 0), stresses in p_ref, as in
//! [`TipScales`]; energies in p_ref ℓ³.

// Element code indexes small fixed arrays (nodes, strain components) by their local numbers,
// as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use crate::error::{Error, Result};
use crate::models::axisymmetric::cycle::CycleModel;
use crate::models::axisymmetric::tip::{ContactSet, TipScales, start_shift};
use rayon::prelude::*;

use crate::models::body_force_fe::assembly::{Assembled, FIXED, assemble, held_top_dofs};
use crate::models::body_force_fe::body::{BodyForce, FAR_POINTS};
use crate::models::body_force_fe::element::{Density, StrainForm, elasticity_matrix};
use crate::models::body_force_fe::mesh::{Mesh, MeshSpec};
use crate::models::lennard_jones::{LennardJones, LennardJonesParams};
use crate::numerics::loading::{Controlled, PathOptions};
use crate::numerics::newton::{Energy, LinearSolver};

/// Rows (or elements) per parallel task of the elastic products.
const ROWS_PER_TASK: usize = 1024;

/// The body the mesh fills.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeGeometry {
    /// A cylinder r ≤ r0, 0 ≤ z ≤ h0 whose flat bottom is the reference plane of the profile:
    /// the profile (4.10) enters the height above the substrate, d = δ + z_s(r) + z + u_z
    /// (the small-slope idealisation of the half-space theories: Hertz, Maugis-Dugdale, JKR
    /// and the surface model). Converges to the half-space as r0 and h0 grow.
    HalfSpace,
    /// The body B0 of (4.8): bottom face z_s(r), top face z_s(r) + h0, d = δ + z + u_z. Near
    /// the apex it is a paraboloid, whose compliance grows like ln(h0): its results depend on
    /// the tip's size (the dissertation does not give it).
    Profiled,
}

/// Parameters of the finite-element tip (SI unless stated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeTipParams {
    /// Radius of curvature R of the apex [m].
    pub radius: f64,
    /// Young's modulus E [Pa].
    pub youngs_modulus: f64,
    /// Poisson's ratio ν [-].
    pub poisson_ratio: f64,
    /// C6 of the potential (4.1) [-]; 0 switches the attraction off.
    pub c6: f64,
    /// C12 of the potential (4.1) [-].
    pub c12: f64,
    /// Characteristic distance σ [m].
    pub sigma: f64,
    /// Hamaker constant A_H [J].
    pub hamaker: f64,
    /// Amplitude A of the waviness (4.10) [m].
    pub amplitude: f64,
    /// Wavelength λ of the waviness (4.10) [m].
    pub wavelength: f64,
    /// Element width along the surface of the fine zone, in units of b = ζ0² E*/w [-].
    pub element_width: f64,
    /// Radius of the fine zone [m].
    pub fine_radius: f64,
    /// Thickness of the first element layer at the surface, in units of ζ0 [-].
    pub first_layer: f64,
    /// Growth of the layer thickness per element width [-].
    pub layer_growth: f64,
    /// Growth of the element size with the distance from the fine zone [-].
    pub grading: f64,
    /// Radius r0 of the tip [m].
    pub r0: f64,
    /// Height h0 of the tip [m] (its top face is the profile raised by h0, Eq. (4.8)).
    pub h0: f64,
    /// Gauss points in r per chord interval of an element [-].
    pub quadrature_points: usize,
    /// Gauss points in r per chord interval of the elements far from the substrate (reference
    /// height above [`FAR_HEIGHT`] normal units), at most `quadrature_points` [-].
    ///
    /// [`FAR_HEIGHT`]: crate::models::body_force_fe::body::FAR_HEIGHT
    pub far_quadrature_points: usize,
    /// The body the mesh fills.
    pub geometry: FeGeometry,
}

impl Default for FeTipParams {
    /// The smooth tip of Fig. 4.5 (R = 5 µm, E = 4.4 MPa, ν = 0.25, C6 = 3, C12 = 1, σ = 1 nm,
    /// A_H = 2e-21 J) on a mesh of surface elements 0.25 b wide over a fine zone of 250 nm,
    /// first layers 0.1 ζ0 thick, in a tip of radius and height 4R.
    fn default() -> Self {
        Self {
            radius: 5e-6,
            youngs_modulus: 4.4e6,
            poisson_ratio: 0.25,
            c6: 3.0,
            c12: 1.0,
            sigma: 1e-9,
            hamaker: 2e-21,
            amplitude: 0.0,
            wavelength: 1.25e-7,
            element_width: 0.25,
            fine_radius: 2.5e-7,
            first_layer: 0.1,
            layer_growth: 1.3,
            grading: 0.3,
            r0: 2e-5,
            h0: 2e-5,
            quadrature_points: 4,
            far_quadrature_points: FAR_POINTS,
            geometry: FeGeometry::HalfSpace,
        }
    }
}

/// The finite-element tip: mesh, stiffness, and the chords of the body-force integral.
#[derive(Debug, Clone)]
pub struct FeTip {
    params: FeTipParams,
    scales: TipScales,
    mesh: Mesh,
    /// Free dofs (u_r, u_z) of each node, [`FIXED`] where constrained.
    dofs: Vec<[usize; 2]>,
    n: usize,
    /// Lower triangle of the Hessian's pattern.
    pattern: Vec<(usize, usize)>,
    /// Stiffness K in pattern order.
    stiffness: Vec<f64>,
    /// Elasticity matrix in stress units.
    elasticity: [[f64; 4]; 4],
    /// Strain form of each element (for the energy).
    strain_forms: Vec<StrainForm>,
    /// K as full rows (CSR) for products.
    row_start: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
    /// The body-force integral over the mesh.
    body: BodyForce,
    /// Reference height of each node above the plane of the undeformed apex (z, plus the
    /// profile for [`FeGeometry::HalfSpace`]).
    height: Vec<f64>,
}

impl FeTip {
    /// Validate the parameters, mesh the tip and assemble its stiffness.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the parameter.
    pub fn new(p: &FeTipParams) -> Result<Self> {
        let positive = Error::require_positive;
        positive("radius", p.radius)?;
        positive("youngs_modulus", p.youngs_modulus)?;
        positive("wavelength", p.wavelength)?;
        if !(p.poisson_ratio >= 0.0 && p.poisson_ratio < 0.5) {
            return Err(Error::invalid(
                "poisson_ratio",
                p.poisson_ratio,
                "must lie in [0, 0.5)",
            ));
        }
        if !(p.amplitude >= 0.0 && p.amplitude.is_finite()) {
            return Err(Error::invalid(
                "amplitude",
                p.amplitude,
                "must be zero or positive",
            ));
        }
        for (name, points) in [
            ("quadrature_points", p.quadrature_points),
            ("far_quadrature_points", p.far_quadrature_points),
        ] {
            if !(1..=16).contains(&points) {
                return Err(Error::invalid(name, points, "must be between 1 and 16"));
            }
        }
        let law = LennardJones::new(&LennardJonesParams {
            c6: p.c6,
            c12: p.c12,
            sigma: p.sigma,
            hamaker: p.hamaker,
        })?;
        let nu = p.poisson_ratio;
        let modulus = p.youngs_modulus / (1.0 - nu * nu);
        let scales = TipScales::new(&law, modulus)?;
        let (l, pref) = (scales.length, scales.traction);
        let profile = |r: f64| {
            let r = r * l;
            (r * r / (2.0 * p.radius) + p.amplitude * (1.0 - (2.0 * PI * r / p.wavelength).cos())) / l
        };
        positive("element_width", p.element_width)?;
        let spec = MeshSpec {
            r0: p.r0 / l,
            h0: p.h0 / l,
            width: p.element_width * scales.radial / l,
            fine_radius: p.fine_radius / l,
            first_layer: p.first_layer,
            layer_growth: p.layer_growth,
            grading: p.grading,
        };
        let profiled = p.geometry == FeGeometry::Profiled;
        let mesh = if profiled {
            Mesh::new(&spec, profile)?
        } else {
            Mesh::new(&spec, |_| 0.0)?
        };
        // The profile in the height above the substrate (half-space geometry).
        let offset = |r: f64| if profiled { 0.0 } else { profile(r) };
        let height = mesh.nodes.iter().map(|&[r, z]| z + offset(r)).collect();

        let (dofs, n) = held_top_dofs(&mesh);

        // Pattern and stiffness.
        let d = elasticity_matrix(p.youngs_modulus / pref, nu);
        let assembled = assemble(&mesh, &dofs, n, &d);
        let lp = law.params();
        let density = Density {
            a3: lp.hamaker * lp.c6 / (6.0 * PI) / (l.powi(3) * pref),
            a9: lp.hamaker * lp.c12 * lp.sigma.powi(6) / (45.0 * PI) / (l.powi(9) * pref),
        };
        let body = BodyForce::new(
            &mesh,
            &dofs,
            [
                p.quadrature_points,
                p.far_quadrature_points.min(p.quadrature_points),
            ],
            offset,
            |a, b| assembled.slot(a, b).unwrap_or(FIXED),
            density,
        );
        let Assembled {
            pattern,
            values: stiffness,
            forms: strain_forms,
            ..
        } = assembled;
        // Full rows for products.
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (&(r, c), &v) in pattern.iter().zip(&stiffness) {
            rows[r].push((c, v));
            if r != c {
                rows[c].push((r, v));
            }
        }
        let mut row_start = Vec::with_capacity(n + 1);
        let (mut cols, mut vals) = (Vec::new(), Vec::new());
        row_start.push(0);
        for mut row in rows {
            row.sort_by_key(|e| e.0);
            for (c, v) in row {
                cols.push(c);
                vals.push(v);
            }
            row_start.push(cols.len());
        }
        Ok(Self {
            params: *p,
            scales,
            mesh,
            dofs,
            n,
            pattern,
            stiffness,
            elasticity: d,
            strain_forms,
            row_start,
            cols,
            vals,
            body,
            height,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &FeTipParams {
        &self.params
    }

    /// The scales of the non-dimensional variables.
    pub fn scales(&self) -> &TipScales {
        &self.scales
    }

    /// The mesh (lengths in the normal unit ℓ).
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Number of unknowns (free nodal displacements).
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the model has no unknown (never, after [`FeTip::new`]).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Number of triangles.
    pub fn elements(&self) -> usize {
        self.mesh.triangles.len()
    }

    /// Displacement (u_r, u_z) of node `k` (normal units; u_z positive away from the
    /// substrate).
    pub fn node_displacement(&self, u: &[f64], k: usize) -> [f64; 2] {
        self.dofs[k].map(|i| if i == FIXED { 0.0 } else { u[i] })
    }

    /// Radii [m] and gaps (normal units) of the surface nodes, by increasing radius.
    pub fn surface_gaps(&self, delta: f64, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let l = self.scales.length;
        self.mesh
            .surface
            .iter()
            .map(|&k| {
                let r = self.mesh.nodes[k][0];
                (r * l, delta + self.height[k] + self.node_displacement(u, k)[1])
            })
            .unzip()
    }

    /// Force on the tip P = −∫ B_z dV, compressive positive [N].
    pub fn force(&self, delta: f64, u: &[f64]) -> f64 {
        -self.body.body_force(delta, u) * self.scales.traction * self.scales.length * self.scales.length
    }

    /// Number of chords of the body-force integral.
    pub fn chords(&self) -> usize {
        self.body.len()
    }

    /// Indentation depth h = δ − ζ0 [m] (as [`crate::models::axisymmetric::tip::Tip::depth`]).
    pub fn depth(&self, delta: f64) -> f64 {
        (delta - 1.0) * self.scales.length
    }

    /// Approach δ of depth `h` [m].
    pub fn approach(&self, h: f64) -> f64 {
        h / self.scales.length + 1.0
    }

    /// The contact set by the gap criterion of section 4.2.2 (gap below `threshold` [m]).
    pub fn contact(&self, delta: f64, u: &[f64], threshold: f64) -> ContactSet {
        let (r, g) = self.surface_gaps(delta, u);
        ContactSet::from_gaps(&r, &g, threshold / self.scales.length)
    }

    /// Stresses (σ_rr, σ_zz, σ_θθ, σ_rz) [Pa] at the centroid of every element, Eq. (4.12).
    pub fn centroid_stresses(&self, u: &[f64]) -> Vec<[f64; 4]> {
        let nu = self.params.poisson_ratio;
        let d = elasticity_matrix(self.params.youngs_modulus, nu);
        self.mesh
            .triangles
            .iter()
            .map(|tri| {
                let pts = tri.map(|k| self.mesh.nodes[k]);
                let shape = crate::models::body_force_fe::element::Shape::new(pts);
                let r = (pts[0][0] + pts[1][0] + pts[2][0]) / 3.0;
                let mut strain = [0.0; 4];
                for a in 0..3 {
                    let [ur, uz] = self.node_displacement(u, tri[a]);
                    let [_, dr, dz] = shape.coef[a];
                    strain[0] += dr * ur;
                    strain[1] += dz * uz;
                    strain[2] += ur / (3.0 * r);
                    strain[3] += dz * ur + dr * uz;
                }
                let mut s = [0.0; 4];
                for i in 0..4 {
                    s[i] = (0..4).map(|j| d[i][j] * strain[j]).sum();
                }
                s
            })
            .collect()
    }

    /// The energy at approach `delta` (normal units).
    pub fn energy_at(&self, delta: f64) -> FeEnergy<'_> {
        FeEnergy { tip: self, delta }
    }

    /// y = K x (rows in parallel).
    fn multiply(&self, x: &[f64], y: &mut [f64]) {
        y.par_chunks_mut(ROWS_PER_TASK)
            .enumerate()
            .for_each(|(chunk, ys)| {
                for (j, yi) in ys.iter_mut().enumerate() {
                    let i = chunk * ROWS_PER_TASK + j;
                    let (a, b) = (self.row_start[i], self.row_start[i + 1]);
                    *yi = self.cols[a..b]
                        .iter()
                        .zip(&self.vals[a..b])
                        .map(|(&c, v)| v * x[c])
                        .sum();
                }
            });
    }

    /// The strain energy ½ ∫ εᵀ D ε dV of the displacements `u` (elements in parallel chunks,
    /// summed in order).
    fn strain_energy(&self, u: &[f64]) -> f64 {
        let partial: Vec<f64> = self
            .mesh
            .triangles
            .par_chunks(ROWS_PER_TASK)
            .zip(self.strain_forms.par_chunks(ROWS_PER_TASK))
            .map(|(tris, forms)| {
                tris.iter()
                    .zip(forms)
                    .map(|(tri, form)| {
                        let [a, b, c] = tri.map(|k| self.node_displacement(u, k));
                        form.energy(&self.elasticity, [a[0], b[0], c[0]], [a[1], b[1], c[1]])
                    })
                    .sum::<f64>()
            })
            .collect();
        partial.iter().sum()
    }
}

/// The total energy of an [`FeTip`] at one approach.
#[derive(Debug, Clone, Copy)]
pub struct FeEnergy<'a> {
    tip: &'a FeTip,
    delta: f64,
}

impl Energy for FeEnergy<'_> {
    fn dim(&self) -> usize {
        self.tip.n
    }

    fn energy(&self, u: &[f64]) -> f64 {
        let body = self.tip.body.energy(self.delta, u);
        if !body.is_finite() {
            return f64::INFINITY;
        }
        self.tip.strain_energy(u) + body
    }

    fn gradient(&self, u: &[f64], g: &mut [f64]) {
        self.tip.multiply(u, g);
        self.tip.body.add_gradient(self.delta, u, g, false);
    }

    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.tip.pattern.clone()
    }

    fn hessian_values(&self, u: &[f64], values: &mut [f64]) {
        values.copy_from_slice(&self.tip.stiffness);
        self.tip.body.add_hessian(self.delta, u, values);
    }

    /// The approach: one tip's energies differ only in it.
    fn key(&self) -> Option<u64> {
        Some(self.delta.to_bits())
    }
}

impl Controlled for FeTip {
    type At<'a> = FeEnergy<'a>;

    fn at(&self, lambda: f64) -> FeEnergy<'_> {
        self.energy_at(lambda)
    }

    /// Where pressing from `from` to `to` would bring a node closer than half its height
    /// above the substrate, the node starts moved away by the difference (order preserving:
    /// no element is inverted).
    fn prepare_start(&self, from: f64, to: f64, u: &mut [f64]) {
        let closing = from - to;
        if closing <= 0.0 {
            return;
        }
        for (k, height) in self.height.iter().enumerate() {
            let i = self.dofs[k][1];
            if i == FIXED {
                continue;
            }
            u[i] += start_shift(from + height + u[i], closing);
        }
    }

    /// ∂g/∂δ = ∫ ψ''(d) N dV on the z-dofs (the elastic part does not depend on δ).
    fn gradient_rate(&self, delta: f64, u: &[f64], out: &mut [f64]) -> bool {
        out.iter_mut().for_each(|v| *v = 0.0);
        self.body.add_gradient(delta, u, out, true);
        true
    }

    /// The largest change of a surface node's u_z in units of half the interaction range.
    fn jump_measure(&self, before: &[f64], after: &[f64]) -> f64 {
        self.mesh
            .surface
            .iter()
            .map(|&k| self.dofs[k][1])
            .filter(|&i| i != FIXED)
            .map(|i| (before[i] - after[i]).abs())
            .fold(0.0, f64::max)
            / 0.5
    }
}

impl CycleModel for FeTip {
    fn unknowns(&self) -> usize {
        self.n
    }
    fn length_unit(&self) -> f64 {
        self.scales.length
    }
    fn depth(&self, delta: f64) -> f64 {
        FeTip::depth(self, delta)
    }
    fn approach(&self, h: f64) -> f64 {
        FeTip::approach(self, h)
    }
    fn force(&self, delta: f64, u: &[f64]) -> f64 {
        FeTip::force(self, delta, u)
    }
    fn contact(&self, delta: f64, u: &[f64], threshold: f64) -> ContactSet {
        FeTip::contact(self, delta, u, threshold)
    }
    fn linear_solver(&self) -> LinearSolver {
        LinearSolver::Direct
    }
    /// A jump of the finite-element tip is a long descent (the contact zips up or peels off
    /// node by node, each node crossing the steep repulsive wall in a few iterations: about
    /// 170 iterations for the pull-in of Fig. 4.5), so the landing after a located jump runs
    /// to the minimiser's own limit instead of being retried from further past the fold after
    /// the surface model's 160. (The retry of a step after a false alarm of the jump measure,
    /// a receding contact edge that outruns the tangent over a full step but not over half of
    /// it, is on for every tip.)
    fn tune_path(&self, path: &mut PathOptions) {
        path.landing_iterations = path.newton.max_iterations;
    }
    /// A load step of the finite-element tip mostly converges on the factorisation of the
    /// state before it: starting warm saves the step's first factorisation and Hessian (the
    /// path is the same: every accepted state is still factorised where it lies).
    fn warm_start(&self) -> bool {
        true
    }
    /// The first Newton steps of a load step, while the contact edge settles on the repulsive
    /// wall (largest gradient component from about 10² down to 10⁻³), take their directions
    /// from single-precision factorisations: half the memory traffic of a factorisation of
    /// about 10⁶ factor entries. The accepted states are certified in double precision as
    /// before.
    fn single_precision_directions(&self) -> bool {
        true
    }
}
