//! Scene parameters: specification (name, unit, help, valid range), parsing from text and TOML,
//! and validation.
//!
//! A scene's parameters are one plain serde struct declared with [`scene_params!`], which
//! generates the struct, its `Default` (the dissertation's values), and its [`ParamSpec`] list
//! from a single declaration, so the docs, the `--describe` output, the terminal UI's form and
//! the range checks cannot drift apart. Validation has two stages: parsing (types, unknown keys)
//! and meaning (ranges here, cross-field checks in the scene).

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::error::{Error, Result, did_you_mean};
/// The message formatting the parameters' errors use, where it has always been reachable.
pub use crate::text::{compact_numbers, echo_value, escape_for_message, fmt_sig, fmt_value};

/// The type of a parameter as the user edits it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamKind {
    /// A real number (finite).
    Float,
    /// A non-negative whole number.
    Int,
    /// `true` or `false`.
    Bool,
    /// One of a fixed set of words.
    Choice(&'static [&'static str]),
    /// A comma-separated list of real numbers.
    FloatList,
    /// Free text (file paths); may be empty.
    Text,
}

impl ParamKind {
    /// What the user is expected to type, for error messages.
    pub fn expected(self) -> String {
        match self {
            ParamKind::Float => "a number".into(),
            ParamKind::Int => "a whole number".into(),
            ParamKind::Bool => "true or false".into(),
            ParamKind::Choice(options) => format!("one of {}", options.join(", ")),
            ParamKind::FloatList => "a comma-separated list of numbers".into(),
            ParamKind::Text => "text".into(),
        }
    }
}

/// One end of a valid range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// No bound.
    Open,
    /// The value may equal the bound.
    Inclusive(f64),
    /// The value must not equal the bound.
    Exclusive(f64),
}

/// The valid range of a numeric parameter (every element, for lists).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower end.
    pub min: Bound,
    /// Upper end.
    pub max: Bound,
}

impl Range {
    /// Any finite value.
    pub const fn any() -> Self {
        Self {
            min: Bound::Open,
            max: Bound::Open,
        }
    }
    /// x > 0.
    pub const fn positive() -> Self {
        Self {
            min: Bound::Exclusive(0.0),
            max: Bound::Open,
        }
    }
    /// x ≥ 0.
    pub const fn non_negative() -> Self {
        Self {
            min: Bound::Inclusive(0.0),
            max: Bound::Open,
        }
    }
    /// x ≥ lo.
    pub const fn at_least(lo: f64) -> Self {
        Self {
            min: Bound::Inclusive(lo),
            max: Bound::Open,
        }
    }
    /// lo ≤ x ≤ hi.
    pub const fn between(lo: f64, hi: f64) -> Self {
        Self {
            min: Bound::Inclusive(lo),
            max: Bound::Inclusive(hi),
        }
    }
    /// lo < x < hi.
    pub const fn open(lo: f64, hi: f64) -> Self {
        Self {
            min: Bound::Exclusive(lo),
            max: Bound::Exclusive(hi),
        }
    }
    /// lo ≤ x < hi.
    pub const fn half_open(lo: f64, hi: f64) -> Self {
        Self {
            min: Bound::Inclusive(lo),
            max: Bound::Exclusive(hi),
        }
    }

    /// `None` if `x` is in range, else the reason ("must be positive").
    pub fn violation(&self, x: f64) -> Option<String> {
        if !x.is_finite() {
            return Some("must be a finite number".into());
        }
        let below = match self.min {
            Bound::Open => false,
            Bound::Inclusive(lo) => x < lo,
            Bound::Exclusive(lo) => x <= lo,
        };
        let above = match self.max {
            Bound::Open => false,
            Bound::Inclusive(hi) => x > hi,
            Bound::Exclusive(hi) => x >= hi,
        };
        (below || above).then(|| match (self.min, self.max) {
            (Bound::Exclusive(0.0), Bound::Open) => "must be positive".into(),
            (Bound::Inclusive(0.0), Bound::Open) => "must not be negative".into(),
            _ => format!("must be in {}", self.describe()),
        })
    }

