//! Sparse symmetric matrices given by their lower triangle, preconditioned conjugate gradients
//! that report negative curvature, and a factorisation-free certificate of positive
//! definiteness for Z-matrices (off-diagonal entries ≤ 0).
//!
//! These serve [`crate::numerics::newton::StableNewton`] on systems too large to factorise at
//! every step: a Jacobi-preconditioned CG solve of a well-conditioned sparse system costs a few
//! dozen matrix-vector products, far less than a sparse Cholesky factorisation with its fill.

use rayon::prelude::*;

/// Rows at or above this count use rayon in the matrix-vector product.
const PARALLEL_ROWS: usize = 16_384;

/// Rows per rayon task in the parallel loops.
const CHUNK: usize = 4096;

/// The full (both triangles) row structure of a symmetric matrix whose lower triangle is given
/// as a list of (row, col) positions. Values in the order of that list are spread into row
/// order once per matrix by [`SymmetricPattern::gather`]; products and row sums then read them
/// contiguously.
#[derive(Debug, Clone)]
pub struct SymmetricPattern {
    n: usize,
    /// Start of each row in `cols`/`slots`, length n + 1.
    row_start: Vec<usize>,
    cols: Vec<u32>,
    /// Index into the values (lower-triangle order) of each stored entry.
    slots: Vec<usize>,
}

impl SymmetricPattern {
    /// Build from lower-triangle positions (r ≥ c); duplicates are summed, as in assembly.
    ///
    /// # Panics
    /// With more than 2³² rows.
    pub fn from_lower(n: usize, lower: &[(usize, usize)]) -> Self {
        assert!(u32::try_from(n).is_ok(), "at most 2^32 rows");
        let mut count = vec![0usize; n + 1];
        for &(r, c) in lower {
            count[r + 1] += 1;
            if r != c {
                count[c + 1] += 1;
            }
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let row_start = count.clone();
        let mut fill = count;
        let total = row_start[n];
        let mut cols = vec![0; total];
        let mut slots = vec![0; total];
        for (k, &(r, c)) in lower.iter().enumerate() {
            cols[fill[r]] = c as u32;
            slots[fill[r]] = k;
            fill[r] += 1;
            if r != c {
                cols[fill[c]] = r as u32;
                slots[fill[c]] = k;
                fill[c] += 1;
            }
        }
        Self {
            n,
            row_start,
            cols,
            slots,
        }
    }

    /// Number of rows.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Spread values in lower-triangle order into row order (`rows`, resized).
    pub fn gather(&self, values: &[f64], rows: &mut Vec<f64>) {
        if self.n >= PARALLEL_ROWS {
            // Chunks of entries: about CHUNK rows of a five-point stencil each.
            rows.resize(self.slots.len(), 0.0);
            rows.par_chunks_mut(5 * CHUNK)
                .zip(self.slots.par_chunks(5 * CHUNK))
                .for_each(|(r, s)| r.iter_mut().zip(s).for_each(|(ri, &k)| *ri = values[k]));
        } else {
            rows.clear();
            rows.extend(self.slots.iter().map(|&s| values[s]));
        }
    }

    /// Columns of the entries of row i (the diagonal included).
    pub fn columns(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        self.cols[self.row_start[i]..self.row_start[i + 1]]
            .iter()
            .map(|&c| c as usize)
    }

    /// Entries of row i: (column, value) from values in row order.
    pub fn row<'a>(&'a self, rows: &'a [f64], i: usize) -> impl Iterator<Item = (usize, f64)> + 'a {
        let r = self.row_start[i]..self.row_start[i + 1];
        self.cols[r.clone()]
            .iter()
            .map(|&c| c as usize)
            .zip(rows[r].iter().copied())
    }

    /// y = A x, values in row order ([`SymmetricPattern::gather`]).
    pub fn mul(&self, rows: &[f64], x: &[f64], y: &mut [f64]) {
        self.mul_dot(rows, x, y);
    }

    /// y = A x as [`SymmetricPattern::mul`], returning xᵀ A x (computed in the same pass).
    pub fn mul_dot(&self, rows: &[f64], x: &[f64], y: &mut [f64]) -> f64 {
        let block = |start: usize, chunk: &mut [f64]| -> f64 {
            let mut q = 0.0;
            for (k, yi) in chunk.iter_mut().enumerate() {
                let i = start + k;
                let (a, b) = (self.row_start[i], self.row_start[i + 1]);
                let mut s = 0.0;
                for (&c, &v) in self.cols[a..b].iter().zip(&rows[a..b]) {
                    s += v * x[c as usize];
                }
                *yi = s;
                q += s * x[i];
            }
            q
        };
        if self.n >= PARALLEL_ROWS {
            y.par_chunks_mut(CHUNK)
                .enumerate()
                .map(|(b, chunk)| block(b * CHUNK, chunk))
                .sum()
        } else {
            block(0, y)
        }
    }

    /// Diagonal entries into `diag` and off-diagonal absolute row sums Σ_{j≠i} |a_ij| into
    /// `off` (values in row order); returns whether every off-diagonal entry is ≤ 0 (a
    /// Z-matrix).
    pub fn diagonal_and_off_sums(&self, rows: &[f64], diag: &mut [f64], off: &mut [f64]) -> bool {
        let block = |start: usize, diag: &mut [f64], off: &mut [f64]| -> bool {
            let mut z = true;
            for (k, (dk, ok)) in diag.iter_mut().zip(off.iter_mut()).enumerate() {
                let i = start + k;
                let (mut d, mut o) = (0.0, 0.0);
                for (c, v) in self.row(rows, i) {
                    if c == i {
                        d += v;
                    } else {
                        o += v.abs();
                        z &= v <= 0.0;
                    }
                }
                *dk = d;
                *ok = o;
            }
            z
        };
        let (diag, off) = (&mut diag[..self.n], &mut off[..self.n]);
        if self.n >= PARALLEL_ROWS {
            diag.par_chunks_mut(CHUNK)
                .zip(off.par_chunks_mut(CHUNK))
                .enumerate()
                .map(|(b, (d, o))| block(b * CHUNK, d, o))
                .reduce(|| true, |p, q| p && q)
        } else {
            block(0, diag, off)
        }
    }
}

/// Matching pieces of x, r, z, d, A d and the inverse diagonal in one pass of [`pcg`].
type CgChunks<'a> = (
    &'a mut [f64],
    &'a mut [f64],
    &'a mut [f64],
    &'a [f64],
    &'a [f64],
    &'a [f64],
);

