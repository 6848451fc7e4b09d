//! Section 4.5.2, the sweeps: the adhesive force P_adh and the loss H of the wavy tip against
//! the interaction range σ for three roughnesses (Fig. 4.9b), and over the non-dimensional
//! roughness and range (α, β) of (4.27) (Fig. 4.10). One full cycle per point with the
//! axisymmetric surface model, the points in parallel (rayon). The contact threshold of each
//! point is its σ (section 4.2.2); P_adh and H do not depend on it.

use super::roughness::{MAX_WIDTH_OVER_WAVELENGTH, Setup, rough_tip_params};
use crate::error::{Error, Result};
use crate::figure::{Axis, Field, Figure, Marker, MarkerShape, Panel, Series, Style};
use crate::job::Job;
use crate::params::{Range, require_not_below};
use crate::scenes::fig4::TipModel;
use crate::scenes::groups::{DepthPath, ElasticTip, FeMesh, Interaction, SurfaceModel, Waviness};
use crate::scenes::sweep::Sweep;
use crate::scenes::{Scene, SceneHeader};
use crate::text::fmt_sig;

/// The relative cost of a cycle at the ring-width scale b (b ∝ σ⁴, (4.6)-(4.7b)), against the
/// smallest `b_min` of the sweep: rings ∝ 1/b and a dense solve ∝ rings³, over a floor for
/// what does not depend on b. Measured at the defaults (seconds per cycle): fig4.9b 20-64 at
/// σ = 1 nm, 4.3 at 1.15 nm, 1.0 at 1.32 nm, 0.45 at 1.51 nm, 0.03 at 3 nm; fig4.10 20 at
/// β = 0.12, 3.9 at 0.21, 1.05 at 0.37, 0.37 at 0.65, 0.1 at 2.
fn cycle_cost(b: f64, b_min: f64) -> f64 {
    (b_min / b).powi(3) + 0.003
}

/// P_adh/(2E*R²) and H/(2E*R³) of one cycle.
pub(super) fn adhesion_of(setup: &Setup, amplitude: f64, job: &Job) -> Result<(f64, f64)> {
    let (tip_cycle, scale) = (setup.cycle(amplitude, false, job)?, setup.scale());
    let cycle = tip_cycle.1;
    Ok((
        -cycle.adhesive_force() / scale.1,
        cycle.hysteresis() / (scale.1 * setup.radius),
    ))
}

/// What a roughness sweep ran: the depth, step and discretisation of its cycles (the caption
/// gives the defaults).
fn ran_note(setup: &Setup, grid: &str) -> String {
    format!(
        "Ran: {grid}; one cycle per point to |h_min|/R = {} from {} ζ0 in steps of {} ζ0; {} with {} b surface \
         elements (b ∝ σ⁴) and {} Gauss points.",
        crate::figure::number(setup.depth / setup.radius, 3),
        setup.h_start_over_zeta0,
        setup.step_over_zeta0,
        match setup.choice.model {
            TipModel::Surface => "surface model",
            TipModel::Fe => "finite elements",
        },
        setup.surface.ring_width,
        setup.surface.quadrature_points
    )
}

/// The set-up of one point of a roughness sweep with its surface elements at most λ/8
/// ([`MAX_WIDTH_OVER_WAVELENGTH`]), and whether that cap applied.
fn capped_setup(setup: Result<Setup>) -> Result<(Setup, bool)> {
    let mut setup = setup?;
    let capped = setup.cap_ring_width(MAX_WIDTH_OVER_WAVELENGTH);
    Ok((setup, capped))
}

/// The note on the cap of the surface elements at λ/8: the values of the swept quantity
/// (`what`, as printed in `capped`) where it applied, or that it applied nowhere.
fn cap_note(setup: &Setup, what: &str, capped: &[String]) -> String {
    let cap = MAX_WIDTH_OVER_WAVELENGTH * setup.wavelength * 1e9;
    if capped.is_empty() {
        format!(
            "Surface elements of {} b at every point (all below λ/8 = {cap:.1} nm).",
            setup.surface.ring_width
        )
    } else {
        format!(
            "Surface elements capped at λ/8 = {cap:.1} nm, narrower than {} b (b ∝ σ⁴), at {what} = {} (the \
             waviness resolved); {} b elsewhere.",
            setup.surface.ring_width,
            capped.join(", "),
            setup.surface.ring_width
        )
    }
}

