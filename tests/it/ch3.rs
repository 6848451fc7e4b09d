//! Chapter 3: the Maugis-Dugdale engine against the classical limits (Hertz, JKR, DMT), its
//! stability classification at extreme parameters, the energy loss per asperity (3.4) by two
//! methods, its limits (3.5a)/(3.5b), the collapse onto the Maugis parameter, the table, and the
//! empirical fit (3.6).

use adhesion::Error;
use adhesion::models::classical::SphereContact;
use adhesion::models::maugis_dugdale::{
    C1, C1_PRINTED, C2_PRINTED, LossTable, MaugisDugdale, MdBranch, S_DMT_EXACT, c2, empirical_loss,
    energy_loss, jkr_loss_constant, loss_table, s_fold_on_contact, scaled_empirical_loss, scaled_loss,
};

use crate::common::{assert_rel, rel};

/// The classical contact with R = 1, E* = 1 and w = ℓ/π, so that (1.1)-(1.7) are in the
/// variables of chapter 3 after h̄ = −h (chapter 1 counts h positive in compression) and
/// P̄ = P/2.
fn classical(ell: f64) -> SphereContact {
    SphereContact::new(1.0, 1.0, ell / std::f64::consts::PI).unwrap()
}

const RADII: [f64; 4] = [0.05, 0.2, 0.5, 1.0];

/// JKR limit (χ → ∞ at fixed ℓ, Sec. 3.2.1 / Fig. 3.4a): at χ = 1e8, ℓ = 0.1 (λ ≈ 3.6e8) the
/// contact branch equals (1.2) to 1e-6 relative at ā = 0.05 ... 1.
#[test]
fn md_reduces_to_jkr_as_chi_grows() {
    let ell = 0.1;
    let md = MaugisDugdale::new(1e8, ell).unwrap();
    let jkr = classical(ell);
    for a in RADII {
        let s = md.contact_state(a).unwrap();
        let j = jkr.jkr(a);
        assert_rel(&format!("JKR h at a = {a}"), s.h, -j.h, 1e-6);
        assert_rel(&format!("JKR P at a = {a}"), s.p, j.p / 2.0, 1e-6);
    }
    // The error decreases as 1/χ² at fixed ā (the cohesive zone's width is O(1/χ) and enters
    // the force and depth at second order): ten times larger χ, a hundred times smaller error.
    let err = |chi: f64| {
        let s = MaugisDugdale::new(chi, ell).unwrap().contact_state(0.2).unwrap();
        rel(s.p, jkr.jkr(0.2).p / 2.0)
    };
    let order = (err(10.0) / err(100.0)).log10();
    assert!((order - 2.0).abs() < 0.1, "order {order}");
}

/// DMT limit (χ → 0 at fixed ℓ, Fig. 3.4a): P̄ − P̄_DMT = O(χ) and h̄ − h̄_Hertz = O(√χ); at
/// χ = 1e-18, ℓ = 0.1 both are within 1e-6 relative of (1.7) at ā = 0.05 ... 1.
#[test]
fn md_reduces_to_dmt_as_chi_vanishes() {
    let ell = 0.1;
    let md = MaugisDugdale::new(1e-18, ell).unwrap();
    let dmt = classical(ell);
    for a in RADII {
        let s = md.contact_state(a).unwrap();
        let d = dmt.dmt(a);
        assert_rel(&format!("DMT h at a = {a}"), s.h, -d.h, 1e-6);
        assert_rel(&format!("DMT P at a = {a}"), s.p, d.p / 2.0, 1e-6);
    }
    // The adhesive force at ā → 0 is the DMT −2πwR, i.e. P̄ = −ℓ, on the a = 0 branch's end.
    let z = md.zone_state(md.junction_radius());
    assert_rel("DMT adhesive force", z.p, -ell, 1e-6);
}

/// Hertz limit (ℓ → 0 at fixed χ, Fig. 3.4b): h̄ + ā² = O(√ℓ); at χ = 0.2, ℓ = 1e-18 the
/// contact branch is (1.1) to 1e-6 relative at ā = 0.05 ... 1.
#[test]
fn md_reduces_to_hertz_as_ell_vanishes() {
    let md = MaugisDugdale::new(0.2, 1e-18).unwrap();
    let hertz = classical(1.0);
    for a in RADII {
        let s = md.contact_state(a).unwrap();
        let h = hertz.hertz(a);
        assert_rel(&format!("Hertz h at a = {a}"), s.h, -h.h, 1e-6);
        assert_rel(&format!("Hertz P at a = {a}"), s.p, h.p / 2.0, 1e-6);
    }
    assert!(MaugisDugdale::new(0.2, 1e-18).unwrap().energy_loss().unwrap() < 1e-22);
}

