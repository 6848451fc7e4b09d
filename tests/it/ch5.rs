//! Chapter 5: fibril mechanics and the single-spring model (section 5.4), the spring arrays of
//! section 5.5, and the stable sparse Newton solver.

use adhesion::models::fibril::{
    self, K_CR_BAR, SingleSpring, SpringBranch, critical_stiffness, equivalent_stiffness,
    tilted_fibril_stiffness,
};

use crate::common::assert_rel;

// Section 5.4.3: k̄_cr = 0.3 is the maximum of d̄⁻⁴/2 − d̄⁻¹⁰/5, so (5.20) is positive for every
// gap above it and has two roots below it. Checked on a dense gap grid, not from the constant.
#[test]
fn critical_stiffness_is_0_3_sec_5_4_3() {
    let max = adhesion::numerics::curve::linspace(0.5, 5.0, 200_001)
        .into_iter()
        .map(|d| -fibril::lj_curvature(d))
        .fold(f64::MIN, f64::max);
    assert!((max - 0.3).abs() < 1e-9, "max of -f'' = {max}");
    assert!(!SingleSpring::new(0.3 * 1.0001).unwrap().has_instabilities());
    assert!(SingleSpring::new(0.3 * 0.9999).unwrap().has_instabilities());
    for d in adhesion::numerics::curve::linspace(0.5, 5.0, 1000) {
        assert!(SingleSpring::new(2.0 * K_CR_BAR).unwrap().curvature(d) > 0.0);
    }
}

// Section 5.4.3, k̄ = 0.5 k̄_cr: the minimizer is non-unique for 1.791 ≤ ū ≤ 2.043; pull-in at
// ū = 1.791, pull-off at ū = 2.043 (printed to 3 decimals: half a unit in the last digit).
#[test]
fn pull_in_and_pull_off_displacements_at_half_critical_stiffness() {
    let s = SingleSpring::new(0.5 * K_CR_BAR).unwrap();
    let pin = s.pull_in().unwrap().unwrap();
    let poff = s.pull_off().unwrap().unwrap();
    assert!((pin.before.u - 1.791).abs() < 5e-4, "pull-in {}", pin.before.u);
    assert!((poff.before.u - 2.043).abs() < 5e-4, "pull-off {}", poff.before.u);
    // The states before the jumps are folds, the states after are stable equilibria.
    assert!(s.curvature(pin.before.d).abs() < 1e-10);
    assert!(s.curvature(poff.before.d).abs() < 1e-10);
    for j in [pin, poff] {
        assert!(j.after.stable);
        assert!(s.residual(j.after.u, j.after.d).abs() < 1e-10);
        assert!(j.energy_released > 0.0);
    }
    // Pull-in moves into contact (gap shrinks), pull-off out of it.
    assert!(pin.after.d < pin.before.d && poff.after.d > poff.before.d);
    // Two stable minimizers strictly inside the bistable range, one outside.
    let u = 1.9;
    let dc = s.gap(u, SpringBranch::Contact).unwrap();
    let df = s.gap(u, SpringBranch::Free).unwrap();
    assert!(df - dc > 0.3);
    assert!(s.gap(1.7, SpringBranch::Free).is_err());
    assert!(s.gap(2.1, SpringBranch::Contact).is_err());
}

// Section 5.4.3 / Fig. 5.4: for k̄ ≥ k̄_cr loading and unloading coincide (no hysteresis); for
// k̄ = 0.5 k̄_cr the loop's area equals the energy released at the two jumps.
#[test]
fn hysteresis_is_the_loop_area_and_vanishes_above_critical_stiffness() {
    for k in [K_CR_BAR, 2.0 * K_CR_BAR] {
        let s = SingleSpring::new(k).unwrap();
        let c = s.cycle(4.0, 0.0, 400).unwrap();
        assert!(c.jumps.is_empty());
        assert_eq!(s.hysteresis().unwrap(), 0.0);
        for (a, b) in c.loading.iter().zip(c.unloading.iter().rev()) {
            assert!((a.d - b.d).abs() < 1e-12);
        }
        assert!(c.loop_area().abs() < 1e-12);
    }
    let s = SingleSpring::new(0.5 * K_CR_BAR).unwrap();
    let c = s.cycle(4.0, 0.0, 20_001).unwrap();
    assert_eq!(c.jumps.len(), 2);
    let h = s.hysteresis().unwrap();
    assert!(h > 0.0);
    // Trapezoid rule with Δū = 2e-4 and the jumps inserted exactly: O(Δū²) error.
    assert_rel("loop area vs jump energies", c.loop_area(), h, 1e-5);
}

