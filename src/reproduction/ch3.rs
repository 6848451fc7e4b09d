//! The printed numbers of chapter 3.

use super::Claim;

/// The claims of chapter 3.
pub fn claims() -> Vec<Claim> {
    Vec::new()
}
