//! The state of the terminal UI and its transitions: keys in, [`Effect`]s out, messages of the
//! background runs in. No I/O, no threads and no clock here: the session carries the effects
//! out, the view draws the state, so tests drive the UI without a terminal.
//!
//! The state never calls the drawing: what it needs from a drawn frame (where the lists, the
//! chart and the tabs were put) comes back as a [`DrawnLayout`] that the session hands over
//! with [`App::set_layout`]. Keys and worker messages are handled here, the chart's cursor,
//! zoom, pins and history in `app/instrument.rs`, the mouse in `app/mouse.rs`, the page of a
//! measured force-curve file in `app/file.rs`.

mod file;
mod instrument;
mod mouse;

use std::cell::{Ref, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::chart::{AxesKey, CursorAt, PanelView};
use super::compare::Pin;
use super::curves::FilePage;
use super::form::{Form, LineEdit};
use super::keymap::{Action, action_for};
use super::layout::DrawnLayout;
use super::worker::{JobMsg, Outcome, Task};
use crate::figure::Figure;
use crate::params::ParamValues;
use crate::render::terminal::View;
use crate::scenes::SceneDyn;

/// Which pane the arrow keys move in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Focus {
    /// The scene list.
    Scenes,
    /// The parameter form.
    Form,
}

/// The page the panes show.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Page {
    /// The scenes: list, parameter form, figure.
    Scenes,
    /// A measured force-curve file: its curves on the map's grid, the fit of the chosen one.
    File,
}

/// What a path prompt is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PromptKind {
    /// Load a preset into the form.
    LoadPreset,
    /// Save the form as a preset.
    SavePreset,
    /// Open a measured force-curve file.
    OpenFile,
    /// The tip radius of the file page's fits (a number in metres, not a path).
    TipRadius,
}

/// Modal state on top of the panes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    /// Keys go to the key map.
    Normal,
    /// The key help is shown; any key closes it.
    Help,
    /// The run history is shown.
    History {
        /// The highlighted entry (0 is the newest).
        selected: usize,
    },
    /// A filter of the scene list is being typed (`/`); the list narrows as it is typed.
    Filter {
        /// The filter text being typed.
        edit: LineEdit,
    },
    /// A file path is being typed.
    Prompt {
        /// What the path is for.
        kind: PromptKind,
        /// The path being typed.
        edit: LineEdit,
    },
}

/// How complete a shown figure is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureState {
    /// Partial results of a running job.
    Partial,
    /// The finished figure.
    Complete,
    /// Partial results of a cancelled job.
    Cancelled,
    /// Partial results of a failed job.
    Failed,
}

/// A scene's latest figure and the parameters it was computed with.
#[derive(Debug, Clone)]
pub struct FigureView {
    /// The figure.
    pub figure: Figure,
    /// Parameters of the run.
    pub values: ParamValues,
    /// Wall time of the run in seconds, once finished.
    pub run_time_s: Option<f64>,
    /// Complete or partial.
    pub state: FigureState,
}

/// The run in progress.
#[derive(Debug, Clone)]
pub struct Running {
    /// Run id.
    pub job: u64,
    /// Index of the scene.
    pub scene: usize,
    /// Parameters of the run.
    pub values: ParamValues,
    /// Fraction done, 0 to 1 (the largest reported, so the gauge never moves back).
    pub fraction: f64,
    /// Seconds since the run started, as of the latest progress message.
    pub elapsed_s: f64,
    /// Latest progress message.
    pub message: String,
    /// Whether cancellation was requested.
    pub cancelling: bool,
}

/// A finished run kept for reopening and exporting without rerunning.
#[derive(Debug, Clone)]
pub struct HistoryEntry {
    /// Scene index.
    pub scene: usize,
    /// The figure.
    pub figure: Figure,
    /// Its parameters.
    pub values: ParamValues,
    /// Wall time in seconds.
    pub run_time_s: f64,
    /// When it ended.
    pub finished_at: std::time::SystemTime,
    /// Complete, or cancelled with the partial figure it had.
    pub state: FigureState,
}

