//! Load-controlled peeling of a soft thin film from a rigid wavy substrate (chapter 6),
//! Eqs. (6.1)-(6.31).
//!
//! The substrate is y(x) = y₀ + Aλρ(x/λ) with a single-valued periodic shape ρ ∈ [−1, 1] of
//! period 1: the sinusoid (6.20), the zigzag (6.24), or a sampled profile (a table of x, y over
//! one period, interpolated by cubic splines between detected corners). The film (modulus E,
//! width b, thickness h) is pulled at the fixed angle θ by the force F; the peel front sits at
//! (x_p, y(x_p)).
//!
//! Non-dimensional variables (Sec. 6.2.2): F̄ = F/(Ebh), w̄ = w/(Eh), x̄ = x/λ, ȳ = y/λ, so the
//! slope is ȳ′ = Aρ′(x̄), the curvature κ̄ = κλ = Aρ″/(1 + ȳ′²)^(3/2) and energies are in units of
//! Ebhλ. The equivalent peel angle is θ_e = θ + φ with φ = atan ȳ′.
//!
//! Sign convention (ERRATA, chapter 6): peeling costs +w per unit area, so the equilibrium
//! (6.8) reads F̄²/2 + F̄(1 − cos θ_e) − w̄ = 0 and its positive root is
//! F̄ = √((cos θ_e − 1)² + 2w̄) + cos θ_e − 1: the square root of (6.9), (6.10), (6.17) covers
//! only the first two terms.
//!
//! Corners (the zigzag's, or those detected in a sampled profile) are treated exactly: the
//! slope jumps there, so the equilibrium force jumps between the values of the two sides and
//! the front rests at the corner for every force in between. A convex corner (curvature −δ)
//! is a stable rest point, a concave corner (+δ) an unstable one; straight segments are
//! neutral (κ = 0).

use crate::error::{Error, Result};
use crate::numerics::quadrature::integrate;
use crate::numerics::roots::brent;
use crate::numerics::spline::CubicSpline;

use std::f64::consts::{FRAC_PI_2, PI};

/// A corner of the substrate shape: the slope ρ′ jumps from `slope_left` to `slope_right`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// Position x̄ in [0, 1).
    pub xi: f64,
    /// ρ′ just before the corner.
    pub slope_left: f64,
    /// ρ′ just after the corner.
    pub slope_right: f64,
}

/// A substrate shape ρ(x̄) of period 1, normalised to [−1, 1].
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    /// ρ = −cos 2πx̄, the sinusoid of Eq. (6.20) (y = Aλ[1 − cos(2πx/λ)] up to the constant).
    Sinusoid,
    /// The zigzag of Eq. (6.24): ρ = 4x̄ − 1 on [0, ½], 3 − 4x̄ on [½, 1].
    Zigzag,
    /// A sampled shape (see [`SampledProfile`]).
    Sampled(SampledProfile),
}

impl Profile {
    /// Short name for legends and messages.
    pub fn name(&self) -> &'static str {
        match self {
            Profile::Sinusoid => "sinusoidal",
            Profile::Zigzag => "zigzag",
            Profile::Sampled(_) => "sampled",
        }
    }

    /// Shape ρ(x̄), Eq. (6.20) or (6.24) up to the constant y₀.
    pub fn shape(&self, xi: f64) -> f64 {
        match self {
            Profile::Sinusoid => -(2.0 * PI * xi).cos(),
            Profile::Zigzag => {
                let t = xi.rem_euclid(1.0);
                if t <= 0.5 { 4.0 * t - 1.0 } else { 3.0 - 4.0 * t }
            }
            Profile::Sampled(s) => s.eval(xi, false).0,
        }
    }

    /// Slope ρ′(x̄), the right-hand value at a corner.
    pub fn slope(&self, xi: f64) -> f64 {
        match self {
            Profile::Sinusoid => 2.0 * PI * (2.0 * PI * xi).sin(),
            Profile::Zigzag => {
                if xi.rem_euclid(1.0) < 0.5 {
                    4.0
                } else {
                    -4.0
                }
            }
            Profile::Sampled(s) => s.eval(xi, false).1,
        }
    }

    /// Slope ρ′(x̄), the left-hand value at a corner (equal to [`Profile::slope`] elsewhere).
    pub fn slope_left(&self, xi: f64) -> f64 {
        match self {
            Profile::Sinusoid => self.slope(xi),
            Profile::Zigzag => {
                let t = xi.rem_euclid(1.0);
                if t > 0.0 && t <= 0.5 { 4.0 } else { -4.0 }
            }
            Profile::Sampled(s) => s.eval(xi, true).1,
        }
    }

    /// Second derivative ρ″(x̄) of the smooth part (corners excluded).
    pub fn second_derivative(&self, xi: f64) -> f64 {
        match self {
            Profile::Sinusoid => 4.0 * PI * PI * (2.0 * PI * xi).cos(),
            Profile::Zigzag => 0.0,
            Profile::Sampled(s) => s.eval(xi, false).2,
        }
    }

    /// The corners in one period, x̄ in [0, 1).
    pub fn corners(&self) -> Vec<Corner> {
        match self {
            Profile::Sinusoid => Vec::new(),
            Profile::Zigzag => vec![
                Corner {
                    xi: 0.0,
                    slope_left: -4.0,
                    slope_right: 4.0,
                },
                Corner {
                    xi: 0.5,
                    slope_left: 4.0,
                    slope_right: -4.0,
                },
            ],
            Profile::Sampled(s) => s.corners.clone(),
        }
    }

    /// Inflection points in one period (x̄ in [0, 1)): where ρ″ changes sign on a smooth
    /// piece. The peel force is extremal there, Eq. (6.16).
    pub fn inflections(&self) -> Vec<f64> {
        match self {
            Profile::Sinusoid => vec![0.25, 0.75],
            Profile::Zigzag => Vec::new(),
            Profile::Sampled(s) => s.inflections.clone(),
        }
    }

    /// Smallest and largest slope (min ρ′, max ρ′) over a period, exact.
    pub fn slope_range(&self) -> (f64, f64) {
        match self {
            Profile::Sinusoid => (-2.0 * PI, 2.0 * PI),
            Profile::Zigzag => (-4.0, 4.0),
            Profile::Sampled(s) => s.slope_range,
        }
    }

    /// The admissible peel angles [θ_lo, θ_hi] in radians at aspect ratio A: the comparability
    /// condition of Sec. 6.2.1, tan θ ≥ |min ȳ′| for θ ≤ π/2 and |tan θ| ≥ max ȳ′ for θ ≥ π/2,
    /// that is θ ∈ [atan|A min ρ′|, π − atan(A max ρ′)].
    pub fn admissible_angles(&self, aspect_ratio: f64) -> (f64, f64) {
        let (lo, hi) = self.slope_range();
        (
            (aspect_ratio * lo).abs().atan(),
            PI - (aspect_ratio * hi).max(0.0).atan(),
        )
    }
}

