//! The terminal workbench as an instrument, driven through ratatui's `TestBackend`: the scene
//! list in two columns and its filter, readable axes, the results beside the chart, pinned runs
//! compared on one chart, the cursor readout and marker jumps, a gauge that advances, the run
//! history, the mouse, and the key help listing every key.

use std::sync::{Arc, Mutex};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{KeyCode, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

use adhesion::job::{Job, JobEvent};
use adhesion::render::labels::{MAX_DIGITS, fmt_quantity};
use adhesion::render::terminal::chart_labels;
use adhesion::scenes::{self, SceneDyn};
use adhesion::tui::app::{FigureState, Focus, Mode};
use adhesion::tui::chart::CursorAt;
use adhesion::tui::keymap::BINDINGS;
use adhesion::tui::session::Session;
use adhesion::tui::view::{result_label, time_left};

use super::tui::{PROBE, WAIT, braille_cells, clear_line, idle, press, session, text, type_text};

pub(crate) fn scene(id: &str) -> &'static dyn SceneDyn {
    scenes::all()
        .into_iter()
        .find(|s| s.info().id == id)
        .expect("a registered scene")
}

/// A session over every scene with `id` selected.
pub(crate) fn at_scene(dir: &std::path::Path, id: &str) -> Session {
    let mut s = session(dir, scenes::all());
    while s.app().scene().is_some_and(|sc| sc.info().id != id) {
        press(&mut s, KeyCode::Down);
    }
    assert_eq!(s.app().scene().expect("a scene").info().id, id);
    s
}

pub(crate) fn run(s: &mut Session) {
    press(s, KeyCode::Char('r'));
    assert!(s.wait_until(WAIT, idle), "the run ends");
    let view = s.app().figure(s.app().selected()).expect("a figure");
    assert_eq!(view.state, FigureState::Complete, "{:?}", s.app().status());
}

/// Set parameter `name` of the selected scene to `value` through the form.
pub(crate) fn set_param(s: &mut Session, name: &str, value: &str) {
    if s.app().focus() != Focus::Form {
        press(s, KeyCode::Tab);
    }
    let form = s.app().form().expect("a form");
    let k = form
        .specs()
        .iter()
        .position(|p| p.name == name)
        .expect("the parameter");
    let step = k as isize - form.selected() as isize;
    let code = if step < 0 { KeyCode::Up } else { KeyCode::Down };
    for _ in 0..step.unsigned_abs() {
        press(s, code);
    }
    press(s, KeyCode::Enter);
    clear_line(s);
    type_text(s, value);
    press(s, KeyCode::Enter);
    press(s, KeyCode::Tab);
    assert!(s.app().form().expect("a form").first_error().is_none());
}

/// The number after `=` in a readout part such as `P/(πwR) = −0.8333`.
fn number_after_eq(part: &str) -> f64 {
    let v = part.rsplit('=').next().expect("a value").trim();
    let v = v.split(' ').next().expect("a number").replace('−', "-");
    v.parse().unwrap_or_else(|_| panic!("a number in `{part}`"))
}

fn mouse(s: &mut Session, kind: MouseEventKind, column: u16, row: u16) {
    s.mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers: KeyModifiers::NONE,
    });
}

pub(crate) fn draw_at(s: &Session, w: u16, h: u16) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    terminal.draw(|f| s.draw(f)).expect("drawing into a test backend");
    terminal.backend().buffer().clone()
}

/// At 80 columns every scene row is ` <mark><id padded> <gap> <title>`: the titles start in one
/// column, two spaces after the longest id, and no id runs into its title.
#[test]
fn the_list_separates_ids_and_titles_at_80_columns() {
    let dir = tempfile::tempdir().expect("temp dir");
    let s = session(dir.path(), scenes::all());
    let screen = text(&draw_at(&s, 80, 40));
    let ids: Vec<&str> = scenes::all().iter().map(|s| s.info().id).collect();
    let longest = ids.iter().map(|id| id.chars().count()).max().expect("scenes");
    let mut rows = 0;
    for line in screen.lines() {
        let cells: Vec<char> = line.chars().collect();
        // Inside the list pane: after the border and the two-character mark column.
        let body: String = cells.iter().skip(3).collect();
        let Some(id) = ids
            .iter()
            .filter(|id| body.starts_with(*id))
            .max_by_key(|id| id.len())
        else {
            continue;
        };
        rows += 1;
        let rest: Vec<char> = body.chars().skip(id.chars().count()).collect();
        let gap = longest - id.chars().count() + 2;
        assert!(
            rest.iter().take(gap).all(|c| *c == ' '),
            "`{id}` is followed by its title without a gap:\n{line}"
        );
        assert!(rest.get(gap).is_some_and(|c| c.is_alphanumeric()), "{line}");
    }
    assert!(rows >= 10, "scene rows on screen:\n{screen}");
    assert!(screen.contains("fig2.5-accuracy  "), "{screen}");
}

