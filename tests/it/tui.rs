//! The terminal UI driven without a terminal: keys into a [`Session`], frames drawn into
//! ratatui's `TestBackend`. Select a scene, run it in the background and see the chart; an
//! invalid value is shown and blocks running; `Esc` cancels a running job; export writes the
//! four files; presets are saved and loaded; the key help; a multi-panel figure; a scene that
//! panics is reported, not fatal. Waits on the worker are bounded.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use adhesion::error::{Error, Result};
use adhesion::figure::{Axis, Figure, Panel, Series, Style};
use adhesion::job::Job;
use adhesion::params::Range;
use adhesion::scenes::sweep::{Sweep, Swept};
use adhesion::scenes::{self, Registered, Scene, SceneDyn, SceneHeader};
use adhesion::tui::app::{App, FigureState, Focus, Mode, Page};
use adhesion::tui::session::Session;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

/// Upper bound on any wait for the worker (runs here take milliseconds).
pub(crate) const WAIT: Duration = Duration::from_secs(20);

adhesion::param_choice! {
    /// What the probe scene's run does.
    pub enum Behaviour { Finish = "finish", Wait = "wait", Panic = "panic", Grow = "grow" }
}

adhesion::scene_params! {
    /// Parameters of the probe scene.
    pub struct ProbeParams {
        /// What the run does: finish, wait to be cancelled, panic, or grow in steps (`GATE`).
        behaviour: Behaviour = Behaviour::Finish, unit = "", range = Range::any();
        /// Amplitude of the drawn sine.
        amplitude: f64 = 1.0, unit = "m", range = Range::positive();
    }
}

adhesion::scene! {
    /// A scene for the UI tests: two panels, a preview, and runs that wait for cancellation.
    pub(crate) struct Probe {
        id: "probe",
        chapter: "1",
        params: ProbeParams,
        title: "Probe scene",
        caption: "A sine, for the terminal UI tests.",
        results: &[("amplitude_m", "the amplitude")],
    }
}

fn sine(amplitude: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1) as f64 * 6.0;
            (x, amplitude * x.sin())
        })
        .collect()
}

impl Scene for Probe {
    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let mut first = Panel::new(Axis::linear("x", ""), Axis::linear("y", "m"));
        first.label = "(a)".into();
        first.add(Series::new("rising sine", Style::Stable, sine(p.amplitude, 200)));
        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(first.clone());
        match p.behaviour {
            Behaviour::Finish => {}
            Behaviour::Panic => panic!("probe panics on purpose"),
            Behaviour::Grow => return grow(p, job),
            Behaviour::Wait => {
                job.progress(0.5, "waiting for Esc");
                job.preview(&fig);
                let start = Instant::now();
                while start.elapsed() < WAIT {
                    job.check()?;
                    std::thread::sleep(Duration::from_millis(2));
                }
                return Err(Error::Unresolvable {
                    model: "probe",
                    reason: "never cancelled".into(),
                });
            }
        }
        let mut second = Panel::new(Axis::linear("x", ""), Axis::linear("y", "m"));
        second.label = "(b)".into();
        second.add(Series::new(
            "falling sine",
            Style::Unstable,
            sine(-p.amplitude, 200),
        ));
        fig.panels.push(second);
        fig.result("amplitude_m", p.amplitude);
        Ok(fig)
    }
}

pub(crate) static PROBE: Registered<Probe> = Registered::<Probe>::NEW;

/// Steps the `grow` behaviour may take (set by the one test that uses it).
static GATE: AtomicUsize = AtomicUsize::new(0);

/// The `grow` behaviour: a preview of 100·k points on x in [0, 2k/3] for k = 1, 2, 3, each step
/// after the test has released it; then the complete figure.
fn grow(p: &ProbeParams, job: &Job) -> Result<Figure> {
    let figure = |k: usize| {
        // A fixed x range, so that a longer curve covers more of the chart.
        let x_axis = Axis::linear("x", "").with_range(0.0, 2.0);
        let mut panel = Panel::new(x_axis, Axis::linear("y", "m"));
        let points = sine(p.amplitude, 100 * k)
            .into_iter()
            .map(|(x, y)| (x * k as f64 / 9.0, y))
            .collect();
        panel.add(Series::new("growing sine", Style::Stable, points));
        Figure::new(Probe::ID, Probe::TITLE).with_panel(panel)
    };
    for k in 1..=3 {
        let start = Instant::now();
        while GATE.load(Ordering::SeqCst) < k - 1 {
            job.check()?;
            if start.elapsed() > WAIT {
                return Err(Error::Unresolvable {
                    model: "probe",
                    reason: "never released".into(),
                });
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        // Longer than the worker's preview interval, so no preview is dropped.
        std::thread::sleep(Duration::from_millis(100));
        job.progress(k as f64 / 3.0, &format!("step {k}/3"));
        job.preview(&figure(k));
    }
    Ok(figure(3))
}

pub(crate) fn key(code: KeyCode) -> KeyEvent {
    KeyEvent::new(code, KeyModifiers::NONE)
}

pub(crate) fn press(s: &mut Session, code: KeyCode) {
    s.key(key(code));
}

pub(crate) fn type_text(s: &mut Session, text: &str) {
    for c in text.chars() {
        press(s, KeyCode::Char(c));
    }
}

pub(crate) fn clear_line(s: &mut Session) {
    s.key(KeyEvent::new(KeyCode::Char('u'), KeyModifiers::CONTROL));
}

pub(crate) fn session(dir: &Path, scenes: Vec<&'static dyn SceneDyn>) -> Session {
    Session::new(scenes, dir.join("out"), dir.join("presets"))
}

pub(crate) fn draw(s: &Session) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(140, 40)).expect("test backend");
    terminal.draw(|f| s.draw(f)).expect("drawing into a test backend");
    terminal.backend().buffer().clone()
}

