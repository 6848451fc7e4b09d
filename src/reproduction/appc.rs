//! The printed numbers of appendix C (random rough surfaces).

use super::Claim;

/// The claims of appendix C (random rough surfaces).
pub fn claims() -> Vec<Claim> {
    Vec::new()
}
