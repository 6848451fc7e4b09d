//! Keys of the terminal UI outside text entry: one table maps keys to [`Action`]s and is also
//! the key help (`?`), so the two cannot drift apart.
//!
//! A new action (for instance loading a measured force curve or a height map from a CSV file)
//! is one [`Action`] variant, one row in [`BINDINGS`] and one branch in
//! [`crate::tui::app::App::update`].

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

/// What a key asks for (outside text entry).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Leave the program.
    Quit,
    /// Show or hide the key help.
    Help,
    /// Run the selected scene in the background.
    Run,
    /// Cancel the running job (or close the help).
    Cancel,
    /// Export the selected scene's figure (PNG, SVG, CSV, JSON).
    Export,
    /// Load a preset file into the form.
    LoadPreset,
    /// Save the form as a preset file.
    SavePreset,
    /// Reset the form to the dissertation's values.
    Defaults,
    /// Move the focus between the scene list and the parameter form.
    SwitchFocus,
    /// Move up in the focused list.
    Up,
    /// Move down in the focused list.
    Down,
    /// Open the selected scene's form, or edit the selected parameter.
    Activate,
    /// Next option of a choice or flag parameter.
    Cycle,
    /// Previous panel of a multi-panel figure.
    PrevPanel,
    /// Next panel of a multi-panel figure.
    NextPanel,
    /// Show the caption and the scalar results instead of the chart, or back.
    Info,
    /// Switch automatic runs after every valid change on or off.
    AutoRun,
    /// Type a filter for the scene list.
    Filter,
    /// Keep the current run on the chart to compare later runs with it.
    Pin,
    /// Remove the most recently pinned run.
    Unpin,
    /// Remove every pinned run.
    UnpinAll,
    /// Show or hide the cursor on the chart.
    Cursor,
    /// Move the cursor to the previous point of its curve.
    CursorPrev,
    /// Move the cursor to the next point of its curve.
    CursorNext,
    /// Move the cursor 20 points back.
    CursorPrevFast,
    /// Move the cursor 20 points on.
    CursorNextFast,
    /// Move the cursor to the next curve.
    CursorCurve,
    /// Move the cursor to the next marker (pull-in, pull-off, adhesive force, ...).
    NextMarker,
    /// Move the cursor to the previous marker.
    PrevMarker,
    /// Mark a corner of a zoom rectangle at the cursor; the second mark zooms.
    ZoomRect,
    /// Zoom in by 2 about the cursor (or the centre).
    ZoomIn,
    /// Zoom out by 2.
    ZoomOut,
    /// Show the whole panel again.
    ZoomReset,
    /// Show the run history.
    History,
    /// Open a measured force-curve file (a path prompt).
    Open,
    /// Switch between the scenes and the opened force-curve file.
    SwitchPage,
    /// Type the tip radius of the file page's fits.
    TipRadius,
    /// Show or hide pinned run #1-#9 (the digit says which).
    TogglePin,
    /// Show or hide the current run (the pins stay).
    HideCurrent,
    /// Step the selected parameter up (its declared step, or ×1.1) and rerun after a pause.
    NudgeUp,
    /// Step the selected parameter down (÷1.1, or its declared step) and rerun after a pause.
    NudgeDown,
    /// Show or hide the chart's legend.
    Legend,
    /// Show or hide the results table.
    Results,
}

/// One key binding: the keys, how the help writes them, the action, what it does.
#[derive(Debug, Clone, Copy)]
pub struct Binding {
    /// Keys that trigger the action.
    pub keys: &'static [KeyCode],
    /// The keys as shown in the help.
    pub label: &'static str,
    /// The action.
    pub action: Action,
    /// One line of help.
    pub help: &'static str,
}

