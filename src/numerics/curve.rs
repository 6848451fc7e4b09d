//! Curve tracing for one-parameter equilibrium problems: grids, all roots of a scalar equation
//! on an interval, extrema (turning points), and the path a quasi-static experiment follows
//! along sampled equilibrium branches, with its jumps.
//!
//! The models of chapters 2, 3, 5 and 6 share one structure: a state variable s (contact radius,
//! gap, peel-front position) and a control λ (stage displacement, indentation depth, load) tied
//! by an equilibrium curve λ(s), stable where the energy's second variation is positive. An
//! experiment that moves λ monotonically stays on a stable segment until it ends (a fold, where
//! dλ/ds = 0), then jumps at fixed λ to another stable state. [`follow`] does this on sampled
//! branches; the exact fold points are best found by the caller with [`extrema`] or
//! [`all_roots`] and inserted into the samples.

use crate::error::{Error, Result};
use crate::numerics::roots::brent;

/// `n` equally spaced points from `lo` to `hi` (inclusive).
///
/// # Panics
/// If `n < 2`.
pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    assert!(n >= 2, "linspace needs two points");
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

/// `n` logarithmically spaced points from `lo` to `hi` (both > 0, inclusive).
///
/// # Panics
/// If `n < 2` or the ends are not positive.
pub fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    assert!(lo > 0.0 && hi > 0.0, "logspace needs positive ends");
    linspace(lo.ln(), hi.ln(), n).into_iter().map(f64::exp).collect()
}

/// All roots of `f` on the sample grid's interval: every sign change between neighbouring
/// samples is refined by Brent's method to `xtol`; a sample where `f` is exactly zero is a root;
/// a local minimum of |f| between samples that reaches |f| ≤ `ftol` without a sign change
/// (a double root, e.g. where two equilibria merge) is refined by golden-section search and
/// reported too. Roots are returned in increasing order, without duplicates closer than `xtol`.
///
/// Roots closer together than the grid spacing can be missed (an even number of sign changes
/// in one interval); choose the grid accordingly.
///
/// # Errors
/// If `f` is NaN at a sample.
pub fn all_roots(f: impl Fn(f64) -> f64, grid: &[f64], xtol: f64, ftol: f64) -> Result<Vec<f64>> {
    let values: Vec<f64> = grid.iter().map(|&x| f(x)).collect();
    if let Some(k) = values.iter().position(|v| v.is_nan()) {
        return Err(Error::Unresolvable {
            model: "all_roots",
            reason: format!("f is NaN at x = {}", grid[k]),
        });
    }
    let mut roots = Vec::new();
    for k in 0..grid.len() {
        if values[k] == 0.0 {
            roots.push(grid[k]);
        }
        if k + 1 == grid.len() {
            break;
        }
        let (a, b, fa, fb) = (grid[k], grid[k + 1], values[k], values[k + 1]);
        if fa != 0.0 && fb != 0.0 && fa.signum() != fb.signum() {
            roots.push(brent(&f, a, b, xtol)?);
        }
    }
    // Tangential roots: |f| has an interior local minimum at sample k and does not change sign.
    for k in 1..grid.len().saturating_sub(1) {
        let (fl, fc, fr) = (values[k - 1], values[k], values[k + 1]);
        let same_sign = fl.signum() == fc.signum() && fc.signum() == fr.signum() && fc != 0.0;
        if same_sign && fc.abs() <= fl.abs() && fc.abs() <= fr.abs() {
            let x = golden_min(|x| f(x).abs(), grid[k - 1], grid[k + 1], xtol);
            if f(x).abs() <= ftol {
                roots.push(x);
            }
        }
    }
    roots.sort_by(f64::total_cmp);
    roots.dedup_by(|a, b| (*a - *b).abs() <= xtol.max(f64::EPSILON * a.abs()));
    Ok(roots)
}

/// Minimum of a unimodal `g` on `[a, b]` by golden-section search to `xtol`.
pub fn golden_min(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64, xtol: f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..300 {
        if (b - a).abs() <= xtol.max(4.0 * f64::EPSILON * (a.abs() + b.abs())) {
            break;
        }
        if gc < gd {
            b = d;
            d = c;
            gd = gc;
            c = b - r * (b - a);
            gc = g(c);
        } else {
            a = c;
            c = d;
            gc = gd;
            d = a + r * (b - a);
            gd = g(d);
        }
    }
    0.5 * (a + b)
}

