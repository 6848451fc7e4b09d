//! The legend of a panel: one entry per series name, region and marker kind, followed by the
//! panel's notes (wrapped text without a swatch), in a box placed where it covers no data.

use plotters::prelude::*;

use super::draw::{
    Anchor, Baseline, Label, draw_hatched, draw_label, draw_marker, draw_pixel_line, draw_polyline,
    draw_ring, fill_polygon, pixel_runs,
};
use super::frame::{Area, Draw, Frame, Metrics, err, ipt, palette, rgb};
use crate::figure::{Legend, MarkerShape, Panel, Style};

/// What a legend entry shows before its text.
#[derive(Clone)]
enum Swatch {
    /// A line (or scatter circle, error bar) in a style and colour.
    Line(Style, RGBColor),
    /// A marker shape in one or more colours.
    Marker(MarkerShape, Vec<RGBColor>),
    /// A translucent fill.
    Fill(RGBColor),
    /// A hatched outline.
    Hatch(RGBColor, usize),
    /// Nothing: a line of a note, written across the swatch column.
    Note,
}

/// Colour of the notes' text.
const NOTE_GREY: RGBColor = RGBColor(70, 70, 70);

/// Widest line of a note, in units of the frame's width.
const NOTE_WIDTH: f64 = 0.5;

/// Distance of notes written under a panel from the bottom of its frame, at scale 1 (below the
/// tick labels and the x-axis title).
pub(super) const FOOTER_OFFSET: f64 = 52.0;

/// A legend ready to draw: its entries and its box in pixels.
pub(super) struct LegendPlan {
    entries: Vec<(String, Swatch)>,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
    row: f64,
    pad: f64,
    swatch_w: f64,
    font: f64,
    /// Notes written under the panel's x-axis title, without a box (where no box fits inside).
    footer: bool,
}

impl LegendPlan {
    /// Whether these are notes written under the panel rather than a box in the frame.
    pub(super) fn is_footer(&self) -> bool {
        self.footer
    }

    /// The bottom edge (pixels of the panel's area).
    pub(super) fn bottom(&self) -> f64 {
        self.y + self.h
    }

