//! Readable numbers for the terminal chart and its readouts: tick labels at 1-2-5 steps with
//! at most four significant digits, the axis' scale moved into its title (an SI prefix on a
//! dimensional unit, `µN` for `N`; a common power of ten otherwise, `×10⁻⁶`), and single
//! values with their unit (`−1.234 µN`).

use super::axes::{nice_step, power_of_ten, ticks};
use crate::figure::{Axis, Scale};

/// Most significant digits a tick label or a readout shows.
pub const MAX_DIGITS: i32 = 4;

/// SI prefixes by power of ten (µ is the micro sign, as in the scenes' units).
const PREFIXES: [(i32, &str); 9] = [
    (-15, "f"),
    (-12, "p"),
    (-9, "n"),
    (-6, "µ"),
    (-3, "m"),
    (0, ""),
    (3, "k"),
    (6, "M"),
    (9, "G"),
];

/// Units that take an SI prefix as a whole (`mJ/m²` is milli of `J/m²`; a power such as `m²`
/// does not, since `mm²` is not milli of `m²`).
const BASE_UNITS: &[&str] = &["m", "N", "Pa", "J", "s", "N/m", "J/m²", "W", "Hz", "V"];

/// The power of ten of a unit's SI prefix and the unit without it, for units that take one.
pub fn split_unit(unit: &str) -> Option<(i32, &str)> {
    if BASE_UNITS.contains(&unit) {
        return Some((0, unit));
    }
    let micro = [(-6, "u"), (-6, "μ")];
    PREFIXES
        .iter()
        .chain(&micro)
        .filter(|(_, p)| !p.is_empty())
        .find_map(|&(e, p)| {
            unit.strip_prefix(p)
                .filter(|rest| BASE_UNITS.contains(rest))
                .map(|rest| (e, rest))
        })
}

fn prefix(exp: i32) -> &'static str {
    PREFIXES.iter().find(|(e, _)| *e == exp).map_or("", |(_, p)| p)
}

/// How an axis' numbers are scaled: shown value = value / 10^`exp`; `title` carries the scale.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisScale {
    /// Power of ten divided out of every value.
    pub exp: i32,
    /// The axis title with the scale: `P [µN]`, `A [10⁻¹² m²]` or `u/σ ×10³`.
    pub title: String,
    /// The unit the shown values are in (with the new prefix), empty when non-dimensional.
    pub unit: String,
}

/// The scale for numbers up to `magnitude` on an axis with `unit`: an engineering SI prefix
/// where the unit takes one, else a common power of ten when the numbers would need more than
/// four digits or leading zeros (outside [0.01, 10⁴)).
pub fn axis_scale(label: &str, unit: &str, magnitude: f64) -> AxisScale {
    let m = magnitude.abs();
    let plain = |unit: &str| AxisScale {
        exp: 0,
        title: if unit.is_empty() {
            label.to_string()
        } else {
            format!("{label} [{unit}]")
        },
        unit: unit.to_string(),
    };
    if !(m.is_finite() && m > 0.0) {
        return plain(unit);
    }
    let decade = m.log10().floor() as i32;
    if let Some((own, base)) = split_unit(unit) {
        let total = decade + own;
        let eng = (total.div_euclid(3) * 3).clamp(-15, 9);
        let unit = format!("{}{base}", prefix(eng));
        return AxisScale {
            exp: eng - own,
            ..plain(&unit)
        };
    }
    if (-2..4).contains(&decade) {
        return plain(unit);
    }
    let power = power_of_ten(i64::from(decade));
    let title = if unit.is_empty() {
        format!("{label} ×{power}")
    } else {
        format!("{label} [{power} {unit}]")
    };
    AxisScale {
        exp: decade,
        title,
        unit: unit.to_string(),
    }
}

/// Ticks of one axis: positions in drawing coordinates (log10 of the value on a log axis) with
/// their labels, and the title carrying the scale.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLabels {
    /// (position, label), increasing.
    pub ticks: Vec<(f64, String)>,
    /// Title with unit and scale.
    pub title: String,
}

