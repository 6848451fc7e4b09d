//! Readers of measured height maps from instrument and exchange files, recognised by their
//! content (magic bytes, zip entries, text headers; the extension only words errors):
//!
//! | format | module | channels |
//! |---|---|---|
//! | text matrix (CSV, whitespace; Gwyddion/SPIP/ST headers) and xyz text | `text` | one |
//! | Gwyddion simple field `.gsf` | [`crate::surface::io`] | one |
//! | ISO 25178-72 XML 3D surface profile `.x3p` (zip + XML) | `x3p` | one |
//! | ISO 25178-71 surface data file `.sdf`, text and binary | `sdf` | one |
//! | Gwyddion native `.gwy` | `gwy` | every data field with a length unit |
//! | Digital Surf `.sur` | `sur` | one per object in the file |
//! | Asylum Research Igor binary wave image `.ibw` | `ibw` | one per layer |
//! | Bruker / Digital Instruments Nanoscope `.di`, `.spm` | `di` | one per image |
//! | Agilent / Molecular Imaging PicoView `.mi` | `mi` | one per buffer |
//! | Alicona Imaging `.al3d` | `al3d` | one (the depth image) |
//! | Nanosurf easyScan `.nid`, `.ezd` | `nid` | one per data set (frame and quantity) |
//! | Sensofar `.plu`, `.apx` | `plu` | one per layer |
//! | Zygo MetroPro `.dat` | `metropro` | one (the phase map) |
//! | Bruker Wyko `.opd` | `opd` | one per raster |
//! | Bruker Dektak `.opdx` | `opdx` | the primary map, or each line scan |
//! | Digital Surf Mountains `.mnt` (OLE compound file) | `mnt` | the surface |
//!
//! Each reader yields [`Channel`]s: name, grid, physical size and units as the file declares
//! them, and the heights decoded on demand (only the chosen channel is decoded). Heights keep
//! the file's numbers times its scale; NaN marks a missing (masked, invalid) point.
//! [`Measured::into_height_map`] converts to metres and refuses what the analysis cannot take:
//! a line scan, missing points (counted, the first located), lengths or heights without a length
//! unit.
//!
//! Bounds: a header's grid is checked against [`MAX_POINTS`] and against the bytes actually
//! present before anything is allocated from it.

use std::path::Path;

use super::height_map::{HeightMap, size_problem};
use crate::error::{Error, Result};
use crate::params::fmt_sig;

mod al3d;
mod di;
pub(crate) mod gsf;
mod gwy;
mod ibw;
mod metropro;
mod mi;
mod mnt;
mod nid;
mod opd;
mod opdx;
mod plu;
mod sdf;
mod sur;
pub(crate) mod text;
mod x3p;

/// A text height map's header and heights ([`text`]), for [`crate::surface::io::parse_csv`].
///
/// # Errors
/// [`Error::DataFile`] naming the line or the file.
pub fn text_map(text: &str, path: &Path) -> Result<(ChannelInfo, Vec<f64>)> {
    text::parse(text, path)
}

/// Largest grid a header may claim: 2^28 points (2 GiB of f64 heights).
pub const MAX_POINTS: usize = 1 << 28;

/// A unit as the file writes it, with its size in metres when it is a length.
#[derive(Debug, Clone, PartialEq)]
pub struct Unit {
    /// The unit as written (empty when the file names none).
    pub name: String,
    /// Metres per unit; `None` when the unit is not a length (or unknown).
    pub metres: Option<f64>,
}

impl Unit {
    /// A unit from its name ([`metres_per_unit`]).
    pub fn named(name: &str) -> Unit {
        let name = name.trim();
        Unit {
            name: name.to_string(),
            metres: metres_per_unit(name),
        }
    }

    /// Metres, for the text formats whose convention is SI.
    pub fn metre() -> Unit {
        Unit::named("m")
    }
}

