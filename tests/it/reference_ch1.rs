//! Chapter 1 reference values: closed forms (1.1)-(1.7) to 1e-12, the hysteresis (1.6) by
//! quadrature of the displacement-controlled loop to 1e-6, and the limits of the theories.

use adhesion::models::classical::{
    JKR_HYSTERESIS_CONSTANT, SphereContact, jkr_bar, jkr_hysteresis_constant_by_quadrature,
};
use adhesion::models::fuller_tabor::{FullerTabor, Phase, asperity_force};

use crate::common::assert_rel;

/// A glass bead on PDMS: R = 10 um, E* = 1 MPa, w = 50 mJ/m^2.
fn contact() -> SphereContact {
    SphereContact::new(10e-6, 1e6, 0.05).unwrap()
}

/// Eq. (1.3)-(1.5): the SI special points equal the printed closed forms to 1e-12.
#[test]
fn jkr_special_points_match_eqs_1_3_to_1_5() {
    let c = contact();
    let (r, e, w) = (c.radius, c.modulus, c.work_of_adhesion);
    let pi = std::f64::consts::PI;
    let b = c.jkr_pull_in();
    assert_rel("a_B", b.a, (2.0 * pi * r * r * w / e).cbrt(), 1e-12);
    assert!(b.h.abs() < 1e-12 * c.h0());
    assert_rel("P_B", b.p, -4.0 / 3.0 * pi * w * r, 1e-12);
    let d = c.jkr_pull_off();
    assert_rel("a_D", d.a, (pi * r * r * w / (8.0 * e)).cbrt(), 1e-12);
    assert_rel(
        "h_D",
        d.h,
        -(27.0 * pi * pi * r * w * w / (64.0 * e * e)).cbrt(),
        1e-12,
    );
    assert_rel("P_D", d.p, -5.0 / 6.0 * pi * w * r, 1e-12);
    let cc = c.jkr_adhesive_force();
    assert_rel("a_C", cc.a, (9.0 * pi * r * r * w / (8.0 * e)).cbrt(), 1e-12);
    assert_rel(
        "h_C",
        cc.h,
        -(3.0 * pi * pi * r * w * w / (64.0 * e * e)).cbrt(),
        1e-12,
    );
    assert_rel("P_C", cc.p, -1.5 * pi * w * r, 1e-12);
    // The points lie on the curve (1.2) itself.
    for s in [b, d, cc] {
        let on = c.jkr(s.a);
        assert!((on.h - s.h).abs() <= 1e-12 * c.h0(), "h on curve");
        assert_rel("P on curve", on.p, s.p, 1e-12);
    }
}

/// Eq. (1.6): the loop area by quadrature equals (π^(5/3) + 3(2π)^(5/3))/10 = 7.092 to 1e-6
/// (it reaches about 1e-14), and the SI hysteresis scales as (R⁴w⁵/E*²)^(1/3).
#[test]
fn jkr_hysteresis_by_quadrature_matches_eq_1_6() {
    let pi = std::f64::consts::PI;
    let exact = (pi.powf(5.0 / 3.0) + 3.0 * (2.0 * pi).powf(5.0 / 3.0)) / 10.0;
    let by_loop = jkr_hysteresis_constant_by_quadrature(1e-13).unwrap();
    assert_rel("hysteresis constant", by_loop, exact, 1e-6);
    assert!((exact - 7.092).abs() < 5e-4, "printed 7.092");
    let c = contact();
    assert_rel(
        "H",
        c.jkr_hysteresis(),
        JKR_HYSTERESIS_CONSTANT * (c.radius.powi(4) * 0.05f64.powi(5) / 1e12).cbrt(),
        1e-12,
    );
}

/// The loop area also follows from a plain trapezoid sum over the traced loop, converging at
/// second order (a check of the quadrature with an independent method).
#[test]
fn traced_loop_area_converges_to_the_hysteresis() {
    let mut errors = Vec::new();
    for n in [200usize, 400, 800] {
        let pts: Vec<(f64, f64)> = (0..=n)
            .map(|i| {
                let a =
                    jkr_bar::PULL_OFF.a + (jkr_bar::PULL_IN.a - jkr_bar::PULL_OFF.a) * i as f64 / n as f64;
                (jkr_bar::depth(a), jkr_bar::force(a))
            })
            .collect();
        let area = -adhesion::numerics::quadrature::trapezoid(&pts) * std::f64::consts::PI.powf(5.0 / 3.0);
        errors.push((area - JKR_HYSTERESIS_CONSTANT).abs());
    }
    let order = (errors[1] / errors[2]).log2();
    assert!(
        (order - 2.0).abs() < 0.1,
        "observed order {order}, errors {errors:?}"
    );
    assert!(errors[2] < 1e-5);
}

/// JKR → Hertz as w → 0 (Eq. 1.2 → 1.1), and DMT is Hertz shifted by −2πwR (1.7).
#[test]
fn jkr_and_dmt_reduce_to_hertz_without_adhesion() {
    let c = SphereContact::new(10e-6, 1e6, 0.0).unwrap();
    for a in [1e-7, 1e-6, 3e-6] {
        let (h, j, d) = (c.hertz(a), c.jkr(a), c.dmt(a));
        assert_eq!((h.h, h.p), (j.h, j.p));
        assert_eq!((h.h, h.p), (d.h, d.p));
    }
    let c = contact();
    let a = 2e-6;
    assert_rel(
        "DMT shift",
        c.hertz(a).p - c.dmt(a).p,
        2.0 * std::f64::consts::PI * 0.05 * 10e-6,
        1e-12,
    );
}

