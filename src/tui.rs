//! The terminal UI: pick a scene by chapter, edit its parameters with validation as you type,
//! run it in a background thread while the chart grows, cancel, export, load and save presets.
//!
//! The parts, from pure to impure:
//! - [`form`]: the parameter form of one scene (text per field, last valid set, validation);
//! - [`keymap`]: keys to actions, also the key help;
//! - [`chart`]: the chart's cursor and zoom as plain data, and finding points and markers on it;
//! - [`compare`]: pinned runs drawn over the current one;
//! - [`curves`]: the page of a measured force-curve file (its curves on the map's grid, the fit
//!   settings, the fits) as plain data;
//! - [`layout`]: where a drawn frame put what the mouse can hit (plain data);
//! - [`app`]: the state machine (keys, mouse and run messages in, effects out; no I/O, no
//!   drawing): the chart as an instrument (cursor, markers, zoom, pins, history) included;
//! - [`view`]: drawing the state into any ratatui backend, returning the [`layout`];
//! - [`worker`]: background runs on threads, messages over a channel;
//! - [`session`]: the state plus the worker, carrying out effects (runs, exports, presets);
//! - [`run`]: the crossterm event loop around a session.
//!
//! The terminal is restored on exit, on error (a drop guard) and on panic (the panic hook of
//! [`ratatui::try_init`], which this module lets through only for the drawing thread: a panic in
//! a worker thread is caught there and reported as a failed run instead).

pub mod app;
pub mod chart;
pub mod compare;
pub mod curves;
pub mod form;
pub mod keymap;
pub mod layout;
pub mod session;
pub mod view;
pub mod worker;

use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context;
use ratatui::crossterm::event::{self, Event, KeyEventKind};

use crate::scenes;
use session::Session;

/// How long the loop waits for a key before it looks at the worker again.
const TICK: Duration = Duration::from_millis(40);

/// Restores the terminal when dropped (normal exit and early return on error).
struct TerminalGuard;

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        release_mouse();
        ratatui::restore();
    }
}

/// Stop mouse reporting (crossterm's `DisableMouseCapture`); harmless when it was never on.
fn release_mouse() {
    let _ = ratatui::crossterm::execute!(std::io::stdout(), event::DisableMouseCapture);
}

/// Start the terminal UI over every scene; exports go to `output/`, presets are offered from
/// `presets/`. With `file`, the UI opens on that measured force-curve file (a file it cannot
/// read leaves a one-line message over the scenes).
///
/// # Errors
/// Terminal errors (no terminal, a failed draw).
pub fn run(file: Option<&std::path::Path>) -> anyhow::Result<ExitCode> {
    let mut session = Session::new(scenes::all(), "output", "presets");
    if let Some(path) = file {
        session.open_file(path);
    }
    let _guard = TerminalGuard;
    let mut terminal =
        ratatui::try_init().context("starting the terminal UI (use --headless without a terminal)")?;
    let ui_thread = std::thread::current().id();
    let restore_and_report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        // Worker threads catch their panics and report them as failed runs; only a panic of
        // the drawing thread restores the terminal and prints.
        if std::thread::current().id() == ui_thread {
            release_mouse();
            restore_and_report(info);
        }
    }));
    // Clicks and the wheel where the terminal reports them; every action stays on a key.
    ratatui::crossterm::execute!(std::io::stdout(), event::EnableMouseCapture)
        .context("turning on mouse reporting")?;
    // Draw only when something changed: a key, a resize, a message of the worker.
    let mut dirty = true;
    loop {
        if dirty {
            terminal
                .draw(|frame| session.draw(frame))
                .context("drawing the terminal UI")?;
            dirty = false;
        }
        if event::poll(TICK).context("reading the terminal")? {
            match event::read().context("reading the terminal")? {
                Event::Key(key) if key.kind != KeyEventKind::Release => {
                    session.key(key);
                    dirty = true;
                }
                Event::Mouse(ev) => {
                    session.mouse(ev);
                    dirty = true;
                }
                Event::Resize(..) => dirty = true,
                _ => {}
            }
        }
        dirty |= session.pump();
        if session.should_quit() {
            break;
        }
    }
    Ok(ExitCode::SUCCESS)
}
