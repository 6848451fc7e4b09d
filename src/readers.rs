//! Readers of what users bring from their instruments: bytes in, typed records with SI units and
//! metadata out. Readers know file formats, not models: [`crate::fit`] takes a
//! [`ForceCurve`], never a file format.
//!
//! A force-distance file (a single curve, or a force map / QI series of many) becomes a
//! [`ForceFile`]: curves, each with its segments (approach, retract, pauses) in acquisition
//! order, the channels they hold in SI units, and the metadata the file declares (spring
//! constant, sensitivity, position in the map, time).
//!
//! Conventions, those of afmformats (so that its readings and ours compare column by column):
//! - `force` [N] is the cantilever force, positive when the cantilever is bent away from the
//!   sample (the tip pressed into it), in the instrument's own baseline (offsets not removed);
//! - `height_measured`, `height_piezo` [m] are the z positions of the cantilever base as the
//!   instrument reports them: they **decrease** as the base moves towards the sample;
//! - `time` [s] from the start of the curve.
//!
//! [`read_force_file`] reads any of the formats below, recognised by their content (zip entries,
//! Igor header, text headers; the extension only breaks ties and words errors):
//!
//! | format | module | curves |
//! |---|---|---|
//! | JPK `.jpk-force`, `.jpk-force-map`, `.jpk-qi-data`, `.jpk-qi-series` | `jpk` | one per index of the map |
//! | Asylum Research Igor binary wave v5 `.ibw` | `igor` | one |
//! | NT-MDT Nova text export `.txt` | `ntmdt` | one |
//! | AFM Workshop `.csv`, and a `.zip` of them (a map) | `workshop` | one per CSV |
//! | afmformats tab-separated export `.tab` | `tab` | one |
//! | Optics11 Chiaro text export `.txt`, and a `.zip` of them | `chiaro` | one per text file |
//! | afmformats HDF5 export `.h5` | `hdf5` | one per group |
//!
//! Values the file lacks or that the user overrides come from [`ReadOptions`]: how each format
//! uses them is in [`ReadOptions`]' documentation.
//!
//! Input is bounded: a file must be regular and within the input limit of [`crate::input`]; sizes, counts and
//! offsets claimed by headers are checked against the bytes actually present before anything is
//! allocated from them; a zip entry decompresses to at most 64 times the archive's size (at least
//! 16 MiB, at most 4 GiB), and so do all entries of one archive together.

use serde::Serialize;
use std::path::Path;

pub(crate) mod archive;
mod chiaro;
mod hdf5;
pub(crate) mod igor;
mod jpk;
mod ntmdt;
mod properties;
mod tab;
mod text;
mod workshop;

/// The kind of a segment of a force-distance curve.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SegmentKind {
    /// Moving towards the sample (extend).
    Approach,
    /// Moving away from the sample.
    Retract,
    /// Holding still (pause, dwell, "intermediate").
    Pause,
}

/// One segment of a curve: its samples in acquisition order, every present channel of the same
/// length as `force`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Segment {
    /// What the segment is, as the file says (or as its direction shows where the file is silent).
    pub kind: Option<SegmentKind>,
    /// Cantilever force [N].
    pub force: Vec<f64>,
    /// Measured height of the cantilever base (strain-gauge / sensor) [m].
    pub height_measured: Option<Vec<f64>>,
    /// Height of the cantilever base from the piezo drive signal [m].
    pub height_piezo: Option<Vec<f64>>,
    /// Time [s].
    pub time: Option<Vec<f64>>,
    /// Position of the tip [m] (height of the base minus the cantilever's deflection), where the
    /// file gives it (Optics11 Chiaro); elsewhere the fits derive it from the height and force.
    pub tip_position: Option<Vec<f64>>,
}

impl Segment {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.force.len()
    }

    /// True when the segment holds no sample.
    pub fn is_empty(&self) -> bool {
        self.force.is_empty()
    }

    /// The height the preprocessing uses: the measured height where the file has one, else the
    /// piezo height.
    pub fn height(&self) -> Option<&[f64]> {
        self.height_measured.as_deref().or(self.height_piezo.as_deref())
    }
}

/// Metadata of one curve as its file declares them (SI units; `None` where the file is silent).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct CurveMeta {
    /// Cantilever spring constant [N/m].
    pub spring_constant: Option<f64>,
    /// Deflection sensitivity (InvOLS) [m/V].
    pub sensitivity: Option<f64>,
    /// Lateral position of the curve [m] (x, y).
    pub position: Option<[f64; 2]>,
    /// Index of the curve in its map's grid (x, y).
    pub grid_index: Option<[usize; 2]>,
    /// Shape of the map's grid (x, y).
    pub grid_shape: Option<[usize; 2]>,
    /// Size of the map's grid [m] (x, y).
    pub grid_size: Option<[f64; 2]>,
    /// Force setpoint [N].
    pub setpoint: Option<f64>,
    /// Date and time of the recording, as the file writes it.
    pub time_of_day: Option<String>,
    /// Instrument or software that wrote the file.
    pub instrument: Option<String>,
}

