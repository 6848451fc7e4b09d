//! The adhesion efficiency of uncoupled spring arrays (section 5.5): against roughness and
//! stiffness (Fig. 5.8) and against the correlation length (Fig. 5.9), sweeps of many
//! surface samples.

use super::ensemble::{efficiencies, k_bar_of_n, mean_std, uncoupled_samples, unit_surfaces};
use crate::error::Result;
use crate::figure::{Axis, Figure, Panel, Series, Style, number};
use crate::job::Job;
use crate::numerics::curve::logspace;
use crate::params::{Range, fmt_sig, require_below, require_non_empty};
use crate::scenes::groups::{ArrayCycle, SurfaceSamples};
use crate::scenes::sweep::Sweep;
use crate::scenes::{Scene, SceneHeader};

crate::scene_params! {
    /// Parameters of scene fig5.8 (section 5.5.2).
    pub struct Fig5_8Params {
        /// Stiffness exponents n: k_e/k_cr = 2⁻ⁿ.
        stiffness_exponents: Vec<f64> = vec![6.0, 7.0, 8.0, 9.0, 10.0, 11.0], unit = "", range = Range::open(0.0, 30.0);
        /// Smallest normalized roughness σ̄_rms.
        roughness_min: f64 = 10.0, unit = "", range = Range::positive();
        /// Largest normalized roughness σ̄_rms.
        roughness_max: f64 = 1500.0, unit = "", range = Range::positive();
        /// Roughness values (log-spaced).
        roughness_points: usize = 10, unit = "", range = Range::between(2.0, 1000.0);
        /// Normalized correlation length L̄_c.
        correlation_length: f64 = 0.01, unit = "", range = Range::open(0.0, 1.0);
        /// The springs and their surfaces.
        group surfaces: SurfaceSamples;
        /// The displacement cycle.
        group cycle: ArrayCycle;
        /// Height bins per displacement step.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
    }
}

/// Axis title of the adhesion efficiency, with its definition (5.36).
const EFFICIENCY_LABEL: &str = "Adhesion efficiency α_F = P_max/(MN P_m)";

/// RMS deviation of the simulated efficiency from (5.37) up to which the fit counts as matching
/// the data: 5 % of the efficiency's range [0, 1], three times the spread of the sample means.
const FIT_MATCH_RMS: f64 = 0.05;

/// What Fig. 5.8 finds about (5.37), against the text (section 5.5.2), which finds that it
/// matches for n = 6-8 and deviates for n = 9-11: the stiffness exponents whose RMS deviation
/// exceeds [`FIT_MATCH_RMS`], or that it fits every one, with the deviations' range.
fn fit_verdict(exponents: &[f64], deviations: &[f64]) -> String {
    let (lo, hi) = deviations
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &d| {
            (a.min(d), b.max(d))
        });
    let off: Vec<String> = exponents
        .iter()
        .zip(deviations)
        .filter(|(_, d)| **d > FIT_MATCH_RMS)
        .map(|(n, _)| fmt_sig(*n))
        .collect();
    let range = format!("RMS deviation {}-{}", number(lo, 2), number(hi, 2));
    if off.is_empty() {
        format!("(5.37) fits every n here ({range}); the text finds deviations for n = 9-11")
    } else {
        format!(
            "(5.37) deviates here for n = {} ({range}); the text finds deviations for n = 9-11",
            off.join(", ")
        )
    }
}

crate::scene! {
    /// Fig. 5.8: adhesion efficiency against roughness for several stiffnesses, with (5.37).
    pub struct Fig5_8 {
        id: "fig5.8",
        chapter: "5",
        params: Fig5_8Params,
        title: "Adhesion efficiency vs roughness and stiffness",
        caption: "Adhesion efficiency alpha_F = P_max/(MN P_m) (5.36) against sigma_rms/sigma for \
            k_e/k_cr = 2^-n, n = 6..11, 256 x 256 uncoupled springs, mean and standard deviation over 15 surfaces \
            (symbols, error bars) and the empirical fit exp(−4 sigma_rms/(sigma 2^n)) (5.37) (lines).",
        results: &[
            ("fit_rms_deviation_first_norm", "RMS over the roughness range of the simulated mean efficiency minus (5.37), first stiffness exponent"),
            ("fit_rms_deviation_last_norm", "as above, last stiffness exponent"),
            ("fit_rms_deviation_max_norm", "largest of these over the stiffness exponents"),
        ],
    }
}