/// Stability at extreme but valid parameters (χ = 1e-3, 1e3; ℓ = 1e-6, 1): finite curves, one
/// change of stability along the curve, exactly at the pull-off fold (the largest h̄), unstable
/// before it and stable after; the JKR-like end has its fold near the JKR ā_D = (ℓ/8)^(1/3), the
/// DMT-like end at c̄ = 4χ/π on the a = 0 branch.
#[test]
fn extreme_parameters_give_finite_correctly_classified_curves() {
    for chi in [1e-3, 1e3] {
        for ell in [1e-6, 1.0] {
            let md = MaugisDugdale::new(chi, ell).unwrap();
            let cycle = md.cycle().unwrap();
            let fold = cycle.pull_off_from;
            let a_max = 3.0 * ell.cbrt().max(md.junction_radius());
            let curve = md.curve(a_max, 400).unwrap();
            let tag = format!("chi = {chi}, ell = {ell}");
            assert!(
                curve
                    .iter()
                    .all(|s| s.h.is_finite() && s.p.is_finite() && s.a.is_finite()),
                "{tag}: non-finite state"
            );
            // Skip the onset point (c = 0, slope exactly 4χ/π > 0 or the junction) and check
            // stability switches once, at the fold.
            let flags: Vec<bool> = curve[1..].iter().map(|s| s.stable).collect();
            let switches = flags.windows(2).filter(|w| w[0] != w[1]).count();
            assert_eq!(switches, 1, "{tag}: stability changes {switches} times");
            assert!(
                !flags[0] && flags[flags.len() - 1],
                "{tag}: unstable, then stable"
            );
            let h_max = curve.iter().map(|s| s.h).fold(f64::NEG_INFINITY, f64::max);
            assert!(
                fold.h >= h_max - 1e-12 * h_max.abs(),
                "{tag}: the fold is the largest h"
            );
            let k = flags.iter().position(|&f| f).unwrap();
            let before = curve[k];
            let after = curve[k + 1];
            assert!(before.h <= fold.h && after.h <= fold.h, "{tag}");
            assert!(
                cycle.loss > 0.0 && cycle.loss.is_finite(),
                "{tag}: loss {}",
                cycle.loss
            );
            assert!(cycle.pull_in_to.stable, "{tag}: pull-in lands on a stable state");
            assert!(
                cycle.pull_in_to.depth_from_onset.abs() <= 1e-9 * md.onset_depth(),
                "{tag}: pull-in at the onset depth"
            );
            if chi == 1e3 {
                assert_eq!(fold.branch, MdBranch::Contact, "{tag}");
                let a_d = (ell / 8.0).cbrt();
                assert!(rel(fold.a, a_d) < 0.05, "{tag}: a_D {} vs JKR {a_d}", fold.a);
            } else {
                assert_eq!(fold.branch, MdBranch::Zone, "{tag}");
                assert_rel(
                    "fold c = 4chi/pi",
                    fold.c,
                    4.0 * chi / std::f64::consts::PI,
                    1e-12,
                );
            }
        }
    }
}

/// Invalid parameters are named; scales beyond the double range are reported as unresolvable
/// rather than returned as garbage.
#[test]
fn invalid_and_unresolvable_parameters_give_clear_errors() {
    for (chi, ell, name) in [
        (0.0, 0.1, "chi"),
        (-1.0, 0.1, "chi"),
        (f64::NAN, 0.1, "chi"),
        (0.1, 0.0, "ell"),
        (0.1, f64::INFINITY, "ell"),
    ] {
        let e = MaugisDugdale::new(chi, ell).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidParameter { name: n, .. } if n == name),
            "{e}"
        );
    }
    for (chi, ell) in [(1e-70, 0.1), (1e70, 0.1), (0.1, 1e-200)] {
        let e = MaugisDugdale::new(chi, ell).unwrap_err();
        assert!(matches!(e, Error::Unresolvable { .. }), "{e}");
        assert!(!e.to_string().contains('\n'));
    }
}