/// How a conjugate-gradient solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PcgEnd {
    /// The residual reached the target.
    Converged,
    /// A search direction d with dᵀ A d ≤ 0: A is not positive definite. The iterate is the
    /// last one before it (a descent direction of the quadratic model if any step was taken).
    NegativeCurvature,
    /// The iteration limit was reached first.
    MaxIterations,
}

/// The matrix A + diag(extra) of a [`SymmetricPattern`] with its values, as an operator.
pub struct Operator<'a> {
    /// Structure.
    pub pattern: &'a SymmetricPattern,
    /// Values in row order ([`SymmetricPattern::gather`]).
    pub values: &'a [f64],
    /// Added to the diagonal (e.g. a modification making the matrix definite); empty for none.
    pub extra_diagonal: &'a [f64],
}

impl Operator<'_> {
    /// y = (A + diag(extra)) x.
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.apply_dot(x, y);
    }

    /// y = (A + diag(extra)) x, returning xᵀ y.
    pub fn apply_dot(&self, x: &[f64], y: &mut [f64]) -> f64 {
        let mut q = self.pattern.mul_dot(self.values, x, y);
        if !self.extra_diagonal.is_empty() {
            for ((yi, e), xi) in y.iter_mut().zip(self.extra_diagonal).zip(x) {
                *yi += e * xi;
                q += e * xi * xi;
            }
        }
        q
    }
}

/// Solve A x = b by conjugate gradients preconditioned with `inv_diag` (the inverse diagonal,
/// Jacobi), from the start in `x`, until the largest residual component is at most `target`.
/// Stops at the first direction of non-positive curvature. Returns the end and the iterations.
pub fn pcg(
    a: &Operator<'_>,
    inv_diag: &[f64],
    b: &[f64],
    x: &mut [f64],
    target: f64,
    max_iterations: usize,
) -> (PcgEnd, usize) {
    pcg_with_curvature(a, inv_diag, b, x, target, max_iterations, &mut [])
}

