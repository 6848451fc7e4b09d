//! Numerical building blocks with no physics in them: root finding, quadrature, curve tracing
//! (all roots on an interval, turning points, the path along equilibrium branches), nonlinear
//! least squares (Levenberg-Marquardt), cubic splines for tabulated data, FFTs, special
//! functions (Struve H₀, H₁), and the stable Newton minimiser of non-convex energies with its
//! sparse linear algebra (conjugate gradients with a definiteness certificate, envelope Cholesky
//! factorisations of small blocks, sparse Cholesky factorisations of whole Hessians).
//!
//! Models call these; they know nothing about contact mechanics, figures or front ends.

pub mod curve;
pub mod elliptic;
pub mod envelope;
pub mod fft;
pub mod least_squares;
pub mod loading;
pub mod newton;
pub mod pcg;
pub mod quadrature;
pub mod roots;
pub mod sparse_llt;
pub mod special;
pub mod spline;