/// A substrate shape given as samples over one period, interpolated by cubic splines.
///
/// Corners are detected where the slope of the polyline jumps by more than
/// [`CORNER_RATIO`] times the median jump; the shape is split there, each piece is a clamped
/// spline with one-sided end slopes (so straight pieces stay exactly straight and the slope
/// jumps at the corner as in the data), and without corners the whole period is one periodic
/// spline.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledProfile {
    /// Spline pieces in unrolled coordinates covering [start, start + 1).
    pieces: Vec<CubicSpline>,
    /// First knot of each piece.
    piece_starts: Vec<f64>,
    /// Start of the first piece (the first corner, or 0).
    start: f64,
    corners: Vec<Corner>,
    inflections: Vec<f64>,
    slope_range: (f64, f64),
    /// Period λ in the units of the data.
    pub period: f64,
    /// The data's own aspect ratio (max y − min y)/(2λ).
    pub aspect_ratio: f64,
    /// Number of distinct samples per period.
    pub n_samples: usize,
}

/// A slope jump larger than this many times the median jump of the sampled polyline is a corner.
pub const CORNER_RATIO: f64 = 8.0;

impl SampledProfile {
    /// Build from samples (x, y) over one period; the last sample closes the period (its height
    /// equals the first one's, its abscissa is one period after the first).
    ///
    /// # Errors
    /// [`Error::Unresolvable`] with a one-line reason: fewer than 4 samples, non-finite values,
    /// abscissae not strictly increasing, a profile that does not close (first and last heights
    /// differ by more than 1e-6 of the height range), or a flat profile.
    pub fn new(points: &[(f64, f64)]) -> Result<Self> {
        let bad = |reason: String| Error::Unresolvable {
            model: "sampled profile",
            reason,
        };
        if points.len() < 4 {
            return Err(bad(format!(
                "needs at least 4 samples (3 per period plus the closing one), got {}",
                points.len()
            )));
        }
        if let Some(k) = points.iter().position(|(x, y)| !x.is_finite() || !y.is_finite()) {
            return Err(bad(format!("sample {} is not a finite number", k + 1)));
        }
        if let Some(k) = points.windows(2).position(|w| w[1].0 <= w[0].0) {
            return Err(bad(format!(
                "x must increase strictly: sample {} (x = {}) follows x = {}",
                k + 2,
                points[k + 1].0,
                points[k].0
            )));
        }
        let (ymin, ymax) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, y)| {
                (a.min(y), b.max(y))
            });
        let range = ymax - ymin;
        if range <= 0.0 {
            return Err(bad("the profile is flat (all heights equal)".into()));
        }
        let (first, last) = (points[0], points[points.len() - 1]);
        if (last.1 - first.1).abs() > 1e-6 * range {
            return Err(bad(format!(
                "the profile does not close: the last height {} differs from the first {}; give one full period, the last sample repeating the first height",
                last.1, first.1
            )));
        }
        let period = last.0 - first.0;
        let xs: Vec<f64> = points.iter().map(|&(x, _)| (x - first.0) / period).collect();
        let n = xs.len() - 1;
        // Normalise by the samples' range first, then by the interpolant's own range (the
        // samples need not hit the extremes), so that ρ spans [−1, 1] exactly.
        let mid = 0.5 * (ymax + ymin);
        let mut ys: Vec<f64> = points.iter().map(|&(_, y)| (y - mid) / (0.5 * range)).collect();
        ys[n] = ys[0];
        let (pieces, start, corner_knots) = Self::build(&xs, &ys)?;
        let (lo, hi) = pieces
            .iter()
            .map(CubicSpline::value_range)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, d)| {
                (a.min(c), b.max(d))
            });
        let (c, h) = (0.5 * (hi + lo), 0.5 * (hi - lo));
        let ys: Vec<f64> = ys.iter().map(|y| (y - c) / h).collect();
        let (pieces, start, corner_knots) = if (c.abs() + (h - 1.0).abs()) > 0.0 {
            Self::build(&xs, &ys)?
        } else {
            (pieces, start, corner_knots)
        };
        let mut profile = Self {
            piece_starts: pieces.iter().map(|p| p.knots()[0]).collect(),
            pieces,
            start,
            corners: Vec::new(),
            inflections: Vec::new(),
            slope_range: (0.0, 0.0),
            period,
            aspect_ratio: h * range / (2.0 * period),
            n_samples: n,
        };
        profile.corners = corner_knots
            .iter()
            .map(|&i| {
                let xi = xs[i];
                Corner {
                    xi,
                    slope_left: profile.eval(xi, true).1,
                    slope_right: profile.eval(xi, false).1,
                }
            })
            .collect();
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let mut inflections = Vec::new();
        for p in &profile.pieces {
            let (a, b) = p.slope_range();
            lo = lo.min(a);
            hi = hi.max(b);
            inflections.extend(p.inflections().into_iter().map(|t| t.rem_euclid(1.0)));
        }
        inflections.sort_by(f64::total_cmp);
        profile.inflections = inflections;
        profile.slope_range = (lo, hi);
        Ok(profile)
    }

    /// Spline pieces of normalised samples (xs in [0, 1], last closing), their start and the
    /// corner knots.
    fn build(xs: &[f64], ys: &[f64]) -> Result<(Vec<CubicSpline>, f64, Vec<usize>)> {
        let n = xs.len() - 1;
        // Secant slopes m_i on [x_i, x_{i+1}] and slope jumps at knot i (cyclic).
        let m: Vec<f64> = (0..n)
            .map(|i| (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]))
            .collect();
        let jump: Vec<f64> = (0..n).map(|i| (m[i] - m[(i + n - 1) % n]).abs()).collect();
        let mut sorted = jump.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[n / 2];
        let m_max = m.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let corner_knots: Vec<usize> = (0..n)
            .filter(|&i| jump[i] > CORNER_RATIO * median + 1e-9 * m_max)
            .collect();
        if corner_knots.is_empty() {
            return Ok((vec![CubicSpline::periodic(xs, ys)?], 0.0, corner_knots));
        }
        let mut pieces = Vec::new();
        for (k, &a) in corner_knots.iter().enumerate() {
            let b = corner_knots.get(k + 1).copied().unwrap_or(corner_knots[0] + n);
            // Knots a..=b in unrolled indices.
            let (px, py): (Vec<f64>, Vec<f64>) =
                (a..=b).map(|j| (xs[j % n] + (j / n) as f64, ys[j % n])).unzip();
            let (s0, s1) = one_sided_slopes(&px, &py);
            pieces.push(CubicSpline::clamped(&px, &py, s0, s1)?);
        }
        Ok((pieces, xs[corner_knots[0]], corner_knots))
    }

    /// Value, slope and second derivative of ρ at x̄ (right-hand or left-hand at a corner).
    fn eval(&self, xi: f64, left: bool) -> (f64, f64, f64) {
        let t = self.start + (xi - self.start).rem_euclid(1.0);
        let starts = &self.piece_starts;
        let mut k = starts.partition_point(|&s| s <= t).saturating_sub(1);
        let mut t = t;
        if left && (t - starts[k]).abs() <= 1e-14 {
            // The left-hand value at a piece start is the end of the previous piece.
            if k == 0 {
                k = self.pieces.len() - 1;
                t += 1.0;
            } else {
                k -= 1;
            }
        }
        self.pieces[k].eval(t)
    }
}

