//! The reproduction registry: every number the dissertation prints that the workbench computes.
//!
//! Each [`Claim`] names its source (equation, figure, section), the printed text, the code that
//! computes it, and the status the workbench expects to obtain: reproduced within the printed
//! precision, or differs, with the reason (see `ERRATA.md`). `adhesion --headless --reproduce`
//! computes them all and writes `reproduction.md` and `reproduction.json`; a test fails when a
//! claim's status changes, so a regression and an unexplained "fix" are both caught.
//!
//! Each chapter registers its claims in its own file under `reproduction/`.

use serde::Serialize;

use crate::error::Result;

mod appc;
mod ch1;
mod ch2;
mod ch3;
mod ch4;
mod ch5;
mod ch6;

/// What the workbench expects to obtain for a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expect {
    /// The computed value rounds to the printed one.
    Reproduced,
    /// The computed value differs; the reason says why (erratum, inconsistent print, ...).
    Differs(&'static str),
}

/// How close the computed value must be to count as reproduced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Precision {
    /// Half a unit in the last printed digit (`7.092` → ±0.0005).
    Printed,
    /// A relative tolerance, for numbers the text reads off a figure or rounds loosely.
    Relative(f64),
    /// An absolute tolerance (for printed zeros).
    Absolute(f64),
}

/// One printed number.
#[derive(Debug, Clone, Copy)]
pub struct Claim {
    /// Stable id, `chN.name`.
    pub id: &'static str,
    /// Where it is printed: `Eq. (1.6)`, `Fig. 2.5`, `Sec. 2.4`.
    pub source: &'static str,
    /// What it is.
    pub quantity: &'static str,
    /// The printed text of the number (mantissa digits define the printed precision).
    pub printed: &'static str,
    /// Tolerance rule.
    pub precision: Precision,
    /// The code that computes it (path of the function).
    pub code: &'static str,
    /// The computation.
    pub compute: fn() -> Result<f64>,
    /// Expected status.
    pub expect: Expect,
}

impl Claim {
    /// A claim that is an exact consequence of the text's numbers (a ratio of printed
    /// parameters, a closed form): computed to a relative 1e-12 and expected reproduced.
    pub const fn exact(
        id: &'static str,
        source: &'static str,
        quantity: &'static str,
        printed: &'static str,
        code: &'static str,
        compute: fn() -> Result<f64>,
    ) -> Self {
        Self {
            id,
            source,
            quantity,
            printed,
            precision: Precision::Relative(1e-12),
            code,
            compute,
            expect: Expect::Reproduced,
        }
    }
}

/// Status obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Within the printed precision.
    Reproduced,
    /// Outside it.
    Differs,
    /// The computation failed.
    Failed,
}

/// A computed claim.
#[derive(Debug, Clone, Serialize)]
pub struct Outcome {
    /// Claim id.
    pub id: &'static str,
    /// Source.
    pub source: &'static str,
    /// Quantity.
    pub quantity: &'static str,
    /// Printed text.
    pub printed_text: &'static str,
    /// Printed value.
    pub printed: f64,
    /// Computed value (NaN when failed).
    pub computed: f64,
    /// (computed − printed)/|printed|.
    pub relative_difference: f64,
    /// Tolerance used (absolute).
    pub tolerance: f64,
    /// Status obtained.
    pub status: Status,
    /// Whether it is the expected status.
    pub as_expected: bool,
    /// Reason for an expected difference, or the error of a failed computation.
    pub reason: String,
    /// The computing code.
    pub code: &'static str,
}

/// Every claim, chapter by chapter.
pub fn claims() -> Vec<Claim> {
    [
        ch1::claims(),
        ch2::claims(),
        ch3::claims(),
        ch4::claims(),
        ch5::claims(),
        ch6::claims(),
        appc::claims(),
    ]
    .concat()
}

