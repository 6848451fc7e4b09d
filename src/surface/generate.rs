//! Random rough surfaces with a Gaussian height distribution and a prescribed isotropic PSD, by
//! filtering Gaussian white noise (appendix C.1, the method of Hu and Tonder, done in Fourier
//! space): steps 1-6 of C.1 become z = F⁻¹[√C(|q|) · F[ζ]], then the heights are scaled to the
//! requested σ_rms exactly.
//!
//! The noise comes from ChaCha8 seeded with a `u64` and the standard normal of `rand_distr`, so
//! a seed gives the same surface on every platform and for any number of threads (up to the
//! last bits of the FFT's rounding, which may differ between SIMD paths). The transforms are
//! real-to-complex ([`RealFft2`]); the filter H of a spectrum and grid is kept for the next
//! surface with the same shape (sample averages draw many).

use std::sync::{Arc, Mutex, PoisonError};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

use super::height_map::HeightMap;
use super::spectrum::Spectrum;
use crate::error::{Error, Result};
use crate::numerics::fft::{RealFft2, recycle_buffer, signed_index};

/// Wavenumber |q| [1/m] of DFT bin (k, l) of an `nx × ny` grid of size `lx × ly`:
/// q_k = 2πk/L with signed k, as in (B.1.9).
pub fn wavenumber(k: usize, l: usize, nx: usize, ny: usize, lx: f64, ly: f64) -> f64 {
    let qx = 2.0 * std::f64::consts::PI * signed_index(k, nx) / lx;
    let qy = 2.0 * std::f64::consts::PI * signed_index(l, ny) / ly;
    qx.hypot(qy)
}

/// Gaussian white noise of unit variance, `n` values, from ChaCha8 seeded with `seed`.
pub fn white_noise(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
}

/// A random rough surface of `nx × ny` points on `lx × ly` [m] with the isotropic PSD of
/// `spectrum`, a Gaussian height distribution (C.1.4), zero mean and RMS height exactly
/// `spectrum.rms()` (appendix C.1, steps 1-6, as a filter in Fourier space).
///
/// Wavelengths outside the grid's band (longer than the box, shorter than two pixels) are absent,
/// so the PSD of the result is the spectrum's shape inside the band, scaled by σ²/m0(band).
///
/// The filtered half spectrum Y = H·F[ζ], with Y(0, 0) = 0, gives the mean-free surface, whose
/// mean square is Σ |Y|² over the whole spectrum (Parseval), so the scale to σ_rms is applied in
/// the inverse transform's last pass.
///
/// # Errors
/// [`Error::InvalidParameter`] for an invalid spectrum or grid, or a spectrum with no power
/// inside the grid's band.
pub fn generate(spectrum: &Spectrum, nx: usize, ny: usize, lx: f64, ly: f64, seed: u64) -> Result<HeightMap> {
    let psd = spectrum.prepare()?;
    HeightMap::validate_grid(nx, ny, lx, ly)?;
    let fft = RealFft2::new(nx, ny);
    // The noise is one sequential stream; the filter is evaluated on the other threads meanwhile.
    let (mut z, filter) = rayon::join(
        || white_noise(nx * ny, seed),
        || Filter::cached(spectrum, &fft, nx, ny, lx, ly, |q| psd.sqrt_psd(q)),
    );
    let mut y = fft.forward(|j, row| row.copy_from_slice(&z[j * nx..(j + 1) * nx]));
    let power: Vec<f64> = fft.inverse_columns(&mut y, |kx, col| {
        let mut sum = 0.0;
        for (ky, v) in col.iter_mut().enumerate() {
            *v *= filter.at(kx, ky.min(ny - ky));
            sum += v.norm_sqr();
        }
        fft.column_weight(kx) * sum
    });
    let mean_square: f64 = power.iter().sum();
    if !(mean_square > 0.0 && mean_square.is_finite()) {
        recycle_buffer(y);
        return Err(Error::invalid(
            "spectrum",
            format!("{spectrum:?}"),
            "has no power inside the grid's wavenumber band",
        ));
    }
    fft.inverse_rows(&y, &mut z, spectrum.rms() / mean_square.sqrt());
    recycle_buffer(y);
    Ok(HeightMap {
        nx,
        ny,
        lx,
        ly,
        z,
        periodic: true,
    })
}

/// The filter H = C^(1/2) (C.1.12) on the bins (kx, |ky|), kx = 0..hx, |ky| = 0..=ny/2 (|q|
/// depends on |signed ky| only), zero at q = 0. On a square grid (nx = ny, lx = ly) H is
/// symmetric in kx and ky, and only the bins kx ≤ ky are evaluated.
struct Filter {
    /// Row kx holds |ky| = first[kx].. (square grid: kx..; else 0..).
    rows: Vec<Vec<f64>>,
    square: bool,
}

/// What a filter depends on: the spectrum and the grid. Its σ_rms cancels in the scaling, but
/// not where the filter's values overflow or underflow (σ_rms = 1e300 or 1e-300), so it is part
/// of the key: such a filter must not serve the next surface of the same shape.
type FilterKey = (Spectrum, usize, usize, f64, f64);

impl Filter {
    /// The filter of `spectrum` on the grid, from the one-entry cache when the last surface had
    /// the same spectrum and grid (a sample average draws many surfaces of one kind).
    fn cached(
        spectrum: &Spectrum,
        fft: &RealFft2,
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        h: impl Fn(f64) -> f64 + Sync,
    ) -> Arc<Filter> {
        static LAST: Mutex<Option<(FilterKey, Arc<Filter>)>> = Mutex::new(None);
        let key = (*spectrum, nx, ny, lx, ly);
        if let Some((k, f)) = &*LAST.lock().unwrap_or_else(PoisonError::into_inner)
            && *k == key
        {
            return Arc::clone(f);
        }
        let f = Arc::new(Filter::new(fft, nx, ny, lx, ly, h));
        *LAST.lock().unwrap_or_else(PoisonError::into_inner) = Some((key, Arc::clone(&f)));
        f
    }

    fn new(fft: &RealFft2, nx: usize, ny: usize, lx: f64, ly: f64, h: impl Fn(f64) -> f64 + Sync) -> Self {
        let square = nx == ny && lx == ly;
        let hy = ny / 2 + 1;
        let tau = 2.0 * std::f64::consts::PI;
        let rows = (0..fft.half_columns())
            .into_par_iter()
            .map(|kx| {
                let qx = tau * kx as f64 / lx;
                let start = if square { kx } else { 0 };
                (start..hy)
                    .map(|ky| {
                        if kx == 0 && ky == 0 {
                            return 0.0;
                        }
                        let qy = tau * ky as f64 / ly;
                        h((qx * qx + qy * qy).sqrt())
                    })
                    .collect()
            })
            .collect();
        Self { rows, square }
    }

    /// H at (kx, |ky|).
    fn at(&self, kx: usize, ky: usize) -> f64 {
        if self.square {
            let (a, b) = if kx <= ky { (kx, ky) } else { (ky, kx) };
            self.rows[a][b - a]
        } else {
            self.rows[kx][ky]
        }
    }
}
