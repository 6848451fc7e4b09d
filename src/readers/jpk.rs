//! JPK force files (`.jpk-force`), force maps (`.jpk-force-map`) and QI data (`.jpk-qi-data`,
//! `.jpk-qi-series`): zip archives of Java properties headers and big-endian binary channels.
//!
//! Layout: `header.properties` (the file), `shared-data/header.properties` (channel descriptions
//! shared by the curves of a map, referred to by `lcd-info.*` and `force-segment-header-info.*`
//! keys), and per curve (`index/N/` in maps, the archive root in single files) a
//! `header.properties` and per segment `segments/S/segment-header.properties` with
//! `segments/S/channels/NAME.dat`. A channel's raw numbers are decoded with its encoder
//! (`signedshort`, `signedinteger`, ... or raw `float`/`double`) and converted to SI through its
//! conversion chain (`conversion-set.conversion.SLOT.base-calibration-slot`, linear
//! multiplier/offset per slot). Port of afmformats' `fmt_jpk` (MIT): the same channels
//! (`vDeflection` in the `force` slot; `strainGaugeHeight`, `capacitiveSensorHeight` or
//! `measuredHeight` in the `nominal` slot; `height` or `head-height` in the `calibrated` slot),
//! the same property substitution and the same metadata keys.

use super::archive::Zip;
use super::{CurveMeta, ForceCurve, ForceFile, ReadOptions, Segment, SegmentKind};
use crate::{Error, Result};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

type Props = HashMap<String, String>;

/// Channels read per column: candidate channel names, calibration slot, unit.
const FORCE: (&[&str], &str, &str) = (&["vDeflection"], "force", "N");
const MEASURED: (&[&str], &str, &str) = (
    &["strainGaugeHeight", "capacitiveSensorHeight", "measuredHeight"],
    "nominal",
    "m",
);
const PIEZO: (&[&str], &str, &str) = (&["height", "head-height"], "calibrated", "m");

const SENSITIVITY_KEY: &str = "channel.vDeflection.conversion-set.conversion.distance.scaling.multiplier";
const SPRING_KEY: &str = "channel.vDeflection.conversion-set.conversion.force.scaling.multiplier";
const HEADS: [&str; 4] = [
    "force-scan-map",
    "force-scan-series",
    "quantitative-imaging-map",
    "quantitative-imaging-series",
];

/// A property as a number, as afmformats reads it (NaN counts as absent).
fn num(p: &Props, key: &str) -> Option<f64> {
    p.get(key)
        .and_then(|v| super::text::float(v))
        .filter(|v| !v.is_nan())
}

/// A property as text (a NaN-valued one counts as absent).
fn text<'a>(p: &'a Props, key: &str) -> Option<&'a str> {
    p.get(key)
        .map(String::as_str)
        .filter(|v| !super::text::float(v).is_some_and(f64::is_nan))
}

/// The first of the map/series/QI variants of `<head>.<rest>` that is a number.
fn num_any(p: &Props, rest: &str) -> Option<f64> {
    HEADS.iter().find_map(|h| num(p, &format!("{h}.{rest}")))
}

/// Where the curves and segments are in the archive.
struct Layout {
    /// Curve number (the `N` of `index/N/`, 0 for a single curve) → its folder prefix and the
    /// entries of each segment, in segment order.
    curves: BTreeMap<u64, (String, Vec<Vec<String>>)>,
}

