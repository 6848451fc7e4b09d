//! Comparing runs on one chart: pinned runs of a scene are drawn over the current one, each in
//! its own colour, with a legend entry naming the parameters in which it differs from the
//! current run ("couplings = [0, 2], roughness = 50"). A pinned run's curves, markers and shaded
//! regions are all named after its entry (`#1 roughness = 50 · pull-off`), so the legend and the
//! CSV tell the runs apart. The same overlay is what an export writes when runs are pinned, so
//! the PNG/SVG/CSV carry every drawn run; in the terminal the run's entry lists the symbols of
//! its markers and regions instead of an entry for each.
//!
//! A pin is drawn in the units of the current run's axes or not at all: a pin computed with
//! other display parameters (`units = normalized` against `si`) is drawn from its own figure
//! recomputed with the current run's display parameters (its own scales: its radius, modulus
//! and work of adhesion), an axis in another SI prefix (`nN` against `µN`) is rescaled, and a
//! pin whose axes still differ is refused: its legend entry stays and says why it is not drawn.

use crate::figure::{Figure, Panel, Scale, Series};
use crate::params::{ParamValues, value_text};
use crate::render::labels::split_unit;
use crate::render::terminal::{REGION_SYMBOL, marker_symbol};

/// A run kept on the chart.
#[derive(Debug, Clone)]
pub struct Pin {
    /// Its figure.
    pub figure: Figure,
    /// Its parameters.
    pub values: ParamValues,
    /// Its wall time in seconds.
    pub run_time_s: f64,
    /// Palette index of all its curves.
    pub color: usize,
    /// Its figure recomputed with other display parameters ([`DISPLAY_PARAMS`]), by the
    /// parameters it was recomputed with.
    pub converted: Vec<(ParamValues, Figure)>,
    /// The run recomputing it in the current run's units, while it goes on.
    pub converting: Option<u64>,
    /// Hidden from the chart (its legend entry and its row of the table stay).
    pub hidden: bool,
}

impl Pin {
    /// A pinned run in colour `color`, shown, with no recomputed figure.
    pub fn new(figure: Figure, values: ParamValues, run_time_s: f64, color: usize) -> Self {
        Self {
            figure,
            values,
            run_time_s,
            color,
            converted: Vec::new(),
            converting: None,
            hidden: false,
        }
    }

    /// The figure to draw against a run with parameters `current`: its own when the display
    /// parameters agree, else its figure recomputed with the current run's display parameters;
    /// `Err` says why there is none yet.
    pub fn figure_for(&self, current: &ParamValues) -> Result<&Figure, String> {
        let Some(wanted) = display_variant(&self.values, current) else {
            return Ok(&self.figure);
        };
        self.converted
            .iter()
            .find(|(v, _)| *v == wanted)
            .map(|(_, f)| f)
            .ok_or_else(|| {
                if self.converting.is_some() {
                    "being converted to the shown units".to_string()
                } else {
                    "computed in other units".to_string()
                }
            })
    }
}

/// The items of the pins among `items` (owned by `owners`), with their owners.
fn pins_only<T>(items: &mut Vec<T>, owners: &mut Vec<Owner>) -> (Vec<T>, Vec<Owner>) {
    std::mem::take(items)
        .into_iter()
        .zip(std::mem::take(owners))
        .filter(|(_, o)| *o != Owner::Current)
        .unzip()
}

/// The legend entry of a hidden current run.
pub const CURRENT_HIDDEN: &str = "this run (hidden: x shows it)";

/// Parameters that change how a run is drawn, not what it computes: a pin that differs from
/// the current run in them is recomputed with the current run's values before it is drawn.
pub const DISPLAY_PARAMS: &[&str] = &["units"];

/// The parameters of `pinned` with the display parameters ([`DISPLAY_PARAMS`]) of `current`,
/// when they differ (`None`: the pin is drawn as computed).
pub fn display_variant(pinned: &ParamValues, current: &ParamValues) -> Option<ParamValues> {
    let mut variant = pinned.clone();
    let mut changed = false;
    for name in DISPLAY_PARAMS {
        if let (Ok(k), Some(v)) = (variant.index(name), current.get(name))
            && variant.values[k] != *v
        {
            variant.values[k] = v.clone();
            changed = true;
        }
    }
    changed.then_some(variant)
}