/// Kind of an extremum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtremumKind {
    /// Local minimum.
    Min,
    /// Local maximum.
    Max,
}

/// A local extremum (a turning point when `g` is the control along a branch).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// Location.
    pub x: f64,
    /// Value g(x).
    pub value: f64,
    /// Minimum or maximum.
    pub kind: ExtremumKind,
}

/// Interior local extrema of `g` on the grid's interval. With the derivative `dg` given, they
/// are the sign changes of `dg` refined by Brent's method; without it, samples that are local
/// extrema are refined by golden-section search.
///
/// # Errors
/// Root-finding failures (not expected for continuous `dg`).
pub fn extrema(
    g: impl Fn(f64) -> f64,
    dg: Option<&dyn Fn(f64) -> f64>,
    grid: &[f64],
    xtol: f64,
) -> Result<Vec<Extremum>> {
    let mut out = Vec::new();
    match dg {
        Some(dg) => {
            let d: Vec<f64> = grid.iter().map(|&x| dg(x)).collect();
            for k in 0..grid.len().saturating_sub(1) {
                if d[k] != 0.0 && d[k + 1] != 0.0 && d[k].signum() != d[k + 1].signum() {
                    let x = brent(dg, grid[k], grid[k + 1], xtol)?;
                    let kind = if d[k] < 0.0 {
                        ExtremumKind::Min
                    } else {
                        ExtremumKind::Max
                    };
                    out.push(Extremum { x, value: g(x), kind });
                }
            }
        }
        None => {
            let v: Vec<f64> = grid.iter().map(|&x| g(x)).collect();
            for k in 1..grid.len().saturating_sub(1) {
                let (l, c, r) = (v[k - 1], v[k], v[k + 1]);
                if c <= l && c <= r && (c < l || c < r) {
                    let x = golden_min(&g, grid[k - 1], grid[k + 1], xtol);
                    out.push(Extremum {
                        x,
                        value: g(x),
                        kind: ExtremumKind::Min,
                    });
                } else if c >= l && c >= r && (c > l || c > r) {
                    let x = golden_min(|x| -g(x), grid[k - 1], grid[k + 1], xtol);
                    out.push(Extremum {
                        x,
                        value: g(x),
                        kind: ExtremumKind::Max,
                    });
                }
            }
        }
    }
    Ok(out)
}

/// A sampled equilibrium branch: state s, control λ, and stability at each sample, in order of
/// increasing s (or any order in which neighbouring samples are neighbours on the curve).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Branch {
    /// State variable s (contact radius, gap, front position) at each sample.
    pub state: Vec<f64>,
    /// Control λ(s) at each sample.
    pub control: Vec<f64>,
    /// Whether the equilibrium is stable under control of λ.
    pub stable: Vec<bool>,
}

impl Branch {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.state.len()
    }

    /// Whether the branch has no samples.
    pub fn is_empty(&self) -> bool {
        self.state.is_empty()
    }
}

/// A point on a path: which branch, and where on it (sample index + fraction to the next).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Branch index.
    pub branch: usize,
    /// State s.
    pub state: f64,
    /// Control λ.
    pub control: f64,
}

/// A jump of the state at fixed control (an instability).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jump {
    /// State just before.
    pub from: PathPoint,
    /// State just after.
    pub to: PathPoint,
}

/// The path an experiment follows: the visited states in order and the jumps.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Path {
    /// Visited states (stable samples along the way, plus the states at the jumps).
    pub points: Vec<PathPoint>,
    /// Jumps in order of occurrence.
    pub jumps: Vec<Jump>,
}

