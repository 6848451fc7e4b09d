//! Drawing the [`App`] state into any ratatui backend: the scene list by chapter, the parameter
//! form (invalid fields in red with their error), the figure as a braille chart
//! ([`crate::render::terminal::render_panel`]) with panel tabs, the progress gauge, the status
//! bar, and the help and path-prompt overlays.
//!
//! Drawing only reads the state. Where it put the parts the mouse can hit comes back from
//! [`draw`] as a [`DrawnLayout`], plain data the state keeps for the next mouse event.

use ratatui::Frame;
use ratatui::crossterm::event::KeyCode;
use ratatui::layout::{Constraint, Layout, Position, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Gauge, Paragraph, Wrap};

use super::app::{
    App, FigureState, FigureView, Focus, HistoryEntry, ListRow, Mode, Page, PromptKind, fmt_duration,
};
use super::compare::{Overlay, Owner, difference};
use super::curves::{FilePage, model_name, raw_panel, segment_name};
use super::keymap::BINDINGS;
use super::layout::{DrawnLayout, Target};
use crate::params::{ParamKind, fmt_float};
use crate::render::labels::{fmt_quantity, result_unit};
use crate::render::terminal::{
    ChartGeometry, ChartOptions, REGION_SYMBOL, color as chart_color, marker_symbol, render_chart,
};
use crate::scenes::chapter_title;

const ACCENT: Color = Color::Cyan;
const ERROR: Color = Color::LightRed;

/// Draw the whole UI; returns where the parts the mouse can hit were put.
pub fn draw(frame: &mut Frame<'_>, app: &App) -> DrawnLayout {
    let mut layout = DrawnLayout::default();
    let [main, status] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(frame.area());
    match app.page() {
        Page::Scenes => draw_scenes_page(frame, app, main, &mut layout),
        Page::File => match app.file_page() {
            Some(page) => draw_file_page(frame, page, main),
            None => draw_scenes_page(frame, app, main, &mut layout),
        },
    }
    draw_status(frame, app, status);
    draw_overlays(frame, app, main, &mut layout);
    layout
}

/// The scenes page: the scene list and the parameter form on the left, the figure on the right.
fn draw_scenes_page(frame: &mut Frame<'_>, app: &App, main: Rect, layout: &mut DrawnLayout) {
    let left_width = (main.width * 2 / 5).clamp(30, 52).min(main.width);
    let [left, right] = Layout::horizontal([Constraint::Length(left_width), Constraint::Min(0)]).areas(main);
    let entries = app.list_rows().len().max(1);
    let list_height = (entries as u16 + 2).min(left.height / 2).max(3);
    let [list_area, form_area] =
        Layout::vertical([Constraint::Length(list_height), Constraint::Min(0)]).areas(left);
    draw_scene_list(frame, app, list_area, layout);
    draw_form(frame, app, form_area, layout);
    draw_figure(frame, app, right, layout);
}

/// The page of a measured force-curve file: the file and the fit settings, the map's grid of
/// curves and the chosen curve's fit on the left; its data, fit and residuals on the right (the
/// curve as recorded until it is fitted).
fn draw_file_page(frame: &mut Frame<'_>, page: &FilePage, main: Rect) {
    let left_width = (main.width * 2 / 5).clamp(30, 52).min(main.width);
    let [left, right] = Layout::horizontal([Constraint::Length(left_width), Constraint::Min(0)]).areas(main);
    let [info_area, grid_area, fit_area] = Layout::vertical([
        Constraint::Length(7.min(left.height)),
        Constraint::Percentage(45),
        Constraint::Min(0),
    ])
    .areas(left);
    let name = page
        .path
        .file_name()
        .map_or(page.path.display().to_string(), |n| {
            n.to_string_lossy().into_owned()
        });
    let block = pane(" Force-curve file (o opens, g scenes) ".into(), false);
    let inner = block.inner(info_area);
    frame.render_widget(block, info_area);
    let k = page
        .curve()
        .and_then(|c| c.meta.spring_constant)
        .map_or("none in the file".to_string(), |k| fmt_quantity(k, "N/m"));
    let info = vec![
        Line::styled(name, Style::default().add_modifier(Modifier::BOLD)),
        Line::from(format!(
            "{} · {} curve(s) · k = {k}",
            page.file.format,
            page.file.curves.len()
        )),
        Line::from(page.settings_text()),
    ];
    frame.render_widget(Paragraph::new(info).wrap(Wrap { trim: true }), inner);
    draw_grid(frame, page, grid_area);
    draw_fit_results(frame, page, fit_area);
    let index = page.curve().map_or(0, |c| c.index);
    let fitted = page.fits.get(&page.selected).and_then(|f| f.as_ref().ok());
    let state = match (&page.fitting, page.fits.get(&page.selected)) {
        (Some(f), _) if f.curve == page.selected => " · fitting…",
        (_, Some(Ok(_))) => " · data, fit and residuals",
        (_, Some(Err(_))) => " · not fitted (see the message)",
        _ => " · as recorded (r fits)",
    };
    let block = pane(format!(" Curve {index}{state} "), false);
    let inner = block.inner(right);
    frame.render_widget(block, right);
    let options = ChartOptions::default();
    match fitted {
        Some(f) if f.figure.panels.len() >= 2 => {
            let [top, bottom] =
                Layout::vertical([Constraint::Percentage(64), Constraint::Percentage(36)]).areas(inner);
            for (panel, area) in f.figure.panels.iter().zip([top, bottom]) {
                let [title, chart] =
                    Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(area);
                frame.render_widget(
                    Line::styled(
                        format!("{} {}", panel.label, crate::render::text::terminal(&panel.title)),
                        Style::default().fg(Color::Yellow),
                    ),
                    title,
                );
                render_chart(panel, &options, chart, frame.buffer_mut());
            }
        }
        Some(f) => {
            if let Some(panel) = f.figure.panels.first() {
                render_chart(panel, &options, inner, frame.buffer_mut());
            }
        }
        None => {
            if let Some(curve) = page.curve() {
                render_chart(&raw_panel(curve), &options, inner, frame.buffer_mut());
            }
        }
    }
}

