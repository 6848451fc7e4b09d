//! The pixel frame of a drawing, shared by the figure and its drawing modules: the metrics of a
//! drawing (pixels per layout unit, the panel size, the SVG collections), a panel's plotting
//! rectangle and its data-to-pixel mapping, the colour palette, and the small conversions to
//! plotters' types.

use plotters::coord::Shift;
use plotters::prelude::*;

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

/// Layout of one drawing: pixels per layout unit, the panel size, and for SVG output the
/// raster images of the fields and the texts.
pub(super) struct Metrics {
    pub(super) s: f64,
    /// Width and height of a panel (layout units).
    pub(super) panel: (f64, f64),
    /// `Some` when drawing SVG: the heat maps go in as embedded PNG images, collected here.
    pub(super) images: Option<std::rc::Rc<std::cell::RefCell<Vec<String>>>>,
    /// `Some` when drawing SVG: the labels in math markup, as `<text>` elements with
    /// `<tspan>`s, appended after the drawing.
    pub(super) texts: Option<std::rc::Rc<std::cell::RefCell<Vec<String>>>>,
    /// Rasterise strokes and fills here with anti-aliasing (PNG); `false` hands them to the
    /// backend as shapes (SVG).
    pub(super) aa: bool,
}

impl Metrics {
    pub(super) fn px(&self, v: f64) -> i32 {
        (v * self.s).round() as i32
    }
    pub(super) fn font(&self, size: f64) -> f64 {
        size * self.s
    }
}

pub(super) type Area<DB> = DrawingArea<DB, Shift>;
pub(super) type Draw<T> = std::result::Result<T, String>;

pub(super) fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

pub(super) fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Pixel mapping of a panel's plotting rectangle.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y0: f64,
    pub(super) y1: f64,
    /// Data ranges (log10 for log axes).
    pub(super) xr: (f64, f64),
    pub(super) yr: (f64, f64),
    pub(super) xlog: bool,
    pub(super) ylog: bool,
}

impl Frame {
    pub(super) fn tx(&self, x: f64) -> Option<f64> {
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
    pub(super) fn ty(&self, y: f64) -> Option<f64> {
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
    pub(super) fn map(&self, p: (f64, f64)) -> Option<(f64, f64)> {
        Some((self.tx(p.0)?, self.ty(p.1)?))
    }
    pub(super) fn inside(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 - 0.5 && p.0 <= self.x1 + 0.5 && p.1 >= self.y0 - 0.5 && p.1 <= self.y1 + 0.5
    }
    /// Clip a segment to the frame (Liang-Barsky).
    pub(super) fn clip(&self, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
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

pub(super) fn ipt(p: (f64, f64)) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}