/// `/` narrows the list as it is typed, selection follows the matches, Esc clears.
#[test]
fn typing_a_filter_narrows_the_list() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Char('/'));
    assert!(matches!(s.app().mode(), Mode::Filter { .. }));
    type_text(&mut s, "accuracy");
    let visible = s.app().visible_scenes();
    assert!(visible.len() >= 2 && visible.len() < scenes::all().len());
    let id = s.app().scene().expect("a scene").info().id;
    assert!(id.contains("accuracy"), "selected {id}");
    let screen = text(&draw_at(&s, 100, 40));
    assert!(!screen.contains("fig1.4b"), "{screen}");
    assert!(screen.contains("/accuracy"), "{screen}");
    press(&mut s, KeyCode::Down);
    assert_ne!(s.app().scene().expect("a scene").info().id, id);
    press(&mut s, KeyCode::Enter);
    assert_eq!(s.app().mode(), &Mode::Normal);
    assert_eq!(s.app().filter(), "accuracy");
    // `r` is a key again, not filter text.
    press(&mut s, KeyCode::Char('/'));
    press(&mut s, KeyCode::Esc);
    assert_eq!(s.app().filter(), "");
    assert_eq!(s.app().visible_scenes().len(), scenes::all().len());
    let screen = text(&draw_at(&s, 100, 40));
    assert!(screen.contains("fig1.1"), "{screen}");
}

/// Significant digits of a tick label (`−1.25` has 3, `0.050` 2, `1200` 2, `10⁻²` and `0` 1).
fn significant_digits(label: &str) -> usize {
    let mantissa = label.split('×').next().unwrap_or(label);
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let lead = digits.trim_start_matches('0');
    let n = if mantissa.contains('.') {
        lead.len()
    } else {
        lead.trim_end_matches('0').len()
    };
    n.max(1)
}

/// The tick labels of fig5.10 (values up to about 1 160 in u/σ, forces near 1e-9 before
/// normalisation) have at most four significant digits, sit on 1-2-5 steps, and are what the
/// screen shows; before, the axes read "-451.1081  354.5449  1160.1979".
#[test]
fn tick_labels_of_fig5_10_have_at_most_4_significant_digits() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig5.10");
    run(&mut s);
    let buf = draw_at(&s, 160, 48);
    let screen = text(&buf);
    let geometry = s.app().chart_geometry().expect("a chart was drawn");
    let drawn = s.app().drawn().expect("a panel");
    // The chart area is the graph plus the axes around it.
    let area = s.app().chart_area();
    let (x, y) = chart_labels(&drawn.panel, None, area).expect("labels");
    assert!(x.ticks.len() >= 3 && y.ticks.len() >= 3, "{x:?} {y:?}");
    for labels in [&x, &y] {
        for (_, l) in &labels.ticks {
            assert!(
                significant_digits(l) <= MAX_DIGITS as usize,
                "`{l}` in {labels:?}"
            );
        }
        let pos: Vec<f64> = labels.ticks.iter().map(|(p, _)| *p).collect();
        let step = pos[1] - pos[0];
        assert!(
            pos.windows(2)
                .all(|w| ((w[1] - w[0]) - step).abs() < 1e-9 * step.abs())
        );
        let m = step / 10f64.powf(step.log10().floor());
        assert!(
            [1.0, 2.0, 5.0].iter().any(|n| (m - n).abs() < 1e-6),
            "step {step}"
        );
    }
    let x_row = screen
        .lines()
        .nth(usize::from(geometry.graph.bottom() + 1))
        .expect("label row");
    for (_, l) in &x.ticks {
        assert!(
            x_row.contains(l.as_str()),
            "x label `{l}` under the chart:\n{screen}"
        );
    }
    for (_, l) in &y.ticks {
        assert!(
            screen.contains(&format!("{l}┤")),
            "y label `{l}` at its tick:\n{screen}"
        );
    }
    assert!(!screen.contains("1160.1979"), "{screen}");
}

/// Log axes where the figure has them: fig2.5's α axis reads in decades.
#[test]
fn log_axes_read_in_decades_and_zoom_goes_in_and_back() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig2.5");
    run(&mut s);
    let screen = text(&draw_at(&s, 160, 48));
    for decade in ["10⁻²", "10²"] {
        assert!(screen.contains(decade), "`{decade}` on the log axis:\n{screen}");
    }
    // Zoom into a rectangle between two cursor positions, then back.
    let before = s.app().chart_geometry().expect("a chart");
    press(&mut s, KeyCode::Char('c'));
    press(&mut s, KeyCode::Char('z'));
    for _ in 0..2 {
        press(&mut s, KeyCode::Char('>'));
    }
    press(&mut s, KeyCode::Char('z'));
    let zoom = s.app().zoom().expect("zoomed");
    draw_at(&s, 160, 48);
    let after = s.app().chart_geometry().expect("a chart");
    assert!(
        after.x[1] - after.x[0] < 0.5 * (before.x[1] - before.x[0]),
        "zoom {zoom:?}: {:?} -> {:?}",
        before.x,
        after.x
    );
    press(&mut s, KeyCode::Char('0'));
    assert_eq!(s.app().zoom(), None);
    draw_at(&s, 160, 48);
    assert_eq!(s.app().chart_geometry().expect("a chart").x, before.x);
    // + and - zoom about the cursor.
    press(&mut s, KeyCode::Char('+'));
    press(&mut s, KeyCode::Char('-'));
    let ((x0, x1), _) = s.app().zoom().expect("zoomed");
    let (b0, b1) = (10f64.powf(before.x[0]), 10f64.powf(before.x[1]));
    assert!(((x1 / x0).log10() - (b1 / b0).log10()).abs() < 1e-9);
}

