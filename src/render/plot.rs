//! PNG and SVG figures through plotters, drawn in pixel space so that both backends give the
//! same picture: axes with ticks and units, log scales, solid/dashed/dotted lines, instability
//! markers, shaded loops, arrows, heat maps with a colour bar, contour lines, and a legend placed
//! where it covers no data (`plot/legend.rs`).
//!
//! In PNG every line, marker and fill is anti-aliased ([`crate::render::raster`], through
//! `plot/draw.rs`) and every text (titles, axis and tick labels, legends, colour-bar and contour
//! labels) is laid out in the math markup of [`crate::render::text`] with the embedded DejaVu
//! Sans (kerned, sub- and superscripts, Greek) and rasterised with anti-aliased coverage; in SVG
//! the same texts are `<text>` elements with `<tspan>`s. Figures render on machines without
//! system fonts.

mod draw;
mod heat;
mod legend;

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use self::draw::{
    Anchor, Baseline, Label, draw_arrow_head, draw_hatched, draw_label, draw_marker, draw_polyline,
    draw_ring, draw_styled_line, fill_polygon, pixel_runs,
};
pub use self::heat::viridis;
use self::heat::{draw_heat, draw_heat_raster, embed_images};
pub use self::legend::{PanelLayout, panel_layouts};
use self::legend::{draw_legend, plan_legend};
use super::axes::{padded_range, ticks};
use crate::error::{Error, Result};
use crate::figure::{FieldKind, Figure, Panel, Scale, Style};

/// The colour palette (Okabe-Ito, colour-blind safe, plus neutrals). Index with
/// [`palette`]; indices wrap around.
pub const PALETTE: [(u8, u8, u8); 10] = [
    (0, 114, 178),   // blue
    (213, 94, 0),    // vermillion
    (0, 158, 115),   // bluish green
    (204, 121, 167), // reddish purple
    (230, 159, 0),   // orange
    (86, 180, 233),  // sky blue
    (140, 86, 75),   // brown
    (0, 0, 0),       // black
    (128, 128, 128), // grey
    (188, 189, 34),  // olive
];

/// Palette colour `k` (wrapping).
pub fn palette(k: usize) -> (u8, u8, u8) {
    PALETTE[k % PALETTE.len()]
}

/// Size of one panel in pixels at scale 1.
const PANEL_W: f64 = 620.0;
const PANEL_H: f64 = 460.0;

/// Layout constants at scale 1 (pixels), and for SVG output the raster images of the fields.
struct Metrics {
    s: f64,
    /// `Some` when drawing SVG: the heat maps go in as embedded PNG images, collected here.
    images: Option<std::rc::Rc<std::cell::RefCell<Vec<String>>>>,
    /// `Some` when drawing SVG: the labels in math markup, as `<text>` elements with
    /// `<tspan>`s, appended after the drawing.
    texts: Option<std::rc::Rc<std::cell::RefCell<Vec<String>>>>,
    /// Rasterise strokes and fills here with anti-aliasing (PNG); `false` hands them to the
    /// backend as shapes (SVG).
    aa: bool,
}

impl Metrics {
    /// The metrics of a PNG drawn at scale `s`.
    fn png(s: f64) -> Self {
        Self {
            s,
            images: None,
            texts: None,
            aa: true,
        }
    }
    fn px(&self, v: f64) -> i32 {
        (v * self.s).round() as i32
    }
    fn font(&self, size: f64) -> f64 {
        size * self.s
    }
}

/// Grid of panels: columns and rows.
fn grid(n: usize) -> (usize, usize) {
    match n {
        0 | 1 => (1, 1),
        2 => (2, 1),
        3 => (3, 1),
        4 => (2, 2),
        n => (3, n.div_ceil(3)),
    }
}

/// Left edge, row and width of panel `k` of `n` (panel width `pw`): the grid of [`grid`],
/// with the panels of a short last row widened to fill it, so that no slot stays empty.
fn panel_slot(n: usize, k: usize, pw: i32) -> (i32, i32, i32) {
    let (cols, _) = grid(n);
    let (c, r) = (k % cols, k / cols);
    let in_last = n - (n / cols) * cols;
    if in_last > 0 && k >= n - in_last {
        let w = pw * cols as i32 / in_last as i32;
        (c as i32 * w, r as i32, w)
    } else {
        (c as i32 * pw, r as i32, pw)
    }
}

/// Pixel size of a figure at scale `s`: the grid of panels, each row as tall as a panel plus
/// the notes written under a panel of the row, if any, and the title.
pub fn figure_size(fig: &Figure, s: f64) -> (u32, u32) {
    let (c, _) = grid(fig.panels.len());
    let m = Metrics::png(s);
    let title_h = if fig.title.is_empty() { 0 } else { m.px(44.0) };
    let rows: i32 = row_heights(fig, &m).iter().sum();
    (
        (PANEL_W * c as f64 * s).round() as u32,
        (rows + title_h).max(1) as u32,
    )
}

