//! Chapter 2: adhesive contact with machine stiffness. Asymptotes of section 2.3, the energy
//! loss two ways, stationary and solution points, the displacement-controlled cycle, stability
//! against plain Newton, and the SI numbers of section 2.4.

use adhesion::models::machine_stiffness::{
    Accuracy, CONE_HYSTERESIS_STIFF, CONE_PULL_IN_STIFF, CONE_PULL_OFF_SOFT, CONE_PULL_OFF_STIFF, Experiment,
    MachineStiffness, SPHERE_HYSTERESIS_STIFF, SPHERE_PULL_IN_STIFF, SPHERE_PULL_OFF_SOFT,
    SPHERE_PULL_OFF_STIFF, TipGeometry, TipShape,
};

use crate::common::{assert_rel, rel};

const XTOL: f64 = 1e-14;

fn model(tip: TipShape, alpha: f64) -> MachineStiffness {
    MachineStiffness::new(tip, alpha).unwrap()
}

/// Sec. 2.3.1: as α → 0 the sphere's pull-in and pull-off forces tend to 0 and −1; as α → ∞ to
/// −8/9 and −5/9, and the hysteresis to 7.092 (the JKR value (1.6)).
#[test]
fn sphere_asymptotes_of_section_2_3_1() {
    let soft = model(TipShape::Sphere, 1e-4);
    let p_in = soft.pull_in(XTOL).unwrap().after.force;
    let p_off = soft.pull_off(XTOL).unwrap().before.force;
    assert!(p_in.abs() < 1e-3, "pull-in {p_in}");
    assert_rel("sphere pull-off, alpha -> 0", p_off, SPHERE_PULL_OFF_SOFT, 1e-3);
    let stiff = model(TipShape::Sphere, 1e4);
    let sp = stiff.sweep_point(Accuracy::default()).unwrap();
    assert_rel(
        "sphere pull-in, alpha -> inf",
        sp.pull_in_force,
        SPHERE_PULL_IN_STIFF,
        1e-3,
    );
    assert_rel(
        "sphere pull-off, alpha -> inf",
        sp.pull_off_force,
        SPHERE_PULL_OFF_STIFF,
        1e-3,
    );
    assert_rel(
        "sphere hysteresis, alpha -> inf",
        sp.hysteresis,
        SPHERE_HYSTERESIS_STIFF,
        1e-3,
    );
    // The hysteresis grows without bound as α → 0 (like 7.657/α in (2.39)).
    assert!(soft.hysteresis(Accuracy::default()).unwrap() > 1e4);
}

/// Sec. 2.3.2: the cone's pull-in and pull-off forces tend to 0 and −54 as α → 0, and to −32, −6
/// with the hysteresis to 22 as α → ∞. At α = 1e4 the stiff limits are reached to 1.6e-3,
/// 2.1e-3 and 2.4e-3 only: the approach is O(1/α) with a large coefficient (the cone's
/// pull-in radius is 8, and the spring term 4ā/(2ā+α) of (2.46) decays like 8ā/α). So the
/// limit is checked at α = 1e4 to 3e-3 and at α = 1e6 to 1e-4, and its 1/α rate is checked.
#[test]
fn cone_asymptotes_of_section_2_3_2() {
    let soft = model(TipShape::Cone, 1e-4);
    assert!(soft.pull_in(XTOL).unwrap().after.force.abs() < 1e-3);
    assert_rel(
        "cone pull-off, alpha -> 0",
        soft.pull_off(XTOL).unwrap().before.force,
        CONE_PULL_OFF_SOFT,
        1e-3,
    );
    let sp4 = model(TipShape::Cone, 1e4)
        .sweep_point(Accuracy::default())
        .unwrap();
    let sp6 = model(TipShape::Cone, 1e6)
        .sweep_point(Accuracy::default())
        .unwrap();
    for (sp, tol) in [(sp4, 3e-3), (sp6, 1e-4)] {
        assert_rel(
            "cone pull-in, alpha -> inf",
            sp.pull_in_force,
            CONE_PULL_IN_STIFF,
            tol,
        );
        assert_rel(
            "cone pull-off, alpha -> inf",
            sp.pull_off_force,
            CONE_PULL_OFF_STIFF,
            tol,
        );
        assert_rel(
            "cone hysteresis, alpha -> inf",
            sp.hysteresis,
            CONE_HYSTERESIS_STIFF,
            tol,
        );
    }
    // O(1/α): a hundredfold stiffer spring cuts the distance to the limit a hundredfold.
    let ratio = (sp4.pull_off_force - CONE_PULL_OFF_STIFF) / (sp6.pull_off_force - CONE_PULL_OFF_STIFF);
    assert!((ratio - 100.0).abs() < 2.0, "ratio {ratio}");
}

/// The hysteresis by the (corrected) integral (2.38)/(2.48) equals the area enclosed by the
/// force vs stage-displacement loop of a followed cycle, to 1e-6.
#[test]
fn hysteresis_integral_equals_loop_area() {
    for tip in [TipShape::Sphere, TipShape::Cone] {
        for alpha in [0.05, 1.0, 30.0, 2000.0] {
            let m = model(tip, alpha);
            let h = m.hysteresis(Accuracy::default()).unwrap();
            let d_o = m.pull_off(XTOL).unwrap().before.delta;
            let cycle = m.cycle(1.5 * d_o - 0.5, 2.0, 4000, XTOL).unwrap();
            let area = cycle.loop_area() * m.energy_factor();
            assert_rel(
                &format!("{tip:?} alpha {alpha}: loop area vs (2.38)"),
                area,
                h,
                1e-6,
            );
        }
    }
}