/// Stable states at control `lambda` on all branches: interpolated crossings of λ on stable
/// segments (both ends stable).
pub fn stable_states_at(branches: &[Branch], lambda: f64) -> Vec<PathPoint> {
    let mut out = Vec::new();
    for (b, br) in branches.iter().enumerate() {
        for k in 0..br.len().saturating_sub(1) {
            if !(br.stable[k] && br.stable[k + 1]) {
                continue;
            }
            let (l0, l1) = (br.control[k], br.control[k + 1]);
            if (l0 - lambda) * (l1 - lambda) <= 0.0 && l0 != l1 {
                let t = (lambda - l0) / (l1 - l0);
                out.push(PathPoint {
                    branch: b,
                    state: br.state[k] + t * (br.state[k + 1] - br.state[k]),
                    control: lambda,
                });
            } else if l0 == lambda && l1 == lambda {
                out.push(PathPoint {
                    branch: b,
                    state: br.state[k],
                    control: lambda,
                });
            }
        }
    }
    out
}

/// Follow the stable equilibria while the control moves from `start.control` to `target`
/// monotonically: stay on the current stable segment; where it ends (a fold or loss of
/// stability) before the target, jump at that control to the stable state nearest in s in the
/// direction the state was moving when stability was lost (or, failing that, the nearest
/// stable state at all). Stops early, with the path so far, when no stable state exists.
///
/// `start` must lie on a stable segment (see [`stable_states_at`]).
pub fn follow(branches: &[Branch], start: PathPoint, target: f64) -> Path {
    let mut path = Path::default();
    let mut cur = start;
    path.points.push(cur);
    let increasing = target >= cur.control;
    for _ in 0..10_000 {
        let br = &branches[cur.branch];
        // Locate the segment containing the current state.
        let Some(k) = segment_of(br, cur.state) else { break };
        // Walk along the stable segment in the direction in which λ moves towards the target.
        let dir = walk_direction(br, k, increasing);
        let mut i = if dir > 0 { k + 1 } else { k };
        // The sample where the walk ends, and whether the target was reached there.
        let (i, reached) = loop {
            let l = br.control[i];
            let reached = if increasing { l >= target } else { l <= target };
            if !br.stable[i] || reached {
                break (i, reached);
            }
            let next = i as isize + dir;
            if next < 0 || next as usize >= br.len() {
                break (i, false);
            }
            path.points.push(PathPoint {
                branch: cur.branch,
                state: br.state[i],
                control: l,
            });
            // A fold: λ turns back.
            let ln = br.control[next as usize];
            if (increasing && ln < l) || (!increasing && ln > l) {
                break (i, false);
            }
            i = next as usize;
        };
        if reached || !br.stable[i] {
            // Interpolate the exact end: the target, or where stability ends.
            let prev = (i as isize - dir) as usize;
            let (l0, l1) = (br.control[prev], br.control[i]);
            if reached {
                let t = if l1 != l0 { (target - l0) / (l1 - l0) } else { 1.0 };
                let p = PathPoint {
                    branch: cur.branch,
                    state: br.state[prev] + t * (br.state[i] - br.state[prev]),
                    control: target,
                };
                path.points.push(p);
                return path;
            }
            cur = PathPoint {
                branch: cur.branch,
                state: br.state[prev],
                control: l0,
            };
        } else {
            cur = PathPoint {
                branch: cur.branch,
                state: br.state[i],
                control: br.control[i],
            };
        }
        // Jump at fixed control, onwards in the direction the state was moving.
        let back = (i as isize - dir).clamp(0, br.len() as isize - 1) as usize;
        let moving = (br.state[i] - br.state[back]).signum() * if back == i { 0.0 } else { 1.0 };
        let candidates: Vec<PathPoint> = stable_states_at(branches, cur.control)
            .into_iter()
            .filter(|p| {
                !(p.branch == cur.branch && (p.state - cur.state).abs() <= 1e-12 * (1.0 + cur.state.abs()))
            })
            .collect();
        let forward: Vec<&PathPoint> = candidates
            .iter()
            .filter(|p| p.branch != cur.branch || (p.state - cur.state) * moving > 0.0)
            .collect();
        let pick = forward
            .iter()
            .copied()
            .min_by(|a, b| {
                (a.state - cur.state)
                    .abs()
                    .total_cmp(&(b.state - cur.state).abs())
            })
            .or_else(|| {
                candidates.iter().min_by(|a, b| {
                    (a.state - cur.state)
                        .abs()
                        .total_cmp(&(b.state - cur.state).abs())
                })
            })
            .copied();
        let Some(to) = pick else {
            path.points.push(cur);
            return path;
        };
        path.points.push(cur);
        path.jumps.push(Jump { from: cur, to });
        path.points.push(to);
        cur = to;
    }
    path
}

