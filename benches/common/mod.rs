//! What the finite-element benchmarks share.

use adhesion::models::axisymmetric::cycle::CycleOptions;
use adhesion::models::axisymmetric::tip::TipParams;
use adhesion::models::body_force_fe::tip::FeTipParams;

/// The finite-element tip of Fig. 4.5 as `fig4.5-models` builds it: the surface model's fine
/// zone for a cycle to 15 ζ0 (ζ0 = 0.5946 nm), surface elements of 0.15 b (the scene's default
/// width; at 0.25 b the receding contact edge hops from ring to ring on unloading, a third jump
/// the dissertation's path does not have), bulk grading 0.15, a tip of 100 µm: 24 542 unknowns.
pub fn fig4_5_fe() -> FeTipParams {
    let surface = TipParams::default();
    FeTipParams {
        fine_radius: surface
            .fine_radius_for_depth(-15.0 * 0.5946e-9)
            .expect("fine zone"),
        element_width: 0.15,
        grading: 0.15,
        r0: 1e-4,
        h0: 1e-4,
        ..FeTipParams::default()
    }
}

/// The cycles the finite-element benchmark times and its path tests check: from 12 ζ0 apart to
/// `h_min` ζ0 in steps of `step` ζ0, jumps located to 1e-3 ζ0 (`z`: ζ0 in metres). The bench
/// cycle is `fe_cycle_options(z, -15.0, 0.2)`.
#[allow(dead_code)] // not every target that shares this module runs a cycle
pub fn fe_cycle_options(z: f64, h_min: f64, step: f64) -> CycleOptions {
    CycleOptions {
        h_start: 12.0 * z,
        h_min: h_min * z,
        step: step * z,
        refine_to: 1e-3 * z,
        contact_gap: 1e-9,
        keep_profiles: false,
        unload_to: None,
    }
}