/// The results panel beside the chart lists fig1.1's results with units.
#[test]
fn the_results_panel_lists_fig1_1_results_with_units() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    run(&mut s);
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains("Results"), "{screen}");
    let fig = &s.app().figure(0).expect("a figure").figure;
    for (name, unit) in [
        ("jkr_pull_off_force_N", "N"),
        ("jkr_pull_off_depth_m", "m"),
        ("jkr_hysteresis_J", "J"),
    ] {
        let v = fig.result_value(name).expect("the result");
        let shown = fmt_quantity(v, unit);
        let (short, _) = result_label(name);
        assert!(short.ends_with(&format!("[{unit}]")), "{short}");
        let line = screen
            .lines()
            .find(|l| l.contains(&format!("│{short} ")))
            .unwrap_or_else(|| panic!("`{short}` in the panel:\n{screen}"));
        assert!(line.contains(&shown), "`{shown}` for {name} = {v}:\n{line}");
    }
    assert!(screen.contains("µN") || screen.contains("nN"), "{screen}");
    // 5/6 of πwR, Eq. (1.4), in the normalised force.
    assert!(screen.contains("−0.8333"), "{screen}");
}

/// A pinned run stays drawn after a rerun with another parameter, and its legend names the
/// difference; the export carries both runs and the JSON each run's parameters.
#[test]
fn a_pinned_run_stays_drawn_after_a_rerun_and_its_legend_names_the_difference() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    run(&mut s);
    let alone = braille_cells(&draw_at(&s, 140, 40));
    press(&mut s, KeyCode::Char('p'));
    assert_eq!(s.app().pins(0).len(), 1);
    set_param(&mut s, "amplitude", "2.5");
    run(&mut s);
    let buf = draw_at(&s, 140, 40);
    let screen = text(&buf);
    assert!(
        screen.contains("#1 amplitude = 1 m"),
        "legend names the difference:\n{screen}"
    );
    assert!(
        braille_cells(&buf) > alone + 50,
        "both curves are drawn:\n{screen}"
    );
    let drawn = s.app().drawn().expect("a panel");
    let pinned: Vec<_> = drawn
        .panel
        .series
        .iter()
        .filter(|x| x.name.starts_with("#1 amplitude = 1 m · "))
        .collect();
    assert_eq!(pinned.len(), 1, "the pinned sine");
    let peak = |pts: &[(f64, f64)]| pts.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    assert!((peak(&pinned[0].points) - 1.0).abs() < 1e-3);
    assert!((peak(&drawn.panel.series[0].points) - 2.5).abs() < 1e-2);

    // Export with the pinned run.
    press(&mut s, KeyCode::Char('e'));
    assert!(
        s.app().status().text.contains("1 pinned run"),
        "{:?}",
        s.app().status()
    );
    let out = dir.path().join("out");
    let csv = std::fs::read_to_string(out.join("probe.csv")).expect("csv");
    assert!(
        csv.contains("#1 amplitude = 1 m · rising sine"),
        "pinned rows in the CSV"
    );
    assert!(csv.contains(",rising sine,"), "current rows in the CSV");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("probe.json")).expect("json"))
            .expect("valid JSON");
    let pinned = &json["pinned_runs"][0];
    let amplitude = pinned["parameters"]
        .as_array()
        .expect("parameters")
        .iter()
        .find(|p| p["name"] == "amplitude")
        .expect("amplitude");
    assert_eq!(amplitude["value"], 1.0);
    assert_eq!(pinned["results"]["amplitude_m"], 1.0);
    assert_eq!(json["results"]["amplitude_m"], 2.5);
    for ext in ["png", "svg"] {
        assert!(std::fs::metadata(out.join(format!("probe.{ext}"))).is_ok_and(|m| m.len() > 100));
    }
    // Unpin: one, then the chart has the current run only.
    press(&mut s, KeyCode::Char('u'));
    assert!(s.app().pins(0).is_empty());
    assert!(!text(&draw_at(&s, 140, 40)).contains("#1 amplitude"));
}

