//! Comparing runs on one chart: pinned runs of a scene are drawn over the current one, each in
//! its own colour, with a legend entry naming the parameters in which it differs from the
//! current run ("couplings = [0, 2], roughness = 50"). A pinned run's curves, markers and shaded
//! regions are all named after its entry (`#1 roughness = 50 · pull-off`), so the legend and the
//! CSV tell the runs apart. The same overlay is what an export writes when runs are pinned, so
//! the PNG/SVG/CSV carry every drawn run; in the terminal the run's entry lists the symbols of
//! its markers and regions instead of an entry for each.

use crate::figure::{Figure, Panel, Series};
use crate::params::{ParamValues, value_text};
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
}

impl Overlay {
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

/// Panel `k` of the current figure with the same panel of every pin drawn over it: the current
/// curves keep their colours; each pin gets one legend entry (`labels[i]`, a series with no
/// points) and all its curves, markers and shaded regions in its colour under the names
/// `label · curve`, `label · marker`, `label · region` (a pinned marker's letter is left out).
pub fn overlay(current: &Panel, k: usize, pins: &[Pin], labels: &[String]) -> Overlay {
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
    for (i, (pin, label)) in pins.iter().zip(labels).enumerate() {
        let Some(p) = pin.figure.panels.get(k) else {
            continue;
        };
        entries[i] = Some(panel.series.len());
        panel.add(Series::new(label.clone(), crate::figure::Style::Stable, Vec::new()).with_color(pin.color));
        series.push(Owner::Pin(i));
        for s in &p.series {
            let mut s = s.clone();
            s.name = format!("{label} · {}", s.name);
            s.color = Some(pin.color);
            s.legend = false;
            panel.add(s);
            series.push(Owner::Pin(i));
        }
        for m in &p.markers {
            let mut m = m.clone();
            m.name = format!("{label} · {}", m.name);
            m.color = Some(pin.color);
            m.label = None;
            panel.mark(m);
            markers.push(Owner::Pin(i));
        }
        for r in &p.regions {
            let mut r = r.clone();
            r.name = format!("{label} · {}", r.name);
            r.color = Some(pin.color);
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
    }
}

/// The current figure with every pin drawn over each of its panels (what an export writes when
/// runs are pinned).
pub fn overlay_figure(current: &Figure, pins: &[Pin], labels: &[String]) -> Figure {
    let mut fig = current.clone();
    fig.panels = current
        .panels
        .iter()
        .enumerate()
        .map(|(k, p)| overlay(p, k, pins, labels).panel)
        .collect();
    fig
}
