//! Drawing the terminal workbench with five pinned runs of fig5.10 (coupling k_μ of the last
//! coupling changed per run) over the current one, at 160 x 48, with the cursor on and the
//! results panel beside the chart: the frame the UI redraws on every key and worker message.
//! The same with five pinned runs of fig1.1, whose shaded hysteresis loops are filled with dots.

use std::hint::black_box;
use std::time::Duration;

use adhesion::scenes;
use adhesion::tui::session::Session;
use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

fn press(s: &mut Session, code: KeyCode) {
    s.key(KeyEvent::new(code, KeyModifiers::NONE));
}

fn type_text(s: &mut Session, text: &str) {
    for c in text.chars() {
        press(s, KeyCode::Char(c));
    }
}

fn run(s: &mut Session) {
    press(s, KeyCode::Char('r'));
    assert!(s.wait_until(Duration::from_secs(120), |a| a.running().is_none()));
}

/// A session at scene `id` with five runs pinned under a sixth, parameter `name` set to
/// `value(k)` for run k, and the cursor on.
fn pinned(dir: &std::path::Path, id: &str, name: &str, value: impl Fn(usize) -> String) -> Session {
    let mut session = Session::new(scenes::all(), dir.join("out"), dir.join("presets"));
    while session.app().scene().is_some_and(|s| s.info().id != id) {
        press(&mut session, KeyCode::Down);
    }
    let at = session
        .app()
        .form()
        .and_then(|f| f.specs().iter().position(|p| p.name == name))
        .expect("the parameter");
    press(&mut session, KeyCode::Tab);
    for _ in 0..at {
        press(&mut session, KeyCode::Down);
    }
    for k in 0..6 {
        if k > 0 {
            press(&mut session, KeyCode::Char('p'));
            press(&mut session, KeyCode::Enter);
            session.key(KeyEvent::new(KeyCode::Char('u'), KeyModifiers::CONTROL));
            type_text(&mut session, &value(k));
            press(&mut session, KeyCode::Enter);
        }
        run(&mut session);
    }
    assert_eq!(session.app().pins(session.app().selected()).len(), 5);
    press(&mut session, KeyCode::Char('c'));
    session
}

fn workbench(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let coupled = pinned(dir.path(), "fig5.10", "couplings", |k| {
        format!("[0, 2, {}]", 10 + 5 * k)
    });
    let shaded = pinned(dir.path(), "fig1.1", "max_depth_norm", |k| {
        format!("{}", 1.5 + 0.25 * k as f64)
    });
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).expect("test backend");
    let mut group = c.benchmark_group("workbench");
    group.sample_size(30);
    for (name, session) in [
        ("frame 160x48, fig5.10 with 5 pinned runs", &coupled),
        (
            "frame 160x48, fig1.1 with 5 pinned runs and their shaded loops",
            &shaded,
        ),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                terminal.draw(|f| session.draw(f)).expect("draw");
                black_box(terminal.backend().buffer().area);
            });
        });
    }
    group.finish();
}

criterion_group!(benches, workbench);
criterion_main!(benches);