/// How long after the last nudge of a parameter the scene reruns.
pub const NUDGE_PAUSE: std::time::Duration = std::time::Duration::from_millis(350);

/// Runs the history keeps.
pub const HISTORY_LEN: usize = 20;

/// A row of the scene list: a chapter heading or a scene (index).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ListRow {
    /// Chapter heading (chapter key).
    Chapter(&'static str),
    /// A scene, by index.
    Scene(usize),
}

/// A line in the status bar.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Status {
    /// Text, one line.
    pub text: String,
    /// Shown as an error.
    pub error: bool,
}

/// Something the session must do outside the state.
pub enum Effect {
    /// Start a background run.
    Start {
        /// Run id (messages carry it).
        job: u64,
        /// The scene.
        scene: &'static dyn SceneDyn,
        /// Validated parameters.
        values: ParamValues,
    },
    /// Ask a run to stop.
    Cancel {
        /// Run id.
        job: u64,
    },
    /// Export the complete figure of scene `scene` (index) with its pinned runs.
    Export {
        /// Scene index.
        scene: usize,
    },
    /// Export entry `entry` of the run history (0 is the newest).
    ExportHistory {
        /// History index.
        entry: usize,
    },
    /// Read a preset file into the form of scene `scene`.
    LoadPreset {
        /// Scene index.
        scene: usize,
        /// The file.
        path: PathBuf,
    },
    /// Write the form of scene `scene` as a preset file.
    SavePreset {
        /// Scene index.
        scene: usize,
        /// The file.
        path: PathBuf,
    },
    /// Call [`App::on_timer`] with `token` once `after` has passed (a later timer replaces
    /// an earlier one).
    Timer {
        /// What the timer is for (only the latest token acts).
        token: u64,
        /// How long to wait.
        after: std::time::Duration,
    },
    /// Do background work that is not a scene run (read a file, fit a curve).
    Task {
        /// Run id (the message carries it).
        job: u64,
        /// The work.
        task: Task,
    },
}

impl std::fmt::Debug for Effect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Effect::Start { job, scene, .. } => write!(f, "Start({job}, {})", scene.info().id),
            Effect::Cancel { job } => write!(f, "Cancel({job})"),
            Effect::Export { scene } => write!(f, "Export({scene})"),
            Effect::ExportHistory { entry } => write!(f, "ExportHistory({entry})"),
            Effect::Timer { token, after } => write!(f, "Timer({token}, {} ms)", after.as_millis()),
            Effect::LoadPreset { scene, path } => write!(f, "LoadPreset({scene}, {})", path.display()),
            Effect::SavePreset { scene, path } => write!(f, "SavePreset({scene}, {})", path.display()),
            Effect::Task { job, task } => match task {
                Task::Open { path } => write!(f, "Open({job}, {})", path.display()),
                Task::Fit { position, .. } => write!(f, "Fit({job}, curve {position})"),
                Task::Convert { scene, .. } => write!(f, "Convert({job}, {scene:?})"),
            },
        }
    }
}

