//! Gwyddion's native files (`.gwy`): `GWYP`, then one serialised `GwyContainer` object.
//!
//! An object is its type name (NUL-terminated), its size (u32) and components: a name
//! (NUL-terminated), a type letter and the value, little-endian: `b` `c` one byte, `i` i32,
//! `q` i64, `d` f64, `s` a NUL-terminated string, `o` an object; upper-case letters are arrays
//! (u32 count, then the items). The container's `/N/data` components are `GwyDataField`s (`xres`,
//! `yres`, `xreal`, `yreal` [m in `si_unit_xy`], `si_unit_xy` and `si_unit_z` as `GwySIUnit`
//! objects with `unitstr`, `data` an f64 array in x-fastest order), titled by `/N/data/title`;
//! `/N/mask` is the channel's mask (points > 0.5 are masked: missing, as SurfaceTopography reads
//! them).

use std::collections::BTreeMap;
use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Unit};
use crate::error::{Error, Result};

/// Deepest nesting of objects read.
const MAX_DEPTH: usize = 32;

/// A component's value, arrays of doubles kept as a place in the file.
enum Value {
    Int(i64),
    Real(f64),
    Str(String),
    Object(Object),
    Doubles { at: usize, count: usize },
    Other,
}

struct Object {
    name: String,
    items: Vec<(String, Value)>,
}

impl Object {
    fn get(&self, key: &str) -> Option<&Value> {
        self.items.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
}

struct Parser<'a> {
    b: Bytes<'a>,
    path: &'a Path,
}

impl Parser<'_> {
    fn err(&self, m: String) -> Error {
        Error::data_file(self.path, 0, format!(".gwy: {m}"))
    }

    fn string(&self, at: usize, end: usize) -> Result<(String, usize)> {
        let s = &self.b.b[at.min(end)..end];
        let n = s
            .iter()
            .position(|&c| c == 0)
            .ok_or_else(|| self.err(format!("truncated: unterminated string at byte {at}")))?;
        Ok((String::from_utf8_lossy(&s[..n]).into_owned(), at + n + 1))
    }

    fn u32(&self, at: usize, end: usize) -> Result<usize> {
        if at.saturating_add(4) > end {
            return Err(self.err(format!("truncated: a size or count at byte {at} past the end")));
        }
        Ok(self.b.u32(at).expect("in bounds") as usize)
    }

    /// An object at `at`, within `end`; returns it and where it ends.
    fn object(&self, at: usize, end: usize, depth: usize) -> Result<(Object, usize)> {
        if depth > MAX_DEPTH {
            return Err(self.err(format!("objects nested deeper than {MAX_DEPTH}")));
        }
        let (name, at) = self.string(at, end)?;
        let size = self.u32(at, end)?;
        let at = at + 4;
        let stop = at.checked_add(size).filter(|&s| s <= end).ok_or_else(|| {
            self.err(format!(
                "truncated: object {name} of {size} bytes ends past its container"
            ))
        })?;
        let mut items = Vec::new();
        let mut p = at;
        while p < stop {
            let (key, q) = self.string(p, stop)?;
            let ty = *self
                .b
                .b
                .get(q)
                .filter(|_| q < stop)
                .ok_or_else(|| self.err(format!("truncated: component {key} of {name} has no type")))?;
            let (v, next) = self.value(ty, q + 1, stop, depth, &key)?;
            items.push((key, v));
            p = next;
        }
        Ok((Object { name, items }, stop))
    }

    fn fixed(&self, at: usize, n: usize, end: usize, key: &str) -> Result<usize> {
        at.checked_add(n)
            .filter(|&e| e <= end)
            .ok_or_else(|| self.err(format!("truncated: component {key} ends past its object")))
    }

    fn value(&self, ty: u8, at: usize, end: usize, depth: usize, key: &str) -> Result<(Value, usize)> {
        let b = &self.b;
        Ok(match ty {
            b'b' | b'c' => (
                Value::Int(i64::from(self.b.b[at.min(end.saturating_sub(1))])),
                self.fixed(at, 1, end, key)?,
            ),
            b'i' => {
                let e = self.fixed(at, 4, end, key)?;
                (Value::Int(i64::from(b.i32(at).expect("in bounds"))), e)
            }
            b'q' => {
                let e = self.fixed(at, 8, end, key)?;
                (Value::Int(i64::from_le_bytes(b.arr(at).expect("in bounds"))), e)
            }
            b'd' => {
                let e = self.fixed(at, 8, end, key)?;
                (Value::Real(b.f64(at).expect("in bounds")), e)
            }
            b's' => {
                let (s, e) = self.string(at, end)?;
                (Value::Str(s), e)
            }
            b'o' => {
                let (o, e) = self.object(at, end, depth + 1)?;
                (Value::Object(o), e)
            }
            b'C' | b'I' | b'Q' | b'D' => {
                let count = self.u32(at, end)?;
                let size = match ty {
                    b'C' => 1,
                    b'I' => 4,
                    _ => 8,
                };
                let bytes = count
                    .checked_mul(size)
                    .ok_or_else(|| self.err(format!("array {key} of {count} items overflows")))?;
                let e = self.fixed(at + 4, bytes, end, key)?;
                let v = if ty == b'D' {
                    Value::Doubles { at: at + 4, count }
                } else {
                    Value::Other
                };
                (v, e)
            }
            b'S' | b'O' => {
                let count = self.u32(at, end)?;
                let mut p = at + 4;
                for _ in 0..count {
                    if p >= end {
                        return Err(self.err(format!("truncated: array {key} of {count} items")));
                    }
                    p = if ty == b'S' {
                        self.string(p, end)?.1
                    } else {
                        self.object(p, end, depth + 1)?.1
                    };
                }
                (Value::Other, p)
            }
            other => {
                return Err(self.err(format!(
                    "component {key} has unknown type `{}`",
                    (other as char).escape_default()
                )));
            }
        })
    }
}

