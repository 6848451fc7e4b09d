//! Heat maps of the figures: a field's cells in the viridis colour map under the frame, and
//! for SVG the same map rasterised into a PNG that is embedded as one `<image>` (instead of a
//! rectangle per cell).

use plotters::prelude::*;

use super::frame::{Area, Draw, Frame, err, ipt, rgb};
use crate::figure::Field;

/// Replace the placeholder rectangles of the heat maps (fill `#0102kk`, k the image index) by
/// the embedded PNG images, at the rectangles' position and size.
pub(super) fn embed_images(svg: &str, images: &[String]) -> String {
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
pub(super) fn base64(bytes: &[u8]) -> String {
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
pub(super) fn draw_heat_raster<DB: DrawingBackend>(
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
pub(super) fn draw_heat<DB: DrawingBackend>(
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
