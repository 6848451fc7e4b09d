//! Optics11 Chiaro indenter text exports (`.txt`, ISO-8859-1): tab-separated metadata lines
//! (`k (N/m)`, `Max load (µN)`, `Date`, `Time`, `Device:`...), then the columns `Time (s)`,
//! `Load (uN)`, `Indentation (nm)`, `Cantilever (nm)`, `Piezo (nm)`, `Auxiliary`; and zips of
//! such exports. Port of afmformats' `fmt_chiaro_txt` (MIT): time, force = load × 1e-6,
//! height (measured) = −indentation × 1e-9 (afmformats' mapping: it is the indentation, not the
//! base's height), height (piezo) = −piezo × 1e-9, tip position = piezo height + cantilever ×
//! 1e-9; the approach ends at the largest force.

use super::archive::Zip;
use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment, SegmentKind};
use crate::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

/// Read one Chiaro text export.
pub(crate) fn read_txt(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let curve = parse(bytes, path, "", opts)?;
    Ok(ForceFile {
        format: "Optics11 Chiaro text export (.txt)".into(),
        curves: vec![curve],
    })
}

/// Read a zip of Chiaro text exports, one curve per entry in name order.
pub(crate) fn read_zip(zip: &mut Zip, path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let curves = super::archive::curves_of_entries(zip, path, opts, parse)?;
    Ok(ForceFile {
        format: "Optics11 Chiaro text exports (.zip of .txt)".into(),
        curves,
    })
}

fn parse(bytes: &[u8], path: &Path, entry: &str, opts: &ReadOptions) -> Result<ForceCurve> {
    let err = |line: usize, msg: String| Error::data_file(path, line, format!("{entry}{msg}"));
    let text = super::text::latin1(bytes);
    let lines = super::text::lines(&text);
    if !lines.iter().any(|l| l.contains("Device:\tChiaro")) {
        return Err(err(
            0,
            "no \"Device:<tab>Chiaro\" line: not a Chiaro export".into(),
        ));
    }
    let h = lines
        .iter()
        .rposition(|l| l.contains("Time (s)\tLoad"))
        .ok_or_else(|| err(0, "no column header line (Time (s)<tab>Load (uN)...)".into()))?;
    let ncol = lines[h].split('\t').count();
    if ncol < 5 {
        return Err(err(
            h + 1,
            format!("{ncol} columns, Chiaro exports have at least 5"),
        ));
    }
    let mut data: Vec<Vec<f64>> = Vec::new();
    for (i, l) in lines.iter().enumerate().skip(h + 1) {
        if l.trim().is_empty() {
            continue;
        }
        let r: Option<Vec<f64>> = l.split('\t').map(super::text::float).collect();
        match r {
            Some(r) if r.len() == ncol => data.push(r),
            _ => return Err(err(i + 1, format!("not a row of {ncol} tab-separated numbers"))),
        }
    }
    let mut notes: HashMap<String, String> = HashMap::new();
    for l in &lines[..h] {
        let parts: Vec<&str> = l.split('\t').collect();
        if parts.len().is_multiple_of(2) {
            for p in parts.chunks(2) {
                notes.insert(p[0].to_owned(), p[1].trim().to_owned());
            }
        } else if parts.len() == 1 && parts[0].matches(':').count() == 1 {
            let (k, v) = parts[0].split_once(':').unwrap_or_default();
            notes.insert(k.to_owned(), v.trim().to_owned());
        }
    }
    let note = |k: &str| notes.get(k).and_then(|v| super::text::float(v));
    let col = |j: usize, f: f64| data.iter().map(|r| r[j] * f).collect::<Vec<f64>>();
    let time = col(0, 1.0);
    let force = col(1, 1e-6);
    let measured: Vec<f64> = col(2, 1e-9).into_iter().map(|v| -v).collect();
    let piezo: Vec<f64> = col(4, 1e-9).into_iter().map(|v| -v).collect();
    let tip: Vec<f64> = piezo.iter().zip(col(3, 1e-9)).map(|(p, c)| p - (-c)).collect();
    // numpy.argmax: the first largest value (a NaN counts as largest).
    let mut imax = 0;
    for (i, &f) in force.iter().enumerate() {
        if f.is_nan() {
            imax = i;
            break;
        }
        if f > force[imax] {
            imax = i;
        }
    }
    let cut = if force.is_empty() { 0 } else { imax + 1 };
    let seg = |kind, a: usize, b: usize| Segment {
        kind: Some(kind),
        force: force[a..b].to_vec(),
        height_measured: Some(measured[a..b].to_vec()),
        height_piezo: Some(piezo[a..b].to_vec()),
        time: Some(time[a..b].to_vec()),
        tip_position: Some(tip[a..b].to_vec()),
    };
    let n = force.len();
    let mut segments = vec![
        seg(SegmentKind::Approach, 0, cut),
        seg(SegmentKind::Retract, cut, n),
    ];
    let (k, s) = super::rescale_stored_force(&mut segments, note("k (N/m)"), None, opts);
    let meta = CurveMeta {
        spring_constant: k,
        sensitivity: s,
        setpoint: note("Max load (\u{b5}N)").map(|v| v * 1e-6),
        time_of_day: match (notes.get("Date"), notes.get("Time")) {
            (Some(d), Some(t)) => Some(format!("{d} {t}")),
            _ => None,
        },
        instrument: notes.get("Device:").cloned(),
        ..CurveMeta::default()
    };
    Ok(ForceCurve {
        index: 0,
        segments,
        meta,
    })
}
