//! The chart as an instrument, as transitions of the state: pinned runs drawn over the current
//! one, a cursor that moves along the data and jumps between markers, zoom into a rectangle and
//! back, each panel's cursor and zoom kept while another is shown, and the run history.

use ratatui::layout::Rect;

use super::{App, Effect, FigureState, FigureView, HISTORY_LEN, HistoryEntry};
use crate::figure::{Figure, Scale};
use crate::render::terminal::{ChartGeometry, View, shown_range};
use crate::tui::chart::{
    AxesKey, CursorAt, PanelView, Readout, cursor_point, first_point, nearest, nearest_in, readout,
    scale_about,
};
use crate::tui::compare::{Overlay, Pin, display_variant, overlay, pin_color, pin_label};
use crate::tui::keymap::Action;
use crate::tui::worker::{SceneRef, Task, TaskDone};

/// Longest legend label of a pinned run, in characters.
const PIN_LABEL_WIDTH: usize = 36;
/// Points the fast cursor keys skip.
const FAST_STEP: isize = 20;

impl App {
    /// The pinned runs of scene `k`.
    pub fn pins(&self, k: usize) -> &[Pin] {
        self.pins.get(k).map_or(&[], Vec::as_slice)
    }

    /// The legend labels of the selected scene's pins against its shown run.
    pub fn pin_labels(&self) -> Vec<String> {
        let Some(view) = self.figure(self.selected) else {
            return Vec::new();
        };
        self.pins(self.selected)
            .iter()
            .enumerate()
            .map(|(i, p)| pin_label(i + 1, p, &view.values, PIN_LABEL_WIDTH))
            .collect()
    }

    /// The shown panel of the selected scene with its pinned runs drawn over it, each pin's
    /// legend entry listing the symbols of its markers and regions.
    pub fn drawn(&self) -> Option<Overlay> {
        let view = self.figure(self.selected)?;
        let k = self.panel();
        let panel = view.figure.panels.get(k)?;
        let drawn = overlay(
            panel,
            k,
            &view.values,
            self.pins(self.selected),
            &self.pin_labels(),
        )
        .with_legend_symbols();
        Some(if self.current_hidden() {
            drawn.with_current_hidden()
        } else {
            drawn
        })
    }

    /// Whether the selected scene's current run is hidden from the chart.
    pub fn current_hidden(&self) -> bool {
        self.current_hidden.get(self.selected).copied().unwrap_or(false)
    }

    /// Show or hide the selected scene's current run (its row of the results table stays,
    /// dimmed; an export still draws it).
    pub(crate) fn toggle_current(&mut self) {
        let Some(hidden) = self.current_hidden.get_mut(self.selected) else {
            return;
        };
        *hidden = !*hidden;
        let text = if *hidden {
            "this run hidden (x shows it; exports still draw it)"
        } else {
            "this run shown"
        };
        self.cursor = None;
        self.set_status(text, false);
    }

    /// Where the last frame drew the chart's graph and what it shows.
    pub fn chart_geometry(&self) -> Option<ChartGeometry> {
        self.layout.borrow().chart
    }

    /// The area the last frame drew the chart into (axes and labels included).
    pub fn chart_area(&self) -> Rect {
        self.layout.borrow().chart_area
    }

    /// The shown range (zoom) of the chart, `None` for the whole panel.
    pub fn zoom(&self) -> Option<View> {
        self.zoom
    }

    /// The run history, newest first.
    pub fn history(&self) -> &[HistoryEntry] {
        &self.history
    }

    /// The cursor position.
    pub fn cursor(&self) -> Option<CursorAt> {
        self.cursor
    }

    /// The cursor's point, curve and coordinates on the drawn panel.
    pub fn readout(&self) -> Option<Readout> {
        let drawn = self.drawn()?;
        readout(&drawn, self.cursor?)
    }

    /// The rectangle being chosen for zooming (first corner and the cursor, or a mouse drag).
    pub fn selection(&self) -> Option<View> {
        if let Some((a, b)) = self.drag {
            return Some(((a.0, b.0), (a.1, b.1)));
        }
        let a = self.zoom_mark?;
        let b = self.readout()?.point;
        Some(((a.0, b.0), (a.1, b.1)))
    }

    pub(crate) fn remember(&mut self, entry: HistoryEntry) {
        self.history.insert(0, entry);
        self.history.truncate(HISTORY_LEN);
    }

