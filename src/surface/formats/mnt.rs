//! Digital Surf Mountains documents (`.mnt`): an OLE compound file whose `ScopedContents`
//! stream holds the studiables (surfaces, profiles and their studies) as nested
//! tag-length-value entries (u16 tag, u64 size, little-endian).
//!
//! Layout read here (established on SurfaceTopography's two example documents, Mountains 9.2
//! and 10.3):
//! - the stream starts with its own length less 8 (u64), then top-level entries; entry 1 is the
//!   document, whose entry `0x2bd` holds the studiables: a one-byte storage code (entry 1) and
//!   entry 2, a list of objects each written as a u64 look-ahead size and one entry;
//! - the surface is the object holding a height block of type 9049 (an entry `{1: {1: 9049},
//!   2: {1: point count, 2: data}}`) and, before it, the axes X and Y (`{0xffff: descriptor,
//!   1: points}`) and after it the axis Z (`{0xffff: descriptor, 1: min, 2: max}`); a descriptor
//!   is `{0xffff: {1: axis number, 2: name}, 1: step, 2: unit of the step, ...}` with strings as
//!   a byte 4 and UTF-16;
//! - the data is the byte count (u64) and blocks of (u64 first point, u32 points, u32 compressed
//!   bytes, zlib stream) in any order, together the int32 heights with x fastest.
//!
//! Heights are the stored integers times the Z step (without the axis offset, which does not
//! change a map's statistics about its mean); the physical size is points times the step. With
//! the storage code 12 a zero marks a missing point, as SurfaceTopography reads it.
//!
//! Where SurfaceTopography 1.25 differs (checked on its examples): it scales the integers by a
//! fixed 10 nm (the document's pixel-scale entry) instead of the Z axis's step, and it takes
//! the physical size from an extracted profile's extent, (points − 1) × step.

use std::io::{Cursor, Read};
use std::path::Path;

use super::{Channel, ChannelInfo, Unit};
use crate::error::{Error, Result};

/// First bytes of an OLE compound file.
pub(crate) const OLE_MAGIC: &[u8] = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1";

/// The stream holding a Mountains document's studiables.
const STREAM: &str = "ScopedContents";

/// Object type of a block of int32 heights.
const HEIGHTS: u32 = 9049;

/// Storage code of a document whose zeros mark missing points.
const ZERO_IS_MISSING: u8 = 12;

/// Deepest nesting searched for the axes and heights.
const MAX_DEPTH: usize = 24;

/// One tag-length-value entry.
#[derive(Clone, Copy)]
struct Tlv<'a> {
    tag: u16,
    data: &'a [u8],
}

/// The entries tiling `data` exactly, or `None` when it is not a list of entries.
fn entries(data: &[u8]) -> Option<Vec<Tlv<'_>>> {
    let mut out = Vec::new();
    let mut rest = data;
    while !rest.is_empty() {
        let tag = u16::from_le_bytes(rest.get(..2)?.try_into().ok()?);
        let size = u64::from_le_bytes(rest.get(2..10)?.try_into().ok()?);
        let size = usize::try_from(size).ok()?;
        let end = size.checked_add(10)?;
        out.push(Tlv {
            tag,
            data: rest.get(10..end)?,
        });
        rest = &rest[end..];
    }
    Some(out)
}

/// The data of the first entry tagged `tag`.
fn child<'a>(list: &[Tlv<'a>], tag: u16) -> Option<&'a [u8]> {
    list.iter().find(|e| e.tag == tag).map(|e| e.data)
}

fn u32_of(d: &[u8]) -> Option<u32> {
    Some(u32::from_le_bytes(d.try_into().ok()?))
}

fn f64_of(d: &[u8]) -> Option<f64> {
    Some(f64::from_le_bytes(d.try_into().ok()?))
}

/// A string entry: the byte 4 and UTF-16 LE.
fn text_of(d: &[u8]) -> Option<String> {
    let (&kind, rest) = d.split_first()?;
    if kind != 4 || rest.len() % 2 != 0 {
        return None;
    }
    let units: Vec<u16> = rest
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    String::from_utf16(&units).ok()
}

/// An axis: its step in `unit`, and its point count (X and Y only).
#[derive(Debug, Clone)]
struct Axis {
    step: f64,
    unit: String,
    points: Option<u32>,
}

