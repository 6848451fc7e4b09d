//! Assembly of the axisymmetric stiffness of a [`Mesh`] into the lower triangle of a sparse
//! symmetric matrix (section 4.2.2, the bilinear form a(u, v) of (4.18)).
//!
//! The pattern is built from the node adjacency (each node's neighbours, sorted), row by row,
//! so that it costs O(entries) without hashing; element matrices are computed in parallel from
//! their strain forms ([`StrainForm::stiffness`]) and added at positions found by binary
//! search in the short rows.

use rayon::prelude::*;

use crate::models::body_force_fe::element::StrainForm;
use crate::models::body_force_fe::mesh::Mesh;

/// A constrained degree of freedom.
pub const FIXED: usize = usize::MAX;

/// The assembled stiffness: the lower triangle (row ≥ column, diagonal included), rows in
/// increasing order and columns increasing within each row.
#[derive(Debug, Clone)]
pub struct Assembled {
    /// Number of unknowns.
    pub n: usize,
    /// Positions (row, column).
    pub pattern: Vec<(usize, usize)>,
    /// Start of each row in `pattern` (n + 1 entries).
    pub row_start: Vec<usize>,
    /// Values in pattern order.
    pub values: Vec<f64>,
    /// Strain form of each element.
    pub forms: Vec<StrainForm>,
}

impl Assembled {
    /// The position of entry (`a`, `b`) of the lower triangle (either order), `None` when
    /// either dof is [`FIXED`] or the entry is not in the pattern.
    pub fn slot(&self, a: usize, b: usize) -> Option<usize> {
        if a == FIXED || b == FIXED {
            return None;
        }
        let (r, c) = (a.max(b), a.min(b));
        let row = &self.pattern[self.row_start[r]..self.row_start[r + 1]];
        row.binary_search_by(|&(_, col)| col.cmp(&c))
            .ok()
            .map(|k| self.row_start[r] + k)
    }
}

/// The free dofs of a tip held at its top (u_r = u_z = 0) with no radial displacement on the
/// axis: (u_r, u_z) of each node, [`FIXED`] where constrained, and their number.
pub fn held_top_dofs(mesh: &Mesh) -> (Vec<[usize; 2]>, usize) {
    let mut fixed = vec![[false; 2]; mesh.nodes.len()];
    for &k in &mesh.top {
        fixed[k] = [true, true];
    }
    for &k in &mesh.axis {
        fixed[k][0] = true;
    }
    let mut n = 0;
    let dofs = fixed
        .iter()
        .map(|f| {
            f.map(|fx| {
                if fx {
                    FIXED
                } else {
                    n += 1;
                    n - 1
                }
            })
        })
        .collect();
    (dofs, n)
}

/// Assemble the stiffness of `mesh` with the elasticity matrix `d` (order rr, zz, θθ, rz) for
/// the free dofs `dofs` ((u_r, u_z) of each node, [`FIXED`] where constrained), `n` of them.
pub fn assemble(mesh: &Mesh, dofs: &[[usize; 2]], n: usize, d: &[[f64; 4]; 4]) -> Assembled {
    let n_nodes = mesh.nodes.len();
    // Node adjacency through the triangles.
    let mut adjacency: Vec<Vec<u32>> = vec![Vec::new(); n_nodes];
    for tri in &mesh.triangles {
        for &a in tri {
            for &b in tri {
                adjacency[a].push(b as u32);
            }
        }
    }
    adjacency.par_iter_mut().for_each(|list| {
        list.sort_unstable();
        list.dedup();
    });
    // Columns of each dof row: the dofs of the neighbouring nodes not above the row.
    let mut rows: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (a, list) in adjacency.iter().enumerate() {
        for &row in &dofs[a] {
            if row == FIXED {
                continue;
            }
            for &b in list {
                for &col in &dofs[b as usize] {
                    if col != FIXED && col <= row {
                        rows[row].push(col);
                    }
                }
            }
        }
    }
    let mut pattern = Vec::with_capacity(rows.iter().map(Vec::len).sum());
    let mut row_start = Vec::with_capacity(n + 1);
    for (r, cols) in rows.iter_mut().enumerate() {
        cols.sort_unstable();
        row_start.push(pattern.len());
        pattern.extend(cols.iter().map(|&c| (r, c)));
    }
    row_start.push(pattern.len());
    let forms: Vec<StrainForm> = mesh
        .triangles
        .par_iter()
        .map(|tri| StrainForm::new(tri.map(|k| mesh.nodes[k])))
        .collect();
    let mut assembled = Assembled {
        n,
        values: vec![0.0; pattern.len()],
        pattern,
        row_start,
        forms,
    };
    let matrices: Vec<[[f64; 6]; 6]> = assembled.forms.par_iter().map(|f| f.stiffness(d)).collect();
    for (tri, ke) in mesh.triangles.iter().zip(&matrices) {
        let local: [usize; 6] = std::array::from_fn(|i| dofs[tri[i / 2]][i % 2]);
        for i in 0..6 {
            for j in 0..=i {
                if let Some(at) = assembled.slot(local[i], local[j]) {
                    // Each unordered pair of distinct local dofs appears once here.
                    assembled.values[at] += ke[i][j];
                }
            }
        }
    }
    assembled
}
