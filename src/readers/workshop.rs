//! AFM Workshop force curves (`.csv`: a `Force-Distance Curve` header of `Key:<tab>value` lines,
//! then comma-separated columns `Extend Z-Sense(nm)`, `Extend T-B(V)` or `Extend Force(nN)`,
//! `Retract Z-Sense(nm)`, `Retract T-B(V)` or `Retract Force(nN)`), and force maps as a zip of
//! such files, one per point. Port of afmformats' `fmt_workshop` (MIT): height = −Z-Sense,
//! force = T-B × sensitivity × spring constant (from the header's `Light Lever Gain, mV/nm` and
//! `Force Constant, nN/nm` where they are not the default 1, or from the options) or the stored
//! force; the map's grid from the distinct X and Y positions.

use super::archive::Zip;
use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment, SegmentKind};
use crate::{Error, Result};
use std::path::Path;

/// Read a single AFM Workshop CSV.
pub(crate) fn read_csv(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let curve = parse(bytes, path, "", opts)?;
    Ok(ForceFile {
        format: "AFM Workshop force curve (.csv)".into(),
        curves: vec![curve],
    })
}

/// Read a zip of AFM Workshop CSVs (a force map), one curve per entry in name order.
pub(crate) fn read_zip(zip: &mut Zip, path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let mut curves = super::archive::curves_of_entries(zip, path, opts, parse)?;
    // The grid from the distinct positions (afmformats' `load_map`): shape = number of distinct
    // values, centre = their mean, size = their range × (1 + 1/(n − 1)) (pixel borders included).
    let mut axes = Vec::new();
    for axis in 0..2 {
        let mut vals: Vec<f64> = curves
            .iter()
            .filter_map(|c| c.meta.position.map(|p| p[axis]))
            .collect();
        if vals.is_empty() || vals.len() != curves.len() {
            break;
        }
        vals.sort_by(f64::total_cmp);
        vals.dedup();
        let n = vals.len();
        let center = vals.iter().sum::<f64>() / n as f64;
        let size = (n > 1).then(|| (vals[n - 1] - vals[0]) * (1.0 + 1.0 / (n as f64 - 1.0)));
        axes.push((n, center, size));
    }
    if let [(nx, cx, sx), (ny, cy, sy)] = axes[..] {
        for c in &mut curves {
            c.meta.grid_shape = Some([nx, ny]);
            if let (Some(sx), Some(sy), Some(p)) = (sx, sy, c.meta.position) {
                c.meta.grid_size = Some([sx, sy]);
                c.meta.grid_index = super::jpk::position_to_index(p[0], sx, cx, nx)
                    .zip(super::jpk::position_to_index(p[1], sy, cy, ny))
                    .map(|(i, j)| [i, j]);
            }
        }
    }
    Ok(ForceFile {
        format: "AFM Workshop force map (.zip of .csv)".into(),
        curves,
    })
}