/// One-sided end slopes of a piece from its first and last three knots (exact for parabolas);
/// the secant for a two-knot piece.
fn one_sided_slopes(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len();
    let d = |i: usize| (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
    if n < 3 {
        let s = d(0);
        return (s, s);
    }
    let (h0, h1) = (x[1] - x[0], x[2] - x[1]);
    let s0 = d(0) - h0 * (d(1) - d(0)) / (h0 + h1);
    let (g0, g1) = (x[n - 2] - x[n - 3], x[n - 1] - x[n - 2]);
    let s1 = d(n - 2) + g1 * (d(n - 2) - d(n - 3)) / (g0 + g1);
    (s0, s1)
}

/// Peel force on a flat substrate at peel angle `theta` (Kendall).
///
/// Implements Eq. (6.11) (and (6.10) with θ → θ_e), in the corrected reading of ERRATA:
/// ```text
/// F̄ = √((cos θ − 1)² + 2w̄) + cos θ − 1 = 2w̄ / (√((1 − cos θ)² + 2w̄) + 1 − cos θ)
/// ```
/// The second form is used: it has no cancellation for small w̄.
pub fn kendall_force(theta: f64, w_bar: f64) -> f64 {
    let u = 2.0 * (0.5 * theta).sin().powi(2); // 1 − cos θ without cancellation
    2.0 * w_bar / ((u * u + 2.0 * w_bar).sqrt() + u)
}

/// Maximum peel force on the sinusoid, closed form.
///
/// Implements Eq. (6.21) (corrected square root):
/// ```text
/// c = (cos θ + 2πA sin θ)/√(1 + 4π²A²),   F̄_max = √((c − 1)² + 2w̄) + c − 1
/// ```
pub fn sinusoid_max_force(aspect_ratio: f64, theta: f64, w_bar: f64) -> f64 {
    let s = 2.0 * PI * aspect_ratio;
    let c = (theta.cos() + s * theta.sin()) / (1.0 + s * s).sqrt();
    ((c - 1.0).powi(2) + 2.0 * w_bar).sqrt() + c - 1.0
}

/// Effective work of adhesion on the sinusoid, closed form.
///
/// Implements Eq. (6.22):
/// ```text
/// w̄_e = ½[cos(θ − atan 2πA) − cos θ + √((cos(θ − atan 2πA) − 1)² + 2w̄)]² − ½(cos θ − 1)²
/// ```
pub fn sinusoid_effective_work(aspect_ratio: f64, theta: f64, w_bar: f64) -> f64 {
    effective_work_6_18(theta, -(2.0 * PI * aspect_ratio).atan(), w_bar)
}

/// Maximum peel force on the zigzag, closed form.
///
/// Implements Eq. (6.25) (corrected square root):
/// ```text
/// c = (cos θ + 4A sin θ)/√(1 + 16A²),   F̄_max = √((c − 1)² + 2w̄) + c − 1
/// ```
pub fn zigzag_max_force(aspect_ratio: f64, theta: f64, w_bar: f64) -> f64 {
    let s = 4.0 * aspect_ratio;
    let c = (theta.cos() + s * theta.sin()) / (1.0 + s * s).sqrt();
    ((c - 1.0).powi(2) + 2.0 * w_bar).sqrt() + c - 1.0
}

/// Effective work of adhesion on the zigzag, closed form.
///
/// Implements Eq. (6.26):
/// ```text
/// w̄_e = ½[cos(θ − atan 4A) − cos θ + √((cos(θ − atan 4A) − 1)² + 2w̄)]² − ½(cos θ − 1)²
/// ```
pub fn zigzag_effective_work(aspect_ratio: f64, theta: f64, w_bar: f64) -> f64 {
    effective_work_6_18(theta, -(4.0 * aspect_ratio).atan(), w_bar)
}

/// Effective work of adhesion from the angle of the minimum slope φ_min.
///
/// Implements Eq. (6.18):
/// ```text
/// w̄_e = ½[cos(θ + φ_min) − cos θ + √((cos(θ + φ_min) − 1)² + 2w̄)]² − ½(cos θ − 1)²
/// ```
///
/// Evaluated without cancellation as w̄_e = ½F̄_e(F̄_e + 2(1 − cos θ)), where
/// F̄_e = √((cos(θ + φ_min) − 1)² + 2w̄) + cos(θ + φ_min) − 1 is Kendall's force (6.11) at the
/// angle θ + φ_min: the printed difference of squares loses all digits for w̄ below ~1e-14.
pub fn effective_work_6_18(theta: f64, phi_min: f64, w_bar: f64) -> f64 {
    let f_e = kendall_force(theta + phi_min, w_bar);
    let u = 2.0 * (0.5 * theta).sin().powi(2); // 1 − cos θ
    0.5 * f_e * (f_e + 2.0 * u)
}

/// Optimum peel angle of the effective work on the sinusoid, the empirical fit.
///
/// Implements Eq. (6.23) with the negative exponent of ERRATA:
/// `θ ≈ 0.5π exp[−1/(0.635 + 5.837A + 15.998A²)]`.
pub fn sinusoid_optimum_angle_fit(aspect_ratio: f64) -> f64 {
    let a = aspect_ratio;
    FRAC_PI_2 * (-1.0 / (0.635 + 5.837 * a + 15.998 * a * a)).exp()
}

/// Optimum peel angle of the effective work on the zigzag, the empirical fit.
///
/// Implements Eq. (6.27) with the negative exponent of ERRATA:
/// `θ ≈ 0.5π exp[−1/(0.631 + 3.786A + 6.306A²)]`.
pub fn zigzag_optimum_angle_fit(aspect_ratio: f64) -> f64 {
    let a = aspect_ratio;
    FRAC_PI_2 * (-1.0 / (0.631 + 3.786 * a + 6.306 * a * a)).exp()
}

/// The flat and steep limits of Sec. 6.4 at θ = π/2, Eqs. (6.28)-(6.31).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteepLimits {
    /// F̄_max,flat = √(1 + 2w̄) − 1, Eq. (6.28a).
    pub force_flat: f64,
    /// F̄_max,steep = √(2w̄), Eq. (6.28b).
    pub force_steep: f64,
    /// α = F̄_max,steep / F̄_max,flat, Eq. (6.29).
    pub alpha: f64,
    /// The small-w̄ approximation α ≈ √(2/w̄) of (6.29).
    pub alpha_approx: f64,
    /// w̄_e,flat = w̄, Eq. (6.30a).
    pub work_flat: f64,
    /// w̄_e,steep = w̄ + √(2w̄), Eq. (6.30b).
    pub work_steep: f64,
    /// β = w̄_e,steep / w̄_e,flat = 1 + √(2/w̄), Eq. (6.31).
    pub beta: f64,
}

