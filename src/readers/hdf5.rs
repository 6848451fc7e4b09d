//! afmformats' HDF5 export (`.h5`): one group per curve (`0`, `1`, ...), its attributes the
//! metadata (`spring constant`, `sensitivity`, `position x`, ...), its datasets the columns
//! (`force`, `height (measured)`, `height (piezo)`, `segment`, `time`, `tip position`), in SI
//! units. Port of afmformats' `fmt_hdf5` (MIT), read with the pure-Rust `hdf5-reader`.

use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions};
use crate::{Error, Result};
use std::path::Path;

/// Read an afmformats HDF5 export. A panic inside the HDF5 decoder (a third-party crate) on a
/// malformed file is turned into an error.
pub(crate) fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| read_unguarded(bytes, path, opts)))
        .unwrap_or_else(|_| {
            Err(Error::data_file(
                path,
                0,
                "HDF5: the decoder failed on malformed content",
            ))
        })
}

fn read_unguarded(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let err = |msg: String| Error::data_file(path, 0, msg);
    let h5 = |e: &dyn std::fmt::Display| err(format!("HDF5: {}", super::archive::one_line(e)));
    // Decompressed data are bounded like a zip's entries.
    let budget = (bytes.len() as u64).saturating_mul(64).clamp(16 << 20, 4 << 30);
    let options = hdf5_reader::OpenOptions::default().with_max_read_bytes(budget as usize);
    let file = hdf5_reader::Hdf5File::from_bytes_with_options(bytes, options).map_err(|e| h5(&e))?;
    let root = file.root_group().map_err(|e| h5(&e))?;
    let (mut groups, _) = root.member_names().map_err(|e| h5(&e))?;
    groups.retain(|g| !g.is_empty() && g.bytes().all(|b| b.is_ascii_digit()) && g.len() < 19);
    groups.sort_by_key(|g| g.parse::<u64>().unwrap_or(u64::MAX));
    if groups.is_empty() {
        return Err(err(
            "HDF5 file without curve groups (0, 1, ...): not an afmformats export".into(),
        ));
    }
    let mut curves = Vec::with_capacity(groups.len());
    let mut used = 0u64;
    for name in &groups {
        let g = root.group(name).map_err(|e| h5(&e))?;
        let (_, sets) = g.member_names().map_err(|e| h5(&e))?;
        let mut column = |c: &str| -> Result<Option<Vec<f64>>> {
            if !sets.iter().any(|s| s == c) {
                return Ok(None);
            }
            let ds = g.dataset(c).map_err(|e| h5(&e))?;
            let n = ds.num_elements().map_err(|e| h5(&e))?;
            used = used.saturating_add(n.saturating_mul(8));
            if used > budget {
                return Err(err(format!(
                    "curve {name}: {c} claims {n} values, past the read budget of {budget} bytes"
                )));
            }
            // The stored number type: afmformats writes f64 columns and a u8 `segment`.
            let v: Vec<f64> = match ds.read_array::<f64>() {
                Ok(a) => a.iter().copied().collect(),
                Err(e) => {
                    if let Ok(a) = ds.read_array::<f32>() {
                        a.iter().map(|&x| f64::from(x)).collect()
                    } else if let Ok(a) = ds.read_array::<u8>() {
                        a.iter().map(|&x| f64::from(x)).collect()
                    } else if let Ok(a) = ds.read_array::<i64>() {
                        a.iter().map(|&x| x as f64).collect()
                    } else if let Ok(a) = ds.read_array::<i32>() {
                        a.iter().map(|&x| f64::from(x)).collect()
                    } else {
                        return Err(h5(&e));
                    }
                }
            };
            Ok(Some(v))
        };
        let what = |c: &str| format!("curve {name}: no {c} dataset");
        let force = column("force")?.ok_or_else(|| err(what("force")))?;
        let measured = column("height (measured)")?;
        let piezo = column("height (piezo)")?;
        let time = column("time")?;
        let tip = column("tip position")?;
        let seg = column("segment")?;
        let seg: Vec<u8> = match seg {
            Some(s) => s
                .iter()
                .map(|v| {
                    if (0.0..=255.0).contains(v) {
                        *v as u8
                    } else {
                        u8::MAX
                    }
                })
                .collect(),
            None => vec![0; force.len()],
        };
        let mut segments = super::split_by_segment(&seg, &force, [&measured, &piezo, &time, &tip])
            .ok_or_else(|| err(format!("curve {name}: columns of different lengths")))?;
        let attrs = g.attributes().map_err(|e| h5(&e))?;
        let num = |k: &str| {
            attrs
                .iter()
                .find(|a| a.name == k)
                .and_then(|a| a.read_as_f64().ok())
        };
        let text = |k: &str| {
            attrs
                .iter()
                .find(|a| a.name == k)
                .and_then(|a| a.read_string().ok())
        };
        let pair = |a: &str, b: &str| Some([num(a)?, num(b)?]);
        let index_pair = |a: &str, b: &str| {
            pair(a, b)
                .filter(|p| p.iter().all(|v| *v >= 0.0 && *v < 1e9))
                .map(|p| [p[0] as usize, p[1] as usize])
        };
        let (k, s) =
            super::rescale_stored_force(&mut segments, num("spring constant"), num("sensitivity"), opts);
        let meta = CurveMeta {
            spring_constant: k,
            sensitivity: s,
            position: pair("position x", "position y"),
            grid_index: index_pair("grid index x", "grid index y"),
            grid_shape: index_pair("grid shape x", "grid shape y"),
            grid_size: pair("grid size x", "grid size y"),
            setpoint: num("setpoint"),
            time_of_day: match (text("date"), text("time")) {
                (Some(d), Some(t)) => Some(format!("{d} {t}")),
                (d, t) => d.or(t),
            },
            instrument: text("instrument"),
        };
        let index = name.parse().unwrap_or(curves.len());
        curves.push(ForceCurve {
            index,
            segments,
            meta,
        });
    }
    Ok(ForceFile {
        format: "afmformats HDF5 export (.h5)".into(),
        curves,
    })
}
