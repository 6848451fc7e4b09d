//! Arrays of uncoupled springs on random rough surfaces (sections 5.4-5.5): the
//! force-displacement cycles of Fig. 5.7.

use super::ensemble::{efficiencies, k_bar_of_n, mean_std, uncoupled_samples, unit_surfaces};
use crate::error::Result;
use crate::figure::{Axis, Figure, Legend, Panel, Series, Style};
use crate::job::Job;
use crate::params::{Range, require_non_empty};
use crate::scenes::groups::{ArrayCycle, SurfaceSamples};
use crate::scenes::{Scene, SceneHeader};

crate::param_choice! {
    /// Path for uncoupled arrays.
    pub enum UncoupledPath { Binned = "binned", Exact = "exact" }
}

crate::scene_params! {
    /// Parameters of scene fig5.7 (section 5.5.2).
    pub struct Fig5_7Params {
        /// Stiffness exponent n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponent: f64 = 7.0, unit = "", range = Range::open(0.0, 30.0);
        /// Normalized roughnesses σ̄_rms = σ_rms/σ of the curves.
        roughness: Vec<f64> = vec![10.0, 25.0, 50.0, 100.0], unit = "", range = Range::positive();
        /// Normalized correlation length L̄_c = L_c/(100 µm).
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// The springs and their surfaces.
        group surfaces: SurfaceSamples
            help { seed: "Seed of the first sample (sample k uses seed + k)." };
        /// The displacement cycle.
        group cycle: ArrayCycle;
        /// Height bins per displacement step of the binned path.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
        /// Uncoupled path: binned (convolution) or exact (spring by spring).
        path: UncoupledPath = UncoupledPath::Binned, unit = "", range = Range::any();
    }
}

