//! Random rough surfaces with a Gaussian height distribution and a prescribed isotropic PSD, by
//! filtering Gaussian white noise (appendix C.1, the method of Hu and Tonder, done in Fourier
//! space): steps 1-6 of C.1 become z = F⁻¹[√C(|q|) · F[ζ]], then the heights are shifted to zero
//! mean and scaled to the requested σ_rms exactly.
//!
//! The noise comes from ChaCha8 seeded with a `u64` and the standard normal of `rand_distr`, so
//! a seed gives the same surface on every platform (up to the last bits of the FFT's rounding).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use super::height_map::HeightMap;
use super::spectrum::Spectrum;
use crate::error::{Error, Result};
use crate::numerics::fft::{Direction, fft2, signed_index};

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
/// # Errors
/// [`Error::InvalidParameter`] for an invalid spectrum or grid, or a spectrum with no power
/// inside the grid's band.
pub fn generate(spectrum: &Spectrum, nx: usize, ny: usize, lx: f64, ly: f64, seed: u64) -> Result<HeightMap> {
    let psd = spectrum.prepare()?;
    // Validates the grid before any work.
    HeightMap::new(nx, ny, lx, ly, vec![0.0; nx * ny])?;
    let noise = white_noise(nx * ny, seed);
    let mut data: Vec<Complex64> = noise.into_iter().map(|v| Complex64::new(v, 0.0)).collect();
    fft2(&mut data, nx, ny, Direction::Forward);
    // |q| depends on |signed k|, |signed l| only: the filter H = C^(1/2) (C.1.12) on one quadrant
    // of (hx × hy) bins serves all four (bit for bit the same values).
    let (hx, hy) = (nx / 2 + 1, ny / 2 + 1);
    let filter: Vec<f64> = (0..hx * hy)
        .into_par_iter()
        .map(|i| {
            let (k, l) = (i % hx, i / hx);
            if k == 0 && l == 0 {
                0.0
            } else {
                psd.psd(wavenumber(k, l, nx, ny, lx, ly)).sqrt()
            }
        })
        .collect();
    data.par_chunks_mut(nx).enumerate().for_each(|(l, row)| {
        let frow = &filter[l.min(ny - l) * hx..][..hx];
        for (k, v) in row.iter_mut().enumerate() {
            *v *= frow[k.min(nx - k)];
        }
    });
    fft2(&mut data, nx, ny, Direction::Inverse);
    let mut z: Vec<f64> = data.into_iter().map(|c| c.re).collect();
    let mut map = HeightMap {
        nx,
        ny,
        lx,
        ly,
        z: std::mem::take(&mut z),
        periodic: true,
    };
    map.remove_mean();
    let rms = map.rms();
    if !(rms > 0.0 && rms.is_finite()) {
        return Err(Error::invalid(
            "spectrum",
            format!("{spectrum:?}"),
            "has no power inside the grid's wavenumber band",
        ));
    }
    map.scale(spectrum.rms() / rms);
    Ok(map)
}