/// The stationary points of Sec. 2.3: two for Δ̄ₒ < Δ̄ < 0 (the smaller unstable, the larger
/// stable), one (stable) for Δ̄ ≥ 0, none below Δ̄ₒ; the out-of-contact state is a solution for
/// every Δ̄ < 0. Each stationary point satisfies (2.34)/(2.35) (or (2.44)/(2.45)).
#[test]
fn stationary_and_solution_points() {
    for tip in [TipShape::Sphere, TipShape::Cone] {
        let m = model(tip, 2.0);
        let d_o = m.pull_off(XTOL).unwrap().before.delta;
        let two = m.stationary_points(0.5 * d_o, XTOL).unwrap();
        assert_eq!(two.len(), 2, "{tip:?}: {two:?}");
        assert!(!two[0].stable && two[1].stable);
        for s in &two {
            assert!((s.delta - 0.5 * d_o).abs() < 1e-12 * d_o.abs());
            assert!((s.h - m.depth(s.a)).abs() < 1e-15 * (1.0 + s.h.abs()));
            assert!(m.g(s.a) * if s.stable { 1.0 } else { -1.0 } > 0.0);
        }
        let one = m.stationary_points(1.0, XTOL).unwrap();
        assert_eq!(one.len(), 1);
        assert!(one[0].stable);
        assert!(m.stationary_points(1.01 * d_o, XTOL).unwrap().is_empty());
        let sol = m.solution_points(1.01 * d_o, XTOL).unwrap();
        assert_eq!(sol.len(), 1);
        assert_eq!((sol[0].a, sol[0].force, sol[0].h), (0.0, 0.0, 1.01 * d_o));
        let sol = m.solution_points(0.5 * d_o, XTOL).unwrap();
        assert_eq!(sol.len(), 2, "out of contact and in contact");
    }
}

/// The followed cycle jumps exactly where the stability analysis says: pull-in at Δ̄ = 0 from
/// (0, 0) to āᵢ, pull-off at the fold āₒ to (0, Δ̄ₒ). The depth jumps are ∓(c/α)P̄ (the spring
/// takes up or releases the force the contact carries), the identity behind ERRATA's note on section 2.4.
#[test]
fn cycle_jumps_at_the_pull_in_and_pull_off() {
    for tip in [TipShape::Sphere, TipShape::Cone] {
        let m = model(tip, 3.0);
        let pi = m.pull_in(XTOL).unwrap();
        let po = m.pull_off(XTOL).unwrap();
        let cycle = m.cycle(1.2 * po.before.delta - 0.1, 1.0, 2000, XTOL).unwrap();
        assert_eq!(cycle.loading_jumps.len(), 1);
        assert_eq!(cycle.unloading_jumps.len(), 1);
        let j_in = cycle.loading_jumps[0];
        assert_eq!(j_in.before.delta, 0.0);
        assert_eq!(j_in.before.a, 0.0);
        assert!((j_in.after.a - pi.after.a).abs() < 1e-9, "{j_in:?} vs {pi:?}");
        let j_off = cycle.unloading_jumps[0];
        assert_eq!(j_off.before.a, po.before.a);
        assert_eq!(j_off.after.a, 0.0);
        assert_eq!(j_off.after.delta, po.before.delta);
        let c = m.compliance();
        assert!((pi.depth_jump() + c * pi.after.force).abs() < 1e-12);
        assert!((po.depth_jump() - c * po.before.force).abs() < 1e-12);
        // The loop is traversed with positive area and the unloading ends out of contact.
        assert!(cycle.loop_area() > 0.0);
        let last = cycle.unloading.last().unwrap();
        assert_eq!((last.a, last.force), (0.0, 0.0));
        // Every visited state is a solution point.
        assert!(
            cycle
                .loading
                .iter()
                .chain(&cycle.unloading)
                .all(|s| s.a == 0.0 || m.g(s.a) >= -1e-12)
        );
    }
}

