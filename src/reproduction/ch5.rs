//! The printed numbers of chapter 5.

use super::Claim;

/// The claims of chapter 5.
pub fn claims() -> Vec<Claim> {
    Vec::new()
}
