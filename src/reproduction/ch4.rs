//! The printed numbers of chapter 4 that the analytic models compute: the coefficients and the
//! critical point of the instability criterion (4.23) (Sec. 4.3), ℓ and χ of the captions of
//! Figures 4.5 and 4.7 from the LJ parameters (4.6), (4.7b), (4.25), and the geometry of the
//! wavy tip of Sec. 4.5.1; with the axisymmetric surface model, the error of the parabola
//! approximation of Sec. 4.3 (Fig. 4.3b) and the adhesive forces and losses of Fig. 4.9a
//! (Sec. 4.5.2; scene fig4.9a, run once for all its claims).

use std::f64::consts::PI;
use std::sync::OnceLock;

use super::{Claim, Expect, Precision};
use crate::error::{Error, Result};
use crate::figure::Figure;
use crate::job::Job;
use crate::models::lennard_jones::{InstabilityCriterion, LennardJones, LennardJonesParams, TractionLaw};
use crate::scenes::fig4::criterion::{Fig4_3Params, parabola_error_before_pull_in};

/// Poisson's ratio of every chapter 4 simulation.
const NU: f64 = 0.25;

/// The LJ interaction C₆ = 3, C₁₂ = 1, σ = 1 nm with Hamaker constant `hamaker` [J].
fn interaction(hamaker: f64) -> Result<LennardJones> {
    LennardJones::new(&LennardJonesParams {
        hamaker,
        ..LennardJonesParams::default()
    })
}

/// E* = E/(1 − ν²) [Pa] for Young's modulus `young` [Pa].
fn effective_modulus(young: f64) -> f64 {
    young / (1.0 - NU * NU)
}

/// Figure 4.5: R = 5 µm, E = 4.4 MPa, A_H = 2e-21 J: (ℓ, χ).
fn fig4_5_ell_chi() -> Result<(f64, f64)> {
    let lj = interaction(2e-21)?;
    let modulus = effective_modulus(4.4e6);
    Ok((lj.ell(5e-6, modulus), lj.chi(modulus)))
}

/// Tip radius R of Figure 4.7 [m].
const FIG4_7_RADIUS: f64 = 10e-6;
/// Amplitude A of the undulation (4.10) of Figure 4.7 [m].
const FIG4_7_AMPLITUDE: f64 = 1.25e-9;
/// Wavelength λ of the undulation (4.10) of Figure 4.7 [m].
const FIG4_7_WAVELENGTH: f64 = 0.125e-6;

/// R_a/R = λ²/(4π²AR), the asperity radius of (4.10) over the tip radius (Sec. 4.5.1).
fn asperity_radius_ratio() -> f64 {
    FIG4_7_WAVELENGTH.powi(2) / (4.0 * PI * PI * FIG4_7_AMPLITUDE * FIG4_7_RADIUS)
}

/// The criterion (4.23) for C₆ = 3, C₁₂ = 1 with the printed traction (4.19).
fn criterion() -> Result<InstabilityCriterion> {
    InstabilityCriterion::new(&interaction(2e-21)?, TractionLaw::AsPrinted)
}

/// Result `name` of scene `id` at its defaults; the scene runs once per process (`cell`) for
/// all its claims.
fn scene_result(
    cell: &'static OnceLock<std::result::Result<Figure, String>>,
    id: &'static str,
    name: &str,
) -> Result<f64> {
    let fig = cell.get_or_init(|| {
        let s = crate::scenes::find(id).map_err(|e| e.to_string())?;
        s.run(&s.defaults(), &Job::quiet()).map_err(|e| e.to_string())
    });
    let fail = |reason: String| Error::Unresolvable { model: id, reason };
    let fig = fig.as_ref().map_err(|e| fail(e.clone()))?;
    fig.result_value(name)
        .ok_or_else(|| fail(format!("no result {name}")))
}

/// A result of scene fig4.9a at its defaults.
fn fig4_9a(name: &str) -> Result<f64> {
    static FIG: OnceLock<std::result::Result<Figure, String>> = OnceLock::new();
    scene_result(&FIG, "fig4.9a", name)
}

/// A result of scene fig4.10 at its defaults (the 6 x 6 sweep, about a minute on 2 cores).
fn fig4_10(name: &str) -> Result<f64> {
    static FIG: OnceLock<std::result::Result<Figure, String>> = OnceLock::new();
    scene_result(&FIG, "fig4.10", name)
}

