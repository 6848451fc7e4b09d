//! The command line (clap). `adhesion` alone starts the terminal UI; `--list`, `--describe` and
//! `--headless ...` work without a terminal.
//!
//! A feature with its own options (curve fitting, surface generation) adds a flattened
//! `Args` struct of its own here and a branch in [`crate::headless::run`].

use std::path::PathBuf;
use std::str::FromStr;

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

    /// A measured force-curve file to open in the terminal UI (JPK, Asylum .ibw, NT-MDT, AFM
    /// Workshop, afmformats .tab/.h5): its curves, a force map as a grid, the chosen curve fitted.
    /// With --headless, fit it with --fit FILE.
    #[arg(value_name = "FILE")]
    pub file: Option<PathBuf>,

    /// Scene to export (with --headless), e.g. fig1.1.
    #[arg(long, value_name = "ID", conflicts_with = "all")]
    pub figure: Option<String>,

    /// Export every scene (with --headless).
    #[arg(long)]
    pub all: bool,

    /// Parameter preset (TOML) for --figure.
    #[arg(long, value_name = "FILE")]
    pub preset: Option<PathBuf>,

    /// Set a parameter, NAME=VALUE (repeatable; applied after the preset).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,

    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "output")]
    pub out: PathBuf,

    /// Formats to write, comma-separated: png, svg, csv, json, pdf.
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        default_value = "png,svg,csv,json"
    )]
    pub format: Vec<String>,

    /// Width of the figures on the page in mm (default: 90 for one panel, 190 for more); text
    /// keeps its size in points (axis titles 8 pt, tick labels 7 pt).
    #[arg(long = "width-mm", value_name = "MM")]
    pub width_mm: Option<f64>,

    /// Resolution of the PNG figures in dots per inch (default 300).
    #[arg(long, value_name = "DPI")]
    pub dpi: Option<f64>,

    /// Compute only shard I of N of a sweep scene (the points whose id is I modulo N, I from 0),
    /// one file per point in a folder under --out; points already there are skipped, so a rerun
    /// resumes. One task of a job array (--shard $SLURM_ARRAY_TASK_ID/N); needs --figure.
    #[arg(long, value_name = "I/N", conflicts_with = "merge")]
    pub shard: Option<Shard>,

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

    /// The options given on the command line (clap's ids, `out`, `tip_radius`, ...), as
    /// opposed to those left at their defaults: an option given to a command that does not use
    /// it is an error ([`check_options`]). Filled by [`parse`].
    #[arg(skip)]
    pub given: Vec<String>,
}

/// Parse the command line (the program name first). Options that apply to one command only
/// are not tied to it here (clap's `requires` would report them as "required arguments not
/// provided" without naming them): [`check_options`] names them.
///
/// # Errors
/// clap's errors (unknown options, bad values, `--help`, `--version`).
pub fn parse<I: IntoIterator<Item = std::ffi::OsString>>(args: I) -> Result<Cli, clap::Error> {
    use clap::{CommandFactory, FromArgMatches};
    let matches = Cli::command()
        .mut_args(|a| a.requires(clap::builder::Resettable::<clap::Id>::Reset))
        .try_get_matches_from(join_negative_values(args))?;
    let mut cli = Cli::from_arg_matches(&matches)?;
    cli.given = matches
        .ids()
        .filter(|id| matches.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine))
        .map(|id| id.as_str().to_string())
        .collect();
    Ok(cli)
}