/// How an axis of a pinned panel is drawn on the same axis of the current panel: the factor
/// its values are multiplied by, or why they cannot be (one line).
///
/// # Errors
/// Another scale (linear against log), another quantity (label) or a unit that is not the
/// same one with another SI prefix.
pub fn axis_factor(
    current: &crate::figure::Axis,
    pinned: &crate::figure::Axis,
    name: &str,
) -> Result<f64, String> {
    let unit = |u: &str| {
        if u.is_empty() {
            "no unit".to_string()
        } else {
            u.to_string()
        }
    };
    if current.scale != pinned.scale {
        let kind = |s: Scale| if s == Scale::Log { "logarithmic" } else { "linear" };
        return Err(format!(
            "{name} is {} here, {} in the pin",
            kind(current.scale),
            kind(pinned.scale)
        ));
    }
    if current.label != pinned.label && current.unit == pinned.unit {
        return Err(format!(
            "{name} shows another quantity in the pin ({})",
            pinned.label
        ));
    }
    if current.unit == pinned.unit {
        return Ok(1.0);
    }
    match (split_unit(&current.unit), split_unit(&pinned.unit)) {
        (Some((a, base_a)), Some((b, base_b))) if base_a == base_b => Ok(10f64.powi(b - a)),
        _ => Err(format!(
            "{name} in {} here, {} in the pin",
            unit(&current.unit),
            unit(&pinned.unit)
        )),
    }
}

/// The factors (x, y) that draw panel `pinned` on the axes of `current` ([`axis_factor`]).
///
/// # Errors
/// The first axis that cannot be converted, in words.
pub fn axes_fit(current: &Panel, pinned: &Panel) -> Result<(f64, f64), String> {
    Ok((
        axis_factor(&current.x, &pinned.x, "x")?,
        axis_factor(&current.y, &pinned.y, "y")?,
    ))
}

/// Palette indices for pinned runs, in order of preference (away from the first colours that
/// scenes use for their own curves).
const PIN_COLORS: [usize; 10] = [5, 3, 4, 9, 6, 8, 2, 1, 0, 7];

/// The colour for a new pin: the first of the pin palette (`PIN_COLORS`) that neither the current figure's
/// first panel nor an earlier pin uses.
pub fn pin_color(current: &Figure, pins: &[Pin]) -> usize {
    let used: Vec<usize> = current
        .panels
        .first()
        .map(Panel::series_colors)
        .unwrap_or_default();
    PIN_COLORS
        .iter()
        .copied()
        .find(|c| !used.contains(c) && !pins.iter().any(|p| p.color == *c))
        .unwrap_or(PIN_COLORS[pins.len() % PIN_COLORS.len()])
}

/// What differs in `pinned` from `current`: `name = value unit` per differing parameter,
/// joined by commas; `same parameters` when nothing does.
pub fn difference(pinned: &ParamValues, current: &ParamValues) -> String {
    let parts: Vec<String> = pinned
        .specs
        .iter()
        .zip(&pinned.values)
        .filter(|(spec, value)| current.get(spec.name) != Some(*value))
        .map(|(spec, value)| {
            let v = value_text(value);
            if spec.unit.is_empty() {
                format!("{} = {v}", spec.name)
            } else {
                format!("{} = {v} {}", spec.name, spec.unit)
            }
        })
        .collect();
    if parts.is_empty() {
        "same parameters".into()
    } else {
        parts.join(", ")
    }
}

/// The legend label of pin `k` (from 1) against the current parameters, at most `width`
/// characters as shown; in the figures' markup, with the parameters' names escaped so that
/// `max_depth_norm` reads as written rather than with subscripts.
pub fn pin_label(k: usize, pin: &Pin, current: &ParamValues, width: usize) -> String {
    let text = format!("#{k} {}", difference(&pin.values, current));
    let shown = if text.chars().count() > width && width > 1 {
        let mut s: String = text.chars().take(width - 1).collect();
        s.push('…');
        s
    } else {
        text
    };
    crate::render::text::escape(&shown)
}