/// The map's grid, y up: `●` fitted, `✗` failed, `·` not fitted yet, the chosen curve
/// highlighted; a window around it when the grid is larger than the area.
fn draw_grid(frame: &mut Frame<'_>, page: &FilePage, area: Rect) {
    let [nx, ny] = page.grid.shape;
    let n = page.file.curves.len();
    let block = pane(format!(" Map {nx} × {ny}, {n} curve(s) — arrows choose "), true);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    if inner.width < 2 || inner.height == 0 || nx == 0 || ny == 0 {
        return;
    }
    let Some(&[si, sj]) = page.grid.cells.get(page.selected) else {
        return;
    };
    // Two columns a cell; the window keeps the chosen cell inside, near its middle.
    let cols = (usize::from(inner.width) / 2).clamp(1, nx);
    let rows = usize::from(inner.height).min(ny);
    let x0 = si.saturating_sub(cols / 2).min(nx - cols);
    let top = ny - 1 - sj;
    let y0 = top.saturating_sub(rows / 2).min(ny - rows);
    let mut lines = Vec::new();
    for r in y0..y0 + rows {
        let j = ny - 1 - r;
        let mut spans = Vec::new();
        for i in x0..x0 + cols {
            let (glyph, mut style) = match page.curve_at([i, j]) {
                None => ("  ", Style::default()),
                Some(k) => match page.fits.get(&k) {
                    Some(Ok(_)) => ("● ", Style::default().fg(Color::Green)),
                    Some(Err(_)) => ("✗ ", Style::default().fg(ERROR)),
                    None => ("· ", Style::default().fg(Color::Gray)),
                },
            };
            if [i, j] == [si, sj] {
                style = style.bg(Color::Blue).fg(Color::White);
            }
            spans.push(Span::styled(glyph, style));
        }
        lines.push(Line::from(spans));
    }
    frame.render_widget(Paragraph::new(lines), inner);
}

/// The chosen curve's fit: values with standard errors, the measured pull-off, the residual,
/// the warnings; or why it was not fitted.
fn draw_fit_results(frame: &mut Frame<'_>, page: &FilePage, area: Rect) {
    let index = page.curve().map_or(0, |c| c.index);
    let block = pane(
        format!(
            " Fit of curve {index} ({} of {}) ",
            page.selected + 1,
            page.file.curves.len()
        ),
        false,
    );
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let dim = Style::default().fg(Color::DarkGray);
    let lines: Vec<Line<'_>> = match page.fits.get(&page.selected) {
        None if page.radius.is_none() => vec![Line::styled("t sets the tip radius, then r fits", dim)],
        None => vec![Line::styled("not fitted yet: r fits", dim)],
        Some(Err(e)) => vec![Line::styled(e.clone(), Style::default().fg(ERROR))],
        Some(Ok(f)) => {
            let r = &f.fit.fit;
            let est = |e: &crate::fit::Estimate, unit: &str| {
                format!(
                    "{} ± {}",
                    fmt_quantity(e.value, unit),
                    fmt_quantity(e.std_error, unit)
                )
            };
            let mut rows = vec![
                format!(
                    "{} fit of the {}",
                    model_name(Some(r.model)),
                    segment_name(Some(r.segment))
                ),
                format!("ℰ    {}", est(&r.plane_strain_modulus_pa, "Pa")),
            ];
            if let Some(w) = &r.work_of_adhesion_j_per_m2 {
                rows.push(format!("w    {}", est(w, "J/m²")));
            }
            rows.push(format!("d_c  {}", est(&r.contact_point_m, "m")));
            rows.push(format!("F₀   {}", est(&r.baseline_n, "N")));
            rows.push(format!(
                "pull-off (measured) {}",
                fmt_quantity(r.measured_pull_off_force_n, "N")
            ));
            rows.push(format!(
                "rms residual {} · {} of {} rows",
                fmt_quantity(r.rms_residual_n, "N"),
                r.points_used,
                r.points_total
            ));
            rows.push(format!("fitted in {}", fmt_duration(f.run_time_s)));
            let mut lines: Vec<Line<'_>> = rows.into_iter().map(Line::from).collect();
            for w in &r.warnings {
                lines.push(Line::styled(
                    format!("warning: {w}"),
                    Style::default().fg(Color::Yellow),
                ));
            }
            lines
        }
    };
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), inner);
}

/// The modal overlays over `main`: help, history, a path prompt.
fn draw_overlays(frame: &mut Frame<'_>, app: &App, main: Rect, layout: &mut DrawnLayout) {
    match &app.mode {
        Mode::Normal | Mode::Filter { .. } => {}
        Mode::Help => draw_help(frame, app, main),
        Mode::History { selected } => draw_history(frame, app, *selected, main, layout),
        Mode::Prompt { kind, edit } => {
            let area = Rect {
                x: main.x,
                y: main.bottom().saturating_sub(3),
                width: main.width,
                height: 3.min(main.height),
            };
            let title = match kind {
                PromptKind::LoadPreset => " Load preset (TOML) — Enter loads, Esc cancels ",
                PromptKind::SavePreset => " Save preset (TOML) — Enter saves, Esc cancels ",
                PromptKind::OpenFile => " Open a force-curve file — Enter opens, Esc cancels ",
                PromptKind::TipRadius => " Tip radius in metres (e.g. 2e-6) — Enter sets, Esc cancels ",
            };
            frame.render_widget(Clear, area);
            let block = Block::bordered()
                .title(title)
                .border_style(Style::default().fg(ACCENT));
            let inner = block.inner(area);
            frame.render_widget(Paragraph::new(edit.text()).block(block), area);
            let x = inner.x + (edit.cursor() as u16).min(inner.width.saturating_sub(1));
            frame.set_cursor_position(Position::new(x, inner.y));
        }
    }
}

fn pane(title: String, focused: bool) -> Block<'static> {
    let style = if focused {
        Style::default().fg(ACCENT)
    } else {
        Style::default().fg(Color::DarkGray)
    };
    Block::bordered().title(title).border_style(style)
}

/// First row shown in a list of `height` rows so that row `selected` is visible.
pub fn scroll_offset(selected: usize, height: usize) -> usize {
    (selected + 1).saturating_sub(height.max(1))
}

/// Cut `text` to `width` characters, ending in `…` when cut.
fn clip(text: &str, width: usize) -> String {
    if text.chars().count() <= width {
        text.to_string()
    } else if width == 0 {
        String::new()
    } else {
        let mut s: String = text.chars().take(width - 1).collect();
        s.push('…');
        s
    }
}