fn layout(names: &[String]) -> Layout {
    let single = names.iter().any(|n| n.starts_with("segments/"));
    let mut found: BTreeMap<u64, (String, BTreeMap<u64, Vec<String>>)> = BTreeMap::new();
    for n in names {
        let (index, prefix, rest) = if single {
            match n.strip_prefix("segments/") {
                Some(rest) => (0, String::new(), rest),
                None => continue,
            }
        } else {
            let Some(after) = n.strip_prefix("index/") else {
                continue;
            };
            let Some((num, rest)) = after.split_once('/') else {
                continue;
            };
            let Ok(index) = num.parse::<u64>() else { continue };
            if !num.bytes().all(|b| b.is_ascii_digit()) {
                continue;
            }
            let prefix = format!("index/{num}/");
            found
                .entry(index)
                .or_insert_with(|| (prefix.clone(), BTreeMap::new()));
            match rest.strip_prefix("segments/") {
                Some(rest) => (index, prefix, rest),
                None => continue,
            }
        };
        let Some((seg, _)) = rest.split_once('/') else {
            continue;
        };
        if seg.is_empty() || !seg.bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        let Ok(seg) = seg.parse::<u64>() else { continue };
        let entry = found.entry(index).or_insert_with(|| (prefix, BTreeMap::new()));
        entry.1.entry(seg).or_default().push(n.clone());
    }
    let curves = found
        .into_iter()
        .map(|(i, (prefix, segs))| {
            // Segments count from 0 without gaps, as afmformats walks them.
            let mut list = Vec::new();
            for (k, (s, files)) in segs.into_iter().enumerate() {
                if s != k as u64 {
                    break;
                }
                list.push(files);
            }
            (i, (prefix, list))
        })
        .collect();
    Layout { curves }
}

/// Shared-header keys grouped by their first two components (`lcd-info.3`), each with the rest
/// of its key.
type Shared = HashMap<(String, String), Vec<(String, String)>>;

fn group_shared(shared: Props) -> Shared {
    let mut out: Shared = HashMap::new();
    for (k, v) in shared {
        let mut it = k.splitn(3, '.');
        if let (Some(a), Some(b), Some(rest)) = (it.next(), it.next(), it.next()) {
            out.entry((a.to_owned(), b.to_owned()))
                .or_default()
                .push((rest.to_owned(), v));
        }
    }
    out
}

/// The properties of one segment: curve header, segment header, `*` references replaced by the
/// shared header's entries, the file header on top, and the user's spring constant and
/// sensitivity written into the deflection's conversions (afmformats'
/// `_get_index_segment_properties`).
fn segment_props(
    curve: &Props,
    segment: Props,
    shared: &Shared,
    general: &Props,
    opts: &ReadOptions,
) -> Props {
    let mut p = curve.clone();
    p.extend(segment);
    let mut refs: Vec<String> = p.keys().filter(|k| k.contains(".*")).cloned().collect();
    refs.sort();
    for key in refs {
        let Some(pindex) = p.get(&key).cloned() else {
            continue;
        };
        let parts: Vec<&str> = key.split('.').collect();
        let mediator = if parts.len() >= 2 {
            parts[parts.len() - 2]
        } else {
            ""
        };
        let head = if parts.len() >= 3 {
            parts[..parts.len() - 2].join(".")
        } else {
            parts[0].to_owned()
        };
        if let Some(list) = shared.get(&(mediator.to_owned(), pindex)) {
            for (var, val) in list {
                p.insert(format!("{head}.{var}"), val.clone());
            }
        }
    }
    for (k, v) in general {
        p.insert(k.clone(), v.clone());
    }
    for (value, key, base, unit) in [
        (opts.spring_constant, SPRING_KEY, "distance", "N"),
        (opts.sensitivity, SENSITIVITY_KEY, "volts", "m"),
    ] {
        if let Some(v) = value {
            let scaling = key.trim_end_matches(".multiplier");
            let conversion = scaling.trim_end_matches(".scaling");
            p.insert(key.to_owned(), format!("{v:?}"));
            p.insert(format!("{scaling}.offset"), "0".into());
            p.insert(format!("{scaling}.unit"), unit.into());
            p.insert(format!("{conversion}.base-calibration-slot"), base.into());
        }
    }
    p
}