// Fig. 5.5: the pull-off force magnitude decreases monotonically with k̄ (the text's "pull-in"
// is a typo, ERRATA.md); the pull-in force magnitude first increases, then decreases; the
// hysteresis decreases with k̄ and vanishes at k̄_cr.
#[test]
fn pull_in_pull_off_forces_and_hysteresis_against_stiffness_fig_5_5() {
    let ks = adhesion::numerics::curve::linspace(0.01, 0.299, 60);
    let mut off = Vec::new();
    let mut inn = Vec::new();
    let mut hys = Vec::new();
    for &k in &ks {
        let s = SingleSpring::new(k).unwrap();
        off.push(s.pull_off().unwrap().unwrap().before.force.abs());
        inn.push(s.pull_in().unwrap().unwrap().after.force.abs());
        hys.push(s.hysteresis().unwrap());
    }
    assert!(
        off.windows(2).all(|w| w[1] < w[0]),
        "pull-off magnitude decreasing"
    );
    assert!(hys.windows(2).all(|w| w[1] < w[0]), "hysteresis decreasing");
    let imax = inn
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .unwrap()
        .0;
    assert!(
        imax > 0 && imax < inn.len() - 1,
        "pull-in magnitude has an interior maximum"
    );
    assert!(*hys.last().unwrap() < 1e-3 * hys[0]);
    // Soft limit: pull-off at the largest attraction, g((2/5)^(1/6)).
    let soft = SingleSpring::new(1e-6).unwrap().pull_off().unwrap().unwrap();
    assert_rel(
        "soft pull-off force",
        -soft.before.force,
        fibril::lj_traction(fibril::max_traction_gap()),
        1e-3,
    );
}

// Section 5.5.2: k_e = π N/m from (5.11) with E = 2 GPa, R_f = 50 nm, l_f = 5 µm, θ = π/2;
// k_cr = 0.3 c w π R_e² / σ² = 5349.87 N/m with c = 8.174, w = 25 mJ/m², σ = 0.3 nm
// (ERRATA: the printed formula lacks 1/σ²); k_e/k_cr = 5.87e-4.
#[test]
fn gecko_branch_stiffness_numbers_sec_5_5_2() {
    let k_e = tilted_fibril_stiffness(2e9, 50e-9, 5e-6, std::f64::consts::FRAC_PI_2).unwrap();
    assert_rel("k_e", k_e, std::f64::consts::PI, 1e-12);
    assert!((fibril::c_lj() - 8.174).abs() < 5e-4);
    let k_cr = critical_stiffness(0.025, 50e-9, 0.3e-9);
    assert!((k_cr - 5349.87).abs() < 0.5, "k_cr = {k_cr}");
    assert!((k_e / k_cr - 5.87e-4).abs() < 5e-6);
    // 2^-6 and 2^-11 as printed.
    assert!((2f64.powi(-6) - 1.56e-2).abs() < 5e-5);
    assert!((2f64.powi(-11) - 4.88e-4).abs() < 5e-7);
}

// Section 5.4.1 (ERRATA): the fibril is stiffest at θ = π/2 (compression) and most compliant
// at θ = 0 (bending), with k_f increasing monotonically in between; the limits are EA/l and
// 3EI/l³.
#[test]
fn tilted_fibril_stiffness_limits_and_monotonicity() {
    let (e, r, l) = (2e9, 0.1, 1.0);
    let area = std::f64::consts::PI * r * r;
    let inertia = std::f64::consts::PI * r.powi(4) / 4.0;
    let k0 = tilted_fibril_stiffness(e, r, l, 0.0).unwrap();
    let k90 = tilted_fibril_stiffness(e, r, l, std::f64::consts::FRAC_PI_2).unwrap();
    assert_rel("bending limit", k0, 3.0 * e * inertia / l.powi(3), 1e-12);
    assert_rel("compression limit", k90, e * area / l, 1e-12);
    let th = adhesion::numerics::curve::linspace(0.0, std::f64::consts::FRAC_PI_2, 100);
    let ks: Vec<f64> = th
        .iter()
        .map(|&t| tilted_fibril_stiffness(e, r, l, t).unwrap())
        .collect();
    assert!(ks.windows(2).all(|w| w[1] > w[0]));
    // (5.11) as printed, away from θ = 0.
    let t: f64 = 0.7;
    let printed = area * e / (l * t.sin().powi(2) * (1.0 + 4.0 * l * l / (t.tan().powi(2) * 3.0 * r * r)));
    assert_rel(
        "(5.11)",
        tilted_fibril_stiffness(e, r, l, t).unwrap(),
        printed,
        1e-12,
    );
    assert!(tilted_fibril_stiffness(e, r, l, 2.0).is_err());
    // (5.13): n branches on one seta.
    let ke = equivalent_stiffness(10.0, 1.0, 100).unwrap();
    assert_rel("(5.13)", ke, 1.0 / (100.0 / 10.0 + 1.0), 1e-15);
    assert!(ke < 1.0);
}