    /// Interval notation, e.g. `(0, inf)` or `[0, 0.5)`.
    pub fn describe(&self) -> String {
        let lo = match self.min {
            Bound::Open => "(-inf".to_string(),
            Bound::Inclusive(v) => format!("[{}", fmt_float(v)),
            Bound::Exclusive(v) => format!("({}", fmt_float(v)),
        };
        let hi = match self.max {
            Bound::Open => "inf)".to_string(),
            Bound::Inclusive(v) => format!("{}]", fmt_float(v)),
            Bound::Exclusive(v) => format!("{})", fmt_float(v)),
        };
        format!("{lo}, {hi}")
    }
}

/// Everything the front ends need to know about one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamSpec {
    /// Name as in presets and `--set`.
    pub name: &'static str,
    /// Type.
    pub kind: ParamKind,
    /// Unit (SI), empty for non-dimensional values.
    pub unit: &'static str,
    /// One-line meaning, with the symbol and equation where the dissertation defines it.
    pub help: &'static str,
    /// Valid range for numbers (ignored for other kinds).
    pub range: Range,
}

impl ParamSpec {
    /// Parse the text a user typed into a TOML value of this parameter's type, checking the
    /// range. The error names the parameter.
    ///
    /// # Errors
    /// [`Error::ParseParameter`] for text of the wrong type, [`Error::InvalidParameter`] for a
    /// value out of range (NaN and infinities included).
    pub fn parse(&self, text: &str) -> Result<toml::Value> {
        let t = text.trim();
        let parse_err = || Error::ParseParameter {
            name: self.name.into(),
            expected: self.kind.expected(),
            text: text.into(),
        };
        let value = match self.kind {
            ParamKind::Float => toml::Value::Float(parse_float(t).ok_or_else(parse_err)?),
            ParamKind::Int => {
                let v: i64 = match t.replace('_', "").parse() {
                    Ok(v) => v,
                    // `1e6`, `2.0`: a whole number in another notation, as --describe prints
                    // ranges; exact below 2^53.
                    Err(_) => match parse_float(t) {
                        Some(x)
                            if x.is_finite() && x.fract() == 0.0 && x.abs() < 9.007_199_254_740_992e15 =>
                        {
                            x as i64
                        }
                        _ => return Err(parse_err()),
                    },
                };
                if v < 0 {
                    return Err(Error::invalid(self.name, v, "must not be negative"));
                }
                toml::Value::Integer(v)
            }
            ParamKind::Bool => match t.to_ascii_lowercase().as_str() {
                "true" | "yes" | "on" | "1" => toml::Value::Boolean(true),
                "false" | "no" | "off" | "0" => toml::Value::Boolean(false),
                _ => return Err(parse_err()),
            },
            ParamKind::Choice(options) => {
                if !options.contains(&t) {
                    return Err(parse_err());
                }
                toml::Value::String(t.into())
            }
            ParamKind::FloatList => {
                let t = t.trim_start_matches('[').trim_end_matches(']');
                let mut items = Vec::new();
                for part in t.split(',').map(str::trim).filter(|p| !p.is_empty()) {
                    items.push(toml::Value::Float(parse_float(part).ok_or_else(parse_err)?));
                }
                if items.is_empty() {
                    return Err(parse_err());
                }
                toml::Value::Array(items)
            }
            // Text parameters are file names: surrounding blanks are never meant ("   " is
            // no file, as "" is none), from the command line, the form or a preset alike.
            ParamKind::Text => toml::Value::String(t.into()),
        };
        self.check(&value)?;
        Ok(value)
    }

