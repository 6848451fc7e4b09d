//! Nonlinear least squares by Levenberg-Marquardt, with standard errors from the Jacobian.
//!
//! Minimises ½‖r(x)‖² for a residual vector r ∈ ℝᵐ of parameters x ∈ ℝⁿ (m ≥ n). The Jacobian
//! is supplied by the caller or taken by central differences. After convergence the covariance
//! of the estimate is s² (JᵀJ)⁻¹ with s² = ‖r‖²/(m − n), the usual estimate for independent
//! residuals of equal variance; its diagonal gives the standard errors. Fit positive quantities
//! through their logarithms to keep them positive.

use nalgebra::{DMatrix, DVector};

use crate::error::{Error, Result};

/// Options of [`levenberg_marquardt`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Maximum iterations (accepted or rejected steps).
    pub max_iterations: usize,
    /// Stop when the relative decrease of the cost in an accepted step is below this.
    pub cost_tol: f64,
    /// Stop when the step is below this relative to ‖x‖ (+ this, absolutely).
    pub step_tol: f64,
    /// Stop when the gradient ‖Jᵀr‖∞ is below this.
    pub gradient_tol: f64,
    /// Relative step of the central-difference Jacobian.
    pub fd_step: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            cost_tol: 1e-14,
            step_tol: 1e-12,
            gradient_tol: 1e-14,
            fd_step: 1e-6,
        }
    }
}

/// Result of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct LmSolution {
    /// Parameters at the minimum.
    pub x: Vec<f64>,
    /// ‖r‖₂.
    pub residual_norm: f64,
    /// Standard errors of the parameters, √diag(s²(JᵀJ)⁻¹); NaN where JᵀJ is singular.
    pub std_errors: Vec<f64>,
    /// Covariance s²(JᵀJ)⁻¹ (row-major n × n).
    pub covariance: Vec<f64>,
    /// Iterations used.
    pub iterations: usize,
}

/// A Jacobian callback: parameters to the m × n matrix ∂r/∂x.
pub type JacobianFn<'a> = dyn Fn(&[f64]) -> DMatrix<f64> + 'a;

/// Central-difference Jacobian of `f` at `x` (m × n).
pub fn jacobian_fd(f: &dyn Fn(&[f64]) -> Vec<f64>, x: &[f64], r0: &[f64], rel_step: f64) -> DMatrix<f64> {
    let m = r0.len();
    let n = x.len();
    let mut jac = DMatrix::zeros(m, n);
    let mut xp = x.to_vec();
    for j in 0..n {
        let h = rel_step * x[j].abs().max(1e-8);
        xp[j] = x[j] + h;
        let rp = f(&xp);
        xp[j] = x[j] - h;
        let rm = f(&xp);
        xp[j] = x[j];
        for i in 0..m {
            jac[(i, j)] = (rp[i] - rm[i]) / (2.0 * h);
        }
    }
    jac
}

/// JᵀJ of a tall m × n Jacobian from the dot products of its (contiguous) columns: the n(n+1)/2
/// products vectorise, where the general product does not.
fn gram(jac: &DMatrix<f64>) -> DMatrix<f64> {
    let n = jac.ncols();
    let mut g = DMatrix::zeros(n, n);
    for i in 0..n {
        for j in i..n {
            let v = jac.column(i).dot(&jac.column(j));
            g[(i, j)] = v;
            g[(j, i)] = v;
        }
    }
    g
}

/// A least-squares problem as [`minimize`] sees it: the cost ½‖r(x)‖² at trial points, and the
/// normal equations (JᵀJ, Jᵀr) at accepted ones. A problem whose rows give their derivatives in
/// closed form accumulates the normal equations in the same pass as the cost, and never forms
/// the m × n Jacobian.
pub trait LeastSquares {
    /// The number of residuals m (asked for after the first cost).
    fn rows(&self) -> usize;
    /// ½‖r(x)‖², or `None` where a residual is not finite.
    fn cost(&mut self, x: &[f64]) -> Option<f64>;
    /// JᵀJ (n × n) and Jᵀr at `x`, a point whose cost was the last one asked for.
    fn normal(&mut self, x: &[f64]) -> (DMatrix<f64>, DVector<f64>);
}

