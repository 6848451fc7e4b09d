//! Anti-aliased rasterisation of the PNG figures' strokes and fills: polylines of any width
//! (round caps and joins), polygons, discs and rings, as pixel coverages in (0, 1].
//!
//! The plotting library draws lines pixel by pixel without anti-aliasing, which leaves curves
//! of a figure visibly stepped. Here every primitive is given in floating-point pixel
//! coordinates (the centre of pixel (i, j) is the point (i, j)) and each pixel receives the
//! fraction of it the shape covers:
//!
//! - a stroke covers a pixel by `clamp(w/2 + 1/2 − d, 0, 1)`, d the distance from the pixel's
//!   centre to the polyline: the box-filtered coverage of a straight edge, exact for a line
//!   crossing a pixel at any angle up to the corners. One polyline is accumulated as the
//!   largest coverage per pixel before it is handed out, so its joins and overlapping
//!   segments are not blended twice;
//! - a polygon is scanned on four sub-rows per pixel row with the exact horizontal overlap of
//!   each span with each pixel (non-zero winding), i.e. a 4 × ∞ area sample;
//! - discs and rings use the distance to the centre, as strokes do.
//!
//! The cost is proportional to the pixels touched (length × width of a stroke), not to the
//! bounding box, so long diagonal hatch lines stay cheap. The renderer blends each coverage
//! into the bitmap with the colour's alpha.

/// Coverage of one shape, accumulated as the largest value per pixel inside a bounding box.
struct Accumulator {
    x0: i32,
    y0: i32,
    w: usize,
    h: usize,
    cov: Vec<f32>,
    touched: Vec<u32>,
}

impl Accumulator {
    fn new(bounds: (f64, f64, f64, f64), margin: f64) -> Option<Self> {
        let (xa, xb, ya, yb) = bounds;
        if !(xa.is_finite() && xb.is_finite() && ya.is_finite() && yb.is_finite()) {
            return None;
        }
        let x0 = (xa - margin).floor() as i32;
        let y0 = (ya - margin).floor() as i32;
        let x1 = (xb + margin).ceil() as i32;
        let y1 = (yb + margin).ceil() as i32;
        let (w, h) = ((x1 - x0 + 1).max(1) as usize, (y1 - y0 + 1).max(1) as usize);
        // A shape larger than any figure (a stray coordinate) is not drawn rather than
        // allocating without bound.
        if w.saturating_mul(h) > 64 << 20 {
            return None;
        }
        Some(Self {
            x0,
            y0,
            w,
            h,
            cov: vec![0.0; w * h],
            touched: Vec::new(),
        })
    }

    fn add(&mut self, x: i32, y: i32, c: f64) {
        let (i, j) = (x - self.x0, y - self.y0);
        if c <= 0.0 || i < 0 || j < 0 || i as usize >= self.w || j as usize >= self.h {
            return;
        }
        let k = j as usize * self.w + i as usize;
        let c = c.min(1.0) as f32;
        if self.cov[k] == 0.0 {
            self.touched.push(k as u32);
        }
        if c > self.cov[k] {
            self.cov[k] = c;
        }
    }

    fn emit(self, mut put: impl FnMut(i32, i32, f64)) {
        for k in self.touched {
            let k = k as usize;
            let (i, j) = (k % self.w, k / self.w);
            put(self.x0 + i as i32, self.y0 + j as i32, f64::from(self.cov[k]));
        }
    }
}

/// Bounding box of points: (x min, x max, y min, y max).
fn bounds(points: &[(f64, f64)]) -> (f64, f64, f64, f64) {
    points.iter().fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), p| (a.min(p.0), b.max(p.0), c.min(p.1), d.max(p.1)),
    )
}

/// Largest bounding box (pixels) of one accumulated piece of a stroke: a long curve across a
/// figure is split into pieces of about this size, so that the buffer cleared for each stays
/// small (the pieces share their end points; only the pixels of those joins are blended twice).
const PIECE_AREA: f64 = 65_536.0;