/// The whole state of the terminal UI.
pub struct App {
    pub(crate) scenes: Vec<&'static dyn SceneDyn>,
    pub(crate) forms: Vec<Form>,
    pub(crate) figures: Vec<Option<FigureView>>,
    pub(crate) selected: usize,
    pub(crate) focus: Focus,
    pub(crate) mode: Mode,
    pub(crate) running: Option<Running>,
    pub(crate) panel: usize,
    pub(crate) show_info: bool,
    pub(crate) status: Status,
    pub(crate) auto_run: bool,
    pub(crate) filter: String,
    pub(crate) pins: Vec<Vec<Pin>>,
    pub(crate) current_hidden: Vec<bool>,
    pub(crate) cursor: Option<CursorAt>,
    pub(crate) zoom: Option<View>,
    pub(crate) zoom_mark: Option<(f64, f64)>,
    pub(crate) drag: Option<((f64, f64), (f64, f64))>,
    pub(crate) history: Vec<HistoryEntry>,
    pub(crate) views: HashMap<(usize, usize), PanelView>,
    pub(crate) last_panel: Vec<usize>,
    pub(crate) axes: Vec<Vec<AxesKey>>,
    pub(crate) layout: RefCell<DrawnLayout>,
    pub(crate) page: Page,
    pub(crate) file: Option<FilePage>,
    pub(crate) opening: Option<u64>,
    pub(crate) legend: bool,
    pub(crate) results: Option<bool>,
    pub(crate) nudged: Option<u64>,
    pub(crate) help_scroll: u16,
    pub(crate) kept_marker: Option<String>,
    preset_dir: PathBuf,
    next_job: u64,
    quit: bool,
}

impl std::fmt::Debug for App {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("App")
            .field("selected", &self.selected)
            .field("focus", &self.focus)
            .field("mode", &self.mode)
            .field("running", &self.running.as_ref().map(|r| r.job))
            .field("status", &self.status)
            .finish()
    }
}

impl App {
    /// The UI over `scenes` (in chapter order); presets are offered from `preset_dir`.
    pub fn new(scenes: Vec<&'static dyn SceneDyn>, preset_dir: impl Into<PathBuf>) -> Self {
        let forms = scenes.iter().map(|s| Form::new(*s)).collect();
        let figures = scenes.iter().map(|_| None).collect();
        let pins = scenes.iter().map(|_| Vec::new()).collect();
        let n = scenes.len();
        Self {
            scenes,
            forms,
            figures,
            selected: 0,
            focus: Focus::Scenes,
            mode: Mode::Normal,
            running: None,
            panel: 0,
            show_info: false,
            status: Status {
                text: "select a scene, Enter to edit its parameters, r to run, ? for help".into(),
                error: false,
            },
            auto_run: false,
            filter: String::new(),
            pins,
            current_hidden: vec![false; n],
            cursor: None,
            zoom: None,
            zoom_mark: None,
            drag: None,
            history: Vec::new(),
            views: HashMap::new(),
            last_panel: vec![0; n],
            axes: vec![Vec::new(); n],
            layout: RefCell::new(DrawnLayout::default()),
            page: Page::Scenes,
            file: None,
            opening: None,
            legend: true,
            results: None,
            nudged: None,
            help_scroll: 0,
            kept_marker: None,
            preset_dir: preset_dir.into(),
            next_job: 1,
            quit: false,
        }
    }

    /// The scenes.
    pub fn scenes(&self) -> &[&'static dyn SceneDyn] {
        &self.scenes
    }

    /// Index of the selected scene.
    pub fn selected(&self) -> usize {
        self.selected
    }