/// Ticks for the shown range `[lo, hi]` (data units) of `axis`, about `target` intervals.
pub fn axis_labels(axis: &Axis, lo: f64, hi: f64, target: usize) -> AxisLabels {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    match axis.scale {
        Scale::Log => {
            let t = ticks(lo, hi, Scale::Log, target);
            let mut pairs: Vec<(f64, String)> = t
                .values
                .iter()
                .zip(t.labels)
                .map(|(v, l)| (v.log10(), l))
                .collect();
            // Thin decades to about `target` labels.
            let every = pairs.len().div_ceil(target.max(2));
            if every > 1 {
                pairs = pairs.into_iter().step_by(every).collect();
            }
            AxisLabels {
                ticks: pairs,
                title: axis.title(),
            }
        }
        Scale::Linear => {
            let scale = axis_scale(&axis.label, &axis.unit, lo.abs().max(hi.abs()));
            let f = 10f64.powi(scale.exp);
            let ticks = linear_ticks(lo / f, hi / f, target)
                .into_iter()
                .map(|(v, l)| (v * f, l))
                .collect();
            AxisLabels {
                ticks,
                title: scale.title,
            }
        }
    }
}

/// 1-2-5 ticks of `[lo, hi]` with labels of at most [`MAX_DIGITS`] significant digits.
pub fn linear_ticks(lo: f64, hi: f64, target: usize) -> Vec<(f64, String)> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return if lo.is_finite() {
            vec![(lo, fmt_sig(lo, MAX_DIGITS))]
        } else {
            Vec::new()
        };
    }
    let mut step = nice_step(hi - lo, target);
    // A range narrow for its magnitude (1000.1 to 1000.3) would need more digits: coarser steps.
    let top = lo.abs().max(hi.abs()).log10().floor() as i32;
    let finest = 10f64.powi(top - (MAX_DIGITS - 1));
    if step < finest {
        step = finest;
    }
    let decimals = (-(step.log10() + 1e-9).floor()).max(0.0) as usize;
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            (v, fmt_fixed(v, decimals))
        })
        .collect()
}

/// `v` with `decimals` decimals, `−` for minus and no negative zero.
fn fmt_fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        "0".into()
    } else {
        s.replace('-', "−")
    }
}

/// `v` with at most `digits` significant digits, trailing zeros dropped; a power of ten
/// (`1.234×10⁻⁸`) outside [10⁻³, 10⁵).
pub fn fmt_sig(v: f64, digits: i32) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let mut decade = v.abs().log10().floor() as i32;
    // Rounding can carry into the next decade (9.9996 -> 10.00).
    let rounded = round_sig(v, digits);
    if rounded != 0.0 {
        decade = rounded.abs().log10().floor() as i32;
    }
    if (-3..5).contains(&decade) {
        let decimals = (digits - 1 - decade).max(0) as usize;
        trim(&fmt_fixed(rounded, decimals))
    } else {
        let mantissa = rounded / 10f64.powi(decade);
        let m = trim(&fmt_fixed(mantissa, (digits - 1).max(0) as usize));
        format!("{m}×{}", power_of_ten(i64::from(decade)))
    }
}

fn round_sig(v: f64, digits: i32) -> f64 {
    let decade = v.abs().log10().floor() as i32;
    let f = 10f64.powi(digits - 1 - decade);
    (v * f).round() / f
}