    /// Check a TOML value against the type and range.
    ///
    /// # Errors
    /// As [`ParamSpec::parse`].
    pub fn check(&self, value: &toml::Value) -> Result<()> {
        let wrong = || Error::ParseParameter {
            name: self.name.into(),
            expected: self.kind.expected(),
            text: value.to_string(),
        };
        let check_number = |x: f64| match self.range.violation(x) {
            Some(reason) => Err(Error::invalid(self.name, fmt_value(x), reason)),
            None => Ok(()),
        };
        match (self.kind, value) {
            (ParamKind::Float, toml::Value::Float(x)) => check_number(*x),
            (ParamKind::Float, toml::Value::Integer(i)) => check_number(*i as f64),
            (ParamKind::Int, toml::Value::Integer(i)) => {
                if *i < 0 {
                    Err(Error::invalid(self.name, i, "must not be negative"))
                } else {
                    check_number(*i as f64)
                }
            }
            (ParamKind::Bool, toml::Value::Boolean(_)) | (ParamKind::Text, toml::Value::String(_)) => Ok(()),
            (ParamKind::Choice(options), toml::Value::String(s)) if options.contains(&s.as_str()) => Ok(()),
            (ParamKind::FloatList, toml::Value::Array(items)) if !items.is_empty() => {
                for item in items {
                    match item {
                        toml::Value::Float(x) => check_number(*x)?,
                        toml::Value::Integer(i) => check_number(*i as f64)?,
                        _ => return Err(wrong()),
                    }
                }
                Ok(())
            }
            _ => Err(wrong()),
        }
    }
}

/// Parse a float, accepting `1e-6`, `1_000`, and rejecting NaN and infinities by returning them
/// (the range check then names them).
fn parse_float(t: &str) -> Option<f64> {
    let t = t.replace('_', "");
    let lower = t.to_ascii_lowercase();
    match lower.as_str() {
        "nan" | "+nan" | "-nan" => Some(f64::NAN),
        "inf" | "+inf" | "infinity" => Some(f64::INFINITY),
        "-inf" | "-infinity" => Some(f64::NEG_INFINITY),
        _ => lower.parse().ok(),
    }
}

/// A cross-field check of two parameters that bound an interval: `Ok` unless `lo >= hi`, then
/// [`Error::InvalidParameter`] naming `lo_name` with "must be below `hi_name`".
///
/// # Errors
/// As above.
pub fn require_below<T: PartialOrd + ToString>(lo_name: &str, lo: T, hi_name: &str, hi: T) -> Result<()> {
    if lo >= hi {
        return Err(Error::invalid(lo_name, lo, format!("must be below {hi_name}")));
    }
    Ok(())
}

/// A cross-field check of two parameters that bound an interval which may be a single point:
/// `Ok` unless `hi < lo`, then [`Error::InvalidParameter`] naming `hi_name` with "must not be
/// below `lo_name`".
///
/// # Errors
/// As above.
pub fn require_not_below<T: PartialOrd + ToString>(hi_name: &str, hi: T, lo_name: &str, lo: T) -> Result<()> {
    if hi < lo {
        return Err(Error::invalid(
            hi_name,
            hi,
            format!("must not be below {lo_name}"),
        ));
    }
    Ok(())
}

/// A check of a list parameter: `Ok` unless `values` is empty, then
/// [`Error::InvalidParameter`] naming `name` with "must not be empty".
///
/// # Errors
/// As above.
pub fn require_non_empty<T>(name: &str, values: &[T]) -> Result<()> {
    if values.is_empty() {
        return Err(Error::invalid(name, "[]", "must not be empty"));
    }
    Ok(())
}

/// Text from a file as every reader here takes it: a UTF-8 byte-order mark skipped, CRLF and
/// CR alone turned into LF (so that each line keeps its number), whatever wrote the file.
pub fn normalise_line_ends(text: &str) -> String {
    text.trim_start_matches('\u{feff}')
        .replace("\r\n", "\n")
        .replace('\r', "\n")
}

/// A TOML syntax error with its line and the key of that line: "line 3 (`radius`): invalid
/// float" (the parser's own message names neither for some errors, such as a duplicate key).
fn toml_error_at(text: &str, e: &toml::de::Error) -> String {
    let message = escape_for_message(e.message().trim(), 200);
    let Some(span) = e.span() else {
        return message;
    };
    let start = span.start.min(text.len());
    let line_no = text[..start].matches('\n').count() + 1;
    let line = text.lines().nth(line_no - 1).unwrap_or("");
    let key = line
        .split_once('=')
        .map(|(k, _)| k.trim().trim_matches('"'))
        .filter(|k| !k.is_empty());
    match key {
        Some(k) => format!("line {line_no} (`{}`): {message}", escape_for_message(k, 40)),
        None => format!("line {line_no}: {message}"),
    }
}