/// The asymptotic limits of Sec. 6.4 for peeling at θ = π/2.
///
/// Implements Eqs. (6.28)-(6.31).
pub fn steep_limits(w_bar: f64) -> SteepLimits {
    let force_flat = kendall_force(FRAC_PI_2, w_bar);
    let force_steep = (2.0 * w_bar).sqrt();
    let work_steep = w_bar + (2.0 * w_bar).sqrt();
    SteepLimits {
        force_flat,
        force_steep,
        alpha: force_steep / force_flat,
        alpha_approx: (2.0 / w_bar).sqrt(),
        work_flat: w_bar,
        work_steep,
        beta: work_steep / w_bar,
    }
}

/// Stability of an equilibrium under load control, by the sign of d²E/dx_p², Eq. (6.15).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stability {
    /// d²E/dx_p² > 0 (κ < 0, or a convex corner).
    Stable,
    /// d²E/dx_p² = 0 (κ = 0: straight segments, the flat substrate).
    Neutral,
    /// d²E/dx_p² < 0 (κ > 0, or a concave corner).
    Unstable,
}

/// Sampled equilibrium curve F̄(x̄_p): points in order of x̄_p (a corner contributes two points
/// at the same x̄_p, the forces of its two sides) and the stability of each segment between
/// consecutive points.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EquilibriumCurve {
    /// (x̄_p, F̄) points.
    pub points: Vec<(f64, f64)>,
    /// Stability of segment k, between points k and k + 1.
    pub segments: Vec<Stability>,
}