/// Eq. (1.8): μ_T = (Rw²/(E*²ζ₀³))^(1/3), checked against a hand calculation:
/// R = 10 um, w = 0.05, E* = 1 MPa, ζ₀ = 0.3 nm gives (2.5e-8 / 2.7e-17)^(1/3) = 975.5...
#[test]
fn tabor_parameter_matches_eq_1_8() {
    let mu = contact().tabor_parameter(0.3e-9).unwrap();
    assert_rel("mu_T", mu, (10e-6 * 0.0025 / (1e12 * 2.7e-29f64)).cbrt(), 1e-12);
    assert!(contact().tabor_parameter(-1.0).is_err());
}

/// Fuller-Tabor (1.14)-(1.15) with vanishing roughness is a single JKR asperity: loading
/// follows F(−d/h_o) from the pull-in (F = −8/9 at d = 0), unloading follows the same branch
/// down to the pull-off at d = h_o (F = −5/9). Roughness θ = 1e-3 smears the curve by O(θ).
#[test]
fn fuller_tabor_with_vanishing_roughness_is_one_jkr_asperity() {
    let ft = FullerTabor::new(1e-3).unwrap();
    for d in [-0.8, -0.5, -0.2, -0.05] {
        let p = ft.force(d, Phase::Loading).unwrap();
        let single = asperity_force(-d).unwrap();
        assert!((p - single).abs() < 2e-3, "loading d = {d}: {p} vs {single}");
    }
    for d in [-0.3, 0.0, 0.4, 0.9] {
        let p = ft.force(d, Phase::Unloading { d_min: -0.5 }).unwrap();
        let single = asperity_force(-d).unwrap();
        assert!((p - single).abs() < 2e-3, "unloading d = {d}: {p} vs {single}");
    }
    // Pull-in and pull-off forces of one asperity in units of P_o = |P_C|.
    assert_rel("F(0)", asperity_force(0.0).unwrap(), -8.0 / 9.0, 1e-10);
    assert_rel("F(-1)", asperity_force(-1.0).unwrap(), -5.0 / 9.0, 1e-12);
    // Beyond h_o the asperities have detached.
    assert!(ft.force(1.05, Phase::Unloading { d_min: -0.5 }).unwrap().abs() < 1e-12);
}

/// Eq. (1.10): the fraction of asperities in contact is the Gaussian tail, 0.841344746 at
/// d = −σ and 1/2 at d = 0.
#[test]
fn contact_fraction_is_the_gaussian_tail() {
    let ft = FullerTabor::new(0.7).unwrap();
    assert_rel(
        "n/N at d = -sigma",
        ft.contact_fraction(-0.7).unwrap(),
        0.841_344_746_068_542_9,
        1e-10,
    );
    assert_rel("n/N at d = 0", ft.contact_fraction(0.0).unwrap(), 0.5, 1e-10);
}

/// Fig. 1.4b's statement: adhesion falls as roughness grows (same cycle in units of σ).
#[test]
fn fuller_tabor_adhesion_falls_with_roughness() {
    let forces: Vec<f64> = [0.3, 1.0, 3.0]
        .iter()
        .map(|&t| {
            FullerTabor::new(t)
                .unwrap()
                .cycle(5.0 * t, -t, 121)
                .unwrap()
                .adhesive_force
        })
        .collect();
    assert!(
        forces[0] < forces[1] && forces[1] < forces[2] && forces[2] < 0.0,
        "{forces:?}"
    );
}

/// Fig. 1.4b as drawn (text below Fig. 1.4: "both the adhesive force and the energy loss
/// decrease as σ_rms increases"): both surfaces cycled on one separation axis d/h_o to one
/// d_min, so the rougher one touches fewer asperities and loses less. Scaled per σ_rms, both
/// were loaded to the same contact fraction and their normalised losses were equal (0.787).
#[test]
fn fig1_4b_losses_differ_and_fall_with_roughness() {
    let scene = adhesion::scenes::find("fig1.4b").expect("scene");
    let values = adhesion::headless::resolve_values(scene, None, &[], true).expect("values");
    let fig = scene.run(&values, &adhesion::job::Job::quiet()).expect("run");
    let r = |n: &str| fig.result_value(n).expect(n);
    let (l1, l2) = (r("energy_loss_1_norm"), r("energy_loss_2_norm"));
    let (f1, f2) = (r("adhesive_force_1_norm"), r("adhesive_force_2_norm"));
    assert!(l1 > 0.0 && l2 > 0.0, "{l1} {l2}");
    assert!(l2 < 0.9 * l1, "loss must fall with roughness: {l1} -> {l2}");
    assert!(
        f1 < f2 && f2 < 0.0,
        "adhesive force must fall with roughness: {f1} -> {f2}"
    );
    let x = &fig.panels[0].x.label;
    assert!(x.contains("h_o"), "one separation axis in units of h_o: {x}");
}