pub(crate) fn text(buf: &Buffer) -> String {
    let mut out = String::new();
    for y in 0..buf.area.height {
        for x in 0..buf.area.width {
            out.push_str(buf[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// Number of braille cells with at least one dot (the chart's curves).
pub(crate) fn braille_cells(buf: &Buffer) -> usize {
    buf.content()
        .iter()
        .filter(|c| {
            c.symbol()
                .chars()
                .any(|ch| ('\u{2801}'..='\u{28ff}').contains(&ch))
        })
        .count()
}

pub(crate) fn idle(app: &App) -> bool {
    app.running().is_none()
}

#[test]
fn selecting_and_running_a_scene_draws_its_chart() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    let screen = text(&draw(&s));
    assert!(
        screen.contains("Classical theories"),
        "chapter heading:\n{screen}"
    );
    assert!(screen.contains("fig1.4b"), "scene list:\n{screen}");
    assert_eq!(braille_cells(&draw(&s)), 0);

    // Select the second scene, then go back to fig1.1.
    press(&mut s, KeyCode::Down);
    assert_eq!(s.app().scene().expect("a scene").info().id, "fig1.4b");
    press(&mut s, KeyCode::Up);
    assert_eq!(s.app().scene().expect("a scene").info().id, "fig1.1");

    press(&mut s, KeyCode::Char('r'));
    assert!(s.app().running().is_some(), "r starts a run");
    assert!(s.wait_until(WAIT, idle), "the run ends");
    let view = s.app().figure(0).expect("a figure");
    assert_eq!(view.state, FigureState::Complete);
    assert!(
        s.app().status().text.starts_with("fig1.1 done in"),
        "{:?}",
        s.app().status()
    );

    let buf = draw(&s);
    let screen = text(&buf);
    assert!(braille_cells(&buf) > 100, "the chart is drawn:\n{screen}");
    for label in ["Hertz", "JKR", "DMT", "Contact force", "computed in"] {
        assert!(screen.contains(label), "`{label}` on screen:\n{screen}");
    }
    // The caption and results page.
    press(&mut s, KeyCode::Char('i'));
    let screen = text(&draw(&s));
    assert!(screen.contains("jkr_pull_off_force_norm"), "results:\n{screen}");
}

#[test]
fn an_invalid_value_is_shown_and_blocks_running() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Enter); // to the form
    assert_eq!(s.app().focus(), Focus::Form);
    press(&mut s, KeyCode::Enter); // edit the first field, radius
    clear_line(&mut s);
    type_text(&mut s, "-1");
    let buf = draw(&s);
    let screen = text(&buf);
    assert!(screen.contains("INVALID"), "{screen}");
    assert!(
        screen.contains("invalid parameter `radius` = -1: must be positive"),
        "{screen}"
    );
    // The field's row is drawn in the error colour.
    let row = (0..buf.area.height)
        .find(|&y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
                .contains("✗radius")
        })
        .expect("the radius row is marked");
    let x = (0..buf.area.width)
        .find(|&x| buf[(x, row)].symbol() == "r")
        .expect("row text");
    assert_eq!(buf[(x, row)].fg, ratatui::style::Color::LightRed);

    press(&mut s, KeyCode::Enter); // keep the invalid text
    press(&mut s, KeyCode::Char('r'));
    assert!(s.app().running().is_none(), "an invalid form does not run");
    assert!(s.app().status().error);
    assert_eq!(
        s.app().status().text,
        "cannot run fig1.1: invalid parameter `radius` = -1: must be positive"
    );
    // The values a run would use are still the last valid ones.
    let form = s.app().form().expect("a form");
    assert_eq!(form.values().get("radius"), Some(&toml::Value::Float(10.0e-6)));

    // A non-number and NaN are rejected the same way.
    press(&mut s, KeyCode::Enter);
    clear_line(&mut s);
    type_text(&mut s, "ten");
    assert_eq!(
        s.app().status().text,
        "parameter `radius` expects a number, got `ten`"
    );
    clear_line(&mut s);
    type_text(&mut s, "NaN");
    assert!(s.app().status().text.contains("must be a finite number"));

    // Fixing it makes the form runnable again.
    clear_line(&mut s);
    type_text(&mut s, "2e-5");
    press(&mut s, KeyCode::Enter);
    assert!(s.app().form().expect("a form").is_valid());
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle));
    let view = s.app().figure(0).expect("a figure");
    assert_eq!(view.state, FigureState::Complete);
    assert_eq!(view.values.get("radius"), Some(&toml::Value::Float(2e-5)));
    let screen = text(&draw(&s));
    assert!(screen.contains("*radius"), "changed value marked:\n{screen}");
    assert!(!screen.contains("parameters changed since this run"), "{screen}");
    // Editing after the run marks the figure as computed with other values.
    press(&mut s, KeyCode::Down);
    press(&mut s, KeyCode::Enter);
    type_text(&mut s, "0");
    press(&mut s, KeyCode::Enter);
    let screen = text(&draw(&s));
    assert!(screen.contains("parameters changed since this run"), "{screen}");
}

#[test]
fn escape_cancels_a_running_job_and_keeps_the_partial_chart() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Tab);
    press(&mut s, KeyCode::Char(' ')); // behaviour: finish -> wait
    assert_eq!(
        s.app().form().expect("a form").values().get("behaviour"),
        Some(&toml::Value::String("wait".into()))
    );
    press(&mut s, KeyCode::Char('r'));
    assert!(
        s.wait_until(WAIT, |a| a.figure(0).is_some()),
        "the preview arrives"
    );
    assert!(s.app().running().is_some(), "still running");
    let buf = draw(&s);
    let screen = text(&buf);
    assert!(braille_cells(&buf) > 20, "the partial chart is drawn:\n{screen}");
    assert!(screen.contains("rising sine"), "{screen}");
    assert!(screen.contains("partial"), "{screen}");
    assert!(screen.contains("Esc cancels"), "the gauge:\n{screen}");
    assert!(screen.contains("50% waiting for Esc"), "the progress:\n{screen}");
    // Export is refused while the figure is partial.
    press(&mut s, KeyCode::Char('e'));
    assert!(s.app().status().error);

    press(&mut s, KeyCode::Esc);
    assert!(s.app().running().expect("still tracked").cancelling);
    assert!(s.wait_until(WAIT, idle), "the run stops after Esc");
    assert_eq!(s.app().figure(0).expect("kept").state, FigureState::Cancelled);
    assert!(
        s.app().status().text.starts_with("probe cancelled"),
        "{:?}",
        s.app().status()
    );
    let screen = text(&draw(&s));
    assert!(screen.contains("cancelled"), "{screen}");
    assert!(!std::fs::exists(dir.path().join("out")).unwrap_or(true));

    // The history keeps the cancelled run, with the time of day it ended; it is not exported.
    assert_eq!(s.app().history().len(), 1);
    let entry = &s.app().history()[0];
    assert_eq!(entry.state, FigureState::Cancelled);
    let line = adhesion::tui::view::history_line(s.app(), entry);
    let time = adhesion::tui::view::time_of_day(entry.finished_at);
    assert!(line.starts_with(&time) && line.contains("cancelled"), "{line}");
    assert_eq!(time.len(), 8, "{time}");
    press(&mut s, KeyCode::Char('h'));
    press(&mut s, KeyCode::Char('e'));
    assert!(s.app().status().error, "{:?}", s.app().status());
    assert!(!std::fs::exists(dir.path().join("out")).unwrap_or(true));
}

/// Number of points of the first series of scene 0's figure.
fn shown_points(app: &App) -> usize {
    app.figure(0)
        .and_then(|v| v.figure.panels.first())
        .and_then(|p| p.series.first())
        .map_or(0, |s| s.points.len())
}