/// [`LeastSquares`] from a residual function and an optional Jacobian (else central
/// differences): the residuals of the last cost are kept for the Jacobian by differences.
struct Dense<'a> {
    residuals: &'a dyn Fn(&[f64]) -> Vec<f64>,
    jacobian: Option<&'a JacobianFn<'a>>,
    fd_step: f64,
    /// The residuals of the last cost.
    last: Vec<f64>,
}

impl LeastSquares for Dense<'_> {
    fn rows(&self) -> usize {
        self.last.len()
    }

    fn cost(&mut self, x: &[f64]) -> Option<f64> {
        self.last = (self.residuals)(x);
        self.last
            .iter()
            .all(|v| v.is_finite())
            .then(|| 0.5 * self.last.iter().map(|v| v * v).sum::<f64>())
    }

    fn normal(&mut self, x: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
        let jac = match self.jacobian {
            Some(j) => j(x),
            None => jacobian_fd(self.residuals, x, &self.last, self.fd_step),
        };
        let rv = DVector::from_column_slice(&self.last);
        let g = DVector::from_fn(jac.ncols(), |i, _| jac.column(i).dot(&rv));
        (gram(&jac), g)
    }
}

/// Minimise ½‖r(x)‖² from `x0` by Levenberg-Marquardt (Marquardt's diagonal scaling, adaptive
/// damping). `jacobian`, if given, returns the m × n matrix ∂r/∂x.
///
/// # Errors
/// [`Error::InvalidParameter`] if there are fewer residuals than parameters or the residuals
/// are not finite at `x0`; [`Error::NoConvergence`] if no tolerance is met within the
/// iteration limit.
pub fn levenberg_marquardt(
    residuals: &dyn Fn(&[f64]) -> Vec<f64>,
    jacobian: Option<&JacobianFn<'_>>,
    x0: &[f64],
    opts: LmOptions,
) -> Result<LmSolution> {
    let mut problem = Dense {
        residuals,
        jacobian,
        fd_step: opts.fd_step,
        last: Vec::new(),
    };
    minimize(&mut problem, x0, opts)
}

