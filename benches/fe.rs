//! Finite-element speed (chapter 4): assembly, factorisation and solve of a 199 712-triangle
//! axisymmetric elasticity problem (the size of `benches/fe_skfem.py`, run there with
//! scikit-fem for comparison), the set-up of the finite-element tip of Fig. 4.5, and one
//! finite-element cycle of Fig. 4.5's smooth tip to 15 ζ0 (criterion group `fe-cycle`, ten
//! samples of one cycle each: about ten minutes). Whether condensing the bulk onto the
//! surface layers (a Schur complement) would make the Newton steps cheaper: `benches/fe_schur.rs`
//! (it does not); whether another Newton method (a nonlinear elimination of the contact
//! edge) would make the load steps cheap enough for a cycle under 15 s:
//! `benches/fe_elimination.rs` (it would not).
//!
//! Where the cycle's time goes (measured on the coarse variant of
//! `fe_cycle_on_a_coarse_mesh_keeps_its_path_with_warm_load_steps`, 6 810 unknowns then, 7 183
//! since the mesh honours its element width; 319 minimisations, 3 656 Newton iterations, on 2
//! cores shared with other builds): energy
//! evaluations 37 % (5 147 of them, most in line searches and the tangent predictor's
//! comparison), numeric factorisations 23 % (2 517, 329 of them failed attempts of shifted
//! steps in the jumps), Hessian values 16 % (2 661), gradients 12 % (3 668). A load step in
//! contact takes 8-20 Newton iterations: the edge nodes start on the steep repulsive wall
//! (gradient about 10² against 10⁻² away from contact) and the first steps are damped.
//! Starting load steps warm (chord steps on the previous state's factorisation,
//! `CycleModel::warm_start`) and not evaluating an accepted state's Hessian again for its
//! stability test and the next tangent (`Energy::key`) keep the path to the digits and save
//! 2-4 % of the factorisations: this cycle took 365 s before and 332 s after (single runs at a
//! load average of 12-13 on the 2 cores; 51 s on a quiet machine before).
//!
//! Where a contact load step's iterations go (the coarse variant, traced iteration by
//! iteration): the step starts from the tangent predictor (used in almost every contact step;
//! a second-order predictor through the state before it cut the iterations by 2 % only), then
//! 5-8 full Newton steps (line search t = 1) in which the largest gradient component bounces
//! between 10 and 500 while the edge nodes settle on the steep repulsive wall (corrections of
//! about 0.1 ζ0, the wall's own length scale), then a tail of 5-7 chord steps converging
//! linearly (about 10× per step) from a gradient of 1 to the tolerance 1e-7: about 1 360 of
//! the 3 865 iterations have a gradient below 0.02, where the energy (about 10⁵) no longer
//! resolves a step's decrease. Such chord steps are now taken without the line search's
//! energy evaluation (`newton/direct.rs`): the same path (P_adh −8.326694758259e-9 N, the two
//! jumps at the same depths), 4 291 Newton iterations and 2 295 factorisations against 4 271
//! and 2 309, and 52.5 s of CPU against 57.0 s (one run each, back to back, single runs of
//! the bench cycle at a load average of 5-6 on the 2 cores: 64 s against 92 s of wall time).
//! Refactorising sooner or later in the chord tail only trades iterations for
//! factorisations (coarse variant: contraction 0.05: 3 186 iterations, 2 756 factorisations;
//! 0.25: 3 865, 2 419; 0.5: 4 756, 2 145; the time within the noise). A threefold speed-up
//! needs the bouncing phase gone: a local nonlinear solve of the wall nodes (each surface
//! node's u_z to its own balance on the wall, as the iterative path's coordinate moves do,
//! which needs `Energy::along_coordinate` of the body force element by element), or fewer
//! bisections (319 minimisations for 121 targets and 8 jumps: the contact edge hopping node
//! by node raises the jump measure against the tangent, and each false alarm costs a half
//! step and a retry).
//!
//! Criterion median of the cycle (quiet machine, 2 cores): **56.25 s** on the 24 542-unknown
//! mesh of surface elements 0.1375 b (the width 0.15 b honoured), single-precision directions
//! on; P_adh −8.327541477632e-9 N, 2 jumps, 369 minimisations, 4 369 Newton iterations, 2 507
//! factorisations. Before the mesh honoured its width the same cycle ran on 22 266 unknowns
//! (0.155 b for a requested 0.25 b) in 51 s.
//!
//! Where the bench cycle's wall time goes (instrumented run on the 22 266-unknown mesh, quiet
//! machine, 54.6 s in the minimisations): numeric factorisations 23.0 s (1 965, 11.7 ms each, sequential), solves
//! 11.4 s (4 274, 2.6 ms each: the factor has 1.18 million entries, 9.4 MB, and a solve
//! streams it twice), gradients 7.2 s (4 294), line searches 5.7 s, Hessian values 3.6 s,
//! tangent predictor 3.1 s. Of the 4 291 Newton iterations 1 756 start with a gradient above
//! 10 (the edge nodes settling on the wall, with line searches halving the steps) and 1 540
//! below 10⁻² (the chord tail). Tried and measured:
//! - faer's parallel supernodal factorisation (`Par::rayon`) on the 2 cores: slower, 18.0 ms
//!   against 11.7 ms per factorisation (the supernodes of a two-dimensional mesh are too
//!   small for the threads to pay);
//! - a nested-dissection ordering from the node coordinates (median splits, the smaller
//!   separator of the two axes) instead of AMD: 2.11 million factor entries against 1.18
//!   million, factorisation 18.0 ms against 9.7 ms; AMD kept;
//! - relaxing the unknowns far out of balance locally before each global step, as the
//!   iterative path does (the finite-element energy along a coordinate and of a region, the
//!   region solved with the global Hessian's couplings): 16 % fewer factorisations but 5-30 %
//!   more Newton iterations and no gain in time (a relaxed region pushes its held neighbours
//!   out of balance, and the chord tail alternates with relaxations); not kept;
//! - single-precision directions far from convergence (largest gradient component above
//!   10⁻³), as the dense path already takes them: the same path (P_adh to 12 digits, the
//!   same two jumps, H to 1e-10), 10 % less wall time in back-to-back runs under load
//!   (78-79 s against 86-90 s at a load of 6); kept (`FeTip` opts in).
//!
//! A threefold speed-up is not in reach of these: it needs fewer Newton iterations per load
//! step (the bouncing phase) or fewer minimisations (the false alarms of the jump measure).
//!
//! Measured again on the 24 542-unknown mesh (instrumented single run, quiet machine, 53.7 s):
//! numeric factorisations 25.4 s (1 681 in single precision at 9.2 ms, 828 in double at
//! 11.9 ms: single precision saves a fifth per factorisation, the supernodes of a
//! two-dimensional mesh being small), solves 9.2 s (4 718 at 2.0 ms), the body force 17.4 s on
//! both cores (6 026 energies at 1.15 ms, 4 751 gradients at 1.27 ms, 2 072 Hessians at
//! 2.12 ms). No part dominates: a threefold gain must come from the iteration count. What a
//! load step in contact corrects: the converged state differs from the tangent's prediction by
//! about 0.1 ζ0 (half the depth step) over the column of nodes where the contact edge passes
//! (about one element per step), with gradients of 1.5-3 × 10³ there and below 10⁻¹
//! elsewhere; from that start full Newton steps (t = 1) cut the gradient by 4-6 per step while
//! the column settles on the wall, then the chord tail runs at about 0.18 per step. Tried
//! (the 15 112-unknown variant of width 0.25 b, back to back): an expanding line search (2t,
//! 4t, … while the energy falls, at gradients above 1): 5 % fewer iterations, 4 % more
//! minimisations, and an unloading jump moved by 2e-4 ζ0, not kept; refactorising in the
//! chord tail at a contraction of 0.1 instead of 0.25: 14 % fewer iterations, 11 % more
//! factorisations, 5 % slower; half the tangent step as predictor: 16 % more iterations; no
//! predictor: 3.1 times the minimisations (the jump measure's false alarms); the predicted
//! surface nodes held no closer to the substrate than the closest node of the state before
//! (0-19 nodes moved per step): 3 % more iterations; starting load
//! steps cold instead of warm: 4 % faster on that mesh, the same on the bench mesh (53.2
//! against 53.7 s), kept warm. Under 15 s needs about four Newton iterations per load step in
//! contact instead of twelve: a solver that takes the contact edge's column onto the wall in
//! one move (a nonlinear elimination of those unknowns inside the global step, or a predictor
//! that knows the wall), not a cheaper linear algebra.
//!
//! How far a better predictor could go (bench mesh and the 15 112-unknown variant, instrumented
//! single runs, quiet machine): the bench cycle's 53.0 s split by the kind of minimisation:
//! 279 load steps started on the tangent and converged, 32.0 s (115 ms, 11.3 iterations and
//! 4.6 factorisations each); everything the jumps and the false alarms cost, 21.0 s (40 %): 8
//! load steps that ran out of their 40 trial iterations (6.5 s; the jump into contact alone
//! 2.0 s with 150 factorisations, then each contact-edge node peeling off in the unloading,
//! about 0.65 s), 66 bisection trials (6.3 s), 8 landings (5.7 s; the jump into contact 3.4 s,
//! 91 iterations and 239 factorisations), 8 steps without the tangent (2.4 s). Of the 2 509
//! factorisations, 466 are failed attempts in the 164 iterations with an indefinite Hessian
//! (single precision, then double, then 1.85 shifts on average). An oracle measured the bound
//! of a perfect predictor: each converged tangent step of the variant was run again from the
//! tangent's prediction with every unknown the step moved by more than `t` (in ζ0) set to its
//! converged value, on a copy of the solver as it stood before the step. t = 0.03: 9.8
//! iterations, 2.6 factorisations, 44 ms against 11.5, 4.4 and 60 ms; t = 0.001 (every unknown
//! within 10⁻³ ζ0 of the answer): 4.8 iterations, 1.8 factorisations, 29 ms. A perfect
//! predictor therefore halves the converged steps at best (32 s to about 16 s on the bench
//! mesh), and with the jumps' 21 s unchanged the cycle stays above 35 s; under 15 s needs the
//! jumps' machinery three times cheaper as well, while the path (the bisection states it
//! records) stays the same. Tried as well, not kept: a load step without the tangent
//! treated as beyond the fold at its first indefinite Hessian, as the bisection trials are
//! (same P_adh and jumps, 422 minimisations against 369, 61.4 s against 53.4 s); the gradient
//! tolerance 10⁻⁵ or 10⁻⁶ instead of 10⁻⁷ (variant: 32.1 and 31.5 s against 32.1 s; P_adh to
//! 6e-12; the tail's chord steps are cheap, the factorisations stay).
//!
//! Whether another Newton method could take a converged load step for much less:
//! `benches/fe_elimination.rs` runs consecutive accepted steps of this cycle again from the
//! tangent's prediction by Newton with a fresh factorisation per iteration (7.0 iterations and
//! factorisations per step), by a nonlinear elimination of the contact edge's column (4.2
//! global iterations and factorisations) and by the elimination with chord steps (9.7
//! iterations, 2.1 factorisations and the certifying one). Priced at the measured unit costs,
//! the 279 converged steps would take 21-24 s instead of 32 s, above 15 s before any jump;
//! even a floor of one certifying factorisation and three cheap iterations per step (7.5 s)
//! would leave 7.5 s for the jumps, which take 21 s. A cycle under 15 s on this mesh, at this
//! depth step and tolerance, on 2 cores, is therefore out of reach of a better nonlinear
//! solver: it needs linear algebra several times cheaper (the Hessian changes in every element
//! the body force reaches, so no part of the factor can be reused exactly, and a Schur
//! complement onto that band is dense, see `benches/fe_schur.rs`) and jumps three times
//! cheaper.

