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

    /// Compute only shard I of N of a sweep scene (the points whose id is I modulo N, I from 0),
    /// one file per point in a folder under --out; points already there are skipped, so a rerun
    /// resumes. One task of a job array (--shard $SLURM_ARRAY_TASK_ID/N); needs --figure.
    #[arg(long, value_name = "I/N", conflicts_with = "merge")]
    pub shard: Option<crate::headless::shard::Shard>,

    /// Assemble a sweep computed with --shard from its folder under --out (same --figure,
    /// --preset, --set and --quick) and export the figure as an unsharded run does.
    #[arg(long)]
    pub merge: bool,

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

/// A command-line parsing error as one line: clap's first line (without its usage block),
/// with a pointer to `--help`.
pub fn one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let first = text
        .lines()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("error: bad command line");
    let first = crate::params::escape_for_message(first, 200);
    if first.starts_with("error:") {
        format!("{first} (see --help)")
    } else {
        format!("error: {first} (see --help)")
    }
}

/// Options that do not belong together, or that the chosen command does not use: one line
/// naming them.
///
/// # Errors
/// The first conflict found.
pub fn check_options(cli: &Cli) -> crate::error::Result<()> {
    let s = &cli.surface;
    let commands: Vec<&str> = [
        (cli.figure.is_some(), "--figure"),
        (cli.all, "--all"),
        (cli.reproduce, "--reproduce"),
        (cli.fit.fit.is_some(), "--fit"),
        (s.generate_surface, "--generate-surface"),
        (s.analyze_surface.is_some(), "--analyze-surface"),
    ]
    .into_iter()
    .filter_map(|(on, name)| on.then_some(name))
    .collect();
    if commands.len() > 1 {
        return Err(crate::error::Error::Usage(format!(
            "{} cannot be combined: give one of them at a time",
            commands.join(" and ")
        )));
    }
    let command = commands.first().copied().unwrap_or("");
    let used = |on: bool, name: &'static str, by: &[&str]| -> crate::error::Result<()> {
        if on && !by.contains(&command) {
            let by = by.join(" or ");
            let reason = if command.is_empty() {
                format!("applies to {by} only")
            } else {
                format!("applies to {by} only, not {command}")
            };
            return Err(conflict(name, &reason));
        }
        Ok(())
    };
    used(cli.preset.is_some(), "--preset", &["--figure"])?;
    used(!cli.set.is_empty(), "--set", &["--figure"])?;
    used(s.surface.is_some(), "--surface", &["--figure"])?;
    used(cli.quick, "--quick", &["--figure", "--all"])?;
    used(cli.shard.is_some(), "--shard", &["--figure"])?;
    used(cli.merge, "--merge", &["--figure"])?;
    used(s.pixel_size.is_some(), "--pixel-size", &["--analyze-surface"])?;
    used(s.periodic, "--periodic", &["--analyze-surface"])?;
    used(s.remove_tilt, "--remove-tilt", &["--analyze-surface"])?;
    used(s.rms.is_some(), "--rms", &["--generate-surface"])?;
    used(
        s.correlation_length.is_some(),
        "--correlation-length",
        &["--generate-surface"],
    )?;
    used(!s.size.is_empty(), "--size", &["--generate-surface"])?;
    used(!s.length.is_empty(), "--length", &["--generate-surface"])?;
    used(s.q_roll.is_some(), "--q-roll", &["--generate-surface"])?;
    used(s.q_high.is_some(), "--q-high", &["--generate-surface"])?;
    Ok(())
}

fn conflict(name: &str, reason: &str) -> crate::error::Error {
    crate::error::Error::Usage(format!("{name} {reason}"))
}

/// The command line with every `--option -1e-9` written as `--option=-1e-9`, so that a negative
/// number (also in exponent form, which clap would take for the short flag `-1`) is read as
/// the option's value.
pub fn join_negative_values<I: IntoIterator<Item = std::ffi::OsString>>(args: I) -> Vec<std::ffi::OsString> {
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    for a in args {
        let negative_number = a
            .to_str()
            .is_some_and(|t| t.starts_with('-') && t.len() > 1 && t.parse::<f64>().is_ok());
        if negative_number
            && let Some(prev) = out.last_mut()
            && let Some(p) = prev.to_str()
            && p.starts_with("--")
            && !p.contains('=')
            && p.len() > 2
        {
            let joined = format!("{p}={}", a.to_string_lossy());
            *prev = joined.into();
            continue;
        }
        out.push(a);
    }
    out
}
