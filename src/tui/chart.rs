//! The chart as an instrument: pinned runs drawn over the current one, a cursor that moves
//! along the data and jumps between markers, zoom into a rectangle and back, the run history,
//! and the mouse (click a scene, a parameter or a point, drag a zoom rectangle, scroll).
//!
//! Everything here is state: the view draws it, the session carries out the effects.

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use ratatui::layout::Rect;

use super::app::{App, Effect, FigureState, FigureView, Focus, Mode};
use super::compare::{Overlay, Pin, overlay, pin_color, pin_label};
use super::keymap::Action;
use super::view::{ListRow, footer_at, scene_rows, tab_at};
use crate::figure::{Figure, Panel, Scale};
use crate::params::ParamValues;
use crate::render::labels::fmt_quantity;
use crate::render::terminal::{ChartGeometry, View, shown_range};
use crate::render::text::terminal;

/// Runs the history keeps.
pub const HISTORY_LEN: usize = 20;
/// Longest legend label of a pinned run, in characters.
pub const PIN_LABEL_WIDTH: usize = 36;
/// Points the fast cursor keys skip.
const FAST_STEP: isize = 20;

/// Where the cursor is on the drawn (overlaid) panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CursorAt {
    /// Point `index` of series `series`.
    Point {
        /// Series index in the drawn panel.
        series: usize,
        /// Point index.
        index: usize,
    },
    /// Marker `k` of the drawn panel.
    Marker(usize),
}

/// What the cursor shows: the point, which curve or marker, and x and y with units.
#[derive(Debug, Clone, PartialEq)]
pub struct Readout {
    /// The point in data units.
    pub point: (f64, f64),
    /// Curve or marker name (with the pinned run it belongs to).
    pub name: String,
    /// `label = value unit` of x.
    pub x: String,
    /// `label = value unit` of y.
    pub y: String,
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
}

/// The cursor and the zoom of one panel, kept while the shown scene or panel changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelView {
    /// The cursor.
    pub cursor: Option<CursorAt>,
    /// The shown range.
    pub zoom: Option<View>,
}

/// What a panel's cursor and zoom refer to: its axes (label, unit, scale) and the range the
/// whole panel shows. New results that change it reset the panel's cursor and zoom.
#[derive(Debug, Clone, PartialEq)]
pub struct AxesKey {
    /// Label, unit and scale of x.
    pub x: (String, String, Scale),
    /// Label, unit and scale of y.
    pub y: (String, String, Scale),
    /// The whole panel's range in data units.
    pub range: Option<View>,
}

impl AxesKey {
    /// The key of `panel`.
    pub fn of(panel: &Panel) -> Self {
        let axis = |a: &crate::figure::Axis| (a.label.clone(), a.unit.clone(), a.scale);
        Self {
            x: axis(&panel.x),
            y: axis(&panel.y),
            range: shown_range(panel, None),
        }
    }
}

/// Where the last frame put the parts the mouse can hit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DrawnLayout {
    /// Inside of the scene list.
    pub list: Rect,
    /// First list row shown.
    pub list_offset: usize,
    /// The parameter rows.
    pub form: Rect,
    /// First parameter shown.
    pub form_offset: usize,
    /// The area the chart (axes included) was drawn into.
    pub chart_area: Rect,
    /// The chart's graph, if a chart was drawn.
    pub chart: Option<ChartGeometry>,
    /// The line of panel tabs (empty when the figure has one panel).
    pub tabs: Rect,
    /// The history overlay (its border included).
    pub overlay: Rect,
    /// The history overlay's rows of runs.
    pub history: Rect,
    /// First history entry shown.
    pub history_offset: usize,
    /// The history overlay's footer line (its actions).
    pub history_footer: Rect,
}

