//! Scenes of chapter/appendix 6.

use super::SceneDyn;

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[];
