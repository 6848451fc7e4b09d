//! A figure panel as a ratatui braille [`Chart`]: the same series, markers and fields as the
//! PNG/SVG, drawn in the terminal. Unstable branches are dashed (drawn in pieces), reference
//! curves dotted, markers as block symbols; fields as contour lines. Log axes are drawn in
//! log10 coordinates with decade labels.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::{Color, Style as TuiStyle};
use ratatui::symbols::Marker as TuiMarker;
use ratatui::text::Line;
use ratatui::widgets::{Axis as TuiAxis, Chart, Dataset, GraphType, LegendPosition, Widget};

use super::axes::{format_number, padded_range, power_of_ten};
use crate::figure::{FieldKind, MarkerShape, Panel, Scale, Style};

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

/// Render `panel` into `area` of `buf`.
pub fn render_panel(panel: &Panel, area: Rect, buf: &mut Buffer) {
    let Some(((xlo, xhi), (ylo, yhi))) = panel.data_bounds() else {
        Line::from("no data").render(area, buf);
        return;
    };
    let (xa, xb) = panel
        .x
        .range
        .unwrap_or_else(|| padded_range(xlo, xhi, panel.x.scale));
    let (ya, yb) = panel
        .y
        .range
        .unwrap_or_else(|| padded_range(ylo, yhi, panel.y.scale));
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
    for m in &panel.markers {
        let c = color(panel.marker_color(m, &colors).unwrap_or(7));
        let symbol = match m.shape {
            MarkerShape::PullIn => "▲",
            MarkerShape::PullOff => "■",
            MarkerShape::StableState => "●",
            MarkerShape::UnstableState => "○",
            MarkerShape::Point => "◆",
            MarkerShape::Cross => "×",
        };
        let label = format!("{symbol} {}", m.name);
        let name = (!named.contains(&label)).then(|| {
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

    let datasets: Vec<Dataset<'_>> = sets
        .iter()
        .map(|s| {
            let mut d = Dataset::default()
                .data(&s.points)
                .marker(s.marker)
                .graph_type(s.kind)
                .style(TuiStyle::default().fg(s.color));
            if let Some(n) = &s.name {
                d = d.name(n.clone());
            }
            d
        })
        .collect();
    let labels = |b: [f64; 2], log: bool| -> Vec<Line<'static>> {
        (0..3)
            .map(|k| {
                let v = b[0] + (b[1] - b[0]) * k as f64 / 2.0;
                let text = if log {
                    let r = v.round();
                    if (v - r).abs() < 0.05 {
                        power_of_ten(r as i64)
                    } else {
                        format_number(10f64.powf(v))
                    }
                } else {
                    format_number(v)
                };
                Line::from(text)
            })
            .collect()
    };
    let chart = Chart::new(datasets)
        .x_axis(
            TuiAxis::default()
                .title(panel.x.title())
                .bounds(xb_)
                .labels(labels(xb_, xlog))
                .style(TuiStyle::default().fg(Color::Gray)),
        )
        .y_axis(
            TuiAxis::default()
                .title(panel.y.title())
                .bounds(yb_)
                .labels(labels(yb_, ylog))
                .style(TuiStyle::default().fg(Color::Gray)),
        )
        .legend_position(Some(LegendPosition::TopRight))
        .hidden_legend_constraints((Constraint::Ratio(1, 2), Constraint::Ratio(1, 2)));
    chart.render(area, buf);
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
