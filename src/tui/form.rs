//! The parameter form of one scene: the text of every field as the user typed it, the last
//! valid parameter set, and the validation of both as the user types.
//!
//! Every change re-parses all fields with [`ParamSpec::parse`] (types and ranges) and, when all
//! of them parse, checks the whole set with [`SceneDyn::validate`] (cross-field checks). Only a
//! set that passes both replaces the last valid one; an invalid field keeps its text, is shown
//! with its error, and blocks running. Nothing here panics on user input.

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use crate::error::Error;
use crate::params::{ParamKind, ParamSpec, ParamValues, fmt_float, value_text};
use crate::scenes::SceneDyn;

/// A one-line text editor with a cursor (counted in characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LineEdit {
    text: String,
    cursor: usize,
}

impl LineEdit {
    /// An editor holding `text`, cursor at the end.
    pub fn new(text: impl Into<String>) -> Self {
        let text = text.into();
        let cursor = text.chars().count();
        Self { text, cursor }
    }

    /// The text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Cursor position in characters from the start.
    pub fn cursor(&self) -> usize {
        self.cursor
    }

    fn byte_index(&self, chars: usize) -> usize {
        self.text
            .char_indices()
            .nth(chars)
            .map_or(self.text.len(), |(i, _)| i)
    }

    /// Apply an editing key: characters, Backspace, Delete, Left, Right, Home, End, Ctrl-U
    /// (clear). Returns whether the text changed.
    pub fn handle(&mut self, key: KeyEvent) -> bool {
        let len = self.text.chars().count();
        let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
        match key.code {
            KeyCode::Char('u') if ctrl => {
                self.text.clear();
                self.cursor = 0;
                true
            }
            KeyCode::Char('a') if ctrl => {
                self.cursor = 0;
                false
            }
            KeyCode::Char('e') if ctrl => {
                self.cursor = len;
                false
            }
            KeyCode::Char(c) if !ctrl && !key.modifiers.contains(KeyModifiers::ALT) => {
                let at = self.byte_index(self.cursor);
                self.text.insert(at, c);
                self.cursor += 1;
                true
            }
            KeyCode::Backspace if self.cursor > 0 => {
                let at = self.byte_index(self.cursor - 1);
                self.text.remove(at);
                self.cursor -= 1;
                true
            }
            KeyCode::Delete if self.cursor < len => {
                let at = self.byte_index(self.cursor);
                self.text.remove(at);
                true
            }
            KeyCode::Left => {
                self.cursor = self.cursor.saturating_sub(1);
                false
            }
            KeyCode::Right => {
                self.cursor = (self.cursor + 1).min(len);
                false
            }
            KeyCode::Home => {
                self.cursor = 0;
                false
            }
            KeyCode::End => {
                self.cursor = len;
                false
            }
            _ => false,
        }
    }
}

/// The parameter form of one scene.
pub struct Form {
    scene: &'static dyn SceneDyn,
    texts: Vec<String>,
    errors: Vec<Option<String>>,
    cross_error: Option<String>,
    valid: ParamValues,
    defaults: ParamValues,
    selected: usize,
    edit: Option<LineEdit>,
}

impl std::fmt::Debug for Form {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Form")
            .field("scene", &self.scene.info().id)
            .field("texts", &self.texts)
            .field("errors", &self.errors)
            .field("cross_error", &self.cross_error)
            .field("selected", &self.selected)
            .finish()
    }
}

/// The factor a number is stepped by ([`Form::nudge`]) unless its parameter declares a step.
pub const NUDGE_FACTOR: f64 = 1.1;

/// A parameter's own step for nudging ([`NUDGE_STEPS`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NudgeStep {
    /// Add or subtract this (a value that may be zero or negative, or whose natural steps are
    /// even: degrees, exponents, seeds).
    Linear(f64),
    /// Multiply or divide by this (a quantity spanning decades).
    Factor(f64),
}

/// Declared nudge steps, by parameter name (a name means one physical parameter in every
/// scene); the others step by [`NUDGE_FACTOR`].
pub const NUDGE_STEPS: &[(&str, NudgeStep)] = &[
    ("peel_angle", NudgeStep::Linear(5.0)),
    ("poisson_ratio", NudgeStep::Linear(0.05)),
    ("stiffness_exponent", NudgeStep::Linear(1.0)),
    ("amplitude_ratio_1", NudgeStep::Linear(0.0025)),
    ("amplitude_ratio_2", NudgeStep::Linear(0.0025)),
    ("amplitude_ratio_3", NudgeStep::Linear(0.0025)),
    ("min_separation_ho", NudgeStep::Linear(0.1)),
    ("start_separation_ho", NudgeStep::Linear(0.5)),
    ("seed", NudgeStep::Linear(1.0)),
    // Ten steps a decade.
    ("roughness", NudgeStep::Factor(1.258_925_411_794_167_2)),
];