    /// Show history entry `k` as its scene's figure and put its parameters into the form.
    pub(crate) fn reopen(&mut self, k: usize) -> Vec<Effect> {
        let Some(entry) = self.history.get(k).cloned() else {
            return Vec::new();
        };
        if self.running.as_ref().is_some_and(|r| r.scene == entry.scene) {
            self.set_status("a run of this scene is in progress: Esc cancels it first", true);
            return Vec::new();
        }
        self.select_index(entry.scene);
        self.filter.clear();
        self.forms[entry.scene].load(entry.values.clone());
        self.on_results(entry.scene, &entry.figure);
        self.figures[entry.scene] = Some(FigureView {
            figure: entry.figure,
            values: entry.values,
            run_time_s: Some(entry.run_time_s),
            state: entry.state,
        });
        let id = self.scenes[entry.scene].info().id;
        self.set_status(
            format!("reopened a run of {id} from the history (not rerun)"),
            false,
        );
        self.convert_pins(entry.scene)
    }

    pub(crate) fn chart_action(&mut self, action: Action) {
        match action {
            Action::Pin => self.pin(),
            Action::Unpin | Action::UnpinAll => {
                let pins = &mut self.pins[self.selected];
                if pins.is_empty() {
                    self.set_status("no pinned run", false);
                    return;
                }
                if action == Action::Unpin {
                    pins.pop();
                } else {
                    pins.clear();
                }
                let n = pins.len();
                self.cursor = None;
                self.set_status(format!("{n} pinned run(s) left"), false);
            }
            Action::Cursor => {
                self.zoom_mark = None;
                self.cursor = match self.cursor {
                    Some(_) => None,
                    None => self.drawn().and_then(|d| first_point(&d)),
                };
                if self.cursor.is_none() && self.drawn().is_none() {
                    self.set_status("no chart yet: run the scene first (r)", false);
                }
            }
            Action::CursorPrev => self.move_cursor(-1),
            Action::CursorNext => self.move_cursor(1),
            Action::CursorPrevFast => self.move_cursor(-FAST_STEP),
            Action::CursorNextFast => self.move_cursor(FAST_STEP),
            Action::CursorCurve => self.next_curve(),
            Action::NextMarker => self.jump_marker(1),
            Action::PrevMarker => self.jump_marker(-1),
            Action::ZoomRect => self.zoom_rect(),
            Action::ZoomIn => self.zoom_by(0.5),
            Action::ZoomOut => self.zoom_by(2.0),
            Action::ZoomReset => {
                self.zoom = None;
                self.zoom_mark = None;
            }
            _ => {}
        }
    }

    fn pin(&mut self) {
        let k = self.selected;
        let Some(view) = self.figure(k) else {
            self.set_status("nothing to pin: run the scene first (r)", true);
            return;
        };
        if view.state != FigureState::Complete {
            self.set_status("only a finished run can be pinned", true);
            return;
        }
        let pin = Pin::new(
            view.figure.clone(),
            view.values.clone(),
            view.run_time_s.unwrap_or(0.0),
            pin_color(&view.figure, self.pins(k)),
        );
        self.pins[k].push(pin);
        let n = self.pins[k].len();
        self.set_status(
            format!("pinned as #{n}: change a parameter and run (r) to compare; u unpins"),
            false,
        );
    }

    /// Pinned runs of scene `scene` computed with other display parameters (units) than its
    /// shown run: each is recomputed with the shown run's, in the background (once).
    pub(crate) fn convert_pins(&mut self, scene: usize) -> Vec<Effect> {
        let Some(current) = self.figure(scene).map(|v| v.values.clone()) else {
            return Vec::new();
        };
        let mut effects = Vec::new();
        let scene_ref = SceneRef(self.scenes[scene]);
        for i in 0..self.pins(scene).len() {
            let pin = &self.pins[scene][i];
            let Some(values) = display_variant(&pin.values, &current) else {
                continue;
            };
            if pin.converting.is_some() || pin.converted.iter().any(|(v, _)| *v == values) {
                continue;
            }
            let job = self.next_job();
            self.pins[scene][i].converting = Some(job);
            effects.push(Effect::Task {
                job,
                task: Task::Convert {
                    scene: scene_ref,
                    values,
                },
            });
        }
        effects
    }

    /// A pinned run recomputed in other units arrives (or why it could not be).
    pub(crate) fn on_converted(&mut self, job: u64, outcome: Result<TaskDone, String>) {
        let Some((k, pin)) = self
            .pins
            .iter_mut()
            .enumerate()
            .find_map(|(k, ps)| ps.iter_mut().find(|p| p.converting == Some(job)).map(|p| (k, p)))
        else {
            return;
        };
        pin.converting = None;
        match outcome {
            Ok(TaskDone::Converted { values, figure }) => pin.converted.push((values, *figure)),
            Ok(_) => {}
            Err(e) => {
                let id = self.scenes[k].info().id;
                self.set_status(format!("a pinned run of {id} could not be converted: {e}"), true);
            }
        }
    }

