//! Statistics of a height map, generated or measured (appendix B.1): the discrete PSD
//! (B.1.8)-(B.1.9), the spectral moments taken from the map directly.
//!
//! A generated map is one period of a periodic surface ([`HeightMap::periodic`]) and is
//! transformed as it is. A measured map is a finite patch: its periodic continuation jumps at
//! the edges, and a plain FFT spreads that jump over all wavenumbers, where the weights q², q⁴
//! of m2, m4 (and so Nayak's α, η (3.9) and a (3.16) fit) make it dominate. Such a map is
//! multiplied by a separable Hann window w before the transform (after the window-weighted mean
//! is removed) and the periodogram is divided by mean(w²), so that Σ p estimates σ_rms². The window
//! itself adds the known amounts m0⟨j²⟩ and 4·(Σ p q²)⟨j²⟩ + m0⟨j⁴⟩ (moments of the window's
//! spectrum |W(j)|²) to the expected Σ p q², Σ p q⁴; [`moments_of_map`] subtracts them.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use super::generate::wavenumber;
use super::height_map::HeightMap;
use super::spectrum::Moments;
use crate::numerics::fft::{Direction, RealFft2, fft2};

/// The periodic Hann window w_i = sin²(πi/n), i = 0..n: its DFT has three bins, 1/2 at 0 and
/// −1/4 at ±1, so it smears a Fourier bin over its two neighbours only; mean(w²) = 3/8.
pub fn hann(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| (std::f64::consts::PI * i as f64 / n as f64).sin().powi(2))
        .collect()
}

/// The periodogram p(k, l) = |DFT(z − z̄)(k, l)|² / (nx ny)² (row-major like the map), the share
/// of the variance in each Fourier bin: Σ p = σ_rms² (Parseval).
///
/// A non-periodic map ([`HeightMap::periodic`] false) is windowed first: p = |DFT(w·(z −
/// z̄_w))|² / ((nx ny)² mean(w²)), w the separable [`hann`] window and z̄_w the window-weighted
/// mean, so that Σ p estimates σ_rms² (in expectation; it is the variance of the map's centre,
/// where the window is large) without the leakage of the edge jump.
pub fn periodogram(map: &HeightMap) -> Vec<f64> {
    let (nx, ny) = (map.nx, map.ny);
    let rows = TransformRows::new(map);
    let fft = RealFft2::new(nx, ny);
    let half: Vec<f64> = fft
        .forward_fold(
            |j, row| rows.fill(j, row),
            Vec::new,
            |acc: &mut Vec<f64>, _, col| acc.extend(col.iter().map(|c| c.norm_sqr() * rows.inv_norm)),
        )
        .concat();
    // The other columns mirror the stored ones: p(k, l) = p(nx − k, ny − l).
    let hx = fft.half_columns();
    let mut p = vec![0.0; nx * ny];
    p.par_chunks_mut(nx).enumerate().for_each(|(ky, row)| {
        for (kx, v) in row.iter_mut().enumerate() {
            *v = if kx < hx {
                half[kx * ny + ky]
            } else {
                half[(nx - kx) * ny + (ny - ky) % ny]
            };
        }
    });
    p
}

/// The rows of a map as the analysis transforms them ([`periodogram`]): mean-free for a periodic
/// map; for a patch, w·(z − z̄_w) with the separable [`hann`] window w and the window-weighted
/// mean z̄_w. `inv_norm` turns |DFT|² into the periodogram: 1/((nx ny)² mean(w²)), w = 1 for
/// a periodic map.
struct TransformRows<'a> {
    map: &'a HeightMap,
    mean: f64,
    window: Option<(Vec<f64>, Vec<f64>)>,
    inv_norm: f64,
}

