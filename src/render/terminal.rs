//! A figure panel as a ratatui braille [`Chart`]: the same series, markers, shaded regions and
//! fields as the PNG/SVG, drawn in the terminal. Unstable branches are dashed (drawn in pieces),
//! reference curves dotted, markers as block symbols, shaded regions (hysteresis loops) as a
//! sparse dot fill under the curves (hatched ones as diagonal rows of dots); fields as contour
//! lines. Log axes are drawn in log10 coordinates with decade labels.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::{Color, Style as TuiStyle};
use ratatui::symbols::Marker as TuiMarker;
use ratatui::text::Line;
use ratatui::widgets::{Axis as TuiAxis, Chart, Dataset, GraphType, LegendPosition, Widget};

use super::axes::padded_range;
use super::labels::{AxisLabels, axis_labels};
use crate::figure::{FieldKind, MarkerShape, Panel, Region, Scale, Style};

/// The symbol of a marker shape, as drawn and in the legend.
pub fn marker_symbol(shape: MarkerShape) -> &'static str {
    match shape {
        MarkerShape::PullIn => "▲",
        MarkerShape::PullOff => "■",
        MarkerShape::StableState => "●",
        MarkerShape::UnstableState => "○",
        MarkerShape::Point => "◆",
        MarkerShape::Cross => "×",
    }
}

/// The legend symbol of a shaded region.
pub const REGION_SYMBOL: &str = "░";

/// Palette index of a region without its own colour.
const REGION_COLOR: usize = 8;

/// Terminal colour of palette index `k` (readable on dark and light backgrounds).
pub fn color(k: usize) -> Color {
    const COLORS: [Color; 10] = [
        Color::LightBlue,
        Color::LightRed,
        Color::LightGreen,
        Color::LightMagenta,
        Color::Yellow,
        Color::Cyan,
        Color::Red,
        Color::White,
        Color::Gray,
        Color::Green,
    ];
    COLORS[k % COLORS.len()]
}

/// A drawable dataset with owned points.
struct Set {
    name: Option<String>,
    color: Color,
    points: Vec<(f64, f64)>,
    marker: TuiMarker,
    kind: GraphType,
}

/// A rectangle in data units: (x range, y range).
pub type View = ((f64, f64), (f64, f64));

/// What is drawn besides the panel: the shown range (zoom), a cursor, a zoom rectangle, and
/// which markers and regions the legend lists.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ChartOptions {
    /// The shown range in data units; `None` fits the data.
    pub view: Option<View>,
    /// A cursor (crosshair and block) at this point, in data units.
    pub cursor: Option<(f64, f64)>,
    /// A rectangle being chosen for zooming, in data units.
    pub selection: Option<View>,
    /// Only the first this many markers and regions get legend entries (`None`: all); the
    /// others belong to an entry that lists them, such as a pinned run's.
    pub listed: Option<(usize, usize)>,
    /// Leave the legend out (the caller draws its own, e.g. one that is never hidden).
    pub legend_off: bool,
}

/// Where the plotting area of a drawn chart is and what it shows, to map screen cells to data
/// (the mouse) and back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChartGeometry {
    /// The cells the curves are drawn in.
    pub graph: Rect,
    /// Shown x range in drawing coordinates (log10 on a log axis).
    pub x: [f64; 2],
    /// Shown y range in drawing coordinates.
    pub y: [f64; 2],
    /// Whether x is logarithmic.
    pub xlog: bool,
    /// Whether y is logarithmic.
    pub ylog: bool,
}

impl ChartGeometry {
    /// The data point at the centre of cell (`column`, `row`), if the cell is in the graph.
    pub fn to_data(&self, column: u16, row: u16) -> Option<(f64, f64)> {
        let g = self.graph;
        if !(g.x..g.right()).contains(&column) || !(g.y..g.bottom()).contains(&row) {
            return None;
        }
        let fx = (f64::from(column - g.x) + 0.5) / f64::from(g.width.max(1));
        let fy = (f64::from(g.bottom() - 1 - row) + 0.5) / f64::from(g.height.max(1));
        let x = self.x[0] + fx * (self.x[1] - self.x[0]);
        let y = self.y[0] + fy * (self.y[1] - self.y[0]);
        let un = |v: f64, log: bool| if log { 10f64.powf(v) } else { v };
        Some((un(x, self.xlog), un(y, self.ylog)))
    }