/// The height of each row of panels in pixels: a panel's, plus the room the notes written
/// under a panel of the row take beyond it.
fn row_heights(fig: &Figure, m: &Metrics) -> Vec<i32> {
    let (pw, ph) = (m.px(PANEL_W), m.px(PANEL_H));
    let mut rows: Vec<i32> = Vec::new();
    for (k, panel) in fig.panels.iter().enumerate() {
        let (_, r, w) = panel_slot(fig.panels.len(), k, pw);
        let r = r as usize;
        if rows.len() <= r {
            rows.resize(r + 1, ph);
        }
        let extra = panel_frame(panel, f64::from(w), f64::from(ph), m).map_or(0.0, |(frame, bar, _)| {
            let (_, boxes) = plan_legend(panel, frame, &panel.series_colors(), m, f64::from(w), bar);
            boxes
                .iter()
                .filter(|b| b.is_footer())
                .map(|b| b.bottom() + 8.0 * m.s - f64::from(ph))
                .fold(0.0, f64::max)
        });
        rows[r] = rows[r].max(ph + extra.ceil() as i32);
    }
    if rows.is_empty() {
        rows.push(ph);
    }
    rows
}

/// Render to PNG bytes at twice the nominal size (1240 × 1008 pixels for one panel: 300 dpi
/// at about 10.5 cm wide), in memory.
///
/// # Errors
/// [`Error::Render`] when drawing or encoding fails.
pub fn png_bytes(fig: &Figure) -> Result<Vec<u8>> {
    let scale = 2.0;
    let (w, h) = figure_size(fig, scale);
    let render_error = |message: String| Error::Render {
        format: "png",
        message,
    };
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_png(&root, fig, scale).map_err(render_error)?;
        root.present().map_err(|e| render_error(e.to_string()))?;
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| render_error(e.to_string()))?;
        writer
            .write_image_data(&rgb)
            .map_err(|e| render_error(e.to_string()))?;
    }
    Ok(out)
}

/// Render to a PNG file at `path` ([`png_bytes`]), atomically.
///
/// # Errors
/// As [`png_bytes`], plus [`Error::File`].
pub fn write_png(fig: &Figure, path: &Path) -> Result<()> {
    super::write_atomic(path, &png_bytes(fig)?)
}

/// Render to an SVG document in memory.
///
/// # Errors
/// [`Error::Render`] when drawing fails.
pub fn svg_string(fig: &Figure) -> Result<String> {
    let mut out = String::new();
    let images = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let texts = std::rc::Rc::new(std::cell::RefCell::new(Vec::<String>::new()));
    {
        // Drawn at 2x so that the integer coordinates of the SVG backend resolve half a
        // nominal pixel; viewers scale the vector image freely.
        let scale = 2.0;
        let size = figure_size(fig, scale);
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        let m = Metrics {
            s: scale,
            images: Some(std::rc::Rc::clone(&images)),
            texts: Some(std::rc::Rc::clone(&texts)),
            aa: false,
        };
        draw_with(&root, fig, m).map_err(|message| Error::Render {
            format: "svg",
            message,
        })?;
        root.present().map_err(|e| Error::Render {
            format: "svg",
            message: e.to_string(),
        })?;
    }
    let out = embed_images(&out, &images.borrow());
    let labels: String = texts.borrow().iter().map(|t| format!("{t}\n")).collect();
    Ok(match out.rfind("</svg>") {
        Some(end) => format!("{}{labels}{}", &out[..end], &out[end..]),
        None => out,
    })
}

/// Render to an SVG file, atomically.
///
/// # Errors
/// As [`svg_string`], plus I/O errors.
pub fn write_svg(fig: &Figure, path: &Path) -> Result<()> {
    let text = svg_string(fig)?;
    super::write_atomic(path, text.as_bytes())
}

type Area<DB> = DrawingArea<DB, Shift>;
type Draw<T> = std::result::Result<T, String>;

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Draw the whole figure onto `root` as a PNG at scale `s`.
fn draw_png<DB: DrawingBackend>(root: &Area<DB>, fig: &Figure, s: f64) -> Draw<()> {
    draw_with(root, fig, Metrics::png(s))
}

/// Draw the whole figure onto `root` with the given metrics.
fn draw_with<DB: DrawingBackend>(root: &Area<DB>, fig: &Figure, m: Metrics) -> Draw<()> {
    root.fill(&WHITE).map_err(err)?;
    let (w, _) = root.dim_in_pixel();
    let mut top = 0;
    if !fig.title.is_empty() {
        let size = fitting_size(&fig.title, m.font(19.0), true, f64::from(w) - 24.0 * m.s);
        draw_label(
            root,
            Label::new(&fig.title, size).bold(),
            (f64::from(w) / 2.0, 24.0 * m.s),
            (Anchor::Middle, Baseline::Center),
            &m,
        )?;
        top = m.px(44.0);
    }
    let pw = m.px(PANEL_W);
    let rows = row_heights(fig, &m);
    for (k, panel) in fig.panels.iter().enumerate() {
        let (x, y, w) = panel_slot(fig.panels.len(), k, pw);
        let above: i32 = rows[..y as usize].iter().sum();
        let area = root
            .clone()
            .shrink((x, top + above), (w as u32, rows[y as usize] as u32));
        draw_panel(&area, panel, &m)?;
    }
    Ok(())
}

