//! Where the texts drawn inside a panel's frame go (marker labels, contour labels): beside the
//! point they label, at the first of the candidate places around it (the eight around the
//! point, then the same further out) whose box stays in the frame, holds no drawn data (curves,
//! markers, arrows, contour lines) and overlaps neither the legend nor another text. A label
//! that must be shown and finds no free place is written in the notes under the figure instead.

use plotters::style::RGBColor;

use super::frame::{Frame, Metrics};

/// A text to place: what it says, how it is drawn, and the points it may sit beside.
pub(super) struct Request {
    /// Math markup.
    pub text: String,
    /// Size in pixels.
    pub size: f64,
    /// Bold face.
    pub bold: bool,
    /// Colour.
    pub color: RGBColor,
    /// Points the text may label, best first (pixels).
    pub anchors: Vec<(f64, f64)>,
    /// Distance of the box from its point (pixels): the size of a marker, or a line's width.
    pub gap: f64,
    /// A light ground under the text (a highlighted level over a colour map).
    pub ground: bool,
    /// What the notes under the figure say instead when no place is free; `None`: the text is
    /// left out (a contour level the colour bar also reads).
    pub instead: Option<String>,
}

/// A text with its place: the box's top-left corner and size (pixels of the panel's area).
pub(super) struct Placed {
    /// Math markup.
    pub text: String,
    /// Size in pixels.
    pub size: f64,
    /// Bold face.
    pub bold: bool,
    /// Colour.
    pub color: RGBColor,
    /// A light ground under the text.
    pub ground: bool,
    /// Left edge.
    pub x: f64,
    /// Top edge.
    pub y: f64,
    /// Width.
    pub w: f64,
    /// Height.
    pub h: f64,
}

impl Placed {
    /// The box: left, top, right, bottom.
    pub(super) fn rect(&self) -> (f64, f64, f64, f64) {
        (self.x, self.y, self.x + self.w, self.y + self.h)
    }
}

/// Height of a line of text of `size` pixels: from the top of the ascent to the bottom of the
/// descent.
pub(super) fn text_height(size: f64) -> f64 {
    (crate::render::text::ASCENT + crate::render::text::DESCENT) * size
}

/// Whether two boxes (left, top, right, bottom) overlap once the first is grown by `pad`.
pub(super) fn overlap(a: (f64, f64, f64, f64), b: (f64, f64, f64, f64), pad: f64) -> bool {
    a.0 - pad < b.2 && b.0 < a.2 + pad && a.1 - pad < b.3 && b.1 < a.3 + pad
}

/// Whether the box `r` (grown by `pad`) holds one of `points`; points nearer than `near` to
/// `anchor` (the labelled marker and the line through it) count only inside the box itself.
pub(super) fn holds_data(
    r: (f64, f64, f64, f64),
    points: &[(f64, f64)],
    pad: f64,
    anchor: (f64, f64),
    near: f64,
) -> bool {
    points.iter().any(|q| {
        let p = if (q.0 - anchor.0).hypot(q.1 - anchor.1) < near {
            0.0
        } else {
            pad
        };
        q.0 >= r.0 - p && q.0 <= r.2 + p && q.1 >= r.1 - p && q.1 <= r.3 + p
    })
}

/// The candidate top-left corners of a `w` × `h` box labelling `a` at distance `g`: upper
/// right (the usual place of a label), right, lower right, upper left, left, lower left,
/// above, below.
fn around(a: (f64, f64), (w, h): (f64, f64), g: f64) -> [(f64, f64); 8] {
    let d = 0.7 * g;
    [
        (a.0 + d, a.1 - d - h),
        (a.0 + g, a.1 - 0.5 * h),
        (a.0 + d, a.1 + d),
        (a.0 - d - w, a.1 - d - h),
        (a.0 - g - w, a.1 - 0.5 * h),
        (a.0 - d - w, a.1 + d),
        (a.0 - 0.5 * w, a.1 - g - h),
        (a.0 - 0.5 * w, a.1 + g),
    ]
}

/// Place `requests` in order, each clear of `data` and of the boxes `taken` (the legend's) and
/// of the texts placed before it. Returns the placed texts and the notes of the texts that must
/// be shown but found no place.
pub(super) fn place(
    requests: Vec<Request>,
    frame: &Frame,
    data: &[(f64, f64)],
    taken: &[(f64, f64, f64, f64)],
    m: &Metrics,
) -> (Vec<Placed>, Vec<String>) {
    let pad = 2.5 * m.s;
    let inset = 2.0 * m.s;
    let mut boxes: Vec<(f64, f64, f64, f64)> = taken.to_vec();
    let mut placed = Vec::new();
    let mut instead = Vec::new();
    for req in requests {
        let w = crate::render::text::width(&req.text, req.size, req.bold);
        let h = text_height(req.size);
        let free = |x: f64, y: f64, anchor: (f64, f64)| {
            let r = (x, y, x + w, y + h);
            r.0 >= frame.x0 + inset
                && r.2 <= frame.x1 - inset
                && r.1 >= frame.y0 + inset
                && r.3 <= frame.y1 - inset
                && !boxes.iter().any(|b| overlap(r, *b, pad))
                && !holds_data(r, data, pad, anchor, req.gap + pad)
        };
        let found = [1.0, 2.0, 3.5].iter().find_map(|k| {
            req.anchors.iter().find_map(|&a| {
                around(a, (w, h), k * req.gap)
                    .into_iter()
                    .find(|&(x, y)| free(x, y, a))
            })
        });
        match found {
            Some((x, y)) => {
                boxes.push((x, y, x + w, y + h));
                placed.push(Placed {
                    text: req.text,
                    size: req.size,
                    bold: req.bold,
                    color: req.color,
                    ground: req.ground,
                    x,
                    y,
                    w,
                    h,
                });
            }
            None => instead.extend(req.instead),
        }
    }
    (placed, instead)
}
