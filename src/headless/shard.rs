//! Sharded sweeps: a sweep scene ([`crate::scenes::sweep::Sweep`]) computed as N shards, each
//! shard a task of a job array (Slurm's `--array`, or `xargs -P` on one machine), then merged
//! into the figure.
//!
//! `--shard I/N` computes the points whose id is I modulo N, in parallel (rayon), and writes each
//! point's result atomically as a file of its own in the sweep's folder under `--out`:
//! `<out>/<scene-id>-<hash>/`, where the hash is that of the (canonical) parameter set, which the
//! folder also holds as `params.toml` (a preset: `--preset` reads it). Points already there are
//! skipped, so rerunning a shard that was killed (a time limit, a pre-emption) computes only
//! what is missing. A folder whose `params.toml` differs from the run's parameters is refused.
//! `--merge` reads every point, names the missing ones if any, and exports the figure through
//! the same assembly as an unsharded run: the same CSV and JSON (only the JSON's `run_time_s`
//! differs; after a merge it is the sum of the points' computing times and the assembly's).
//!
//! Point files are JSON: the scene, the point id and label, the seconds it took, and the values
//! as text that reads back to the same `f64` (`{:e}`, the shortest exact form; `NaN`, `inf`).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, anyhow, bail};
use serde::{Deserialize, Serialize};

use super::{create_folder, write_figure};
use crate::job::Job;
use crate::params::{ParamValues, value_text};
use crate::render::{Format, write_atomic};
use crate::scenes::sweep::SweepDyn;
use crate::scenes::{self, SceneDyn};

/// The name of the parameter file in a sweep's folder.
pub const PARAMS_FILE: &str = "params.toml";

pub use crate::cli::Shard;

/// The parameter set as canonical text, one `name=value` line per parameter in declaration
/// order, floats in their shortest exact form: equal sets give equal text.
pub fn canonical(values: &ParamValues) -> String {
    values
        .specs
        .iter()
        .zip(&values.values)
        .map(|(s, v)| format!("{}={}\n", s.name, canonical_value(v)))
        .collect()
}

/// One value as canonical text (see [`canonical`]).
fn canonical_value(v: &toml::Value) -> String {
    match v {
        toml::Value::Float(x) => format!("{x:e}"),
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Array(items) => {
            format!(
                "[{}]",
                items.iter().map(canonical_value).collect::<Vec<_>>().join(",")
            )
        }
        other => other.to_string(),
    }
}

/// 64-bit FNV-1a: a hash that stays the same across platforms and compiler versions.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The hash of a parameter set: 16 hex digits of the FNV-1a hash of its [`canonical`] text.
pub fn params_hash(values: &ParamValues) -> String {
    format!("{:016x}", fnv1a(canonical(values).as_bytes()))
}

/// The folder of a sweep's points: `<out>/<scene-id>-<16 hex digits of the parameters' hash>`.
pub fn folder(out: &Path, scene_id: &str, values: &ParamValues) -> PathBuf {
    out.join(format!("{scene_id}-{}", params_hash(values)))
}

/// The file of point `id` in a sweep's folder.
pub fn point_path(folder: &Path, id: usize) -> PathBuf {
    folder.join(format!("point-{id:06}.json"))
}

/// The largest point file read (a point holds at most a few thousand numbers).
const POINT_FILE_LIMIT: u64 = 64 << 20;

/// The longest computing time a point file may claim, in seconds (about 30 years).
const MAX_POINT_SECONDS: f64 = 1e9;

/// A point's result as stored: the parameter set's hash ([`params_hash`]) ties it to its
/// sweep, and the checksum over everything else to the text the shard wrote.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PointFile {
    scene: String,
    point: usize,
    label: String,
    params: String,
    seconds: f64,
    values: Vec<String>,
    checksum: String,
}

impl PointFile {
    /// The checksum of the other fields: 16 hex digits of FNV-1a over their text.
    fn digest(&self) -> String {
        let text = format!(
            "{}\n{}\n{}\n{}\n{}\n{}",
            self.scene,
            self.point,
            self.label,
            self.params,
            encode(self.seconds),
            self.values.join(",")
        );
        format!("{:016x}", fnv1a(text.as_bytes()))
    }
}

