//! Force maps: every curve of a map file fitted ([`super::instrument::fit_all`], in parallel)
//! and the fitted values drawn as maps over the grid: the plane-strain modulus ℰ, the work of
//! adhesion w, the measured pull-off force, the contact point and the rms residual. A curve that
//! fails is named with its reason in the JSON and on stderr, and drawn as an empty cell, never
//! filled in.

use serde::Serialize;

use super::instrument::CurveFit;
use crate::error::Result;
use crate::figure::{Axis, Field, Figure, Panel};
use crate::readers::ForceCurve;

/// A curve that could not be fitted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failure {
    /// Index of the curve in its file.
    pub curve: usize,
    /// Grid index (x, y), where the file gives one.
    pub grid_index: Option<[usize; 2]>,
    /// Why, one line.
    pub reason: String,
}

/// Where each curve sits on the map's grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layout {
    /// Grid columns and rows.
    pub shape: [usize; 2],
    /// Cell (i, j) of each curve, in file order.
    pub cells: Vec<[usize; 2]>,
    /// Cell size [m] (x, y), where the file gives the grid's size; the maps are then in µm.
    pub cell_size_m: Option<[f64; 2]>,
    /// How the layout was found, in words.
    pub source: String,
}

/// The grid of a map: the file's grid indices where every curve has one inside the declared
/// shape (and no two share a cell), otherwise the curves in file order, row by row, on a
/// near-square grid (and `source` says so).
pub fn layout(curves: &[ForceCurve]) -> Layout {
    let n = curves.len().max(1);
    let shape = curves.iter().find_map(|c| c.meta.grid_shape);
    if let Some([nx, ny]) = shape
        && nx > 0
        && ny > 0
        && nx.saturating_mul(ny) <= 1 << 24
    {
        let cells: Option<Vec<[usize; 2]>> = curves
            .iter()
            .map(|c| c.meta.grid_index.filter(|[i, j]| *i < nx && *j < ny))
            .collect();
        if let Some(cells) = cells {
            let mut seen = std::collections::HashSet::new();
            if cells.iter().all(|c| seen.insert(*c)) {
                let size = curves.iter().find_map(|c| c.meta.grid_size);
                return Layout {
                    shape: [nx, ny],
                    cells,
                    cell_size_m: size.map(|[sx, sy]| [sx / nx as f64, sy / ny as f64]),
                    source: "the file's grid indices".into(),
                };
            }
        }
    }
    let nx = (n as f64).sqrt().ceil() as usize;
    let ny = n.div_ceil(nx);
    Layout {
        shape: [nx, ny],
        cells: (0..curves.len()).map(|k| [k % nx, k / nx]).collect(),
        cell_size_m: None,
        source: "no grid indices in the file: the curves in file order, row by row".into(),
    }
}

/// The quantities drawn, as (name, unit, scale from SI, value of a fit).
type Quantity = (&'static str, &'static str, f64, fn(&CurveFit) -> Option<f64>);

const QUANTITIES: &[Quantity] = &[
    ("Plane-strain modulus ℰ", "kPa", 1e-3, |f| {
        Some(f.fit.plane_strain_modulus_pa.value)
    }),
    ("Work of adhesion w", "mJ/m²", 1e3, |f| {
        f.fit.work_of_adhesion_j_per_m2.map(|w| w.value)
    }),
    ("Pull-off force (measured)", "nN", 1e9, |f| {
        Some(f.fit.measured_pull_off_force_n)
    }),
    ("Contact point d_c", "nm", 1e9, |f| {
        Some(f.fit.contact_point_m.value)
    }),
    ("RMS residual", "nN", 1e9, |f| Some(f.fit.rms_residual_n)),
];

