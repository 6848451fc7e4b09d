//! Asylum Research force curves saved as Igor binary waves (`.ibw`, version 5).
//!
//! Layout (Igor technical note TN003): a 64-byte `BinHeader5` (version, checksum, and the sizes
//! of the sections that follow the data), a 320-byte `WaveHeader5` (point count, number type,
//! dimensions, scaling, units), the wave's data (column-major), then formula, note, extended
//! units, dimension labels and further sections. Byte order is the writer's: the version field
//! reads 5 in one of the two orders.
//!
//! Port of afmformats' `fmt_igor` (MIT): columns labelled `Raw`/`Height` are the piezo height,
//! `ZSnsr`/`ZSensor` the measured height (both negated, so that they decrease towards the
//! sample), `Defl`/`Deflection` the deflection [m], force = deflection × `SpringConstant` of the
//! note (`key:value` lines separated by carriage returns). Beyond afmformats, the curve is split
//! into its segments where the note's `Indexes` (last sample of each segment) and `Direction`
//! (1 towards the sample, -1 away, 0 dwell) describe them, and the time [s] follows from the
//! first dimension's scaling when its unit is `s`.

use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment, SegmentKind};
use crate::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

const BIN_HEADER: usize = 64;
const WAVE_HEADER: usize = 320;

/// Decoder of one sample from its bytes and byte order (true: little-endian).
type Decode = fn(&[u8], bool) -> f64;

/// The version of an Igor binary wave and whether it is little-endian, if `bytes` starts like one.
pub(crate) fn version(bytes: &[u8]) -> Option<(i16, bool)> {
    let b = bytes.get(..2)?;
    let le = i16::from_le_bytes([b[0], b[1]]);
    let be = i16::from_be_bytes([b[0], b[1]]);
    [(le, true), (be, false)]
        .into_iter()
        .find(|(v, _)| matches!(v, 1 | 2 | 3 | 5))
}

struct Reader<'a> {
    b: &'a [u8],
    le: bool,
}

impl Reader<'_> {
    fn i16(&self, at: usize) -> i16 {
        let x = [self.b[at], self.b[at + 1]];
        if self.le {
            i16::from_le_bytes(x)
        } else {
            i16::from_be_bytes(x)
        }
    }
    fn i32(&self, at: usize) -> i32 {
        let x = [self.b[at], self.b[at + 1], self.b[at + 2], self.b[at + 3]];
        if self.le {
            i32::from_le_bytes(x)
        } else {
            i32::from_be_bytes(x)
        }
    }
    fn f64(&self, at: usize) -> f64 {
        let mut x = [0u8; 8];
        x.copy_from_slice(&self.b[at..at + 8]);
        if self.le {
            f64::from_le_bytes(x)
        } else {
            f64::from_be_bytes(x)
        }
    }
}

/// A NUL-terminated name in a fixed-size field.
fn cstr(b: &[u8]) -> String {
    let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    super::text::latin1(&b[..end])
}

/// The number type of an Igor wave: bytes per point and decoder.
fn number_type(ty: i16) -> Option<(u64, Decode)> {
    Some(match ty {
        2 => (4, |b, le| {
            let x = [b[0], b[1], b[2], b[3]];
            f64::from(if le {
                f32::from_le_bytes(x)
            } else {
                f32::from_be_bytes(x)
            })
        }),
        4 => (8, |b, le| {
            let mut x = [0u8; 8];
            x.copy_from_slice(b);
            if le {
                f64::from_le_bytes(x)
            } else {
                f64::from_be_bytes(x)
            }
        }),
        0x08 => (1, |b, _| f64::from(b[0] as i8)),
        0x48 => (1, |b, _| f64::from(b[0])),
        0x10 => (2, |b, le| {
            f64::from(if le {
                i16::from_le_bytes([b[0], b[1]])
            } else {
                i16::from_be_bytes([b[0], b[1]])
            })
        }),
        0x50 => (2, |b, le| {
            f64::from(if le {
                u16::from_le_bytes([b[0], b[1]])
            } else {
                u16::from_be_bytes([b[0], b[1]])
            })
        }),
        0x20 => (4, |b, le| {
            let x = [b[0], b[1], b[2], b[3]];
            f64::from(if le {
                i32::from_le_bytes(x)
            } else {
                i32::from_be_bytes(x)
            })
        }),
        0x60 => (4, |b, le| {
            let x = [b[0], b[1], b[2], b[3]];
            f64::from(if le {
                u32::from_le_bytes(x)
            } else {
                u32::from_be_bytes(x)
            })
        }),
        _ => return None,
    })
}

