//! Numerical building blocks with no physics in them: root finding, quadrature.
//!
//! Models call these; they know nothing about contact mechanics, figures or front ends.

pub mod quadrature;
pub mod roots;