/// Metres per unit of a length unit: `m` with an SI prefix (`km` to `fm`; `u`, `µ`, `μ` or
/// `micro` for micro), ångström (`A`, `Å`), or a spelled-out name (`micrometer`, `nm`, `micron`);
/// `None` for anything else.
pub fn metres_per_unit(unit: &str) -> Option<f64> {
    let u = unit.trim();
    Some(match u {
        "m" | "meter" | "metre" | "meters" | "metres" => 1.0,
        "km" => 1e3,
        "cm" => 1e-2,
        "mm" | "millimeter" | "millimetre" => 1e-3,
        "um" | "µm" | "μm" | "micrometer" | "micrometre" | "micron" | "microns" | "micro m" => 1e-6,
        "nm" | "nanometer" | "nanometre" => 1e-9,
        "pm" | "picometer" | "picometre" => 1e-12,
        "fm" => 1e-15,
        "A" | "\u{c5}" | "\u{212b}" | "Ang" | "angstrom" => 1e-10,
        _ => return None,
    })
}

/// What a channel holds, read from the header only.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelInfo {
    /// Channel name (as the file gives it, or `Default`).
    pub name: String,
    /// Points in x.
    pub nx: usize,
    /// Points in y (1 for a line scan).
    pub ny: usize,
    /// Physical size in x and y [`xy_unit`], when the file gives it.
    pub size: Option<[f64; 2]>,
    /// Unit of the lengths.
    pub xy_unit: Unit,
    /// Unit of the heights.
    pub z_unit: Unit,
    /// One period of a periodic surface (as the file says).
    pub periodic: bool,
}

impl ChannelInfo {
    /// The one channel (`Default`) of a file whose grid of `nx` × `ny` points is spaced by
    /// `dx`, `dy` and whose lengths and heights are in metres (not periodic).
    fn single_in_metres(nx: usize, ny: usize, dx: f64, dy: f64) -> Self {
        Self {
            name: "Default".into(),
            nx,
            ny,
            size: Some([dx * nx as f64, dy * ny as f64]),
            xy_unit: Unit::metre(),
            z_unit: Unit::metre(),
            periodic: false,
        }
    }

    /// Check the grid before anything is allocated from it.
    fn check_grid(&self, path: &Path) -> Result<()> {
        let n = self.nx.checked_mul(self.ny).filter(|&n| n <= MAX_POINTS);
        if n.is_none() {
            return Err(Error::data_file(
                path,
                0,
                format!(
                    "channel {}: the header claims {} x {} points, above the limit of {MAX_POINTS}",
                    self.name, self.nx, self.ny
                ),
            ));
        }
        if self.nx == 0 || self.ny == 0 {
            return Err(Error::data_file(
                path,
                0,
                format!(
                    "channel {}: the header claims {} x {} points",
                    self.name, self.nx, self.ny
                ),
            ));
        }
        Ok(())
    }

    /// One line describing the channel, for listings.
    pub fn describe(&self) -> String {
        let size = match self.size {
            Some([x, y]) if self.ny > 1 => {
                format!("{} x {} {}", fmt_sig(x), fmt_sig(y), unit_or(&self.xy_unit))
            }
            Some([x, _]) => format!("{} {}", fmt_sig(x), unit_or(&self.xy_unit)),
            None => "size not given".to_string(),
        };
        let grid = if self.ny > 1 {
            format!("{} x {} points", self.nx, self.ny)
        } else {
            format!("line scan of {} points", self.nx)
        };
        format!(
            "{}: {grid}, {size}, heights in {}",
            self.name,
            unit_or(&self.z_unit)
        )
    }
}

fn unit_or(u: &Unit) -> &str {
    if u.name.is_empty() { "(no unit)" } else { &u.name }
}

/// Decoder of a channel's heights, run only for the chosen channel.
type Decode<'a> = Box<dyn FnOnce() -> Result<Vec<f64>> + 'a>;

/// A channel of a file: its header and its heights, decoded on demand.
pub(crate) struct Channel<'a> {
    pub(crate) info: ChannelInfo,
    pub(crate) decode: Decode<'a>,
}

impl<'a> Channel<'a> {
    /// A channel whose heights are already decoded.
    pub(crate) fn ready(info: ChannelInfo, z: Vec<f64>) -> Channel<'a> {
        Channel {
            info,
            decode: Box::new(move || Ok(z)),
        }
    }
}

