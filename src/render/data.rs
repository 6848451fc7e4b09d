//! The figure as data: long-form CSV (`panel,series,style,x,y`, one row per point) and a JSON
//! record of the run (scene, caption, parameters with units, named results, fields, notes and
//! the notes drawn on panels, crate version, run time).
//!
//! CSV rows: every series point (style `stable`, `unstable`, `reference`, `scatter`,
//! `errorbar`, `contour`, `jump`), every marker (style = its shape: `pull-in`, `pull-off`, ...),
//! the vertices of shaded regions (style `region`), arrows (style `arrow`, tail then head), and
//! the contour lines of fields (style `contour`, series `<field>=<level>`). The `panel` column
//! is the panel's number, starting at 1. Field grids themselves are in the JSON.

use serde::Serialize;

use crate::figure::{Figure, Style};
use crate::params::{ParamValues, value_text};

/// Quote a CSV cell when needed.
fn cell(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Shortest text that reads back to the same f64 (`NaN` and `inf` as such).
fn num(v: f64) -> String {
    format!("{v}")
}

/// The long-form CSV of a figure.
pub fn csv(fig: &Figure) -> String {
    let mut out = String::from("panel,series,style,x,y\n");
    let mut row = |panel: usize, series: &str, style: &str, x: f64, y: f64| {
        out.push_str(&format!(
            "{},{},{},{},{}\n",
            panel,
            cell(series),
            style,
            num(x),
            num(y)
        ));
    };
    for (k, p) in fig.panels.iter().enumerate() {
        let k = k + 1;
        for s in &p.series {
            for &(x, y) in &s.points {
                row(k, &s.name, s.style.as_str(), x, y);
            }
        }
        for m in &p.markers {
            let name = match &m.label {
                Some(l) => format!("{} {}", m.name, l),
                None => m.name.clone(),
            };
            row(k, &name, m.shape.as_str(), m.x, m.y);
        }
        for r in &p.regions {
            for &(x, y) in &r.points {
                row(k, &r.name, "region", x, y);
            }
        }
        for a in &p.arrows {
            row(k, "arrow", "arrow", a.from.0, a.from.1);
            row(k, "arrow", "arrow", a.to.0, a.to.1);
        }
        if let Some(f) = &p.field {
            for level in f.contour_levels() {
                let name = format!("{}={}", f.name, num(level));
                for line in f.contour(level) {
                    for (x, y) in line {
                        row(k, &name, Style::Contour.as_str(), x, y);
                    }
                }
            }
        }
    }
    out
}

#[derive(Serialize)]
struct ParamRecord {
    name: &'static str,
    value: serde_json::Value,
    unit: &'static str,
    meaning: &'static str,
}

#[derive(Serialize)]
struct FieldRecord<'a> {
    panel: usize,
    name: &'a str,
    unit: &'a str,
    x: &'a [f64],
    y: &'a [f64],
    /// Row-major in y: values[j][i] at (x[i], y[j]).
    values: Vec<&'a [f64]>,
}

/// The notes drawn on one panel.
#[derive(Serialize)]
struct PanelNotes<'a> {
    /// Panel number, from 1 (as the CSV's `panel`).
    panel: usize,
    notes: &'a [String],
}

#[derive(Serialize)]
struct Record<'a> {
    scene: &'a str,
    title: &'a str,
    caption: &'a str,
    parameters: Vec<ParamRecord>,
    results: serde_json::Map<String, serde_json::Value>,
    notes: &'a [String],
    /// What the run computed more coarsely than the full figure (absent at full resolution).
    #[serde(skip_serializing_if = "Option::is_none")]
    quick_form: Option<&'a str>,
    /// The notes drawn on the panels (what a panel finds against the text).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    panel_notes: Vec<PanelNotes<'a>>,
    fields: Vec<FieldRecord<'a>>,
    crate_name: &'static str,
    version: &'static str,
    run_time_s: f64,
}

/// A JSON value for a TOML value (numbers stay numbers; NaN becomes null).
fn json_value(v: &toml::Value) -> serde_json::Value {
    match v {
        toml::Value::Float(x) => {
            serde_json::Number::from_f64(*x).map_or(serde_json::Value::Null, serde_json::Value::Number)
        }
        toml::Value::Integer(i) => serde_json::Value::from(*i),
        toml::Value::Boolean(b) => serde_json::Value::Bool(*b),
        toml::Value::String(s) => serde_json::Value::String(s.clone()),
        toml::Value::Array(items) => serde_json::Value::Array(items.iter().map(json_value).collect()),
        other => serde_json::Value::String(value_text(other)),
    }
}