/// Plain Newton on the stationary conditions (2.34)-(2.35) from a poor start converges to the
/// unstable stationary point between the folds, and finds nothing (diverges or stalls) past the
/// pull-off; following the stable branch gives the stable state at the same Δ̄, and the jump.
#[test]
fn plain_newton_lands_on_unstable_points_branch_following_does_not() {
    let m = model(TipShape::Sphere, 2.0);
    let po = m.pull_off(XTOL).unwrap();
    let c = m.compliance();
    // Residual of the stationary conditions in (ā, h̄) and its Jacobian.
    let newton = |delta: f64, mut a: f64, mut h: f64| -> Option<(f64, f64)> {
        for _ in 0..50 {
            let r1 = h - m.depth(a);
            let r2 = c * m.force(a, h) + h - delta;
            if r1.abs() + r2.abs() < 1e-13 {
                return Some((a, h));
            }
            let (p1, p2) = m.force_partials(a, h);
            let (j11, j12, j21, j22) = (-m.depth_slope(a), 1.0, c * p1, c * p2 + 1.0);
            let det = j11 * j22 - j12 * j21;
            a -= (r1 * j22 - r2 * j12) / det;
            h -= (j11 * r2 - j21 * r1) / det;
            if !(a > 0.0 && a.is_finite() && h.is_finite()) {
                return None;
            }
        }
        None
    };
    let delta = 0.7 * po.before.delta;
    let (a_n, _) = newton(delta, 0.3, 0.0).expect("Newton converges from this start");
    assert!(m.g(a_n) < 0.0, "Newton landed on ā = {a_n}, g = {}", m.g(a_n));
    // Past the pull-off there is no contact state: Newton cannot converge to one.
    let beyond = 1.05 * po.before.delta;
    assert!(newton(beyond, po.before.a, po.before.h).is_none_or(|(a, _)| m.g(a) <= 0.0));
    // Branch following: on unloading at that Δ̄ the state is the stable one, and past the fold
    // it is out of contact.
    let cycle = m.cycle(1.5 * po.before.delta, 1.0, 2000, XTOL).unwrap();
    let at = |delta: f64| {
        let k = cycle
            .unloading
            .windows(2)
            .position(|w| (w[0].delta - delta) * (w[1].delta - delta) <= 0.0)
            .unwrap();
        cycle.unloading[k]
    };
    let s = at(delta);
    assert!(s.a > po.before.a && m.g(s.a) > 0.0, "{s:?}");
    let s = at(beyond);
    assert_eq!((s.a, s.force), (0.0, 0.0));
}

/// The SI wrapper reproduces the non-dimensional scaling: α from k̂ = (9πwℰ²R²/8)^(1/3), and
/// the JKR pull-off −5πwR/6 of Sec. 2.4 is P̂ P̄ at the minimum of h̄ (ā_D), for both experiments.
#[test]
fn jkr_pull_off_of_section_2_4() {
    let pi = std::f64::consts::PI;
    for (e, w, r, k) in [(6.39e6, 63.2e-3, 58e-9, 0.66), (0.65e6, 25.7e-3, 2.5e-6, 0.642)] {
        let x = Experiment::new(TipGeometry::Sphere { radius: r }, e, w, k).unwrap();
        let k_hat = (9.0 * pi * w * e * e * r * r / 8.0).cbrt();
        assert_rel("alpha", x.alpha(), k / k_hat, 1e-12);
        // Displacement-controlled JKR pull-off: the minimum of the depth along the branch.
        let a_d = adhesion::models::machine_stiffness::sphere_depth_minimum_radius();
        let m = model(TipShape::Sphere, 1.0);
        assert!(m.depth_slope(a_d).abs() < 1e-14);
        let p_jkr = x.scales().force * m.branch_force(a_d);
        assert_rel("JKR pull-off -5 pi w R / 6", p_jkr, -5.0 * pi * w * r / 6.0, 1e-9);
        // The machine-stiffness pull-off lies between the JKR one and the force-control limit.
        let p_o = x.pull_off().unwrap().before.force;
        assert!(p_o < p_jkr && p_o > -1.5 * pi * w * r);
        // SI depth jumps equal force / k_s.
        let po = x.pull_off().unwrap();
        assert!(rel(-po.depth_jump(), -po.before.force / k) < 1e-9);
    }
}

