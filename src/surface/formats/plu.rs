//! Sensofar files (`.plu`, `.apx`; confocal, interferometric and focus-variation profilers):
//! a little-endian binary header of fixed layout, then the measured layers.
//!
//! Header fields used: the date (a text of 128 bytes at 0, NUL-padded), the points in y and x
//! (u32 at 388 and 392), the micrometres per pixel in x and y (f32 at 404 and 408), the
//! measurement type (u32 at 428: 3 a topography, 1 a profile), the number of layers (u8 at
//! 489). From byte 500 each layer is its points in y and x (u32, u32), the heights (f32 in
//! micrometres, x fastest, rows in y) and their minimum and maximum (f32, f32). A height of
//! exactly 1 000 001 marks a point not measured (missing). The layers are the channels `layer0`,
//! `layer1`, … of size points × micrometres per pixel, as SurfaceTopography reads them. A profile
//! is refused as a line scan (SurfaceTopography reads topographies only).

use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Num, Unit};
use crate::error::{Error, Result};

/// Start of the first layer.
const LAYERS: usize = 500;
/// The value of a point not measured.
const UNDEFINED: f64 = 1_000_001.0;

/// True when `bytes` look like a Sensofar file: a NUL-padded text date, the grid of the
/// calibration block repeated at the first layer, a known measurement type.
pub(crate) fn looks_like(bytes: &[u8]) -> bool {
    let r = Bytes { b: bytes, le: true };
    bytes.len() >= LAYERS + 8
        && bytes[..128].contains(&0)
        && bytes[..128]
            .iter()
            .take_while(|&&c| c != 0)
            .all(|&c| c.is_ascii_graphic() || c == b' ')
        && bytes[388..396] == bytes[LAYERS..LAYERS + 8]
        && matches!(r.u32(428), Some(1 | 3))
}

/// The layers of a Sensofar file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".plu: {m}"));
    if bytes.len() < LAYERS {
        return Err(super::truncated(path, ".plu header", LAYERS, bytes.len()));
    }
    let r = Bytes { b: bytes, le: true };
    let header = |at: usize| r.u32(at).expect("in header");
    if header(428) == 1 {
        return Err(err(
            "a profile: a line scan (1D profile); the surface analysis needs a 2D height map".into(),
        ));
    }
    if header(428) != 3 {
        return Err(err(format!(
            "measurement type {} is not a topography (3)",
            header(428)
        )));
    }
    let dx = f64::from(r.f32(404).expect("in header"));
    let dy = f64::from(r.f32(408).expect("in header"));
    if !(dx > 0.0 && dy > 0.0 && dx.is_finite() && dy.is_finite()) {
        return Err(err(format!(
            "micrometres per pixel {dx}, {dy} must be positive and finite"
        )));
    }
    let layers = usize::from(bytes[489]);
    let mut out = Vec::with_capacity(layers);
    let mut at = LAYERS;
    for k in 0..layers {
        let (Some(ny), Some(nx)) = (r.u32(at), r.u32(at + 4)) else {
            return Err(super::truncated(
                path,
                &format!(".plu layer {k}"),
                8,
                bytes.len().saturating_sub(at),
            ));
        };
        let (nx, ny) = (nx as usize, ny as usize);
        let info = ChannelInfo {
            name: format!("layer{k}"),
            nx,
            ny,
            size: Some([dx * nx as f64, dy * ny as f64]),
            xy_unit: Unit::named("µm"),
            z_unit: Unit::named("µm"),
            periodic: false,
        };
        info.check_grid(path)?;
        let start = at + 8;
        let n = nx * ny;
        let end = start + 4 * n + 8;
        if end > bytes.len() {
            return Err(super::truncated(
                path,
                &format!(".plu layer {k}"),
                4 * n + 8,
                bytes.len().saturating_sub(start),
            ));
        }
        let decode = move || -> Result<Vec<f64>> {
            let mut z = super::numbers(bytes, start, n, Num::F32, true, path, ".plu layer")?;
            for v in &mut z {
                if *v == UNDEFINED {
                    *v = f64::NAN;
                }
            }
            Ok(z)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
        at = end;
    }
    Ok(out)
}
