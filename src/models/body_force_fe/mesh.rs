//! The graded triangular mesh of the axisymmetric tip (section 4.2.2): the tip occupies
//! r ≤ r0, z_s(r) ≤ z ≤ z_s(r) + h0, the region B0 of (4.8) (a body of radius r0 and height h0
//! whose bottom face is the profile (4.10) and whose top face is that profile raised by h0).
//!
//! The mesh is built in a parametric rectangle (ρ, s) ∈ [0, r0] × [0, S] as a balanced
//! quadtree: squares of the surface element width h along the bottom edge of the fine zone
//! ρ ≤ r_f, growing by a factor `grading` with the distance from it, neighbours differing by at
//! most one level. Each leaf is cut into two triangles, or fanned from its centre where a finer
//! neighbour puts a node on its edge, so the mesh is conforming. The map to the tip,
//!
//! ```text
//! r = ρ,   z = z_s(r) + T(s),
//! ```
//!
//! lays the rows along the surface profile, with T(s) stretching the rows next to the surface
//! into thin layers: T'(s) = (t1/h) q^(s/h) from a first layer of thickness ≈ t1 (well below
//! the interaction range), growing by q per element width until the elements are square, and
//! linear beyond, up to T(S) = h0. Lengths are in any unit, the caller's.

use std::collections::{HashMap, HashSet};

use crate::error::{Error, Result};

/// Largest number of quadtree leaves a mesh may have (about twice as many triangles).
pub const MAX_LEAVES: usize = 400_000;

/// Geometry and grading of a mesh (lengths in the caller's unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSpec {
    /// Radius r0 of the tip.
    pub r0: f64,
    /// Height h0 of the tip (the top face is the bottom face raised by h0).
    pub h0: f64,
    /// Element width h along the surface of the fine zone (an upper bound: the mesh uses
    /// r0/(n 2^k) ≤ h with 8 ≤ n ≤ 16, which lies within (8/9 h, h] where r0 ≥ 8 h).
    pub width: f64,
    /// Radius r_f of the fine zone.
    pub fine_radius: f64,
    /// Thickness t1 of the first layer at the surface.
    pub first_layer: f64,
    /// Growth q of the layer thickness per element width (> 1).
    pub layer_growth: f64,
    /// Growth of the element size with the distance from the fine zone (size ≤ h + grading ·
    /// distance).
    pub grading: f64,
}

/// A conforming mesh of linear triangles.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Node positions (r, z).
    pub nodes: Vec<[f64; 2]>,
    /// Triangles, nodes counter-clockwise in the (r, z) plane.
    pub triangles: Vec<[usize; 3]>,
    /// Nodes on the bottom face (the tip's surface), by increasing r.
    pub surface: Vec<usize>,
    /// Nodes on the top face.
    pub top: Vec<usize>,
    /// Nodes on the axis r = 0.
    pub axis: Vec<usize>,
    /// The element width along the fine zone actually used.
    pub width: f64,
}

/// The stretch T(s) of the parametric height into the tip's height.
#[derive(Debug, Clone, Copy)]
struct Stretch {
    /// Width h (one parametric unit of the fine rows).
    h: f64,
    /// Thickness of the first layer t1.
    t1: f64,
    /// ln q.
    ln_q: f64,
    /// Where the layers become square, s*.
    s_star: f64,
    /// T(s*).
    t_star: f64,
    /// Slope of T beyond s*.
    slope: f64,
}

impl Stretch {
    fn new(h: f64, t1: f64, q: f64) -> Self {
        let ln_q = q.ln();
        let s_star = if t1 < h { h * (h / t1).ln() / ln_q } else { 0.0 };
        let t_star = if t1 < h {
            t1 * ((s_star / h * ln_q).exp() - 1.0) / ln_q
        } else {
            0.0
        };
        Self {
            h,
            t1,
            ln_q,
            s_star,
            t_star,
            slope: 1.0,
        }
    }

    fn at(&self, s: f64) -> f64 {
        if s <= self.s_star {
            self.t1 * ((s / self.h * self.ln_q).exp() - 1.0) / self.ln_q
        } else {
            self.t_star + self.slope * (s - self.s_star)
        }
    }
}

/// A quadtree cell: lower-left corner and side, in units of the finest width.
type Cell = (u64, u64, u64);

