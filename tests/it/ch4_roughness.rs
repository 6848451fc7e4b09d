//! Chapter 4, section 4.5.2: roughness (the amplitude of the waviness (4.10)) and adhesion at
//! σ = 1.5 nm and |h_min|/R = 6e-4 with the axisymmetric surface model: the scenes fig4.9a,
//! fig4.11 and fig4.12 at their defaults, checked against what the dissertation's text says.

use adhesion::figure::Figure;
use adhesion::job::Job;

fn run(id: &str) -> Figure {
    let s = adhesion::scenes::find(id).unwrap();
    s.run(&s.defaults(), &Job::quiet()).unwrap()
}

// Fig. 4.9a: a small roughness (A/λ = 0.0075) raises the adhesive force and the loss, a larger
// one (0.02) lowers them again, at both moduli. At E = 1.1 MPa (ERRATA's reading of the
// caption) the smooth tip's P_adh/(2E*R²) is the printed 1.54e-5 to 1%; at the caption's
// 2.2 MPa it is half of it, below the DMT bound the printed value exceeds. The rough tips
// differ from the printed values (2.87e-5 vs 3.06e-5, 2.45e-5 vs 1.93e-5 at 1.1 MPa): the
// dissertation's body-force FE model and its grid are not the surface model, and its other
// parameters may differ too; recorded, not tuned.
#[test]
fn fig4_9a_small_roughness_raises_adhesion_and_large_roughness_lowers_it() {
    let fig = run("fig4.9a");
    let r = |n: &str| fig.result_value(n).unwrap();
    for suffix in ["", "_b"] {
        let p = |i: usize| r(&format!("p_adh_{i}{suffix}_norm"));
        let h = |i: usize| r(&format!("hysteresis_{i}{suffix}_norm"));
        assert!(
            p(2) > p(1) && p(2) > p(3),
            "P_adh{suffix}: {} {} {}",
            p(1),
            p(2),
            p(3)
        );
        assert!(
            h(2) > h(1) && h(2) > h(3),
            "H{suffix}: {} {} {}",
            h(1),
            h(2),
            h(3)
        );
    }
    let smooth_b = r("p_adh_1_b_norm");
    assert!((smooth_b / 1.54e-5 - 1.0).abs() < 0.01, "{smooth_b}");
    assert!(r("p_adh_1_norm") < r("dmt_bound_norm") && 1.54e-5 > r("dmt_bound_norm"));
    // More asperity-level instabilities on the rough tip than the smooth tip's two.
    assert_eq!(r("jumps_1_count"), 2.0);
    assert!(r("jumps_2_count") > 2.0);
}

// Fig. 4.11: P_adh is largest at A/λ = 0.01, where the contact at the adhesive force is still
// simply connected and largest; at 0.02 and 0.03 it is multiply connected and the real contact
// area has fallen.
#[test]
fn fig4_11_adhesion_peaks_where_the_contact_stops_being_simply_connected() {
    let fig = run("fig4.11");
    let r = |n: &str| fig.result_value(n).unwrap();
    let p: Vec<f64> = (1..=4).map(|i| r(&format!("p_adh_{i}_norm"))).collect();
    let area: Vec<f64> = (1..=4).map(|i| r(&format!("area_{i}_m2"))).collect();
    let parts: Vec<f64> = (1..=4).map(|i| r(&format!("parts_{i}_count"))).collect();
    assert!(p[1] > p[0] && p[1] > p[2] && p[2] > p[3], "{p:?}");
    assert_eq!(&parts[..2], &[1.0, 1.0]);
    assert!(parts[2] > 1.0 && parts[3] > 1.0, "{parts:?}");
    assert!(
        area[1] > area[0] && area[2] < area[1] && area[3] < area[1],
        "{area:?}"
    );
}

// Fig. 4.12: at the large roughness the contact detaches in more pull-off jumps, one ring per
// jump before the last (crack arrest and reinitiation); at the small roughness the last jump
// detaches two rings at once (a cascade). The final pull-off of the large roughness also takes
// the central disc and the last annulus together: the workbench's finding, on the figure.
#[test]
fn fig4_12_large_roughness_detaches_in_more_steps() {
    let fig = run("fig4.12");
    let r = |n: &str| fig.result_value(n).unwrap();
    assert!(r("pull_offs_2_count") > r("pull_offs_1_count"));
    assert!(r("cascades_1_count") >= 1.0);
    assert!(r("rings_per_jump_1_count") > r("rings_per_jump_2_count"));
    // Before its final pull-off the large roughness loses one ring per jump.
    let n2 = r("pull_offs_2_count");
    let total2 = r("rings_per_jump_2_count") * n2;
    assert!(total2 - (n2 - 1.0) <= 2.0 + 1e-9, "{total2} rings in {n2} jumps");
}

