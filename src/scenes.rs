//! The scene registry: one scene per computational figure of the dissertation.
//!
//! A scene is data plus one function: an id (the figure number, `fig2.5`), a title, the caption
//! in short, a parameter struct with the dissertation's values as defaults (and a preset file
//! `presets/<id>.toml`), the names of the scalar results it reports, and
//! `run(&Params, &Job) -> Result<Figure>`. The terminal UI and the headless exporter list the
//! same registry through the object-safe [`SceneDyn`].
//!
//! Adding a scene: declare it with [`crate::scene!`] (its id, chapter, title, caption, results
//! and parameter struct) and implement [`Scene`] (its checks and run) beside it, in the
//! chapter's file under `scenes/`; add it to that file's `SCENES` list, and add
//! `presets/<id>.toml`. A scene made of many independent points also implements
//! [`sweep::Sweep`] and is listed as `Swept::<S>::NEW`, which lets it run in shards (a job
//! array on a cluster) and be merged.

use std::marker::PhantomData;

use crate::error::{Error, Result, did_you_mean};
use crate::figure::Figure;
use crate::job::Job;
use crate::params::{ParamSpec, ParamValues, Params};

pub mod fig1;
pub mod fig2;
pub mod fig3;
pub mod fig4;
pub mod fig5;
pub mod fig6;
pub mod figc;
pub mod groups;
pub mod sweep;

/// What the registry lists of a scene: its id, chapter, title, caption, result names and
/// parameter struct. Declared with [`crate::scene!`] beside the scene's [`Scene`] impl.
pub trait SceneHeader {
    /// Parameter struct (declared with [`crate::scene_params!`]).
    type Params: Params;
    /// Id, the dissertation's figure number: `fig1.1`, `fig2.5-accuracy`, `figC.2`.
    const ID: &'static str;
    /// Chapter or appendix the figure belongs to: `"1"` ... `"6"`, `"A"` ... `"C"`.
    const CHAPTER: &'static str;
    /// Title.
    const TITLE: &'static str;
    /// The dissertation's caption, in short, with the equations the scene uses.
    const CAPTION: &'static str;
    /// Names of the scalar results (with unit suffix or `_norm`) and their meaning.
    const RESULTS: &'static [(&'static str, &'static str)];
    /// Whether the scene is a sweep of many independent runs (minutes at its defaults):
    /// `--all` runs it in its quick form, and `--describe` says so.
    const SWEEP: bool = false;
    /// Whether one run takes minutes at the defaults (the finite-element scenes): `--all` runs
    /// it in its quick form, and `--describe` says so. Sweeps are long by
    /// [`SceneHeader::SWEEP`].
    const LONG: bool = false;
}

/// A figure of the dissertation, computed: the checks, quick form and run of a scene whose
/// header ([`SceneHeader`]) is declared with [`crate::scene!`].
pub trait Scene: SceneHeader + Send + Sync + 'static {
    /// Checks across fields (ranges of single fields are checked by their specs).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the field.
    fn validate(_params: &Self::Params) -> Result<()> {
        Ok(())
    }

    /// Reduce the resolution for quick runs (tests of every preset); the physics is unchanged.
    fn quick(_params: &mut Self::Params) {}

    /// An estimate of the memory the run needs, for scenes whose memory grows with their
    /// parameters beyond what a machine may have (grids, arrays of springs); `None` for scenes
    /// that stay small everywhere in their declared ranges. Checked against
    /// [`memory_limit`] before the run starts.
    fn memory_estimate(_params: &Self::Params) -> Option<MemoryEstimate> {
        None
    }

    /// Compute the figure.
    ///
    /// # Errors
    /// Model errors, [`Error::Cancelled`] when the job is cancelled.
    fn run(params: &Self::Params, job: &Job) -> Result<Figure>;
}