/// The text of a TOML value as the user would type it (the inverse of [`ParamSpec::parse`]).
pub fn value_text(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(x) => fmt_float(*x),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::String(s) => s.clone(),
        toml::Value::Array(items) => items.iter().map(value_text).collect::<Vec<_>>().join(", "),
        other => other.to_string(),
    }
}

/// Short float text: plain for moderate magnitudes, scientific otherwise.
pub fn fmt_float(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || (1e-3..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A parameter struct of a scene: serde data with defaults and a spec per field.
///
/// Implemented by [`scene_params!`]; do not implement by hand.
pub trait Params: Serialize + DeserializeOwned + Default + Clone + Send + Sync + 'static {
    /// One spec per field, in declaration order.
    fn specs() -> Vec<ParamSpec>;
}

/// The current values of a scene's parameters as TOML values, in spec order. This is what the
/// front ends edit; [`ParamValues::to_params`] turns it into the typed struct.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamValues {
    /// The scene id (for messages).
    pub scene: &'static str,
    /// Specs, in order.
    pub specs: Vec<ParamSpec>,
    /// Values, parallel to `specs`.
    pub values: Vec<toml::Value>,
    /// Reduced by quick mode (`SceneDyn::quick`): a failure then names what differs from the
    /// defaults in quick form, not the resolution quick mode itself set.
    pub quick: bool,
}

impl ParamValues {
    /// The values of a typed parameter struct.
    ///
    /// # Panics
    /// If the struct does not serialise to a TOML table with one entry per spec (a bug in the
    /// declaration, caught by the registry test).
    pub fn from_params<P: Params>(scene: &'static str, params: &P) -> Self {
        let specs = P::specs();
        let table = toml::Table::try_from(params).expect("scene params serialise to a TOML table");
        let values = specs
            .iter()
            .map(|s| table.get(s.name).cloned().expect("every spec names a field"))
            .collect();
        Self {
            scene,
            specs,
            values,
            quick: false,
        }
    }