fn draw_scene_list(frame: &mut Frame<'_>, app: &App, area: Rect, layout: &mut DrawnLayout) {
    let filtering = matches!(app.mode, Mode::Filter { .. });
    let focused = app.focus == Focus::Scenes && (app.mode == Mode::Normal || filtering);
    let title = if app.filter.is_empty() && !filtering {
        " Scenes (/ filters) ".to_string()
    } else {
        let n = app.visible_scenes().len();
        format!(" Scenes /{} — {n} of {} ", app.filter, app.scenes.len())
    };
    let block = pane(title, focused);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    if let Mode::Filter { edit } = &app.mode {
        // The typed filter sits in the title, after " Scenes /".
        let x = area.x + 9 + edit.cursor() as u16;
        if x < area.right() {
            frame.set_cursor_position(Position::new(x, area.y));
        }
    }
    if inner.height == 0 || inner.width == 0 {
        return;
    }
    let rows = app.list_rows();
    if rows.is_empty() {
        frame.render_widget(
            Line::styled(
                "no scene matches the filter (Esc clears)",
                Style::default().fg(Color::DarkGray),
            ),
            inner,
        );
        return;
    }
    let id_width = rows
        .iter()
        .filter_map(|r| match r {
            ListRow::Scene(k) => Some(app.scenes[*k].info().id.chars().count()),
            ListRow::Chapter(_) => None,
        })
        .max()
        .unwrap_or(0);
    let width = inner.width as usize;
    let selected_row = rows
        .iter()
        .position(|r| *r == ListRow::Scene(app.selected))
        .unwrap_or(0);
    let offset = scroll_offset(selected_row, inner.height as usize);
    layout.list = inner;
    layout.list_offset = offset;
    let highlight = if focused {
        Style::default().bg(Color::Blue).fg(Color::White)
    } else {
        Style::default().add_modifier(Modifier::REVERSED)
    };
    let mut lines = Vec::new();
    for (i, row) in rows.iter().enumerate().skip(offset).take(inner.height as usize) {
        let line = match *row {
            ListRow::Chapter(chapter) => Line::styled(
                clip(&format!("{chapter} {}", chapter_title(chapter)), width),
                Style::default().fg(Color::Yellow).add_modifier(Modifier::BOLD),
            ),
            ListRow::Scene(k) => {
                let info = app.scenes[k].info();
                let running = app.running.as_ref().is_some_and(|r| r.scene == k);
                let mark = if running { "▶" } else { " " };
                // Two columns: the id padded to the longest id shown, a gap, the title cut to
                // what is left.
                let id = clip(info.id, width.saturating_sub(2));
                let title_width = width.saturating_sub(2 + id_width + 2);
                let mut spans = vec![
                    Span::raw(format!(" {mark}")),
                    Span::styled(
                        format!("{id:<id_width$}"),
                        Style::default().add_modifier(Modifier::BOLD),
                    ),
                ];
                if title_width > 0 {
                    spans.push(Span::raw(format!("  {}", clip(info.title, title_width))));
                }
                let mut line = Line::from(spans);
                if i == selected_row {
                    line = line.style(highlight);
                }
                line
            }
        };
        lines.push(line);
    }
    frame.render_widget(Paragraph::new(lines), inner);
}

fn draw_form(frame: &mut Frame<'_>, app: &App, area: Rect, layout: &mut DrawnLayout) {
    let Some(form) = app.form() else {
        frame.render_widget(pane(" Parameters ".into(), false), area);
        return;
    };
    let focused = app.focus == Focus::Form;
    let verdict = if form.is_valid() { "valid" } else { "INVALID" };
    let auto = if app.auto_run { " · auto-run" } else { "" };
    let title = format!(" Parameters of {} — {verdict}{auto} ", form.scene().info().id);
    let block = pane(title, focused);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    if inner.height == 0 || inner.width == 0 {
        return;
    }
    let help_height = 3.min(inner.height.saturating_sub(1));
    let [rows_area, help_area] =
        Layout::vertical([Constraint::Min(0), Constraint::Length(help_height)]).areas(inner);

    let visible = rows_area.height as usize;
    let offset = scroll_offset(form.selected(), visible);
    let (name_width, value_width, unit_width) = form_columns(form, offset, visible, inner.width as usize);
    layout.form = rows_area;
    layout.form_offset = offset;
    let mut lines = Vec::new();
    for k in offset..form.len().min(offset + visible) {
        let spec = &form.specs()[k];
        let text = form.text(k);
        // A value is never cut from the left (its exponent or its end is what differs): the
        // columns leave it room, and only a value longer than the whole row is cut, at the end.
        let shown = clip(text, value_width);
        let mut style = Style::default();
        if form.error(k).is_some() {
            style = style.fg(ERROR).add_modifier(Modifier::BOLD);
        }
        if k == form.selected() {
            style = if focused {
                style.bg(Color::Blue).fg(if form.error(k).is_some() {
                    ERROR
                } else {
                    Color::White
                })
            } else {
                style.add_modifier(Modifier::REVERSED)
            };
        }
        let marker = if form.error(k).is_some() {
            "✗"
        } else if form.is_changed(k) {
            "*"
        } else {
            " "
        };
        lines.push(Line::styled(
            format!(
                "{marker}{:<name_width$} {shown:<value_width$} {}",
                clip(spec.name, name_width),
                clip(spec.unit, unit_width),
                name_width = name_width,
                value_width = value_width
            ),
            style,
        ));
        if k == form.selected()
            && let Some(edit) = form.editor()
        {
            let col = (1 + name_width + 1 + edit.cursor()) as u16;
            let x = rows_area.x + col.min(rows_area.width.saturating_sub(1));
            frame.set_cursor_position(Position::new(x, rows_area.y + (k - offset) as u16));
        }
    }
    frame.render_widget(Paragraph::new(lines), rows_area);

    let k = form.selected();
    let help = match (form.error(k), form.cross_error()) {
        (Some(e), _) | (None, Some(e)) => {
            Paragraph::new(Line::styled(e.to_string(), Style::default().fg(ERROR)))
        }
        (None, None) => match form.specs().get(k) {
            Some(spec) => {
                let range = match spec.kind {
                    ParamKind::Float | ParamKind::Int | ParamKind::FloatList => spec.range.describe(),
                    ParamKind::Bool => "true or false (Space toggles)".into(),
                    ParamKind::Choice(options) => format!("{} (Space cycles)", options.join(", ")),
                    ParamKind::Text => "text".into(),
                };
                let unit = if spec.unit.is_empty() { "-" } else { spec.unit };
                Paragraph::new(vec![
                    Line::from(spec.help),
                    Line::styled(format!("[{unit}]  {range}"), Style::default().fg(Color::DarkGray)),
                ])
            }
            None => Paragraph::new("no parameters"),
        },
    };
    frame.render_widget(help.wrap(Wrap { trim: true }), help_area);
}