fn hit(r: Rect, column: u16, row: u16) -> bool {
    (r.x..r.right()).contains(&column) && (r.y..r.bottom()).contains(&row)
}

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
        Some(overlay(panel, k, self.pins(self.selected), &self.pin_labels()).with_legend_symbols())
    }

    /// Where the last frame drew the chart's graph and what it shows.
    pub fn chart_geometry(&self) -> Option<ChartGeometry> {
        self.layout.get().chart
    }

    /// The area the last frame drew the chart into (axes and labels included).
    pub fn chart_area(&self) -> Rect {
        self.layout.get().chart_area
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

    pub(crate) fn remember(&mut self, scene: usize, figure: &Figure, values: &ParamValues, run_time_s: f64) {
        self.history.insert(
            0,
            HistoryEntry {
                scene,
                figure: figure.clone(),
                values: values.clone(),
                run_time_s,
            },
        );
        self.history.truncate(HISTORY_LEN);
    }

    /// Show history entry `k` as its scene's figure and put its parameters into the form.
    pub(crate) fn reopen(&mut self, k: usize) {
        let Some(entry) = self.history.get(k).cloned() else {
            return;
        };
        if self.running.as_ref().is_some_and(|r| r.scene == entry.scene) {
            self.set_status("a run of this scene is in progress: Esc cancels it first", true);
            return;
        }
        self.select_index(entry.scene);
        self.filter.clear();
        self.forms[entry.scene].load(entry.values.clone());
        self.on_results(entry.scene, &entry.figure);
        self.figures[entry.scene] = Some(FigureView {
            figure: entry.figure,
            values: entry.values,
            run_time_s: Some(entry.run_time_s),
            state: FigureState::Complete,
        });
        let id = self.scenes[entry.scene].info().id;
        self.set_status(
            format!("reopened a run of {id} from the history (not rerun)"),
            false,
        );
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
        let pin = Pin {
            color: pin_color(&view.figure, self.pins(k)),
            figure: view.figure.clone(),
            values: view.values.clone(),
            run_time_s: view.run_time_s.unwrap_or(0.0),
        };
        self.pins[k].push(pin);
        let n = self.pins[k].len();
        self.set_status(
            format!("pinned as #{n}: change a parameter and run (r) to compare; u unpins"),
            false,
        );
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

    /// Handle a mouse event (where the terminal reports them); returns what the session must
    /// do.
    pub fn on_mouse(&mut self, ev: MouseEvent) -> Vec<Effect> {
        let layout = self.layout.get();
        let (column, row) = (ev.column, ev.row);
        match self.mode {
            Mode::Normal | Mode::Filter { .. } => {}
            Mode::Help => {
                if matches!(ev.kind, MouseEventKind::Down(_)) {
                    self.mode = Mode::Normal;
                }
                return Vec::new();
            }
            Mode::History { .. } => return self.history_mouse(ev, &layout),
            Mode::Prompt { .. } => return Vec::new(),
        }
        if ev.kind == MouseEventKind::Down(MouseButton::Left) && hit(layout.tabs, column, row) {
            if let Some(k) = self
                .figure(self.selected)
                .and_then(|v| tab_at(v, layout.tabs.x, column))
            {
                self.show_panel(k);
            }
            return Vec::new();
        }
        let in_list = hit(layout.list, column, row);
        let in_form = hit(layout.form, column, row);
        let at_chart = layout.chart.and_then(|g| g.to_data(column, row));
        match ev.kind {
            MouseEventKind::ScrollUp | MouseEventKind::ScrollDown => {
                let step = if ev.kind == MouseEventKind::ScrollUp {
                    -1
                } else {
                    1
                };
                if in_list {
                    self.act_scroll(Focus::Scenes, step);
                } else if in_form {
                    self.act_scroll(Focus::Form, step);
                } else if at_chart.is_some() {
                    // Scrolling over the chart zooms about the pointer, as in most plot windows.
                    let factor = if step < 0 { 0.8 } else { 1.25 };
                    self.zoom_about(at_chart, factor);
                }
            }
            MouseEventKind::Down(MouseButton::Left) => {
                if in_list {
                    let rows = scene_rows(self);
                    let k = usize::from(row - layout.list.y) + layout.list_offset;
                    if let Some(ListRow::Scene(scene)) = rows.get(k) {
                        self.focus = Focus::Scenes;
                        self.select_index(*scene);
                    }
                } else if in_form {
                    let k = usize::from(row - layout.form.y) + layout.form_offset;
                    if let Some(form) = self.forms.get_mut(self.selected)
                        && k < form.len()
                    {
                        self.focus = Focus::Form;
                        let step = k as isize - form.selected() as isize;
                        if step != 0 {
                            form.move_selection(step);
                        }
                    }
                } else if let Some(p) = at_chart
                    && let Some(drawn) = self.drawn()
                {
                    self.cursor = nearest(&drawn, p, self.zoom, true);
                    self.drag = Some((p, p));
                }
            }
            MouseEventKind::Drag(MouseButton::Left) => {
                if let (Some((a, _)), Some(p)) = (self.drag, at_chart) {
                    self.drag = Some((a, p));
                }
            }
            MouseEventKind::Up(MouseButton::Left) => {
                if let Some((a, b)) = self.drag.take()
                    && let Some(g) = layout.chart
                {
                    let (fa, fb) = (g.fraction(a), g.fraction(b));
                    let cells = (
                        (fa.0 - fb.0).abs() * f64::from(g.graph.width),
                        (fa.1 - fb.1).abs() * f64::from(g.graph.height),
                    );
                    if cells.0 >= 2.0 || cells.1 >= 2.0 {
                        self.zoom_to((a, b));
                    }
                }
            }
            MouseEventKind::Down(MouseButton::Right) if at_chart.is_some() => {
                self.zoom = None;
                self.zoom_mark = None;
            }
            _ => {}
        }
        Vec::new()
    }

    /// The mouse over the history overlay: a click chooses a run, a click on the chosen run
    /// reopens it, the wheel moves the choice, the footer's actions act as their keys, a click
    /// outside closes the overlay.
    fn history_mouse(&mut self, ev: MouseEvent, layout: &DrawnLayout) -> Vec<Effect> {
        let (column, row) = (ev.column, ev.row);
        let key = |code: KeyCode| KeyEvent::new(code, KeyModifiers::NONE);
        match ev.kind {
            MouseEventKind::ScrollUp => self.update(key(KeyCode::Up)),
            MouseEventKind::ScrollDown => self.update(key(KeyCode::Down)),
            MouseEventKind::Down(MouseButton::Left) => {
                if hit(layout.history, column, row) {
                    let k = usize::from(row - layout.history.y) + layout.history_offset;
                    let Mode::History { selected } = &mut self.mode else {
                        return Vec::new();
                    };
                    if k >= self.history.len() {
                        return Vec::new();
                    }
                    if *selected == k {
                        return self.update(key(KeyCode::Enter));
                    }
                    *selected = k;
                    Vec::new()
                } else if hit(layout.history_footer, column, row) {
                    match footer_at(layout.history_footer.x, column) {
                        Some(code) => self.update(key(code)),
                        None => Vec::new(),
                    }
                } else if !hit(layout.overlay, column, row) {
                    self.mode = Mode::Normal;
                    Vec::new()
                } else {
                    Vec::new()
                }
            }
            _ => Vec::new(),
        }
    }

    fn act_scroll(&mut self, focus: Focus, step: isize) {
        match focus {
            Focus::Scenes => {
                let visible = self.visible_scenes();
                if let Some(i) = visible.iter().position(|&k| k == self.selected) {
                    let j = (i as isize + step).clamp(0, visible.len() as isize - 1) as usize;
                    self.select_index(visible[j]);
                }
            }
            Focus::Form => {
                if let Some(form) = self.forms.get_mut(self.selected) {
                    form.move_selection(step);
                }
            }
        }
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
        for k in changed {
            self.views.remove(&(scene, k));
            if scene == self.selected && k == self.panel {
                self.cursor = None;
                self.zoom = None;
                self.zoom_mark = None;
                self.drag = None;
            }
        }
    }

    fn zoom_about(&mut self, at: Option<(f64, f64)>, factor: f64) {
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

/// `[lo, hi]` scaled by `factor` about `c` (in log10 on a log axis).
fn scale_about(lo: f64, hi: f64, c: f64, factor: f64, scale: Scale) -> (f64, f64) {
    match scale {
        Scale::Linear => (c + (lo - c) * factor, c + (hi - c) * factor),
        Scale::Log => {
            let (l, h, c) = (lo.log10(), hi.log10(), c.max(f64::MIN_POSITIVE).log10());
            (10f64.powf(c + (l - c) * factor), 10f64.powf(c + (h - c) * factor))
        }
    }
}

/// The middle point of the first curve with points.
fn first_point(drawn: &Overlay) -> Option<CursorAt> {
    drawn
        .panel
        .series
        .iter()
        .position(|s| !s.points.is_empty())
        .map(|series| CursorAt::Point {
            series,
            index: drawn.panel.series[series].points.len() / 2,
        })
}

/// Distance between two data points in fractions of the shown range (log10 on log axes).
fn distance(drawn: &Overlay, view: Option<View>, a: (f64, f64), b: (f64, f64)) -> f64 {
    let Some(((x0, x1), (y0, y1))) = shown_range(&drawn.panel, view) else {
        return f64::INFINITY;
    };
    let d = |p: f64, q: f64, lo: f64, hi: f64, log: bool| {
        if log {
            (p.log10() - q.log10()) / (hi.log10() - lo.log10())
        } else {
            (p - q) / (hi - lo)
        }
    };
    let dx = d(a.0, b.0, x0, x1, drawn.panel.x.scale == Scale::Log);
    let dy = d(a.1, b.1, y0, y1, drawn.panel.y.scale == Scale::Log);
    let r = dx.hypot(dy);
    if r.is_nan() { f64::INFINITY } else { r }
}

fn nearest_in(points: &[(f64, f64)], p: (f64, f64), drawn: &Overlay, view: Option<View>) -> usize {
    points
        .iter()
        .enumerate()
        .map(|(i, q)| (i, distance(drawn, view, *q, p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(i, _)| i)
}

/// The drawn point nearest to `p`; markers count too when `markers` (a click on a marker
/// selects it).
fn nearest(drawn: &Overlay, p: (f64, f64), view: Option<View>, markers: bool) -> Option<CursorAt> {
    let mut best: Option<(CursorAt, f64)> = None;
    for (s, series) in drawn.panel.series.iter().enumerate() {
        for (i, q) in series.points.iter().enumerate() {
            let d = distance(drawn, view, *q, p);
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((CursorAt::Point { series: s, index: i }, d));
            }
        }
    }
    if markers {
        for (k, m) in drawn.panel.markers.iter().enumerate() {
            // A marker wins a near tie: it is what a click near it means.
            let d = distance(drawn, view, (m.x, m.y), p) * 0.5;
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((CursorAt::Marker(k), d));
            }
        }
    }
    best.map(|(c, _)| c)
}

fn cursor_point(drawn: &Overlay, at: CursorAt) -> Option<(f64, f64)> {
    match at {
        CursorAt::Point { series, index } => drawn.panel.series.get(series)?.points.get(index).copied(),
        CursorAt::Marker(k) => drawn.panel.markers.get(k).map(|m| (m.x, m.y)),
    }
}

/// The readout of the cursor at `at` on `drawn` (a pinned run's curves and markers are named
/// after the run).
pub fn readout(drawn: &Overlay, at: CursorAt) -> Option<Readout> {
    let point = cursor_point(drawn, at)?;
    let name = match at {
        CursorAt::Point { series, .. } => terminal(&drawn.panel.series[series].name),
        CursorAt::Marker(k) => {
            let m = &drawn.panel.markers[k];
            let name = terminal(&m.name);
            m.label.as_ref().map_or(name.clone(), |l| format!("{name} ({l})"))
        }
    };
    let axis =
        |a: &crate::figure::Axis, v: f64| format!("{} = {}", terminal(&a.label), fmt_quantity(v, &a.unit));
    Some(Readout {
        point,
        name,
        x: axis(&drawn.panel.x, point.0),
        y: axis(&drawn.panel.y, point.1),
    })
}

/// Labels of the history entries for the list: scene, run time, the parameters that differ
/// from the scene's defaults.
pub fn history_line(app: &App, entry: &HistoryEntry) -> String {
    let scene = app.scenes[entry.scene];
    let diff = super::compare::difference(&entry.values, &scene.defaults());
    let diff = if diff == "same parameters" {
        "defaults".to_string()
    } else {
        diff
    };
    format!(
        "{:<16} {:>8}  {diff}",
        scene.info().id,
        super::app::fmt_duration(entry.run_time_s)
    )
}