/// A `GwyDataField` read from its object: grid, lengths, units and where its data are.
struct Field {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    xy: String,
    z: String,
    data: (usize, usize),
}

fn field(o: &Object, key: &str, p: &Parser) -> Result<Field> {
    if o.name != "GwyDataField" {
        return Err(p.err(format!("{key} is a {}, not a GwyDataField", o.name)));
    }
    let int = |k: &str| match o.get(k) {
        Some(Value::Int(v)) => {
            usize::try_from(*v).map_err(|_| p.err(format!("{key}: {k} = {v} is negative")))
        }
        _ => Err(p.err(format!("{key} lacks {k}"))),
    };
    let real = |k: &str, default: f64| match o.get(k) {
        Some(Value::Real(v)) => *v,
        _ => default,
    };
    let unit = |k: &str| match o.get(k) {
        Some(Value::Object(u)) => match u.get("unitstr") {
            Some(Value::Str(s)) => s.clone(),
            _ => String::new(),
        },
        _ => String::new(),
    };
    let data = match o.get("data") {
        Some(Value::Doubles { at, count }) => (*at, *count),
        _ => return Err(p.err(format!("{key} has no data array"))),
    };
    Ok(Field {
        nx: int("xres")?,
        ny: int("yres")?,
        lx: real("xreal", 1.0),
        ly: real("yreal", 1.0),
        xy: unit("si_unit_xy"),
        z: unit("si_unit_z"),
        data,
    })
}

/// The channels (data fields) of a `.gwy` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let p = Parser {
        b: Bytes { b: bytes, le: true },
        path,
    };
    let (top, _) = p.object(4, bytes.len(), 0)?;
    if top.name != "GwyContainer" {
        return Err(p.err(format!("the top object is a {}, not a GwyContainer", top.name)));
    }
    let index =
        |k: &str, tail: &str| -> Option<u32> { k.strip_prefix('/')?.strip_suffix(tail)?.parse::<u32>().ok() };
    let mut fields: BTreeMap<u32, Field> = BTreeMap::new();
    let mut masks: BTreeMap<u32, Field> = BTreeMap::new();
    let mut titles: BTreeMap<u32, String> = BTreeMap::new();
    for (k, v) in &top.items {
        if let (Some(n), Value::Object(o)) = (index(k, "/data"), v) {
            fields.insert(n, field(o, k, &p)?);
        } else if let (Some(n), Value::Object(o)) = (index(k, "/mask"), v) {
            masks.insert(n, field(o, k, &p)?);
        } else if let (Some(n), Value::Str(s)) = (index(k, "/data/title"), v) {
            titles.insert(n, s.clone());
        }
    }
    let mut out = Vec::new();
    for (n, f) in fields {
        let name = titles.remove(&n).unwrap_or_else(|| format!("Channel {n}"));
        let count = f.nx.saturating_mul(f.ny);
        if count != f.data.1 {
            return Err(p.err(format!(
                "/{n}/data ({name}): xres x yres = {} x {} but {} values",
                f.nx, f.ny, f.data.1
            )));
        }
        let mask = masks.remove(&n);
        if let Some(m) = &mask
            && (m.nx, m.ny, m.data.1) != (f.nx, f.ny, count)
        {
            return Err(p.err(format!(
                "/{n}/mask is {} x {}, its channel {} x {}",
                m.nx, m.ny, f.nx, f.ny
            )));
        }
        let info = ChannelInfo {
            name,
            nx: f.nx,
            ny: f.ny,
            size: Some([f.lx, f.ly]),
            xy_unit: Unit::named(&f.xy),
            z_unit: Unit::named(&f.z),
            periodic: false,
        };
        let (at, count) = f.data;
        let decode = move || -> Result<Vec<f64>> {
            let mut z = super::numbers(bytes, at, count, super::Num::F64, true, path, ".gwy data")?;
            if let Some(m) = mask {
                let mv = super::numbers(bytes, m.data.0, count, super::Num::F64, true, path, ".gwy mask")?;
                for (v, m) in z.iter_mut().zip(mv) {
                    if m > 0.5 {
                        *v = f64::NAN;
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