#[test]
fn the_chart_grows_as_partial_results_arrive() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Tab);
    for _ in 0..3 {
        press(&mut s, KeyCode::Char(' ')); // finish -> wait -> panic -> grow
    }
    press(&mut s, KeyCode::Char('r'));
    let mut cells = Vec::new();
    for k in 1..=2 {
        assert!(
            s.wait_until(WAIT, |a| shown_points(a) == 100 * k),
            "preview {k} arrives"
        );
        assert_eq!(s.app().figure(0).expect("preview").state, FigureState::Partial);
        let screen = text(&draw(&s));
        assert!(screen.contains(&format!("step {k}/3")), "{screen}");
        cells.push(braille_cells(&draw(&s)));
        GATE.store(k, Ordering::SeqCst);
    }
    assert!(s.wait_until(WAIT, idle));
    assert_eq!(shown_points(s.app()), 300);
    assert_eq!(s.app().figure(0).expect("figure").state, FigureState::Complete);
    cells.push(braille_cells(&draw(&s)));
    assert!(
        cells.windows(2).all(|w| w[1] > w[0]),
        "the curve covers more cells at every step: {cells:?}"
    );
}

#[test]
fn auto_run_reruns_after_every_valid_change_only() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Char('a'));
    assert!(s.app().auto_run());
    assert!(
        s.app().running().is_some(),
        "switching auto-run on runs the current values"
    );
    assert!(s.wait_until(WAIT, idle));
    assert!(text(&draw(&s)).contains("auto-run"));

    press(&mut s, KeyCode::Enter);
    press(&mut s, KeyCode::Enter);
    clear_line(&mut s);
    assert!(s.app().running().is_none(), "an empty field does not run");
    type_text(&mut s, "-");
    assert!(s.app().running().is_none(), "an invalid value does not run");
    clear_line(&mut s);
    type_text(&mut s, "2e-5");
    assert!(s.wait_until(WAIT, idle));
    let view = s.app().figure(0).expect("a figure");
    assert_eq!(view.state, FigureState::Complete);
    assert_eq!(view.values.get("radius"), Some(&toml::Value::Float(2e-5)));
    // Leaving the field changes nothing: no new run.
    press(&mut s, KeyCode::Enter);
    assert!(s.app().running().is_none());
    press(&mut s, KeyCode::Char('d'));
    assert!(s.wait_until(WAIT, idle));
    let view = s.app().figure(0).expect("a figure");
    assert_eq!(view.values, s.app().form().expect("form").values().clone());
    assert_eq!(view.values.get("radius"), Some(&toml::Value::Float(10.0e-6)));
}

#[test]
fn a_new_run_replaces_the_running_one() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Tab);
    press(&mut s, KeyCode::Char(' ')); // wait
    press(&mut s, KeyCode::Char('r'));
    let first = s.app().running().expect("running").job;
    press(&mut s, KeyCode::Char(' ')); // wait -> panic
    press(&mut s, KeyCode::Char(' ')); // panic -> grow
    press(&mut s, KeyCode::Char(' ')); // grow -> finish
    press(&mut s, KeyCode::Char('r'));
    let second = s.app().running().expect("running").job;
    assert_ne!(first, second);
    assert!(s.wait_until(WAIT, idle));
    let view = s.app().figure(0).expect("a figure");
    assert_eq!(view.state, FigureState::Complete, "{:?}", s.app().status());
    assert_eq!(view.figure.panels.len(), 2);
}

#[test]
fn panels_switch_and_a_panicking_scene_is_reported() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle));
    let screen = text(&draw(&s));
    assert!(
        screen.contains("(a)") && screen.contains("(b)"),
        "tabs:\n{screen}"
    );
    assert!(screen.contains("rising sine"), "{screen}");
    press(&mut s, KeyCode::Right);
    assert_eq!(s.app().panel(), 1);
    let screen = text(&draw(&s));
    assert!(screen.contains("falling sine"), "{screen}");
    press(&mut s, KeyCode::Right); // stays on the last panel
    assert_eq!(s.app().panel(), 1);
    press(&mut s, KeyCode::Char('['));
    assert_eq!(s.app().panel(), 0);

    press(&mut s, KeyCode::Tab);
    press(&mut s, KeyCode::Char(' '));
    press(&mut s, KeyCode::Char(' ')); // panic
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle));
    let status = s.app().status();
    assert!(status.error);
    assert!(status.text.contains("probe panics on purpose"), "{status:?}");
    // The last complete figure stays.
    assert_eq!(s.app().figure(0).expect("kept").state, FigureState::Complete);
}

#[test]
fn export_writes_png_svg_csv_and_json() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Char('e'));
    assert_eq!(
        s.app().status().text,
        "nothing to export: run the scene first (r)"
    );
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle));
    press(&mut s, KeyCode::Char('e'));
    assert!(!s.app().status().error, "{:?}", s.app().status());
    for ext in ["png", "svg", "csv", "json"] {
        let p = dir.path().join("out").join(format!("fig1.1.{ext}"));
        let size = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        assert!(size > 100, "{} written ({size} bytes)", p.display());
    }
    let csv = std::fs::read_to_string(dir.path().join("out/fig1.1.csv")).expect("csv");
    assert!(csv.starts_with("panel,series,style,x,y"));
    let json = std::fs::read_to_string(dir.path().join("out/fig1.1.json")).expect("json");
    assert!(json.contains("jkr_hysteresis_norm"));
    assert!(
        !s.app().status().text.contains("replaced"),
        "{:?}",
        s.app().status()
    );
    // A second export says which files it replaced.
    press(&mut s, KeyCode::Char('e'));
    let status = &s.app().status().text;
    assert!(
        status.contains("replaced the earlier fig1.1.png, fig1.1.svg, fig1.1.csv, fig1.1.json"),
        "{status}"
    );
}

#[test]
fn presets_are_saved_and_loaded_and_bad_ones_are_named() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Enter);
    press(&mut s, KeyCode::Enter);
    clear_line(&mut s);
    type_text(&mut s, "3e-5");
    press(&mut s, KeyCode::Enter);

    press(&mut s, KeyCode::Char('s'));
    let Mode::Prompt { edit, .. } = s.app().mode() else {
        panic!("s opens the path prompt");
    };
    let path = dir.path().join("presets/fig1.1.toml");
    assert_eq!(edit.text(), path.display().to_string());
    assert!(text(&draw(&s)).contains("Save preset"));
    press(&mut s, KeyCode::Enter);
    assert!(!s.app().status().error, "{:?}", s.app().status());
    let saved = std::fs::read_to_string(&path).expect("preset written");
    assert!(saved.contains("radius = 3e-5"), "{saved}");

    press(&mut s, KeyCode::Char('d'));
    let radius = |s: &Session| s.app().form().expect("form").values().get("radius").cloned();
    assert_eq!(radius(&s), Some(toml::Value::Float(10.0e-6)));
    press(&mut s, KeyCode::Char('l'));
    press(&mut s, KeyCode::Enter);
    assert_eq!(radius(&s), Some(toml::Value::Float(3e-5)));

    // A misspelled key in a typed path: one line naming the file and the key.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "radus = 1e-6\n").expect("write");
    press(&mut s, KeyCode::Char('l'));
    clear_line(&mut s);
    type_text(&mut s, &bad.display().to_string());
    press(&mut s, KeyCode::Enter);
    let status = s.app().status();
    assert!(status.error);
    assert!(status.text.contains("bad.toml"), "{status:?}");
    assert!(status.text.contains("did you mean `radius`"), "{status:?}");
    assert_eq!(radius(&s), Some(toml::Value::Float(3e-5)), "kept on error");

    // Esc closes the prompt without loading.
    press(&mut s, KeyCode::Char('l'));
    press(&mut s, KeyCode::Esc);
    assert_eq!(s.app().mode(), &Mode::Normal);
}