/// `n` values from `lo` to `hi`, geometric.
fn geometric(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![lo];
    }
    (0..n)
        .map(|k| lo * (hi / lo).powf(k as f64 / (n - 1) as f64))
        .collect()
}

rough_tip_params! {
    /// Parameters of scene fig4.9b (section 4.5.2: those of Fig. 4.7a with σ varied for
    /// A/λ = 0, 0.0075 and 0.02, |h_min|/R = 6e-4).
    Fig4_9bParams, youngs_modulus = 2.2e6, {
        /// Smallest σ of the sweep [m].
        sigma_min: f64 = 1.0e-9, unit = "m", range = Range::between(0.5e-9, 1.0e-8);
        /// Largest σ of the sweep [m].
        sigma_max: f64 = 3.0e-9, unit = "m", range = Range::between(0.5e-9, 1.0e-8);
        /// Values of σ (geometric between the two).
        sigma_points: usize = 9, unit = "", range = Range::between(2.0, 64.0);
        /// A/λ of the first curve.
        amplitude_ratio_1: f64 = 0.0, unit = "", range = Range::between(0.0, 0.2);
        /// A/λ of the second curve.
        amplitude_ratio_2: f64 = 0.0075, unit = "", range = Range::between(0.0, 0.2);
        /// A/λ of the third curve.
        amplitude_ratio_3: f64 = 0.02, unit = "", range = Range::between(0.0, 0.2);
    }
}

crate::scene! {
    /// Fig. 4.9b: P_adh and H against σ for three roughnesses.
    pub struct Fig4_9b {
        id: "fig4.9b",
        chapter: "4",
        params: Fig4_9bParams,
        title: "Adhesive force and loss against the interaction range",
        caption: "P_adh/(2E*R^2) (a) and H/(2E*R^3) (b) of a wavy tip (surface model, or with model = fe \
            the finite-element model; one cycle per point to |h_min|/R = 6 × 10⁻⁴ at the defaults, the figure's notes give \
            what ran) against the range sigma of the LJ potential for A/lambda = 0, 0.0075 and 0.02 \
            (the other parameters of Fig. 4.7a; E = 2.2 MPa, ERRATA on Fig. 4.9). A sweep: sigma_points x 3 cycles. \
            The dissertation: for the smooth tip both fall monotonically with sigma (the instabilities vanish as mu_T \
            falls); for the rough tips they first rise, peak and then fall.",
        results: &[
            ("sigma_p_adh_max_1_nm", "sigma of the largest P_adh, curve 1"),
            ("sigma_p_adh_max_2_nm", "sigma of the largest P_adh, curve 2"),
            ("sigma_p_adh_max_3_nm", "sigma of the largest P_adh, curve 3"),
            ("sigma_h_max_1_nm", "sigma of the largest H, curve 1"),
            ("sigma_h_max_2_nm", "sigma of the largest H, curve 2"),
            ("sigma_h_max_3_nm", "sigma of the largest H, curve 3"),
            ("p_adh_max_1_norm", "largest P_adh/(2E*R^2), curve 1"),
            ("p_adh_max_2_norm", "largest P_adh/(2E*R^2), curve 2"),
            ("p_adh_max_3_norm", "largest P_adh/(2E*R^2), curve 3"),
            ("points_count", "cycles computed"),
        ],
        sweep: true,
    }
}

impl Scene for Fig4_9b {
    /// Three values of σ over the whole range (from 1 nm: where the text's rise would be), a
    /// shallow cycle in coarser steps.
    fn quick(p: &mut Self::Params) {
        p.sigma_points = p.sigma_points.min(3);
        p.shallow_quick();
    }

    fn validate(p: &Self::Params) -> Result<()> {
        require_not_below("sigma_max", p.sigma_max, "sigma_min", p.sigma_min)?;
        p.setup(p.tip.youngs_modulus, p.sigma_min, p.sigma_min)
            .map(|_| ())
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        crate::scenes::sweep::run::<Self>(p, job)
    }
}

