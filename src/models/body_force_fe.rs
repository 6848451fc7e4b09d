//! The finite-element model of chapter 4 (sections 4.2-4.5): an axisymmetric linear elastic tip
//! with the Lennard-Jones body force (4.15) of a rigid flat substrate, the dissertation's own
//! model. [`mesh`] builds the graded triangular mesh, [`element`] the linear triangle (its
//! stiffness and the exact-in-z integration of the body force), [`assembly`] the sparse
//! stiffness, [`tip`] the total energy of
//! the tip for the stable minimiser and the cycle driver of the surface model
//! ([`crate::models::axisymmetric::cycle`]).

pub mod assembly;
pub mod body;
pub mod element;
pub mod mesh;
pub mod tip;