/// Minimise a [`LeastSquares`] problem from `x0` by Levenberg-Marquardt (Marquardt's diagonal
/// scaling, adaptive damping). Converged when the gradient vanishes, when an accepted step
/// lowers the cost by less than `cost_tol` relative or moves x by less than `step_tol`, or when
/// the undamped (Gauss-Newton) model predicts a decrease below `cost_tol` relative at an
/// accepted point: that last step would only confirm the minimum, and is not taken.
///
/// # Errors
/// As [`levenberg_marquardt`].
pub fn minimize(problem: &mut dyn LeastSquares, x0: &[f64], opts: LmOptions) -> Result<LmSolution> {
    let n = x0.len();
    let mut x = x0.to_vec();
    let start = problem.cost(&x);
    let m = problem.rows();
    if m < n {
        return Err(Error::invalid(
            "residuals",
            m,
            format!("need at least {n} residuals for {n} parameters"),
        ));
    }
    let Some(mut c) = start else {
        return Err(Error::invalid(
            "x0",
            format!("{x0:?}"),
            "residuals are not finite at the start",
        ));
    };
    let (mut jtj, mut g) = problem.normal(&x);
    let mut fresh = true;
    let mut lambda = 1e-3;
    let mut converged = false;
    let mut iterations = 0;
    while iterations < opts.max_iterations {
        iterations += 1;
        if g.amax() <= opts.gradient_tol * (1.0 + c) {
            converged = true;
            break;
        }
        if fresh {
            fresh = false;
            // ½gᵀ(JᵀJ)⁻¹g: the decrease the Gauss-Newton step would bring.
            let predicted = jtj.clone().cholesky().map(|ch| 0.5 * g.dot(&ch.solve(&g)));
            if predicted.is_some_and(|p| p >= 0.0 && p < opts.cost_tol * c) {
                converged = true;
                break;
            }
        }
        let mut a = jtj.clone();
        for i in 0..n {
            a[(i, i)] += lambda * jtj[(i, i)].max(1e-300);
        }
        let Some(step) = a.cholesky().map(|ch| ch.solve(&(-&g))) else {
            lambda *= 10.0;
            continue;
        };
        let x_new: Vec<f64> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
        let c_new = problem.cost(&x_new).unwrap_or(f64::INFINITY);
        if c_new < c {
            let rel_decrease = (c - c_new) / c.max(f64::MIN_POSITIVE);
            let step_small = step
                .iter()
                .zip(&x)
                .all(|(s, xi)| s.abs() <= opts.step_tol * (xi.abs() + opts.step_tol));
            x = x_new;
            c = c_new;
            (jtj, g) = problem.normal(&x);
            fresh = true;
            lambda = (lambda / 3.0).max(1e-12);
            if rel_decrease < opts.cost_tol || step_small {
                converged = true;
                break;
            }
        } else {
            lambda *= 4.0;
            if lambda > 1e16 {
                // No descent possible at machine precision: we are at the minimum.
                converged = true;
                break;
            }
        }
    }
    if !converged {
        return Err(Error::NoConvergence {
            method: "levenberg-marquardt",
            iterations,
            residual: (2.0 * c).sqrt(),
        });
    }
    let dof = (m - n).max(1) as f64;
    let s2 = 2.0 * c / dof;
    let (covariance, std_errors) = match jtj.try_inverse() {
        Some(inv) => {
            let cov = inv * s2;
            let se = (0..n).map(|i| cov[(i, i)].max(0.0).sqrt()).collect();
            (cov.transpose().as_slice().to_vec(), se)
        }
        None => (vec![f64::NAN; n * n], vec![f64::NAN; n]),
    };
    Ok(LmSolution {
        x,
        residual_norm: (2.0 * c).sqrt(),
        std_errors,
        covariance,
        iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fit y = A exp(−k t) to noisy data: the estimate is within a few standard errors of the
    /// truth, and the standard errors match the scatter of the noise.
    #[test]
    fn exponential_fit_recovers_parameters_within_their_errors() {
        let (a_true, k_true) = (2.5, 1.3);
        let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.02).collect();
        // Deterministic pseudo-noise of standard deviation about 0.01.
        let noise: Vec<f64> = (0..200)
            .map(|i| 0.01 * 1.732 * (((i * 7919) % 1000) as f64 / 500.0 - 1.0))
            .collect();
        let y: Vec<f64> = t
            .iter()
            .zip(&noise)
            .map(|(t, e)| a_true * (-k_true * t).exp() + e)
            .collect();
        let res = |p: &[f64]| -> Vec<f64> {
            t.iter()
                .zip(&y)
                .map(|(t, y)| p[0] * (-p[1] * t).exp() - y)
                .collect()
        };
        let sol = levenberg_marquardt(&res, None, &[1.0, 0.5], LmOptions::default()).unwrap();
        assert!((sol.x[0] - a_true).abs() < 4.0 * sol.std_errors[0], "{sol:?}");
        assert!((sol.x[1] - k_true).abs() < 4.0 * sol.std_errors[1], "{sol:?}");
        assert!(sol.std_errors[0] > 1e-4 && sol.std_errors[0] < 1e-2);
        let rms = sol.residual_norm / (t.len() as f64).sqrt();
        assert!((rms - 0.01).abs() < 0.002, "rms {rms}");
    }

    #[test]
    fn too_few_residuals_is_an_error() {
        let res = |p: &[f64]| vec![p[0]];
        assert!(levenberg_marquardt(&res, None, &[1.0, 2.0], LmOptions::default()).is_err());
    }
}