/// Fig. 4.9b is a sweep of one cycle per point: point `c·n + i` is curve `c` (its A/λ) at σ
/// number `i` (n values of σ); its result is (P_adh/(2E*R²), H/(2E*R³)).
impl Sweep for Fig4_9b {
    type Context = ();
    const POINT_LEN: usize = 2;

    fn points(p: &Self::Params) -> Vec<String> {
        let sigmas = geometric(p.sigma_min, p.sigma_max, p.sigma_points);
        [p.amplitude_ratio_1, p.amplitude_ratio_2, p.amplitude_ratio_3]
            .iter()
            .flat_map(|r| {
                sigmas
                    .iter()
                    .map(move |s| format!("A/λ = {r}, σ = {} nm", fmt_sig(s * 1e9)))
            })
            .collect()
    }

    fn point_weights(p: &Self::Params) -> Vec<f64> {
        let sigmas = geometric(p.sigma_min, p.sigma_max, p.sigma_points);
        let one: Vec<f64> = sigmas
            .iter()
            .map(|s| cycle_cost(s.powi(4), p.sigma_min.powi(4)))
            .collect();
        [one.clone(), one.clone(), one].concat()
    }

    fn run_point(p: &Self::Params, _context: &(), id: usize, job: &Job) -> Result<Vec<f64>> {
        let sigmas = geometric(p.sigma_min, p.sigma_max, p.sigma_points);
        let ratios = [p.amplitude_ratio_1, p.amplitude_ratio_2, p.amplitude_ratio_3];
        let (curve, i) = (id / sigmas.len(), id % sigmas.len());
        let (setup, _) = capped_setup(p.setup(p.tip.youngs_modulus, sigmas[i], sigmas[i]))?;
        let (force, loss) = adhesion_of(&setup, ratios[curve] * p.wavelength, job)?;
        Ok(vec![force, loss])
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let sigmas = geometric(p.sigma_min, p.sigma_max, p.sigma_points);
        let ratios = [p.amplitude_ratio_1, p.amplitude_ratio_2, p.amplitude_ratio_3];
        let n = sigmas.len();
        let values: Vec<(f64, f64)> = points.iter().map(|v| (v[0], v[1])).collect();
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        let mut panels = [
            Panel::new(
                Axis::linear("Interaction range σ", "nm"),
                Axis::linear("P_adh/(2E*R²)", ""),
            )
            .titled("(a)", "adhesive force"),
            Panel::new(
                Axis::linear("Interaction range σ", "nm"),
                Axis::linear("H/(2E*R³)", ""),
            )
            .titled("(b)", "hysteresis"),
        ];
        let mut notes = Vec::new();
        for (c, ratio) in ratios.iter().enumerate() {
            let rows = &values[c * n..(c + 1) * n];
            let name = format!("A/λ = {ratio}");
            for (panel, pick) in panels.iter_mut().zip([0usize, 1]) {
                let pts: Vec<(f64, f64)> = sigmas
                    .iter()
                    .zip(rows)
                    .map(|(s, v)| (s * 1e9, if pick == 0 { v.0 } else { v.1 }))
                    .collect();
                panel.add(Series::new(name.clone(), Style::Stable, pts.clone()).with_color([0, 3, 2][c]));
                panel.add(
                    Series::new(name.clone(), Style::Scatter, pts)
                        .with_color([0, 3, 2][c])
                        .without_legend(),
                );
            }
            let argmax = |pick: usize| {
                (0..n)
                    .max_by(|&a, &b| {
                        let (x, y) = (rows[a], rows[b]);
                        if pick == 0 {
                            x.0.total_cmp(&y.0)
                        } else {
                            x.1.total_cmp(&y.1)
                        }
                    })
                    .unwrap_or(0)
            };
            let (ip, ih) = (argmax(0), argmax(1));
            fig.result(format!("sigma_p_adh_max_{}_nm", c + 1), sigmas[ip] * 1e9);
            fig.result(format!("sigma_h_max_{}_nm", c + 1), sigmas[ih] * 1e9);
            fig.result(format!("p_adh_max_{}_norm", c + 1), rows[ip].0);
            let shape = |i: usize| {
                if i == 0 {
                    "largest at the smallest sigma (falling)"
                } else if i == n - 1 {
                    "largest at the largest sigma (rising)"
                } else {
                    "peaks inside the range"
                }
            };
            notes.push(format!(
                "{name}: P_adh {} ({:.2} nm), H {} ({:.2} nm)",
                shape(ip),
                sigmas[ip] * 1e9,
                shape(ih),
                sigmas[ih] * 1e9
            ));
        }
        fig.result("points_count", (3 * n) as f64);
        fig.note(ran_note(
            &p.setup(p.tip.youngs_modulus, p.sigma_min, p.sigma_min)?,
            &format!(
                "{n} values of σ from {} to {} nm",
                fmt_sig(p.sigma_min * 1e9),
                fmt_sig(p.sigma_max * 1e9)
            ),
        ));
        let mut capped = Vec::new();
        for &s in &sigmas {
            if capped_setup(p.setup(p.tip.youngs_modulus, s, s))?.1 {
                capped.push(format!("{} nm", fmt_sig(s * 1e9)));
            }
        }
        let first = p.setup(p.tip.youngs_modulus, p.sigma_min, p.sigma_min)?;
        fig.note(cap_note(&first, "σ", &capped));
        fig.note(format!("{}.", notes.join("; ")));
        let rough_rise = (1..3).any(|c| {
            ratios[c] > 0.0
                && fig.result_value(&format!("sigma_p_adh_max_{}_nm", c + 1)) > Some(p.sigma_min * 1e9 + 1e-9)
        });
        if !rough_rise {
            fig.note(format!(
                "Unlike the text, no rough curve rises with sigma in {:.2}-{:.2} nm: at a fixed Hamaker constant w grows \
                 as sigma^-2 ((4.6), (4.7b)), and with it P_adh and H. A rise at smaller sigma is not excluded; below \
                 about 1 nm the ring width 0.25 b (b grows as sigma^4) makes the dense surface model costly.",
                p.sigma_min * 1e9,
                p.sigma_max * 1e9
            ));
        }
        fig.panels.extend(panels);
        job.progress(1.0, "done");
        Ok(fig)
    }
}