/// Why the optimum of Fig. 4.10 differs.
const FIG4_10_OPTIMUM: &str = "surface model on the default 6 x 6 grid (alpha 0-0.6, beta 0.12-2, E = 2.2 MPa): the \
    largest P_adh (and H) lies on the grid's edge at (0.48, 0.12), no interior optimum; at a fixed Hamaker constant w \
    grows as sigma^-2, so P_adh/(2E*R^2) grows as beta falls (scene fig4.10, ERRATA candidate)";

/// Why the rough-tip values of Fig. 4.9a differ.
const FIG4_9_ROUGH: &str = "surface model at E = 1.1 MPa (converged in ring width, scene fig4.5-accuracy); the \
    trend (a rise at A/lambda = 0.0075, a fall at 0.02) is reproduced. The dissertation's own finite-element model \
    (scene fig4.9a with model = fe: 7 154 unknowns, surface elements of 0.25 b, tip 20 R, grading 0.15; 63 s of one \
    core, not recomputed here) gives at E = 1.1 MPa P_adh/(2E*R^2) = 1.562e-5, 2.923e-5, 2.238e-5 (printed 1.54e-5, \
    3.06e-5, 1.93e-5: +1.4 %, -4.5 %, +16 %) and H/(2E*R^3) = 3.090e-9, 15.38e-9, 10.25e-9 (printed 2.93e-9, \
    12.43e-9, 7.7e-9: +5.5 %, +24 %, +33 %), and on surface elements of 0.125 b (11 211 unknowns) P_adh 1.567e-5, \
    2.915e-5, 2.309e-5 and H 3.100e-9, 15.28e-9, 10.85e-9 (changes under 1 % but at A/lambda = 0.02: 3 % and 6 %): \
    the model closes most of the surface model's gap in P_adh at A/lambda = 0.0075; the rest (A/lambda = 0.02, and H \
    of the rough tips, 20-40 % above the print) is not discretisation and is unexplained, the dissertation's mesh, tip \
    size and depth step not being given; at the caption's E = 2.2 MPa both models give about half the printed forces. \
    Fig. 4.9b's rise of P_adh with sigma for the rough tip is in neither model: scene fig4.9b-models, converged, \
    falls monotonically from sigma = 1 nm in the surface model, the finite elements and on a fixed mesh";

/// The largest parabola error (4.24) just before the pull-in at μ_T = 5 and its radius over
/// √(2R z_c) (scene fig4.3 at its defaults: one surface-model cycle, computed once).
///
/// # Errors
/// [`Error::Unresolvable`] when the cycle fails or has no pull-in.
fn parabola_error_max() -> Result<(f64, f64)> {
    static ONCE: OnceLock<std::result::Result<(f64, f64), String>> = OnceLock::new();
    ONCE.get_or_init(|| {
        let e = parabola_error_before_pull_in(&Fig4_3Params::default())
            .map_err(|e| e.to_string())?
            .ok_or_else(|| "no pull-in at mu_T = 5".to_string())?;
        let (err, at) = e.max();
        Ok((err, at / e.zone))
    })
    .clone()
    .map_err(|reason| Error::Unresolvable {
        model: "fig4.3 surface model",
        reason,
    })
}

/// Why the parabola error of Fig. 4.3b differs from the text.
const WHY_PARABOLA: &str = "surface model: 14.6 % at r = 0.81 sqrt(2 R z_c) (115 nm); with z0 the deformed apex gap \
    err(0) = 0 by construction, and the apex has moved 0.56 z_c before the pull-in ((4.21)-(4.22) themselves put it \
    near 2 z_c/5), so the profile is not a parabola to 5 % (scene fig4.3, ERRATA candidate)";