impl<'a> TransformRows<'a> {
    fn new(map: &'a HeightMap) -> Self {
        let (nx, ny) = (map.nx, map.ny);
        let norm = ((nx * ny) as f64).powi(2);
        // Row sums in parallel, added in row order: independent of the number of threads.
        let row_sums = |weight: &(dyn Fn(&[f64]) -> f64 + Sync)| -> Vec<f64> {
            map.z.par_chunks(nx).map(weight).collect()
        };
        if map.periodic {
            let mean = row_sums(&|row| row.iter().sum()).iter().sum::<f64>() / (nx * ny) as f64;
            return Self {
                map,
                mean,
                window: None,
                inv_norm: 1.0 / norm,
            };
        }
        let (wx, wy) = (hann(nx), hann(ny));
        let sw: f64 = wx.iter().sum::<f64>() * wy.iter().sum::<f64>();
        let mean_w = row_sums(&|row| row.iter().zip(&wx).map(|(z, a)| a * z).sum())
            .iter()
            .zip(&wy)
            .map(|(s, b)| b * s)
            .sum::<f64>()
            / sw;
        let w2 =
            wx.iter().map(|a| a * a).sum::<f64>() * wy.iter().map(|b| b * b).sum::<f64>() / (nx * ny) as f64;
        Self {
            map,
            mean: mean_w,
            window: Some((wx, wy)),
            inv_norm: 1.0 / (norm * w2),
        }
    }

    /// Row `j` as transformed.
    fn fill(&self, j: usize, row: &mut [f64]) {
        let nx = self.map.nx;
        let z = &self.map.z[j * nx..(j + 1) * nx];
        match &self.window {
            None => row.iter_mut().zip(z).for_each(|(r, v)| *r = v - self.mean),
            Some((wx, wy)) => {
                let b = wy[j];
                for ((r, v), a) in row.iter_mut().zip(z).zip(wx) {
                    *r = (v - self.mean) * a * b;
                }
            }
        }
    }
}

/// The discrete 2D PSD C̃(q_k, q_l) [m⁴] of (B.1.8)-(B.1.9), in the convention of (3.8)
/// (divided by 4π², so that Σ C̃ Δq_x Δq_y = σ_rms²): C̃ = |Z|²/(4π² L1 L2),
/// Z = Δx Δy Σ z e^{-2πi(mk/N1 + nl/N2)}. Row-major like the map, bins at q = 2πk/L with k
/// signed ([`wavenumber`]). Windowed for a non-periodic map, as [`periodogram`].
pub fn psd_2d(map: &HeightMap) -> Vec<f64> {
    // |Z|² = (Δx Δy)² |DFT|² = (lx ly)² p, so C̃ = lx ly p / (4π²).
    let s = map.lx * map.ly / (4.0 * std::f64::consts::PI.powi(2));
    periodogram(map).into_iter().map(|p| p * s).collect()
}

/// Spectral moments of a height map taken directly from its Fourier coefficients (spectral
/// derivatives of the periodic band-limited interpolant), averaged over directions so that they
/// estimate the isotropic m_n of (3.8):
/// m0 = Σ p, m2 = ½ Σ p q² = ½⟨|∇z|²⟩, m4 = ⅜ Σ p q⁴ = ⅜⟨(∇²z)²⟩, p the [`periodogram`].
///
/// For a non-periodic (windowed) map the window's contribution is subtracted (expectation for a
/// stationary surface, exact for the Hann window's three-bin spectrum): with ⟨j²⟩, ⟨j⁴⟩ the
/// moments of |W|², Σ p q² − m0⟨j²⟩ and Σ p q⁴ − 4 s2 ⟨j²⟩ − m0 ⟨j⁴⟩ (s2 the corrected Σ p q²).
/// m0 of such a map is its plain variance about the mean, which needs no periodicity and uses
/// the whole map (the windowed Σ p is the variance of the map's centre: with a red spectrum it
/// scatters more, while m2 and m4, set by short wavelengths, are local).
pub fn moments_of_map(map: &HeightMap) -> Moments {
    spectrum_sums(map, false).0
}

