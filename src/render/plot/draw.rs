//! Drawing primitives of the PNG and SVG figures in pixel space: labels in math markup,
//! polylines in the line styles (solid, dashed, dotted, jump arrows), arrow heads, markers,
//! translucent and hatched regions.
//!
//! In PNG every stroke and fill is anti-aliased by [`crate::render::raster`] and blended into
//! the bitmap with its coverage; axis-parallel lines (frame, ticks, grid) are first snapped to
//! whole pixels so that they stay sharp. In SVG the same shapes go to the vector backend and
//! the viewer anti-aliases them.

use plotters::prelude::*;
use plotters::style::RGBAColor;

use super::frame::{Area, Draw, Frame, Metrics, err, ipt};
use crate::figure::{MarkerShape, Style};
use crate::render::raster;

/// Horizontal anchor of a label: where `at` lies along the text.
#[derive(Debug, Clone, Copy)]
pub(super) enum Anchor {
    /// At the start of the text.
    Start,
    /// At its middle.
    Middle,
    /// At its end.
    End,
}

/// Vertical anchor of a label: where `at` lies across a line of plain text of its size
/// ([`crate::render::text::ASCENT`], [`crate::render::text::DESCENT`]).
#[derive(Debug, Clone, Copy)]
pub(super) enum Baseline {
    /// At the top of the ascent.
    Top,
    /// Half-way between ascent and descent.
    Center,
    /// At the bottom of the descent.
    Bottom,
}

/// A label's text, size and weight.
#[derive(Debug, Clone, Copy)]
pub(super) struct Label<'a> {
    /// Math markup ([`crate::render::text`]).
    pub text: &'a str,
    /// Size in pixels.
    pub size: f64,
    /// Bold face.
    pub bold: bool,
    /// Colour.
    pub color: RGBColor,
    /// Read from bottom to top (y-axis titles).
    pub vertical: bool,
}

impl<'a> Label<'a> {
    /// A horizontal black label in the regular face.
    pub fn new(text: &'a str, size: f64) -> Self {
        Self {
            text,
            size,
            bold: false,
            color: BLACK,
            vertical: false,
        }
    }

    /// In the bold face.
    #[must_use]
    pub fn bold(self) -> Self {
        Self { bold: true, ..self }
    }

    /// In `color`.
    #[must_use]
    pub fn color(self, color: RGBColor) -> Self {
        Self { color, ..self }
    }

    /// Reading from bottom to top.
    #[must_use]
    pub fn vertical(self) -> Self {
        Self {
            vertical: true,
            ..self
        }
    }

    /// Width of the laid-out text (pixels).
    pub fn width(&self) -> f64 {
        crate::render::text::width(self.text, self.size, self.bold)
    }
}

