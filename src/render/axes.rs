//! Axis ticks and number formatting shared by the plot and terminal renderers.

use crate::figure::Scale;
/// `10ᵏ` with a superscript exponent (also the power of ten of numbers in a figure's text).
pub use crate::figure::power_of_ten;

/// Tick positions (in data units) and their labels for an axis range.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// Tick positions, in data units, inside the range.
    pub values: Vec<f64>,
    /// Labels, parallel to `values`.
    pub labels: Vec<String>,
    /// Minor tick positions (log axes: 2..9 × 10^k).
    pub minor: Vec<f64>,
}

/// Padded drawing range for data bounds: linear axes get 4 % margins (or a unit window when
/// the data are constant); log axes snap outward to whole or half decades.
pub fn padded_range(lo: f64, hi: f64, scale: Scale) -> (f64, f64) {
    match scale {
        Scale::Linear => {
            if !(lo.is_finite() && hi.is_finite()) {
                return (0.0, 1.0);
            }
            if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) {
                let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
                return (lo - d, hi + d);
            }
            let m = 0.04 * (hi - lo);
            (lo - m, hi + m)
        }
        Scale::Log => {
            let lo = if lo > 0.0 && lo.is_finite() { lo } else { 1e-3 };
            let hi = if hi > 0.0 && hi.is_finite() { hi } else { lo * 10.0 };
            let (l, h) = (lo.log10(), hi.log10());
            if h - l < 1e-12 {
                return (10f64.powf(l - 0.5), 10f64.powf(h + 0.5));
            }
            let m = 0.03 * (h - l);
            (10f64.powf(l - m), 10f64.powf(h + m))
        }
    }
}

/// A "nice" step (1, 2 or 5 × 10^k) giving about `target` intervals over `span`.
pub fn nice_step(span: f64, target: usize) -> f64 {
    let raw = span / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let norm = raw / mag;
    let nice = if norm < 1.5 {
        1.0
    } else if norm < 3.0 {
        2.0
    } else if norm < 7.0 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// The most ticks of a linear axis: more means the step is below the numbers' resolution.
const MAX_TICKS: usize = 1000;

/// The largest decade exponent of a log axis (the double range is 1e-324 to 1.8e308).
const MAX_DECADE: f64 = 330.0;

/// Ticks for the range `[lo, hi]`, in bounded time for any range (spans of hundreds of
/// decades, or below the resolution of the numbers, included).
pub fn ticks(lo: f64, hi: f64, scale: Scale, target: usize) -> Ticks {
    match scale {
        Scale::Linear => {
            let step = nice_step(hi - lo, target);
            let (first, last) = ((lo / step).ceil(), (hi / step).floor());
            // A span that is zero, not finite or below the numbers' resolution (1e-300 next to
            // 1) gives no usable step: the ends alone are labelled, never an endless count.
            if !(step > 0.0 && first.is_finite() && last.is_finite() && last - first <= MAX_TICKS as f64) {
                let values: Vec<f64> = [lo, hi].into_iter().filter(|v| v.is_finite()).collect();
                let labels = values.iter().map(|&v| format_number(v)).collect();
                return Ticks {
                    values,
                    labels,
                    minor: Vec::new(),
                };
            }
            let (first, last) = (first as i64, last as i64);
            let values: Vec<f64> = (first..=last).map(|k| k as f64 * step).collect();
            let labels = format_ticks(&values, step);
            Ticks {
                values,
                labels,
                minor: Vec::new(),
            }
        }
        Scale::Log => {
            // Ends outside the double range (0, a negative number, infinity) are clamped to it:
            // at most about 630 decades are visited.
            let clamp = |v: f64| {
                if v.is_finite() {
                    v.clamp(-MAX_DECADE, MAX_DECADE)
                } else if v > 0.0 {
                    MAX_DECADE
                } else {
                    -MAX_DECADE
                }
            };
            let (l, h) = (clamp(lo.log10()), clamp(hi.log10()));
            let (l, h) = (l.min(h), h.max(l));
            let decades = h - l;
            let every = if decades > 12.0 {
                (decades / 6.0).ceil() as i64
            } else {
                1
            };
            let first = l.ceil() as i64;
            let last = h.floor() as i64;
            let mut values = Vec::new();
            let mut labels = Vec::new();
            let mut minor = Vec::new();
            for k in (l.floor() as i64)..=(h.ceil() as i64) {
                if (first..=last).contains(&k) && k % every == 0 {
                    values.push(10f64.powi(k as i32));
                    labels.push(power_of_ten(k));
                }
                if every == 1 {
                    for m in 2..10 {
                        let v = m as f64 * 10f64.powi(k as i32);
                        if v >= lo && v <= hi {
                            minor.push(v);
                        }
                    }
                }
            }
            // Less than a decade or two: label some of the 2 and 5 multiples as well.
            if values.len() < 2 {
                for &v in &minor {
                    let m = (v / 10f64.powf(v.log10().floor())).round();
                    if m == 2.0 || m == 5.0 {
                        values.push(v);
                        labels.push(format_number(v));
                    }
                }
                let mut pairs: Vec<_> = values.into_iter().zip(labels).collect();
                pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
                let (v, lab): (Vec<f64>, Vec<String>) = pairs.into_iter().unzip();
                values = v;
                labels = lab;
            }
            Ticks {
                values,
                labels,
                minor,
            }
        }
    }
}

/// Labels for equally spaced ticks: as many decimals as the step needs, or a common
/// scientific form for very large or small values.
pub fn format_ticks(values: &[f64], step: f64) -> Vec<String> {
    let max = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // A degenerate step (a constant field's colour bar): each value on its own.
    if !(step > 0.0 && step.is_finite()) {
        return values.iter().map(|&v| format_number(v)).collect();
    }
    if max >= 1e5 || (max > 0.0 && max < 1e-3) {
        let decimals = ((max.log10().floor() - step.log10().floor()).max(0.0) as usize).min(6);
        return values
            .iter()
            .map(|&v| {
                if v == 0.0 {
                    "0".into()
                } else {
                    format!("{v:.decimals$e}")
                }
            })
            .collect();
    }
    let decimals = (-step.log10().floor()).clamp(0.0, 12.0) as usize;
    values
        .iter()
        .map(|&v| {
            let s = format!("{v:.decimals$}");
            if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
                "0".into()
            } else {
                s.replace('-', "−")
            }
        })
        .collect()
}

