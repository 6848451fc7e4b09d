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
use crate::render::plot::Print;
use crate::render::{Format, data, pdf, plot, write_set};
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
    let print = Print::new(cli.width_mm, cli.dpi)?;
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
        let (_, written) = export_scene_at(scene, &values, &cli.out, &formats, &print, &progress_job(id))?;
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
            let outcome = values.and_then(|values| {
                export_scene_at(scene, &values, &cli.out, &formats, &print, &progress_job(id))
            });
            let mut entry = GalleryEntry {
                id,
                chapter: info.chapter,
                title: info.title,
                caption: info.caption,
                thumbnail: None,
                files: Vec::new(),
                notes: Vec::new(),
                quick_form,
                error: None,
            };
            match outcome.and_then(|(fig, paths)| {
                let thumb = write_thumbnail(&fig, &cli.out)?;
                Ok((fig, paths, thumb))
            }) {
                Ok((fig, paths, thumb)) => {
                    for p in &paths {
                        emit_line(&p.display())?;
                    }
                    entry.files = paths
                        .iter()
                        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                        .collect();
                    entry.thumbnail = Some(thumb);
                    // The quick form has its own line on the page.
                    entry.notes = figure_notes(&fig)
                        .into_iter()
                        .filter(|n| !n.starts_with("quick form:"))
                        .collect();
                }
                Err(e) => {
                    failed += 1;
                    eprintln!("error: {id}: {e}");
                    entry.error = Some(format!("{e:#}"));
                }
            }
            gallery.push(entry);
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
    /// Chapter key (the table of contents groups by it).
    pub chapter: &'static str,
    /// Title.
    pub title: &'static str,
    /// Caption (math markup and Greek names, shown with Unicode letters and sub-/superscripts).
    pub caption: &'static str,
    /// The small PNG shown on the page (a path relative to the page), if one was written.
    pub thumbnail: Option<String>,
    /// The files written for the figure, next to the page (linked by their extension).
    pub files: Vec<String>,
    /// The figure's notes: what the workbench finds where it differs from the text.
    pub notes: Vec<String>,
    /// Why the scene failed, if it did.
    pub error: Option<String>,
    /// What its quick form computed more coarsely ([`scenes::quick_form`]), if it ran in one.
    pub quick_form: Option<String>,
}

/// Width of a gallery thumbnail (pixels).
const THUMBNAIL_PX: f64 = 480.0;

/// Write the gallery's thumbnail of `fig`, `thumbs/<id>.png` under `out`, a PNG about
/// [`THUMBNAIL_PX`] wide; returns its path relative to `out`.
///
/// # Errors
/// Rendering and I/O errors.
pub fn write_thumbnail(fig: &Figure, out: &Path) -> Result<String> {
    let width_mm = Print::default().width_of(fig);
    let dpi = (THUMBNAIL_PX / (width_mm / 25.4)).max(Print::MIN_DPI);
    let bytes = plot::png_bytes_at(fig, &Print::new(Some(width_mm), Some(dpi))?)?;
    let name = format!("thumbs/{}.png", fig.id);
    create_folder(&out.join("thumbs"))?;
    crate::render::write_atomic(&out.join(&name), &bytes)?;
    Ok(name)
}

