//! Scenes of chapter/appendix C.

use super::SceneDyn;

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[];