/// The cursor readout shows the JKR pull-off of fig1.1, −5/6 πwR at h_D, Eq. (1.4), within the
/// chart's resolution, by the marker key and by a mouse click at the marker's cell.
#[test]
fn the_cursor_reads_the_jkr_pull_off_of_fig1_1() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    run(&mut s);
    draw_at(&s, 160, 48);
    let fig = s.app().figure(0).expect("a figure").figure.clone();
    let depth = fig.result_value("jkr_pull_off_depth_norm").expect("h_D");
    let force = fig.result_value("jkr_pull_off_force_norm").expect("P_D");
    assert!(
        (force + 5.0 / 6.0).abs() < 1e-9,
        "closed form, Eq. (1.4): {force}"
    );
    let mut found = None;
    for _ in 0..8 {
        press(&mut s, KeyCode::Char('m'));
        let r = s.app().readout().expect("a readout");
        if r.name.starts_with("pull-off") {
            found = Some(r);
            break;
        }
    }
    let r = found.expect("m reaches the pull-off marker");
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains(&r.y), "readout `{}` on screen:\n{screen}", r.y);
    let g = s.app().chart_geometry().expect("a chart");
    let (dx, dy) = g.resolution(r.point);
    assert!((number_after_eq(&r.x) - depth).abs() <= dx, "{} vs {depth}", r.x);
    assert!((number_after_eq(&r.y) - force).abs() <= dy, "{} vs {force}", r.y);
    assert!(r.y.contains("Contact force"), "{}", r.y);

    // A click on the marker's cell puts the cursor there (or on a curve point in that cell).
    let (fx, fy) = g.fraction((depth, force));
    let column = g.graph.x + (fx * f64::from(g.graph.width)).floor() as u16;
    let row = g.graph.bottom() - 1 - (fy * f64::from(g.graph.height)).floor() as u16;
    press(&mut s, KeyCode::Char('c')); // cursor off
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), column, row);
    mouse(&mut s, MouseEventKind::Up(MouseButton::Left), column, row);
    let r = s.app().readout().expect("a click places the cursor");
    assert!(
        (r.point.0 - depth).abs() <= 1.5 * dx && (r.point.1 - force).abs() <= 1.5 * dy,
        "{r:?}"
    );
    assert_eq!(s.app().zoom(), None, "a click does not zoom");

    // Along the curve: `.` moves one point on the same curve.
    press(&mut s, KeyCode::Char(';'));
    let Some(CursorAt::Point { series, index }) = s.app().cursor() else {
        panic!("on a curve: {:?}", s.app().cursor())
    };
    press(&mut s, KeyCode::Char('.'));
    let moved = s.app().cursor();
    assert!(
        moved
            == Some(CursorAt::Point {
                series,
                index: index + 1
            })
            || moved == Some(CursorAt::Point { series, index }),
        "{moved:?}"
    );
}

/// The gauge of fig5.10 with three couplings advances with the work of every coupling: the
/// fraction the job reports stays below 1 until the last coupling's last step (before, only
/// the first, uncoupled and fastest, cycle reported, and the gauge sat at 100 % for most of the
/// run), and the gauge the UI shows never moves back and never reads 100 % while running.
#[test]
fn the_gauge_is_monotone_and_below_100_percent_before_a_long_scene_ends() {
    let sc = scene("fig5.10");
    let mut values = sc.defaults();
    values.set_text("springs_x", "64").expect("springs_x");
    values.set_text("steps", "200").expect("steps");
    let seen = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&seen);
    let job = Job::with_sink(move |e| {
        if let JobEvent::Progress { fraction, .. } = e {
            sink.lock().expect("test mutex").push(*fraction);
        }
    });
    sc.run(&values, &job).expect("fig5.10 runs");
    let seen = seen.lock().expect("test mutex").clone();
    let below = seen.iter().filter(|f| **f < 0.999).count();
    // 3 couplings x 2 phases x about 200 steps each.
    assert!(
        below >= 3 * 2 * 190 - 1,
        "{below} reports below 100 % of {}",
        seen.len()
    );
    assert!(seen.windows(2).all(|w| w[1] >= w[0]), "{seen:?}");
    let (last, before) = seen.split_last().expect("progress reported");
    assert_eq!(*last, 1.0);
    assert!(before.iter().all(|f| *f < 1.0), "100 % before `done`");

    // Through the UI: the gauge as drawn.
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig5.10");
    press(&mut s, KeyCode::Char('r'));
    let mut shown = Vec::new();
    while s.app().running().is_some() {
        s.wait_until(std::time::Duration::from_millis(20), |_| false);
        if let Some(r) = s.app().running() {
            shown.push(r.fraction);
            let screen = text(&draw_at(&s, 160, 48));
            assert!(!screen.contains("fig5.10 100%"), "{screen}");
        }
    }
    assert!(shown.len() >= 3, "{shown:?}");
    assert!(shown.windows(2).all(|w| w[1] >= w[0]), "{shown:?}");
    assert_eq!(time_left(0.25, 10.0), " · 10.0 s, about 30.0 s left");
    assert_eq!(time_left(0.5, 0.2), "");
}

