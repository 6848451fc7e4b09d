//! Chapter 4 speed: one displacement-controlled cycle of the smooth tip of Fig. 4.5 with the
//! axisymmetric surface model (Lennard-Jones interaction, stable minimiser, jumps located to
//! 1e-3 ζ0), on the grid the tests use (ring width 0.25 b, 4 Gauss points per interval), to a
//! shallow and a deeper maximum depth; one cycle of the wavy tip of Fig. 4.7 to its deeper
//! depth; and the set-up of the tip (kernel and stiffness).

use std::hint::black_box;

use adhesion::models::axisymmetric::cycle::{CycleOptions, run_cycle};
use adhesion::models::axisymmetric::tip::{Tip, TipParams};
use criterion::{Criterion, criterion_group, criterion_main};

fn fig4_5(fine_radius: f64) -> TipParams {
    TipParams {
        fine_radius,
        ..TipParams::default()
    }
}

fn chapter4(c: &mut Criterion) {
    let mut group = c.benchmark_group("ch4");
    group.sample_size(10);
    group.bench_function("tip set-up, 250 nm fine zone", |b| {
        b.iter(|| black_box(Tip::new(&fig4_5(2.5e-7)).expect("tip")));
    });
    for (label, fine, h_min) in [("to 3 zeta0", 2.5e-7, -3.0), ("to 15 zeta0", 4.0e-7, -15.0)] {
        let tip = Tip::new(&fig4_5(fine)).expect("tip");
        let z = tip.scales().length;
        let opts = CycleOptions {
            h_start: 12.0 * z,
            h_min: h_min * z,
            step: 0.2 * z,
            refine_to: 1e-3 * z,
            contact_gap: 1e-9,
            keep_profiles: false,
            unload_to: None,
        };
        group.bench_function(format!("smooth-tip cycle {label} ({} rings)", tip.len()), |b| {
            b.iter(|| black_box(run_cycle(&tip, &opts, |_| Ok(())).expect("cycle")));
        });
    }
    // Fig. 4.7's wavy tip (R = 10 µm, E = 2.2 MPa, ν = 0.25, A_H = 1e-21 J, A = 1.25 nm,
    // λ = 125 nm) cycled to the caption's deeper depth |h_min|/R = 7e-4 from 25 ζ0 in steps of
    // 0.25 ζ0, as the scene runs it.
    let mut wavy = TipParams {
        radius: 1e-5,
        modulus: 2.2e6 / (1.0 - 0.25 * 0.25),
        hamaker: 1e-21,
        amplitude: 1.25e-9,
        wavelength: 1.25e-7,
        ..TipParams::default()
    };
    let h_min = -7e-4 * wavy.radius;
    wavy.fine_radius = wavy.fine_radius_for_depth(h_min).expect("fine zone");
    let tip = Tip::new(&wavy).expect("tip");
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
    group.bench_function(
        format!("wavy-tip cycle of fig4.7 to 7e-4 R ({} rings)", tip.len()),
        |b| {
            b.iter(|| black_box(run_cycle(&tip, &opts, |_| Ok(())).expect("cycle")));
        },
    );
    group.finish();
}

criterion_group!(benches, chapter4);
criterion_main!(benches);