/// The approximations (2.37), (2.39), (2.47), (2.49) against the exact values over
/// α ∈ [1e-2, 1e3] (201 log-spaced values). The text calls them "excellent" and "very close for
/// a wide range of α"; measured: sphere pull-off 1.55 % and hysteresis 1.30 % at most, but the
/// pull-in 33 % (at α = 0.01, where |P̄ᵢ| is only 0.006; within 5 % for α ≥ 0.25). Cone:
/// pull-in 46 % (within 5 % for α ≥ 8), pull-off 10 % (at α ≈ 100), hysteresis off by a factor
/// 23 at α = 0.01 (within 5 % only for α ≥ 8: as α → 0 the exact loss grows like 1458/α,
/// (P̄ₒ² − P̄ᵢ²)/(2α), not like α^(-1.4478)).
#[test]
fn approximations_over_alpha() {
    use adhesion::numerics::curve::logspace;
    let alphas = logspace(1e-2, 1e3, 201);
    let expected = [
        (TipShape::Sphere, [0.3258, 0.01549, 0.01303], [0.25, 0.0, 0.0]),
        (TipShape::Cone, [0.4582, 0.0998, 22.61], [8.0, f64::INFINITY, 8.0]),
    ];
    for (tip, worst_expected, good_from) in expected {
        let mut worst = [0.0f64; 3];
        for &al in &alphas {
            let m = model(tip, al);
            let s = m.sweep_point(Accuracy::default()).unwrap();
            let e = [
                rel(m.pull_in_force_fit(), s.pull_in_force),
                rel(m.pull_off_force_fit(), s.pull_off_force),
                rel(m.hysteresis_fit(), s.hysteresis),
            ];
            for k in 0..3 {
                worst[k] = worst[k].max(e[k]);
                if al >= good_from[k] {
                    assert!(e[k] < 0.05, "{tip:?} alpha {al}: fit {k} off by {}", e[k]);
                }
            }
        }
        for k in 0..3 {
            assert_rel(
                &format!("{tip:?} worst error of fit {k}"),
                worst[k],
                worst_expected[k],
                2e-3,
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Fitting measured curves (appendix A.4).

mod fit {
    use std::path::Path;

    use adhesion::error::Error;
    use adhesion::fit::{FitModel, fit_curve, parse_curve, simulate_cycle};
    use adhesion::models::machine_stiffness::{Experiment, TipGeometry};
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    use crate::common::rel;

    /// A synthetic cycle of a 1 µm bead on a soft substrate, as CSV in nm and nN, with Gaussian
    /// force noise of standard deviation `noise` × the largest |P|.
    fn synthetic_csv(noise: f64, seed: u64) -> (String, Experiment, usize) {
        let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, 2.0e6, 0.04, 0.5).unwrap();
        let d_o = x.pull_off().unwrap().before.delta;
        let curve = simulate_cycle(&x, 1.5 * d_o, 3.0 * x.scales().h, 700).unwrap();
        let p_max = curve.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, noise * p_max).unwrap();
        let mut text = String::from("# synthetic cycle: approach, contact, retract\ndepth_nm,force_nN\n");
        for (h, p) in curve.depth.iter().zip(&curve.force) {
            text.push_str(&format!("{},{}\n", h * 1e9, (p + normal.sample(&mut rng)) * 1e9));
        }
        let n_contact = curve.force.iter().filter(|p| **p != 0.0).count();
        (text, x, n_contact)
    }

    /// A full cycle generated by the model at known (ℰ, w, k_s) with 1 % force noise is fitted
    /// back to within 3 of its reported standard errors; the in-contact part is found.
    #[test]
    fn round_trip_with_one_percent_noise() {
        let (text, x, in_contact) = synthetic_csv(0.01, 7);
        let curve = parse_curve(&text, Path::new("synthetic.csv")).unwrap();
        let r = fit_curve(&curve, Path::new("synthetic.csv"), 1e-6, Some(0.5), None).unwrap();
        assert_eq!(r.model, FitModel::MachineStiffness);
        let (w, e) = (r.work_of_adhesion().unwrap(), r.plane_strain_modulus_pa);
        assert!((w.value - x.work_of_adhesion).abs() < 3.0 * w.std_error, "{r:#?}");
        assert!((e.value - x.modulus).abs() < 3.0 * e.std_error, "{r:#?}");
        assert!(w.std_error < 0.02 * w.value && e.std_error < 0.02 * e.value);
        // The retract is fitted (the adhesive models' default) with the approach's baseline.
        assert_eq!(r.segment, adhesion::fit::SegmentChoice::Retract);
        // With both segments every in-contact sample is in contact, none of the zero-force ones.
        let settings = adhesion::fit::FitSettings {
            radius: 1e-6,
            spring_constant: Some(0.5),
            model: None,
            segment: Some(adhesion::fit::SegmentChoice::Both),
            poisson: None,
        };
        let both = adhesion::fit::fit_with(&curve, Path::new("synthetic.csv"), &settings).unwrap();
        assert!(
            both.points_in_contact <= in_contact + 2 && both.points_in_contact + 2 >= in_contact,
            "{} vs {in_contact}",
            both.points_in_contact
        );
        assert_eq!(both.points_used, curve.depth.len());
        assert!(rel(both.work_of_adhesion().unwrap().value, w.value) < 0.01);
        // The predicted pull-off is the one the data were made with.
        let ms = r.machine_stiffness.unwrap();
        assert!(rel(ms.pull_off_force_n, x.pull_off().unwrap().before.force) < 0.03);
        assert!(ms.pull_off_force_n < r.jkr.unwrap().pull_off_force_n);
    }

    /// The depth origin of a measured curve is never the contact point: the fixture with every
    /// depth shifted by +150 nm and by −80 nm is fitted to within 1 % of the unshifted fit's w
    /// and ℰ (the fit is translation-invariant: the same numbers to round-off), and the fitted
    /// contact point moves with the shift to within 1 nm. The unshifted contact point is the
    /// true origin within 1 nm; the measured pull-off is the retract's force minimum.
    #[test]
    fn shifted_depth_origin_is_fitted_as_a_contact_point() {
        let path = crate::common::root().join("tests/fixtures/curves/synthetic_cycle.csv");
        let curve = adhesion::fit::read_curve(&path).unwrap();
        let base = fit_curve(&curve, &path, 1e-6, Some(0.5), None).unwrap();
        assert!(
            base.contact_point_m.value.abs() < 1e-9,
            "{:?}",
            base.contact_point_m
        );
        assert!(
            rel(base.work_of_adhesion().unwrap().value, 0.04) < 0.01,
            "{base:#?}"
        );
        assert!(rel(base.plane_strain_modulus_pa.value, 2.0e6) < 0.01, "{base:#?}");
        let turn = base.turning_row;
        let retract_min = curve.force[turn..].iter().copied().fold(f64::INFINITY, f64::min);
        assert!((base.measured_pull_off_force_n - (retract_min - base.baseline_n.value)).abs() < 1e-15);
        for shift in [150e-9, -80e-9] {
            let mut c = curve.clone();
            c.depth.iter_mut().for_each(|d| *d += shift);
            let r = fit_curve(&c, &path, 1e-6, Some(0.5), None).unwrap();
            let (w0, w1) = (
                base.work_of_adhesion().unwrap().value,
                r.work_of_adhesion().unwrap().value,
            );
            assert!(rel(w1, w0) < 0.01, "shift {shift:e}: w {w1} vs {w0}");
            assert!(
                rel(
                    r.plane_strain_modulus_pa.value,
                    base.plane_strain_modulus_pa.value
                ) < 0.01,
                "shift {shift:e}"
            );
            let moved = r.contact_point_m.value - base.contact_point_m.value;
            assert!(
                (moved - shift).abs() < 1e-9,
                "shift {shift:e}: contact point moved {moved:e}"
            );
            assert!(r.warnings.is_empty(), "{:?}", r.warnings);
        }
    }

    /// Noise-free data are fitted exactly.
    #[test]
    fn exact_data_are_fitted_exactly() {
        let x = Experiment::new(TipGeometry::Sphere { radius: 58e-9 }, 6.39e6, 63.2e-3, 0.66).unwrap();
        let d_o = x.pull_off().unwrap().before.delta;
        let curve = simulate_cycle(&x, 1.5 * d_o, 2.0 * x.scales().h, 300).unwrap();
        let r = fit_curve(
            &curve,
            Path::new("exact.csv"),
            58e-9,
            Some(0.66),
            Some(FitModel::Jkr),
        )
        .unwrap();
        assert!(rel(r.work_of_adhesion().unwrap().value, 63.2e-3) < 1e-7, "{r:#?}");
        assert!(rel(r.plane_strain_modulus_pa.value, 6.39e6) < 1e-7, "{r:#?}");
    }

    /// Header variants: units in brackets, parentheses or suffixes; semicolons; extra columns.
    #[test]
    fn header_variants_and_units() {
        let p = Path::new("f.csv");
        let a = parse_curve("depth [um],force [uN]\n0.1,2\n", p).unwrap();
        assert!(rel(a.depth[0], 0.1e-6) < 1e-15 && rel(a.force[0], 2e-6) < 1e-15);
        let b = parse_curve("time_s;h (nm);P (nN)\n0;5;-3\n", p).unwrap();
        assert!(rel(b.depth[0], 5e-9) < 1e-15 && rel(b.force[0], -3e-9) < 1e-15);
        let c = parse_curve("\u{feff}# comment\ndepth_m,force_N\n\n1e-9,1e-9\r\n", p).unwrap();
        assert!(rel(c.depth[0], 1e-9) < 1e-15 && c.lines[0] == 4);
    }

    #[track_caller]
    fn rejects(text: &str, line: usize, needle: &str) {
        match parse_curve(text, Path::new("bad.csv")) {
            Err(e @ Error::DataFile { .. }) => {
                let msg = e.to_string();
                assert!(msg.starts_with(&format!("bad.csv:{line}: ")), "{msg}");
                assert!(msg.contains(needle), "{msg}");
                assert_eq!(msg.lines().count(), 1);
            }
            other => panic!("{other:?}"),
        }
    }

    /// Each kind of bad file gives a one-line error naming the line.
    #[test]
    fn bad_files_are_rejected_naming_the_line() {
        rejects("", 0, "empty file");
        rejects("# only a comment\n", 0, "empty file");
        rejects("time_s,force_nN\n1,2\n", 1, "no depth column");
        rejects("depth_nm,time_s\n1,2\n", 1, "no force column");
        rejects("depth_furlong,force_nN\n1,2\n", 1, "no depth column");
        rejects("depth [furlong],force_nN\n1,2\n", 1, "unknown unit `furlong`");
        rejects("depth,force_nN\n1,2\n", 1, "has no unit");
        rejects("depth_nm,force [kg]\n1,2\n", 1, "unknown unit `kg`");
        rejects(
            "depth_nm,force_nN\n1,2\n3,abc\n",
            3,
            "force `abc` is not a finite number",
        );
        rejects("depth_nm,force_nN\n1,2\nNaN,1\n", 3, "depth `NaN`");
        rejects("depth_nm,force_nN\n1,2\n3\n", 3, "1 column(s)");
        rejects("depth_nm,force_nN\n# no rows\n", 1, "no data rows");
        // Too few in-contact points: a flat curve.
        let mut flat = String::from("depth_nm,force_nN\n");
        for k in 0..100 {
            flat.push_str(&format!("{k},0\n"));
        }
        flat.push_str("100,5\n101,6\n");
        let c = parse_curve(&flat, Path::new("flat.csv")).unwrap();
        let e = fit_curve(&c, Path::new("flat.csv"), 1e-6, None, None).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("flat.csv:102: only 2 in-contact point(s)"),
            "{e}"
        );
        // The machine-stiffness model needs a spring constant.
        let (text, _, _) = synthetic_csv(0.0, 1);
        let c = parse_curve(&text, Path::new("s.csv")).unwrap();
        let e = fit_curve(
            &c,
            Path::new("s.csv"),
            1e-6,
            None,
            Some(FitModel::MachineStiffness),
        )
        .unwrap_err();
        assert!(e.to_string().contains("needs --spring-constant"), "{e}");
        assert!(fit_curve(&c, Path::new("s.csv"), -1.0, None, None).is_err());
    }

    /// The command line writes fit.json, .png, .svg, .csv for a good file, and nothing (with a
    /// one-line error naming the line) for a bad one.
    #[test]
    fn command_line_fit() {
        let dir = tempfile::tempdir().unwrap();
        let (text, _, _) = synthetic_csv(0.01, 3);
        let good = dir.path().join("cycle.csv");
        std::fs::write(&good, text).unwrap();
        let out = dir.path().join("out");
        let run = |file: &Path, out: &Path| {
            std::process::Command::new(env!("CARGO_BIN_EXE_adhesion"))
                .args(["--headless", "--fit"])
                .arg(file)
                .args(["--tip-radius", "1e-6", "--spring-constant", "0.5", "--out"])
                .arg(out)
                .output()
                .unwrap()
        };
        let o = run(&good, &out);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        for f in ["fit.json", "fit.png", "fit.svg", "fit.csv"] {
            assert!(out.join(f).exists(), "{f}");
        }
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
        assert!(json["work_of_adhesion_j_per_m2"]["std_error"].as_f64().unwrap() > 0.0);
        assert!(json["machine_stiffness"]["pull_off_force_n"].as_f64().unwrap() < 0.0);
        let bad = dir.path().join("bad.csv");
        std::fs::write(&bad, "depth_nm,force_nN\n1,2\n3,x\n").unwrap();
        let out2 = dir.path().join("out2");
        let o = run(&bad, &out2);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success());
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert!(stderr.contains("bad.csv:3:"), "{stderr}");
        assert!(!out2.exists() || std::fs::read_dir(&out2).unwrap().next().is_none());
    }

    /// The synthetic cycle of [`synthetic_csv`] cropped as AFM users crop curves: `before` rows
    /// of zero-force approach before the pull-in and `after` rows of retract after the pull-off
    /// (0: the file starts or ends in contact), 1 % force noise. Returns the curve and its
    /// in-contact rows.
    fn cropped_cycle(
        before: usize,
        after: usize,
        seed: u64,
    ) -> (adhesion::fit::Curve, std::ops::Range<usize>) {
        let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, 2.0e6, 0.04, 0.5).unwrap();
        let d_o = x.pull_off().unwrap().before.delta;
        let mut c = simulate_cycle(&x, 1.5 * d_o, 3.0 * x.scales().h, 700).unwrap();
        // Out of contact the tip follows the stage: the retract continues at zero force with
        // the last depth step (the model's cycle ends soon after the pull-off).
        let step = c.depth[c.depth.len() - 1] - c.depth[c.depth.len() - 2];
        for _ in 0..60 {
            let h = c.depth[c.depth.len() - 1] + step;
            c.depth.push(h);
            c.force.push(0.0);
        }
        let first = c.force.iter().position(|p| *p != 0.0).unwrap();
        let last = c.force.iter().rposition(|p| *p != 0.0).unwrap();
        let keep = first - before..last + 1 + after;
        let p_max = c.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, 0.01 * p_max).unwrap();
        let curve = adhesion::fit::Curve {
            depth: c.depth[keep.clone()].to_vec(),
            force: c.force[keep.clone()]
                .iter()
                .map(|p| p + normal.sample(&mut rng))
                .collect(),
            lines: (2..keep.len() + 2).collect(),
        };
        if std::env::var_os("ADHESION_WRITE_CROPPED_FIXTURE").is_some()
            && (before, after, seed) == (40, 40, 2019)
        {
            let mut t = String::from(
                "# Synthetic AFM cycle of the machine-stiffness model, cropped as users crop curves:\n\
                 # 40 rows of approach before the pull-in, 40 rows of retract after the pull-off, 1 % force noise.\n\
                 # R = 1 um, plane-strain modulus 2 MPa, w = 40 mJ/m^2, k_s = 0.5 N/m.\n\
                 # Fit: adhesion --headless --fit tests/fixtures/curves/cropped_cycle.csv --tip-radius 1e-6 --spring-constant 0.5\n\
                 depth_nm,force_nN\n",
            );
            for (h, p) in curve.depth.iter().zip(&curve.force) {
                t.push_str(&format!("{:.4},{:.5}\n", h * 1e9, p * 1e9));
            }
            std::fs::write(
                crate::common::root().join("tests/fixtures/curves/cropped_cycle.csv"),
                t,
            )
            .unwrap();
        }
        (curve, before..before + last + 1 - first)
    }

    /// Short baselines (10, 20, 40 rows at either end, or at one end only), where a noise
    /// level taken from a tenth of the rows would include the jumps and the contact: the
    /// contact is found from the baseline that is there, every in-contact row is used, and the
    /// fit recovers w and E within the round-trip test's tolerances (3 standard errors, each
    /// under 2 %). fit.json says how the rows were found.
    #[test]
    fn short_baselines_at_either_or_one_end() {
        use adhesion::fit::detect_contact;
        let cases = [
            (10, 10),
            (20, 20),
            (40, 40),
            (10, 40),
            (40, 10),
            (40, 0),
            (0, 40),
            (10, 0),
            (0, 10),
        ];
        for (k, (before, after)) in cases.into_iter().enumerate() {
            let (curve, truth) = cropped_cycle(before, after, 11 + k as u64);
            let path = Path::new("cropped.csv");
            let (range, how) =
                detect_contact(&curve, path, 10).unwrap_or_else(|e| panic!("{before}/{after}: {e}"));
            assert!(
                range.start.abs_diff(truth.start) <= 2 && range.end.abs_diff(truth.end) <= 2,
                "{before}/{after}: rows {range:?} taken, {truth:?} in contact ({how:?})"
            );
            assert_eq!(
                how.baseline_rows_start > 0,
                before > 0,
                "{before}/{after}: {how:?}"
            );
            assert_eq!(how.baseline_rows_end > 0, after > 0, "{before}/{after}: {how:?}");
            let r = fit_curve(&curve, path, 1e-6, Some(0.5), None).unwrap();
            let (w, e) = (r.work_of_adhesion().unwrap(), r.plane_strain_modulus_pa);
            assert!(
                (w.value - 0.04).abs() < 3.0 * w.std_error,
                "{before}/{after}: {r:#?}"
            );
            assert!(
                (e.value - 2.0e6).abs() < 3.0 * e.std_error,
                "{before}/{after}: {r:#?}"
            );
            assert!(w.std_error < 0.02 * w.value && e.std_error < 0.02 * e.value);
            assert!(r.warnings.is_empty(), "{:?}", r.warnings);
        }
    }

    /// The fixture of the issue's shape (40 rows of approach, 40 of retract) fits from the
    /// command line, and fit.json records the baselines found.
    #[test]
    fn cropped_fixture_fits_from_the_command_line() {
        // Written by `ADHESION_WRITE_CROPPED_FIXTURE=1 cargo test cropped_fixture` from cropped_cycle(40, 40, 2019).
        let _ = cropped_cycle(40, 40, 2019);
        let path = crate::common::root().join("tests/fixtures/curves/cropped_cycle.csv");
        let curve = adhesion::fit::read_curve(&path).unwrap();
        let r = fit_curve(&curve, &path, 1e-6, Some(0.5), None).unwrap();
        assert!(
            rel(r.work_of_adhesion().unwrap().value, 0.04)
                < 3.0 * r.work_of_adhesion().unwrap().std_error / 0.04
        );
        assert!(r.contact_detection.baseline_rows_start >= 38 && r.contact_detection.baseline_rows_end >= 38);
        let json = serde_json::to_value(&r).unwrap();
        assert!(
            json["contact_detection"]["method"]
                .as_str()
                .unwrap()
                .contains("both ends")
        );
    }

    /// Non-physical data are refused with one line naming the file and what to check, or fitted
    /// with a warning when the values are not determined: sign-flipped forces, constant forces,
    /// all-zero depths; CR-only line ends are read as lines.
    #[test]
    fn non_physical_data_are_refused() {
        let (curve, _) = cropped_cycle(40, 40, 5);
        let path = Path::new("odd.csv");
        let check = |c: &adhesion::fit::Curve, needle: &str| match fit_curve(c, path, 1e-6, None, None) {
            Err(e @ Error::DataFile { .. }) => {
                let m = e.to_string();
                assert!(
                    m.starts_with("odd.csv:") && m.contains(needle) && !m.contains('\n'),
                    "{m}"
                );
            }
            other => panic!("{needle}: {other:?}"),
        };
        let mut flipped = curve.clone();
        flipped.force.iter_mut().for_each(|p| *p = -*p);
        check(&flipped, "sign of one column flipped");
        let mut constant = curve.clone();
        constant.force.iter_mut().for_each(|p| *p = 1e-9);
        check(&constant, "force does not vary");
        let mut flat = curve.clone();
        flat.depth.iter_mut().for_each(|h| *h = 0.0);
        check(&flat, "depth does not vary");
        let text = "depth_nm,force_nN\r1,2\r3,4\r";
        let c = parse_curve(text, path).unwrap();
        assert_eq!((c.depth.len(), c.lines.clone()), (2, vec![2, 3]));
    }
}