impl Scene for Fig5_8 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_below("roughness_min", p.roughness_min, "roughness_max", p.roughness_max)?;
        require_non_empty("stiffness_exponents", &p.stiffness_exponents)
    }

    fn quick(p: &mut Self::Params) {
        p.surfaces.quick();
        p.cycle.quick();
        p.roughness_points = p.roughness_points.min(3);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        crate::scenes::sweep::run::<Self>(p, job)
    }
}

/// Fig. 5.8 is a sweep over (stiffness exponent, roughness): point `c·R + i` is exponent `c`
/// and roughness `i` (R roughness values), averaged over the samples of the unit surfaces
/// `seed .. seed + samples`, the same surfaces at every point (common random numbers, as in
/// Sec. 5.5.2). A point's result is the adhesion efficiency of each sample.
impl Sweep for Fig5_8 {
    type Context = Vec<Vec<f64>>;

    fn point_len(p: &Self::Params, _id: usize) -> usize {
        p.surfaces.samples
    }

    fn context(p: &Self::Params, job: &Job) -> Result<Self::Context> {
        unit_surfaces(&p.surfaces, p.correlation_length, job)
    }

    fn points(p: &Self::Params) -> Vec<String> {
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        p.stiffness_exponents
            .iter()
            .flat_map(|ne| {
                sigmas
                    .iter()
                    .map(move |s| format!("n = {ne}, σ_rms/σ = {}", fmt_sig(*s)))
            })
            .collect()
    }

    fn run_point(p: &Self::Params, unit: &Self::Context, id: usize, job: &Job) -> Result<Vec<f64>> {
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        let (ne, sigma) = (
            p.stiffness_exponents[id / sigmas.len()],
            sigmas[id % sigmas.len()],
        );
        let k_e = k_bar_of_n(ne);
        let cycles = uncoupled_samples(unit, sigma, k_e, &p.cycle, p.oversample, job)?;
        Ok(efficiencies(&cycles, p.surfaces.count()))
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let sigmas = logspace(p.roughness_min, p.roughness_max, p.roughness_points);
        let mut panel = Panel::new(
            Axis::log("Roughness σ_rms/σ", ""),
            Axis::linear(EFFICIENCY_LABEL, ""),
        );
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut deviations = Vec::with_capacity(p.stiffness_exponents.len());
        for (c, &ne) in p.stiffness_exponents.iter().enumerate() {
            let mut pts = Vec::new();
            let mut bars = Vec::new();
            let mut dev2 = 0.0;
            for (i, &sigma) in sigmas.iter().enumerate() {
                let (m, sd) = mean_std(&points[c * sigmas.len() + i]);
                pts.push((sigma, m));
                bars.push((sigma, m - sd));
                bars.push((sigma, m + sd));
                dev2 += (m - crate::models::spring_array::efficiency_fit(sigma, ne)).powi(2);
            }
            let name = format!("n = {ne}");
            panel.add(Series::new(&name, Style::Scatter, pts).with_color(c));
            panel.add(
                Series::new(&name, Style::ErrorBar, bars)
                    .with_color(c)
                    .without_legend(),
            );
            let fit: Vec<(f64, f64)> = logspace(p.roughness_min, p.roughness_max, 100)
                .into_iter()
                .map(|s| (s, crate::models::spring_array::efficiency_fit(s, ne)))
                .collect();
            panel.add(
                Series::new(&name, Style::Stable, fit)
                    .with_color(c)
                    .without_legend(),
            );
            deviations.push((dev2 / sigmas.len() as f64).sqrt());
        }
        fig.result("fit_rms_deviation_first_norm", deviations[0]);
        fig.result("fit_rms_deviation_last_norm", deviations[deviations.len() - 1]);
        fig.result(
            "fit_rms_deviation_max_norm",
            deviations.iter().copied().fold(0.0, f64::max),
        );
        panel.annotate(format!(
            "symbols: simulation, mean ± 1 s.d. over {} surfaces; lines: (5.37)",
            p.surfaces.samples
        ));
        panel.annotate(fit_verdict(&p.stiffness_exponents, &deviations));
        fig.panels.push(panel);
        job.progress(1.0, "done");
        Ok(fig)
    }
}