/// The fractions a run of `id` (in quick form when `quick`, with `sets`) reports, in order.
fn progress_of(id: &str, sets: &[&str], quick: bool) -> Vec<f64> {
    let sc = scene(id);
    let mut values = sc.defaults();
    for a in sets {
        values.set_assignment(a).expect("a valid assignment");
    }
    if quick {
        values = sc.quick(&values).expect("quick form");
    }
    let seen = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&seen);
    let job = Job::with_sink(move |e| {
        if let JobEvent::Progress { fraction, .. } = e {
            sink.lock().expect("test mutex").push(*fraction);
        }
    });
    sc.run(&values, &job).expect("the scene runs");
    seen.lock().expect("test mutex").clone()
}

/// The scenes that take over a second report progress that means something, here in the
/// forms that take a second or two: the fraction never moves back, stays below 1 until the
/// run's last report (which is 1), advances in many small steps (per point, per step of a
/// cycle, per sample) and never jumps by more than a quarter. Before, fig4.12 reported twice
/// (0.5, 1.0: its cycles, then the top views at 100 %), fig4.9a went back from 1.0 to 0.33 for
/// its second panel, fig4.10's points came as 9 reports, fig4.5-accuracy's cycles as 6.
#[test]
fn long_scenes_report_progress_that_advances_and_ends_only_at_the_end() {
    let cases: &[(&str, &[&str], bool)] = &[
        // Weighted cycles in parallel, then bisection cycles.
        ("fig4.3", &[], true),
        // Two panels of parallel cycles, weighted.
        ("fig4.9a", &[], true),
        // A sweep whose points are cycles.
        ("fig4.10", &[], true),
        // Parallel cycles, then the top views.
        ("fig4.12", &[], true),
        // Cycles on grids, weighted by their cost.
        ("fig4.5-accuracy", &[], true),
        // A sweep whose assembly computes a second grid.
        ("fig3.8", &[], false),
        // A reference cycle, then cycles weighted by their steps.
        ("fig5.10-accuracy", &[], true),
        // Surfaces weighted by their size.
        ("figC.2-accuracy", &[], true),
    ];
    for (id, sets, quick) in cases {
        let seen = progress_of(id, sets, *quick);
        let (last, before) = seen.split_last().expect("progress reported");
        assert_eq!(*last, 1.0, "{id} ends at 1: {seen:?}");
        assert!(
            before.iter().all(|f| *f < 1.0),
            "{id}: 100 % before the end: {seen:?}"
        );
        assert!(seen.windows(2).all(|w| w[1] >= w[0]), "{id} moves back: {seen:?}");
        let jump = seen.windows(2).map(|w| w[1] - w[0]).fold(seen[0], f64::max);
        assert!(jump <= 0.25, "{id} jumps by {jump}: {seen:?}");
        let mut distinct = seen.clone();
        distinct.dedup();
        assert!(
            distinct.len() >= 20,
            "{id}: {} distinct fractions: {seen:?}",
            distinct.len()
        );
    }
}

/// The history keeps finished runs with their parameters and run times; Enter reopens one
/// without rerunning, `e` exports it.
#[test]
fn the_history_reopens_and_exports_past_runs_without_rerunning() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    run(&mut s);
    set_param(&mut s, "amplitude", "3");
    run(&mut s);
    assert_eq!(s.app().history().len(), 2);
    press(&mut s, KeyCode::Char('h'));
    let screen = text(&draw_at(&s, 140, 40));
    assert!(screen.contains("Run history"), "{screen}");
    assert!(screen.contains("amplitude = 3 m"), "{screen}");
    assert!(screen.contains("defaults"), "{screen}");
    // The older run (defaults, amplitude 1).
    press(&mut s, KeyCode::Down);
    press(&mut s, KeyCode::Char('e'));
    let json = std::fs::read_to_string(dir.path().join("out/probe.json")).expect("exported");
    assert!(json.contains("\"amplitude_m\": 1.0"), "{json}");
    press(&mut s, KeyCode::Enter);
    assert_eq!(s.app().mode(), &Mode::Normal);
    assert!(s.app().running().is_none(), "reopening does not rerun");
    let view = s.app().figure(0).expect("reopened");
    assert_eq!(view.figure.result_value("amplitude_m"), Some(1.0));
    assert_eq!(
        s.app().form().expect("form").values().get("amplitude"),
        Some(&toml::Value::Float(1.0))
    );
}