    /// The selected scene.
    pub fn scene(&self) -> Option<&'static dyn SceneDyn> {
        self.scenes.get(self.selected).copied()
    }

    /// The form of the selected scene.
    pub fn form(&self) -> Option<&Form> {
        self.forms.get(self.selected)
    }

    /// The latest figure of scene `k`.
    pub fn figure(&self, k: usize) -> Option<&FigureView> {
        self.figures.get(k).and_then(Option::as_ref)
    }

    /// The run in progress.
    pub fn running(&self) -> Option<&Running> {
        self.running.as_ref()
    }

    /// The status line.
    pub fn status(&self) -> &Status {
        &self.status
    }

    /// The modal state.
    pub fn mode(&self) -> &Mode {
        &self.mode
    }

    /// The focused pane.
    pub fn focus(&self) -> Focus {
        self.focus
    }

    /// The shown panel of the selected figure.
    pub fn panel(&self) -> usize {
        let n = self
            .figure(self.selected)
            .map_or(1, |f| f.figure.panels.len().max(1));
        self.panel.min(n - 1)
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// Set the status line.
    pub fn set_status(&mut self, text: impl Into<String>, error: bool) {
        self.status = Status {
            text: text.into(),
            error,
        };
    }

    /// Whether valid changes start a run by themselves.
    pub fn auto_run(&self) -> bool {
        self.auto_run
    }

    /// Put loaded preset values into the form of scene `scene` (with auto-run, this may start
    /// a run).
    pub fn load_values(&mut self, scene: usize, values: ParamValues) -> Vec<Effect> {
        match self.forms.get_mut(scene) {
            Some(form) => {
                form.load(values);
                self.after_change()
            }
            None => Vec::new(),
        }
    }

    /// After a change of the form: with auto-run on, run a valid set that is neither running
    /// nor shown already.
    fn after_change(&mut self) -> Vec<Effect> {
        let mut effects = Vec::new();
        let Some(form) = self.forms.get(self.selected) else {
            return effects;
        };
        if !self.auto_run || !form.is_valid() {
            return effects;
        }
        let values = form.values();
        let running = self
            .running
            .as_ref()
            .is_some_and(|r| r.scene == self.selected && &r.values == values);
        let shown = self
            .figure(self.selected)
            .is_some_and(|v| v.state == FigureState::Complete && &v.values == values);
        if !running && !shown {
            self.run(&mut effects);
        }
        effects
    }

    /// Handle a key; returns what the session must do.
    pub fn update(&mut self, key: KeyEvent) -> Vec<Effect> {
        if key.kind == KeyEventKind::Release {
            return Vec::new();
        }
        // Ctrl-C quits from anywhere, text entry included.
        if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
            return self.act(Action::Quit);
        }
        match &mut self.mode {
            Mode::Normal => {}
            Mode::Help => {
                match key.code {
                    KeyCode::Down | KeyCode::Char('j') | KeyCode::PageDown => {
                        self.help_scroll = self.help_scroll.saturating_add(1);
                    }
                    KeyCode::Up | KeyCode::Char('k') | KeyCode::PageUp => {
                        self.help_scroll = self.help_scroll.saturating_sub(1);
                    }
                    _ => self.mode = Mode::Normal,
                }
                return Vec::new();
            }
            Mode::History { selected } => {
                let n = self.history.len();
                let k = *selected;
                match key.code {
                    KeyCode::Up | KeyCode::Char('k') => *selected = k.saturating_sub(1),
                    KeyCode::Down | KeyCode::Char('j') => *selected = (k + 1).min(n.saturating_sub(1)),
                    KeyCode::Enter => {
                        self.mode = Mode::Normal;
                        return self.reopen(k);
                    }
                    KeyCode::Char('e')
                        if self
                            .history
                            .get(k)
                            .is_some_and(|e| e.state != FigureState::Complete) =>
                    {
                        self.set_status("a cancelled run is partial: it is not exported", true);
                    }
                    KeyCode::Char('e') if k < n => return vec![Effect::ExportHistory { entry: k }],
                    KeyCode::Esc | KeyCode::Char('h' | 'q') => self.mode = Mode::Normal,
                    _ => {}
                }
                return Vec::new();
            }
            Mode::Filter { edit } => {
                match key.code {
                    KeyCode::Esc => {
                        self.filter.clear();
                        self.mode = Mode::Normal;
                    }
                    KeyCode::Enter => self.mode = Mode::Normal,
                    KeyCode::Up => self.select_scene(-1),
                    KeyCode::Down => self.select_scene(1),
                    _ => {
                        if edit.handle(key) {
                            self.filter = edit.text().to_string();
                            self.keep_selection_visible();
                        }
                    }
                }
                self.focus = Focus::Scenes;
                return Vec::new();
            }
            Mode::Prompt { kind, edit } => {
                let kind = *kind;
                match key.code {
                    KeyCode::Esc => self.mode = Mode::Normal,
                    KeyCode::Enter => {
                        let path = PathBuf::from(edit.text().trim());
                        self.mode = Mode::Normal;
                        if path.as_os_str().is_empty() {
                            self.set_status("no file given", true);
                            return Vec::new();
                        }
                        let scene = self.selected;
                        return match kind {
                            PromptKind::LoadPreset => vec![Effect::LoadPreset { scene, path }],
                            PromptKind::SavePreset => vec![Effect::SavePreset { scene, path }],
                            PromptKind::OpenFile => self.open_file(path),
                            PromptKind::TipRadius => self.set_tip_radius(&path.to_string_lossy()),
                        };
                    }
                    _ => {
                        edit.handle(key);
                    }
                }
                return Vec::new();
            }
        }
        if self.focus == Focus::Form
            && let Some(form) = self.forms.get_mut(self.selected)
            && form.editor().is_some()
        {
            match key.code {
                KeyCode::Enter | KeyCode::Tab => form.finish_edit(),
                KeyCode::Esc => form.cancel_edit(),
                KeyCode::Up => form.move_selection(-1),
                KeyCode::Down => form.move_selection(1),
                _ => {
                    form.edit_key(key);
                }
            }
            self.show_form_status();
            return self.after_change();
        }
        if let (Some(Action::TogglePin), KeyCode::Char(d)) = (action_for(key), key.code)
            && self.page == Page::Scenes
        {
            let i = d.to_digit(10).map_or(0, |d| d as usize);
            self.toggle_pin(i.saturating_sub(1));
            return Vec::new();
        }
        match action_for(key) {
            Some(action) if self.page == Page::File => self.file_action(action),
            Some(action) => self.act(action),
            None => Vec::new(),
        }
    }

    fn show_form_status(&mut self) {
        if let Some(form) = self.forms.get(self.selected) {
            match form.first_error() {
                Some(e) => self.set_status(e.to_string(), true),
                None if self.status.error => self.set_status("parameters valid", false),
                None => {}
            }
        }
    }

    fn act(&mut self, action: Action) -> Vec<Effect> {
        let mut effects = Vec::new();
        match action {
            Action::Quit => {
                self.quit = true;
                if let Some(run) = &self.running {
                    effects.push(Effect::Cancel { job: run.job });
                }
            }
            Action::Help => {
                self.mode = Mode::Help;
                self.help_scroll = 0;
            }
            Action::Filter => {
                self.focus = Focus::Scenes;
                self.mode = Mode::Filter {
                    edit: LineEdit::new(self.filter.clone()),
                };
            }
            Action::Run => self.run(&mut effects),
            Action::Cancel => {
                if let Some(run) = &mut self.running {
                    run.cancelling = true;
                    effects.push(Effect::Cancel { job: run.job });
                    let id = self.scenes[run.scene].info().id;
                    self.set_status(format!("cancelling {id}…"), false);
                } else if self.show_info {
                    self.show_info = false;
                }
            }
            Action::Export => match self.figure(self.selected) {
                Some(view) if view.state == FigureState::Complete => {
                    effects.push(Effect::Export { scene: self.selected });
                }
                Some(_) => self.set_status(
                    "the figure is incomplete: run the scene to the end (r) before exporting",
                    true,
                ),
                None => self.set_status("nothing to export: run the scene first (r)", true),
            },
            Action::LoadPreset | Action::SavePreset => {
                if let Some(scene) = self.scene() {
                    let path = default_preset_path(&self.preset_dir, scene.info().id);
                    let kind = if action == Action::LoadPreset {
                        PromptKind::LoadPreset
                    } else {
                        PromptKind::SavePreset
                    };
                    self.mode = Mode::Prompt {
                        kind,
                        edit: LineEdit::new(path.display().to_string()),
                    };
                }
            }
            Action::Defaults => {
                if let Some(form) = self.forms.get_mut(self.selected) {
                    form.reset();
                    self.set_status("parameters reset to the dissertation's values", false);
                    effects.extend(self.after_change());
                }
            }
            Action::AutoRun => {
                self.auto_run = !self.auto_run;
                let text = if self.auto_run {
                    "auto-run on: every valid change runs the scene"
                } else {
                    "auto-run off"
                };
                self.set_status(text, false);
                effects.extend(self.after_change());
            }
            Action::SwitchFocus => {
                self.focus = match self.focus {
                    Focus::Scenes => Focus::Form,
                    Focus::Form => Focus::Scenes,
                };
            }
            Action::Up | Action::Down => {
                let step = if action == Action::Up { -1 } else { 1 };
                match self.focus {
                    Focus::Scenes => self.select_scene(step),
                    Focus::Form => {
                        if let Some(form) = self.forms.get_mut(self.selected) {
                            form.move_selection(step);
                        }
                    }
                }
            }
            Action::Activate => match self.focus {
                Focus::Scenes => self.focus = Focus::Form,
                Focus::Form => {
                    if let Some(form) = self.forms.get_mut(self.selected) {
                        form.start_edit();
                    }
                }
            },
            Action::Cycle => {
                if self.focus == Focus::Form
                    && let Some(form) = self.forms.get_mut(self.selected)
                {
                    form.cycle();
                    self.show_form_status();
                    effects.extend(self.after_change());
                }
            }
            Action::PrevPanel | Action::NextPanel => {
                let before = self.panel();
                let next = if action == Action::PrevPanel {
                    before.saturating_sub(1)
                } else {
                    before + 1
                };
                self.show_panel(next);
            }
            Action::History => {
                if self.history.is_empty() {
                    self.set_status("no finished run yet: the history keeps the last 20 runs", false);
                } else {
                    self.mode = Mode::History { selected: 0 };
                }
            }
            Action::Pin
            | Action::Unpin
            | Action::UnpinAll
            | Action::Cursor
            | Action::CursorPrev
            | Action::CursorNext
            | Action::CursorPrevFast
            | Action::CursorNextFast
            | Action::CursorCurve
            | Action::NextMarker
            | Action::PrevMarker
            | Action::ZoomRect
            | Action::ZoomIn
            | Action::ZoomOut
            | Action::ZoomReset => self.chart_action(action),
            Action::Info => self.show_info = !self.show_info,
            Action::TogglePin => {}
            Action::HideCurrent => self.toggle_current(),
            Action::NudgeUp | Action::NudgeDown => effects.extend(self.nudge(action == Action::NudgeUp)),
            Action::Legend => {
                self.legend = !self.legend;
                let text = if self.legend {
                    "legend shown"
                } else {
                    "legend hidden (L shows it)"
                };
                self.set_status(text, false);
            }
            Action::Results => {
                // From what is shown: beside the chart where there is room, else nothing.
                let shown = self.results.unwrap_or(self.layout.borrow().results_beside);
                self.results = Some(!shown);
                let text = if shown {
                    "results hidden (R shows them)"
                } else {
                    "results shown"
                };
                self.set_status(text, false);
            }
            Action::Open => self.prompt_open(),
            Action::SwitchPage => self.switch_page(),
            Action::TipRadius => {
                self.set_status("the tip radius is set on the file page (o opens a file)", false);
            }
        }
        // Keep the panel index within the figure.
        self.panel = self.panel();
        effects
    }

    /// The filter of the scene list (empty: every scene).
    pub fn filter(&self) -> &str {
        &self.filter
    }

    /// The rows of the scene list under the filter: each chapter with visible scenes, then them.
    pub fn list_rows(&self) -> Vec<ListRow> {
        let mut rows = Vec::new();
        let mut chapter = "";
        for k in self.visible_scenes() {
            let info = self.scenes[k].info();
            if info.chapter != chapter {
                chapter = info.chapter;
                rows.push(ListRow::Chapter(chapter));
            }
            rows.push(ListRow::Scene(k));
        }
        rows
    }

    /// Take the layout of a drawn frame: the mouse acts on what that frame showed.
    pub fn set_layout(&self, layout: DrawnLayout) {
        *self.layout.borrow_mut() = layout;
    }

    /// The layout of the last drawn frame.
    pub fn layout(&self) -> Ref<'_, DrawnLayout> {
        self.layout.borrow()
    }

    /// Indices of the scenes the filter lets through (id or title contains every word of the
    /// filter, ignoring case), in list order.
    pub fn visible_scenes(&self) -> Vec<usize> {
        let words: Vec<String> = self.filter.split_whitespace().map(str::to_lowercase).collect();
        self.scenes
            .iter()
            .enumerate()
            .filter(|(_, s)| {
                let info = s.info();
                let text = format!("{} {}", info.id, info.title).to_lowercase();
                words.iter().all(|w| text.contains(w.as_str()))
            })
            .map(|(k, _)| k)
            .collect()
    }

    /// Select the first visible scene when the selected one is filtered out.
    fn keep_selection_visible(&mut self) {
        let visible = self.visible_scenes();
        if !visible.contains(&self.selected)
            && let Some(&k) = visible.first()
        {
            self.select_index(k);
        }
    }

    fn select_scene(&mut self, step: isize) {
        let visible = self.visible_scenes();
        if visible.is_empty() {
            return;
        }
        let at = visible.iter().position(|&k| k == self.selected);
        let k = match at {
            Some(i) => visible[(i as isize + step).clamp(0, visible.len() as isize - 1) as usize],
            None => visible[0],
        };
        self.select_index(k);
    }

    /// Step the selected parameter ([`Form::nudge`]) and ask for a rerun after [`NUDGE_PAUSE`]:
    /// steps in quick succession rerun once, with the last value.
    fn nudge(&mut self, up: bool) -> Vec<Effect> {
        let Some(form) = self.forms.get_mut(self.selected) else {
            return Vec::new();
        };
        match form.nudge(up) {
            Ok(text) => {
                let k = form.selected();
                let name = form.specs()[k].name;
                self.focus = Focus::Form;
                match form.first_error() {
                    Some(e) => {
                        let text = format!("{name} = {text}, but: {e}");
                        self.set_status(text, true);
                        Vec::new()
                    }
                    None => {
                        let token = self.next_job();
                        self.nudged = Some(token);
                        self.set_status(format!("{name} = {text}: reruns in a moment"), false);
                        vec![Effect::Timer {
                            token,
                            after: NUDGE_PAUSE,
                        }]
                    }
                }
            }
            Err(e) => {
                self.set_status(e, true);
                Vec::new()
            }
        }
    }

    /// A timer asked for by [`Effect::Timer`] ran out: the latest nudge reruns the scene
    /// (cancelling the run in flight); earlier ones do nothing.
    pub fn on_timer(&mut self, token: u64) -> Vec<Effect> {
        if self.nudged != Some(token) {
            return Vec::new();
        }
        self.nudged = None;
        let mut effects = Vec::new();
        self.run(&mut effects);
        effects
    }

    fn run(&mut self, effects: &mut Vec<Effect>) {
        let Some(form) = self.forms.get(self.selected) else {
            return;
        };
        let scene = form.scene();
        if let Some(e) = form.first_error() {
            let text = format!("cannot run {}: {e}", scene.info().id);
            self.set_status(text, true);
            return;
        }
        let values = form.values().clone();
        if let Some(old) = self.running.take() {
            effects.push(Effect::Cancel { job: old.job });
        }
        self.keep_marker();
        let job = self.next_job();
        self.running = Some(Running {
            job,
            scene: self.selected,
            values: values.clone(),
            fraction: 0.0,
            elapsed_s: 0.0,
            message: "starting".into(),
            cancelling: false,
        });
        self.set_status(format!("running {}…", scene.info().id), false);
        effects.push(Effect::Start { job, scene, values });
    }

    /// Take a message of a background run; returns what the session must do next (a file
    /// read fits its first curve when the tip radius is known). Messages of runs no longer
    /// tracked are ignored.
    pub fn on_job(&mut self, msg: JobMsg) -> Vec<Effect> {
        if let JobMsg::Task { job, outcome } = msg {
            if self.pins.iter().flatten().any(|p| p.converting == Some(job)) {
                self.on_converted(job, outcome);
                return Vec::new();
            }
            return self.on_task(job, outcome);
        }
        let Some(run) = &mut self.running else {
            return Vec::new();
        };
        if msg.job() != run.job {
            return Vec::new();
        }
        let scene = run.scene;
        let id = self.scenes[scene].info().id;
        match msg {
            JobMsg::Progress {
                fraction,
                message,
                elapsed_s,
                ..
            } => {
                // Parallel parts of a run may report out of order: the gauge only advances.
                run.fraction = run.fraction.max(fraction);
                run.elapsed_s = elapsed_s;
                run.message = message;
            }
            JobMsg::Preview { figure, .. } => {
                self.figures[scene] = Some(FigureView {
                    figure: *figure,
                    values: run.values.clone(),
                    run_time_s: None,
                    state: FigureState::Partial,
                });
            }
            JobMsg::Task { .. } => {}
            JobMsg::Finished {
                outcome,
                run_time_s,
                finished_at,
                ..
            } => {
                let run = self.running.take();
                match outcome {
                    Outcome::Done(figure) => {
                        let values = run
                            .map(|r| r.values)
                            .unwrap_or_else(|| self.forms[scene].values().clone());
                        self.remember(HistoryEntry {
                            scene,
                            figure: (*figure).clone(),
                            values: values.clone(),
                            run_time_s,
                            finished_at,
                            state: FigureState::Complete,
                        });
                        self.on_results(scene, &figure);
                        self.figures[scene] = Some(FigureView {
                            figure: *figure,
                            values,
                            run_time_s: Some(run_time_s),
                            state: FigureState::Complete,
                        });
                        self.set_status(format!("{id} done in {}", fmt_duration(run_time_s)), false);
                        self.panel = self.panel();
                        return self.convert_pins(scene);
                    }
                    Outcome::Cancelled => {
                        mark_partial(&mut self.figures[scene], FigureState::Cancelled);
                        // The history keeps a cancelled run with what it had computed.
                        if let (Some(run), Some(v)) = (run, &self.figures[scene])
                            && v.state == FigureState::Cancelled
                            && v.values == run.values
                        {
                            let entry = HistoryEntry {
                                scene,
                                figure: v.figure.clone(),
                                values: run.values,
                                run_time_s,
                                finished_at,
                                state: FigureState::Cancelled,
                            };
                            self.remember(entry);
                        }
                        self.set_status(
                            format!("{id} cancelled after {}", fmt_duration(run_time_s)),
                            false,
                        );
                    }
                    Outcome::Failed(message) => {
                        mark_partial(&mut self.figures[scene], FigureState::Failed);
                        self.set_status(format!("{id} failed: {message}"), true);
                    }
                }
                self.panel = self.panel();
            }
        }
        Vec::new()
    }
}

/// Mark the partial figure of a run that ended early (a complete figure of an earlier run stays).
fn mark_partial(figure: &mut Option<FigureView>, state: FigureState) {
    if let Some(v) = figure
        && v.state == FigureState::Partial
    {
        v.state = state;
    }
}

/// `presets/<id>.toml` under `dir`.
pub fn default_preset_path(dir: &Path, id: &str) -> PathBuf {
    dir.join(format!("{id}.toml"))
}

/// A run time for people: `12 ms`, `3.4 s`.
pub fn fmt_duration(seconds: f64) -> String {
    if seconds < 1.0 {
        format!("{:.0} ms", seconds * 1e3)
    } else {
        format!("{seconds:.1} s")
    }
}