impl Mesh {
    /// Build the mesh of a tip with bottom profile `profile(r)` (0 at the apex, increasing).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `r0`, `h0`, `element_width`, `fine_radius`,
    /// `first_layer`, `layer_growth` or `grading` where they give no valid mesh (a tip lower
    /// than its graded surface layers, a fine zone wider than the tip, more than
    /// [`MAX_LEAVES`] leaves).
    pub fn new(spec: &MeshSpec, profile: impl Fn(f64) -> f64) -> Result<Self> {
        let positive = Error::require_positive;
        positive("r0", spec.r0)?;
        positive("h0", spec.h0)?;
        positive("element_width", spec.width)?;
        positive("fine_radius", spec.fine_radius)?;
        positive("first_layer", spec.first_layer)?;
        positive("grading", spec.grading)?;
        if !(spec.layer_growth > 1.0 && spec.layer_growth <= 4.0) {
            return Err(Error::invalid(
                "layer_growth",
                spec.layer_growth,
                "must lie in (1, 4]",
            ));
        }
        if spec.fine_radius >= spec.r0 {
            return Err(Error::invalid(
                "r0",
                spec.r0,
                format!("must exceed the fine zone's radius {:.4e}", spec.fine_radius),
            ));
        }
        // Root cells of side N = 2^k finest widths, n_r ∈ [8, 16] of them across r0 (fewer
        // where r0 spans fewer than 8 widths), so that the finest width r0/(n_r N) is the
        // requested width to within 1/8 (see [`root_cells`]).
        let ratio = spec.r0 / spec.width;
        if !(ratio.is_finite() && ratio < 2f64.powi(40)) {
            return Err(Error::invalid(
                "element_width",
                spec.width,
                "is too small for the tip radius r0",
            ));
        }
        let (side, n_r) = root_cells(ratio);
        let h = spec.r0 / (n_r * side) as f64;
        let mut stretch = Stretch::new(h, spec.first_layer.min(h), spec.layer_growth);
        if spec.h0 <= stretch.t_star {
            return Err(Error::invalid(
                "h0",
                spec.h0,
                format!(
                    "must exceed the graded surface layers' height {:.4e}",
                    stretch.t_star
                ),
            ));
        }
        let s_needed = stretch.s_star + (spec.h0 - stretch.t_star);
        let n_s = (s_needed / (side as f64 * h)).ceil().max(1.0) as u64;
        let s_total = (n_s * side) as f64 * h;
        stretch.slope = (spec.h0 - stretch.t_star) / (s_total - stretch.s_star);

        // Refinement: a cell is split while its side exceeds h + grading · distance to the
        // fine segment {ρ ≤ r_f, s = 0}.
        let fine_units = spec.fine_radius / h;
        let target = |(i, j, _): Cell| {
            let (x0, y0) = (i as f64, j as f64);
            let dx = (x0 - fine_units).max(0.0);
            let dist = (dx * dx + y0 * y0).sqrt();
            1.0 + spec.grading * dist
        };
        let mut leaves: HashSet<Cell> = HashSet::new();
        let mut stack: Vec<Cell> = Vec::new();
        for a in 0..n_r {
            for b in 0..n_s {
                stack.push((a * side, b * side, side));
            }
        }
        let too_many = |n: usize| {
            Error::invalid(
                "element_width",
                spec.width,
                format!(
                    "gives more than {n} mesh cells; use wider elements, a smaller fine zone or a larger grading"
                ),
            )
        };
        while let Some(c @ (i, j, n)) = stack.pop() {
            if n > 1 && n as f64 > target(c) {
                let m = n / 2;
                stack.extend([(i, j, m), (i + m, j, m), (i, j + m, m), (i + m, j + m, m)]);
            } else {
                leaves.insert(c);
            }
            if leaves.len() + stack.len() > MAX_LEAVES {
                return Err(too_many(MAX_LEAVES));
            }
        }
        let (width_units, height_units) = (n_r * side, n_s * side);
        balance(&mut leaves, width_units, height_units, side);
        if leaves.len() > MAX_LEAVES {
            return Err(too_many(MAX_LEAVES));
        }

        // Nodes at the leaves' corners, then triangles.
        let mut sorted: Vec<Cell> = leaves.iter().copied().collect();
        sorted.sort_unstable();
        let mut index: HashMap<(u64, u64), usize> = HashMap::new();
        let mut param: Vec<(f64, f64)> = Vec::new();
        fn node(
            index: &mut HashMap<(u64, u64), usize>,
            param: &mut Vec<(f64, f64)>,
            x: u64,
            y: u64,
        ) -> usize {
            *index.entry((x, y)).or_insert_with(|| {
                param.push((x as f64, y as f64));
                param.len() - 1
            })
        }
        for &(i, j, n) in &sorted {
            for (x, y) in [(i, j), (i + n, j), (i + n, j + n), (i, j + n)] {
                node(&mut index, &mut param, x, y);
            }
        }
        let mut triangles = Vec::with_capacity(sorted.len() * 3);
        for &(i, j, n) in &sorted {
            let corners = [(i, j), (i + n, j), (i + n, j + n), (i, j + n)];
            let mut ring: Vec<usize> = Vec::with_capacity(8);
            let mut hanging = false;
            for e in 0..4 {
                let (a, b) = (corners[e], corners[(e + 1) % 4]);
                ring.push(index[&a]);
                if n >= 2 {
                    let mid = ((a.0 + b.0) / 2, (a.1 + b.1) / 2);
                    if let Some(&m) = index.get(&mid) {
                        ring.push(m);
                        hanging = true;
                    }
                }
            }
            if hanging {
                let c = node(&mut index, &mut param, i + n / 2, j + n / 2);
                for k in 0..ring.len() {
                    triangles.push([ring[k], ring[(k + 1) % ring.len()], c]);
                }
            } else {
                triangles.push([ring[0], ring[1], ring[2]]);
                triangles.push([ring[0], ring[2], ring[3]]);
            }
        }
        let nodes: Vec<[f64; 2]> = param
            .iter()
            .map(|&(x, y)| {
                let r = x * h;
                let t = stretch.at(y * h);
                [r, profile(r) + t]
            })
            .collect();
        let mut surface: Vec<usize> = (0..param.len()).filter(|&k| param[k].1 == 0.0).collect();
        surface.sort_by(|&a, &b| param[a].0.total_cmp(&param[b].0));
        let top = (0..param.len())
            .filter(|&k| param[k].1 == height_units as f64)
            .collect();
        let axis = (0..param.len()).filter(|&k| param[k].0 == 0.0).collect();
        Ok(Self {
            nodes,
            triangles,
            surface,
            top,
            axis,
            width: h,
        })
    }