/// One force-distance curve.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ForceCurve {
    /// Index of the curve in its file (0 for a single-curve file).
    pub index: usize,
    /// Segments in acquisition order.
    pub segments: Vec<Segment>,
    /// Metadata.
    pub meta: CurveMeta,
}

impl ForceCurve {
    /// The first segment of a kind.
    pub fn segment(&self, kind: SegmentKind) -> Option<&Segment> {
        self.segments.iter().find(|s| s.kind.as_ref() == Some(&kind))
    }
}

/// A force-distance file: its format and its curves.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ForceFile {
    /// The format, in words (e.g. "JPK force map (.jpk-force-map)").
    pub format: String,
    /// The curves in file order.
    pub curves: Vec<ForceCurve>,
}

/// Values a reader may need that the file does not hold (given on the command line).
///
/// How the readers use them:
/// - JPK: as afmformats does, an override replaces the multiplier of the deflection channel's
///   `force` (spring constant) or `distance` (sensitivity) conversion and zeroes its offset, so
///   the force is the raw deflection converted through the new chain (with the usual zero offsets
///   this is the file's force times k_new/k_file, resp. s_new/s_file); a file lacking either value
///   is refused unless the option gives it.
/// - Asylum `.ibw`: the deflection [m] is stored; force = deflection × k, with k the override
///   where given; a sensitivity override rescales the deflection by s_new/s_file.
/// - AFM Workshop: a curve stored in volts needs both values (force = V × s × k), from the file
///   header or the options (options win); a curve stored in nN keeps its force and only records
///   the values.
/// - NT-MDT: the file has no metadata, both options are required (the sensitivity in [m/A], as
///   the deflection is exported in nA).
/// - afmformats `.tab` and `.h5`, Chiaro: the force is stored in N; an override rescales it by
///   k_new/k_file (resp. s_new/s_file) where the file states k (resp. s), otherwise only the
///   metadata take the value.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadOptions {
    /// Spring constant [N/m] (`--spring-constant`): overrides the file's value.
    pub spring_constant: Option<f64>,
    /// Deflection sensitivity [m/V] (`--sensitivity`): overrides the file's value.
    pub sensitivity: Option<f64>,
}

/// Read a force-distance file of any supported format (see the module documentation), the
/// format recognised from the content.
///
/// Errors are [`crate::Error::DataFile`], one line naming the file and what is wrong: not a
/// regular file, larger than the input limit ([`crate::input::limit`]), not a supported format, truncated or
/// inconsistent content, or a value the file lacks and [`ReadOptions`] does not give.
pub fn read_force_file(path: &Path, opts: &ReadOptions) -> crate::Result<ForceFile> {
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    parse_force_bytes(&bytes, path, opts)
}

/// Parse the bytes of a force-distance file; `path` words errors and breaks ties (its
/// extension) where the content fits more than one format.
pub fn parse_force_bytes(bytes: &[u8], path: &Path, opts: &ReadOptions) -> crate::Result<ForceFile> {
    for v in [opts.spring_constant, opts.sensitivity].into_iter().flatten() {
        if !(v.is_finite() && v > 0.0) {
            return Err(crate::Error::data_file(
                path,
                0,
                format!("--spring-constant and --sensitivity must be positive, got {v}"),
            ));
        }
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    let err = |msg: String| crate::Error::data_file(path, 0, msg);
    if bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06") {
        let mut zip = archive::Zip::open(bytes, path)?;
        if zip.has("header.properties") {
            return jpk::read(&mut zip, path, opts);
        }
        let first = zip.names().first().cloned();
        if let Some(first) = first {
            let lower = first.to_ascii_lowercase();
            if lower.ends_with(".csv") {
                return workshop::read_zip(&mut zip, path, opts);
            }
            if lower.ends_with(".txt") {
                return chiaro::read_zip(&mut zip, path, opts);
            }
        }
        return Err(err(
            "zip archive holds neither a JPK header.properties nor AFM Workshop .csv nor Chiaro .txt files"
                .into(),
        ));
    }
    if bytes.starts_with(b"\x89HDF\r\n\x1a\n") {
        return hdf5::read(bytes, path, opts);
    }
    if let Some(version) = igor::version(bytes) {
        return igor::read(bytes, version, path, opts);
    }
    if ext.starts_with("jpk") {
        return Err(err(format!("not a zip archive, as a .{ext} file is")));
    }
    if ext == "ibw" {
        return Err(err(
            "not an Igor binary wave (no version 1, 2, 3 or 5 header)".into()
        ));
    }
    if ext == "h5" || ext == "hdf5" {
        return Err(err("not an HDF5 file (no HDF5 signature)".into()));
    }
    // Text headers are searched for in the first bytes only (headers are short).
    let head = &bytes[..bytes.len().min(4096)];
    let long_head = &bytes[..bytes.len().min(1 << 16)];
    if text::contains(head, b"Force-Distance Curve") {
        return workshop::read_csv(bytes, path, opts);
    }
    if text::contains(long_head, b"Device:\tChiaro") {
        return chiaro::read_txt(bytes, path, opts);
    }
    if head.starts_with(b"#")
        && (text::contains(head, b"# afmformats") || text::contains(long_head, b"# BEGIN METADATA"))
    {
        return tab::read(bytes, path, opts);
    }
    if ntmdt::looks_like(head) {
        return ntmdt::read(bytes, path, opts);
    }
    if ext == "tab" {
        return tab::read(bytes, path, opts);
    }
    Err(err(
        "not a force-distance file that is read: JPK (zip), Asylum .ibw, NT-MDT .txt, AFM Workshop .csv, \
         afmformats .tab, Chiaro .txt"
            .into(),
    ))
}

