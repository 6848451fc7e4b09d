//! Helpers shared by the integration tests.

use std::path::PathBuf;

/// Relative difference |a − b| / max(|b|, tiny).
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Assert |a − b| ≤ tol·|b| with a message naming the quantity.
#[track_caller]
pub fn assert_rel(what: &str, a: f64, b: f64, tol: f64) {
    assert!(
        rel(a, b) <= tol,
        "{what}: got {a:.15e}, expected {b:.15e} (rel. diff {:.2e} > {tol:.0e})",
        rel(a, b)
    );
}
