//! Integration tests, one binary: reference values from the dissertation, limits and
//! consistency, the scene registry and presets, snapshots of exported data, the command line,
//! and the reproduction registry.

mod cli;
mod common;
mod layering;
mod reference_ch1;
mod registry;
mod reproduction;
mod snapshots;
