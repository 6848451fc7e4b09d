//! The page of a measured force-curve file, as transitions of the state: open a file (read in
//! the background; a bad file leaves a one-line message and the last good page), move through
//! its curves on the map's grid, set the tip radius, model and segment, and fit the chosen curve
//! in the background. With a tip radius set, choosing a curve fits it unless it is fitted
//! already, so moving through a map shows each curve's fit.

use std::path::PathBuf;

use super::{App, Effect, Mode, Page, PromptKind};
use crate::fit::TIP_RADIUS_RANGE;
use crate::params::fmt_sig;
use crate::tui::curves::{FilePage, Fitting, MODELS, SEGMENTS, model_name, next_of, segment_name};
use crate::tui::form::LineEdit;
use crate::tui::keymap::Action;
use crate::tui::worker::{Task, TaskDone};

impl App {
    /// The page shown.
    pub fn page(&self) -> Page {
        self.page
    }

    /// The opened force-curve file, if any.
    pub fn file_page(&self) -> Option<&FilePage> {
        self.file.as_ref()
    }

    /// Whether a file is being read.
    pub fn opening(&self) -> bool {
        self.opening.is_some()
    }

    pub(super) fn next_job(&mut self) -> u64 {
        let job = self.next_job;
        self.next_job += 1;
        job
    }

    /// Ask for the path of a file to open (the last opened file's path to start from).
    pub(super) fn prompt_open(&mut self) {
        let start = self
            .file
            .as_ref()
            .map_or(String::new(), |f| f.path.display().to_string());
        self.mode = Mode::Prompt {
            kind: PromptKind::OpenFile,
            edit: LineEdit::new(start),
        };
    }

    /// Read `path` in the background; the page shows it once read.
    pub fn open_file(&mut self, path: PathBuf) -> Vec<Effect> {
        let job = self.next_job();
        self.opening = Some(job);
        self.set_status(format!("reading {}…", path.display()), false);
        vec![Effect::Task {
            job,
            task: Task::Open { path },
        }]
    }

    /// Show the other page (the file page only once a file is open).
    pub(super) fn switch_page(&mut self) {
        match self.page {
            Page::Scenes if self.file.is_some() => self.page = Page::File,
            Page::Scenes => self.set_status("no force-curve file open: o opens one", false),
            Page::File => self.page = Page::Scenes,
        }
    }

    /// Take the tip radius typed at the prompt (metres).
    pub(super) fn set_tip_radius(&mut self, text: &str) -> Vec<Effect> {
        let (lo, hi) = TIP_RADIUS_RANGE;
        let radius = match text.trim().parse::<f64>() {
            Ok(r) if r.is_finite() && (lo..=hi).contains(&r) => r,
            _ => {
                let text = format!(
                    "tip radius must be a number of metres in [{}, {}], got {:?}",
                    fmt_sig(lo),
                    fmt_sig(hi),
                    text.trim()
                );
                self.set_status(text, true);
                return Vec::new();
            }
        };
        let Some(page) = self.file.as_mut() else {
            return Vec::new();
        };
        page.radius = Some(radius);
        page.clear_fits();
        self.fit_selected(false)
    }

    /// A key's action on the file page.
    pub(super) fn file_action(&mut self, action: Action) -> Vec<Effect> {
        let Some(page) = self.file.as_mut() else {
            self.page = Page::Scenes;
            return self.act(action);
        };
        let moved = match action {
            Action::Up => page.step(0, 1),
            Action::Down => page.step(0, -1),
            Action::PrevPanel => page.step(-1, 0),
            Action::NextPanel => page.step(1, 0),
            Action::Run => return self.fit_selected(true),
            Action::Cycle => {
                page.model = next_of(&MODELS, page.model);
                page.clear_fits();
                let text = format!("model: {}", model_name(page.model));
                self.set_status(text, false);
                return self.fit_selected(false);
            }
            Action::SwitchFocus => {
                page.segment = next_of(&SEGMENTS, page.segment);
                page.clear_fits();
                let text = format!("segment fitted: {}", segment_name(page.segment));
                self.set_status(text, false);
                return self.fit_selected(false);
            }
            Action::TipRadius => {
                let start = page.radius.map_or(String::new(), fmt_sig);
                self.mode = Mode::Prompt {
                    kind: PromptKind::TipRadius,
                    edit: LineEdit::new(start),
                };
                return Vec::new();
            }
            Action::Cancel => {
                // A fit takes milliseconds: Esc forgets it rather than stopping it.
                if page.fitting.take().is_some() {
                    self.set_status("fit abandoned", false);
                }
                return Vec::new();
            }
            Action::Quit | Action::Help | Action::Open | Action::SwitchPage => return self.act(action),
            _ => {
                self.set_status(
                    "on the file page: arrows choose a curve, r fits, t tip radius, Space model, \
                     Tab segment, g back to the scenes",
                    false,
                );
                return Vec::new();
            }
        };
        if moved {
            let (index, n) = (page.curve().map_or(0, |c| c.index), page.file.curves.len());
            let text = format!("curve {index} ({} of {n})", page.selected + 1);
            self.set_status(text, false);
            return self.fit_selected(false);
        }
        Vec::new()
    }