/// An Igor binary wave (version 5) parsed: its dimensions, scaling, units, note and labels, and
/// its data (column-major: the first dimension fastest) still as bytes. Every size of the header
/// is checked against the file.
pub(crate) struct Wave<'a> {
    /// Byte order of the file (true: little-endian).
    pub(crate) le: bool,
    /// Points in each of the four dimensions (0 for an unused one).
    pub(crate) dims: [u64; 4],
    /// Scaling of each dimension: point k is at `sfb + k sfa`.
    pub(crate) sfa: [f64; 4],
    /// Offsets of each dimension.
    pub(crate) sfb: [f64; 4],
    /// Unit of the data (the extended unit where the file has one).
    pub(crate) data_unit: String,
    /// Unit of each dimension (the extended unit where the file has one).
    pub(crate) dim_units: [String; 4],
    /// The wave note.
    pub(crate) note: String,
    /// Labels of each dimension's indices (the label of the whole dimension first).
    pub(crate) labels: [Vec<String>; 4],
    data: &'a [u8],
    elsize: u64,
    conv: Decode,
}

impl Wave<'_> {
    /// Number of points.
    pub(crate) fn len(&self) -> usize {
        (self.data.len() as u64 / self.elsize) as usize
    }

    /// The points `from..from + n` (in storage order) as f64.
    pub(crate) fn values(&self, from: usize, n: usize) -> Vec<f64> {
        let e = self.elsize as usize;
        self.data[from * e..(from + n) * e]
            .chunks_exact(e)
            .map(|b| (self.conv)(b, self.le))
            .collect()
    }
}