/// What a point file must hold to be merged.
#[derive(Debug, Clone, Copy)]
pub struct Expected<'a> {
    /// The scene id.
    pub scene: &'a str,
    /// The point id.
    pub point: usize,
    /// The hash of the sweep's parameter set ([`params_hash`]).
    pub params_hash: &'a str,
    /// The number of values of the point ([`crate::scenes::sweep::SweepDyn::point_len`]).
    pub len: usize,
    /// Whether a value may be NaN (a map cell where the quantity is not defined).
    pub nan_allowed: bool,
}

/// The text of a point file (JSON, one line).
pub fn point_text(
    scene: &str,
    point: usize,
    label: &str,
    params_hash: &str,
    seconds: f64,
    values: &[f64],
) -> String {
    let mut file = PointFile {
        scene: scene.to_string(),
        point,
        label: label.to_string(),
        params: params_hash.to_string(),
        seconds,
        values: values.iter().map(|&x| encode(x)).collect(),
        checksum: String::new(),
    };
    file.checksum = file.digest();
    serde_json::to_string(&file).unwrap_or_default()
}

/// A point file's text with its checksum recomputed, or `None` if it is not a point file's
/// JSON: what an edit that also forges the checksum gives (for fuzzing the checks behind it).
pub fn reseal(text: &str) -> Option<String> {
    let mut file: PointFile = serde_json::from_str(text).ok()?;
    file.checksum = file.digest();
    serde_json::to_string(&file).ok()
}

/// Parse and check a point file's text: the values and the seconds the point took, or why
/// the file cannot be merged (one line).
///
/// # Errors
/// Not a point file's JSON; another scene or point; another parameter set; a checksum that
/// does not match; seconds that are not finite and in [0, 1e9]; a wrong number of values; a
/// value that is not a number, or not finite (NaN where `nan_allowed`).
pub fn parse_point(text: &str, expected: &Expected<'_>) -> Result<(Vec<f64>, f64), String> {
    let f: PointFile =
        serde_json::from_str(text).map_err(|e| crate::text::escape_for_message(&e.to_string(), 200))?;
    if f.scene != expected.scene || f.point != expected.point {
        return Err(format!(
            "it holds point {} of {}",
            f.point,
            crate::text::escape_for_message(&f.scene, 40)
        ));
    }
    if f.params != expected.params_hash {
        return Err(format!(
            "it was computed with another parameter set (hash {}, this sweep's is {}): copied from \
             another sweep's folder?",
            crate::text::escape_for_message(&f.params, 40),
            expected.params_hash
        ));
    }
    if f.checksum != f.digest() {
        return Err("its content does not match its checksum (edited or truncated)".into());
    }
    if !(f.seconds.is_finite() && (0.0..=MAX_POINT_SECONDS).contains(&f.seconds)) {
        return Err(format!(
            "its computing time {} s is not in [0, {}]",
            crate::text::fmt_sig(f.seconds),
            crate::text::fmt_sig(MAX_POINT_SECONDS)
        ));
    }
    if f.values.len() != expected.len {
        return Err(format!(
            "it holds {} values, the point has {}",
            f.values.len(),
            expected.len
        ));
    }
    let values = f
        .values
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let x = decode(t).ok_or_else(|| {
                format!(
                    "value {k} `{}` is not a number",
                    crate::text::escape_for_message(t, 40)
                )
            })?;
            if x.is_finite() || (x.is_nan() && expected.nan_allowed) {
                Ok(x)
            } else {
                Err(format!("value {k} is {x}, not a finite number"))
            }
        })
        .collect::<Result<Vec<f64>, String>>()?;
    Ok((values, f.seconds))
}

/// An `f64` as text that reads back to the same value (`-0e0`, `NaN`, `inf` included).
pub fn encode(x: f64) -> String {
    format!("{x:e}")
}

/// The inverse of [`encode`].
pub fn decode(text: &str) -> Option<f64> {
    text.parse().ok()
}

