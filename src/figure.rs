//! The backend-free figure: panels, axes, series, markers, regions, arrows and fields.
//!
//! A scene's `run` returns a [`Figure`]; the PNG/SVG renderer, the terminal chart and the CSV/JSON
//! exporters all draw or write the same `Figure`, so what a user sees and what a user loads into
//! their own analysis are the same numbers. Nothing here knows about plotting libraries, terminals or files.
//!
//! Conventions (as in the dissertation's figures): stable equilibrium branches are solid,
//! unstable ones dashed; pull-in instabilities are marked with triangles, pull-off instabilities
//! with squares; analytic limits and reference curves are dotted.

use serde::Serialize;

/// A whole figure: one or more panels and the named scalar results of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figure {
    /// Scene id, e.g. `fig1.1`.
    pub id: String,
    /// Title drawn above the panels.
    pub title: String,
    /// Panels, drawn left to right, top to bottom.
    pub panels: Vec<Panel>,
    /// Named scalar results, in insertion order. Names carry their unit as a suffix
    /// (`_N`, `_m`, `_J_per_m2`, ...) or `_norm` for non-dimensional values.
    pub results: Vec<(String, f64)>,
    /// Remarks worth keeping with the data (what differs from the dissertation and why).
    pub notes: Vec<String>,
    /// What a run in quick form computed more coarsely than the full figure (the parameters
    /// the quick form changed, with their full values); `None` for a run at full resolution.
    pub quick_form: Option<String>,
}

impl Figure {
    /// An empty figure.
    pub fn new(id: impl Into<String>, title: impl Into<String>) -> Self {
        Self {
            id: id.into(),
            title: title.into(),
            panels: Vec::new(),
            results: Vec::new(),
            notes: Vec::new(),
            quick_form: None,
        }
    }

    /// Mark the figure as computed in quick form: `coarser` says what is coarser than the full
    /// figure. It is kept in [`Figure::quick_form`], as the first note ("quick form: ...", its
    /// parameter names escaped for the markup) and in the title, so that no copy of the figure
    /// passes for the full one.
    pub fn mark_quick(&mut self, coarser: &str) {
        self.quick_form = Some(coarser.to_string());
        // The note is markup, and parameter names hold underscores: escaped, they read as typed.
        self.notes
            .insert(0, format!("quick form: {}", crate::render::text::escape(coarser)));
        if !self.title.ends_with("(quick form)") {
            self.title.push_str(" (quick form)");
        }
    }

    /// Add a panel and return `self` (builder style).
    #[must_use]
    pub fn with_panel(mut self, panel: Panel) -> Self {
        self.panels.push(panel);
        self
    }

    /// Record a named scalar result (replacing an earlier one of the same name).
    pub fn result(&mut self, name: impl Into<String>, value: f64) {
        let name = name.into();
        if let Some(slot) = self.results.iter_mut().find(|(n, _)| *n == name) {
            slot.1 = value;
        } else {
            self.results.push((name, value));
        }
    }

    /// Look up a named result.
    pub fn result_value(&self, name: &str) -> Option<f64> {
        self.results.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }

    /// Add a note.
    pub fn note(&mut self, text: impl Into<String>) {
        self.notes.push(text.into());
    }

    /// Number of data points over all panels (series, markers, field cells), a cheap size
    /// measure.
    pub fn n_points(&self) -> usize {
        self.panels
            .iter()
            .map(|p| {
                p.series.iter().map(|s| s.points.len()).sum::<usize>()
                    + p.markers.len()
                    + p.field.as_ref().map_or(0, |f| f.values.len())
            })
            .sum()
    }
}

/// Linear or logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// Linear axis.
    Linear,
    /// Base-10 logarithmic axis (non-positive values are not drawn).
    Log,
}

/// One axis: label, unit, scale and an optional fixed range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Axis {
    /// Quantity, e.g. `P/P_C` or `Indentation depth h`.
    pub label: String,
    /// Unit, e.g. `nm`; empty for non-dimensional quantities.
    pub unit: String,
    /// Linear or log.
    pub scale: Scale,
    /// Fixed range; `None` fits the data.
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// A linear axis.
    pub fn linear(label: impl Into<String>, unit: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            unit: unit.into(),
            scale: Scale::Linear,
            range: None,
        }
    }

    /// A base-10 logarithmic axis.
    pub fn log(label: impl Into<String>, unit: impl Into<String>) -> Self {
        Self {
            scale: Scale::Log,
            ..Self::linear(label, unit)
        }
    }

    /// Fix the range.
    #[must_use]
    pub fn with_range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }

    /// `label [unit]`, or `label` for a non-dimensional quantity.
    pub fn title(&self) -> String {
        if self.unit.is_empty() {
            self.label.clone()
        } else {
            format!("{} [{}]", self.label, self.unit)
        }
    }
}

