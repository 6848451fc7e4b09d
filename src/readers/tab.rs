//! afmformats' tab-separated export (`.tab`): `#` comment lines holding the metadata as JSON
//! between `# BEGIN METADATA` and `# END METADATA`, the last comment line before the data naming
//! the columns (`force`, `height (measured)`, `height (piezo)`, `segment`, `time`,
//! `tip position`, ...), then one tab-separated row per sample, all in SI units. Port of
//! afmformats' `fmt_tab` (MIT), including its quirks: unknown columns are skipped and a missing
//! trailing value reads as 0.

use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment};
use crate::{Error, Result};
use std::path::Path;

/// Read an afmformats `.tab` export.
pub(crate) fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let text = String::from_utf8_lossy(bytes);
    let lines = super::text::lines(&text);
    let err = |line: usize, msg: String| Error::data_file(path, line, msg);
    let mut dump = Vec::new();
    let mut inside = false;
    let mut end = None;
    for (i, l) in lines.iter().enumerate() {
        if l.starts_with("# BEGIN METADATA") {
            inside = true;
        } else if l.starts_with("# END METADATA") {
            end = Some(i);
            break;
        } else if inside {
            dump.push(l.trim_matches('#').trim());
        }
    }
    let meta_json: serde_json::Map<String, serde_json::Value> = if dump.is_empty() {
        serde_json::Map::new()
    } else {
        serde_json::from_str(&dump.join("\n")).map_err(|e| {
            err(
                end.unwrap_or(0),
                format!(
                    "metadata block is not a JSON object: {}",
                    super::archive::one_line(&e)
                ),
            )
        })?
    };
    let mut header = None;
    let mut first_data = None;
    for (i, l) in lines.iter().enumerate() {
        if l.trim().is_empty() {
            continue;
        }
        if l.starts_with('#') {
            header = Some(i);
        } else {
            first_data = Some(i);
            break;
        }
    }
    let (Some(h), Some(_)) = (header, first_data) else {
        return Err(err(0, "no column header line followed by data".into()));
    };
    let columns: Vec<&str> = lines[h].trim_matches('#').trim().split('\t').collect();
    #[derive(Clone, Copy, PartialEq)]
    enum Col {
        Force,
        Measured,
        Piezo,
        Segment,
        Time,
        Tip,
        Other,
    }
    let kinds: Vec<Col> = columns
        .iter()
        .map(|c| match *c {
            "force" => Col::Force,
            "height (measured)" => Col::Measured,
            "height (piezo)" => Col::Piezo,
            "segment" => Col::Segment,
            "time" => Col::Time,
            "tip position" => Col::Tip,
            _ => Col::Other,
        })
        .collect();
    if !kinds.contains(&Col::Force) {
        return Err(err(h + 1, "no force column".into()));
    }
    let has = |c: Col| kinds.contains(&c);
    let mut rows: Vec<([f64; 5], u8)> = Vec::new();
    for (i, l) in lines.iter().enumerate() {
        let t = l.trim();
        if t.is_empty() || l.starts_with('#') {
            continue;
        }
        let mut vals = [0.0; 5];
        let mut seg = 0u8;
        for (j, item) in t.split('\t').enumerate() {
            let Some(&kind) = kinds.get(j) else {
                return Err(err(
                    i + 1,
                    format!("more values than the {} columns", columns.len()),
                ));
            };
            let item = item.trim();
            let slot = match kind {
                Col::Force => 0,
                Col::Measured => 1,
                Col::Piezo => 2,
                Col::Time => 3,
                Col::Tip => 4,
                Col::Other => continue,
                Col::Segment => {
                    seg = match item {
                        "False" => 0,
                        "True" => 1,
                        s => s
                            .parse()
                            .map_err(|_| err(i + 1, format!("segment `{s}` is not 0..255")))?,
                    };
                    continue;
                }
            };
            let v = match item {
                "False" => 0.0,
                "True" => 1.0,
                s => super::text::float(s).ok_or_else(|| err(i + 1, format!("`{s}` is not a number")))?,
            };
            vals[slot] = v;
        }
        rows.push((vals, seg));
    }
    let mut ids: Vec<u8> = rows.iter().map(|r| r.1).collect();
    ids.sort_unstable();
    ids.dedup();
    let mut segments: Vec<Segment> = ids
        .iter()
        .enumerate()
        .map(|(i, _)| Segment {
            kind: super::kind_by_position(i, ids.len()),
            height_measured: has(Col::Measured).then(Vec::new),
            height_piezo: has(Col::Piezo).then(Vec::new),
            time: has(Col::Time).then(Vec::new),
            tip_position: has(Col::Tip).then(Vec::new),
            ..Segment::default()
        })
        .collect();
    for (v, s) in &rows {
        let Ok(i) = ids.binary_search(s) else { continue };
        let seg = &mut segments[i];
        seg.force.push(v[0]);
        for (ch, x) in [
            (&mut seg.height_measured, v[1]),
            (&mut seg.height_piezo, v[2]),
            (&mut seg.time, v[3]),
            (&mut seg.tip_position, v[4]),
        ] {
            if let Some(ch) = ch {
                ch.push(x);
            }
        }
    }
    let num = |k: &str| meta_json.get(k).and_then(serde_json::Value::as_f64);
    let string = |k: &str| meta_json.get(k).and_then(|v| v.as_str()).map(str::to_owned);
    let pair = |a: &str, b: &str| Some([num(a)?, num(b)?]);
    let (k, s) = super::rescale_stored_force(&mut segments, num("spring constant"), num("sensitivity"), opts);
    let meta = CurveMeta {
        spring_constant: k,
        sensitivity: s,
        position: pair("position x", "position y"),
        grid_index: pair("grid index x", "grid index y")
            .filter(|p| p.iter().all(|v| *v >= 0.0 && *v < 1e9))
            .map(|p| [p[0] as usize, p[1] as usize]),
        grid_shape: pair("grid shape x", "grid shape y")
            .filter(|p| p.iter().all(|v| *v >= 0.0 && *v < 1e9))
            .map(|p| [p[0] as usize, p[1] as usize]),
        grid_size: pair("grid size x", "grid size y"),
        setpoint: num("setpoint"),
        time_of_day: match (string("date"), string("time")) {
            (Some(d), Some(t)) => Some(format!("{d} {t}")),
            (d, t) => d.or(t),
        },
        instrument: string("instrument"),
    };
    Ok(ForceFile {
        format: "afmformats tab-separated export (.tab)".into(),
        curves: vec![ForceCurve {
            index: 0,
            segments,
            meta,
        }],
    })
}
