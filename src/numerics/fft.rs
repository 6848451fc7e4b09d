//! Two-dimensional discrete Fourier transforms of row-major arrays, parallel with rayon.
//!
//! - [`fft2`]: complex data in place (rows, transpose, rows).
//! - [`RealFft2`]: real data, the rough-surface pipeline's transform. A real `ny × nx` array has
//!   a Hermitian spectrum, X(−k, −l) = X̄(k, l), so the columns k = 0..=nx/2 (`hx` of them) hold
//!   all of it: a real-to-complex transform along each row, then complex transforms along those
//!   `hx` columns, half the work of [`fft2`]. The half spectrum is stored by column,
//!   `spectrum[kx * ny + ky]`, so that the column transforms run on contiguous memory and the
//!   only reordering is one blocked gather between the row and the column pass.
//!   [`RealFft2::forward_fold`] hands each transformed column to a visitor instead of storing
//!   the spectrum, for statistics that need one pass over it (the map plus one half spectrum in
//!   memory, no second copy).
//!
//! Work is split into blocks whose size depends on the grid only, and per-block results are
//! combined in block order: results do not depend on the number of threads. Plans come from one
//! process-wide planner, so a length is planned once.
//!
//! The forward transform is X(k, l) = Σ x(i, j) e^{-2πi(ik/nx + jl/ny)} (no scaling); the
//! inverse of [`fft2`] carries the factor 1/(nx·ny), so that `inverse(forward(x)) = x`; the
//! inverse of [`RealFft2`] is unscaled and takes a factor of the caller's choice.

use std::sync::{Arc, Mutex, MutexGuard, OnceLock, PoisonError};

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

/// The process-wide planners (complex and real-to-complex).
struct Planners {
    complex: FftPlanner<f64>,
    real: RealFftPlanner<f64>,
}

/// Lock the process-wide planners (a poisoned lock still holds valid plans).
fn planners() -> MutexGuard<'static, Planners> {
    static PLANNERS: OnceLock<Mutex<Planners>> = OnceLock::new();
    PLANNERS
        .get_or_init(|| {
            Mutex::new(Planners {
                complex: FftPlanner::new(),
                real: RealFftPlanner::new(),
            })
        })
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
}

/// Direction of a transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// e^{-2πi…}, unscaled.
    Forward,
    /// e^{+2πi…}, scaled by 1/(nx·ny).
    Inverse,
}

/// Transform every row of length `n` of `data` in place.
fn rows(data: &mut [Complex64], n: usize, direction: Direction) {
    let fft = {
        let mut p = planners();
        match direction {
            Direction::Forward => p.complex.plan_fft_forward(n),
            Direction::Inverse => p.complex.plan_fft_inverse(n),
        }
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
    rows(data, nx, direction);
    let mut t = vec![Complex64::new(0.0, 0.0); data.len()];
    transpose(data, &mut t, nx, ny);
    rows(&mut t, ny, direction);
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

/// Total length of the spectrum buffers kept between transforms: the two half spectra that
/// generating a 4096² surface holds at once (268 MiB). A fresh buffer costs a page fault and a
/// kernel zeroing per 4 KiB on every call, as much as the transform's arithmetic on a 1024² grid;
/// larger buffers are freed after use.
const POOL_MAX_LEN: usize = 2 * (4096 / 2 + 1) * 4096;

/// Spectrum buffers kept for the next transform (see [`POOL_MAX_LEN`]).
static POOL: Mutex<Vec<Vec<Complex64>>> = Mutex::new(Vec::new());

/// A buffer of `len` values from the pool (contents unspecified) or newly allocated.
pub fn take_buffer(len: usize) -> Vec<Complex64> {
    let mut pool = POOL.lock().unwrap_or_else(PoisonError::into_inner);
    let best = pool
        .iter()
        .enumerate()
        .filter(|(_, b)| b.capacity() >= len)
        .min_by_key(|(_, b)| b.capacity())
        .map(|(i, _)| i);
    match best {
        Some(i) => {
            let mut b = pool.swap_remove(i);
            drop(pool);
            b.resize(len, Complex64::default());
            b
        }
        None => {
            drop(pool);
            vec![Complex64::default(); len]
        }
    }
}

/// Return a buffer from [`take_buffer`] to the pool, which keeps the largest buffers up to
/// 2 · 2049 · 4096 values (268 MiB, the two half spectra of a 4096² generation) in all.
pub fn recycle_buffer(buf: Vec<Complex64>) {
    if buf.capacity() > POOL_MAX_LEN {
        return;
    }
    let mut pool = POOL.lock().unwrap_or_else(PoisonError::into_inner);
    pool.push(buf);
    pool.sort_unstable_by_key(|b| std::cmp::Reverse(b.capacity()));
    let mut total = 0;
    pool.retain(|b| {
        total += b.capacity();
        total <= POOL_MAX_LEN
    });
}

/// Grid lines per block of a pass over `n` lines: about 16 blocks, at most 32 lines each (the
/// gather between the passes moves runs of this many contiguous values). Depends on `n` only.
fn block_len(n: usize) -> usize {
    (n / 16).clamp(1, 32)
}

/// A planned two-dimensional transform of real `ny × nx` row-major arrays (`x[j*nx + i]`) and
/// their half spectra, `hx = nx/2 + 1` columns stored by column (`spectrum[kx * ny + ky]`); see
/// the module documentation.
#[derive(Clone)]
pub struct RealFft2 {
    nx: usize,
    ny: usize,
    hx: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
}

impl std::fmt::Debug for RealFft2 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RealFft2")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .finish_non_exhaustive()
    }
}