/// Who drew an element of an overlaid panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Owner {
    /// The current run.
    Current,
    /// Pinned run `k` (index into the pins).
    Pin(usize),
}

/// A panel with pinned runs drawn over it, and who drew each series, marker and region.
#[derive(Debug, Clone)]
pub struct Overlay {
    /// The panel to draw.
    pub panel: Panel,
    /// Owner of each series of `panel`.
    pub series: Vec<Owner>,
    /// Owner of each marker of `panel`.
    pub markers: Vec<Owner>,
    /// Owner of each shaded region of `panel`.
    pub regions: Vec<Owner>,
    /// Index in `panel.series` of each pin's legend entry (a series with no points), by pin.
    pub entries: Vec<Option<usize>>,
    /// Why each pin is not drawn, by pin (`None`: drawn, or hidden).
    pub refused: Vec<Option<String>>,
}

impl Overlay {
    /// The panel with the current run's curves moved after the pins' so that they are drawn on
    /// top (the order of [`Overlay::panel`], which the cursor indexes, is kept there).
    pub fn current_on_top(&self) -> Panel {
        let mut panel = self.panel.clone();
        let (current, pinned): (Vec<_>, Vec<_>) = self
            .panel
            .series
            .iter()
            .cloned()
            .zip(&self.series)
            .partition(|(_, o)| **o == Owner::Current);
        panel.series = pinned.into_iter().chain(current).map(|(s, _)| s).collect();
        panel
    }

    /// The overlay with the current run hidden: its curves, markers, regions, arrows and field
    /// leave the chart (its axes stay, the pins are drawn on them), and one legend entry says
    /// it is hidden.
    #[must_use]
    pub fn with_current_hidden(mut self) -> Self {
        let color = self.panel.series_colors().first().copied();
        let mut entry = Series::new(CURRENT_HIDDEN, crate::figure::Style::Stable, Vec::new());
        entry.color = color;
        let mut kept = vec![entry];
        let mut owners = vec![Owner::Current];
        let mut moved = vec![None; self.panel.series.len()];
        for (k, (s, o)) in std::mem::take(&mut self.panel.series)
            .into_iter()
            .zip(&self.series)
            .enumerate()
        {
            if *o != Owner::Current {
                moved[k] = Some(kept.len());
                kept.push(s);
                owners.push(*o);
            }
        }
        self.panel.series = kept;
        self.series = owners;
        for e in &mut self.entries {
            *e = e.and_then(|k| moved[k]);
        }
        (self.panel.markers, self.markers) = pins_only(&mut self.panel.markers, &mut self.markers);
        (self.panel.regions, self.regions) = pins_only(&mut self.panel.regions, &mut self.regions);
        self.panel.arrows.clear();
        self.panel.field = None;
        self
    }

    /// The markers and regions of the current run: they come first, the pins' follow (what the
    /// terminal legend lists one by one; see [`Overlay::with_legend_symbols`]).
    pub fn current_counts(&self) -> (usize, usize) {
        let count = |o: &[Owner]| o.iter().take_while(|w| **w == Owner::Current).count();
        (count(&self.markers), count(&self.regions))
    }

    /// The overlay for the terminal legend: each pin's entry followed by the symbols of its
    /// markers and regions (`#1 roughness = 50 ▲■░`), which then get no entries of their own.
    #[must_use]
    pub fn with_legend_symbols(mut self) -> Self {
        for (i, entry) in self.entries.iter().enumerate() {
            let Some(e) = *entry else { continue };
            let mut symbols = String::new();
            for (m, owner) in self.panel.markers.iter().zip(&self.markers) {
                let s = marker_symbol(m.shape);
                if *owner == Owner::Pin(i) && !symbols.contains(s) {
                    symbols.push_str(s);
                }
            }
            if self.regions.contains(&Owner::Pin(i)) {
                symbols.push_str(REGION_SYMBOL);
            }
            if !symbols.is_empty() {
                let name = &mut self.panel.series[e].name;
                name.push(' ');
                name.push_str(&symbols);
            }
        }
        self
    }
}

