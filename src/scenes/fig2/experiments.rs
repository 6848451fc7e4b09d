//! Fig. 2.8 and its version for the user's own data: the machine-stiffness model and JKR at the
//! best-fit parameters of the experiments of section 2.4 (Sun et al., Notbohm et al.), each with
//! a second panel on the adhesive region where the instabilities the text discusses happen;
//! and the fit of a measured (or, without a file, synthetic) force-indentation cycle.

use crate::error::{Error, Result};
use crate::figure::{COINCIDENCE_TOL, Figure, Legend, Panel, Style, number};
use crate::fit::predictions::{ph_panel, predictions};
use crate::job::Job;
use crate::models::machine_stiffness::{Experiment, TipGeometry};
use crate::params::Range;
use crate::scenes::{Scene, SceneHeader};

/// The root tolerance of the machine-stiffness model in the chapter 2 scenes.
pub(super) const XTOL: f64 = 1e-14;

// ---------------------------------------------------------------------------------------------
// Fig. 2.8: the experiments of section 2.4.

crate::scene_params! {
    /// Parameters of scene fig2.8: the best-fit parameters of Sec. 2.4 for Sun et al. (a) and
    /// Notbohm et al. (b). ℰ is the plane-strain modulus (ERRATA); the Notbohm work of
    /// adhesion is 25.7 mJ/m² (the text's J/m² is a typo).
    pub struct Fig2_8Params {
        /// (a) Sun et al.: tip radius R.
        sun_radius: f64 = 58.0e-9, unit = "m", range = Range::positive();
        /// (a) Sun et al.: plane-strain modulus ℰ.
        sun_modulus: f64 = 6.39e6, unit = "Pa", range = Range::positive();
        /// (a) Sun et al.: work of adhesion w.
        sun_work_of_adhesion: f64 = 63.2e-3, unit = "J/m^2", range = Range::positive();
        /// (a) Sun et al.: cantilever stiffness k_s.
        sun_spring_constant: f64 = 0.66, unit = "N/m", range = Range::positive();
        /// (b) Notbohm et al.: tip radius R.
        notbohm_radius: f64 = 2.5e-6, unit = "m", range = Range::positive();
        /// (b) Notbohm et al.: plane-strain modulus ℰ.
        notbohm_modulus: f64 = 0.65e6, unit = "Pa", range = Range::positive();
        /// (b) Notbohm et al.: work of adhesion w.
        notbohm_work_of_adhesion: f64 = 25.7e-3, unit = "J/m^2", range = Range::positive();
        /// (b) Notbohm et al.: cantilever stiffness k_s.
        notbohm_spring_constant: f64 = 0.642, unit = "N/m", range = Range::positive();
        /// Largest indentation depth drawn, in units of ĥ = â²/R.
        max_depth_norm: f64 = 3.0, unit = "", range = Range::open(0.0, 1.0e3);
        /// Samples per branch.
        points: usize = 300, unit = "", range = Range::between(20.0, 1.0e6);
    }
}

/// The numbers section 2.4 prints for one experiment, as printed, for the notes on the figure.
struct Printed {
    /// Pull-off force of the machine-stiffness model [nN].
    pull_off_nn: &'static str,
    /// Measured pull-off force [nN].
    measured_pull_off_nn: &'static str,
    /// JKR pull-off force −5πwR/6 [nN].
    jkr_pull_off_nn: &'static str,
    /// Depth change in the pull-in (nm for Sun et al., µm for Notbohm et al.).
    pull_in_jump: &'static str,
    /// Depth change in the pull-off (same unit).
    pull_off_jump: &'static str,
}

/// Sun et al. [58], section 2.4: −14.73 nN, measured −14.8 nN, JKR −9.59 nN; model depth jumps
/// 27.4 nm and 26 nm (ERRATA: not |P|/k_s of the printed forces).
const SUN_PRINTED: Printed = Printed {
    pull_off_nn: "−14.73",
    measured_pull_off_nn: "−14.8",
    jkr_pull_off_nn: "−9.59",
    pull_in_jump: "27.4",
    pull_off_jump: "26",
};

