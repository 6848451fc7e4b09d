//! Two-dimensional discrete Fourier transforms of row-major arrays (rows, transpose, rows),
//! parallel over rows with rayon.
//!
//! The forward transform is X(k, l) = Σ x(i, j) e^{-2πi(ik/nx + jl/ny)} (no scaling); the
//! inverse carries the factor 1/(nx·ny), so that `inverse(forward(x)) = x`.

use rayon::prelude::*;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

/// Direction of a transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// e^{-2πi…}, unscaled.
    Forward,
    /// e^{+2πi…}, scaled by 1/(nx·ny).
    Inverse,
}

/// Transform every row of length `n` of `data` in place.
fn rows(data: &mut [Complex64], n: usize, direction: Direction, planner: &mut FftPlanner<f64>) {
    let fft = match direction {
        Direction::Forward => planner.plan_fft_forward(n),
        Direction::Inverse => planner.plan_fft_inverse(n),
    };
    let scratch_len = fft.get_inplace_scratch_len();
    // Blocks of rows per task keep the scratch allocation per task, not per row.
    let block = (data.len() / n).div_ceil(4 * rayon::current_num_threads()).max(1) * n;
    data.par_chunks_mut(block).for_each(|chunk| {
        let mut scratch = vec![Complex64::new(0.0, 0.0); scratch_len];
        for row in chunk.chunks_exact_mut(n) {
            fft.process_with_scratch(row, &mut scratch);
        }
    });
}

/// Transpose an `ny × nx` row-major array into `out` (`nx × ny`), in cache blocks.
fn transpose(src: &[Complex64], out: &mut [Complex64], nx: usize, ny: usize) {
    const B: usize = 32;
    out.par_chunks_mut(ny * B.min(nx))
        .enumerate()
        .for_each(|(bi, dst)| {
            let i0 = bi * B.min(nx);
            let rows_here = dst.len() / ny;
            for j0 in (0..ny).step_by(B) {
                for j in j0..(j0 + B).min(ny) {
                    let srow = &src[j * nx..(j + 1) * nx];
                    for di in 0..rows_here {
                        dst[di * ny + j] = srow[i0 + di];
                    }
                }
            }
        });
}

/// 2D DFT in place of `data`, an `ny × nx` row-major array (`data[j*nx + i]`).
///
/// # Panics
/// If `data.len() != nx * ny`.
pub fn fft2(data: &mut [Complex64], nx: usize, ny: usize, direction: Direction) {
    assert_eq!(data.len(), nx * ny, "fft2: array is not nx × ny");
    if data.is_empty() {
        return;
    }
    let mut planner = FftPlanner::new();
    rows(data, nx, direction, &mut planner);
    let mut t = vec![Complex64::new(0.0, 0.0); data.len()];
    transpose(data, &mut t, nx, ny);
    rows(&mut t, ny, direction, &mut planner);
    transpose(&t, data, ny, nx);
    if direction == Direction::Inverse {
        let s = 1.0 / (nx * ny) as f64;
        data.par_iter_mut().for_each(|v| *v *= s);
    }
}

/// Signed frequency index of DFT bin `k` of an `n`-point transform: 0, 1, …, n/2, −(n/2−1), …, −1
/// (the Nyquist bin of an even `n` counted as positive).
pub fn signed_index(k: usize, n: usize) -> f64 {
    if k <= n / 2 { k as f64 } else { k as f64 - n as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_matches_direct_sum_and_inverse_restores() {
        let (nx, ny) = (6, 5);
        let x: Vec<Complex64> = (0..nx * ny)
            .map(|k| Complex64::new((k as f64 * 0.7).sin(), (k as f64 * 0.3).cos()))
            .collect();
        let mut y = x.clone();
        fft2(&mut y, nx, ny, Direction::Forward);
        for (l, k) in [(0, 0), (1, 2), (4, 5), (3, 1)] {
            let mut s = Complex64::new(0.0, 0.0);
            for j in 0..ny {
                for i in 0..nx {
                    let ph = -2.0
                        * std::f64::consts::PI
                        * ((i * k) as f64 / nx as f64 + (j * l) as f64 / ny as f64);
                    s += x[j * nx + i] * Complex64::new(ph.cos(), ph.sin());
                }
            }
            assert!((y[l * nx + k] - s).norm() < 1e-12);
        }
        fft2(&mut y, nx, ny, Direction::Inverse);
        for (a, b) in x.iter().zip(&y) {
            assert!((a - b).norm() < 1e-14);
        }
    }
}
