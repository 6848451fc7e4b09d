//! The command line (clap). `adhesion` alone starts the terminal UI; `--list`, `--describe` and
//! `--headless ...` work without a terminal.
//!
//! A feature with its own options (curve fitting, surface generation) adds a flattened
//! `Args` struct of its own here and a branch in [`crate::headless::run`].

use std::path::PathBuf;

use clap::Parser;

/// Command-line options.
#[derive(Debug, Clone, Parser)]
#[command(
    name = "adhesion",
    version,
    about = "Workbench for adhesive elastic contact of rough surfaces (Deng, Brown University, 2019)",
    long_about = "Without arguments, starts the terminal UI. With --headless, exports figures \
                  (PNG, SVG, CSV, JSON) of the dissertation's scenes, or runs the reproduction report."
)]
pub struct Cli {
    /// List the scenes with their titles and exit.
    #[arg(long)]
    pub list: bool,

    /// Print a scene's parameters (name, default, unit, meaning, valid range) and result names.
    #[arg(long, value_name = "ID")]
    pub describe: Option<String>,

    /// Print a scene's default parameters as a commented preset (TOML) and exit.
    #[arg(long, value_name = "ID")]
    pub print_preset: Option<String>,

    /// Run without the terminal UI.
    #[arg(long)]
    pub headless: bool,

    /// Scene to export (with --headless), e.g. fig1.1.
    #[arg(long, value_name = "ID", conflicts_with = "all")]
    pub figure: Option<String>,

    /// Export every scene (with --headless).
    #[arg(long)]
    pub all: bool,

    /// Parameter preset (TOML) for --figure.
    #[arg(long, value_name = "FILE", requires = "figure")]
    pub preset: Option<PathBuf>,

    /// Set a parameter, NAME=VALUE (repeatable; applied after the preset).
    #[arg(long = "set", value_name = "NAME=VALUE", requires = "figure")]
    pub set: Vec<String>,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "output")]
    pub out: PathBuf,

    /// Formats to write, comma-separated: png, svg, csv, json.
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        default_value = "png,svg,csv,json"
    )]
    pub format: Vec<String>,

    /// Reduced resolution (the tests' quick mode): same physics, fewer points.
    #[arg(long)]
    pub quick: bool,

    /// Compute every number of the dissertation the workbench reproduces and write
    /// reproduction.md and reproduction.json.
    #[arg(long)]
    pub reproduce: bool,

    /// Curve fitting (appendix A.4).
    #[command(flatten)]
    pub fit: crate::fit::FitArgs,

    /// Rough-surface generation and analysis.
    #[command(flatten)]
    pub surface: crate::surface::SurfaceArgs,
}