/// Widths of the name, value and unit columns of the form's rows `offset..offset + visible`
/// in `width` cells: the values shown get the room they need first (up to 24 cells), the
/// names what is left (at least 6, cut at the end), the units at most what remains.
fn form_columns(
    form: &super::form::Form,
    offset: usize,
    visible: usize,
    width: usize,
) -> (usize, usize, usize) {
    let rows = offset..form.len().min(offset + visible);
    let longest = |f: &dyn Fn(usize) -> usize| rows.clone().map(f).max().unwrap_or(0);
    let values = longest(&|k| form.text(k).chars().count()).clamp(4, 24);
    let units = longest(&|k| form.specs()[k].unit.chars().count());
    let names = longest(&|k| form.specs()[k].name.len()).max(4);
    // marker + name + space + value + space + unit
    let room = width.saturating_sub(3);
    let unit_width = units.min(room.saturating_sub(values + 6));
    let name_width = names.min(room.saturating_sub(values + unit_width)).max(6);
    let value_width = room.saturating_sub(name_width + unit_width).max(4);
    (name_width, value_width, unit_width)
}

/// How much of a partial figure there is: a sweep's note ("partial: 3 of 8 points") or
/// "partial".
fn partial_text(figure: &crate::figure::Figure) -> &str {
    figure
        .notes
        .iter()
        .find(|n| n.starts_with("partial"))
        .map_or("partial", String::as_str)
}

fn draw_figure(frame: &mut Frame<'_>, app: &App, area: Rect, layout: &mut DrawnLayout) {
    let Some(scene) = app.scene() else {
        frame.render_widget(pane(" Figure ".into(), false), area);
        return;
    };
    let info = scene.info();
    let view = app.figure(app.selected);
    let running_here = app.running.as_ref().is_some_and(|r| r.scene == app.selected);
    let state = view.map_or(String::new(), |v| match v.state {
        // A finished figure shown while this scene runs again is the previous run's.
        FigureState::Complete if running_here => " · PREVIOUS RUN (running a new one)".into(),
        FigureState::Complete => v
            .run_time_s
            .map_or(String::new(), |t| format!(" · computed in {}", fmt_duration(t))),
        FigureState::Partial => format!(" · {}", partial_text(&v.figure)),
        FigureState::Cancelled => format!(" · cancelled, {}", partial_text(&v.figure)),
        FigureState::Failed => format!(" · failed, {}", partial_text(&v.figure)),
    });
    // The state first: a long title is cut at the end, never what the figure shows.
    let block = pane(format!(" {}{state} — {} ", info.id, info.title), false);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let panels = view.map_or(0, |v| v.figure.panels.len());
    let tabs_height = u16::from(panels > 1);
    let readout = app.readout();
    let readout_height = u16::from(readout.is_some() || app.zoom().is_some());
    let [tabs_area, body, readout_area, gauge_area] = Layout::vertical([
        Constraint::Length(tabs_height),
        Constraint::Min(0),
        Constraint::Length(readout_height),
        Constraint::Length(1),
    ])
    .areas(inner);
    if panels > 1
        && let Some(v) = view
    {
        let mut spans = vec![Span::styled(TABS_PREFIX, Style::default().fg(Color::DarkGray))];
        let mut left = tabs_area.x + Span::raw(TABS_PREFIX).width() as u16;
        for (k, text) in panel_tabs(v).into_iter().enumerate() {
            let style = if k == app.panel() {
                Style::default().bg(ACCENT).fg(Color::Black)
            } else {
                Style::default()
            };
            let span = Span::styled(text, style);
            let width = span.width() as u16;
            layout.targets.push((
                Rect {
                    x: left,
                    width,
                    ..tabs_area
                }
                .intersection(tabs_area),
                Target::Tab(k),
            ));
            left = left.saturating_add(width);
            spans.push(span);
        }
        frame.render_widget(Line::from(spans), tabs_area);
        layout.tabs = tabs_area;
    }
    let mut geometry = None;
    match view {
        Some(v) if !app.show_info && !v.figure.panels.is_empty() => {
            let (chart_area, results_area) = split_results(app, body);
            layout.results_beside = results_area.is_some();
            let results_wanted = app.results.unwrap_or(results_area.is_some());
            let chart_area = match results_area {
                Some(area) if results_wanted => {
                    draw_results(frame, app, Some(v), area);
                    chart_area
                }
                _ => body,
            };
            if let Some(drawn) = app.drawn() {
                let options = ChartOptions {
                    view: app.zoom(),
                    cursor: readout.as_ref().map(|r| r.point),
                    selection: app.selection(),
                    listed: Some(drawn.current_counts()),
                    legend_off: true,
                };
                geometry = render_chart(&drawn.current_on_top(), &options, chart_area, frame.buffer_mut());
                layout.chart_area = chart_area;
                if let Some(g) = &geometry {
                    draw_marker_shapes(frame, &drawn.panel, g);
                    if app.legend {
                        draw_legend(frame, &drawn, g);
                    }
                }
            }
            if results_area.is_none() && results_wanted {
                // No room beside the chart: the results over it, bottom right.
                let width = RESULTS_WIDTH.min(chart_area.width);
                let height = (chart_area.height * 2 / 3).max(3).min(chart_area.height);
                let area = Rect {
                    x: chart_area.right().saturating_sub(width),
                    y: chart_area.bottom().saturating_sub(height),
                    width,
                    height,
                };
                frame.render_widget(Clear, area);
                draw_results(frame, app, Some(v), area);
            }
        }
        _ => draw_info(frame, app, view, body),
    }
    layout.chart = geometry;
    if readout_height > 0 {
        let mut spans = Vec::new();
        if let Some(r) = &readout {
            // The values never cut: on a narrow chart the axes' labels give way to `x =`, `y =`.
            let change = marker_change(app);
            let change_len = change.as_ref().map_or(0, |(t, _)| t.chars().count() + 2);
            let full = format!("◆ {}  {}  {}", r.name, r.x, r.y);
            let value = |t: &str| t.rsplit(" = ").next().unwrap_or(t).to_string();
            let (x, y) = if full.chars().count() + change_len <= usize::from(readout_area.width) {
                (r.x.clone(), r.y.clone())
            } else {
                (format!("x = {}", value(&r.x)), format!("y = {}", value(&r.y)))
            };
            spans.push(Span::raw(format!("{x}  {y}  ")));
            spans.push(Span::styled(
                format!("◆ {}", r.name),
                Style::default().fg(Color::White),
            ));
            if let Some((text, color)) = change {
                spans.push(Span::styled(format!("  {text}"), Style::default().fg(color)));
            }
        }
        if app.zoom().is_some() {
            spans.push(Span::styled(
                "  · zoomed (0 resets)",
                Style::default().fg(Color::DarkGray),
            ));
        }
        frame.render_widget(Line::from(spans), readout_area);
    }
    draw_gauge(frame, app, view, gauge_area);
}

