//! The state of the force-curve file page: a measured file ([`crate::readers`]) opened in the
//! terminal UI, its curves on the map's grid (one cell for a single curve), the chosen curve,
//! the fit settings (tip radius, model, segment) and the fits done so far. Plain data and the
//! moves on it; the app turns keys into these moves and fits into [`crate::tui::app::Effect`]s,
//! the view draws it.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use crate::figure::{Axis, Figure, Panel, Series, Style};
use crate::fit::instrument::CurveFit;
use crate::fit::map::{Layout, layout};
use crate::fit::{FitModel, FitSettings, SegmentChoice};
use crate::readers::{ForceCurve, ForceFile};

/// The models in the order Space cycles them (`None`: the default of [`FitSettings::model`]).
pub const MODELS: [Option<FitModel>; 6] = [
    None,
    Some(FitModel::Jkr),
    Some(FitModel::MachineStiffness),
    Some(FitModel::Dmt),
    Some(FitModel::MaugisDugdale),
    Some(FitModel::Hertz),
];

/// The segments in the order Tab cycles them (`None`: the model's default).
pub const SEGMENTS: [Option<SegmentChoice>; 4] = [
    None,
    Some(SegmentChoice::Retract),
    Some(SegmentChoice::Approach),
    Some(SegmentChoice::Both),
];

/// A finished fit of one curve: the report, and the figure of data, fit and residuals
/// ([`crate::fit::fit_figure`]).
#[derive(Debug, Clone)]
pub struct FittedCurve {
    /// The preprocessing and the fit.
    pub fit: CurveFit,
    /// (a) the measured curve with the fitted model, (b) the residuals of the fitted rows.
    pub figure: Figure,
    /// Wall time of the fit in seconds.
    pub run_time_s: f64,
}

/// A fit in the background.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fitting {
    /// Run id.
    pub job: u64,
    /// Position of the curve in the file.
    pub curve: usize,
}

/// An opened force-curve file and what has been done with it.
#[derive(Debug, Clone)]
pub struct FilePage {
    /// The file.
    pub path: PathBuf,
    /// Its format and curves.
    pub file: Arc<ForceFile>,
    /// Where each curve sits on the map's grid.
    pub grid: Layout,
    /// The chosen curve (position in the file).
    pub selected: usize,
    /// Tip radius R [m]; no fit without it (no default: the fitted w and ℰ scale with it).
    pub radius: Option<f64>,
    /// The model (`None`: machine-stiffness with a spring constant, else JKR).
    pub model: Option<FitModel>,
    /// The segment (`None`: the model's default).
    pub segment: Option<SegmentChoice>,
    /// The finished fits by curve position, or why the curve could not be fitted.
    pub fits: HashMap<usize, Result<FittedCurve, String>>,
    /// The fit in the background.
    pub fitting: Option<Fitting>,
}

impl FilePage {
    /// The page of a freshly read file: the first curve chosen, nothing fitted.
    pub fn new(path: PathBuf, file: ForceFile) -> Self {
        let grid = layout(&file.curves);
        Self {
            path,
            file: Arc::new(file),
            grid,
            selected: 0,
            radius: None,
            model: None,
            segment: None,
            fits: HashMap::new(),
            fitting: None,
        }
    }

    /// The chosen curve.
    pub fn curve(&self) -> Option<&ForceCurve> {
        self.file.curves.get(self.selected)
    }

    /// The settings of a fit, once the tip radius is given.
    pub fn settings(&self) -> Option<FitSettings> {
        Some(FitSettings {
            radius: self.radius?,
            spring_constant: None,
            model: self.model,
            segment: self.segment,
            poisson: None,
        })
    }

    /// The curve at grid cell `cell`, if any.
    pub fn curve_at(&self, cell: [usize; 2]) -> Option<usize> {
        self.grid.cells.iter().position(|c| *c == cell)
    }

    /// Move the choice by (`dx`, `dy`) cells on the grid (y up), skipping empty cells; stays at
    /// the edge. Returns whether the choice changed.
    pub fn step(&mut self, dx: isize, dy: isize) -> bool {
        let Some(&[i, j]) = self.grid.cells.get(self.selected) else {
            return false;
        };
        let [nx, ny] = self.grid.shape;
        let (mut x, mut y) = (i as isize, j as isize);
        loop {
            x += dx;
            y += dy;
            if x < 0 || y < 0 || x >= nx as isize || y >= ny as isize {
                return false;
            }
            if let Some(k) = self.curve_at([x as usize, y as usize]) {
                self.selected = k;
                return true;
            }
        }
    }

    /// Forget every fit (the settings changed).
    pub fn clear_fits(&mut self) {
        self.fits.clear();
    }

    /// The settings in words: `R = 2 µm · model: default (machine-stiffness) · segment: default`.
    pub fn settings_text(&self) -> String {
        let radius = self.radius.map_or("not set (t sets it)".to_string(), |r| {
            crate::render::labels::fmt_quantity(r, "m")
        });
        format!(
            "R = {radius} · model: {} · segment: {}",
            model_name(self.model),
            segment_name(self.segment)
        )
    }
}

/// A model in words.
pub fn model_name(model: Option<FitModel>) -> &'static str {
    match model {
        None => "default",
        Some(FitModel::Hertz) => "Hertz",
        Some(FitModel::Dmt) => "DMT",
        Some(FitModel::Jkr) => "JKR",
        Some(FitModel::MachineStiffness) => "machine-stiffness",
        Some(FitModel::MaugisDugdale) => "Maugis-Dugdale",
    }
}

/// A segment in words.
pub fn segment_name(segment: Option<SegmentChoice>) -> &'static str {
    match segment {
        None => "default",
        Some(SegmentChoice::Approach) => "approach",
        Some(SegmentChoice::Retract) => "retract",
        Some(SegmentChoice::Both) => "both",
    }
}

/// The next of `options` after `current` (cyclic).
pub fn next_of<T: PartialEq + Copy>(options: &[T], current: T) -> T {
    let at = options.iter().position(|o| *o == current).unwrap_or(0);
    options[(at + 1) % options.len()]
}

/// The raw curve as the file holds it: force [nN] against the cantilever height [nm], one
/// series per segment, for the page before a fit.
pub fn raw_panel(curve: &ForceCurve) -> Panel {
    let mut panel = Panel::new(Axis::linear("height", "nm"), Axis::linear("force", "nN"))
        .titled("", format!("curve {} as recorded", curve.index));
    for (k, s) in curve.segments.iter().enumerate() {
        let Some(h) = s.height() else { continue };
        let pts: Vec<(f64, f64)> = h
            .iter()
            .zip(&s.force)
            .filter(|(z, f)| z.is_finite() && f.is_finite())
            .map(|(z, f)| (z * 1e9, f * 1e9))
            .collect();
        let name = match &s.kind {
            Some(kind) => format!("{kind:?}").to_lowercase(),
            None => format!("segment {}", k + 1),
        };
        panel.add(Series::new(name, Style::Stable, pts));
    }
    panel
}