// Section 5.3: w = A/(16π Z0²) = 22.1 mJ/m² for A = 1e-19 J, Z0 = 0.3 nm; the JKR spatula force
// (3/2)πwR = 10.4 nN for R = 100 nm.
#[test]
fn spatula_work_of_adhesion_and_force_sec_5_3() {
    let w = fibril::work_of_adhesion(1e-19, 0.3e-9);
    assert!((w - 0.0221).abs() < 5e-5, "w = {w}");
    let f = 1.5 * std::f64::consts::PI * w * 100e-9;
    assert!((f - 10.4e-9).abs() < 0.05e-9, "force = {f}");
}

// ---------------------------------------------------------------------------------------------
// Spring arrays (section 5.5) and the stable Newton solver.

use adhesion::models::spring_array::{
    SpringArray, adhesion_efficiency, coupled_cycle, uncoupled_cycle, uncoupled_cycle_binned,
};
use adhesion::numerics::newton::{LinearSolver, NewtonOptions, StableNewton, plain_newton};

/// Independent Gaussian heights with standard deviation `sigma` and zero mean (a fixed seed);
/// the tests of the solvers need heights, not a correlated surface.
fn gaussian_heights(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut z: Vec<f64> = (0..n).map(|_| StandardNormal.sample(&mut rng)).collect();
    let mean = z.iter().sum::<f64>() / n as f64;
    z.iter_mut().for_each(|v| *v = sigma * (*v - mean));
    z
}

// Section 5.4.3 with the array solver: one spring, k = 0.5 k_cr, ū = 1.9 (inside the bistable
// range). Plain Newton from d = 1.1 converges to the middle equilibrium, a maximum of the
// energy (unstable, (5.20) < 0); the stable solver from the same start reaches a minimum.
#[test]
fn plain_newton_accepts_the_unstable_spring_state_the_stable_solver_does_not() {
    let s = SingleSpring::new(0.15).unwrap();
    let a = SpringArray::new(1, 1, 0.15, 0.0, vec![0.0]).unwrap();
    let e = a.energy_at(1.9);
    let opts = NewtonOptions::default();
    let mut x = vec![1.1];
    plain_newton(&e, &mut x, &opts).unwrap();
    assert!(s.residual(1.9, x[0]).abs() < 1e-9, "plain Newton converged");
    assert!(s.curvature(x[0]) < 0.0, "to an unstable state d = {}", x[0]);
    let mut solver = StableNewton::new(&e).unwrap();
    assert!(!solver.is_stable(&e, &x).unwrap());
    let mut y = vec![1.1];
    let rep = solver.minimize(&e, &mut y, &opts).unwrap();
    assert!(rep.left_unstable_state());
    assert!(s.curvature(y[0]) > 0.0 && s.residual(1.9, y[0]).abs() < 1e-9);
    assert!(solver.is_stable(&e, &y).unwrap());
}

// Consistency of the two paths (issue, "What to build" 4): with k_μ = 0 the coupled solver
// must reproduce the uncoupled result: the same contact state at every step (so the same
// jumps) and the same force to solver tolerance.
#[test]
fn coupled_solver_at_zero_coupling_reproduces_the_uncoupled_cycle() {
    zero_coupling_reproduces_the_uncoupled_cycle(LinearSolver::Direct);
}

// The same with the iterative linear algebra (CG steps, certificate instead of Cholesky,
// springs jumping along their own axis).
#[test]
fn iterative_solver_at_zero_coupling_reproduces_the_uncoupled_cycle() {
    zero_coupling_reproduces_the_uncoupled_cycle(LinearSolver::Iterative);
}

