//! Digital Surf files (`.sur`, uncompressed): one or more objects, each a 512-byte header, a
//! comment, a private zone and the data (int16 or int32, x fastest).
//!
//! Header fields used (little-endian for `format` 0, big-endian for 257): object name (20), the
//! special-points flag (86), item size in bits (98), points in x and y (108, 112), point count
//! (116), spacings in x and y (120, 124, f32, in the `delta` units at 180 and 196), height scale
//! (128, f32, in the data `delta` unit at 212), comment and private sizes (334, 336). Heights are
//! the stored integers times the scale, without the header's z offset, as SurfaceTopography
//! reads them (the offset does not change a height map's statistics about its mean). A profile
//! (one row) is a line scan.

use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Num, Unit, cstr};
use crate::error::{Error, Result};

const HEADER: usize = 512;

/// The objects of a `.sur` file, one channel each.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".sur: {m}"));
    if bytes.starts_with(b"DSCOMPRESSED") {
        return Err(err(
            "compressed Digital Surf files are not read; save it uncompressed".into(),
        ));
    }
    let mut out = Vec::new();
    let mut at = 0usize;
    let mut objects = 1usize;
    let mut k = 0usize;
    while k < objects {
        let h = bytes.get(at..at.saturating_add(HEADER)).ok_or_else(|| {
            super::truncated(
                path,
                &format!(".sur header of object {}", k + 1),
                HEADER,
                bytes.len().saturating_sub(at),
            )
        })?;
        if !h.starts_with(b"DIGITAL SURF") {
            return Err(err(format!("object {} does not start with DIGITAL SURF", k + 1)));
        }
        let le = match u16::from_le_bytes([h[12], h[13]]) {
            0 => true,
            257 => false,
            f => {
                return Err(err(format!(
                    "byte-order field {f} is neither 0 (PC) nor 257 (Mac)"
                )));
            }
        };
        let r = Bytes { b: h, le };
        let get16 = |o: usize| usize::from(r.u16(o).expect("in header"));
        if k == 0 {
            objects = get16(14).max(1);
        }
        let bits = get16(98);
        let num = match bits {
            16 => Num::I16,
            32 => Num::I32,
            other => return Err(err(format!("item size of {other} bits is not read (16 or 32)"))),
        };
        let dim = |o: usize, what: &str| -> Result<usize> {
            let v = r.i32(o).expect("in header");
            usize::try_from(v)
                .ok()
                .filter(|&v| v > 0)
                .ok_or_else(|| err(format!("{what} = {v} points")))
        };
        let nx = dim(108, "points in x")?;
        let ny = dim(112, "points in y")?;
        let count = r.u32(116).expect("in header") as usize;
        if nx.checked_mul(ny) != Some(count) {
            return Err(err(format!("{nx} x {ny} points but a point count of {count}")));
        }
        let dx = f64::from(r.f32(120).expect("in header"));
        let dy = f64::from(r.f32(124).expect("in header"));
        let scale = f64::from(r.f32(128).expect("in header"));
        let unit = |o: usize| cstr(&h[o..o + 16]);
        let (ux, uy, uz) = (Unit::named(&unit(180)), Unit::named(&unit(196)), unit(212));
        let (Some(fx), Some(fy)) = (ux.metres, uy.metres) else {
            return Err(err(format!(
                "spacing units `{}`, `{}` are not lengths",
                ux.name, uy.name
            )));
        };
        if !(dx > 0.0 && dy > 0.0 && dx.is_finite() && dy.is_finite() && scale.is_finite()) {
            return Err(err(format!(
                "spacings {dx}, {dy} and height scale {scale} must be positive and finite"
            )));
        }
        let skip = get16(334) + get16(336);
        let data_at = at + HEADER + skip;
        let need = count.saturating_mul(bits / 8);
        let end = data_at
            .checked_add(need)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                super::truncated(
                    path,
                    &format!(".sur data of object {}", k + 1),
                    need,
                    bytes.len().saturating_sub(data_at),
                )
            })?;
        let object_name = cstr(&h[20..50]);
        let name = if !object_name.is_empty() {
            object_name
        } else if k == 0 {
            "Default".to_string()
        } else {
            format!("Object {}", k + 1)
        };
        let info = ChannelInfo {
            name,
            nx,
            ny,
            size: Some([dx * fx * nx as f64, dy * fy * ny as f64]),
            xy_unit: Unit::metre(),
            z_unit: Unit::named(&uz),
            periodic: false,
        };
        let decode = move || -> Result<Vec<f64>> {
            let mut z = super::numbers(bytes, data_at, count, num, le, path, ".sur data")?;
            z.iter_mut().for_each(|v| *v *= scale);
            Ok(z)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
        at = end;
        k += 1;
    }
    Ok(out)
}