/// With the cursor on one of the current run's markers: how it moved against the same marker
/// of the first shown pin (`Δ vs #1: x +0.1 µm, y −1.3 µN`), in that pin's colour.
fn marker_change(app: &App) -> Option<(String, Color)> {
    let Some(super::chart::CursorAt::Marker(m)) = app.cursor() else {
        return None;
    };
    let drawn = app.drawn()?;
    if drawn.markers.get(m) != Some(&Owner::Current) {
        return None;
    }
    let mine = &drawn.panel.markers[m];
    let suffix = format!(" · {}", mine.name);
    let pins = app.pins(app.selected);
    let (other, owner) = drawn
        .panel
        .markers
        .iter()
        .zip(&drawn.markers)
        .find(|(mk, o)| matches!(o, Owner::Pin(i) if !pins[*i].hidden) && mk.name.ends_with(&suffix))?;
    let Owner::Pin(i) = *owner else { return None };
    let d = |a: f64, b: f64, unit: &str| {
        let v = fmt_quantity(a - b, unit);
        if a >= b { format!("+{v}") } else { v }
    };
    let text = format!(
        "Δ vs #{}: x {}, y {}",
        i + 1,
        d(mine.x, other.x, &drawn.panel.x.unit),
        d(mine.y, other.y, &drawn.panel.y.unit)
    );
    Some((text, chart_color(pins[i].color)))
}

/// What the panel tabs start with.
pub const TABS_PREFIX: &str = "panels (← → or click): ";

/// The text of each panel's tab: ` (a) title `.
pub fn panel_tabs(view: &FigureView) -> Vec<String> {
    view.figure
        .panels
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let label = if p.label.is_empty() {
                format!("{}", k + 1)
            } else {
                p.label.clone()
            };
            if p.title.is_empty() {
                format!(" {label} ")
            } else {
                format!(" {label} {} ", crate::render::text::terminal(&p.title))
            }
        })
        .collect()
}

/// The parts of the history overlay's last line, each a mouse target: what it says and the key
/// it stands for.
pub const HISTORY_FOOTER: [(&str, KeyCode); 3] = [
    ("Enter reopens (no rerun)", KeyCode::Enter),
    ("e exports", KeyCode::Char('e')),
    ("Esc closes", KeyCode::Esc),
];

const FOOTER_PREFIX: &str = " ↑ ↓ or click choose · ";
const FOOTER_GAP: &str = " · ";

/// Width of the results panel beside the chart.
const RESULTS_WIDTH: u16 = 40;

/// The chart's area and, where there is room, the results panel's: beside the chart when the
/// figure pane is wide, under it when it is tall, none on small terminals.
fn split_results(app: &App, body: Rect) -> (Rect, Option<Rect>) {
    let declared = app.scene().map_or(0, |s| s.info().results.len());
    let shown = app.figure(app.selected).map_or(0, |v| v.figure.results.len());
    let n = declared.max(shown) as u16;
    if n == 0 {
        return (body, None);
    }
    if body.width >= 60 + RESULTS_WIDTH {
        let [chart, results] =
            Layout::horizontal([Constraint::Min(0), Constraint::Length(RESULTS_WIDTH)]).areas(body);
        (chart, Some(results))
    } else if body.height >= 20 {
        let h = (n + 2).min(body.height / 3);
        let [chart, results] = Layout::vertical([Constraint::Min(0), Constraint::Length(h)]).areas(body);
        (chart, Some(results))
    } else {
        (body, None)
    }
}

/// The scene's results as a table: each result by its label with its unit, the shown run's
/// value (partial while it runs; the declared results still to come dimmed), and under it each
/// pinned run's value with its difference to the shown run, in the pin's colour. The key
/// results (pull-off, adhesive force, hysteresis, jumps) come first.
fn draw_results(frame: &mut Frame<'_>, app: &App, view: Option<&FigureView>, area: Rect) {
    let partial = view.is_some_and(|v| v.state != FigureState::Complete);
    let pins = app.pins(app.selected);
    let hidden = app.current_hidden();
    let this_run = if hidden { "this run (hidden)" } else { "this run" };
    let title = match (partial, pins.is_empty()) {
        (true, _) if hidden => " Results (partial, this run hidden) ".to_string(),
        (true, _) => " Results (partial) ".to_string(),
        (false, true) if hidden => " Results (this run hidden) ".to_string(),
        (false, true) => " Results (R hides) ".to_string(),
        (false, false) => format!(" Results: {this_run} and {} pin(s) ", pins.len()),
    };
    let block = Block::bordered()
        .title(title)
        .border_style(Style::default().fg(Color::DarkGray));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let mut rows: Vec<(String, Option<f64>)> = view
        .map(|v| {
            v.figure
                .results
                .iter()
                .map(|(n, x)| (n.clone(), Some(*x)))
                .collect()
        })
        .unwrap_or_default();
    if let Some(scene) = app.scene() {
        for (name, _) in scene.info().results {
            if !rows.iter().any(|(n, _)| n == name) {
                rows.push(((*name).to_string(), None));
            }
        }
    }
    rows.sort_by_key(|(name, _)| key_rank(name));
    let width = inner.width as usize;
    let dim = Style::default().fg(Color::DarkGray);
    let mut lines: Vec<Line<'_>> = Vec::new();
    for (name, value) in &rows {
        let (label, unit) = result_label(name);
        let text = value.map_or("…".to_string(), |v| result_text(name, v, unit));
        let name_width = width.saturating_sub(text.chars().count() + 1);
        let line = format!("{:<name_width$} {text}", clip(&label, name_width));
        lines.push(if value.is_some() && !hidden {
            Line::from(line)
        } else {
            Line::styled(line, dim)
        });
        for (i, pin) in pins.iter().enumerate() {
            let Some(x) = pin.figure.result_value(name) else {
                continue;
            };
            let diff = value.map_or(String::new(), |v| format!(" {}", difference_text(x, v)));
            let text = format!("{}{diff}", result_text(name, x, unit));
            let tag = format!("  #{}", i + 1);
            let pad = width.saturating_sub(tag.chars().count() + 1);
            let style = if pin.hidden {
                dim
            } else {
                Style::default().fg(chart_color(pin.color))
            };
            lines.push(Line::styled(format!("{tag} {:>pad$}", clip(&text, pad)), style));
        }
    }
    frame.render_widget(Paragraph::new(lines), inner);
}