/// A snap-through of the peel front at constant force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnapThrough {
    /// Front position before the jump, x̄_p.
    pub from: f64,
    /// Front position after the jump.
    pub to: f64,
    /// The force F̄ at which it happens.
    pub force: f64,
}

/// The path of the peel front as the force rises quasi-statically (load control).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadPath {
    /// Quasi-static states visited, (x̄_p, F̄), in order; a jump joins two consecutive states.
    pub points: Vec<(f64, f64)>,
    /// The snap-throughs in order.
    pub jumps: Vec<SnapThrough>,
    /// Whether the force reached the largest equilibrium force F̄_max, beyond which the front
    /// runs away (complete peeling: a snap-through every period).
    pub runaway: bool,
}

/// A peeling configuration: profile, aspect ratio A, peel angle θ, work of adhesion w̄.
///
/// ```
/// use adhesion::models::peeling::{Profile, WavyPeeling, kendall_force};
/// let theta = std::f64::consts::FRAC_PI_2;
/// let p = WavyPeeling::new(&Profile::Sinusoid, 0.05, theta, 0.005)?;
/// // The wavy substrate needs a larger force than the flat one (Kendall, (6.11)).
/// assert!(p.max_force() > 1.4 * kendall_force(theta, 0.005));
/// // Under a rising load the front snaps through once the force reaches F_max.
/// let path = p.load_path(&p.equilibrium_curve(0.0, 2.0, 100))?;
/// assert!(path.runaway && (path.jumps[0].from - 0.75).abs() < 1e-9);
/// // Angles where the film would touch the substrate are refused.
/// assert!(WavyPeeling::new(&Profile::Sinusoid, 0.05, 0.1, 0.005).is_err());
/// # Ok::<(), adhesion::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct WavyPeeling<'p> {
    profile: &'p Profile,
    aspect_ratio: f64,
    theta: f64,
    w_bar: f64,
}

