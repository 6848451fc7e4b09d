//! Cubic interpolating splines (clamped and periodic) in Hermite form, with exact first and
//! second derivatives and the exact extreme slopes, plus the tridiagonal solvers they need.
//!
//! Used for tabulated data that must be differentiated (a sampled substrate profile): the spline
//! is C² at interior knots, reproduces straight lines exactly when the end slopes are exact, and
//! its slope is a quadratic on each interval, so the extreme slopes are found in closed form.

use crate::error::{Error, Result};

/// Solve a tridiagonal system by the Thomas algorithm: `lower[i] x[i-1] + diag[i] x[i] +
/// upper[i] x[i+1] = rhs[i]` (`lower[0]` and `upper[n-1]` are ignored).
///
/// # Errors
/// [`Error::Unresolvable`] on a zero pivot (not reached for diagonally dominant systems).
///
/// # Panics
/// If the slices differ in length.
pub fn tridiagonal_solve(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &[f64]) -> Result<Vec<f64>> {
    let n = diag.len();
    assert!(
        lower.len() == n && upper.len() == n && rhs.len() == n,
        "tridiagonal slices must have equal lengths"
    );
    let mut c = vec![0.0; n];
    let mut d = vec![0.0; n];
    for i in 0..n {
        let l = if i == 0 { 0.0 } else { lower[i] };
        let denom = diag[i] - l * if i == 0 { 0.0 } else { c[i - 1] };
        if denom == 0.0 || !denom.is_finite() {
            return Err(Error::Unresolvable {
                model: "tridiagonal_solve",
                reason: format!("zero pivot at row {i}"),
            });
        }
        c[i] = upper[i] / denom;
        d[i] = (rhs[i] - l * if i == 0 { 0.0 } else { d[i - 1] }) / denom;
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        x[i] = d[i] - if i + 1 < n { c[i] * x[i + 1] } else { 0.0 };
    }
    Ok(x)
}

/// Solve a cyclic tridiagonal system (corner entries `lower[0]` at (0, n−1) and `upper[n−1]` at
/// (n−1, 0)) by the Sherman-Morrison formula around [`tridiagonal_solve`]. Needs n ≥ 3.
///
/// # Errors
/// As [`tridiagonal_solve`].
///
/// # Panics
/// If the slices differ in length or n < 3.
pub fn cyclic_tridiagonal_solve(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &[f64]) -> Result<Vec<f64>> {
    let n = diag.len();
    assert!(n >= 3, "cyclic tridiagonal system needs n >= 3");
    let (alpha, beta) = (upper[n - 1], lower[0]);
    let gamma = -diag[0];
    let mut dd = diag.to_vec();
    dd[0] -= gamma;
    dd[n - 1] -= alpha * beta / gamma;
    let x = tridiagonal_solve(lower, &dd, upper, rhs)?;
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = alpha;
    let z = tridiagonal_solve(lower, &dd, upper, &u)?;
    let fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
    Ok(x.iter().zip(&z).map(|(xi, zi)| xi - fact * zi).collect())
}

/// A cubic spline in Hermite form: knot abscissae, values and slopes.
#[derive(Debug, Clone, PartialEq)]
pub struct CubicSpline {
    x: Vec<f64>,
    y: Vec<f64>,
    slope: Vec<f64>,
}

impl CubicSpline {
    /// The C² spline through `(x, y)` with the end slopes given (clamped). Two knots give the
    /// cubic Hermite interpolant of the end slopes.
    ///
    /// # Errors
    /// [`Error::Unresolvable`] for fewer than two knots or abscissae not strictly increasing.
    pub fn clamped(x: &[f64], y: &[f64], slope_start: f64, slope_end: f64) -> Result<Self> {
        check_knots(x, y, 2)?;
        let n = x.len();
        let mut slope = vec![0.0; n];
        slope[0] = slope_start;
        slope[n - 1] = slope_end;
        if n > 2 {
            // Interior C² conditions in slope form:
            // h_i s_{i-1} + 2(h_{i-1} + h_i) s_i + h_{i-1} s_{i+1} = 3(h_i δ_{i-1} + h_{i-1} δ_i).
            let m = n - 2;
            let (mut lo, mut di, mut up, mut rhs) = (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
            for k in 0..m {
                let i = k + 1;
                let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
                let (d0, d1) = ((y[i] - y[i - 1]) / h0, (y[i + 1] - y[i]) / h1);
                lo[k] = h1;
                di[k] = 2.0 * (h0 + h1);
                up[k] = h0;
                rhs[k] = 3.0 * (h1 * d0 + h0 * d1);
            }
            rhs[0] -= lo[0] * slope_start;
            rhs[m - 1] -= up[m - 1] * slope_end;
            let s = tridiagonal_solve(&lo, &di, &up, &rhs)?;
            slope[1..n - 1].copy_from_slice(&s);
        }
        Ok(Self {
            x: x.to_vec(),
            y: y.to_vec(),
            slope,
        })
    }

    /// The periodic C² spline through `(x, y)`, where the last knot closes the period
    /// (`y[n−1]` is taken equal to `y[0]`, period `x[n−1] − x[0]`). Needs at least 4 knots
    /// (3 distinct points per period).
    ///
    /// # Errors
    /// [`Error::Unresolvable`] for too few knots or abscissae not strictly increasing.
    pub fn periodic(x: &[f64], y: &[f64]) -> Result<Self> {
        check_knots(x, y, 4)?;
        let n = x.len() - 1; // distinct knots per period
        let h = |i: usize| x[(i % n) + 1] - x[i % n];
        let delta = |i: usize| {
            let i = i % n;
            let y1 = if i + 1 == n { y[0] } else { y[i + 1] };
            (y1 - y[i]) / h(i)
        };
        let (mut lo, mut di, mut up, mut rhs) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            let prev = (i + n - 1) % n;
            let (h0, h1) = (h(prev), h(i));
            lo[i] = h1;
            di[i] = 2.0 * (h0 + h1);
            up[i] = h0;
            rhs[i] = 3.0 * (h1 * delta(prev) + h0 * delta(i));
        }
        let s = cyclic_tridiagonal_solve(&lo, &di, &up, &rhs)?;
        let mut slope = s.clone();
        slope.push(s[0]);
        let mut yy = y.to_vec();
        yy[n] = y[0];
        Ok(Self {
            x: x.to_vec(),
            y: yy,
            slope,
        })
    }

