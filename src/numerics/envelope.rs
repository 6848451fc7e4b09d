//! Small sparse symmetric matrices in envelope (skyline) storage, with a Cholesky
//! factorisation that keeps its fill inside the envelope.
//!
//! The stable Newton solver tests and relaxes small groups of unknowns on their own (a patch of
//! a spring array around a fold, [`crate::numerics::newton`]): principal submatrices of a
//! sparse Hessian, a few dozen to a few hundred unknowns, thousands of times per load step.
//! Taken in the order of the unknowns (row by row of the array), row r of such a block reaches
//! back at most about one grid row, so a factorisation within the envelope costs
//! O(Σ_r w_r²) (w_r the row's width) where a dense one costs O(m³/3): for a 16 x 16 patch
//! some 70 times less.

use super::pcg::{SymmetricPattern, dot};

/// A symmetric m x m matrix stored by rows from each row's first nonzero column to the
/// diagonal (the lower envelope).
#[derive(Debug, Clone)]
pub struct Envelope {
    /// First stored column of each row.
    first: Vec<usize>,
    /// Start of each row in `values`, length m + 1; row r holds columns first[r]..=r.
    start: Vec<usize>,
    values: Vec<f64>,
}

impl Envelope {
    /// The principal submatrix on the sorted unknowns `set` of the matrix with sparsity
    /// `pattern` and values in row order `row_values` ([`SymmetricPattern::gather`]).
    pub fn principal_block(pattern: &SymmetricPattern, row_values: &[f64], set: &[usize]) -> Self {
        let m = set.len();
        let local = |c: usize| set.binary_search(&c).ok();
        let mut first = Vec::with_capacity(m);
        let mut start = Vec::with_capacity(m + 1);
        start.push(0);
        for (r, &i) in set.iter().enumerate() {
            let f = pattern
                .row(row_values, i)
                .filter_map(|(c, _)| local(c))
                .fold(r, usize::min);
            first.push(f);
            start.push(start[r] + r + 1 - f);
        }
        let mut values = vec![0.0; start[m]];
        for (r, &i) in set.iter().enumerate() {
            for (c, v) in pattern.row(row_values, i) {
                if let Some(q) = local(c).filter(|&q| q <= r) {
                    values[start[r] + q - first[r]] += v;
                }
            }
        }
        Envelope { first, start, values }
    }

    /// Order m.
    pub fn order(&self) -> usize {
        self.first.len()
    }

    /// Entry (r, c) for c ≤ r (zero outside the envelope).
    pub fn get(&self, r: usize, c: usize) -> f64 {
        if c < self.first[r] {
            0.0
        } else {
            self.values[self.start[r] + c - self.first[r]]
        }
    }

    /// Whether every stored entry is finite.
    pub fn all_finite(&self) -> bool {
        self.values.iter().all(|v| v.is_finite())
    }

    /// Set the diagonal entry of row r.
    pub fn set_diagonal(&mut self, r: usize, v: f64) {
        self.values[self.start[r + 1] - 1] = v;
    }