/// Pixel mapping of a panel's plotting rectangle.
#[derive(Debug, Clone, Copy)]
struct Frame {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// Data ranges (log10 for log axes).
    xr: (f64, f64),
    yr: (f64, f64),
    xlog: bool,
    ylog: bool,
}

impl Frame {
    fn tx(&self, x: f64) -> Option<f64> {
        let v = if self.xlog {
            if x <= 0.0 {
                return None;
            }
            x.log10()
        } else {
            x
        };
        v.is_finite()
            .then(|| self.x0 + (v - self.xr.0) / (self.xr.1 - self.xr.0) * (self.x1 - self.x0))
    }
    fn ty(&self, y: f64) -> Option<f64> {
        let v = if self.ylog {
            if y <= 0.0 {
                return None;
            }
            y.log10()
        } else {
            y
        };
        v.is_finite()
            .then(|| self.y1 - (v - self.yr.0) / (self.yr.1 - self.yr.0) * (self.y1 - self.y0))
    }
    fn map(&self, p: (f64, f64)) -> Option<(f64, f64)> {
        Some((self.tx(p.0)?, self.ty(p.1)?))
    }
    fn inside(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 - 0.5 && p.0 <= self.x1 + 0.5 && p.1 >= self.y0 - 0.5 && p.1 <= self.y1 + 0.5
    }
    /// Clip a segment to the frame (Liang-Barsky).
    fn clip(&self, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let mut t0: f64 = 0.0;
        let mut t1: f64 = 1.0;
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1).then_some(((a.0 + t0 * dx, a.1 + t0 * dy), (a.0 + t1 * dx, a.1 + t1 * dy)))
    }
}

fn ipt(p: (f64, f64)) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}
/// The outer edges of the cells centred on the grid values `g` (half a spacing beyond the first
/// and the last, geometric on a log axis); `None` for fewer than two values.
fn cell_edges(g: &[f64], scale: Scale) -> Option<(f64, f64)> {
    let (&a, &b) = (g.first()?, g.last()?);
    let (&a1, &b1) = (g.get(1)?, g.get(g.len() - 2)?);
    match scale {
        Scale::Linear => Some((a - 0.5 * (a1 - a), b + 0.5 * (b - b1))),
        Scale::Log if a > 0.0 && a1 > 0.0 && b1 > 0.0 => Some((a * (a / a1).sqrt(), b * (b / b1).sqrt())),
        Scale::Log => None,
    }
}

/// The plotting frame of a panel of size `w` × `h` pixels before the legend is placed, and
/// whether it has a colour bar; `None` when there is nothing to draw.
fn panel_frame(panel: &Panel, w: f64, h: f64, m: &Metrics) -> Option<(Frame, bool, [f64; 4])> {
    let has_bar = panel.field.as_ref().is_some_and(|f| {
        matches!(f.kind, FieldKind::Heat) || matches!(f.kind, FieldKind::Contour { filled: true, .. })
    });
    let frame_box = (
        92.0 * m.s,
        w - if has_bar { 110.0 } else { 24.0 } * m.s,
        (if panel.title.is_empty() && panel.label.is_empty() {
            14.0
        } else {
            38.0
        }) * m.s,
        h - 66.0 * m.s,
    );
    let ((xlo, xhi), (ylo, yhi)) = panel.data_bounds()?;
    // A colour map fills its frame (as far as its cells reach), unless something drawn over
    // it reaches beyond; other panels get margins.
    let filled = panel.field.as_ref().filter(|_| has_bar);
    let auto = |lo: f64, hi: f64, scale: Scale, grid: Option<&[f64]>| match grid
        .and_then(|g| cell_edges(g, scale))
    {
        Some((a, b)) if lo >= a && hi <= b => (a, b),
        _ => padded_range(lo, hi, scale),
    };
    let (xa, xb) = panel
        .x
        .range
        .unwrap_or_else(|| auto(xlo, xhi, panel.x.scale, filled.map(|f| f.x.as_slice())));
    let (ya, yb) = panel
        .y
        .range
        .unwrap_or_else(|| auto(ylo, yhi, panel.y.scale, filled.map(|f| f.y.as_slice())));
    let xlog = panel.x.scale == Scale::Log;
    let ylog = panel.y.scale == Scale::Log;
    let tr = |v: f64, log: bool| if log { v.max(1e-300).log10() } else { v };
    let mut frame_box = frame_box;
    if panel.equal_aspect && !xlog && !ylog {
        // Shrink the longer side so that one data unit has one length on both axes.
        let (fw, fh) = (frame_box.1 - frame_box.0, frame_box.3 - frame_box.2);
        let (dx, dy) = (xb - xa, yb - ya);
        if dx > 0.0 && dy > 0.0 {
            let unit = (fw / dx).min(fh / dy);
            let (nw, nh) = (unit * dx, unit * dy);
            frame_box.0 += 0.5 * (fw - nw);
            frame_box.1 = frame_box.0 + nw;
            frame_box.2 += 0.5 * (fh - nh);
            frame_box.3 = frame_box.2 + nh;
        }
    }
    Some((
        Frame {
            x0: frame_box.0,
            x1: frame_box.1,
            y0: frame_box.2,
            y1: frame_box.3,
            xr: (tr(xa, xlog), tr(xb, xlog)),
            yr: (tr(ya, ylog), tr(yb, ylog)),
            xlog,
            ylog,
        },
        has_bar,
        [xa, xb, ya, yb],
    ))
}