/// Coverage of a polyline of `width` pixels with round caps and joins: `put(x, y, coverage)`
/// once per covered pixel (once per piece at the joins of the pieces a long polyline is cut
/// into, see `PIECE_AREA`).
pub fn stroke(points: &[(f64, f64)], width: f64, mut put: impl FnMut(i32, i32, f64)) {
    if points.is_empty() || width.is_nan() || width <= 0.0 {
        return;
    }
    let margin = 0.5 * width + 2.0;
    let mut start = 0;
    while start + 1 < points.len() {
        // Grow the piece while its padded bounding box stays small (at least one segment).
        let mut end = start + 1;
        let (mut b0, mut b1, mut b2, mut b3) = bounds(&points[start..=end]);
        while end + 1 < points.len() {
            let q = points[end + 1];
            let (n0, n1, n2, n3) = (b0.min(q.0), b1.max(q.0), b2.min(q.1), b3.max(q.1));
            if (n1 - n0 + 2.0 * margin) * (n3 - n2 + 2.0 * margin) > PIECE_AREA {
                break;
            }
            (b0, b1, b2, b3) = (n0, n1, n2, n3);
            end += 1;
        }
        stroke_piece(&points[start..=end], width, &mut put);
        start = end;
    }
    if points.len() == 1 {
        stroke_piece(points, width, &mut put);
    }
}