crate::scene_params! {
    /// Parameters of scene fig5.9 (section 5.5.2).
    pub struct Fig5_9Params {
        /// Stiffness exponent n.
        stiffness_exponent: f64 = 6.0, unit = "", range = Range::open(0.0, 30.0);
        /// Normalized roughnesses σ̄_rms of the two panels.
        roughness: Vec<f64> = vec![10.0, 50.0], unit = "", range = Range::positive();
        /// Normalized correlation lengths L̄_c.
        correlation_lengths: Vec<f64> = vec![0.01, 0.02, 0.04, 0.06, 0.08, 0.1], unit = "", range = Range::open(0.0, 1.0);
        /// The springs and their surfaces.
        group surfaces: SurfaceSamples
            help { springs: "Springs along each side.", samples: "Surface samples." };
        /// The displacement cycle.
        group cycle: ArrayCycle;
        /// Height bins per displacement step.
        oversample: usize = 4, unit = "", range = Range::between(1.0, 1000.0);
    }
}

/// The top of an efficiency axis that starts at zero: the first of 0.1, 0.12, 0.15, 0.2, 0.25,
/// 0.3, 0.4, 0.5, 0.6, 0.8, 1 (times a power of ten) at least 30 % above `top`, and at most 1
/// (the efficiency's bound).
fn efficiency_axis_top(top: f64) -> f64 {
    const STEPS: [f64; 11] = [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0];
    let want = 1.3 * top;
    if !(want > 0.0 && want.is_finite()) {
        return 1.0;
    }
    let decade = 10f64.powf(want.log10().floor());
    let nice = STEPS
        .iter()
        .map(|s| s * decade)
        .find(|v| *v >= want * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade);
    nice.min(1.0)
}

crate::scene! {
    /// Fig. 5.9: adhesion efficiency against correlation length.
    pub struct Fig5_9 {
        id: "fig5.9",
        chapter: "5",
        params: Fig5_9Params,
        title: "Adhesion efficiency vs correlation length",
        caption: "Adhesion efficiency (5.36) against L_c/(100 um) for sigma_rms/sigma = 10 (a) and 50 \
            (b), k_e = 2^-6 k_cr, 256 x 256 uncoupled springs; mean and standard deviation over 15 surfaces.",
        results: &[
            ("max_relative_spread_norm", "largest (max - min)/mean of the mean efficiency over the correlation lengths, over the panels"),
        ],
    }
}

impl Scene for Fig5_9 {
    fn validate(p: &Self::Params) -> Result<()> {
        require_non_empty("roughness", &p.roughness)?;
        require_non_empty("correlation_lengths", &p.correlation_lengths)
    }

    fn quick(p: &mut Self::Params) {
        p.surfaces.quick();
        p.cycle.quick();
        p.correlation_lengths.truncate(2);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        crate::scenes::sweep::run::<Self>(p, job)
    }
}

/// Fig. 5.9 is a sweep over (roughness, correlation length): point `c·L + l` is roughness `c`
/// and correlation length `l` (L lengths), on the unit surfaces of seeds `seed .. seed + samples`
/// at that length. A point's result is the adhesion efficiency of each sample.
impl Sweep for Fig5_9 {
    type Context = ();

    fn point_len(p: &Self::Params, _id: usize) -> usize {
        p.surfaces.samples
    }

    fn points(p: &Self::Params) -> Vec<String> {
        p.roughness
            .iter()
            .flat_map(|s| {
                p.correlation_lengths
                    .iter()
                    .map(move |lc| format!("σ_rms/σ = {s}, L_c/(100 µm) = {lc}"))
            })
            .collect()
    }