/// Declare a scene: its unit struct and its [`SceneHeader`] (id, chapter, parameter struct,
/// title, caption, results; `sweep: true` or `long: true` for scenes of minutes), written once
/// in this order. The scene's checks and run follow in its `impl Scene`.
///
/// ```
/// use adhesion::error::Result;
/// use adhesion::figure::Figure;
/// use adhesion::job::Job;
/// use adhesion::params::Range;
/// use adhesion::scenes::{Scene, SceneHeader};
///
/// adhesion::scene_params! {
///     /// Parameters of an example scene.
///     pub struct ExampleParams {
///         /// Number of points.
///         points: usize = 20, unit = "", range = Range::between(2.0, 100.0);
///     }
/// }
///
/// adhesion::scene! {
///     /// An example scene.
///     pub struct Example {
///         id: "example",
///         chapter: "1",
///         params: ExampleParams,
///         title: "An example",
///         caption: "Nothing, drawn.",
///         results: &[("points_count", "points drawn")],
///     }
/// }
///
/// impl Scene for Example {
///     fn run(p: &Self::Params, _job: &Job) -> Result<Figure> {
///         let mut fig = Figure::new(Self::ID, Self::TITLE);
///         fig.result("points_count", p.points as f64);
///         Ok(fig)
///     }
/// }
/// assert_eq!(Example::ID, "example");
/// assert!(!Example::SWEEP);
/// ```
#[macro_export]
macro_rules! scene {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            id: $id:expr,
            chapter: $chapter:expr,
            params: $params:ty,
            title: $title:expr,
            caption: $caption:expr,
            results: $results:expr,
            $(sweep: $sweep:expr,)?
            $(long: $long:expr,)?
        }
    ) => {
        $(#[$meta])*
        $vis struct $name;

        impl $crate::scenes::SceneHeader for $name {
            type Params = $params;
            const ID: &'static str = $id;
            const CHAPTER: &'static str = $chapter;
            const TITLE: &'static str = $title;
            const CAPTION: &'static str = $caption;
            const RESULTS: &'static [(&'static str, &'static str)] = $results;
            $(const SWEEP: bool = $sweep;)?
            $(const LONG: bool = $long;)?
        }
    };
}

/// Static description of a scene.
#[derive(Debug, Clone, Copy)]
pub struct SceneInfo {
    /// Id.
    pub id: &'static str,
    /// Chapter key.
    pub chapter: &'static str,
    /// Title.
    pub title: &'static str,
    /// Caption.
    pub caption: &'static str,
    /// Result names and meanings.
    pub results: &'static [(&'static str, &'static str)],
    /// A sweep of many runs ([`SceneHeader::SWEEP`]).
    pub sweep: bool,
    /// A single run of minutes at the defaults ([`SceneHeader::LONG`]).
    pub long: bool,
}

/// Object-safe view of a [`Scene`], used by the front ends.
pub trait SceneDyn: Send + Sync {
    /// Id, title, caption, results.
    fn info(&self) -> SceneInfo;
    /// Parameter specs.
    fn specs(&self) -> Vec<ParamSpec>;
    /// The default values (the dissertation's).
    fn defaults(&self) -> ParamValues;
    /// Validate values fully (types, ranges, cross-field checks) without running.
    ///
    /// # Errors
    /// The first problem found.
    fn validate(&self, values: &ParamValues) -> Result<()>;
    /// Reduce `values` for a quick run.
    ///
    /// # Errors
    /// If the values are invalid.
    fn quick(&self, values: &ParamValues) -> Result<ParamValues>;
    /// Validate and run.
    ///
    /// # Errors
    /// Validation errors, model errors, cancellation.
    fn run(&self, values: &ParamValues, job: &Job) -> Result<Figure>;
    /// The values a failure of a run with `values` measures the user's changes from (see
    /// [`attribute_failure`]): the defaults, or in a quick run ([`ParamValues::quick`]) the
    /// defaults in quick form, so that only what the user changed (`--set`, a preset, the
    /// form) is named, never the resolution quick mode set.
    fn baseline(&self, values: &ParamValues) -> ParamValues {
        let defaults = self.defaults();
        if values.quick {
            self.quick(&defaults).unwrap_or(defaults)
        } else {
            defaults
        }
    }
    /// The sweep interface of a scene made of independent points ([`sweep::Sweep`]), which the
    /// headless exporter runs in shards and merges; `None` for other scenes.
    fn sweep(&self) -> Option<&dyn sweep::SweepDyn> {
        None
    }
}

/// The memory a run needs [bytes] and the parameters that set it, as the user writes them.
#[derive(Debug, Clone, PartialEq)]
pub struct MemoryEstimate {
    /// Estimated peak memory [bytes].
    pub bytes: f64,
    /// The parameter(s) the estimate grows with, e.g. "springs_x x springs_y".
    pub parameter: &'static str,
    /// Their values, e.g. "4096 x 4096".
    pub value: String,
}

