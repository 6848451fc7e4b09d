//! # adhesion: a workbench for adhesive elastic contact of rough surfaces
//!
//! Implements the computational models of W. Deng, *Mechanics of Elastic Contact and Adhesion of
//! Rough Surfaces*, Ph.D. dissertation, Brown University, 2019 (cited as `[Deng19]`; equation
//! numbers in doc comments are that work's): the classical Hertz/JKR/DMT/Maugis-Dugdale theories
//! and the Fuller-Tabor rough-surface model (ch. 1, 3), JKR with machine stiffness and the fitting
//! of measured force-indentation curves (ch. 2, app. A), the Maugis-Dugdale/Nayak model of
//! depth-dependent hysteresis (ch. 3, app. B), the Lennard-Jones interaction, the critical
//! separation of the contact instabilities, the axisymmetric surface model of smooth and wavy
//! tips with its displacement-controlled cycles, and the JKR theory of a wavy tip (ch. 4), spring-array
//! models of fibrillar adhesion on random rough surfaces (ch. 5, app. C) and peeling from wavy
//! substrates (ch. 6).
//!
//! ## Module map (data flows down)
//!
//! | layer | module | what |
//! |---|---|---|
//! | front ends | [`tui`], [`headless`], [`cli`] | terminal UI with a background worker; exports; sharded sweeps |
//! | scenes | [`scenes`] | one scene per dissertation figure: params, caption, `run` |
//! | output | [`figure`], [`render`] | backend-free figure; PNG/SVG, CSV/JSON, terminal chart |
//! | models | [`models`] | one module per theory, equations only |
//! | numerics | [`numerics`] | roots, quadrature; no physics |
//! | data in | [`readers`] | instrument files (force curves, maps) to typed records with units |
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
//! | C₆, C₁₂, σ | `c6`, `c12`, `sigma` | weights and length of the LJ potential (4.1) [-, -, m] |
//! | A_H | `hamaker` | Hamaker constant 4π²ερ₁ρ₂σ⁶ [J] |
//! | ζ₀ | `zeta0()` | equilibrium separation of two LJ half-spaces, Eq. (4.6) [m] |
//! | δ₀ | `dugdale_range()` | range of the equivalent Dugdale zone, (9√3/16) ζ₀ [m] |
//! | ℓ, χ | `ell`, `chi` | πw/(E*R) and w/(E*δ₀), Eqs. (3.1)-(3.2), (4.25) |
//! | Ā, λ̄ | `amplitude_bar`, `wavelength_bar` | amplitude A and wavelength λ of the wavy tip (4.10), over R |
//! | A, λ | `amplitude`, `wavelength` | waviness of the tip (4.10) [m] |
//! | b | `TipScales::radial` | radial scale ζ₀²E*/w of the surface model; ring widths are in b |
//! | σ_rms | `sigma` | RMS roughness [m] |
//! | h_o, P_o | | Fuller-Tabor scales \|h_D\|, \|P_C\| |
//!
//! Non-dimensional quantities carry the suffix `_bar` in code and `_norm` in exported results.
//!
//! Other sources are cited by a short key: `[Johnson85]` K. L. Johnson, *Contact Mechanics*,
//! Cambridge University Press, 1985.

pub mod cli;
pub mod error;
pub mod figure;
pub mod fit;
pub mod headless;
pub mod input;
pub mod job;
pub mod models;
pub mod numerics;
pub mod params;
pub mod readers;
pub mod render;
pub mod reproduction;
pub mod scenes;
pub mod surface;
pub mod text;
pub mod tui;

pub use error::{Error, Result};