fn zero_coupling_reproduces_the_uncoupled_cycle(linear: LinearSolver) {
    let opts = NewtonOptions {
        linear,
        ..NewtonOptions::default()
    };
    let k_e = 0.3 * 2f64.powi(-5);
    let z = gaussian_heights(12 * 10, 8.0, 7);
    let a = SpringArray::new(12, 10, k_e, 0.0, z.clone()).unwrap();
    let s = a.single().unwrap();
    let (u_in, u_off) = s.bistable_range().unwrap();
    let (u_max, u_min, n) = (u_off + 30.0, -25.0, 301);
    let exact = uncoupled_cycle(&a, u_max, u_min, n).unwrap();
    let coupled = coupled_cycle(&a, u_max, u_min, n, &opts, |_| Ok(())).unwrap();
    assert!(coupled.all_stable);
    let scale = a.len() as f64 * 0.17;
    for (x, y) in exact
        .loading
        .iter()
        .chain(&exact.unloading)
        .zip(coupled.loading.iter().chain(&coupled.unloading))
    {
        assert_eq!(x.u, y.u);
        assert_eq!(x.contact_ratio, y.contact_ratio, "contact state at u = {}", x.u);
        assert!((x.force - y.force).abs() < 1e-8 * scale, "force at u = {}", x.u);
    }
    // The jumps: at each step, the springs whose shifted displacement crossed a fold.
    let grid = adhesion::numerics::curve::linspace(u_max, u_min, n);
    let mut expected = Vec::new();
    for w in grid.windows(2) {
        let c = z
            .iter()
            .filter(|&&zi| w[1] - zi <= u_in && w[0] - zi > u_in)
            .count();
        if c > 0 {
            expected.push((w[1], c, 0));
        }
    }
    let touched = |zi: f64| u_min - zi <= u_in;
    for w in grid.windows(2).rev() {
        let c = z
            .iter()
            .filter(|&&zi| touched(zi) && w[0] - zi >= u_off && w[1] - zi < u_off)
            .count();
        if c > 0 {
            expected.push((w[0], 0, c));
        }
    }
    let got: Vec<(f64, usize, usize)> = coupled
        .jumps
        .iter()
        .map(|j| (j.u, j.into_contact, j.out_of_contact))
        .collect();
    assert_eq!(got, expected);
}

// For k_μ > 0 every accepted state has a positive-definite tangent (checked by Cholesky at
// every step inside the cycle and asserted here), and coupling lowers the adhesion and the
// contact ratio on unloading (Figs. 5.10, 5.11).
#[test]
fn coupled_states_are_stable_and_coupling_reduces_adhesion() {
    let k_e = 0.3 * 2f64.powi(-6);
    let z = gaussian_heights(64, 20.0, 3);
    let mut eff = Vec::new();
    let mut ratio = Vec::new();
    for mult in [0.0, 2.0, 10.0] {
        let a = SpringArray::new(64, 1, k_e, mult * k_e, z.clone()).unwrap();
        let c = coupled_cycle(&a, 80.0, -60.0, 400, &NewtonOptions::default(), |_| Ok(())).unwrap();
        assert!(c.all_stable, "k_mu = {mult} k_e");
        eff.push(adhesion_efficiency(&c, a.len()));
        let mid = c.unloading.len() / 2;
        ratio.push(c.unloading[mid].contact_ratio);
        if mult > 0.0 {
            assert!(!c.jumps.is_empty());
        }
    }
    assert!(eff[0] > eff[1] && eff[1] > eff[2], "efficiency {eff:?}");
    assert!(
        ratio[0] >= ratio[1] && ratio[1] >= ratio[2],
        "contact ratio {ratio:?}"
    );
}

