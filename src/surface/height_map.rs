//! A sampled height map z(x, y) on a rectangular grid (appendix B.1), periodic (a generated
//! surface) or not (a measured scan).

use serde::Serialize;

use crate::error::{Error, Result};

/// Heights [m] on an `nx × ny` grid of physical size `lx × ly` [m], row-major:
/// `z[j*nx + i]` is the height at x = i·lx/nx, y = j·ly/ny.
///
/// `periodic` says whether the map is one period of a periodic surface (the convention of
/// (B.1.8); true for [`crate::surface::generate`]) or a finite patch such as a measured scan
/// (false for [`HeightMap::new`] and the importers). The analysis treats the two differently:
/// a patch is windowed before its Fourier transform and its peaks are counted away from the
/// border (see [`crate::surface::analysis`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeightMap {
    /// Points in x (columns).
    pub nx: usize,
    /// Points in y (rows).
    pub ny: usize,
    /// Period in x [m].
    pub lx: f64,
    /// Period in y [m].
    pub ly: f64,
    /// Heights [m], row-major, `nx * ny` values.
    pub z: Vec<f64>,
    /// One period of a periodic surface (true) or a finite, non-periodic patch (false).
    pub periodic: bool,
}

impl HeightMap {
    /// A validated, non-periodic height map (a finite patch such as a measured scan; set
    /// `periodic` for one period of a periodic surface).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the grid is smaller than 2 × 2, the sizes are not
    /// positive and finite, the data length is not `nx * ny`, or a height is not finite.
    pub fn new(nx: usize, ny: usize, lx: f64, ly: f64, z: Vec<f64>) -> Result<Self> {
        let map = Self {
            nx,
            ny,
            lx,
            ly,
            z,
            periodic: false,
        };
        map.validate()?;
        Ok(map)
    }

    /// Check the invariants listed at [`HeightMap::new`].
    ///
    /// # Errors
    /// As [`HeightMap::new`].
    pub fn validate(&self) -> Result<()> {
        Self::validate_grid(self.nx, self.ny, self.lx, self.ly)?;
        if self.z.len() != self.nx * self.ny {
            return Err(Error::invalid(
                "heights",
                self.z.len(),
                format!("expected nx*ny = {} values", self.nx * self.ny),
            ));
        }
        if let Some(k) = self.z.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "heights",
                self.z[k],
                format!(
                    "height at column {}, row {} is not finite",
                    k % self.nx,
                    k / self.nx
                ),
            ));
        }
        Ok(())
    }

    /// Check a grid before any heights exist: at least 2 × 2 points, sizes positive and finite.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `grid`, `length` or `length-y`.
    pub fn validate_grid(nx: usize, ny: usize, lx: f64, ly: f64) -> Result<()> {
        if nx < 2 || ny < 2 {
            return Err(Error::invalid(
                "grid",
                format!("{nx}x{ny}"),
                "needs at least 2 points in each direction",
            ));
        }
        for (name, v) in [("length", lx), ("length-y", ly)] {
            if !(v > 0.0 && v.is_finite()) {
                return Err(Error::invalid(name, v, "must be positive and finite"));
            }
        }
        if let Some(reason) = size_problem(nx, ny, lx, ly) {
            return Err(Error::invalid(
                "length",
                format!("{} x {}", fmt_g(lx), fmt_g(ly)),
                reason,
            ));
        }
        Ok(())
    }

    /// Grid spacing in x, lx/nx [m].
    pub fn dx(&self) -> f64 {
        self.lx / self.nx as f64
    }

    /// Grid spacing in y, ly/ny [m].
    pub fn dy(&self) -> f64 {
        self.ly / self.ny as f64
    }

    /// Height at column i, row j.
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    /// Mean height [m].
    pub fn mean(&self) -> f64 {
        self.z.iter().sum::<f64>() / self.z.len() as f64
    }

    /// RMS height about the mean [m], the discrete (B.1.1).
    pub fn rms(&self) -> f64 {
        let m = self.mean();
        (self.z.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / self.z.len() as f64).sqrt()
    }

    /// Subtract the mean height, so that the mean plane is z = 0 (section 3.2.2).
    pub fn remove_mean(&mut self) {
        let m = self.mean();
        self.z.iter_mut().for_each(|v| *v -= m);
    }

    /// Subtract the least-squares plane z = a + b x + c y (tilt of a measured map) and the mean.
    pub fn remove_tilt(&mut self) {
        let (nx, ny) = (self.nx as f64, self.ny as f64);
        // Centred coordinates make the normal equations diagonal.
        let xc = |i: usize| i as f64 - 0.5 * (nx - 1.0);
        let yc = |j: usize| j as f64 - 0.5 * (ny - 1.0);
        let (mut sxz, mut syz, mut sxx, mut syy) = (0.0, 0.0, 0.0, 0.0);
        let mean = self.mean();
        for j in 0..self.ny {
            for i in 0..self.nx {
                let z = self.z[j * self.nx + i] - mean;
                sxz += xc(i) * z;
                syz += yc(j) * z;
                sxx += xc(i) * xc(i);
                syy += yc(j) * yc(j);
            }
        }
        let (b, c) = (sxz / sxx, syz / syy);
        for j in 0..self.ny {
            for i in 0..self.nx {
                self.z[j * self.nx + i] -= mean + b * xc(i) + c * yc(j);
            }
        }
    }

    /// Multiply every height by `k`.
    pub fn scale(&mut self, k: f64) {
        self.z.iter_mut().for_each(|v| *v *= k);
    }
}