/// Notbohm et al. [59], section 2.4: −281.5 nN, measured −281.6 nN, JKR −167.5 nN; model depth
/// jumps 0.19 µm and 0.42 µm.
const NOTBOHM_PRINTED: Printed = Printed {
    pull_off_nn: "−281.5",
    measured_pull_off_nn: "−281.6",
    jkr_pull_off_nn: "−167.5",
    pull_in_jump: "0.19",
    pull_off_jump: "0.42",
};

/// A copy of a P-h panel framed on its adhesive region: the depths of every state at negative
/// force (the curves, jumps and pull-off squares there) with a margin, and forces from 15 %
/// below the most negative one up to as far above zero. The curves leave the frame upwards;
/// the first panel shows them whole.
fn adhesive_region(panel: &Panel, label: &str, title: &str) -> Panel {
    let mut zoom = panel.clone().titled(label, format!("{title}: adhesive region"));
    let below: Vec<(f64, f64)> = panel
        .series
        .iter()
        .filter(|s| s.style != Style::Scatter)
        .flat_map(|s| s.points.iter().copied())
        .chain(panel.markers.iter().map(|m| (m.x, m.y)))
        .filter(|p| p.1 <= 0.0 && p.0.is_finite() && p.1.is_finite())
        .collect();
    let (x0, x1) = below
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let y0 = below.iter().fold(0.0f64, |a, p| a.min(p.1));
    if x1 > x0 && y0 < 0.0 {
        let dx = 0.12 * (x1 - x0);
        zoom.x = zoom.x.clone().with_range(x0 - dx, x1 + dx);
        zoom.y = zoom.y.clone().with_range(1.15 * y0, -y0);
    }
    zoom.legend = Legend::Hidden;
    zoom
}

crate::scene! {
    /// Fig. 2.8: P-h cycles of the machine-stiffness model and of JKR at the best-fit parameters of
    /// Sec. 2.4, with the pull-off squares.
    pub struct Fig2_8 {
        id: "fig2.8",
        chapter: "2",
        params: Fig2_8Params,
        title: "Machine-stiffness model and JKR at the best fits of section 2.4",
        caption: "Contact force vs indentation depth of the machine-stiffness model \
            ((2.31b)-(2.32b) with the jumps of Sec. 2.3.1, blue) and of JKR ((1.2), red) at the best-fit \
            parameters of Sec. 2.4: (a), (b) Sun et al., R = 58 nm; (c), (d) Notbohm et al., R = 2.5 um; \
            (a), (c) the whole cycle, (b), (d) its adhesive region, with the pull-off forces and depth jumps \
            against the text's. Where the JKR curve lies on the model's (the same P-h relation) it is dashed. \
            Squares: the state just before the pull-off. Measured curves: `--fit FILE.csv` or scene fig2.8-fit.",
        results: &[
            ("sun_alpha_norm", "alpha = k_s/k_hat, Sun et al."),
            ("sun_pull_off_force_nN", "machine-stiffness pull-off force, Sun et al. (printed -14.73)"),
            ("sun_jkr_pull_off_force_nN", "JKR pull-off -5 pi w R/6, Sun et al. (printed -9.59)"),
            ("sun_pull_in_force_nN", "machine-stiffness pull-in force, Sun et al."),
            ("sun_pull_off_force_exact_sphere_nN", "pull-off force with the exact spherical profile (2.28)"),
            ("sun_pull_in_depth_jump_nm", "depth change in the pull-in, Sun et al. (printed 27.4)"),
            ("sun_pull_off_depth_jump_nm", "|depth change| in the pull-off, Sun et al. (printed 26)"),
            ("notbohm_alpha_norm", "alpha = k_s/k_hat, Notbohm et al."),
            ("notbohm_pull_off_force_nN", "machine-stiffness pull-off force, Notbohm et al. (printed -281.5)"),
            ("notbohm_jkr_pull_off_force_nN", "JKR pull-off -5 pi w R/6, Notbohm et al. (printed -167.5)"),
            ("notbohm_pull_in_force_nN", "machine-stiffness pull-in force, Notbohm et al."),
            ("notbohm_pull_off_force_exact_sphere_nN", "pull-off force with the exact spherical profile (2.28)"),
            ("notbohm_pull_in_depth_jump_um", "depth change in the pull-in, Notbohm et al. (printed 0.19)"),
            ("notbohm_pull_off_depth_jump_um", "|depth change| in the pull-off, Notbohm et al. (printed 0.42)"),
        ],
    }
}

