//! Scenes of chapter/appendix 2.

use super::SceneDyn;

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[];
