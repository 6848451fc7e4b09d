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