/// A command-line parsing error as one line: clap's first line (without its usage block),
/// with a pointer to `--help`.
pub fn one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let mut lines = text.lines().skip_while(|l| l.trim().is_empty());
    let mut first = lines
        .next()
        .unwrap_or("error: bad command line")
        .trim_end()
        .to_string();
    if first.ends_with(':') {
        // A list follows ("the following required arguments were not provided:"): its items
        // are part of the message.
        let items: Vec<&str> = lines
            .take_while(|l| l.starts_with(char::is_whitespace) && !l.trim().is_empty())
            .map(str::trim)
            .collect();
        first = format!("{first} {}", items.join(", "));
    }
    let first = crate::params::escape_for_message(&first, 200);
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
    let given = |id: &str| cli.given.iter().any(|g| g == id);
    // --list, --describe and --print-preset print and exit: nothing else applies.
    let printers: Vec<&str> = [
        (cli.list, "--list"),
        (cli.describe.is_some(), "--describe"),
        (cli.print_preset.is_some(), "--print-preset"),
    ]
    .into_iter()
    .filter_map(|(on, name)| on.then_some(name))
    .collect();
    if let Some(printer) = printers.first() {
        if printers.len() > 1 {
            return Err(crate::error::Error::Usage(format!(
                "{} cannot be combined: give one of them at a time",
                printers.join(" and ")
            )));
        }
        let ids = ["list", "describe", "print_preset", "headless"];
        if let Some(other) = cli.given.iter().find(|g| !ids.contains(&g.as_str())) {
            return Err(conflict(
                &option_name(other),
                &format!("does not apply to {printer}"),
            ));
        }
        return Ok(());
    }
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
    // --shard and --merge are modes of --figure with their own outputs.
    let mode = if cli.shard.is_some() {
        "--shard"
    } else if cli.merge {
        "--merge"
    } else {
        command
    };
    let used = |on: bool, name: &'static str, by: &[&str]| -> crate::error::Result<()> {
        if on && !by.contains(&command) && !by.contains(&mode) {
            let by = by.join(" or ");
            let reason = if command.is_empty() {
                format!("applies to {by} only")
            } else {
                format!("applies to {by} only, not {mode}")
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
    // --shard writes point files, --reproduce its report, --generate-surface the --out file,
    // --analyze-surface prints: --format is theirs only where figures are written.
    let by_format: &[&str] = if cli.shard.is_some() {
        &["--merge"]
    } else {
        &["--figure", "--all", "--merge"]
    };
    used(given("format"), "--format", by_format)?;
    used(cli.width_mm.is_some(), "--width-mm", by_format)?;
    used(cli.dpi.is_some(), "--dpi", by_format)?;
    used(
        given("out"),
        "--out",
        &["--figure", "--all", "--reproduce", "--fit", "--generate-surface"],
    )?;
    used(cli.fit.tip_radius.is_some(), "--tip-radius", &["--fit"])?;
    used(cli.fit.spring_constant.is_some(), "--spring-constant", &["--fit"])?;
    used(cli.fit.model.is_some(), "--model", &["--fit"])?;
    used(cli.fit.segment.is_some(), "--segment", &["--fit"])?;
    used(cli.fit.poisson.is_some(), "--poisson", &["--fit"])?;
    used(cli.fit.curve.is_some(), "--curve", &["--fit"])?;
    used(cli.fit.sensitivity.is_some(), "--sensitivity", &["--fit"])?;
    used(cli.fit.baseline_tilt, "--baseline-tilt", &["--fit"])?;
    used(s.pixel_size.is_some(), "--pixel-size", &["--analyze-surface"])?;
    used(s.periodic, "--periodic", &["--analyze-surface"])?;
    used(s.list_channels, "--list-channels", &["--analyze-surface"])?;
    used(
        s.channel.is_some(),
        "--channel",
        &["--analyze-surface", "--figure"],
    )?;
    used(s.remove_tilt, "--remove-tilt", &["--analyze-surface"])?;
    used(given("fit_cutoff"), "--fit-cutoff", &["--analyze-surface"])?;
    let generation: [(&str, bool); 12] = [
        ("--seed", given("seed")),
        ("--rms", s.rms.is_some()),
        ("--correlation-length", s.correlation_length.is_some()),
        ("--size", !s.size.is_empty()),
        ("--length", !s.length.is_empty()),
        ("--q-roll", s.q_roll.is_some()),
        ("--q-high", s.q_high.is_some()),
        ("--spectrum", given("spectrum")),
        ("--exponent", given("exponent")),
        ("--cutoff", given("cutoff")),
        ("--hurst", given("hurst")),
        ("--q-low", given("q_low")),
    ];
    for (name, on) in generation {
        used(on, name, &["--generate-surface"])?;
    }
    if s.generate_surface {
        // Each spectrum's own options: another spectrum ignores them.
        let spectra: [(&str, bool, &[&str]); 7] = [
            (
                "--correlation-length",
                s.correlation_length.is_some(),
                &["gaussian", "abc"],
            ),
            ("--exponent", given("exponent"), &["abc"]),
            ("--cutoff", given("cutoff"), &["abc"]),
            ("--hurst", given("hurst"), &["self-affine"]),
            ("--q-low", given("q_low"), &["self-affine"]),
            ("--q-roll", s.q_roll.is_some(), &["self-affine"]),
            ("--q-high", s.q_high.is_some(), &["self-affine"]),
        ];
        for (name, on, kinds) in spectra {
            if on && !kinds.contains(&s.spectrum.as_str()) {
                return Err(conflict(
                    name,
                    &format!(
                        "applies to --spectrum {} only, not {}",
                        kinds.join(" or "),
                        s.spectrum
                    ),
                ));
            }
        }
    }
    if let Some(map) = &s.analyze_surface
        && s.pixel_size.is_some()
        && crate::surface::io::MapFormat::of(map) == crate::surface::io::MapFormat::Gsf
    {
        return Err(conflict(
            "--pixel-size",
            "does not apply to a .gsf map: its header gives the lengths (XReal, YReal)",
        ));
    }
    Ok(())
}

/// The command-line spelling of a clap id: `print_preset` → `--print-preset`.
fn option_name(id: &str) -> String {
    format!("--{}", id.replace('_', "-"))
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

/// Shard `index` of `count`: the points whose id is `index` modulo `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// I, from 0 (Slurm's `$SLURM_ARRAY_TASK_ID` with `--array=0-(N-1)`).
    pub index: usize,
    /// N, at least 1.
    pub count: usize,
}

impl FromStr for Shard {
    type Err = String;

    /// `I/N` with 0 ≤ I < N.
    fn from_str(text: &str) -> Result<Self, String> {
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| "expected I/N, e.g. 0/4 (shard I of N, I from 0 to N-1)".to_string())?;
        let parse = |t: &str, what: &str| {
            t.trim().parse::<usize>().map_err(|_| {
                format!(
                    "{what} `{}` is not a whole number (expected I/N, e.g. 0/4)",
                    t.trim()
                )
            })
        };
        let (index, count) = (parse(i, "the shard index I")?, parse(n, "the shard count N")?);
        if count == 0 {
            return Err("the shard count N must be at least 1".into());
        }
        if index >= count {
            return Err(format!(
                "the shard index I = {index} must be below N = {count} (shards are numbered 0 to {})",
                count - 1
            ));
        }
        Ok(Shard { index, count })
    }
}
