//! Test energies of the Newton minimiser: chains of double wells w(x) = x⁴/4 − x²/2 coupled by
//! springs, with and without the local evaluations the iterative path's local moves use, and
//! the options that select that path.

use super::{Energy, LinearSolver, NewtonOptions};

/// A chain of double wells w(x) = x⁴/4 − x²/2 coupled by springs c(x_{i+1} − x_i)²/2: the
/// origin is a stationary point that is a maximum (c small), the minima are near ±1.
pub(super) struct Wells {
    pub(super) n: usize,
    pub(super) c: f64,
}

impl Energy for Wells {
    fn dim(&self) -> usize {
        self.n
    }
    fn energy(&self, x: &[f64]) -> f64 {
        let wells: f64 = x.iter().map(|v| v.powi(4) / 4.0 - v * v / 2.0).sum();
        let springs: f64 = x.windows(2).map(|w| 0.5 * self.c * (w[1] - w[0]).powi(2)).sum();
        wells + springs
    }
    fn gradient(&self, x: &[f64], g: &mut [f64]) {
        for i in 0..self.n {
            g[i] = x[i].powi(3) - x[i];
            if i > 0 {
                g[i] += self.c * (x[i] - x[i - 1]);
            }
            if i + 1 < self.n {
                g[i] += self.c * (x[i] - x[i + 1]);
            }
        }
    }
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let mut p: Vec<(usize, usize)> = (0..self.n).map(|i| (i, i)).collect();
        p.extend((1..self.n).map(|i| (i, i - 1)));
        p
    }
    fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
        for i in 0..self.n {
            let deg = usize::from(i > 0) + usize::from(i + 1 < self.n);
            v[i] = 3.0 * x[i] * x[i] - 1.0 + self.c * deg as f64;
        }
        for k in 0..self.n.saturating_sub(1) {
            v[self.n + k] = -self.c;
        }
    }
}

/// The chain of wells with its one-coordinate energy offered.
pub(super) struct WellsAlong(pub(super) Wells);

impl Energy for WellsAlong {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn energy(&self, x: &[f64]) -> f64 {
        self.0.energy(x)
    }
    fn gradient(&self, x: &[f64], g: &mut [f64]) {
        self.0.gradient(x, g);
    }
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.0.hessian_pattern()
    }
    fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
        self.0.hessian_values(x, v);
    }
    fn along_coordinate(&self, x: &[f64], i: usize, s: f64) -> Option<(f64, f64, f64)> {
        let c = self.0.c;
        let (mut e, mut d, mut h) = (s.powi(4) / 4.0 - s * s / 2.0, s.powi(3) - s, 3.0 * s * s - 1.0);
        for j in [i.checked_sub(1), (i + 1 < self.0.n).then_some(i + 1)]
            .into_iter()
            .flatten()
        {
            e += 0.5 * c * (s - x[j]).powi(2);
            d += c * (s - x[j]);
            h += c;
        }
        Some((e, d, h))
    }
}

/// Double wells w(x) = x⁴/4 − x²/2 in a uniform field b (energy −b·x each), coupled in a
/// chain by springs c(x_{i+1} − x_i)²/2, offering both local evaluations.
pub(super) struct FieldWells {
    pub(super) n: usize,
    pub(super) c: f64,
    pub(super) b: f64,
}

impl FieldWells {
    fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> {
        [i.checked_sub(1), (i + 1 < self.n).then_some(i + 1)]
            .into_iter()
            .flatten()
    }
}

impl Energy for FieldWells {
    fn dim(&self) -> usize {
        self.n
    }
    fn energy(&self, x: &[f64]) -> f64 {
        let wells: f64 = x.iter().map(|v| v.powi(4) / 4.0 - v * v / 2.0 - self.b * v).sum();
        let springs: f64 = x.windows(2).map(|w| 0.5 * self.c * (w[1] - w[0]).powi(2)).sum();
        wells + springs
    }
    fn gradient(&self, x: &[f64], g: &mut [f64]) {
        for i in 0..self.n {
            g[i] = x[i].powi(3) - x[i] - self.b;
            for j in self.neighbours(i) {
                g[i] += self.c * (x[i] - x[j]);
            }
        }
    }
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let mut p: Vec<(usize, usize)> = (0..self.n).map(|i| (i, i)).collect();
        p.extend((1..self.n).map(|i| (i, i - 1)));
        p
    }
    fn hessian_values(&self, x: &[f64], v: &mut [f64]) {
        for i in 0..self.n {
            v[i] = 3.0 * x[i] * x[i] - 1.0 + self.c * self.neighbours(i).count() as f64;
        }
        for k in 0..self.n.saturating_sub(1) {
            v[self.n + k] = -self.c;
        }
    }
    fn along_coordinate(&self, x: &[f64], i: usize, s: f64) -> Option<(f64, f64, f64)> {
        let (mut e, mut d, mut h) = (
            s.powi(4) / 4.0 - s * s / 2.0 - self.b * s,
            s.powi(3) - s - self.b,
            3.0 * s * s - 1.0,
        );
        for j in self.neighbours(i) {
            e += 0.5 * self.c * (s - x[j]).powi(2);
            d += self.c * (s - x[j]);
            h += self.c;
        }
        Some((e, d, h))
    }
    fn local_energy(&self, x: &[f64], set: &[usize], grad: &mut [f64]) -> Option<f64> {
        let mut e = 0.0;
        for (gi, &i) in grad.iter_mut().zip(set) {
            let s = x[i];
            e += s.powi(4) / 4.0 - s * s / 2.0 - self.b * s;
            *gi = s.powi(3) - s - self.b;
            for j in self.neighbours(i) {
                *gi += self.c * (s - x[j]);
                if j > i || set.binary_search(&j).is_err() {
                    e += 0.5 * self.c * (s - x[j]).powi(2);
                }
            }
        }
        Some(e)
    }
}

/// The default options with the iterative linear algebra.
pub(super) fn iterative() -> NewtonOptions {
    NewtonOptions {
        linear: LinearSolver::Iterative,
        ..NewtonOptions::default()
    }
}
