//! A terminal-free session of the UI: the [`App`] state, the background [`Worker`], and the
//! effects carried out (runs, exports, presets). The crossterm loop in [`crate::tui::run`] feeds
//! it keys and draws it; tests do the same with ratatui's `TestBackend`.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use ratatui::Frame;
use ratatui::crossterm::event::{KeyEvent, MouseEvent};

use super::app::{App, Effect};
use super::compare::overlay_figure;
use super::view;
use super::worker::Worker;
use crate::figure::Figure;
use crate::headless::{preset_header, write_figure_with_runs};
use crate::params::ParamValues;
use crate::render::data::RunRecord;
use crate::render::{Format, write_atomic};
use crate::scenes::SceneDyn;

/// The UI state, its worker, and where exports go.
#[derive(Debug)]
pub struct Session {
    app: App,
    worker: Worker,
    out_dir: PathBuf,
    timer: Option<(Instant, u64)>,
}

impl Session {
    /// A session over `scenes`, exporting to `out_dir`, offering presets from `preset_dir`.
    pub fn new(
        scenes: Vec<&'static dyn SceneDyn>,
        out_dir: impl Into<PathBuf>,
        preset_dir: impl Into<PathBuf>,
    ) -> Self {
        Self {
            app: App::new(scenes, preset_dir),
            worker: Worker::new(),
            out_dir: out_dir.into(),
            timer: None,
        }
    }

    /// The state.
    pub fn app(&self) -> &App {
        &self.app
    }

    /// Where exports go.
    pub fn out_dir(&self) -> &Path {
        &self.out_dir
    }

    /// Handle a key and carry out what it asks for.
    pub fn key(&mut self, key: KeyEvent) {
        for effect in self.app.update(key) {
            self.apply(effect);
        }
    }

    /// Handle a mouse event and carry out what it asks for.
    pub fn mouse(&mut self, ev: MouseEvent) {
        for effect in self.app.on_mouse(ev) {
            self.apply(effect);
        }
    }

    /// Open a measured force-curve file (read in the background; the file page shows it).
    pub fn open_file(&mut self, path: impl Into<PathBuf>) {
        for effect in self.app.open_file(path.into()) {
            self.apply(effect);
        }
    }

    /// Take every message the worker has, and fire the timer when it is due; returns whether
    /// anything happened.
    pub fn pump(&mut self) -> bool {
        let fired = self.fire_timer();
        let msgs = self.worker.drain();
        let any = fired || !msgs.is_empty();
        for m in msgs {
            for effect in self.app.on_job(m) {
                self.apply(effect);
            }
        }
        any
    }

    /// Take messages until `done(app)` holds or `timeout` passes; returns whether it holds.
    pub fn wait_until(&mut self, timeout: Duration, done: impl Fn(&App) -> bool) -> bool {
        let end = Instant::now() + timeout;
        loop {
            self.pump();
            if done(&self.app) {
                return true;
            }
            let now = Instant::now();
            if now >= end {
                return false;
            }
            if let Some(m) = self
                .worker
                .recv_timeout((end - now).min(Duration::from_millis(20)))
            {
                for effect in self.app.on_job(m) {
                    self.apply(effect);
                }
            }
        }
    }

    /// Hand a due timer to the state; returns whether one fired.
    fn fire_timer(&mut self) -> bool {
        match self.timer {
            Some((due, token)) if Instant::now() >= due => {
                self.timer = None;
                for effect in self.app.on_timer(token) {
                    self.apply(effect);
                }
                true
            }
            _ => false,
        }
    }

    /// Draw the state into a frame; the state keeps where the frame put what the mouse can hit.
    pub fn draw(&self, frame: &mut Frame<'_>) {
        let layout = view::draw(frame, &self.app);
        self.app.set_layout(layout);
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.app.should_quit()
    }

    fn apply(&mut self, effect: Effect) {
        match effect {
            Effect::Start { job, scene, values } => self.worker.start(job, scene, values),
            Effect::Cancel { job } => self.worker.cancel(job),
            Effect::Export { scene } => self.export(scene),
            Effect::ExportHistory { entry } => {
                if let Some(e) = self.app.history().get(entry).cloned() {
                    self.write(e.scene, &e.figure, &e.values, e.run_time_s, &[]);
                }
            }
            Effect::LoadPreset { scene, path } => self.load_preset(scene, &path),
            Effect::SavePreset { scene, path } => self.save_preset(scene, &path),
            Effect::Task { job, task } => self.worker.task(job, task),
            Effect::Timer { token, after } => self.timer = Some((Instant::now() + after, token)),
        }
    }