/// Draw a label in math markup at `at` with the given anchors: in PNG laid out and rasterised
/// here (kerned, anti-aliased), in SVG as `<text>` with `<tspan>`s.
pub(super) fn draw_label<DB: DrawingBackend>(
    area: &Area<DB>,
    label: Label<'_>,
    at: (f64, f64),
    anchor: (Anchor, Baseline),
    m: &Metrics,
) -> Draw<()> {
    let Label {
        text,
        size,
        bold,
        color,
        vertical,
    } = label;
    let l = crate::render::text::layout(text, size, bold);
    let dx = match anchor.0 {
        Anchor::Start => 0.0,
        Anchor::Middle => -0.5 * l.width,
        Anchor::End => -l.width,
    };
    // On the extent of plain text of this size, not of this text: labels with and without
    // sub- or superscripts (10^{−2} beside 10) share their baseline.
    let (ascent, descent) = (
        crate::render::text::ASCENT * size,
        crate::render::text::DESCENT * size,
    );
    let base = match anchor.1 {
        Baseline::Top => ascent,
        Baseline::Center => 0.5 * (ascent - descent),
        Baseline::Bottom => -descent,
    };
    // Text coordinates (u along the text, v down from the baseline) to panel pixels.
    let map = |u: f64, v: f64| {
        if vertical {
            (at.0 + v + base, at.1 - (u + dx))
        } else {
            (at.0 + u + dx, at.1 + v + base)
        }
    };
    if let Some(texts) = &m.texts {
        let (ox, oy) = area.get_base_pixel();
        let (x, y) = map(-dx, 0.0);
        let (x, y) = (x + f64::from(ox), y + f64::from(oy));
        let anchor_name = match anchor.0 {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let rotate = if vertical {
            format!(" transform=\"rotate(-90 {x:.1} {y:.1})\"")
        } else {
            String::new()
        };
        texts.borrow_mut().push(format!(
            "<text x=\"{x:.1}\" y=\"{y:.1}\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"{size:.1}\" \
             font-weight=\"{}\" fill=\"#{:02X}{:02X}{:02X}\" text-anchor=\"{anchor_name}\"{rotate}>{}</text>",
            if bold { "bold" } else { "normal" },
            color.0,
            color.1,
            color.2,
            crate::render::text::svg_tspans(text)
        ));
        return Ok(());
    }
    let mut result = Ok(());
    crate::render::text::rasterize(&l, |u, v, c| {
        let (x, y) = map(u, v);
        if result.is_ok() {
            result = area
                .draw_pixel((x.round() as i32, y.round() as i32), &color.mix(c))
                .map_err(err);
        }
    });
    result
}

/// Blend the coverage a rasteriser hands out into the bitmap in `color` (its alpha times the
/// coverage).
fn paint<DB: DrawingBackend>(
    area: &Area<DB>,
    color: RGBAColor,
    shape: impl FnOnce(&mut dyn FnMut(i32, i32, f64)),
) -> Draw<()> {
    let mut result = Ok(());
    shape(&mut |x, y, c| {
        if result.is_ok() {
            let c = RGBAColor(color.0, color.1, color.2, color.3 * c);
            result = area.draw_pixel((x, y), &c).map_err(err);
        }
    });
    result
}

/// Map data points to pixel polylines, splitting at points that cannot be drawn (NaN, ≤ 0 on
/// log axes) and clipping to the frame.
pub(super) fn pixel_runs(frame: &Frame, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let mut prev: Option<(f64, f64)> = None;
    for &p in points {
        let q = frame.map(p);
        match (prev, q) {
            (Some(a), Some(b)) => {
                if let Some((ca, cb)) = frame.clip(a, b) {
                    if current.is_empty() || current.last() != Some(&ca) {
                        if !current.is_empty() {
                            runs.push(std::mem::take(&mut current));
                        }
                        current.push(ca);
                    }
                    current.push(cb);
                    if cb != b {
                        runs.push(std::mem::take(&mut current));
                    }
                } else if !current.is_empty() {
                    runs.push(std::mem::take(&mut current));
                }
            }
            (None, Some(b)) => {
                if frame.inside(b) && points.len() == 1 {
                    current.push(b);
                }
            }
            (_, None) => {
                if !current.is_empty() {
                    runs.push(std::mem::take(&mut current));
                }
            }
        }
        prev = q;
    }
    if !current.is_empty() {
        runs.push(current);
    }
    runs
}

/// Split a pixel polyline into dashes of length `on` separated by `off`.
pub(super) fn dash(run: &[(f64, f64)], on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut cur = vec![run[0]];
    let mut drawing = true;
    let mut left = on;
    for w in run.windows(2) {
        let (mut a, b) = (w[0], w[1]);
        let mut len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        while len > 0.0 {
            if len <= left {
                left -= len;
                if drawing {
                    cur.push(b);
                }
                len = 0.0;
            } else {
                let t = left / len;
                let c = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
                if drawing {
                    cur.push(c);
                    out.push(std::mem::take(&mut cur));
                } else {
                    cur = vec![c];
                }
                drawing = !drawing;
                len -= left;
                a = c;
                left = if drawing { on } else { off };
            }
        }
    }
    if drawing && cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// A polyline in pixels, `width` pixels wide: anti-aliased in PNG. A polyline of axis-parallel
/// segments (frame, ticks, grid lines) is snapped to whole pixels first (to pixel centres for
/// an odd width, to pixel edges for an even one), so that it is drawn sharp.
pub(super) fn draw_polyline<DB: DrawingBackend>(
    area: &Area<DB>,
    pts: &[(f64, f64)],
    color: RGBAColor,
    width: f64,
    m: &Metrics,
) -> Draw<()> {
    if pts.len() < 2 {
        return Ok(());
    }
    if !m.aa {
        let v: Vec<(i32, i32)> = pts.iter().copied().map(ipt).collect();
        return area
            .draw(&PathElement::new(
                v,
                color.stroke_width(width.round().max(1.0) as u32),
            ))
            .map_err(err);
    }
    let axis_parallel = pts.windows(2).all(|w| w[0].0 == w[1].0 || w[0].1 == w[1].1);
    if axis_parallel {
        let width = width.round().max(1.0);
        let offset = if width as i64 % 2 == 0 { 0.5 } else { 0.0 };
        let snap = |v: f64| (v - offset).round() + offset;
        let snapped: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (snap(x), snap(y))).collect();
        return paint(area, color, |put| raster::stroke(&snapped, width, put));
    }
    paint(area, color, |put| raster::stroke(pts, width, put))
}

/// A closed polygon in pixels, filled: anti-aliased in PNG.
pub(super) fn fill_polygon<DB: DrawingBackend>(
    area: &Area<DB>,
    poly: &[(f64, f64)],
    color: RGBAColor,
    m: &Metrics,
) -> Draw<()> {
    if poly.len() < 3 {
        return Ok(());
    }
    if m.aa {
        paint(area, color, |put| raster::fill(poly, put))
    } else {
        let v: Vec<(i32, i32)> = poly.iter().copied().map(ipt).collect();
        area.draw(&Polygon::new(v, color.filled())).map_err(err)
    }
}

/// A filled disc of radius `r` pixels: anti-aliased in PNG.
fn fill_disc<DB: DrawingBackend>(
    area: &Area<DB>,
    c: (f64, f64),
    r: f64,
    color: RGBAColor,
    m: &Metrics,
) -> Draw<()> {
    if m.aa {
        paint(area, color, |put| raster::disc(c, r, put))
    } else {
        area.draw(&Circle::new(ipt(c), r.round() as i32, color.filled()))
            .map_err(err)
    }
}

/// A circle of radius `r` pixels drawn `width` pixels wide: anti-aliased in PNG.
pub(super) fn draw_ring<DB: DrawingBackend>(
    area: &Area<DB>,
    c: (f64, f64),
    r: f64,
    width: f64,
    color: RGBAColor,
    m: &Metrics,
) -> Draw<()> {
    if m.aa {
        paint(area, color, |put| raster::ring(c, r, width, put))
    } else {
        area.draw(&Circle::new(
            ipt(c),
            r.round() as i32,
            color.stroke_width(width.round().max(1.0) as u32),
        ))
        .map_err(err)
    }
}

pub(super) fn draw_styled_line<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    points: &[(f64, f64)],
    style: Style,
    color: RGBColor,
    m: &Metrics,
) -> Draw<()> {
    for run in pixel_runs(frame, points) {
        draw_pixel_line(area, &run, style, color, m)?;
    }
    Ok(())
}