/// The exact spherical profile (2.28): it tends to the paraboloid (2.30) as R/â → ∞, its
/// stability function is again a positive multiple of dΔ̄/dā, and its hysteresis by (2.38)
/// equals the loop area. At Sun et al.'s parameters (â = 0.85 R) the paraboloid is a poor
/// approximation: the exact profile changes the pull-off force by 18 %.
#[test]
fn exact_sphere_profile() {
    let far = MachineStiffness::new(TipShape::SphereExact { radius_ratio: 1e4 }, 2.0).unwrap();
    let par = model(TipShape::Sphere, 2.0);
    let (a, b) = (
        far.sweep_point(Accuracy::default()).unwrap(),
        par.sweep_point(Accuracy::default()).unwrap(),
    );
    assert_rel("pull-in, R/a_hat = 1e4", a.pull_in_force, b.pull_in_force, 1e-6);
    assert_rel(
        "pull-off, R/a_hat = 1e4",
        a.pull_off_force,
        b.pull_off_force,
        1e-6,
    );
    assert_rel("hysteresis, R/a_hat = 1e4", a.hysteresis, b.hysteresis, 1e-6);
    for rho in [1.5, 3.0] {
        let m = MachineStiffness::new(TipShape::SphereExact { radius_ratio: rho }, 2.0).unwrap();
        let h = m.hysteresis(Accuracy::default()).unwrap();
        let d_o = m.pull_off(XTOL).unwrap().before.delta;
        let area = m.cycle(1.5 * d_o, 1.0, 4000, XTOL).unwrap().loop_area() * m.energy_factor();
        assert_rel(
            &format!("exact sphere rho {rho}: loop area vs (2.38)"),
            area,
            h,
            1e-6,
        );
        // Stationary points satisfy Δ̄(ā) = Δ̄.
        for s in m.stationary_points(0.5 * d_o, XTOL).unwrap() {
            assert!((s.delta - 0.5 * d_o).abs() < 1e-12);
        }
    }
    assert!(MachineStiffness::new(TipShape::SphereExact { radius_ratio: 0.9 }, 1.0).is_err());
    let sun = Experiment::new(TipGeometry::Sphere { radius: 58e-9 }, 6.39e6, 63.2e-3, 0.66).unwrap();
    let p_par = sun.pull_off().unwrap().before.force;
    let m = sun.model_exact_sphere().unwrap();
    let p_exact = m.pull_off(XTOL).unwrap().before.force * sun.scales().force;
    // Measured: −11.93 nN exact vs −14.54 nN paraboloid (R/â = 1.18), 18 % apart.
    assert!(
        (0.17..0.19).contains(&rel(p_exact, p_par)),
        "{p_exact:e} vs {p_par:e}"
    );
}

