//! Chapter 4: the Lennard-Jones contact of a smooth tip with the axisymmetric surface model,
//! sections 4.2-4.4, and the loading-path driver it runs on.
//!
//! The surface model is exact for a rigid flat substrate up to the strain of the surface layer
//! (ERRATA on (4.19)); its limits are the DMT force 2πwR for a stiff tip (small Tabor
//! parameter) and the JKR force 1.5πwR for a compliant one. Fig. 4.5's parameters (μ_T ≈ 5)
//! sit between, near JKR (χ = 0.124 in the Maugis-Dugdale reading).

use std::f64::consts::PI;

use adhesion::figure::Figure;
use adhesion::job::Job;
use adhesion::models::axisymmetric::cycle::{CycleOptions, TipCycle, run_cycle};
use adhesion::models::axisymmetric::tip::{Tip, TipParams};
use adhesion::numerics::newton::{Energy, NewtonOptions, StableNewton, plain_newton};
use adhesion::scenes::Scene;
use adhesion::scenes::fig4::criterion::{Fig4_3, Fig4_3Params, parabola_error_before_pull_in};

/// Fig. 4.5: R = 5 µm, E = 4.4 MPa, ν = 0.25, C6 = 3, C12 = 1, σ = 1 nm, A_H = 2e-21 J; a
/// grid of ring width 0.25 b (b = ζ0²E*/w ≈ 4.9 nm) over 250 nm, 4 Gauss points per interval.
fn fig4_5(modulus_factor: f64) -> TipParams {
    let d = TipParams::default();
    TipParams {
        modulus: modulus_factor * d.modulus,
        ..d
    }
}

/// A shallow cycle: from 12 ζ0 apart to 3 ζ0 deep, steps of 0.2 ζ0, jumps to 1e-3 ζ0.
fn shallow_cycle(tip: &Tip, keep_profiles: bool) -> TipCycle {
    let z = tip.scales().length;
    let opts = CycleOptions {
        h_start: 12.0 * z,
        h_min: -3.0 * z,
        step: 0.2 * z,
        refine_to: 1e-3 * z,
        contact_gap: 1e-9,
        keep_profiles,
        unload_to: None,
    };
    run_cycle(tip, &opts, |_| Ok(())).expect("cycle")
}

// Sec. 4.4, Fig. 4.5: one pull-in on loading and one pull-off on unloading, nothing else (a
// grid fine enough that the contact edge does not hop from ring to ring); every accepted
// state has a positive-definite Hessian (asserted by the driver's certificate); the adhesive
// force lies between the JKR (1.5πwR) and DMT (2πwR) limits, near JKR at μ_T ≈ 5.
#[test]
fn smooth_tip_has_one_pull_in_and_one_pull_off_and_only_stable_states() {
    let tip = Tip::new(&fig4_5(1.0)).expect("tip");
    let w = tip.scales().work_of_adhesion;
    let cycle = shallow_cycle(&tip, false);
    assert!(cycle.stats.all_stable, "an accepted state was not stable");
    assert!(cycle.loading.iter().chain(&cycle.unloading).all(|s| s.stable));
    assert_eq!(cycle.jumps.len(), 2, "{:?}", cycle.jump_counts());
    let (pull_in, pull_off) = (&cycle.jumps[0], &cycle.jumps[1]);
    assert!(pull_in.loading && pull_in.is_pull_in());
    assert!(!pull_off.loading && !pull_off.is_pull_in());
    assert_eq!(pull_in.before.contact.radius(), 0.0);
    assert_eq!(pull_off.after.contact.radius(), 0.0);
    // Pull-off happens at a larger separation than pull-in (the neck), Fig. 4.5a.
    assert!(pull_off.before.depth > pull_in.before.depth);
    let ratio = -cycle.adhesive_force() / (PI * w * 5e-6);
    assert!((1.5..1.6).contains(&ratio), "P_adh/(πwR) = {ratio}");
    // The loop encloses energy: the instabilities dissipate.
    assert!(cycle.hysteresis() > 0.0);
    // After pull-off the tip is free: the force returns to the loading branch's value.
    let (first, last) = (&cycle.loading[0], cycle.unloading.last().expect("states"));
    assert!((first.force - last.force).abs() < 1e-6 * PI * w * 5e-6);
}