impl<'p> WavyPeeling<'p> {
    /// Validated configuration.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for A < 0, w̄ ≤ 0, θ outside [0, π], or θ outside the
    /// admissible range of the comparability condition (Sec. 6.2.1), naming the range.
    pub fn new(profile: &'p Profile, aspect_ratio: f64, theta: f64, w_bar: f64) -> Result<Self> {
        if !(aspect_ratio.is_finite() && aspect_ratio >= 0.0) {
            return Err(Error::invalid(
                "aspect_ratio",
                aspect_ratio,
                "must not be negative",
            ));
        }
        if !(w_bar.is_finite() && w_bar > 0.0) {
            return Err(Error::invalid("work_of_adhesion_norm", w_bar, "must be positive"));
        }
        if !(theta.is_finite() && (0.0..=PI).contains(&theta)) {
            return Err(Error::invalid(
                "peel_angle",
                format!("{:.6} rad ({:.3}°)", theta, theta.to_degrees()),
                "must be in [0, 180]°",
            ));
        }
        let (lo, hi) = profile.admissible_angles(aspect_ratio);
        let slack = 1e-12;
        if theta < lo - slack || theta > hi + slack {
            return Err(Error::invalid(
                "peel_angle",
                format!("{:.4}°", theta.to_degrees()),
                format!(
                    "the peeled film would touch the {} substrate of aspect ratio A = {}: the comparability condition (Sec. 6.2.1) needs {}° <= θ <= {}°",
                    profile.name(),
                    crate::text::fmt_sig(aspect_ratio),
                    crate::text::fmt_sig(lo.to_degrees()),
                    crate::text::fmt_sig(hi.to_degrees())
                ),
            ));
        }
        Ok(Self {
            profile,
            aspect_ratio,
            theta,
            w_bar,
        })
    }

    /// Peel angle θ [rad].
    pub fn theta(&self) -> f64 {
        self.theta
    }

    /// Aspect ratio A.
    pub fn aspect_ratio(&self) -> f64 {
        self.aspect_ratio
    }

    /// Surface slope ȳ′ = Aρ′(x̄) (right-hand value at a corner).
    pub fn slope(&self, xi: f64) -> f64 {
        self.aspect_ratio * self.profile.slope(xi)
    }

    /// Surface height ȳ = Aρ(x̄) − the constant y₀/λ, Eq. (6.20)/(6.24).
    pub fn height(&self, xi: f64) -> f64 {
        self.aspect_ratio * self.profile.shape(xi)
    }

    /// Equivalent peel angle θ_e = θ + atan ȳ′, Eq. (6.10).
    pub fn equivalent_angle(&self, xi: f64) -> f64 {
        self.theta + self.slope(xi).atan()
    }

    /// Equilibrium peel force at the front position x̄_p (right-hand value at a corner).
    ///
    /// Implements Eq. (6.9)/(6.10): `F̄ = √((cos θ_e − 1)² + 2w̄) + cos θ_e − 1`.
    pub fn force(&self, xi: f64) -> f64 {
        kendall_force(self.equivalent_angle(xi), self.w_bar)
    }

    /// Equilibrium peel force for the left-hand slope (differs from [`WavyPeeling::force`]
    /// only at corners).
    pub fn force_left(&self, xi: f64) -> f64 {
        kendall_force(
            self.theta + (self.aspect_ratio * self.profile.slope_left(xi)).atan(),
            self.w_bar,
        )
    }

    /// Equilibrium peel force from (6.9) as printed in ȳ′ (with the corrected square root):
    /// ```text
    /// c = (cos θ − ȳ′ sin θ)/√(1 + ȳ′²),   F̄ = √((c − 1)² + 2w̄) + c − 1
    /// ```
    /// Same value as [`WavyPeeling::force`]; kept as the literal form of Eq. (6.9).
    pub fn force_6_9(&self, xi: f64) -> f64 {
        let yp = self.slope(xi);
        let c = (self.theta.cos() - yp * self.theta.sin()) / (1.0 + yp * yp).sqrt();
        ((c - 1.0).powi(2) + 2.0 * self.w_bar).sqrt() + c - 1.0
    }

    /// Curvature κ̄ = κλ of the substrate at x̄ (smooth part).
    ///
    /// Implements Eq. (6.14): `κ = y″/(1 + y′²)^(3/2)`.
    pub fn curvature(&self, xi: f64) -> f64 {
        let yp = self.slope(xi);
        self.aspect_ratio * self.profile.second_derivative(xi) / (1.0 + yp * yp).powf(1.5)
    }

