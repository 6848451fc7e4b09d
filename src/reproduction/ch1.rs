//! Chapter 1's printed numbers.

use super::{Claim, Expect, Precision};
use crate::error::Result;
use crate::models::classical::{SphereContact, jkr_bar, jkr_hysteresis_constant_by_quadrature};
use crate::numerics::roots::brent;

/// ā at the minimum of h̄(ā) (the displacement-controlled pull-off, D), found numerically.
fn a_min_depth() -> Result<f64> {
    brent(jkr_bar::depth_slope, 0.1, 1.0, 1e-15)
}

/// ā at the minimum of P̄(ā) (the adhesive force, C): dP̄/dā = 4ā² − 3√(2ā) = 0.
fn a_min_force() -> Result<f64> {
    brent(|a| 4.0 * a * a - 3.0 * (2.0 * a).sqrt(), 0.5, 2.0, 1e-15)
}

/// ā where h̄(ā) = 0 on the large-contact branch (pull-in in displacement control, B).
fn a_zero_depth() -> Result<f64> {
    brent(jkr_bar::depth, 0.6, 2.0, 1e-15)
}

/// Chapter 1 claims: the hysteresis constant of (1.6) and the special points (1.3)-(1.5), (1.7).
///
/// The special points are located numerically on the curve (1.2) (as extrema and zeros), not
/// read from the constants they are compared with; forces are in units of πwR, depths of
/// h₀ = (π²Rw²/E*²)^(1/3), radii of a₀ = (πR²w/E*)^(1/3), so the printed fractions are
/// 4/3, 5/6, 3/2, (27/64)^(1/3) = 3/4, (3/64)^(1/3), 2^(1/3), (1/8)^(1/3), (9/8)^(1/3).
pub fn claims() -> Vec<Claim> {
    vec![
        Claim {
            id: "ch1.jkr_hysteresis_constant",
            source: "Eq. (1.6)",
            quantity: "JKR hysteresis H/(R^4 w^5/E*^2)^(1/3), quadrature of the loop",
            printed: "7.092",
            precision: Precision::Printed,
            code: "models::classical::jkr_hysteresis_constant_by_quadrature",
            compute: || jkr_hysteresis_constant_by_quadrature(1e-13),
            expect: Expect::Reproduced,
        },
        Claim::exact(
            "ch1.jkr_pull_in_radius",
            "Eq. (1.3)",
            "(a_B/a0)^3 where h(a) = 0",
            "2/1",
            "models::classical::jkr_bar::depth",
            || Ok(a_zero_depth()?.powi(3)),
        ),
        Claim::exact(
            "ch1.jkr_pull_in_force",
            "Eq. (1.3)",
            "P_B/(pi w R) where h(a) = 0",
            "-4/3",
            "models::classical::jkr_bar::force",
            || Ok(jkr_bar::force(a_zero_depth()?)),
        ),
        Claim {
            id: "ch1.jkr_pull_off_radius",
            source: "Eq. (1.4)",
            quantity: "(a_D/a0)^3 at the minimum of h(a)",
            printed: "1/8",
            precision: Precision::Relative(1e-9),
            code: "models::classical::jkr_bar::depth_slope",
            compute: || Ok(a_min_depth()?.powi(3)),
            expect: Expect::Reproduced,
        },
        Claim::exact(
            "ch1.jkr_pull_off_depth",
            "Eq. (1.4)",
            "(h_D/h0)^3 at the minimum of h(a)",
            "-27/64",
            "models::classical::jkr_bar::depth",
            || Ok(jkr_bar::depth(a_min_depth()?).powi(3)),
        ),
        Claim::exact(
            "ch1.jkr_pull_off_force",
            "Eq. (1.4)",
            "P_D/(pi w R) at the minimum of h(a)",
            "-5/6",
            "models::classical::jkr_bar::force",
            || Ok(jkr_bar::force(a_min_depth()?)),
        ),
        Claim {
            id: "ch1.jkr_adhesive_force_radius",
            source: "Eq. (1.5)",
            quantity: "(a_C/a0)^3 at the minimum of P(a)",
            printed: "9/8",
            precision: Precision::Relative(1e-9),
            code: "models::classical::jkr_bar::force",
            compute: || Ok(a_min_force()?.powi(3)),
            expect: Expect::Reproduced,
        },
        Claim {
            id: "ch1.jkr_adhesive_force_depth",
            source: "Eq. (1.5)",
            quantity: "(h_C/h0)^3 at the minimum of P(a)",
            printed: "-3/64",
            precision: Precision::Relative(1e-9),
            code: "models::classical::jkr_bar::depth",
            compute: || Ok(jkr_bar::depth(a_min_force()?).powi(3)),
            expect: Expect::Reproduced,
        },
        Claim::exact(
            "ch1.jkr_adhesive_force",
            "Eq. (1.5)",
            "P_C/(pi w R) at the minimum of P(a)",
            "-3/2",
            "models::classical::jkr_bar::force",
            || Ok(jkr_bar::force(a_min_force()?)),
        ),
        Claim {
            id: "ch1.dmt_adhesive_force",
            source: "Eq. (1.7)",
            quantity: "DMT adhesive force P_F/(pi w R)",
            printed: "-2/1",
            precision: Precision::Relative(1e-12),
            code: "models::classical::SphereContact::dmt_adhesive_force",
            compute: || {
                let c = SphereContact::new(1.0e-6, 1.0e6, 0.05)?;
                Ok(c.dmt_adhesive_force().p / c.p0())
            },
            expect: Expect::Reproduced,
        },
    ]
}