// The DMT limit (sec. 4.4, (3.3) as χ → 0): a tip 1000 times stiffer has μ_T ≈ 0.05, no
// instability at all, and its most tensile force approaches 2πwR (Derjaguin: the undeformed
// sphere's plate interaction, −2πR φ(ζ0) at touching).
#[test]
fn stiff_tip_reaches_the_dmt_force_without_instabilities() {
    // The ring width must resolve the sphere's interaction zone √(2Rζ0) ≈ 77 nm, which is far
    // below b ≈ 4.9 µm here: rings of 2.5 nm.
    let mut p = fig4_5(1000.0);
    p.ring_width = 5e-4;
    let tip = Tip::new(&p).expect("tip");
    let w = tip.scales().work_of_adhesion;
    let cycle = shallow_cycle(&tip, false);
    assert!(cycle.jumps.is_empty(), "{} jumps", cycle.jumps.len());
    assert!(cycle.stats.all_stable);
    let ratio = -cycle.adhesive_force() / (PI * w * 5e-6);
    assert!((ratio - 2.0).abs() < 0.03, "P_adh/(πwR) = {ratio}");
    // No instability, no loss (up to the trapezoid rule on identical paths).
    let scale = PI * w * 5e-6 * tip.scales().length;
    assert!(
        cycle.hysteresis().abs() < 1e-3 * scale,
        "H = {} πwRζ0",
        cycle.hysteresis() / scale
    );
}

/// Fraction of the way from the free state just before pull-in towards the state after it
/// where plain Newton starts (0.02 to 0.2 all reach the saddle).
const T_START: f64 = 0.05;

// Stability is the subject: just before pull-in the free state and a saddle (the unstable
// equilibrium of the incipient neck) lie close together and annihilate at the fold. Plain
// Newton started a little way from the free state towards contact converges to the saddle, an
// equilibrium no experiment can observe; the stable minimiser from the same start ends in a
// state with a positive-definite Hessian and lower energy.
#[test]
fn plain_newton_finds_the_saddle_the_stable_minimiser_avoids() {
    let tip = Tip::new(&fig4_5(1.0)).expect("tip");
    let cycle = shallow_cycle(&tip, true);
    let pull_in = &cycle.jumps[0];
    let (before, after) = (&pull_in.before, &pull_in.after);
    let e = tip.energy_at(tip.approach(before.depth));
    let opts = NewtonOptions {
        gradient_tol: 1e-7,
        step_tol: 1e-6,
        max_iterations: 200,
        ..NewtonOptions::default()
    };
    let mut solver = StableNewton::new(&e).expect("solver");
    let start: Vec<f64> = before
        .displacement
        .iter()
        .zip(&after.displacement)
        .map(|(a, b)| a + T_START * (b - a))
        .collect();
    let mut saddle = start.clone();
    plain_newton(&e, &mut saddle, &opts).expect("plain Newton converges");
    let mut g = vec![0.0; e.dim()];
    e.gradient(&saddle, &mut g);
    assert!(
        g.iter().all(|x| x.abs() < 1e-6),
        "plain Newton ended at an equilibrium"
    );
    assert!(e.energy(&saddle).is_finite());
    assert!(!solver.is_stable(&e, &saddle).expect("test"), "it is a saddle");
    let mut stable = start;
    solver.minimize(&e, &mut stable, &opts).expect("stable minimiser");
    assert!(solver.is_stable(&e, &stable).expect("test"));
    assert!(e.energy(&stable) < e.energy(&saddle));
}

/// Fig. 4.7: R = 10 µm, E = 2.2 MPa, ν = 0.25, A_H = 1e-21 J, σ = 1 nm, C6 = 3, C12 = 1, and the
/// waviness A = `amplitude`, λ = 0.125 µm, on the grid of [`fig4_5`].
fn fig4_7(amplitude: f64) -> TipParams {
    let nu: f64 = 0.25;
    TipParams {
        radius: 10e-6,
        modulus: 2.2e6 / (1.0 - nu * nu),
        hamaker: 1e-21,
        amplitude,
        wavelength: 1.25e-7,
        fine_radius: 4.5e-7,
        ..fig4_5(1.0)
    }
}

