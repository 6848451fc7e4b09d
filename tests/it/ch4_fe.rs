//! Chapter 4, the finite-element model (sections 4.2.2-4.4): the body force against the plate
//! traction, adhesionless loading against Hertz, and the finite-element model against the
//! surface model where the surface layer's strain is small.

use std::f64::consts::PI;

use adhesion::models::axisymmetric::cycle::{
    CycleModel, CycleOptions, TipCycle, run_convex_loading, run_cycle,
};
use adhesion::models::axisymmetric::tip::{Tip, TipParams};
use adhesion::models::body_force_fe::tip::{FeTip, FeTipParams};
use adhesion::models::lennard_jones::{LennardJones, LennardJonesParams};
use std::time::Instant;

// Fig. 4.5's finite-element tip as the benchmarks build it.
#[path = "../../benches/common/mod.rs"]
mod common;
use common::{fe_cycle_options, fig4_5_fe};

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

/// The finite-element tip of the Hertz test of Fig. 4.4 (R = 10 µm, E = 1.1 MPa, ν = 0.25,
/// C6 = 0, C12 = 1, σ = 1 nm, A_H = 2e-21 J): surface elements of 3.3 nm over a fine zone of
/// 2.1 µm (the contact radius at 300 σ is 1.73 µm), in a tip of radius and height `size` R
/// whose elements grow by `grading` with the distance from the fine zone; the surface elements
/// `width` times as wide and the first layer `layer` times as thick (0.1 σ).
fn hertz_tip(size: f64, grading: f64, width: f64, layer: f64) -> FeTip {
    let radius = 10e-6;
    FeTip::new(&FeTipParams {
        radius,
        youngs_modulus: 1.1e6,
        poisson_ratio: 0.25,
        c6: 0.0,
        // b = σE*/p_ref is 0.66 µm without attraction: elements of 3.3 nm.
        element_width: 0.005 * width,
        first_layer: 0.1 * layer,
        fine_radius: 2.1e-6,
        grading,
        r0: size * radius,
        h0: size * radius,
        ..FeTipParams::default()
    })
    .expect("tip")
}

/// The adhesionless tip pressed from `step` σ above contact to −h = 300 σ in steps of `step`
/// σ (σ = ℓ, the normal unit, when C6 = 0) by [`run_convex_loading`]: without attraction the
/// energy is convex, each depth has one equilibrium and the path needs no small steps.
/// Returns (depth [σ], force [N], central gap [σ]) of every state and the path.
fn press(tip: &FeTip, step: f64) -> (Vec<(f64, f64, f64)>, TipCycle) {
    let l = tip.length_unit();
    let opts = CycleOptions {
        h_start: step * l,
        h_min: -300.0 * l,
        // A hair longer, so that rounding does not add a step: the depths are multiples of
        // `step`.
        step: step * l * (1.0 + 1e-9),
        refine_to: 1e-3 * l,
        contact_gap: 1e-9,
        keep_profiles: true,
        unload_to: None,
    };
    let mut c = run_convex_loading(tip, &opts, |_| Ok(())).expect("path");
    let states = c
        .loading
        .iter()
        .map(|st| {
            let (_, gaps) = tip.surface_gaps(tip.approach(st.depth), &st.displacement);
            (st.depth / l, st.force, gaps[0])
        })
        .collect();
    c.loading.iter_mut().for_each(|st| st.displacement = Vec::new());
    (states, c)
}

/// How an adhesionless path compares with Hertz P = (4/3) E* √R d^{3/2} over d = 100-300 σ.
#[derive(Debug, Clone, Copy)]
struct HertzFit {
    /// Largest |P − P_H(h_w − h)|/P, with the wall offset h_w fitted at the deepest state
    /// (the test's measure).
    deviation: f64,
    /// That offset h_w [σ].
    offset: f64,
    /// Stiffness ratio c and offset [σ] of the straight-line fit P^{2/3} = c^{2/3} k^{2/3}
    /// (h_w − h) by least squares: c − 1 is the excess stiffness of the model over Hertz,
    /// free of the offset.
    stiffness: f64,
    line_offset: f64,
    /// The same deviation with the offset of the central gap, h_w = g(0) − σ (the compression
    /// of the apex is d = g(0) − δ), no fit.
    gap_deviation: f64,
    gap_offset: f64,
}