impl MemoryEstimate {
    /// Refuse when the estimate exceeds `limit` [bytes].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the parameters, with the estimate and the limit.
    pub fn check(&self, limit: f64) -> Result<()> {
        if self.bytes > limit {
            return Err(Error::invalid(
                self.parameter,
                &self.value,
                format!(
                    "the run needs about {} of memory, more than the {} available; choose a \
                     smaller value",
                    fmt_bytes(self.bytes),
                    fmt_bytes(limit)
                ),
            ));
        }
        Ok(())
    }
}

/// Bytes as "1.2 GiB", "340 MiB".
pub fn fmt_bytes(b: f64) -> String {
    const GIB: f64 = 1024.0 * 1024.0 * 1024.0;
    if b >= GIB {
        format!("{:.1} GiB", b / GIB)
    } else {
        format!("{:.0} MiB", b / (1024.0 * 1024.0))
    }
}

/// The memory a run may use [bytes]: `ADHESION_MEMORY_LIMIT` (bytes, or with a suffix K, M, G)
/// when set, else the memory the system reports available (`MemAvailable` of /proc/meminfo),
/// else 4 GiB.
pub fn memory_limit() -> f64 {
    fn parse(t: &str) -> Option<f64> {
        let t = t.trim();
        let (num, mult) = match t.char_indices().last()? {
            (i, 'k' | 'K') => (&t[..i], 1024.0),
            (i, 'm' | 'M') => (&t[..i], 1024.0 * 1024.0),
            (i, 'g' | 'G') => (&t[..i], 1024.0 * 1024.0 * 1024.0),
            _ => (t, 1.0),
        };
        num.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| *v > 0.0)
            .map(|v| v * mult)
    }
    if let Some(v) = std::env::var("ADHESION_MEMORY_LIMIT")
        .ok()
        .as_deref()
        .and_then(parse)
    {
        return v;
    }
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("MemAvailable:"))
                .and_then(|v| v.trim().strip_suffix("kB"))
                .and_then(|v| v.trim().parse::<f64>().ok())
        })
        .map_or(4.0 * 1024.0 * 1024.0 * 1024.0, |kb| kb * 1024.0)
}

/// Adapter from a typed [`Scene`] to [`SceneDyn`].
pub struct Registered<S>(PhantomData<S>);

impl<S> Registered<S> {
    /// The adapter (a zero-sized constant).
    pub const NEW: Self = Registered(PhantomData);
}

impl<S: Scene> SceneDyn for Registered<S> {
    fn info(&self) -> SceneInfo {
        SceneInfo {
            id: S::ID,
            chapter: S::CHAPTER,
            title: S::TITLE,
            caption: S::CAPTION,
            results: S::RESULTS,
            sweep: S::SWEEP,
            long: S::LONG,
        }
    }

    fn specs(&self) -> Vec<ParamSpec> {
        S::Params::specs()
    }

    fn defaults(&self) -> ParamValues {
        ParamValues::from_params(S::ID, &S::Params::default())
    }

    fn validate(&self, values: &ParamValues) -> Result<()> {
        let p: S::Params = values.to_params()?;
        S::validate(&p).map_err(|e| attribute_failure(S::ID, values, &self.baseline(values), e))
    }

    fn quick(&self, values: &ParamValues) -> Result<ParamValues> {
        let mut p: S::Params = values.to_params()?;
        S::quick(&mut p);
        let mut quick = ParamValues::from_params(S::ID, &p);
        quick.quick = true;
        Ok(quick)
    }

    fn run(&self, values: &ParamValues, job: &Job) -> Result<Figure> {
        let p: S::Params = values.to_params()?;
        self.validate(values)?;
        if let Some(m) = S::memory_estimate(&p) {
            m.check(memory_limit())?;
        }
        let mut fig = finish(S::ID, values, &self.baseline(values), S::run(&p, job))?;
        if let Some(coarser) = quick_form(self, values) {
            fig.mark_quick(&coarser);
        }
        Ok(fig)
    }
}

