//! Parameter groups: the physical parameters that several scenes share, each declared once
//! with its name, unit, default, valid range and help.
//!
//! A scene takes a group whole (`group tip: ElasticTip { radius: 10.0e-6 };` in
//! [`crate::scene_params!`], with its own defaults in braces) or one parameter of it
//! (`from Interaction: sigma: f64 = 1.5e-9;`); either way the parameter keeps its flat name in
//! `--set`, presets, `--describe`, the form and the JSON, and its unit, range and help come
//! from here. A range is one promise for every scene: each value in it gives finite results or
//! a one-line error naming the parameter (the edge tests in `tests/it/edges.rs`). The ranges
//! are those every scene that shares the parameter was tested at (where scenes had drifted
//! apart, the narrower range).
//!
//! The registry test `tests/it/registry.rs` checks that no two scenes give one name different
//! units, ranges or help, except the declared exceptions listed there with their reasons.

use crate::params::Range;

crate::param_group! {
    /// An elastic tip of radius of curvature R (chapter 4): its plane-strain modulus is
    /// E* = E/(1 − ν²) ([`ElasticTip::plane_strain_modulus`]). Defaults: Fig. 4.5's tip.
    pub struct ElasticTip {
        /// Radius of curvature R of the tip [m].
        radius: f64 = 5.0e-6, unit = "m", range = Range::between(1.0e-7, 1.0e-3);
        /// Young's modulus E of the tip [Pa].
        youngs_modulus: f64 = 4.4e6, unit = "Pa", range = Range::between(1.0e4, 1.0e11);
        /// Poisson's ratio ν of the tip.
        poisson_ratio: f64 = 0.25, unit = "", range = Range::between(0.0, 0.49);
    }
}

impl ElasticTip {
    /// The plane-strain modulus E* = E/(1 − ν²) [Pa] (the modulus of (4.2)-(4.7b) against a
    /// rigid substrate).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.youngs_modulus / (1.0 - self.poisson_ratio * self.poisson_ratio)
    }
}

crate::param_group! {
    /// The Lennard-Jones interaction (4.1) between the tip and the substrate, with its Hamaker
    /// constant (4.7a). Defaults: Fig. 4.5's.
    pub struct Interaction {
        /// C6 of the potential (4.1).
        c6: f64 = 3.0, unit = "", range = Range::between(0.1, 100.0);
        /// C12 of the potential (4.1).
        c12: f64 = 1.0, unit = "", range = Range::between(0.01, 100.0);
        /// Characteristic distance σ of the potential (4.1) [m].
        sigma: f64 = 1.0e-9, unit = "m", range = Range::between(1.0e-11, 1.0e-7);
        /// Hamaker constant A_H [J].
        hamaker: f64 = 2.0e-21, unit = "J", range = Range::between(1.0e-23, 1.0e-17);
    }
}

impl Interaction {
    /// The potential of these parameters.
    ///
    /// # Errors
    /// [`crate::error::Error::InvalidParameter`] naming the interaction parameter.
    pub fn lennard_jones(&self) -> crate::error::Result<crate::models::lennard_jones::LennardJones> {
        crate::models::lennard_jones::LennardJones::new(&crate::models::lennard_jones::LennardJonesParams {
            c6: self.c6,
            c12: self.c12,
            sigma: self.sigma,
            hamaker: self.hamaker,
        })
    }
}

crate::param_group! {
    /// The waviness (4.10) of a tip: a sinusoid of amplitude A and wavelength λ on the
    /// paraboloid. Defaults: Fig. 4.7's.
    pub struct Waviness {
        /// Amplitude A of the waviness (4.10) [m].
        amplitude: f64 = 1.25e-9, unit = "m", range = Range::between(0.0, 1.0e-6);
        /// Wavelength λ of the waviness (4.10) [m].
        wavelength: f64 = 1.25e-7, unit = "m", range = Range::between(1.0e-9, 1.0e-4);
    }
}

crate::param_group! {
    /// The depth path of a displacement-controlled cycle in units of the equilibrium distance
    /// ζ0 of (4.1): from `h_start` down to `h_min` and back, in steps of `step`. Defaults:
    /// Fig. 4.5's cycle.
    pub struct DepthPath {
        /// Deepest depth of the cycle in units of ζ0 (negative: pressed).
        h_min_over_zeta0: f64 = -15.0, unit = "", range = Range::between(-50.0, 0.0);
        /// Start (and end) of the cycle in units of ζ0; beyond the pull-off separation.
        h_start_over_zeta0: f64 = 12.0, unit = "", range = Range::between(1.0, 100.0);
        /// Depth step in units of ζ0.
        step_over_zeta0: f64 = 0.2, unit = "", range = Range::between(0.02, 1.0);
    }
}

impl DepthPath {
    /// The path's cross-field check: the deepest depth below the start.
    ///
    /// # Errors
    /// [`crate::error::Error::InvalidParameter`] naming `h_min_over_zeta0`.
    pub fn validate(&self) -> crate::error::Result<()> {
        crate::params::require_below(
            "h_min_over_zeta0",
            self.h_min_over_zeta0,
            "h_start_over_zeta0",
            self.h_start_over_zeta0,
        )
    }
}