/// The map figure over the grid `lay` (of [`layout`]): one heat-map panel per quantity that the
/// model has.
///
/// # Errors
/// None at present (kept for the figure builders' common signature).
pub fn map_figure(lay: &Layout, fits: &[Result<CurveFit>], title: &str) -> Result<Figure> {
    let [nx, ny] = lay.shape;
    let (sx, sy, unit) = match lay.cell_size_m {
        Some([a, b]) => (a * 1e6, b * 1e6, "µm"),
        None => (1.0, 1.0, ""),
    };
    let xs: Vec<f64> = (0..nx).map(|i| (i as f64 + 0.5) * sx).collect();
    let ys: Vec<f64> = (0..ny).map(|j| (j as f64 + 0.5) * sy).collect();
    let mut fig = Figure::new("fit-map", title);
    let letters = "abcdefgh";
    let mut k = 0;
    for (name, qunit, scale, get) in QUANTITIES {
        let mut values = vec![f64::NAN; nx * ny];
        let mut any = false;
        for (fit, cell) in fits.iter().zip(&lay.cells) {
            if let Ok(f) = fit
                && let Some(v) = get(f)
            {
                values[cell[1] * nx + cell[0]] = v * scale;
                any = true;
            }
        }
        if !any {
            continue;
        }
        let (xl, yl) = if unit.is_empty() {
            (Axis::linear("Grid column", ""), Axis::linear("Grid row", ""))
        } else {
            (Axis::linear("x", unit), Axis::linear("y", unit))
        };
        let mut panel = Panel::new(xl, yl)
            .titled(format!("({})", &letters[k..k + 1]), *name)
            .with_equal_aspect();
        panel.field = Some(Field::heat(*name, *qunit, xs.clone(), ys.clone(), values));
        fig = fig.with_panel(panel);
        k += 1;
    }
    let failed = fits.iter().filter(|f| f.is_err()).count();
    let warned = fits
        .iter()
        .filter(|f| f.as_ref().is_ok_and(|f| !f.fit.warnings.is_empty()))
        .count();
    let n = fits.len();
    fig.result("curves_count", n as f64);
    fig.result("failed_count", failed as f64);
    fig.result("warned_count", warned as f64);
    fig.note(format!(
        "{} curves, {} fitted ({} with warnings), {} failed (empty cells); layout: {}",
        n,
        n - failed,
        warned,
        failed,
        lay.source
    ));
    Ok(fig)
}

/// One CSV row per curve: its place, the fitted values with standard errors, the measured
/// pull-off, the warnings' count, and the error of a curve that failed.
pub fn table_csv(curves: &[ForceCurve], lay: &Layout, fits: &[Result<CurveFit>]) -> String {
    let mut out = String::from(
        "curve,grid_x,grid_y,position_x_m,position_y_m,plane_strain_modulus_pa,plane_strain_modulus_std_error_pa,work_of_adhesion_j_per_m2,work_of_adhesion_std_error_j_per_m2,contact_point_m,contact_point_std_error_m,baseline_n,measured_pull_off_force_n,rms_residual_n,warnings,error\n",
    );
    let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for ((c, fit), cell) in curves.iter().zip(fits).zip(&lay.cells) {
        let pos = c.meta.position;
        let head = format!(
            "{},{},{},{},{}",
            c.index,
            cell[0],
            cell[1],
            num(pos.map(|p| p[0])),
            num(pos.map(|p| p[1]))
        );
        match fit {
            Ok(f) => {
                let r = &f.fit;
                let w = r.work_of_adhesion_j_per_m2;
                out.push_str(&format!(
                    "{head},{},{},{},{},{},{},{},{},{},{},\n",
                    num(Some(r.plane_strain_modulus_pa.value)),
                    num(Some(r.plane_strain_modulus_pa.std_error)),
                    num(w.map(|w| w.value)),
                    num(w.map(|w| w.std_error)),
                    num(Some(r.contact_point_m.value)),
                    num(Some(r.contact_point_m.std_error)),
                    num(Some(r.baseline_n.value)),
                    num(Some(r.measured_pull_off_force_n)),
                    num(Some(r.rms_residual_n)),
                    r.warnings.len()
                ));
            }
            Err(e) => {
                let msg = e.to_string().replace('"', "'");
                out.push_str(&format!("{head},,,,,,,,,,,\"{msg}\"\n"));
            }
        }
    }
    out
}