/// Parse an Igor binary wave of `version` (only 5 is read).
pub(crate) fn wave<'a>(bytes: &'a [u8], (version, le): (i16, bool), path: &Path) -> Result<Wave<'a>> {
    let err = |msg: String| Error::data_file(path, 0, msg);
    if version != 5 {
        return Err(err(format!(
            "Igor binary wave version {version} is not read (only version 5, as Asylum Research software writes)"
        )));
    }
    if bytes.len() < BIN_HEADER + WAVE_HEADER {
        return Err(err(format!(
            "truncated Igor binary wave: {} bytes, the headers alone take {}",
            bytes.len(),
            BIN_HEADER + WAVE_HEADER
        )));
    }
    let r = Reader { b: bytes, le };
    let size = |at: usize, what: &str| -> Result<u64> {
        let v = r.i32(at);
        u64::try_from(v).map_err(|_| err(format!("negative {what} size {v} in the Igor header")))
    };
    let wfm_size = size(4, "wave")?;
    let formula = size(8, "formula")?;
    let note_size = size(12, "note")?;
    let data_eunits = size(16, "data units")?;
    let mut dim_eunits = [0u64; 4];
    let mut dim_labels = [0u64; 4];
    for d in 0..4 {
        dim_eunits[d] = size(20 + 4 * d, "dimension units")?;
        dim_labels[d] = size(36 + 4 * d, "dimension labels")?;
    }
    let w = BIN_HEADER;
    let npnts =
        u64::try_from(r.i32(w + 12)).map_err(|_| err("negative point count in the Igor header".into()))?;
    let ty = r.i16(w + 16);
    let mut dims = [0u64; 4];
    for (d, dim) in dims.iter_mut().enumerate() {
        *dim = u64::try_from(r.i32(w + 68 + 4 * d))
            .map_err(|_| err("negative dimension in the Igor header".into()))?;
    }
    let sfa: [f64; 4] = std::array::from_fn(|d| r.f64(w + 84 + 8 * d));
    let sfb: [f64; 4] = std::array::from_fn(|d| r.f64(w + 116 + 8 * d));
    let mut data_unit = cstr(&bytes[w + 148..w + 152]);
    let mut dim_units: [String; 4] = std::array::from_fn(|d| cstr(&bytes[w + 152 + 4 * d..w + 156 + 4 * d]));
    let (elsize, conv) = number_type(ty).ok_or_else(|| {
        err(format!(
            "Igor number type {ty:#x} is not read (complex or text wave?)"
        ))
    })?;
    // Sizes checked against the file before anything is allocated from them.
    let data_bytes = npnts
        .checked_mul(elsize)
        .ok_or_else(|| err("Igor point count overflows".into()))?;
    let used = dims
        .iter()
        .take_while(|&&d| d > 0)
        .try_fold(1u64, |a, &d| a.checked_mul(d));
    if used != Some(npnts) && !(npnts == 0 && dims[0] == 0) {
        return Err(err(format!(
            "Igor header: {npnts} points but dimensions {} × {} × {} × {}",
            dims[0], dims[1], dims[2], dims[3]
        )));
    }
    if wfm_size != WAVE_HEADER as u64 + data_bytes {
        return Err(err(format!(
            "Igor header: wave section of {wfm_size} bytes, the header and {npnts} points take {}",
            WAVE_HEADER as u64 + data_bytes
        )));
    }
    let mut at = (BIN_HEADER + WAVE_HEADER) as u64;
    let mut take = |n: u64, what: &str| -> Result<&[u8]> {
        let end = at
            .checked_add(n)
            .filter(|&e| e <= bytes.len() as u64)
            .ok_or_else(|| {
                err(format!(
                    "truncated Igor binary wave: the {what} ends past the file's {} bytes",
                    bytes.len()
                ))
            })?;
        let s = &bytes[at as usize..end as usize];
        at = end;
        Ok(s)
    };
    let data = take(data_bytes, "data")?;
    take(formula, "formula")?;
    let note = super::text::latin1(take(note_size, "note")?);
    let eunits = take(data_eunits, "data units")?;
    if !eunits.is_empty() {
        data_unit = cstr(eunits);
    }
    for (d, &n) in dim_eunits.iter().enumerate() {
        let u = take(n, &format!("dimension {d} units"))?;
        if !u.is_empty() {
            dim_units[d] = cstr(u);
        }
    }
    let mut labels: [Vec<String>; 4] = Default::default();
    for (d, &n) in dim_labels.iter().enumerate() {
        let l = take(n, &format!("dimension {d} labels"))?;
        labels[d] = l.chunks(32).map(cstr).collect();
    }
    Ok(Wave {
        le,
        dims,
        sfa,
        sfb,
        data_unit,
        dim_units,
        note,
        labels,
        data,
        elsize,
        conv,
    })
}