/// [`moments_of_map`] from a periodogram already computed.
pub fn moments_of_periodogram(map: &HeightMap, p: &[f64]) -> Moments {
    let (nx, ny) = (map.nx, map.ny);
    let (qx2, qy2) = axis_wavenumbers_squared(map);
    // Per-row sums in parallel, added in row order: independent of the number of threads.
    let rows: Vec<(f64, f64, f64)> = p
        .par_chunks(nx)
        .enumerate()
        .map(|(l, row)| {
            let mut acc = (0.0, 0.0, 0.0);
            for (k, &pk) in row.iter().enumerate() {
                if k == 0 && l == 0 {
                    continue;
                }
                let q2 = qx2[k] + qy2[l];
                acc.0 += pk;
                acc.1 += pk * q2;
                acc.2 += pk * q2 * q2;
            }
            acc
        })
        .collect();
    debug_assert_eq!(rows.len(), ny);
    let (m0, s2, s4) = rows
        .into_iter()
        .fold((0.0, 0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
    moments_from_sums(map, m0, s2, s4)
}

/// The moments from the sums Σ p, Σ p q², Σ p q⁴ over the periodogram (the DC bin left out),
/// with the window's contribution removed for a non-periodic map ([`moments_of_map`]).
fn moments_from_sums(map: &HeightMap, m0: f64, mut s2: f64, mut s4: f64) -> Moments {
    if !map.periodic {
        let (j2, j4) = hann_spectrum_moments(map);
        s2 -= m0 * j2;
        s4 -= 4.0 * s2 * j2 + m0 * j4;
        let mean = map.mean();
        let var = map.z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / map.z.len() as f64;
        return Moments {
            m0: var,
            m2: 0.5 * s2,
            m4: 0.375 * s4,
        };
    }
    Moments {
        m0,
        m2: 0.5 * s2,
        m4: 0.375 * s4,
    }
}

/// ⟨|j|²⟩ and ⟨|j|⁴⟩ [1/m², 1/m⁴] over the normalised power spectrum |W(j)|² of the separable
/// [`hann`] window of `map`: per axis |W|² ∝ (1, 4, 1) at j = −Δq, 0, Δq (Δq = 2π/L), so
/// ⟨j_x²⟩ = a_x = Δq_x²/3 and ⟨j_x⁴⟩ = 3a_x²; ⟨|j|⁴⟩ = 3a_x² + 2a_x a_y + 3a_y².
fn hann_spectrum_moments(map: &HeightMap) -> (f64, f64) {
    let tau = 2.0 * std::f64::consts::PI;
    let (ax, ay) = ((tau / map.lx).powi(2) / 3.0, (tau / map.ly).powi(2) / 3.0);
    (ax + ay, 3.0 * ax * ax + 2.0 * ax * ay + 3.0 * ay * ay)
}

/// q_k² and q_l² of the DFT bins along x and y (signed indices, as [`wavenumber`]).
fn axis_wavenumbers_squared(map: &HeightMap) -> (Vec<f64>, Vec<f64>) {
    let axis = |n: usize, l: f64| -> Vec<f64> {
        (0..n)
            .map(|k| (2.0 * std::f64::consts::PI * crate::numerics::fft::signed_index(k, n) / l).powi(2))
            .collect()
    };
    (axis(map.nx, map.lx), axis(map.ny, map.ly))
}

/// The isotropic PSD C̃^iso(q) of (B.1.10) by radial averaging of [`psd_2d`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RadialPsd {
    /// Mean wavenumber of each ring [1/m].
    pub q: Vec<f64>,
    /// Mean C̃ over the ring [m⁴], convention of (3.8).
    pub c: Vec<f64>,
    /// Number of Fourier bins in the ring.
    pub count: Vec<usize>,
}

/// The isotropic PSD (B.1.10): C̃ averaged over rings of width Δq = 2π/max(L1, L2) centred on
/// multiples of Δq, from Δq up to the Nyquist wavenumber π/max(Δx, Δy) (the largest full
/// circle on the grid). Empty rings are left out.
pub fn radial_psd(map: &HeightMap) -> RadialPsd {
    spectrum_sums(map, true).1
}

/// The isotropic PSD (B.1.10) ([`radial_psd`]) and the spectral moments (3.8)
/// ([`moments_of_map`]) from one Fourier transform of the map.
pub fn radial_psd_and_moments(map: &HeightMap) -> (RadialPsd, Moments) {
    let (m, psd) = spectrum_sums(map, true);
    (psd, m)
}

/// The rings of the isotropic PSD (B.1.10) on the grid of `map`: width Δq = 2π/max(L1, L2),
/// centred on multiples of Δq up to the Nyquist wavenumber; (Δq, number of rings).
fn rings(map: &HeightMap) -> (f64, usize) {
    let dq = 2.0 * std::f64::consts::PI / map.lx.max(map.ly);
    let q_nyq = std::f64::consts::PI / map.dx().max(map.dy());
    (dq, (q_nyq / dq).floor() as usize)
}

/// The ring of wavenumber q ≥ 0: the nearest multiple of Δq, q/Δq rounded half up (the same
/// expression wherever rings are formed, so that bins fall into the same rings).
fn ring_of(q: f64, dq: f64) -> usize {
    (q / dq + 0.5) as usize
}

/// Sums over the periodogram of one block of spectrum columns: Σ p, Σ p q², Σ p q⁴ and, per
/// ring, Σ q, Σ p and the number of bins (each over the whole spectrum, a stored column
/// standing for its mirror image too).
struct SpectrumSums {
    moments: [f64; 3],
    sum_q: Vec<f64>,
    sum_p: Vec<f64>,
    count: Vec<usize>,
}

/// The spectral moments ([`moments_of_map`]) and, if `with_rings`, the isotropic PSD
/// ([`radial_psd`]; empty otherwise) in one pass over the half spectrum of the map's real
/// Fourier transform, which is never stored whole.
fn spectrum_sums(map: &HeightMap, with_rings: bool) -> (Moments, RadialPsd) {
    let rows = TransformRows::new(map);
    let fft = RealFft2::new(map.nx, map.ny);
    let (qx2, qy2) = axis_wavenumbers_squared(map);
    let (dq, n_rings) = rings(map);
    let n_bins = if with_rings { n_rings + 1 } else { 0 };
    let blocks = fft.forward_fold(
        |j, row| rows.fill(j, row),
        || SpectrumSums {
            moments: [0.0; 3],
            sum_q: vec![0.0; n_bins],
            sum_p: vec![0.0; n_bins],
            count: vec![0; n_bins],
        },
        |acc, kx, col| {
            let w = fft.column_weight(kx);
            let (mut s0, mut s2, mut s4) = (0.0, 0.0, 0.0);
            for (ky, c) in col.iter().enumerate() {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let p = c.norm_sqr() * rows.inv_norm;
                let q2 = qx2[kx] + qy2[ky];
                s0 += p;
                s2 += p * q2;
                s4 += p * q2 * q2;
                if with_rings {
                    let q = q2.sqrt();
                    let ring = ring_of(q, dq);
                    if ring == 0 || ring > n_rings {
                        continue;
                    }
                    acc.sum_q[ring] += w * q;
                    acc.sum_p[ring] += w * p;
                    acc.count[ring] += w as usize;
                }
            }
            acc.moments[0] += w * s0;
            acc.moments[1] += w * s2;
            acc.moments[2] += w * s4;
        },
    );
    // Blocks added in order: independent of the number of threads.
    let mut total = SpectrumSums {
        moments: [0.0; 3],
        sum_q: vec![0.0; n_bins],
        sum_p: vec![0.0; n_bins],
        count: vec![0; n_bins],
    };
    for b in &blocks {
        for i in 0..3 {
            total.moments[i] += b.moments[i];
        }
        for r in 0..n_bins {
            total.sum_q[r] += b.sum_q[r];
            total.sum_p[r] += b.sum_p[r];
            total.count[r] += b.count[r];
        }
    }
    let [m0, s2, s4] = total.moments;
    let moments = moments_from_sums(map, m0, s2, s4);
    // C̃ = lx ly p / (4π²), as psd_2d.
    let scale = map.lx * map.ly / (4.0 * std::f64::consts::PI.powi(2));
    let mut psd = RadialPsd {
        q: Vec::new(),
        c: Vec::new(),
        count: Vec::new(),
    };
    for r in 1..n_bins {
        if total.count[r] > 0 {
            let n = total.count[r] as f64;
            psd.q.push(total.sum_q[r] / n);
            psd.c.push(scale * total.sum_p[r] / n);
            psd.count.push(total.count[r]);
        }
    }
    (moments, psd)
}

/// [`radial_psd`] of a 2D PSD already computed.
pub fn radial_average(map: &HeightMap, c2d: &[f64]) -> RadialPsd {
    let nx = map.nx;
    let (dq, n_rings) = rings(map);
    let (qx2, qy2) = axis_wavenumbers_squared(map);
    // Partial sums over fixed blocks of rows in parallel, added in block order: the result does
    // not depend on the number of threads.
    const ROWS: usize = 32;
    let partial: Vec<(Vec<f64>, Vec<f64>, Vec<usize>)> = c2d
        .par_chunks(nx * ROWS)
        .enumerate()
        .map(|(b, block)| {
            let mut sum_q = vec![0.0; n_rings + 1];
            let mut sum_c = vec![0.0; n_rings + 1];
            let mut count = vec![0usize; n_rings + 1];
            for (dl, row) in block.chunks_exact(nx).enumerate() {
                let l = b * ROWS + dl;
                for (k, &c) in row.iter().enumerate() {
                    let q = (qx2[k] + qy2[l]).sqrt();
                    let ring = ring_of(q, dq);
                    if ring == 0 || ring > n_rings {
                        continue;
                    }
                    sum_q[ring] += q;
                    sum_c[ring] += c;
                    count[ring] += 1;
                }
            }
            (sum_q, sum_c, count)
        })
        .collect();
    let mut sum_q = vec![0.0; n_rings + 1];
    let mut sum_c = vec![0.0; n_rings + 1];
    let mut count = vec![0usize; n_rings + 1];
    for (q, c, n) in &partial {
        for r in 0..=n_rings {
            sum_q[r] += q[r];
            sum_c[r] += c[r];
            count[r] += n[r];
        }
    }
    let mut out = RadialPsd {
        q: Vec::new(),
        c: Vec::new(),
        count: Vec::new(),
    };
    for r in 1..=n_rings {
        if count[r] > 0 {
            out.q.push(sum_q[r] / count[r] as f64);
            out.c.push(sum_c[r] / count[r] as f64);
            out.count.push(count[r]);
        }
    }
    out
}

/// The autocorrelation R(k Δx, l Δy) = (1/N) Σ z(i, j) z(i + k, j + l) of the mean-free map
/// (periodic, the discrete (B.1.2)/(C.1.9)), row-major with lags k, l ≥ 0 wrapping; R(0, 0) = σ².
/// For a non-periodic map it is the circular autocorrelation of the windowed map of
/// [`periodogram`] (scaled so that R(0, 0) estimates σ²), trustworthy for lags well below the
/// window's half-width.
pub fn autocorrelation(map: &HeightMap) -> Vec<f64> {
    let p = periodogram(map);
    let mut data: Vec<Complex64> = p.into_iter().map(|v| Complex64::new(v, 0.0)).collect();
    // R = Σ p e^{+2πi…}: the inverse transform without its 1/N.
    fft2(&mut data, map.nx, map.ny, Direction::Inverse);
    let n = (map.nx * map.ny) as f64;
    data.into_iter().map(|c| c.re * n).collect()
}

/// Local maxima of a map: points higher than their 8 neighbours, section B.4 (neighbours wrap
/// around for a periodic map; a non-periodic map's border rows and columns, whose neighbours are
/// partly unknown, are not candidates). Returned as (column, row) indices.
pub fn peaks(map: &HeightMap) -> Vec<(usize, usize)> {
    let (nx, ny) = (map.nx, map.ny);
    let (i0, j0) = if map.periodic { (0, 0) } else { (1, 1) };
    (j0..ny - j0)
        .into_par_iter()
        .flat_map_iter(move |j| {
            (i0..nx - i0).filter_map(move |i| {
                let z = map.at(i, j);
                for dj in [ny - 1, 0, 1] {
                    for di in [nx - 1, 0, 1] {
                        if di == 0 && dj == 0 {
                            continue;
                        }
                        if map.at((i + di) % nx, (j + dj) % ny) >= z {
                            return None;
                        }
                    }
                }
                Some((i, j))
            })
        })
        .collect()
}

/// Peak statistics of section B.4.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PeakStatistics {
    /// Number of 8-neighbour local maxima.
    pub count: usize,
    /// Peaks per unit area [1/m²] (compare with Nayak's η (3.9)); for a non-periodic map, per
    /// area of the interior (nx − 2)(ny − 2) pixels where peaks are counted.
    pub density: f64,
    /// Mean distance from each peak to its nearest neighbour [m] (periodic distance for a
    /// periodic map); NaN with < 2 peaks.
    pub mean_nearest_distance: f64,
}

