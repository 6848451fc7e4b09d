//! Bruker Dektak files (`.opdx`, Vision64 software of stylus profilometers): the magic
//! `VCA DATA\x01\0\0U`, then a tree of little-endian items: a name (u32 length and UTF-8), a type
//! byte and a value; containers hold items up to a terminator (type 0x7f). Lengths of variable
//! size are a byte (1, 2 or 4) giving the size of the length that follows.
//!
//! Items used, by path: `/MetaData/DataKind` (`Surface Height`: a map; `Surface Profile`: line
//! scans), for a map `/MetaData/PrimaryData2D` naming `/2D_Data/NAME/` with `Dimension1Points`
//! (y), `Dimension2Points` (x), `Dimension1Extent`, `Dimension2Extent` (quantities: value and
//! unit symbol), `DataScale` (a quantity: height per stored value), `DataKind` (the channel's
//! name) and `Matrix` (f32, x fastest, rows in y); for line scans the names in
//! `/MetaData/1D_Channels/Height`, each `/1D_Data/NAME/` with `NumPoints`, `Extent`, `DataScale`,
//! `DataKind` and `Array` (f64 after 5 bytes). A height is the stored value × `DataScale`, as
//! SurfaceTopography reads it. A profile is read as a line scan (one row) and refused as such by
//! the surface analysis.

use std::collections::HashMap;
use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Num, Unit};
use crate::error::{Error, Result};

/// The magic bytes at the start.
pub(crate) const MAGIC: &[u8] = b"VCA DATA\x01\x00\x00\x55";

/// Nesting depth of containers read (the files nest about 6 deep).
const MAX_DEPTH: usize = 64;

/// An item's value, where it is used.
#[derive(Debug, Clone)]
enum Value {
    Number(f64),
    Text(String),
    Texts(Vec<String>),
    /// A value and its unit's symbol.
    Quantity(f64, String),
    /// Start and length of a 1D array of f64 (after its 5-byte prefix).
    Array(usize, usize),
    /// Start and length of a matrix's values, points in x and y.
    Matrix(usize, usize, usize, usize),
    Other,
}

struct Reader<'a> {
    r: Bytes<'a>,
    at: usize,
}