/// Where a result comes in the table: the scene's key results first.
fn key_rank(name: &str) -> usize {
    const KEYS: [&str; 6] = ["pull_off", "adhesive", "hysteresis", "jump", "pull_in", "loss"];
    KEYS.iter().position(|k| name.contains(k)).unwrap_or(KEYS.len())
}

/// A result's label for people and its unit: `jkr_pull_off_force_N` reads `jkr pull-off
/// force` in `N`, `hysteresis_norm` reads `hysteresis (normalised)` (the identifier is on
/// the caption page, `i`).
pub fn result_label(name: &str) -> (String, &'static str) {
    let (short, unit) = result_unit(name);
    let (short, note) = match short.strip_suffix("_norm") {
        Some(s) => (s, " (norm.)"),
        None => (short.strip_suffix("_count").unwrap_or(short), ""),
    };
    let words = short
        .replace('_', " ")
        .replace("pull off", "pull-off")
        .replace("pull in", "pull-in")
        .replace("jkr", "JKR")
        .replace("dmt", "DMT")
        .replace(" md ", " MD ");
    let words = words
        .strip_prefix("md ")
        .map_or(words.clone(), |w| format!("MD {w}"));
    let label = if unit.is_empty() {
        format!("{words}{note}")
    } else {
        format!("{words} [{unit}]")
    };
    (label, unit)
}

/// A result's value as shown: counts whole, others with their unit's prefix.
fn result_text(name: &str, v: f64, unit: &str) -> String {
    if name.ends_with("_count") {
        format!("{v:.0}")
    } else {
        fmt_quantity(v, unit)
    }
}

/// The difference of a pinned run's value `pinned` to the shown run's `current`, relative
/// where that means something: `+4.0 %`, `=`, or `Δ −0.5` when the current value is 0.
pub fn difference_text(pinned: f64, current: f64) -> String {
    let d = pinned - current;
    if d == 0.0 {
        "(=)".into()
    } else if current != 0.0 && current.is_finite() {
        format!("({:+.1} %)", 100.0 * d / current.abs()).replace('-', "−")
    } else {
        format!("(Δ {})", fmt_quantity(d, ""))
    }
}

/// The shapes of the drawn markers (▲ pull-in, ■ pull-off, ● ○ ◆ ×) in their colours, over the
/// chart's cells.
fn draw_marker_shapes(frame: &mut Frame<'_>, panel: &crate::figure::Panel, g: &ChartGeometry) {
    let colors = panel.series_colors();
    let buf = frame.buffer_mut();
    for m in &panel.markers {
        let Some((x, y)) = cell_of(g, (m.x, m.y)) else {
            continue;
        };
        let c = chart_color(panel.marker_color(m, &colors).unwrap_or(7));
        if let Some(cell) = buf.cell_mut(Position::new(x, y)) {
            cell.set_symbol(marker_symbol(m.shape)).set_fg(c);
        }
    }
}

/// The cell of a data point on a drawn chart, if it is inside the graph.
fn cell_of(g: &ChartGeometry, p: (f64, f64)) -> Option<(u16, u16)> {
    let (fx, fy) = g.fraction(p);
    if g.graph.is_empty() || !((0.0..=1.0).contains(&fx) && (0.0..=1.0).contains(&fy)) {
        return None;
    }
    let w = f64::from(g.graph.width.max(1));
    let h = f64::from(g.graph.height.max(1));
    let x = g.graph.x + ((fx * w) as u16).min(g.graph.width.saturating_sub(1));
    let y = g.graph.bottom() - 1 - ((fy * h) as u16).min(g.graph.height.saturating_sub(1));
    Some((x, y))
}

/// The legend entries of a drawn panel: the current run's named curves, markers and regions,
/// then each pin's entry (which says when the pin is hidden or not drawn), with colours.
pub fn legend_entries(drawn: &Overlay) -> Vec<(String, Color)> {
    let panel = &drawn.panel;
    let colors = panel.series_colors();
    let (markers, regions) = drawn.current_counts();
    let mut entries: Vec<(String, Color)> = Vec::new();
    let mut push = |name: String, c: Color| {
        if !entries.iter().any(|(n, _)| *n == name) {
            entries.push((name, c));
        }
    };
    for ((s, c), owner) in panel.series.iter().zip(&colors).zip(&drawn.series) {
        if s.legend && (*owner == Owner::Current || s.points.is_empty()) {
            push(crate::render::text::terminal(&s.name), chart_color(*c));
        }
    }
    for m in panel.markers.iter().take(markers) {
        let c = chart_color(panel.marker_color(m, &colors).unwrap_or(7));
        push(
            format!(
                "{} {}",
                marker_symbol(m.shape),
                crate::render::text::terminal(&m.name)
            ),
            c,
        );
    }
    for r in panel.regions.iter().take(regions) {
        let c = chart_color(r.color.unwrap_or(8));
        push(
            format!("{REGION_SYMBOL} {}", crate::render::text::terminal(&r.name)),
            c,
        );
    }
    entries
}