/// Count the peaks of a map and the mean distance from each to its nearest neighbour
/// (section B.4).
///
/// The nearest-neighbour search runs on a cell list laid over the pixel grid (at most one
/// cell per pixel in each direction, cells of about one peak each and as square as the grid
/// allows), and distances are taken in pixel offsets scaled by the larger pixel side, so the
/// cost depends on the grid and the peaks only, never on the physical lengths: a map of
/// 1e-9 m by 1e9 m or of pixels of 1e-170 m costs what a square map of the same grid costs.
/// With lengths so extreme that the density or the distance leaves the f64 range, those
/// fields are not finite (the callers report that as an error).
pub fn peak_statistics(map: &HeightMap) -> PeakStatistics {
    let pk = peaks(map);
    let n = pk.len();
    let (nx, ny) = (map.nx, map.ny);
    // Counted area in pixels times the pixel area, multiplied in an order that cannot
    // overflow before the result does.
    let (ix, iy) = if map.periodic { (nx, ny) } else { (nx - 2, ny - 2) };
    let area = (ix as f64 * map.dx()) * (iy as f64 * map.dy());
    let density = n as f64 / area;
    if n < 2 {
        return PeakStatistics {
            count: n,
            density,
            mean_nearest_distance: f64::NAN,
        };
    }
    let mean_scaled = mean_nearest_scaled(&pk, nx, ny, map.dx(), map.dy(), map.periodic);
    PeakStatistics {
        count: n,
        density,
        mean_nearest_distance: mean_scaled * map.dx().max(map.dy()),
    }
}

