//! The local moves of the iterative path: instabilities resolved where they are, at a cost in
//! proportion to the unknowns they move rather than to the whole system. Unknowns past their
//! own fold jump along their axes to their next minimum, and the avalanche they start spreads
//! to their neighbours ([`jump_along_coordinates`]); the region around whatever moved, or
//! around a few unknowns far out of balance, is relaxed by a small stable Newton of its own
//! ([`settle`], [`relax_region`]); unstable groups move along their own lowest mode, found on a
//! small patch of the Hessian ([`escape_patches`], [`escape_around`]); a move along an axis or a
//! mode goes downhill to the first minimum on that line ([`descend_1d`]), so that no barrier is
//! crossed. The moves read the iteration's Hessian as a [`Tangent`]; those of one unknown or of
//! a group need the energy's local evaluations ([`Energy::along_coordinate`],
//! [`Energy::local_energy`]) and do nothing without them.

use nalgebra::DMatrix;
use std::collections::VecDeque;

use super::{Energy, NewtonReport, armijo};
use crate::numerics::envelope::Envelope;
use crate::numerics::pcg::{SymmetricPattern, dot, inf_norm};

/// Move every unknown past its own fold downhill along its axis to its next minimum, one after
/// the other (coordinate descent; each move lowers the energy and stops at the first minimum
/// met, so no barrier is crossed). The candidates are the rows that are not diagonally
/// dominant and the `unbalanced` unknowns; one jumps when its descent crosses non-positive
/// curvature. The jump spreads as it
/// does in the system: the neighbours (in the Hessian's pattern) of an unknown that jumped are
/// relaxed along their axes in turn, and pass the jump on when they jumped as well. An
/// avalanche thus costs work in proportion to the unknowns it moves, not one global iteration
/// per generation; [`settle`] then relaxes its surroundings. Returns what happened
/// ([`Jumps`]): nothing also when the energy does not offer [`Energy::along_coordinate`].
pub(super) fn jump_along_coordinates(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    g: &[f64],
    unbalanced: &[usize],
    rep: &mut NewtonReport,
) -> Jumps {
    let Tangent {
        pattern, diag, off, ..
    } = *h;
    let n = x.len();
    let mut out = Jumps::default();
    if n == 0 || energy.along_coordinate(x, 0, x[0]).is_none() {
        return out;
    }
    // Candidates: the rows that are not diagonally dominant (h_ii ≤ Σ|h_ij|), among them every
    // row with h_ii ≤ 0: the unknowns near a fold. One whose minimum is taken away by its
    // neighbours while its row is still dominant enters this set within a step or two, or at
    // once when it is among the `unbalanced` (its gradient component far above the rest's).
    let mut queued = vec![false; n];
    let mut queue: VecDeque<usize> = (0..n).filter(|&i| diag[i] <= off[i]).collect();
    queue.iter().for_each(|&i| queued[i] = true);
    let fold_seeds = queue.len();
    for &i in unbalanced {
        if !queued[i] {
            queued[i] = true;
            queue.push_back(i);
        }
    }
    if queue.is_empty() {
        return out;
    }
    let seeds = queue.len();
    // Each unknown may move a few times as its neighbours settle; beyond that the global
    // iteration takes over.
    let mut budget = 4 * n + 64;
    let mut jumped_set = Vec::new();
    let mut popped = 0;
    while let Some(i) = queue.pop_front() {
        queued[i] = false;
        popped += 1;
        if budget == 0 {
            break;
        }
        budget -= 1;
        let Some((to, jumped)) = descend_1d(|s| energy.along_coordinate(x, i, s), x[i]) else {
            continue;
        };
        let seed = popped <= seeds;
        // A candidate still stable on its axis jumps only when no neighbour has overshot its
        // own balance against the move (g_j pushing it back): such a neighbour would, at
        // equilibrium, pull less, and the spring might keep a minimum. Newton settles those
        // first. (From a state every unknown wants to leave in the same sense, as after a
        // uniform load step, a jump found with the neighbours held is a jump at equilibrium
        // too: the neighbours only follow.)
        if jumped && seed && diag[i] > 0.0 {
            let sense = -g[i].signum();
            if pattern
                .columns(i)
                .any(|j| j != i && g[j] * sense > 1e-3 * g[i].abs())
            {
                out.held |= popped > fold_seeds;
                continue;
            }
        }
        // A candidate that only settles stays for the Newton step; a neighbour of a jump moves.
        if jumped || !seed {
            x[i] = to;
        }
        if jumped {
            rep.coordinate_jumps += 1;
            jumped_set.push(i);
            for j in pattern.columns(i) {
                if j != i && !queued[j] {
                    queued[j] = true;
                    queue.push_back(j);
                }
            }
        }
    }
    out.moved = !jumped_set.is_empty();
    settle(energy, x, h, jumped_set, rep);
    out
}