/// Read an Igor binary wave of `version` (only 5 is read) as a force curve.
pub(crate) fn read(bytes: &[u8], version: (i16, bool), path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let err = |msg: String| Error::data_file(path, 0, msg);
    let wave = wave(bytes, version, path)?;
    let dims = wave.dims;
    let rows = dims[0];
    let cols = dims[1].max(1);
    if dims[2] > 1 || dims[3] > 1 {
        return Err(err(
            "Igor wave with more than two dimensions: not a force curve".into()
        ));
    }
    let (sfa0, sfb0) = (wave.sfa[0], wave.sfb[0]);
    let dim0_unit = wave.dim_units[0].clone();
    let note = wave.note.clone();
    let mut labels: Vec<String> = wave.labels[1].iter().skip(1).cloned().collect();
    let notes: HashMap<&str, &str> = note
        .split('\r')
        .filter_map(|line| line.split_once(':'))
        .map(|(k, v)| (k, v.trim()))
        .collect();
    let note_num = |k: &str| {
        notes
            .get(k)
            .and_then(|v| super::text::float(v))
            .filter(|v| v.is_finite())
    };
    let k_file = note_num("SpringConstant")
        .ok_or_else(|| err("the note has no SpringConstant (needed for the force)".into()))?;
    let s_file = note_num("InvOLS");
    let column = |j: usize| -> Vec<f64> { wave.values(j * rows as usize, rows as usize) };
    if labels.len() < cols as usize {
        labels.resize(cols as usize, String::new());
    }
    let find = |names: &[&str]| {
        names
            .iter()
            .find_map(|n| labels.iter().take(cols as usize).position(|l| l == n))
    };
    let piezo = find(&["Raw", "Height"]).map(|j| column(j).into_iter().map(|v| -v).collect::<Vec<_>>());
    let measured = find(&["ZSnsr", "ZSensor"]).map(|j| column(j).into_iter().map(|v| -v).collect::<Vec<_>>());
    let defl_col = find(&["Defl", "Deflection"]).ok_or_else(|| {
        err(format!(
            "no Defl or Deflection column among the labels {labels:?}"
        ))
    })?;
    let k = opts.spring_constant.unwrap_or(k_file);
    let defl_scale = match (opts.sensitivity, s_file) {
        (Some(s), Some(sf)) if sf != 0.0 => s / sf,
        _ => 1.0,
    };
    let force: Vec<f64> = column(defl_col).into_iter().map(|v| v * defl_scale * k).collect();
    let time = (dim0_unit == "s" && sfa0.is_finite() && sfb0.is_finite())
        .then(|| (0..rows).map(|i| sfb0 + i as f64 * sfa0).collect::<Vec<_>>());
    let n = force.len();
    let whole = Segment {
        kind: None,
        force,
        height_measured: measured,
        height_piezo: piezo,
        time,
        tip_position: None,
    };
    let segments = split(
        whole,
        notes.get("Indexes").copied(),
        notes.get("Direction").copied(),
        n,
    );
    let setpoint = (notes.get("TriggerChannel").copied() == Some("Force"))
        .then(|| note_num("TriggerPoint"))
        .flatten();
    let meta = CurveMeta {
        spring_constant: Some(k),
        sensitivity: opts.sensitivity.or(s_file),
        setpoint,
        time_of_day: match (notes.get("Date"), notes.get("Time")) {
            (Some(d), Some(t)) => Some(format!("{d} {t}")),
            (Some(d), None) => Some(d.to_string()),
            _ => None,
        },
        instrument: notes.get("MicroscopeModel").map(|s| s.to_string()),
        ..CurveMeta::default()
    };
    let file = ForceFile {
        format: "Asylum Research Igor binary wave (.ibw)".into(),
        curves: vec![ForceCurve {
            index: 0,
            segments,
            meta,
        }],
    };
    super::check_lengths(&file, path)?;
    Ok(file)
}

/// Split the whole curve at the note's `Indexes` (the last sample of each segment, the first
/// entry 0) with the `Direction` of each; one segment without a kind when they do not describe
/// the curve.
fn split(whole: Segment, indexes: Option<&str>, direction: Option<&str>, n: usize) -> Vec<Segment> {
    let parse = |s: Option<&str>| -> Option<Vec<f64>> {
        s?.split(',')
            .filter(|t| !t.trim().is_empty())
            .map(super::text::float)
            .collect()
    };
    let (Some(idx), Some(dir)) = (parse(indexes), parse(direction)) else {
        return vec![whole];
    };
    let valid = idx.len() >= 2
        && idx.len() == dir.len()
        && idx[0] == 0.0
        && idx.iter().all(|v| v.fract() == 0.0 && *v >= 0.0)
        && idx.windows(2).all(|w| w[1] > w[0])
        && idx[idx.len() - 1] == (n as f64 - 1.0);
    if !valid {
        return vec![whole];
    }
    let cut = |v: &Option<Vec<f64>>, a: usize, b: usize| v.as_ref().map(|v| v[a..b].to_vec());
    (1..idx.len())
        .map(|j| {
            let a = if j == 1 { 0 } else { idx[j - 1] as usize + 1 };
            let b = idx[j] as usize + 1;
            let kind = if dir[j] > 0.0 {
                Some(SegmentKind::Approach)
            } else if dir[j] < 0.0 {
                Some(SegmentKind::Retract)
            } else if dir[j] == 0.0 {
                Some(SegmentKind::Pause)
            } else {
                None
            };
            Segment {
                kind,
                force: whole.force[a..b].to_vec(),
                height_measured: cut(&whole.height_measured, a, b),
                height_piezo: cut(&whole.height_piezo, a, b),
                time: cut(&whole.time, a, b),
                tip_position: None,
            }
        })
        .collect()
}