/// The legend in the corner of the graph with the fewest drawn points (off the data), in a
/// box at most two thirds of the graph wide; entries that do not fit are counted, never
/// dropped silently, and the legend is drawn whatever the labels' length.
fn draw_legend(frame: &mut Frame<'_>, drawn: &Overlay, g: &ChartGeometry) {
    let entries = legend_entries(drawn);
    // The graph without its top row (the y axis' title) and bottom row (the x axis' title).
    let graph = Rect {
        y: g.graph.y + 1,
        height: g.graph.height.saturating_sub(2),
        ..g.graph
    };
    if entries.is_empty() || graph.width < 8 || graph.height < 3 {
        return;
    }
    let longest = entries.iter().map(|(n, _)| n.chars().count()).max().unwrap_or(0);
    let width = (longest as u16 + 4)
        .min(graph.width * 2 / 3)
        .max(8.min(graph.width));
    let rows = (graph.height.saturating_sub(2)).max(1);
    let shown = entries.len().min(usize::from(rows));
    let height = (shown as u16 + 2).min(graph.height);
    // Count the points in each corner box; take the emptiest (top right on a tie).
    let corners = [
        (graph.right() - width, graph.y),
        (graph.x, graph.y),
        (graph.right() - width, graph.bottom() - height),
        (graph.x, graph.bottom() - height),
    ];
    let count = |(x, y): (u16, u16)| {
        let r = Rect { x, y, width, height };
        drawn
            .panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().step_by((s.points.len() / 200).max(1)))
            .filter_map(|p| cell_of(g, *p))
            .filter(|(cx, cy)| crate::tui::layout::hit(r, *cx, *cy))
            .count()
    };
    let (x, y) = corners
        .iter()
        .copied()
        .min_by_key(|c| count(*c))
        .unwrap_or(corners[0]);
    let area = Rect { x, y, width, height };
    frame.render_widget(Clear, area);
    let block = Block::bordered()
        .title(" L hides ")
        .border_style(Style::default().fg(Color::DarkGray));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let text_width = usize::from(inner.width);
    let mut lines: Vec<Line<'_>> = entries
        .iter()
        .take(shown)
        .map(|(n, c)| Line::styled(clip(n, text_width), Style::default().fg(*c)))
        .collect();
    if shown < entries.len()
        && let Some(last) = lines.last_mut()
    {
        *last = Line::styled(
            clip(
                &format!("+{} more entries", entries.len() - shown + 1),
                text_width,
            ),
            Style::default().fg(Color::Gray),
        );
    }
    frame.render_widget(Paragraph::new(lines), inner);
}

/// A bordered box of `width` × `height` centred in `area` over what is drawn there, with
/// `title`: the box and the area inside its border.
fn overlay_box(frame: &mut Frame<'_>, area: Rect, width: u16, height: u16, title: String) -> (Rect, Rect) {
    let rect = Rect {
        x: area.x + (area.width - width) / 2,
        y: area.y + (area.height - height) / 2,
        width,
        height,
    };
    frame.render_widget(Clear, rect);
    let block = Block::bordered()
        .title(title)
        .border_style(Style::default().fg(ACCENT));
    let inner = block.inner(rect);
    frame.render_widget(block, rect);
    (rect, inner)
}

fn draw_history(frame: &mut Frame<'_>, app: &App, selected: usize, area: Rect, layout: &mut DrawnLayout) {
    let n = app.history().len();
    let width = 96.min(area.width);
    let height = (n as u16 + 4).min(area.height);
    let (rect, inner) = overlay_box(
        frame,
        area,
        width,
        height,
        format!(" Run history — last {n} runs (times UTC) "),
    );
    let footer_height = 2.min(inner.height);
    let [rows_area, footer_area] =
        Layout::vertical([Constraint::Min(0), Constraint::Length(footer_height)]).areas(inner);
    let offset = scroll_offset(selected, rows_area.height as usize);
    let lines: Vec<Line<'_>> = app
        .history()
        .iter()
        .enumerate()
        .skip(offset)
        .take(rows_area.height as usize)
        .map(|(k, e)| {
            let style = if k == selected {
                Style::default().bg(Color::Blue).fg(Color::White)
            } else {
                Style::default()
            };
            Line::styled(format!(" {}", history_line(app, e)), style)
        })
        .collect();
    frame.render_widget(Paragraph::new(lines), rows_area);
    let footer_row = Rect {
        y: footer_area.bottom().saturating_sub(1),
        height: footer_area.height.min(1),
        ..footer_area
    };
    let mut footer = FOOTER_PREFIX.to_string();
    let parts: Vec<&str> = HISTORY_FOOTER.iter().map(|(t, _)| *t).collect();
    footer.push_str(&parts.join(FOOTER_GAP));
    frame.render_widget(
        Line::styled(footer, Style::default().fg(Color::DarkGray)),
        footer_row,
    );
    // Each action of the footer is a mouse target standing for its key.
    let mut left = footer_row
        .x
        .saturating_add(Span::raw(FOOTER_PREFIX).width() as u16);
    for (text, key) in HISTORY_FOOTER {
        let width = Span::raw(text).width() as u16;
        let target = Rect {
            x: left,
            width,
            ..footer_row
        };
        layout
            .targets
            .push((target.intersection(footer_row), Target::Key(key)));
        left = left
            .saturating_add(width)
            .saturating_add(Span::raw(FOOTER_GAP).width() as u16);
    }
    layout.overlay = rect;
    layout.history = rows_area;
    layout.history_offset = offset;
    layout.history_footer = footer_row;
}

/// Labels of the history entries for the list: time of day (UTC) the run ended, scene, run
/// time (`cancelled` for a run stopped early), the parameters that differ from the scene's
/// defaults.
pub fn history_line(app: &App, entry: &HistoryEntry) -> String {
    let scene = app.scenes[entry.scene];
    let diff = difference(&entry.values, &scene.defaults());
    let diff = if diff == "same parameters" {
        "defaults".to_string()
    } else {
        diff
    };
    let ended = if entry.state == FigureState::Complete {
        "".to_string()
    } else {
        " cancelled".to_string()
    };
    format!(
        "{} {:<16} {:>8}{ended:<10}  {diff}",
        time_of_day(entry.finished_at),
        scene.info().id,
        fmt_duration(entry.run_time_s)
    )
}

/// `14:05:09` (UTC) of a moment.
pub fn time_of_day(at: std::time::SystemTime) -> String {
    let s = at
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
        % 86_400;
    format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

fn draw_info(frame: &mut Frame<'_>, app: &App, view: Option<&FigureView>, area: Rect) {
    let Some(scene) = app.scene() else { return };
    let info = scene.info();
    let mut lines = vec![Line::from(info.caption), Line::from("")];
    match view {
        None if app.running.as_ref().is_some_and(|r| r.scene == app.selected) => lines.push(Line::styled(
            "Running: the figure appears here as it is computed (Esc cancels).",
            Style::default().fg(Color::DarkGray),
        )),
        None => lines.push(Line::styled(
            "Not computed yet: press r to run, i to switch between chart and this page.",
            Style::default().fg(Color::DarkGray),
        )),
        Some(v) => {
            lines.push(Line::styled(
                "Results",
                Style::default().add_modifier(Modifier::BOLD),
            ));
            for (name, value) in &v.figure.results {
                let (label, unit) = result_label(name);
                lines.push(Line::from(format!(
                    "  {label:<40} {} {unit}  ({name})",
                    fmt_float(*value)
                )));
            }
            for note in &v.figure.notes {
                lines.push(Line::styled(
                    format!("  {note}"),
                    Style::default().fg(Color::DarkGray),
                ));
            }
        }
    }
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: false }), area);
}