/// The declared nudge step of parameter `name`, if any.
pub fn nudge_step(name: &str) -> Option<NudgeStep> {
    NUDGE_STEPS.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// `x` rounded to `digits` significant digits (so that steps by 1.1 read `1.331e-5`, not
/// `1.3310000000000003e-5`).
fn round_significant(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

impl Form {
    /// The form of `scene`, filled with its defaults.
    pub fn new(scene: &'static dyn SceneDyn) -> Self {
        let valid = scene.defaults();
        let n = valid.specs.len();
        let mut form = Self {
            scene,
            texts: vec![String::new(); n],
            errors: vec![None; n],
            cross_error: None,
            valid: valid.clone(),
            defaults: valid.clone(),
            selected: 0,
            edit: None,
        };
        form.load(valid);
        form
    }

    /// The scene.
    pub fn scene(&self) -> &'static dyn SceneDyn {
        self.scene
    }

    /// The specs, in order.
    pub fn specs(&self) -> &[ParamSpec] {
        &self.valid.specs
    }

    /// Number of fields.
    pub fn len(&self) -> usize {
        self.texts.len()
    }

    /// Whether the scene has no parameters.
    pub fn is_empty(&self) -> bool {
        self.texts.is_empty()
    }

    /// The last valid parameter set (what a run uses).
    pub fn values(&self) -> &ParamValues {
        &self.valid
    }

    /// The text of field `k` as shown (the editor's text while editing).
    pub fn text(&self, k: usize) -> &str {
        match (&self.edit, k == self.selected) {
            (Some(e), true) => e.text(),
            _ => &self.texts[k],
        }
    }

    /// The error of field `k`, if its text is invalid.
    pub fn error(&self, k: usize) -> Option<&str> {
        self.errors.get(k).and_then(|e| e.as_deref())
    }

    /// A problem of the whole set (a failed cross-field check), if any.
    pub fn cross_error(&self) -> Option<&str> {
        self.cross_error.as_deref()
    }

    /// Whether every field is valid and the set passes the scene's checks.
    pub fn is_valid(&self) -> bool {
        self.cross_error.is_none() && self.errors.iter().all(Option::is_none)
    }

    /// The first problem, for the status bar.
    pub fn first_error(&self) -> Option<&str> {
        self.errors
            .iter()
            .flatten()
            .map(String::as_str)
            .next()
            .or(self.cross_error.as_deref())
    }

    /// Whether field `k`'s valid value differs from the scene's default.
    pub fn is_changed(&self, k: usize) -> bool {
        self.valid.values.get(k) != self.defaults.values.get(k)
    }

    /// The selected field.
    pub fn selected(&self) -> usize {
        self.selected
    }

    /// The editor of the selected field, while editing.
    pub fn editor(&self) -> Option<&LineEdit> {
        self.edit.as_ref()
    }

    /// Select the next (`+1`) or previous (`-1`) field, wrapping; ends editing.
    pub fn move_selection(&mut self, step: isize) {
        if self.is_empty() {
            return;
        }
        self.finish_edit();
        let n = self.len() as isize;
        self.selected = (self.selected as isize + step).rem_euclid(n) as usize;
    }

    /// Replace every field by `values` (a loaded preset, the defaults) and validate.
    pub fn load(&mut self, values: ParamValues) {
        self.edit = None;
        self.texts = values.values.iter().map(value_text).collect();
        self.valid = values;
        self.revalidate();
    }

    /// Reset every field to the scene's defaults.
    pub fn reset(&mut self) {
        self.load(self.defaults.clone());
    }

    /// Set the text of field `k` and validate.
    pub fn set_text(&mut self, k: usize, text: &str) {
        if k < self.len() {
            self.texts[k] = text.to_string();
            if k == self.selected
                && let Some(e) = &mut self.edit
            {
                *e = LineEdit::new(text);
            }
            self.revalidate();
        }
    }

    /// Start editing the selected field.
    pub fn start_edit(&mut self) {
        if !self.is_empty() {
            self.edit = Some(LineEdit::new(self.texts[self.selected].clone()));
        }
    }

    /// Feed a key to the editor; validates after every change. Returns whether the text changed.
    pub fn edit_key(&mut self, key: KeyEvent) -> bool {
        let Some(e) = &mut self.edit else {
            return false;
        };
        let changed = e.handle(key);
        if changed {
            self.texts[self.selected] = e.text().to_string();
            self.revalidate();
        }
        changed
    }

    /// Stop editing and keep the text (valid or not: an invalid one stays marked).
    pub fn finish_edit(&mut self) {
        self.edit = None;
    }

    /// Stop editing and put back the text of the last valid value.
    pub fn cancel_edit(&mut self) {
        if self.edit.take().is_some() {
            self.texts[self.selected] = value_text(&self.valid.values[self.selected]);
            self.revalidate();
        }
    }

    /// Step the selected field up or down, as a slider would: by its declared step
    /// ([`NUDGE_STEPS`]: added, or a factor), else a number by the factor [`NUDGE_FACTOR`] (its
    /// magnitude grows when `up` for a positive value, the value grows for a negative one), an
    /// integer by about a tenth of it (at least 1), a choice or a flag to its next option.
    /// Returns the new text, or why the field cannot be stepped (zero cannot be scaled; a step
    /// out of the range is refused, the value kept).
    ///
    /// # Errors
    /// One line naming the parameter.
    pub fn nudge(&mut self, up: bool) -> std::result::Result<String, String> {
        let Some(spec) = self.valid.specs.get(self.selected).cloned() else {
            return Err("no parameter to step".into());
        };
        let value = &self.valid.values[self.selected];
        let sign = if up { 1.0 } else { -1.0 };
        let text = match (spec.kind, value, nudge_step(spec.name)) {
            (ParamKind::Float, toml::Value::Float(x), Some(NudgeStep::Linear(d))) => {
                let y = round_significant(x + sign * d, 9);
                // No 1e-17 left where the steps meet zero.
                fmt_float(if y.abs() < 1e-9 * d { 0.0 } else { y })
            }
            (ParamKind::Int, toml::Value::Integer(i), Some(NudgeStep::Linear(d))) => {
                (i + sign as i64 * (d.round() as i64).max(1)).to_string()
            }
            (ParamKind::Float, toml::Value::Float(x), Some(NudgeStep::Factor(f))) if *x != 0.0 => {
                fmt_float(round_significant(x * f.powf(sign), 6))
            }
            (ParamKind::Float, toml::Value::Float(x), _) => {
                if *x == 0.0 {
                    return Err(format!("{} is 0: type a value to step from (Enter)", spec.name));
                }
                let factor = if up == (*x > 0.0) {
                    NUDGE_FACTOR
                } else {
                    1.0 / NUDGE_FACTOR
                };
                fmt_float(round_significant(x * factor, 6))
            }
            (ParamKind::Int, toml::Value::Integer(i), _) => {
                let step = (i.abs() / 10).max(1);
                (if up { i + step } else { i - step }).to_string()
            }
            (ParamKind::Bool | ParamKind::Choice(_), _, _) => {
                self.cycle();
                return Ok(self.texts[self.selected].clone());
            }
            _ => return Err(format!("{} is not a number: Enter edits it", spec.name)),
        };
        if let Err(e) = spec.parse(&text) {
            return Err(format!("not stepped: {e}"));
        }
        self.edit = None;
        self.set_text(self.selected, &text);
        Ok(text)
    }

    /// For a choice or a flag: the next option of the selected field. Returns whether the
    /// field is of such a kind.
    pub fn cycle(&mut self) -> bool {
        if self.is_empty() {
            return false;
        }
        let k = self.selected;
        let current = self.texts[k].trim().to_string();
        let next = match self.valid.specs[k].kind {
            ParamKind::Bool => match current.to_ascii_lowercase().as_str() {
                "true" | "yes" | "on" | "1" => "false".to_string(),
                _ => "true".to_string(),
            },
            ParamKind::Choice(options) => {
                let at = options.iter().position(|o| *o == current);
                options[at.map_or(0, |i| (i + 1) % options.len())].to_string()
            }
            _ => return false,
        };
        self.edit = None;
        self.set_text(k, &next);
        true
    }

    /// Parse every field; if all parse, check the set; keep it if it passes.
    fn revalidate(&mut self) {
        let mut candidate = self.valid.clone();
        for (k, text) in self.texts.iter().enumerate() {
            match candidate.specs[k].parse(text) {
                Ok(v) => {
                    candidate.values[k] = v;
                    self.errors[k] = None;
                }
                Err(e) => self.errors[k] = Some(e.to_string()),
            }
        }
        self.cross_error = None;
        if self.errors.iter().any(Option::is_some) {
            return;
        }
        match self.scene.validate(&candidate) {
            Ok(()) => self.valid = candidate,
            Err(e) => {
                let message = e.to_string();
                if let Error::InvalidParameter { name, .. } = &e
                    && let Some(k) = candidate.specs.iter().position(|s| s.name == name)
                {
                    self.errors[k] = Some(message.clone());
                }
                self.cross_error = Some(message);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    fn key(code: KeyCode) -> KeyEvent {
        KeyEvent::new(code, KeyModifiers::NONE)
    }

    fn form() -> Form {
        Form::new(scenes::find("fig1.1").expect("fig1.1 is registered"))
    }

    fn index(f: &Form, name: &str) -> usize {
        f.specs()
            .iter()
            .position(|s| s.name == name)
            .expect("field exists")
    }

    #[test]
    fn line_edit_inserts_deletes_and_moves_by_characters() {
        let mut e = LineEdit::new("1e-6");
        e.handle(key(KeyCode::Home));
        assert!(e.handle(key(KeyCode::Char('2'))));
        assert_eq!(e.text(), "21e-6");
        e.handle(key(KeyCode::End));
        assert!(e.handle(key(KeyCode::Backspace)));
        assert_eq!(e.text(), "21e-");
        e.handle(key(KeyCode::Left));
        e.handle(key(KeyCode::Left));
        assert!(e.handle(key(KeyCode::Delete)));
        assert_eq!(e.text(), "21-");
        // Multi-byte characters move and delete as one.
        let mut e = LineEdit::new("µm");
        e.handle(key(KeyCode::Left));
        assert!(e.handle(key(KeyCode::Backspace)));
        assert_eq!(e.text(), "m");
        assert!(!e.handle(key(KeyCode::Backspace)));
        assert!(e.handle(KeyEvent::new(KeyCode::Char('u'), KeyModifiers::CONTROL)));
        assert_eq!(e.text(), "");
    }

    #[test]
    fn typing_validates_each_keystroke_and_keeps_the_last_valid_set() {
        let mut f = form();
        let k = index(&f, "modulus");
        while f.selected() != k {
            f.move_selection(1);
        }
        f.start_edit();
        f.edit_key(KeyEvent::new(KeyCode::Char('u'), KeyModifiers::CONTROL));
        // Empty text: not a number.
        assert!(!f.is_valid());
        for c in "-2e6".chars() {
            f.edit_key(key(KeyCode::Char(c)));
        }
        assert_eq!(
            f.error(k),
            Some("invalid parameter `modulus` = -2000000: must be positive")
        );
        assert!(!f.is_valid());
        // The run values are still the defaults.
        assert_eq!(f.values().get("modulus"), Some(&toml::Value::Float(1.0e6)));
        // Remove the sign: valid again, and the new value is taken.
        f.edit_key(key(KeyCode::Home));
        f.edit_key(key(KeyCode::Delete));
        assert!(f.is_valid(), "{:?}", f.first_error());
        assert_eq!(f.values().get("modulus"), Some(&toml::Value::Float(2.0e6)));
        f.finish_edit();
        assert_eq!(f.text(k), "2e6");
    }

    #[test]
    fn non_numbers_and_nan_are_marked_and_escape_restores_the_valid_text() {
        let mut f = form();
        let k = index(&f, "radius");
        while f.selected() != k {
            f.move_selection(1);
        }
        f.set_text(k, "abc");
        assert_eq!(f.error(k), Some("parameter `radius` expects a number, got `abc`"));
        f.set_text(k, "NaN");
        assert_eq!(
            f.error(k),
            Some("invalid parameter `radius` = NaN: must be a finite number")
        );
        assert_eq!(f.first_error(), f.error(k));
        f.start_edit();
        f.edit_key(key(KeyCode::Char('x')));
        f.cancel_edit();
        assert!(f.is_valid());
        assert_eq!(f.text(k), value_text(&toml::Value::Float(10.0e-6)));
    }

    #[test]
    fn choices_cycle_through_their_options_and_reset_restores_defaults() {
        let mut f = form();
        let k = index(&f, "units");
        while f.selected() != k {
            f.move_selection(1);
        }
        assert_eq!(f.text(k), "normalized");
        assert!(!f.is_changed(k));
        assert!(f.cycle());
        assert_eq!(f.text(k), "si");
        assert!(f.is_changed(k));
        assert_eq!(f.values().get("units"), Some(&toml::Value::String("si".into())));
        assert!(f.cycle());
        assert_eq!(f.text(k), "normalized");
        f.set_text(index(&f, "points"), "3");
        assert!(!f.is_valid());
        f.reset();
        assert!(f.is_valid());
        assert_eq!(f.values(), &f.scene().defaults());
        // A number field does not cycle.
        let r = index(&f, "radius");
        while f.selected() != r {
            f.move_selection(1);
        }
        assert!(!f.cycle());
        assert!(f.is_valid());
    }

    crate::scene_params! {
        /// Parameters of a scene with a cross-field check.
        pub struct SpanParams {
            /// Lower end.
            lo: f64 = 1.0, unit = "m", range = crate::params::Range::positive();
            /// Upper end, above the lower.
            hi: f64 = 2.0, unit = "m", range = crate::params::Range::positive();
        }
    }

    crate::scene! {
        struct Span {
            id: "span",
            chapter: "1",
            params: SpanParams,
            title: "span",
            caption: "a scene with lo < hi",
            results: &[],
        }
    }

    impl crate::scenes::Scene for Span {
        fn validate(p: &SpanParams) -> crate::error::Result<()> {
            if p.lo < p.hi {
                Ok(())
            } else {
                Err(Error::invalid("hi", p.hi, format!("must exceed lo = {}", p.lo)))
            }
        }

        fn run(_: &SpanParams, _: &crate::job::Job) -> crate::error::Result<crate::figure::Figure> {
            Ok(crate::figure::Figure::new("span", "span"))
        }
    }

    static SPAN: crate::scenes::Registered<Span> = crate::scenes::Registered::<Span>::NEW;

    #[test]
    fn cross_field_checks_mark_the_named_field_and_clear_when_either_field_is_fixed() {
        let mut f = Form::new(&SPAN);
        f.set_text(0, "3");
        assert!(!f.is_valid());
        assert_eq!(f.error(0), None);
        assert_eq!(f.error(1), Some("invalid parameter `hi` = 2: must exceed lo = 3"));
        assert_eq!(f.cross_error(), f.error(1));
        // The run values are the last valid set.
        assert_eq!(f.values().get("lo"), Some(&toml::Value::Float(1.0)));
        // Fixing the other field makes the whole set valid, with both new values.
        f.set_text(1, "4");
        assert!(f.is_valid(), "{:?}", f.first_error());
        assert_eq!(f.values().get("lo"), Some(&toml::Value::Float(3.0)));
        assert_eq!(f.values().get("hi"), Some(&toml::Value::Float(4.0)));
    }

    #[test]
    fn declared_steps_add_or_multiply_and_every_declared_name_is_a_parameter() {
        let names: Vec<&str> = scenes::all()
            .iter()
            .flat_map(|s| s.specs().into_iter().map(|p| p.name))
            .collect();
        for (name, _) in NUDGE_STEPS {
            assert!(names.contains(name), "{name} is no scene's parameter");
        }
        // Linear: A/λ steps from 0 (a factor could not), back to 0 exactly, and not below
        // its range.
        let mut f = Form::new(scenes::find("fig4.9b").expect("fig4.9b is registered"));
        f.selected = index(&f, "amplitude_ratio_1");
        assert_eq!(f.nudge(true).as_deref(), Ok("0.0025"));
        assert_eq!(f.nudge(true).as_deref(), Ok("0.005"));
        assert_eq!(f.nudge(false).as_deref(), Ok("0.0025"));
        assert_eq!(f.nudge(false).as_deref(), Ok("0"));
        assert!(f.nudge(false).is_err(), "below the range");
        // Linear in degrees.
        let mut f = Form::new(scenes::find("fig6.2").expect("fig6.2 is registered"));
        f.selected = index(&f, "peel_angle");
        assert_eq!(f.nudge(false).as_deref(), Ok("85"));
        // Undeclared: ×1.1.
        let mut f = form();
        f.selected = index(&f, "radius");
        let before = f
            .values()
            .get("radius")
            .and_then(toml::Value::as_float)
            .expect("radius");
        let after: f64 = f.nudge(true).expect("stepped").parse().expect("a number");
        assert!(
            (after / before - NUDGE_FACTOR).abs() < 1e-5,
            "{before} -> {after}"
        );
    }

    #[test]
    fn selection_wraps_around() {
        let mut f = form();
        let n = f.len();
        f.move_selection(-1);
        assert_eq!(f.selected(), n - 1);
        f.move_selection(1);
        assert_eq!(f.selected(), 0);
    }
}