/// A cycle from 25 ζ0 apart (beyond every pull-off here) to `h_min` [m], steps of 0.25 ζ0.
fn cycle_to(tip: &Tip, h_min: f64) -> TipCycle {
    let z = tip.scales().length;
    let opts = CycleOptions {
        h_start: 25.0 * z,
        h_min,
        step: 0.25 * z,
        refine_to: 1e-3 * z,
        contact_gap: 1e-9,
        keep_profiles: false,
        unload_to: None,
    };
    run_cycle(tip, &opts, |_| Ok(())).expect("cycle")
}

// Sec. 4.5.1, Fig. 4.7a: depth-dependent hysteresis. The wavy tip (A = 1.25 nm) pressed to
// |h_min|/R = 7e-4 meets more asperity-level instabilities than pressed to 1.5e-4, and loses
// more energy; the smooth tip's single loop does not depend on the depth (both cycles end
// free, so the loss is the loop's area).
#[test]
fn wavy_tip_loss_grows_with_depth_and_the_smooth_tip_loss_does_not() {
    let depths = [1.5e-4 * 10e-6, 7e-4 * 10e-6];
    let mut losses = Vec::new();
    for amplitude in [1.25e-9, 0.0] {
        let tip = Tip::new(&fig4_7(amplitude)).expect("tip");
        let scale = 2.0 * tip.params().modulus * 1e-15; // 2E*R³
        let cycles: Vec<TipCycle> = depths.iter().map(|&h| cycle_to(&tip, -h)).collect();
        for c in &cycles {
            assert!(c.stats.all_stable);
            // Ends free: the last jump is a pull-off to no contact.
            let last = c.jumps.last().expect("jumps");
            assert!(!last.loading && last.after.contact.radius() == 0.0);
        }
        let (shallow, deep) = (&cycles[0], &cycles[1]);
        let (h0, h1) = (shallow.hysteresis() / scale, deep.hysteresis() / scale);
        losses.push((h0, h1, shallow.jumps.len(), deep.jumps.len()));
        if amplitude > 0.0 {
            assert!(deep.jumps.len() > shallow.jumps.len(), "{losses:?}");
            assert!(h1 > 1.3 * h0, "wavy: {h0} -> {h1}");
        } else {
            assert_eq!((shallow.jumps.len(), deep.jumps.len()), (2, 2));
            assert!((h1 - h0).abs() < 0.02 * h0, "smooth: {h0} -> {h1}");
        }
    }
    eprintln!("(H shallow, H deep, jumps shallow, jumps deep) / 2E*R^3, wavy then smooth: {losses:?}");
}

// Sec. 4.4, Fig. 4.4: without attraction (C6 = 0, only the repulsive wall of (4.4)) the tip
// follows Hertz, P = (4/3) E* √R d^(3/2), up to the position of the wall: d = h0 − h with one
// offset h0 of the order of σ, fitted here. R = 10 µm, E = 1.1 MPa, ν = 0.25, σ = 1 nm,
// A_H = 2e-21 J; loading to 300 σ (a/R ≈ 0.17), no jump, every state stable.
#[test]
fn adhesionless_tip_follows_hertz() {
    let nu: f64 = 0.25;
    let radius = 10e-6;
    let modulus = 1.1e6 / (1.0 - nu * nu);
    let p = TipParams {
        radius,
        modulus,
        c6: 0.0,
        // b = σE*/p_ref is 0.66 µm without attraction: rings of 13 nm.
        ring_width: 0.02,
        fine_radius: 2.1e-6,
        ..TipParams::default()
    };
    let tip = Tip::new(&p).expect("tip");
    let s = tip.scales().length;
    let opts = CycleOptions {
        h_start: 5.0 * s,
        h_min: -300.0 * s,
        step: 4.0 * s,
        refine_to: 1e-3 * s,
        contact_gap: 1e-9,
        keep_profiles: false,
        unload_to: Some(-299.0 * s),
    };
    let c = run_cycle(&tip, &opts, |_| Ok(())).expect("cycle");
    let hertz = |d: f64| 4.0 / 3.0 * modulus * radius.sqrt() * d.max(0.0).powf(1.5);
    let pts: Vec<(f64, f64)> = c
        .loading
        .iter()
        .filter(|st| st.depth < -100.0 * s)
        .map(|st| (st.depth, st.force))
        .collect();
    // Offset h0 from the deepest state, then the error over the deep half of the loading.
    let (hd, pd) = *pts.last().expect("states");
    let h0 = hd + (pd / (4.0 / 3.0 * modulus * radius.sqrt())).powf(2.0 / 3.0);
    let err = pts
        .iter()
        .map(|&(h, f)| (f - hertz(h0 - h)).abs() / f)
        .fold(0.0, f64::max);
    assert!(c.jumps.is_empty() && c.stats.all_stable);
    assert!(h0.abs() < s, "wall offset {} sigma", h0 / s);
    // The soft repulsive wall differs from Hertz's hard contact by terms of order σ/d (its gap
    // shrinks with the pressure, g ∝ p^(-1/9)); with one fitted offset the deviation over
    // d = 30-100 σ was 3.2e-3 (the same at rings of 0.02 b and 0.01 b, so not the grid); over
    // d = 100-300 σ, measured 8.2e-4.
    assert!(err < 1e-3, "largest relative deviation from Hertz {err}");
}