    /// A data point's position as a fraction of the graph's width and height (0 to 1 inside).
    pub fn fraction(&self, p: (f64, f64)) -> (f64, f64) {
        let tr = |v: f64, log: bool| if log { v.log10() } else { v };
        (
            (tr(p.0, self.xlog) - self.x[0]) / (self.x[1] - self.x[0]),
            (tr(p.1, self.ylog) - self.y[0]) / (self.y[1] - self.y[0]),
        )
    }

    /// The size of one cell in data units near `p` (the chart's resolution there).
    pub fn resolution(&self, p: (f64, f64)) -> (f64, f64) {
        let dx = (self.x[1] - self.x[0]) / f64::from(self.graph.width.max(1));
        let dy = (self.y[1] - self.y[0]) / f64::from(self.graph.height.max(1));
        let res = |v: f64, d: f64, log: bool| {
            if log { v.abs() * (10f64.powf(d) - 1.0) } else { d }
        };
        (res(p.0, dx, self.xlog), res(p.1, dy, self.ylog))
    }
}

/// The shown range of `panel` in data units: the view where given, else the panel's fixed
/// ranges or its padded data bounds. `None` when there is nothing to draw.
pub fn shown_range(panel: &Panel, view: Option<View>) -> Option<View> {
    if let Some(v) = view {
        return Some(v);
    }
    let ((xlo, xhi), (ylo, yhi)) = panel.data_bounds()?;
    let x = panel
        .x
        .range
        .unwrap_or_else(|| padded_range(xlo, xhi, panel.x.scale));
    let y = panel
        .y
        .range
        .unwrap_or_else(|| padded_range(ylo, yhi, panel.y.scale));
    Some((x, y))
}

/// The tick labels and titles of both axes for `panel` drawn into `area` with `view`.
pub fn chart_labels(panel: &Panel, view: Option<View>, area: Rect) -> Option<(AxisLabels, AxisLabels)> {
    let ((xa, xb), (ya, yb)) = shown_range(panel, view)?;
    let x_target = usize::from(area.width / 12).clamp(2, 8);
    let y_target = usize::from(area.height.saturating_sub(3) / 3).clamp(2, 6);
    Some((
        axis_labels(&panel.x, xa, xb, x_target),
        axis_labels(&panel.y, ya, yb, y_target),
    ))
}

/// Render `panel` into `area` of `buf`.
pub fn render_panel(panel: &Panel, area: Rect, buf: &mut Buffer) {
    render_chart(panel, &ChartOptions::default(), area, buf);
}