/// Every key binding, in the order of the help.
pub const BINDINGS: &[Binding] = &[
    Binding {
        keys: &[KeyCode::Up, KeyCode::Char('k')],
        label: "↑ k",
        action: Action::Up,
        help: "previous scene or parameter; file page: the curve above on the map",
    },
    Binding {
        keys: &[KeyCode::Down, KeyCode::Char('j')],
        label: "↓ j",
        action: Action::Down,
        help: "next scene or parameter; file page: the curve below on the map",
    },
    Binding {
        keys: &[KeyCode::Char('/')],
        label: "/",
        action: Action::Filter,
        help: "filter the scenes by id or title words (Enter keeps, Esc clears)",
    },
    Binding {
        keys: &[KeyCode::Tab, KeyCode::BackTab],
        label: "Tab",
        action: Action::SwitchFocus,
        help: "scene list ⇄ parameters; file page: next segment fitted",
    },
    Binding {
        keys: &[KeyCode::Enter],
        label: "Enter",
        action: Action::Activate,
        help: "open the parameters / edit a value (Enter keeps, Esc reverts)",
    },
    Binding {
        keys: &[KeyCode::Char(' ')],
        label: "Space",
        action: Action::Cycle,
        help: "next option of a choice or true/false; file page: next model",
    },
    Binding {
        keys: &[KeyCode::Char('r')],
        label: "r",
        action: Action::Run,
        help: "run the scene (a new run replaces a running one); file page: fit",
    },
    Binding {
        keys: &[KeyCode::Esc],
        label: "Esc",
        action: Action::Cancel,
        help: "cancel the running job",
    },
    Binding {
        keys: &[KeyCode::Char('a')],
        label: "a",
        action: Action::AutoRun,
        help: "auto-run: run again after every valid change (for fast scenes)",
    },
    Binding {
        keys: &[KeyCode::Char('e')],
        label: "e",
        action: Action::Export,
        help: "export the figure as PNG, SVG, CSV and JSON to output/",
    },
    Binding {
        keys: &[KeyCode::Char('l')],
        label: "l",
        action: Action::LoadPreset,
        help: "load a preset (TOML; presets/<id>.toml or a path you type)",
    },
    Binding {
        keys: &[KeyCode::Char('s')],
        label: "s",
        action: Action::SavePreset,
        help: "save the parameters as a preset",
    },
    Binding {
        keys: &[KeyCode::Char('d')],
        label: "d",
        action: Action::Defaults,
        help: "reset the parameters to the dissertation's values",
    },
    Binding {
        keys: &[KeyCode::Left, KeyCode::Char('[')],
        label: "← [",
        action: Action::PrevPanel,
        help: "previous panel (or click its tab); file page: the curve to the left",
    },
    Binding {
        keys: &[KeyCode::Right, KeyCode::Char(']')],
        label: "→ ]",
        action: Action::NextPanel,
        help: "next panel; file page: the curve to the right",
    },
    Binding {
        keys: &[KeyCode::Char('p')],
        label: "p",
        action: Action::Pin,
        help: "pin the run: later runs draw over it; its legend names what differs",
    },
    Binding {
        keys: &[KeyCode::Char('u')],
        label: "u",
        action: Action::Unpin,
        help: "unpin the most recently pinned run",
    },
    Binding {
        keys: &[KeyCode::Char('U')],
        label: "U",
        action: Action::UnpinAll,
        help: "unpin every run of the scene",
    },
    Binding {
        keys: &[KeyCode::Char('c')],
        label: "c",
        action: Action::Cursor,
        help: "cursor on the chart: x, y with units, the curve of the point",
    },
    Binding {
        keys: &[KeyCode::Char(',')],
        label: ",",
        action: Action::CursorPrev,
        help: "cursor to the previous point of its curve",
    },
    Binding {
        keys: &[KeyCode::Char('.')],
        label: ".",
        action: Action::CursorNext,
        help: "cursor to the next point of its curve",
    },
    Binding {
        keys: &[KeyCode::Char('<')],
        label: "<",
        action: Action::CursorPrevFast,
        help: "cursor 20 points back",
    },
    Binding {
        keys: &[KeyCode::Char('>')],
        label: ">",
        action: Action::CursorNextFast,
        help: "cursor 20 points on",
    },
    Binding {
        keys: &[KeyCode::Char(';')],
        label: ";",
        action: Action::CursorCurve,
        help: "cursor to the next curve (nearest point)",
    },
    Binding {
        keys: &[KeyCode::Char('m')],
        label: "m",
        action: Action::NextMarker,
        help: "cursor to the next marker (pull-in, pull-off, adhesive force)",
    },
    Binding {
        keys: &[KeyCode::Char('M')],
        label: "M",
        action: Action::PrevMarker,
        help: "cursor to the previous marker",
    },
    Binding {
        keys: &[KeyCode::Char('z')],
        label: "z",
        action: Action::ZoomRect,
        help: "zoom: z marks a corner at the cursor, z again zooms to it",
    },
    Binding {
        keys: &[KeyCode::Char('+'), KeyCode::Char('=')],
        label: "+",
        action: Action::ZoomIn,
        help: "zoom in by 2 about the cursor",
    },
    Binding {
        keys: &[KeyCode::Char('-')],
        label: "-",
        action: Action::ZoomOut,
        help: "zoom out by 2",
    },
    Binding {
        keys: &[KeyCode::Char('0'), KeyCode::Char('Z')],
        label: "0 Z",
        action: Action::ZoomReset,
        help: "whole panel again (undo zoom)",
    },
    Binding {
        keys: &[KeyCode::Char('h')],
        label: "h",
        action: Action::History,
        help: "run history: reopen (Enter) or export (e) a run, no rerun",
    },
    Binding {
        keys: &[KeyCode::Char('o')],
        label: "o",
        action: Action::Open,
        help: "open a measured force-curve file (the formats of --fit)",
    },
    Binding {
        keys: &[KeyCode::Char('g')],
        label: "g",
        action: Action::SwitchPage,
        help: "go between the scenes and the opened force-curve file",
    },
    Binding {
        keys: &[KeyCode::Char('t')],
        label: "t",
        action: Action::TipRadius,
        help: "file page: tip radius of the fits (metres; no fit without it)",
    },
    Binding {
        keys: &[KeyCode::Char('i')],
        label: "i",
        action: Action::Info,
        help: "caption and results / chart",
    },
    Binding {
        keys: &[KeyCode::Char('?')],
        label: "?",
        action: Action::Help,
        help: "this help",
    },
    Binding {
        keys: &[
            KeyCode::Char('1'),
            KeyCode::Char('2'),
            KeyCode::Char('3'),
            KeyCode::Char('4'),
            KeyCode::Char('5'),
            KeyCode::Char('6'),
            KeyCode::Char('7'),
            KeyCode::Char('8'),
            KeyCode::Char('9'),
        ],
        label: "1-9",
        action: Action::TogglePin,
        help: "hide / show pinned run #1-#9 (legend entry, table rows stay)",
    },
    Binding {
        keys: &[KeyCode::Char('x')],
        label: "x",
        action: Action::HideCurrent,
        help: "hide / show this run (legend entry, table row stay; exports draw it)",
    },
    Binding {
        keys: &[KeyCode::Char('}')],
        label: "}",
        action: Action::NudgeUp,
        help: "nudge the selected parameter up (its step, else ×1.1), rerun after a pause",
    },
    Binding {
        keys: &[KeyCode::Char('{')],
        label: "{",
        action: Action::NudgeDown,
        help: "nudge the selected parameter down (its step, else ÷1.1), rerun after a pause",
    },
    Binding {
        keys: &[KeyCode::Char('L')],
        label: "L",
        action: Action::Legend,
        help: "show or hide the chart's legend",
    },
    Binding {
        keys: &[KeyCode::Char('R')],
        label: "R",
        action: Action::Results,
        help: "show or hide the results table (current run, pins, differences)",
    },
    Binding {
        keys: &[KeyCode::Char('q')],
        label: "q Ctrl-C",
        action: Action::Quit,
        help: "quit (cancels a running job)",
    },
];

/// The action of a key outside text entry, if any.
pub fn action_for(key: KeyEvent) -> Option<Action> {
    if key.modifiers.contains(KeyModifiers::CONTROL) {
        return matches!(key.code, KeyCode::Char('c')).then_some(Action::Quit);
    }
    BINDINGS
        .iter()
        .find(|b| b.keys.contains(&key.code))
        .map(|b| b.action)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_action_has_exactly_one_binding_and_no_key_is_bound_twice() {
        let mut keys = Vec::new();
        for b in BINDINGS {
            for k in b.keys {
                assert!(!keys.contains(k), "{k:?} bound twice");
                keys.push(*k);
            }
            assert_eq!(
                BINDINGS.iter().filter(|c| c.action == b.action).count(),
                1,
                "{:?}",
                b.action
            );
        }
        let ctrl_c = KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL);
        assert_eq!(action_for(ctrl_c), Some(Action::Quit));
        let plain = |c| KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE);
        assert_eq!(action_for(plain('r')), Some(Action::Run));
        assert_eq!(action_for(plain('y')), None);
    }
}