/// The mouse: a click selects a scene or a parameter, the wheel scrolls the lists, a drag on
/// the chart zooms and the right button zooms back.
#[test]
fn the_mouse_selects_scrolls_and_zooms() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    let screen = text(&draw_at(&s, 140, 40));
    let row = screen
        .lines()
        .position(|l| l.contains("fig1.4b "))
        .expect("fig1.4b listed") as u16;
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 5, row);
    assert_eq!(s.app().scene().expect("a scene").info().id, "fig1.4b");
    mouse(&mut s, MouseEventKind::ScrollDown, 5, row);
    assert_ne!(s.app().scene().expect("a scene").info().id, "fig1.4b");
    mouse(&mut s, MouseEventKind::ScrollUp, 5, row);
    assert_eq!(s.app().scene().expect("a scene").info().id, "fig1.4b");

    // A parameter row.
    let screen = text(&draw_at(&s, 140, 40));
    let name = s.app().form().expect("a form").specs()[2].name;
    let row = screen
        .lines()
        .position(|l| l.contains(&format!(" {name} ")) || l.contains(&format!("*{name} ")))
        .expect("the parameter is listed") as u16;
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 3, row);
    assert_eq!(s.app().focus(), Focus::Form);
    assert_eq!(s.app().form().expect("a form").selected(), 2);

    // Drag a rectangle on a chart.
    let mut s = session(dir.path(), vec![&PROBE]);
    run(&mut s);
    draw_at(&s, 140, 40);
    let g = s.app().chart_geometry().expect("a chart");
    let (c0, r0) = (g.graph.x + g.graph.width / 4, g.graph.y + g.graph.height / 4);
    let (c1, r1) = (g.graph.x + g.graph.width / 2, g.graph.y + g.graph.height / 2);
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), c0, r0);
    mouse(&mut s, MouseEventKind::Drag(MouseButton::Left), c1, r1);
    assert!(
        text(&draw_at(&s, 140, 40)).contains('◆'),
        "readout while dragging"
    );
    mouse(&mut s, MouseEventKind::Up(MouseButton::Left), c1, r1);
    let ((x0, x1), _) = s.app().zoom().expect("the drag zooms");
    let a = g.to_data(c0, r0).expect("inside");
    let b = g.to_data(c1, r1).expect("inside");
    assert!(
        (x0 - a.0).abs() < 1e-9 && (x1 - b.0).abs() < 1e-9,
        "{x0} {x1} vs {a:?} {b:?}"
    );
    mouse(&mut s, MouseEventKind::Down(MouseButton::Right), c0, r0);
    assert_eq!(s.app().zoom(), None);
}

/// `?` lists every binding of the key map: its keys and its line of help.
#[test]
fn help_lists_every_key_of_the_key_map() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), scenes::all());
    press(&mut s, KeyCode::Char('?'));
    let screen = text(&draw_at(&s, 160, 48));
    for b in BINDINGS {
        let line = format!("{:<10}{}", b.label, b.help);
        assert!(screen.contains(&line), "`{line}` in the help:\n{screen}");
    }
}

/// A pinned run's markers and shaded region carry the run: named after its legend entry, drawn
/// in its colour (the region as a dot fill under the curves), listed by symbol in its terminal
/// legend entry, told apart by run in the CSV, and named in the cursor readout.
#[test]
fn pinned_markers_and_regions_carry_their_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.1");
    run(&mut s);
    press(&mut s, KeyCode::Char('p'));
    set_param(&mut s, "max_depth_norm", "1.5");
    run(&mut s);
    let run_label = "#1 max_depth_norm = 2.5";
    // In the figure (and its CSV) the label is markup with the parameter's name escaped; the
    // terminal and the PNG show it as written.
    let run_markup = adhesion::render::text::escape(run_label);
    let pin_color = s.app().pins(0)[0].color;
    let drawn = s.app().drawn().expect("a panel");
    let pinned_markers: Vec<_> = drawn
        .panel
        .markers
        .iter()
        .filter(|m| m.name.starts_with(&format!("{run_markup} · ")))
        .collect();
    let current = drawn.current_counts();
    assert_eq!(pinned_markers.len(), current.0, "every marker of the pinned run");
    assert!(pinned_markers.iter().all(|m| m.color == Some(pin_color)));
    assert!(
        pinned_markers
            .iter()
            .any(|m| m.name == format!("{run_markup} · pull-off"))
    );
    assert_eq!(current.1, 1, "the current run's JKR hysteresis");
    let region = &drawn.panel.regions[1];
    assert_eq!(region.name, format!("{run_markup} · JKR hysteresis"));
    assert_eq!(region.color, Some(pin_color));

    // The terminal legend: the run's entry lists its markers and region by symbol; the kinds
    // of marker and the current loop are listed once, for the current run.
    let screen = text(&draw_at(&s, 160, 48));
    assert!(
        screen.contains(&format!("{run_label} ▲●◆■░")),
        "the pinned run's entry with its symbols:\n{screen}"
    );
    assert!(screen.contains("░ JKR hysteresis"), "{screen}");
    assert!(screen.contains("■ pull-off"), "{screen}");
    assert!(!screen.contains(&format!("{run_label} · pull-off")), "{screen}");

    // The cursor reaches the pinned markers and names their run.
    let mut names = Vec::new();
    for _ in 0..drawn.panel.markers.len() {
        press(&mut s, KeyCode::Char('m'));
        names.push(s.app().readout().expect("a readout").name);
    }
    assert!(names.contains(&format!("{run_label} · pull-off")), "{names:?}");
    assert!(names.contains(&"pull-off (D)".to_string()), "{names:?}");

    // The export tells the runs apart: the pinned markers and loop rows are named after it.
    press(&mut s, KeyCode::Char('e'));
    let csv = std::fs::read_to_string(dir.path().join("out/fig1.1.csv")).expect("csv");
    let rows = |series: &str, style: &str| {
        csv.lines()
            .filter(|l| l.starts_with(&format!("1,{series},{style},")))
            .count()
    };
    assert_eq!(rows(&format!("{run_markup} · pull-off"), "pull-off"), 1, "{csv}");
    assert_eq!(rows("pull-off D", "pull-off"), 1);
    let loop_rows = rows(&format!("{run_markup} · JKR hysteresis"), "region");
    assert!(loop_rows > 10, "{loop_rows} rows of the pinned loop");
    assert!(rows("JKR hysteresis", "region") > 10);
}

