//! Chapter 4, the finite-element model (sections 4.2.2-4.4): the body force against the plate
//! traction, adhesionless loading against Hertz, and the finite-element model against the
//! surface model where the surface layer's strain is small.

use std::f64::consts::PI;

use adhesion::models::axisymmetric::cycle::{CycleOptions, TipCycle, run_cycle};
use adhesion::models::axisymmetric::tip::{Tip, TipParams};
use adhesion::models::body_force_fe::tip::{FeTip, FeTipParams};
use adhesion::models::lennard_jones::{LennardJones, LennardJonesParams};

/// A loading path from `start` to `end` (in units of the normal length) in steps of `step`,
/// with one unloading step.
fn load<M: adhesion::models::axisymmetric::cycle::CycleModel>(
    model: &M,
    start: f64,
    end: f64,
    step: f64,
) -> TipCycle {
    let l = model.length_unit();
    let opts = CycleOptions {
        h_start: start * l,
        h_min: end * l,
        step: step * l,
        refine_to: 1e-3 * l,
        contact_gap: 1e-9,
        keep_profiles: false,
        unload_to: Some((end + 0.5 * step) * l),
    };
    run_cycle(model, &opts, |_| Ok(())).expect("path")
}

// The body force (4.15) integrated through an undeformed column of a flat tip is the plate
// traction (4.5): P/(π r0²) = −p(δ) + p(δ + h0) for the column from the gap δ to δ + h0, to
// 1e-10 of the largest traction σ0, however thin or thick its elements (the integration is
// exact in z), with the near field's Gauss rule in r everywhere. At δ = ζ0 the traction
// vanishes: attraction and repulsion cancel through the column, so the error is measured
// against σ0, not against the traction itself. With the default 2 Gauss points in r beyond
// 30 ζ0 (where a chord ending on a sloping edge is no longer integrated exactly in r) the
// force stays within 1e-8 σ0 (measured: 1.5e-9 at δ = 0.9 ζ0).
#[test]
fn body_force_column_integral_is_the_plate_traction() {
    let p = FeTipParams {
        radius: 1e300,
        r0: 2e-7,
        h0: 3e-7,
        fine_radius: 5e-8,
        far_quadrature_points: 4,
        ..FeTipParams::default()
    };
    let tip = FeTip::new(&p).expect("tip");
    let far = FeTip::new(&FeTipParams {
        far_quadrature_points: FeTipParams::default().far_quadrature_points,
        ..p
    })
    .expect("tip");
    let law = LennardJones::new(&LennardJonesParams {
        c6: p.c6,
        c12: p.c12,
        sigma: p.sigma,
        hamaker: p.hamaker,
    })
    .expect("law");
    let l = tip.scales().length;
    let u = vec![0.0; tip.len()];
    for delta in [0.9, 1.0, 1.3, 3.0, 20.0] {
        let force = tip.force(delta, &u) / (PI * p.r0 * p.r0);
        let exact = -law.traction(delta * l) + law.traction(delta * l + p.h0);
        assert!(
            (force - exact).abs() < 1e-10 * law.max_traction(),
            "gap {delta} zeta0: {force} vs {exact}"
        );
        let reduced = far.force(delta, &u) / (PI * p.r0 * p.r0);
        eprintln!(
            "column at {delta} zeta0: 2 Gauss points beyond 30 zeta0 off by {:.2e} sigma0",
            (reduced - exact).abs() / law.max_traction()
        );
        assert!((reduced - exact).abs() < 1e-8 * law.max_traction());
    }
}

/// The Hertz test of Fig. 4.4 (R = 10 µm, E = 1.1 MPa, ν = 0.25, C6 = 0, C12 = 1, σ = 1 nm,
/// A_H = 2e-21 J) on a tip of radius and height 16 R, with elements growing by `grading`
/// with the distance from the contact zone: the largest relative deviation of the force from
/// Hertz over d = 100-300 σ, with one wall offset fitted at the deepest state (as for the
/// surface model), and the states' stability.
fn hertz_deviation(grading: f64) -> (f64, f64, bool, usize) {
    let nu: f64 = 0.25;
    let (radius, young) = (10e-6, 1.1e6);
    let modulus = young / (1.0 - nu * nu);
    let p = FeTipParams {
        radius,
        youngs_modulus: young,
        poisson_ratio: nu,
        c6: 0.0,
        // b = σE*/p_ref is 0.66 µm without attraction: elements of 3.3 nm.
        element_width: 0.005,
        fine_radius: 2.1e-6,
        grading,
        r0: 16.0 * radius,
        h0: 16.0 * radius,
        ..FeTipParams::default()
    };
    let tip = FeTip::new(&p).expect("tip");
    let c = load(&tip, 5.0, -300.0, 4.0);
    let s = tip.scales().length;
    let pts: Vec<(f64, f64)> = c
        .loading
        .iter()
        .filter(|st| st.depth < -90.0 * s)
        .map(|st| (st.depth, st.force))
        .collect();
    let k = 4.0 / 3.0 * modulus * radius.sqrt();
    let (hd, pd) = *pts.last().expect("states");
    let h0 = hd + (pd / k).powf(2.0 / 3.0);
    let err = pts
        .iter()
        .map(|&(h, f)| (f - k * (h0 - h).max(0.0).powf(1.5)).abs() / f)
        .fold(0.0, f64::max);
    (err, h0 / s, c.jumps.is_empty() && c.stats.all_stable, tip.len())
}