/// A stored point: `None` if there is no file, `Some(Err)` naming what is wrong if the file is
/// damaged, belongs to another point or parameter set, or holds values the point cannot have,
/// else the values and the seconds the point took.
fn read_point(folder: &Path, expected: &Expected<'_>) -> Option<anyhow::Result<(Vec<f64>, f64)>> {
    let path = point_path(folder, expected.point);
    if std::fs::symlink_metadata(&path).is_err() {
        return None;
    }
    let parsed = match crate::input::read_input(&path, POINT_FILE_LIMIT.min(crate::input::limit())) {
        Ok(bytes) => parse_point(&String::from_utf8_lossy(&bytes), expected).map_err(|e| anyhow!(e)),
        Err(e) => Err(anyhow!(e)),
    };
    Some(parsed.with_context(|| format!("point file {} is damaged", path.display())))
}

/// The scene's sweep interface, or a one-line error naming the scenes that have one.
fn sweep_of(scene: &dyn SceneDyn) -> anyhow::Result<&dyn SweepDyn> {
    scene.sweep().ok_or_else(|| {
        let sweeps: Vec<&str> = scenes::all()
            .iter()
            .filter(|s| s.sweep().is_some())
            .map(|s| s.info().id)
            .collect();
        anyhow!(
            "scene {} is not a sweep: --shard and --merge apply to {} only",
            scene.info().id,
            sweeps.join(", ")
        )
    })
}

/// Check the folder's parameter file against `values`: `Ok(false)` if there is none.
fn check_params(scene: &dyn SceneDyn, values: &ParamValues, folder: &Path) -> anyhow::Result<bool> {
    let path = folder.join(PARAMS_FILE);
    if !path.is_file() {
        return Ok(false);
    }
    let mut stored = scene.defaults();
    stored.apply_preset_file(&path).with_context(|| {
        format!(
            "the sweep folder {} has an unreadable {PARAMS_FILE}",
            folder.display()
        )
    })?;
    if canonical(&stored) == canonical(values) {
        return Ok(true);
    }
    let differing = values
        .specs
        .iter()
        .zip(values.values.iter().zip(&stored.values))
        .find(|(_, (a, b))| canonical_value(a) != canonical_value(b));
    let what = differing.map_or_else(
        || "other parameters".to_string(),
        |(s, (a, b))| format!("{} = {}, not {}", s.name, value_text(b), value_text(a)),
    );
    bail!(
        "the sweep folder {} holds points of {} computed with {what}: refusing to mix parameter sets \
         (use another --out, or remove the folder)",
        folder.display(),
        scene.info().id
    )
}

/// Create `folder` and its missing parents; the folders created, outermost first.
fn create_folders(folder: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let missing: Vec<PathBuf> = folder
        .ancestors()
        .take_while(|d| !d.as_os_str().is_empty() && std::fs::symlink_metadata(d).is_err())
        .map(Path::to_path_buf)
        .collect();
    create_folder(folder)?;
    Ok(missing.into_iter().rev().collect())
}

/// Whether a sweep folder holds a point file.
fn has_points(folder: &Path) -> bool {
    std::fs::read_dir(folder).is_ok_and(|rd| {
        rd.filter_map(Result::ok)
            .any(|e| e.file_name().to_string_lossy().starts_with("point-"))
    })
}

/// A duration as "1.23 s" or "4.5 ms".
fn fmt_seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

/// A point as "17 (n = 7, σ_rms/σ = 31.6)".
fn named(id: usize, labels: &[String]) -> String {
    format!("{id} ({})", labels.get(id).map_or("", String::as_str))
}