/// One channel of a file, read: its header and heights (in [`ChannelInfo::z_unit`], NaN where
/// the point is missing), `z[j * nx + i]` at x index i and y index j.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The file format.
    pub format: &'static str,
    /// The channel's header.
    pub info: ChannelInfo,
    /// Heights, row-major (rows are y).
    pub z: Vec<f64>,
}

/// The formats read, recognised by content.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Text matrix or xyz text.
    Text,
    /// Gwyddion simple field.
    Gsf,
    /// ISO 25178-72 `.x3p`.
    X3p,
    /// ISO 25178-71 `.sdf`.
    Sdf,
    /// Gwyddion native `.gwy`.
    Gwy,
    /// Digital Surf `.sur`.
    Sur,
    /// Asylum Igor binary wave `.ibw`.
    Ibw,
    /// Bruker / Digital Instruments Nanoscope.
    Di,
    /// Agilent / Molecular Imaging `.mi`.
    Mi,
    /// Alicona Imaging `.al3d`.
    Al3d,
    /// Nanosurf easyScan `.nid`.
    Nid,
    /// Sensofar `.plu`.
    Plu,
    /// Zygo MetroPro `.dat`.
    MetroPro,
    /// Bruker Wyko `.opd`.
    Opd,
    /// Bruker Dektak `.opdx`.
    Opdx,
    /// Digital Surf Mountains `.mnt`.
    Mnt,
}

impl Format {
    /// A name for messages and listings.
    pub fn name(self) -> &'static str {
        match self {
            Format::Text => "text height map",
            Format::Gsf => "Gwyddion simple field (.gsf)",
            Format::X3p => "ISO 25178-72 X3P (.x3p)",
            Format::Sdf => "ISO 25178-71 surface data file (.sdf)",
            Format::Gwy => "Gwyddion (.gwy)",
            Format::Sur => "Digital Surf (.sur)",
            Format::Ibw => "Igor binary wave (.ibw)",
            Format::Di => "Bruker/Digital Instruments Nanoscope (.di, .spm)",
            Format::Mi => "Agilent/Molecular Imaging (.mi)",
            Format::Al3d => "Alicona Imaging (.al3d)",
            Format::Nid => "Nanosurf easyScan (.nid)",
            Format::Plu => "Sensofar (.plu)",
            Format::MetroPro => "Zygo MetroPro (.dat)",
            Format::Opd => "Bruker Wyko (.opd)",
            Format::Opdx => "Bruker Dektak (.opdx)",
            Format::Mnt => "Digital Surf Mountains (.mnt)",
        }
    }

    /// True for the formats that carry their own lengths (a pixel size does not apply).
    pub fn has_lengths(self) -> bool {
        self != Format::Text
    }
}