// The iterative path on a coupled 16 x 16 array (k_μ = 2 k_e) over a cycle with jumps: every
// accepted state has a positive-definite tangent by Cholesky (a separate direct solver checks
// each state), and the cycle equals the direct path's: the same jumps, force and hysteresis to
// solver tolerance (measured: 5e-10 and 2e-10 relative). On larger arrays the two can differ
// slightly (0.1-0.2 % in hysteresis on 32 x 32 and 64 x 64): where several coupled springs lose
// stability in one step, the state reached after the jump depends on the descent taken (the
// direct path damps all unknowns by one shift; the iterative one moves unstable springs along
// their own axis), and both are stable states an energy-decreasing jump can reach.
#[test]
fn iterative_and_direct_paths_agree_on_a_coupled_array() {
    let k_e = 0.3 * 2f64.powi(-6);
    let z = gaussian_heights(16 * 16, 20.0, 5);
    let a = SpringArray::new(16, 16, k_e, 2.0 * k_e, z).unwrap();
    let (u_max, u_min, n) = (90.0, -60.0, 300);
    let iterative = NewtonOptions {
        linear: LinearSolver::Iterative,
        ..NewtonOptions::default()
    };
    // By hand, to check every accepted state with a factorisation.
    let s = a.single().unwrap();
    let mut d: Vec<f64> = a
        .heights()
        .iter()
        .map(|z| s.gap(u_max - z, s.branch_on(u_max - z, true, false)).unwrap())
        .collect();
    let mut solver = StableNewton::new(&a.energy_at(u_max)).unwrap();
    let mut check = StableNewton::new(&a.energy_at(u_max)).unwrap();
    let grid = adhesion::numerics::curve::linspace(u_max, u_min, n);
    let (mut jumps, mut fallbacks) = (0, 0);
    for &u in grid.iter().chain(grid.iter().rev()) {
        let e = a.energy_at(u);
        let rep = solver.minimize(&e, &mut d, &iterative).unwrap();
        jumps += rep.coordinate_jumps;
        fallbacks += rep.direct_fallbacks;
        assert!(
            check.is_stable(&e, &d).unwrap(),
            "unstable state accepted at u = {u}"
        );
    }
    assert!(jumps > 0, "the cycle has springs jumping along their axis");
    assert_eq!(fallbacks, 0);
    let direct = coupled_cycle(&a, u_max, u_min, n, &NewtonOptions::default(), |_| Ok(())).unwrap();
    let iter = coupled_cycle(&a, u_max, u_min, n, &iterative, |_| Ok(())).unwrap();
    assert!(direct.all_stable && iter.all_stable);
    assert_rel(
        "adhesive force",
        iter.max_tensile_force(),
        direct.max_tensile_force(),
        1e-7,
    );
    let jumps = |c: &adhesion::models::spring_array::ArrayCycle| -> Vec<(f64, usize, usize)> {
        c.jumps
            .iter()
            .map(|j| (j.u, j.into_contact, j.out_of_contact))
            .collect()
    };
    let (ji, jd) = (jumps(&iter), jumps(&direct));
    assert_rel("hysteresis", iter.hysteresis(), direct.hysteresis(), 1e-7);
    assert_eq!(ji, jd);
}

// The binned (convolution) path against the exact uncoupled path on 64 x 64 heights: force
// curves within 0.5 % of N·M·|P_m| at every step, efficiency within 0.5 %.
#[test]
fn binned_uncoupled_cycle_matches_the_exact_one() {
    let k_e = 0.3 * 2f64.powi(-7);
    let z = gaussian_heights(64 * 64, 20.0, 11);
    let a = SpringArray::new(64, 64, k_e, 0.0, z.clone()).unwrap();
    let (u_max, u_min, n) = (120.0, -80.0, 401);
    let exact = uncoupled_cycle(&a, u_max, u_min, n).unwrap();
    let binned = uncoupled_cycle_binned(&z, k_e, u_max, u_min, n, 8).unwrap();
    let scale = a.len() as f64 * 0.1757;
    for (x, y) in exact
        .loading
        .iter()
        .chain(&exact.unloading)
        .zip(binned.loading.iter().chain(&binned.unloading))
    {
        assert!(
            (x.force - y.force).abs() < 5e-3 * scale,
            "u = {}: {} vs {}",
            x.u,
            x.force,
            y.force
        );
        assert!((x.contact_ratio - y.contact_ratio).abs() < 5e-3);
    }
    let (ea, eb) = (
        adhesion_efficiency(&exact, a.len()),
        adhesion_efficiency(&binned, a.len()),
    );
    assert!((ea - eb).abs() < 5e-3, "{ea} vs {eb}");
    assert!(ea > 0.0 && ea < 1.0);
}

// Fig. 5.8 at reduced size (64 x 64 springs, 4 samples, 300 steps): the efficiency falls with
// the roughness for a given stiffness and rises as the springs soften (larger n), as the text
// of section 5.5.2 states, and it follows the empirical fit (5.37) within 0.04 RMS for every
// n = 6..11. (The text finds (5.37) deviating for n = 9..11; this model does not: at full size
// the RMS deviation is 0.014-0.016 for every n, confirmed independently from Gaussian heights
// and the exact single-spring branches. A likely cause is an unloading run in the original that
// stops before the softest springs reach their large pull-off displacement; our window ends
// 5 σ_rms beyond it. Reported for ERRATA.)
#[test]
fn efficiency_falls_with_roughness_rises_with_softness_and_follows_the_fit_5_37() {
    use adhesion::job::Job;
    use adhesion::scenes::Scene;
    use adhesion::scenes::fig5::{Fig5_8, Fig5_8Params};
    let p = Fig5_8Params {
        surfaces: small_surfaces(),
        cycle: short_cycle(),
        roughness_points: 5,
        ..Default::default()
    };
    let fig = Fig5_8::run(&p, &Job::quiet()).unwrap();
    let means: Vec<Vec<(f64, f64)>> = fig.panels[0]
        .series
        .iter()
        .filter(|s| s.style == adhesion::figure::Style::Scatter)
        .map(|s| s.points.clone())
        .collect();
    assert_eq!(means.len(), 6);
    for (k, m) in means.iter().enumerate() {
        for w in m.windows(2) {
            assert!(w[1].1 <= w[0].1 + 1e-12, "n = {}: not decreasing {m:?}", k + 6);
        }
        assert!(m[0].1 > 0.5 && m[0].1 < 1.0, "n = {}: {m:?}", k + 6);
    }
    for w in means.windows(2) {
        for (a, b) in w[0].iter().zip(&w[1]) {
            assert!(b.1 >= a.1 - 1e-12, "softer springs adhere less at {}", a.0);
        }
    }
    let max_dev = fig.result_value("fit_rms_deviation_max_norm").unwrap();
    assert!(max_dev < 0.04, "RMS deviation from (5.37): {max_dev}");
}

