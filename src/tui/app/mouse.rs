//! The mouse, where the terminal reports it: click a scene, a parameter, a panel tab or a point,
//! drag a zoom rectangle, scroll the lists and zoom the chart with the wheel, and choose runs in
//! the history. What lies under the pointer comes from the layout of the last drawn frame
//! ([`DrawnLayout`]), never from the drawing code.

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

use super::{App, Effect, Focus, ListRow, Mode};
use crate::tui::chart::nearest;
use crate::tui::layout::{DrawnLayout, Target, hit};

impl App {
    /// Handle a mouse event (where the terminal reports them); returns what the session must
    /// do.
    pub fn on_mouse(&mut self, ev: MouseEvent) -> Vec<Effect> {
        let layout = self.layout.borrow().clone();
        let (column, row) = (ev.column, ev.row);
        match self.mode {
            Mode::Normal | Mode::Filter { .. } => {}
            Mode::Help => {
                match ev.kind {
                    MouseEventKind::Down(_) => self.mode = Mode::Normal,
                    MouseEventKind::ScrollDown => self.help_scroll = self.help_scroll.saturating_add(1),
                    MouseEventKind::ScrollUp => self.help_scroll = self.help_scroll.saturating_sub(1),
                    _ => {}
                }
                return Vec::new();
            }
            Mode::History { .. } => return self.history_mouse(ev, &layout),
            Mode::Prompt { .. } => return Vec::new(),
        }
        if ev.kind == MouseEventKind::Down(MouseButton::Left) && hit(layout.tabs, column, row) {
            if let Some(Target::Tab(k)) = layout.target_at(column, row) {
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
                    let rows = self.list_rows();
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
                    match layout.target_at(column, row) {
                        Some(Target::Key(code)) => self.update(key(code)),
                        _ => Vec::new(),
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
}