fn draw_panel<DB: DrawingBackend>(area: &Area<DB>, panel: &Panel, m: &Metrics) -> Draw<()> {
    // The frame is laid out in a panel of the nominal height; notes under it extend the area.
    let (w, h) = (f64::from(area.dim_in_pixel().0), f64::from(m.px(PANEL_H)));
    let Some((frame, has_bar, [xa, xb, ya, yb])) = panel_frame(panel, w, h, m) else {
        return draw_label(
            area,
            Label::new("no data", m.font(14.0)),
            (w / 2.0, h / 2.0),
            (Anchor::Middle, Baseline::Center),
            m,
        );
    };
    if !(frame.xr.1 > frame.xr.0 && frame.yr.1 > frame.yr.0) {
        return Err(format!("empty axis range in panel `{}`", panel.title));
    }
    let colors = panel.series_colors();
    let (frame, legend_boxes) = plan_legend(panel, frame, &colors, m, w, has_bar);
    let grey = RGBColor(225, 225, 225);

    // Field first.
    let mut bar_range = None;
    if let Some(field) = &panel.field {
        let filled = match &field.kind {
            FieldKind::Heat => true,
            FieldKind::Contour { filled, .. } => *filled,
        };
        if filled && let Some(range) = field.value_range() {
            if let Some(images) = &m.images {
                draw_heat_raster(area, &frame, field, range, images)?;
            } else {
                draw_heat(area, &frame, field, range)?;
            }
            bar_range = Some(range);
        }
    }

    // Grid.
    let xt = ticks(xa, xb, panel.x.scale, 6);
    let yt = ticks(ya, yb, panel.y.scale, 6);
    if panel.field.is_none() {
        for &v in &xt.values {
            if let Some(px) = frame.tx(v) {
                draw_polyline(area, &[(px, frame.y0), (px, frame.y1)], grey.to_rgba(), 1.0, m)?;
            }
        }
        for &v in &yt.values {
            if let Some(py) = frame.ty(v) {
                draw_polyline(area, &[(frame.x0, py), (frame.x1, py)], grey.to_rgba(), 1.0, m)?;
            }
        }
    }

    // Regions.
    let mut next_color = colors.iter().copied().max().map_or(0, |c| c + 1);
    for region in &panel.regions {
        let c = region.color.unwrap_or_else(|| {
            next_color += 1;
            next_color - 1
        });
        let poly: Vec<(f64, f64)> = region
            .points
            .iter()
            .filter_map(|&p| frame.map(p))
            .map(|(x, y)| (x.clamp(frame.x0, frame.x1), y.clamp(frame.y0, frame.y1)))
            .collect();
        if poly.len() >= 3 {
            if region.hatched {
                draw_hatched(area, &poly, rgb(palette(c)), c, m)?;
            } else {
                fill_polygon(area, &poly, rgb(palette(c)).mix(0.18), m)?;
            }
        }
    }

    if let Some(field) = &panel.field {
        let boxes: Vec<_> = legend_boxes.iter().map(|b| b.rect()).collect();
        draw_contours(area, &frame, field, bar_range.is_some(), &boxes, m)?;
    }

    // Series.
    for (series, &c) in panel.series.iter().zip(&colors) {
        let color = rgb(palette(c));
        match series.style {
            Style::Scatter => {
                for &p in &series.points {
                    // Open circles: the lines under many data points stay visible.
                    if let Some(q) = frame.map(p).filter(|q| frame.inside(*q)) {
                        draw_ring(area, q, 3.4 * m.s, 1.3 * m.s, color.to_rgba(), m)?;
                    }
                }
            }
            Style::ErrorBar => {
                for pair in series.points.chunks(2) {
                    if let [lo, hi] = pair
                        && let (Some(a), Some(b)) = (frame.map(*lo), frame.map(*hi))
                        && let Some((a, b)) = frame.clip(a, b)
                    {
                        let cap = 4.0 * m.s;
                        let wdt = (1.3 * m.s).round().max(1.0);
                        let c = color.to_rgba();
                        draw_polyline(area, &[a, b], c, wdt, m)?;
                        draw_polyline(area, &[(a.0 - cap, a.1), (a.0 + cap, a.1)], c, wdt, m)?;
                        draw_polyline(area, &[(b.0 - cap, b.1), (b.0 + cap, b.1)], c, wdt, m)?;
                    }
                }
            }
            style => draw_styled_line(area, &frame, &series.points, style, color, m)?,
        }
    }

    // Arrows.
    for arrow in &panel.arrows {
        let color = rgb(palette(arrow.color.unwrap_or(7)));
        if let (Some(a), Some(b)) = (frame.map(arrow.from), frame.map(arrow.to)) {
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = (dx * dx + dy * dy).sqrt();
            // Very short arrows (direction marks) get a visible head of fixed size.
            let b = if len < 14.0 * m.s && len > 0.0 {
                (a.0 + dx / len * 14.0 * m.s, a.1 + dy / len * 14.0 * m.s)
            } else {
                b
            };
            if frame.inside(a) || frame.inside(b) {
                draw_polyline(area, &[a, b], color.to_rgba(), 1.4 * m.s, m)?;
                draw_arrow_head(area, a, b, color, m)?;
            }
        }
    }

    // Markers and their labels.
    for marker in &panel.markers {
        let color = rgb(palette(panel.marker_color(marker, &colors).unwrap_or(7)));
        if let Some(p) = frame.map((marker.x, marker.y)).filter(|p| frame.inside(*p)) {
            draw_marker(area, p, marker.shape, color, m)?;
            if let Some(label) = &marker.label {
                draw_label(
                    area,
                    Label::new(label, m.font(14.0)).bold(),
                    (p.0 + 7.0 * m.s, p.1 - 5.0 * m.s),
                    (Anchor::Start, Baseline::Bottom),
                    m,
                )?;
            }
        }
    }

    draw_axes(area, panel, &frame, (&xt, &yt), m)?;
    if let (Some(range), Some(field)) = (bar_range, &panel.field) {
        draw_colour_bar(area, &frame, field, range, m)?;
    }
    for plan in &legend_boxes {
        draw_legend(area, plan, m)?;
    }
    Ok(())
}