/// Index k of the segment [k, k+1] containing `state` (nearest sample's segment).
fn segment_of(br: &Branch, state: f64) -> Option<usize> {
    if br.len() < 2 {
        return None;
    }
    let k = (0..br.len()).min_by(|&a, &b| {
        (br.state[a] - state)
            .abs()
            .total_cmp(&(br.state[b] - state).abs())
    })?;
    Some(k.min(br.len() - 2))
}

/// +1 to walk to higher indices, −1 to lower, so that λ moves towards the target.
fn walk_direction(br: &Branch, k: usize, increasing: bool) -> isize {
    let up = br.control[k + 1] >= br.control[k];
    if up == increasing { 1 } else { -1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_roots_finds_simple_and_double_roots() {
        // (x − 1)(x − 2)²(x + 0.5): a simple root at 1 and −0.5, a double root at 2.
        let f = |x: f64| (x - 1.0) * (x - 2.0).powi(2) * (x + 0.5);
        let roots = all_roots(f, &linspace(-1.0, 3.0, 41), 1e-12, 1e-14).unwrap();
        assert_eq!(roots.len(), 3, "{roots:?}");
        assert!((roots[0] + 0.5).abs() < 1e-10);
        assert!((roots[1] - 1.0).abs() < 1e-10);
        assert!((roots[2] - 2.0).abs() < 1e-6);
    }

    #[test]
    fn extrema_of_a_cubic() {
        let g = |x: f64| x * x * x - 3.0 * x;
        let dg = |x: f64| 3.0 * x * x - 3.0;
        let e = extrema(g, Some(&dg), &linspace(-3.0, 3.0, 20), 1e-14).unwrap();
        assert_eq!(e.len(), 2);
        assert_eq!(e[0].kind, ExtremumKind::Max);
        assert!((e[0].x + 1.0).abs() < 1e-12 && (e[1].x - 1.0).abs() < 1e-12);
        let e2 = extrema(g, None, &linspace(-3.0, 3.0, 20), 1e-10).unwrap();
        assert!((e2[1].x - 1.0).abs() < 1e-6);
    }

    /// An S-shaped equilibrium curve λ(s) = s³ − 3s, stable where dλ/ds > 0 (|s| > 1): loading
    /// from λ = −4 jumps at the fold λ = 2 (s = −1) to the other stable segment (s = 2), and
    /// unloading jumps back at λ = −2 (s = 1 → s = −2). The classic hysteresis loop.
    #[test]
    fn follow_jumps_at_folds_in_both_directions() {
        let s = linspace(-2.5, 2.5, 501);
        let control: Vec<f64> = s.iter().map(|&x| x * x * x - 3.0 * x).collect();
        let stable: Vec<bool> = s.iter().map(|&x| 3.0 * x * x - 3.0 > 0.0).collect();
        let br = vec![Branch {
            state: s.clone(),
            control,
            stable,
        }];
        let start = stable_states_at(&br, -4.0)
            .into_iter()
            .min_by(|a, b| a.state.total_cmp(&b.state))
            .unwrap();
        let up = follow(&br, start, 4.0);
        assert_eq!(up.jumps.len(), 1);
        let j = up.jumps[0];
        assert!((j.from.control - 2.0).abs() < 1e-3 && (j.from.state + 1.0).abs() < 0.03);
        assert!((j.to.state - 2.0).abs() < 1e-3);
        assert!((up.points.last().unwrap().control - 4.0).abs() < 1e-12);
        let down = follow(&br, *up.points.last().unwrap(), -4.0);
        assert_eq!(down.jumps.len(), 1);
        assert!((down.jumps[0].from.control + 2.0).abs() < 1e-3);
        assert!((down.jumps[0].to.state + 2.0).abs() < 1e-3);
    }
}