fn trim(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// A value with its unit for people: an SI prefix where the unit takes one (`−1.234 µN`),
/// else four significant digits (`0.1234`, `3.5×10⁻⁸ m²`).
pub fn fmt_quantity(v: f64, unit: &str) -> String {
    if let Some((own, base)) = split_unit(unit)
        && v.is_finite()
        && v != 0.0
    {
        let total = v.abs().log10().floor() as i32 + own;
        let mut eng = (total.div_euclid(3) * 3).clamp(-15, 9);
        let mut shown = round_sig(v * 10f64.powi(own - eng), MAX_DIGITS);
        if shown.abs() >= 1000.0 && eng < 9 {
            eng += 3;
            shown /= 1000.0;
        }
        return format!("{} {}{base}", fmt_sig(shown, MAX_DIGITS), prefix(eng));
    }
    let number = fmt_sig(v, MAX_DIGITS);
    if unit.is_empty() {
        number
    } else {
        format!("{number} {unit}")
    }
}

/// The unit of a result from its name's suffix (`_N`, `_J_per_m2`, ...), and the name without
/// it. Non-dimensional results (`_norm`, `_count`) and names without a known suffix keep their
/// whole name and get no unit (`jkr_pull_off_force_norm` and `jkr_pull_off_force_N` stay
/// apart).
pub fn result_unit(name: &str) -> (&str, &'static str) {
    const SUFFIXES: [(&str, &str); 23] = [
        ("_m2_per_m2", "m²/m²"),
        ("_J_per_m2", "J/m²"),
        ("_N_per_m", "N/m"),
        ("_per_m2", "1/m²"),
        ("_per_m", "1/m"),
        ("_percent", "%"),
        ("_count", ""),
        ("_norm", ""),
        ("_MPa", "MPa"),
        ("_Pa", "Pa"),
        ("_nN", "nN"),
        ("_uN", "µN"),
        ("_N", "N"),
        ("_nm", "nm"),
        ("_um", "µm"),
        ("_m4", "m⁴"),
        ("_m3", "m³"),
        ("_m2", "m²"),
        ("_m", "m"),
        ("_J", "J"),
        ("_rad", "rad"),
        ("_deg", "°"),
        ("_s", "s"),
    ];
    if name.ends_with("_norm") || name.ends_with("_count") {
        return (name, "");
    }
    SUFFIXES
        .iter()
        .find_map(|(s, u)| name.strip_suffix(s).map(|n| (n, *u)))
        .unwrap_or((name, ""))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Significant digits: from the first non-zero digit to the last decimal, or to the last
    /// non-zero digit of an integer (`20000` has one).
    fn digits(label: &str) -> usize {
        let mantissa = label.split('×').next().unwrap_or(label);
        let all: String = mantissa.chars().filter(char::is_ascii_digit).collect();
        let lead = all.trim_start_matches('0');
        if mantissa.contains('.') {
            lead.len()
        } else {
            lead.trim_end_matches('0').len()
        }
    }

    #[test]
    fn ticks_are_1_2_5_steps_with_at_most_four_digits() {
        let t = linear_ticks(-451.1081, 1160.1979, 5);
        let labels: Vec<&str> = t.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["0", "500", "1000"]);
        assert!(labels.contains(&"0"), "{labels:?}");
        for (lo, hi) in [
            (1000.1, 1000.3),
            (-3e-9, 7e-9),
            (0.0012, 0.0019),
            (12345.0, 98765.0),
        ] {
            for (_, l) in linear_ticks(lo, hi, 6) {
                assert!(digits(&l) <= 4, "{l} for [{lo}, {hi}]");
            }
        }
        let steps: Vec<f64> = t.windows(2).map(|w| w[1].0 - w[0].0).collect();
        assert!(steps.iter().all(|s| (s - steps[0]).abs() < 1e-9));
        let m = steps[0] / 10f64.powf(steps[0].log10().floor());
        assert!(
            [1.0, 2.0, 5.0].iter().any(|n| (m - n).abs() < 1e-9),
            "step {}",
            steps[0]
        );
    }

    #[test]
    fn dimensional_axes_take_a_prefix_and_others_a_power_of_ten() {
        assert_eq!(axis_scale("P", "N", 3.2e-6).title, "P [µN]");
        assert_eq!(axis_scale("P", "N", 3.2e-6).exp, -6);
        assert_eq!(axis_scale("h", "nm", 4500.0).title, "h [µm]");
        assert_eq!(axis_scale("h", "nm", 4500.0).exp, 3);
        assert_eq!(axis_scale("u/σ", "", 1160.0).title, "u/σ");
        assert_eq!(axis_scale("u/σ", "", 11600.0).title, "u/σ ×10⁴");
        assert_eq!(axis_scale("A", "m²", 3e-12).title, "A [10⁻¹² m²]");
        assert_eq!(fmt_quantity(-1.23456e-6, "N"), "−1.235 µN");
        assert_eq!(fmt_quantity(999.96, "m"), "1 km");
        assert_eq!(fmt_quantity(0.5, ""), "0.5");
        assert_eq!(fmt_quantity(2.5e-8, "m²"), "2.5×10⁻⁸ m²");
        assert_eq!(result_unit("jkr_pull_off_force_N"), ("jkr_pull_off_force", "N"));
        assert_eq!(result_unit("loss_J_per_m2"), ("loss", "J/m²"));
        assert_eq!(result_unit("ratio_norm"), ("ratio_norm", ""));
    }
}