/// A shaded region in the terminal: dots in its colour inside the polygon, none outside, under
/// the curves that cross it, and a legend entry.
#[test]
fn a_shaded_region_is_drawn_as_a_dot_fill_under_the_curves() {
    use adhesion::figure::{Axis, Panel, Series, Style};
    use adhesion::render::terminal::{ChartOptions, color, render_chart};
    let mut panel = Panel::new(Axis::linear("x", ""), Axis::linear("y", "")).titled("", "");
    panel.x = panel.x.clone().with_range(0.0, 4.0);
    panel.y = panel.y.clone().with_range(0.0, 4.0);
    panel.shade(
        "loop",
        vec![(1.0, 1.0), (3.0, 1.0), (3.0, 3.0), (1.0, 3.0)],
        Some(4),
    );
    panel.add(Series::new("line", Style::Stable, vec![(0.0, 2.0), (4.0, 2.0)]).with_color(0));
    let area = ratatui::layout::Rect::new(0, 0, 60, 24);
    let mut buf = Buffer::empty(area);
    let g = render_chart(&panel, &ChartOptions::default(), area, &mut buf).expect("a chart");
    let cell = |x: f64, y: f64| {
        let (fx, fy) = g.fraction((x, y));
        let col = g.graph.x + (fx * f64::from(g.graph.width)).floor() as u16;
        let row = g.graph.bottom() - 1 - (fy * f64::from(g.graph.height)).floor() as u16;
        buf[(col, row)].clone()
    };
    let braille = |c: &ratatui::buffer::Cell| {
        c.symbol()
            .chars()
            .any(|ch| ('\u{2801}'..='\u{28ff}').contains(&ch))
    };
    // Inside: about every other cell has a dot of the region's colour.
    let mut inside = 0;
    let mut dotted = 0;
    for i in 0..10 {
        for j in 0..10 {
            // Rows away from the line at y = 2.
            let y = if j < 5 { 1.2 } else { 2.4 } + 0.1 * f64::from(j % 5);
            let x = 1.2 + 0.16 * f64::from(i);
            inside += 1;
            let c = cell(x, y);
            if braille(&c) {
                assert_eq!(c.fg, color(4), "at ({x}, {y})");
                dotted += 1;
            }
        }
    }
    assert!(dotted * 4 >= inside, "{dotted} of {inside} cells dotted");
    // Outside: nothing.
    for (x, y) in [(0.5, 0.5), (3.5, 3.5), (0.5, 3.2), (3.6, 1.2)] {
        assert!(!braille(&cell(x, y)), "a dot outside at ({x}, {y})");
    }
    // The curve crossing the region is drawn over it: across the whole width.
    let line_cells = buf
        .content()
        .iter()
        .filter(|c| braille(c) && c.fg == color(0))
        .count();
    assert!(
        line_cells + 1 >= usize::from(g.graph.width),
        "{line_cells} cells of the line in {} columns",
        g.graph.width
    );
    let screen = text(&buf);
    assert!(screen.contains("░ loop"), "{screen}");
}