/// Draw a polyline given in pixels in a line style (solid, dashed, dotted, jump arrow).
pub(super) fn draw_pixel_line<DB: DrawingBackend>(
    area: &Area<DB>,
    run: &[(f64, f64)],
    style: Style,
    color: RGBColor,
    m: &Metrics,
) -> Draw<()> {
    if run.len() < 2 {
        return Ok(());
    }
    let width = match style {
        Style::Jump | Style::Contour => 1.2 * m.s,
        _ => 2.0 * m.s,
    };
    let c = color.to_rgba();
    // The anti-aliased strokes have round caps, which lengthen each dash by the line's width:
    // the dashes are shortened by as much, so that the pattern looks as specified (dots of the
    // dotted style become round dots).
    let pattern = |on: f64, off: f64| {
        let (on, off) = (on * m.s, off * m.s);
        if m.aa {
            let shown = (on - width).max(0.05 * m.s);
            (shown, off + on - shown)
        } else {
            (on, off)
        }
    };
    match style {
        Style::Stable | Style::Contour => draw_polyline(area, run, c, width, m)?,
        Style::Unstable | Style::Dashed => {
            let (on, off) = pattern(9.0, 6.0);
            for d in dash(run, on, off) {
                draw_polyline(area, &d, c, width, m)?;
            }
        }
        Style::Reference => {
            let (on, off) = pattern(2.5, 4.0);
            for d in dash(run, on, off) {
                draw_polyline(area, &d, c, width, m)?;
            }
        }
        Style::Jump => {
            let (on, off) = pattern(4.0, 3.0);
            for d in dash(run, on, off) {
                draw_polyline(area, &d, c, width, m)?;
            }
            let n = run.len();
            draw_arrow_head(area, run[n - 2], run[n - 1], color, m)?;
        }
        Style::Scatter | Style::ErrorBar => {}
    }
    Ok(())
}

pub(super) fn draw_arrow_head<DB: DrawingBackend>(
    area: &Area<DB>,
    from: (f64, f64),
    to: (f64, f64),
    color: RGBColor,
    m: &Metrics,
) -> Draw<()> {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = (dx * dx + dy * dy).sqrt();
    if len < 1e-9 {
        return Ok(());
    }
    let (ux, uy) = (dx / len, dy / len);
    let size = 9.0 * m.s;
    let base = (to.0 - ux * size, to.1 - uy * size);
    let half = 0.45 * size;
    let p1 = (base.0 - uy * half, base.1 + ux * half);
    let p2 = (base.0 + uy * half, base.1 - ux * half);
    fill_polygon(area, &[to, p1, p2], color.to_rgba(), m)
}