    /// Knot abscissae.
    pub fn knots(&self) -> &[f64] {
        &self.x
    }

    /// Interval index containing `t` (clamped to the ends).
    fn interval(&self, t: f64) -> usize {
        let n = self.x.len();
        match self.x.partition_point(|&v| v <= t) {
            0 => 0,
            k if k >= n => n - 2,
            k => k - 1,
        }
    }

    /// Hermite coefficients on interval i: p(u) = a + b u + c u² + d u³ with u = t − x_i.
    fn coefficients(&self, i: usize) -> (f64, f64, f64, f64) {
        let h = self.x[i + 1] - self.x[i];
        let delta = (self.y[i + 1] - self.y[i]) / h;
        let (s0, s1) = (self.slope[i], self.slope[i + 1]);
        let c = (3.0 * delta - 2.0 * s0 - s1) / h;
        let d = (s0 + s1 - 2.0 * delta) / (h * h);
        (self.y[i], s0, c, d)
    }

    /// Value, first and second derivative at `t` (the end cubics extend beyond the knots).
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        let i = self.interval(t);
        let (a, b, c, d) = self.coefficients(i);
        let u = t - self.x[i];
        (
            a + u * (b + u * (c + u * d)),
            b + u * (2.0 * c + 3.0 * u * d),
            2.0 * c + 6.0 * u * d,
        )
    }

    /// Smallest and largest value over the knot range, exact (at knots or where the quadratic
    /// derivative vanishes inside an interval).
    pub fn value_range(&self) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in 0..self.x.len() - 1 {
            let (a, b, c, d) = self.coefficients(i);
            let h = self.x[i + 1] - self.x[i];
            let mut consider = |u: f64| {
                if (0.0..=h).contains(&u) {
                    let v = a + u * (b + u * (c + u * d));
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            };
            consider(0.0);
            consider(h);
            // b + 2c u + 3d u² = 0.
            if d == 0.0 {
                if c != 0.0 {
                    consider(-b / (2.0 * c));
                }
            } else {
                let disc = c * c - 3.0 * b * d;
                if disc >= 0.0 {
                    let q = -(c + c.signum() * disc.sqrt());
                    if q != 0.0 {
                        consider(q / (3.0 * d));
                        consider(b / q);
                    } else {
                        consider(0.0);
                    }
                }
            }
        }
        (lo, hi)
    }

    /// Smallest and largest first derivative over the knot range, exact (the derivative is a
    /// quadratic on each interval).
    pub fn slope_range(&self) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in 0..self.x.len() - 1 {
            let (_, b, c, d) = self.coefficients(i);
            let h = self.x[i + 1] - self.x[i];
            let mut consider = |u: f64| {
                let s = b + u * (2.0 * c + 3.0 * u * d);
                lo = lo.min(s);
                hi = hi.max(s);
            };
            consider(0.0);
            consider(h);
            if d != 0.0 {
                let u = -c / (3.0 * d);
                if u > 0.0 && u < h {
                    consider(u);
                }
            }
        }
        (lo, hi)
    }

    /// Abscissae in the open knot range where the second derivative changes sign (inflection
    /// points), exact (the second derivative is linear on each interval), in increasing order.
    pub fn inflections(&self) -> Vec<f64> {
        let n = self.x.len();
        let second = |i: usize, u: f64| {
            let (_, _, c, d) = self.coefficients(i);
            2.0 * c + 6.0 * u * d
        };
        let mut out: Vec<f64> = Vec::new();
        let mut mid_sign = Vec::with_capacity(n - 1);
        let mut interior = Vec::with_capacity(n - 1);
        for i in 0..n - 1 {
            let h = self.x[i + 1] - self.x[i];
            let (s0, s1) = (second(i, 0.0), second(i, h));
            interior.push(s0 * s1 < 0.0);
            if s0 * s1 < 0.0 {
                out.push(self.x[i] + h * s0 / (s0 - s1));
            }
            mid_sign.push(second(i, 0.5 * h).signum() * f64::from(second(i, 0.5 * h) != 0.0));
        }
        // A zero exactly at an interior knot: no interior root on either side, yet the sign
        // differs between the neighbouring intervals (the second derivative is linear on each).
        for k in 1..n - 1 {
            let (a, b) = (mid_sign[k - 1], mid_sign[k]);
            if !interior[k - 1] && !interior[k] && a != 0.0 && b != 0.0 && a != b {
                out.push(self.x[k]);
            }
        }
        out.sort_by(f64::total_cmp);
        out
    }
}

