//! The printed numbers of chapter 2.

use super::Claim;

/// The claims of chapter 2.
pub fn claims() -> Vec<Claim> {
    Vec::new()
}