pub(super) fn draw_marker<DB: DrawingBackend>(
    area: &Area<DB>,
    p: (f64, f64),
    shape: MarkerShape,
    color: RGBColor,
    m: &Metrics,
) -> Draw<()> {
    let r = 6.0 * m.s;
    let (x, y) = p;
    let w = (1.6 * m.s).round().max(1.0);
    let outline = m.s.round().max(1.0);
    let closed = |pts: &[(f64, f64)]| {
        let mut v = pts.to_vec();
        v.push(pts[0]);
        v
    };
    match shape {
        MarkerShape::PullIn => {
            let pts = [(x, y - r * 1.1), (x - r, y + r * 0.75), (x + r, y + r * 0.75)];
            fill_polygon(area, &pts, color.to_rgba(), m)?;
            draw_polyline(area, &closed(&pts), BLACK.to_rgba(), outline, m)
        }
        MarkerShape::PullOff => {
            let (a, b) = (r * 0.85, r * 0.85);
            let pts = [(x - a, y - b), (x + a, y - b), (x + a, y + b), (x - a, y + b)];
            fill_polygon(area, &pts, color.to_rgba(), m)?;
            draw_polyline(area, &closed(&pts), BLACK.to_rgba(), outline, m)
        }
        MarkerShape::StableState => fill_disc(area, p, r * 0.8, color.to_rgba(), m),
        MarkerShape::UnstableState => {
            fill_disc(area, p, r * 0.8, WHITE.to_rgba(), m)?;
            draw_ring(area, p, r * 0.8, w, color.to_rgba(), m)
        }
        MarkerShape::Point => {
            let pts = [(x, y - r), (x + r, y), (x, y + r), (x - r, y)];
            fill_polygon(area, &pts, color.to_rgba(), m)
        }
        MarkerShape::Cross => {
            let d = r * 0.7;
            draw_polyline(area, &[(x - d, y - d), (x + d, y + d)], color.to_rgba(), w, m)?;
            draw_polyline(area, &[(x - d, y + d), (x + d, y - d)], color.to_rgba(), w, m)
        }
    }
}

/// Hatch angle of palette colour `c`: overlapping regions of different colours are hatched
/// in different directions, so each stays readable.
pub(super) fn hatch_angle(c: usize) -> f64 {
    const ANGLES: [f64; 4] = [45.0, -45.0, 0.0, 90.0];
    ANGLES[c % ANGLES.len()].to_radians()
}

/// Segments of the lines `p·n = s` (n the normal of direction `angle`, s on a grid of
/// `spacing`) inside the closed polygon `poly`, by the even-odd rule.
pub(super) fn hatch_segments(poly: &[(f64, f64)], angle: f64, spacing: f64) -> Vec<((f64, f64), (f64, f64))> {
    let (dx, dy) = (angle.cos(), angle.sin());
    let (nx, ny) = (-dy, dx);
    let proj = |p: (f64, f64)| p.0 * nx + p.1 * ny;
    let lo = poly.iter().map(|&p| proj(p)).fold(f64::INFINITY, f64::min);
    let hi = poly.iter().map(|&p| proj(p)).fold(f64::NEG_INFINITY, f64::max);
    let mut out = Vec::new();
    if !(lo.is_finite() && hi.is_finite() && spacing > 0.0) {
        return out;
    }
    let mut s = (lo / spacing).floor() * spacing + 0.5 * spacing;
    while s < hi {
        let mut cuts: Vec<(f64, (f64, f64))> = Vec::new();
        for k in 0..poly.len() {
            let a = poly[k];
            let b = poly[(k + 1) % poly.len()];
            let (da, db) = (proj(a) - s, proj(b) - s);
            if (da < 0.0) != (db < 0.0) {
                let t = da / (da - db);
                let q = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
                cuts.push((q.0 * dx + q.1 * dy, q));
            }
        }
        cuts.sort_by(|u, v| u.0.total_cmp(&v.0));
        for pair in cuts.chunks_exact(2) {
            out.push((pair[0].1, pair[1].1));
        }
        s += spacing;
    }
    out
}

/// A region as an outline with hatching in its colour.
pub(super) fn draw_hatched<DB: DrawingBackend>(
    area: &Area<DB>,
    poly: &[(f64, f64)],
    color: RGBColor,
    c: usize,
    m: &Metrics,
) -> Draw<()> {
    let thin = 0.8 * m.s;
    for (a, b) in hatch_segments(poly, hatch_angle(c), 7.0 * m.s) {
        draw_polyline(area, &[a, b], color.mix(0.55), thin, m)?;
    }
    let mut closed = poly.to_vec();
    closed.push(poly[0]);
    draw_polyline(area, &closed, color.mix(0.8), m.s, m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dashes_cover_about_the_on_fraction_of_a_line() {
        let run = vec![(0.0, 0.0), (150.0, 0.0)];
        let d = dash(&run, 10.0, 5.0);
        let drawn: f64 = d.iter().map(|s| s.last().unwrap().0 - s[0].0).sum();
        assert!((drawn - 100.0).abs() < 1e-9, "{drawn}");
    }
}