/// The format of a file from its first bytes.
///
/// # Errors
/// [`Error::DataFile`] for binary content of no known format (naming what the start looks like).
pub fn detect(bytes: &[u8], path: &Path) -> Result<Format> {
    if bytes.starts_with(b"Gwyddion Simple Field") {
        return Ok(Format::Gsf);
    }
    if bytes.starts_with(b"GWYP") {
        return Ok(Format::Gwy);
    }
    if bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06") {
        return Ok(Format::X3p);
    }
    if bytes.starts_with(b"aISO-1.0") || bytes.starts_with(b"bISO-1.0") {
        return Ok(Format::Sdf);
    }
    if bytes.starts_with(b"DIGITAL SURF") || bytes.starts_with(b"DSCOMPRESSED") {
        return Ok(Format::Sur);
    }
    if bytes.starts_with(b"\\*File list") || bytes.starts_with(b"\\*EC File list") {
        return Ok(Format::Di);
    }
    if bytes.starts_with(al3d::MAGIC) {
        return Ok(Format::Al3d);
    }
    if bytes.starts_with(b"fileType      ") {
        return Ok(Format::Mi);
    }
    if bytes.starts_with(nid::MAGIC) && matches!(bytes.get(nid::MAGIC.len()), Some(b'\r' | b'\n')) {
        return Ok(Format::Nid);
    }
    if metropro::MAGICS.iter().any(|m| bytes.starts_with(m)) {
        return Ok(Format::MetroPro);
    }
    if bytes.get(2..2 + opd::MAGIC.len()) == Some(opd::MAGIC) {
        return Ok(Format::Opd);
    }
    if bytes.starts_with(opdx::MAGIC) {
        return Ok(Format::Opdx);
    }
    if bytes.starts_with(mnt::OLE_MAGIC) {
        return Ok(Format::Mnt);
    }
    if bytes.len() >= 8 && crate::readers::igor::version(bytes).is_some() {
        return Ok(Format::Ibw);
    }
    if plu::looks_like(bytes) {
        return Ok(Format::Plu);
    }
    let head = &bytes[..bytes.len().min(4096)];
    let binary = head.contains(&0)
        || (std::str::from_utf8(head).is_err()
            && head.iter().filter(|&&b| b >= 0x80).count() * 4 > head.len());
    if binary {
        let shown: String = bytes
            .iter()
            .take(16)
            .map(|&b| if b.is_ascii_graphic() { b as char } else { '.' })
            .collect();
        return Err(Error::data_file(
            path,
            0,
            format!(
                "not a height map this program reads (binary file starting `{shown}`); formats: \
                 text matrix or xyz, .gsf, .gwy, .x3p, .sdf, .sur, .ibw, Nanoscope .di/.spm, .mi, .al3d, \
                 .nid, .plu, MetroPro .dat, .opd, .opdx, .mnt"
            ),
        ));
    }
    Ok(Format::Text)
}

/// The channels of the file in `bytes`.
fn channels<'a>(format: Format, bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let list = match format {
        Format::Text => text::channels(bytes, path)?,
        Format::Gsf => {
            let map = gsf::parse_gsf(bytes, path)?;
            let info = ChannelInfo {
                name: "Default".into(),
                nx: map.nx,
                ny: map.ny,
                size: Some([map.lx, map.ly]),
                xy_unit: Unit::metre(),
                z_unit: Unit::metre(),
                periodic: map.periodic,
            };
            vec![Channel::ready(info, map.z)]
        }
        Format::X3p => x3p::channels(bytes, path)?,
        Format::Sdf => sdf::channels(bytes, path)?,
        Format::Gwy => gwy::channels(bytes, path)?,
        Format::Sur => sur::channels(bytes, path)?,
        Format::Ibw => ibw::channels(bytes, path)?,
        Format::Di => di::channels(bytes, path)?,
        Format::Mi => mi::channels(bytes, path)?,
        Format::Al3d => al3d::channels(bytes, path)?,
        Format::Nid => nid::channels(bytes, path)?,
        Format::Plu => plu::channels(bytes, path)?,
        Format::MetroPro => metropro::channels(bytes, path)?,
        Format::Opd => opd::channels(bytes, path)?,
        Format::Opdx => opdx::channels(bytes, path)?,
        Format::Mnt => mnt::channels(bytes, path)?,
    };
    if list.is_empty() {
        return Err(Error::data_file(
            path,
            0,
            format!("{}: the file holds no height channel", format.name()),
        ));
    }
    for c in &list {
        c.info.check_grid(path)?;
    }
    Ok(list)
}

/// The format and channels of the file in `bytes`, headers only.
///
/// # Errors
/// [`Error::DataFile`] naming the file and what is wrong with it.
pub fn list_bytes(bytes: &[u8], path: &Path) -> Result<(Format, Vec<ChannelInfo>)> {
    let format = detect(bytes, path)?;
    let list = channels(format, bytes, path)?;
    Ok((format, list.into_iter().map(|c| c.info).collect()))
}

