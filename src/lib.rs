//! # adhesion: a workbench for adhesive elastic contact of rough surfaces
//!
//! Implements the computational models of W. Deng, *Mechanics of Elastic Contact and Adhesion of
//! Rough Surfaces*, Ph.D. dissertation, Brown University, 2019 (cited as `[Deng19]`; equation
//! numbers in doc comments are that work's): the classical Hertz/JKR/DMT/Maugis-Dugdale theories
//! and the Fuller-Tabor rough-surface model (ch. 1, 3), JKR with machine stiffness and the fitting
//! of measured force-indentation curves (ch. 2, app. A), the Maugis-Dugdale/Nayak model of
//! depth-dependent hysteresis (ch. 3, app. B), spring-array models of fibrillar adhesion on random
//! rough surfaces (ch. 5, app. C) and peeling from wavy substrates (ch. 6).
//!
//! ## Module map (data flows down)
//!
//! | layer | module | what |
//! |---|---|---|
//! | front ends | [`tui`], [`headless`], [`cli`] | terminal UI with a background worker; exports |
//! | scenes | [`scenes`] | one scene per dissertation figure: params, caption, `run` |
//! | output | [`figure`], [`render`] | backend-free figure; PNG/SVG, CSV/JSON, terminal chart |
//! | models | [`models`] | one module per theory, equations only |
//! | numerics | [`numerics`] | roots, quadrature; no physics |
//! | plumbing | [`error`], [`job`], [`params`], [`reproduction`] | errors, progress/cancel, parameters, printed numbers |
//!
//! ## Notation
//!
//! | symbol | identifier | meaning |
//! |---|---|---|
//! | R | `radius` | sphere (tip, asperity) radius [m] |
//! | E* | `modulus` | effective (plane-strain) modulus E/(1−ν²) [Pa] |
//! | w | `work_of_adhesion` | Dupré work of adhesion [J/m²] |
//! | a, h, P | `a`, `h`, `p` | contact radius, indentation depth, force (compression positive) |
//! | a₀, h₀, P₀ | `a0()`, `h0()`, `p0()` | JKR scales (πR²w/E*)^(1/3), (π²Rw²/E*²)^(1/3), πwR |
//! | μ_T | `tabor_parameter` | Tabor parameter, Eq. (1.8) |
//! | σ_rms | `sigma` | RMS roughness [m] |
//! | h_o, P_o | | Fuller-Tabor scales \|h_D\|, \|P_C\| |
//!
//! Non-dimensional quantities carry the suffix `_bar` in code and `_norm` in exported results.

pub mod cli;
pub mod error;
pub mod figure;
pub mod fit;
pub mod headless;
pub mod job;
pub mod models;
pub mod numerics;
pub mod params;
pub mod render;
pub mod reproduction;
pub mod scenes;
pub mod surface;
pub mod tui;

pub use error::{Error, Result};