/// What [`jump_along_coordinates`] did.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct Jumps {
    /// Some unknown jumped.
    pub(super) moved: bool,
    /// Some unbalanced candidate past its own fold was held back for the Newton step (a
    /// neighbour out of balance against its move).
    pub(super) held: bool,
}

/// The Hessian of one iteration of the iterative path, as the local moves read it: its
/// pattern, its values in row order, its diagonal and its off-diagonal absolute row sums
/// Σ_{j≠i} |h_ij|.
#[derive(Clone, Copy)]
pub(super) struct Tangent<'a> {
    pub(super) pattern: &'a SymmetricPattern,
    pub(super) rows: &'a [f64],
    pub(super) diag: &'a [f64],
    pub(super) off: &'a [f64],
}

/// Rings of neighbours around moved unknowns that [`settle`] relaxes.
const SETTLE_RINGS: usize = 4;

/// Largest connected region that [`settle`] relaxes.
const MAX_REGION: usize = 400;

/// Newton iterations per region in [`settle`] at most.
const SETTLE_ITERATIONS: usize = 40;

/// Let the surroundings of unknowns that just moved (jumped, or escaped an instability) settle
/// before the next global step: each connected region of the unknowns within [`SETTLE_RINGS`]
/// of them is relaxed on its own with the rest of the system held ([`relax_region`]). The
/// nonlinear part of the response to a jump is local (the neighbours follow, and some of them
/// lose stability and jump in turn: an avalanche); resolving it here costs work in proportion
/// to the region, where every global step costs work in proportion to the whole system. The
/// global Newton step that follows corrects the smooth remainder. Returns whether anything
/// moved.
pub(super) fn settle(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    moved: Vec<usize>,
    rep: &mut NewtonReport,
) -> bool {
    let pattern = h.pattern;
    if moved.is_empty() || energy.local_energy(x, &moved[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut relaxed = false;
    let n = x.len();
    let mut mark = vec![false; n];
    let mut region = Vec::new();
    for i in moved {
        if !mark[i] {
            mark[i] = true;
            region.push(i);
        }
    }
    for _ in 0..SETTLE_RINGS {
        add_ring(pattern, &mut region, &mut mark);
    }
    let mut seen = vec![false; n];
    for &s0 in &region {
        if seen[s0] {
            continue;
        }
        let mut comp = component(pattern, s0, &mark, &mut seen, usize::MAX);
        if comp.len() <= MAX_REGION {
            comp.sort_unstable();
            relaxed |= relax_region(energy, x, h, &comp, rep);
        }
    }
    relaxed
}

/// The unknowns connected to `s0` through the pattern within `member` (breadth first, `s0`
/// included), marked in `seen`, stopping once more than `cap` are found.
fn component(
    pattern: &SymmetricPattern,
    s0: usize,
    member: &[bool],
    seen: &mut [bool],
    cap: usize,
) -> Vec<usize> {
    seen[s0] = true;
    let mut comp = vec![s0];
    let mut k = 0;
    while k < comp.len() && comp.len() <= cap {
        let i = comp[k];
        k += 1;
        for j in pattern.columns(i) {
            if member[j] && !seen[j] {
                seen[j] = true;
                comp.push(j);
            }
        }
    }
    comp
}

/// Add to `set` the neighbours of its unknowns not yet in `seen` (one ring), marking them.
/// Returns whether any was added.
fn add_ring(pattern: &SymmetricPattern, set: &mut Vec<usize>, seen: &mut [bool]) -> bool {
    let ring: Vec<usize> = set
        .iter()
        .flat_map(|&i| pattern.columns(i))
        .filter(|&j| !seen[j])
        .collect();
    let before = set.len();
    for j in ring {
        if !seen[j] {
            seen[j] = true;
            set.push(j);
        }
    }
    set.len() > before
}

/// Grow `patch` ring by ring (up to [`PATCH_RINGS`] rings, at most [`MAX_PATCH`] unknowns)
/// until its principal submatrix of H shows negative curvature ([`negative_mode`]), and then
/// move it along that mode to the next minimum ([`descend_along`]); the unknowns moved are
/// appended to `escaped`. A group's unstable mode reaches into the stable unknowns around it
/// (the Schur complement of the rest subtracts from the group's block), hence the growth.
fn escape_patch(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    mut patch: Vec<usize>,
    seen: &mut [bool],
    escaped: &mut Vec<usize>,
    rep: &mut NewtonReport,
) {
    if patch.len() > MAX_PATCH {
        return;
    }
    // Rings up to the largest patch within the size limit, each unknown with its ring.
    let mut ring_of = vec![0; patch.len()];
    let mut testable = patch.len();
    for ring in 1..=PATCH_RINGS {
        if !add_ring(h.pattern, &mut patch, seen) {
            break;
        }
        ring_of.resize(patch.len(), ring);
        if patch.len() > MAX_PATCH {
            break;
        }
        testable = patch.len();
    }
    // A principal submatrix of a positive-definite block is positive definite: one
    // factorisation of the largest patch rules out all the smaller ones.
    let mut largest = patch[..testable].to_vec();
    largest.sort_unstable();
    if Envelope::principal_block(h.pattern, h.rows, &largest)
        .cholesky()
        .is_some()
    {
        return;
    }
    let last_ring = ring_of[testable - 1];
    for ring in 0..=last_ring {
        let mut set: Vec<usize> = (0..testable)
            .filter(|&k| ring_of[k] <= ring)
            .map(|k| patch[k])
            .collect();
        set.sort_unstable();
        let scale = set.iter().fold(0.0f64, |s, &i| s.max(h.diag[i].abs()));
        if let Some((lambda, v)) = negative_mode(h, &set, scale) {
            if descend_along(energy, x, &set, v, lambda) != 0.0 {
                rep.patch_escapes += 1;
                escaped.extend_from_slice(&set);
            }
            // The rings beyond this one were not reached.
            (0..patch.len())
                .filter(|&k| ring_of[k] > ring)
                .for_each(|k| seen[patch[k]] = false);
            return;
        }
    }
}

/// Stable Newton on the unknowns `set` (sorted) alone, all others held at `x`: the energy and
/// gradient from [`Energy::local_energy`], the Hessian block with its diagonal from
/// [`Energy::along_coordinate`] and its off-diagonal entries from `h` (the last global
/// Hessian; exact for couplings that are quadratic, as in the spring arrays, otherwise a chord
/// approximation). Where the Cholesky factorisation of the block (within its
/// envelope, [`Envelope`]) fails, the region is unstable on its own and moves along its lowest
/// mode to the next minimum on that line ([`descend_along`]); otherwise it takes Newton steps
/// with backtracking. Stops when the region's largest gradient component
/// has fallen by 10³ (the global iteration finishes). Returns whether anything moved.
pub(super) fn relax_region(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    set: &[usize],
    rep: &mut NewtonReport,
) -> bool {
    let m = set.len();
    let mut grad = vec![0.0; m];
    let mut moved = false;
    let Some(mut e) = energy.local_energy(x, set, &mut grad) else {
        return false;
    };
    if !e.is_finite() {
        return false;
    }
    let tol = 1e-3 * inf_norm(&grad);
    // Off-diagonal entries from the global Hessian; the diagonal is set at every iteration.
    let mut block = Envelope::principal_block(h.pattern, h.rows, set);
    if !block.all_finite() {
        return false;
    }
    let mut trial_grad = vec![0.0; m];
    let mut p = vec![0.0; m];
    for _ in 0..SETTLE_ITERATIONS {
        if inf_norm(&grad) <= tol {
            break;
        }
        for (r, &i) in set.iter().enumerate() {
            let d = energy.along_coordinate(x, i, x[i]).map_or(f64::NAN, |t| t.2);
            if !d.is_finite() {
                return moved;
            }
            block.set_diagonal(r, d);
        }
        let Some(chol) = block.cholesky() else {
            let (lambda, v) = lowest_mode(&block);
            if lambda.is_nan() || lambda >= 0.0 || descend_along(energy, x, set, v, lambda) == 0.0 {
                return moved;
            }
            rep.patch_escapes += 1;
            moved = true;
            match energy.local_energy(x, set, &mut grad) {
                Some(e1) if e1.is_finite() => e = e1,
                _ => return true,
            }
            continue;
        };
        p.iter_mut().zip(&grad).for_each(|(pi, g)| *pi = -g);
        chol.solve(&mut p);
        let slope: f64 = p.iter().zip(&grad).map(|(a, b)| a * b).sum();
        if slope.is_nan() || slope >= 0.0 {
            return moved;
        }
        let start: Vec<f64> = set.iter().map(|&i| x[i]).collect();
        let accepted = armijo(e, slope, 1e-12, |t| {
            for ((&i, s0), pi) in set.iter().zip(&start).zip(p.iter()) {
                x[i] = s0 + t * pi;
            }
            energy
                .local_energy(x, set, &mut trial_grad)
                .unwrap_or(f64::INFINITY)
        });
        // On acceptance x and the trial gradient are those of the accepted step.
        match accepted {
            Some(e1) => {
                moved = true;
                e = e1;
                grad.copy_from_slice(&trial_grad);
            }
            None => {
                for (&i, s0) in set.iter().zip(&start) {
                    x[i] = *s0;
                }
                return moved;
            }
        }
    }
    moved
}

/// Leave an instability whose mode CG met as the direction `dir` (dᵀHd ≤ 0): the unknowns
/// where |d_i| is at least a tenth of its largest component fall into connected groups; each
/// group, with up to [`PATCH_RINGS`] rings of neighbours, forms a patch, and when the patch's
/// principal submatrix of H has a negative eigenvalue, the patch moves along that eigenvector
/// to the next minimum ([`descend_along`], then [`settle`]). Returns whether any moved.
pub(super) fn escape_around(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    dir: &[f64],
    rep: &mut NewtonReport,
) -> bool {
    let largest = inf_norm(dir);
    if !(largest > 0.0 && largest.is_finite()) {
        return false;
    }
    let n = x.len();
    let strong: Vec<usize> = (0..n).filter(|&i| dir[i].abs() >= 0.1 * largest).collect();
    if strong.is_empty() || energy.local_energy(x, &strong[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut in_strong = vec![false; n];
    strong.iter().for_each(|&i| in_strong[i] = true);
    let mut mark = vec![false; n];
    let mut escaped = Vec::new();
    for &s0 in &strong {
        if mark[s0] {
            continue;
        }
        let patch = component(h.pattern, s0, &in_strong, &mut mark, MAX_PATCH);
        escape_patch(energy, x, h, patch, &mut mark, &mut escaped, rep);
    }
    let moved = !escaped.is_empty();
    settle(energy, x, h, escaped, rep);
    moved
}

/// Move `x` along the direction `dir` (either sense, downhill) to the first minimum of the
/// energy on that line ([`descend_1d`], whole-system evaluations into the scratch vectors
/// `point` and `grad`). Returns whether it moved.
pub(super) fn descend_line(
    energy: &impl Energy,
    x: &mut [f64],
    dir: &mut [f64],
    point: &mut [f64],
    grad: &mut [f64],
) -> bool {
    let norm = inf_norm(dir);
    if !(norm > 0.0 && norm.is_finite()) {
        return false;
    }
    dir.iter_mut().for_each(|v| *v /= norm);
    let line = |t: f64| -> Option<(f64, f64, f64)> {
        for ((pi, xi), di) in point.iter_mut().zip(x.iter()).zip(dir.iter()) {
            *pi = xi + t * di;
        }
        let e = energy.energy(point);
        if !e.is_finite() {
            return Some((e, 0.0, 0.0));
        }
        energy.gradient(point, grad);
        Some((e, dot(grad, dir), if t == 0.0 { -1.0 } else { f64::NAN }))
    };
    let Some((t, _)) = descend_1d(line, 0.0) else {
        return false;
    };
    x.iter_mut().zip(dir.iter()).for_each(|(xi, di)| *xi += t * di);
    t != 0.0
}

/// The lowest eigenvalue of a symmetric matrix with its unit eigenvector: by shift and invert
/// within the envelope ([`Envelope::lowest_eigenpair`]), else by the dense eigenproblem.
fn lowest_mode(a: &Envelope) -> (f64, Vec<f64>) {
    if let Some(pair) = a.lowest_eigenpair() {
        return pair;
    }
    let eig = DMatrix::from_fn(a.order(), a.order(), |r, c| a.get(r.max(c), r.min(c))).symmetric_eigen();
    match eig
        .eigenvalues
        .iter()
        .copied()
        .enumerate()
        .min_by(|p, q| p.1.total_cmp(&q.1))
    {
        Some((k, lambda)) => (lambda, eig.eigenvectors.column(k).iter().copied().collect()),
        None => (f64::INFINITY, Vec::new()),
    }
}

/// Move the unknowns `set` (sorted) along the direction `v` of curvature `lambda` < 0, downhill,
/// to the first minimum of the energy on that line ([`descend_1d`] on
/// [`Energy::local_energy`]). Returns the step taken along v (0 if none).
fn descend_along(energy: &impl Energy, x: &mut [f64], set: &[usize], mut v: Vec<f64>, lambda: f64) -> f64 {
    let m = set.len();
    let mut grad = vec![0.0; m];
    match energy.local_energy(x, set, &mut grad) {
        Some(e) if e.is_finite() => {}
        _ => return 0.0,
    }
    if dot(&grad, &v) > 0.0 {
        v.iter_mut().for_each(|vi| *vi = -*vi);
    }
    let base: Vec<f64> = set.iter().map(|&i| x[i]).collect();
    let line = |t: f64| -> Option<(f64, f64, f64)> {
        for ((&i, b), vi) in set.iter().zip(&base).zip(&v) {
            x[i] = b + t * vi;
        }
        let e = energy.local_energy(x, set, &mut grad)?;
        Some((e, dot(&grad, &v), if t == 0.0 { lambda } else { f64::NAN }))
    };
    let t = descend_1d(line, 0.0).map_or(0.0, |(t, _)| t);
    for ((&i, b), vi) in set.iter().zip(&base).zip(&v) {
        x[i] = b + t * vi;
    }
    t
}

/// Largest group of unknowns that [`escape_patches`] treats as one patch.
const MAX_PATCH: usize = 256;

/// Rings of neighbours by which [`escape_patch`] grows a patch at most.
const PATCH_RINGS: usize = 4;

/// Leave a collective instability locally. Negative curvature needs rows of H that are not
/// diagonally dominant (h_ii ≤ Σ_{j≠i} |h_ij|): the principal submatrix of the other rows is
/// strictly diagonally dominant, hence positive definite. Each connected group of such rows
/// with their neighbours, grown ring by ring ([`escape_patch`]), whose principal submatrix of
/// H has a negative eigenvalue λ is moved along the eigenvector v (padded with zeros,
/// vᵀHv = λ|v|² < 0 for the whole H), downhill, to the first minimum of the energy on that
/// line, evaluated locally ([`Energy::local_energy`]). This is the unstable group's own mode,
/// taken in one move instead of being crept along by damped steps. Returns whether any patch
/// moved; `false` also when the energy does not offer [`Energy::local_energy`].
pub(super) fn escape_patches(
    energy: &impl Energy,
    x: &mut [f64],
    h: &Tangent<'_>,
    rep: &mut NewtonReport,
) -> bool {
    let Tangent {
        pattern, diag, off, ..
    } = *h;
    let n = x.len();
    let seeds: Vec<usize> = (0..n).filter(|&i| diag[i] - off[i] <= 0.0).collect();
    if seeds.is_empty() || energy.local_energy(x, &seeds[..1], &mut [0.0]).is_none() {
        return false;
    }
    let mut in_patch = vec![false; n];
    for &i in &seeds {
        pattern.columns(i).for_each(|j| in_patch[j] = true);
    }
    let mut seen = vec![false; n];
    let mut escaped = Vec::new();
    for &s0 in &seeds {
        if seen[s0] {
            continue;
        }
        let comp = component(pattern, s0, &in_patch, &mut seen, usize::MAX);
        escape_patch(energy, x, h, comp, &mut seen, &mut escaped, rep);
    }
    let moved = !escaped.is_empty();
    settle(energy, x, h, escaped, rep);
    moved
}

/// A direction of negative curvature of the principal submatrix of H (the iteration's `h`) on
/// the sorted unknowns `set`: its lowest eigenvalue, when below −1e-12·`scale`, with the unit
/// eigenvector ([`lowest_mode`]). A successful Cholesky factorisation rules it out first, at a
/// fraction of the cost of the eigenproblem.
fn negative_mode(h: &Tangent<'_>, set: &[usize], scale: f64) -> Option<(f64, Vec<f64>)> {
    let a = Envelope::principal_block(h.pattern, h.rows, set);
    if a.cholesky().is_some() {
        return None;
    }
    let (lambda, v) = lowest_mode(&a);
    (lambda < -1e-12 * scale).then_some((lambda, v))
}

/// From `s0`, go downhill on the one-variable energy `f` (value, slope, curvature) to the first
/// local minimum: steps doubling from the local length scale until the energy stops falling
/// (slope turned, energy risen, or the domain left), then bisection inside that bracket.
/// Returns the minimum and whether the way down met non-positive curvature (the start past a
/// fold: a jump rather than a settling). `None` if `f` is not offered, the start is outside the
/// domain or no lower point is found.
fn descend_1d(mut f: impl FnMut(f64) -> Option<(f64, f64, f64)>, s0: f64) -> Option<(f64, bool)> {
    let (e0, d0, c0) = f(s0)?;
    if !e0.is_finite() {
        return None;
    }
    let dir = if d0 > 0.0 { -1.0 } else { 1.0 };
    // Still going down (in `dir`) at s, and not above the energy at the bracket's low end.
    let descending = |e: f64, d: f64, e_ref: f64| e.is_finite() && e <= e_ref && dir * d < 0.0;
    let floor = 1e-12 * (1.0 + s0.abs());
    let mut h = if c0 != 0.0 && d0 != 0.0 && c0.is_finite() {
        (d0 / c0).abs()
    } else {
        0.0
    }
    .max(1e-6 * (1.0 + s0.abs()));
    let mut unstable = c0 <= 0.0;
    let (mut a, mut ea, mut da, mut ca) = (s0, e0, d0, c0);
    let mut b = None;
    for _ in 0..400 {
        // Where the curvature is positive a minimum may be near: never step further than half
        // again the Newton step to it, or a doubled step could cross it and the barrier
        // beyond into another basin (a jump the system does not make).
        if ca > 0.0 {
            h = h.min(1.5 * (da / ca).abs()).max(floor);
        }
        let t = a + dir * h;
        let (et, dt, ct) = f(t)?;
        if descending(et, dt, ea) {
            // Curvature where `f` does not give it (NaN): the secant of the slopes.
            let ct = if ct.is_nan() { (dt - da) / (t - a) } else { ct };
            (a, ea, da, ca) = (t, et, dt, ct);
            unstable |= ct <= 0.0;
            h *= 2.0;
        } else {
            b = Some(t);
            break;
        }
    }
    let mut b = b?;
    // The minimum to a 10⁻⁸ of the bracket (or to roundoff): the local Newton iterations that
    // follow every move polish it.
    let width = 1e-8 * (b - a).abs();
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m == a || m == b || (b - a).abs() <= width {
            break;
        }
        let (em, dm, cm) = f(m)?;
        if descending(em, dm, ea) {
            (a, ea) = (m, em);
            unstable |= cm <= 0.0;
        } else {
            b = m;
        }
    }
    (ea < e0).then_some((a, unstable))
}

#[cfg(test)]
mod tests {
    use super::descend_1d;
    use crate::numerics::newton::wells::{FieldWells, iterative};
    use crate::numerics::newton::{NewtonOptions, StableNewton};

    // Two wells coupled strongly (c = 2) at the stationary point x = (0, 0): each is stable
    // along its own axis (curvature −1 + 2 = 1), the pair is not (eigenvalue −1 along (1, 1)).
    // No coordinate move lowers the energy; the local unstable mode does, in one move, and
    // the pair ends in a common well without factorisation.
    #[test]
    fn a_collective_saddle_is_left_along_its_local_mode() {
        let e = FieldWells { n: 2, c: 2.0, b: 0.0 };
        let mut s = StableNewton::new(&e).unwrap();
        let mut x = vec![0.0, 0.0];
        let rep = s.minimize(&e, &mut x, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 0);
        assert_eq!(rep.coordinate_jumps, 0);
        assert!(rep.patch_escapes >= 1);
        assert!(
            (x[0] - x[1]).abs() < 1e-9 && (x[0].abs() - 1.0).abs() < 1e-9,
            "x = {x:?}"
        );
        let mut check = StableNewton::new(&e).unwrap();
        assert!(check.is_stable(&e, &x).unwrap());
    }

    // A front in a chain of 400 bistable wells in a field: the first ten sit in the right
    // well, the rest in the left one, where each is metastable on its own (b = 0.2 is below
    // the fold field 2/√27 = 0.385) but not next to a neighbour in the right well: the pull
    // 2c = 0.5 exceeds the fold field of its own-axis energy x⁴/4 − (1 − 2c)x²/2 − bx, 0.136.
    // Every well jumps, one after the other: an avalanche of 390 generations. The iterative
    // path resolves it locally, in a few global iterations (not one per generation), and
    // ends where the direct path ends.
    #[test]
    fn an_avalanche_is_resolved_locally() {
        let n = 400;
        let e = FieldWells { n, c: 0.25, b: 0.2 };
        let start: Vec<f64> = (0..n).map(|i| if i < 10 { 1.0 } else { -1.0 }).collect();
        let mut s = StableNewton::new(&e).unwrap();
        let (mut a, mut b) = (start.clone(), start);
        // The direct path meets the generations one at a time, a few iterations each.
        let direct = NewtonOptions {
            max_iterations: 20_000,
            ..NewtonOptions::default()
        };
        let slow = s.minimize(&e, &mut a, &direct).unwrap();
        assert!(slow.iterations > n, "{} direct iterations", slow.iterations);
        let rep = s.minimize(&e, &mut b, &iterative()).unwrap();
        assert_eq!(rep.direct_fallbacks, 0);
        // Each well leaves by a local move: along its own axis, or with a few neighbours
        // along their common lowest mode.
        assert!(rep.coordinate_jumps + rep.patch_escapes >= n - 10, "{rep:?}");
        assert!(rep.iterations <= 20, "{} global iterations", rep.iterations);
        assert!(b.iter().all(|&v| v > 0.9), "every well jumped");
        assert!(a.iter().zip(&b).all(|(p, q)| (p - q).abs() < 1e-8));
        let mut check = StableNewton::new(&e).unwrap();
        assert!(check.is_stable(&e, &b).unwrap());
    }

    // A tilted double well E = s⁴/4 − s²/2 + 0.3 s, entered from s = 3: the first minimum
    // downhill is the shallow one near 0.79 (s³ − s + 0.3 = 0), behind which lie the barrier
    // at 0.34 and the deep well at −1.13. Doubling steps alone land past the barrier (at 0.21,
    // lower and still going down); the descent must stop in the shallow well and report no
    // instability on the way.
    #[test]
    fn a_one_dimensional_descent_does_not_cross_a_barrier() {
        let f = |s: f64| {
            Some((
                s.powi(4) / 4.0 - s * s / 2.0 + 0.3 * s,
                s.powi(3) - s + 0.3,
                3.0 * s * s - 1.0,
            ))
        };
        let (to, unstable) = descend_1d(f, 3.0).unwrap();
        assert!(
            (to.powi(3) - to + 0.3).abs() < 1e-9 && to > 0.75 && to < 0.9,
            "to = {to}"
        );
        assert!(!unstable);
        // From just past the barrier top the way down runs through negative curvature.
        let (to, unstable) = descend_1d(f, 0.3).unwrap();
        assert!(to < -1.0 && unstable, "to = {to}");
    }
}