/// Why the item tree could not be read: the offset and what.
type Fail = (usize, String);

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> std::result::Result<&'a [u8], Fail> {
        let s = self
            .r
            .slice(self.at, n)
            .ok_or((self.at, format!("truncated: an item needs {n} bytes")))?;
        self.at += n;
        Ok(s)
    }
    fn u8(&mut self) -> std::result::Result<u8, Fail> {
        Ok(self.take(1)?[0])
    }
    fn u32(&mut self) -> std::result::Result<u32, Fail> {
        let at = self.at;
        self.take(4)?;
        Ok(self.r.u32(at).expect("taken"))
    }
    fn f64(&mut self) -> std::result::Result<f64, Fail> {
        let at = self.at;
        self.take(8)?;
        Ok(self.r.f64(at).expect("taken"))
    }
    fn name(&mut self) -> std::result::Result<String, Fail> {
        let n = self.u32()? as usize;
        Ok(String::from_utf8_lossy(self.take(n)?).into_owned())
    }
    fn varlen(&mut self) -> std::result::Result<usize, Fail> {
        let at = self.at;
        Ok(match self.u8()? {
            1 => usize::from(self.u8()?),
            2 => {
                self.take(2)?;
                usize::from(self.r.u16(at + 1).expect("taken"))
            }
            4 => self.u32()? as usize,
            k => return Err((at, format!("a length of {k} bytes (1, 2 or 4)"))),
        })
    }
    /// Skip `n` bytes, which must be present.
    fn skip(&mut self, n: usize) -> std::result::Result<(), Fail> {
        self.take(n).map(|_| ())
    }
    /// The end of a sized part starting here, checked against the data.
    fn end_of(&self, n: usize) -> std::result::Result<usize, Fail> {
        self.at
            .checked_add(n)
            .filter(|&e| e <= self.r.b.len())
            .ok_or((self.at, format!("truncated: a part of {n} bytes")))
    }

    /// Read one item under `prefix` into `out`; `false` at a terminator.
    fn item(
        &mut self,
        prefix: &str,
        out: &mut HashMap<String, Value>,
        depth: usize,
    ) -> std::result::Result<bool, Fail> {
        let name = self.name()?;
        let path = format!("{prefix}/{name}");
        let kind = self.u8()?;
        let value = match kind {
            0x7f => return Ok(false),
            0x7d | 0x46 | 0x47 => {
                if depth >= MAX_DEPTH {
                    return Err((self.at, format!("containers nested deeper than {MAX_DEPTH}")));
                }
                let length = self.varlen()?;
                let end = self.end_of(length)?;
                while self.item(&path, out, depth + 1)? {}
                self.skip(2)?;
                if self.at != end {
                    return Err((self.at, format!("container {path} ends at {} not {end}", self.at)));
                }
                return Ok(true);
            }
            0x7c => {
                self.name()?;
                let length = self.varlen()?;
                self.skip(length)?;
                Value::Other
            }
            0x01 => {
                self.skip(1)?;
                Value::Other
            }
            0x04 | 0x05 => {
                let at = self.at;
                self.skip(2)?;
                let v = if kind == 0x04 {
                    f64::from(self.r.i16(at).expect("taken"))
                } else {
                    f64::from(self.r.u16(at).expect("taken"))
                };
                Value::Number(v)
            }
            0x06 | 0x07 | 0x0c => {
                let at = self.at;
                self.skip(4)?;
                Value::Number(match kind {
                    0x06 => f64::from(self.r.i32(at).expect("taken")),
                    0x07 => f64::from(self.r.u32(at).expect("taken")),
                    _ => f64::from(self.r.f32(at).expect("taken")),
                })
            }
            0x0a | 0x0b => {
                let b: [u8; 8] = self.take(8)?.try_into().expect("8 bytes");
                Value::Number(if kind == 0x0a {
                    i64::from_le_bytes(b) as f64
                } else {
                    u64::from_le_bytes(b) as f64
                })
            }
            0x0d => Value::Number(self.f64()?),
            0x0e => {
                self.name()?;
                let n = self.varlen()?;
                self.skip(n)?;
                Value::Other
            }
            0x12 => {
                let n = self.varlen()?;
                Value::Text(String::from_utf8_lossy(self.take(n)?).into_owned())
            }
            0x13 => {
                let length = self.varlen()?;
                let end = self.end_of(length)?;
                let v = self.f64()?;
                self.name()?;
                let symbol = self.name()?;
                if self.at > end {
                    return Err((self.at, format!("quantity {path} overruns its length")));
                }
                self.at = end;
                Value::Quantity(v, symbol)
            }
            0x15 => {
                self.skip(9)?;
                Value::Other
            }
            0x18 => {
                let length = self.varlen()?;
                let end = self.end_of(length)?;
                self.name()?;
                let symbol = self.name()?;
                let v = self.f64()?;
                self.skip(12)?;
                if self.at != end {
                    return Err((self.at, format!("unit {path} does not fill its length")));
                }
                Value::Quantity(v, symbol)
            }
            0x40 => {
                self.name()?;
                let n = self.varlen()?;
                let at = self.at;
                self.skip(n)?;
                Value::Array(at, n)
            }
            0x42 => {
                self.name()?;
                let length = self.varlen()?;
                let end = self.end_of(length)?;
                let mut list = Vec::new();
                while self.at < end {
                    list.push(self.name()?);
                }
                if self.at != end {
                    return Err((self.at, format!("string list {path} overruns its length")));
                }
                Value::Texts(list)
            }
            0x00 | 0x45 => {
                self.name()?;
                if kind == 0x00 {
                    self.u32()?;
                    self.name()?;
                }
                let length = self.varlen()?;
                let ny = self.u32()? as usize;
                let nx = self.u32()? as usize;
                let n = length
                    .checked_sub(8)
                    .ok_or((self.at, format!("matrix {path} of {length} bytes")))?;
                let at = self.at;
                self.skip(n)?;
                Value::Matrix(at, n, nx, ny)
            }
            k => return Err((self.at - 1, format!("item {path} of unknown type {k:#04x}"))),
        };
        out.insert(path, value);
        Ok(true)
    }
}

