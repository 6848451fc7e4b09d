//! Numerical building blocks with no physics in them: root finding, quadrature, curve tracing
//! (all roots on an interval, turning points, the path along equilibrium branches), and
//! nonlinear least squares (Levenberg-Marquardt), and cubic splines for tabulated data.
//!
//! Models call these; they know nothing about contact mechanics, figures or front ends.

pub mod curve;
pub mod envelope;
pub mod fft;
pub mod least_squares;
pub mod newton;
pub mod pcg;
pub mod quadrature;
pub mod roots;
pub mod spline;