fn hertz_fit(states: &[(f64, f64, f64)]) -> HertzFit {
    let (nu, young, radius, s): (f64, f64, f64, f64) = (0.25, 1.1e6, 10e-6, 1e-9);
    let k = 4.0 / 3.0 * young / (1.0 - nu * nu) * radius.sqrt() * s.powf(1.5);
    let pts: Vec<(f64, f64, f64)> = states
        .iter()
        .copied()
        .filter(|st| st.0 <= -100.0 + 1e-6)
        .collect();
    assert!(
        (pts[0].0 + 100.0).abs() < 1e-6,
        "the range starts at {} sigma",
        -pts[0].0
    );
    let deviation_from = |w: f64| {
        pts.iter()
            .map(|&(h, f, _)| (f - k * (w - h).max(0.0).powf(1.5)).abs() / f)
            .fold(0.0, f64::max)
    };
    let &(hd, pd, gd) = pts.last().expect("states");
    let offset = hd + (pd / k).powf(2.0 / 3.0);
    // Least squares of y = P^{2/3} against x = −h: y = α + β x.
    let n = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |a, &(h, f, _)| (a.0 - h, a.1 + f.powf(2.0 / 3.0)));
    let (mx, my) = (sx / n, sy / n);
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for &(h, f, _) in &pts {
        sxx += (-h - mx) * (-h - mx);
        sxy += (-h - mx) * (f.powf(2.0 / 3.0) - my);
    }
    let beta = sxy / sxx;
    let alpha = my - beta * mx;
    HertzFit {
        deviation: deviation_from(offset),
        offset,
        stiffness: (beta / k.powf(2.0 / 3.0)).powf(1.5),
        line_offset: alpha / beta,
        gap_deviation: deviation_from(gd - 1.0),
        gap_offset: gd - 1.0,
    }
}

/// One row of the Hertz study: the fit, the unknowns, the wall-clock time [s] and the path.
fn hertz_row(size: f64, grading: f64, step: f64) -> (HertzFit, usize, f64, TipCycle) {
    hertz_row_with(size, grading, step, (1.0, 1.0))
}

/// [`hertz_row`] with the surface layers `(width, layer)` of [`hertz_tip`].
fn hertz_row_with(
    size: f64,
    grading: f64,
    step: f64,
    (width, layer): (f64, f64),
) -> (HertzFit, usize, f64, TipCycle) {
    let clock = Instant::now();
    let tip = hertz_tip(size, grading, width, layer);
    let (states, c) = press(&tip, step);
    let fit = hertz_fit(&states);
    let seconds = clock.elapsed().as_secs_f64();
    eprintln!(
        "hertz study: size {size} R, grading {grading}, step {step} sigma, surface width x{width}, first layer x{layer}: {} unknowns, {seconds:.1} s, {} Newton iterations, {} factorizations, jumps {}, stable {}: deviation {:.3e} (offset {:.2} sigma), line fit c - 1 = {:+.3e} (offset {:.2} sigma), central-gap offset {:.2} sigma: deviation {:.3e}",
        tip.len(),
        c.stats.newton_iterations,
        c.stats.factorizations,
        c.jumps.len(),
        c.stats.all_stable,
        fit.deviation,
        fit.offset,
        fit.stiffness - 1.0,
        fit.line_offset,
        fit.gap_offset,
        fit.gap_deviation
    );
    (fit, tip.len(), seconds, c)
}

// The study of the Hertz test's error: `HERTZ_STUDY="size:grading:step[:width:layer],…"` (tip
// size in R, bulk grading, depth step in σ, and optionally the surface elements' width and the
// first layer's thickness relative to the test's), one configuration after the other, e.g.
// `RAYON_NUM_THREADS=1 HERTZ_STUDY=16:0.3:20,128:0.07:20 cargo test --release --test it
// hertz_study -- --ignored --nocapture`.
#[test]
#[ignore = "study: configurations from HERTZ_STUDY"]
fn hertz_study() {
    let spec = std::env::var("HERTZ_STUDY").unwrap_or_else(|_| "16:0.3:20".into());
    for item in spec.split(',') {
        let v: Vec<f64> = item
            .split(':')
            .map(|x| x.trim().parse().expect("number"))
            .collect();
        let surface = (v.get(3).copied().unwrap_or(1.0), v.get(4).copied().unwrap_or(1.0));
        hertz_row_with(v[0], v[1], v[2], surface);
    }
}