/// Read a JPK archive.
pub(crate) fn read(zip: &mut Zip, path: &Path, opts: &ReadOptions) -> Result<ForceFile> {
    let err = |msg: String| Error::data_file(path, 0, msg);
    let general = super::properties::parse_map(&zip.read("header.properties")?);
    let shared = if zip.has("shared-data/header.properties") {
        super::properties::parse_map(&zip.read("shared-data/header.properties")?)
    } else {
        Props::new()
    };
    let shared = group_shared(shared);
    let names = zip.names().to_vec();
    let layout = layout(&names);
    let kind = general.get("type").map(String::as_str).unwrap_or("");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let format = match kind {
        "force-scan-map" => "JPK force map (.jpk-force-map)",
        "quantitative-imaging-map" => "JPK QI map (.jpk-qi-data)",
        "quantitative-imaging-series" => "JPK QI series (.jpk-qi-series)",
        "force-scan-series" => "JPK force curve (.jpk-force)",
        _ => match ext {
            "jpk-force-map" => "JPK force map (.jpk-force-map)",
            "jpk-qi-data" => "JPK QI map (.jpk-qi-data)",
            "jpk-qi-series" => "JPK QI series (.jpk-qi-series)",
            _ => "JPK force curve (.jpk-force)",
        },
    };
    if layout.curves.is_empty() {
        return Err(err(
            "JPK archive without segments/ or index/N/segments/ entries".into()
        ));
    }
    let mut curves = Vec::with_capacity(layout.curves.len());
    for (&index, (prefix, segments)) in &layout.curves {
        let curve_header = if prefix.is_empty() {
            general.clone()
        } else {
            let name = format!("{prefix}header.properties");
            if !zip.has(&name) {
                return Err(err(format!("curve {index}: no {name}")));
            }
            super::properties::parse_map(&zip.read(&name)?)
        };
        if segments.is_empty() {
            return Err(err(format!("curve {index}: no segments/0/")));
        }
        let mut props = Vec::with_capacity(segments.len());
        for (s, _) in segments.iter().enumerate() {
            let name = format!("{prefix}segments/{s}/segment-header.properties");
            if !zip.has(&name) {
                return Err(err(format!("curve {index}: no {name}")));
            }
            let seg = super::properties::parse_map(&zip.read(&name)?);
            props.push(segment_props(&curve_header, seg, &shared, &general, opts));
        }
        let first = &props[0];
        let k = num(first, SPRING_KEY);
        let sens = num(first, SENSITIVITY_KEY);
        match (k, sens) {
            (None, None) => {
                return Err(err(
                    "the file states neither spring constant nor sensitivity: give --spring-constant N/m \
                     and --sensitivity m/V"
                        .into(),
                ));
            }
            (None, _) => {
                return Err(err(
                    "the file states no spring constant: give --spring-constant N/m".into(),
                ));
            }
            (_, None) => {
                return Err(err(
                    "the file states no sensitivity: give --sensitivity m/V".into()
                ));
            }
            _ => {}
        }
        let durations: Vec<Option<f64>> = props
            .iter()
            .map(|p| num(p, "force-segment-header.duration"))
            .collect();
        let mut out_segments = Vec::with_capacity(segments.len());
        let mut start = 0.0;
        for (s, (files, p)) in segments.iter().zip(&props).enumerate() {
            let what = format!("curve {index} segment {s}");
            let force = channel(zip, files, p, FORCE, &what, path)?
                .ok_or_else(|| err(format!("{what}: no vDeflection channel")))?;
            let height_measured = channel(zip, files, p, MEASURED, &what, path)?;
            let height_piezo = channel(zip, files, p, PIEZO, &what, path)?;
            if let Some(n) = num(p, "force-segment-header.num-points")
                && n != force.len() as f64
            {
                return Err(err(format!(
                    "{what}: the header says {n} points, the vDeflection channel has {}",
                    force.len()
                )));
            }
            let time = if durations.iter().all(Option::is_some) {
                let d = durations[s].unwrap_or(0.0);
                // numpy.linspace(start, start + d, n, endpoint=False)
                let step = ((start + d) - start) / force.len().max(1) as f64;
                let t = (0..force.len()).map(|i| i as f64 * step + start).collect();
                start += d;
                Some(t)
            } else {
                None
            };
            let style = text(p, "force-segment-header.settings.style")
                .or_else(|| text(p, "force-segment-header.settings.segment-settings.style"));
            let kind = match style {
                Some("extend") => Some(SegmentKind::Approach),
                Some("retract") => Some(SegmentKind::Retract),
                Some("pause") => Some(SegmentKind::Pause),
                _ => None,
            };
            out_segments.push(Segment {
                kind,
                force,
                height_measured,
                height_piezo,
                time,
                tip_position: None,
            });
        }
        let meta = metadata(&props, &out_segments);
        curves.push(ForceCurve {
            index: index as usize,
            segments: out_segments,
            meta,
        });
    }
    let file = ForceFile {
        format: format.into(),
        curves,
    };
    super::check_lengths(&file, path)?;
    Ok(file)
}