/// Panel `k` of the current figure (computed with `values`) with the same panel of every
/// shown pin drawn over it in the current axes' units: the current curves keep their colours
/// and are drawn last (on top); each pin gets one legend entry (`labels[i]`, a series with no
/// points) and all its curves, markers and shaded regions in its colour under the names
/// `label · curve`, `label · marker`, `label · region` (a pinned marker's letter is left out).
/// A pin that cannot be drawn in these units keeps its legend entry, which says why
/// ([`Overlay::refused`]); a hidden pin keeps its entry, marked hidden.
pub fn overlay(current: &Panel, k: usize, values: &ParamValues, pins: &[Pin], labels: &[String]) -> Overlay {
    let mut panel = current.clone();
    for (s, c) in panel.series.iter_mut().zip(current.series_colors()) {
        s.color = Some(c);
    }
    let colors = current.series_colors();
    for m in &mut panel.markers {
        m.color = current.marker_color(m, &colors).or(m.color);
    }
    let mut series = vec![Owner::Current; panel.series.len()];
    let mut markers = vec![Owner::Current; panel.markers.len()];
    let mut regions = vec![Owner::Current; panel.regions.len()];
    let mut entries = vec![None; pins.len()];
    let mut refused = vec![None; pins.len()];
    for (i, (pin, label)) in pins.iter().zip(labels).enumerate() {
        let drawn = pin.figure_for(values).and_then(|f| {
            let p = f
                .panels
                .get(k)
                .ok_or_else(|| "it has no such panel".to_string())?;
            axes_fit(current, p).map(|fit| (p, fit))
        });
        // The note goes right after `#k`, where a legend cut to its width still shows it.
        let note = match (&drawn, pin.hidden) {
            (Err(why), _) => Some(format!("not drawn: {why} ·")),
            (Ok(_), true) => Some("(hidden)".to_string()),
            (Ok(_), false) if display_variant(&pin.values, values).is_some() => {
                Some("(converted)".to_string())
            }
            _ => None,
        };
        let entry = match (&note, label.split_once(' ')) {
            (Some(n), Some((tag, rest))) => format!("{tag} {} {rest}", crate::render::text::escape(n)),
            (Some(n), None) => format!("{label} {}", crate::render::text::escape(n)),
            (None, _) => label.clone(),
        };
        entries[i] = Some(panel.series.len());
        panel.add(Series::new(entry, crate::figure::Style::Stable, Vec::new()).with_color(pin.color));
        series.push(Owner::Pin(i));
        let (p, (fx, fy)) = match drawn {
            Ok(d) => d,
            Err(why) => {
                refused[i] = Some(why);
                continue;
            }
        };
        if pin.hidden {
            continue;
        }
        let at = |(x, y): (f64, f64)| (x * fx, y * fy);
        for s in &p.series {
            let mut s = s.clone();
            s.name = format!("{label} · {}", s.name);
            s.color = Some(pin.color);
            s.legend = false;
            s.points.iter_mut().for_each(|q| *q = at(*q));
            panel.add(s);
            series.push(Owner::Pin(i));
        }
        for m in &p.markers {
            let mut m = m.clone();
            m.name = format!("{label} · {}", m.name);
            m.color = Some(pin.color);
            m.label = None;
            (m.x, m.y) = at((m.x, m.y));
            panel.mark(m);
            markers.push(Owner::Pin(i));
        }
        for r in &p.regions {
            let mut r = r.clone();
            r.name = format!("{label} · {}", r.name);
            r.color = Some(pin.color);
            r.points.iter_mut().for_each(|q| *q = at(*q));
            panel.regions.push(r);
            regions.push(Owner::Pin(i));
        }
    }
    Overlay {
        panel,
        series,
        markers,
        regions,
        entries,
        refused,
    }
}

/// The current figure with every pin drawn over each of its panels (what an export writes when
/// runs are pinned), in the current figure's units as on the screen.
pub fn overlay_figure(current: &Figure, values: &ParamValues, pins: &[Pin], labels: &[String]) -> Figure {
    let mut fig = current.clone();
    fig.panels = current
        .panels
        .iter()
        .enumerate()
        .map(|(k, p)| overlay(p, k, values, pins, labels).panel)
        .collect();
    fig
}