/// Read the channel named `channel` (or the first whose heights are lengths, else the first)
/// of the file in `bytes`.
///
/// # Errors
/// [`Error::DataFile`] naming the file and what is wrong with it; for a channel the file does
/// not hold, the message lists the channels it does hold.
pub fn parse_bytes(bytes: &[u8], path: &Path, channel: Option<&str>) -> Result<Measured> {
    let format = detect(bytes, path)?;
    let list = channels(format, bytes, path)?;
    let k = choose(&list, channel, path)?;
    let c = list.into_iter().nth(k).expect("chosen index in range");
    let info = c.info;
    let z = (c.decode)()?;
    if z.len() != info.nx * info.ny {
        return Err(Error::data_file(
            path,
            0,
            format!(
                "channel {}: {} heights decoded for {} x {} points",
                info.name,
                z.len(),
                info.nx,
                info.ny
            ),
        ));
    }
    Ok(Measured {
        format: format.name(),
        info,
        z,
    })
}

/// The index of the wanted channel: by exact name, else by name ignoring case; the first length
/// channel when none is named.
fn choose(list: &[Channel], wanted: Option<&str>, path: &Path) -> Result<usize> {
    let Some(w) = wanted else {
        return Ok(list
            .iter()
            .position(|c| c.info.z_unit.metres.is_some())
            .unwrap_or(0));
    };
    list.iter()
        .position(|c| c.info.name == w)
        .or_else(|| {
            list.iter()
                .position(|c| c.info.name.eq_ignore_ascii_case(w.trim()))
        })
        .ok_or_else(|| {
            let names: Vec<String> = list.iter().map(|c| format!("`{}`", c.info.name)).collect();
            Error::data_file(
                path,
                0,
                format!("no channel `{w}`; the file holds {}", names.join(", ")),
            )
        })
}

/// Read the file at `path` (bounded by [`crate::input`]) and its channel `channel`.
///
/// # Errors
/// As [`parse_bytes`], or when the file cannot be read.
pub fn read_measured(path: &Path, channel: Option<&str>) -> Result<Measured> {
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    parse_bytes(&bytes, path, channel)
}

/// The channels of the file at `path`, one line each, after a line naming the format.
///
/// # Errors
/// As [`list_bytes`], or when the file cannot be read.
pub fn list_channels(path: &Path) -> Result<String> {
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    let (format, list) = list_bytes(&bytes, path)?;
    let mut s = format!("{}: {}\n", path.display(), format.name());
    for c in list {
        s.push_str("  ");
        s.push_str(&c.describe());
        s.push('\n');
    }
    Ok(s)
}

