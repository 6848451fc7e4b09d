//! Quadrature: adaptive Gauss-Kronrod (7-15) with a global error estimate, fixed-order
//! Gauss-Legendre rules, and the trapezoid rule for tabulated data.

use crate::error::{Error, Result};

/// Kronrod abscissae of the 15-point rule on [-1, 1] (non-negative half).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights.
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights of the embedded 7-point rule (at XGK[1], XGK[3], XGK[5], XGK[7]).
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// One Gauss-Kronrod 7-15 panel: (integral estimate, error estimate).
fn gk15(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[7] * fc;
    let mut g = WG[3] * fc;
    for j in 0..7 {
        let dx = h * XGK[j];
        let s = f(c - dx) + f(c + dx);
        k += WGK[j] * s;
        if j % 2 == 1 {
            g += WG[j / 2] * s;
        }
    }
    (k * h, ((k - g) * h).abs())
}

/// Result of an adaptive integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integral {
    /// The integral.
    pub value: f64,
    /// Estimated absolute error.
    pub error: f64,
    /// Function evaluations used.
    pub evaluations: usize,
}

/// Integrate `f` over `[a, b]` adaptively to `max(abs_tol, rel_tol |I|)`, bisecting the panel
/// with the largest error estimate first (global adaptivity, as QUADPACK's QAG).
///
/// # Errors
/// [`Error::NoConvergence`] when `max_panels` panels do not reach the tolerance (the
/// estimate is then in the error's residual), or when `f` returns NaN.
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, abs_tol: f64, rel_tol: f64) -> Result<Integral> {
    integrate_with_limit(f, a, b, abs_tol, rel_tol, 2000)
}

/// As [`integrate`] with an explicit panel limit.
///
/// # Errors
/// As [`integrate`].
pub fn integrate_with_limit(
    f: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    abs_tol: f64,
    rel_tol: f64,
    max_panels: usize,
) -> Result<Integral> {
    if a == b {
        return Ok(Integral {
            value: 0.0,
            error: 0.0,
            evaluations: 0,
        });
    }
    let mut panels: Vec<(f64, f64, f64, f64)> = Vec::new();
    let (v, e) = gk15(&f, a, b);
    panels.push((a, b, v, e));
    let mut evaluations = 15;
    loop {
        let total: f64 = panels.iter().map(|p| p.2).sum();
        let err: f64 = panels.iter().map(|p| p.3).sum();
        if total.is_nan() {
            return Err(Error::NoConvergence {
                method: "gauss-kronrod",
                iterations: panels.len(),
                residual: f64::NAN,
            });
        }
        if err <= abs_tol.max(rel_tol * total.abs()) {
            return Ok(Integral {
                value: total,
                error: err,
                evaluations,
            });
        }
        if panels.len() >= max_panels {
            return Err(Error::NoConvergence {
                method: "gauss-kronrod",
                iterations: panels.len(),
                residual: err,
            });
        }
        let k = panels
            .iter()
            .enumerate()
            .max_by(|x, y| x.1.3.total_cmp(&y.1.3))
            .map(|(k, _)| k)
            .expect("at least one panel");
        let (pa, pb, _, _) = panels.swap_remove(k);
        let m = 0.5 * (pa + pb);
        if m <= pa.min(pb) || m >= pa.max(pb) {
            // The panel cannot be split further in floating point.
            return Err(Error::NoConvergence {
                method: "gauss-kronrod",
                iterations: panels.len(),
                residual: err,
            });
        }
        let (v1, e1) = gk15(&f, pa, m);
        let (v2, e2) = gk15(&f, m, pb);
        evaluations += 30;
        panels.push((pa, m, v1, e1));
        panels.push((m, pb, v2, e2));
    }
}

/// ∫_a^∞ f adaptively: [a, a + scale] directly, the tail through x = a + scale/t, t ∈ (0, 1]
/// (dx = scale/t² dt). `scale` should be the length over which f changes; f must decay faster
/// than 1/x.
///
/// # Errors
/// As [`integrate`], and [`Error::InvalidParameter`] when `scale` is not positive and finite.
pub fn integrate_to_infinity(
    f: impl Fn(f64) -> f64,
    a: f64,
    scale: f64,
    abs_tol: f64,
    rel_tol: f64,
) -> Result<Integral> {
    if !(scale > 0.0 && scale.is_finite()) {
        return Err(Error::invalid("scale", scale, "must be positive and finite"));
    }
    let head = integrate(&f, a, a + scale, 0.5 * abs_tol, rel_tol)?;
    let tail = integrate(
        |t: f64| {
            if t <= 0.0 {
                0.0
            } else {
                f(a + scale / t) * scale / (t * t)
            }
        },
        0.0,
        1.0,
        0.5 * abs_tol,
        rel_tol,
    )?;
    Ok(Integral {
        value: head.value + tail.value,
        error: head.error + tail.error,
        evaluations: head.evaluations + tail.evaluations,
    })
}

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1], by Newton's method on the
/// Legendre polynomial from Chebyshev-like initial guesses (accurate to a few ulps for n ≤ 200).
///
/// # Panics
/// If `n == 0`.
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n > 0, "a Gauss rule needs at least one point");
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pn1 = if n == 1 { 1.0 } else { p0 };
            dp = nf * (z * pn - pn1) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        if n == 1 {
            dp = 1.0;
            z = 0.0;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n == 1 {
        w[0] = 2.0;
    }
    (x, w)
}

