//! Zygo MetroPro files (`.dat`, interferometers): a big-endian binary header (834 bytes, or
//! 4 096 for header format 3), the intensity data, then the phase data.
//!
//! Header fields used: the magic (`88 1b 03 6f`, `…70`, `…71`), header format and size (u16 at
//! 4, u32 at 6), the intensity block's width, height and buckets (u16 at 52, 54, 56: it holds
//! 2 × buckets × width × height bytes), the phase block's width and height (u16 at 68, 70), the
//! interferometric scale factor S, wavelength λ [m], obliquity factor O and lateral resolution
//! [m per pixel] (f32 at 164, 168, 176, 184), the phase resolution (i16 at 218: 0, 1, 2 for
//! R = 4 096, 32 768, 131 072) and the sign (i16 at 232). The phase data are i32, x fastest,
//! rows in y; a value of 2 147 483 640 or more marks a point not measured (missing). A height is
//! the stored integer × S × O × λ / R (negated when the sign is set), in metres, as
//! SurfaceTopography reads it.

use std::path::Path;

use super::Channel;
use super::{Bytes, ChannelInfo, Num};
use crate::error::{Error, Result};

/// The magic numbers of header formats 1, 2 and 3.
pub(crate) const MAGICS: [&[u8]; 3] = [b"\x88\x1b\x03\x6f", b"\x88\x1b\x03\x70", b"\x88\x1b\x03\x71"];

/// Stored phases from this value up are points not measured.
const INVALID: f64 = 2_147_483_640.0;

/// The phase map of a MetroPro file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!("MetroPro: {m}"));
    let expected = if bytes.starts_with(MAGICS[2]) { 4096 } else { 834 };
    if bytes.len() < 834 {
        return Err(super::truncated(path, "MetroPro header", expected, bytes.len()));
    }
    let r = Bytes { b: bytes, le: false };
    let u16_at = |at: usize| usize::from(r.u16(at).expect("in header"));
    let f32_at = |at: usize| f64::from(r.f32(at).expect("in header"));
    let header = r.u32(6).expect("in header") as usize;
    if header != expected {
        return Err(err(format!(
            "header size {header} bytes, not {expected} for header format {}",
            u16_at(4)
        )));
    }
    let intensity = 2 * u16_at(56) * u16_at(54) * u16_at(52);
    let (nx, ny) = (u16_at(68), u16_at(70));
    let (s, lambda, o, res) = (f32_at(164), f32_at(168), f32_at(176), f32_at(184));
    let range = match r.i16(218).expect("in header") {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131_072.0,
        p => return Err(err(format!("phase resolution {p} is not 0, 1 or 2"))),
    };
    let sign = if r.i16(232).expect("in header") != 0 {
        -1.0
    } else {
        1.0
    };
    let scale = sign * s * o * lambda / range;
    if !(res > 0.0 && res.is_finite() && scale.is_finite()) {
        return Err(err(format!(
            "lateral resolution {res} m and height scale {scale} m must be finite, the resolution positive"
        )));
    }
    let info = ChannelInfo::single_in_metres(nx, ny, res, res);
    info.check_grid(path)?;
    let start = header + intensity;
    let n = nx * ny;
    if start + 4 * n > bytes.len() {
        return Err(super::truncated(
            path,
            "MetroPro phase data",
            4 * n,
            bytes.len().saturating_sub(start),
        ));
    }
    let decode = move || -> Result<Vec<f64>> {
        let mut z = super::numbers(bytes, start, n, Num::I32, false, path, "MetroPro phase data")?;
        for v in &mut z {
            *v = if *v >= INVALID { f64::NAN } else { *v * scale };
        }
        Ok(z)
    };
    Ok(vec![Channel {
        info,
        decode: Box::new(decode),
    }])
}