impl Measured {
    /// The heights as a [`HeightMap`] in metres. `pixel_size` [m] gives the lengths of a file
    /// without them (a plain text matrix) and overrides those of a text file's header.
    ///
    /// # Errors
    /// [`Error::DataFile`] naming the file for a line scan, missing points (how many, the first
    /// located), heights or lengths without a length unit, no lengths and no pixel size, or a
    /// grid the analysis cannot take.
    pub fn into_height_map(self, path: &Path, pixel_size: Option<f64>, text: bool) -> Result<HeightMap> {
        let Measured { info, z, .. } = self;
        let err = |m: String| Error::data_file(path, 0, format!("channel {}: {m}", info.name));
        if info.ny < 2 || info.nx < 2 {
            return Err(err(format!(
                "a line scan (1D profile) of {} points; the surface analysis needs a 2D height map \
                 of at least 2 x 2 points",
                info.nx * info.ny
            )));
        }
        let missing = z.iter().filter(|v| !v.is_finite()).count();
        if missing > 0 {
            let first = z.iter().position(|v| !v.is_finite()).unwrap_or(0);
            return Err(err(format!(
                "{missing} of {} points are missing (not finite: NaN or masked), the first at x index {}, y \
                 index {} (counting from 0); fill or crop them first (Gwyddion: Data Process > \
                 Correct Data > Interpolate Data Under Mask, or Basic Operations > Crop)",
                z.len(),
                first % info.nx,
                first / info.nx
            )));
        }
        let zf = info.z_unit.metres.ok_or_else(|| {
            err(if info.z_unit.name.is_empty() {
                "the file gives no unit for the heights: not read as lengths".to_string()
            } else {
                format!(
                    "heights in `{}`, not a length unit: not a height channel",
                    info.z_unit.name
                )
            })
        })?;
        let (lx, ly) = match (pixel_size.filter(|_| text), info.size) {
            (Some(p), _) => {
                if !(p > 0.0 && p.is_finite()) {
                    return Err(err(format!(
                        "pixel size {} must be positive and finite",
                        fmt_sig(p)
                    )));
                }
                (p * info.nx as f64, p * info.ny as f64)
            }
            (None, Some([x, y])) => {
                let f = info.xy_unit.metres.ok_or_else(|| {
                    err(if info.xy_unit.name.is_empty() {
                        "the file gives no unit for its lengths: not read as lengths".to_string()
                    } else {
                        format!("lengths in `{}`, not a length unit", info.xy_unit.name)
                    })
                })?;
                (x * f, y * f)
            }
            (None, None) => {
                return Err(err(
                    "no pixel size: give --pixel-size METRES for a plain text matrix".into(),
                ));
            }
        };
        if !(lx > 0.0 && ly > 0.0 && lx.is_finite() && ly.is_finite()) {
            return Err(err(format!(
                "physical size {} m x {} m must be positive and finite",
                fmt_sig(lx),
                fmt_sig(ly)
            )));
        }
        if let Some(reason) = size_problem(info.nx, info.ny, lx, ly) {
            return Err(match pixel_size.filter(|_| text) {
                Some(p) => err(format!("pixel size {}: {reason}", fmt_sig(p))),
                None if text => err(format!(
                    "header lx = {}, ly = {}: {reason}",
                    fmt_sig(lx),
                    fmt_sig(ly)
                )),
                None => err(format!(
                    "physical size {} m x {} m: {reason}",
                    fmt_sig(lx),
                    fmt_sig(ly)
                )),
            });
        }
        let z: Vec<f64> = if zf == 1.0 {
            z
        } else {
            z.into_iter().map(|v| v * zf).collect()
        };
        if let Some(bad) = z.iter().position(|v| !v.is_finite()) {
            return Err(err(format!(
                "height at x index {}, y index {} overflows in metres",
                bad % info.nx,
                bad / info.nx
            )));
        }
        let mut map = HeightMap::new(info.nx, info.ny, lx, ly, z).map_err(|e| err(e.to_string()))?;
        map.periodic = info.periodic;
        Ok(map)
    }
}

/// Split `FILE#CHANNEL` into the file and the channel, when the whole is not itself an existing
/// file and the part after the last `#` is not empty.
pub fn split_channel(path: &Path) -> (std::borrow::Cow<'_, Path>, Option<String>) {
    if path.exists() {
        return (path.into(), None);
    }
    let Some(s) = path.to_str() else {
        return (path.into(), None);
    };
    match s.rsplit_once('#') {
        Some((file, channel)) if !channel.is_empty() && !file.is_empty() && !channel.contains('/') => {
            (Path::new(file).to_path_buf().into(), Some(channel.to_string()))
        }
        _ => (path.into(), None),
    }
}

/// Little-endian / big-endian readers of fixed-size fields, bounds-checked.
pub(crate) struct Bytes<'a> {
    pub(crate) b: &'a [u8],
    pub(crate) le: bool,
}

impl<'a> Bytes<'a> {
    pub(crate) fn slice(&self, at: usize, n: usize) -> Option<&'a [u8]> {
        self.b.get(at..at.checked_add(n)?)
    }
    pub(crate) fn arr<const N: usize>(&self, at: usize) -> Option<[u8; N]> {
        let mut x: [u8; N] = self.slice(at, N)?.try_into().ok()?;
        if !self.le {
            x.reverse();
        }
        Some(x)
    }
    pub(crate) fn u16(&self, at: usize) -> Option<u16> {
        self.arr(at).map(u16::from_le_bytes)
    }
    pub(crate) fn i16(&self, at: usize) -> Option<i16> {
        self.arr(at).map(i16::from_le_bytes)
    }
    pub(crate) fn u32(&self, at: usize) -> Option<u32> {
        self.arr(at).map(u32::from_le_bytes)
    }
    pub(crate) fn i32(&self, at: usize) -> Option<i32> {
        self.arr(at).map(i32::from_le_bytes)
    }
    pub(crate) fn f32(&self, at: usize) -> Option<f32> {
        self.arr(at).map(f32::from_le_bytes)
    }
    pub(crate) fn f64(&self, at: usize) -> Option<f64> {
        self.arr(at).map(f64::from_le_bytes)
    }
}