/// Render `panel` with `options` into `area` of `buf`; returns where the graph went.
pub fn render_chart(
    panel: &Panel,
    options: &ChartOptions,
    area: Rect,
    buf: &mut Buffer,
) -> Option<ChartGeometry> {
    let (Some(((xa, xb), (ya, yb))), Some((x_labels, y_labels))) = (
        shown_range(panel, options.view),
        chart_labels(panel, options.view, area),
    ) else {
        Line::from("no data").render(area, buf);
        return None;
    };
    let xlog = panel.x.scale == Scale::Log;
    let ylog = panel.y.scale == Scale::Log;
    let tx = |v: f64| if xlog { v.log10() } else { v };
    let ty = |v: f64| if ylog { v.log10() } else { v };
    let xb_ = [tx(xa), tx(xb)];
    let yb_ = [ty(ya), ty(yb)];
    let map = |p: &(f64, f64)| -> Option<(f64, f64)> {
        let x = tx(p.0);
        let y = ty(p.1);
        (x.is_finite() && y.is_finite()).then_some((x, y))
    };
    let span = (xb_[1] - xb_[0], yb_[1] - yb_[0]);
    let colors = panel.series_colors();
    let mut sets: Vec<Set> = Vec::new();
    let mut named: Vec<String> = Vec::new();
    let (listed_markers, listed_regions) = options.listed.unwrap_or((usize::MAX, usize::MAX));
    let y_width = y_labels
        .ticks
        .iter()
        .map(|(_, l)| l.chars().count())
        .max()
        .unwrap_or(1)
        .max(1);

    if let Some(field) = &panel.field {
        let mut levels = field.contour_levels();
        if matches!(field.kind, FieldKind::Heat)
            && let Some((lo, hi)) = field.value_range()
        {
            levels.extend((1..6).map(|k| lo + (hi - lo) * k as f64 / 6.0));
        }
        for (k, level) in levels.iter().enumerate() {
            let emphasised = field.highlight.iter().any(|(l, _)| l == level);
            for (j, line) in field.contour(*level).into_iter().enumerate() {
                let name = (j == 0 && emphasised)
                    .then(|| {
                        field
                            .highlight
                            .iter()
                            .find(|(l, _)| l == level)
                            .map(|(_, t)| t.clone())
                    })
                    .flatten();
                sets.push(Set {
                    name,
                    color: if emphasised { Color::LightRed } else { color(k + 2) },
                    points: line.iter().filter_map(map).collect(),
                    marker: TuiMarker::Braille,
                    kind: GraphType::Line,
                });
            }
        }
    }

    if let Some(layout) = chart_layout(area, y_width as u16) {
        for (k, region) in panel.regions.iter().enumerate() {
            let label = format!("{REGION_SYMBOL} {}", region.name);
            let name = (k < listed_regions && !named.contains(&label)).then(|| {
                named.push(label.clone());
                label
            });
            sets.push(Set {
                name,
                color: color(region.color.unwrap_or(REGION_COLOR)),
                points: region_fill(region, layout.graph, xb_, yb_, &map),
                marker: TuiMarker::Braille,
                kind: GraphType::Scatter,
            });
        }
    }

    for (s, &c) in panel.series.iter().zip(&colors) {
        let pts: Vec<(f64, f64)> = s.points.iter().filter_map(map).collect();
        let name = if s.legend && !named.contains(&s.name) {
            named.push(s.name.clone());
            Some(s.name.clone())
        } else {
            None
        };
        let col = color(c);
        match s.style {
            Style::Stable | Style::Contour | Style::Jump => sets.push(Set {
                name,
                color: col,
                points: pts,
                marker: TuiMarker::Braille,
                kind: GraphType::Line,
            }),
            Style::Unstable | Style::Dashed | Style::Reference => {
                let (on, off) = if s.style != Style::Reference {
                    (0.02, 0.015)
                } else {
                    (0.004, 0.012)
                };
                let mut first = true;
                for piece in dashes(&pts, span, on, off) {
                    sets.push(Set {
                        name: if first { name.clone() } else { None },
                        color: col,
                        points: piece,
                        marker: TuiMarker::Braille,
                        kind: GraphType::Line,
                    });
                    first = false;
                }
            }
            Style::Scatter | Style::ErrorBar => sets.push(Set {
                name,
                color: col,
                points: pts,
                marker: TuiMarker::Dot,
                kind: GraphType::Scatter,
            }),
        }
    }
    for (k, m) in panel.markers.iter().enumerate() {
        let c = color(panel.marker_color(m, &colors).unwrap_or(7));
        let label = format!("{} {}", marker_symbol(m.shape), m.name);
        let name = (k < listed_markers && !named.contains(&label)).then(|| {
            named.push(label.clone());
            label
        });
        if let Some(p) = map(&(m.x, m.y)) {
            sets.push(Set {
                name,
                color: c,
                points: vec![p],
                marker: TuiMarker::Block,
                kind: GraphType::Scatter,
            });
        }
    }

    if let Some(c) = options.cursor.and_then(|c| map(&c)) {
        // The crosshair under the curves, the point itself on top.
        let line = |points: Vec<(f64, f64)>| Set {
            name: None,
            color: Color::DarkGray,
            points,
            marker: TuiMarker::Braille,
            kind: GraphType::Line,
        };
        sets.insert(0, line(vec![(c.0, yb_[0]), (c.0, yb_[1])]));
        sets.insert(0, line(vec![(xb_[0], c.1), (xb_[1], c.1)]));
        sets.push(Set {
            name: None,
            color: Color::White,
            points: vec![c],
            marker: TuiMarker::Block,
            kind: GraphType::Scatter,
        });
    }
    if let Some(((x0, x1), (y0, y1))) = options.selection
        && let (Some(a), Some(b)) = (map(&(x0, y0)), map(&(x1, y1)))
    {
        sets.push(Set {
            name: None,
            color: Color::Yellow,
            points: vec![(a.0, a.1), (b.0, a.1), (b.0, b.1), (a.0, b.1), (a.0, a.1)],
            marker: TuiMarker::Braille,
            kind: GraphType::Line,
        });
    }
    let datasets: Vec<Dataset<'_>> = sets
        .iter()
        .map(|s| {
            let mut d = Dataset::default()
                .data(&s.points)
                .marker(s.marker)
                .graph_type(s.kind)
                .style(TuiStyle::default().fg(s.color));
            if let Some(n) = &s.name {
                d = d.name(super::text::terminal(n));
            }
            d
        })
        .collect();
    // Blank labels reserve the room; the real ones go where their ticks are (ratatui spaces
    // labels evenly between the bounds, which 1-2-5 ticks are not).
    let blank = |w: usize| Line::from(" ".repeat(w));
    let chart = Chart::new(datasets)
        .x_axis(
            TuiAxis::default()
                .title(super::text::terminal(&x_labels.title))
                .bounds(xb_)
                .labels(vec![Line::from(""), blank(1)])
                .style(TuiStyle::default().fg(Color::Gray)),
        )
        .y_axis(
            TuiAxis::default()
                .title(super::text::terminal(&y_labels.title))
                .bounds(yb_)
                .labels(vec![blank(y_width), blank(y_width)])
                .style(TuiStyle::default().fg(Color::Gray)),
        )
        .legend_position((!options.legend_off).then_some(LegendPosition::TopRight))
        .hidden_legend_constraints((Constraint::Ratio(2, 3), Constraint::Ratio(2, 3)));
    chart.render(area, buf);
    let layout = chart_layout(area, y_width as u16)?;
    let geometry = ChartGeometry {
        graph: layout.graph,
        x: xb_,
        y: yb_,
        xlog,
        ylog,
    };
    draw_ticks(buf, area, &layout, &geometry, &x_labels, &y_labels);
    Some(geometry)
}