// Sec. 4.4, Fig. 4.4: without attraction the finite-element tip follows Hertz over d = 100-300 σ
// (a/R up to 0.17), converging as the bulk mesh is refined; no jump, every state positive
// definite. The aim of 1 % is not met on these meshes: measured 6.70e-2 (grading 0.3, 18 312
// unknowns) and 3.96e-2 (grading 0.15, 32 215 unknowns) with a fitted wall offset of 3.0 σ; the
// finite tip (16 R, top held) stiffens it by about a(1+ν)(3−2ν)/(π(1−ν²)h0) ≈ 1 % at the
// deepest state and the bulk mesh accounts for the rest. A study of 12 minutes (two paths of
// 76 states); the default run checks the convergence on the quick scene below.
#[test]
#[ignore = "slow study: 12 minutes"]
fn adhesionless_finite_element_tip_follows_hertz() {
    let (fine, offset, clean, n_fine) = hertz_deviation(0.15);
    let (coarse, _, clean_coarse, n_coarse) = hertz_deviation(0.3);
    eprintln!(
        "Hertz deviation: grading 0.3 ({n_coarse} unknowns) {coarse:.3e}, grading 0.15 ({n_fine} unknowns) {fine:.3e}, wall offset {offset:.2} sigma"
    );
    assert!(clean && clean_coarse);
    assert!(fine < 0.05, "deviation from Hertz {fine}");
    assert!(fine < coarse, "refinement: {coarse} -> {fine}");
    assert!(offset.abs() < 4.0, "wall offset {offset} sigma");
}

/// The surface model and the finite-element model of the same tip, loaded along the same path,
/// both with rings (elements) 1.2 nm wide over the contact zone (0.25 b at 4.4 MPa).
fn both_models(young: f64) -> (TipCycle, TipCycle) {
    let nu: f64 = 0.25;
    let modulus = young / (1.0 - nu * nu);
    let b = Tip::new(&TipParams {
        modulus,
        ..TipParams::default()
    })
    .expect("tip")
    .scales()
    .radial;
    let fe = FeTipParams {
        youngs_modulus: young,
        poisson_ratio: nu,
        element_width: 1.2e-9 / b,
        fine_radius: 2.0e-7,
        r0: 1e-4,
        h0: 1e-4,
        grading: 0.15,
        ..FeTipParams::default()
    };
    let surface = TipParams {
        modulus,
        ring_width: 1.2e-9 / b,
        fine_radius: 2.0e-7,
        ..TipParams::default()
    };
    let fe_tip = FeTip::new(&fe).expect("fe tip");
    let surface_tip = Tip::new(&surface).expect("surface tip");
    (load(&fe_tip, 6.0, -2.0, 0.5), load(&surface_tip, 6.0, -2.0, 0.5))
}

/// Largest difference of the forces at the depths both paths visited (the targets; a jump's
/// bisection states are in one path only), over the largest |force|.
fn force_gap(a: &TipCycle, b: &TipCycle) -> f64 {
    let scale = a.loading.iter().map(|s| s.force.abs()).fold(0.0, f64::max);
    let mut common = 0;
    let gap = a
        .loading
        .iter()
        .filter_map(|x| {
            let y = b.loading.iter().find(|y| (x.depth - y.depth).abs() < 1e-15)?;
            common += 1;
            Some((x.force - y.force).abs())
        })
        .fold(0.0, f64::max);
    assert!(common >= 10, "{common} common depths");
    gap / scale
}