/// Number types of binary height data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Num {
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Num {
    pub(crate) fn size(self) -> usize {
        match self {
            Num::I16 | Num::U16 => 2,
            Num::I32 | Num::U32 | Num::F32 => 4,
            Num::F64 => 8,
        }
    }

    /// Decode `n` numbers from `data` (which must hold them: checked by the caller, again here).
    /// One loop over whole chunks per type and byte order (no bounds check per number).
    pub(crate) fn decode(self, data: &[u8], n: usize, le: bool) -> Option<Vec<f64>> {
        let data = data.get(..n.checked_mul(self.size())?)?;
        fn all<const N: usize>(data: &[u8], f: impl Fn([u8; N]) -> f64) -> Vec<f64> {
            data.chunks_exact(N)
                .map(|c| f(c.try_into().expect("chunks_exact gives N bytes")))
                .collect()
        }
        macro_rules! of {
            ($n:literal, $t:ty) => {
                if le {
                    all::<$n>(data, |b| <$t>::from_le_bytes(b) as f64)
                } else {
                    all::<$n>(data, |b| <$t>::from_be_bytes(b) as f64)
                }
            };
        }
        Some(match self {
            Num::I16 => of!(2, i16),
            Num::U16 => of!(2, u16),
            Num::I32 => of!(4, i32),
            Num::U32 => of!(4, u32),
            Num::F32 => of!(4, f32),
            Num::F64 => of!(8, f64),
        })
    }
}

/// `n` numbers of type `num` at `at` in `bytes`, or an error naming what is truncated.
pub(crate) fn numbers(
    bytes: &[u8],
    at: usize,
    n: usize,
    num: Num,
    le: bool,
    path: &Path,
    what: &str,
) -> Result<Vec<f64>> {
    let need = n.checked_mul(num.size());
    match need.and_then(|need| at.checked_add(need)) {
        Some(end) if end <= bytes.len() => Ok(num.decode(&bytes[at..end], n, le).expect("length checked")),
        _ => Err(truncated(
            path,
            what,
            need.unwrap_or(usize::MAX),
            bytes.len().saturating_sub(at),
        )),
    }
}

/// "truncated file: the {what} needs {need} bytes, {have} are left".
pub(crate) fn truncated(path: &Path, what: &str, need: usize, have: usize) -> Error {
    Error::data_file(
        path,
        0,
        format!("truncated file: the {what} needs {need} bytes, {have} are left"),
    )
}

/// A NUL-terminated (or field-filling) Latin-1 string.
pub(crate) fn cstr(b: &[u8]) -> String {
    let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    b[..end]
        .iter()
        .map(|&c| c as char)
        .collect::<String>()
        .trim()
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_and_channel_suffix() {
        assert_eq!(metres_per_unit("µm"), Some(1e-6));
        assert_eq!(metres_per_unit("nm"), Some(1e-9));
        assert_eq!(metres_per_unit("V"), None);
        let (p, c) = split_channel(Path::new("/no/such/file.gwy#Height"));
        assert_eq!(p.to_str(), Some("/no/such/file.gwy"));
        assert_eq!(c.as_deref(), Some("Height"));
        let (_, c) = split_channel(Path::new("/no/such/file.gwy"));
        assert_eq!(c, None);
    }

    #[test]
    fn a_huge_grid_is_refused_before_decoding() {
        let info = ChannelInfo {
            name: "Z".into(),
            nx: 100_000,
            ny: 100_000,
            size: Some([1.0, 1.0]),
            xy_unit: Unit::metre(),
            z_unit: Unit::metre(),
            periodic: false,
        };
        let e = info.check_grid(Path::new("f")).unwrap_err().to_string();
        assert!(e.contains("100000 x 100000"), "{e}");
    }
}