/// What a run of `scene` with `values` computes more coarsely than the full figure, when the
/// values are in quick form ([`ParamValues::quick`]): each parameter the scene's quick form
/// changes from its defaults, as it ran and at full resolution ("sigma_points = 3 (full: 9)").
/// `None` for a run at full resolution, and for a quick form that changes nothing (or whose
/// every change the user set back).
pub fn quick_form(scene: &dyn SceneDyn, values: &ParamValues) -> Option<String> {
    if !values.quick {
        return None;
    }
    let full = scene.defaults();
    let quick = scene.quick(&full).ok()?;
    let changed: Vec<String> = full
        .specs
        .iter()
        .zip(full.values.iter().zip(&quick.values))
        .filter(|(_, (f, q))| f != q)
        .filter_map(|(spec, (f, _))| {
            let ran = values.specs.iter().position(|s| s.name == spec.name)?;
            let ran = &values.values[ran];
            (ran != f).then(|| {
                format!(
                    "{} = {} (full: {})",
                    spec.name,
                    crate::params::value_text(ran),
                    crate::params::value_text(f)
                )
            })
        })
        .collect();
    (!changed.is_empty()).then(|| changed.join(", "))
}

/// The end of every run, sharded or not: a model's failure as [`attribute_failure`] makes it,
/// non-finite results refused the same way, the figure's id set.
///
/// # Errors
/// The run's error, attributed; non-finite results.
pub fn finish(
    id: &'static str,
    values: &ParamValues,
    defaults: &ParamValues,
    run: Result<Figure>,
) -> Result<Figure> {
    let mut figure = run.map_err(|e| attribute_failure(id, values, defaults, e))?;
    let nonfinite: Vec<&str> = figure
        .results
        .iter()
        .filter(|(_, v)| !v.is_finite())
        .map(|(n, _)| n.as_str())
        .collect();
    if !nonfinite.is_empty() {
        let cause = Error::Unresolvable {
            model: "results",
            reason: format!(
                "{} not finite (the model leaves its double range)",
                nonfinite.join(", ")
            ),
        };
        return Err(attribute_failure(id, values, defaults, cause));
    }
    figure.id = id.to_string();
    Ok(figure)
}

/// A model's failure (or non-finite results) as the user can act on it: an error that already
/// names one of the parameters the user changed (or any parameter when none was changed), a
/// cancellation and file errors pass unchanged; any other, which names internal quantities
/// (`no sign change on [..]`, `m0`, a Newton residual) or a parameter derived from the one the
/// user set (`ring_width` from `radius`), is prefixed by the parameters the user changed, most changed first (by the ratio to the
/// default), with their defaults, and its numbers are cut to 6 significant digits. `defaults`
/// is what the changes are measured from: [`SceneDyn::baseline`] (in quick runs, the defaults
/// in quick form).
pub fn attribute_failure(
    scene: &'static str,
    values: &ParamValues,
    defaults: &ParamValues,
    error: Error,
) -> Error {
    if matches!(
        error,
        Error::Cancelled
            | Error::File { .. }
            | Error::DataFile { .. }
            | Error::Io(_)
            | Error::Render { .. }
            | Error::AtParameters { .. }
    ) {
        return error;
    }
    let message = error.to_string();
    let names = |name: &str| names_word(&message, name);
    let changed: Vec<&str> = values
        .specs
        .iter()
        .zip(values.values.iter().zip(&defaults.values))
        .filter(|(_, (v, d))| v != d)
        .map(|(s, _)| s.name)
        .collect();
    // An error naming a parameter (quoted) passes as it is when it also names one the user
    // changed, quoted or not ("must be below alpha_max"), or the user changed none; one naming
    // only another parameter (`ring_width` when `radius` was set) is prefixed by what the user
    // changed.
    let quoted = values
        .specs
        .iter()
        .any(|s| message.contains(&format!("`{}`", s.name)));
    if quoted && (changed.is_empty() || changed.iter().any(|n| names(n))) {
        return match error {
            Error::InvalidParameter { name, value, reason } => Error::InvalidParameter {
                name,
                value,
                reason: crate::text::compact_numbers(&reason),
            },
            e => e,
        };
    }
    Error::AtParameters {
        scene,
        at: changed_parameters(values, defaults),
        cause: crate::text::compact_numbers(&message),
    }
}

/// Whether `message` names `name` as a word of its own (`alpha_max`, also unquoted as in "must
/// be below alpha_max"; not the `alpha` of `alpha_max`).
pub fn names_word(message: &str, name: &str) -> bool {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    message.match_indices(name).any(|(i, _)| {
        let before = message[..i].chars().next_back();
        let after = message[i + name.len()..].chars().next();
        !before.is_some_and(ident) && !after.is_some_and(ident)
    })
}