/// The JSON record of a run.
pub fn json(fig: &Figure, caption: &str, params: &ParamValues, run_time_s: f64) -> String {
    let parameters = params
        .specs
        .iter()
        .zip(&params.values)
        .map(|(s, v)| ParamRecord {
            name: s.name,
            value: json_value(v),
            unit: s.unit,
            meaning: s.help,
        })
        .collect();
    let results = fig
        .results
        .iter()
        .map(|(n, v)| {
            let value =
                serde_json::Number::from_f64(*v).map_or(serde_json::Value::Null, serde_json::Value::Number);
            (n.clone(), value)
        })
        .collect();
    let fields = fig
        .panels
        .iter()
        .enumerate()
        .filter_map(|(k, p)| p.field.as_ref().map(|f| (k, f)))
        .map(|(k, f)| FieldRecord {
            panel: k + 1,
            name: &f.name,
            unit: &f.unit,
            x: &f.x,
            y: &f.y,
            values: f.values.chunks(f.x.len().max(1)).collect(),
        })
        .collect();
    let record = Record {
        scene: &fig.id,
        title: &fig.title,
        caption,
        parameters,
        results,
        notes: &fig.notes,
        quick_form: fig.quick_form.as_deref(),
        panel_notes: fig
            .panels
            .iter()
            .enumerate()
            .filter(|(_, p)| !p.notes.is_empty())
            .map(|(k, p)| PanelNotes {
                panel: k + 1,
                notes: &p.notes,
            })
            .collect(),
        fields,
        crate_name: env!("CARGO_PKG_NAME"),
        version: env!("CARGO_PKG_VERSION"),
        run_time_s,
    };
    serde_json::to_string_pretty(&record).expect("the record has only string keys and finite-or-null numbers")
}

/// An earlier run drawn in the same figure (a pinned run of the terminal UI).
#[derive(Debug, Clone, Copy)]
pub struct RunRecord<'a> {
    /// Its legend label (what differs from the current run).
    pub label: &'a str,
    /// Its parameters.
    pub params: &'a ParamValues,
    /// Its named results.
    pub results: &'a [(String, f64)],
    /// Its wall time in seconds.
    pub run_time_s: f64,
}

/// [`json`] with the earlier runs drawn in the figure under `pinned_runs`: label, parameters
/// (name, value, unit), results and run time of each.
pub fn json_with_runs(
    fig: &Figure,
    caption: &str,
    params: &ParamValues,
    run_time_s: f64,
    runs: &[RunRecord<'_>],
) -> String {
    let text = json(fig, caption, params, run_time_s);
    if runs.is_empty() {
        return text;
    }
    let Ok(serde_json::Value::Object(mut record)) = serde_json::from_str::<serde_json::Value>(&text) else {
        return text;
    };
    let number =
        |v: f64| serde_json::Number::from_f64(v).map_or(serde_json::Value::Null, serde_json::Value::Number);
    let runs: Vec<serde_json::Value> = runs
        .iter()
        .map(|r| {
            let parameters: Vec<serde_json::Value> = r
                .params
                .specs
                .iter()
                .zip(&r.params.values)
                .map(|(s, v)| serde_json::json!({ "name": s.name, "value": json_value(v), "unit": s.unit }))
                .collect();
            let results: serde_json::Map<String, serde_json::Value> =
                r.results.iter().map(|(n, v)| (n.clone(), number(*v))).collect();
            serde_json::json!({
                "label": r.label,
                "parameters": parameters,
                "results": results,
                "run_time_s": number(r.run_time_s),
            })
        })
        .collect();
    record.insert("pinned_runs".into(), serde_json::Value::Array(runs));
    serde_json::to_string_pretty(&record).unwrap_or(text)
}

/// One parsed CSV row: panel, series, style, x, y.
pub type CsvRow = (usize, String, String, f64, f64);

/// Read a long-form CSV back into rows (for tests and for users' round trips).
///
/// # Errors
/// A description of the first malformed line.
pub fn parse_csv(text: &str) -> Result<Vec<CsvRow>, String> {
    let mut lines = text.lines();
    match lines.next() {
        Some("panel,series,style,x,y") => {}
        other => return Err(format!("bad header {other:?}")),
    }
    let mut rows = Vec::new();
    for (k, line) in lines.enumerate() {
        let fields = split_csv_line(line);
        let bad = || format!("line {}: `{line}`", k + 2);
        if fields.len() != 5 {
            return Err(bad());
        }
        let panel = fields[0].parse().map_err(|_| bad())?;
        let x = fields[3].parse().map_err(|_| bad())?;
        let y = fields[4].parse().map_err(|_| bad())?;
        rows.push((panel, fields[1].clone(), fields[2].clone(), x, y));
    }
    Ok(rows)
}

/// Split one CSV line, honouring double quotes.
pub fn split_csv_line(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut cur)),
            (c, _) => cur.push(c),
        }
    }
    out.push(cur);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::{Axis, Panel, Series};

    #[test]
    fn csv_round_trips_names_with_commas_and_exact_floats() {
        let mut p = Panel::new(Axis::linear("x", ""), Axis::linear("y", ""));
        p.add(Series::new(
            "a, \"b\"",
            Style::Unstable,
            vec![(0.1, 1.0 / 3.0), (1e-300, -2.5e7)],
        ));
        let fig = Figure::new("t", "t").with_panel(p);
        let rows = parse_csv(&csv(&fig)).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].1, "a, \"b\"");
        assert_eq!(rows[0].2, "unstable");
        assert_eq!(rows[0].4, 1.0 / 3.0);
        assert_eq!(rows[1].3, 1e-300);
    }
}