rough_tip_params! {
    /// Parameters of scene fig4.10 (the caption of Fig. 4.10: those of Fig. 4.7a with A and σ
    /// varied, |h_min|/R = 6e-4), over α = A²/(λw/E*) and β = σ²/(λw/E*) of (4.27).
    Fig4_10Params, youngs_modulus = 2.2e6, {
        /// Largest α of the grid (the smallest is 0, a smooth tip).
        alpha_max: f64 = 0.6, unit = "", range = Range::between(1.0e-3, 10.0);
        /// Values of α (uniform from 0).
        alpha_points: usize = 6, unit = "", range = Range::between(2.0, 64.0);
        /// Smallest β of the grid.
        beta_min: f64 = 0.12, unit = "", range = Range::between(0.02, 100.0);
        /// Largest β of the grid.
        beta_max: f64 = 2.0, unit = "", range = Range::between(0.02, 100.0);
        /// Values of β (geometric between the two).
        beta_points: usize = 6, unit = "", range = Range::between(2.0, 64.0);
    }
}

/// The printed optimum of Fig. 4.10 (section 4.5.2), (α, β).
const PRINTED_OPTIMUM: (f64, f64) = (0.1741, 0.4457);

impl Fig4_10Params {
    /// The grid: α uniform from 0, β geometric.
    fn grid(&self) -> (Vec<f64>, Vec<f64>) {
        let alphas: Vec<f64> = (0..self.alpha_points)
            .map(|i| self.alpha_max * i as f64 / (self.alpha_points - 1) as f64)
            .collect();
        (alphas, geometric(self.beta_min, self.beta_max, self.beta_points))
    }

    /// σ [m] and A [m] of a grid point (α, β): with ζ0 ∝ σ, w ∝ σ⁻² (4.6), (4.7b), so
    /// β = σ²E*/(λw) ∝ σ⁴ is solved from w at a reference σ; then A = √(α λ w/E*).
    fn point(&self, alpha: f64, beta: f64) -> Result<(f64, f64)> {
        let reference = 1e-9;
        let setup = self.setup(self.tip.youngs_modulus, reference, reference)?;
        let k = setup.lj.work_of_adhesion() * reference * reference / setup.modulus;
        let sigma = (beta * self.wavelength * k).powf(0.25);
        let w_over_e = k / (sigma * sigma);
        Ok((sigma, (alpha * self.wavelength * w_over_e).sqrt()))
    }
}