/// The contour lines of a field, each level labelled once at the middle of its longest line;
/// the highlighted levels (a measured value) thicker, in red, with their own label. A label
/// that would overlap one already drawn, or the legend's boxes `covered` (left, top, right,
/// bottom), is left out.
fn draw_contours<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    field: &crate::figure::Field,
    over_colours: bool,
    covered: &[(f64, f64, f64, f64)],
    m: &Metrics,
) -> Draw<()> {
    let highlight: Vec<f64> = field.highlight.iter().map(|(l, _)| *l).collect();
    let mut levels = field.contour_levels();
    // Highlighted levels label first: their labels win where two would overlap.
    levels.sort_by_key(|l| !highlight.contains(l));
    let mut taken: Vec<(f64, f64, f64, f64)> = covered.to_vec();
    for level in levels {
        let emphasised = highlight.contains(&level);
        let color = if emphasised {
            RGBColor(200, 0, 0)
        } else if over_colours {
            WHITE
        } else {
            RGBColor(60, 60, 60)
        };
        let lines = field.contour(level);
        for line in &lines {
            for run in pixel_runs(frame, line) {
                let width = if emphasised { 2.6 } else { 1.0 } * m.s;
                draw_polyline(area, &run, color.to_rgba(), width, m)?;
            }
        }
        let Some(line) = lines.into_iter().max_by_key(Vec::len) else {
            continue;
        };
        let Some(p) = frame.map(line[line.len() / 2]).filter(|p| frame.inside(*p)) else {
            continue;
        };
        let text = field.highlight.iter().find(|(l, _)| *l == level).map_or_else(
            || tick_markup(&super::axes::format_number(level)),
            |(_, t)| t.clone(),
        );
        let label = Label::new(&text, m.font(if emphasised { 13.0 } else { 11.0 })).color(color);
        let label = if emphasised { label.bold() } else { label };
        // Right of the point, or left of it where the text would leave the frame.
        let x = (p.0 + 3.0 * m.s).min(frame.x1 - label.width() - 3.0 * m.s);
        let y = (p.1 - 2.0 * m.s).max(frame.y0 + 1.2 * label.size);
        let bbox = (x, y - 1.1 * label.size, x + label.width(), y);
        let overlaps =
            |b: &(f64, f64, f64, f64)| bbox.0 < b.2 && b.0 < bbox.2 && bbox.1 < b.3 && b.1 < bbox.3;
        if taken.iter().any(overlaps) {
            continue;
        }
        taken.push(bbox);
        if emphasised && over_colours {
            // A light ground keeps the measured level's label readable over the dark map.
            let pad = 2.0 * m.s;
            let ground = [
                (bbox.0 - pad, bbox.1 - pad),
                (bbox.2 + pad, bbox.1 - pad),
                (bbox.2 + pad, bbox.3 + pad),
                (bbox.0 - pad, bbox.3 + pad),
            ];
            fill_polygon(area, &ground, WHITE.mix(0.8), m)?;
        }
        draw_label(area, label, (x, y), (Anchor::Start, Baseline::Bottom), m)?;
    }
    Ok(())
}