/// The axis described by the entries `list` (`{0xffff: descriptor, 1: …}`), with its name
/// (X, Y or Z).
fn axis(list: &[Tlv<'_>]) -> Option<(String, Axis)> {
    let first = list.first().filter(|e| e.tag == 0xffff)?;
    let desc = entries(first.data)?;
    let id = entries(child(&desc, 0xffff)?)?;
    let number = u32_of(child(&id, 1)?)?;
    let name = text_of(child(&id, 2)?)?;
    if !matches!((number, name.as_str()), (1, "X") | (2, "Y") | (3, "Z")) {
        return None;
    }
    let step = f64_of(child(&desc, 1)?)?;
    let unit = text_of(child(&desc, 2)?)?;
    let points = if name == "Z" {
        None
    } else {
        Some(u32_of(child(list, 1)?)?)
    };
    Some((name, Axis { step, unit, points }))
}

/// What a search of one object found: the first X, Y and Z axes and the height block (its
/// point count and data).
#[derive(Default)]
struct Found<'a> {
    x: Option<Axis>,
    y: Option<Axis>,
    z: Option<Axis>,
    heights: Option<(u32, &'a [u8])>,
}

impl<'a> Found<'a> {
    fn search(&mut self, list: &[Tlv<'a>], depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        if let Some((name, a)) = axis(list) {
            let slot = match name.as_str() {
                "X" => &mut self.x,
                "Y" => &mut self.y,
                _ => &mut self.z,
            };
            if slot.is_none() {
                *slot = Some(a);
            }
            return;
        }
        if self.heights.is_none()
            && let Some(block) = heights_block(list)
        {
            self.heights = Some(block);
            return;
        }
        for e in list {
            if e.data.len() >= 10
                && let Some(inner) = entries(e.data)
            {
                self.search(&inner, depth + 1);
            }
        }
    }
}

/// `{1: {1: 9049}, 2: {1: count, 2: data}}`: the point count and data of a height block.
fn heights_block<'a>(list: &[Tlv<'a>]) -> Option<(u32, &'a [u8])> {
    let kind = entries(child(list, 1)?)?;
    if u32_of(child(&kind, 1)?)? != HEIGHTS {
        return None;
    }
    let body = entries(child(list, 2)?)?;
    Some((u32_of(child(&body, 1)?)?, child(&body, 2)?))
}

/// The `ScopedContents` stream of the compound file in `bytes`.
fn stream(bytes: &[u8], path: &Path) -> Result<Vec<u8>> {
    let err = |m: String| Error::data_file(path, 0, format!(".mnt: {m}"));
    let mut cf = cfb::CompoundFile::open(Cursor::new(bytes))
        .map_err(|e| err(format!("not a readable OLE compound file ({e})")))?;
    if !cf.is_stream(STREAM) {
        return Err(err(format!(
            "an OLE compound file without the {STREAM} stream of a Mountains document"
        )));
    }
    let mut s = cf
        .open_stream(STREAM)
        .map_err(|e| err(format!("the {STREAM} stream cannot be opened ({e})")))?;
    let len = s.len();
    // A stream longer than the file is a corrupt directory entry: read no more than the file.
    if len > bytes.len() as u64 {
        return Err(err(format!(
            "the {STREAM} stream claims {len} bytes in a file of {}",
            bytes.len()
        )));
    }
    let mut out = Vec::with_capacity(len as usize);
    (&mut s)
        .take(len)
        .read_to_end(&mut out)
        .map_err(|e| err(format!("the {STREAM} stream cannot be read ({e})")))?;
    if out.len() as u64 != len {
        return Err(super::truncated(
            path,
            &format!(".mnt {STREAM} stream"),
            len as usize,
            out.len(),
        ));
    }
    Ok(out)
}

/// The surface of a Mountains document.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let sc = stream(bytes, path)?;
    let (info, s) = {
        let s = surface(&sc, path)?;
        let start = s.data.as_ptr() as usize - sc.as_ptr() as usize;
        let range = start..start + s.data.len();
        (s.info, (s.zero_missing, s.count, s.step, range))
    };
    let (zero_missing, count, step, range) = s;
    let decode = move || -> Result<Vec<f64>> {
        let counts = decode_blocks(&sc[range], count, path)?;
        Ok(counts
            .into_iter()
            .map(|c| {
                if zero_missing && c == 0 {
                    f64::NAN
                } else {
                    f64::from(c) * step
                }
            })
            .collect())
    };
    Ok(vec![Channel {
        info,
        decode: Box::new(decode),
    }])
}