crate::scene! {
    /// Fig. 4.10: P_adh and H over (α, β).
    pub struct Fig4_10 {
        id: "fig4.10",
        chapter: "4",
        params: Fig4_10Params,
        title: "Adhesive force and loss over roughness and interaction range",
        caption: "P_adh/(2E*R^2) (a) and H/(2E*R^3) (b) of a wavy tip (surface model, or with model = fe \
            the finite-element model; one cycle per point to |h_min|/R = 6 × 10⁻⁴ at the defaults, the figure's notes give \
            what ran) over alpha = A^2/(lambda w/E*) and beta = sigma^2/(lambda w/E*) of (4.27) (the \
            other parameters of Fig. 4.7a, E = 2.2 MPa). A sweep of alpha_points x beta_points cycles; the default \
            6 x 6 grid is coarse (about a minute on 2 cores): refine it for a paper figure. The diamond marks the \
            grid's largest value, the cross the dissertation's optimum (0.1741, 0.4457) for both.",
        results: &[
            ("alpha_p_adh_max_norm", "alpha of the largest P_adh on the grid"),
            ("beta_p_adh_max_norm", "beta of the largest P_adh on the grid"),
            ("alpha_h_max_norm", "alpha of the largest H on the grid"),
            ("beta_h_max_norm", "beta of the largest H on the grid"),
            ("p_adh_max_norm", "largest P_adh/(2E*R^2) on the grid"),
            ("h_max_norm", "largest H/(2E*R^3) on the grid"),
            ("points_count", "cycles computed"),
        ],
        sweep: true,
    }
}

impl Scene for Fig4_10 {
    /// A 3 x 3 grid over the whole range (β from the default's smallest, where the printed
    /// optimum's neighbourhood starts), a shallow cycle in coarser steps.
    fn quick(p: &mut Self::Params) {
        p.alpha_points = p.alpha_points.min(3);
        p.beta_points = p.beta_points.min(3);
        p.shallow_quick();
    }

    fn validate(p: &Self::Params) -> Result<()> {
        require_not_below("beta_max", p.beta_max, "beta_min", p.beta_min)?;
        let (sigma, _) = p.point(0.0, p.beta_min)?;
        if sigma < 0.5e-9 {
            return Err(Error::invalid(
                "beta_min",
                p.beta_min,
                format!(
                    "gives sigma = {:.3} nm, below 0.5 nm (too many rings)",
                    sigma * 1e9
                ),
            ));
        }
        Ok(())
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        crate::scenes::sweep::run::<Self>(p, job)
    }
}

/// Fig. 4.10 is a sweep of one cycle per grid point: point `j·n_α + i` is (α_i, β_j); its
/// result is (P_adh/(2E*R²), H/(2E*R³)).
impl Sweep for Fig4_10 {
    type Context = ();
    const POINT_LEN: usize = 2;

    fn points(p: &Self::Params) -> Vec<String> {
        let (alphas, betas) = p.grid();
        betas
            .iter()
            .flat_map(|b| {
                alphas
                    .iter()
                    .map(move |a| format!("α = {}, β = {}", fmt_sig(*a), fmt_sig(*b)))
            })
            .collect()
    }

    fn point_weights(p: &Self::Params) -> Vec<f64> {
        let (alphas, betas) = p.grid();
        let b_min = betas.iter().copied().fold(f64::INFINITY, f64::min);
        betas
            .iter()
            .flat_map(|&b| alphas.iter().map(move |_| cycle_cost(b, b_min)))
            .collect()
    }

    fn run_point(p: &Self::Params, _context: &(), id: usize, job: &Job) -> Result<Vec<f64>> {
        let (alphas, betas) = p.grid();
        let (ia, ib) = (id % alphas.len(), id / alphas.len());
        let (sigma, amplitude) = p.point(alphas[ia], betas[ib])?;
        let (setup, _) = capped_setup(p.setup(p.tip.youngs_modulus, sigma, sigma))?;
        let (force, loss) = adhesion_of(&setup, amplitude, job)?;
        Ok(vec![force, loss])
    }

