//! The printed numbers of chapter 6.

use super::Claim;

/// The claims of chapter 6.
pub fn claims() -> Vec<Claim> {
    Vec::new()
}