impl Scene for Fig2_8 {
    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(40);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let sun = Experiment::new(
            TipGeometry::Sphere { radius: p.sun_radius },
            p.sun_modulus,
            p.sun_work_of_adhesion,
            p.sun_spring_constant,
        )?;
        let notbohm = Experiment::new(
            TipGeometry::Sphere {
                radius: p.notbohm_radius,
            },
            p.notbohm_modulus,
            p.notbohm_work_of_adhesion,
            p.notbohm_spring_constant,
        )?;
        let mut fig = Figure::new(Self::ID, Self::TITLE);
        for (k, (name, x, title, depth_unit, printed)) in [
            ("sun", sun, "Sun et al.", ("nm", "nm", 1e9), &SUN_PRINTED),
            (
                "notbohm",
                notbohm,
                "Notbohm et al.",
                ("um", "µm", 1e6),
                &NOTBOHM_PRINTED,
            ),
        ]
        .into_iter()
        .enumerate()
        {
            job.check()?;
            let pr = predictions(&x)?;
            let mut full = ph_panel(
                &x,
                ["(a)", "(c)"][k],
                &format!("{title}: cycle"),
                p.max_depth_norm,
                p.points,
            )?;
            full.mark_coinciding(COINCIDENCE_TOL);
            // The instabilities the text discusses happen at negative force, a sliver of the
            // whole cycle: the second panel frames them.
            let mut zoom = adhesive_region(&full, ["(b)", "(d)"][k], title);
            let (off, jkr_off) = (pr.pull_off.before.force * 1e9, pr.jkr_pull_off_force * 1e9);
            let (jump_in, jump_off) = (
                pr.pull_in.depth_jump().abs() * depth_unit.2,
                pr.pull_off.depth_jump().abs() * depth_unit.2,
            );
            let n = |v: f64| number(v, 4);
            zoom.annotate(format!(
                "pull-off force: this model {} nN (text {}, measured {}); JKR {} nN (text {})",
                n(off),
                printed.pull_off_nn,
                printed.measured_pull_off_nn,
                n(jkr_off),
                printed.jkr_pull_off_nn
            ));
            let (unit, n3) = (depth_unit.1, |v: f64| number(v, 3));
            zoom.annotate(format!(
                "depth jumps, |P|/k_s: pull-in {} {unit}, pull-off {} {unit} (text {}, {} {unit}); JKR: no jump",
                n3(jump_in),
                n3(jump_off),
                printed.pull_in_jump,
                printed.pull_off_jump
            ));
            fig.panels.push(full);
            fig.panels.push(zoom);
            fig.result(format!("{name}_alpha_norm"), x.alpha());
            fig.result(format!("{name}_pull_off_force_nN"), off);
            fig.result(format!("{name}_jkr_pull_off_force_nN"), jkr_off);
            fig.result(format!("{name}_pull_in_force_nN"), pr.pull_in.after.force * 1e9);
            // The exact profile (2.28) is a secondary result: where the contact would reach the
            // bead's equator (R/â ≤ 1) it has no pull-off, and the figure is drawn without it.
            match x.model_exact_sphere().and_then(|m| m.pull_off(XTOL)) {
                Ok(po) => fig.result(
                    format!("{name}_pull_off_force_exact_sphere_nN"),
                    po.before.force * x.scales().force * 1e9,
                ),
                Err(e) => fig.note(format!(
                    "{title}: no pull-off with the exact spherical profile ({e})"
                )),
            }
            fig.result(format!("{name}_pull_in_depth_jump_{}", depth_unit.0), jump_in);
            fig.result(format!("{name}_pull_off_depth_jump_{}", depth_unit.0), jump_off);
        }
        fig.note("in this model the depth changes by |P|/k_s in each jump; JKR predicts no change of depth");
        fig.note(
            "where the JKR curve lies on the machine-stiffness curve (the same P-h relation, \
             (2.31b)-(2.32b)), it is drawn dashed and named \"coincides\" in the legend",
        );
        job.progress(1.0, "done");
        Ok(fig)
    }
}

// ---------------------------------------------------------------------------------------------
// fig2.8-fit: Fig. 2.8 for the user's own data (the `--fit` command as a scene).

crate::param_choice! {
    /// The model drawn and reported first by a fit.
    pub enum FitModelChoice { Auto = "auto", Jkr = "jkr", MachineStiffness = "machine-stiffness" }
}

