//! Integration tests, one binary: reference values from the dissertation, limits and
//! consistency, the scene registry and presets, snapshots of exported data, the command line,
//! and the reproduction registry.

mod ch2;
mod ch3;
mod ch4;
mod ch4_fe;
mod ch4_roughness;
mod ch5;
mod ch6;
mod cli;
mod common;
mod edges;
mod figures;
mod force_curves;
mod fuzz;
mod hardening;
mod layering;
mod maps;
mod readers;
mod reference_ch1;
mod registry;
mod reproduction;
mod shards;
mod silent;
mod snapshots;
mod surface;
mod tui;
mod workbench;
