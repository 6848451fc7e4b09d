//! Scenes of chapter/appendix 5.

use super::SceneDyn;

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[];