fn draw_gauge(frame: &mut Frame<'_>, app: &App, view: Option<&FigureView>, area: Rect) {
    match &app.running {
        Some(run) => {
            let id = app.scenes[run.scene].info().id;
            let message = if run.cancelling {
                "cancelling…"
            } else {
                run.message.as_str()
            };
            let label = format!(
                "{id} {:>3.0}% {message}{}  (Esc cancels)",
                // Whole percent, never 100 % before the run ends.
                (run.fraction * 100.0).floor().min(99.0),
                time_left(run.fraction, run.elapsed_s)
            );
            let gauge = Gauge::default()
                .gauge_style(Style::default().fg(ACCENT).bg(Color::Black))
                .ratio(run.fraction.clamp(0.0, 1.0))
                .label(label);
            frame.render_widget(gauge, area);
        }
        None => {
            let stale = view.is_some_and(|v| app.form().is_some_and(|f| f.values() != &v.values));
            let text = match view.map(|v| v.state) {
                Some(FigureState::Complete) if stale => {
                    "parameters changed since this run: r reruns · e exports the figure as computed"
                }
                Some(FigureState::Complete) => "done · e exports · i caption and results",
                Some(FigureState::Cancelled) => "cancelled · r runs again",
                Some(FigureState::Failed) => "failed · see the status line",
                Some(FigureState::Partial) | None => "idle · r runs",
            };
            frame.render_widget(Line::styled(text, Style::default().fg(Color::DarkGray)), area);
        }
    }
}

/// ` · 12 s, about 30 s left` once a run has taken a second and done 2 % of its work.
pub fn time_left(fraction: f64, elapsed_s: f64) -> String {
    if elapsed_s < 1.0 {
        return String::new();
    }
    if fraction < 0.02 {
        return format!(" · {}", fmt_duration(elapsed_s));
    }
    let left = elapsed_s * (1.0 - fraction) / fraction;
    format!(
        " · {}, about {} left",
        fmt_duration(elapsed_s),
        fmt_duration(left)
    )
}

fn draw_status(frame: &mut Frame<'_>, app: &App, area: Rect) {
    let hint = " ? help · q quit ";
    let [text_area, hint_area] =
        Layout::horizontal([Constraint::Min(0), Constraint::Length(hint.len() as u16)]).areas(area);
    let style = if app.status.error {
        Style::default().fg(ERROR).add_modifier(Modifier::BOLD)
    } else {
        Style::default()
    };
    frame.render_widget(Line::styled(app.status.text.as_str(), style), text_area);
    frame.render_widget(
        Line::styled(hint, Style::default().fg(Color::DarkGray)),
        hint_area,
    );
}

/// The key help: every binding and notes on editing and the mouse. In two columns where two
/// whole key lines fit side by side and one column is too long, else in one column with long
/// lines wrapped (never cut) and scrolled with ↑ ↓ when it is taller than the terminal.
fn draw_help(frame: &mut Frame<'_>, app: &App, area: Rect) {
    let keys: Vec<Line<'_>> = BINDINGS
        .iter()
        .map(|b| {
            Line::from(vec![
                Span::styled(format!(" {:<10}", b.label), Style::default().fg(ACCENT)),
                Span::raw(b.help),
            ])
        })
        .collect();
    let notes: Vec<Line> = [
        "While editing a value: type, ← → Home End, Backspace Del, Ctrl-U clears; invalid values turn \
         red (✗) and block running; the last valid values are kept; * marks a value changed from the \
         dissertation's default.",
        "Mouse: click a scene, a parameter, a panel tab or a point; drag on the chart zooms, right click \
         and 0 show it whole; the wheel scrolls the lists and zooms the chart. In the history a click \
         chooses a run, a click on the chosen run reopens it; click the footer's actions.",
        "Each panel keeps its cursor and zoom until new results change its axes. ↑ ↓ scroll this help; \
         any other key closes it.",
    ]
    .into_iter()
    .map(|t| Line::styled(t, Style::default().fg(Color::DarkGray)))
    .collect();
    let key_width = keys.iter().map(Line::width).max().unwrap_or(0) as u16;
    // Rows a paragraph of `lines` takes at `width` when wrapped.
    let rows = |lines: &[Line<'_>], width: u16| -> u16 {
        lines
            .iter()
            .map(|l| (l.width() as u16).div_ceil(width.max(1)).max(1))
            .sum()
    };
    let two_columns = area.width >= 2 * key_width + 3
        && rows(&keys, key_width) + rows(&notes, 2 * key_width) + 2 > area.height;
    let width = if two_columns {
        2 * key_width + 3
    } else {
        (key_width + 2).max(60)
    }
    .min(area.width);
    let inner_width = width.saturating_sub(2);
    let key_rows = if two_columns {
        (keys.len() as u16).div_ceil(2)
    } else {
        rows(&keys, inner_width)
    };
    let note_rows = rows(&notes, inner_width);
    let height = (key_rows + note_rows + 3).min(area.height);
    let (_, inner) = overlay_box(
        frame,
        area,
        width,
        height,
        " Keys — ↑ ↓ scroll, any other key closes ".to_string(),
    );
    if two_columns {
        let [keys_area, notes_area] =
            Layout::vertical([Constraint::Length(key_rows), Constraint::Min(0)]).areas(inner);
        let [a, b] =
            Layout::horizontal([Constraint::Length(key_width + 1), Constraint::Min(0)]).areas(keys_area);
        let mut keys = keys;
        let second = keys.split_off(usize::from(key_rows));
        frame.render_widget(Paragraph::new(keys), a);
        frame.render_widget(Paragraph::new(second), b);
        let mut lines = vec![Line::from("")];
        lines.extend(notes);
        frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: false }), notes_area);
    } else {
        let mut lines = keys;
        lines.push(Line::from(""));
        lines.extend(notes);
        let most = (key_rows + note_rows + 1).saturating_sub(inner.height);
        let scroll = app.help_scroll.min(most);
        frame.render_widget(
            Paragraph::new(lines)
                .wrap(Wrap { trim: false })
                .scroll((scroll, 0)),
            inner,
        );
    }
}