/// The frame, the ticks with their labels (math markup: powers of ten as superscripts) and the
/// axis titles and panel heading.
fn draw_axes<DB: DrawingBackend>(
    area: &Area<DB>,
    panel: &Panel,
    frame: &Frame,
    (xt, yt): (&super::axes::Ticks, &super::axes::Ticks),
    m: &Metrics,
) -> Draw<()> {
    let black = BLACK.to_rgba();
    let frame_pts = [
        (frame.x0, frame.y0),
        (frame.x1, frame.y0),
        (frame.x1, frame.y1),
        (frame.x0, frame.y1),
        (frame.x0, frame.y0),
    ];
    draw_polyline(area, &frame_pts, black, (1.2 * m.s).round().max(1.0), m)?;
    let tick_len = 6.0 * m.s;
    let tick_font = m.font(13.0);
    for (v, label) in xt.values.iter().zip(&xt.labels) {
        if let Some(px) = frame.tx(*v) {
            draw_polyline(area, &[(px, frame.y1), (px, frame.y1 - tick_len)], black, 1.0, m)?;
            draw_label(
                area,
                Label::new(&tick_markup(label), tick_font),
                (px, frame.y1 + 5.0 * m.s),
                (Anchor::Middle, Baseline::Top),
                m,
            )?;
        }
    }
    for v in &xt.minor {
        if let Some(px) = frame.tx(*v) {
            let tick = [(px, frame.y1), (px, frame.y1 - tick_len * 0.5)];
            draw_polyline(area, &tick, black, 1.0, m)?;
        }
    }
    let mut widest = 0.0f64;
    for (v, label) in yt.values.iter().zip(&yt.labels) {
        if let Some(py) = frame.ty(*v) {
            draw_polyline(area, &[(frame.x0, py), (frame.x0 + tick_len, py)], black, 1.0, m)?;
            let label = tick_markup(label);
            let label = Label::new(&label, tick_font);
            widest = widest.max(label.width());
            draw_label(
                area,
                label,
                (frame.x0 - 5.0 * m.s, py),
                (Anchor::End, Baseline::Center),
                m,
            )?;
        }
    }
    for v in &yt.minor {
        if let Some(py) = frame.ty(*v) {
            let tick = [(frame.x0, py), (frame.x0 + tick_len * 0.5, py)];
            draw_polyline(area, &tick, black, 1.0, m)?;
        }
    }
    let label_font = m.font(15.0);
    // The x-axis title under the tick labels; notes written under the panel come after it.
    draw_label(
        area,
        Label::new(&panel.x.title(), label_font),
        (0.5 * (frame.x0 + frame.x1), frame.y1 + 58.0 * m.s),
        (Anchor::Middle, Baseline::Bottom),
        m,
    )?;
    let yl_x = (frame.x0 - widest - 12.0 * m.s - label_font).max(4.0 * m.s);
    draw_label(
        area,
        Label::new(&panel.y.title(), label_font).vertical(),
        (yl_x, 0.5 * (frame.y0 + frame.y1)),
        (Anchor::Middle, Baseline::Top),
        m,
    )?;
    let heading = match (panel.label.is_empty(), panel.title.is_empty()) {
        (true, true) => String::new(),
        (false, true) => panel.label.clone(),
        (true, false) => panel.title.clone(),
        (false, false) => format!("{} {}", panel.label, panel.title),
    };
    if !heading.is_empty() {
        let room = f64::from(area.dim_in_pixel().0) - frame.x0 - 4.0 * m.s;
        let size = fitting_size(&heading, m.font(15.0), true, room);
        draw_label(
            area,
            Label::new(&heading, size).bold(),
            (frame.x0, frame.y0 - 8.0 * m.s),
            (Anchor::Start, Baseline::Bottom),
            m,
        )?;
    }
    Ok(())
}

/// The colour bar of a filled field right of the frame: the colour map, ticks with labels and
/// the field's name and unit as its title (math markup).
fn draw_colour_bar<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    field: &crate::figure::Field,
    (lo, hi): (f64, f64),
    m: &Metrics,
) -> Draw<()> {
    let bx0 = frame.x1 + 14.0 * m.s;
    let bx1 = bx0 + 16.0 * m.s;
    let steps = 64;
    for k in 0..steps {
        let t0 = k as f64 / steps as f64;
        let t1 = (k + 1) as f64 / steps as f64;
        let ya = frame.y1 - t0 * (frame.y1 - frame.y0);
        let yb = frame.y1 - t1 * (frame.y1 - frame.y0);
        area.draw(&Rectangle::new(
            [ipt((bx0, yb)), ipt((bx1, ya))],
            rgb(viridis(0.5 * (t0 + t1))).filled(),
        ))
        .map_err(err)?;
    }
    let outline = [
        (bx0, frame.y0),
        (bx1, frame.y0),
        (bx1, frame.y1),
        (bx0, frame.y1),
        (bx0, frame.y0),
    ];
    draw_polyline(area, &outline, BLACK.to_rgba(), 1.0, m)?;
    let bt = ticks(lo, hi, Scale::Linear, 5);
    for (v, label) in bt.values.iter().zip(&bt.labels) {
        let y = frame.y1 - (v - lo) / (hi - lo).max(f64::MIN_POSITIVE) * (frame.y1 - frame.y0);
        draw_polyline(area, &[(bx1, y), (bx1 + 4.0 * m.s, y)], BLACK.to_rgba(), 1.0, m)?;
        draw_label(
            area,
            Label::new(&tick_markup(label), m.font(11.0)),
            (bx1 + 6.0 * m.s, y),
            (Anchor::Start, Baseline::Center),
            m,
        )?;
    }
    let title = if field.unit.is_empty() {
        field.name.clone()
    } else {
        format!("{} [{}]", field.name, field.unit)
    };
    draw_label(
        area,
        Label::new(&title, m.font(11.0)),
        (0.5 * (bx0 + bx1) + 10.0 * m.s, frame.y0 - 6.0 * m.s),
        (Anchor::Middle, Baseline::Bottom),
        m,
    )
}