    /// Show or hide pinned run `i` (from 0) of the selected scene.
    pub(crate) fn toggle_pin(&mut self, i: usize) {
        let Some(pin) = self.pins.get_mut(self.selected).and_then(|p| p.get_mut(i)) else {
            self.set_status(format!("no pinned run #{}", i + 1), false);
            return;
        };
        pin.hidden = !pin.hidden;
        let text = if pin.hidden { "hidden" } else { "shown" };
        self.cursor = None;
        self.set_status(format!("pinned run #{} {text}", i + 1), false);
    }

    fn move_cursor(&mut self, step: isize) {
        let Some(drawn) = self.drawn() else { return };
        let at = match self.cursor {
            Some(CursorAt::Point { series, index }) if series < drawn.panel.series.len() => {
                let n = drawn.panel.series[series].points.len();
                if n == 0 {
                    first_point(&drawn)
                } else {
                    let index = (index.min(n - 1) as isize + step).clamp(0, n as isize - 1) as usize;
                    Some(CursorAt::Point { series, index })
                }
            }
            Some(CursorAt::Marker(m)) => drawn
                .panel
                .markers
                .get(m)
                .and_then(|mk| nearest(&drawn, (mk.x, mk.y), self.zoom, false)),
            _ => first_point(&drawn),
        };
        self.cursor = at;
    }

    fn next_curve(&mut self) {
        let Some(drawn) = self.drawn() else { return };
        let from = self
            .cursor
            .and_then(|c| cursor_point(&drawn, c))
            .unwrap_or((f64::NAN, f64::NAN));
        let current = match self.cursor {
            Some(CursorAt::Point { series, .. }) => series,
            _ => drawn.panel.series.len() - 1,
        };
        let n = drawn.panel.series.len();
        for d in 1..=n {
            let s = (current + d) % n;
            let pts = &drawn.panel.series[s].points;
            if pts.is_empty() {
                continue;
            }
            let index = if from.0.is_finite() {
                nearest_in(pts, from, &drawn, self.zoom)
            } else {
                0
            };
            self.cursor = Some(CursorAt::Point { series: s, index });
            return;
        }
    }

    fn jump_marker(&mut self, step: isize) {
        let Some(drawn) = self.drawn() else { return };
        let n = drawn.panel.markers.len();
        if n == 0 {
            self.set_status("this panel has no markers", false);
            return;
        }
        let k = match self.cursor {
            Some(CursorAt::Marker(m)) => (m as isize + step).rem_euclid(n as isize) as usize,
            _ if step > 0 => 0,
            _ => n - 1,
        };
        self.cursor = Some(CursorAt::Marker(k));
    }

    fn zoom_rect(&mut self) {
        let Some(point) = self.readout().map(|r| r.point) else {
            self.cursor = self.drawn().and_then(|d| first_point(&d));
            if self.cursor.is_some() {
                self.set_status("move the cursor to a corner (, . ; m), then z", false);
            }
            return;
        };
        match self.zoom_mark.take() {
            None => {
                self.zoom_mark = Some(point);
                self.set_status(
                    "corner marked: move the cursor to the other corner, z zooms",
                    false,
                );
            }
            Some(a) => self.zoom_to((a, point)),
        }
    }

    /// Zoom to the rectangle between two points (data units); too thin a rectangle keeps the
    /// other axis' range.
    pub(crate) fn zoom_to(&mut self, (a, b): ((f64, f64), (f64, f64))) {
        let Some(drawn) = self.drawn() else { return };
        let Some(((x0, x1), (y0, y1))) = shown_range(&drawn.panel, self.zoom) else {
            return;
        };
        let span = |lo: f64, hi: f64, p: f64, q: f64, log: bool| {
            let (p, q) = (p.min(q), p.max(q));
            let thin = if log {
                (q / p).log10() < 1e-3 * (hi / lo).log10().abs()
            } else {
                q - p < 1e-3 * (hi - lo).abs()
            };
            if thin { (lo, hi) } else { (p, q) }
        };
        self.zoom = Some((
            span(x0, x1, a.0, b.0, drawn.panel.x.scale == Scale::Log),
            span(y0, y1, a.1, b.1, drawn.panel.y.scale == Scale::Log),
        ));
        self.zoom_mark = None;
        self.set_status("zoomed: 0 shows the whole panel", false);
    }