/// Metadata of a curve from its segments' properties (afmformats' primary and secondary keys).
fn metadata(props: &[Props], segments: &[Segment]) -> CurveMeta {
    let first = &props[0];
    let k = num(first, SPRING_KEY);
    let sens = num(first, SENSITIVITY_KEY);
    let axis = |a: &str, b: &str| Some([num_any(first, a)?, num_any(first, b)?]);
    let position = axis("header.position.x", "header.position.y");
    let center = axis("position-pattern.grid.xcenter", "position-pattern.grid.ycenter");
    let shape = axis("position-pattern.grid.ilength", "position-pattern.grid.jlength")
        .filter(|s| s.iter().all(|v| v.is_finite() && *v >= 1.0 && *v < 1e9))
        .map(|s| [s[0].round() as usize, s[1].round() as usize]);
    let size = axis("position-pattern.grid.ulength", "position-pattern.grid.vlength");
    let grid_index = match (position, center, shape, size) {
        (Some(p), Some(c), Some(n), Some(l)) => position_to_index(p[0], l[0], c[0], n[0])
            .zip(position_to_index(p[1], l[1], c[1], n[1]))
            .map(|(x, y)| [x, y]),
        _ => None,
    };
    let setpoint = props
        .iter()
        .find_map(|p| num(p, "force-segment-header.settings.segment-settings.setpoint"))
        .and_then(|v| Some(v * k? * sens?));
    let approach = segments
        .iter()
        .position(|s| s.kind == Some(SegmentKind::Approach))
        .unwrap_or(0);
    let time_of_day = text(&props[approach], "force-segment-header.time-stamp").map(str::to_owned);
    let instrument = HEADS
        .iter()
        .find_map(|h| text(first, &format!("{h}.description.instrument")))
        .map(str::to_owned);
    CurveMeta {
        spring_constant: k,
        sensitivity: sens,
        position,
        grid_index,
        grid_shape: shape,
        grid_size: size,
        setpoint,
        time_of_day,
        instrument,
    }
}

/// The grid column of a position (afmformats' `_convert_position_to_index`): the nearest of the
/// pixel centres of `n` pixels spanning `size` around `center`.
pub(crate) fn position_to_index(pos: f64, size: f64, center: f64, n: usize) -> Option<usize> {
    if n == 0 || !(pos.is_finite() && size.is_finite() && center.is_finite()) {
        return None;
    }
    let s1 = center - size / 2.0;
    let s2 = center + size / 2.0;
    let dx = (s2 - s1) / n as f64;
    let mut best = None;
    let mut best_d = f64::INFINITY;
    for i in 0..n {
        let x = i as f64 * dx + s1 + dx / 2.0;
        let d = (x - pos).abs();
        if d < best_d {
            best_d = d;
            best = Some(i);
        }
    }
    best
}