    /// Index of a parameter, or an error with a suggestion.
    ///
    /// # Errors
    /// [`Error::UnknownParameter`].
    pub fn index(&self, name: &str) -> Result<usize> {
        self.specs
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| Error::UnknownParameter {
                name: name.into(),
                scene: self.scene.into(),
                hint: did_you_mean(name, self.specs.iter().map(|s| s.name)),
            })
    }

    /// The value of a parameter.
    pub fn get(&self, name: &str) -> Option<&toml::Value> {
        self.specs
            .iter()
            .position(|s| s.name == name)
            .map(|k| &self.values[k])
    }

    /// Set a parameter from user text (`--set name=value`, the form).
    ///
    /// # Errors
    /// Unknown name, unparsable text, value out of range.
    pub fn set_text(&mut self, name: &str, text: &str) -> Result<()> {
        let k = self.index(name)?;
        self.values[k] = self.specs[k].parse(text)?;
        Ok(())
    }

    /// Parse `name=value`.
    ///
    /// # Errors
    /// A missing `=`, or as [`ParamValues::set_text`].
    pub fn set_assignment(&mut self, assignment: &str) -> Result<()> {
        let Some((name, text)) = assignment.split_once('=') else {
            return Err(Error::ParseParameter {
                name: assignment.into(),
                expected: "name=value".into(),
                text: assignment.into(),
            });
        };
        self.set_text(name.trim(), text)
    }

    /// Apply a TOML table (a preset): every key must be a parameter, every value valid.
    ///
    /// # Errors
    /// Unknown keys (with a suggestion), wrong types, values out of range.
    pub fn apply_table(&mut self, table: &toml::Table) -> Result<()> {
        for (key, value) in table {
            let k = self.index(key)?;
            let spec = &self.specs[k];
            // Integers are accepted where floats are expected.
            let value = match (spec.kind, value) {
                (ParamKind::Float, toml::Value::Integer(i)) => toml::Value::Float(*i as f64),
                (ParamKind::FloatList, toml::Value::Array(items)) => toml::Value::Array(
                    items
                        .iter()
                        .map(|v| match v {
                            toml::Value::Integer(i) => toml::Value::Float(*i as f64),
                            other => other.clone(),
                        })
                        .collect(),
                ),
                (ParamKind::Text, toml::Value::String(text)) => toml::Value::String(text.trim().into()),
                _ => value.clone(),
            };
            spec.check(&value)?;
            self.values[k] = value;
        }
        Ok(())
    }

    /// Load and apply a preset file.
    ///
    /// # Errors
    /// [`Error::Preset`] naming the file for unreadable or invalid TOML, unknown keys and
    /// invalid values.
    pub fn apply_preset_file(&mut self, path: &std::path::Path) -> Result<()> {
        let preset_err = |message: String| Error::Preset {
            path: path.to_path_buf(),
            message,
        };
        let text = crate::input::read_text(path).map_err(|e| match e {
            Error::DataFile { message, .. } => preset_err(message),
            other => preset_err(other.to_string()),
        })?;
        // As the data files: a UTF-8 byte-order mark is skipped, CRLF and CR alone end lines.
        let text = normalise_line_ends(&text);
        let table: toml::Table = toml::from_str(&text).map_err(|e| preset_err(toml_error_at(&text, &e)))?;
        self.apply_table(&table).map_err(|e| preset_err(e.to_string()))
    }

    /// The values as a TOML table.
    pub fn to_table(&self) -> toml::Table {
        self.specs
            .iter()
            .zip(&self.values)
            .map(|(s, v)| (s.name.to_string(), v.clone()))
            .collect()
    }

    /// The typed parameter struct.
    ///
    /// # Errors
    /// When the values do not deserialise (cannot happen for values that passed
    /// [`ParamSpec::check`], but reported rather than assumed).
    pub fn to_params<P: Params>(&self) -> Result<P> {
        for (s, v) in self.specs.iter().zip(&self.values) {
            s.check(v)?;
        }
        toml::Value::Table(self.to_table())
            .try_into()
            .map_err(|e: toml::de::Error| Error::Preset {
                path: std::path::PathBuf::from(self.scene),
                message: e.message().to_string(),
            })
    }

    /// The values as a preset file: a commented TOML document (unit and help per line).
    pub fn to_preset_text(&self, header: &str) -> String {
        let mut out = String::new();
        for line in header.lines() {
            out.push_str("# ");
            out.push_str(line);
            out.push('\n');
        }
        for (s, v) in self.specs.iter().zip(&self.values) {
            let value = match v {
                toml::Value::Float(x) => toml_float(*x),
                toml::Value::Array(items) => format!(
                    "[{}]",
                    items
                        .iter()
                        .map(|i| match i {
                            toml::Value::Float(x) => toml_float(*x),
                            other => other.to_string(),
                        })
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                other => other.to_string(),
            };
            let unit = if s.unit.is_empty() { "-" } else { s.unit };
            out.push_str(&format!("{} = {}  # [{}] {}\n", s.name, value, unit, s.help));
        }
        out
    }
}

/// A float as TOML text that reads back as a float.
fn toml_float(x: f64) -> String {
    let t = fmt_float(x);
    if t.contains(['.', 'e', 'E', 'i', 'n']) {
        t
    } else {
        format!("{t}.0")
    }
}

/// Conversion of a field type to its [`ParamKind`].
pub trait ParamType {
    /// The kind of this type.
    const KIND: ParamKind;
}
impl ParamType for f64 {
    const KIND: ParamKind = ParamKind::Float;
}
impl ParamType for usize {
    const KIND: ParamKind = ParamKind::Int;
}
impl ParamType for u64 {
    const KIND: ParamKind = ParamKind::Int;
}
impl ParamType for bool {
    const KIND: ParamKind = ParamKind::Bool;
}
impl ParamType for String {
    const KIND: ParamKind = ParamKind::Text;
}
impl ParamType for Vec<f64> {
    const KIND: ParamKind = ParamKind::FloatList;
}

