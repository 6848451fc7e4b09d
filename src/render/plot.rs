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
mod frame;
mod heat;
mod legend;
mod place;

use std::path::Path;

use plotters::prelude::*;

use self::draw::{
    Anchor, Baseline, Label, draw_arrow_head, draw_hatched, draw_label, draw_marker, draw_polyline,
    draw_ring, draw_styled_line, fill_polygon, pixel_runs,
};
use self::frame::{Area, Draw, Frame, Metrics, err, ipt, rgb};
pub use self::frame::{PALETTE, palette};
pub use self::heat::viridis;
use self::heat::{draw_heat, draw_heat_raster, embed_images};
use self::legend::{LegendPlan, draw_legend, plan_legend};
use super::axes::{padded_range, ticks};
use crate::error::{Error, Result};
use crate::figure::{FieldKind, Figure, Panel, Scale, Style};

/// Width of a figure in one journal column (mm).
pub const COLUMN_MM: f64 = 90.0;
/// Width of a figure across the page (mm).
pub const FULL_WIDTH_MM: f64 = 190.0;
/// Resolution of a PNG unless asked otherwise (dots per inch).
pub const DEFAULT_DPI: f64 = 300.0;

/// Points per layout unit. A figure is laid out in units of 8/15 pt: axis titles (15 units)
/// come out at 8 pt, tick labels (13 units) at 7 pt, panel letters (17 units, bold) at 9 pt,
/// legends (12.5 units) at 6.7 pt and curves (2 units) 1.07 pt wide, whatever the figure's
/// width; margins scale with the text.
pub const PT_PER_UNIT: f64 = 8.0 / 15.0;

/// Millimetres per point.
pub const MM_PER_PT: f64 = 25.4 / 72.0;

/// Height of a panel as a fraction of its width (at least [`PANEL_MIN_H`]).
const PANEL_ASPECT: f64 = 460.0 / 620.0;
/// The least height of a panel (layout units): a narrow panel keeps room for its data between
/// the heading and the tick labels.
const PANEL_MIN_H: f64 = 300.0;

/// The physical size of an exported figure: its width on the page and the PNG's resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Print {
    /// Width on the page (mm); `None` chooses by the panel count ([`Print::width_of`]).
    pub width_mm: Option<f64>,
    /// Dots per inch of the PNG.
    pub dpi: f64,
}

impl Default for Print {
    fn default() -> Self {
        Self {
            width_mm: None,
            dpi: DEFAULT_DPI,
        }
    }
}

impl Print {
    /// The least width a figure may be given (mm): below it the frames have no room left.
    pub const MIN_WIDTH_MM: f64 = 40.0;
    /// The largest width (mm).
    pub const MAX_WIDTH_MM: f64 = 500.0;
    /// The least resolution (dpi).
    pub const MIN_DPI: f64 = 30.0;
    /// The largest resolution (dpi).
    pub const MAX_DPI: f64 = 1200.0;

    /// A print size with the given width (mm; `None`: by panel count) and resolution (`None`:
    /// [`DEFAULT_DPI`]), checked.
    ///
    /// # Errors
    /// [`Error::Invalid`] for a width or a resolution outside its range (or not finite).
    pub fn new(width_mm: Option<f64>, dpi: Option<f64>) -> Result<Self> {
        if let Some(w) = width_mm
            && !(Self::MIN_WIDTH_MM..=Self::MAX_WIDTH_MM).contains(&w)
        {
            return Err(Error::invalid(
                "--width-mm",
                w,
                format!(
                    "a figure is {}-{} mm wide",
                    Self::MIN_WIDTH_MM,
                    Self::MAX_WIDTH_MM
                ),
            ));
        }
        let dpi = dpi.unwrap_or(DEFAULT_DPI);
        if !(Self::MIN_DPI..=Self::MAX_DPI).contains(&dpi) {
            return Err(Error::invalid(
                "--dpi",
                dpi,
                format!("the resolution is {}-{} dpi", Self::MIN_DPI, Self::MAX_DPI),
            ));
        }
        Ok(Self { width_mm, dpi })
    }

    /// The figure's width (mm): the one given, else one column for a single panel and the full
    /// page width for two or more.
    pub fn width_of(&self, fig: &Figure) -> f64 {
        self.width_mm.unwrap_or(if fig.panels.len() <= 1 {
            COLUMN_MM
        } else {
            FULL_WIDTH_MM
        })
    }

    /// PNG pixels per layout unit.
    fn png_scale(&self) -> f64 {
        self.dpi / 72.0 * PT_PER_UNIT
    }
}

/// SVG (and PDF) user units per layout unit: the SVG backend writes whole numbers, so the
/// drawing is made at a quarter point per user unit.
const SVG_SCALE: f64 = 4.0 * PT_PER_UNIT;

/// Width and height of one panel (layout units) of a figure `width_mm` wide.
fn panel_size(fig: &Figure, width_mm: f64) -> (f64, f64) {
    let (cols, _) = grid(fig.panels.len());
    let w = width_mm / MM_PER_PT / PT_PER_UNIT / cols as f64;
    (w, (PANEL_ASPECT * w).max(PANEL_MIN_H))
}