/// Panel (b) of Fig. 5.7: the cycles of `full` framed on their tensile part. Forces from 15 %
/// below the most negative one to as far above zero; displacements over the points in that
/// band whose force is not yet (or no longer) negligible (|P| above 2 % of the most negative
/// force), so the range ends where the slowest decay reaches zero. One arrow per branch, at the
/// middle of its part inside the frame, gives the direction of travel.
fn adhesive_window(full: &Panel) -> Panel {
    let mut zoom = full.clone().titled("(b)", "tensile part, where the loops lie");
    zoom.arrows.clear();
    zoom.legend = Legend::Hidden;
    let y_min = full
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(0.0f64, f64::min);
    if y_min >= 0.0 {
        return zoom;
    }
    let (y_lo, y_hi) = (1.15 * y_min, -y_min);
    let inside = |p: &(f64, f64)| p.1 >= y_lo && p.1 <= y_hi && p.1.abs() >= 0.02 * -y_min;
    let (x_lo, x_hi) = full
        .series
        .iter()
        .flat_map(|s| s.points.iter().filter(|p| inside(p)).map(|p| p.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if x_hi <= x_lo {
        return zoom;
    }
    let dx = 0.05 * (x_hi - x_lo);
    zoom.x = zoom.x.clone().with_range(x_lo - dx, x_hi + dx);
    zoom.y = zoom.y.clone().with_range(y_lo, y_hi);
    for s in &full.series {
        let idx: Vec<usize> = (0..s.points.len().saturating_sub(1))
            .filter(|&i| inside(&s.points[i]) && s.points[i].0 >= x_lo && s.points[i].0 <= x_hi)
            .collect();
        if let Some(&k) = idx.get(idx.len() / 2) {
            zoom.arrow(s.points[k], s.points[k + 1], s.color);
        }
    }
    zoom
}

crate::scene! {
    /// Fig. 5.7: force-displacement cycles of uncoupled spring arrays on rough surfaces.
    pub struct Fig5_7 {
        id: "fig5.7",
        chapter: "5",
        params: Fig5_7Params,
        title: "Spring-array force-displacement cycles on rough surfaces",
        caption: "Total force P/(MN |P_m|) (positive in compression) against the displacement \
            u/sigma over a loading-unloading cycle of 256 x 256 uncoupled springs, k_e = 2^-7 k_cr, on Gaussian \
            rough surfaces of several sigma_rms/sigma, averaged over the samples: the sum of shifted single-spring \
            branches (5.35). (a) The whole cycles (the roughest surface sets the range); (b) the tensile part, \
            where the smoother surfaces' loops lie. Arrows: loading to the left, unloading to the right.",
        results: &[
            ("efficiency_first_norm", "adhesion efficiency (5.36) of the first roughness, sample mean"),
            ("efficiency_last_norm", "adhesion efficiency (5.36) of the last roughness, sample mean"),
        ],
    }
}

impl Scene for Fig5_7 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_non_empty("roughness", &p.roughness)
    }

    fn quick(p: &mut Self::Params) {
        p.surfaces.quick();
        p.cycle.quick();
        p.roughness.truncate(2);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let k_e = k_bar_of_n(p.stiffness_exponent);
        let n = p.surfaces.springs;
        let norm =
            p.surfaces.count() as f64 * crate::models::spring_array::single_spring_adhesive_force().abs();
        let mut panel = Panel::new(
            Axis::linear("Displacement u/σ", ""),
            Axis::linear("Force P/(MN |P_m|)", ""),
        )
        .titled(
            "(a)",
            format!("whole cycles, k_e = 2^-{} k_cr", p.stiffness_exponent),
        );
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut effs = Vec::new();
        // Progress: the surfaces (about 4 % of a run at the defaults), then each roughness's
        // cycles sample by sample.
        let unit = unit_surfaces(&p.surfaces, p.correlation_length, &job.part(0.0, 0.04))?;
        let stages = job.parts(&vec![1.0; p.roughness.len()], 0.04, 0.99);
        for ((c, &sigma), stage) in p.roughness.iter().enumerate().zip(&stages) {
            job.check()?;
            stage.progress(0.0, &format!("σ_rms/σ = {sigma}"));
            let cycles = match p.path {
                UncoupledPath::Binned => uncoupled_samples(&unit, sigma, k_e, &p.cycle, p.oversample, stage)?,
                UncoupledPath::Exact => {
                    use rayon::prelude::*;
                    let window = p.cycle.window(k_e, sigma)?;
                    let done = stage.ticker(p.surfaces.samples, "samples", 0.0, 1.0);
                    (0..p.surfaces.samples)
                        .into_par_iter()
                        .map(|k| {
                            job.check()?;
                            let z: Vec<f64> = unit[k].iter().map(|v| v * sigma).collect();
                            let a = crate::models::spring_array::SpringArray::new(n, n, k_e, 0.0, z)?;
                            let cycle = crate::models::spring_array::uncoupled_cycle(
                                &a,
                                window.0,
                                window.1,
                                p.cycle.steps,
                            );
                            done.tick();
                            cycle
                        })
                        .collect::<Result<Vec<_>>>()?
                }
            };
            let m = cycles.len() as f64;
            let avg = |sel: fn(
                &crate::models::spring_array::ArrayCycle,
            ) -> &Vec<crate::models::spring_array::ArrayStep>| {
                let first = sel(&cycles[0]);
                (0..first.len())
                    .map(|i| {
                        let f = cycles.iter().map(|cy| sel(cy)[i].force).sum::<f64>() / m;
                        (first[i].u, f / norm)
                    })
                    .collect::<Vec<_>>()
            };
            let name = format!("σ_rms/σ = {sigma}");
            let load = avg(|c| &c.loading);
            let unload = avg(|c| &c.unloading);
            let k = load.len() / 3;
            panel.arrow(load[k], load[k + 1], Some(c));
            panel.arrow(unload[k], unload[k + 1], Some(c));
            panel.add(Series::new(&name, Style::Stable, load).with_color(c));
            panel.add(Series::new(&name, Style::Stable, unload).with_color(c));
            effs.push(mean_std(&efficiencies(&cycles, p.surfaces.count())).0);
        }
        let zoom = adhesive_window(&panel);
        fig.panels.push(panel);
        fig.panels.push(zoom);
        fig.result("efficiency_first_norm", effs[0]);
        fig.result("efficiency_last_norm", *effs.last().unwrap_or(&f64::NAN));
        fig.note("arrows give the direction of travel: loading to the left, unloading to the right");
        job.progress(1.0, "done");
        Ok(fig)
    }
}