    /// y = A x.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for r in 0..self.order() {
            let f = self.first[r];
            let row = &self.values[self.start[r]..self.start[r + 1]];
            let (off, d) = row.split_at(row.len() - 1);
            let mut s = d[0] * x[r];
            for (k, a) in off.iter().enumerate() {
                s += a * x[f + k];
                y[f + k] += a * x[r];
            }
            y[r] += s;
        }
    }

    /// The Cholesky factor L (A = L Lᵀ) in the same envelope, or `None` where a pivot is not
    /// positive (or not finite): then A is not positive definite.
    pub fn cholesky(&self) -> Option<EnvelopeCholesky> {
        self.cholesky_shifted(0.0)
    }

    /// The Cholesky factor of A − σI, or `None` where it is not positive definite (σ ≥ λ_min).
    pub fn cholesky_shifted(&self, sigma: f64) -> Option<EnvelopeCholesky> {
        let m = self.order();
        let mut l = self.values.clone();
        for r in 0..m {
            let fr = self.first[r];
            let sr = self.start[r];
            for c in fr..r {
                let fc = self.first[c];
                let sc = self.start[c];
                let k0 = fr.max(fc);
                let mut s = l[sr + c - fr];
                for k in k0..c {
                    s -= l[sr + k - fr] * l[sc + k - fc];
                }
                // The diagonal of row c is the last entry of its row.
                l[sr + c - fr] = s / l[self.start[c + 1] - 1];
            }
            let row = &l[sr..self.start[r + 1]];
            let (off, d) = row.split_at(row.len() - 1);
            let pivot = d[0] - sigma - off.iter().map(|v| v * v).sum::<f64>();
            if !(pivot > 0.0 && pivot.is_finite()) {
                return None;
            }
            l[self.start[r + 1] - 1] = pivot.sqrt();
        }
        Some(EnvelopeCholesky {
            first: self.first.clone(),
            start: self.start.clone(),
            l,
        })
    }

    /// Gershgorin's bounds on the spectrum: every eigenvalue lies in [lo, hi].
    pub fn gershgorin(&self) -> (f64, f64) {
        let m = self.order();
        let mut radius = vec![0.0; m];
        for r in 0..m {
            let f = self.first[r];
            for (k, a) in self.values[self.start[r]..self.start[r + 1] - 1]
                .iter()
                .enumerate()
            {
                radius[r] += a.abs();
                radius[f + k] += a.abs();
            }
        }
        (0..m).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
            let d = self.get(r, r);
            (lo.min(d - radius[r]), hi.max(d + radius[r]))
        })
    }

    /// The lowest eigenvalue with its unit eigenvector, by shift and invert. Bisection on the
    /// shift σ between Gershgorin's lower bound and the least diagonal entry (A − σI has a
    /// Cholesky factorisation exactly when σ < λ_min) brackets λ_min to 10⁻³ of its size;
    /// inverse iteration with the bracket's lower end then runs until the residual
    /// ‖Av − ρv‖₂ (ρ the Rayleigh quotient) is below 10⁻¹⁰ of the spectrum's scale. `None`
    /// when that is not reached in 200 iterations (λ_min nearly degenerate), or for an empty
    /// or non-finite matrix: then a dense eigensolver decides. The cost is some 20-50
    /// factorisations within the envelope, for a block of a grid far below the dense
    /// eigenproblem's O(m³).
    pub fn lowest_eigenpair(&self) -> Option<(f64, Vec<f64>)> {
        let m = self.order();
        if m == 0 || !self.all_finite() {
            return None;
        }
        let (g_lo, g_hi) = self.gershgorin();
        let scale = g_lo.abs().max(g_hi.abs()).max(f64::MIN_POSITIVE);
        let mut lo = g_lo - 1e-12 * scale;
        let mut hi = (0..m).map(|r| self.get(r, r)).fold(f64::INFINITY, f64::min);
        let mut factor = self.cholesky_shifted(lo)?;
        // Bisect until the bracket is within 10⁻³ of |λ_min|: inverse iteration from its lower
        // end σ then gains the factor (λ₁ − σ)/(λ₂ − σ) per step.
        for _ in 0..60 {
            if hi - lo <= 1e-3 * (hi.abs() + lo.abs()) + 1e-14 * scale {
                break;
            }
            let mid = 0.5 * (lo + hi);
            match self.cholesky_shifted(mid) {
                Some(f) => {
                    lo = mid;
                    factor = f;
                }
                None => hi = mid,
            }
        }
        let mut v: Vec<f64> = (0..m)
            .map(|k| 1.0 + 0.5 * ((k as f64) * 0.7548776662).sin())
            .collect();
        let mut av = vec![0.0; m];
        for _ in 0..200 {
            factor.solve(&mut v);
            let norm = dot(&v, &v).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return None;
            }
            v.iter_mut().for_each(|x| *x /= norm);
            self.mul(&v, &mut av);
            let rho = dot(&v, &av);
            let residual = av
                .iter()
                .zip(&v)
                .map(|(a, b)| (a - rho * b).powi(2))
                .sum::<f64>()
                .sqrt();
            if residual <= 1e-10 * scale {
                return Some((rho, v));
            }
        }
        None
    }
}

/// The Cholesky factor of an [`Envelope`] matrix.
#[derive(Debug, Clone)]
pub struct EnvelopeCholesky {
    first: Vec<usize>,
    start: Vec<usize>,
    l: Vec<f64>,
}