    fn zoom_by(&mut self, factor: f64) {
        let Some(drawn) = self.drawn() else { return };
        let Some(((x0, x1), (y0, y1))) = shown_range(&drawn.panel, self.zoom) else {
            return;
        };
        let centre = self
            .readout()
            .map(|r| r.point)
            .unwrap_or(((x0 + x1) / 2.0, (y0 + y1) / 2.0));
        self.zoom = Some((
            scale_about(x0, x1, centre.0, factor, drawn.panel.x.scale),
            scale_about(y0, y1, centre.1, factor, drawn.panel.y.scale),
        ));
    }

    /// Show scene `k` at the panel it showed last, with that panel's cursor and zoom.
    pub(crate) fn select_index(&mut self, k: usize) {
        if k != self.selected && k < self.scenes.len() {
            self.keep_view();
            self.selected = k;
            self.panel = self.last_panel.get(k).copied().unwrap_or(0);
            self.panel = self.panel();
            self.restore_view();
        }
    }

    /// Show panel `k` of the selected scene (clamped to its panels), with its cursor and zoom.
    pub(crate) fn show_panel(&mut self, k: usize) {
        let n = self
            .figure(self.selected)
            .map_or(1, |f| f.figure.panels.len().max(1));
        let k = k.min(n - 1);
        if k != self.panel() {
            self.keep_view();
            self.panel = k;
            self.restore_view();
        }
    }

    /// Keep the shown panel's cursor and zoom for when it is shown again.
    fn keep_view(&mut self) {
        let key = (self.selected, self.panel());
        if self.cursor.is_some() || self.zoom.is_some() {
            self.views.insert(
                key,
                PanelView {
                    cursor: self.cursor,
                    zoom: self.zoom,
                },
            );
        } else {
            self.views.remove(&key);
        }
        let panel = self.panel();
        if let Some(p) = self.last_panel.get_mut(self.selected) {
            *p = panel;
        }
    }

    /// The shown panel's kept cursor and zoom (none if it had none); a half-chosen zoom
    /// rectangle is dropped.
    fn restore_view(&mut self) {
        let view = self.views.get(&(self.selected, self.panel())).copied();
        self.cursor = view.and_then(|v| v.cursor);
        self.zoom = view.and_then(|v| v.zoom);
        self.zoom_mark = None;
        self.drag = None;
    }

    /// The name of the current run's marker under the cursor, kept when a run starts so that
    /// the cursor finds the marker of that name in its results.
    pub(crate) fn keep_marker(&mut self) {
        self.kept_marker = match self.cursor {
            Some(CursorAt::Marker(m)) => self
                .figure(self.selected)
                .and_then(|v| v.figure.panels.get(self.panel))
                .and_then(|p| p.markers.get(m))
                .map(|mk| mk.name.clone()),
            _ => None,
        };
    }

    /// Complete results of scene `scene` arrive: the cursor and zoom of every panel whose axes
    /// they change are reset (those of the others are kept).
    pub(crate) fn on_results(&mut self, scene: usize, figure: &Figure) {
        let new: Vec<AxesKey> = figure.panels.iter().map(AxesKey::of).collect();
        let Some(old) = self.axes.get_mut(scene) else {
            return;
        };
        let changed: Vec<usize> = (0..old.len().max(new.len()))
            .filter(|k| old.get(*k) != new.get(*k))
            .collect();
        *old = new;
        // A cursor on one of the current run's markers (the pull-off) stays on the marker of
        // the same name in the new results, wherever it moved: nudging a parameter then reads
        // how that marker moves.
        let on_marker = if scene == self.selected {
            self.kept_marker.take()
        } else {
            None
        };
        for k in changed {
            self.views.remove(&(scene, k));
            if scene == self.selected && k == self.panel {
                self.cursor = on_marker.as_ref().and_then(|name| {
                    let p = figure.panels.get(k)?;
                    p.markers
                        .iter()
                        .position(|m| m.name == *name)
                        .map(CursorAt::Marker)
                });
                self.zoom = None;
                self.zoom_mark = None;
                self.drag = None;
            }
        }
    }

    pub(super) fn zoom_about(&mut self, at: Option<(f64, f64)>, factor: f64) {
        let Some(drawn) = self.drawn() else { return };
        let (Some(p), Some(((x0, x1), (y0, y1)))) = (at, shown_range(&drawn.panel, self.zoom)) else {
            return;
        };
        self.zoom = Some((
            scale_about(x0, x1, p.0, factor, drawn.panel.x.scale),
            scale_about(y0, y1, p.1, factor, drawn.panel.y.scale),
        ));
    }
}
