//! Statistics of a height map, generated or measured (appendix B.1): the discrete PSD
//! (B.1.8)-(B.1.9), the spectral moments taken from the map directly.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use super::generate::wavenumber;
use super::height_map::HeightMap;
use super::spectrum::Moments;
use crate::numerics::fft::{Direction, fft2};

/// The periodogram p(k, l) = |DFT(z − z̄)(k, l)|² / (nx ny)² (row-major like the map), the share
/// of the variance in each Fourier bin: Σ p = σ_rms² (Parseval).
pub fn periodogram(map: &HeightMap) -> Vec<f64> {
    let mean = map.mean();
    let mut data: Vec<Complex64> = map.z.iter().map(|v| Complex64::new(v - mean, 0.0)).collect();
    fft2(&mut data, map.nx, map.ny, Direction::Forward);
    let n2 = ((map.nx * map.ny) as f64).powi(2);
    data.into_par_iter().map(|c| c.norm_sqr() / n2).collect()
}

/// The discrete 2D PSD C̃(q_k, q_l) [m⁴] of (B.1.8)-(B.1.9), in the convention of (3.8)
/// (divided by 4π², so that Σ C̃ Δq_x Δq_y = σ_rms²): C̃ = |Z|²/(4π² L1 L2),
/// Z = Δx Δy Σ z e^{-2πi(mk/N1 + nl/N2)}. Row-major like the map, bins at q = 2πk/L with k
/// signed ([`wavenumber`]).
pub fn psd_2d(map: &HeightMap) -> Vec<f64> {
    // |Z|² = (Δx Δy)² |DFT|² = (lx ly)² p, so C̃ = lx ly p / (4π²).
    let s = map.lx * map.ly / (4.0 * std::f64::consts::PI.powi(2));
    periodogram(map).into_iter().map(|p| p * s).collect()
}

/// Spectral moments of a height map taken directly from its Fourier coefficients (spectral
/// derivatives of the periodic band-limited interpolant), averaged over directions so that they
/// estimate the isotropic m_n of (3.8):
/// m0 = Σ p, m2 = ½ Σ p q² = ½⟨|∇z|²⟩, m4 = ⅜ Σ p q⁴ = ⅜⟨(∇²z)²⟩, p the [`periodogram`].
pub fn moments_of_map(map: &HeightMap) -> Moments {
    moments_of_periodogram(map, &periodogram(map))
}

/// [`moments_of_map`] from a periodogram already computed.
pub fn moments_of_periodogram(map: &HeightMap, p: &[f64]) -> Moments {
    let (nx, ny, lx, ly) = (map.nx, map.ny, map.lx, map.ly);
    let (m0, s2, s4) = p
        .par_chunks(nx)
        .enumerate()
        .map(|(l, row)| {
            let mut acc = (0.0, 0.0, 0.0);
            for (k, &pk) in row.iter().enumerate() {
                if k == 0 && l == 0 {
                    continue;
                }
                let q2 = wavenumber(k, l, nx, ny, lx, ly).powi(2);
                acc.0 += pk;
                acc.1 += pk * q2;
                acc.2 += pk * q2 * q2;
            }
            acc
        })
        .reduce(|| (0.0, 0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
    Moments {
        m0,
        m2: 0.5 * s2,
        m4: 0.375 * s4,
    }
}