crate::scene_params! {
    /// Parameters of scene fig2.8-fit. With no data file, a synthetic cycle of the model (with
    /// the demo parameters and deterministic force noise) is fitted, as a demonstration.
    pub struct Fig2_8FitParams {
        /// Measured cycle (CSV with a header such as `depth_nm,force_nN`); empty: a synthetic demonstration cycle.
        data_file: String = String::new(), unit = "", range = Range::any();
        /// Tip radius R.
        tip_radius: f64 = 1.0e-6, unit = "m", range = Range::positive();
        /// Cantilever stiffness k_s; 0: unknown (JKR only).
        spring_constant: f64 = 0.5, unit = "N/m", range = Range::non_negative();
        /// Model drawn and reported first: auto (machine-stiffness when k_s > 0), jkr, machine-stiffness.
        model: FitModelChoice = FitModelChoice::Auto, unit = "", range = Range::any();
        /// Demonstration cycle: plane-strain modulus ℰ.
        demo_modulus: f64 = 2.0e6, unit = "Pa", range = Range::positive();
        /// Demonstration cycle: work of adhesion w.
        demo_work_of_adhesion: f64 = 0.04, unit = "J/m^2", range = Range::positive();
        /// Demonstration cycle: force noise, as a fraction of the largest |P|.
        demo_noise: f64 = 0.01, unit = "", range = Range::between(0.0, 0.5);
        /// Demonstration cycle: samples per branch.
        demo_points: usize = 400, unit = "", range = Range::between(20.0, 1.0e6);
    }
}

/// The synthetic demonstration cycle of [`Fig2_8Fit`]: the model's cycle with seeded Gaussian
/// force noise (standard deviation `noise` × max |P|; the same cycle on every run and platform).
///
/// # Errors
/// Model errors.
pub fn demo_cycle(x: &Experiment, noise: f64, samples: usize) -> Result<crate::fit::Curve> {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    let d_o = x.pull_off()?.before.delta;
    let mut curve = crate::fit::simulate_cycle(x, 1.5 * d_o, 3.0 * x.scales().h, samples)?;
    let p_max = curve.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2019);
    for p in curve.force.iter_mut() {
        let z: f64 = StandardNormal.sample(&mut rng);
        *p += noise * p_max * z;
    }
    Ok(curve)
}

crate::scene! {
    /// fig2.8-fit: fit a measured force-indentation cycle (appendix A.4) and draw it against both
    /// models, as `adhesion --headless --fit FILE.csv` does.
    pub struct Fig2_8Fit {
        id: "fig2.8-fit",
        chapter: "2",
        params: Fig2_8FitParams,
        title: "Fit of a measured force-indentation cycle (your data)",
        caption: "A measured cycle (CSV: depth and force columns with units; positive depth is \
            indentation) fitted for the work of adhesion and the plane-strain modulus by Levenberg-Marquardt on the \
            contact relation (2.31b)-(2.32b), appendix A.4, with the contact point and the force baseline free; \
            the in-contact part is found automatically and the retract is fitted. Drawn against \
            the machine-stiffness model and JKR at the fitted parameters, with their predicted jumps.",
        results: &[
            ("work_of_adhesion_J_per_m2", "fitted w"),
            ("work_of_adhesion_std_error_J_per_m2", "standard error of w"),
            ("plane_strain_modulus_Pa", "fitted plane-strain modulus E/(1-nu^2)"),
            ("plane_strain_modulus_std_error_Pa", "its standard error"),
            ("rms_residual_N", "root-mean-square force residual"),
            ("points_used_count", "rows fitted (in and out of contact)"),
            ("contact_point_m", "fitted contact point, in the data's depth origin"),
            ("contact_point_std_error_m", "its standard error"),
            ("baseline_N", "fitted force baseline"),
            ("measured_pull_off_force_N", "measured pull-off: the retract's force minimum"),
            ("jkr_pull_off_force_N", "JKR pull-off -5 pi w R/6 at the fit"),
            ("pull_in_force_N", "machine-stiffness pull-in force (k_s > 0 only)"),
            ("pull_in_depth_jump_m", "machine-stiffness depth change at the pull-in (k_s > 0 only)"),
            ("pull_off_force_N", "machine-stiffness pull-off force (k_s > 0 only)"),
            ("pull_off_depth_jump_m", "machine-stiffness depth change at the pull-off (k_s > 0 only)"),
        ],
    }
}