/// Run scene `id` with `sets` (NAME=VALUE) on top of its defaults.
fn run_scene(id: &str, sets: &[&str]) -> adhesion::figure::Figure {
    let scene = adhesion::scenes::find(id).expect("scene");
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_string()).collect();
    let values = adhesion::headless::resolve_values(scene, None, &sets, false).expect("values");
    scene.run(&values, &adhesion::job::Job::quiet()).expect("run")
}

// fig4.5-accuracy, the smooth tip of Fig. 4.5 cycled from 12 ζ0 apart to 3 ζ0 deep in steps of
// 0.2 ζ0: the exact cycle has one pull-in and one pull-off. Rings of 1 b (b = ζ0²E*/w ≈ 4.9 nm,
// the edge zone of the adhesive traction) let the contact edge hop from ring to ring: tens of
// spurious jumps (measured 46 with 4 or 1 Gauss points) and fake loss (H 24 % off, P_adh 6 %).
// The default rings of 0.25 b have none, and their P_adh is within 1.2e-4 and H within 2.2e-4 of
// rings of 0.18 b (the scene's default reference, 0.125 b, costs 20 s more). Bounds: about 4x
// the measured errors, which are not monotone in h at this level (against 0.125 b: 4.1e-5 and
// 4.6e-4).
#[test]
fn coarse_rings_hop_and_the_default_rings_do_not() {
    let fig = run_scene(
        "fig4.5-accuracy",
        &[
            "ring_widths=1,0.18",
            "steps=0.2",
            "quadrature_sweep=1",
            "wall_clock=false",
        ],
    );
    let r = |n: &str| fig.result_value(n).unwrap_or_else(|| panic!("no result {n}"));
    assert_eq!(r("reference_ring_width_norm"), 0.18);
    assert_eq!(r("all_states_stable_count"), 1.0);
    // The mechanism: hopping on coarse rings, with 4 and with 1 Gauss point.
    assert!(
        r("coarsest_spurious_jumps_count") >= 10.0,
        "{}",
        r("coarsest_spurious_jumps_count")
    );
    let one_point = fig.panels[1]
        .series
        .iter()
        .find(|s| s.name == "1 Gauss point")
        .expect("the 1-point width sweep");
    assert!(
        one_point.points.iter().any(|&(h, n)| h == 1.0 && n >= 10.0),
        "{:?}",
        one_point.points
    );
    assert!(r("coarsest_hysteresis_error_norm") > 0.1);
    assert!(r("coarsest_adhesive_force_error_norm") > 0.01);
    // The default: clean, and close to the finer rings.
    assert_eq!(r("default_spurious_jumps_count"), 0.0);
    assert_eq!(r("fewest_points_spurious_jumps_count"), 0.0);
    assert_eq!(r("coarsest_clean_ring_width_norm"), 0.25);
    assert!(
        r("default_adhesive_force_error_norm") < 5e-4,
        "{}",
        r("default_adhesive_force_error_norm")
    );
    assert!(
        r("default_hysteresis_error_norm") < 1e-3,
        "{}",
        r("default_hysteresis_error_norm")
    );
    // Between the JKR (1.5) and DMT (2) limits, near JKR at μ_T ≈ 5 (sec. 4.4).
    assert!((1.5..1.6).contains(&r("reference_adhesive_force_norm")));
}