// Fig. 4.9b in quick form (σ = 1 ... 3 nm, as the full figure): the smooth tip's adhesion falls
// with σ, as the text says (w ∝ σ⁻² at a fixed Hamaker constant, and μ_T falls); in this range
// the rough tips fall too (the text's initial rise is not found: a note on the figure says so).
// The figure says it is a quick form, and what is coarser.
#[test]
fn fig4_9b_smooth_adhesion_falls_with_the_interaction_range() {
    let s = adhesion::scenes::find("fig4.9b").unwrap();
    let values = s.quick(&s.defaults()).unwrap();
    let fig = s.run(&values, &Job::quiet()).unwrap();
    let r = |n: &str| fig.result_value(n).unwrap();
    assert_eq!(r("sigma_p_adh_max_1_nm"), 1.0);
    assert_eq!(r("sigma_h_max_1_nm"), 1.0);
    let coarser = fig.quick_form.as_deref().expect("a quick figure says so");
    assert!(coarser.contains("sigma_points = 3 (full: 9)"), "{coarser}");
    assert!(
        coarser.contains("depth_over_radius = 1e-4 (full: 6e-4)"),
        "{coarser}"
    );
    assert_eq!(
        fig.notes[0],
        format!("quick form: {}", adhesion::render::text::escape(coarser))
    );
    assert!(fig.title.ends_with("(quick form)"));
    assert!(
        fig.notes
            .iter()
            .any(|n| n.starts_with("Ran: 3 values of σ from 1 to 3 nm"))
    );
    let json = adhesion::render::data::json(&fig, s.info().caption, &values, 0.0);
    let record: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(record["quick_form"].as_str(), Some(coarser));
    let p = &fig.panels[0].series[0].points;
    assert!(p.windows(2).all(|w| w[1].1 < w[0].1), "{p:?}");
    assert!(fig.notes.iter().any(|n| n.starts_with("Unlike the text")));
    assert!(s.info().sweep);
}

// Every scene whose quick form is coarser than its defaults says so, naming each parameter the
// quick form changed with its full value; a run at the defaults says nothing. `--all` runs the
// sweeps and the long scenes in quick form, and every run (sharded or not) ends in the one
// place that marks the figure (`Figure::mark_quick`).
#[test]
fn every_quick_form_names_what_is_coarser() {
    for s in adhesion::scenes::all() {
        let id = s.info().id;
        let defaults = s.defaults();
        assert_eq!(adhesion::scenes::quick_form(s, &defaults), None, "{id}");
        let quick = s.quick(&defaults).unwrap();
        let changed: Vec<&str> = defaults
            .specs
            .iter()
            .zip(defaults.values.iter().zip(&quick.values))
            .filter(|(_, (d, q))| d != q)
            .map(|(spec, _)| spec.name)
            .collect();
        let text = adhesion::scenes::quick_form(s, &quick);
        if changed.is_empty() {
            assert_eq!(text, None, "{id}");
            continue;
        }
        let text = text.unwrap_or_else(|| panic!("{id}: the quick form does not say so"));
        for name in changed {
            assert!(text.contains(&format!("{name} = ")), "{id}: {text} lacks {name}");
        }
    }
}

// The chapter 4 sweeps' quick forms keep what their figures are for: fig4.9b from σ = 1 nm,
// fig4.10 from the default's smallest β.
#[test]
fn roughness_sweeps_quick_forms_keep_the_small_range() {
    for (id, name) in [("fig4.9b", "sigma_min"), ("fig4.10", "beta_min")] {
        let s = adhesion::scenes::find(id).unwrap();
        let (d, q) = (s.defaults(), s.quick(&s.defaults()).unwrap());
        let k = d.specs.iter().position(|p| p.name == name).unwrap();
        assert_eq!(d.values[k], q.values[k], "{id}: {name}");
    }
}

// The study of the σ claim (fig4.9b-models) in quick form (σ = 2, 3 nm, shallow cycles on the
// quick mesh): the table of every (A/λ, σ) in the three variants, each variant's convergence
// evidence and a verdict; the refined and the unrefined surface model agree to a few per cent;
// a cycle without jumps reports no loop rather than a percentage of round-off.
#[test]
fn fig4_9b_models_reports_its_table_convergence_and_verdict() {
    let s = adhesion::scenes::find("fig4.9b-models").unwrap();
    let fig = s.run(&s.quick(&s.defaults()).unwrap(), &Job::quiet()).unwrap();
    let r = |n: &str| fig.result_value(n).unwrap();
    assert_eq!(r("points_count"), 20.0);
    for v in ["surface", "fe", "fixed"] {
        assert!(r(&format!("{v}_p_adh_smallest_sigma_norm")) > 0.0, "{v}");
    }
    assert!(r("surface_refinement_change_max_norm") < 0.05);
    let table: Vec<&String> = fig.notes.iter().filter(|n| n.starts_with("A/λ = ")).collect();
    assert_eq!(table.len(), 2);
    for row in table {
        assert!(
            row.contains("σ = 2 nm: (i)") && row.contains("σ = 3 nm: (i)"),
            "{row}"
        );
        // At σ = 3 nm the quick cycles have no jump: no loop, and no relative change of the
        // Newton tolerance's trace that H is then.
        let at_3 = &row[row.find("σ = 3 nm").unwrap()..];
        assert_eq!(at_3.matches("H 0 (no loop)").count(), 3, "{row}");
    }
    assert!(fig.notes.iter().any(|n| n.starts_with("Verdict at A/λ = 0.0075")));
}

// The full study (σ = 1, 1.25, 1.5, 2, 3 nm at |h_min|/R = 6e-4; hours on 2 cores: run it in
// shards, see the README): both converged variants are converged to 2 % in P_adh, and the
// verdict is on the figure.
#[test]
#[ignore = "hours: the full study of the σ claim"]
fn fig4_9b_models_full_study_is_converged() {
    let fig = run("fig4.9b-models");
    let r = |n: &str| fig.result_value(n).unwrap();
    assert!(r("surface_refinement_change_max_norm") < 0.02);
    assert!(r("fe_refinement_change_max_norm") < 0.02);
    for n in &fig.notes {
        println!("{n}");
    }
}