// The body-force and the surface-traction models differ only through the strain of the surface
// layer (of order p/E): for a stiff tip (E = 100 × 4.4 MPa, Fig. 4.5's geometry and
// interaction, no instability) the two loading paths agree closely, and the gap shrinks as the
// modulus grows.
#[test]
fn finite_element_and_surface_models_agree_at_small_surface_strain() {
    let (fe_stiff, surface_stiff) = both_models(440e6);
    let (fe_mid, surface_mid) = both_models(44e6);
    let stiff = force_gap(&fe_stiff, &surface_stiff);
    let mid = force_gap(&fe_mid, &surface_mid);
    eprintln!(
        "FE vs surface model, largest force difference / largest force: E = 44 MPa {mid:.3e}, E = 440 MPa {stiff:.3e}"
    );
    assert!(fe_stiff.stats.all_stable && fe_mid.stats.all_stable);
    assert!(stiff < 0.02, "{stiff}");
    assert!(stiff < mid, "{mid} -> {stiff}");
}

// Fig. 4.4 in quick form (a tip of 6 R, coarse bulk mesh, to 60 σ): no jump, every state
// stable, and the deviation from Hertz falls as the bulk mesh is refined.
#[test]
fn fig4_4_deviation_from_hertz_falls_with_the_bulk_mesh() {
    use adhesion::job::Job;
    use adhesion::scenes::Scene;
    use adhesion::scenes::fig4::fe::{Fig4_4, Fig4_4Params};
    let mut p = Fig4_4Params::default();
    Fig4_4::quick(&mut p);
    let coarse = Fig4_4::run(&p, &Job::quiet()).expect("coarse");
    p.grading = 0.25;
    let fine = Fig4_4::run(&p, &Job::quiet()).expect("fine");
    let dev = |f: &adhesion::figure::Figure| f.result_value("hertz_deviation_norm").expect("result");
    eprintln!(
        "fig4.4 quick: deviation from Hertz {:.3e} (grading 0.5) -> {:.3e} (grading 0.25)",
        dev(&coarse),
        dev(&fine)
    );
    for f in [&coarse, &fine] {
        assert_eq!(f.result_value("jumps_count"), Some(0.0));
        assert_eq!(f.result_value("all_states_stable_count"), Some(1.0));
    }
    assert!(dev(&fine) < dev(&coarse));
}

/// The wavy tip of Fig. 4.7 (A = 1.25 nm, λ = 0.125 µm, R = 10 µm, E = 2.2 MPa,
/// A_H = 1e-21 J) in the finite-element model with surface elements `element_width` b wide and
/// bulk grading `grading` in a tip of `size` R, cycled from `h_start` ζ0 to |h_min|/R = 1.5e-4
/// and 7e-4 in steps of `step` ζ0, jumps located to `refine` ζ0: (H/(2E*R³), jumps) of the
/// shallow and the deep cycle, the unknowns, and whether every state was stable.
fn wavy_cycles(
    element_width: f64,
    grading: f64,
    size: f64,
    (h_start, step, refine): (f64, f64, f64),
) -> ([(f64, usize); 2], usize, bool) {
    let p = FeTipParams {
        radius: 10e-6,
        youngs_modulus: 2.2e6,
        hamaker: 1e-21,
        amplitude: 1.25e-9,
        wavelength: 1.25e-7,
        fine_radius: 4.5e-7,
        element_width,
        grading,
        r0: size * 10e-6,
        h0: size * 10e-6,
        ..FeTipParams::default()
    };
    let tip = FeTip::new(&p).expect("tip");
    let z = tip.scales().length;
    let cycle = |h_min: f64| {
        let opts = CycleOptions {
            h_start: h_start * z,
            h_min,
            step: step * z,
            refine_to: refine * z,
            contact_gap: 1e-9,
            keep_profiles: false,
            unload_to: None,
        };
        run_cycle(&tip, &opts, |_| Ok(())).expect("cycle")
    };
    let (shallow, deep) = rayon::join(|| cycle(-1.5e-4 * 10e-6), || cycle(-7e-4 * 10e-6));
    let scale = 2.0 * 2.2e6 / (1.0 - 0.0625) * 1e-15;
    let loss = |c: &TipCycle| (c.hysteresis() / scale, c.jumps.len());
    (
        [loss(&shallow), loss(&deep)],
        tip.len(),
        shallow.stats.all_stable && deep.stats.all_stable,
    )
}

// Sec. 4.5.1, Fig. 4.7a with the finite-element model: the wavy tip pressed to |h_min|/R = 7e-4
// meets more asperity-level instabilities than pressed to 1.5e-4 and loses more energy, as in
// the surface model. The study (grading 0.3, tip of 8 R, 8 598 unknowns, steps of 0.25 ζ0,
// jumps to 1e-3 ζ0) measured H/(2E*R³) = 1.554e-8 with 3 jumps -> 2.746e-8 (x1.77) with 6 jumps.
#[test]
#[ignore = "slow study: several minutes"]
fn wavy_finite_element_tip_loss_grows_with_depth() {
    let ([(h0, j0), (h1, j1)], n, stable) = wavy_cycles(0.25, 0.3, 8.0, (25.0, 0.25, 1e-3));
    eprintln!(
        "FE wavy tip ({n} unknowns): H/(2E*R^3) {h0:.4e} (|h_min|/R = 1.5e-4, {j0} jumps) -> {h1:.4e} (7e-4, {j1} jumps)"
    );
    assert!(stable);
    assert!(j1 > j0);
    assert!(h1 > 1.3 * h0, "{h0} -> {h1}");
}