    /// The box: left, top, right, bottom (pixels of the panel's area).
    pub(super) fn rect(&self) -> (f64, f64, f64, f64) {
        (self.x, self.y, self.x + self.w, self.y + self.h)
    }
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

/// The names of a panel's legend entries, in order (empty for a hidden legend).
pub(super) fn entry_names(panel: &Panel) -> Vec<String> {
    legend_entries(panel, &panel.series_colors())
        .into_iter()
        .map(|(n, _)| n)
        .collect()
}

/// Pixel positions of everything a legend must not cover: the series drawn as lines (densified,
/// so that a line crossing a box counts), the series points and the markers.
pub(super) fn covered_points(panel: &Panel, frame: &Frame) -> Vec<(f64, f64)> {
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
/// the middles of the edges inside the frame. The panel's notes go under the legend entries in
/// the same box; when that box fits nowhere, the legend and the notes are placed as two boxes
/// (the notes' box also clear of the legend's); failing that, the notes are written under the
/// panel, below the x-axis title (the figure grows to hold them), and the legend alone placed
/// in the frame. When even that fails, the legend goes outside the frame on the right (the
/// frame narrows to make room) and the notes under the panel.
/// Returns the frame to draw in and the boxes.
pub(super) fn plan_legend(
    panel: &Panel,
    frame: Frame,
    colors: &[usize],
    m: &Metrics,
    panel_w: f64,
    has_bar: bool,
) -> (Frame, Vec<LegendPlan>) {
    let entries = legend_entries(panel, colors);
    let font = m.font(12.5);
    let swatch_w = 30.0 * m.s;
    let pad = 7.0 * m.s;
    let row = font * 1.45;
    let width = |t: &str| crate::render::text::width(t, font, false);
    let text_w = entries.iter().map(|(n, _)| width(n)).fold(0.0, f64::max);
    // Notes wrap at half the frame's width, or at the entries' width where that is wider.
    let note_limit = (NOTE_WIDTH * (frame.x1 - frame.x0)).max(swatch_w + pad + text_w);
    let notes: Vec<(String, Swatch)> = panel
        .notes
        .iter()
        .flat_map(|n| wrap(n, font, note_limit))
        .map(|line| (line, Swatch::Note))
        .collect();
    let boxed = |entries: Vec<(String, Swatch)>| -> Option<LegendPlan> {
        if entries.is_empty() {
            return None;
        }
        let (mut item_w, mut note_w) = (0.0f64, 0.0f64);
        for (n, sw) in &entries {
            if matches!(sw, Swatch::Note) {
                note_w = note_w.max(width(n));
            } else {
                item_w = item_w.max(width(n));
            }
        }
        let w = if item_w > 0.0 {
            swatch_w + 3.0 * pad + item_w
        } else {
            0.0
        }
        .max(2.0 * pad + note_w);
        let h = row * entries.len() as f64 + 2.0 * pad - 0.3 * row;
        Some(LegendPlan {
            entries,
            x: 0.0,
            y: 0.0,
            w,
            h,
            row,
            pad,
            swatch_w,
            font,
            footer: false,
        })
    };
    let points = covered_points(panel, &frame);
    let place = |mut plan: LegendPlan, avoid: Option<&LegendPlan>| -> Result<LegendPlan, LegendPlan> {
        match free_place(panel.legend, &frame, &points, (plan.w, plan.h), pad, avoid, m) {
            Some((x, y)) => {
                plan.x = x;
                plan.y = y;
                Ok(plan)
            }
            None => Err(plan),
        }
    };
    let all: Vec<(String, Swatch)> = entries.iter().chain(&notes).cloned().collect();
    let Some(combined) = boxed(all) else {
        return (frame, Vec::new());
    };
    let combined = match place(combined, None) {
        Ok(plan) => return (frame, vec![plan]),
        Err(plan) => plan,
    };
    if !entries.is_empty()
        && !notes.is_empty()
        && let (Some(legend), Some(note_box)) = (boxed(entries.clone()), boxed(notes.clone()))
        && let Ok(legend) = place(legend, None)
        && let Ok(note_box) = place(note_box, Some(&legend))
    {
        return (frame, vec![legend, note_box]);
    }
    // The notes written under the panel, across the frame's width (the panel grows to hold them).
    let footer_under = |frame: &Frame| -> Option<LegendPlan> {
        let lines: Vec<(String, Swatch)> = panel
            .notes
            .iter()
            .flat_map(|n| wrap(n, font, frame.x1 - frame.x0))
            .map(|line| (line, Swatch::Note))
            .collect();
        let mut f = boxed(lines)?;
        f.footer = true;
        f.x = frame.x0 - pad;
        f.y = frame.y1 + FOOTER_OFFSET * m.s;
        Some(f)
    };
    if !notes.is_empty() {
        let legend = if entries.is_empty() {
            Some(None)
        } else {
            boxed(entries.clone()).and_then(|plan| place(plan, None).ok().map(Some))
        };
        if let (Some(legend), Some(footer)) = (legend, footer_under(&frame)) {
            return (frame, legend.into_iter().chain([footer]).collect());
        }
    }
    // Outside on the right, beyond the colour bar if there is one, where the frame keeps most
    // of its width; else under the panel, below the x-axis title (the panel grows to hold it).
    let right_margin = if has_bar { 110.0 } else { 16.0 } * m.s;
    let legend_w = boxed(entries.clone()).map_or(combined.w, |l| l.w);
    if panel_w - legend_w - 6.0 * m.s - right_margin < frame.x0 + 0.55 * (frame.x1 - frame.x0) {
        let mut plan = combined;
        plan.footer = true;
        plan.x = frame.x0 - pad;
        plan.y = frame.y1 + FOOTER_OFFSET * m.s;
        return (frame, vec![plan]);
    }
    // The notes, if any, under the panel, so that the frame narrows only by the legend's width.
    let (mut plan, footer) = match (boxed(entries), notes.is_empty()) {
        (Some(legend), false) => (legend, true),
        _ => (combined, false),
    };
    let x = panel_w - plan.w - 6.0 * m.s;
    let x1 = (x - right_margin).max(frame.x0 + 0.3 * (frame.x1 - frame.x0));
    let frame = Frame { x1, ..frame };
    plan.x = x;
    plan.y = frame.y0;
    let mut boxes = vec![plan];
    if footer {
        boxes.extend(footer_under(&frame));
    }
    (frame, boxes)
}

/// The first place for a box of `size` inside the frame that holds none of `points` (with
/// `pad` around it) and does not overlap `avoid`: the preferred corner, the other corners, the
/// middles of the edges.
fn free_place(
    preferred: Legend,
    frame: &Frame,
    points: &[(f64, f64)],
    (box_w, box_h): (f64, f64),
    pad: f64,
    avoid: Option<&LegendPlan>,
    m: &Metrics,
) -> Option<(f64, f64)> {
    let inset = 8.0 * m.s;
    let (l, r) = (frame.x0 + inset, frame.x1 - inset - box_w);
    let (t, b) = (frame.y0 + inset, frame.y1 - inset - box_h);
    if r < l || b < t {
        return None;
    }
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
        .position(|c| c.0 == preferred && c.0 != Legend::Auto)
    {
        let c = candidates.remove(k);
        candidates.insert(0, c);
    }
    let clear = |x: f64, y: f64| {
        let no_point = !points
            .iter()
            .any(|p| p.0 >= x - pad && p.0 <= x + box_w + pad && p.1 >= y - pad && p.1 <= y + box_h + pad);
        let apart = avoid.is_none_or(|a| {
            x + box_w + pad <= a.x || a.x + a.w + pad <= x || y + box_h + pad <= a.y || a.y + a.h + pad <= y
        });
        no_point && apart
    };
    candidates
        .into_iter()
        .find(|(_, x, y)| clear(*x, *y))
        .map(|(_, x, y)| (x, y))
}

pub(super) fn draw_legend<DB: DrawingBackend>(area: &Area<DB>, plan: &LegendPlan, m: &Metrics) -> Draw<()> {
    let (bx, by, box_w, box_h) = (plan.x, plan.y, plan.w, plan.h);
    let (row, pad, swatch_w) = (plan.row, plan.pad, plan.swatch_w);
    if !plan.footer {
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
    }
    for (k, (name, swatch)) in plan.entries.iter().enumerate() {
        let y = by + pad + row * (k as f64 + 0.35);
        let x0 = bx + pad;
        let x1 = x0 + swatch_w;
        match swatch {
            Swatch::Line(style, c) => match style {
                Style::Scatter => {
                    draw_ring(area, (0.5 * (x0 + x1), y), 3.4 * m.s, 1.3 * m.s, c.to_rgba(), m)?;
                }
                Style::ErrorBar => {
                    let (xm, cap) = (0.5 * (x0 + x1), 4.0 * m.s);
                    let (ya, yb) = (y - 6.0 * m.s, y + 6.0 * m.s);
                    let wdt = (1.3 * m.s).round();
                    draw_polyline(area, &[(xm, ya), (xm, yb)], c.to_rgba(), wdt, m)?;
                    draw_polyline(area, &[(xm - cap, ya), (xm + cap, ya)], c.to_rgba(), wdt, m)?;
                    draw_polyline(area, &[(xm - cap, yb), (xm + cap, yb)], c.to_rgba(), wdt, m)?;
                }
                other => draw_pixel_line(area, &[(x0, y), (x1, y)], *other, *c, m)?,
            },
            Swatch::Marker(shape, cols) => {
                // Up to four colours side by side, smaller when there are several.
                let k = cols.len().clamp(1, 4);
                let step = (x1 - x0) / k as f64;
                let mm = Metrics {
                    s: if k > 1 { m.s * 0.75 } else { m.s },
                    panel: m.panel,
                    images: None,
                    texts: None,
                    aa: m.aa,
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
                let poly = [
                    (x0, y - 5.0 * m.s),
                    (x1, y - 5.0 * m.s),
                    (x1, y + 5.0 * m.s),
                    (x0, y + 5.0 * m.s),
                ];
                fill_polygon(area, &poly, c.mix(0.25), m)?;
            }
            Swatch::Note => {
                draw_label(
                    area,
                    Label::new(name, plan.font).color(NOTE_GREY),
                    (x0, y),
                    (Anchor::Start, Baseline::Center),
                    m,
                )?;
                continue;
            }
        }
        draw_label(
            area,
            Label::new(name, plan.font),
            (x1 + pad, y),
            (Anchor::Start, Baseline::Center),
            m,
        )?;
    }
    Ok(())
}

/// Pixel points along a series, with extra points on long segments so that a line crossing
/// a legend candidate box counts as covering it.
pub(super) fn densify(frame: &Frame, points: &[(f64, f64)]) -> Vec<(f64, f64)> {
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

/// Split a note or heading into lines of at most `limit` pixels at `font` px, at spaces (a
/// word longer than the limit stays whole), never inside a value: not before or after `=` (or
/// another relation), nor around the `×` of a power of ten, nor between a number and its unit,
/// so that `h/R = −2.08 × 10⁻⁴` and `358 nm` stay on one line.
pub(super) fn wrap(note: &str, font: f64, limit: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in unbreakable(note) {
        let candidate = if line.is_empty() {
            word.clone()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && crate::render::text::width(&candidate, font, false) > limit {
            lines.push(std::mem::replace(&mut line, word));
        } else {
            line = candidate;
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// The words of a text, those that must share a line ([`wrap`]) joined by their space.
fn unbreakable(text: &str) -> Vec<String> {
    const RELATIONS: [&str; 9] = ["=", "≈", "≤", "≥", "<", ">", "±", "×", "~"];
    const UNITS: [&str; 21] = [
        "nm", "µm", "um", "mm", "m", "N", "nN", "µN", "mN", "Pa", "kPa", "MPa", "GPa", "J", "J/m²", "mJ/m²",
        "%", "s", "b", "ζ0", "°",
    ];
    let number = |w: &str| {
        let w = w.trim_start_matches(['−', '-', '+', '(']);
        w.starts_with(|c: char| c.is_ascii_digit())
            && w.chars()
                .all(|c| c.is_ascii_digit() || ".⁰¹²³⁴⁵⁶⁷⁸⁹⁻".contains(c))
    };
    let unit = |w: &str| UNITS.contains(&w.trim_end_matches([',', ';', ':', '.', ')']));
    let mut out: Vec<String> = Vec::new();
    let mut prev: Option<&str> = None;
    for word in text.split_whitespace() {
        let glued = prev.is_some_and(|p| {
            RELATIONS.iter().any(|r| p.ends_with(r) || word.starts_with(r)) || (number(p) && unit(word))
        });
        match out.last_mut() {
            Some(last) if glued => {
                last.push(' ');
                last.push_str(word);
            }
            _ => out.push(word.to_string()),
        }
        prev = Some(word);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_wrap_at_spaces_within_the_limit() {
        let note = "in this model (5.37) fits every n; the text finds deviations for n = 9-11";
        let lines = wrap(note, 25.0, 300.0);
        assert!(lines.len() > 1, "{lines:?}");
        assert_eq!(lines.join(" "), note);
        for l in &lines {
            assert!(crate::render::text::width(l, 25.0, false) <= 300.0, "{l}");
        }
    }

    #[test]
    fn values_are_not_split_by_the_wrapping() {
        let heading = "A = 3.125 nm, h/R = −2.08 × 10⁻⁴, a = 378 nm";
        for limit in [60.0, 150.0, 250.0, 400.0] {
            let lines = wrap(heading, 25.0, limit);
            assert_eq!(lines.join(" "), heading);
            for l in &lines {
                for cut in ["=", "×", "−2.08", "3.125", "378"] {
                    assert!(!l.ends_with(cut), "{lines:?} breaks after {cut:?}");
                }
                for cut in ["=", "×", "10⁻⁴", "nm"] {
                    assert!(!l.starts_with(cut), "{lines:?} breaks before {cut:?}");
                }
            }
        }
        // Ordinary words still wrap.
        assert_eq!(unbreakable("the 2 rings at h/R = 1").len(), 5);
    }
}