/// Eq. (3.5b): the small-χ limit. The loop lies on the a = 0 branch whenever χ³/ℓ ≤ 1/16, and
/// there ΔĒ_md = (544/(3π³)) χ⁵ exactly; the printed 5.8483 is this constant to 5 digits.
#[test]
fn small_chi_limit_3_5b() {
    for (chi, ell) in [(1e-3, 1e-6), (1e-2, 0.1), (0.1, 0.1), (0.3, 1.0)] {
        let l = energy_loss(chi, ell).unwrap();
        assert_rel("loss / chi^5", l / chi.powi(5), C1, 1e-10);
    }
    assert!((C1 - C1_PRINTED).abs() < 5e-5, "c1 = {C1}");
    assert!((format!("{:.3}", C1) == "5.848"));
}

/// Eq. (3.5a): the large-χ limit ΔĒ_md/ℓ^(5/3) → (1 + 3·2^(5/3))/20 = 0.52622 (the JKR
/// hysteresis (1.6) in these units). The approach is O(1/λ): at λ ≈ 1.7e4 (s = 1e12) the
/// computed value is 0.5262 to 4 digits; error × λ is constant (≈ 0.66) between λ = 3.6e3 and
/// 1.7e4.
#[test]
fn large_chi_limit_3_5a() {
    let k = jkr_loss_constant();
    assert!((k - 0.5262).abs() < 5e-5);
    let g12 = scaled_loss(1e12).unwrap();
    assert_eq!(format!("{g12:.4}"), "0.5262");
    let g10 = scaled_loss(1e10).unwrap();
    let (l10, l12) = ((4.5f64 * 1e10).cbrt(), (4.5f64 * 1e12).cbrt());
    let (b10, b12) = ((1.0 - g10 / k) * l10, (1.0 - g12 / k) * l12);
    assert!(rel(b10, b12) < 0.02, "1/lambda approach: {b10} {b12}");
    // c2 of (3.6) follows from the two limits.
    assert!((c2() - C2_PRINTED).abs() < 5e-5, "c2 = {}", c2());
}

/// The two computations of the loss agree: quadrature along the stable segment and the shoelace
/// area of the sampled loop (n = 4000), to 2e-6, over the DMT end, the transition and the JKR
/// end; the loop area converges at second order.
#[test]
fn quadrature_and_loop_area_agree() {
    for s in [1e-3f64, 0.07, 0.1, 0.2, 1.0, 30.0, 1e4, 1e9] {
        let md = MaugisDugdale::new(s.cbrt(), 1.0).unwrap();
        let q = md.energy_loss().unwrap();
        let area = md.energy_loss_by_loop_area(4000).unwrap();
        assert_rel(&format!("loop area at s = {s}"), area, q, 2e-6);
    }
    let md = MaugisDugdale::new(1.0, 1.0).unwrap();
    let q = md.energy_loss().unwrap();
    let e1 = rel(md.energy_loss_by_loop_area(500).unwrap(), q);
    let e2 = rel(md.energy_loss_by_loop_area(1000).unwrap(), q);
    assert!((e1 / e2 - 4.0).abs() < 0.3, "order: {e1} {e2}");
}

/// The collapse: ΔĒ_md/ℓ^(5/3) depends on (χ, ℓ) only through s = χ³/ℓ (i.e. the Maugis λ);
/// at fixed s and ℓ over eight decades the scaled loss is the same to 1e-9.
#[test]
fn loss_collapses_onto_the_maugis_parameter() {
    for s in [0.01f64, 0.08, 0.5, 3.0, 1e3, 1e7] {
        let reference = scaled_loss(s).unwrap();
        for ell in [1e-6, 1e-3, 0.3, 10.0, 100.0] {
            let chi = (s * ell).cbrt();
            let g = energy_loss(chi, ell).unwrap() / ell.powf(5.0 / 3.0);
            assert_rel(&format!("collapse s = {s}, ell = {ell}"), g, reference, 1e-9);
        }
    }
}

/// The loss is monotone in s and the curve has one fold over λ ∈ [0.06, 1.7e4] (the engine
/// would report more as unresolvable); the branch changes at s = 1/16 and s = π/(8(π−1)).
#[test]
fn loss_increases_with_s_and_the_curve_has_one_fold_everywhere() {
    let mut prev = 0.0;
    let mut s: f64 = 1e-4;
    while s < 1e12 {
        let g = scaled_loss(s).unwrap();
        assert!(g > prev, "G not increasing at s = {s}");
        prev = g;
        let md = MaugisDugdale::new(s.cbrt(), 1.0).unwrap();
        let c = md.cycle().unwrap();
        let expect_zone_fold = s < s_fold_on_contact();
        assert_eq!(
            c.pull_off_from.branch == MdBranch::Zone,
            expect_zone_fold,
            "s = {s}"
        );
        assert_eq!(c.pull_in_to.branch == MdBranch::Zone, s <= S_DMT_EXACT, "s = {s}");
        s *= 1.15;
    }
}