/// [`pcg`], and on [`PcgEnd::NegativeCurvature`] the direction d with dᵀ A d ≤ 0 written into
/// `negative` (when it has the length of `b`; an empty slice asks for nothing).
pub fn pcg_with_curvature(
    a: &Operator<'_>,
    inv_diag: &[f64],
    b: &[f64],
    x: &mut [f64],
    target: f64,
    max_iterations: usize,
    negative: &mut [f64],
) -> (PcgEnd, usize) {
    let n = b.len();
    // r = b − A x (no product from a zero start, the usual one).
    let mut r = b.to_vec();
    if x.iter().any(|&v| v != 0.0) {
        let mut ax = vec![0.0; n];
        a.apply(x, &mut ax);
        r.iter_mut().zip(&ax).for_each(|(ri, axi)| *ri -= axi);
    }
    let mut z: Vec<f64> = r.iter().zip(inv_diag).map(|(ri, m)| ri * m).collect();
    let mut d = z.clone();
    let mut ad = vec![0.0; n];
    let mut rz = dot(&r, &z);
    let mut r_norm = inf_norm(&r);
    for it in 0..max_iterations {
        if r_norm <= target {
            return (PcgEnd::Converged, it);
        }
        let curvature = a.apply_dot(&d, &mut ad);
        if curvature <= 0.0 || curvature.is_nan() {
            if negative.len() == n {
                negative.copy_from_slice(&d);
            }
            return (PcgEnd::NegativeCurvature, it);
        }
        let alpha = rz / curvature;
        // One pass for the updates of x, r, z and the reductions over r.
        let update = |(xs, rs, zs, ds, ads, ms): CgChunks<'_>| {
            let (mut rz, mut norm) = (0.0, 0.0f64);
            for k in 0..xs.len() {
                xs[k] += alpha * ds[k];
                rs[k] -= alpha * ads[k];
                zs[k] = rs[k] * ms[k];
                rz += rs[k] * zs[k];
                norm = norm.max(rs[k].abs());
            }
            (rz, norm)
        };
        let (rz_new, norm) = if n >= PARALLEL_ROWS {
            x.par_chunks_mut(CHUNK)
                .zip(r.par_chunks_mut(CHUNK))
                .zip(z.par_chunks_mut(CHUNK))
                .zip(d.par_chunks(CHUNK))
                .zip(ad.par_chunks(CHUNK))
                .zip(inv_diag.par_chunks(CHUNK))
                .map(|(((((xs, rs), zs), ds), ads), ms)| update((xs, rs, zs, ds, ads, ms)))
                .reduce(|| (0.0, 0.0), |p, q| (p.0 + q.0, p.1.max(q.1)))
        } else {
            update((x, &mut r, &mut z, &d, &ad, inv_diag))
        };
        r_norm = norm;
        let beta = rz_new / rz;
        rz = rz_new;
        if n >= PARALLEL_ROWS {
            d.par_chunks_mut(CHUNK)
                .zip(z.par_chunks(CHUNK))
                .for_each(|(ds, zs)| ds.iter_mut().zip(zs).for_each(|(di, zi)| *di = zi + beta * *di));
        } else {
            d.iter_mut().zip(&z).for_each(|(di, zi)| *di = zi + beta * *di);
        }
    }
    if r_norm <= target {
        (PcgEnd::Converged, max_iterations)
    } else {
        (PcgEnd::MaxIterations, max_iterations)
    }
}