/// The height channels of a Dektak file: its primary map, or its line scans.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".opdx: {m}"));
    let mut items = HashMap::new();
    let mut reader = Reader {
        r: Bytes { b: bytes, le: true },
        at: MAGIC.len(),
    };
    while reader.at < bytes.len() {
        match reader.item("", &mut items, 0) {
            Ok(true) => {}
            Ok(false) => break,
            Err((at, m)) => return Err(err(format!("at byte {at}: {m}"))),
        }
    }
    let get = |k: &str| items.get(k).ok_or_else(|| err(format!("no item `{k}`")));
    let text = |k: &str| match get(k)? {
        Value::Text(s) => Ok(s.clone()),
        _ => Err(err(format!("item `{k}` is not a text"))),
    };
    let count = |k: &str| match get(k)? {
        Value::Number(v) if *v >= 0.0 && v.fract() == 0.0 && *v <= super::MAX_POINTS as f64 => {
            Ok(*v as usize)
        }
        v => Err(err(format!(
            "item `{k}` = {v:?} is not a point count up to {}",
            super::MAX_POINTS
        ))),
    };
    let quantity = |k: &str| match get(k)? {
        Value::Quantity(v, s) if v.is_finite() => Ok((*v, Unit::named(s))),
        v => Err(err(format!("item `{k}` = {v:?} is not a finite quantity"))),
    };
    let kind = text("/MetaData/DataKind")?;
    let mut out = Vec::new();
    match kind.as_str() {
        "Surface Height" => {
            let prefix = format!("/2D_Data/{}", text("/MetaData/PrimaryData2D")?);
            let ny = count(&format!("{prefix}/Dimension1Points"))?;
            let nx = count(&format!("{prefix}/Dimension2Points"))?;
            let (ly, uy) = quantity(&format!("{prefix}/Dimension1Extent"))?;
            let (lx, ux) = quantity(&format!("{prefix}/Dimension2Extent"))?;
            let (scale, uz) = quantity(&format!("{prefix}/DataScale"))?;
            let (Some(fx), Some(fy)) = (ux.metres, uy.metres) else {
                return Err(err(format!(
                    "extents in `{}`, `{}`: not lengths",
                    ux.name, uy.name
                )));
            };
            let (at, length, mx, my) = match get(&format!("{prefix}/Matrix"))? {
                Value::Matrix(at, length, mx, my) => (*at, *length, *mx, *my),
                _ => return Err(err(format!("item `{prefix}/Matrix` is not a matrix"))),
            };
            let info = ChannelInfo {
                name: text(&format!("{prefix}/DataKind"))?,
                nx,
                ny,
                size: Some([lx * fx, ly * fy]),
                xy_unit: Unit::metre(),
                z_unit: uz,
                periodic: false,
            };
            info.check_grid(path)?;
            if (mx, my) != (nx, ny) || length != nx * ny * 4 {
                return Err(err(format!(
                    "the matrix of {mx} x {my} points in {length} bytes is not the {nx} x {ny} points of f32 the header gives"
                )));
            }
            let decode = move || -> Result<Vec<f64>> {
                let mut z = super::numbers(bytes, at, nx * ny, Num::F32, true, path, ".opdx matrix")?;
                z.iter_mut().for_each(|v| *v *= scale);
                Ok(z)
            };
            out.push(Channel {
                info,
                decode: Box::new(decode),
            });
        }
        "Surface Profile" => {
            let names = match get("/MetaData/1D_Channels/Height")? {
                Value::Texts(list) => list.clone(),
                _ => return Err(err("item `/MetaData/1D_Channels/Height` is not a list".into())),
            };
            for name in names {
                let prefix = format!("/1D_Data/{name}");
                let n = count(&format!("{prefix}/NumPoints"))?;
                let (l, ux) = quantity(&format!("{prefix}/Extent"))?;
                let (scale, uz) = quantity(&format!("{prefix}/DataScale"))?;
                let at = match get(&format!("{prefix}/Array"))? {
                    Value::Array(at, length) if Some(*length) == n.checked_mul(8).map(|b| b + 5) => at + 5,
                    _ => {
                        return Err(err(format!(
                            "item `{prefix}/Array` is not an array of the {n} points of f64 the header gives"
                        )));
                    }
                };
                let info = ChannelInfo {
                    name: text(&format!("{prefix}/DataKind"))?,
                    nx: n,
                    ny: 1,
                    size: Some([l, l / n.max(1) as f64]),
                    xy_unit: ux,
                    z_unit: uz,
                    periodic: false,
                };
                let decode = move || -> Result<Vec<f64>> {
                    let mut z = super::numbers(bytes, at, n, Num::F64, true, path, ".opdx array")?;
                    z.iter_mut().for_each(|v| *v *= scale);
                    Ok(z)
                };
                out.push(Channel {
                    info,
                    decode: Box::new(decode),
                });
            }
        }
        other => {
            return Err(err(format!(
                "data kind `{other}` is not read (Surface Height or Surface Profile)"
            )));
        }
    }
    Ok(out)
}