fn parse(bytes: &[u8], path: &Path, entry: &str, opts: &ReadOptions) -> Result<ForceCurve> {
    let text = String::from_utf8_lossy(bytes);
    let lines = super::text::lines(&text);
    let err = |line: usize, msg: String| Error::data_file(path, line, format!("{entry}{msg}"));
    let mut fd = false;
    let mut meta = CurveMeta {
        instrument: Some("AFM Workshop".into()),
        ..CurveMeta::default()
    };
    let (mut x, mut y) = (None, None);
    let (mut date, mut time) = (None, None);
    let mut k_file = None;
    let mut s_file = None;
    let mut header = None;
    let value = |l: &str| {
        l.split_once(':')
            .map(|(_, v)| v.trim().to_owned())
            .unwrap_or_default()
    };
    for (i, l) in lines.iter().enumerate() {
        if l.contains("Force-Distance Curve") {
            fd = true;
        } else if l.starts_with("Date:") {
            date = Some(value(l));
        } else if l.starts_with("Time:") {
            time = Some(value(l));
        } else if l.starts_with("X, um:") {
            x = super::text::float(&value(l)).map(|v| v * 1e-6);
        } else if l.starts_with("Y, um:") {
            y = super::text::float(&value(l)).map(|v| v * 1e-6);
        } else if l.starts_with("Light Lever Gain, mV/nm:") {
            let v = super::text::float(&value(l))
                .ok_or_else(|| err(i + 1, "light lever gain is not a number".into()))?;
            if v != 1.0 {
                s_file = Some(1.0 / (v * 1e-3 / 1e-9));
            }
        } else if l.starts_with("Force Constant, nN/nm:") {
            let v = super::text::float(&value(l))
                .ok_or_else(|| err(i + 1, "force constant is not a number".into()))?;
            if v != 1.0 {
                k_file = Some(v);
            }
        } else if l.matches(',').count() >= 3 {
            header = Some(i);
            break;
        }
    }
    let Some(h) = header else {
        return Err(err(0, "no column header line (Extend Z-Sense(nm),...)".into()));
    };
    if !fd {
        return Err(err(
            1,
            "no \"Force-Distance Curve\" line: not an AFM Workshop force curve".into(),
        ));
    }
    let columns: Vec<&str> = lines[h].trim().split(',').collect();
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for (i, l) in lines.iter().enumerate().skip(h + 1) {
        if l.trim().is_empty() {
            continue;
        }
        let row: Option<Vec<f64>> = l.split(',').map(super::text::float).collect();
        match row {
            Some(r) if r.len() == columns.len() => rows.push(r),
            Some(r) => {
                return Err(err(
                    i + 1,
                    format!("{} values, the header has {} columns", r.len(), columns.len()),
                ));
            }
            None => return Err(err(i + 1, "not a row of comma-separated numbers".into())),
        }
    }
    let k = opts.spring_constant.or(k_file);
    let s = opts.sensitivity.or(s_file);
    let mut force: [Option<Vec<f64>>; 2] = [None, None];
    let mut height: [Option<Vec<f64>>; 2] = [None, None];
    for (j, c) in columns.iter().enumerate() {
        let col = || rows.iter().map(|r| r[j]);
        let seg = if c.starts_with("Extend") { 0 } else { 1 };
        match *c {
            "Extend Z-Sense(nm)" | "Retract Z-Sense(nm)" => {
                height[seg] = Some(col().map(|v| -v * 1e-9).collect())
            }
            "Extend Force(nN)" | "Retract Force(nN)" => force[seg] = Some(col().map(|v| v * 1e-9).collect()),
            "Extend T-B(V)" | "Retract T-B(V)" => {
                let (k, s) = match (k, s) {
                    (Some(k), Some(s)) => (k, s),
                    (None, None) => {
                        return Err(err(
                            0,
                            "the deflection is in volts and the file states neither spring constant nor \
                             sensitivity: give --spring-constant N/m and --sensitivity m/V"
                                .into(),
                        ));
                    }
                    (None, _) => {
                        return Err(err(
                            0,
                            "the deflection is in volts and the file states no spring constant: give \
                             --spring-constant N/m"
                                .into(),
                        ));
                    }
                    (_, None) => {
                        return Err(err(
                            0,
                            "the deflection is in volts and the file states no sensitivity: give --sensitivity m/V"
                                .into(),
                        ));
                    }
                };
                let fmult = s * k;
                force[seg] = Some(col().map(|v| v * fmult).collect());
            }
            _ => {}
        }
    }
    let [Some(f0), Some(f1)] = force else {
        return Err(err(
            h + 1,
            "no Extend and Retract force columns (T-B(V) or Force(nN))".into(),
        ));
    };
    let [h0, h1] = height;
    let (h0, h1) = match (h0, h1) {
        (Some(a), Some(b)) => (Some(a), Some(b)),
        _ => (None, None),
    };
    meta.spring_constant = k;
    meta.sensitivity = s;
    meta.position = x.zip(y).map(|(x, y)| [x, y]);
    meta.time_of_day = match (date, time) {
        (Some(d), Some(t)) => Some(format!("{d} {t}")),
        (d, t) => d.or(t),
    };
    let seg = |kind, force, height_measured| Segment {
        kind: Some(kind),
        force,
        height_measured,
        height_piezo: None,
        time: None,
        tip_position: None,
    };
    Ok(ForceCurve {
        index: 0,
        segments: vec![
            seg(SegmentKind::Approach, f0, h0),
            seg(SegmentKind::Retract, f1, h1),
        ],
        meta,
    })
}