impl RealFft2 {
    /// Plans for an `nx × ny` grid (taken from the process-wide planner).
    ///
    /// # Panics
    /// If `nx` or `ny` is zero.
    pub fn new(nx: usize, ny: usize) -> Self {
        assert!(nx > 0 && ny > 0, "RealFft2: empty grid {nx} x {ny}");
        let mut p = planners();
        let r2c = p.real.plan_fft_forward(nx);
        let c2r = p.real.plan_fft_inverse(nx);
        let column_forward = p.complex.plan_fft_forward(ny);
        let column_inverse = p.complex.plan_fft_inverse(ny);
        Self {
            nx,
            ny,
            hx: nx / 2 + 1,
            r2c,
            c2r,
            column_forward,
            column_inverse,
        }
    }

    /// Number of stored spectrum columns, `hx = nx/2 + 1` (wavenumber indices kx = 0..hx).
    pub fn half_columns(&self) -> usize {
        self.hx
    }

    /// Length of a half spectrum, `hx * ny`.
    pub fn spectrum_len(&self) -> usize {
        self.hx * self.ny
    }

    /// Weight of stored column `kx` in a sum over the whole spectrum: 1 for kx = 0 and, for an
    /// even `nx`, the Nyquist column kx = nx/2 (each its own mirror image), 2 for the others
    /// (they stand for their mirror columns nx − kx too).
    pub fn column_weight(&self, kx: usize) -> f64 {
        if kx == 0 || 2 * kx == self.nx { 1.0 } else { 2.0 }
    }

    /// The row pass of the forward transform: the real-to-complex DFT of each row that
    /// `fill_row(j, row)` writes (row j of the input, `nx` values), into `rows`
    /// (`ny × hx`, row-major).
    fn forward_rows(&self, fill_row: &(impl Fn(usize, &mut [f64]) + Sync), rows: &mut [Complex64]) {
        let (nx, hx) = (self.nx, self.hx);
        let band = block_len(self.ny);
        rows.par_chunks_mut(band * hx).enumerate().for_each_init(
            || {
                (
                    vec![0.0; nx],
                    vec![Complex64::default(); self.r2c.get_scratch_len()],
                )
            },
            |(row, scratch), (b, out)| {
                for (dj, out_row) in out.chunks_exact_mut(hx).enumerate() {
                    fill_row(b * band + dj, row);
                    self.r2c
                        .process_with_scratch(row, out_row, scratch)
                        .expect("buffer lengths match the plan");
                }
            },
        );
    }

    /// Copy columns `k0..k0 + out.len()/ny` of the row-major `ny × hx` array `rows` into `out`,
    /// one column after the other.
    fn gather_columns(&self, rows: &[Complex64], k0: usize, out: &mut [Complex64]) {
        // Tiles of 8 rows: each column receives 8 consecutive values (two cache lines) at once.
        // Row by row, the columns' destinations lie ny values apart, for a power-of-two ny all
        // in one cache set, and partly written lines would be evicted before they fill.
        const TILE: usize = 8;
        let (ny, hx) = (self.ny, self.hx);
        let w = out.len() / ny;
        for j0 in (0..ny).step_by(TILE) {
            let j1 = (j0 + TILE).min(ny);
            for c in 0..w {
                let dst = &mut out[c * ny + j0..c * ny + j1];
                for (dj, d) in dst.iter_mut().enumerate() {
                    *d = rows[(j0 + dj) * hx + k0 + c];
                }
            }
        }
    }

    /// The forward transform of the rows that `fill_row(j, row)` writes, as a half spectrum
    /// (`hx * ny` values, by column; hand it to [`recycle_buffer`] when done).
    pub fn forward(&self, fill_row: impl Fn(usize, &mut [f64]) + Sync) -> Vec<Complex64> {
        let ny = self.ny;
        let mut rows = take_buffer(self.spectrum_len());
        self.forward_rows(&fill_row, &mut rows);
        let mut spectrum = take_buffer(self.spectrum_len());
        let block = block_len(self.hx);
        spectrum.par_chunks_mut(block * ny).enumerate().for_each_init(
            || vec![Complex64::default(); self.column_forward.get_inplace_scratch_len()],
            |scratch, (b, cols)| {
                self.gather_columns(&rows, b * block, cols);
                for col in cols.chunks_exact_mut(ny) {
                    self.column_forward.process_with_scratch(col, scratch);
                }
            },
        );
        recycle_buffer(rows);
        spectrum
    }