    /// A uniform mesh of the rectangle [0, r0] × [0, h0]: `nr` × `nz` squares, each cut into
    /// two triangles (for tests and benchmarks of the elasticity alone).
    pub fn uniform(r0: f64, h0: f64, nr: usize, nz: usize) -> Self {
        let id = |i: usize, j: usize| j * (nr + 1) + i;
        let nodes = (0..=nz)
            .flat_map(|j| (0..=nr).map(move |i| [r0 * i as f64 / nr as f64, h0 * j as f64 / nz as f64]))
            .collect();
        let mut triangles = Vec::with_capacity(2 * nr * nz);
        for j in 0..nz {
            for i in 0..nr {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        Self {
            nodes,
            triangles,
            surface: (0..=nr).map(|i| id(i, 0)).collect(),
            top: (0..=nr).map(|i| id(i, nz)).collect(),
            axis: (0..=nz).map(|j| id(0, j)).collect(),
            width: r0 / nr as f64,
        }
    }

    /// Signed area of triangle `t` in the (r, z) plane (positive: counter-clockwise).
    pub fn area(&self, t: usize) -> f64 {
        let [a, b, c] = self.triangles[t].map(|k| self.nodes[k]);
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
    }
}

/// The root cells of a quadtree whose finest cells are r0/(n_r N) ≤ w wide, for `ratio` =
/// r0/w: their side N = 2^k (in finest widths) and their number n_r across r0.
///
/// With N = 2^(k−3) for 2^k ≤ ratio < 2^(k+1), n_r = ⌈ratio/N⌉ lies in [8, 16] and
/// ratio ≤ n_r N < ratio + N ≤ (9/8) ratio: the finest width lies within (8/9 w, w]. Where r0
/// spans fewer than 8 widths, N = 1 and the width is r0/⌈ratio⌉, the widest uniform one not
/// above w.
fn root_cells(ratio: f64) -> (u64, u64) {
    let k = ratio.log2().floor().max(3.0) as u32 - 3;
    let side: u64 = 1 << k;
    let n_r = (ratio / side as f64).ceil().max(1.0) as u64;
    (side, n_r)
}

/// Split leaves until neighbours across an edge differ by at most one level.
fn balance(leaves: &mut HashSet<Cell>, width: u64, height: u64, root: u64) {
    // The leaf containing the finest cell (x, y).
    let find = |leaves: &HashSet<Cell>, x: u64, y: u64| {
        let mut n = 1;
        while n <= root {
            let c = (x - x % n, y - y % n, n);
            if leaves.contains(&c) {
                return Some(c);
            }
            n *= 2;
        }
        None
    };
    loop {
        let mut split: HashSet<Cell> = HashSet::new();
        for &(i, j, n) in leaves.iter() {
            // A finest cell just outside each edge.
            let mut probes = Vec::with_capacity(4);
            if i + n < width {
                probes.push((i + n, j));
            }
            if i > 0 {
                probes.push((i - 1, j));
            }
            if j + n < height {
                probes.push((i, j + n));
            }
            if j > 0 {
                probes.push((i, j - 1));
            }
            for (x, y) in probes {
                if let Some(c) = find(leaves, x, y)
                    && c.2 > 2 * n
                {
                    split.insert(c);
                }
            }
        }
        if split.is_empty() {
            return;
        }
        for (i, j, n) in split {
            leaves.remove(&(i, j, n));
            let m = n / 2;
            leaves.extend([(i, j, m), (i + m, j, m), (i, j + m, m), (i + m, j + m, m)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> MeshSpec {
        MeshSpec {
            r0: 400.0,
            h0: 400.0,
            width: 1.0,
            fine_radius: 30.0,
            first_layer: 0.1,
            layer_growth: 1.3,
            grading: 0.3,
        }
    }

    /// Every triangle is counter-clockwise with positive area, the areas sum to the tip's
    /// cross-section ∫ (h0 − z_s(r)) dr, and every edge is shared by two triangles or lies on
    /// the boundary (no hanging node: a node inside an edge would leave both halves unpaired).
    #[test]
    fn the_mesh_is_conforming_and_covers_the_tip() {
        let radius = 1000.0;
        let profile = |r: f64| r * r / (2.0 * radius);
        let s = spec();
        let mesh = Mesh::new(&s, profile).unwrap();
        let mut total = 0.0;
        let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
        for t in 0..mesh.triangles.len() {
            let a = mesh.area(t);
            assert!(a > 0.0, "triangle {t} has area {a}");
            total += a;
            let tri = mesh.triangles[t];
            for e in 0..3 {
                let (p, q) = (tri[e], tri[(e + 1) % 3]);
                *edges.entry((p.min(q), p.max(q))).or_default() += 1;
            }
        }
        // The cross-section between the polygons of the top and bottom faces.
        let under = |nodes: &[usize]| {
            let mut pts: Vec<[f64; 2]> = nodes.iter().map(|&k| mesh.nodes[k]).collect();
            pts.sort_by(|a, b| a[0].total_cmp(&b[0]));
            pts.windows(2)
                .map(|w| 0.5 * (w[1][0] - w[0][0]) * (w[0][1] + w[1][1]))
                .sum::<f64>()
        };
        let exact = under(&mesh.top) - under(&mesh.surface);
        assert!((exact / (s.r0 * s.h0) - 1.0).abs() < 0.01);
        assert!((total - exact).abs() < 1e-9 * exact, "{total} vs {exact}");
        let boundary = edges.values().filter(|&&c| c == 1).count();
        assert!(edges.values().all(|&c| c == 1 || c == 2));
        // Boundary edges: along the four sides, the number of boundary nodes on them.
        let on_side = |k: usize| {
            let r = mesh.nodes[k][0];
            r == 0.0 || r == s.r0 || mesh.top.contains(&k) || mesh.surface.contains(&k)
        };
        let n_side = (0..mesh.nodes.len()).filter(|&k| on_side(k)).count();
        assert_eq!(boundary, n_side, "boundary edges vs boundary nodes");
        // The fine zone has uniform surface elements of the requested width: 13 root cells of
        // 32 widths across r0 = 400.
        assert!((mesh.width - 400.0 / 416.0).abs() < 1e-12);
        let first_gap = mesh.nodes[mesh.surface[1]][0] - mesh.nodes[mesh.surface[0]][0];
        assert!((first_gap - mesh.width).abs() < 1e-12);
    }

    /// The first layer is about t1 thick and the layers grow by about q.
    #[test]
    fn surface_layers_are_thin_and_graded() {
        let mesh = Mesh::new(&spec(), |_| 0.0).unwrap();
        let mut on_axis: Vec<f64> = mesh.axis.iter().map(|&k| mesh.nodes[k][1]).collect();
        on_axis.sort_by(f64::total_cmp);
        let t1 = on_axis[1] - on_axis[0];
        let t2 = on_axis[2] - on_axis[1];
        assert!((t1 / 0.1 - 1.0).abs() < 0.15, "first layer {t1}");
        assert!((t2 / t1 - 1.3).abs() < 0.05, "growth {}", t2 / t1);
        assert!((on_axis.last().unwrap() - 400.0).abs() < 1e-9);
    }

    /// The finest width is the requested one to within 1/8, (8/9 w, w], for widths at and
    /// between powers of two of r0, and the surface nodes of the fine zone are that far apart.
    /// At r0 = 200 µm, 6.2 and 7.8 nm (once both 6.10 nm) give different meshes.
    #[test]
    fn the_finest_width_is_the_requested_one_to_within_an_eighth() {
        for r0 in [400.0, 1000.0, 2.0e5] {
            for w in [0.3, 0.5, 1.0, 1.7, 3.3, 6.2, 7.8, 12.5, 24.0] {
                let s = MeshSpec {
                    r0,
                    h0: r0,
                    width: w,
                    fine_radius: 40.0,
                    ..spec()
                };
                let mesh = Mesh::new(&s, |r| r * r / 2000.0).unwrap();
                let h = mesh.width;
                assert!(
                    h <= w * (1.0 + 1e-12) && h > w * 8.0 / 9.0,
                    "r0 {r0}, width {w}: finest {h}"
                );
                let gap = mesh.nodes[mesh.surface[1]][0] - mesh.nodes[mesh.surface[0]][0];
                assert!((gap / h - 1.0).abs() < 1e-9, "r0 {r0}, width {w}: gap {gap}");
            }
        }
        let at = |w: f64| {
            Mesh::new(
                &MeshSpec {
                    r0: 2.0e5,
                    h0: 2.0e5,
                    width: w,
                    fine_radius: 200.0,
                    ..spec()
                },
                |_| 0.0,
            )
            .unwrap()
        };
        let (fine, coarse) = (at(6.2), at(7.8));
        assert!((fine.width - 2.0e5 / 32768.0).abs() < 1e-9, "{}", fine.width);
        assert!((coarse.width - 2.0e5 / 26624.0).abs() < 1e-9, "{}", coarse.width);
        assert!(
            fine.nodes.len() > coarse.nodes.len(),
            "{} nodes at 6.2 against {} at 7.8",
            fine.nodes.len(),
            coarse.nodes.len()
        );
    }

    /// A tip spanning fewer than 8 widths gets the widest uniform width not above the request.
    #[test]
    fn a_narrow_tip_gets_the_widest_uniform_width_not_above_the_request() {
        for (ratio, side, n_r) in [(0.5, 1, 1), (1.0, 1, 1), (3.2, 1, 4), (7.9, 1, 8), (8.0, 1, 8)] {
            assert_eq!(root_cells(ratio), (side, n_r), "ratio {ratio}");
        }
        assert_eq!(root_cells(16.0), (2, 8));
        assert_eq!(root_cells(17.0), (2, 9));
        assert_eq!(root_cells(31.9), (2, 16));
    }

    #[test]
    fn a_tip_lower_than_its_surface_layers_names_h0() {
        let mut s = spec();
        s.h0 = 1.0;
        let e = Mesh::new(&s, |r| r * r / 2000.0).unwrap_err().to_string();
        assert!(e.contains("`h0`"), "{e}");
    }
}