/// A single number, short.
pub fn format_number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.2e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_nice_and_inside() {
        let t = ticks(-1.37, 2.9, Scale::Linear, 6);
        assert_eq!(t.values.first().copied(), Some(-1.0));
        assert!(t.values.iter().all(|v| (-1.37..=2.9).contains(v)));
        assert_eq!(t.labels[0], "−1");
    }

    #[test]
    fn log_ticks_are_decades() {
        let t = ticks(0.009, 1100.0, Scale::Log, 6);
        assert_eq!(t.labels, vec!["10⁻²", "10⁻¹", "1", "10", "10²", "10³"]);
    }

    // A constant field's colour bar has a zero tick step: labels, not a formatting panic.
    #[test]
    fn any_range_gives_few_ticks_at_once() {
        for (lo, hi) in [
            (1.0, 1.0 + 1e-15),
            (1.0, 1.0),
            (0.0, 0.0),
            (-1e308, 1e308),
            (f64::MIN, f64::MAX),
            (1e-300, 1.0),
            (1.0, f64::INFINITY),
            (f64::NAN, 1.0),
        ] {
            let t = ticks(lo, hi, Scale::Linear, 6);
            assert!(t.values.len() <= MAX_TICKS + 1, "{lo} {hi}");
        }
        for (lo, hi) in [
            (0.0, 1.0),
            (1e-320, 1e300),
            (5e-324, f64::MAX),
            (-1.0, 1.0),
            (1.0, f64::INFINITY),
        ] {
            let t = ticks(lo, hi, Scale::Log, 6);
            assert!(
                t.values.len() <= 20 && t.minor.len() <= 9 * 700,
                "{lo} {hi}: {}",
                t.values.len()
            );
        }
    }

    #[test]
    fn a_degenerate_step_still_gives_labels() {
        assert_eq!(format_ticks(&[4.5, 4.5], 0.0), vec![format_number(4.5); 2]);
        assert_eq!(format_ticks(&[2.0], f64::NAN), vec![format_number(2.0)]);
        assert_eq!(format_ticks(&[1.0], 1e-300), vec!["1.000000000000"]);
    }
}