/// Value and absolute tolerance of a printed number: half a unit of its last digit.
///
/// `"7.092"` → (7.092, 0.0005). A printed fraction (`"-5/6"`) is exact: its tolerance is
/// 1e-12 relative.
///
/// # Panics
/// If `text` is not a number (a registry bug caught by the registry test).
pub fn printed_value(text: &str) -> (f64, f64) {
    let t = text.trim();
    if let Some((num, den)) = t.split_once('/') {
        let num: f64 = num
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("numerator of `{t}` parses"));
        let den: f64 = den
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("denominator of `{t}` parses"));
        let value = num / den;
        return (value, 1e-12 * value.abs());
    }
    let value: f64 = t
        .parse()
        .unwrap_or_else(|_| panic!("printed number `{t}` parses"));
    let (mantissa, exponent) = match t.find(['e', 'E']) {
        Some(k) => (&t[..k], t[k + 1..].parse::<i32>().expect("exponent parses")),
        None => (t, 0),
    };
    let decimals = mantissa.find('.').map_or(0, |k| mantissa.len() - k - 1) as i32;
    (value, 0.5 * 10f64.powi(exponent - decimals))
}

/// Compute one claim.
pub fn evaluate(claim: &Claim) -> Outcome {
    let (printed, printed_tol) = printed_value(claim.printed);
    let tolerance = match claim.precision {
        Precision::Printed => printed_tol,
        Precision::Relative(r) => r * printed.abs(),
        Precision::Absolute(a) => a,
    };
    let (computed, status, error) = match (claim.compute)() {
        Ok(v) => {
            // A hair of slack for values that sit exactly on a rounding boundary.
            let ok = (v - printed).abs() <= tolerance * (1.0 + 1e-9);
            (v, if ok { Status::Reproduced } else { Status::Differs }, None)
        }
        Err(e) => (f64::NAN, Status::Failed, Some(e.to_string())),
    };
    let as_expected = matches!(
        (status, claim.expect),
        (Status::Reproduced, Expect::Reproduced) | (Status::Differs, Expect::Differs(_))
    );
    let reason = match (error, claim.expect) {
        (Some(e), _) => e,
        (None, Expect::Differs(r)) => r.to_string(),
        (None, Expect::Reproduced) => String::new(),
    };
    Outcome {
        id: claim.id,
        source: claim.source,
        quantity: claim.quantity,
        printed_text: claim.printed,
        printed,
        computed,
        relative_difference: if printed == 0.0 {
            computed - printed
        } else {
            (computed - printed) / printed.abs()
        },
        tolerance,
        status,
        as_expected,
        reason,
        code: claim.code,
    }
}

/// Compute every claim (in parallel).
pub fn evaluate_all() -> Vec<Outcome> {
    use rayon::prelude::*;
    claims().par_iter().map(evaluate).collect()
}

/// Text for a Markdown table cell: a `|` (as in |P_o|) is escaped, not a column break.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// The report as Markdown.
pub fn markdown(outcomes: &[Outcome]) -> String {
    let mut out = String::from(
        "# Reproduction of the dissertation's printed numbers\n\n\
         Each row is a number printed in the dissertation, the value the workbench computes, \
         their relative difference, and the status: `reproduced` (within half a unit of the last \
         printed digit, or the stated relative tolerance) or `differs` (with the reason; see \
         ERRATA.md).\n\n\
         | id | source | quantity | printed | computed | rel. diff. | status | reason |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for o in outcomes {
        let flag = if o.as_expected { "" } else { " (UNEXPECTED)" };
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {:.2e} | {:?}{} | {} |\n",
            o.id,
            o.source,
            cell(o.quantity),
            o.printed_text,
            format_computed(o.computed),
            o.relative_difference,
            o.status,
            flag,
            cell(&o.reason),
        ));
    }
    let reproduced = outcomes.iter().filter(|o| o.status == Status::Reproduced).count();
    out.push_str(&format!(
        "\n{} claims: {} reproduced, {} differ, {} failed.\n",
        outcomes.len(),
        reproduced,
        outcomes.iter().filter(|o| o.status == Status::Differs).count(),
        outcomes.iter().filter(|o| o.status == Status::Failed).count(),
    ));
    out
}

fn format_computed(v: f64) -> String {
    if v.is_nan() {
        "-".into()
    } else {
        format!("{v:.6e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printed_precision_is_half_a_unit_of_the_last_digit() {
        assert_eq!(printed_value("7.092").0, 7.092);
        assert!((printed_value("7.092").1 - 0.0005).abs() < 1e-15);
        assert!((printed_value("5349.87").1 - 0.005).abs() < 1e-12);
        assert!((printed_value("2.5e-3").1 - 0.5e-4).abs() < 1e-18);
        assert!((printed_value("22").1 - 0.5).abs() < 1e-15);
        assert!((printed_value("-5/6").0 + 5.0 / 6.0).abs() < 1e-15);
    }
}