#[test]
fn help_lists_the_keys_and_q_quits() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Char('?'));
    let screen = text(&draw(&s));
    for line in ["export the figure", "cancel the running job", "load a preset"] {
        assert!(screen.contains(line), "`{line}` in the help:\n{screen}");
    }
    press(&mut s, KeyCode::Char('q')); // closes the help only
    assert!(!s.should_quit());
    assert_eq!(s.app().mode(), &Mode::Normal);
    press(&mut s, KeyCode::Char('q'));
    assert!(s.should_quit());

    // Ctrl-C quits even while a value is being edited (where `q` is just a letter).
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Enter);
    press(&mut s, KeyCode::Enter);
    press(&mut s, KeyCode::Char('q'));
    assert!(!s.should_quit());
    s.key(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL));
    assert!(s.should_quit());
}

#[test]
fn drawing_never_panics_on_tiny_terminals() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle));
    for (w, h) in [(1, 1), (10, 3), (30, 8), (50, 12)] {
        let mut terminal = Terminal::new(TestBackend::new(w, h)).expect("test backend");
        terminal.draw(|f| s.draw(f)).expect("draw");
        press(&mut s, KeyCode::Char('?'));
        terminal.draw(|f| s.draw(f)).expect("draw help");
        press(&mut s, KeyCode::Esc);
    }
}

/// The modules of `src/tui` a file names: `use super::x…`, `use crate::tui::x…` and such paths in
/// code, as the top-level module `x` (a file under `src/tui/app/` counts as `app`).
fn tui_imports(text: &str, own: &str, nested: bool) -> Vec<String> {
    let mut names = Vec::new();
    let mut take = |path: &str| {
        let path = path.trim_start_matches(|c: char| c == '{' || c.is_whitespace());
        let name: String = path
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if !name.is_empty() && name != own && name.chars().next().is_some_and(char::is_lowercase) {
            names.push(name);
        }
    };
    let code: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    // In a top-level file `super::` is `crate::tui::`; in a nested one `super::super::` is.
    let prefixes: &[&str] = if nested {
        &["crate::tui::", "super::super::"]
    } else {
        &["crate::tui::", "super::"]
    };
    for prefix in prefixes {
        for (at, _) in code.match_indices(prefix) {
            let rest = &code[at + prefix.len()..];
            if nested && *prefix == "crate::tui::" || !rest.starts_with('{') {
                take(rest);
                continue;
            }
            // A group: `super::{a::X, b::{Y, Z}}` names `a` and `b`.
            let mut depth = 0;
            let mut start = 1;
            for (i, c) in rest.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            take(&rest[start..i]);
                            break;
                        }
                    }
                    ',' if depth == 1 => {
                        take(&rest[start..i]);
                        start = i + 1;
                    }
                    _ => {}
                }
            }
        }
    }
    names.sort();
    names.dedup();
    names
}

/// The state of the terminal UI never imports its drawing, and the modules of `src/tui` import
/// each other without a circle (benches/import_graph.py checks the whole of `src/`).
#[test]
fn the_state_does_not_import_the_drawing_and_the_tui_modules_form_no_circle() {
    let dir = super::common::root().join("src/tui");
    let mut graph: std::collections::BTreeMap<String, Vec<String>> = Default::default();
    let mut files = Vec::new();
    for e in std::fs::read_dir(&dir).expect("src/tui").flatten() {
        let p = e.path();
        if p.is_dir() {
            for f in std::fs::read_dir(&p).expect("a folder of src/tui").flatten() {
                files.push((
                    p.file_name().unwrap().to_string_lossy().into_owned(),
                    f.path(),
                    true,
                ));
            }
        } else {
            files.push((p.file_stem().unwrap().to_string_lossy().into_owned(), p, false));
        }
    }
    for (module, path, nested) in files {
        let text = std::fs::read_to_string(&path).expect("a source file");
        let names = tui_imports(&text, &module, nested);
        graph.entry(module).or_default().extend(names);
    }
    for edges in graph.values_mut() {
        edges.retain(|n| n != "tests");
        edges.sort();
        edges.dedup();
    }
    assert!(
        graph["view"].contains(&"app".to_string()),
        "the parser sees view -> app: {graph:?}"
    );
    for state in ["app", "chart", "layout", "compare", "form", "keymap", "worker"] {
        for drawing in ["view", "session"] {
            assert!(
                !graph[state].contains(&drawing.to_string()),
                "{state} imports {drawing}: {:?}",
                graph[state]
            );
        }
    }
    // Depth-first search for a back edge.
    fn visit<'a>(
        m: &'a str,
        graph: &'a std::collections::BTreeMap<String, Vec<String>>,
        path: &mut Vec<&'a str>,
        done: &mut Vec<&'a str>,
    ) {
        if done.contains(&m) {
            return;
        }
        if let Some(at) = path.iter().position(|p| *p == m) {
            panic!("import circle: {} -> {m}", path[at..].join(" -> "));
        }
        path.push(m);
        for n in graph.get(m).into_iter().flatten() {
            visit(n, graph, path, done);
        }
        path.pop();
        done.push(m);
    }
    let mut done = Vec::new();
    for m in graph.keys() {
        visit(m, &graph, &mut Vec::new(), &mut done);
    }
}

/// A force map of the afmformats test data: 4 curves of JPK's, at the corners of a 10 × 10 grid.
fn map_fixture() -> std::path::PathBuf {
    super::common::root().join("tests/fixtures/afm/fmt-jpk-fd_map2x2_extracted.jpk-force-map")
}

fn file_idle(app: &App) -> bool {
    !app.opening() && app.file_page().is_none_or(|p| p.fitting.is_none())
}