    fn run_point(p: &Self::Params, _context: &(), id: usize, job: &Job) -> Result<Vec<f64>> {
        let k_e = k_bar_of_n(p.stiffness_exponent);
        let nl = p.correlation_lengths.len();
        let (sigma, lc) = (p.roughness[id / nl], p.correlation_lengths[id % nl]);
        let unit = unit_surfaces(&p.surfaces, lc, &job.part(0.0, 0.5))?;
        let cycles = uncoupled_samples(&unit, sigma, k_e, &p.cycle, p.oversample, &job.part(0.5, 1.0))?;
        Ok(efficiencies(&cycles, p.surfaces.count()))
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut spread = 0.0f64;
        let labels = ["(a)", "(b)", "(c)", "(d)"];
        let nl = p.correlation_lengths.len();
        for (c, &sigma) in p.roughness.iter().enumerate() {
            let mut pts = Vec::new();
            let mut bars = Vec::new();
            for (l, &lc) in p.correlation_lengths.iter().enumerate() {
                let (m, sd) = mean_std(&points[c * nl + l]);
                pts.push((lc, m));
                bars.push((lc, m - sd));
                bars.push((lc, m + sd));
            }
            let ms: Vec<f64> = pts.iter().map(|q| q.1).collect();
            let sds: Vec<f64> = (0..nl).map(|l| mean_std(&points[c * nl + l]).1).collect();
            let (lo, hi) = ms.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
            let mean = mean_std(&ms).0;
            spread = spread.max((hi - lo) / mean);
            let mut panel = Panel::new(
                Axis::linear("Correlation length L_c/(100 µm)", ""),
                Axis::linear(EFFICIENCY_LABEL, ""),
            )
            .titled(labels[c.min(3)], format!("σ_rms/σ = {sigma}"));
            // From zero, to a round value above the largest error bar: the figure is about
            // whether the efficiency depends on L_c, which a range fitted to the means'
            // scatter would exaggerate into a trend.
            let top = bars.iter().map(|b| b.1).fold(0.0, f64::max);
            panel.y = panel.y.clone().with_range(0.0, efficiency_axis_top(top));
            let (first, last) = (p.correlation_lengths[0], p.correlation_lengths[nl - 1]);
            panel.add(
                Series::new(
                    "mean over all L_c",
                    Style::Reference,
                    vec![(first, mean), (last, mean)],
                )
                .with_color(7),
            );
            panel.add(
                Series::new(
                    format!("simulation: mean of {} surfaces", p.surfaces.samples),
                    Style::Scatter,
                    pts,
                )
                .with_color(c),
            );
            panel.add(Series::new("± 1 s.d. over the surfaces", Style::ErrorBar, bars).with_color(c));
            // The text (section 5.5.2): no appreciable dependence on L_c, the uncertainty
            // growing with L_c. Compare the spread of the means with their standard errors.
            let sem_max =
                sds.iter().fold(0.0f64, |a, &v| a.max(v)) / (p.surfaces.samples.max(1) as f64).sqrt();
            panel.annotate(format!(
                "s.d. over the surfaces {} at L_c = {} to {} at {}",
                number(sds[0], 2),
                fmt_sig(first),
                number(sds[nl - 1], 2),
                fmt_sig(last)
            ));
            panel.annotate(format!(
                "means {}-{} ({} % of their mean), standard errors ≤ {}: {}",
                number(lo, 3),
                number(hi, 3),
                number(100.0 * (hi - lo) / mean, 2),
                number(sem_max, 2),
                if hi - lo <= 2.0 * sem_max {
                    "no dependence on L_c beyond the scatter, as the text finds"
                } else {
                    "they vary by more than the scatter, a dependence on L_c the text does not report"
                }
            ));
            fig.panels.push(panel);
        }
        fig.result("max_relative_spread_norm", spread);
        job.progress(1.0, "done");
        Ok(fig)
    }
}