/// Whether the vector `v` certifies that the symmetric Z-matrix A (off-diagonals ≤ 0, checked
/// by the caller; values in row order) is positive definite: every v_i > 0 and every
/// (A v)_i > 0 by more than the rounding error of its computation. When it does, returns the
/// bound max v / min (A v) ≥ ‖A⁻¹‖∞ (A⁻¹ has no negative entries, so A⁻¹·1 ≤ v / min(A v)).
///
/// Proof: with V = diag(v), B = V A V is a symmetric Z-matrix with row sums
/// (B·1)_i = v_i (A v)_i > 0, so b_ii − Σ_{j≠i} |b_ij| > 0 for every row: B is strictly
/// diagonally dominant with a positive diagonal, hence positive definite (Gershgorin), and A is
/// congruent to B. Conversely, a positive-definite Z-matrix is a nonsingular M-matrix, its
/// inverse has no negative entries, and v = A⁻¹·1 ≥ diag(A)⁻¹ > 0 is such a certificate.
pub fn certifies_z_matrix(pattern: &SymmetricPattern, values: &[f64], v: &[f64]) -> Option<f64> {
    if v.len() != pattern.n || v.iter().any(|&x| !(x > 0.0 && x.is_finite())) {
        return None;
    }
    // The smallest margin (A v)_i, or −1 where the rounding error could hide its sign.
    let margin = |i: usize| -> f64 {
        let (mut s, mut a) = (0.0, 0.0);
        for (c, val) in pattern.row(values, i) {
            s += val * v[c];
            a += (val * v[c]).abs();
        }
        // A sum of m products carries a rounding error below m·ε·Σ|terms|; 64 ε covers any
        // row of up to dozens of entries with room to spare.
        if s > 64.0 * f64::EPSILON * a { s } else { -1.0 }
    };
    let least = if pattern.n >= PARALLEL_ROWS {
        (0..pattern.n)
            .into_par_iter()
            .map(margin)
            .reduce(|| f64::INFINITY, f64::min)
    } else {
        (0..pattern.n).map(margin).fold(f64::INFINITY, f64::min)
    };
    (least > 0.0).then(|| inf_norm(v) / least)
}

/// Look for a certificate that the symmetric Z-matrix A is positive definite (see
/// [`certifies_z_matrix`]), starting from `v` when it has the right length (the certificate of
/// a nearby matrix often still serves), otherwise from diag(A)⁻¹·1, and refining it towards
/// A⁻¹·1 by Jacobi-preconditioned CG. Returns `Some(true)` with the certificate in `v`,
/// `Some(false)` when A is shown not to be positive definite (a non-positive diagonal entry or
/// a direction of non-positive curvature), `None` when neither was found (undecided: the caller
/// decides by factorisation). With `Some(true)` comes the bound on ‖A⁻¹‖∞ of
/// [`certifies_z_matrix`].
pub fn certify_z_matrix(
    pattern: &SymmetricPattern,
    values: &[f64],
    diag: &[f64],
    v: &mut Vec<f64>,
    max_iterations: usize,
) -> (Option<bool>, f64) {
    let n = pattern.n;
    if diag.iter().any(|&d| d <= 0.0 || d.is_nan()) {
        return (Some(false), f64::INFINITY);
    }
    if let Some(bound) = certifies_z_matrix(pattern, values, v) {
        return (Some(true), bound);
    }
    let inv: Vec<f64> = diag.iter().map(|d| 1.0 / d).collect();
    if v.len() != n || v.iter().any(|x| !x.is_finite()) {
        v.clear();
        v.extend_from_slice(&inv);
        if let Some(bound) = certifies_z_matrix(pattern, values, v) {
            return (Some(true), bound);
        }
    }
    let ones = vec![1.0; n];
    let op = Operator {
        pattern,
        values,
        extra_diagonal: &[],
    };
    // Refine in rounds, checking the certificate after each: A v = 1 − r with |r| < 1 and v > 0
    // is enough, so a modest residual suffices.
    let mut done = 0;
    let mut target = 0.5;
    while done < max_iterations {
        let (end, its) = pcg(&op, &inv, &ones, v, target, 25.min(max_iterations - done));
        done += its.max(1);
        if end == PcgEnd::NegativeCurvature {
            return (Some(false), f64::INFINITY);
        }
        if let Some(bound) = certifies_z_matrix(pattern, values, v) {
            return (Some(true), bound);
        }
        if end == PcgEnd::Converged {
            target *= 1e-3;
            if target < 1e-14 {
                break;
            }
        }
    }
    (None, f64::INFINITY)
}

