//! Chapter 4 scenes (placeholder module, filled by the scene's commit).
