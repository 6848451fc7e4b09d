//! Headless mode: list and describe scenes, export figures (PNG, SVG, CSV, JSON), and the
//! reproduction report. Everything is validated before anything is computed, and every file is
//! written atomically, so a bad input or a failed run leaves no (half-written) output.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};

use crate::cli::Cli;
use crate::error::{Error, Result};
use crate::figure::Figure;
use crate::job::{Job, JobEvent};
use crate::params::{ParamValues, fmt_float, value_text};
use crate::render::{Format, data, plot, write_set};
use crate::reproduction;
use crate::scenes::{self, SceneDyn, chapter_title};

pub mod shard;

/// Run the command line in headless mode (also `--list` and `--describe`).
///
/// # Errors
/// Any problem, as one line of context and cause.
pub fn run(cli: &Cli) -> anyhow::Result<ExitCode> {
    crate::cli::check_options(cli)?;
    if cli.list {
        emit(&list())?;
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(id) = &cli.describe {
        emit(&describe(id)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(id) = &cli.print_preset {
        emit(&preset_text(scenes::find(id)?))?;
        return Ok(ExitCode::SUCCESS);
    }
    let formats = parse_formats(&cli.format)?;
    if cli.reproduce {
        return reproduce_command(&cli.out);
    }
    if cli.fit.fit.is_some() {
        for p in crate::fit::command(&cli.fit, &cli.out)? {
            emit_line(&p.display())?;
        }
        return Ok(ExitCode::SUCCESS);
    }
    if cli.surface.generate_surface || cli.surface.analyze_surface.is_some() {
        emit(&crate::surface::command::run(&cli.surface, &cli.out)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(id) = &cli.figure {
        let scene = scenes::find(id)?;
        let mut sets = cli.set.clone();
        if let Some(path) = &cli.surface.surface {
            let takes_map = |s: &dyn scenes::SceneDyn| s.specs().iter().any(|p| p.name == "surface");
            if !takes_map(scene) {
                let with: Vec<&str> = scenes::all()
                    .iter()
                    .filter(|s| takes_map(**s))
                    .map(|s| s.info().id)
                    .collect();
                return Err(crate::error::Error::invalid(
                    "surface",
                    path.display(),
                    format!(
                        "scene {id} takes no height map (scenes that do: {})",
                        with.join(", ")
                    ),
                )
                .into());
            }
            match &cli.surface.channel {
                Some(c) => sets.push(format!("surface={}#{c}", path.display())),
                None => sets.push(format!("surface={}", path.display())),
            }
        } else if cli.surface.channel.is_some() {
            return Err(crate::error::Error::Usage(
                "--channel applies to the map of --surface FILE (or --analyze-surface FILE)".into(),
            )
            .into());
        }
        let values = resolve_values(scene, cli.preset.as_deref(), &sets, cli.quick)?;
        if let Some(part) = cli.shard {
            emit_line(&shard::run_shard(scene, &values, part, &cli.out)?.display())?;
            return Ok(ExitCode::SUCCESS);
        }
        if cli.merge {
            for p in shard::merge(scene, &values, &cli.out, &formats)? {
                emit_line(&p.display())?;
            }
            return Ok(ExitCode::SUCCESS);
        }
        let written = export_scene(scene, &values, &cli.out, &formats, &progress_job(id))?;
        for p in written {
            emit_line(&p.display())?;
        }
        return Ok(ExitCode::SUCCESS);
    }
    if cli.all {
        let mut failed = 0;
        let mut gallery = Vec::new();
        for scene in scenes::all() {
            let id = scene.info().id;
            let info = scene.info();
            // Sweeps and long runs (minutes each at their defaults) run in their quick form here.
            let quick = cli.quick || info.sweep || info.long;
            let values = resolve_values(scene, None, &[], quick);
            let quick_form = values.as_ref().ok().and_then(|v| scenes::quick_form(scene, v));
            let outcome =
                values.and_then(|values| export_scene(scene, &values, &cli.out, &formats, &progress_job(id)));
            let image = [Format::Png, Format::Svg]
                .into_iter()
                .find(|f| formats.contains(f))
                .map(|f| format!("{id}.{}", f.extension()));
            match outcome {
                Ok(paths) => {
                    for p in paths {
                        emit_line(&p.display())?;
                    }
                    gallery.push(GalleryEntry {
                        id,
                        title: info.title,
                        caption: info.caption,
                        image,
                        error: None,
                        quick_form,
                    });
                }
                Err(e) => {
                    failed += 1;
                    eprintln!("error: {id}: {e}");
                    gallery.push(GalleryEntry {
                        id,
                        title: info.title,
                        caption: info.caption,
                        image: None,
                        error: Some(format!("{e:#}")),
                        quick_form,
                    });
                }
            }
        }
        let index = cli.out.join("index.html");
        crate::render::write_atomic(&index, gallery_html(&gallery).as_bytes())?;
        emit_line(&index.display())?;
        if failed > 0 {
            bail!("{failed} scene(s) failed");
        }
        return Ok(ExitCode::SUCCESS);
    }
    bail!("nothing to do: give --figure ID, --all or --reproduce (see --help)")
}

/// Write `text` to stdout and flush it: a failed write (a full disk behind a redirection, a
/// closed pipe) is an error naming stdout, never a panic.
///
/// # Errors
/// [`Error::File`] for "standard output".
pub fn emit(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(Error::file("writing to", Path::new("standard output")))
}

/// [`emit`] of one line: `line` and a newline.
///
/// # Errors
/// As [`emit`].
pub fn emit_line(line: &dyn std::fmt::Display) -> Result<()> {
    emit(&format!("{line}\n"))
}

/// One figure of the gallery page.
#[derive(Debug, Clone)]
pub struct GalleryEntry {
    /// Scene id.
    pub id: &'static str,
    /// Title.
    pub title: &'static str,
    /// Caption.
    pub caption: &'static str,
    /// Image file name next to the page (PNG, else SVG), if one was written.
    pub image: Option<String>,
    /// Why the scene failed, if it did.
    pub error: Option<String>,
    /// What its quick form computed more coarsely ([`scenes::quick_form`]), if it ran in one.
    pub quick_form: Option<String>,
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The gallery page written by `--all`: every figure with its id, title and caption, so that a
/// reader can check them all at once.
pub fn gallery_html(entries: &[GalleryEntry]) -> String {
    let mut out = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n\
         <title>adhesion: every figure</title>\n<style>body{font-family:sans-serif;max-width:1400px;\
         margin:auto;padding:1em}figure{margin:2em 0;border-top:1px solid #ccc;padding-top:1em}\
         img{max-width:100%}figcaption{max-width:60em}.error{color:#b00}</style></head><body>\n\
         <h1>Figures of the adhesion workbench</h1>\n",
    );
    out.push_str("<ul>\n");
    for e in entries {
        out.push_str(&format!(
            "<li><a href=\"#{id}\">{id}</a>: {t}</li>\n",
            id = html_escape(e.id),
            t = html_escape(e.title)
        ));
    }
    out.push_str("</ul>\n");
    for e in entries {
        out.push_str(&format!("<figure id=\"{}\">\n", html_escape(e.id)));
        if let Some(img) = &e.image {
            out.push_str(&format!(
                "<a href=\"{img}\"><img src=\"{img}\" alt=\"{}\" loading=\"lazy\"></a>\n",
                html_escape(e.title),
                img = html_escape(img)
            ));
        }
        if let Some(err) = &e.error {
            out.push_str(&format!("<p class=\"error\">failed: {}</p>\n", html_escape(err)));
        }
        if let Some(q) = &e.quick_form {
            out.push_str(&format!(
                "<p class=\"quick\">quick form: {}</p>\n",
                html_escape(q)
            ));
        }
        out.push_str(&format!(
            "<figcaption><b>{}</b> {}. {}</figcaption>\n</figure>\n",
            html_escape(e.id),
            html_escape(e.title),
            html_escape(e.caption)
        ));
    }
    out.push_str("</body></html>\n");
    out
}

/// Parse the `--format` list.
///
/// # Errors
/// An unknown format name.
pub fn parse_formats(names: &[String]) -> anyhow::Result<Vec<Format>> {
    let mut formats = Vec::new();
    for n in names {
        let f =
            Format::parse(n).with_context(|| format!("unknown format `{n}`: use png, svg, csv or json"))?;
        if !formats.contains(&f) {
            formats.push(f);
        }
    }
    if formats.is_empty() {
        bail!("no output format given");
    }
    Ok(formats)
}

/// The scene list, grouped by chapter.
pub fn list() -> String {
    let mut out = String::new();
    let mut chapter = "";
    for s in scenes::all() {
        let info = s.info();
        if info.chapter != chapter {
            chapter = info.chapter;
            out.push_str(&format!("\nChapter {chapter}: {}\n", chapter_title(chapter)));
        }
        out.push_str(&format!("  {:<18} {}\n", info.id, info.title));
    }
    out
}

/// A scene's description: caption, parameters and results.
///
/// # Errors
/// Unknown scene.
pub fn describe(id: &str) -> Result<String> {
    let scene = scenes::find(id)?;
    let info = scene.info();
    let defaults = scene.defaults();
    let mut out = format!("{} — {}\n\n{}\n\n", info.id, info.title, info.caption);
    if let Some(sweep) = scene.sweep() {
        let n = sweep.points(&defaults)?.len();
        let quick = sweep.points(&scene.quick(&defaults)?)?.len();
        out.push_str(&format!(
            "A sweep of {n} independent points at these defaults ({quick} in quick form); the count \
             follows the parameters. Run it in shards with --shard I/N --out DIR (a job array), then \
             --merge --out DIR (see the README).\n\n"
        ));
    } else if info.sweep {
        out.push_str(
            "A sweep of many independent cycles: `--all` runs it in its quick form; export it \
             with --figure for the full grid.\n\n",
        );
    } else if info.long {
        out.push_str(
            "A run of minutes at these defaults: `--all` runs it in its quick form (as --quick \
             does); export it with --figure for the full model.\n\n",
        );
    }
    out.push_str("Parameters (SI units; set with --set NAME=VALUE):\n");
    out.push_str(&format!(
        "  {:<24} {:>14}  {:<8} {:<16} {}\n",
        "name", "default", "unit", "valid range", "meaning"
    ));
    for (s, v) in defaults.specs.iter().zip(&defaults.values) {
        let range = match s.kind {
            crate::params::ParamKind::Float
            | crate::params::ParamKind::Int
            | crate::params::ParamKind::FloatList => s.range.describe(),
            crate::params::ParamKind::Bool => "true, false".into(),
            crate::params::ParamKind::Choice(options) => options.join(", "),
            crate::params::ParamKind::Text => "text".into(),
        };
        let unit = if s.unit.is_empty() { "-" } else { s.unit };
        out.push_str(&format!(
            "  {:<24} {:>14}  {:<8} {:<16} {}\n",
            s.name,
            value_text(v),
            unit,
            range,
            s.help
        ));
    }
    out.push_str("\nResults (JSON `results`):\n");
    for (name, meaning) in info.results {
        out.push_str(&format!("  {name:<36} {meaning}\n"));
    }
    Ok(out)
}

/// The scene's defaults as a commented preset file.
pub fn preset_text(scene: &dyn SceneDyn) -> String {
    scene.defaults().to_preset_text(&preset_header(scene))
}

/// The comment heading a preset file of `scene`: file name, title, caption, how to load it.
pub fn preset_header(scene: &dyn SceneDyn) -> String {
    let info = scene.info();
    format!(
        "presets/{}.toml -- {}\n{}\nSI units; load with `adhesion --headless --figure {} --preset FILE`.",
        info.id, info.title, info.caption, info.id
    )
}

/// Defaults, then the preset, then the `--set` assignments; validated. In quick form the
/// scene's quick values, then the `--set` assignments again: a value the user set is kept.
///
/// # Errors
/// Preset problems, unknown names, bad values, failed cross-field checks.
pub fn resolve_values(
    scene: &dyn SceneDyn,
    preset: Option<&Path>,
    sets: &[String],
    quick: bool,
) -> Result<ParamValues> {
    let mut values = scene.defaults();
    if let Some(path) = preset {
        values.apply_preset_file(path)?;
    }
    for s in sets {
        values.set_assignment(s)?;
    }
    scene.validate(&values)?;
    if quick {
        values = scene.quick(&values)?;
        // A value the user set wins over the quick form's (which lowers resolutions).
        for s in sets {
            values.set_assignment(s)?;
        }
        scene.validate(&values)?;
    }
    Ok(values)
}

/// Run a scene and write its files. Nothing is written unless the run succeeds.
///
/// # Errors
/// Run errors, rendering errors, I/O errors.
pub fn export_scene(
    scene: &dyn SceneDyn,
    values: &ParamValues,
    out: &Path,
    formats: &[Format],
    job: &Job,
) -> Result<Vec<PathBuf>> {
    let start = Instant::now();
    let fig = scene.run(values, job)?;
    let run_time = start.elapsed().as_secs_f64();
    finish_progress();
    write_figure(&fig, scene.info().caption, values, run_time, out, formats)
}

/// Write a computed figure in the given formats as `<out>/<id>.<ext>`. All files are rendered
/// in memory first, then written together ([`write_set`]): all formats appear or none.
///
/// # Errors
/// Rendering and I/O errors; on error no new file is left behind.
pub fn write_figure(
    fig: &Figure,
    caption: &str,
    values: &ParamValues,
    run_time_s: f64,
    out: &Path,
    formats: &[Format],
) -> Result<Vec<PathBuf>> {
    write_figure_with_runs(fig, caption, values, run_time_s, &[], out, formats)
}

/// [`write_figure`] for a figure that also draws earlier runs (pinned in the terminal UI): the
/// JSON lists each of them with its parameters under `pinned_runs`.
///
/// # Errors
/// Rendering and I/O errors; on error no new file is left behind.
pub fn write_figure_with_runs(
    fig: &Figure,
    caption: &str,
    values: &ParamValues,
    run_time_s: f64,
    runs: &[data::RunRecord<'_>],
    out: &Path,
    formats: &[Format],
) -> Result<Vec<PathBuf>> {
    let path = |f: Format| out.join(format!("{}.{}", fig.id, f.extension()));
    // Render every format in memory first: a failure there writes nothing.
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for &f in formats {
        let bytes = match f {
            Format::Png => plot::png_bytes(fig)?,
            Format::Svg => plot::svg_string(fig)?.into_bytes(),
            Format::Csv => data::csv(fig).into_bytes(),
            Format::Json => data::json_with_runs(fig, caption, values, run_time_s, runs).into_bytes(),
        };
        files.push((path(f), bytes));
    }
    create_folder(out)?;
    write_set(&files)?;
    Ok(files.into_iter().map(|(p, _)| p).collect())
}

/// Create the output folder (and its parents).
///
/// # Errors
/// [`Error::File`] naming the folder.
pub fn create_folder(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).map_err(Error::file("creating the folder", out))
}

/// A job that draws a progress bar on stderr once a run has taken more than a second, at most
/// ten times a second and only when its text changes (a long minimisation reports the same
/// fraction at every iteration; a log file gets a line per change, not per report).
pub fn progress_job(id: &str) -> Job {
    struct Bar {
        start: Instant,
        last: Option<Instant>,
        text: String,
    }
    let id = id.to_string();
    let state = Mutex::new(Bar {
        start: Instant::now(),
        last: None,
        text: String::new(),
    });
    Job::with_sink(move |event| {
        let JobEvent::Progress { fraction, message } = event else {
            return;
        };
        let Ok(mut bar) = state.lock() else { return };
        let now = Instant::now();
        if now.duration_since(bar.start) < Duration::from_secs(1) {
            return;
        }
        if bar
            .last
            .is_some_and(|t| now.duration_since(t) < Duration::from_millis(100))
            && *fraction < 1.0
        {
            return;
        }
        let width = 30;
        let filled = (fraction * width as f64).round() as usize;
        let text = format!(
            "{id:<14} [{}{}] {:>3.0}% {:<40.40}",
            "#".repeat(filled),
            " ".repeat(width - filled.min(width)),
            fraction * 100.0,
            message
        );
        if text == bar.text {
            return;
        }
        bar.last = Some(now);
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r{text}");
        let _ = err.flush();
        bar.text = text;
        PROGRESS_SHOWN.store(true, std::sync::atomic::Ordering::Relaxed);
    })
}

static PROGRESS_SHOWN: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// End the progress line, if one was drawn.
fn finish_progress() {
    if PROGRESS_SHOWN.swap(false, std::sync::atomic::Ordering::Relaxed) {
        eprintln!();
    }
}

/// `--reproduce`: compute every registered number, write the report, print a summary.
fn reproduce_command(out: &Path) -> anyhow::Result<ExitCode> {
    let outcomes = reproduction::evaluate_all();
    let md = reproduction::markdown(&outcomes);
    let json = serde_json::to_string_pretty(&outcomes).context("serialising the report")?;
    create_folder(out)?;
    write_set(&[
        (out.join("reproduction.md"), md.into_bytes()),
        (out.join("reproduction.json"), json.into_bytes()),
    ])?;
    for o in &outcomes {
        emit_line(&format_args!(
            "{:<44} {:<12} printed {:<14} computed {:<14} {:?}{}",
            o.id,
            o.source,
            o.printed_text,
            if o.computed.is_nan() {
                "-".to_string()
            } else {
                fmt_float(o.computed)
            },
            o.status,
            if o.as_expected { "" } else { "  UNEXPECTED" }
        ))?;
    }
    emit_line(&out.join("reproduction.md").display())?;
    emit_line(&out.join("reproduction.json").display())?;
    if outcomes.iter().all(|o| o.as_expected) {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(Error::Unresolvable {
            model: "reproduction",
            reason: "some claims changed status (marked UNEXPECTED)".into(),
        }
        .into())
    }
}

#[cfg(test)]
mod gallery_tests {
    use super::*;

    #[test]
    fn gallery_shows_every_figure_with_its_caption_and_escapes_text() {
        let entries = vec![
            GalleryEntry {
                id: "fig1.1",
                title: "JKR",
                caption: "P < 0 & pull-off",
                image: Some("fig1.1.png".into()),
                error: None,
                quick_form: Some("steps = 100 (full: 1000)".into()),
            },
            GalleryEntry {
                id: "fig9.9",
                title: "broken",
                caption: "c",
                image: None,
                error: Some("no bracket".into()),
                quick_form: None,
            },
        ];
        let html = gallery_html(&entries);
        assert!(html.contains("<img src=\"fig1.1.png\""));
        assert!(html.contains("P &lt; 0 &amp; pull-off"));
        assert!(html.contains("failed: no bracket"));
        assert!(html.contains("quick form: steps = 100 (full: 1000)"));
        assert_eq!(html.matches("quick form:").count(), 1);
        assert_eq!(html.matches("<figure").count(), 2);
    }
}