    /// Fit the chosen curve in the background: always when `asked` (r), otherwise only when the
    /// tip radius is set and the curve has no fit yet.
    fn fit_selected(&mut self, asked: bool) -> Vec<Effect> {
        let job = self.next_job;
        let Some(page) = self.file.as_mut() else {
            return Vec::new();
        };
        let Some(settings) = page.settings() else {
            if asked {
                self.set_status("set the tip radius first (t, in metres)", true);
            }
            return Vec::new();
        };
        let position = page.selected;
        if !asked && page.fits.contains_key(&position) {
            return Vec::new();
        }
        let Some(curve) = page.curve().cloned() else {
            return Vec::new();
        };
        page.fitting = Some(Fitting { job, curve: position });
        let path = page.path.clone();
        self.next_job += 1;
        self.set_status(format!("fitting curve {}…", curve.index), false);
        vec![Effect::Task {
            job,
            task: Task::Fit {
                path,
                curve: Box::new(curve),
                position,
                settings,
            },
        }]
    }

    /// A task ended: a file read (shown, or its error in the status line with the last page
    /// kept) or a curve fitted. Results of tasks no longer awaited are dropped.
    pub(super) fn on_task(&mut self, job: u64, outcome: Result<TaskDone, String>) -> Vec<Effect> {
        if self.opening == Some(job) {
            self.opening = None;
            match outcome {
                Ok(TaskDone::Opened { path, file }) => {
                    let n = file.curves.len();
                    let text = format!("opened {} ({}, {n} curve(s))", path.display(), file.format);
                    let mut page = FilePage::new(path, *file);
                    // Keep the settings of the last file: the same tip usually measured both.
                    if let Some(old) = &self.file {
                        (page.radius, page.model, page.segment) = (old.radius, old.model, old.segment);
                    }
                    self.file = Some(page);
                    self.page = Page::File;
                    self.mode = Mode::Normal;
                    self.set_status(text, false);
                    return self.fit_selected(false);
                }
                Ok(TaskDone::Fitted { .. } | TaskDone::Converted { .. }) => {}
                Err(message) => self.set_status(message, true),
            }
            return Vec::new();
        }
        let Some(page) = self.file.as_mut() else {
            return Vec::new();
        };
        if page.fitting.map(|f| f.job) != Some(job) {
            return Vec::new();
        }
        let curve = page.fitting.take().map_or(0, |f| f.curve);
        match outcome {
            Ok(TaskDone::Fitted { position, fitted }) => {
                let text = fit_summary(&fitted.fit.fit);
                let warned = !fitted.fit.fit.warnings.is_empty();
                page.fits.insert(position, Ok(*fitted));
                let warning = if warned { " (see the warnings)" } else { "" };
                self.set_status(format!("{text}{warning}"), false);
            }
            Ok(TaskDone::Opened { .. } | TaskDone::Converted { .. }) => {}
            Err(message) => {
                page.fits.insert(curve, Err(message.clone()));
                self.set_status(message, true);
            }
        }
        Vec::new()
    }
}

/// A fit in one line: `ℰ = 2.01 MPa ± 0.4 %, w = 40.1 mJ/m² ± 0.6 %`.
pub fn fit_summary(r: &crate::fit::FitReport) -> String {
    let est = |e: &crate::fit::Estimate, unit: &str| {
        let rel = if e.value != 0.0 {
            format!(" ± {:.1} %", 100.0 * e.std_error / e.value.abs())
        } else {
            String::new()
        };
        format!("{}{rel}", crate::render::labels::fmt_quantity(e.value, unit))
    };
    let mut text = format!("ℰ = {}", est(&r.plane_strain_modulus_pa, "Pa"));
    if let Some(w) = &r.work_of_adhesion_j_per_m2 {
        text.push_str(&format!(", w = {}", est(w, "J/m²")));
    }
    text
}