/// The header of a document's surface.
struct Surface<'s> {
    info: ChannelInfo,
    /// Zeros mark missing points.
    zero_missing: bool,
    /// Points.
    count: usize,
    /// Height per stored integer, in the Z unit.
    step: f64,
    /// The height block's data.
    data: &'s [u8],
}

/// The surface in the stream `sc`.
fn surface<'s>(sc: &'s [u8], path: &Path) -> Result<Surface<'s>> {
    let err = |m: &str| Error::data_file(path, 0, format!(".mnt: {m}"));
    let corrupt = |what: &str| err(&format!("the {STREAM} stream is corrupt: {what}"));
    let head = sc
        .get(..8)
        .ok_or_else(|| super::truncated(path, &format!(".mnt {STREAM} stream"), 8, sc.len()))?;
    let declared = u64::from_le_bytes(head.try_into().expect("8 bytes"));
    if declared != sc.len() as u64 - 8 {
        return Err(corrupt(&format!(
            "it declares {declared} bytes after its first 8, {} are present",
            sc.len() - 8
        )));
    }
    let top = entries(&sc[8..]).ok_or_else(|| corrupt("its entries overrun it"))?;
    let doc = entries(child(&top, 1).ok_or_else(|| corrupt("no document entry"))?)
        .ok_or_else(|| corrupt("the document's entries overrun it"))?;
    let store =
        entries(child(&doc, 0x2bd).ok_or_else(|| err("the document holds no studiable (entry 0x2bd)"))?)
            .ok_or_else(|| corrupt("the studiables' entries overrun them"))?;
    let code = child(&store, 1).and_then(|d| d.first().copied());
    let objects = entries(child(&store, 2).ok_or_else(|| corrupt("no object list"))?)
        .and_then(|l| l.first().map(|e| e.data))
        .ok_or_else(|| corrupt("the object list overruns it"))?;
    // Objects: u64 look-ahead size, then one entry.
    let mut rest = objects;
    let mut found = None;
    while rest.len() >= 8 && found.is_none() {
        let ahead = u64::from_le_bytes(rest[..8].try_into().expect("8 bytes"));
        let len = usize::try_from(ahead)
            .ok()
            .filter(|&l| l >= 10 && l <= rest.len() - 8)
            .ok_or_else(|| corrupt(&format!("an object of {ahead} bytes overruns the list")))?;
        let object = entries(&rest[8..8 + len]).ok_or_else(|| corrupt("an object's entries overrun it"))?;
        rest = &rest[8 + len..];
        let mut f = Found::default();
        for e in &object {
            if let Some(inner) = entries(e.data) {
                f.search(&inner, 1);
            }
        }
        if let Some(h) = f.heights {
            found = Some((f.x, f.y, f.z, h));
        }
    }
    let (x, y, z, (count, data)) =
        found.ok_or_else(|| err("the document holds no surface of int32 heights (object type 9049)"))?;
    let (Some(x), Some(y), Some(z)) = (x, y, z) else {
        return Err(err("the surface lacks its X, Y or Z axis"));
    };
    let nx = x.points.unwrap_or(0) as usize;
    let ny = y.points.unwrap_or(0) as usize;
    let (ux, uy, uz) = (Unit::named(&x.unit), Unit::named(&y.unit), Unit::named(&z.unit));
    let (Some(fx), Some(fy)) = (ux.metres, uy.metres) else {
        return Err(err(&format!(
            "axis units `{}`, `{}` are not lengths",
            ux.name, uy.name
        )));
    };
    let info = ChannelInfo {
        name: "Default".into(),
        nx,
        ny,
        size: Some([x.step * fx * nx as f64, y.step * fy * ny as f64]),
        xy_unit: Unit::metre(),
        z_unit: uz,
        periodic: false,
    };
    info.check_grid(path)?;
    let count = count as usize;
    if nx * ny != count {
        return Err(err(&format!(
            "{nx} x {ny} points on the axes but {count} heights"
        )));
    }
    let ok = |v: f64| v.is_finite() && v > 0.0;
    if !(ok(x.step) && ok(y.step) && z.step.is_finite() && z.step != 0.0) {
        return Err(err(&format!(
            "steps {} (x), {} (y), {} (z) must be finite, x and y positive, z non-zero",
            x.step, y.step, z.step
        )));
    }
    Ok(Surface {
        info,
        zero_missing: code == Some(ZERO_IS_MISSING),
        count,
        step: z.step,
        data,
    })
}