impl Metrics {
    /// The metrics of a PNG of `fig` at the print size `print`.
    fn png(fig: &Figure, print: &Print) -> Self {
        Self {
            s: print.png_scale(),
            panel: panel_size(fig, print.width_of(fig)),
            images: None,
            texts: None,
            aa: true,
        }
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

/// Pixel size of a figure drawn with the metrics `m`: the title, the grid of panels and the
/// notes under them.
fn figure_size(fig: &Figure, m: &Metrics) -> (u32, u32) {
    let (c, _) = grid(fig.panels.len());
    let title_h = if fig.title.is_empty() { 0 } else { m.px(44.0) };
    let rows: i32 = row_heights(fig, m).iter().sum();
    (
        (m.panel.0 * c as f64 * m.s).round() as u32,
        (rows + title_h + notes_height(fig, m)).max(1) as u32,
    )
}

/// The height of each row of panels in pixels: a panel's, plus the room the notes written
/// under a panel of the row take beyond it.
fn row_heights(fig: &Figure, m: &Metrics) -> Vec<i32> {
    let (pw, ph) = (m.px(m.panel.0), m.px(m.panel.1));
    let mut rows: Vec<i32> = Vec::new();
    for (k, plan) in panel_plans(fig, m).iter().enumerate() {
        let (_, r, _) = panel_slot(fig.panels.len(), k, pw);
        let r = r as usize;
        if rows.len() <= r {
            rows.resize(r + 1, 0);
        }
        // A map kept at its aspect may be less tall than the panel: the row shrinks to it.
        let need = plan.as_ref().map_or(f64::from(ph), |plan| {
            plan.legend
                .iter()
                .filter(|b| b.is_footer())
                .map(|b| b.bottom() + 8.0 * m.s)
                .fold(plan.frame.y1 + PANEL_BOTTOM * m.s, f64::max)
        });
        rows[r] = rows[r].max(need.ceil() as i32);
    }
    if rows.is_empty() {
        rows.push(ph);
    }
    rows
}

/// Render to PNG bytes at the default print size ([`png_bytes_at`] of [`Print::default`]).
///
/// # Errors
/// [`Error::Render`] when drawing or encoding fails.
pub fn png_bytes(fig: &Figure) -> Result<Vec<u8>> {
    png_bytes_at(fig, &Print::default())
}

/// Render to PNG bytes in memory, `print.width_of(fig)` mm wide at `print.dpi` (2 244 pixels
/// for a 190 mm figure at 300 dpi); the resolution is recorded in the PNG (`pHYs`).
///
/// # Errors
/// [`Error::Render`] when drawing or encoding fails.
pub fn png_bytes_at(fig: &Figure, print: &Print) -> Result<Vec<u8>> {
    let m = Metrics::png(fig, print);
    let (w, h) = figure_size(fig, &m);
    let render_error = |message: String| Error::Render {
        format: "png",
        message,
    };
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_with(&root, fig, m).map_err(render_error)?;
        root.present().map_err(|e| render_error(e.to_string()))?;
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let per_metre = (print.dpi / 0.0254).round() as u32;
        enc.set_pixel_dims(Some(png::PixelDimensions {
            xppu: per_metre,
            yppu: per_metre,
            unit: png::Unit::Meter,
        }));
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

/// Render to an SVG document in memory at the default print size ([`svg_string_at`]).
///
/// # Errors
/// [`Error::Render`] when drawing fails.
pub fn svg_string(fig: &Figure) -> Result<String> {
    svg_string_at(fig, &Print::default())
}

/// Render to an SVG document in memory, `print.width_of(fig)` mm wide: the root element gives
/// its width and height in mm and a `viewBox` in user units of a quarter point.
///
/// # Errors
/// [`Error::Render`] when drawing fails.
pub fn svg_string_at(fig: &Figure, print: &Print) -> Result<String> {
    let mut out = String::new();
    let images = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let texts = std::rc::Rc::new(std::cell::RefCell::new(Vec::<String>::new()));
    let m = Metrics {
        s: SVG_SCALE,
        panel: panel_size(fig, print.width_of(fig)),
        images: Some(std::rc::Rc::clone(&images)),
        texts: Some(std::rc::Rc::clone(&texts)),
        aa: false,
    };
    let size = figure_size(fig, &m);
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
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
    let out = physical_size(&out, size);
    let labels: String = texts.borrow().iter().map(|t| format!("{t}\n")).collect();
    Ok(match out.rfind("</svg>") {
        Some(end) => format!("{}{labels}{}", &out[..end], &out[end..]),
        None => out,
    })
}

/// The SVG's root element with its size in mm (a user unit is a quarter point) and a
/// `viewBox` of the drawing's user units.
fn physical_size(svg: &str, (w, h): (u32, u32)) -> String {
    let mm = |v: u32| f64::from(v) * PT_PER_UNIT / SVG_SCALE * MM_PER_PT;
    let from = format!("width=\"{w}\" height=\"{h}\"");
    let to = format!("width=\"{:.2}mm\" height=\"{:.2}mm\"", mm(w), mm(h));
    match svg.find("<svg") {
        Some(start) => {
            let end = svg[start..].find('>').map_or(svg.len(), |e| start + e);
            let mut head = svg[start..end].replacen(&from, &to, 1);
            if !head.contains("viewBox") {
                head.push_str(&format!(" viewBox=\"0 0 {w} {h}\""));
            }
            format!("{}{head}{}", &svg[..start], &svg[end..])
        }
        None => svg.to_string(),
    }
}

/// Render to an SVG file, atomically.
///
/// # Errors
/// As [`svg_string`], plus I/O errors.
pub fn write_svg(fig: &Figure, path: &Path) -> Result<()> {
    let text = svg_string(fig)?;
    super::write_atomic(path, text.as_bytes())
}

/// Draw the whole figure onto `root` with the given metrics.
fn draw_with<DB: DrawingBackend>(root: &Area<DB>, fig: &Figure, m: Metrics) -> Draw<()> {
    root.fill(&WHITE).map_err(err)?;
    let (w, _) = root.dim_in_pixel();
    let mut top = 0;
    if !fig.title.is_empty() {
        let size = fitting_size(&fig.title, m.font(19.0), true, f64::from(w) - 24.0 * m.s, &m);
        draw_label(
            root,
            Label::new(&fig.title, size).bold(),
            (f64::from(w) / 2.0, 24.0 * m.s),
            (Anchor::Middle, Baseline::Center),
            &m,
        )?;
        top = m.px(44.0);
    }
    let pw = m.px(m.panel.0);
    let rows = row_heights(fig, &m);
    for (k, panel) in shown_panels(fig).iter().enumerate() {
        let (x, y, w) = panel_slot(fig.panels.len(), k, pw);
        let above: i32 = rows[..y as usize].iter().sum();
        let area = root
            .clone()
            .shrink((x, top + above), (w as u32, rows[y as usize] as u32));
        draw_panel(&area, panel, &m)?;
    }
    let below = f64::from(top + rows.iter().sum::<i32>()) + NOTE_GAP * m.s;
    let row = m.font(NOTE_TEXT) * 1.45;
    for (k, line) in note_lines(fig, &m).iter().enumerate() {
        draw_label(
            root,
            Label::new(line, m.font(NOTE_TEXT)),
            (NOTE_INSET * m.s, below + row * k as f64),
            (Anchor::Start, Baseline::Top),
            &m,
        )?;
    }
    Ok(())
}

/// The most cells of a field drawn as vector rectangles in SVG and PDF.
const VECTOR_CELLS: usize = 128 * 128;

/// Size of the notes under a figure (layout units): 6.7 pt, as the legends.
const NOTE_TEXT: f64 = 12.5;
/// Gap between the panels and the notes under them (layout units).
const NOTE_GAP: f64 = 6.0;
/// Left and right inset of the notes under a figure (layout units).
const NOTE_INSET: f64 = 16.0;

/// The notes of the figure as written under it, a caption-like block: the figure's own notes
/// first (its quick form, what the workbench finds otherwise than the text, a fit's warnings),
/// then each panel's with the panel's letter (where the figure has several panels), wrapped to
/// the figure's width.
fn note_lines(fig: &Figure, m: &Metrics) -> Vec<String> {
    let (cols, _) = grid(fig.panels.len());
    let width = (m.panel.0 * cols as f64 - 2.0 * NOTE_INSET) * m.s;
    let mut lines = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for n in &fig.notes {
        if !seen.contains(&n.as_str()) {
            seen.push(n);
            lines.extend(legend::wrap(n, m.font(NOTE_TEXT), width));
        }
    }
    let plans = panel_plans(fig, m);
    for ((p, letter), plan) in fig.panels.iter().zip(panel_letters(fig)).zip(&plans) {
        let instead = plan.iter().flat_map(|plan| plan.instead.iter());
        for n in p.notes.iter().chain(instead) {
            if seen.contains(&n.as_str()) {
                continue;
            }
            seen.push(n);
            let text = if letter.is_empty() {
                n.clone()
            } else {
                format!("{letter} {n}")
            };
            lines.extend(legend::wrap(&text, m.font(NOTE_TEXT), width));
        }
    }
    lines
}

/// The letters of the panels as drawn: (a), (b), ... in order where the figure's panels are
/// lettered with single letters that do not run from (a) (a figure drawing panels (b)-(d) of
/// the dissertation's), none for a lone panel; other labels as they are.
fn panel_letters(fig: &Figure) -> Vec<String> {
    let single = |l: &str| {
        let inner = l.strip_prefix('(').and_then(|r| r.strip_suffix(')'));
        inner.is_some_and(|c| c.len() == 1 && c.chars().all(|c| c.is_ascii_lowercase()))
    };
    let labels: Vec<String> = fig.panels.iter().map(|p| p.label.clone()).collect();
    if labels.len() == 1 && single(&labels[0]) {
        return vec![String::new()];
    }
    if labels.len() > 1 && labels.iter().all(|l| single(l)) {
        return (0..labels.len())
            .map(|k| format!("({})", char::from(b'a' + (k % 26) as u8)))
            .collect();
    }
    labels
}

/// The height of the notes under a figure (pixels; 0 without notes).
fn notes_height(fig: &Figure, m: &Metrics) -> i32 {
    let n = note_lines(fig, m).len();
    if n == 0 {
        0
    } else {
        m.px(NOTE_GAP + NOTE_TEXT * 1.45 * n as f64 + NOTE_GAP)
    }
}

/// The panels as they are drawn: their notes moved under the figure ([`note_lines`]); the
/// legend of a panel whose entries repeat those of an earlier panel left out (one legend for
/// series the panels share); panels lettered in order ([`panel_letters`]); a map with one length unit on
/// both axes drawn at equal aspect.
fn shown_panels(fig: &Figure) -> Vec<std::borrow::Cow<'_, Panel>> {
    use std::borrow::Cow;
    let mut shown: Vec<Vec<String>> = Vec::new();
    let letters = panel_letters(fig);
    fig.panels
        .iter()
        .zip(letters)
        .map(|(p, letter)| {
            let names = legend::entry_names(p);
            let repeated = !names.is_empty() && shown.contains(&names);
            if !repeated {
                shown.push(names);
            }
            let lone = letter != p.label;
            // A map over lengths in one unit on both axes and of comparable spans (a top view,
            // a cross-section) keeps its aspect: square cells stay square, circles round. A map
            // over two parameters that share a unit (Z₀ and σ_rms in nm, spans 7:1) does not.
            let comparable = p.data_bounds().is_some_and(|((x0, x1), (y0, y1))| {
                let r = (x1 - x0) / (y1 - y0);
                (0.5..=2.0).contains(&r)
            });
            let square = p.field.is_some()
                && !p.equal_aspect
                && p.x.scale == Scale::Linear
                && p.y.scale == Scale::Linear
                && !p.x.unit.is_empty()
                && p.x.unit == p.y.unit
                && comparable;
            if !repeated && !lone && !square && p.notes.is_empty() {
                return Cow::Borrowed(p);
            }
            let mut q = p.clone();
            q.notes.clear();
            q.equal_aspect |= square;
            if repeated {
                q.legend = crate::figure::Legend::Hidden;
            }
            if lone {
                q.label = letter;
            }
            Cow::Owned(q)
        })
        .collect()
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

/// Room under a panel's frame for the tick labels and the x-axis title (layout units).
const PANEL_BOTTOM: f64 = 56.0;

/// The plotting frame of a panel of size `w` × `h` pixels before the legend is placed, and
/// whether it has a colour bar; `None` when there is nothing to draw.
fn panel_frame(panel: &Panel, w: f64, h: f64, m: &Metrics) -> Option<(Frame, bool, [f64; 4])> {
    let has_bar = panel.field.as_ref().is_some_and(|f| {
        matches!(f.kind, FieldKind::Heat) || matches!(f.kind, FieldKind::Contour { filled: true, .. })
    });
    let frame_box = (
        92.0 * m.s,
        w - if has_bar { 110.0 } else { 24.0 } * m.s,
        if panel.title.is_empty() && panel.label.is_empty() {
            14.0 * m.s
        } else {
            // A heading wrapped onto two lines takes a line more.
            let head = heading(panel, 92.0 * m.s, w, m);
            38.0 * m.s + head.row * (head.lines.len().max(1) - 1) as f64
        },
        h - PANEL_BOTTOM * m.s,
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
            // Centred across, at the top: the row shrinks to the frame's height.
            frame_box.0 += 0.5 * (fw - nw);
            frame_box.1 = frame_box.0 + nw;
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

/// A panel laid out before anything is drawn: the frame, the legend, the ticks, the texts
/// placed beside markers and contour lines, and the data they were placed clear of.
struct PanelPlan {
    frame: Frame,
    colors: Vec<usize>,
    legend: Vec<LegendPlan>,
    x_ticks: (super::axes::Ticks, Option<i32>),
    y_ticks: (super::axes::Ticks, Option<i32>),
    /// Marker and contour labels with their places.
    texts: Vec<place::Placed>,
    /// What the notes under the figure say for labels that found no free place.
    instead: Vec<String>,
    /// Pixel points of everything drawn as data: curves (densified), markers, arrows,
    /// contour lines.
    data: Vec<(f64, f64)>,
}

/// Lay out a panel of `w` × `h` pixels ([`PanelPlan`]); `None` when there is nothing to draw.
fn plan_panel(panel: &Panel, w: f64, h: f64, m: &Metrics) -> Option<PanelPlan> {
    let (frame, has_bar, ranges) = panel_frame(panel, w, h, m)?;
    let colors = panel.series_colors();
    let (frame, legend) = plan_legend(panel, frame, &colors, m, w, has_bar);
    let [xa, xb, ya, yb] = ranges;
    let x_ticks = spaced_ticks((xa, xb), panel.x.scale, 6, &|v| frame.tx(v), true, m);
    let y_ticks = spaced_ticks((ya, yb), panel.y.scale, 6, &|v| frame.ty(v), false, m);
    let mut data = legend::covered_points(panel, &frame);
    for a in &panel.arrows {
        data.extend(legend::densify(&frame, &[a.from, a.to]));
    }
    let mut first = Vec::new();
    let mut last = Vec::new();
    if let Some(field) = &panel.field {
        let over_colours = has_bar;
        let highlight: Vec<f64> = field.highlight.iter().map(|(l, _)| *l).collect();
        for level in field.contour_levels() {
            let emphasised = highlight.contains(&level);
            let mut lines = field.contour(level);
            for line in &lines {
                data.extend(legend::densify(&frame, line));
            }
            lines.sort_by_key(|l| std::cmp::Reverse(l.len()));
            // Along the longest line first, then at the middle of the others.
            let mut anchors: Vec<(f64, f64)> = Vec::new();
            if let Some(line) = lines.first() {
                for f in [0.5, 0.3, 0.7, 0.15, 0.85, 0.05, 0.95] {
                    anchors.extend(frame.map(line[((line.len() - 1) as f64 * f) as usize]));
                }
            }
            anchors.extend(lines.iter().skip(1).filter_map(|l| frame.map(l[l.len() / 2])));
            anchors.retain(|p| frame.inside(*p));
            let color = contour_color(emphasised, over_colours);
            let text = field.highlight.iter().find(|(l, _)| *l == level).map_or_else(
                || tick_markup(&super::axes::format_number(level)),
                |(_, t)| t.clone(),
            );
            let request = place::Request {
                // A level with no line in the frame has nothing to label.
                instead: (emphasised && !anchors.is_empty()).then(|| format!("red line: {text}")),
                text,
                size: m.font(if emphasised { 13.0 } else { SMALL_TEXT }),
                bold: emphasised,
                color,
                anchors,
                gap: 3.0 * m.s,
                ground: emphasised && over_colours,
            };
            if emphasised {
                first.push(request);
            } else {
                last.push(request);
            }
        }
    }
    for marker in &panel.markers {
        if let Some(label) = &marker.label
            && let Some(p) = frame.map((marker.x, marker.y)).filter(|p| frame.inside(*p))
        {
            first.push(place::Request {
                instead: Some(format!("{label}: {}", marker.name)),
                text: label.clone(),
                size: m.font(14.0),
                bold: true,
                color: BLACK,
                anchors: vec![p],
                gap: 8.0 * m.s,
                ground: false,
            });
        }
    }
    first.extend(last);
    let taken: Vec<_> = legend
        .iter()
        .filter(|b| !b.is_footer())
        .map(|b| b.rect())
        .collect();
    let (texts, instead) = place::place(first, &frame, &data, &taken, m);
    Some(PanelPlan {
        frame,
        colors,
        legend,
        x_ticks,
        y_ticks,
        texts,
        instead,
        data,
    })
}

/// Colour of a highlighted contour level and its label.
const HIGHLIGHT: RGBColor = RGBColor(200, 0, 0);

/// Colour of a contour line and its label: red for a highlighted level, white over a colour
/// map, else dark grey.
fn contour_color(highlighted: bool, over_colours: bool) -> RGBColor {
    if highlighted {
        HIGHLIGHT
    } else if over_colours {
        WHITE
    } else {
        RGBColor(60, 60, 60)
    }
}

/// The plan of every panel as drawn ([`shown_panels`]) with the metrics `m`.
fn panel_plans(fig: &Figure, m: &Metrics) -> Vec<Option<PanelPlan>> {
    let (pw, ph) = (m.px(m.panel.0), m.px(m.panel.1));
    shown_panels(fig)
        .iter()
        .enumerate()
        .map(|(k, panel)| {
            let (_, _, w) = panel_slot(fig.panels.len(), k, pw);
            plan_panel(panel, f64::from(w), f64::from(ph), m)
        })
        .collect()
}

/// Where each panel's frame, legend and texts go, as the PNG renderer draws them (pixels of
/// the panel's own area at the PNG scale), with the pixel positions of every series point and
/// marker inside the frame and of everything drawn as data. `None` for a panel with nothing to
/// draw.
pub fn panel_layouts(fig: &Figure) -> Vec<Option<PanelLayout>> {
    let m = Metrics::png(fig, &Print::default());
    let pw = m.px(m.panel.0);
    let panels = shown_panels(fig);
    panel_plans(fig, &m)
        .into_iter()
        .zip(panels.iter())
        .enumerate()
        .map(|(k, (plan, panel))| {
            let plan = plan?;
            let frame = plan.frame;
            let (_, _, width) = panel_slot(fig.panels.len(), k, pw);
            let points = panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().filter_map(|&p| frame.map(p)))
                .chain(panel.markers.iter().filter_map(|mk| frame.map((mk.x, mk.y))))
                .filter(|p| frame.inside(*p))
                .collect();
            let font = m.font(TICK_TEXT);
            let ticks = vec![
                tick_boxes(
                    &plan.x_ticks.0,
                    &|v| frame.tx(v),
                    true,
                    (frame.y1 + 5.0 * m.s, 0.0),
                    font,
                ),
                tick_boxes(
                    &plan.y_ticks.0,
                    &|v| frame.ty(v),
                    false,
                    (0.0, frame.x0 - 5.0 * m.s),
                    font,
                ),
            ];
            let head = heading(panel, frame.x0, f64::from(width), &m);
            let boxes: Vec<_> = plan
                .legend
                .iter()
                .filter(|b| !b.is_footer())
                .map(|b| b.rect())
                .collect();
            Some(PanelLayout {
                frame: (frame.x0, frame.x1, frame.y0, frame.y1),
                legend: plan.legend.first().map(LegendPlan::rect),
                notes: plan.legend.get(1).map(LegendPlan::rect),
                points,
                boxes,
                texts: plan.texts.iter().map(|t| (t.text.clone(), t.rect())).collect(),
                data: plan.data,
                ticks,
                heading_right: head.right(),
                width: f64::from(width),
            })
        })
        .collect()
}

/// A panel's layout in pixels ([`panel_layouts`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PanelLayout {
    /// Plotting frame: left, right, top, bottom.
    pub frame: (f64, f64, f64, f64),
    /// Legend box (with the panel's notes, unless they have a box of their own): left, top,
    /// right, bottom.
    pub legend: Option<(f64, f64, f64, f64)>,
    /// The notes' own box, where they did not fit in the legend's.
    pub notes: Option<(f64, f64, f64, f64)>,
    /// Every series point and marker inside the frame.
    pub points: Vec<(f64, f64)>,
    /// The legend's boxes drawn in the frame (left, top, right, bottom).
    pub boxes: Vec<(f64, f64, f64, f64)>,
    /// The texts drawn beside markers and contour lines, with their boxes (left, top, right,
    /// bottom).
    pub texts: Vec<(String, (f64, f64, f64, f64))>,
    /// Everything drawn as data, as pixel points: curves (a point every 8 pixels along them),
    /// markers, arrows, contour lines.
    pub data: Vec<(f64, f64)>,
    /// The boxes of the tick labels of the x and the y axis, in order along each.
    pub ticks: Vec<Vec<(f64, f64, f64, f64)>>,
    /// The right edge of the panel's heading.
    pub heading_right: f64,
    /// The width of the panel's area.
    pub width: f64,
}

fn draw_panel<DB: DrawingBackend>(area: &Area<DB>, panel: &Panel, m: &Metrics) -> Draw<()> {
    // The frame is laid out in a panel of the nominal height; notes under it extend the area.
    let (w, h) = (f64::from(area.dim_in_pixel().0), f64::from(m.px(m.panel.1)));
    let Some(plan) = plan_panel(panel, w, h, m) else {
        return draw_label(
            area,
            Label::new("no data", m.font(14.0)),
            (w / 2.0, h / 2.0),
            (Anchor::Middle, Baseline::Center),
            m,
        );
    };
    let PanelPlan {
        frame,
        colors,
        legend: legend_boxes,
        x_ticks: (xt, x_power),
        y_ticks: (yt, y_power),
        texts,
        ..
    } = plan;
    if !(frame.xr.1 > frame.xr.0 && frame.yr.1 > frame.yr.0) {
        return Err(format!("empty axis range in panel `{}`", panel.title));
    }
    let grey = RGBColor(225, 225, 225);

    // Field first.
    let mut bar_range = None;
    if let Some(field) = &panel.field {
        let filled = match &field.kind {
            FieldKind::Heat => true,
            FieldKind::Contour { filled, .. } => *filled,
        };
        if filled && let Some(range) = field.value_range() {
            // Vector cells for a grid of up to 128 × 128 (one rectangle each); a finer grid
            // goes into the SVG as one image of the frame's resolution.
            let fine = field.x.len() * field.y.len() > VECTOR_CELLS;
            if let Some(images) = m.images.as_ref().filter(|_| fine) {
                draw_heat_raster(area, &frame, field, range, images)?;
            } else {
                draw_heat(area, &frame, field, range)?;
            }
            bar_range = Some(range);
        }
    }

    // Grid.
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
        draw_contours(area, &frame, field, bar_range.is_some(), m)?;
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

    // Markers.
    for marker in &panel.markers {
        let color = rgb(palette(panel.marker_color(marker, &colors).unwrap_or(7)));
        if let Some(p) = frame.map((marker.x, marker.y)).filter(|p| frame.inside(*p)) {
            draw_marker(area, p, marker.shape, color, m)?;
        }
    }

    // Marker and contour labels, each where it covers no data ([`plan_panel`]).
    for t in &texts {
        if t.ground {
            // A light ground keeps a highlighted level's label readable over the dark map.
            let pad = 2.0 * m.s;
            let (x0, y0, x1, y1) = t.rect();
            let ground = [
                (x0 - pad, y0 - pad),
                (x1 + pad, y0 - pad),
                (x1 + pad, y1 + pad),
                (x0 - pad, y1 + pad),
            ];
            fill_polygon(area, &ground, WHITE.mix(0.8), m)?;
        }
        let label = Label::new(&t.text, t.size).color(t.color);
        let label = if t.bold { label.bold() } else { label };
        draw_label(area, label, (t.x, t.y), (Anchor::Start, Baseline::Top), m)?;
    }

    let titles = (
        scaled_title(&panel.x.label, &panel.x.unit, x_power),
        scaled_title(&panel.y.label, &panel.y.unit, y_power),
    );
    draw_axes(area, panel, &frame, (&xt, &yt), &titles, m)?;
    if let (Some(range), Some(field)) = (bar_range, &panel.field) {
        draw_colour_bar(area, &frame, field, range, m)?;
    }
    for plan in &legend_boxes {
        draw_legend(area, plan, m)?;
    }
    Ok(())
}

/// The contour lines of a field; the highlighted levels (a measured value) thicker, in red.
/// Their labels are placed with the panel's other texts ([`plan_panel`]).
fn draw_contours<DB: DrawingBackend>(
    area: &Area<DB>,
    frame: &Frame,
    field: &crate::figure::Field,
    over_colours: bool,
    m: &Metrics,
) -> Draw<()> {
    for level in field.contour_levels() {
        let emphasised = field.highlight.iter().any(|(l, _)| *l == level);
        let color = contour_color(emphasised, over_colours);
        for line in &field.contour(level) {
            for run in pixel_runs(frame, line) {
                let width = if emphasised { 2.6 } else { 1.0 } * m.s;
                draw_polyline(area, &run, color.to_rgba(), width, m)?;
            }
        }
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
    (x_title, y_title): &(String, String),
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
    let tick_font = m.font(TICK_TEXT);
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
        Label::new(x_title, label_font),
        (0.5 * (frame.x0 + frame.x1), frame.y1 + 46.0 * m.s),
        (Anchor::Middle, Baseline::Bottom),
        m,
    )?;
    let yl_x = (frame.x0 - widest - 12.0 * m.s - label_font).max(4.0 * m.s);
    draw_label(
        area,
        Label::new(y_title, label_font).vertical(),
        (yl_x, 0.5 * (frame.y0 + frame.y1)),
        (Anchor::Middle, Baseline::Top),
        m,
    )?;
    // The panel letter in bold at 9 pt, the title after it in bold ([`heading`]).
    let head = heading(panel, frame.x0, f64::from(area.dim_in_pixel().0), m);
    let at_top = frame.y0 - 8.0 * m.s;
    if !panel.label.is_empty() {
        let letter = Label::new(&panel.label, m.font(PANEL_LETTER)).bold();
        let first = at_top - head.row * (head.lines.len().max(1) - 1) as f64;
        draw_label(
            area,
            letter,
            (frame.x0, first),
            (Anchor::Start, Baseline::Bottom),
            m,
        )?;
    }
    let n = head.lines.len();
    for (k, line) in head.lines.iter().enumerate() {
        draw_label(
            area,
            Label::new(line, head.size).bold(),
            (head.x, at_top - head.row * (n - 1 - k) as f64),
            (Anchor::Start, Baseline::Bottom),
            m,
        )?;
    }
    Ok(())
}

/// A panel's heading as laid out: the title's lines, their size, the left edge of the title
/// (after the letter) and the distance between lines (pixels).
struct Heading {
    lines: Vec<String>,
    size: f64,
    x: f64,
    row: f64,
}

impl Heading {
    /// The right edge of the widest line (pixels of the panel's area).
    fn right(&self) -> f64 {
        self.lines
            .iter()
            .map(|l| self.x + crate::render::text::width(l, self.size, true))
            .fold(self.x, f64::max)
    }
}

/// The heading of a panel whose frame starts at `x0` in an area `area_w` pixels wide: the
/// letter in bold at 9 pt, then the title in bold at 8 pt on one line; where that is too
/// long, smaller down to 6 pt, else wrapped onto two lines (smaller where still too long,
/// never below 6 pt).
fn heading(panel: &Panel, x0: f64, area_w: f64, m: &Metrics) -> Heading {
    let letter = if panel.label.is_empty() {
        0.0
    } else {
        crate::render::text::width(&panel.label, m.font(PANEL_LETTER), true) + 0.35 * m.font(PANEL_LETTER)
    };
    let x = x0 + letter;
    let room = area_w - x - 4.0 * m.s;
    let size = m.font(15.0);
    let row = 1.2 * size;
    if panel.title.is_empty() {
        return Heading {
            lines: Vec::new(),
            size,
            x,
            row,
        };
    }
    let width = |t: &str, size: f64| crate::render::text::width(t, size, true);
    let one = width(&panel.title, size);
    if one <= room || size * room / one >= m.font(MIN_TEXT) {
        return Heading {
            lines: vec![panel.title.clone()],
            size: size.min(size * room / one),
            x,
            row,
        };
    }
    let mut lines = legend::wrap(&panel.title, size, room);
    if lines.len() > 2 {
        // Two lines at the least size, the rest of the words on the second.
        let least = legend::wrap(&panel.title, m.font(MIN_TEXT), room);
        lines = if least.len() <= 2 {
            least
        } else {
            vec![least[0].clone(), least[1..].join(" ")]
        };
    }
    let widest = lines.iter().map(|l| width(l, size)).fold(0.0, f64::max);
    let size = (size * room / widest).min(size).max(m.font(MIN_TEXT));
    Heading {
        lines,
        size,
        x,
        row: 1.2 * size,
    }
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
    let at = |v: f64| Some(frame.y1 - (v - lo) / (hi - lo).max(f64::MIN_POSITIVE) * (frame.y1 - frame.y0));
    let (bt, power) = spaced_ticks((lo, hi), Scale::Linear, 5, &at, false, m);
    let mut widest = 0.0f64;
    for (v, label) in bt.values.iter().zip(&bt.labels) {
        let y = frame.y1 - (v - lo) / (hi - lo).max(f64::MIN_POSITIVE) * (frame.y1 - frame.y0);
        draw_polyline(area, &[(bx1, y), (bx1 + 4.0 * m.s, y)], BLACK.to_rgba(), 1.0, m)?;
        let text = tick_markup(label);
        let label = Label::new(&text, m.font(SMALL_TEXT));
        widest = widest.max(label.width());
        draw_label(
            area,
            label,
            (bx1 + 6.0 * m.s, y),
            (Anchor::Start, Baseline::Center),
            m,
        )?;
    }
    let title = scaled_title(&field.name, &field.unit, power);
    // Along the bar, right of its tick labels (above the frame it would meet the heading).
    draw_label(
        area,
        Label::new(&title, m.font(SMALL_TEXT)).vertical(),
        (bx1 + 10.0 * m.s + widest, 0.5 * (frame.y0 + frame.y1)),
        (Anchor::Middle, Baseline::Top),
        m,
    )
}

/// Ticks of a linear axis whose labels would need powers of ten (`1.5e-5`, `2.0e-5`, ...)
/// relabelled with one power of ten for the whole axis: the mantissas (`1.5`, `2.0`) and the
/// exponent, which the axis title shows once ([`scaled_title`]). Other ticks are returned as
/// they are, with `None`.
fn common_power(t: super::axes::Ticks) -> (super::axes::Ticks, Option<i32>) {
    let sci = t.labels.iter().any(|l| l.contains('e'));
    let top = t.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(sci && top > 0.0 && top.is_finite() && t.minor.is_empty()) {
        return (t, None);
    }
    let k = top.log10().floor() as i32;
    let step = t
        .values
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let decimals = if step.is_finite() && step > 0.0 {
        (f64::from(k) - step.log10().floor()).clamp(0.0, 6.0) as usize
    } else {
        3
    };
    let f = 10f64.powi(k);
    let labels = t
        .values
        .iter()
        .map(|&v| {
            let s = format!("{:.decimals$}", v / f);
            if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                "0".into()
            } else {
                s.replace('-', "−")
            }
        })
        .collect();
    (super::axes::Ticks { labels, ..t }, Some(k))
}

/// The ticks of an axis from `lo` to `hi` whose labels do not run together where they are
/// drawn (`at` maps a value to its pixel along the axis; `horizontal` for labels side by side
/// under an x axis, else stacked beside a y axis or a colour bar): the ticks of [`ticks`] for
/// `target` intervals, else for fewer (at least three ticks), else every second (third, ...)
/// of them, keeping zero. Relabelled with a common power of ten ([`common_power`]).
fn spaced_ticks(
    (lo, hi): (f64, f64),
    scale: Scale,
    target: usize,
    at: &dyn Fn(f64) -> Option<f64>,
    horizontal: bool,
    m: &Metrics,
) -> (super::axes::Ticks, Option<i32>) {
    let font = m.font(TICK_TEXT);
    let apart = |t: &super::axes::Ticks| {
        tick_boxes(t, at, horizontal, (0.0, 0.0), font)
            .windows(2)
            .all(|w| !place::overlap(w[0], w[1], 0.4 * font))
    };
    let first = common_power(ticks(lo, hi, scale, target));
    if apart(&first.0) {
        return first;
    }
    for fewer in (3..target).rev() {
        let t = common_power(ticks(lo, hi, scale, fewer));
        if t.0.values.len() >= 3 && apart(&t.0) {
            return t;
        }
    }
    let (t, power) = first;
    let zero = t.values.iter().position(|v| *v == 0.0).unwrap_or(0);
    for k in 2..t.values.len().max(2) {
        let keep = |i: &usize| i % k == zero % k;
        let thin = super::axes::Ticks {
            values: (0..t.values.len()).filter(keep).map(|i| t.values[i]).collect(),
            labels: (0..t.labels.len())
                .filter(keep)
                .map(|i| t.labels[i].clone())
                .collect(),
            minor: t.minor.clone(),
        };
        if apart(&thin) || thin.values.len() <= 2 {
            return (thin, power);
        }
    }
    (t, power)
}

/// The boxes (left, top, right, bottom) of tick labels at `font` px: centred under their tick
/// below `edge.0` for an x axis (`horizontal`), else right-aligned left of `edge.1` and centred
/// on their tick; in order along the axis.
fn tick_boxes(
    t: &super::axes::Ticks,
    at: &dyn Fn(f64) -> Option<f64>,
    horizontal: bool,
    (below, right): (f64, f64),
    font: f64,
) -> Vec<(f64, f64, f64, f64)> {
    let h = place::text_height(font);
    let mut boxes: Vec<(f64, f64, f64, f64)> = t
        .values
        .iter()
        .zip(&t.labels)
        .filter_map(|(&v, l)| {
            let p = at(v)?;
            let w = crate::render::text::width(&tick_markup(l), font, false);
            Some(if horizontal {
                (p - 0.5 * w, below, p + 0.5 * w, below + h)
            } else {
                (right - w, p - 0.5 * h, right, p + 0.5 * h)
            })
        })
        .collect();
    let along = |b: &(f64, f64, f64, f64)| if horizontal { b.0 + b.2 } else { b.1 + b.3 };
    boxes.sort_by(|a, b| along(a).total_cmp(&along(b)));
    boxes
}

/// An axis (or colour-bar) title with its unit and the common power of ten of its ticks:
/// `label [10^{k} unit]`, `label ×10^{k}`, or `label [unit]` without one.
fn scaled_title(label: &str, unit: &str, power: Option<i32>) -> String {
    let power = power.map(|k| format!("10^{{{}}}", k.to_string().replace('-', "−")));
    match (unit.is_empty(), power) {
        (true, None) => label.to_string(),
        (false, None) => format!("{label} [{unit}]"),
        (true, Some(p)) => format!("{label} ×{p}"),
        (false, Some(p)) => format!("{label} [{p} {unit}]"),
    }
}

/// Size of the tick labels (layout units): 7 pt.
const TICK_TEXT: f64 = 7.0 / PT_PER_UNIT;

/// Size of the panel letters (layout units): 9 pt.
const PANEL_LETTER: f64 = 9.0 / PT_PER_UNIT;

/// The least size of any text (layout units): 6 pt at the figure's print size.
pub const MIN_TEXT: f64 = 6.0 / PT_PER_UNIT;

/// Size of the smallest texts, colour-bar ticks and contour labels (layout units): 6.1 pt.
const SMALL_TEXT: f64 = 11.5;

/// The text size, at most `size`, at which `text` is at most `room` pixels wide (never below
/// 70 % of `size` nor below [`MIN_TEXT`]: a longer text runs over rather than turning
/// unreadable).
fn fitting_size(text: &str, size: f64, bold: bool, room: f64, m: &Metrics) -> f64 {
    let w = crate::render::text::width(text, size, bold);
    if w <= room || w <= 0.0 {
        size
    } else {
        (size * room / w).max(0.7 * size).max(m.font(MIN_TEXT))
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
            let m = Metrics {
                s: 1.0,
                panel: (620.0, 460.0),
                images: None,
                texts: None,
                aa: true,
            };
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