mod common;

use common::{fe_cycle_options, fig4_5_fe};
use std::f64::consts::PI;
use std::hint::black_box;

use adhesion::models::axisymmetric::cycle::run_cycle;
use adhesion::models::body_force_fe::assembly::{FIXED, assemble, held_top_dofs};
use adhesion::models::body_force_fe::element::elasticity_matrix;
use adhesion::models::body_force_fe::mesh::Mesh;
use adhesion::models::body_force_fe::tip::FeTip;
use criterion::Criterion;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Par, Side};

/// Assemble the held cylinder r ≤ 1, 0 ≤ z ≤ 1 of `n` × `n` squares (2n² triangles), load its
/// bottom with a unit pressure, factorise (supernodal LLᵀ) and solve; the apex displacement.
fn elasticity(n: usize) -> f64 {
    let mesh = Mesh::uniform(1.0, 1.0, n, n);
    let (dofs, unknowns) = held_top_dofs(&mesh);
    let k = assemble(&mesh, &dofs, unknowns, &elasticity_matrix(1.0, 0.25));
    let mut rhs = vec![0.0; unknowns];
    for w in mesh.surface.windows(2) {
        let (a, b) = (mesh.nodes[w[0]][0], mesh.nodes[w[1]][0]);
        // ∫ 2πr N dr over the edge for each end node.
        let (fa, fb) = (
            PI * (b - a) * (2.0 * a + b) / 3.0,
            PI * (b - a) * (a + 2.0 * b) / 3.0,
        );
        for (node, f) in [(w[0], fa), (w[1], fb)] {
            if dofs[node][1] != FIXED {
                rhs[dofs[node][1]] += f;
            }
        }
    }
    let pairs: Vec<Pair<usize, usize>> = k.pattern.iter().map(|&(r, c)| Pair::new(r, c)).collect();
    let (symbolic, argsort) =
        SymbolicSparseColMat::try_new_from_indices(unknowns, unknowns, &pairs).expect("pattern");
    let matrix = SparseColMat::new_from_argsort(symbolic.clone(), &argsort, &k.values).expect("matrix");
    let llt = factorize_symbolic_cholesky(
        symbolic.as_ref(),
        Side::Lower,
        SymmetricOrdering::Amd,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        },
    )
    .expect("symbolic");
    let par = Par::rayon(0);
    let mut values = vec![0.0; llt.len_val()];
    let mut buf = MemBuffer::new(
        llt.factorize_numeric_llt_scratch::<f64>(par, Default::default())
            .or(llt.solve_in_place_scratch::<f64>(1, par)),
    );
    let l = llt
        .factorize_numeric_llt(
            &mut values,
            matrix.as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .expect("positive definite");
    let m = faer::MatMut::from_column_major_slice_mut(&mut rhs, unknowns, 1);
    l.solve_in_place_with_conj(Conj::No, m, par, MemStack::new(&mut buf));
    rhs[dofs[mesh.surface[0]][1]]
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    {
        let mut group = c.benchmark_group("fe");
        group.bench_function("assemble + factorise + solve, 199712 triangles", |b| {
            b.iter(|| black_box(elasticity(316)))
        });
        let params = fig4_5_fe();
        let tip = FeTip::new(&params).expect("tip");
        group.bench_function(
            format!(
                "fig4.5 tip set-up ({} triangles, {} unknowns)",
                tip.elements(),
                tip.len()
            ),
            |b| b.iter(|| black_box(FeTip::new(&params).expect("tip"))),
        );
        group.finish();
    }
    // The cycle takes most of a minute: `FE_BENCH_SKIP_CYCLE=1 cargo bench --bench fe` leaves
    // it out (criterion's own argument parser refuses unknown flags).
    if std::env::var_os("FE_BENCH_SKIP_CYCLE").is_none() {
        let tip = FeTip::new(&fig4_5_fe()).expect("tip");
        let z = tip.scales().length;
        let opts = fe_cycle_options(z, -15.0, 0.2);
        let cycle = run_cycle(&tip, &opts, |_| Ok(())).expect("cycle");
        println!(
            "fe/fig4.5 cycle to 15 zeta0 ({} unknowns): P_adh {:.12e} N, {} jumps, {} minimisations, {} Newton iterations, {} factorisations",
            tip.len(),
            cycle.adhesive_force(),
            cycle.jumps.len(),
            cycle.stats.minimisations,
            cycle.stats.newton_iterations,
            cycle.stats.factorizations
        );
        let mut group = c.benchmark_group("fe-cycle");
        group
            .sample_size(10)
            .warm_up_time(std::time::Duration::from_millis(1))
            .measurement_time(std::time::Duration::from_secs(1));
        group.bench_function(format!("fig4.5 cycle to 15 zeta0, {} unknowns", tip.len()), |b| {
            b.iter(|| black_box(run_cycle(&tip, &opts, |_| Ok(())).expect("cycle")))
        });
        group.finish();
    }
    c.final_summary();
}