// Sec. 4.4, Fig. 4.4: without attraction the finite-element tip follows Hertz over d = 100-300 σ
// (a/R up to 0.17) within 1 % at the test mesh (a tip of 128 R, bulk grading 0.07: 71 970
// unknowns) and converges as the bulk mesh is refined and the tip grows; no instability, every
// state positive definite. The error is an excess stiffness c − 1 of the model over Hertz (from
// the slope of P^{2/3} against the depth), which the offset fitted at the deepest state turns
// into a deviation of about 2 (c − 1) at 100 σ. It has two parts, measured on the grid of tip
// sizes 16-128 R and gradings 0.3-0.05 (steps of 20 σ, one thread): the held top, 16.9 % R/h0
// (the excess falls by 0.52 %, 0.26 %, 0.13 % from 16 to 32, 64, 128 R at every grading: 1.06 %
// at 16 R, 0.13 % at 128 R, about a(1+ν)(3−2ν)/(π(1−ν²)h0) at a = 0.17 R), and the linear
// triangles of the bulk, 1.87 %, 0.68 %, 0.34 %, 0.15 %, 0.07 % at gradings 0.3, 0.15, 0.1,
// 0.07, 0.05 (the same at every size; orders 1.45, 1.72, 2.26, 2.4 between them). Nothing else
// is left at the 0.05 % level: the surface layers move c − 1 by less than 3e-5 (elements half or
// twice as wide, a first layer half or twice as thick), and as both parts vanish the fitted
// offset tends to the wall's position, the central gap minus σ (−0.21 σ; the
// offset of the straight-line fit is −0.10 σ at 128 R, grading 0.05). Measured at the test mesh:
// deviation 5.6e-3 with the offset 0.47 σ, c − 1 = 2.8e-3, 21 s for 16 states (grading 0.3,
// 18 618 unknowns: 4.0e-2, 3.2 s; grading 0.05, 101 820 unknowns: 3.9e-3, 35 s).
// A study of 2-2.5 minutes (seven meshes).
#[test]
#[ignore = "slow study: about 2 minutes"]
fn adhesionless_finite_element_tip_follows_hertz() {
    let gradings = [0.3, 0.15, 0.1, 0.07];
    let by_grading: Vec<_> = gradings.iter().map(|&g| hertz_row(128.0, g, 20.0)).collect();
    let sizes = [16.0, 32.0, 64.0];
    let mut by_size: Vec<_> = sizes.iter().map(|&r| hertz_row(r, 0.07, 20.0)).collect();
    let test_mesh = by_grading.last().expect("rows");
    by_size.push(test_mesh.clone());
    for (fit, n, seconds, c) in by_grading.iter().chain(&by_size) {
        assert!(c.jumps.is_empty() && c.stats.all_stable, "{n} unknowns");
        assert!(*seconds < 300.0, "{n} unknowns: {seconds} s");
        assert!(fit.offset.abs() < 6.0 && fit.line_offset.abs() < 1.0, "{fit:?}");
    }
    let (fit, ..) = test_mesh;
    assert!(fit.deviation < 1e-2, "deviation from Hertz {}", fit.deviation);
    assert!(fit.offset.abs() < 1.0, "wall offset {} sigma", fit.offset);
    // Converging: the deviation and the stiffness excess fall with the bulk mesh and the size.
    for rows in [&by_grading, &by_size] {
        for w in rows.windows(2) {
            let (a, b) = (&w[0].0, &w[1].0);
            assert!(b.deviation < a.deviation, "{} -> {}", a.deviation, b.deviation);
            assert!(b.stiffness < a.stiffness, "{} -> {}", a.stiffness, b.stiffness);
        }
    }
    // The held top's part halves with each doubling of the tip.
    let excess: Vec<f64> = by_size.iter().map(|row| row.0.stiffness - 1.0).collect();
    for w in excess.windows(3) {
        let ratio = (w[0] - w[1]) / (w[1] - w[2]);
        assert!((1.6..2.5).contains(&ratio), "{excess:?}");
    }
    // So the held top's part at 128 R is the last halving, and the rest of the excess is the
    // bulk mesh's, which falls faster than grading^1.3 (measured orders 1.45, 1.72, 2.26).
    let top = excess[2] - excess[3];
    let bulk: Vec<f64> = by_grading.iter().map(|row| row.0.stiffness - 1.0 - top).collect();
    let shares: Vec<String> = bulk.iter().map(|b| format!("{b:.2e}")).collect();
    eprintln!("excess stiffness at 128 R: held top {top:.2e}, bulk mesh {shares:?} at gradings {gradings:?}");
    for (w, g) in bulk.windows(2).zip(gradings.windows(2)) {
        let order = (w[0] / w[1]).ln() / (g[0] / g[1]).ln();
        assert!(order > 1.3, "order {order} from grading {} to {}", g[0], g[1]);
    }
}

