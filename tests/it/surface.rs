//! Rough surfaces (appendices B, C, section 3.2.2): spectra and their moments, generation,
//! analysis of height maps.

use adhesion::numerics::quadrature::integrate;
use adhesion::surface::{
    HeightMap, Moments, Spectrum, generate, moments_of_map, moments_of_psd, nayak_curvature_pdf,
    nayak_joint_pdf,
};

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// The parameters (3.17) of the Si mold's PSD fit.
fn mold() -> Spectrum {
    Spectrum::Abc {
        rms: 1.45e-9,
        correlation_length: 20.1e-9,
        exponent: 3.28,
        cutoff: Some(1.0e8),
    }
}

#[test]
fn gaussian_moments_match_closed_forms_of_c_1_3() {
    // (C.1.3) by quadrature of (3.8) against m2 = 2σ²/Lc², m4 = 12σ²/Lc⁴ (R(δ) = σ² e^{-δ²/Lc²}).
    let (s, lc) = (10.0, 0.05);
    let g = Spectrum::Gaussian {
        rms: s,
        correlation_length: lc,
    };
    let exact = g.moments().unwrap();
    assert!(rel(exact.m2, 2.0 * s * s / (lc * lc)) < 1e-15);
    assert!(rel(exact.m4, 12.0 * s * s / lc.powi(4)) < 1e-15);
    let quad = g.moments_in_band(0.0, 40.0 / lc).unwrap();
    assert!(rel(quad.m0, exact.m0) < 1e-9, "{quad:?}");
    assert!(rel(quad.m2, exact.m2) < 1e-9, "{quad:?}");
    assert!(rel(quad.m4, exact.m4) < 1e-9, "{quad:?}");
    // Nayak's α is 3 for a Gaussian autocorrelation.
    assert!((exact.nayak_alpha() - 3.0).abs() < 1e-12);
}

#[test]
fn k_correlation_moments_match_beta_function_closed_forms() {
    // (3.16) without cut-off: m0 = σ², m2 = σ²/(2(n-2) Lc²), m4 = 3σ²/(4(n-2)(n-3) Lc⁴), from
    // the Beta integrals J1, J3, J5; quadrature over a wide band must agree.
    let (s, lc, n) = (1.0e-9, 20.0e-9, 4.5);
    let abc = Spectrum::Abc {
        rms: s,
        correlation_length: lc,
        exponent: n,
        cutoff: None,
    };
    let m = abc.moments().unwrap();
    assert!(rel(m.m2, s * s / (2.0 * (n - 2.0) * lc * lc)) < 1e-14);
    assert!(rel(m.m4, 0.75 * s * s / ((n - 2.0) * (n - 3.0) * lc.powi(4))) < 1e-14);
    let quad = abc.moments_in_band(0.0, 1.0e7 / lc).unwrap();
    assert!(rel(quad.m0, m.m0) < 1e-8, "{quad:?}");
    assert!(rel(quad.m2, m.m2) < 1e-8, "{quad:?}");
    assert!(rel(quad.m4, m.m4) < 1e-6, "{quad:?}");
}

#[test]
fn self_affine_moments_match_quadrature() {
    let sa = Spectrum::SelfAffine {
        rms: 1.0e-9,
        hurst: 0.7,
        q_low: 2.0e5,
        q_roll: 1.0e6,
        q_high: 1.0e9,
    };
    let m = sa.moments().unwrap();
    let p = sa.prepare().unwrap();
    let quad = moments_of_psd(|q| p.psd(q), 2.0e5, 1.0e9).unwrap();
    for (a, b) in [(quad.m0, m.m0), (quad.m2, m.m2), (quad.m4, m.m4)] {
        assert!(rel(a, b) < 1e-8, "{a} vs {b}");
    }
}

#[test]
fn moments_of_the_mold_psd_3_17_against_3_18() {
    // Section 3.3 prints m0 ≈ 2.1 nm², m2 ≈ 1.3e-3, m4 ≈ 4.3 µm⁻², η ≈ 101.4 µm⁻² for (3.17).
    // m0 = σ² = 2.1025 nm² matches. m2 and m4 do not follow from the printed q0 (ERRATA): the
    // quadrature of (3.8) gives the values pinned here (they are the model's, not the print's).
    let m = mold().moments().unwrap();
    assert!((m.m0 * 1e18 - 2.1).abs() < 0.05, "m0 = {} nm^2", m.m0 * 1e18);
    // Independent of q0's reading of the print: m2 agrees with 1.3e-3 to 8 %, m4 and η do not.
    assert!(rel(m.m2, 1.3959e-3) < 1e-4, "m2 = {:e}", m.m2);
    assert!(rel(m.m4, 5.2141e12) < 1e-4, "m4 = {:e}", m.m4);
    assert!(
        rel(m.asperity_density(), 114.41e12) < 1e-4,
        "eta = {:e}",
        m.asperity_density()
    );
    // The printed moments are consistent with each other through (3.9): 4.3/(6π√3·1.3e-3) µm⁻².
    let printed = Moments {
        m0: 2.1e-18,
        m2: 1.3e-3,
        m4: 4.3e12,
    };
    assert!((printed.asperity_density() * 1e-12 - 101.4).abs() < 0.1);
    // Truncating to the band a 2 µm, 256² scan resolves changes m2 and m4 by < 1 %: the
    // difference is not the finite scan.
    let band = mold()
        .moments_in_band(
            2.0 * std::f64::consts::PI / 2e-6,
            256.0 * std::f64::consts::PI / 2e-6,
        )
        .unwrap();
    assert!(rel(band.m2, m.m2) < 0.01 && rel(band.m4, m.m4) < 0.01, "{band:?}");
}