/// A fixed Gauss-Legendre rule, mapped to any interval.
#[derive(Debug, Clone)]
pub struct GaussLegendre {
    x: Vec<f64>,
    w: Vec<f64>,
}

impl GaussLegendre {
    /// The n-point rule.
    ///
    /// # Panics
    /// If `n == 0`.
    pub fn new(n: usize) -> Self {
        let (x, w) = gauss_legendre(n);
        Self { x, w }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether the rule is empty (never: `new` requires n > 0).
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// ∫_a^b f.
    pub fn integrate(&self, f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let c = 0.5 * (a + b);
        let h = 0.5 * (b - a);
        h * self
            .x
            .iter()
            .zip(&self.w)
            .map(|(x, w)| w * f(c + h * x))
            .sum::<f64>()
    }
}

/// Trapezoid rule over tabulated points (x need not be uniform; it may decrease).
pub fn trapezoid(points: &[(f64, f64)]) -> f64 {
    points
        .windows(2)
        .map(|p| 0.5 * (p[1].0 - p[0].0) * (p[0].1 + p[1].1))
        .sum()
}

/// Signed area of a closed polygon (positive when counter-clockwise), the shoelace formula.
pub fn polygon_area(points: &[(f64, f64)]) -> f64 {
    let n = points.len();
    if n < 3 {
        return 0.0;
    }
    0.5 * (0..n)
        .map(|i| {
            let (x0, y0) = points[i];
            let (x1, y1) = points[(i + 1) % n];
            x0 * y1 - x1 * y0
        })
        .sum::<f64>()
}

/// Radon's 7-point rule on a triangle, exact for polynomials of degree 5: barycentric
/// coordinates (λ₁, λ₂, λ₃) of each point and its weight as a fraction of the triangle's area
/// (the weights sum to one).
pub fn triangle_rule_7() -> [([f64; 3], f64); 7] {
    let s15 = 15f64.sqrt();
    let a = (6.0 - s15) / 21.0;
    let b = (6.0 + s15) / 21.0;
    let wa = (155.0 - s15) / 1200.0;
    let wb = (155.0 + s15) / 1200.0;
    let third = 1.0 / 3.0;
    [
        ([third, third, third], 9.0 / 40.0),
        ([a, a, 1.0 - 2.0 * a], wa),
        ([a, 1.0 - 2.0 * a, a], wa),
        ([1.0 - 2.0 * a, a, a], wa),
        ([b, b, 1.0 - 2.0 * b], wb),
        ([b, 1.0 - 2.0 * b, b], wb),
        ([1.0 - 2.0 * b, b, b], wb),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adaptive_rule_handles_an_endpoint_singularity() {
        // ∫_0^1 x^{-1/2} dx = 2.
        let r = integrate(|x| 1.0 / x.sqrt(), 0.0, 1.0, 1e-12, 1e-12).unwrap();
        assert!((r.value - 2.0).abs() < 1e-10, "{r:?}");
    }

    #[test]
    fn gauss_legendre_is_exact_for_polynomials_of_degree_2n_minus_1() {
        for n in [1, 2, 5, 20, 64] {
            let g = GaussLegendre::new(n);
            let deg = 2 * n - 1;
            let exact = if deg % 2 == 1 {
                0.0
            } else {
                2.0 / (deg as f64 + 1.0)
            };
            let got = g.integrate(|x| x.powi(deg as i32) + 1.0, -1.0, 1.0);
            assert!((got - exact - 2.0).abs() < 1e-13, "n={n}: {got}");
        }
        let g = GaussLegendre::new(30);
        let got = g.integrate(f64::exp, 0.0, 1.0);
        assert!((got - (1f64.exp() - 1.0)).abs() < 1e-14);
    }

    #[test]
    fn semi_infinite_integral_of_a_lorentzian_and_an_exponential() {
        let i = integrate_to_infinity(|x| 1.0 / (1.0 + x * x), 0.0, 1.0, 0.0, 1e-12).unwrap();
        assert!((i.value - std::f64::consts::FRAC_PI_2).abs() < 1e-11);
        let e = integrate_to_infinity(|x| (-x).exp(), 2.0, 1.0, 0.0, 1e-12).unwrap();
        assert!((e.value - (-2.0f64).exp()).abs() < 1e-13);
    }

    #[test]
    fn shoelace_of_unit_square() {
        let sq = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        assert!((polygon_area(&sq) - 1.0).abs() < 1e-15);
    }

    /// The 7-point rule integrates every monomial x^i y^j of degree ≤ 5 over the unit triangle
    /// exactly: ∫ x^i y^j = i! j!/(i + j + 2)!.
    #[test]
    fn triangle_rule_is_exact_to_degree_five() {
        let fact = |n: usize| (1..=n).map(|k| k as f64).product::<f64>();
        for i in 0..=5 {
            for j in 0..=(5 - i) {
                let exact = fact(i) * fact(j) / fact(i + j + 2);
                let quad: f64 = triangle_rule_7()
                    .iter()
                    .map(|(l, w)| 0.5 * w * l[1].powi(i as i32) * l[2].powi(j as i32))
                    .sum();
                assert!((quad - exact).abs() < 1e-15, "x^{i} y^{j}: {quad} vs {exact}");
            }
        }
    }
}