/// fig2.5-accuracy: the exact computation converges (Brent's tolerance bounds the pull-off
/// error; Gauss-Legendre reaches machine precision for the hysteresis with 8 points, the
/// integrand being smooth on [āₒ, āᵢ]), while the fits (2.37b), (2.39) stay at the per-cent level.
#[test]
fn accuracy_scene_shows_convergence() {
    let s = adhesion::scenes::find("fig2.5-accuracy").unwrap();
    let fig = s
        .run(&s.quick(&s.defaults()).unwrap(), &adhesion::job::Job::quiet())
        .unwrap();
    let r = |n: &str| fig.result_value(n).unwrap();
    assert!(r("tolerance_1e-8_pull_off_max_rel_error_norm") < 1e-7);
    assert!(r("order_8_hysteresis_max_rel_error_norm") < 1e-12);
    for n in [
        "fits_pull_off_max_rel_error_norm",
        "fits_hysteresis_max_rel_error_norm",
    ] {
        assert!((1e-3..0.05).contains(&r(n)), "{n} = {}", r(n));
    }
    // Panel (a): the pull-off error falls as the tolerance tightens.
    let tol_series = &fig.panels[0].series[0];
    let first = tol_series.points.first().unwrap().1;
    let last = tol_series.points.last().unwrap().1;
    assert!(first > 1e-4 && last < 1e-13, "{:?}", tol_series.points);
}