/// Each panel keeps its cursor and zoom: switching panels or scenes and coming back restores
/// them (by key and by a click on the panel's tab); a rerun with the same results keeps them;
/// results that change the axes reset them.
#[test]
fn each_panel_keeps_its_zoom_and_cursor_until_new_results_change_its_axes() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE, scene("fig1.1")]);
    run(&mut s);
    draw_at(&s, 140, 40);
    press(&mut s, KeyCode::Char('c'));
    press(&mut s, KeyCode::Char('>'));
    press(&mut s, KeyCode::Char('+'));
    let (cursor_a, zoom_a) = (s.app().cursor(), s.app().zoom());
    assert!(cursor_a.is_some() && zoom_a.is_some());

    // Panel (b) starts whole, without a cursor; it gets its own zoom.
    press(&mut s, KeyCode::Char(']'));
    assert_eq!(s.app().panel(), 1);
    assert_eq!((s.app().cursor(), s.app().zoom()), (None, None));
    press(&mut s, KeyCode::Char('-'));
    let zoom_b = s.app().zoom();
    assert!(zoom_b.is_some());

    // Back to (a) by a click on its tab: its cursor and zoom again.
    let screen = text(&draw_at(&s, 140, 40));
    let (row, line) = screen
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains("panels (← → or click)"))
        .expect("the panel tabs");
    let column = line
        .find("(a)")
        .map(|b| line[..b].chars().count())
        .expect("tab (a)") as u16;
    mouse(
        &mut s,
        MouseEventKind::Down(MouseButton::Left),
        column,
        row as u16,
    );
    assert_eq!(s.app().panel(), 0);
    assert_eq!((s.app().cursor(), s.app().zoom()), (cursor_a, zoom_a));
    press(&mut s, KeyCode::Char(']'));
    assert_eq!((s.app().cursor(), s.app().zoom()), (None, zoom_b));

    // Another scene and back: the panel shown last, with its view.
    press(&mut s, KeyCode::Down);
    assert_eq!(s.app().scene().expect("a scene").info().id, "fig1.1");
    assert_eq!(s.app().zoom(), None);
    press(&mut s, KeyCode::Up);
    assert_eq!(s.app().panel(), 1);
    assert_eq!(s.app().zoom(), zoom_b);

    // The same results again: kept.
    run(&mut s);
    assert_eq!(s.app().zoom(), zoom_b);
    press(&mut s, KeyCode::Char('['));
    assert_eq!((s.app().cursor(), s.app().zoom()), (cursor_a, zoom_a));

    // Results that change the axes: both panels start afresh.
    set_param(&mut s, "amplitude", "3");
    run(&mut s);
    assert_eq!((s.app().cursor(), s.app().zoom()), (None, None));
    press(&mut s, KeyCode::Char(']'));
    assert_eq!((s.app().cursor(), s.app().zoom()), (None, None));
}

/// The mouse in the run history: a click chooses a run, a click on the chosen one reopens it,
/// the wheel moves the choice, the footer's actions work, a click outside closes; a click
/// closes the key help.
#[test]
fn the_history_and_the_help_answer_the_mouse() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = session(dir.path(), vec![&PROBE]);
    run(&mut s);
    set_param(&mut s, "amplitude", "3");
    run(&mut s);
    press(&mut s, KeyCode::Char('h'));
    let screen = text(&draw_at(&s, 140, 40));
    let row_of = |needle: &str| {
        screen
            .lines()
            .position(|l| l.contains("probe") && l.contains(needle))
            .unwrap_or_else(|| panic!("`{needle}` in the history:\n{screen}")) as u16
    };
    let (newest, oldest) = (row_of("amplitude = 3 m"), row_of("defaults"));
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 40, oldest);
    assert_eq!(s.app().mode(), &Mode::History { selected: 1 });
    mouse(&mut s, MouseEventKind::ScrollUp, 40, oldest);
    assert_eq!(s.app().mode(), &Mode::History { selected: 0 });
    mouse(&mut s, MouseEventKind::ScrollDown, 40, newest);
    assert_eq!(s.app().mode(), &Mode::History { selected: 1 });

    // The footer: `e exports` exports the chosen run.
    let footer = screen
        .lines()
        .position(|l| l.contains("e exports"))
        .expect("the footer") as u16;
    let column = screen
        .lines()
        .nth(usize::from(footer))
        .and_then(|l| l.chars().position(|c| c == 'x'))
        .expect("`exports`") as u16;
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), column, footer);
    let json = std::fs::read_to_string(dir.path().join("out/probe.json")).expect("exported");
    assert!(json.contains("\"amplitude_m\": 1.0"), "{json}");

    // A second click on the chosen run reopens it, without rerunning.
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 40, oldest);
    assert_eq!(s.app().mode(), &Mode::Normal);
    assert!(s.app().running().is_none());
    let view = s.app().figure(0).expect("reopened");
    assert_eq!(view.figure.result_value("amplitude_m"), Some(1.0));

    // A click outside closes the history; a click closes the help.
    press(&mut s, KeyCode::Char('h'));
    draw_at(&s, 140, 40);
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 0, 0);
    assert_eq!(s.app().mode(), &Mode::Normal);
    press(&mut s, KeyCode::Char('?'));
    draw_at(&s, 140, 40);
    mouse(&mut s, MouseEventKind::Down(MouseButton::Left), 70, 20);
    assert_eq!(s.app().mode(), &Mode::Normal);
}

/// The figures' label markup reads in the terminal as Unicode scripts, never as raw markup:
/// fig1.4b's `d/h_o` axis is drawn `d/hₒ`, its legend `σᵣₘₛ/hₒ` (the form's parameter help
/// is plain text and keeps its underscores).
#[test]
fn the_terminal_chart_shows_label_markup_as_unicode_scripts() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = at_scene(dir.path(), "fig1.4b");
    run(&mut s);
    let screen = text(&draw_at(&s, 160, 48));
    assert!(screen.contains("Separation d/hₒ"), "{screen}");
    assert!(screen.contains("σᵣₘₛ/hₒ = 0.5"), "{screen}");
    assert!(
        !screen.contains("d/h_o") && !screen.contains("_{") && !screen.contains("^{"),
        "{screen}"
    );
}