    /// The forward transform of the rows that `fill_row(j, row)` writes, without storing the
    /// spectrum: `visit(acc, kx, column)` sees each transformed column (ny values, which it may
    /// overwrite), `acc` being the accumulator of the column's block (from `init`). Returns the
    /// accumulators in block order; the blocks depend on the grid only.
    pub fn forward_fold<A: Send>(
        &self,
        fill_row: impl Fn(usize, &mut [f64]) + Sync,
        init: impl Fn() -> A + Sync,
        visit: impl Fn(&mut A, usize, &mut [Complex64]) + Sync,
    ) -> Vec<A> {
        let (ny, hx) = (self.ny, self.hx);
        let mut rows = take_buffer(self.spectrum_len());
        self.forward_rows(&fill_row, &mut rows);
        let block = block_len(hx);
        let out = (0..hx.div_ceil(block))
            .into_par_iter()
            .map_init(
                || {
                    (
                        vec![Complex64::default(); block * ny],
                        vec![Complex64::default(); self.column_forward.get_inplace_scratch_len()],
                    )
                },
                |(buf, scratch), b| {
                    let k0 = b * block;
                    let w = block.min(hx - k0);
                    let cols = &mut buf[..w * ny];
                    self.gather_columns(&rows, k0, cols);
                    let mut acc = init();
                    for (c, col) in cols.chunks_exact_mut(ny).enumerate() {
                        self.column_forward.process_with_scratch(col, scratch);
                        visit(&mut acc, k0 + c, col);
                    }
                    acc
                },
            )
            .collect();
        recycle_buffer(rows);
        out
    }

    /// The column pass of the inverse transform, in place on a half spectrum (`hx * ny`, by
    /// column): `hook(kx, column)` sees each column before its inverse transform (to filter
    /// it); returns the hook's results in column order.
    ///
    /// # Panics
    /// If `spectrum.len() != hx * ny`.
    pub fn inverse_columns<R: Send>(
        &self,
        spectrum: &mut [Complex64],
        hook: impl Fn(usize, &mut [Complex64]) -> R + Sync,
    ) -> Vec<R> {
        assert_eq!(
            spectrum.len(),
            self.spectrum_len(),
            "inverse_columns: not a half spectrum"
        );
        let ny = self.ny;
        let block = block_len(self.hx);
        let per_block: Vec<Vec<R>> = spectrum
            .par_chunks_mut(block * ny)
            .enumerate()
            .map_init(
                || vec![Complex64::default(); self.column_inverse.get_inplace_scratch_len()],
                |scratch, (b, cols)| {
                    cols.chunks_exact_mut(ny)
                        .enumerate()
                        .map(|(c, col)| {
                            let r = hook(b * block + c, col);
                            self.column_inverse.process_with_scratch(col, scratch);
                            r
                        })
                        .collect()
                },
            )
            .collect();
        per_block.into_iter().flatten().collect()
    }

    /// The row pass of the inverse transform: from a half spectrum after
    /// [`RealFft2::inverse_columns`] (used as scratch) into `out` (`ny × nx`, row-major), each
    /// value times `scale`. The imaginary parts of column 0 and of the Nyquist column of an even
    /// `nx` are dropped (they vanish, up to rounding, for the spectrum of a real array).
    ///
    /// # Panics
    /// If the lengths do not match the grid.
    pub fn inverse_rows(&self, spectrum: &[Complex64], out: &mut [f64], scale: f64) {
        assert_eq!(
            spectrum.len(),
            self.spectrum_len(),
            "inverse_rows: not a half spectrum"
        );
        assert_eq!(
            out.len(),
            self.nx * self.ny,
            "inverse_rows: output is not nx × ny"
        );
        let (nx, ny, hx) = (self.nx, self.ny, self.hx);
        let band = block_len(ny);
        let even = nx % 2 == 0;
        out.par_chunks_mut(band * nx).enumerate().for_each_init(
            || {
                (
                    vec![Complex64::default(); band * hx],
                    vec![Complex64::default(); self.c2r.get_scratch_len()],
                )
            },
            |(buf, scratch), (b, out)| {
                let j0 = b * band;
                let rows_here = out.len() / nx;
                for (kx, col) in spectrum.chunks_exact(ny).enumerate() {
                    for (dj, v) in col[j0..j0 + rows_here].iter().enumerate() {
                        buf[dj * hx + kx] = *v;
                    }
                }
                for (row_in, row_out) in buf.chunks_exact_mut(hx).zip(out.chunks_exact_mut(nx)) {
                    row_in[0].im = 0.0;
                    if even {
                        row_in[hx - 1].im = 0.0;
                    }
                    self.c2r
                        .process_with_scratch(row_in, row_out, scratch)
                        .expect("buffer lengths match the plan and the edge values are real");
                    if scale != 1.0 {
                        row_out.iter_mut().for_each(|v| *v *= scale);
                    }
                }
            },
        );
    }
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