fn check_knots(x: &[f64], y: &[f64], min: usize) -> Result<()> {
    if x.len() != y.len() || x.len() < min {
        return Err(Error::Unresolvable {
            model: "cubic spline",
            reason: format!(
                "needs at least {min} knots with one value each, got {} and {}",
                x.len(),
                y.len()
            ),
        });
    }
    if x.windows(2).any(|w| w[1] <= w[0] || !w[1].is_finite()) || y.iter().any(|v| !v.is_finite()) {
        return Err(Error::Unresolvable {
            model: "cubic spline",
            reason: "knots must be finite and strictly increasing".into(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cyclic_solve_matches_a_dense_check() {
        let n = 6;
        let lo = vec![1.0, 0.5, 1.0, 0.3, 1.0, 0.7];
        let di = vec![4.0, 5.0, 4.5, 4.0, 6.0, 5.0];
        let up = vec![0.9, 1.0, 0.2, 1.0, 0.4, 1.1];
        let rhs = vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let x = cyclic_tridiagonal_solve(&lo, &di, &up, &rhs).unwrap();
        for i in 0..n {
            let r = lo[i] * x[(i + n - 1) % n] + di[i] * x[i] + up[i] * x[(i + 1) % n];
            assert!((r - rhs[i]).abs() < 1e-12, "row {i}: {r}");
        }
    }

    #[test]
    fn clamped_spline_reproduces_a_line_and_a_cubic() {
        let x = [0.0, 0.3, 0.5, 1.2, 2.0];
        let line: Vec<f64> = x.iter().map(|t| 2.0 - 3.0 * t).collect();
        let s = CubicSpline::clamped(&x, &line, -3.0, -3.0).unwrap();
        let (v, d, dd) = s.eval(0.77);
        assert!((v - (2.0 - 3.0 * 0.77)).abs() < 1e-14 && (d + 3.0).abs() < 1e-13 && dd.abs() < 1e-12);
        let cubic: Vec<f64> = x.iter().map(|t| t * t * t - t).collect();
        let s = CubicSpline::clamped(&x, &cubic, -1.0, 3.0 * 4.0 - 1.0).unwrap();
        let (v, d, dd) = s.eval(1.5);
        assert!((v - (3.375 - 1.5)).abs() < 1e-12);
        assert!((d - (3.0 * 2.25 - 1.0)).abs() < 1e-12 && (dd - 9.0).abs() < 1e-11);
    }

    #[test]
    fn periodic_spline_of_a_sine_converges_at_fourth_order() {
        let err = |n: usize| {
            let x: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
            let y: Vec<f64> = x.iter().map(|t| (2.0 * std::f64::consts::PI * t).sin()).collect();
            let s = CubicSpline::periodic(&x, &y).unwrap();
            (0..1000)
                .map(|k| {
                    let t = (k as f64 + 0.5) / 1000.0;
                    (s.eval(t).0 - (2.0 * std::f64::consts::PI * t).sin()).abs()
                })
                .fold(0.0, f64::max)
        };
        let (e1, e2) = (err(20), err(40));
        let order = (e1 / e2).log2();
        assert!(order > 3.8 && order < 4.2, "order {order}");
        let x: Vec<f64> = (0..=40).map(|i| i as f64 / 40.0).collect();
        let y: Vec<f64> = x.iter().map(|t| (2.0 * std::f64::consts::PI * t).sin()).collect();
        let s = CubicSpline::periodic(&x, &y).unwrap();
        let (lo, hi) = s.slope_range();
        let exact = 2.0 * std::f64::consts::PI;
        assert!((lo + exact).abs() < 1e-3 * exact && (hi - exact).abs() < 1e-3 * exact);
        // sin″ vanishes at 0.5 (a knot) and at the period end (rounding puts it just inside).
        let infl = s.inflections();
        assert!(!infl.is_empty() && infl.len() <= 2, "{infl:?}");
        assert!((infl[0] - 0.5).abs() < 1e-9, "{infl:?}");
        assert!(infl.iter().skip(1).all(|r| (r - 1.0).abs() < 1e-9), "{infl:?}");
    }
}
