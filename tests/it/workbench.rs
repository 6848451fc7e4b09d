//! The terminal workbench as an instrument, driven through ratatui's `TestBackend`: the scene
//! list in two columns and its filter, readable axes, the results beside the chart, pinned runs
//! compared on one chart, the cursor readout and marker jumps, a gauge that advances, the run
//! history, the mouse, and the key help listing every key.

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;

use adhesion::scenes;
use adhesion::tui::app::Mode;
use adhesion::tui::session::Session;

use super::tui::{press, session, text, type_text};

fn draw_at(s: &Session, w: u16, h: u16) -> Buffer {
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