// The same growth on a coarse mesh in CI (12 s of CPU): surface elements of 0.5 b, bulk grading
// 0.4 in a tip of 4 R (3 970 unknowns), steps of 0.5 ζ0 from 20 ζ0, jumps located to 1e-2 ζ0.
// Measured: H/(2E*R³) = 1.648e-8 with 6 jumps -> 2.935e-8 (x1.78) with 9 jumps; the coarse
// surface elements add contact-edge hops to both cycles (with elements of 0.25 b: 1.546e-8,
// 4 jumps -> 2.744e-8, 6 jumps, 22 s).
#[test]
fn wavy_finite_element_tip_loss_grows_with_depth_on_a_coarse_mesh() {
    let ([(h0, j0), (h1, j1)], n, stable) = wavy_cycles(0.5, 0.4, 4.0, (20.0, 0.5, 1e-2));
    eprintln!(
        "FE wavy tip, coarse ({n} unknowns): H/(2E*R^3) {h0:.4e} (|h_min|/R = 1.5e-4, {j0} jumps) -> {h1:.4e} (7e-4, {j1} jumps)"
    );
    assert!(stable);
    assert!(j1 > j0);
    assert!(h1 > 1.3 * h0, "{h0} -> {h1}");
}

// Fig. 4.5 with `model = fe` in quick form (to h = −3 ζ0 in steps of 0.25 ζ0; a tip of 4 R with
// bulk grading 0.4, 5 572 unknowns) against the same scene with the surface model: P_adh within
// 5 % (measured +3.4 %), H within 5 % (+1.8 %), the pull-in and pull-off depths within 2 %
// (−1.2 %, −0.85 %), every state stable. The coarse bulk of the quick mesh also coarsens the thin
// surface layers (only the rows next to the surface stay fine), and the receding contact edge
// hops from element to element on unloading: 8 jumps instead of the surface model's 2 (6 at
// grading 0.3, 3 at 0.2, 2 at 0.15 and at the scene's default mesh).
#[test]
fn fig4_5_finite_element_model_agrees_with_the_surface_model_in_quick_form() {
    use adhesion::job::Job;
    use adhesion::scenes::Scene;
    use adhesion::scenes::fig4::{Fig4_5, Fig4_5Params, TipModel};
    let mut p = Fig4_5Params::default();
    Fig4_5::quick(&mut p);
    let surface = Fig4_5::run(&p, &Job::quiet()).expect("surface model");
    p.model = TipModel::Fe;
    Fig4_5::quick(&mut p);
    let fe = Fig4_5::run(&p, &Job::quiet()).expect("finite elements");
    let get = |f: &adhesion::figure::Figure, name: &str| f.result_value(name).expect("result");
    let rel = |name: &str| get(&fe, name) / get(&surface, name) - 1.0;
    eprintln!(
        "fig4.5 quick, finite elements ({} unknowns) against the surface model: P_adh {:+.2e}, H {:+.2e}, pull-in depth {:+.2e}, pull-off depth {:+.2e}, jumps {} and {}",
        get(&fe, "unknowns_count"),
        rel("adhesive_force_norm"),
        rel("hysteresis_norm"),
        rel("pull_in_depth_norm"),
        rel("pull_off_depth_norm"),
        get(&fe, "jumps_count"),
        get(&surface, "jumps_count")
    );
    assert_eq!(get(&fe, "all_states_stable_count"), 1.0);
    assert_eq!(get(&fe, "rings_count"), 0.0);
    assert!(rel("adhesive_force_norm").abs() < 0.05);
    assert!(rel("hysteresis_norm").abs() < 0.05);
    assert!(rel("pull_in_depth_norm").abs() < 0.02);
    assert!(rel("pull_off_depth_norm").abs() < 0.02);
    assert!(get(&fe, "jumps_count") >= 2.0);
    // The same figure: the P-h panel draws the model's cycle with its jumps and markers.
    let ph = &fe.panels[0];
    assert!(
        ph.series
            .iter()
            .any(|s| s.name == "finite elements (LJ body force)")
    );
    assert!(ph.markers.iter().any(|m| m.name == "pull-in"));
    assert!(ph.markers.iter().any(|m| m.name == "pull-off"));
}
