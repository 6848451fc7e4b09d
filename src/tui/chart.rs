//! The chart's state as plain data and the geometry on it: where the cursor is
//! ([`CursorAt`]) and what it reads ([`Readout`]), each panel's kept cursor and zoom
//! ([`PanelView`]) and what they refer to ([`AxesKey`]), and the functions that find points,
//! markers and zoomed ranges on a drawn (overlaid) panel. No state machine and no drawing here:
//! [`crate::tui::app`] moves the cursor and the zoom with these, the view draws the result.

use super::compare::Overlay;
use crate::figure::{Axis, Panel, Scale};
use crate::render::labels::fmt_quantity;
use crate::render::terminal::{View, shown_range};
use crate::render::text::terminal;

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
        let axis = |a: &Axis| (a.label.clone(), a.unit.clone(), a.scale);
        Self {
            x: axis(&panel.x),
            y: axis(&panel.y),
            range: shown_range(panel, None),
        }
    }
}

/// `[lo, hi]` scaled by `factor` about `c` (in log10 on a log axis).
pub fn scale_about(lo: f64, hi: f64, c: f64, factor: f64, scale: Scale) -> (f64, f64) {
    match scale {
        Scale::Linear => (c + (lo - c) * factor, c + (hi - c) * factor),
        Scale::Log => {
            let (l, h, c) = (lo.log10(), hi.log10(), c.max(f64::MIN_POSITIVE).log10());
            (10f64.powf(c + (l - c) * factor), 10f64.powf(c + (h - c) * factor))
        }
    }
}

/// The middle point of the first curve with points.
pub fn first_point(drawn: &Overlay) -> Option<CursorAt> {
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
pub fn distance(drawn: &Overlay, view: Option<View>, a: (f64, f64), b: (f64, f64)) -> f64 {
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

/// Index of the point of `points` nearest to `p` (0 for none).
pub fn nearest_in(points: &[(f64, f64)], p: (f64, f64), drawn: &Overlay, view: Option<View>) -> usize {
    points
        .iter()
        .enumerate()
        .map(|(i, q)| (i, distance(drawn, view, *q, p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(i, _)| i)
}

/// The drawn point nearest to `p`; markers count too when `markers` (a click on a marker
/// selects it).
pub fn nearest(drawn: &Overlay, p: (f64, f64), view: Option<View>, markers: bool) -> Option<CursorAt> {
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

/// The data point the cursor at `at` stands on.
pub fn cursor_point(drawn: &Overlay, at: CursorAt) -> Option<(f64, f64)> {
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
    let axis = |a: &Axis, v: f64| format!("{} = {}", terminal(&a.label), fmt_quantity(v, &a.unit));
    Some(Readout {
        point,
        name,
        x: axis(&drawn.panel.x, point.0),
        y: axis(&drawn.panel.y, point.1),
    })
}
