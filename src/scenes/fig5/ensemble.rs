//! The ensembles of the spring-array scenes (Figs. 5.7-5.11): unit-RMS rough surfaces of many
//! samples, the displacement window of a cycle over them, their uncoupled cycles, adhesion
//! efficiencies and the mean and spread over the samples.

use crate::error::Result;
use crate::job::Job;
use crate::models::fibril::{K_CR_BAR, SingleSpring};
use crate::scenes::groups::{ArrayCycle, ArraySurface, SurfaceSamples};

/// Heights z̄ = z/σ of sample `seed`: a Gaussian-autocorrelation surface (appendix C) of
/// N x M points with σ_rms = 1 on a box of length 1 along ê₁ (so L_c is L̄_c = L_c/(100 µm)),
/// to be scaled by σ̄_rms. A single row (M = 1) is the first row of an N x 2 surface, shifted
/// to zero mean and scaled to unit RMS (its autocorrelation along ê₁ is the same Gaussian).
fn unit_surface(nx: usize, ny: usize, lc_bar: f64, seed: u64) -> Result<Vec<f64>> {
    let spectrum = crate::surface::Spectrum::Gaussian {
        rms: 1.0,
        correlation_length: lc_bar,
    };
    let gy = ny.max(2);
    let map = crate::surface::generate(&spectrum, nx, gy, 1.0, gy as f64 / nx as f64, seed)?;
    let mut z = map.z;
    if gy != ny {
        z.truncate(nx * ny);
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        z.iter_mut().for_each(|v| *v -= mean);
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64).sqrt();
        if rms > 0.0 {
            z.iter_mut().for_each(|v| *v /= rms);
        }
    }
    Ok(z)
}

/// The displacement window of a cycle over a surface of roughness σ̄_rms: from `c_max` σ̄_rms
/// beyond the pull-off displacement (every spring detached) down to `c_min` σ̄_rms below the
/// pull-in displacement (every spring within that many σ_rms of the mean plane touched). Both
/// ends keep a margin of at least half the bistable width u_off − u_in (and 1 in ū), so that a
/// nearly flat surface (σ̄_rms far below the displacement step) is still fully loaded and
/// unloaded, and the last step before each fold does not end a hair past it.
pub(super) fn cycle_window(k_e: f64, sigma_bar: f64, c_min: f64, c_max: f64) -> Result<(f64, f64)> {
    let s = SingleSpring::new(k_e)?;
    let (u_in, u_off) = s.bistable_range().unwrap_or((1.0, 1.0));
    let margin = (0.5 * (u_off - u_in)).max(1.0);
    Ok((
        u_off + (c_max * sigma_bar).max(margin),
        u_in - (c_min * sigma_bar).max(margin),
    ))
}

impl ArrayCycle {
    /// The displacement window of this cycle over a surface of roughness σ̄_rms
    /// ([`cycle_window`] with `depth_sigmas` and `end_sigmas`).
    pub(super) fn window(&self, k_e: f64, sigma_bar: f64) -> Result<(f64, f64)> {
        cycle_window(k_e, sigma_bar, self.depth_sigmas, self.end_sigmas)
    }
}

impl ArraySurface {
    /// Heights z̄ = z/σ of the N x M surface of `seed`: the unit surface scaled by σ̄_rms.
    pub(super) fn heights(&self, nx: usize, ny: usize, seed: u64) -> Result<Vec<f64>> {
        let mut z = unit_surface(nx, ny, self.correlation_length, seed)?;
        z.iter_mut().for_each(|v| *v *= self.roughness);
        Ok(z)
    }
}

/// k̄_e of k̂_e = k_e/k_cr = 2⁻ⁿ (section 5.5.2).
pub(super) fn k_bar_of_n(n: f64) -> f64 {
    K_CR_BAR * 2f64.powf(-n)
}

/// Mean and sample standard deviation.
pub(super) fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    (mean, var.sqrt())
}

/// Unit-RMS N x N surfaces of correlation length L̄_c, of samples `seed .. seed + samples`
/// (rayon over samples).
pub(super) fn unit_surfaces(samples: &SurfaceSamples, lc_bar: f64, job: &Job) -> Result<Vec<Vec<f64>>> {
    use rayon::prelude::*;
    let n = samples.springs;
    let done = job.ticker(samples.samples, "surfaces", 0.0, 1.0);
    (0..samples.samples)
        .into_par_iter()
        .map(|k| {
            job.check()?;
            let surface = unit_surface(n, n, lc_bar, samples.seed + k as u64);
            done.tick();
            surface
        })
        .collect()
}

/// Uncoupled cycles over unit surfaces scaled by σ̄_rms (binned path, tables shared by the
/// samples, rayon over samples).
pub(super) fn uncoupled_samples(
    unit: &[Vec<f64>],
    sigma_bar: f64,
    k_e: f64,
    cycle: &ArrayCycle,
    oversample: usize,
    job: &Job,
) -> Result<Vec<crate::models::spring_array::ArrayCycle>> {
    use rayon::prelude::*;
    let window = cycle.window(k_e, sigma_bar)?;
    let (lo, hi) = unit
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let tables = crate::models::spring_array::BinnedBranches::new(
        k_e,
        window.0,
        window.1,
        cycle.steps,
        oversample,
        (sigma_bar * lo, sigma_bar * hi),
    )?;
    let done = job.ticker(unit.len(), "samples", 0.0, 1.0);
    unit.par_iter()
        .map(|u| {
            job.check()?;
            let z: Vec<f64> = u.iter().map(|v| v * sigma_bar).collect();
            let cycle = tables.cycle(&z);
            done.tick();
            cycle
        })
        .collect()
}

/// The adhesion efficiency (5.36) of each cycle of an array of `springs` springs.
pub(super) fn efficiencies(cycles: &[crate::models::spring_array::ArrayCycle], springs: usize) -> Vec<f64> {
    cycles
        .iter()
        .map(|cy| crate::models::spring_array::adhesion_efficiency(cy, springs))
        .collect()
}