    fn assemble(p: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let (alphas, betas) = p.grid();
        let (na, nb) = (alphas.len(), betas.len());
        let values: Vec<(f64, f64)> = points.iter().map(|v| (v[0], v[1])).collect();
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        for (pick, (label, name)) in [("(a)", "P_adh/(2E*R²)"), ("(b)", "H/(2E*R³)")]
            .iter()
            .enumerate()
        {
            let field_values: Vec<f64> = values.iter().map(|v| if pick == 0 { v.0 } else { v.1 }).collect();
            let best = (0..field_values.len())
                .max_by(|&a, &b| field_values[a].total_cmp(&field_values[b]))
                .unwrap_or(0);
            let (ba, bb) = (alphas[best % na], betas[best / na]);
            let mut panel = Panel::new(
                Axis::linear("α = A²/(λw/E*)", ""),
                Axis::log("β = σ²/(λw/E*)", ""),
            )
            .titled(*label, *name);
            panel.field = Some(Field::heat(
                *name,
                "",
                alphas.clone(),
                betas.clone(),
                field_values.clone(),
            ));
            panel.mark(Marker::new("grid maximum", MarkerShape::Point, ba, bb).with_color(1));
            panel.mark(
                Marker::new(
                    "printed optimum",
                    MarkerShape::Cross,
                    PRINTED_OPTIMUM.0,
                    PRINTED_OPTIMUM.1,
                )
                .with_color(0),
            );
            fig.panels.push(panel);
            let key = if pick == 0 { "p_adh" } else { "h" };
            fig.result(format!("alpha_{key}_max_norm"), ba);
            fig.result(format!("beta_{key}_max_norm"), bb);
            fig.result(format!("{key}_max_norm"), field_values[best]);
        }
        fig.result("points_count", (na * nb) as f64);
        let (sigma_lo, _) = p.point(0.0, p.beta_min)?;
        fig.note(ran_note(
            &p.setup(p.tip.youngs_modulus, sigma_lo, sigma_lo)?,
            &format!(
                "{na} x {nb} grid, α from 0 to {}, β from {} to {}",
                fmt_sig(p.alpha_max),
                fmt_sig(p.beta_min),
                fmt_sig(p.beta_max)
            ),
        ));
        let mut capped = Vec::new();
        for &b in &betas {
            let (sigma, _) = p.point(0.0, b)?;
            if capped_setup(p.setup(p.tip.youngs_modulus, sigma, sigma))?.1 {
                capped.push(fmt_sig(b));
            }
        }
        fig.note(cap_note(
            &p.setup(p.tip.youngs_modulus, sigma_lo, sigma_lo)?,
            "β",
            &capped,
        ));
        let r = |n: &str| fig.result_value(n).unwrap_or(0.0);
        let on_edge = |a: f64, b: f64| {
            a <= 0.0
                || a >= p.alpha_max * (1.0 - 1e-12)
                || b <= p.beta_min * (1.0 + 1e-12)
                || b >= p.beta_max * (1.0 - 1e-12)
        };
        let edge = on_edge(r("alpha_p_adh_max_norm"), r("beta_p_adh_max_norm"));
        let summary = format!(
            "Grid maxima: P_adh at (α, β) = ({:.3}, {:.3}), H at ({:.3}, {:.3}); printed optimum (0.1741, 0.4457) for both. \
             Grid spacing: Δα = {:.3}, β by a factor {:.2}.",
            r("alpha_p_adh_max_norm"),
            r("beta_p_adh_max_norm"),
            r("alpha_h_max_norm"),
            r("beta_h_max_norm"),
            p.alpha_max / (p.alpha_points - 1) as f64,
            (p.beta_max / p.beta_min).powf(1.0 / (p.beta_points - 1).max(1) as f64)
        );
        fig.note(summary);
        if edge {
            fig.note(
                "The grid maximum of P_adh lies on the edge of the grid: no interior optimum in this range, unlike the \
                 printed (0.1741, 0.4457). At a fixed Hamaker constant w grows as sigma^-2, so P_adh/(2E*R^2) grows as \
                 beta falls.",
            );
        }
        job.progress(1.0, "done");
        Ok(fig)
    }
}
