//! NT-MDT Nova text exports (`.txt`): three white-space separated columns with decimal commas,
//! height [nm], deflection of the approach [nA], deflection of the retraction [nA], no metadata.
//! Port of afmformats' `fmt_ntmdt_txt` (MIT): the constant padding that the export puts at the
//! start of each deflection column is cropped, the approach is reversed into acquisition order,
//! height (measured) = height × 1e-9, force = deflection × sensitivity [m/A] × spring constant ×
//! 1e-9, both values from the options.

use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment, SegmentKind};
use crate::{Error, Result};
use std::path::Path;

/// One row of numbers with decimal commas, if `line` is one.
fn row(line: &str) -> Option<Vec<f64>> {
    line.split_whitespace()
        .map(|t| super::text::float(&t.replace(',', ".")))
        .collect()
}

/// True when the first non-empty line is three numbers (decimal commas allowed).
pub(crate) fn looks_like(head: &[u8]) -> bool {
    let text = String::from_utf8_lossy(head);
    super::text::lines(&text)
        .into_iter()
        .find(|l| !l.trim().is_empty())
        .and_then(row)
        .is_some_and(|r| r.len() == 3)
}

/// The first index to keep: one before the first value that differs from the first (afmformats'
/// `crop_beginning`); `None` when the column is constant.
fn crop(col: &[f64]) -> Option<usize> {
    let first = *col.first()?;
    col.iter().position(|&v| v != first).map(|i| i - 1)
}

/// Read an NT-MDT text export.
pub(crate) fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let text = String::from_utf8_lossy(bytes);
    let mut data = Vec::new();
    for (i, l) in super::text::lines(&text).into_iter().enumerate() {
        let l = l.split('#').next().unwrap_or("");
        if l.trim().is_empty() {
            continue;
        }
        match row(l) {
            Some(r) if r.len() == 3 => data.push([r[0], r[1], r[2]]),
            Some(r) => {
                return Err(Error::data_file(
                    path,
                    i + 1,
                    format!("{} columns, NT-MDT exports have 3", r.len()),
                ));
            }
            None => return Err(Error::data_file(path, i + 1, "not a row of three numbers")),
        }
    }
    let (k, s) = match (opts.spring_constant, opts.sensitivity) {
        (Some(k), Some(s)) => (k, s),
        (None, None) => {
            return Err(Error::data_file(
                path,
                0,
                "NT-MDT exports state neither spring constant nor sensitivity: give --spring-constant N/m and \
                 --sensitivity m/A",
            ));
        }
        (None, _) => {
            return Err(Error::data_file(
                path,
                0,
                "NT-MDT exports state no spring constant: give --spring-constant N/m",
            ));
        }
        (_, None) => {
            return Err(Error::data_file(
                path,
                0,
                "NT-MDT exports state no sensitivity: give --sensitivity m/A (deflection is in nA)",
            ));
        }
    };
    let height: Vec<f64> = data.iter().map(|r| r[0]).collect();
    let appr: Vec<f64> = data.iter().map(|r| r[1]).collect();
    let retr: Vec<f64> = data.iter().map(|r| r[2]).collect();
    let constant = |what| Error::data_file(path, 0, format!("the {what} deflection column is constant"));
    let a0 = crop(&appr).ok_or_else(|| constant("approach"))?;
    let r0 = crop(&retr).ok_or_else(|| constant("retract"))?;
    let fmult = s * k;
    let seg = |kind, h: Vec<f64>, f: Vec<f64>| Segment {
        kind: Some(kind),
        force: f.into_iter().map(|v| v * fmult * 1e-9).collect(),
        height_measured: Some(h.into_iter().map(|v| v * 1e-9).collect()),
        height_piezo: None,
        time: None,
        tip_position: None,
    };
    let approach = seg(
        SegmentKind::Approach,
        height[a0..].iter().rev().copied().collect(),
        appr[a0..].iter().rev().copied().collect(),
    );
    let retract = seg(SegmentKind::Retract, height[r0..].to_vec(), retr[r0..].to_vec());
    let meta = CurveMeta {
        spring_constant: Some(k),
        sensitivity: Some(s),
        ..CurveMeta::default()
    };
    Ok(ForceFile {
        format: "NT-MDT Nova text export (.txt)".into(),
        curves: vec![ForceCurve {
            index: 0,
            segments: vec![approach, retract],
            meta,
        }],
    })
}
