//! The axisymmetric surface (boundary-element) model of an elastic tip against a rigid flat
//! substrate with the Lennard-Jones interaction of chapter 4.
//!
//! For a rigid flat substrate the body force (4.15) integrated through a material column of the
//! tip is exactly the plate traction (4.19) (ERRATA: the consistent 3-9 form), so a model of the
//! tip's surface carries the whole interaction; it differs from the finite-element model of the
//! dissertation only through the strain of the surface layer. [`kernel`] holds the half-space's
//! ring influence kernel and the ring grid, [`tip`] the energy of the tip as a function of the
//! ring displacements, with its gradient and Hessian for the stable minimiser.

pub mod cycle;
pub mod kernel;
pub mod tip;