/// The `count` int32 heights of a height block's data: byte count, then zlib blocks of (u64
/// first point, u32 points, u32 compressed bytes) in any order, together covering every point
/// once. Each block is inflated into its place, refused as soon as it would expand beyond its
/// points.
fn decode_blocks(data: &[u8], count: usize, path: &Path) -> Result<Vec<i32>> {
    let err = |m: String| Error::data_file(path, 0, format!(".mnt height data: {m}"));
    let bytes = count
        .checked_mul(4)
        .ok_or_else(|| err(format!("{count} points overflow")))?;
    let declared = data
        .get(..8)
        .map(|h| u64::from_le_bytes(h.try_into().expect("8 bytes")))
        .ok_or_else(|| super::truncated(path, ".mnt height data", 8, data.len()))?;
    if declared != bytes as u64 {
        return Err(err(format!(
            "declares {declared} bytes for {count} int32 heights ({bytes} bytes)"
        )));
    }
    // Blocks first (cheap), so that the output is allocated only for a consistent list.
    let mut blocks = Vec::new();
    let mut at = 8usize;
    while at < data.len() {
        let h = data
            .get(at..at + 16)
            .ok_or_else(|| super::truncated(path, ".mnt height block header", 16, data.len() - at))?;
        let first = u64::from_le_bytes(h[..8].try_into().expect("8 bytes"));
        let points = u32::from_le_bytes(h[8..12].try_into().expect("4 bytes")) as u64;
        let packed = u32::from_le_bytes(h[12..16].try_into().expect("4 bytes")) as usize;
        let stream = data
            .get(at + 16..at + 16 + packed)
            .ok_or_else(|| super::truncated(path, ".mnt height block", packed, data.len() - at - 16))?;
        if first.checked_add(points).is_none_or(|end| end > count as u64) || points == 0 {
            return Err(err(format!(
                "a block of {points} points from point {first} lies outside the {count} points"
            )));
        }
        blocks.push((first as usize, points as usize, stream));
        at += 16 + packed;
    }
    blocks.sort_by_key(|b| b.0);
    let mut next = 0usize;
    for &(first, points, _) in &blocks {
        if first != next {
            return Err(err(format!(
                "the blocks leave points {next} to {first} uncovered or overlap there"
            )));
        }
        next = first + points;
    }
    if next != count {
        return Err(err(format!("the blocks cover {next} of {count} points")));
    }
    let mut raw = vec![0u8; bytes];
    for &(first, points, stream) in &blocks {
        inflate_exact(stream, &mut raw[4 * first..4 * (first + points)])
            .map_err(|m| err(format!("block at point {first}: {m}")))?;
    }
    Ok(raw
        .chunks_exact(4)
        .map(|c| i32::from_le_bytes(c.try_into().expect("4 bytes")))
        .collect())
}

/// Inflate the zlib stream `input` into `out`, which it must fill exactly.
fn inflate_exact(input: &[u8], out: &mut [u8]) -> std::result::Result<(), String> {
    use flate2::{Decompress, FlushDecompress, Status};
    let mut z = Decompress::new(true);
    let status = z
        .decompress(input, out, FlushDecompress::Finish)
        .map_err(|e| format!("corrupt zlib stream ({e})"))?;
    let filled = z.total_out() as usize;
    if matches!(status, Status::StreamEnd) {
        if filled == out.len() {
            return Ok(());
        }
        return Err(format!("inflates to {filled} bytes, {} expected", out.len()));
    }
    if filled == out.len() {
        // Full: one more byte tells a longer stream (refused unread) from a truncated one.
        let used = z.total_in() as usize;
        let mut one = [0u8; 1];
        let more = z
            .decompress(&input[used.min(input.len())..], &mut one, FlushDecompress::Finish)
            .map(|_| z.total_out() as usize > filled)
            .unwrap_or(false);
        if more {
            return Err(format!("inflates beyond its {} bytes", out.len()));
        }
    }
    Err(format!(
        "truncated zlib stream ({filled} of {} bytes inflated)",
        out.len()
    ))
}