/// A file with only the in-contact part (no zero-force segments) is fitted with all its points.
#[test]
fn contact_only_file() {
    use adhesion::fit::simulate_cycle;
    let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, 2.0e6, 0.04, 0.5).unwrap();
    let d_o = x.pull_off().unwrap().before.delta;
    let mut c = simulate_cycle(&x, 1.5 * d_o, 3.0 * x.scales().h, 300).unwrap();
    let keep: Vec<usize> = (0..c.force.len()).filter(|&k| c.force[k] != 0.0).collect();
    c.depth = keep.iter().map(|&k| c.depth[k]).collect();
    c.force = keep.iter().map(|&k| c.force[k]).collect();
    c.lines = (2..keep.len() + 2).collect();
    let settings = adhesion::fit::FitSettings {
        radius: 1e-6,
        spring_constant: None,
        model: None,
        segment: Some(adhesion::fit::SegmentChoice::Both),
        poisson: None,
    };
    let r = adhesion::fit::fit_with(&c, std::path::Path::new("contact.csv"), &settings).unwrap();
    assert!(
        r.points_in_contact + 3 >= keep.len(),
        "{} of {}",
        r.points_used,
        keep.len()
    );
    assert!(rel(r.work_of_adhesion().unwrap().value, 0.04) < 1e-7);
}