/// The claims of chapter 4.
pub fn claims() -> Vec<Claim> {
    vec![
        Claim {
            id: "ch4.c1",
            source: "Eq. (4.23)",
            quantity: "c1 (coefficient of z^-7/2) for C6 = 3, C12 = 1, from (4.21)-(4.22) with the printed (4.19)",
            printed: "23.1",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::c1",
            compute: || Ok(criterion()?.c1()),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.c2",
            source: "Eq. (4.23)",
            quantity: "c2 (coefficient of z^-19/2) for C6 = 3, C12 = 1 (the printed definitions of c1, c2 are swapped, ERRATA)",
            printed: "13.7",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::c2",
            compute: || Ok(criterion()?.c2()),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.critical_tabor",
            source: "Sec. 4.3",
            quantity: "critical Tabor parameter mu_T* of (4.23), unrounded coefficients",
            printed: "0.20155",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::critical_tabor",
            compute: || Ok(criterion()?.critical_tabor()),
            expect: Expect::Differs(
                "unrounded c1 = 23.1039, c2 = 13.7123 give 0.201584; the print follows from the rounded 23.1, 13.7 (ERRATA (4.23), claim ch4.critical_tabor_rounded)",
            ),
        },
        Claim {
            id: "ch4.critical_tabor_rounded",
            source: "Sec. 4.3",
            quantity: "critical Tabor parameter mu_T* of (4.23) with the printed, rounded c1 = 23.1, c2 = 13.7",
            printed: "0.20155",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::from_coefficients",
            compute: || Ok(InstabilityCriterion::from_coefficients(23.1, 13.7)?.critical_tabor()),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.critical_separation",
            source: "Sec. 4.3",
            quantity: "double root z_c*/zeta0 of (4.23) at mu_T*, unrounded coefficients",
            printed: "1.08258",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::double_root",
            compute: || Ok(criterion()?.double_root()),
            expect: Expect::Differs(
                "unrounded c1, c2 give 1.082713; the print follows from the rounded 23.1, 13.7 (ERRATA (4.23), claim ch4.critical_separation_rounded)",
            ),
        },
        Claim {
            id: "ch4.critical_separation_rounded",
            source: "Sec. 4.3",
            quantity: "double root z_c*/zeta0 of (4.23) with the printed, rounded c1 = 23.1, c2 = 13.7",
            printed: "1.08258",
            precision: Precision::Printed,
            code: "models::lennard_jones::InstabilityCriterion::from_coefficients",
            compute: || Ok(InstabilityCriterion::from_coefficients(23.1, 13.7)?.double_root()),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.parabola_error_max",
            source: "Sec. 4.3, Fig. 4.3b",
            quantity: "largest err(r) of (4.24) just before the pull-in at mu_T = 5 (the text: less than 5 %), surface model",
            printed: "0.05",
            precision: Precision::Printed,
            code: "scenes::fig4::criterion::parabola_error_before_pull_in",
            compute: || Ok(parabola_error_max()?.0),
            expect: Expect::Differs(WHY_PARABOLA),
        },
        Claim {
            id: "ch4.parabola_error_max_radius",
            source: "Sec. 4.3, Fig. 4.3b",
            quantity: "radius of the largest err(r) of (4.24) over sqrt(2 R z_c) (the text: at the centre), surface model",
            printed: "0",
            precision: Precision::Absolute(0.05),
            code: "scenes::fig4::criterion::parabola_error_before_pull_in",
            compute: || Ok(parabola_error_max()?.1),
            expect: Expect::Differs(WHY_PARABOLA),
        },
        Claim {
            id: "ch4.fig4.5_ell",
            source: "Fig. 4.5",
            quantity: "ell = pi w/(E* R), w = C6 A_H/(16 pi zeta0^2) (4.7b), R = 5 um, E = 4.4 MPa, nu = 0.25, A_H = 2e-21 J",
            printed: "4.51e-5",
            precision: Precision::Printed,
            code: "models::lennard_jones::LennardJones::ell",
            compute: || Ok(fig4_5_ell_chi()?.0),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.fig4.5_chi",
            source: "Fig. 4.5",
            quantity: "chi = w/(E* delta0), delta0 = (9 sqrt3/16) zeta0 from the consistent traction (ERRATA (4.19); the printed c3 of Sec. 4.4 would give 0.446)",
            printed: "0.124",
            precision: Precision::Printed,
            code: "models::lennard_jones::LennardJones::chi",
            compute: || Ok(fig4_5_ell_chi()?.1),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.fig4.7_ell",
            source: "Fig. 4.7",
            quantity: "ell = pi w/(E* R) of the wavy-tip theory (printed as chi, ERRATA (4.26)), R = 10 um, E = 2.2 MPa, nu = 0.25, A_H = 1e-21 J",
            printed: "2.26e-5",
            precision: Precision::Printed,
            code: "models::lennard_jones::LennardJones::ell",
            compute: || Ok(interaction(1e-21)?.ell(FIG4_7_RADIUS, effective_modulus(2.2e6))),
            expect: Expect::Reproduced,
        },
        Claim::exact(
            "ch4.fig4.7_amplitude_ratio",
            "Fig. 4.7",
            "A/R for A = 1.25 nm, R = 10 um",
            "1.25e-4",
            "reproduction::ch4",
            || Ok(FIG4_7_AMPLITUDE / FIG4_7_RADIUS),
        ),
        Claim::exact(
            "ch4.fig4.7_wavelength_ratio",
            "Fig. 4.7",
            "lambda/R for lambda = 0.125 um, R = 10 um",
            "1.25e-2",
            "reproduction::ch4",
            || Ok(FIG4_7_WAVELENGTH / FIG4_7_RADIUS),
        ),
        Claim::exact(
            "ch4.aspect_ratio",
            "Sec. 4.5.1",
            "A/lambda of the tip of Figs. 4.7-4.8 (A = 1.25 nm, lambda = 0.125 um)",
            "0.01",
            "reproduction::ch4",
            || Ok(FIG4_7_AMPLITUDE / FIG4_7_WAVELENGTH),
        ),
        Claim {
            id: "ch4.asperity_radius_ratio",
            source: "Sec. 4.5.1",
            quantity: "R_a/R = lambda^2/(4 pi^2 A R) of the tip of Figs. 4.7-4.8",
            printed: "0.0317",
            precision: Precision::Printed,
            code: "reproduction::ch4::asperity_radius_ratio",
            compute: || Ok(asperity_radius_ratio()),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.contact_radius_ratio",
            source: "Sec. 4.5.1",
            quantity: "ratio of the JKR pull-in contact radii (2 pi R_a w/E*)^(1/3)/(2 pi R w/E*)^(1/3), printed as R_a/R",
            printed: "0.0317",
            precision: Precision::Printed,
            code: "reproduction::ch4::asperity_radius_ratio",
            compute: || Ok(asperity_radius_ratio().cbrt()),
            expect: Expect::Differs(
                "the ratio of the contact radii is (R_a/R)^(1/3) = 0.316; the text prints R_a/R (ERRATA Sec. 4.5.1)",
            ),
        },
        Claim {
            id: "ch4.fig4_9_p_adh_smooth",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "P_adh/(2E*R^2) of the smooth tip (A = 0, sigma = 1.5 nm, |h_min|/R = 6e-4) at E = 1.1 MPa (ERRATA Fig. 4.9)",
            printed: "1.54e-5",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("p_adh_1_b_norm"),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch4.fig4_9_p_adh_0075",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "P_adh/(2E*R^2) at A/lambda = 0.0075 at E = 1.1 MPa",
            printed: "3.06e-5",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("p_adh_2_b_norm"),
            expect: Expect::Differs(FIG4_9_ROUGH),
        },
        Claim {
            id: "ch4.fig4_9_p_adh_02",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "P_adh/(2E*R^2) at A/lambda = 0.02 at E = 1.1 MPa",
            printed: "1.93e-5",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("p_adh_3_b_norm"),
            expect: Expect::Differs(FIG4_9_ROUGH),
        },
        Claim {
            id: "ch4.fig4_9_hysteresis_smooth",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "H/(2E*R^3) of the smooth tip at E = 1.1 MPa",
            printed: "2.93e-9",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("hysteresis_1_b_norm"),
            expect: Expect::Differs(
                "the loss of the smooth tip is the loop area between the pull-in and pull-off branches, 3.03e-9 with the surface model (3% above the print) while its P_adh reproduces 1.54e-5; the FE model's mesh and tip size are not given",
            ),
        },
        Claim {
            id: "ch4.fig4_9_hysteresis_0075",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "H/(2E*R^3) at A/lambda = 0.0075 at E = 1.1 MPa",
            printed: "12.43e-9",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("hysteresis_2_b_norm"),
            expect: Expect::Differs(FIG4_9_ROUGH),
        },
        Claim {
            id: "ch4.fig4_9_hysteresis_02",
            source: "Sec. 4.5.2, Fig. 4.9a",
            quantity: "H/(2E*R^3) at A/lambda = 0.02 at E = 1.1 MPa",
            printed: "7.7e-9",
            precision: Precision::Printed,
            code: "scenes::fig4::roughness::Fig4_9a",
            compute: || fig4_9a("hysteresis_3_b_norm"),
            expect: Expect::Differs(FIG4_9_ROUGH),
        },
        Claim {
            id: "ch4.fig4_10_alpha_optimum",
            source: "Sec. 4.5.2, Fig. 4.10",
            quantity: "alpha = A^2/(lambda w/E*) of the largest adhesive force (grid maximum of scene fig4.10)",
            printed: "0.1741",
            precision: Precision::Printed,
            code: "scenes::fig4::sweeps::Fig4_10",
            compute: || fig4_10("alpha_p_adh_max_norm"),
            expect: Expect::Differs(FIG4_10_OPTIMUM),
        },
        Claim {
            id: "ch4.fig4_10_beta_optimum",
            source: "Sec. 4.5.2, Fig. 4.10",
            quantity: "beta = sigma^2/(lambda w/E*) of the largest adhesive force (grid maximum of scene fig4.10)",
            printed: "0.4457",
            precision: Precision::Printed,
            code: "scenes::fig4::sweeps::Fig4_10",
            compute: || fig4_10("beta_p_adh_max_norm"),
            expect: Expect::Differs(FIG4_10_OPTIMUM),
        },
    ]
}