/// The text size, at most `size`, at which `text` is at most `room` pixels wide (never below
/// 70 % of `size`: a longer text runs over rather than turning unreadable).
fn fitting_size(text: &str, size: f64, bold: bool, room: f64) -> f64 {
    let w = crate::render::text::width(text, size, bold);
    if w <= room || w <= 0.0 {
        size
    } else {
        (size * room / w).max(0.7 * size)
    }
}

/// A tick label in math markup: a power of ten written with superscript digits (`10⁻²`) or in
/// e-notation (`1.5e-5`) becomes `10^{−2}`, `1.5×10^{−5}`; other labels are returned as they
/// are.
fn tick_markup(label: &str) -> String {
    const SUP: [(char, char); 12] = [
        ('⁰', '0'),
        ('¹', '1'),
        ('²', '2'),
        ('³', '3'),
        ('⁴', '4'),
        ('⁵', '5'),
        ('⁶', '6'),
        ('⁷', '7'),
        ('⁸', '8'),
        ('⁹', '9'),
        ('⁻', '−'),
        ('⁺', '+'),
    ];
    let plain = |c: char| SUP.iter().find(|(s, _)| *s == c).map(|(_, p)| *p);
    if let Some(k) = label.find(|c: char| plain(c).is_some()) {
        let exponent: String = label[k..].chars().filter_map(plain).collect();
        if exponent.chars().count() == label[k..].chars().count() {
            return format!("{}^{{{exponent}}}", &label[..k]);
        }
    }
    if let Some((mantissa, exponent)) = label.split_once('e')
        && let Ok(e) = exponent.parse::<i32>()
        && mantissa.parse::<f64>().is_ok()
    {
        let mantissa = mantissa.replace('-', "−");
        let power = format!("10^{{{}}}", e.to_string().replace('-', "−"));
        return if mantissa == "1" {
            power
        } else {
            format!("{mantissa}×{power}")
        };
    }
    label.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dark pixels of `text` drawn at baseline y = 60 from x = 10, 40 px, in the box
    /// `x0..x1` × `y0..y1` of a 200 × 100 white bitmap.
    fn ink(text: &str, x0: i32, x1: i32, y0: i32, y1: i32) -> usize {
        let (w, h) = (200u32, 100u32);
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            let m = Metrics::png(1.0);
            // Baseline at y = 60: anchor the top at 60 - ascent.
            draw_label(
                &root,
                Label::new(text, 40.0),
                (10.0, 60.0 - crate::render::text::ASCENT * 40.0),
                (Anchor::Start, Baseline::Top),
                &m,
            )
            .unwrap();
        }
        let mut n = 0;
        for y in y0.max(0)..y1.min(h as i32) {
            for x in x0.max(0)..x1.min(w as i32) {
                if rgb[((y as u32 * w + x as u32) * 3) as usize] < 128 {
                    n += 1;
                }
            }
        }
        n
    }

    /// The PNG of `fig` decoded: width, height and RGB bytes.
    fn decode(fig: &Figure) -> (usize, usize, Vec<u8>) {
        let bytes = png_bytes(fig).unwrap();
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        buf.truncate(info.buffer_size());
        (info.width as usize, info.height as usize, buf)
    }

    #[test]
    fn png_curves_are_anti_aliased() {
        // A black diagonal across the frame: in each pixel column it crosses, its two edges
        // leave pixels between white and black (partial coverage; the grid's grey is 225),
        // about two per column. Drawn without anti-aliasing there are none.
        let mut p = Panel::new(
            crate::figure::Axis::linear("x", "").with_range(0.0, 1.0),
            crate::figure::Axis::linear("y", "").with_range(0.0, 1.0),
        );
        p.legend = crate::figure::Legend::Hidden;
        p.add(crate::figure::Series::new("d", Style::Stable, vec![(0.1, 0.2), (0.9, 0.75)]).with_color(7));
        let fig = Figure::new("t", "").with_panel(p);
        let (w, h, rgb) = decode(&fig);
        let layout = &panel_layouts(&fig)[0].clone().unwrap();
        let (fx0, fx1, fy0, fy1) = layout.frame;
        let at = |x: f64| fy1 - (0.2 + (x - 0.1) / 0.8 * 0.55) * (fy1 - fy0);
        let (mut grey, mut rows) = (0, 0);
        for i in 0..200 {
            let x = 0.15 + 0.7 * f64::from(i) / 200.0;
            let px = (fx0 + x * (fx1 - fx0)).round() as usize;
            let py = at(x).round() as usize;
            rows += 1;
            for y in py.saturating_sub(6)..(py + 7).min(h) {
                let v = rgb[(y * w + px) * 3];
                if v > 20 && v < 215 {
                    grey += 1;
                }
            }
        }
        assert!(
            2 * grey >= 3 * rows,
            "{grey} intermediate pixels over {rows} columns"
        );
    }

    #[test]
    fn markup_renders_subscripts_below_and_hats_above_in_png() {
        // "x_2": the 2 is lowered below the baseline (y = 60); in "x2" it sits on it.
        let x_end = 10 + super::super::text::width("x", 40.0, false).ceil() as i32;
        let below_sub = ink("x_2", x_end, x_end + 30, 64, 100);
        let below_plain = ink("x2", x_end, x_end + 30, 64, 100);
        assert!(below_sub > 20 && below_plain == 0, "{below_sub} vs {below_plain}");
        // "\hat{P}": ink above the cap height of P (about 60 - 0.73 * 40 = 31).
        let above_hat = ink("\\hat{P}", 10, 40, 0, 28);
        let above_plain = ink("P", 10, 40, 0, 28);
        assert!(above_hat > 5 && above_plain == 0, "{above_hat} vs {above_plain}");
    }

    #[test]
    fn svg_labels_carry_tspans_with_a_baseline_shift() {
        let mut p = Panel::new(
            crate::figure::Axis::linear("σ_rms", "nm"),
            crate::figure::Axis::linear("m^4", ""),
        );
        p.line("a", Style::Stable, vec![(0.0, 0.0), (1.0, 1.0)]);
        let fig = Figure::new("t", "t").with_panel(p);
        let svg = svg_string(&fig).unwrap();
        assert!(
            svg.contains("<tspan baseline-shift=\"-31%\" font-size=\"70%\">rms</tspan>"),
            "{svg}"
        );
        assert!(svg.contains("font-size=\"70%\">4</tspan>"));
    }

    #[test]
    fn tick_labels_and_titles_use_the_markup_in_svg() {
        let mut p = Panel::new(
            crate::figure::Axis::log("α", ""),
            crate::figure::Axis::linear("y", ""),
        );
        p.line("a", Style::Stable, vec![(0.01, 0.0), (100.0, 1.0)]);
        let fig = Figure::new("t", "k_e = 2^-7 k_cr").with_panel(p);
        let svg = svg_string(&fig).unwrap();
        // 10⁻² as 10 with a raised −2, not as superscript glyphs.
        assert!(
            svg.contains("<tspan>10</tspan><tspan baseline-shift=\"51%\" font-size=\"70%\">−2</tspan>"),
            "{svg}"
        );
        assert!(!svg.contains('⁻'));
        assert!(svg.contains("font-weight=\"bold\"") && svg.contains("font-size=\"70%\">−7</tspan>"));
        // The x tick labels, with and without a superscript, share one baseline.
        let ys: std::collections::BTreeSet<&str> = svg
            .lines()
            .filter(|l| l.contains("text-anchor=\"middle\"") && l.contains("<tspan>10</tspan>"))
            .filter_map(|l| l.split("y=\"").nth(1)?.split('"').next())
            .collect();
        assert_eq!(ys.len(), 1, "{ys:?}");
        // No text is left to the backend's own font rendering.
        assert_eq!(
            svg.matches("<text").count(),
            svg.matches("DejaVu Sans, sans-serif").count()
        );
    }

    #[test]
    fn tick_labels_become_powers_of_ten_in_markup() {
        assert_eq!(tick_markup("10⁻²"), "10^{−2}");
        assert_eq!(tick_markup("10³"), "10^{3}");
        assert_eq!(tick_markup("1.50e-5"), "1.50×10^{−5}");
        assert_eq!(tick_markup("-2e5"), "−2×10^{5}");
        assert_eq!(tick_markup("1e-3"), "10^{−3}");
        assert_eq!(tick_markup("0.25"), "0.25");
        assert_eq!(tick_markup("−1"), "−1");
    }

    #[test]
    fn clipping_keeps_the_inside_part() {
        let f = Frame {
            x0: 0.0,
            x1: 10.0,
            y0: 0.0,
            y1: 10.0,
            xr: (0.0, 1.0),
            yr: (0.0, 1.0),
            xlog: false,
            ylog: false,
        };
        let (a, b) = f.clip((-5.0, 5.0), (15.0, 5.0)).unwrap();
        assert_eq!((a, b), ((0.0, 5.0), (10.0, 5.0)));
        assert!(f.clip((-5.0, -5.0), (-1.0, -1.0)).is_none());
    }
}
