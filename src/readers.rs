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

use serde::Serialize;

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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadOptions {
    /// Spring constant [N/m] (`--spring-constant`): overrides the file's value.
    pub spring_constant: Option<f64>,
    /// Deflection sensitivity [m/V] (`--sensitivity`): overrides the file's value.
    pub sensitivity: Option<f64>,
}

/// Read a force-distance file, its format found from its content.
///
/// # Errors
/// [`crate::Error::DataFile`] naming the file and what is wrong.
pub fn read_force_file(path: &std::path::Path, _opts: &ReadOptions) -> crate::Result<ForceFile> {
    Err(crate::Error::data_file(
        path,
        0,
        "not a force-curve format this workbench reads",
    ))
}