impl EnvelopeCholesky {
    /// Solve A x = b in place (b in, x out).
    pub fn solve(&self, b: &mut [f64]) {
        let m = self.first.len();
        // L y = b.
        for r in 0..m {
            let f = self.first[r];
            let row = &self.l[self.start[r]..self.start[r + 1]];
            let (off, d) = row.split_at(row.len() - 1);
            let s: f64 = off.iter().zip(&b[f..r]).map(|(a, y)| a * y).sum();
            b[r] = (b[r] - s) / d[0];
        }
        // Lᵀ x = y.
        for r in (0..m).rev() {
            let f = self.first[r];
            let row = &self.l[self.start[r]..self.start[r + 1]];
            let (off, d) = row.split_at(row.len() - 1);
            b[r] /= d[0];
            let xr = b[r];
            for (a, y) in off.iter().zip(&mut b[f..r]) {
                *y -= a * xr;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// The 5-point Laplacian of an nx x ny grid plus `shift` on the diagonal, as lower-triangle
    /// positions and values.
    fn grid(nx: usize, ny: usize, shift: f64) -> (SymmetricPattern, Vec<f64>) {
        let n = nx * ny;
        let mut lower = Vec::new();
        let mut vals = Vec::new();
        for i in 0..n {
            lower.push((i, i));
            vals.push(4.0 + shift + 0.1 * (i % 7) as f64);
        }
        for i in 0..n {
            if i % nx + 1 < nx {
                lower.push((i + 1, i));
                vals.push(-1.0);
            }
            if i + nx < n {
                lower.push((i + nx, i));
                vals.push(-1.0 - 0.01 * (i % 3) as f64);
            }
        }
        let pattern = SymmetricPattern::from_lower(n, &lower);
        let mut rows = Vec::new();
        pattern.gather(&vals, &mut rows);
        (pattern, rows)
    }

    fn dense(pattern: &SymmetricPattern, rows: &[f64], set: &[usize]) -> DMatrix<f64> {
        DMatrix::from_fn(set.len(), set.len(), |r, c| {
            pattern
                .row(rows, set[r])
                .filter(|&(j, _)| j == set[c])
                .map(|(_, v)| v)
                .sum()
        })
    }

    /// An irregular patch of a 12 x 9 grid: the block, its product and its factorisation
    /// against dense linear algebra.
    #[test]
    fn a_patch_factorises_as_the_dense_block_does() {
        let (pattern, rows) = grid(12, 9, 0.0);
        let set: Vec<usize> = (0..108)
            .filter(|i| (i * 7 + i / 12) % 5 != 0 || i % 12 < 6)
            .collect();
        let env = Envelope::principal_block(&pattern, &rows, &set);
        let a = dense(&pattern, &rows, &set);
        let m = set.len();
        for r in 0..m {
            for c in 0..=r {
                assert_eq!(env.get(r, c), a[(r, c)], "entry ({r}, {c})");
            }
        }
        let x: Vec<f64> = (0..m).map(|k| ((k * 37) % 11) as f64 - 5.0).collect();
        let mut y = vec![0.0; m];
        env.mul(&x, &mut y);
        let y_dense = &a * DVector::from_vec(x.clone());
        for (p, q) in y.iter().zip(y_dense.iter()) {
            assert!((p - q).abs() < 1e-12, "{p} vs {q}");
        }
        let chol = env.cholesky().expect("positive definite");
        let mut b = y;
        chol.solve(&mut b);
        for (p, q) in b.iter().zip(&x) {
            assert!((p - q).abs() < 1e-10, "{p} vs {q}");
        }
    }

    /// The lowest eigenpair by shift and invert equals the dense eigensolver's.
    #[test]
    fn the_lowest_eigenpair_matches_the_dense_one() {
        let (pattern, rows) = grid(14, 11, -3.0);
        let set: Vec<usize> = (0..154).filter(|i| (i * 5 + i / 14) % 7 != 0).collect();
        let env = Envelope::principal_block(&pattern, &rows, &set);
        let a = dense(&pattern, &rows, &set);
        let eig = a.symmetric_eigen();
        let k = eig.eigenvalues.imin();
        let (lambda, v) = env.lowest_eigenpair().expect("converges");
        assert!(lambda < 0.0, "indefinite test block: {lambda}");
        assert!(
            (lambda - eig.eigenvalues[k]).abs() < 1e-10,
            "{lambda} vs {}",
            eig.eigenvalues[k]
        );
        let along: f64 = v
            .iter()
            .zip(eig.eigenvectors.column(k).iter())
            .map(|(p, q)| p * q)
            .sum();
        assert!((along.abs() - 1.0).abs() < 1e-9, "|cos| = {}", along.abs());
    }

    /// Definiteness is decided as by the dense factorisation, on both sides of the shift that
    /// makes the block singular.
    #[test]
    fn definiteness_follows_the_lowest_eigenvalue() {
        let (pattern, rows) = grid(10, 10, 0.0);
        let set: Vec<usize> = (0..100).filter(|i| i % 10 > 1).collect();
        let a = dense(&pattern, &rows, &set);
        let lowest = a.clone().symmetric_eigen().eigenvalues.min();
        for (delta, definite) in [(-1e-6, true), (1e-6, false), (1.0, false)] {
            let mut env = Envelope::principal_block(&pattern, &rows, &set);
            for r in 0..env.order() {
                let d = env.get(r, r);
                env.set_diagonal(r, d - lowest - delta);
            }
            assert_eq!(env.cholesky().is_some(), definite, "shift {delta}");
        }
    }
}
