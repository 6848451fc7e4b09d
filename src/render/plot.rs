//! PNG and SVG figures through plotters, drawn in pixel space so that both backends give the
//! same picture: axes with ticks and units, log scales, solid/dashed/dotted lines, instability
//! markers, shaded loops, arrows, heat maps with a colour bar, contour lines, and a legend placed
//! in the corner that covers the fewest data points.
//!
//! Text uses DejaVu Sans embedded in the binary (registered once as `sans-serif`), so figures
//! render on machines without system fonts.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontDesc, FontFamily, FontStyle, RGBAColor};

use super::axes::{padded_range, ticks};
use crate::error::{Error, Result};
use crate::figure::{Field, FieldKind, Figure, Legend, MarkerShape, Panel, Scale, Style};

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
}

/// Horizontal and vertical anchor of a label.
#[derive(Debug, Clone, Copy)]
enum Anchor {
    Start,
    Middle,
}

#[derive(Debug, Clone, Copy)]
enum Baseline {
    Top,
    Center,
    Bottom,
}

/// Draw a label in math markup ([`super::text`]) at `at` with the given anchors: in PNG laid
/// out and rasterised here (kerned, anti-aliased), in SVG as `<text>` with `<tspan>`s.
/// `vertical` turns it to read bottom to top (y-axis labels).
#[allow(clippy::too_many_arguments)]
fn draw_label<DB: DrawingBackend>(
    area: &Area<DB>,
    text: &str,
    at: (f64, f64),
    anchor: (Anchor, Baseline),
    size: f64,
    bold: bool,
    color: RGBColor,
    vertical: bool,
    m: &Metrics,
) -> Draw<()> {
    let l = super::text::layout(text, size, bold);
    let dx = match anchor.0 {
        Anchor::Start => 0.0,
        Anchor::Middle => -0.5 * l.width,
    };
    let base = match anchor.1 {
        Baseline::Top => l.ascent,
        Baseline::Center => 0.5 * (l.ascent - l.descent),
        Baseline::Bottom => -l.descent,
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
            super::text::svg_tspans(text)
        ));
        return Ok(());
    }
    let mut result = Ok(());
    super::text::rasterize(&l, |u, v, c| {
        let (x, y) = map(u, v);
        if result.is_ok() {
            result = area
                .draw_pixel((x.round() as i32, y.round() as i32), &color.mix(c))
                .map_err(err);
        }
    });
    result
}

impl Metrics {
    fn px(&self, v: f64) -> i32 {
        (v * self.s).round() as i32
    }
    fn font(&self, size: f64) -> f64 {
        size * self.s
    }
}