/// The kind of a segment from its position among `count` segments, where the format only numbers
/// them (afmformats' convention: first approach, last retract, pauses between).
fn kind_by_position(i: usize, count: usize) -> Option<SegmentKind> {
    if i == 0 {
        Some(SegmentKind::Approach)
    } else if i + 1 == count {
        Some(SegmentKind::Retract)
    } else {
        Some(SegmentKind::Pause)
    }
}

/// Check that every present channel of every segment has as many samples as the force.
fn check_lengths(file: &ForceFile, path: &Path) -> crate::Result<()> {
    for c in &file.curves {
        for (i, s) in c.segments.iter().enumerate() {
            for (name, ch) in [
                ("height (measured)", &s.height_measured),
                ("height (piezo)", &s.height_piezo),
                ("time", &s.time),
                ("tip position", &s.tip_position),
            ] {
                if let Some(v) = ch
                    && v.len() != s.force.len()
                {
                    return Err(crate::Error::data_file(
                        path,
                        0,
                        format!(
                            "curve {} segment {i}: {name} has {} samples, force {}",
                            c.index,
                            v.len(),
                            s.force.len()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Rescale a force stored in N by the overrides of [`ReadOptions`] (k_new/k_file, s_new/s_file,
/// each where the file states the value), and return the spring constant and sensitivity the
/// curve's metadata record.
fn rescale_stored_force(
    segments: &mut [Segment],
    k_file: Option<f64>,
    s_file: Option<f64>,
    opts: &ReadOptions,
) -> (Option<f64>, Option<f64>) {
    let mut factor = 1.0;
    if let (Some(new), Some(old)) = (
        opts.spring_constant,
        k_file.filter(|v| *v != 0.0 && v.is_finite()),
    ) {
        factor *= new / old;
    }
    if let (Some(new), Some(old)) = (opts.sensitivity, s_file.filter(|v| *v != 0.0 && v.is_finite())) {
        factor *= new / old;
    }
    if factor != 1.0 {
        for s in segments {
            for f in &mut s.force {
                *f *= factor;
            }
        }
    }
    (opts.spring_constant.or(k_file), opts.sensitivity.or(s_file))
}

/// Segments of a curve whose samples carry afmformats' segment numbers (0 approach, 1 retract,
/// ...): the samples of each number in order, the numbers in increasing order. `None` when a
/// channel's length differs from the force's.
fn split_by_segment(seg: &[u8], force: &[f64], channels: [&Option<Vec<f64>>; 4]) -> Option<Vec<Segment>> {
    if seg.len() != force.len()
        || channels
            .iter()
            .any(|c| c.as_ref().is_some_and(|c| c.len() != force.len()))
    {
        return None;
    }
    let mut ids: Vec<u8> = seg.to_vec();
    ids.sort_unstable();
    ids.dedup();
    let pick = |c: &Option<Vec<f64>>, id: u8| {
        c.as_ref().map(|c| {
            c.iter()
                .zip(seg)
                .filter(|(_, s)| **s == id)
                .map(|(v, _)| *v)
                .collect()
        })
    };
    let [measured, piezo, time, tip] = channels;
    Some(
        ids.iter()
            .enumerate()
            .map(|(i, &id)| Segment {
                kind: kind_by_position(i, ids.len()),
                force: force
                    .iter()
                    .zip(seg)
                    .filter(|(_, s)| **s == id)
                    .map(|(v, _)| *v)
                    .collect(),
                height_measured: pick(measured, id),
                height_piezo: pick(piezo, id),
                time: pick(time, id),
                tip_position: pick(tip, id),
            })
            .collect(),
    )
}
