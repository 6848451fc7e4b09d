//! Bruker (Veeco) Wyko files (`.opd`, Vision software of white-light interferometers): two
//! bytes, then a directory of 24-byte entries (a 16-byte NUL-padded name, an i16 type, an i32
//! length, a u16 attribute; little-endian), the first being the directory itself; the blocks
//! follow back to back in the directory's order, each of its entry's length.
//!
//! Blocks used: `Wavelength` (f32, nm), `Mult` (u16, 1 when absent), `Aspect` (f32, 1 when
//! absent), `Pixel_size` (f32, mm) and the rasters `RAW DATA`, `RAW_DATA`, `OPD` or `Raw` (one
//! channel each): points in x and y and the item size (u16 each; 2 for i16, 4 for f32), then the
//! values with y fastest, the first stored at the top of the image (y reversed). A height is the
//! value × wavelength / mult, in nm; an i16 of 32 766 or more, an f32 of 1e38 (as f32) or more, or a value
//! not finite marks a point not measured (missing). The size is points × pixel size in x and ×
//! pixel size × aspect in y, as SurfaceTopography reads it; a file without a pixel size is
//! refused (SurfaceTopography would take 1 mm).

use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Num, Unit, cstr};
use crate::error::{Error, Result};

/// Bytes of a directory entry.
const ENTRY: usize = 24;

/// The magic: the directory's own entry, at byte 2.
pub(crate) const MAGIC: &[u8] = b"Directory";

/// The rasters of a Wyko file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".opd: {m}"));
    let r = Bytes { b: bytes, le: true };
    let entry = |k: usize| -> Result<(String, usize)> {
        let at = 2 + k * ENTRY;
        let e = r.slice(at, ENTRY).ok_or_else(|| {
            super::truncated(
                path,
                &format!(".opd directory entry {k}"),
                ENTRY,
                bytes.len().saturating_sub(at),
            )
        })?;
        let length = r.i32(at + 18).expect("in entry");
        Ok((cstr(&e[..16]), usize::try_from(length).unwrap_or(0)))
    };
    let (name, length) = entry(0)?;
    if name != "Directory" || length % ENTRY != 0 || length == 0 {
        return Err(err(format!(
            "the directory entry is `{name}` of {length} bytes, not `Directory` of a multiple of {ENTRY}"
        )));
    }
    let mut wavelength = None;
    let (mut mult, mut aspect, mut pixel) = (1.0, 1.0, None);
    let mut rasters = Vec::new();
    let mut at = 2 + length;
    for k in 1..length / ENTRY {
        let (name, length) = entry(k)?;
        if length == 0 {
            continue;
        }
        let block = r.slice(at, length).ok_or_else(|| {
            super::truncated(
                path,
                &format!(".opd block {name}"),
                length,
                bytes.len().saturating_sub(at),
            )
        })?;
        let b = Bytes { b: block, le: true };
        let small = |v: Option<f32>| {
            v.map(f64::from)
                .ok_or_else(|| err(format!("block {name} of {length} bytes is too short")))
        };
        match name.as_str() {
            "Wavelength" => wavelength = Some(small(b.f32(0))?),
            "Mult" => mult = small(b.u16(0).map(f32::from))?,
            "Aspect" => aspect = small(b.f32(0))?,
            "Pixel_size" => pixel = Some(small(b.f32(0))?),
            "RAW DATA" | "RAW_DATA" | "OPD" | "Raw" => rasters.push((name, at, length)),
            _ => {}
        }
        at += length;
    }
    let wavelength =
        wavelength.ok_or_else(|| err("no Wavelength block: the height scale is unknown".into()))?;
    let pixel = pixel.ok_or_else(|| err("no Pixel_size block: the lateral size is unknown".into()))?;
    let scale = wavelength / mult;
    if !(scale.is_finite() && pixel > 0.0 && pixel.is_finite() && aspect > 0.0 && aspect.is_finite()) {
        return Err(err(format!(
            "wavelength {wavelength} nm / mult {mult}, pixel size {pixel} mm and aspect {aspect} must be finite, the sizes positive"
        )));
    }
    let mut out = Vec::with_capacity(rasters.len());
    for (name, at, length) in rasters {
        let b = Bytes {
            b: &bytes[at..at + length],
            le: true,
        };
        let head = |o: usize| {
            b.u16(o)
                .map(usize::from)
                .ok_or_else(|| super::truncated(path, &format!(".opd raster {name}"), 6, length))
        };
        let (nx, ny, item) = (head(0)?, head(2)?, head(4)?);
        let num = match item {
            2 => Num::I16,
            4 => Num::F32,
            i => {
                return Err(err(format!(
                    "raster {name}: item size {i} is not read (2 or 4 bytes)"
                )));
            }
        };
        let info = ChannelInfo {
            name,
            nx,
            ny,
            size: Some([nx as f64 * pixel, ny as f64 * pixel * aspect]),
            xy_unit: Unit::named("mm"),
            z_unit: Unit::named("nm"),
            periodic: false,
        };
        info.check_grid(path)?;
        let n = nx * ny;
        if 6 + n * item > length {
            return Err(super::truncated(
                path,
                &format!(".opd raster {}", info.name),
                n * item,
                length - 6,
            ));
        }
        // Compared in the stored type, as SurfaceTopography compares them.
        let invalid = if num == Num::I16 {
            32766.0
        } else {
            f64::from(1e38f32)
        };
        let decode = move || -> Result<Vec<f64>> {
            let v = super::numbers(bytes, at + 6, n, num, true, path, ".opd raster")?;
            // Stored with y fastest from the top: z[j * nx + i] = v[i * ny + ny - 1 - j].
            // Transposed in blocks of 32 columns: each output row is written 32 values at a
            // time while the 32 columns being read stay in cache.
            const BLOCK: usize = 32;
            let mut z = vec![0.0; n];
            for i0 in (0..nx).step_by(BLOCK) {
                let i1 = (i0 + BLOCK).min(nx);
                for k in 0..ny {
                    let row = (ny - 1 - k) * nx;
                    for i in i0..i1 {
                        let h = v[i * ny + k];
                        z[row + i] = if h.is_finite() && h < invalid {
                            h * scale
                        } else {
                            f64::NAN
                        };
                    }
                }
            }
            Ok(z)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
    }
    Ok(out)
}