/// The arrays of the efficiency tests (Figs. 5.8, 5.9): 64 × 64 springs, 4 surfaces averaged.
fn small_surfaces() -> adhesion::scenes::groups::SurfaceSamples {
    adhesion::scenes::groups::SurfaceSamples {
        springs: 64,
        samples: 4,
        ..Default::default()
    }
}

/// The cycle of the efficiency tests: 300 displacement steps.
fn short_cycle() -> adhesion::scenes::groups::ArrayCycle {
    adhesion::scenes::groups::ArrayCycle {
        steps: 300,
        ..Default::default()
    }
}

// Fig. 5.9: the uncoupled efficiency depends on the height distribution only, so the
// correlation length changes it little (the text: "no appreciable dependence").
#[test]
fn efficiency_barely_depends_on_the_correlation_length_fig_5_9() {
    use adhesion::job::Job;
    use adhesion::scenes::Scene;
    use adhesion::scenes::fig5::{Fig5_9, Fig5_9Params};
    let p = Fig5_9Params {
        surfaces: small_surfaces(),
        cycle: short_cycle(),
        correlation_lengths: vec![0.01, 0.05, 0.1],
        ..Default::default()
    };
    let fig = Fig5_9::run(&p, &Job::quiet()).unwrap();
    let spread = fig.result_value("max_relative_spread_norm").unwrap();
    assert!(spread < 0.15, "relative spread over L_c: {spread}");
}

// Fig. 5.11: at every displacement step the contact ratio on unloading is at least that on
// loading (springs stay attached past their pull-in point), for each coupling; and the contact
// ratio summed over unloading falls as the coupling grows.
#[test]
fn contact_ratio_on_unloading_exceeds_loading_and_falls_with_coupling_fig_5_11() {
    let k_e = 0.3 * 2f64.powi(-8);
    let z = gaussian_heights(96, 40.0, 5);
    let mut attached = Vec::new();
    for mult in [0.0, 2.0, 10.0] {
        let a = SpringArray::new(96, 1, k_e, mult * k_e, z.clone()).unwrap();
        let c = coupled_cycle(&a, 250.0, -150.0, 400, &NewtonOptions::default(), |_| Ok(())).unwrap();
        assert!(c.all_stable);
        for (l, u) in c.loading.iter().zip(c.unloading.iter().rev()) {
            assert_eq!(l.u, u.u);
            assert!(
                u.contact_ratio >= l.contact_ratio,
                "k_mu = {mult} k_e, u = {}: unloading {} < loading {}",
                l.u,
                u.contact_ratio,
                l.contact_ratio
            );
        }
        attached.push(c.unloading.iter().map(|s| s.contact_ratio).sum::<f64>());
    }
    assert!(
        attached[0] > attached[1] && attached[1] > attached[2],
        "contact ratio summed over unloading: {attached:?}"
    );
}

// The binned tables reject heights outside the range they were built for, with an error.
#[test]
fn binned_tables_reject_heights_outside_their_range() {
    use adhesion::models::spring_array::BinnedBranches;
    let t = BinnedBranches::new(0.3 / 128.0, 100.0, -50.0, 200, 4, (-10.0, 10.0)).unwrap();
    assert!(t.cycle(&[0.0, 5.0, -9.0]).is_ok());
    assert!(t.cycle(&[0.0, 50.0]).is_err());
    assert!(t.cycle(&[]).is_err());
    assert!(BinnedBranches::new(0.01, 100.0, -50.0, 200, 0, (-1.0, 1.0)).is_err());
}