/// The table: at the midpoints between its nodes the interpolated loss is within 1e-7 of the
/// quadrature (the stated maximum error), and agrees with the direct computation at random
/// (χ, ℓ) pairs, including both ends.
#[test]
fn loss_table_interpolation_error_is_below_its_stated_bound() {
    let table = loss_table().unwrap();
    let (err, at) = table.max_midpoint_error().unwrap();
    assert!(err < 1e-7, "max midpoint error {err} at s = {at}");
    for (chi, ell) in [
        (1e-3, 1e-6),
        (0.05, 0.1),
        (0.4, 0.1),
        (3.0, 0.01),
        (1e3, 1.0),
        (1e4, 1e-6),
    ] {
        assert_rel(
            &format!("table at chi = {chi}, ell = {ell}"),
            table.loss(chi, ell),
            energy_loss(chi, ell).unwrap(),
            1e-7,
        );
    }
    // A coarser table is worse, as stated on LossTable.
    let coarse = LossTable::new(10).unwrap();
    assert!(coarse.max_midpoint_error().unwrap().0 > err);
}

/// Eq. (3.6) and the claim of Sec. 3.2.1 that it is within 15 % of the exact loss: the empirical
/// function is exact in both limits, but its largest error, found on a dense scan of s = χ³/ℓ
/// (all (χ, ℓ) collapse onto s), is 36 % (at s ≈ 0.087, λ ≈ 0.73): the claim does not hold over
/// the whole range (ERRATA.md). It exceeds 15 % for s ∈ [0.024, 0.31] (λ ∈ [0.48, 1.11], where
/// (3.6) is too small) and s ∈ [1.36, 16.7] (λ ∈ [1.83, 4.22], too large).
#[test]
fn empirical_fit_3_6_largest_error() {
    let mut worst: (f64, f64) = (0.0, 0.0);
    let mut s: f64 = 1e-4;
    while s < 1e12 {
        let e = (scaled_empirical_loss(s) / scaled_loss(s).unwrap() - 1.0).abs();
        if e > worst.0 {
            worst = (e, s);
        }
        s *= 1.02;
    }
    assert!((worst.0 - 0.3626).abs() < 2e-3, "worst {worst:?}");
    assert!((worst.1 - 0.087).abs() < 0.005, "at {worst:?}");
    for (s, over) in [
        (0.02, false),
        (0.03, true),
        (0.3, true),
        (0.32, false),
        (1.3, false),
    ] {
        let e = (scaled_empirical_loss(s) / scaled_loss(s).unwrap() - 1.0).abs();
        assert_eq!(e > 0.15, over, "s = {s}: {e}");
    }
    for (s, over) in [(1.4, true), (16.0, true), (17.5, false)] {
        let e = (scaled_empirical_loss(s) / scaled_loss(s).unwrap() - 1.0).abs();
        assert_eq!(e > 0.15, over, "s = {s}: {e}");
    }
    // Exact in the limits.
    assert!(rel(scaled_empirical_loss(1e-6), scaled_loss(1e-6).unwrap()) < 1e-5);
    assert!(rel(scaled_empirical_loss(1e12), scaled_loss(1e12).unwrap()) < 1e-4);
    // (3.6) itself, in (χ, ℓ).
    assert_rel(
        "3.6",
        empirical_loss(0.3, 0.1),
        scaled_empirical_loss(0.27) * 0.1f64.powf(5.0 / 3.0),
        1e-12,
    );
}

mod ddh {
    //! Section 3.2.2-3.3 and appendix B.2: the depth-dependent loss.

    use adhesion::job::Job;
    use adhesion::models::ddh::{JkrNominalArea, LossMethod, area_change_approx};
    use adhesion::scenes::fig3::Fig3_8Params;

    use crate::common::{assert_rel, rel};