#[test]
fn nayak_pdfs_are_normalised_and_consistent() {
    for alpha in [1.6, 3.0, 10.0, 100.0] {
        let norm = integrate(|t| nayak_curvature_pdf(t, alpha), -40.0, 0.0, 0.0, 1e-12).unwrap();
        assert!((norm.value - 1.0).abs() < 1e-9, "α = {alpha}: {}", norm.value);
        // (3.11) is the marginal of (3.7) over heights (ERRATA).
        for t in [-0.5, -2.0, -4.0] {
            let marginal = integrate(|xi| nayak_joint_pdf(xi, t, alpha), -60.0, 60.0, 0.0, 1e-12).unwrap();
            assert!(
                rel(marginal.value, nayak_curvature_pdf(t, alpha)) < 1e-8,
                "α = {alpha}, t = {t}"
            );
        }
    }
}

#[test]
fn asperity_density_is_eq_3_9() {
    let m = Moments {
        m0: 1.0,
        m2: 2.0,
        m4: 3.0,
    };
    assert!(
        rel(
            m.asperity_density(),
            3.0 / (6.0 * std::f64::consts::PI * 3f64.sqrt() * 2.0)
        ) < 1e-15
    );
}

fn gaussian(lc: f64) -> Spectrum {
    Spectrum::Gaussian {
        rms: 10.0,
        correlation_length: lc,
    }
}

#[test]
fn generated_surface_has_the_requested_rms_exactly_and_is_reproducible() {
    let map = generate(&gaussian(0.05), 128, 96, 1.0, 0.75, 7).unwrap();
    assert_eq!((map.nx, map.ny, map.z.len()), (128, 96, 128 * 96));
    assert!(map.mean().abs() < 1e-12);
    assert!(rel(map.rms(), 10.0) < 1e-13);
    let again = generate(&gaussian(0.05), 128, 96, 1.0, 0.75, 7).unwrap();
    assert_eq!(map, again);
    let other = generate(&gaussian(0.05), 128, 96, 1.0, 0.75, 8).unwrap();
    assert_ne!(map.z, other.z);
    // Pinned values of seed 7 (ChaCha8 + standard normal + FFT filter): a change of generator,
    // normal sampler or filter convention shows here.
    let pinned = [(0, 0), (17, 3), (127, 95)].map(|(i, j)| map.at(i, j));
    let expected = [-28.916783791905267, -0.9152330956973987, -27.37867996307572];
    for (a, b) in pinned.iter().zip(expected) {
        // FFT rounding may differ in the last bits between SIMD paths.
        assert!((a - b).abs() < 1e-10, "{pinned:?}");
    }
}

#[test]
fn moments_of_generated_gaussian_surfaces_approach_closed_forms() {
    // Lc = 0.05 of a unit box on 256²: well resolved (Lc = 12.8 pixels) and many correlation
    // areas; the seed average of m2, m4 from the map is within a few per cent of 2σ²/Lc², 12σ²/Lc⁴.
    let g = gaussian(0.05);
    let exact = g.moments().unwrap();
    let n_seeds = 8;
    let mut acc = (0.0, 0.0);
    for seed in 0..n_seeds {
        let m = moments_of_map(&generate(&g, 256, 256, 1.0, 1.0, seed).unwrap());
        assert!(rel(m.m0, exact.m0) < 1e-12);
        acc.0 += m.m2 / n_seeds as f64;
        acc.1 += m.m4 / n_seeds as f64;
    }
    assert!(rel(acc.0, exact.m2) < 0.03);
    assert!(rel(acc.1, exact.m4) < 0.03);
}

#[test]
fn invalid_spectra_and_grids_are_rejected_with_the_parameter_named() {
    let e = generate(&gaussian(-1.0), 16, 16, 1.0, 1.0, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("correlation-length"), "{e}");
    let e = generate(&gaussian(0.1), 1, 16, 1.0, 1.0, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("grid"), "{e}");
    let e = generate(&gaussian(0.1), 16, 16, f64::NAN, 1.0, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("length"), "{e}");
    let bad = Spectrum::Abc {
        rms: 1.0,
        correlation_length: 1.0,
        exponent: 2.5,
        cutoff: None,
    };
    assert!(bad.moments().unwrap_err().to_string().contains("diverges"));
    let _ = HeightMap::new(2, 2, 1.0, 1.0, vec![0.0; 4]).unwrap();
}