/// The fig2.8-fit demonstration (defaults: ℰ = 2 MPa, w = 0.04 J/m², 1 % noise) fits back its
/// own parameters within 3 standard errors, using only the in-contact rows.
#[test]
fn demonstration_fit_recovers_its_parameters() {
    use adhesion::scenes::Scene;
    use adhesion::scenes::fig2::{Fig2_8Fit, Fig2_8FitParams};
    let p = Fig2_8FitParams::default();
    let fig = Fig2_8Fit::run(&p, &adhesion::job::Job::quiet()).unwrap();
    let r = |n: &str| fig.result_value(n).unwrap();
    let (w, sw) = (
        r("work_of_adhesion_J_per_m2"),
        r("work_of_adhesion_std_error_J_per_m2"),
    );
    let (e, se) = (
        r("plane_strain_modulus_Pa"),
        r("plane_strain_modulus_std_error_Pa"),
    );
    assert!((w - 0.04).abs() < 3.0 * sw, "w = {w} ± {sw}");
    assert!((e - 2.0e6).abs() < 3.0 * se, "E = {e} ± {se}");
    assert!(sw < 0.02 * w && se < 0.02 * e);
}

/// Correlated baseline noise (a sawtooth, for which successive differences underestimate the
/// noise level about sixfold) is still recognised as out of contact.
#[test]
fn correlated_baseline_noise_is_not_contact() {
    use adhesion::fit::{contact_range, simulate_cycle};
    let x = Experiment::new(TipGeometry::Sphere { radius: 1e-6 }, 2.0e6, 0.04, 0.5).unwrap();
    let d_o = x.pull_off().unwrap().before.delta;
    let mut c = simulate_cycle(&x, 1.5 * d_o, 3.0 * x.scales().h, 400).unwrap();
    let in_contact = c.force.iter().filter(|p| **p != 0.0).count();
    let p_max = c.force.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    for (k, p) in c.force.iter_mut().enumerate() {
        *p += 0.01 * p_max * 3f64.sqrt() * (((k * 7919) % 1000) as f64 / 500.0 - 1.0);
    }
    let range = contact_range(&c, std::path::Path::new("sawtooth.csv"), 10).unwrap();
    assert!(
        range.len() <= in_contact + 2 && range.len() + 10 >= in_contact,
        "{} rows taken, {in_contact} in contact",
        range.len()
    );
}