/// Where ratatui's chart puts its parts (its `Chart::layout`, for one-line x labels with an
/// empty first label and y labels `y_label_width` wide).
struct ChartLayout {
    graph: Rect,
    label_row: Option<u16>,
    axis_row: Option<u16>,
    axis_col: Option<u16>,
}

fn chart_layout(area: Rect, y_label_width: u16) -> Option<ChartLayout> {
    if area.height == 0 || area.width == 0 {
        return None;
    }
    let mut x = area.left();
    let mut y = area.bottom() - 1;
    let mut label_row = None;
    if y > area.top() {
        label_row = Some(y);
        y -= 1;
    }
    x += y_label_width.min(area.width / 3);
    let mut axis_row = None;
    if y > area.top() {
        axis_row = Some(y);
        y -= 1;
    }
    let mut axis_col = None;
    if x + 1 < area.right() {
        axis_col = Some(x);
        x += 1;
    }
    let width = area.right().saturating_sub(x);
    let height = y.saturating_sub(area.top()) + 1;
    (width > 0 && height > 0).then_some(ChartLayout {
        graph: Rect::new(x, area.top(), width, height),
        label_row,
        axis_row,
        axis_col,
    })
}

/// Write the tick labels at their ticks and mark the ticks on the axis lines.
fn draw_ticks(
    buf: &mut Buffer,
    area: Rect,
    layout: &ChartLayout,
    g: &ChartGeometry,
    x_labels: &AxisLabels,
    y_labels: &AxisLabels,
) {
    let style = TuiStyle::default().fg(Color::Gray);
    let graph = layout.graph;
    let inside = |frac: f64| (-1e-9..=1.0 + 1e-9).contains(&frac);
    if let (Some(row), Some(axis_row)) = (layout.label_row, layout.axis_row) {
        let mut free_from = area.left();
        for (pos, label) in &x_labels.ticks {
            let frac = (pos - g.x[0]) / (g.x[1] - g.x[0]);
            if !inside(frac) {
                continue;
            }
            let col = graph.left() + (frac * f64::from(graph.width - 1)).round() as u16;
            let w = label.chars().count() as u16;
            let start = col
                .saturating_sub(w / 2)
                .max(area.left())
                .min(area.right().saturating_sub(w));
            if start < free_from {
                continue;
            }
            buf.set_string(start, row, label, style);
            free_from = start + w + 1;
            buf[(col, axis_row)].set_symbol("┴");
        }
    }
    if let Some(col) = layout.axis_col {
        let mut taken: Vec<u16> = Vec::new();
        for (pos, label) in &y_labels.ticks {
            let frac = (pos - g.y[0]) / (g.y[1] - g.y[0]);
            if !inside(frac) {
                continue;
            }
            let row = graph.bottom() - 1 - (frac * f64::from(graph.height - 1)).round() as u16;
            if taken.contains(&row) {
                continue;
            }
            taken.push(row);
            let w = label.chars().count() as u16;
            let start = col.saturating_sub(w).max(area.left());
            buf.set_stringn(start, row, label, usize::from(col - start), style);
            buf[(col, row)].set_symbol("┤");
        }
    }
}