/// How a series is drawn. The name is also the CSV `style` column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Style {
    /// Stable equilibrium branch or an ordinary curve: solid line.
    Stable,
    /// Unstable equilibrium branch: dashed line.
    Unstable,
    /// A dashed line that is not an equilibrium branch (a second quantity, a bound, a level
    /// of another model): drawn like [`Style::Unstable`], named apart in the CSV.
    Dashed,
    /// Analytic limit, asymptote or approximation: dotted line.
    Reference,
    /// Points without a line (measured data, FE points, exact points on a fit).
    Scatter,
    /// Error bars: points come in pairs (x, y_lo), (x, y_hi).
    ErrorBar,
    /// A contour line of a field.
    Contour,
    /// A jump at an instability: thin line between the states before and after.
    Jump,
}

impl Style {
    /// Lower-case name used in CSV and legends.
    pub fn as_str(self) -> &'static str {
        match self {
            Style::Stable => "stable",
            Style::Unstable => "unstable",
            Style::Dashed => "dashed",
            Style::Reference => "reference",
            Style::Scatter => "scatter",
            Style::ErrorBar => "errorbar",
            Style::Contour => "contour",
            Style::Jump => "jump",
        }
    }
}

/// A named line (or point set) in a panel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Series {
    /// Name shown in the legend; series with the same name share a colour and one legend entry
    /// (e.g. the stable and unstable parts of one curve).
    pub name: String,
    /// Line style.
    pub style: Style,
    /// Palette index; `None` assigns colours by name in order of appearance.
    pub color: Option<usize>,
    /// Whether the series appears in the legend.
    pub legend: bool,
    /// Points (x, y) in data units.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A series with automatic colour that appears in the legend.
    pub fn new(name: impl Into<String>, style: Style, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            style,
            color: None,
            legend: true,
            points,
        }
    }

    /// Fix the palette colour.
    #[must_use]
    pub fn with_color(mut self, color: usize) -> Self {
        self.color = Some(color);
        self
    }

    /// Keep the series out of the legend.
    #[must_use]
    pub fn without_legend(mut self) -> Self {
        self.legend = false;
        self
    }
}

/// Marker shapes. The name is the CSV `style` column of a marker row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MarkerShape {
    /// Pull-in instability: triangle.
    PullIn,
    /// Pull-off instability: square.
    PullOff,
    /// A stable state: filled circle.
    StableState,
    /// An unstable state: open circle.
    UnstableState,
    /// A distinguished point (e.g. the adhesive-force point): filled diamond.
    Point,
    /// A data point: cross.
    Cross,
}

impl MarkerShape {
    /// Kebab-case name used in CSV.
    pub fn as_str(self) -> &'static str {
        match self {
            MarkerShape::PullIn => "pull-in",
            MarkerShape::PullOff => "pull-off",
            MarkerShape::StableState => "stable-state",
            MarkerShape::UnstableState => "unstable-state",
            MarkerShape::Point => "point",
            MarkerShape::Cross => "cross",
        }
    }
}

/// A single marked point, optionally with a text label (e.g. the letters A-F of Fig. 1.1).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Marker {
    /// Legend name, e.g. `JKR pull-off`.
    pub name: String,
    /// Shape.
    pub shape: MarkerShape,
    /// Position x.
    pub x: f64,
    /// Position y.
    pub y: f64,
    /// Palette index; `None` takes the colour of the series with the same name, else black.
    pub color: Option<usize>,
    /// Short text drawn next to the marker.
    pub label: Option<String>,
}

impl Marker {
    /// A marker with automatic colour and no label.
    pub fn new(name: impl Into<String>, shape: MarkerShape, x: f64, y: f64) -> Self {
        Self {
            name: name.into(),
            shape,
            x,
            y,
            color: None,
            label: None,
        }
    }

    /// Fix the palette colour.
    #[must_use]
    pub fn with_color(mut self, color: usize) -> Self {
        self.color = Some(color);
        self
    }

    /// Attach a text label.
    #[must_use]
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = Some(label.into());
        self
    }
}