    /// (B.2.2) equals πR_t²(ā_h² − ā₀²), the area between the two JKR contact radii; its bracket
    /// runs from 1.33 (|h_min| → 0) to 1.19 (|h_min| = 1500 nm) and ā from 0.189 to 0.327 for
    /// ℓ_JKR = 3.35e-3 (R_t = 25 µm, E* = 0.75 MPa, w = 20 mJ/m²), all as printed in B.2.
    #[test]
    fn nominal_area_b_2_2_and_its_printed_range() {
        let j = JkrNominalArea::new(25e-6, 0.75e6, 0.020).unwrap();
        assert_eq!(format!("{:.2e}", j.ell), "3.35e-3");
        let a0 = j.radius(0.0).unwrap();
        assert_rel("a0 = (2 ell)^(1/3)", a0, (2.0 * j.ell).cbrt(), 1e-12);
        assert_eq!(format!("{a0:.3}"), "0.189");
        let d = 1500e-9;
        let ah = j.radius(-d / 25e-6).unwrap();
        assert_eq!(format!("{ah:.3}"), "0.327");
        let pi = std::f64::consts::PI;
        assert_rel(
            "B.2.2",
            j.area_change(d).unwrap(),
            pi * 25e-6f64.powi(2) * (ah * ah - a0 * a0),
            1e-10,
        );
        assert_eq!(format!("{:.2}", j.area_bracket(d).unwrap()), "1.19");
        assert_eq!(format!("{:.2}", j.area_bracket(1e-12).unwrap()), "1.33");
        // (B.2.3) is within the bracket's range: 4/π = 1.27.
        assert_rel("B.2.3", area_change_approx(25e-6, d), 4.0 * 25e-6 * d, 1e-15);
        assert!(j.radius(1e-3).is_err(), "a separation is not an indentation");
    }

    /// The mean loss (3.13) with the tabulated exact loss equals the one with the loss by
    /// quadrature at every node (1e-6), at both pairs of Sec. 3.3.
    #[test]
    fn mean_loss_table_equals_quadrature() {
        let p = Fig3_8Params::default();
        for (z0, sigma) in [(24e-9, 12.2e-9), (96e-9, 3e-9)] {
            let m = p.model(z0, sigma).unwrap();
            let t = m.mean_loss(LossMethod::Table).unwrap();
            let q = m.mean_loss(LossMethod::Quadrature).unwrap();
            assert_rel("table vs quadrature", t, q, 1e-6);
        }
    }

    /// Section 3.3 at the two stated pairs (Z₀, σ_rms) = (24 nm, 12.2 nm) and (96 nm, 3 nm),
    /// w = 26 mJ/m², E* = 0.75 MPa, R_t = 25 µm, PSD (3.16)-(3.17) scaled by k = σ_rms/1.52 nm.
    /// The text reads both off a fit to the measured 0.0241 J/m². The model gives (exact loss)
    /// 0.02209 and 0.03745 J/m², (empirical (3.6)) 0.02513 and 0.02557 J/m²: with (3.6) both
    /// pairs land near the measured value as the text says; with the exact loss the second pair
    /// (χ = 0.36, in the range where (3.6) is 30 % low) is 55 % higher. η = 114.4 µm⁻² from the
    /// moments of (3.16)-(3.17), not the printed 101.4 (ERRATA.md).
    #[test]
    fn loss_per_area_at_the_two_pairs_of_section_3_3() {
        let p = Fig3_8Params::default();
        let expect = [
            (24e-9, 12.2e-9, 0.022_09, 0.025_13),
            (96e-9, 3e-9, 0.037_45, 0.025_57),
        ];
        for (z0, sigma, exact, empirical) in expect {
            let m = p.model(z0, sigma).unwrap();
            assert_rel("exact", m.loss_per_area(LossMethod::Table).unwrap(), exact, 5e-4);
            assert_rel(
                "empirical",
                m.loss_per_area(LossMethod::Empirical).unwrap(),
                empirical,
                5e-4,
            );
        }
        let eta = p.model(24e-9, 12.2e-9).unwrap().asperity_density();
        assert_rel(
            "eta independent of k",
            eta,
            p.model(24e-9, 3e-9).unwrap().asperity_density(),
            1e-12,
        );
        assert_eq!(format!("{:.1}", eta * 1e-12), "114.4");
        // (3.15): ΔE_D = η ΔA_c ⟨ΔE_md⟩, linear in ΔA_c.
        let m = p.model(24e-9, 12.2e-9).unwrap();
        let a = area_change_approx(25e-6, 1e-6);
        assert_rel(
            "3.15",
            m.depth_dependent_loss(a, LossMethod::Table).unwrap(),
            eta * a * m.mean_loss(LossMethod::Table).unwrap(),
            1e-12,
        );
    }