/// [`stroke`] of one piece, accumulated in one buffer.
fn stroke_piece(points: &[(f64, f64)], width: f64, put: impl FnMut(i32, i32, f64)) {
    let r = 0.5 * width;
    let Some(mut acc) = Accumulator::new(bounds(points), r + 2.0) else {
        return;
    };
    // Lines thinner than a pixel keep their width as a fainter line one pixel wide.
    let (r_eff, scale) = if width < 1.0 { (0.5, width) } else { (r, 1.0) };
    let single = [points[0], points[0]];
    let segments: Box<dyn Iterator<Item = &[(f64, f64)]>> = if points.len() == 1 {
        Box::new(std::iter::once(&single[..]))
    } else {
        Box::new(points.windows(2))
    };
    for seg in segments {
        let (a, b) = (seg[0], seg[1]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        let cover = |x: i32, y: i32| {
            let d = crate::figure::segment_distance((f64::from(x), f64::from(y)), a, b);
            scale * (r_eff + 0.5 - d).clamp(0.0, 1.0)
        };
        // March along the major axis; across it, the pixels within reach of the line.
        let x_major = dx.abs() >= dy.abs();
        let (u0, u1, cos) = if x_major {
            (
                a.0.min(b.0),
                a.0.max(b.0),
                if len > 0.0 { dx.abs() / len } else { 1.0 },
            )
        } else {
            (a.1.min(b.1), a.1.max(b.1), dy.abs() / len)
        };
        let reach = r_eff / cos + 1.5;
        let first = (u0 - r_eff - 1.0).floor() as i32;
        let last = (u1 + r_eff + 1.0).ceil() as i32;
        for u in first..=last {
            let uf = f64::from(u);
            let t = if len > 0.0 {
                if x_major {
                    ((uf - a.0) / dx).clamp(0.0, 1.0)
                } else {
                    ((uf - a.1) / dy).clamp(0.0, 1.0)
                }
            } else {
                0.0
            };
            let t = if t.is_finite() { t } else { 0.0 };
            let centre = if x_major { a.1 + t * dy } else { a.0 + t * dx };
            let (v0, v1) = ((centre - reach).floor() as i32, (centre + reach).ceil() as i32);
            for v in v0..=v1 {
                let (x, y) = if x_major { (u, v) } else { (v, u) };
                acc.add(x, y, cover(x, y));
            }
        }
    }
    acc.emit(put);
}

/// Sub-rows per pixel row of [`fill`].
const SUB_ROWS: usize = 4;

/// Coverage of a closed polygon (the last point joins the first; non-zero winding):
/// `put(x, y, coverage)` once per covered pixel.
pub fn fill(poly: &[(f64, f64)], mut put: impl FnMut(i32, i32, f64)) {
    if poly.len() < 3 || poly.iter().any(|p| !(p.0.is_finite() && p.1.is_finite())) {
        return;
    }
    let (xa, xb, ya, yb) = bounds(poly);
    let (x0, x1) = ((xa - 1.0).floor() as i32, (xb + 1.0).ceil() as i32);
    let (j0, j1) = ((ya - 0.5).floor() as i32, (yb + 0.5).ceil() as i32);
    let w = (x1 - x0 + 1) as usize;
    if w.saturating_mul((j1 - j0 + 1).max(0) as usize) > 64 << 20 {
        return;
    }
    let mut row = vec![0.0f64; w];
    let mut crossings: Vec<(f64, i32)> = Vec::new();
    for j in j0..=j1 {
        row.iter_mut().for_each(|c| *c = 0.0);
        let mut any = false;
        for s in 0..SUB_ROWS {
            let y = f64::from(j) - 0.5 + (s as f64 + 0.5) / SUB_ROWS as f64;
            crossings.clear();
            for k in 0..poly.len() {
                let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                if (a.1 <= y) != (b.1 <= y) {
                    let t = (y - a.1) / (b.1 - a.1);
                    crossings.push((a.0 + t * (b.0 - a.0), if b.1 > a.1 { 1 } else { -1 }));
                }
            }
            crossings.sort_by(|p, q| p.0.total_cmp(&q.0));
            let mut winding = 0;
            for pair in crossings.windows(2) {
                winding += pair[0].1;
                if winding == 0 {
                    continue;
                }
                let (sa, sb) = (pair[0].0, pair[1].0);
                if sb <= sa {
                    continue;
                }
                any = true;
                // Pixel i spans [i − 1/2, i + 1/2).
                let (ia, ib) = ((sa + 0.5).floor() as i32, (sb + 0.5).floor() as i32);
                for i in ia.max(x0)..=ib.min(x1) {
                    let lo = sa.max(f64::from(i) - 0.5);
                    let hi = sb.min(f64::from(i) + 0.5);
                    if hi > lo {
                        row[(i - x0) as usize] += (hi - lo) / SUB_ROWS as f64;
                    }
                }
            }
        }
        if any {
            for (k, &c) in row.iter().enumerate() {
                if c > 1e-4 {
                    put(x0 + k as i32, j, c.min(1.0));
                }
            }
        }
    }
}

/// Coverage of a filled disc of radius `r` about `c`.
pub fn disc(c: (f64, f64), r: f64, mut put: impl FnMut(i32, i32, f64)) {
    if !(r > 0.0 && c.0.is_finite() && c.1.is_finite()) {
        return;
    }
    let (ya, yb) = ((c.1 - r - 1.0).floor() as i32, (c.1 + r + 1.0).ceil() as i32);
    let (xa, xb) = ((c.0 - r - 1.0).floor() as i32, (c.0 + r + 1.0).ceil() as i32);
    for y in ya..=yb {
        for x in xa..=xb {
            let d = (f64::from(x) - c.0).hypot(f64::from(y) - c.1);
            let cov = (r + 0.5 - d).clamp(0.0, 1.0);
            if cov > 0.0 {
                put(x, y, cov);
            }
        }
    }
}

/// Coverage of a circle of radius `r` about `c` drawn with a line `width` pixels wide.
pub fn ring(c: (f64, f64), r: f64, width: f64, mut put: impl FnMut(i32, i32, f64)) {
    if !(r > 0.0 && width > 0.0 && c.0.is_finite() && c.1.is_finite()) {
        return;
    }
    let half = 0.5 * width;
    let reach = r + half + 1.0;
    let (ya, yb) = ((c.1 - reach).floor() as i32, (c.1 + reach).ceil() as i32);
    let (xa, xb) = ((c.0 - reach).floor() as i32, (c.0 + reach).ceil() as i32);
    for y in ya..=yb {
        for x in xa..=xb {
            let d = (f64::from(x) - c.0).hypot(f64::from(y) - c.1);
            let cov = (half + 0.5 - (d - r).abs()).clamp(0.0, 1.0);
            if cov > 0.0 {
                put(x, y, cov);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn collect(f: impl FnOnce(&mut dyn FnMut(i32, i32, f64))) -> HashMap<(i32, i32), f64> {
        let mut m = HashMap::new();
        f(&mut |x, y, c| {
            *m.entry((x, y)).or_insert(0.0) += c;
        });
        m
    }

    #[test]
    fn a_stroke_covers_its_area_and_each_pixel_once() {
        // A 40 px diagonal of width 3: the covered area is the capsule's, 40·3 + π·1.5²,
        // to within the box-filter's error at the two caps.
        let m = collect(|put| stroke(&[(10.0, 10.0), (38.28, 38.28)], 3.0, put));
        let area: f64 = m.values().sum();
        let exact = 40.0 * 3.0 + std::f64::consts::PI * 1.5 * 1.5;
        assert!((area - exact).abs() < 0.03 * exact, "{area} vs {exact}");
        assert!(m.values().all(|&c| c > 0.0 && c <= 1.0));
        // Intermediate levels along the edges: the line is anti-aliased.
        let partial = m.values().filter(|&&c| c > 0.05 && c < 0.95).count();
        assert!(partial > 40, "{partial}");
    }

    #[test]
    fn a_long_curve_cut_into_pieces_covers_its_area() {
        // A sine across 2 000 px, 4 px wide: far larger than one piece's buffer.
        let pts: Vec<(f64, f64)> = (0..=2000)
            .map(|i| {
                let x = f64::from(i);
                (x, 500.0 + 300.0 * (x / 200.0).sin())
            })
            .collect();
        let length: f64 = pts
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .sum();
        let m = collect(|put| stroke(&pts, 4.0, put));
        let area: f64 = m.values().sum();
        let exact = 4.0 * length + std::f64::consts::PI * 4.0;
        assert!((area - exact).abs() < 0.01 * exact, "{area} vs {exact}");
    }

    #[test]
    fn joins_of_a_polyline_are_not_counted_twice() {
        let m = collect(|put| stroke(&[(0.0, 0.0), (20.0, 0.0), (20.0, 20.0)], 2.0, put));
        assert!(m.values().all(|&c| c <= 1.0 + 1e-12));
        // A horizontal line of width 1 at an integer row fills that row alone.
        let h = collect(|put| stroke(&[(0.0, 5.0), (10.0, 5.0)], 1.0, put));
        assert!((0..=10).all(|x| (h[&(x, 5)] - 1.0).abs() < 1e-12));
        assert!(!h.contains_key(&(5, 4)) && !h.contains_key(&(5, 6)));
    }

    #[test]
    fn a_filled_polygon_covers_its_area() {
        // A triangle of area 0.5 · 30 · 20 = 300 with fractional corners.
        let m = collect(|put| fill(&[(3.3, 4.7), (33.3, 4.7), (3.3, 24.7)], put));
        let area: f64 = m.values().sum();
        assert!((area - 300.0).abs() < 3.0, "{area}");
        let d = collect(|put| disc((10.2, 10.7), 5.0, put));
        let area: f64 = d.values().sum();
        assert!((area - std::f64::consts::PI * 25.0).abs() < 0.5, "{area}");
        let r = collect(|put| ring((10.0, 10.0), 6.0, 2.0, put));
        let area: f64 = r.values().sum();
        let exact = std::f64::consts::PI * (7.0f64.powi(2) - 5.0f64.powi(2));
        assert!((area - exact).abs() < 0.02 * exact, "{area} vs {exact}");
    }
}