/// Declare a scene's parameter struct, its defaults and its specs in one place.
///
/// Each entry is a parameter of the scene's own (`name: type = default, unit = …, range = …;`)
/// or a [`param_group!`] shared with other scenes (`group field: Group;`). A group's parameters
/// keep their flat names in `--set`, presets, `--describe`, the form and the JSON (the group
/// is a `#[serde(flatten)]` field); the scene reaches them as `p.field.name`. A scene that
/// needs other defaults gives them in braces after the group (`group tip: ElasticTip
/// { radius: 5.0e-6 };`): the declaration (unit, range) stays the group's. A scene whose help
/// line says more than the group's (a note on the scene's own figure) gives it after the
/// defaults (`help { youngs_modulus: "…" }`); such lines are listed, each with its reason, in
/// the registry test that keeps one unit, range and help per parameter name. A single parameter
/// of a group, where the scene does not take the whole group, is `from Group: name: type;`
/// (`from Group: name: type = default;` with the scene's default).
///
/// ```
/// adhesion::param_group! {
///     /// An elastic sphere.
///     pub struct Sphere {
///         /// Sphere radius R.
///         radius: f64 = 1.0e-6, unit = "m", range = adhesion::params::Range::positive();
///     }
/// }
/// adhesion::scene_params! {
///     /// Parameters of an example scene.
///     pub struct ExampleParams {
///         /// The sphere.
///         group sphere: Sphere { radius: 2.0e-6 };
///         /// Number of points on each curve.
///         points: usize = 200, unit = "", range = adhesion::params::Range::between(10.0, 1e5);
///     }
/// }
/// use adhesion::params::Params;
/// assert_eq!(ExampleParams::default().points, 200);
/// assert_eq!(ExampleParams::default().sphere.radius, 2.0e-6);
/// assert_eq!(ExampleParams::specs()[0].name, "radius");
/// assert_eq!(ExampleParams::specs()[0].unit, "m");
/// ```
#[macro_export]
macro_rules! scene_params {
    (
        $(#[$meta:meta])*
        pub struct $name:ident { $($body:tt)* }
    ) => {
        $crate::scene_params!(@entry [$(#[$meta])*] $name [] [] [] [] $($body)*);
    };
    // A shared group, flattened into the scene's parameters, with the scene's own defaults.
    (@entry $metas:tt $name:ident [$($fields:tt)*] [$($defaults:tt)*] [$($specs:tt)*] [$($groups:tt)*]
        #[doc = $doc:literal]
        group $field:ident : $group:ident $({ $($key:ident : $value:expr),* $(,)? })?
            $(help { $($help_key:ident : $help:literal),* $(,)? })? ;
        $($rest:tt)*
    ) => {
        $crate::scene_params!(@entry $metas $name
            [$($fields)* #[doc = $doc] #[serde(flatten)] pub $field: $group,]
            [$($defaults)* $field: {
                // A group of one parameter given its default has nothing left to update.
                #[allow(clippy::needless_update)]
                let group = $group { $($($key: $value,)*)? ..<$group as Default>::default() };
                group
            },]
            [$($specs)* {
                #[allow(unused_mut)]
                let mut group = <$group as $crate::params::Params>::specs();
                $($(
                    let _: fn(&$group) = |g| { let _ = &g.$help_key; };
                    for s in group.iter_mut().filter(|s| s.name == stringify!($help_key)) {
                        s.help = $help;
                    }
                )*)?
                group
            }]
            [$($groups)* $field]
            $($rest)*
        );
    };
    // One parameter of a group, declared there, where the scene does not take the whole
    // group (its other parameters do not apply, or stand elsewhere in the scene's order).
    (@entry $metas:tt $name:ident [$($fields:tt)*] [$($defaults:tt)*] [$($specs:tt)*] [$($groups:tt)*]
        from $group:ident : $field:ident : $ty:ty $(= $default:expr)? $(, help = $help:literal)? ;
        $($rest:tt)*
    ) => {
        $crate::scene_params!(@entry $metas $name
            [$($fields)*
                #[doc = concat!("[`", stringify!($group), "::", stringify!($field), "`], declared there.")]
                pub $field: $ty,
            ]
            [$($defaults)* $field: $crate::scene_params!(@or [$($default)?] [<$group as Default>::default().$field]),]
            [$($specs)* {
                #[allow(unused_mut)]
                let mut spec = <$group as $crate::params::Params>::specs()
                    .into_iter()
                    .find(|s| s.name == stringify!($field))
                    .expect("a group declares a spec per field");
                $(spec.help = $help;)?
                vec![spec]
            }]
            [$($groups)*]
            $($rest)*
        );
    };
    // A parameter of the scene's own.
    (@entry $metas:tt $name:ident [$($fields:tt)*] [$($defaults:tt)*] [$($specs:tt)*] [$($groups:tt)*]
        #[doc = $doc:literal]
        $field:ident : $ty:ty = $default:expr, unit = $unit:literal, range = $range:expr;
        $($rest:tt)*
    ) => {
        $crate::scene_params!(@entry $metas $name
            [$($fields)* #[doc = $doc] #[doc = concat!("\n\nUnit: `", $unit, "`.")] pub $field: $ty,]
            [$($defaults)* $field: $default,]
            [$($specs)* {
                vec![$crate::params::ParamSpec {
                    name: stringify!($field),
                    kind: <$ty as $crate::params::ParamType>::KIND,
                    unit: $unit,
                    help: $doc.trim_ascii(),
                    range: $range,
                }]
            }]
            [$($groups)*]
            $($rest)*
        );
    };
    // Without groups: unknown and missing keys are caught by serde as well.
    (@entry [$(#[$meta:meta])*] $name:ident [$($fields:tt)*] [$($defaults:tt)*] [$($specs:tt)*] []) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct $name { $($fields)* }
        $crate::scene_params!(@impls $name [$($defaults)*] [$($specs)*]);
    };
    // With groups (serde cannot deny unknown keys beside a flattened field; the keys are
    // checked against the specs before they reach serde, `ParamValues::apply_table`).
    (@entry [$(#[$meta:meta])*] $name:ident [$($fields:tt)*] [$($defaults:tt)*] [$($specs:tt)*] [$($groups:tt)+]) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        pub struct $name { $($fields)* }
        $crate::scene_params!(@impls $name [$($defaults)*] [$($specs)*]);
    };
    (@or [$value:expr] [$fallback:expr]) => { $value };
    (@or [] [$fallback:expr]) => { $fallback };
    (@impls $name:ident [$($defaults:tt)*] [$($specs:tt)*]) => {
        impl Default for $name {
            fn default() -> Self {
                Self { $($defaults)* }
            }
        }

        impl $crate::params::Params for $name {
            fn specs() -> Vec<$crate::params::ParamSpec> {
                let mut specs = Vec::new();
                $(specs.extend($specs);)*
                specs
            }
        }
    };
}

/// Declare a parameter group: physical parameters that several scenes share (an interaction,
/// an elastic tip, a loading path, a discretisation), with their names, units, defaults,
/// ranges and help, once. A scene takes the group with `group field: Group;` in
/// [`scene_params!`]; the group's parameters keep their flat names.
///
/// Every key must be present when a group is read (no serde defaults: a missing key would
/// silently take the group's default instead of the scene's).
#[macro_export]
macro_rules! param_group {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(
                #[doc = $doc:literal]
                $field:ident : $ty:ty = $default:expr, unit = $unit:literal, range = $range:expr;
            )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        pub struct $name {
            $(
                #[doc = $doc]
                #[doc = concat!("\n\nUnit: `", $unit, "`.")]
                pub $field: $ty,
            )*
        }

        impl Default for $name {
            fn default() -> Self {
                Self { $($field: $default,)* }
            }
        }

        impl $crate::params::Params for $name {
            fn specs() -> Vec<$crate::params::ParamSpec> {
                vec![$(
                    $crate::params::ParamSpec {
                        name: stringify!($field),
                        kind: <$ty as $crate::params::ParamType>::KIND,
                        unit: $unit,
                        help: $doc.trim_ascii(),
                        range: $range,
                    },
                )*]
            }
        }
    };
}

/// Declare a closed set of words as a parameter type (a [`ParamKind::Choice`]).
///
/// ```
/// adhesion::param_choice! {
///     /// How the loss per asperity is computed.
///     pub enum LossMethod { Exact = "exact", Empirical = "empirical" }
/// }
/// assert_eq!(LossMethod::Exact.as_str(), "exact");
/// ```
#[macro_export]
macro_rules! param_choice {
    (
        $(#[$meta:meta])*
        pub enum $name:ident { $first:ident = $first_text:literal $(, $variant:ident = $text:literal)* $(,)? }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
        pub enum $name {
            #[doc = concat!("`", $first_text, "`")]
            #[serde(rename = $first_text)]
            $first,
            $(
                #[doc = concat!("`", $text, "`")]
                #[serde(rename = $text)]
                $variant,
            )*
        }

        impl $name {
            /// The word the user types.
            pub fn as_str(self) -> &'static str {
                match self {
                    $name::$first => $first_text,
                    $($name::$variant => $text,)*
                }
            }
        }

        impl Default for $name {
            fn default() -> Self {
                $name::$first
            }
        }

        impl $crate::params::ParamType for $name {
            const KIND: $crate::params::ParamKind =
                $crate::params::ParamKind::Choice(&[$first_text $(, $text)*]);
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    crate::scene_params! {
        /// Test parameters.
        pub struct TestParams {
            /// Modulus E*.
            modulus: f64 = 1.0e6, unit = "Pa", range = Range::positive();
            /// Points.
            points: usize = 10, unit = "", range = Range::between(2.0, 100.0);
            /// Values.
            levels: Vec<f64> = vec![1.0, 2.0], unit = "nm", range = Range::non_negative();
            /// Flag.
            exact: bool = true, unit = "", range = Range::any();
        }
    }

    fn values() -> ParamValues {
        ParamValues::from_params("test", &TestParams::default())
    }

    #[test]
    fn text_round_trip_and_errors_name_the_parameter() {
        let mut v = values();
        v.set_text("modulus", "2e6").unwrap();
        v.set_text("levels", "1, 2.5, 3").unwrap();
        let p: TestParams = v.to_params().unwrap();
        assert_eq!(p.modulus, 2e6);
        assert_eq!(p.levels, vec![1.0, 2.5, 3.0]);

        let e = v.set_text("modulus", "-1").unwrap_err().to_string();
        assert_eq!(e, "invalid parameter `modulus` = -1: must be positive");
        let e = v.set_text("modulus", "abc").unwrap_err().to_string();
        assert_eq!(e, "parameter `modulus` expects a number, got `abc`");
        let e = v.set_text("modulus", "NaN").unwrap_err().to_string();
        assert_eq!(e, "invalid parameter `modulus` = NaN: must be a finite number");
        let e = v.set_text("points", "1").unwrap_err().to_string();
        assert_eq!(e, "invalid parameter `points` = 1: must be in [2, 100]");
        let e = v.set_text("modulos", "1").unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown parameter `modulos` for scene test (did you mean `modulus`?)"
        );
        // The failed assignments kept the last valid values.
        assert_eq!(v.to_params::<TestParams>().unwrap().modulus, 2e6);
    }

    #[test]
    fn preset_text_reads_back_to_the_same_values() {
        let mut v = values();
        v.set_text("modulus", "3").unwrap();
        let text = v.to_preset_text("header");
        let table: toml::Table = toml::from_str(&text).unwrap();
        let mut w = values();
        w.apply_table(&table).unwrap();
        assert_eq!(v, w);
    }
}