// The 1 % aim in the default run (about 10 s on one thread): the test mesh of the study above
// (a tip of 128 R, bulk grading 0.07) pressed to 100, 200 and 300 σ in steps of 100 σ is within
// 1 % of Hertz (measured 5.6e-3, the same as with steps of 20 σ: the deviation is largest at
// 100 σ), closer than with a bulk twice as coarse (grading 0.15: 1.6e-2), with no instability.
#[test]
fn adhesionless_finite_element_tip_is_within_one_percent_of_hertz() {
    let (fine, n_fine, _, c_fine) = hertz_row(128.0, 0.07, 100.0);
    let (coarse, n_coarse, _, c_coarse) = hertz_row(128.0, 0.15, 100.0);
    for c in [&c_fine, &c_coarse] {
        assert!(c.jumps.is_empty() && c.stats.all_stable);
    }
    assert!(n_fine > n_coarse);
    assert!(fine.deviation < 1e-2, "deviation from Hertz {}", fine.deviation);
    assert!(
        fine.deviation < coarse.deviation,
        "{} -> {}",
        coarse.deviation,
        fine.deviation
    );
    assert!(fine.offset.abs() < 1.0, "wall offset {} sigma", fine.offset);
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
    let coarse_grading = p.bulk.grading;
    let coarse = Fig4_4::run(&p, &Job::quiet()).expect("coarse");
    p.bulk.grading = 0.25;
    let fine = Fig4_4::run(&p, &Job::quiet()).expect("fine");
    let dev = |f: &adhesion::figure::Figure| f.result_value("hertz_deviation_norm").expect("result");
    eprintln!(
        "fig4.4 quick: deviation from Hertz {:.3e} (grading {coarse_grading}) -> {:.3e} (grading 0.25)",
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
// 0.4 in a tip of 4 R (4 343 unknowns), steps of 0.5 ζ0 from 20 ζ0, jumps located to 1e-2 ζ0.
// Measured: H/(2E*R³) = 1.647e-8 with 6 jumps -> 2.930e-8 (x1.78) with 10 jumps; the coarse
// surface elements add contact-edge hops to both cycles (measured when the mesh made the
// surface elements narrower than requested, 3 970 unknowns: 1.648e-8, 6 jumps -> 2.935e-8,
// 9 jumps; then with elements of 0.25 b: 1.546e-8, 4 jumps -> 2.744e-8, 6 jumps, 22 s).
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
// bulk grading 0.4, 5 945 unknowns) against the same scene with the surface model: P_adh within
// 5 % (measured +3.75 %), H within 5 % (+2.9 %), the pull-in and pull-off depths within 2 %
// (−0.92 %, −0.28 %), every state stable. The coarse bulk of the quick mesh also coarsens the
// thin surface layers (only the rows next to the surface stay fine), and the receding contact
// edge hops from element to element on unloading: 7 jumps instead of the surface model's 2
// (measured when the surface elements were 0.155 b for the requested 0.25 b, 5 572 unknowns:
// +3.4 %, +1.8 %, −1.2 %, −0.85 %, 8 jumps; 6 at grading 0.3, 3 at 0.2, 2 at 0.15).
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

/// Fig. 4.5's finite-element cycle (from 12 ζ0 to `h_min` ζ0 and back in steps of `step` ζ0,
/// jumps located to 1e-3 ζ0) on the tip `params`: P_adh [N] and the jumps (loading or not, the
/// depths before and after in ζ0), and whether every state was stable.
fn fe_cycle_path(params: &FeTipParams, h_min: f64, step: f64) -> (f64, Vec<(bool, f64, f64)>, bool) {
    let tip = FeTip::new(params).expect("tip");
    let z = tip.scales().length;
    let cycle = run_cycle(&tip, &fe_cycle_options(z, h_min, step), |_| Ok(())).expect("cycle");
    eprintln!("{} unknowns, {} triangles", tip.len(), tip.elements());
    let jumps = cycle
        .jumps
        .iter()
        .map(|j| (j.loading, j.before.depth / z, j.after.depth / z))
        .collect();
    (cycle.adhesive_force(), jumps, cycle.stats.all_stable)
}

/// The path of a cycle against the one recorded before the minimiser started its load steps
/// warm (chord steps on the previous state's factorisation) and stopped re-evaluating the
/// Hessian of a state it had just evaluated: P_adh to 1e-6 relative, the same jumps at the
/// same bisection points (depths to 1e-9 ζ0; a bisection point moved by one trial would move
/// them by at least 1e-3 ζ0).
fn assert_same_path(
    (p_adh, jumps, stable): (f64, Vec<(bool, f64, f64)>, bool),
    recorded_p_adh: f64,
    recorded_jumps: &[(bool, f64, f64)],
) {
    eprintln!("P_adh {p_adh:.12e} N (recorded {recorded_p_adh:.12e}), jumps {jumps:?}");
    assert!(stable);
    assert!(
        (p_adh / recorded_p_adh - 1.0).abs() < 1e-6,
        "P_adh {p_adh:e} against {recorded_p_adh:e}"
    );
    assert_eq!(jumps.len(), recorded_jumps.len(), "{jumps:?}");
    for (got, want) in jumps.iter().zip(recorded_jumps) {
        assert_eq!(got.0, want.0, "{got:?} against {want:?}");
        assert!(
            (got.1 - want.1).abs() < 1e-9 && (got.2 - want.2).abs() < 1e-9,
            "{got:?} against {want:?}"
        );
    }
}

// Fig. 4.5's finite-element cycle on a coarse bulk (surface elements of 0.25 b, grading 0.4 in
// a tip of 4 R, 7 183 unknowns, to h = −3 ζ0 in steps of 0.25 ζ0): the pull-in and the six hops
// of the receding contact edge on unloading at the depths, and P_adh to the digits, of the path
// recorded after the load steps started warm (`FeTip::warm_start`, which changed the cost only:
// 2 515 to 2 419 factorisations) and recorded again when the mesh started honouring its element
// width: its surface elements had been 0.155 b for the requested 0.25 b (6 810 unknowns, the
// pull-in and seven hops, P_adh −8.347624872492e-9 N); at 0.248 b P_adh is 0.29 % larger in
// magnitude and the edge hops six times. The width stays at 0.25 b, not the benchmark's 0.15 b,
// to keep this test's cost.
#[test]
fn fe_cycle_on_a_coarse_mesh_keeps_its_path_with_warm_load_steps() {
    let params = FeTipParams {
        element_width: 0.25,
        grading: 0.4,
        r0: 2e-5,
        h0: 2e-5,
        ..fig4_5_fe()
    };
    let recorded = [
        (true, 4.207031250000, 4.206054687500),
        (false, 7.860107421875, 7.860839843750),
        (false, 7.953794479370, 7.954338073730),
        (false, 8.025390625000, 8.026367187500),
        (false, 8.075286865234, 8.076160430908),
        (false, 8.102643802762, 8.103322863579),
        (false, 8.107906524092, 8.108479481656),
    ];
    assert_same_path(fe_cycle_path(&params, -3.0, 0.25), -8.371643206458e-9, &recorded);
}

// The same for the cycle `cargo bench --bench fe` times (Fig. 4.5's tip with surface elements
// of 0.15 b, 24 542 unknowns, to h = −15 ζ0 in steps of 0.2 ζ0): the dissertation's two jumps,
// pull-in and pull-off, where they were recorded, P_adh to 1e-6. Recorded again when the mesh
// started honouring its element width (its surface elements had been 0.155 b for a requested
// 0.25 b, 22 266 unknowns: P_adh −8.326694758257e-9 N, pull-in 4.228125 → 4.227344 ζ0,
// pull-off 8.168213 → 8.169206 ζ0; at an honoured 0.25 b the receding contact edge makes a third
// jump, from element to element).
#[test]
#[ignore = "slow: the benchmark's cycle, about a minute"]
fn fe_cycle_of_the_benchmark_keeps_its_path_with_warm_load_steps() {
    let recorded = [
        (true, 4.231250000000, 4.230468750000),
        (false, 8.180773925781, 8.181374740601),
    ];
    assert_same_path(
        fe_cycle_path(&fig4_5_fe(), -15.0, 0.2),
        -8.327541477630e-9,
        &recorded,
    );
}