/// Read one column's channel of a segment: the first entry (in archive order) named after one of
/// the candidate channels, decoded and converted to the slot's unit; `None` when the segment has
/// none of them.
fn channel(
    zip: &mut Zip,
    files: &[String],
    p: &Props,
    (candidates, slot, unit): (&[&str], &str, &str),
    what: &str,
    path: &Path,
) -> Result<Option<Vec<f64>>> {
    let found = files.iter().find_map(|f| {
        let base = f.rsplit('/').next().unwrap_or("");
        let stem = base.split('.').next().unwrap_or("");
        candidates.iter().find(|c| **c == stem).map(|c| (*c, f.clone()))
    });
    let Some((name, file)) = found else {
        return Ok(None);
    };
    let err = |msg: String| Error::data_file(path, 0, format!("{what}: channel {name}: {msg}"));
    let bytes = zip.read(&file)?;
    let mut data = decode(&bytes, name, p).map_err(err)?;
    let conv = format!("channel.{name}.conversion-set");
    let base = text(p, &format!("{conv}.conversions.base"))
        .ok_or_else(|| err("no conversions.base in the header".into()))?
        .to_owned();
    let mut chain = Vec::new();
    let mut cur = slot.to_owned();
    while cur != base {
        if chain.len() >= 32 {
            return Err(err(format!("conversion chain from {slot} does not reach {base}")));
        }
        let key = format!("{conv}.conversion.{cur}");
        if let Some(t) = text(p, &format!("{key}.scaling.type"))
            && t != "linear"
        {
            return Err(err(format!("conversion {cur} is {t}, only linear ones are read")));
        }
        let m = num(p, &format!("{key}.scaling.multiplier"))
            .ok_or_else(|| err(format!("no multiplier of conversion {cur}")))?;
        let o = num(p, &format!("{key}.scaling.offset"))
            .ok_or_else(|| err(format!("no offset of conversion {cur}")))?;
        chain.push((m, o));
        cur = text(p, &format!("{key}.base-calibration-slot"))
            .ok_or_else(|| err(format!("no base-calibration-slot of conversion {cur}")))?
            .to_owned();
    }
    for &(m, o) in chain.iter().rev() {
        for v in &mut data {
            *v = m * *v + o;
        }
    }
    let got = if slot == base {
        text(p, &format!("channel.{name}.data.encoder.scaling.unit.unit"))
            .or_else(|| text(p, &format!("channel.{name}.encoder.scaling.unit.unit")))
    } else {
        text(p, &format!("{conv}.conversion.{slot}.scaling.unit"))
            .or_else(|| text(p, &format!("{conv}.conversion.{slot}.scaling.unit.unit")))
    };
    match got {
        Some(u) if u == unit => Ok(Some(data)),
        Some(u) => Err(err(format!("slot {slot} is in {u}, not {unit}"))),
        None => Err(err(format!("no unit of slot {slot}"))),
    }
}

/// Decode a channel's big-endian samples and apply its encoder scaling.
fn decode(bytes: &[u8], name: &str, p: &Props) -> std::result::Result<Vec<f64>, String> {
    let first = |keys: [String; 2]| keys.iter().find_map(|k| text(p, k).map(str::to_owned));
    let enc = first([
        format!("channel.{name}.data.encoder.type"),
        format!("channel.{name}.encoder.type"),
    ]);
    let scaling = |what: &str| {
        [
            format!("channel.{name}.data.encoder.scaling.{what}"),
            format!("channel.{name}.encoder.scaling.{what}"),
        ]
        .iter()
        .find_map(|k| num(p, k))
    };
    let (size, read): (usize, fn(&[u8]) -> f64) = match enc.as_deref() {
        Some("signedshort") => (2, |b| i16::from_be_bytes([b[0], b[1]]) as f64),
        Some("unsignedshort") => (2, |b| u16::from_be_bytes([b[0], b[1]]) as f64),
        Some("signedinteger") => (4, |b| i32::from_be_bytes([b[0], b[1], b[2], b[3]]) as f64),
        Some("unsignedinteger") => (4, |b| u32::from_be_bytes([b[0], b[1], b[2], b[3]]) as f64),
        Some("signedlong") => (8, |b| {
            i64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]) as f64
        }),
        Some(other) => return Err(format!("encoder type {other} is not read")),
        None => {
            let ty = first([
                format!("channel.{name}.data.type"),
                format!("channel.{name}.type"),
            ]);
            match ty.as_deref() {
                Some("float" | "float-data") => (4, |b| f32::from_be_bytes([b[0], b[1], b[2], b[3]]) as f64),
                Some("double" | "double-data") => (8, |b| {
                    f64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
                }),
                Some("short" | "short-data") => (2, |b| i16::from_be_bytes([b[0], b[1]]) as f64),
                Some("integer" | "integer-data") => {
                    (4, |b| i32::from_be_bytes([b[0], b[1], b[2], b[3]]) as f64)
                }
                Some(other) => return Err(format!("data type {other} without encoder is not read")),
                None => return Err("no encoder or data type in the header".into()),
            }
        }
    };
    let (mult, off) = match (scaling("multiplier"), scaling("offset")) {
        (Some(m), Some(o)) => (m, o),
        _ if enc.is_none() => (1.0, 0.0),
        _ => return Err("no encoder multiplier and offset in the header".into()),
    };
    if !bytes.len().is_multiple_of(size) {
        return Err(format!(
            "{} bytes, not a whole number of {size}-byte samples (truncated?)",
            bytes.len()
        ));
    }
    Ok(bytes.chunks_exact(size).map(|b| read(b) * mult + off).collect())
}