/// Mean nearest-neighbour distance of the points `pk` (column, row) of an `nx × ny` grid with
/// pixel sides `dx`, `dy`, in units of max(dx, dy) (periodic distances when `wrap`).
fn mean_nearest_scaled(pk: &[(usize, usize)], nx: usize, ny: usize, dx: f64, dy: f64, wrap: bool) -> f64 {
    let n = pk.len();
    let s = dx.max(dy);
    // Pixel sides relative to the larger one: in (0, 1], and exactly 1 for the larger.
    let (ex, ey) = (dx / s, dy / s);
    // Cells of about one peak each, as square as the grid allows: cx/cy = (nx ex)/(ny ey), taken
    // through logarithms so that no ratio of lengths overflows, and at most one per pixel.
    let ln_aspect = (nx as f64).ln() + ex.ln() - (ny as f64).ln() - ey.ln();
    let ln_n = (n as f64).ln();
    let cells_along =
        |ln: f64, max: usize| -> usize { (0.5 * ln).exp().round().clamp(1.0, max as f64) as usize };
    let cx = cells_along(ln_n + ln_aspect, nx);
    let cy = cells_along(ln_n - ln_aspect, ny);
    let cell_of = |i: usize, j: usize| (i * cx / nx, j * cy / ny);
    let mut cells: Vec<Vec<usize>> = vec![Vec::new(); cx * cy];
    for (k, &(i, j)) in pk.iter().enumerate() {
        let (a, b) = cell_of(i, j);
        cells[b * cx + a].push(k);
    }
    // A point whose cell is r > 0 cells away along x is more than (r − 1)·nx/cx pixels away, so
    // every point outside a rectangle of ra × rb cells around a peak's cell is farther than
    // ra·wx along x or rb·wy along y.
    let (wx, wy) = (nx as f64 / cx as f64 * ex, ny as f64 / cy as f64 * ey);
    let offset = |d: usize, n: usize| if wrap { d.min(n - d) } else { d };
    let total: f64 = (0..n)
        .into_par_iter()
        .map(|k| {
            let (i, j) = pk[k];
            let (a, b) = cell_of(i, j);
            let visit = |ca: isize, cb: isize| -> f64 {
                let mut best = f64::INFINITY;
                if !wrap && (ca < 0 || cb < 0 || ca >= cx as isize || cb >= cy as isize) {
                    return best;
                }
                let ca = ca.rem_euclid(cx as isize) as usize;
                let cb = cb.rem_euclid(cy as isize) as usize;
                for &o in &cells[cb * cx + ca] {
                    if o == k {
                        continue;
                    }
                    let (io, jo) = pk[o];
                    let di = offset(io.abs_diff(i), nx) as f64 * ex;
                    let dj = offset(jo.abs_diff(j), ny) as f64 * ey;
                    best = best.min(di.hypot(dj));
                }
                best
            };
            let (a, b) = (a as isize, b as isize);
            // Every cell is examined once the rectangle spans the grid (both ways round when
            // the grid wraps).
            let spans = |r: isize, c: usize, at: isize| {
                if wrap {
                    2 * r + 1 >= c as isize
                } else {
                    at - r <= 0 && at + r >= c as isize - 1
                }
            };
            let (mut ra, mut rb) = (0isize, 0isize);
            let mut best = visit(a, b);
            loop {
                let (sx, sy) = (spans(ra, cx, a), spans(rb, cy, b));
                if sx && sy {
                    break;
                }
                // Points outside the rectangle are farther than this along x or along y.
                let reach_x = if sx { f64::INFINITY } else { ra as f64 * wx };
                let reach_y = if sy { f64::INFINITY } else { rb as f64 * wy };
                if best <= reach_x.min(reach_y) {
                    break;
                }
                if reach_x <= reach_y {
                    ra += 1;
                    for db in -rb..=rb {
                        best = best.min(visit(a - ra, b + db));
                        if !(wrap && 2 * ra == cx as isize) {
                            best = best.min(visit(a + ra, b + db));
                        }
                    }
                } else {
                    rb += 1;
                    for da in -ra..=ra {
                        best = best.min(visit(a + da, b - rb));
                        if !(wrap && 2 * rb == cy as isize) {
                            best = best.min(visit(a + da, b + rb));
                        }
                    }
                }
            }
            best
        })
        .sum();
    total / n as f64
}

/// An analytic PSD averaged over the same rings as [`radial_psd`] of `map`: the expectation of
/// the estimate. The rings are Δq wide, so where C changes fast on the scale Δq the ring average
/// exceeds C(q̄) (C is convex there); comparing with this removes that bias.
pub fn radial_model(map: &HeightMap, psd: impl Fn(f64) -> f64 + Sync) -> RadialPsd {
    let (nx, ny, lx, ly) = (map.nx, map.ny, map.lx, map.ly);
    let c2d: Vec<f64> = (0..nx * ny)
        .into_par_iter()
        .map(|k| psd(wavenumber(k % nx, k / nx, nx, ny, lx, ly)))
        .collect();
    radial_average(map, &c2d)
}