/// `o` asks for a path; a JPK force map opens (read in the background) on the file page with
/// its grid (10 × 10, the curves at the corners); the arrow keys move to the next curve in their
/// direction, and stay at the edge.
#[test]
fn a_force_map_opens_as_a_grid_and_the_arrows_choose_its_curves() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Char('o'));
    assert!(matches!(s.app().mode(), Mode::Prompt { .. }));
    clear_line(&mut s);
    type_text(&mut s, &map_fixture().display().to_string());
    press(&mut s, KeyCode::Enter);
    assert!(s.wait_until(WAIT, |a| a.file_page().is_some() && file_idle(a)));
    assert_eq!(s.app().page(), Page::File);
    let page = s.app().file_page().expect("the file page");
    assert_eq!(page.file.curves.len(), 4);
    assert_eq!(page.grid.shape, [10, 10]);
    assert_eq!(page.selected, 0);
    let screen = text(&draw(&s));
    assert!(screen.contains("Map 10 × 10"), "{screen}");
    assert!(screen.contains("Fit of curve 0 (1 of 4)"), "{screen}");
    assert!(screen.contains("as recorded"), "{screen}");
    // The chart of the recorded curve is drawn before any fit.
    assert!(braille_cells(&draw(&s)) > 50);
    // An arrow moves to the next curve in its direction (the cells between are empty).
    let cell = |s: &Session| {
        let p = s.app().file_page().expect("the file page");
        p.grid.cells[p.selected]
    };
    let start = cell(&s);
    let right = if start[0] == 0 {
        KeyCode::Right
    } else {
        KeyCode::Left
    };
    press(&mut s, right);
    let moved = cell(&s);
    assert_eq!(moved[1], start[1]);
    assert_eq!(moved[0].abs_diff(start[0]), 9);
    let chosen = s.app().file_page().expect("the file page").selected;
    assert_ne!(chosen, 0);
    let screen = text(&draw(&s));
    assert!(screen.contains(&format!("({} of 4)", chosen + 1)), "{screen}");
    let up = if start[1] == 0 { KeyCode::Up } else { KeyCode::Down };
    press(&mut s, up);
    assert_eq!(cell(&s)[1].abs_diff(start[1]), 9);
    assert_eq!(cell(&s)[0], moved[0]);
    // Moving past the edge stays at the edge.
    let before = cell(&s);
    press(&mut s, up);
    assert_eq!(cell(&s), before);
    // Small terminals draw the page without a panic.
    for (w, h) in [(1, 1), (10, 3), (30, 8), (50, 12), (80, 24)] {
        let mut terminal = Terminal::new(TestBackend::new(w, h)).expect("test backend");
        terminal.draw(|f| s.draw(f)).expect("draw");
    }
    // g goes back to the scenes and again to the file.
    press(&mut s, KeyCode::Char('g'));
    assert_eq!(s.app().page(), Page::Scenes);
    press(&mut s, KeyCode::Char('g'));
    assert_eq!(s.app().page(), Page::File);
}

/// With a tip radius (t), r fits the chosen curve in the background (the key returns at once);
/// the page then shows the data with the fitted model and the residuals, and the values are the
/// library's own fit of the same curve. Choosing another curve fits it too.
#[test]
fn the_chosen_curve_is_fitted_in_the_background_with_data_fit_and_residuals() {
    use adhesion::fit::instrument::{PrepareOptions, fit_curve};
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    s.open_file(map_fixture());
    assert!(s.wait_until(WAIT, |a| a.file_page().is_some() && file_idle(a)));
    press(&mut s, KeyCode::Char('r'));
    assert!(s.app().status().error, "no fit without a tip radius");
    assert!(s.app().status().text.contains("tip radius"));
    press(&mut s, KeyCode::Char('t'));
    clear_line(&mut s);
    type_text(&mut s, "2e-6");
    press(&mut s, KeyCode::Enter);
    // Setting the radius starts the fit of the chosen curve; it runs on the worker.
    assert!(s.app().file_page().expect("page").fitting.is_some());
    assert!(s.wait_until(WAIT, file_idle));
    let page = s.app().file_page().expect("page");
    let fitted = match page.fits.get(&0) {
        Some(Ok(f)) => f.clone(),
        other => panic!("curve 0 not fitted: {:?}", other.map(|r| r.as_ref().err())),
    };
    let settings = page.settings().expect("settings");
    let (_, direct) = fit_curve(
        &page.file.curves[0],
        &page.path,
        &PrepareOptions::default(),
        &settings,
    )
    .expect("the library fits the same curve");
    let (e_ui, e_lib) = (
        fitted.fit.fit.plane_strain_modulus_pa.value,
        direct.fit.plane_strain_modulus_pa.value,
    );
    assert!((e_ui - e_lib).abs() <= 1e-12 * e_lib.abs(), "{e_ui} vs {e_lib}");
    // Panels: (a) the measured points with the model, (b) one residual per fitted row.
    let fig = &fitted.figure;
    assert_eq!(fig.panels.len(), 2);
    assert!(
        fig.panels[0]
            .series
            .iter()
            .any(|x| x.name.starts_with("measured"))
    );
    assert!(
        fig.panels[0]
            .series
            .iter()
            .any(|x| !x.name.starts_with("measured"))
    );
    let residuals = &fig.panels[1].series[0];
    assert_eq!(residuals.name, "residual");
    assert_eq!(residuals.points.len(), fitted.fit.fit.points_used);
    let buf = draw(&s);
    let screen = text(&buf);
    assert!(screen.contains("data, fit and residuals"), "{screen}");
    assert!(screen.contains("residuals of the fitted rows"), "{screen}");
    assert!(screen.contains("ℰ"), "{screen}");
    assert!(screen.contains("pull-off (measured)"), "{screen}");
    // The measured points and the residuals are drawn as dots.
    assert!(screen.matches('•').count() > 100, "{screen}");
    // The fitted cell is marked on the grid.
    assert!(screen.contains('●'), "{screen}");
    // Another curve is fitted as soon as it is chosen.
    press(&mut s, KeyCode::Right);
    press(&mut s, KeyCode::Left);
    press(&mut s, KeyCode::Up);
    press(&mut s, KeyCode::Down);
    assert!(s.wait_until(WAIT, file_idle));
    let page = s.app().file_page().expect("page");
    assert!(page.fits.len() >= 2, "{:?}", page.fits.keys());
}

/// A file that is not a force-curve file gives one line in the status bar and keeps the page
/// that was open; a bad tip radius is refused with its range.
#[test]
fn a_bad_file_or_radius_leaves_one_line_and_the_last_good_page() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bad = dir.path().join("notes.jpk-force");
    std::fs::write(&bad, "not a zip archive\n").expect("write");
    let mut s = session(dir.path(), vec![&PROBE]);
    s.open_file(&bad);
    assert!(s.wait_until(WAIT, file_idle));
    assert!(s.app().status().error);
    assert!(!s.app().status().text.contains('\n'));
    assert!(
        s.app().status().text.contains("notes.jpk-force"),
        "{:?}",
        s.app().status()
    );
    assert_eq!(s.app().page(), Page::Scenes);
    assert!(s.app().file_page().is_none());
    s.open_file(map_fixture());
    assert!(s.wait_until(WAIT, |a| a.file_page().is_some() && file_idle(a)));
    s.open_file(dir.path().join("missing.jpk-force"));
    assert!(s.wait_until(WAIT, file_idle));
    assert!(s.app().status().error);
    let page = s.app().file_page().expect("the last good page");
    assert_eq!(page.file.curves.len(), 4);
    assert_eq!(s.app().page(), Page::File);
    press(&mut s, KeyCode::Char('t'));
    clear_line(&mut s);
    type_text(&mut s, "-1");
    press(&mut s, KeyCode::Enter);
    assert!(s.app().status().error);
    assert!(
        s.app().status().text.contains("tip radius"),
        "{:?}",
        s.app().status()
    );
    assert!(s.app().file_page().expect("page").radius.is_none());
    let screen = text(&draw(&s));
    assert!(screen.contains("Map 10 × 10"), "{screen}");
}