/// A shaded polygon, e.g. a hysteresis loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Region {
    /// Legend name.
    pub name: String,
    /// Palette index.
    pub color: Option<usize>,
    /// Closed polygon (the last point connects to the first).
    pub points: Vec<(f64, f64)>,
    /// Drawn as an outline with hatching instead of a translucent fill, so that overlapping
    /// regions stay readable.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub hatched: bool,
}

/// An arrow, e.g. a snap-through jump.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Arrow {
    /// Tail.
    pub from: (f64, f64),
    /// Head.
    pub to: (f64, f64),
    /// Palette index.
    pub color: Option<usize>,
}

/// How a field is drawn.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FieldKind {
    /// Colour map with a colour bar.
    Heat,
    /// Contour lines at the given levels (a colour map underneath when `filled`).
    Contour {
        /// Levels to draw.
        levels: Vec<f64>,
        /// Draw a colour map under the lines.
        filled: bool,
    },
}

/// A scalar field on a rectangular grid: `values[j * x.len() + i]` is the value at `(x[i], y[j])`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Field {
    /// Quantity name, e.g. `Loss per area`.
    pub name: String,
    /// Unit of the values.
    pub unit: String,
    /// Grid abscissae, strictly increasing (in data units, log axes included).
    pub x: Vec<f64>,
    /// Grid ordinates, strictly increasing.
    pub y: Vec<f64>,
    /// Values, row-major in y: `values[j * nx + i]`.
    pub values: Vec<f64>,
    /// Heat map or contours.
    pub kind: FieldKind,
    /// Levels drawn as emphasised, labelled contour lines (e.g. a measured value).
    pub highlight: Vec<(f64, String)>,
    /// A fixed range of the colour map (values outside are drawn at its ends); `None`: the
    /// values' own range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color_range: Option<(f64, f64)>,
}

impl Field {
    /// A heat field.
    ///
    /// # Panics
    /// If `values.len() != x.len() * y.len()`.
    pub fn heat(
        name: impl Into<String>,
        unit: impl Into<String>,
        x: Vec<f64>,
        y: Vec<f64>,
        values: Vec<f64>,
    ) -> Self {
        assert_eq!(values.len(), x.len() * y.len(), "field values must be nx * ny");
        Self {
            name: name.into(),
            unit: unit.into(),
            x,
            y,
            values,
            kind: FieldKind::Heat,
            highlight: Vec::new(),
            color_range: None,
        }
    }

    /// Value at grid node (i, j).
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.values[j * self.x.len() + i]
    }

    /// The range of the colour map: the fixed one where set, otherwise the smallest and
    /// largest finite value.
    pub fn value_range(&self) -> Option<(f64, f64)> {
        if let Some(r) = self.color_range {
            return Some(r);
        }
        let mut it = self.values.iter().copied().filter(|v| v.is_finite());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
    }

    /// The levels to draw as contour lines: the explicit levels, or for a heat field none.
    pub fn contour_levels(&self) -> Vec<f64> {
        let mut levels = match &self.kind {
            FieldKind::Heat => Vec::new(),
            FieldKind::Contour { levels, .. } => levels.clone(),
        };
        levels.extend(self.highlight.iter().map(|(l, _)| *l));
        levels
    }

    /// Contour lines of the field at `level` by marching squares, as polylines in data units.
    ///
    /// Segments are joined into polylines where they share end points; saddle cells are
    /// resolved by the cell-centre average.
    pub fn contour(&self, level: f64) -> Vec<Vec<(f64, f64)>> {
        let nx = self.x.len();
        let ny = self.y.len();
        let mut segments: Vec<((f64, f64), (f64, f64))> = Vec::new();
        if nx < 2 || ny < 2 {
            return Vec::new();
        }
        let lerp = |p0: (f64, f64), v0: f64, p1: (f64, f64), v1: f64| {
            let t = if (v1 - v0).abs() > 0.0 {
                (level - v0) / (v1 - v0)
            } else {
                0.5
            };
            (p0.0 + t * (p1.0 - p0.0), p0.1 + t * (p1.1 - p0.1))
        };
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let corners = [
                    ((self.x[i], self.y[j]), self.at(i, j)),
                    ((self.x[i + 1], self.y[j]), self.at(i + 1, j)),
                    ((self.x[i + 1], self.y[j + 1]), self.at(i + 1, j + 1)),
                    ((self.x[i], self.y[j + 1]), self.at(i, j + 1)),
                ];
                if corners.iter().any(|(_, v)| !v.is_finite()) {
                    continue;
                }
                // Crossing points on the four edges, in order 0-1, 1-2, 2-3, 3-0.
                let mut crossings = Vec::with_capacity(4);
                for e in 0..4 {
                    let (p0, v0) = corners[e];
                    let (p1, v1) = corners[(e + 1) % 4];
                    if (v0 >= level) != (v1 >= level) {
                        crossings.push((e, lerp(p0, v0, p1, v1)));
                    }
                }
                match crossings.len() {
                    2 => segments.push((crossings[0].1, crossings[1].1)),
                    4 => {
                        let centre = corners.iter().map(|(_, v)| v).sum::<f64>() / 4.0;
                        let corner0_above = corners[0].1 >= level;
                        // Join so that the centre's side is connected.
                        if (centre >= level) == corner0_above {
                            segments.push((crossings[0].1, crossings[1].1));
                            segments.push((crossings[2].1, crossings[3].1));
                        } else {
                            segments.push((crossings[3].1, crossings[0].1));
                            segments.push((crossings[1].1, crossings[2].1));
                        }
                    }
                    _ => {}
                }
            }
        }
        join_segments(segments)
    }
}