/// `--shard I/N`: compute this shard's points that are not stored yet, each written to its
/// file as soon as it is done; progress lines on stderr. Returns the sweep's folder.
///
/// # Errors
/// Not a sweep, invalid values, a folder of another parameter set, the first failing point
/// (named; the points finished before it stay stored), I/O errors.
pub fn run_shard(
    scene: &dyn SceneDyn,
    values: &ParamValues,
    shard: Shard,
    out: &Path,
) -> anyhow::Result<PathBuf> {
    let sweep = sweep_of(scene)?;
    let id = scene.info().id;
    let labels = sweep.points(values)?;
    let n = labels.len();
    let hash = params_hash(values);
    let expected = |point: usize| -> crate::error::Result<Expected<'_>> {
        Ok(Expected {
            scene: id,
            point,
            params_hash: &hash,
            len: sweep.point_len(values, point)?,
            nan_allowed: sweep.nan_values(),
        })
    };
    let folder = folder(out, id, values);
    let created = create_folders(&folder)?;
    // A shard that fails before its first point is stored removes the folders it created.
    let undo = |e: anyhow::Error| {
        if !created.is_empty() && !has_points(&folder) {
            let _ = std::fs::remove_file(folder.join(PARAMS_FILE));
            for d in created.iter().rev() {
                let _ = std::fs::remove_dir(d);
            }
        }
        e
    };
    if !check_params(scene, values, &folder).map_err(undo)? {
        let header = format!(
            "Parameters of the sharded sweep {id} in this folder ({n} points): the same set is \
             needed for every shard and for --merge.\nRun again with `adhesion --headless --figure {id} \
             --preset {}/{PARAMS_FILE} ...`.",
            folder.display()
        );
        write_atomic(
            &folder.join(PARAMS_FILE),
            values.to_preset_text(&header).as_bytes(),
        )
        .map_err(|e| undo(e.into()))?;
    }
    let mine: Vec<usize> = (shard.index..n).step_by(shard.count).collect();
    let mut todo = Vec::new();
    for &k in &mine {
        if !matches!(read_point(&folder, &expected(k)?), Some(Ok(_))) {
            todo.push(k);
        }
    }
    let tag = format!("{id} shard {}/{}", shard.index, shard.count);
    eprintln!(
        "{tag}: {} of the {n} points, {} already done in {}, {} to compute",
        mine.len(),
        mine.len() - todo.len(),
        folder.display(),
        todo.len()
    );
    let start = Instant::now();
    let done = AtomicUsize::new(0);
    let busy = Mutex::new(0.0f64);
    let failed = Mutex::new(None);
    let visit = |k: usize, task: scenes::sweep::PointTask<'_>| -> crate::error::Result<()> {
        let t0 = Instant::now();
        let result = task().and_then(|v| {
            let seconds = t0.elapsed().as_secs_f64();
            let text = point_text(id, k, &labels[k], &hash, seconds, &v);
            write_atomic(&point_path(&folder, k), text.as_bytes()).map(|()| seconds)
        });
        let seconds = match result {
            Ok(s) => s,
            Err(e) => {
                if let Ok(mut f) = failed.lock() {
                    f.get_or_insert(k);
                }
                return Err(e);
            }
        };
        let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
        let total = busy.lock().map_or(seconds, |mut b| {
            *b += seconds;
            *b
        });
        eprintln!(
            "{tag}: {finished}/{} done, point {} in {} ({} per point)",
            todo.len(),
            named(k, &labels),
            fmt_seconds(seconds),
            fmt_seconds(total / finished as f64)
        );
        Ok(())
    };
    if let Err(e) = sweep.run_points(values, &todo, &Job::quiet(), &visit) {
        let point = failed.lock().ok().and_then(|f| *f);
        return Err(undo(match point {
            Some(k) => anyhow!(e).context(format!("{tag}: point {}", named(k, &labels))),
            None => anyhow!(e).context(tag),
        }));
    }
    eprintln!(
        "{tag}: finished, {} points computed in {:.1} s",
        todo.len(),
        start.elapsed().as_secs_f64()
    );
    Ok(folder)
}