/// Largest absolute value.
pub fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Dot product summed in eight lanes, which the compiler vectorises: several times faster
/// than [`dot`] on long vectors (dense matrix rows), with a different rounding order.
pub fn dot_lanes(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Dot product.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 1D Laplacian-like chain with diagonal `d` and off-diagonal −1.
    /// Values in row order.
    fn chain(n: usize, d: f64) -> (SymmetricPattern, Vec<f64>) {
        let mut lower: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
        lower.extend((1..n).map(|i| (i, i - 1)));
        let mut values = vec![d; n];
        values.extend(std::iter::repeat_n(-1.0, n - 1));
        let p = SymmetricPattern::from_lower(n, &lower);
        let mut rows = Vec::new();
        p.gather(&values, &mut rows);
        (p, rows)
    }

    /// Above [`PARALLEL_ROWS`] the row-order values, the diagonal, the off-diagonal sums and
    /// the Z-matrix test come from parallel passes: they equal the entries row by row, and a
    /// positive off-diagonal entry in the last row is seen.
    #[test]
    fn the_parallel_passes_read_every_row() {
        let n = PARALLEL_ROWS + 1234;
        let mut lower: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
        lower.extend((1..n).map(|i| (i, i - 1)));
        lower.extend((7..n).step_by(3).map(|i| (i, i - 7)));
        let mut values: Vec<f64> = (0..n).map(|i| 3.0 + (i % 13) as f64).collect();
        values.extend((1..lower.len() - n + 1).map(|k| -0.5 - (k % 5) as f64 * 0.1));
        let p = SymmetricPattern::from_lower(n, &lower);
        let mut rows = Vec::new();
        p.gather(&values, &mut rows);
        let mut diag = vec![0.0; n];
        let mut off = vec![0.0; n];
        assert!(p.diagonal_and_off_sums(&rows, &mut diag, &mut off));
        let mut want_off = vec![0.0; n];
        for (&(r, c), v) in lower.iter().zip(&values).skip(n) {
            want_off[r] += v.abs();
            want_off[c] += v.abs();
        }
        for i in 0..n {
            assert_eq!(diag[i], values[i], "diagonal {i}");
            assert!(
                (off[i] - want_off[i]).abs() < 1e-12,
                "row {i}: {} vs {}",
                off[i],
                want_off[i]
            );
        }
        *values.last_mut().expect("entries") = 0.25;
        p.gather(&values, &mut rows);
        assert!(!p.diagonal_and_off_sums(&rows, &mut diag, &mut off));
    }

    #[test]
    fn cg_solves_a_definite_chain() {
        let (p, v) = chain(200, 2.5);
        let b: Vec<f64> = (0..200).map(|i| (i as f64 * 0.1).sin()).collect();
        let mut x = vec![0.0; 200];
        let inv = vec![1.0 / 2.5; 200];
        let op = Operator {
            pattern: &p,
            values: &v,
            extra_diagonal: &[],
        };
        let (end, its) = pcg(&op, &inv, &b, &mut x, 1e-12, 500);
        assert_eq!(end, PcgEnd::Converged);
        assert!(its < 100, "{its} iterations");
        let mut ax = vec![0.0; 200];
        op.apply(&x, &mut ax);
        assert!(ax.iter().zip(&b).all(|(a, b)| (a - b).abs() < 1e-11));
    }

    // The chain with diagonal d has eigenvalues d − 2 cos(kπ/(n+1)): positive definite exactly
    // when d > 2 cos(π/(n+1)). Just above, the certificate is found; just below, it is refused.
    #[test]
    fn the_certificate_decides_definiteness_at_the_margin() {
        let n = 50;
        let edge = 2.0 * (std::f64::consts::PI / (n as f64 + 1.0)).cos();
        for (d, definite) in [(edge + 1e-4, true), (edge - 1e-4, false), (1.5, false)] {
            let (p, v) = chain(n, d);
            let diag = vec![d; n];
            let mut cert = Vec::new();
            let (found, bound) = certify_z_matrix(&p, &v, &diag, &mut cert, 2000);
            if definite {
                assert_eq!(found, Some(true), "d = {d}");
                assert!(certifies_z_matrix(&p, &v, &cert).is_some());
                // ‖A⁻¹‖∞ ≥ 1/λ_min = 1e4 here; the bound must hold.
                let lambda_min = d - edge;
                assert!(
                    bound >= 0.99 / lambda_min,
                    "bound {bound:.3e} vs 1/λ = {:.3e}",
                    1.0 / lambda_min
                );
            } else {
                assert_ne!(found, Some(true), "d = {d}");
            }
        }
    }

    #[test]
    fn a_non_positive_diagonal_is_refused_at_once() {
        let (p, v) = chain(10, 3.0);
        let mut diag = vec![3.0; 10];
        diag[4] = 0.0;
        assert_eq!(
            certify_z_matrix(&p, &v, &diag, &mut Vec::new(), 10).0,
            Some(false)
        );
    }
}