/// The notes of a figure and of its panels, each once (panel notes with the panel's letter).
pub fn figure_notes(fig: &Figure) -> Vec<String> {
    let mut notes: Vec<String> = Vec::new();
    let mut add = |n: String| {
        if !notes.contains(&n) {
            notes.push(n);
        }
    };
    for n in &fig.notes {
        add(n.clone());
    }
    for p in &fig.panels {
        for n in &p.notes {
            add(if p.label.is_empty() {
                n.clone()
            } else {
                format!("{} {n}", p.label)
            });
        }
    }
    notes
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The gallery page written by `--all`: a table of contents by chapter, then every figure as a
/// thumbnail linking to its full-size image, with links to its files (SVG, PDF, CSV, JSON), its
/// caption with Unicode math, whether it ran in quick form, and its notes.
pub fn gallery_html(entries: &[GalleryEntry]) -> String {
    let math = |s: &str| crate::render::text::html(&crate::render::text::greek_words(s));
    let mut out = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n\
         <title>adhesion: every figure</title>\n<style>body{font-family:sans-serif;max-width:1100px;\
         margin:auto;padding:1em}figure{margin:2em 0;border-top:1px solid #ccc;padding-top:1em}\
         img{max-width:100%;border:1px solid #eee}figcaption{max-width:60em}.error{color:#b00}\
         .files a{margin-right:.8em}.quick{color:#a60}.notes{font-size:90%;color:#333}</style>\
         </head><body>\n<h1>Figures of the adhesion workbench</h1>\n<nav><h2>Contents</h2>\n",
    );
    let mut chapter = None;
    for e in entries {
        if chapter != Some(e.chapter) {
            if chapter.is_some() {
                out.push_str("</ul>\n");
            }
            chapter = Some(e.chapter);
            out.push_str(&format!(
                "<h3>Chapter {}: {}</h3>\n<ul>\n",
                html_escape(e.chapter),
                html_escape(chapter_title(e.chapter))
            ));
        }
        out.push_str(&format!(
            "<li><a href=\"#{id}\">{id}</a>: {t}</li>\n",
            id = html_escape(e.id),
            t = math(e.title)
        ));
    }
    if chapter.is_some() {
        out.push_str("</ul>\n");
    }
    out.push_str("</nav>\n");
    for e in entries {
        out.push_str(&format!("<figure id=\"{}\">\n", html_escape(e.id)));
        let full = ["png", "svg", "pdf"]
            .iter()
            .find_map(|ext| e.files.iter().find(|f| f.ends_with(&format!(".{ext}"))));
        if let Some(thumb) = &e.thumbnail {
            let img = format!(
                "<img src=\"{}\" alt=\"{}\" loading=\"lazy\" width=\"{}\">",
                html_escape(thumb),
                html_escape(e.title),
                THUMBNAIL_PX
            );
            match full {
                Some(f) => out.push_str(&format!("<a href=\"{}\">{img}</a>\n", html_escape(f))),
                None => out.push_str(&format!("{img}\n")),
            }
        }
        if !e.files.is_empty() {
            out.push_str("<p class=\"files\">");
            for ext in ["png", "svg", "pdf", "csv", "json"] {
                if let Some(f) = e.files.iter().find(|f| f.ends_with(&format!(".{ext}"))) {
                    out.push_str(&format!(
                        "<a href=\"{}\">{}</a>",
                        html_escape(f),
                        ext.to_uppercase()
                    ));
                }
            }
            out.push_str("</p>\n");
        }
        if let Some(err) = &e.error {
            out.push_str(&format!("<p class=\"error\">failed: {}</p>\n", html_escape(err)));
        }
        if let Some(q) = &e.quick_form {
            out.push_str(&format!(
                "<p class=\"quick\">quick form: {} (export it with --figure for the full run)</p>\n",
                html_escape(q)
            ));
        }
        out.push_str(&format!(
            "<figcaption><b>{}</b> {}. {}</figcaption>\n",
            html_escape(e.id),
            math(e.title),
            math(e.caption),
        ));
        if !e.notes.is_empty() {
            out.push_str("<ul class=\"notes\">\n");
            for n in &e.notes {
                out.push_str(&format!("<li>{}</li>\n", math(n)));
            }
            out.push_str("</ul>\n");
        }
        out.push_str("</figure>\n");
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
        let f = Format::parse(n)
            .with_context(|| format!("unknown format `{n}`: use png, svg, csv, json or pdf"))?;
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

/// Run a scene and write its files at the default print size. Nothing is written unless the
/// run succeeds.
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
    export_scene_at(scene, values, out, formats, &Print::default(), job).map(|(_, paths)| paths)
}

/// [`export_scene`] with the figures at the print size `print` (`--width-mm`, `--dpi`);
/// returns the figure with the paths written.
///
/// # Errors
/// Run errors, rendering errors, I/O errors.
pub fn export_scene_at(
    scene: &dyn SceneDyn,
    values: &ParamValues,
    out: &Path,
    formats: &[Format],
    print: &Print,
    job: &Job,
) -> Result<(Figure, Vec<PathBuf>)> {
    let start = Instant::now();
    let fig = scene.run(values, job)?;
    let run_time = start.elapsed().as_secs_f64();
    finish_progress();
    let record = FigureRecord {
        fig: &fig,
        caption: scene.info().caption,
        values,
        run_time_s: run_time,
        runs: &[],
    };
    let paths = write_figure_at(&record, out, formats, print)?;
    Ok((fig, paths))
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
    let record = FigureRecord {
        fig,
        caption,
        values,
        run_time_s,
        runs,
    };
    write_figure_at(&record, out, formats, &Print::default())
}

/// A computed figure with what its JSON records beside it.
pub struct FigureRecord<'a> {
    /// The figure.
    pub fig: &'a Figure,
    /// The scene's caption.
    pub caption: &'a str,
    /// The parameters of the run.
    pub values: &'a ParamValues,
    /// Run time (s).
    pub run_time_s: f64,
    /// Earlier runs drawn in the figure (pinned in the terminal UI).
    pub runs: &'a [data::RunRecord<'a>],
}

/// [`write_figure_with_runs`] at the print size `print`: `<out>/<id>.<ext>` per format, all
/// rendered in memory first and written together.
///
/// # Errors
/// Rendering and I/O errors; on error no new file is left behind.
pub fn write_figure_at(
    record: &FigureRecord<'_>,
    out: &Path,
    formats: &[Format],
    print: &Print,
) -> Result<Vec<PathBuf>> {
    let fig = record.fig;
    let path = |f: Format| out.join(format!("{}.{}", fig.id, f.extension()));
    // Render every format in memory first: a failure there writes nothing.
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for &f in formats {
        let bytes = match f {
            Format::Png => plot::png_bytes_at(fig, print)?,
            Format::Svg => plot::svg_string_at(fig, print)?.into_bytes(),
            Format::Pdf => pdf::pdf_bytes_at(fig, print)?,
            Format::Csv => data::csv(fig).into_bytes(),
            Format::Json => {
                data::json_with_runs(fig, record.caption, record.values, record.run_time_s, record.runs)
                    .into_bytes()
            }
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
    .without_previews()
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
        let entry = |id, title, caption| GalleryEntry {
            id,
            chapter: "1",
            title,
            caption,
            thumbnail: None,
            files: Vec::new(),
            notes: Vec::new(),
            quick_form: None,
            error: None,
        };
        let entries = vec![
            GalleryEntry {
                thumbnail: Some("thumbs/fig1.1.png".into()),
                files: vec!["fig1.1.png".into(), "fig1.1.csv".into(), "fig1.1.pdf".into()],
                notes: vec!["mu_T = 2 differs".into()],
                quick_form: Some("steps = 100 (full: 1000)".into()),
                ..entry("fig1.1", "JKR", "P < 0 & pull-off at P_adh/(2E*R^2)")
            },
            GalleryEntry {
                error: Some("no bracket".into()),
                ..entry("fig9.9", "broken", "c")
            },
        ];
        let html = gallery_html(&entries);
        // The thumbnail links to the full-size PNG; the files by their kind.
        assert!(html.contains("<a href=\"fig1.1.png\"><img src=\"thumbs/fig1.1.png\""));
        assert!(html.contains("<a href=\"fig1.1.pdf\">PDF</a>"));
        assert!(html.contains("<a href=\"fig1.1.csv\">CSV</a>"));
        assert!(!html.contains("SVG</a>"));
        // Captions and notes with Unicode math, escaped.
        assert!(html.contains("P &lt; 0 &amp; pull-off"), "{html}");
        assert!(
            html.contains("P<sub>adh</sub>/(2E<sup>*</sup>R<sup>2</sup>)"),
            "{html}"
        );
        assert!(html.contains("μ<sub>T</sub> = 2 differs"), "{html}");
        assert!(html.contains("quick form"));
        assert!(html.contains("failed: no bracket"));
        assert!(html.contains("<h3>Chapter 1"));
        assert!(html.contains("quick form: steps = 100 (full: 1000)"));
        assert_eq!(html.matches("quick form:").count(), 1);
        assert_eq!(html.matches("<figure").count(), 2);
    }
}