/// Scene fig4.3 at the default grid with the Tabor parameters `mus` and `bisections` cycles of
/// onset bisection.
fn fig4_3(mus: &[f64], bisections: usize) -> Figure {
    let p = Fig4_3Params {
        tabor_parameters: mus.to_vec(),
        onset_bisections: bisections,
        ..Fig4_3Params::default()
    };
    Fig4_3::run(&p, &Job::quiet()).expect("fig4.3")
}

/// The (μ_T, z_c/ζ0) markers named `name` in panel (a).
fn onset_markers(fig: &Figure, name: &str) -> Vec<(f64, f64)> {
    fig.panels[0]
        .markers
        .iter()
        .filter(|m| m.name == name)
        .map(|m| (m.x, m.y))
        .collect()
}

// Sec. 4.3, Fig. 4.3a: the critical separations of the surface model against (4.23) (the
// tip of Fig. 4.5, μ_T = 1, 3, 5 set through E*). (4.23) is an estimate (parabolic profile,
// Boussinesq point load; ERRATA), so the test states how far the model lies from it rather than
// asserting agreement: the pull-in separation grows with μ_T like (4.23)'s, close to
// μ_T^(3/7) (fitted exponent 0.44 measured; (4.23) 0.43), and lies below the root of (4.23) by
// a factor 0.67-0.69 with the printed traction and 0.84-0.85 with the consistent one
// (measured; bounds 0.6-0.8 and 0.75-0.95 cover the grid and the 1e-4 ζ0 jump tolerance,
// which move them by about 1 %). The pull-off separation is the gap of a contact that is
// about to let go: 1.005-1.06 ζ0 (the text: "≈ 1"; bound 0.98-1.15).
#[test]
fn surface_model_onsets_follow_4_23_below_it_and_pull_off_stays_near_zeta0() {
    let fig = fig4_3(&[1.0, 3.0, 5.0], 0);
    let r = |n: &str| fig.result_value(n).expect(n);
    let pull_in = onset_markers(&fig, "surface model, pull-in");
    let pull_off = onset_markers(&fig, "surface model, pull-off");
    assert_eq!(
        (pull_in.len(), pull_off.len()),
        (3, 3),
        "{pull_in:?} {pull_off:?}"
    );
    assert!(pull_in.windows(2).all(|w| w[1].1 > w[0].1), "{pull_in:?}");
    assert!((r("pull_in_exponent_norm") - 3.0 / 7.0).abs() < 0.05);
    for (lo, hi, name) in [
        (0.6, 0.8, "pull_in_ratio"),
        (0.75, 0.95, "pull_in_consistent_ratio"),
    ] {
        let (a, b) = (r(&format!("{name}_min_norm")), r(&format!("{name}_max_norm")));
        assert!(lo < a && b < hi, "{name}: {a}-{b}");
    }
    assert!(
        pull_off.iter().all(|q| (0.98..1.15).contains(&q.1)),
        "{pull_off:?}"
    );
    assert_eq!(r("all_states_stable_count"), 1.0);
    // (4.23)'s own numbers, unrounded (ERRATA): μ_T* = 0.201584, z̄* = 1.082713.
    assert!((r("critical_tabor_norm") - 0.201_584).abs() < 5e-7);
    assert!((r("double_root_norm") - 1.082_713).abs() < 5e-7);
}

// Sec. 4.3: "there is no instability for μ_T < μ_T*". The surface model's first jump comes at
// a larger μ_T than (4.23) predicts with either traction (ERRATA: a full LJ solution jumps
// later): measured between 0.766 and 0.781, above μ_T* = 0.2016 (printed traction) and 0.5036
// (consistent traction); no jump at μ_T = 0.5, one pull-in and one pull-off at 1. Three
// bisections of [0.5, 1] bracket it to 1/16.
#[test]
fn surface_model_jumps_only_above_both_critical_tabor_parameters() {
    let fig = fig4_3(&[0.5, 1.0], 3);
    let r = |n: &str| fig.result_value(n).expect(n);
    let (lo, hi) = (r("onset_tabor_low_norm"), r("onset_tabor_high_norm"));
    assert!((hi - lo - 0.5 / 8.0).abs() < 1e-12, "{lo}-{hi}");
    assert!(lo > r("critical_tabor_consistent_norm") && lo > r("critical_tabor_norm"));
    assert!((0.7..0.85).contains(&lo) && hi < 0.9, "{lo}-{hi}");
    assert_eq!(r("cycles_with_jumps_count"), 2.0); // μ_T = 1 and the μ_T = 5 of panel (b)
}

