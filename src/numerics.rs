//! Numerical building blocks with no physics in them: root finding, quadrature, curve tracing
//! (all roots on an interval, turning points, the path along equilibrium branches).
//!
//! Models call these; they know nothing about contact mechanics, figures or front ends.

pub mod curve;
pub mod quadrature;
pub mod roots;