/// Contour levels at round values for a field spanning decades: 1, 2 and 5 × 10ⁿ strictly
/// between `lo` and `hi` (both positive); where those are more than twice `target`, only the
/// powers of ten (every second, third, ... decade where still too many). Empty for an empty
/// or non-positive range.
pub fn round_log_levels(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Vec::new();
    }
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    // Parsed from their decimal form: 2e-3 is the double nearest 0.002, not 2 × 10^-3.
    let at = |mantissas: &[u8]| -> Vec<f64> {
        (first..=last)
            .flat_map(|n| mantissas.iter().map(move |m| format!("{m}e{n}")))
            .filter_map(|t| t.parse::<f64>().ok())
            .filter(|&v| v > lo && v < hi)
            .collect()
    };
    let all = at(&[1, 2, 5]);
    if all.len() <= 2 * target.max(1) {
        return all;
    }
    let decades = at(&[1]);
    let every = decades.len().div_ceil(2 * target.max(1)).max(1);
    decades.into_iter().step_by(every).collect()
}

/// Where two curves count as one in the drawing, for [`Panel::mark_coinciding`]: within this
/// fraction of the panel's span on each axis, about a pixel of a PNG's frame.
pub const COINCIDENCE_TOL: f64 = 1.5e-3;

/// A number for text drawn on a figure (notes, legends, headings): `digits` significant digits
/// (a number with more integer digits keeps them all), trailing zeros kept (they state the
/// precision), and the typographic minus sign; outside [10⁻³, 10⁵) a power of ten as print
/// writes it (`−2.08 × 10⁻⁴`, never the `-2.08e-4` of Rust's `{:e}`).
pub fn number(v: f64, digits: usize) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let digits = digits.max(1);
    if !(1e-3..1e5).contains(&v.abs()) {
        return scientific(&format!("{v:.prec$e}", prec = digits - 1));
    }
    let magnitude = v.abs().log10().floor() as i64;
    let decimals = (digits as i64 - 1 - magnitude).max(0) as usize;
    let rounded = format!("{v:.decimals$}");
    // Rounding up into the next decade (9.9996 -> 10.000) gives one digit too many.
    let text = if rounded
        .trim_start_matches('-')
        .replace('.', "")
        .trim_start_matches('0')
        .len()
        > digits
        && decimals > 0
    {
        format!("{v:.prec$}", prec = decimals - 1)
    } else {
        rounded
    };
    text.replace('-', "−")
}

/// A number for text drawn on a figure with all the digits it needs to read back as the same
/// value (a tolerance the user set, `2.5e-7`), written as [`number`] writes it (`2.5 × 10⁻⁷`).
pub fn exact_number(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    if !(1e-3..1e5).contains(&v.abs()) {
        return scientific(&format!("{v:e}"));
    }
    format!("{v}").replace('-', "−")
}

/// Rust's e-notation (`-2.08e-4`) as print writes it: `−2.08 × 10⁻⁴`, and a bare power of ten
/// for a mantissa of 1 (`1e-12` → `10⁻¹²`).
fn scientific(e_notation: &str) -> String {
    let (mantissa, exponent) = e_notation.split_once('e').unwrap_or((e_notation, "0"));
    let power = power_of_ten(exponent.parse().unwrap_or(0));
    match mantissa.trim_start_matches('-') {
        "1" => format!("{}{power}", if mantissa.starts_with('-') { "−" } else { "" }),
        _ => format!("{} × {power}", mantissa.replace('-', "−")),
    }
}