/// A run pinned in normalised units is drawn on the axes of a later SI run converted with its
/// own scales: its pull-off marker lands at its own P_D and h_D (Eq. 1.4, the SI results of the
/// pinned run) in the axes' prefixed units, and its legend entry stays, saying so. The export
/// draws the same converted pin.
#[test]
fn a_normalised_pin_on_an_si_run_is_converted_with_its_own_scales() {
    use super::workbench::{at_scene, draw_at, run, set_param};
    use adhesion::render::labels::split_unit;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    run(&mut s);
    press(&mut s, KeyCode::Char('p'));
    let k = s.app().selected();
    let pinned = s.app().pins(k)[0].figure.clone();
    set_param(&mut s, "units", "si");
    set_param(&mut s, "radius", "2e-5");
    run(&mut s);
    assert!(
        s.wait_until(WAIT, |a| a.pins(k)[0].converting.is_none()),
        "the conversion ends"
    );
    assert_eq!(s.app().pins(k)[0].converted.len(), 1, "{:?}", s.app().status());
    let drawn = s.app().drawn().expect("a chart");
    assert_eq!(drawn.refused, vec![None], "the pin is drawn");
    let marker = drawn
        .panel
        .markers
        .iter()
        .find(|m| m.name.starts_with("#1") && m.name.ends_with("· pull-off"))
        .expect("the pinned pull-off marker");
    let (ex, xu) = split_unit(&drawn.panel.x.unit).expect("an SI depth axis");
    let (ey, yu) = split_unit(&drawn.panel.y.unit).expect("an SI force axis");
    assert_eq!((xu, yu), ("m", "N"));
    let h_d = pinned.result_value("jkr_pull_off_depth_m").expect("h_D") / 10f64.powi(ex);
    let p_d = pinned.result_value("jkr_pull_off_force_N").expect("P_D") / 10f64.powi(ey);
    assert!(
        (marker.x - h_d).abs() < 1e-9 * h_d.abs().max(1.0),
        "{} vs {h_d}",
        marker.x
    );
    assert!(
        (marker.y - p_d).abs() < 1e-9 * p_d.abs().max(1.0),
        "{} vs {p_d}",
        marker.y
    );
    // The current run's pull-off is twice the pin's (P_D = −(5/6)·πwR... ∝ R).
    let current = drawn
        .panel
        .markers
        .iter()
        .find(|m| m.name == "pull-off")
        .expect("the current pull-off");
    assert!(
        (current.y / marker.y - 2.0).abs() < 1e-9,
        "{} / {}",
        current.y,
        marker.y
    );
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains("#1 "), "the pin's legend entry:\n{screen}");
    assert!(screen.contains("(converted)"), "says it was converted:\n{screen}");
    // The export writes the converted pin (its CSV rows in the SI axes).
    press(&mut s, KeyCode::Char('e'));
    let csv = std::fs::read_to_string(dir.path().join("out").join("fig1.1.csv")).expect("csv");
    assert!(csv.contains("· pull-off"), "the pinned marker in the CSV");
}

/// An axis in another unit that no display parameter explains is refused, in words; a unit with
/// another SI prefix is rescaled.
#[test]
fn pins_in_units_that_cannot_be_converted_are_refused_with_a_reason() {
    use adhesion::tui::compare::{Pin, axes_fit, overlay};
    let panel = |unit: &str| {
        let mut p = Panel::new(Axis::linear("x", ""), Axis::linear("Contact force P", unit));
        p.add(Series::new("curve", Style::Stable, vec![(0.0, 1.0), (1.0, 2.0)]));
        p
    };
    let si = panel("µN");
    assert_eq!(axes_fit(&si, &panel("nN")), Ok((1.0, 1e-3)));
    let why = axes_fit(&si, &panel("")).expect_err("refused");
    assert!(why.contains("µN") && why.contains("no unit"), "{why}");
    let values = PROBE.defaults();
    let pin = Pin::new(
        Figure::new("probe", "p").with_panel(panel("")),
        values.clone(),
        0.0,
        5,
    );
    let drawn = overlay(&si, 0, &values, &[pin], &["#1 run".to_string()]);
    assert!(drawn.refused[0].is_some());
    assert_eq!(
        drawn.panel.series.len(),
        2,
        "the current curve and the pin's entry only"
    );
    assert!(
        drawn.panel.series[1].name.contains("not drawn"),
        "{}",
        drawn.panel.series[1].name
    );
}

/// A chapter 4 cycle (fig4.5) draws its P-h path as it is computed: the curve grows over at
/// least 3 frames before the run ends, the title says partial.
#[test]
fn a_chapter_4_cycle_shows_a_growing_curve_while_it_runs() {
    use super::workbench::at_scene;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig4.5");
    press(&mut s, KeyCode::Char('r'));
    let mut counts: Vec<usize> = Vec::new();
    let start = Instant::now();
    while s.app().running().is_some() && start.elapsed() < Duration::from_secs(300) {
        s.wait_until(Duration::from_millis(40), |_| false);
        if s.app().running().is_none() {
            break;
        }
        let k = s.app().selected();
        if let Some(v) = s.app().figure(k)
            && v.state == FigureState::Partial
        {
            let points: usize = v.figure.panels[0].series.iter().map(|x| x.points.len()).sum();
            let screen = text(&draw(&s));
            assert!(screen.contains("partial"), "{screen}");
            if counts.last() != Some(&points) {
                counts.push(points);
            }
        }
    }
    assert!(s.wait_until(Duration::from_secs(300), idle), "the run ends");
    assert!(counts.len() >= 3, "frames with a growing curve: {counts:?}");
    assert!(
        counts.windows(2).all(|w| w[1] > w[0]),
        "it only grows: {counts:?}"
    );
    let k = s.app().selected();
    assert_eq!(s.app().figure(k).expect("a figure").state, FigureState::Complete);
}

/// The results table beside the chart lists the pinned run's pull-off force under the current
/// run's, with the difference: P_D ∝ R (Eq. 1.4), so a pin at half the radius reads +50 %
/// against the current run's (a negative force half as large).
#[test]
fn the_comparison_table_lists_a_pins_pull_off_and_the_difference() {
    use super::workbench::{at_scene, draw_at, run, set_param};
    use adhesion::render::labels::fmt_quantity;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    run(&mut s);
    press(&mut s, KeyCode::Char('p'));
    set_param(&mut s, "radius", "2e-5");
    run(&mut s);
    let k = s.app().selected();
    let pinned = s.app().pins(k)[0]
        .figure
        .result_value("jkr_pull_off_force_N")
        .expect("P_D");
    let screen = text(&draw_at(&s, 160, 48));
    let lines: Vec<&str> = screen.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.contains("JKR pull-off force [N]"))
        .unwrap_or_else(|| panic!("the pull-off row:\n{screen}"));
    let row = lines[at + 1];
    assert!(row.contains("#1"), "the pin's row under it:\n{screen}");
    assert!(
        row.contains(&fmt_quantity(pinned, "N")),
        "its value {pinned}:\n{row}"
    );
    assert!(row.contains("(+50.0 %)"), "the difference:\n{row}");
    // Hiding the pin (1) keeps its row and legend entry.
    press(&mut s, KeyCode::Char('1'));
    assert!(s.app().pins(k)[0].hidden);
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains("(hidden)"), "{screen}");
    assert!(screen.contains("(+50.0 %)"), "{screen}");
}