    /// Fig. 3.8c: the loss per area falls with σ_rms at fixed Z₀ and with Z₀ at fixed σ_rms
    /// (Sec. 3.4), on the whole grid.
    #[test]
    fn loss_per_area_decreases_with_roughness_and_range() {
        let p = Fig3_8Params::default();
        let n = 8;
        let (zs, ss, v) = p.loss_grid(LossMethod::Table, n, &Job::quiet()).unwrap();
        assert_eq!((zs.len(), ss.len(), v.len()), (n, n, n * n));
        for j in 0..n {
            for i in 0..n {
                if i + 1 < n {
                    assert!(v[j * n + i + 1] < v[j * n + i], "Z0 trend at ({i}, {j})");
                }
                if j + 1 < n {
                    assert!(v[(j + 1) * n + i] < v[j * n + i], "sigma trend at ({i}, {j})");
                }
            }
        }
        assert!(rel(v[0], v[n * n - 1]) > 1.0);
    }
}

/// The accuracy of fig3.8c (the contour of the loss per area over Z₀ ∈ [10, 100] nm,
/// σ_rms ∈ [2, 14] nm): on a 4 x 4 grid the table equals the quadrature at every node to 1e-6,
/// while the empirical (3.6) is up to 31 % off (where χ = w/(E*Z₀) puts the asperities near
/// λ ≈ 0.7, the worst range of (3.6)).
#[test]
fn fig3_8c_grid_table_and_empirical_against_quadrature() {
    use adhesion::job::Job;
    use adhesion::models::ddh::LossMethod;
    use adhesion::scenes::fig3::Fig3_8Params;
    let p = Fig3_8Params::default();
    let n = 4;
    let (_, _, reference) = p.loss_grid(LossMethod::Quadrature, n, &Job::quiet()).unwrap();
    let (_, _, table) = p.loss_grid(LossMethod::Table, n, &Job::quiet()).unwrap();
    let (_, _, empirical) = p.loss_grid(LossMethod::Empirical, n, &Job::quiet()).unwrap();
    let worst = |v: &[f64]| {
        v.iter()
            .zip(&reference)
            .map(|(x, r)| rel(*x, *r))
            .fold(0.0, f64::max)
    };
    let (t, e) = (worst(&table), worst(&empirical));
    eprintln!("fig3.8c 4x4: table {t:e}, empirical {e}");
    assert!(t < 1e-6, "table {t}");
    assert!((e - 0.314).abs() < 0.005, "empirical {e}");
}

/// The depth-dependent loss on a user's height map instead of the PSD (3.16): a surface
/// generated from (3.16)-(3.17) on the grid of Fig. 3.7c (7.8 nm pixels, here 4 µm × 4 µm)
/// and written as Gwyddion .gsf, read back by fig3.8's `surface` parameter, gives a loss per
/// area within a few per cent of the one from the PSD's moments (the map's m2, m4 are those of
/// one finite, pixelated sample: η within 2 %, α within 3 %); an unreadable file is a one-line error naming it.
#[test]
fn loss_per_area_from_a_height_map() {
    use adhesion::models::ddh::LossMethod;
    use adhesion::scenes::fig3::Fig3_8Params;
    use adhesion::surface::{generate, write_height_map};
    let spectrum = adhesion::surface::spectrum::PSD_3_17;
    let map = generate(&spectrum, 512, 512, 4e-6, 4e-6, 7).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mold.gsf");
    write_height_map(&map, &path).unwrap();
    let mut p = Fig3_8Params::default();
    let (psd_base, _) = p.base_moments().unwrap();
    p.surface = path.to_string_lossy().into_owned();
    let (map_base, map_rms) = p.base_moments().unwrap();
    assert_rel("map rms", map_rms, 1.45e-9, 1e-6);
    assert_rel(
        "eta of the map",
        map_base.asperity_density(),
        psd_base.asperity_density(),
        0.02,
    );
    assert_rel(
        "alpha of the map",
        map_base.nayak_alpha(),
        psd_base.nayak_alpha(),
        0.03,
    );
    let q = Fig3_8Params::default();
    for (z0, sigma) in [(24e-9, 12.2e-9), (96e-9, 3e-9)] {
        let from_map = p
            .model(z0, sigma)
            .unwrap()
            .loss_per_area(LossMethod::Table)
            .unwrap();
        let from_psd = q
            .model(z0, sigma)
            .unwrap()
            .loss_per_area(LossMethod::Table)
            .unwrap();
        eprintln!(
            "({z0:e}, {sigma:e}): map {from_map} psd {from_psd} rel {}",
            rel(from_map, from_psd)
        );
    }
    p.surface = dir.path().join("missing.gsf").to_string_lossy().into_owned();
    let e = p.model(24e-9, 12.2e-9).unwrap_err().to_string();
    assert!(e.contains("missing.gsf") && !e.contains('\n'), "{e}");
}