    fn real_input(nx: usize, ny: usize) -> Vec<f64> {
        (0..nx * ny)
            .map(|k| (k as f64 * 0.7).sin() + (k as f64 * 0.013).cos())
            .collect()
    }

    #[test]
    fn real_transform_matches_the_complex_one_on_the_stored_columns() {
        for (nx, ny) in [(6, 5), (7, 4), (16, 16), (33, 20)] {
            let x = real_input(nx, ny);
            let mut full: Vec<Complex64> = x.iter().map(|&v| Complex64::new(v, 0.0)).collect();
            fft2(&mut full, nx, ny, Direction::Forward);
            let fft = RealFft2::new(nx, ny);
            let half = fft.forward(|j, row| row.copy_from_slice(&x[j * nx..(j + 1) * nx]));
            assert_eq!(half.len(), (nx / 2 + 1) * ny);
            for kx in 0..fft.half_columns() {
                for ky in 0..ny {
                    let d = (half[kx * ny + ky] - full[ky * nx + kx]).norm();
                    assert!(d < 1e-12, "{nx} x {ny}, ({kx}, {ky}): {d:e}");
                }
            }
            // The fold sees the same columns, in order.
            let cols = fft.forward_fold(
                |j, row| row.copy_from_slice(&x[j * nx..(j + 1) * nx]),
                Vec::new,
                |acc: &mut Vec<(usize, Vec<Complex64>)>, kx, col| acc.push((kx, col.to_vec())),
            );
            let flat: Vec<(usize, Vec<Complex64>)> = cols.into_iter().flatten().collect();
            assert_eq!(flat.len(), fft.half_columns());
            for (kx, col) in flat.iter().enumerate() {
                assert_eq!(col.0, kx);
                assert_eq!(col.1[..], half[kx * ny..(kx + 1) * ny]);
            }
            // Sums over the whole spectrum from the stored half (Parseval).
            let energy: f64 = (0..fft.half_columns())
                .map(|kx| {
                    fft.column_weight(kx)
                        * half[kx * ny..(kx + 1) * ny]
                            .iter()
                            .map(|c| c.norm_sqr())
                            .sum::<f64>()
                })
                .sum();
            let direct = (nx * ny) as f64 * x.iter().map(|v| v * v).sum::<f64>();
            assert!((energy / direct - 1.0).abs() < 1e-13, "{nx} x {ny}");
        }
    }

    #[test]
    fn real_inverse_restores_the_array_with_the_given_scale() {
        for (nx, ny) in [(6, 5), (7, 4), (64, 48), (33, 20)] {
            let x = real_input(nx, ny);
            let fft = RealFft2::new(nx, ny);
            let mut half = fft.forward(|j, row| row.copy_from_slice(&x[j * nx..(j + 1) * nx]));
            let seen = fft.inverse_columns(&mut half, |kx, col| (kx, col.len()));
            assert_eq!(
                seen,
                (0..fft.half_columns()).map(|kx| (kx, ny)).collect::<Vec<_>>()
            );
            let mut y = vec![0.0; nx * ny];
            fft.inverse_rows(&half, &mut y, 1.0 / (nx * ny) as f64);
            for (a, b) in x.iter().zip(&y) {
                assert!((a - b).abs() < 1e-13, "{nx} x {ny}");
            }
        }
    }

    #[test]
    fn real_transforms_do_not_depend_on_the_number_of_threads() {
        let (nx, ny) = (96, 80);
        let x = real_input(nx, ny);
        let run = || {
            let fft = RealFft2::new(nx, ny);
            let mut half = fft.forward(|j, row| row.copy_from_slice(&x[j * nx..(j + 1) * nx]));
            let sums = fft.forward_fold(
                |j, row| row.copy_from_slice(&x[j * nx..(j + 1) * nx]),
                || 0.0,
                |acc: &mut f64, _, col| *acc += col.iter().map(|c| c.norm_sqr()).sum::<f64>(),
            );
            fft.inverse_columns(&mut half, |_, _| ());
            let mut y = vec![0.0; nx * ny];
            fft.inverse_rows(&half, &mut y, 1.0);
            (sums, y)
        };
        let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
        assert_eq!(pool(1).install(run), pool(3).install(run));
    }
}