/// Two nudges of a parameter in quick succession rerun the scene once, after the pause, with
/// the value stepped twice (×1.1²).
#[test]
fn nudging_twice_reruns_once_after_the_pause() {
    use adhesion::tui::app::{Effect, NUDGE_PAUSE};
    // The state alone: each nudge asks for a timer; only the last one runs.
    let mut app = App::new(vec![&PROBE], std::env::temp_dir());
    app.update(key(KeyCode::Tab));
    app.update(key(KeyCode::Down));
    let first = app.update(key(KeyCode::Char('}')));
    let second = app.update(key(KeyCode::Char('}')));
    let token = |e: &[Effect]| match e {
        [Effect::Timer { token, after }] => {
            assert_eq!(*after, NUDGE_PAUSE);
            *token
        }
        other => panic!("a timer, not {other:?}"),
    };
    let (t1, t2) = (token(&first), token(&second));
    assert!(
        app.on_timer(t1).is_empty(),
        "the first nudge's timer does nothing"
    );
    let effects = app.on_timer(t2);
    assert!(
        matches!(effects.as_slice(), [Effect::Start { .. }]),
        "{effects:?}"
    );
    assert!(app.on_timer(t2).is_empty(), "once");

    // Through a session: nothing runs before the pause, one run after it.
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Tab);
    press(&mut s, KeyCode::Down);
    press(&mut s, KeyCode::Char('}'));
    press(&mut s, KeyCode::Char('}'));
    assert!(s.app().running().is_none(), "no run before the pause");
    assert!(s.wait_until(WAIT, |a| !a.history().is_empty()), "a run after it");
    std::thread::sleep(NUDGE_PAUSE * 2);
    s.pump();
    assert_eq!(s.app().history().len(), 1, "one run");
    let amplitude = s.app().history()[0]
        .values
        .get("amplitude")
        .and_then(|v| v.as_float());
    assert!(
        amplitude.is_some_and(|a| (a - 1.21).abs() < 1e-12),
        "{amplitude:?}"
    );
}

/// At 80 × 24 every parameter value of fig1.1 shown is whole (never cut from the left), and
/// the legend is drawn and toggled by L.
#[test]
fn at_80_by_24_values_are_whole_and_the_legend_toggles() {
    use super::workbench::{at_scene, draw_at, run};
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    press(&mut s, KeyCode::Tab);
    run(&mut s);
    let screen = text(&draw_at(&s, 80, 24));
    let form = s.app().form().expect("a form");
    let layout = s.app().layout().clone();
    let first = layout.form_offset;
    let shown = usize::from(layout.form.height).min(form.len() - first);
    assert!(shown >= 3, "parameter rows at 80 × 24:\n{screen}");
    let lines: Vec<&str> = screen.lines().collect();
    for (row, k) in (first..first + shown).enumerate() {
        let line = lines[usize::from(layout.form.y) + row];
        let value = form.text(k);
        assert!(
            line.contains(&format!(" {value} ")),
            "`{value}` whole in:\n{line}\n{screen}"
        );
    }
    assert!(screen.contains("L hides"), "the legend at 80 × 24:\n{screen}");
    assert!(screen.contains("Hertz"), "its entries:\n{screen}");
    press(&mut s, KeyCode::Char('L'));
    let hidden = text(&draw_at(&s, 80, 24));
    assert!(!hidden.contains("L hides"), "{hidden}");
    press(&mut s, KeyCode::Char('L'));
    assert!(text(&draw_at(&s, 80, 24)).contains("L hides"));
}

/// Nudging as a slider over the pull-off: with the cursor on fig1.1's pull-off marker and a
/// pin, a nudge of the radius (×1.1) reruns, the cursor stays on the pull-off of the new run,
/// and the readout shows how it moved against the pin: P_D ∝ R (Eq. 1.4), so by a tenth of the
/// pin's P_D.
#[test]
fn the_cursor_stays_on_the_pull_off_across_nudges_and_reads_the_change() {
    use super::workbench::{at_scene, draw_at, run, set_param};
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    set_param(&mut s, "units", "si");
    run(&mut s);
    press(&mut s, KeyCode::Char('p'));
    for _ in 0..12 {
        if s.app().readout().is_some_and(|r| r.name == "pull-off (D)") {
            break;
        }
        press(&mut s, KeyCode::Char('m'));
    }
    assert_eq!(s.app().readout().expect("a readout").name, "pull-off (D)");
    let before = s.app().readout().expect("a readout").point;
    // The radius is the first parameter.
    press(&mut s, KeyCode::Tab);
    while s.app().form().expect("a form").selected() > 0 {
        press(&mut s, KeyCode::Up);
    }
    press(&mut s, KeyCode::Char('}'));
    assert!(
        s.wait_until(WAIT, |a| a.history().len() == 2 && idle(a)),
        "the nudge reruns"
    );
    let r = s.app().readout().expect("the cursor is kept");
    assert_eq!(r.name, "pull-off (D)");
    assert!(
        (r.point.1 / before.1 - 1.1).abs() < 1e-9,
        "{:?} vs {before:?}",
        r.point
    );
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains("Δ vs #1: x "), "{screen}");
    let k = s.app().selected();
    let pinned = s.app().pins(k)[0]
        .figure
        .result_value("jkr_pull_off_force_N")
        .expect("P_D");
    let moved = adhesion::render::labels::fmt_quantity(0.1 * pinned, "N");
    assert!(screen.contains(&format!("y {moved}")), "Δy = {moved}:\n{screen}");
}

adhesion::scene_params! {
    /// Parameters of the probe sweep.
    pub struct ProbeSweepParams {
        /// Points of the sweep.
        points: usize = 8, unit = "", range = Range::between(2.0, 100.0);
    }
}

adhesion::scene! {
    /// A sweep for the UI tests: point `id` gives `id²` once the test has released it
    /// (`SWEEP_GATE` > `id`), and waits (cancellable) until then.
    pub(crate) struct ProbeSweep {
        id: "probe-sweep",
        chapter: "1",
        params: ProbeSweepParams,
        title: "Probe sweep",
        caption: "Squares, point by point, for the terminal UI tests.",
        results: &[("sum_norm", "the sum of the squares")],
    }
}

/// Points of the probe sweep released so far.
static SWEEP_GATE: AtomicUsize = AtomicUsize::new(0);

impl Scene for ProbeSweep {
    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        adhesion::scenes::sweep::run::<Self>(p, job)
    }
}

impl Sweep for ProbeSweep {
    type Context = ();