    /// Export the shown figure of scene `k`; with pinned runs, the figure with every pinned
    /// run drawn over it and the JSON with each run's parameters.
    fn export(&mut self, k: usize) {
        let Some(view) = self.app.figure(k) else {
            return;
        };
        let pins = self.app.pins(k);
        let values = view.values.clone();
        let run_time_s = view.run_time_s.unwrap_or(0.0);
        if pins.is_empty() {
            let figure = view.figure.clone();
            self.write(k, &figure, &values, run_time_s, &[]);
            return;
        }
        let labels: Vec<String> = pins
            .iter()
            .enumerate()
            .map(|(i, p)| super::compare::pin_label(i + 1, p, &values, usize::MAX))
            .collect();
        let figure = overlay_figure(&view.figure, &values, pins, &labels);
        let pins = pins.to_vec();
        let runs: Vec<RunRecord<'_>> = pins
            .iter()
            .zip(&labels)
            .map(|(p, label)| RunRecord {
                label,
                params: &p.values,
                results: &p.figure.results,
                run_time_s: p.run_time_s,
            })
            .collect();
        self.write(k, &figure, &values, run_time_s, &runs);
    }

    fn write(
        &mut self,
        k: usize,
        figure: &Figure,
        values: &ParamValues,
        run_time_s: f64,
        runs: &[RunRecord<'_>],
    ) {
        let Some(scene) = self.app.scenes().get(k) else {
            return;
        };
        // Files of an earlier export of this figure that this one replaces: said, not silent.
        let replaced: Vec<String> = Format::ALL
            .iter()
            .map(|f| format!("{}.{}", figure.id, f.extension()))
            .filter(|name| self.out_dir.join(name).exists())
            .collect();
        let written = write_figure_with_runs(
            figure,
            scene.info().caption,
            values,
            run_time_s,
            runs,
            &self.out_dir,
            &Format::ALL,
        );
        match written {
            Ok(paths) => {
                let names: Vec<String> = paths
                    .iter()
                    .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                    .collect();
                let extra = if runs.is_empty() {
                    String::new()
                } else {
                    format!(" (with {} pinned run(s))", runs.len())
                };
                let replaced = if replaced.is_empty() {
                    String::new()
                } else {
                    format!("; replaced the earlier {}", replaced.join(", "))
                };
                let text = format!(
                    "exported to {}: {}{extra}{replaced}",
                    self.out_dir.display(),
                    names.join(", ")
                );
                self.app.set_status(text, false);
            }
            Err(e) => self.app.set_status(format!("export failed: {e}"), true),
        }
    }

    fn load_preset(&mut self, k: usize, path: &Path) {
        let Some(scene) = self.app.scenes().get(k).copied() else {
            return;
        };
        let mut values = scene.defaults();
        match values.apply_preset_file(path) {
            Ok(()) => {
                let effects = self.app.load_values(k, values);
                let problem = self.app.form().and_then(|f| f.first_error().map(str::to_string));
                match problem {
                    Some(e) => self
                        .app
                        .set_status(format!("loaded {}, but: {e}", path.display()), true),
                    None => self.app.set_status(format!("loaded {}", path.display()), false),
                }
                for e in effects {
                    self.apply(e);
                }
            }
            Err(e) => self.app.set_status(e.to_string(), true),
        }
    }

    fn save_preset(&mut self, k: usize, path: &Path) {
        let (Some(scene), Some(form)) = (self.app.scenes().get(k).copied(), self.app.forms.get(k)) else {
            return;
        };
        if let Some(e) = form.first_error() {
            let text = format!("not saved: {e}");
            self.app.set_status(text, true);
            return;
        }
        let text = form.values().to_preset_text(&preset_header(scene));
        let written = (|| -> crate::error::Result<()> {
            if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir)
                    .map_err(crate::error::Error::file("creating the folder", dir))?;
            }
            write_atomic(path, text.as_bytes())
        })();
        match written {
            Ok(()) => self.app.set_status(format!("saved {}", path.display()), false),
            Err(e) => self
                .app
                .set_status(format!("saving {}: {e}", path.display()), true),
        }
    }
}