    /// Total potential energy Ē = E_tot/(Ebhλ) at front position x̄_p under the force F̄
    /// (constant y₀ terms dropped, arc length by adaptive quadrature).
    ///
    /// Implements Eq. (6.6) with the sign of the adhesion term of ERRATA:
    /// ```text
    /// Ē = −(F̄²/2 + F̄ − w̄) ∫₀^x̄p √(1 + ȳ′²) dx̄ + F̄ x̄_p cos θ − F̄ ȳ(x̄_p) sin θ
    /// ```
    ///
    /// # Errors
    /// Quadrature failure (not expected: the integrand is bounded).
    pub fn energy(&self, xi: f64, force: f64) -> Result<f64> {
        // Integrate piecewise between corners so the quadrature never straddles a kink.
        let mut breaks: Vec<f64> = vec![0.0, xi];
        let (lo, hi) = (xi.min(0.0), xi.max(0.0));
        for c in self.profile.corners() {
            let mut t = c.xi + lo.floor();
            while t < hi {
                if t > lo {
                    breaks.push(t);
                }
                t += 1.0;
            }
        }
        breaks.sort_by(f64::total_cmp);
        let mut arc = 0.0;
        for w in breaks.windows(2) {
            arc += integrate(|t| (1.0 + self.slope(t).powi(2)).sqrt(), w[0], w[1], 1e-15, 1e-13)?.value;
        }
        let arc = if xi < 0.0 { -arc } else { arc };
        let f = force;
        Ok(-(0.5 * f * f + f - self.w_bar) * arc + f * xi * self.theta.cos()
            - f * self.height(xi) * self.theta.sin())
    }

    /// Second derivative of the energy, d²Ē/dx̄_p² = (λ/Ebh) d²E/dx_p², at an equilibrium.
    ///
    /// Implements Eq. (6.15): `−F̄ κ̄ (sin θ + ȳ′ cos θ) √(1 + ȳ′²)`.
    pub fn energy_curvature(&self, xi: f64) -> f64 {
        let yp = self.slope(xi);
        -self.force(xi)
            * self.curvature(xi)
            * (self.theta.sin() + yp * self.theta.cos())
            * (1.0 + yp * yp).sqrt()
    }

    /// Second derivative of the energy in the form of Eq. (6.12) (with the corrected sign of w̄):
    /// ```text
    /// d²Ē/dx̄² = −ȳ″ [F̄ sin θ + (F̄²/2 + F̄ − w̄) ȳ′/√(1 + ȳ′²)]
    /// ```
    pub fn energy_curvature_6_12(&self, xi: f64) -> f64 {
        let yp = self.slope(xi);
        let ypp = self.aspect_ratio * self.profile.second_derivative(xi);
        let f = self.force(xi);
        -ypp * (f * self.theta.sin() + (0.5 * f * f + f - self.w_bar) * yp / (1.0 + yp * yp).sqrt())
    }

    /// Slope of the equilibrium force along the substrate, dF̄/dx̄_p.
    ///
    /// Implements Eq. (6.16):
    /// ```text
    /// dF̄/dx̄_p = −κ̄ sin θ_e √(1 + ȳ′²) [1 − (1 − cos θ_e)/√(2w̄ + (1 − cos θ_e)²)]
    /// ```
    pub fn force_slope(&self, xi: f64) -> f64 {
        let yp = self.slope(xi);
        let te = self.equivalent_angle(xi);
        let u = 2.0 * (0.5 * te).sin().powi(2);
        -self.curvature(xi)
            * te.sin()
            * (1.0 + yp * yp).sqrt()
            * (1.0 - u / (2.0 * self.w_bar + u * u).sqrt())
    }

    /// Stability of the equilibrium at x̄_p on a smooth piece, by the sign of (6.15). A
    /// curvature below 1e-7 of the largest slope counts as zero (neutral): the straight pieces
    /// of a sampled profile carry rounding noise in ρ″.
    pub fn stability(&self, xi: f64) -> Stability {
        let (lo, hi) = self.profile.slope_range();
        let zero = 1e-7 * lo.abs().max(hi.abs());
        if (self.profile.second_derivative(xi)).abs() <= zero {
            return Stability::Neutral;
        }
        let k = self.energy_curvature(xi);
        if k > 0.0 {
            Stability::Stable
        } else if k < 0.0 {
            Stability::Unstable
        } else {
            Stability::Neutral
        }
    }

    /// The effective (maximum) peel force, reached where the slope is smallest.
    ///
    /// Implements Eq. (6.17):
    /// ```text
    /// c = (cos θ − ȳ′_min sin θ)/√(1 + ȳ′_min²),   F̄_max = √((c − 1)² + 2w̄) + c − 1
    /// ```
    pub fn max_force(&self) -> f64 {
        let ymin = self.aspect_ratio * self.profile.slope_range().0;
        kendall_force(self.theta + ymin.atan(), self.w_bar)
    }

    /// The smallest equilibrium peel force, where the slope is largest ((6.10) at ȳ′_max).
    pub fn min_force(&self) -> f64 {
        let ymax = self.aspect_ratio * self.profile.slope_range().1;
        kendall_force(self.theta + ymax.atan(), self.w_bar)
    }

    /// The effective work of adhesion w̄_e.
    ///
    /// Implements Eq. (6.18) with φ_min = atan ȳ′_min.
    pub fn effective_work(&self) -> f64 {
        let phi_min = (self.aspect_ratio * self.profile.slope_range().0).atan();
        effective_work_6_18(self.theta, phi_min, self.w_bar)
    }

