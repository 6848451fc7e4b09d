//! Terminal UI speed: one full frame with a computed figure (the UI redraws on every key and
//! every worker message), the latency from `r` to the finished figure through the background
//! worker, and the instrument under load: a frame of fig4.5 with 5 pinned runs and a live run
//! (its partial cycle on screen, the solver busy on another thread), and a key answered and
//! drawn during that run.

use std::hint::black_box;
use std::time::Duration;

use adhesion::scenes;
use adhesion::tui::app::FigureState;
use adhesion::tui::session::Session;
use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

fn press(s: &mut Session, c: char) {
    s.key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn at_scene(dir: &std::path::Path, id: &str) -> Session {
    let mut session = Session::new(scenes::all(), dir.join("out"), dir.join("presets"));
    while session.app().scene().is_some_and(|s| s.info().id != id) {
        session.key(KeyEvent::new(KeyCode::Down, KeyModifiers::NONE));
    }
    session
}

fn tui(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let mut group = c.benchmark_group("tui");
    group.sample_size(30);
    for id in ["fig1.1", "fig1.4b"] {
        let mut session = at_scene(dir.path(), id);
        press(&mut session, 'r');
        assert!(session.wait_until(Duration::from_secs(30), |a| a.running().is_none()));
        let mut terminal = Terminal::new(TestBackend::new(160, 48)).expect("test backend");
        group.bench_function(format!("frame 160x48 with {id}"), |b| {
            b.iter(|| {
                terminal.draw(|f| session.draw(f)).expect("draw");
                black_box(terminal.backend().buffer().area);
            });
        });
        group.bench_function(format!("r to finished figure, {id}"), |b| {
            b.iter(|| {
                press(&mut session, 'r');
                assert!(session.wait_until(Duration::from_secs(30), |a| a.running().is_none()));
            });
        });
    }

    // fig4.5 with 5 pinned runs and a sixth running: the frame shows its partial cycle. The
    // session is not pumped while measuring, so the partial figure stays on screen while the
    // solver keeps a core busy.
    let mut session = at_scene(dir.path(), "fig4.5");
    for _ in 0..5 {
        press(&mut session, 'r');
        assert!(session.wait_until(Duration::from_secs(300), |a| a.running().is_none()));
        press(&mut session, 'p');
    }
    press(&mut session, 'r');
    let live = |a: &adhesion::tui::app::App| {
        a.figure(a.selected())
            .is_some_and(|v| v.state == FigureState::Partial && v.figure.n_points() > 20)
    };
    assert!(
        session.wait_until(Duration::from_secs(300), live),
        "a partial cycle"
    );
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).expect("test backend");
    group.bench_function("frame 160x48, fig4.5 with 5 pins and a live run", |b| {
        b.iter(|| {
            terminal.draw(|f| session.draw(f)).expect("draw");
            black_box(terminal.backend().buffer().area);
        });
    });
    // A key during the run: the cursor on and off, each answered and drawn.
    group.bench_function("key c answered and drawn during a live fig4.5 run", |b| {
        b.iter(|| {
            press(&mut session, 'c');
            terminal.draw(|f| session.draw(f)).expect("draw");
            black_box(terminal.backend().buffer().area);
        });
    });
    press(&mut session, 'q');
    group.finish();
}

criterion_group!(benches, tui);
criterion_main!(benches);