/// `adhesion --headless --figure fig3.8 --surface FILE`: the moments come from the map (its η
/// in the JSON results, its RMS as the k = 1 roughness), the loss per area at the first pair is
/// within 10 % of the PSD's 0.02209 J/m² (a 2 µm × 2 µm, 256² sample of (3.16)-(3.17), like the
/// scan of Fig. 3.7c); a missing file fails in one line and writes nothing.
#[test]
fn command_line_fig3_8_on_a_height_map() {
    use adhesion::surface::{generate, moments_of_map, write_height_map};
    let spectrum = adhesion::surface::spectrum::PSD_3_17;
    let map = generate(&spectrum, 256, 256, 2e-6, 2e-6, 3).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mold.gsf");
    write_height_map(&map, &path).unwrap();
    let out = dir.path().join("out");
    let run = |surface: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_adhesion"))
            .args([
                "--headless",
                "--figure",
                "fig3.8",
                "--quick",
                "--format",
                "json",
                "--out",
            ])
            .arg(&out)
            .arg("--surface")
            .arg(surface)
            .output()
            .unwrap()
    };
    let o = run(&path);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fig3.8.json")).unwrap()).unwrap();
    let r = &v["results"];
    let get = |k: &str| r[k].as_f64().unwrap_or_else(|| panic!("{k} in {r}"));
    assert_rel(
        "eta",
        get("asperity_density_per_m2"),
        moments_of_map(&map).asperity_density(),
        1e-4,
    );
    assert_rel("base rms", get("base_rms_m"), 1.45e-9, 1e-4);
    assert!(rel(get("loss_per_area_1_exact_J_per_m2"), 0.022_09) < 0.1, "{r}");
    std::fs::remove_dir_all(&out).unwrap();
    let o = run(&dir.path().join("missing.gsf"));
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("missing.gsf") && err.trim().lines().count() == 1,
        "{err}"
    );
    assert!(!out.join("fig3.8.json").exists());
}

/// Fig. 3.8 as the dissertation draws it (Sec. 3.3: the two best-fit pairs are "almost
/// indistinguishable" and lie on the measured 0.0241 J/m² line): by default the scene uses the
/// empirical loss (3.6) and gives 0.0251 and 0.0256 J/m² at (24 nm, 12.2 nm) and (96 nm, 3 nm)
/// with the moments of (3.16)-(3.17) (the reproduction report's values); the exact loss (3.4)
/// is drawn beside it and named on the figure.
#[test]
fn fig3_8_default_is_the_empirical_loss_of_the_dissertation() {
    let scene = adhesion::scenes::find("fig3.8").expect("scene");
    let values = adhesion::headless::resolve_values(scene, None, &[], true).expect("values");
    let fig = scene.run(&values, &adhesion::job::Job::quiet()).expect("run");
    let r = |n: &str| fig.result_value(n).expect(n);
    assert!(
        (r("loss_per_area_1_J_per_m2") - 0.0251).abs() < 5e-5,
        "{}",
        r("loss_per_area_1_J_per_m2")
    );
    assert!(
        (r("loss_per_area_2_J_per_m2") - 0.0256).abs() < 5e-5,
        "{}",
        r("loss_per_area_2_J_per_m2")
    );
    let names: Vec<&str> = fig.panels[1].series.iter().map(|s| s.name.as_str()).collect();
    assert!(
        names.iter().any(|n| n.contains("empirical loss (3.6)")),
        "{names:?}"
    );
    assert!(names.iter().any(|n| n.contains("exact loss (3.4)")), "{names:?}");
    assert!(
        fig.panels[2]
            .series
            .iter()
            .any(|s| s.name.contains("exact loss (3.4)")),
        "the measured level under the exact loss is drawn in (c)"
    );
}