    /// The equilibrium curve F̄(x̄_p) on [x̄_start, x̄_end]: `points_per_period` uniform samples
    /// per period plus every inflection (where F̄ is extremal) and both sides of every corner,
    /// each segment classified by (6.15) at its midpoint (corners: stable when the force rises
    /// across them).
    pub fn equilibrium_curve(&self, start: f64, end: f64, points_per_period: usize) -> EquilibriumCurve {
        let n = ((end - start) * points_per_period as f64).ceil().max(1.0) as usize;
        let mut xs: Vec<(f64, bool)> = (0..=n)
            .map(|i| (start + (end - start) * i as f64 / n as f64, false))
            .collect();
        let corners = self.profile.corners();
        let mut period = start.floor();
        while period <= end {
            for t in self.profile.inflections() {
                let x = period + t;
                if x > start && x < end {
                    xs.push((x, false));
                }
            }
            if self.aspect_ratio > 0.0 {
                for c in &corners {
                    let x = period + c.xi;
                    if x >= start && x <= end {
                        xs.push((x, true));
                    }
                }
            }
            period += 1.0;
        }
        xs.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
        // Drop uniform samples that coincide with a corner or inflection.
        let mut grid: Vec<(f64, bool)> = Vec::with_capacity(xs.len());
        for (x, corner) in xs {
            match grid.last_mut() {
                Some(last) if (x - last.0).abs() <= 1e-12 => last.1 |= corner,
                _ => grid.push((x, corner)),
            }
        }
        let mut curve = EquilibriumCurve::default();
        for (x, corner) in grid {
            if let Some(&(px, _)) = curve.points.last() {
                curve.segments.push(self.stability(0.5 * (px + x)));
            }
            if corner {
                let (fl, fr) = (self.force_left(x), self.force(x));
                if (fl - fr).abs() > 0.0 {
                    curve.points.push((x, fl));
                    curve.segments.push(if fr > fl {
                        Stability::Stable
                    } else {
                        Stability::Unstable
                    });
                }
                curve.points.push((x, fr));
            } else {
                curve.points.push((x, self.force(x)));
            }
        }
        curve
    }

    /// The load-controlled path along a sampled equilibrium curve: the force starts at the
    /// smallest equilibrium force of the curve's first period and rises; the front advances
    /// quasi-statically while the equilibrium force rises (stable, or neutral at constant
    /// force), and where it falls the front snaps through at constant force to the next
    /// position where the equilibrium force is as large again. Landing points on smooth
    /// pieces are refined by Brent's method on (6.10).
    ///
    /// # Errors
    /// Root-finding failures (not expected for a continuous force between samples).
    pub fn load_path(&self, curve: &EquilibriumCurve) -> Result<LoadPath> {
        let pts = &curve.points;
        let mut path = LoadPath::default();
        if pts.len() < 2 {
            return Ok(path);
        }
        let f_max = self.max_force();
        let tol = 1e-9 * f_max;
        let x0 = pts[0].0;
        let first_period = pts.iter().take_while(|p| p.0 <= x0 + 1.0).count().max(1);
        let start = (0..first_period)
            .min_by(|&a, &b| pts[a].1.total_cmp(&pts[b].1).then(a.cmp(&b)))
            .unwrap_or(0);
        let mut level = pts[start].1;
        path.points.push(pts[start]);
        let mut k = start + 1;
        while k < pts.len() {
            let (x, f) = pts[k];
            if f >= level - tol {
                level = level.max(f);
                path.points.push((x, level));
                k += 1;
                continue;
            }
            // The force falls below the load: snap-through from the previous state.
            let from = pts[k - 1].0;
            let Some(j) = (k..pts.len()).find(|&j| pts[j].1 >= level - tol) else {
                path.runaway = level >= f_max - tol;
                break;
            };
            let (xa, fa) = pts[j - 1];
            let (xb, fb) = pts[j];
            let to = if xa == xb || fb <= level + tol {
                xb
            } else {
                brent(|t| self.force(t) - level, xa, xb, 1e-13).unwrap_or_else(|_| {
                    // Linear interpolation if the force is not monotone between the samples.
                    xa + (xb - xa) * (level - fa) / (fb - fa)
                })
            };
            path.jumps.push(SnapThrough {
                from,
                to,
                force: level,
            });
            if level >= f_max - tol {
                path.runaway = true;
            }
            path.points.push((to, level));
            // Continue from the landing point along the rising samples.
            k = if to < xb { j } else { j + 1 };
        }
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corrected_force_solves_the_equilibrium_equation() {
        for &te in &[0.0, 0.3, 1.0, 2.0, 3.0] {
            let w = 0.005;
            let f = kendall_force(te, w);
            let residual = 0.5 * f * f + f * (1.0 - f64::cos(te)) - w;
            assert!(residual.abs() < 1e-16, "θe = {te}: {residual}");
        }
    }
}