crate::param_group! {
    /// The discretisation of the axisymmetric surface model (section 4.2): ring width and
    /// Gauss points of the interaction energy.
    pub struct SurfaceModel {
        /// Ring width (surface model) or width of the surface elements (finite elements) in units of b = ζ0²E*/w.
        ring_width: f64 = 0.25, unit = "", range = Range::between(0.02, 2.0);
        /// Gauss points per interval of the interaction energy (per chord interval in r near the substrate for finite elements).
        quadrature_points: usize = 4, unit = "", range = Range::between(1.0, 16.0);
    }
}

crate::param_group! {
    /// The contact criterion of section 4.2.2: a point is in contact where its gap is below
    /// the threshold (the dissertation: σ).
    pub struct ContactCriterion {
        /// Contact threshold of the gap (section 4.2.2: σ) [m].
        contact_gap: f64 = 1.0e-9, unit = "m", range = Range::between(1.0e-11, 1.0e-7);
    }
}

crate::param_group! {
    /// The finite-element mesh of a tip when a scene's `model` is `fe`: bulk grading and the
    /// size of the modelled tip.
    pub struct FeMesh {
        /// Growth of the finite-element size with the distance from the contact zone (model = fe).
        fe_grading: f64 = 0.15, unit = "", range = Range::between(0.05, 1.0);
        /// Radius and height of the finite-element tip in units of R (model = fe).
        fe_size_over_radius: f64 = 20.0, unit = "", range = Range::between(2.0, 1000.0);
    }
}

impl FeMesh {
    /// The quick form of the mesh: a coarse bulk (grading at least 0.4) in a tip of at most
    /// 4 R.
    pub fn quick(&mut self) {
        self.fe_grading = self.fe_grading.max(0.4);
        self.fe_size_over_radius = self.fe_size_over_radius.min(4.0);
    }
}

crate::param_group! {
    /// The bulk of a finite-element tip in the scenes that run the finite-element model alone
    /// or beside the surface model (Figs. 4.4-4.6): how fast its elements grow away from the
    /// contact zone and how large the modelled tip is. The mesh of
    /// [`crate::models::body_force_fe`] takes any positive grading and any tip wider than its
    /// fine zone, and refuses one of too many elements with a one-line error; the tip's size
    /// reaches 1000 R as [`FeMesh`]'s does (fig4.4's Hertz check wants 128 R by default).
    pub struct FeBulk {
        /// Growth of the element size with the distance from the contact zone.
        grading: f64 = 0.15, unit = "", range = Range::between(0.05, 1.0);
        /// Radius and height of the finite-element tip in units of R.
        size_over_radius: f64 = 20.0, unit = "", range = Range::between(2.0, 1000.0);
    }
}

impl FeBulk {
    /// The quick form of the bulk: a grading of at least `grading`, a tip of at most
    /// `size_over_radius` R.
    pub fn coarsen(&mut self, grading: f64, size_over_radius: f64) {
        self.grading = self.grading.max(grading);
        self.size_over_radius = self.size_over_radius.min(size_over_radius);
    }
}

crate::param_group! {
    /// The surface samples of an uncoupled spring array (section 5.5.2): N x N springs on
    /// `samples` Gaussian surfaces of seeds `seed .. seed + samples`, the same surfaces at every
    /// point of a study (common random numbers). Defaults: Figs. 5.7-5.9's.
    pub struct SurfaceSamples {
        /// Springs along each side (N = M).
        springs: usize = 256, unit = "", range = Range::between(2.0, 4096.0);
        /// Surface samples averaged.
        samples: usize = 15, unit = "", range = Range::between(1.0, 1000.0);
        /// Seed of the first sample.
        seed: u64 = 1, unit = "", range = Range::non_negative();
    }
}

impl SurfaceSamples {
    /// The quick form: at most 32 x 32 springs on two surfaces.
    pub fn quick(&mut self) {
        self.springs = self.springs.min(32);
        self.samples = self.samples.min(2);
    }

    /// The number of springs MN = N².
    pub fn count(&self) -> usize {
        self.springs * self.springs
    }
}

crate::param_group! {
    /// The displacement-controlled cycle of a spring array over a surface of roughness σ̄_rms
    /// (sections 5.5-5.6): `steps` displacement steps per phase, from `end_sigmas` σ̄_rms beyond
    /// the pull-off displacement down to `depth_sigmas` σ̄_rms below the pull-in displacement and
    /// back. Defaults: Figs. 5.7-5.11's.
    pub struct ArrayCycle {
        /// Displacement steps per phase.
        steps: usize = 1000, unit = "", range = Range::between(10.0, 1.0e6);
        /// Loading goes this many σ_rms below the pull-in displacement.
        depth_sigmas: f64 = 4.0, unit = "", range = Range::positive();
        /// Unloading ends this many σ_rms beyond the pull-off displacement.
        end_sigmas: f64 = 5.0, unit = "", range = Range::positive();
    }
}

impl ArrayCycle {
    /// The quick form: at most 100 steps per phase.
    pub fn quick(&mut self) {
        self.steps = self.steps.min(100);
    }
}

crate::param_group! {
    /// One Gaussian rough surface under a spring array (section 5.6): normalized roughness
    /// σ̄_rms = σ_rms/σ and correlation length L̄_c = L_c/(100 µm). Defaults: Fig. 5.10's.
    pub struct ArraySurface {
        /// Normalized roughness σ̄_rms.
        roughness: f64 = 100.0, unit = "", range = Range::positive();
        /// Normalized correlation length L̄_c.
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
    }
}