/// The dots that shade `region` in a graph of `graph` cells showing `x` × `y` (drawing
/// coordinates): one braille dot at the centre of every other cell inside the polygon, in a
/// checkerboard (a fill) or on diagonals (a hatched region). Rows are cut by the polygon's edges
/// (even-odd rule), so the cost is cells plus rows × edges.
fn region_fill(
    region: &Region,
    graph: Rect,
    x: [f64; 2],
    y: [f64; 2],
    map: &impl Fn(&(f64, f64)) -> Option<(f64, f64)>,
) -> Vec<(f64, f64)> {
    let poly: Vec<(f64, f64)> = region.points.iter().filter_map(map).collect();
    let (w, h) = (usize::from(graph.width), usize::from(graph.height));
    if poly.len() < 3 || w == 0 || h == 0 {
        return Vec::new();
    }
    let (dx, dy) = ((x[1] - x[0]) / w as f64, (y[1] - y[0]) / h as f64);
    let mut dots = Vec::new();
    let mut cuts: Vec<f64> = Vec::new();
    for row in 0..h {
        let yc = y[0] + (row as f64 + 0.5) * dy;
        cuts.clear();
        for (k, a) in poly.iter().enumerate() {
            let b = poly[(k + 1) % poly.len()];
            if (a.1 <= yc) != (b.1 <= yc) {
                cuts.push(a.0 + (yc - a.1) / (b.1 - a.1) * (b.0 - a.0));
            }
        }
        cuts.sort_by(f64::total_cmp);
        for pair in cuts.chunks_exact(2) {
            // Cells whose centre lies between the two cuts.
            let first = ((pair[0] - x[0]) / dx - 0.5).ceil().max(0.0);
            let last = ((pair[1] - x[0]) / dx - 0.5).floor().min(w as f64 - 1.0);
            if first.is_nan() || last.is_nan() || first > last {
                continue;
            }
            for col in first as usize..=last as usize {
                let on = if region.hatched {
                    (col + row) % 4 == 0
                } else {
                    (col + row) % 2 == 0
                };
                if on {
                    dots.push((x[0] + (col as f64 + 0.5) * dx, yc));
                }
            }
        }
    }
    dots
}

/// Cut a polyline into dashes measured in fractions of the chart's span.
fn dashes(points: &[(f64, f64)], span: (f64, f64), on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
    let sx = span.0.abs().max(f64::MIN_POSITIVE);
    let sy = span.1.abs().max(f64::MIN_POSITIVE);
    let mut out = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let mut drawing = true;
    let mut left = on;
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (((b.0 - a.0) / sx).powi(2) + ((b.1 - a.1) / sy).powi(2)).sqrt();
        let mut t = 0.0;
        let mut remaining = len;
        while remaining > 0.0 {
            let step = remaining.min(left);
            let t1 = if len > 0.0 { t + step / len } else { 1.0 };
            let p0 = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            let p1 = (a.0 + t1 * (b.0 - a.0), a.1 + t1 * (b.1 - a.1));
            if drawing {
                if cur.is_empty() {
                    cur.push(p0);
                }
                cur.push(p1);
            }
            left -= step;
            remaining -= step;
            t = t1;
            if left <= 1e-15 {
                if drawing && !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                }
                drawing = !drawing;
                left = if drawing { on } else { off };
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}
