//! Terminal UI speed: one full frame with a computed figure (the UI redraws on every key and
//! every worker message), and the latency from `r` to the finished figure through the
//! background worker.

use std::hint::black_box;
use std::time::Duration;

use adhesion::scenes;
use adhesion::tui::session::Session;
use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

fn press(s: &mut Session, c: char) {
    s.key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn tui(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let mut group = c.benchmark_group("tui");
    group.sample_size(30);
    for id in ["fig1.1", "fig1.4b"] {
        let mut session = Session::new(scenes::all(), dir.path().join("out"), dir.path().join("presets"));
        while session.app().scene().is_some_and(|s| s.info().id != id) {
            session.key(KeyEvent::new(KeyCode::Down, KeyModifiers::NONE));
        }
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
    group.finish();
}

criterion_group!(benches, tui);
criterion_main!(benches);