    fn points(p: &Self::Params) -> Vec<String> {
        (0..p.points).map(|i| format!("x = {i}")).collect()
    }

    fn run_point(_p: &Self::Params, _context: &(), id: usize, job: &Job) -> Result<Vec<f64>> {
        let start = Instant::now();
        while SWEEP_GATE.load(Ordering::SeqCst) <= id {
            job.check()?;
            if start.elapsed() > WAIT {
                return Err(Error::Unresolvable {
                    model: "probe",
                    reason: "never released".into(),
                });
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        Ok(vec![(id * id) as f64])
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], _job: &Job) -> Result<Figure> {
        let squares: Vec<(f64, f64)> = points.iter().enumerate().map(|(i, v)| (i as f64, v[0])).collect();
        let x_axis = Axis::linear("x", "").with_range(0.0, (p.points - 1) as f64);
        let mut panel = Panel::new(x_axis, Axis::linear("x²", ""));
        panel.add(Series::new("squares", Style::Stable, squares));
        panel.annotate("a finding about every point");
        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(panel);
        fig.result("sum_norm", points.iter().map(|v| v[0]).sum());
        fig.note("a note about every point");
        Ok(fig)
    }
}

static PROBE_SWEEP: Swept<ProbeSweep> = Swept::<ProbeSweep>::NEW;

/// The finite points of the first series of scene 0's figure.
fn sweep_points(app: &App) -> Vec<(f64, f64)> {
    app.figure(0)
        .and_then(|v| v.figure.panels.first())
        .and_then(|p| p.series.first())
        .map_or(Vec::new(), |s| s.points.clone())
}

/// A sweep fills its points as they finish: released one, then two, of eight points (each
/// after the interval between previews, so the point that finishes sends one), the chart shows
/// a partial figure of the finished points only (the others absent, not NaN), marked
/// "partial: k of 8 points" in its title, without the results and findings that need every
/// point; the complete figure follows. The same sweep cancelled keeps its partial figure,
/// marked cancelled, with the points finished since its last preview.
#[test]
fn a_sweep_fills_its_points_as_they_finish_and_a_cancelled_one_keeps_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE_SWEEP]);
    SWEEP_GATE.store(0, Ordering::SeqCst);
    press(&mut s, KeyCode::Char('r'));
    let mut cells = Vec::new();
    for released in [1usize, 2] {
        // Past the interval between previews, so the next finished point sends one.
        std::thread::sleep(adhesion::scenes::sweep::PREVIEW_INTERVAL + Duration::from_millis(50));
        SWEEP_GATE.store(released, Ordering::SeqCst);
        assert!(
            s.wait_until(WAIT, |a| sweep_points(a).len() == released),
            "a preview of {released} points: {:?}",
            sweep_points(s.app())
        );
        let v = s.app().figure(0).expect("a preview");
        assert_eq!(v.state, FigureState::Partial);
        let want: Vec<(f64, f64)> = (0..released).map(|i| (i as f64, (i * i) as f64)).collect();
        assert_eq!(sweep_points(s.app()), want, "the finished points, in order");
        assert!(v.figure.results.is_empty(), "{:?}", v.figure.results);
        assert_eq!(v.figure.notes, vec![format!("partial: {released} of 8 points")]);
        assert!(
            v.figure.panels[0].notes.is_empty(),
            "{:?}",
            v.figure.panels[0].notes
        );
        let buf = draw(&s);
        let screen = text(&buf);
        assert!(
            screen.contains(&format!("partial: {released} of 8 points")),
            "{screen}"
        );
        cells.push(braille_cells(&buf));
    }
    SWEEP_GATE.store(8, Ordering::SeqCst);
    assert!(s.wait_until(WAIT, idle), "the run ends");
    let v = s.app().figure(0).expect("the figure");
    assert_eq!(v.state, FigureState::Complete);
    assert_eq!(v.figure.result_value("sum_norm"), Some(140.0));
    cells.push(braille_cells(&draw(&s)));
    assert!(
        cells.windows(2).all(|w| w[1] > w[0]),
        "the curve grows: {cells:?}"
    );

    // Cancelled after three points: the partial figure stays, marked.
    SWEEP_GATE.store(0, Ordering::SeqCst);
    press(&mut s, KeyCode::Char('r'));
    std::thread::sleep(adhesion::scenes::sweep::PREVIEW_INTERVAL);
    SWEEP_GATE.store(1, Ordering::SeqCst);
    assert!(
        s.wait_until(WAIT, |a| {
            a.figure(0).is_some_and(|v| v.state == FigureState::Partial) && sweep_points(a).len() == 1
        }),
        "a preview of 1 point"
    );
    // Two more finish before the next preview is due; the cancelled run shows them.
    SWEEP_GATE.store(3, Ordering::SeqCst);
    std::thread::sleep(Duration::from_millis(60));
    press(&mut s, KeyCode::Esc);
    assert!(s.wait_until(WAIT, idle), "the run stops after Esc");
    let v = s.app().figure(0).expect("kept");
    assert_eq!(v.state, FigureState::Cancelled);
    assert_eq!(sweep_points(s.app()).len(), 3);
    let screen = text(&draw(&s));
    assert!(screen.contains("cancelled, partial: 3 of 8 points"), "{screen}");
}

/// `x` hides the current run: its curves leave the chart and the pin's stay, one legend entry
/// says it is hidden, the results table says so; `x` again shows it.
#[test]
fn x_hides_and_shows_the_current_run() {
    use adhesion::tui::compare::Owner;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    press(&mut s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, |a| a.history().len() == 1), "the first run");
    press(&mut s, KeyCode::Char('p'));
    press(&mut s, KeyCode::Tab);
    press(&mut s, KeyCode::Down);
    press(&mut s, KeyCode::Char('}'));
    assert!(
        s.wait_until(WAIT, |a| a.history().len() == 2 && idle(a)),
        "the nudged run"
    );
    let drawn_points = |s: &Session, owner: Owner| -> usize {
        let d = s.app().drawn().expect("a chart");
        d.panel
            .series
            .iter()
            .zip(&d.series)
            .filter(|(_, o)| **o == owner)
            .map(|(x, _)| x.points.len())
            .sum()
    };
    assert_eq!(drawn_points(&s, Owner::Current), 200);
    assert_eq!(drawn_points(&s, Owner::Pin(0)), 200);
    let before = text(&draw(&s));
    assert!(!before.contains("this run (hidden"), "{before}");

    press(&mut s, KeyCode::Char('x'));
    assert!(s.app().current_hidden());
    assert_eq!(
        drawn_points(&s, Owner::Current),
        0,
        "the current run's curves are gone"
    );
    assert_eq!(drawn_points(&s, Owner::Pin(0)), 200, "the pin's stay");
    let screen = text(&draw(&s));
    assert!(
        screen.contains("this run (hidden"),
        "the legend and the table say so:\n{screen}"
    );

    press(&mut s, KeyCode::Char('x'));
    assert!(!s.app().current_hidden());
    assert_eq!(drawn_points(&s, Owner::Current), 200);
}