/// `--merge`: read every point of the sweep from its folder under `out` and export the figure
/// as an unsharded run does (`<out>/<scene-id>.<ext>`).
///
/// # Errors
/// Not a sweep, no folder, a folder of another parameter set, missing points (named) or
/// damaged point files, assembly, rendering and I/O errors.
pub fn merge(
    scene: &dyn SceneDyn,
    values: &ParamValues,
    out: &Path,
    formats: &[Format],
) -> anyhow::Result<Vec<PathBuf>> {
    let sweep = sweep_of(scene)?;
    let id = scene.info().id;
    let labels = sweep.points(values)?;
    let n = labels.len();
    let folder = folder(out, id, values);
    if !folder.is_dir() {
        bail!(
            "no points of {id} with these parameters under {}: expected the folder {} (run the shards \
             first, with the same parameters)",
            out.display(),
            folder.display()
        );
    }
    check_params(scene, values, &folder)?;
    let hash = params_hash(values);
    let mut points = Vec::with_capacity(n);
    let mut missing = Vec::new();
    let mut seconds = 0.0;
    for k in 0..n {
        let expected = Expected {
            scene: id,
            point: k,
            params_hash: &hash,
            len: sweep.point_len(values, k)?,
            nan_allowed: sweep.nan_values(),
        };
        match read_point(&folder, &expected) {
            None => missing.push(k),
            Some(Err(e)) => return Err(e.context("delete it and run its shard again")),
            Some(Ok((v, s))) => {
                points.push(v);
                seconds += s;
            }
        }
    }
    if !missing.is_empty() {
        const SHOWN: usize = 8;
        let mut list: Vec<String> = missing.iter().take(SHOWN).map(|&k| named(k, &labels)).collect();
        if missing.len() > SHOWN {
            list.push(format!("and {} more", missing.len() - SHOWN));
        }
        bail!(
            "{} of the {n} points of {id} are missing in {}: {}; run the shards that hold them again",
            missing.len(),
            folder.display(),
            list.join(", ")
        );
    }
    let start = Instant::now();
    let fig = sweep.assemble(values, &points, &Job::quiet())?;
    let run_time = seconds + start.elapsed().as_secs_f64();
    Ok(write_figure(
        &fig,
        scene.info().caption,
        values,
        run_time,
        out,
        formats,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoded_floats_read_back_bit_for_bit() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut samples = vec![
            0.0,
            -0.0,
            1.0,
            0.1,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for _ in 0..10_000 {
            // xorshift: bit patterns over the whole range, subnormals included.
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            samples.push(f64::from_bits(x));
        }
        for v in samples {
            let back = decode(&encode(v)).expect("encoded text parses");
            if v.is_nan() {
                assert!(back.is_nan());
            } else {
                assert_eq!(back.to_bits(), v.to_bits(), "{v:e}");
            }
        }
    }

    // The computing time is stored as a JSON number and read back into the checksum's text:
    // it must read back to the same bits (serde_json's `float_roundtrip`), or a point whose
    // time has 17 significant digits reads as damaged (7.7244911179999995 s did).
    #[test]
    fn point_files_read_back_whatever_their_computing_time() {
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut times = vec![7.724_491_117_999_999_5, 0.0, 1e-9, 123.456, 1e9];
        for _ in 0..2_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            times.push((x >> 11) as f64 / (1u64 << 53) as f64 * 1e4);
        }
        let expected = Expected {
            scene: "fig4.9b-models",
            point: 37,
            params_hash: "8903454df41e0df3",
            len: 2,
            nan_allowed: false,
        };
        for t in times {
            let text = point_text(
                "fig4.9b-models",
                37,
                "a point",
                "8903454df41e0df3",
                t,
                &[1.5e-5, 7.9e-9],
            );
            let (values, seconds) = parse_point(&text, &expected).unwrap_or_else(|e| panic!("{t:e} s: {e}"));
            assert_eq!(seconds.to_bits(), t.to_bits(), "{t:e}");
            assert_eq!(values, vec![1.5e-5, 7.9e-9]);
        }
    }

    #[test]
    fn shard_specs_are_checked() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard { index: 2, count: 4 }));
        assert!("4/4".parse::<Shard>().unwrap_err().contains("below N = 4"));
        assert!("0/0".parse::<Shard>().unwrap_err().contains("at least 1"));
        assert!("a/4".parse::<Shard>().unwrap_err().contains("not a whole number"));
        assert!("3".parse::<Shard>().unwrap_err().contains("expected I/N"));
    }

    #[test]
    fn the_folder_name_changes_with_any_parameter() {
        let scene = scenes::find("fig5.8").expect("registered");
        let a = scene.defaults();
        let mut b = a.clone();
        b.set_assignment("seed=2").expect("valid");
        let out = Path::new("o");
        assert_ne!(folder(out, "fig5.8", &a), folder(out, "fig5.8", &b));
        assert_eq!(folder(out, "fig5.8", &a), folder(out, "fig5.8", &a.clone()));
    }
}