/// Why a grid of `nx × ny` points and physical size `lx × ly` [m] (positive, finite) cannot be
/// analysed in f64, or `None` when it can: a pixel side so small (below about 1e-77 m) that
/// (2π/Δx)⁴ of the spectral moment m4 overflows, or an area lx·ly that leaves the normal f64 range (the PSD
/// scale and the peak density overflow or vanish).
pub fn size_problem(nx: usize, ny: usize, lx: f64, ly: f64) -> Option<String> {
    let (dx, dy) = (lx / nx as f64, ly / ny as f64);
    // The spectral moment m4 sums q⁴ up to the corner of the Fourier grid, (q_x² + q_y²)² ≤
    // 4 (2π/Δ)⁴ with Δ the smaller pixel side.
    let q = 2.0 * std::f64::consts::PI / dx.min(dy);
    if !(dx >= f64::MIN_POSITIVE && dy >= f64::MIN_POSITIVE && (4.0 * q.powi(4)).is_finite()) {
        return Some(format!(
            "a pixel of {} x {} m is too small: its wavenumbers 2π/Δx to the 4th power leave \
             the f64 range",
            fmt_g(dx),
            fmt_g(dy)
        ));
    }
    let area = lx * ly;
    if !(area.is_finite() && area >= f64::MIN_POSITIVE) {
        return Some(format!(
            "the area {} m x {} m is outside the f64 range",
            fmt_g(lx),
            fmt_g(ly)
        ));
    }
    None
}

/// A number with at most 6 significant digits, for messages.
fn fmt_g(v: f64) -> String {
    crate::params::fmt_sig(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilt_removal_leaves_zero_for_a_plane() {
        let (nx, ny) = (5, 4);
        let z = (0..nx * ny)
            .map(|k| 3.0 + 0.5 * (k % nx) as f64 - 0.25 * (k / nx) as f64)
            .collect();
        let mut m = HeightMap::new(nx, ny, 1.0, 1.0, z).unwrap();
        m.remove_tilt();
        assert!(m.z.iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn bad_maps_are_rejected() {
        assert!(HeightMap::new(1, 4, 1.0, 1.0, vec![0.0; 4]).is_err());
        assert!(HeightMap::new(2, 2, 0.0, 1.0, vec![0.0; 4]).is_err());
        assert!(HeightMap::new(2, 2, 1.0, 1.0, vec![0.0; 3]).is_err());
        assert!(HeightMap::new(2, 2, 1.0, 1.0, vec![0.0, f64::NAN, 0.0, 0.0]).is_err());
    }
}