/// A nearly flat surface (σ̄_rms far below the displacement step) is fully loaded and unloaded:
/// the cycle window keeps a margin beyond the folds. Both the binned and the exact uncoupled
/// paths, and the coupled path with the stable Newton solver, give an efficiency near 1 and the
/// flat-surface hysteresis. Before the margin, the binned path gave 0.43 here and the Newton
/// path accepted a near-equilibrium just past the pull-in fold (efficiency 0.004, no jump).
#[test]
fn nearly_flat_surfaces_are_fully_cycled() {
    use adhesion::headless::resolve_values;
    use adhesion::job::Job;
    let run = |id: &str, sets: &[&str]| {
        let s = adhesion::scenes::find(id).unwrap();
        let sets: Vec<String> = sets.iter().map(|x| x.to_string()).collect();
        let values = resolve_values(s, None, &sets, true).unwrap();
        s.run(&values, &Job::quiet()).unwrap()
    };
    for path in ["path=binned", "path=exact"] {
        let fig = run(
            "fig5.7",
            &[
                "springs=32",
                "samples=1",
                "roughness=[0.01]",
                "stiffness_exponent=10",
                path,
            ],
        );
        let e = fig.result_value("efficiency_first_norm").unwrap();
        assert!(e > 0.99, "{path}: efficiency {e}");
    }
    let fig = run("fig5.10", &["roughness=1e-9", "couplings=[0.0]"]);
    let e = fig.result_value("efficiency_uncoupled_norm").unwrap();
    let jumps = fig.result_value("jumps_uncoupled_count").unwrap();
    assert!(e > 0.99, "coupled path, k_mu = 0: efficiency {e}");
    assert!(jumps >= 2.0, "pull-in and pull-off jumps, got {jumps}");
}

// Which state does a jump end in? The experiment's: overdamped dynamics, the gradient flow of
// the energy from the state before the step. On a 32 x 32 array (k̄_e = k̄_cr/2¹⁰, k̄_μ = 2k̄_e,
// σ̄ = 100, the window of the benchmark, 1000 steps per phase) the direct and iterative paths
// part at a few steps where several coupled springs lose stability together. At the first
// such step, from their common previous state, a long explicit gradient flow (Δt = 0.05,
// 1.5·10⁶ steps; the slowest mode relaxes as e^{−k̄_e t}) ends where the iterative path ends
// (its local jumps follow the avalanche); the direct path's shifted Newton steps had carried
// the group into another basin.
#[test]
fn the_iterative_path_follows_the_overdamped_dynamics_through_an_avalanche() {
    use adhesion::models::fibril::{K_CR_BAR, SingleSpring};
    use adhesion::models::spring_array::CONTACT_GAP;
    use adhesion::numerics::newton::Energy;
    use adhesion::surface::{Spectrum, generate};
    let n = 32;
    let spectrum = Spectrum::Gaussian {
        rms: 1.0,
        correlation_length: 0.01,
    };
    let map = generate(&spectrum, n, n, 1.0, 1.0, 1).unwrap();
    let mean = map.z.iter().sum::<f64>() / map.z.len() as f64;
    let z: Vec<f64> = map.z.iter().map(|v| 100.0 * (v - mean)).collect();
    let k_e = K_CR_BAR * 2f64.powi(-10);
    let s = SingleSpring::new(k_e).unwrap();
    let (u_in, u_off) = s.bistable_range().unwrap();
    let (u_max, u_min) = (u_off + 500.0, u_in - 400.0);
    let a = SpringArray::new(n, n, k_e, 2.0 * k_e, z).unwrap();
    let grid = adhesion::numerics::curve::linspace(u_max, u_min, 1000);
    let mut d: Vec<f64> = a
        .heights()
        .iter()
        .map(|z| s.gap(u_max - z, s.branch_on(u_max - z, true, false)).unwrap())
        .collect();
    let (mut dd, mut di) = (d.clone(), d.clone());
    let mut direct = StableNewton::new(&a.energy_at(u_max)).unwrap();
    let mut iterative = StableNewton::new(&a.energy_at(u_max)).unwrap();
    let (od, oi) = (
        NewtonOptions {
            linear: LinearSolver::Direct,
            ..NewtonOptions::default()
        },
        NewtonOptions {
            linear: LinearSolver::Iterative,
            ..NewtonOptions::default()
        },
    );
    let contact = |x: &[f64]| x.iter().filter(|&&v| v < CONTACT_GAP).count();
    let mut checked = false;
    for &u in grid.iter().chain(grid.iter().rev()) {
        let e = a.energy_at(u);
        direct.minimize(&e, &mut dd, &od).unwrap();
        iterative.minimize(&e, &mut di, &oi).unwrap();
        if contact(&dd) == contact(&di) {
            d.copy_from_slice(&di);
            dd.copy_from_slice(&di);
            continue;
        }
        let mut g = vec![0.0; d.len()];
        for _ in 0..1_500_000 {
            e.gradient(&d, &mut g);
            d.iter_mut().zip(&g).for_each(|(x, gi)| *x -= 0.05 * gi);
        }
        let gap = |x: &[f64]| d.iter().zip(x).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        assert_eq!(contact(&d), contact(&di), "at u = {u}");
        assert!(gap(&di) < 1e-6, "flow vs iterative {:.2e} at u = {u}", gap(&di));
        assert!(gap(&dd) > 1.0, "the direct path ends elsewhere");
        checked = true;
        break;
    }
    assert!(
        checked,
        "the paths no longer part in this cycle: the check has nothing left to decide"
    );
}