/// The (at most three) parameters that differ most from their defaults, as
/// `name = value (default d)`; "its default parameters" when none differs.
fn changed_parameters(values: &ParamValues, defaults: &ParamValues) -> String {
    fn numbers(v: &toml::Value) -> Vec<f64> {
        match v {
            toml::Value::Float(x) => vec![*x],
            toml::Value::Integer(i) => vec![*i as f64],
            toml::Value::Array(a) => a.iter().flat_map(numbers).collect(),
            _ => Vec::new(),
        }
    }
    // How far a value moved: the largest |ln(x/d)| over its numbers (infinite across zero or
    // a sign change); 0.5 for a changed non-numeric value.
    let distance = |v: &toml::Value, d: &toml::Value| -> f64 {
        let (a, b) = (numbers(v), numbers(d));
        if a.is_empty() || a.len() != b.len() {
            return 0.5;
        }
        a.iter()
            .zip(&b)
            .map(|(x, y)| {
                if x == y {
                    0.0
                } else if x * y > 0.0 {
                    (x / y).ln().abs()
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max)
    };
    let mut changed: Vec<(f64, String)> = values
        .specs
        .iter()
        .zip(&values.values)
        .zip(&defaults.values)
        .filter(|((_, v), d)| v != d)
        .map(|((s, v), d)| {
            let text = |v: &toml::Value| match v {
                toml::Value::Float(x) => crate::text::fmt_sig(*x),
                other => crate::text::escape_for_message(&crate::params::value_text(other), 40),
            };
            (
                distance(v, d),
                format!("`{}` = {} (default {})", s.name, text(v), text(d)),
            )
        })
        .collect();
    if changed.is_empty() {
        return "its default parameters".into();
    }
    changed.sort_by(|a, b| b.0.total_cmp(&a.0));
    changed
        .into_iter()
        .take(3)
        .map(|(_, t)| t)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every scene, in chapter order (chapters 1-6, then the appendices; a scene registered in
/// another chapter's file, like fig3.7d in `figc`, joins its own chapter).
pub fn all() -> Vec<&'static dyn SceneDyn> {
    let mut scenes = [
        fig1::SCENES,
        fig2::SCENES,
        fig3::SCENES,
        fig4::SCENES,
        fig5::SCENES,
        fig6::SCENES,
        figc::SCENES,
    ]
    .concat();
    scenes.sort_by_key(|s| s.info().chapter);
    scenes
}

/// Look a scene up by id.
///
/// # Errors
/// [`Error::UnknownScene`] with a suggestion.
pub fn find(id: &str) -> Result<&'static dyn SceneDyn> {
    let scenes = all();
    scenes
        .iter()
        .find(|s| s.info().id == id)
        .copied()
        .ok_or_else(|| Error::UnknownScene {
            id: id.into(),
            hint: did_you_mean(id, scenes.iter().map(|s| s.info().id)),
        })
}

/// Chapter titles, for grouping scenes in lists.
pub const CHAPTERS: &[(&str, &str)] = &[
    ("1", "Classical theories and Fuller-Tabor"),
    ("2", "Machine stiffness (JKR with a spring)"),
    ("3", "Maugis-Dugdale and depth-dependent hysteresis"),
    ("4", "Lennard-Jones adhesion of smooth and wavy tips"),
    ("5", "Fibrils and spring arrays"),
    ("6", "Peeling from wavy substrates"),
    ("C", "Random rough surfaces (appendix C)"),
];

/// Title of a chapter key.
pub fn chapter_title(key: &str) -> &'static str {
    CHAPTERS
        .iter()
        .find(|(k, _)| *k == key)
        .map_or("Other", |(_, t)| *t)
}

/// A readable SI prefix for values of magnitude around `magnitude`: returns (scale, unit) such
/// that `value / scale` is in the prefixed unit, e.g. `(1e-9, "nm")` for 3e-8 m.
pub fn engineering_unit(base: &str, magnitude: f64) -> (f64, String) {
    const PREFIXES: [(f64, &str); 9] = [
        (1e-15, "f"),
        (1e-12, "p"),
        (1e-9, "n"),
        (1e-6, "µ"),
        (1e-3, "m"),
        (1.0, ""),
        (1e3, "k"),
        (1e6, "M"),
        (1e9, "G"),
    ];
    let m = magnitude.abs();
    let (scale, prefix) = PREFIXES
        .iter()
        .rev()
        .find(|(s, _)| m >= *s)
        .copied()
        .unwrap_or(PREFIXES[0]);
    (scale, format!("{prefix}{base}"))
}