/// `10ᵏ` with superscript digits and a superscript minus (`10⁻²`); `1` and `10` for k = 0, 1.
pub fn power_of_ten(k: i64) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    match k {
        0 => "1".into(),
        1 => "10".into(),
        _ => {
            let mut s = String::from("10");
            if k < 0 {
                s.push('⁻');
            }
            for c in k.unsigned_abs().to_string().chars() {
                s.push(SUP[c.to_digit(10).unwrap_or(0) as usize]);
            }
            s
        }
    }
}

/// Distance from `p` to the polyline `line`.
fn polyline_distance(p: (f64, f64), line: &[(f64, f64)]) -> f64 {
    line.windows(2)
        .map(|w| segment_distance(p, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from `p` to the segment `a`-`b` (also the renderer's coverage of a stroke).
pub(crate) fn segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + t * dx - p.0, a.1 + t * dy - p.1);
    (qx * qx + qy * qy).sqrt()
}

/// Join line segments sharing end points into polylines.
fn join_segments(mut segments: Vec<((f64, f64), (f64, f64))>) -> Vec<Vec<(f64, f64)>> {
    let close = |a: (f64, f64), b: (f64, f64)| {
        let scale = a.0.abs().max(a.1.abs()).max(b.0.abs()).max(b.1.abs()).max(1e-300);
        (a.0 - b.0).abs() <= 1e-9 * scale && (a.1 - b.1).abs() <= 1e-9 * scale
    };
    // Grid nodes exactly on the level give zero-length segments; they join nothing.
    segments.retain(|(a, b)| !close(*a, *b));
    let mut lines = Vec::new();
    while let Some((a, b)) = segments.pop() {
        let mut line = std::collections::VecDeque::from(vec![a, b]);
        loop {
            let back = *line.back().expect("line has two points");
            let front = *line.front().expect("line has two points");
            let found = segments.iter().position(|(p, q)| {
                close(*p, back) || close(*q, back) || close(*p, front) || close(*q, front)
            });
            let Some(k) = found else { break };
            let (p, q) = segments.swap_remove(k);
            if close(p, back) {
                line.push_back(q);
            } else if close(q, back) {
                line.push_back(p);
            } else if close(p, front) {
                line.push_front(q);
            } else {
                line.push_front(p);
            }
        }
        lines.push(line.into_iter().collect());
    }
    lines
}

/// Where the legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Legend {
    /// The corner that covers the fewest data points.
    #[default]
    Auto,
    /// Upper left.
    UpperLeft,
    /// Upper right.
    UpperRight,
    /// Lower left.
    LowerLeft,
    /// Lower right.
    LowerRight,
    /// No legend.
    Hidden,
}

/// One panel: axes and everything drawn in them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Panel {
    /// Panel letter, e.g. `(a)`; may be empty.
    pub label: String,
    /// Short title.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Lines and point sets.
    pub series: Vec<Series>,
    /// Marked points.
    pub markers: Vec<Marker>,
    /// Shaded polygons (drawn first).
    pub regions: Vec<Region>,
    /// Arrows.
    pub arrows: Vec<Arrow>,
    /// A scalar field (drawn under everything else).
    pub field: Option<Field>,
    /// Legend placement.
    pub legend: Legend,
    /// Draw one data unit as long on both axes (maps of a square surface stay square).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub equal_aspect: bool,
    /// Short remarks drawn on the panel, under its legend entries (what the figure finds where
    /// it differs from the text, what its symbols mean).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

impl Panel {
    /// An empty panel with the given axes.
    pub fn new(x: Axis, y: Axis) -> Self {
        Self {
            label: String::new(),
            title: String::new(),
            x,
            y,
            series: Vec::new(),
            markers: Vec::new(),
            regions: Vec::new(),
            arrows: Vec::new(),
            field: None,
            legend: Legend::Auto,
            equal_aspect: false,
            notes: Vec::new(),
        }
    }

    /// Set label and title.
    #[must_use]
    pub fn titled(mut self, label: impl Into<String>, title: impl Into<String>) -> Self {
        self.label = label.into();
        self.title = title.into();
        self
    }

    /// Draw one data unit as long on both axes.
    #[must_use]
    pub fn with_equal_aspect(mut self) -> Self {
        self.equal_aspect = true;
        self
    }

    /// Add a note drawn on the panel (with the legend).
    pub fn annotate(&mut self, text: impl Into<String>) -> &mut Self {
        self.notes.push(text.into());
        self
    }

    /// Add a series.
    pub fn add(&mut self, series: Series) -> &mut Self {
        self.series.push(series);
        self
    }

    /// Add a series from name, style and points.
    pub fn line(&mut self, name: impl Into<String>, style: Style, points: Vec<(f64, f64)>) -> &mut Series {
        self.series.push(Series::new(name, style, points));
        self.series.last_mut().expect("just pushed")
    }

    /// Add a marker.
    pub fn mark(&mut self, marker: Marker) -> &mut Self {
        self.markers.push(marker);
        self
    }

    /// Add a shaded region.
    pub fn shade(
        &mut self,
        name: impl Into<String>,
        points: Vec<(f64, f64)>,
        color: Option<usize>,
    ) -> &mut Self {
        self.regions.push(Region {
            name: name.into(),
            color,
            points,
            hatched: false,
        });
        self
    }

    /// Add a region drawn as an outline with hatching (readable where regions overlap).
    pub fn hatch(
        &mut self,
        name: impl Into<String>,
        points: Vec<(f64, f64)>,
        color: Option<usize>,
    ) -> &mut Self {
        self.shade(name, points, color);
        if let Some(r) = self.regions.last_mut() {
            r.hatched = true;
        }
        self
    }

    /// Add an arrow.
    pub fn arrow(&mut self, from: (f64, f64), to: (f64, f64), color: Option<usize>) -> &mut Self {
        self.arrows.push(Arrow { from, to, color });
        self
    }

    /// The palette index of every series, by the rule of [`Series::color`]: fixed where given,
    /// else one colour per distinct name in order of appearance, skipping fixed colours.
    pub fn series_colors(&self) -> Vec<usize> {
        let fixed: Vec<usize> = self.series.iter().filter_map(|s| s.color).collect();
        let mut by_name: Vec<(&str, usize)> = Vec::new();
        let mut next = 0;
        self.series
            .iter()
            .map(|s| {
                if let Some(c) = s.color {
                    return c;
                }
                if let Some((_, c)) = by_name.iter().find(|(n, _)| *n == s.name) {
                    return *c;
                }
                while fixed.contains(&next) {
                    next += 1;
                }
                by_name.push((&s.name, next));
                next += 1;
                next - 1
            })
            .collect()
    }

    /// Colour of a marker: its own, else that of the series with the same name, else `None`.
    pub fn marker_color(&self, marker: &Marker, series_colors: &[usize]) -> Option<usize> {
        marker.color.or_else(|| {
            self.series
                .iter()
                .position(|s| s.name == marker.name)
                .map(|k| series_colors[k])
        })
    }

    /// Make solid curves that lie on an earlier solid curve tell apart: where a later series
    /// runs along an earlier one of another name (every point within `tol` of it, in units of
    /// the panel's data span on each axis, over at least a twentieth of the span), that part
    /// is split off as a dashed series in the same colour, named `"<later>: coincides with
    /// <earlier>"` (the earlier name up to its first bracket), so the curve under it shows
    /// between the dashes and the legend says why. Returns the names of the split-off series.
    ///
    /// Colours are fixed first (as [`Panel::series_colors`] assigns them), so the figure's
    /// other colours stay as they were. Only where the curves coincide is anything changed.
    pub fn mark_coinciding(&mut self, tol: f64) -> Vec<String> {
        let Some(((x0, x1), (y0, y1))) = self.data_bounds() else {
            return Vec::new();
        };
        let (sx, sy) = ((x1 - x0).max(f64::MIN_POSITIVE), (y1 - y0).max(f64::MIN_POSITIVE));
        let norm = |p: (f64, f64)| (p.0 / sx, p.1 / sy);
        let colors = self.series_colors();
        for (s, c) in self.series.iter_mut().zip(colors) {
            s.color = Some(c);
        }
        let mut added = Vec::new();
        let mut k = 0;
        while k < self.series.len() {
            let top = &self.series[k];
            if top.style != Style::Stable || top.points.len() < 2 {
                k += 1;
                continue;
            }
            let under = self.series[..k].iter().find_map(|s| {
                let solid = s.style == Style::Stable && s.name != top.name && s.points.len() > 1;
                let on = solid.then(|| {
                    let line: Vec<(f64, f64)> = s.points.iter().map(|&p| norm(p)).collect();
                    top.points
                        .iter()
                        .map(|&p| polyline_distance(norm(p), &line) <= tol)
                        .collect::<Vec<bool>>()
                })?;
                Some((s.name.clone(), on))
            });
            let Some((under_name, on)) = under else {
                k += 1;
                continue;
            };
            // Runs of points on the curve below, long enough to be seen as one line.
            let mut runs: Vec<(usize, usize)> = Vec::new();
            let mut i = 0;
            while i < on.len() {
                if !on[i] {
                    i += 1;
                    continue;
                }
                let j = (i..on.len()).find(|&j| !on[j]).unwrap_or(on.len());
                let length: f64 = top.points[i..j]
                    .windows(2)
                    .map(|w| {
                        let (a, b) = (norm(w[0]), norm(w[1]));
                        (b.0 - a.0).hypot(b.1 - a.1)
                    })
                    .sum();
                if j - i >= 2 && length >= 0.05 {
                    runs.push((i, j));
                }
                i = j;
            }
            if runs.is_empty() {
                k += 1;
                continue;
            }
            let short = under_name.split(" (").next().unwrap_or(&under_name).trim();
            let name = format!("{}: coincides with {short}", top.name);
            let (points, color) = (top.points.clone(), top.color);
            // The parts off the curve below stay solid (sharing their end points with the
            // dashed parts, so the line stays unbroken); the parts on it become dashed.
            let mut pieces: Vec<Series> = Vec::new();
            let mut start = 0;
            for &(i, j) in &runs {
                if i > start {
                    let mut s = self.series[k].clone();
                    s.points = points[start..=i].to_vec();
                    pieces.push(s);
                }
                let mut dashed = Series::new(name.clone(), Style::Dashed, points[i..j].to_vec());
                dashed.color = color;
                pieces.push(dashed);
                start = j - 1;
            }
            if start + 1 < points.len() {
                let mut s = self.series[k].clone();
                s.points = points[start..].to_vec();
                pieces.push(s);
            }
            let n = pieces.len();
            self.series.splice(k..=k, pieces);
            if !added.contains(&name) {
                added.push(name);
            }
            k += n;
        }
        added
    }

    /// Bounding box of everything drawn, in data units, honouring fixed ranges and skipping
    /// non-positive values on log axes. `None` when there is nothing to draw.
    pub fn data_bounds(&self) -> Option<((f64, f64), (f64, f64))> {
        let ok_x = |v: f64| v.is_finite() && (self.x.scale == Scale::Linear || v > 0.0);
        let ok_y = |v: f64| v.is_finite() && (self.y.scale == Scale::Linear || v > 0.0);
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        let mut push = |x: f64, y: f64| {
            if ok_x(x) && ok_y(y) {
                xs.push(x);
                ys.push(y);
            }
        };
        for s in &self.series {
            for &(x, y) in &s.points {
                push(x, y);
            }
        }
        for m in &self.markers {
            push(m.x, m.y);
        }
        for r in &self.regions {
            for &(x, y) in &r.points {
                push(x, y);
            }
        }
        for a in &self.arrows {
            push(a.from.0, a.from.1);
            push(a.to.0, a.to.1);
        }
        if let Some(f) = &self.field {
            for &x in [f.x.first(), f.x.last()].into_iter().flatten() {
                for &y in [f.y.first(), f.y.last()].into_iter().flatten() {
                    push(x, y);
                }
            }
        }
        let fold = |v: &[f64]| -> Option<(f64, f64)> {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (lo <= hi).then_some((lo, hi))
        };
        let xr = self.x.range.or_else(|| fold(&xs))?;
        let yr = self.y.range.or_else(|| fold(&ys))?;
        Some((xr, yr))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_with_one_name_share_a_colour_and_fixed_colours_are_skipped() {
        let mut p = Panel::new(Axis::linear("h", "m"), Axis::linear("P", "N"));
        p.line("JKR", Style::Stable, vec![(0.0, 0.0)]);
        p.add(Series::new("Hertz", Style::Stable, vec![]).with_color(0));
        p.line("JKR", Style::Unstable, vec![(1.0, 1.0)]);
        p.line("DMT", Style::Stable, vec![]);
        assert_eq!(p.series_colors(), vec![1, 0, 1, 2]);
    }

    #[test]
    fn numbers_on_figures_have_their_significant_digits_and_a_true_minus() {
        assert_eq!(number(-14.54272352431763, 4), "−14.54");
        assert_eq!(number(-282.6612192302118, 4), "−282.7");
        assert_eq!(number(0.44028227, 3), "0.440");
        assert_eq!(number(9.9996, 4), "10.00");
        assert_eq!(number(15.260879, 3), "15.3");
        // Whole numbers keep their integer digits.
        assert_eq!(number(1234.6, 2), "1235");
        // Outside [10⁻³, 10⁵): a power of ten, never e-notation, the mantissa's zeros kept.
        assert_eq!(number(-2.0799e-4, 3), "−2.08 × 10⁻⁴");
        assert_eq!(number(1.5e-9, 2), "1.5 × 10⁻⁹");
        assert_eq!(number(3.0e-4, 3), "3.00 × 10⁻⁴");
        assert_eq!(number(9.9996e-4, 3), "1.00 × 10⁻³");
        assert_eq!(number(123_456.0, 3), "1.23 × 10⁵");
        assert_eq!(number(1e-6, 1), "10⁻⁶");
        assert_eq!(exact_number(2.5e-7), "2.5 × 10⁻⁷");
        assert_eq!(exact_number(1e-15), "10⁻¹⁵");
        assert_eq!(exact_number(-0.25), "−0.25");
    }

    #[test]
    fn a_curve_on_another_is_dashed_only_where_they_coincide() {
        let parabola = |a: f64, b: f64, n: usize, dy: f64| -> Vec<(f64, f64)> {
            (0..n)
                .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
                .map(|x| (x, x * x + dy))
                .collect()
        };
        let mut p = Panel::new(Axis::linear("h", ""), Axis::linear("P", ""));
        p.line("model (2.31)", Style::Stable, parabola(0.5, 2.0, 300, 0.0));
        p.line("JKR", Style::Stable, parabola(0.0, 2.0, 170, 0.0));
        // Parallel but 5 % of the span away: not the same curve.
        p.line("shifted", Style::Stable, parabola(0.0, 2.0, 50, 0.2));
        let colors = p.series_colors();
        let added = p.mark_coinciding(1.5e-3);
        assert_eq!(added, vec!["JKR: coincides with model".to_string()]);
        let dashed: Vec<&Series> = p.series.iter().filter(|s| s.style == Style::Dashed).collect();
        assert_eq!(dashed.len(), 1);
        // The dashed part is exactly the part over the model's range, in the JKR colour.
        let xs: Vec<f64> = dashed[0].points.iter().map(|q| q.0).collect();
        assert!(
            xs[0] >= 0.5 - 2.0 / 169.0 && xs[0] <= 0.5 + 2.0 / 169.0,
            "{}",
            xs[0]
        );
        assert!((xs[xs.len() - 1] - 2.0).abs() < 1e-12);
        assert_eq!(dashed[0].color, Some(colors[1]));
        // The JKR part below x = 0.5 stays solid and joins the dashed part; nothing else moved.
        let solid: Vec<&Series> = p.series.iter().filter(|s| s.name == "JKR").collect();
        assert_eq!(solid.len(), 1);
        assert_eq!(solid[0].points.last(), dashed[0].points.first());
        let shifted = p.series.iter().find(|s| s.name == "shifted").unwrap();
        assert_eq!((shifted.style, shifted.color), (Style::Stable, Some(colors[2])));
    }

    #[test]
    fn round_log_levels_are_one_two_five_times_powers_of_ten() {
        assert_eq!(
            round_log_levels(0.0048, 0.1543, 7),
            vec![0.005, 0.01, 0.02, 0.05, 0.1]
        );
        // Six decades: the powers of ten alone.
        assert_eq!(
            round_log_levels(3.0e-7, 0.3, 7),
            vec![1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1]
        );
        // Twenty decades: every second one.
        assert_eq!(round_log_levels(0.5e-20, 1.0, 5).len(), 10);
        assert!(round_log_levels(0.0, 1.0, 5).is_empty());
        assert!(round_log_levels(2.0, 1.0, 5).is_empty());
    }

    #[test]
    fn contour_of_a_cone_is_a_closed_circle_of_the_right_radius() {
        let n = 41;
        let g: Vec<f64> = (0..n).map(|i| -1.0 + 2.0 * i as f64 / (n - 1) as f64).collect();
        let mut v = Vec::new();
        for &y in &g {
            for &x in &g {
                v.push((x * x + y * y).sqrt());
            }
        }
        let f = Field::heat("r", "", g.clone(), g, v);
        let lines = f.contour(0.5);
        assert_eq!(lines.len(), 1);
        let line = &lines[0];
        assert!(line.len() > 20);
        for &(x, y) in line {
            let r = (x * x + y * y).sqrt();
            assert!((r - 0.5).abs() < 0.01, "r = {r}");
        }
        let first = line[0];
        let last = line[line.len() - 1];
        assert!((first.0 - last.0).abs() < 1e-9 && (first.1 - last.1).abs() < 1e-9);
    }
}