// A chain of 256 coupled springs (k̄_e = k̄_cr/2¹⁰, k̄_μ = 2k̄_e) on a smooth surface (σ̄ = 10): on
// unloading the contact front peels spring after spring within one step, an avalanche of many
// generations. The direct path takes one generation per iteration and gives up after its 500;
// the iterative path resolves the avalanche locally and finishes the cycle, every state
// certified stable. (Why the chapter 5 scenes use the iterative path at every size.)
#[test]
fn a_peeling_front_along_a_chain_is_followed_by_the_iterative_path() {
    use adhesion::models::fibril::{K_CR_BAR, SingleSpring};
    use adhesion::surface::{Spectrum, generate};
    let spectrum = Spectrum::Gaussian {
        rms: 1.0,
        correlation_length: 0.01,
    };
    let map = generate(&spectrum, 256, 2, 1.0, 2.0 / 256.0, 1).unwrap();
    let z = &map.z[..256];
    let mean = z.iter().sum::<f64>() / 256.0;
    let z: Vec<f64> = z.iter().map(|v| 10.0 * (v - mean)).collect();
    let k_e = K_CR_BAR * 2f64.powi(-10);
    let (u_in, u_off) = SingleSpring::new(k_e).unwrap().bistable_range().unwrap();
    let a = SpringArray::new(256, 1, k_e, 2.0 * k_e, z).unwrap();
    let (u_max, u_min) = (u_off + 50.0, u_in - 40.0);
    let direct = NewtonOptions {
        linear: LinearSolver::Direct,
        ..NewtonOptions::default()
    };
    let stalled = coupled_cycle(&a, u_max, u_min, 1000, &direct, |_| Ok(()));
    assert!(
        matches!(stalled, Err(adhesion::error::Error::NoConvergence { .. })),
        "the direct path is expected to stall here: {:?}",
        stalled.map(|c| c.jumps.len())
    );
    let iterative = NewtonOptions {
        linear: LinearSolver::Iterative,
        ..NewtonOptions::default()
    };
    let c = coupled_cycle(&a, u_max, u_min, 1000, &iterative, |_| Ok(())).unwrap();
    assert!(c.all_stable);
    assert!(
        c.jumps.iter().any(|j| j.out_of_contact > 50),
        "a front peels many springs at once"
    );
    assert!(adhesion_efficiency(&c, 256) > 0.0);
}

// The local energy of a set of springs (what the iterative path's local moves minimise) against
// the whole energy: moving the springs of the set changes both by the same amount, and its
// gradient is theirs. The set holds pairs of neighbours along a row and across rows (each
// coupling spring inside the set counted once), one at the grid's edge, and a lone spring.
#[test]
fn the_local_energy_of_a_set_of_springs_matches_the_whole_energy() {
    use adhesion::numerics::newton::Energy;
    let (nx, ny) = (7, 5);
    let k_e = 0.01;
    let a = SpringArray::new(nx, ny, k_e, 3.0 * k_e, gaussian_heights(nx * ny, 0.5, 3)).unwrap();
    let e = a.energy_at(1.5);
    let d: Vec<f64> = (0..nx * ny).map(|i| 1.2 + 0.05 * ((i * 7) % 11) as f64).collect();
    let set = [0, 1, 7, 8, 9, 16, 23, 24, 30, 34];
    let mut local_grad = vec![0.0; set.len()];
    let e_local = e.local_energy(&d, &set, &mut local_grad).unwrap();
    let mut grad = vec![0.0; d.len()];
    e.gradient(&d, &mut grad);
    for (k, &i) in set.iter().enumerate() {
        assert_rel("gradient of a set member", local_grad[k], grad[i], 1e-12);
    }
    let mut moved = d.clone();
    for (k, &i) in set.iter().enumerate() {
        moved[i] += 0.02 * (k as f64 - 4.5);
    }
    let moved_local = e.local_energy(&moved, &set, &mut local_grad).unwrap();
    assert_rel(
        "energy change",
        moved_local - e_local,
        e.energy(&moved) - e.energy(&d),
        1e-9,
    );
}