fn register_fonts() {
    static ONCE: OnceLock<()> = OnceLock::new();
    ONCE.get_or_init(|| {
        // The font bytes are valid TrueType shipped with the `dejavu` crate.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold());
        let _ = plotters::style::register_font("sans-serif", FontStyle::Italic, dejavu::sans::oblique());
    });
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

/// Pixel size of a figure at scale `s`.
pub fn figure_size(fig: &Figure, s: f64) -> (u32, u32) {
    let (c, r) = grid(fig.panels.len());
    let title_h = if fig.title.is_empty() { 0.0 } else { 44.0 };
    (
        (PANEL_W * c as f64 * s).round() as u32,
        ((PANEL_H * r as f64 + title_h) * s).round() as u32,
    )
}

/// Render to PNG bytes at twice the nominal size (1240 × 1008 pixels for one panel: 300 dpi
/// at about 10.5 cm wide), in memory.
///
/// # Errors
/// [`Error::Render`] when drawing or encoding fails.
pub fn png_bytes(fig: &Figure) -> Result<Vec<u8>> {
    register_fonts();
    let scale = 2.0;
    let (w, h) = figure_size(fig, scale);
    let render_error = |message: String| Error::Render {
        format: "png",
        message,
    };
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw(&root, fig, scale).map_err(render_error)?;
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
    register_fonts();
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

/// Replace the placeholder rectangles of the heat maps (fill `#0102kk`, k the image index) by
/// the embedded PNG images, at the rectangles' position and size.
fn embed_images(svg: &str, images: &[String]) -> String {
    let mut out = svg.to_string();
    for (k, href) in images.iter().enumerate() {
        let key = format!("fill=\"#0102{k:02X}\"");
        let Some(at) = out.find(&key) else { continue };
        let (Some(start), Some(end)) = (out[..at].rfind("<rect"), out[at..].find("/>")) else {
            continue;
        };
        let end = at + end + 2;
        let attr = |name: &str| -> String {
            let tag = &out[start..end];
            let pat = format!(" {name}=\"");
            tag.find(&pat)
                .and_then(|i| {
                    let v = &tag[i + pat.len()..];
                    v.find('"').map(|j| v[..j].to_string())
                })
                .unwrap_or_default()
        };
        let image = format!(
            "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" \
             style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{href}\"/>",
            attr("x"),
            attr("y"),
            attr("width"),
            attr("height")
        );
        out.replace_range(start..end, &image);
    }
    out
}

/// Standard base64 (RFC 4648) with padding.
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= c.len() {
                out.push(char::from(A[((n >> shift) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A heat map for SVG: rasterised at the frame's pixel size into a PNG that is embedded as an
/// `<image>` (one element instead of one rectangle per cell); a placeholder rectangle keeps its
/// place in the drawing order.
fn draw_heat_raster<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    field: &Field,
    range: (f64, f64),
    images: &std::cell::RefCell<Vec<String>>,
) -> Draw<()> {
    let w = (frame.x1 - frame.x0).round().max(1.0) as u32;
    let h = (frame.y1 - frame.y0).round().max(1.0) as u32;
    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let local = Frame {
            x0: 0.0,
            x1: f64::from(w),
            y0: 0.0,
            y1: f64::from(h),
            ..*frame
        };
        draw_heat(&root, &local, field, range)?;
        root.present().map_err(err)?;
    }
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_bytes, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Best);
        let mut writer = enc.write_header().map_err(err)?;
        writer.write_image_data(&rgb).map_err(err)?;
    }
    let k = images.borrow().len();
    if k > 255 {
        return Err("more than 256 heat maps in one figure".into());
    }
    images.borrow_mut().push(base64(&png_bytes));
    area.draw(&Rectangle::new(
        [ipt((frame.x0, frame.y0)), ipt((frame.x1, frame.y1))],
        RGBColor(1, 2, k as u8).filled(),
    ))
    .map_err(err)
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

fn text_style(size: f64, bold: bool, color: RGBColor) -> TextStyle<'static> {
    let style = if bold { FontStyle::Bold } else { FontStyle::Normal };
    FontDesc::new(FontFamily::SansSerif, size, style).color(&color)
}

/// Draw the whole figure onto `root`.
fn draw<DB: DrawingBackend>(root: &Area<DB>, fig: &Figure, s: f64) -> Draw<()> {
    draw_with(
        root,
        fig,
        Metrics {
            s,
            images: None,
            texts: None,
        },
    )
}

/// Draw the whole figure onto `root` with the given metrics.
fn draw_with<DB: DrawingBackend>(root: &Area<DB>, fig: &Figure, m: Metrics) -> Draw<()> {
    root.fill(&WHITE).map_err(err)?;
    let (w, _) = root.dim_in_pixel();
    let mut top = 0;
    if !fig.title.is_empty() {
        let style = text_style(m.font(19.0), true, BLACK).pos(Pos::new(HPos::Center, VPos::Center));
        root.draw_text(&fig.title, &style, (w as i32 / 2, m.px(24.0)))
            .map_err(err)?;
        top = m.px(44.0);
    }
    let pw = m.px(PANEL_W);
    let ph = m.px(PANEL_H);
    for (k, panel) in fig.panels.iter().enumerate() {
        let (x, y, w) = panel_slot(fig.panels.len(), k, pw);
        let area = root.clone().shrink((x, top + y * ph), (w as u32, ph as u32));
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

/// Map data points to pixel polylines, splitting at points that cannot be drawn (NaN, ≤ 0 on
/// log axes) and clipping to the frame.
fn pixel_runs(frame: &Frame, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
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
fn dash(run: &[(f64, f64)], on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
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

fn draw_polyline<DB: DrawingBackend>(
    area: &Area<DB>,
    pts: &[(f64, f64)],
    color: RGBAColor,
    width: u32,
) -> Draw<()> {
    if pts.len() < 2 {
        return Ok(());
    }
    let v: Vec<(i32, i32)> = pts.iter().copied().map(ipt).collect();
    area.draw(&PathElement::new(v, color.stroke_width(width)))
        .map_err(err)
}

fn draw_styled_line<DB: DrawingBackend>(
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
fn draw_pixel_line<DB: DrawingBackend>(
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
        Style::Jump | Style::Contour => m.px(1.2).max(1) as u32,
        _ => m.px(2.0).max(1) as u32,
    };
    let c = color.to_rgba();
    match style {
        Style::Stable | Style::Contour => draw_polyline(area, run, c, width)?,
        Style::Unstable | Style::Dashed => {
            for d in dash(run, m.s * 9.0, m.s * 6.0) {
                draw_polyline(area, &d, c, width)?;
            }
        }
        Style::Reference => {
            for d in dash(run, m.s * 2.5, m.s * 4.0) {
                draw_polyline(area, &d, c, width)?;
            }
        }
        Style::Jump => {
            for d in dash(run, m.s * 4.0, m.s * 3.0) {
                draw_polyline(area, &d, c, width)?;
            }
            let n = run.len();
            draw_arrow_head(area, run[n - 2], run[n - 1], color, m)?;
        }
        Style::Scatter | Style::ErrorBar => {}
    }
    Ok(())
}

fn draw_arrow_head<DB: DrawingBackend>(
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
    area.draw(&Polygon::new(vec![ipt(to), ipt(p1), ipt(p2)], color.filled()))
        .map_err(err)
}

fn draw_marker<DB: DrawingBackend>(
    area: &Area<DB>,
    p: (f64, f64),
    shape: MarkerShape,
    color: RGBColor,
    m: &Metrics,
) -> Draw<()> {
    let r = 6.0 * m.s;
    let (x, y) = p;
    let w = m.px(1.6).max(1) as u32;
    match shape {
        MarkerShape::PullIn => {
            let pts = vec![
                ipt((x, y - r * 1.1)),
                ipt((x - r, y + r * 0.75)),
                ipt((x + r, y + r * 0.75)),
            ];
            area.draw(&Polygon::new(pts.clone(), color.filled()))
                .map_err(err)?;
            let mut closed = pts;
            closed.push(closed[0]);
            area.draw(&PathElement::new(closed, BLACK.stroke_width(1)))
                .map_err(err)
        }
        MarkerShape::PullOff => {
            let a = ipt((x - r * 0.85, y - r * 0.85));
            let b = ipt((x + r * 0.85, y + r * 0.85));
            area.draw(&Rectangle::new([a, b], color.filled())).map_err(err)?;
            area.draw(&Rectangle::new([a, b], BLACK.stroke_width(1)))
                .map_err(err)
        }
        MarkerShape::StableState => area
            .draw(&Circle::new(ipt(p), (r * 0.8) as i32, color.filled()))
            .map_err(err),
        MarkerShape::UnstableState => {
            area.draw(&Circle::new(ipt(p), (r * 0.8) as i32, WHITE.filled()))
                .map_err(err)?;
            area.draw(&Circle::new(ipt(p), (r * 0.8) as i32, color.stroke_width(w)))
                .map_err(err)
        }
        MarkerShape::Point => {
            let pts = vec![ipt((x, y - r)), ipt((x + r, y)), ipt((x, y + r)), ipt((x - r, y))];
            area.draw(&Polygon::new(pts, color.filled())).map_err(err)
        }
        MarkerShape::Cross => {
            let d = r * 0.7;
            area.draw(&PathElement::new(
                vec![ipt((x - d, y - d)), ipt((x + d, y + d))],
                color.stroke_width(w),
            ))
            .map_err(err)?;
            area.draw(&PathElement::new(
                vec![ipt((x - d, y + d)), ipt((x + d, y - d))],
                color.stroke_width(w),
            ))
            .map_err(err)
        }
    }
}

/// Viridis colour map, t in [0, 1].
pub fn viridis(t: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 9] = [
        (0.267, 0.005, 0.329),
        (0.283, 0.141, 0.458),
        (0.254, 0.265, 0.530),
        (0.207, 0.372, 0.553),
        (0.164, 0.471, 0.558),
        (0.128, 0.567, 0.551),
        (0.135, 0.659, 0.518),
        (0.267, 0.749, 0.441),
        (0.993, 0.906, 0.144),
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let c = |u: f64, v: f64| ((u + f * (v - u)) * 255.0).round() as u8;
    (c(a.0, b.0), c(a.1, b.1), c(a.2, b.2))
}

/// Draw a heat map (cells centred on the grid nodes) under the frame.
fn draw_heat<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    field: &Field,
    range: (f64, f64),
) -> Draw<()> {
    let (nx, ny) = (field.x.len(), field.y.len());
    if nx == 0 || ny == 0 {
        return Ok(());
    }
    let edges = |v: &[f64], log: bool| -> Vec<f64> {
        let t: Vec<f64> = v.iter().map(|&x| if log { x.log10() } else { x }).collect();
        let n = t.len();
        let mut e = Vec::with_capacity(n + 1);
        if n == 1 {
            return vec![t[0] - 0.5, t[0] + 0.5];
        }
        e.push(t[0] - 0.5 * (t[1] - t[0]));
        for k in 0..n - 1 {
            e.push(0.5 * (t[k] + t[k + 1]));
        }
        e.push(t[n - 1] + 0.5 * (t[n - 1] - t[n - 2]));
        e.into_iter()
            .map(|x| if log { 10f64.powf(x) } else { x })
            .collect()
    };
    let xe = edges(&field.x, frame.xlog);
    let ye = edges(&field.y, frame.ylog);
    let span = (range.1 - range.0).max(f64::MIN_POSITIVE);
    // Downsample very fine grids to about one cell per pixel column.
    let stride_x = (nx / 700).max(1);
    let stride_y = (ny / 700).max(1);
    for j in (0..ny).step_by(stride_y) {
        for i in (0..nx).step_by(stride_x) {
            let v = field.at(i, j);
            if !v.is_finite() {
                continue;
            }
            let (Some(xa), Some(xb), Some(ya), Some(yb)) = (
                frame.tx(xe[i]),
                frame.tx(xe[(i + stride_x).min(nx)]),
                frame.ty(ye[j]),
                frame.ty(ye[(j + stride_y).min(ny)]),
            ) else {
                continue;
            };
            let (xa, xb) = (xa.max(frame.x0), xb.min(frame.x1));
            let (ya, yb) = (ya.min(frame.y1), yb.max(frame.y0));
            if xb <= xa || ya <= yb {
                continue;
            }
            let c = viridis((v - range.0) / span);
            area.draw(&Rectangle::new(
                [
                    (xa.floor() as i32, yb.floor() as i32),
                    (xb.ceil() as i32, ya.ceil() as i32),
                ],
                rgb(c).filled(),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

/// One legend entry.
enum Swatch {
    Line(Style, RGBColor),
    Marker(MarkerShape, Vec<RGBColor>),
    Fill(RGBColor),
    Hatch(RGBColor, usize),
}

/// Hatch angle of palette colour `c`: overlapping regions of different colours are hatched
/// in different directions, so each stays readable.
fn hatch_angle(c: usize) -> f64 {
    const ANGLES: [f64; 4] = [45.0, -45.0, 0.0, 90.0];
    ANGLES[c % ANGLES.len()].to_radians()
}

/// Segments of the lines `p·n = s` (n the normal of direction `angle`, s on a grid of
/// `spacing`) inside the closed polygon `poly`, by the even-odd rule.
pub(crate) fn hatch_segments(poly: &[(f64, f64)], angle: f64, spacing: f64) -> Vec<((f64, f64), (f64, f64))> {
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
fn draw_hatched<DB: DrawingBackend>(
    area: &Area<DB>,
    poly: &[(f64, f64)],
    color: RGBColor,
    c: usize,
    m: &Metrics,
) -> Draw<()> {
    let thin = m.px(0.8).max(1) as u32;
    for (a, b) in hatch_segments(poly, hatch_angle(c), 7.0 * m.s) {
        draw_polyline(area, &[a, b], color.mix(0.55), thin)?;
    }
    let mut closed = poly.to_vec();
    closed.push(poly[0]);
    draw_polyline(area, &closed, color.mix(0.8), m.px(1.0).max(1) as u32)
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
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (f64::from(w), f64::from(h));
    let Some((frame, has_bar, [xa, xb, ya, yb])) = panel_frame(panel, w, h, m) else {
        let style = text_style(m.font(14.0), false, BLACK).pos(Pos::new(HPos::Center, VPos::Center));
        return area
            .draw_text("no data", &style, ((w / 2.0) as i32, (h / 2.0) as i32))
            .map_err(err);
    };
    if !(frame.xr.1 > frame.xr.0 && frame.yr.1 > frame.yr.0) {
        return Err(format!("empty axis range in panel `{}`", panel.title));
    }
    let colors = panel.series_colors();
    let (frame, legend) = plan_legend(panel, frame, &colors, m, w, has_bar);
    let grey = RGBColor(225, 225, 225);
    let tick_font = m.font(13.0);

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

    // Grid and ticks.
    let xt = ticks(xa, xb, panel.x.scale, 6);
    let yt = ticks(ya, yb, panel.y.scale, 6);
    if panel.field.is_none() {
        for &v in &xt.values {
            if let Some(px) = frame.tx(v) {
                draw_polyline(area, &[(px, frame.y0), (px, frame.y1)], grey.to_rgba(), 1)?;
            }
        }
        for &v in &yt.values {
            if let Some(py) = frame.ty(v) {
                draw_polyline(area, &[(frame.x0, py), (frame.x1, py)], grey.to_rgba(), 1)?;
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
        let pts: Vec<(i32, i32)> = region
            .points
            .iter()
            .filter_map(|&p| frame.map(p))
            .map(|(x, y)| ipt((x.clamp(frame.x0, frame.x1), y.clamp(frame.y0, frame.y1))))
            .collect();
        if pts.len() >= 3 {
            if region.hatched {
                let poly: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (f64::from(x), f64::from(y))).collect();
                draw_hatched(area, &poly, rgb(palette(c)), c, m)?;
            } else {
                area.draw(&Polygon::new(pts, rgb(palette(c)).mix(0.18).filled()))
                    .map_err(err)?;
            }
        }
    }

    // Contours.
    if let Some(field) = &panel.field {
        let highlight: Vec<f64> = field.highlight.iter().map(|(l, _)| *l).collect();
        for level in field.contour_levels() {
            let emphasised = highlight.contains(&level);
            let color = if emphasised {
                RGBColor(200, 0, 0)
            } else if bar_range.is_some() {
                WHITE
            } else {
                RGBColor(60, 60, 60)
            };
            for line in field.contour(level) {
                for run in pixel_runs(&frame, &line) {
                    let width = if emphasised { m.px(2.6) } else { m.px(1.0) }.max(1) as u32;
                    draw_polyline(area, &run, color.to_rgba(), width)?;
                }
            }
            // Label each level once, at the middle of its longest line.
            if let Some(line) = field.contour(level).into_iter().max_by_key(Vec::len)
                && let Some(p) = frame.map(line[line.len() / 2])
                && frame.inside(p)
            {
                let text = field
                    .highlight
                    .iter()
                    .find(|(l, _)| *l == level)
                    .map_or_else(|| super::axes::format_number(level), |(_, t)| t.clone());
                let style = text_style(m.font(if emphasised { 13.0 } else { 11.0 }), emphasised, color)
                    .pos(Pos::new(HPos::Left, VPos::Bottom));
                area.draw_text(&text, &style, ipt((p.0 + 3.0 * m.s, p.1 - 2.0 * m.s)))
                    .map_err(err)?;
            }
        }
    }

    // Series.
    for (series, &c) in panel.series.iter().zip(&colors) {
        let color = rgb(palette(c));
        match series.style {
            Style::Scatter => {
                for &p in &series.points {
                    // Open circles: the lines under many data points stay visible.
                    if let Some(q) = frame.map(p).filter(|q| frame.inside(*q)) {
                        area.draw(&Circle::new(
                            ipt(q),
                            m.px(3.4),
                            color.stroke_width(m.px(1.3).max(1) as u32),
                        ))
                        .map_err(err)?;
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
                        let wdt = m.px(1.3).max(1) as u32;
                        draw_polyline(area, &[a, b], color.to_rgba(), wdt)?;
                        draw_polyline(area, &[(a.0 - cap, a.1), (a.0 + cap, a.1)], color.to_rgba(), wdt)?;
                        draw_polyline(area, &[(b.0 - cap, b.1), (b.0 + cap, b.1)], color.to_rgba(), wdt)?;
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
                draw_polyline(area, &[a, b], color.to_rgba(), m.px(1.4).max(1) as u32)?;
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
                    label,
                    (p.0 + 7.0 * m.s, p.1 - 5.0 * m.s),
                    (Anchor::Start, Baseline::Bottom),
                    m.font(14.0),
                    true,
                    BLACK,
                    false,
                    m,
                )?;
            }
        }
    }

    // Frame, ticks and labels.
    let frame_pts = [
        (frame.x0, frame.y0),
        (frame.x1, frame.y0),
        (frame.x1, frame.y1),
        (frame.x0, frame.y1),
        (frame.x0, frame.y0),
    ];
    draw_polyline(area, &frame_pts, BLACK.to_rgba(), m.px(1.2).max(1) as u32)?;
    let tick_len = 6.0 * m.s;
    let tick_style_x = text_style(tick_font, false, BLACK).pos(Pos::new(HPos::Center, VPos::Top));
    for (v, label) in xt.values.iter().zip(&xt.labels) {
        if let Some(px) = frame.tx(*v) {
            draw_polyline(
                area,
                &[(px, frame.y1), (px, frame.y1 - tick_len)],
                BLACK.to_rgba(),
                1,
            )?;
            area.draw_text(label, &tick_style_x, ipt((px, frame.y1 + 5.0 * m.s)))
                .map_err(err)?;
        }
    }
    for v in &xt.minor {
        if let Some(px) = frame.tx(*v) {
            draw_polyline(
                area,
                &[(px, frame.y1), (px, frame.y1 - tick_len * 0.5)],
                BLACK.to_rgba(),
                1,
            )?;
        }
    }
    let tick_style_y = text_style(tick_font, false, BLACK).pos(Pos::new(HPos::Right, VPos::Center));
    let mut widest = 0u32;
    for (v, label) in yt.values.iter().zip(&yt.labels) {
        if let Some(py) = frame.ty(*v) {
            draw_polyline(
                area,
                &[(frame.x0, py), (frame.x0 + tick_len, py)],
                BLACK.to_rgba(),
                1,
            )?;
            area.draw_text(label, &tick_style_y, ipt((frame.x0 - 5.0 * m.s, py)))
                .map_err(err)?;
            let (tw, _) = area.estimate_text_size(label, &tick_style_y).map_err(err)?;
            widest = widest.max(tw);
        }
    }
    for v in &yt.minor {
        if let Some(py) = frame.ty(*v) {
            draw_polyline(
                area,
                &[(frame.x0, py), (frame.x0 + tick_len * 0.5, py)],
                BLACK.to_rgba(),
                1,
            )?;
        }
    }
    let label_font = m.font(15.0);
    draw_label(
        area,
        &panel.x.title(),
        (0.5 * (frame.x0 + frame.x1), h - 8.0 * m.s),
        (Anchor::Middle, Baseline::Bottom),
        label_font,
        false,
        BLACK,
        false,
        m,
    )?;
    let yl_x = (frame.x0 - f64::from(widest) - 12.0 * m.s - label_font).max(4.0 * m.s);
    draw_label(
        area,
        &panel.y.title(),
        (yl_x, 0.5 * (frame.y0 + frame.y1)),
        (Anchor::Middle, Baseline::Top),
        label_font,
        false,
        BLACK,
        true,
        m,
    )?;
    let heading = match (panel.label.is_empty(), panel.title.is_empty()) {
        (true, true) => String::new(),
        (false, true) => panel.label.clone(),
        (true, false) => panel.title.clone(),
        (false, false) => format!("{} {}", panel.label, panel.title),
    };
    if !heading.is_empty() {
        draw_label(
            area,
            &heading,
            (frame.x0, frame.y0 - 8.0 * m.s),
            (Anchor::Start, Baseline::Bottom),
            m.font(15.0),
            true,
            BLACK,
            false,
            m,
        )?;
    }

    // Colour bar.
    if let (Some((lo, hi)), Some(field)) = (bar_range, &panel.field) {
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
        area.draw(&Rectangle::new(
            [ipt((bx0, frame.y0)), ipt((bx1, frame.y1))],
            BLACK.stroke_width(1),
        ))
        .map_err(err)?;
        let bt = ticks(lo, hi, Scale::Linear, 5);
        let style = text_style(m.font(11.0), false, BLACK).pos(Pos::new(HPos::Left, VPos::Center));
        for (v, label) in bt.values.iter().zip(&bt.labels) {
            let y = frame.y1 - (v - lo) / (hi - lo).max(f64::MIN_POSITIVE) * (frame.y1 - frame.y0);
            draw_polyline(area, &[(bx1, y), (bx1 + 4.0 * m.s, y)], BLACK.to_rgba(), 1)?;
            area.draw_text(label, &style, ipt((bx1 + 6.0 * m.s, y)))
                .map_err(err)?;
        }
        let title = if field.unit.is_empty() {
            field.name.clone()
        } else {
            format!("{} [{}]", field.name, field.unit)
        };
        let style = text_style(m.font(11.0), false, BLACK).pos(Pos::new(HPos::Center, VPos::Bottom));
        area.draw_text(
            &title,
            &style,
            ipt((0.5 * (bx0 + bx1) + 10.0 * m.s, frame.y0 - 6.0 * m.s)),
        )
        .map_err(err)?;
    }

    if let Some(plan) = legend {
        draw_legend(area, &plan, m)?;
    }
    Ok(())
}

/// A legend ready to draw: its entries and its box in pixels.
struct LegendPlan {
    entries: Vec<(String, Swatch)>,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
    row: f64,
    pad: f64,
    swatch_w: f64,
    font: f64,
}

/// The legend entries of a panel: one per series name, region name and marker name.
fn legend_entries(panel: &Panel, colors: &[usize]) -> Vec<(String, Swatch)> {
    let mut entries: Vec<(String, Swatch)> = Vec::new();
    if panel.legend == Legend::Hidden {
        return entries;
    }
    for (s, &c) in panel.series.iter().zip(colors) {
        if !s.legend || entries.iter().any(|(n, _)| *n == s.name) {
            continue;
        }
        // A curve drawn in stable and unstable parts shows its solid style in the legend.
        let style = if panel
            .series
            .iter()
            .any(|o| o.name == s.name && o.style == Style::Stable)
        {
            Style::Stable
        } else {
            s.style
        };
        entries.push((s.name.clone(), Swatch::Line(style, rgb(palette(c)))));
    }
    for r in &panel.regions {
        if !entries.iter().any(|(n, _)| *n == r.name) {
            let c = r.color.unwrap_or(8);
            let swatch = if r.hatched {
                Swatch::Hatch(rgb(palette(c)), c)
            } else {
                Swatch::Fill(rgb(palette(c)))
            };
            entries.push((r.name.clone(), swatch));
        }
    }
    for mk in &panel.markers {
        if !entries.iter().any(|(n, _)| *n == mk.name) {
            // Markers of one name share a legend entry, which shows each of their colours.
            let mut same: Vec<usize> = Vec::new();
            for o in panel.markers.iter().filter(|o| o.name == mk.name) {
                let c = panel.marker_color(o, colors).unwrap_or(7);
                if !same.contains(&c) {
                    same.push(c);
                }
            }
            let cols = same.iter().map(|&c| rgb(palette(c))).collect();
            entries.push((mk.name.clone(), Swatch::Marker(mk.shape, cols)));
        }
    }
    entries
}

/// Pixel positions of everything a legend must not cover: the series drawn as lines (densified,
/// so that a line crossing a box counts), the series points and the markers.
fn covered_points(panel: &Panel, frame: &Frame) -> Vec<(f64, f64)> {
    panel
        .series
        .iter()
        .flat_map(|s| {
            if matches!(s.style, Style::Scatter | Style::ErrorBar) {
                s.points.iter().filter_map(|&p| frame.map(p)).collect()
            } else {
                densify(frame, &s.points)
            }
        })
        .chain(panel.markers.iter().filter_map(|mk| frame.map((mk.x, mk.y))))
        .filter(|p| frame.inside(*p))
        .collect()
}

/// Place the legend where it covers no drawn point: the preferred corner, the other corners and
/// the middles of the edges inside the frame; when every one covers data, outside the frame on
/// the right (the frame narrows to make room). Returns the frame to draw in and the legend.
fn plan_legend(
    panel: &Panel,
    frame: Frame,
    colors: &[usize],
    m: &Metrics,
    panel_w: f64,
    has_bar: bool,
) -> (Frame, Option<LegendPlan>) {
    let entries = legend_entries(panel, colors);
    if entries.is_empty() {
        return (frame, None);
    }
    let font = m.font(12.5);
    let text_w = entries
        .iter()
        .map(|(n, _)| super::text::width(n, font, false))
        .fold(0.0, f64::max);
    let row = font * 1.45;
    let swatch_w = 30.0 * m.s;
    let pad = 7.0 * m.s;
    let box_w = swatch_w + 3.0 * pad + text_w;
    let box_h = row * entries.len() as f64 + 2.0 * pad - 0.3 * row;
    let plan = |x: f64, y: f64, entries: Vec<(String, Swatch)>| LegendPlan {
        entries,
        x,
        y,
        w: box_w,
        h: box_h,
        row,
        pad,
        swatch_w,
        font,
    };
    let inset = 8.0 * m.s;
    let (l, r) = (frame.x0 + inset, frame.x1 - inset - box_w);
    let (t, b) = (frame.y0 + inset, frame.y1 - inset - box_h);
    let (cx, cy) = (0.5 * (l + r), 0.5 * (t + b));
    let mut candidates = vec![
        (Legend::UpperRight, r, t),
        (Legend::UpperLeft, l, t),
        (Legend::LowerRight, r, b),
        (Legend::LowerLeft, l, b),
        (Legend::Auto, cx, t),
        (Legend::Auto, cx, b),
        (Legend::Auto, l, cy),
        (Legend::Auto, r, cy),
    ];
    // A scene's preferred corner is tried first.
    if let Some(k) = candidates
        .iter()
        .position(|c| c.0 == panel.legend && c.0 != Legend::Auto)
    {
        let c = candidates.remove(k);
        candidates.insert(0, c);
    }
    let fits = r >= l && b >= t;
    if fits {
        let points = covered_points(panel, &frame);
        let cover = |x: f64, y: f64| {
            points
                .iter()
                .filter(|p| {
                    p.0 >= x - pad && p.0 <= x + box_w + pad && p.1 >= y - pad && p.1 <= y + box_h + pad
                })
                .count()
        };
        if let Some(&(_, x, y)) = candidates.iter().find(|(_, x, y)| cover(*x, *y) == 0) {
            return (frame, Some(plan(x, y, entries)));
        }
    }
    // Outside on the right, beyond the colour bar if there is one.
    let x = panel_w - box_w - 6.0 * m.s;
    let right_margin = if has_bar { 110.0 } else { 16.0 } * m.s;
    let x1 = (x - right_margin).max(frame.x0 + 0.3 * (frame.x1 - frame.x0));
    let frame = Frame { x1, ..frame };
    (frame, Some(plan(x, frame.y0, entries)))
}

/// Where each panel's frame and legend go, as the PNG renderer draws them (pixels of the
/// panel's own area at the PNG scale), with the pixel positions of every series point and
/// marker inside the frame. `None` for a panel with nothing to draw.
pub fn panel_layouts(fig: &Figure) -> Vec<Option<PanelLayout>> {
    let m = Metrics {
        s: 2.0,
        images: None,
        texts: None,
    };
    let (pw, ph) = (m.px(PANEL_W), m.px(PANEL_H));
    fig.panels
        .iter()
        .enumerate()
        .map(|(k, panel)| {
            let (_, _, pw) = panel_slot(fig.panels.len(), k, pw);
            let (frame, has_bar, _) = panel_frame(panel, f64::from(pw), f64::from(ph), &m)?;
            let colors = panel.series_colors();
            let (frame, legend) = plan_legend(panel, frame, &colors, &m, f64::from(pw), has_bar);
            let points = panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().filter_map(|&p| frame.map(p)))
                .chain(panel.markers.iter().filter_map(|mk| frame.map((mk.x, mk.y))))
                .filter(|p| frame.inside(*p))
                .collect();
            Some(PanelLayout {
                frame: (frame.x0, frame.x1, frame.y0, frame.y1),
                legend: legend.map(|l| (l.x, l.y, l.x + l.w, l.y + l.h)),
                points,
            })
        })
        .collect()
}

/// A panel's layout in pixels ([`panel_layouts`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PanelLayout {
    /// Plotting frame: left, right, top, bottom.
    pub frame: (f64, f64, f64, f64),
    /// Legend box: left, top, right, bottom.
    pub legend: Option<(f64, f64, f64, f64)>,
    /// Every series point and marker inside the frame.
    pub points: Vec<(f64, f64)>,
}

fn draw_legend<DB: DrawingBackend>(area: &Area<DB>, plan: &LegendPlan, m: &Metrics) -> Draw<()> {
    let (bx, by, box_w, box_h) = (plan.x, plan.y, plan.w, plan.h);
    let (row, pad, swatch_w) = (plan.row, plan.pad, plan.swatch_w);
    area.draw(&Rectangle::new(
        [ipt((bx, by)), ipt((bx + box_w, by + box_h))],
        WHITE.mix(0.88).filled(),
    ))
    .map_err(err)?;
    area.draw(&Rectangle::new(
        [ipt((bx, by)), ipt((bx + box_w, by + box_h))],
        RGBColor(160, 160, 160).stroke_width(1),
    ))
    .map_err(err)?;
    for (k, (name, swatch)) in plan.entries.iter().enumerate() {
        let y = by + pad + row * (k as f64 + 0.35);
        let x0 = bx + pad;
        let x1 = x0 + swatch_w;
        match swatch {
            Swatch::Line(style, c) => match style {
                Style::Scatter => {
                    area.draw(&Circle::new(
                        ipt((0.5 * (x0 + x1), y)),
                        m.px(3.4),
                        c.stroke_width(m.px(1.3).max(1) as u32),
                    ))
                    .map_err(err)?;
                }
                Style::ErrorBar => {
                    draw_polyline(
                        area,
                        &[(0.5 * (x0 + x1), y - 6.0 * m.s), (0.5 * (x0 + x1), y + 6.0 * m.s)],
                        c.to_rgba(),
                        m.px(1.3) as u32,
                    )?;
                }
                other => draw_pixel_line(area, &[(x0, y), (x1, y)], *other, *c, m)?,
            },
            Swatch::Marker(shape, cols) => {
                // Up to four colours side by side, smaller when there are several.
                let k = cols.len().clamp(1, 4);
                let step = (x1 - x0) / k as f64;
                let mm = Metrics {
                    s: if k > 1 { m.s * 0.75 } else { m.s },
                    images: None,
                    texts: None,
                };
                for (i, c) in cols.iter().take(4).enumerate() {
                    draw_marker(area, (x0 + step * (i as f64 + 0.5), y), *shape, *c, &mm)?;
                }
            }
            Swatch::Hatch(c, k) => {
                let poly = [
                    (x0, y - 5.0 * m.s),
                    (x1, y - 5.0 * m.s),
                    (x1, y + 5.0 * m.s),
                    (x0, y + 5.0 * m.s),
                ];
                draw_hatched(area, &poly, *c, *k, m)?;
            }
            Swatch::Fill(c) => {
                area.draw(&Rectangle::new(
                    [ipt((x0, y - 5.0 * m.s)), ipt((x1, y + 5.0 * m.s))],
                    c.mix(0.25).filled(),
                ))
                .map_err(err)?;
            }
        }
        draw_label(
            area,
            name,
            (x1 + pad, y),
            (Anchor::Start, Baseline::Center),
            plan.font,
            false,
            BLACK,
            false,
            m,
        )?;
    }
    Ok(())
}

/// Pixel points along a series, with extra points on long segments so that a line crossing
/// a legend candidate box counts as covering it.
fn densify(frame: &Frame, points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for run in pixel_runs(frame, points) {
        for w in run.windows(2) {
            let len = ((w[1].0 - w[0].0).powi(2) + (w[1].1 - w[0].1).powi(2)).sqrt();
            let n = (len / 8.0).ceil().max(1.0) as usize;
            for k in 0..n {
                let t = k as f64 / n as f64;
                out.push((w[0].0 + t * (w[1].0 - w[0].0), w[0].1 + t * (w[1].1 - w[0].1)));
            }
        }
        if let Some(&p) = run.last() {
            out.push(p);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dark pixels of `text` drawn at baseline y = 60 from x = 10, 40 px, in the box
    /// `x0..x1` × `y0..y1` of a 200 × 100 white bitmap.
    fn ink(text: &str, x0: i32, x1: i32, y0: i32, y1: i32) -> usize {
        register_fonts();
        let (w, h) = (200u32, 100u32);
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            let m = Metrics {
                s: 1.0,
                images: None,
                texts: None,
            };
            let l = super::super::text::layout(text, 40.0, false);
            // Baseline at y = 60: anchor the top at 60 - ascent.
            draw_label(
                &root,
                text,
                (10.0, 60.0 - l.ascent),
                (Anchor::Start, Baseline::Top),
                40.0,
                false,
                BLACK,
                false,
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
    fn base64_matches_rfc_4648_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }

    #[test]
    fn dashes_cover_about_the_on_fraction_of_a_line() {
        let run = vec![(0.0, 0.0), (150.0, 0.0)];
        let d = dash(&run, 10.0, 5.0);
        let drawn: f64 = d.iter().map(|s| s.last().unwrap().0 - s[0].0).sum();
        assert!((drawn - 100.0).abs() < 1e-9, "{drawn}");
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
