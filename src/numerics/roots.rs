//! Scalar root finding: bracketing (Brent's method) and bracket expansion.

use crate::error::{Error, Result};

/// Find a root of `f` on `[lo, hi]` by Brent's method (inverse quadratic interpolation with
/// bisection safeguard). `f(lo)` and `f(hi)` must differ in sign (or one be zero).
///
/// Converges when the bracket is narrower than `xtol` (absolute) plus 4 ε |x|.
///
/// # Errors
/// [`Error::NoBracket`] without a sign change, [`Error::NoConvergence`] after 200 iterations
/// (not reached for continuous `f`).
pub fn brent(f: impl Fn(f64) -> f64, lo: f64, hi: f64, xtol: f64) -> Result<f64> {
    let (mut a, mut b) = (lo, hi);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.is_nan() || fb.is_nan() || fa.signum() == fb.signum() {
        return Err(Error::NoBracket { lo, hi });
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qa = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
        if fb.is_nan() {
            return Err(Error::NoConvergence {
                method: "brent",
                iterations: 0,
                residual: f64::NAN,
            });
        }
    }
    Err(Error::NoConvergence {
        method: "brent",
        iterations: 200,
        residual: fb.abs(),
    })
}

/// Grow `[lo, hi]` geometrically upward (keeping `lo`) until `f` changes sign, at most
/// `max_doublings` times; returns the bracket.
///
/// # Errors
/// [`Error::NoBracket`] if no sign change was found.
pub fn expand_upward(
    f: impl Fn(f64) -> f64,
    lo: f64,
    mut hi: f64,
    max_doublings: usize,
) -> Result<(f64, f64)> {
    let flo = f(lo);
    if flo == 0.0 {
        return Ok((lo, lo));
    }
    let mut prev = lo;
    for _ in 0..=max_doublings {
        let fhi = f(hi);
        if flo.signum() != fhi.signum() || fhi == 0.0 {
            return Ok((prev, hi));
        }
        prev = hi;
        hi = lo + 2.0 * (hi - lo);
    }
    Err(Error::NoBracket { lo, hi })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_cube_root_of_two_to_machine_precision() {
        let r = brent(|x| x * x * x - 2.0, 0.0, 2.0, 1e-15).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-14);
        assert!(matches!(
            brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12),
            Err(Error::NoBracket { .. })
        ));
    }

    #[test]
    fn expansion_finds_a_far_root() {
        let (a, b) = expand_upward(|x| x - 1000.0, 0.0, 1.0, 20).unwrap();
        assert!(a <= 1000.0 && b >= 1000.0);
    }
}