// Sec. 4.3, Fig. 4.3b and (4.24): the text finds the parabola through the apex within 5 % of
// the deformed profile just before pull-in at μ_T = 5, largest at the centre. With z0 the
// deformed apex gap, err(0) = 0 by construction; the workbench finds the largest error 14.6 %
// at 0.81 √(2Rz_c) (115 nm), and the apex displaced by 0.56 z_c. Bounds: 10-20 % and
// 0.6-1.0 √(2Rz_c) (rings of 0.5 b give 14.3 % at 0.81), and 0.45-0.65 for u(0)/z_c.
#[test]
fn parabola_error_before_pull_in_exceeds_the_printed_5_percent_away_from_the_centre() {
    let p = Fig4_3Params::default();
    let e = parabola_error_before_pull_in(&p)
        .expect("cycle")
        .expect("a pull-in at μ_T = 5");
    assert!(e.error[0] < 1e-12, "err at the first ring {}", e.error[0]);
    let (err, at) = e.max();
    assert!((0.10..0.20).contains(&err), "largest err {err}");
    assert!((0.6..1.0).contains(&(at / e.zone)), "at {} nm", at * 1e9);
    assert!((0.45..0.65).contains(&(e.apex_displacement / e.central_gap)));
    // The other reading (z0 the undeformed apex gap) puts the maximum at the centre.
    let centre = e.error_undeformed[0];
    assert!(e.error_undeformed.iter().all(|&v| v <= centre));
}

// The JKR limit (sec. 4.4): as the Tabor parameter grows the adhesive force of the smooth tip
// falls from the DMT value 2πwR towards the JKR value 1.5πwR. At μ_T = 1, 2.5 and 5 (Fig. 4.5's
// interaction and radius, E* from (1.8)) the surface model's P_adh/(πwR) falls monotonically and
// at μ_T = 5 is within 2% of 1.5 (measured 1.657, 1.562, 1.525; Maugis-Dugdale at μ_T = 5
// gives 1.505).
// Larger μ_T cost about μ_T⁶ (rings of 0.25 b over a contact that grows as μ_T): the limit is
// approached, not reached, in a test.
#[test]
fn smooth_tip_adhesive_force_approaches_jkr_as_the_tabor_parameter_grows() {
    use adhesion::models::lennard_jones::{LennardJones, LennardJonesParams};
    let d = TipParams::default();
    let lj = LennardJones::new(&LennardJonesParams {
        c6: d.c6,
        c12: d.c12,
        sigma: d.sigma,
        hamaker: d.hamaker,
    })
    .unwrap();
    let ratios: Vec<f64> = [1.0, 2.5, 5.0]
        .iter()
        .map(|&mu| {
            let mut p = TipParams {
                modulus: lj.modulus_for_tabor(d.radius, mu).unwrap(),
                ..d
            };
            let tip0 = Tip::new(&p).unwrap();
            let z = tip0.scales().length;
            p.fine_radius = p.fine_radius_for_depth(-3.0 * z).unwrap();
            let tip = Tip::new(&p).unwrap();
            let cycle = shallow_cycle(&tip, false);
            assert!(cycle.stats.all_stable);
            -cycle.adhesive_force() / (PI * tip.scales().work_of_adhesion * d.radius)
        })
        .collect();
    eprintln!("P_adh/(πwR) at μ_T = 1, 2.5, 5: {ratios:?}");
    assert!(ratios.windows(2).all(|w| w[1] < w[0]), "{ratios:?}");
    assert!(ratios[0] < 2.0 && ratios[0] > 1.55, "{ratios:?}");
    assert!((ratios[2] / 1.5 - 1.0).abs() < 0.02, "{ratios:?}");
}