impl Scene for Fig2_8Fit {
    fn validate(p: &Self::Params) -> Result<()> {
        if p.model == FitModelChoice::MachineStiffness && p.spring_constant == 0.0 {
            return Err(Error::invalid(
                "model",
                "machine-stiffness",
                "needs spring_constant > 0",
            ));
        }
        Ok(())
    }

    fn quick(p: &mut Self::Params) {
        p.demo_points = p.demo_points.min(80);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let k = (p.spring_constant > 0.0).then_some(p.spring_constant);
        let path = std::path::PathBuf::from(if p.data_file.is_empty() {
            "demonstration"
        } else {
            p.data_file.as_str()
        });
        let curve = if p.data_file.is_empty() {
            let x = Experiment::new(
                TipGeometry::Sphere { radius: p.tip_radius },
                p.demo_modulus,
                p.demo_work_of_adhesion,
                k.unwrap_or(1.0),
            )?;
            demo_cycle(&x, p.demo_noise, p.demo_points)?
        } else {
            crate::fit::read_curve(&path)?
        };
        job.check()?;
        let model = match p.model {
            FitModelChoice::Auto => None,
            FitModelChoice::Jkr => Some(crate::fit::FitModel::Jkr),
            FitModelChoice::MachineStiffness => Some(crate::fit::FitModel::MachineStiffness),
        };
        let report = crate::fit::fit_curve(&curve, &path, p.tip_radius, k, model).map_err(|e| match e {
            // The demonstration is no file of the user's: its failure is the parameters'.
            Error::DataFile { message, .. } if p.data_file.is_empty() => Error::Unresolvable {
                model: "fit of the demonstration cycle",
                reason: message,
            },
            e => e,
        })?;
        let mut fig = crate::fit::fit_figure(&curve, &report)?;
        fig.id = Self::ID.into();
        fig.title = Self::TITLE.into();
        if let Some(jkr) = report.jkr {
            fig.result("jkr_pull_off_force_N", jkr.pull_off_force_n);
        }
        if let Some(ms) = report.machine_stiffness {
            fig.result("pull_in_force_N", ms.pull_in_force_n);
            fig.result("pull_in_depth_jump_m", ms.pull_in_depth_jump_m);
            fig.result("pull_off_force_N", ms.pull_off_force_n);
            fig.result("pull_off_depth_jump_m", ms.pull_off_depth_jump_m);
        }
        if p.data_file.is_empty() {
            fig.note("no data file given: a synthetic demonstration cycle of the model is fitted");
            label_synthetic(&mut fig, p, &report);
        }
        job.progress(1.0, "done");
        Ok(fig)
    }
}

/// The demonstration's figure says on its face that its data are synthetic: the title, the
/// panel's title, the data series' names, and a note with the parameters the cycle was made
/// with beside the fitted ones.
fn label_synthetic(fig: &mut Figure, p: &Fig2_8FitParams, report: &crate::fit::FitReport) {
    fig.title = "Fit of a synthetic cycle (demonstration: no data file)".into();
    let Some(panel) = fig.panels.first_mut() else {
        return;
    };
    panel.title = "synthetic cycle of the model with noise, fitted".into();
    for s in &mut panel.series {
        s.name = match s.name.as_str() {
            "measured" => "synthetic data".into(),
            "measured, fitted in contact" => "synthetic data, in-contact rows fitted".into(),
            _ => continue,
        };
    }
    let (Some(w), e) = (&report.work_of_adhesion_j_per_m2, &report.plane_strain_modulus_pa) else {
        return;
    };
    panel.annotate(format!(
        "synthetic: w = {} mJ/m², ℰ = {} MPa, noise {} % of max |P|",
        number(p.demo_work_of_adhesion * 1e3, 3),
        number(p.demo_modulus * 1e-6, 3),
        number(p.demo_noise * 100.0, 2)
    ));
    panel.annotate(format!(
        "fitted: w = {} ± {} mJ/m², ℰ = {} ± {} MPa",
        number(w.value * 1e3, 4),
        number(w.std_error * 1e3, 2),
        number(e.value * 1e-6, 4),
        number(e.std_error * 1e-6, 2)
    ));
}
