//! The scene registry and the presets: ids are unique, every scene has a preset equal to its
//! defaults, every preset runs in quick mode, results are the declared ones with unit suffixes.

use adhesion::headless::resolve_values;
use adhesion::job::Job;
use adhesion::scenes;

use crate::common::root;

/// Allowed endings of result names: a unit or `_norm`.
const SUFFIXES: &[&str] = &[
    "_norm",
    "_N",
    "_nN",
    "_uN",
    "_m",
    "_nm",
    "_um",
    "_J",
    "_J_per_m2",
    "_Pa",
    "_MPa",
    "_m2",
    "_per_m2",
    "_rad",
    "_deg",
    "_N_per_m",
    "_count",
    "_percent",
    "_s",
    "_m4",
    "_m2_per_m2",
    "_per_m",
    "_m3",
];

#[test]
fn scene_ids_are_unique_and_chapters_known() {
    let all = scenes::all();
    let mut ids: Vec<&str> = all.iter().map(|s| s.info().id).collect();
    ids.sort_unstable();
    let n = ids.len();
    ids.dedup();
    assert_eq!(ids.len(), n, "duplicate scene ids");
    for s in &all {
        let key = s.info().chapter;
        assert!(
            scenes::CHAPTERS.iter().any(|(k, _)| *k == key),
            "unknown chapter {key}"
        );
    }
}

#[test]
fn every_scene_has_a_preset_equal_to_its_defaults() {
    for s in scenes::all() {
        let id = s.info().id;
        let path = root().join("presets").join(format!("{id}.toml"));
        assert!(path.exists(), "missing preset {}", path.display());
        let mut from_preset = s.defaults();
        from_preset
            .apply_preset_file(&path)
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        assert_eq!(
            from_preset,
            s.defaults(),
            "presets/{id}.toml differs from the scene's defaults"
        );
    }
}

#[test]
fn every_preset_runs_in_quick_mode_and_reports_its_declared_results() {
    for s in scenes::all() {
        let info = s.info();
        let path = root().join("presets").join(format!("{}.toml", info.id));
        let values = resolve_values(s, Some(&path), &[], true).unwrap_or_else(|e| panic!("{}: {e}", info.id));
        let fig = s
            .run(&values, &Job::quiet())
            .unwrap_or_else(|e| panic!("{}: {e}", info.id));
        assert_eq!(fig.id, info.id);
        assert!(!fig.panels.is_empty(), "{}: no panels", info.id);
        assert!(fig.n_points() > 0, "{}: nothing drawn", info.id);
        let got: Vec<&str> = fig.results.iter().map(|(n, _)| n.as_str()).collect();
        let declared: Vec<&str> = info.results.iter().map(|(n, _)| *n).collect();
        let mut g = got.clone();
        let mut d = declared.clone();
        g.sort_unstable();
        d.sort_unstable();
        assert_eq!(g, d, "{}: results differ from the declared list", info.id);
        for (name, v) in &fig.results {
            assert!(
                SUFFIXES.iter().any(|s| name.ends_with(s)),
                "{}: result `{name}` has no unit suffix",
                info.id
            );
            assert!(v.is_finite(), "{}: result `{name}` = {v}", info.id);
        }
        for p in &fig.panels {
            for series in &p.series {
                assert!(
                    series.points.iter().all(|(x, y)| x.is_finite() && y.is_finite()),
                    "{}: series `{}` has non-finite points",
                    info.id,
                    series.name
                );
            }
        }
    }
}

#[test]
fn cancelled_jobs_stop_with_the_cancelled_error() {
    for s in scenes::all() {
        let job = Job::quiet();
        job.cancel();
        let values = s.quick(&s.defaults()).unwrap();
        match s.run(&values, &job) {
            Err(adhesion::Error::Cancelled) => {}
            other => panic!(
                "{}: expected cancellation, got {:?}",
                s.info().id,
                other.map(|f| f.id)
            ),
        }
    }
}

/// Parameter names that scenes declare differently (unit, range, help or choices), each with
/// the scenes that differ from the others (empty: every scene its own) and why. Any other name
/// must mean one thing with one range everywhere: the shared ones are declared once, in
/// `scenes::groups`.
const DECLARED_DIFFERENCES: &[(&str, &[&str], &str)] = &[
    // Counts and seeds whose meaning is the scene's own.
    (
        "points",
        &[],
        "a count of the scene's own samples (per curve, per branch, of α)",
    ),
    (
        "seed",
        &[],
        "the help says what the seed draws in the scene (one surface, the first of several)",
    ),
    ("samples", &[], "the help says how the scene uses the samples"),
    (
        "oversample",
        &["fig5.7"],
        "fig5.7 names its binned path, which fig5.8-5.9 always use",
    ),
    (
        "springs",
        &[],
        "the help says the array's shape (N = M, or M = 1)",
    ),
    ("steps", &[], "the help says what is stepped in the scene"),
    ("grid", &[], "the help cites the figure the scene reproduces"),
    (
        "grid_points",
        &[],
        "two different grids: fig3.5-accuracy's comparison and fig3.8's contour",
    ),
    // One symbol, different quantities.
    (
        "radius",
        &["fig1.1"],
        "fig1.1's sphere of the classical theories takes any size (non-dimensional curves)",
    ),
    (
        "modulus",
        &[],
        "E* of the substrate (fig1.1) or of the asperities (fig3.8)",
    ),
    ("work_of_adhesion", &[], "the help says whose work of adhesion"),
    ("max_depth_norm", &[], "normalised by h0 (fig1.1) or ĥ (fig2.8)"),
    (
        "alpha",
        &[],
        "the stiffness ratio of a spherical (2.35a) or a conical tip (2.45a)",
    ),
    ("alpha_min", &[], "the help says which set of α"),
    (
        "alpha_max",
        &[],
        "the stiffness ratio α of chapter 2, or the roughness α of (4.27) in fig4.10",
    ),
    ("tip_radius", &[], "an AFM tip (fig2.8-fit) or a bead (fig3.8)"),
    (
        "correlation_length",
        &[],
        "L_c in metres (chapter 3), normalised (chapter 5) or in periods (appendix C)",
    ),
    (
        "correlation_lengths",
        &[],
        "normalised (chapter 5) or in periods (appendix C)",
    ),
    (
        "rms",
        &[],
        "fig3.7d's σ_rms is in metres, the appendix's maps in their own units; the help cites the caption",
    ),
    (
        "exponent",
        &["fig3.7d"],
        "the PSD (3.17) is drawn for any n > 0; fig3.8's loss integral needs n > 1",
    ),
    ("cutoff", &[], "the help says whether q0 is also the fit's"),
    (
        "surface",
        &[],
        "a map to analyse (fig3.7d) or one replacing the PSD (fig3.8)",
    ),
    ("remove_tilt", &[], "the help names the map of the scene"),
    (
        "sigma_min",
        &[],
        "σ_rms of fig3.8's contour or σ of fig4.9b's potential",
    ),
    (
        "sigma_max",
        &[],
        "σ_rms of fig3.8's contour or σ of fig4.9b's potential",
    ),
    (
        "model",
        &[],
        "different sets of models: chapter 2's fits, chapter 4's tips (with their cost per scene)",
    ),
    (
        "roughness",
        &[],
        "one roughness (fig5.10-5.11) or a list, one per curve (fig5.7) or panel (fig5.9)",
    ),
    (
        "stiffness_exponent",
        &[],
        "the help says whether k_e/k_cr = 2⁻ⁿ is shown",
    ),
    ("wall_clock", &[], "the help names the cost axis of the scene"),
    (
        "profile_file",
        &["fig6.3-limits"],
        "fig6.3-limits' profile replaces only its zigzag",
    ),
    (
        "aspect_ratio_max",
        &["fig6.3-limits"],
        "fig6.3-limits goes to the steep limit, A up to 1e9",
    ),
    // Chapter 4: help lines that say what the scene does with a shared parameter (the unit and
    // range are the group's, `scenes::groups`).
    (
        "youngs_modulus",
        &[
            "fig4.9a",
            "fig4.9b",
            "fig4.9b-models",
            "fig4.10",
            "fig4.11",
            "fig4.12",
        ],
        "the roughness scenes cite ERRATA on Fig. 4.9's modulus",
    ),
    ("c12", &["fig4.4"], "fig4.4 is adhesionless: C6 = 0"),
    (
        "h_min_over_zeta0",
        &["fig4.3", "fig4.5-accuracy"],
        "fig4.3 stops a little past the pull-in; fig4.5-accuracy stays shallow for its finest grid",
    ),
    (
        "h_start_over_zeta0",
        &[
            "fig4.5-accuracy",
            "fig4.5-models",
            "fig4.7",
            "fig4.8",
            "fig4.9a",
            "fig4.9b",
            "fig4.9b-models",
            "fig4.10",
            "fig4.11",
            "fig4.12",
        ],
        "one cycle or several, and the pull-off they pass",
    ),
    (
        "step_over_zeta0",
        &["fig4.5-accuracy", "fig4.6"],
        "fig4.5-accuracy's default of its sweeps; fig4.6 only loads",
    ),
    (
        "ring_width",
        &[
            "fig4.3",
            "fig4.5",
            "fig4.5-accuracy",
            "fig4.9a",
            "fig4.9b",
            "fig4.10",
            "fig4.11",
            "fig4.12",
        ],
        "the surface model alone, its widest ring (fig4.3) or the default of a sweep",
    ),
    (
        "quadrature_points",
        &[
            "fig4.3",
            "fig4.5-accuracy",
            "fig4.9a",
            "fig4.9b",
            "fig4.10",
            "fig4.11",
            "fig4.12",
        ],
        "the surface model alone, or the default of a sweep",
    ),
    (
        "refine_over_zeta0",
        &["fig4.3"],
        "fig4.3 reads the gap before a jump at this tolerance",
    ),
    (
        "grading",
        &["fig4.4"],
        "fig4.4 cites its measured excess stiffness over Hertz",
    ),
    (
        "size_over_radius",
        &["fig4.4", "fig4.6"],
        "fig4.4's help cites the excess stiffness of the held top; fig4.6 has the finite elements alone",
    ),
    (
        "width",
        &[],
        "both models (fig4.5-models) or the finite elements alone (fig4.6)",
    ),
    ("amplitude_1", &[], "the help names the scene's configuration"),
    ("amplitude_2", &[], "the help names the scene's configuration"),
    ("amplitude_3", &[], "the help names the scene's configuration"),
];

/// One scene's declaration of a parameter as the user sees it.
fn declaration(spec: &adhesion::params::ParamSpec) -> String {
    format!(
        "[{}] {} {} {}",
        spec.unit,
        spec.range.describe(),
        spec.kind.expected(),
        spec.help
    )
}

#[test]
fn a_parameter_name_has_one_unit_range_and_help_across_the_scenes() {
    use std::collections::BTreeMap;
    let mut by_name: BTreeMap<&str, Vec<(&str, String)>> = BTreeMap::new();
    for s in scenes::all() {
        for spec in s.specs() {
            by_name
                .entry(spec.name)
                .or_default()
                .push((s.info().id, declaration(&spec)));
        }
    }
    let mut drift = Vec::new();
    for (name, declared) in &by_name {
        let excepted = DECLARED_DIFFERENCES.iter().find(|(n, _, _)| n == name);
        let kept: Vec<&(&str, String)> = declared
            .iter()
            .filter(|(id, _)| excepted.is_none_or(|(_, ids, _)| !ids.is_empty() && !ids.contains(id)))
            .collect();
        let mut forms: Vec<&String> = kept.iter().map(|(_, d)| d).collect();
        forms.sort_unstable();
        forms.dedup();
        if forms.len() > 1 {
            drift.push(format!(
                "{name}: {}",
                kept.iter()
                    .map(|(id, d)| format!("{id} {d}"))
                    .collect::<Vec<_>>()
                    .join(" | ")
            ));
        }
    }
    assert!(
        drift.is_empty(),
        "names declared differently without a reason in DECLARED_DIFFERENCES:\n{}",
        drift.join("\n")
    );
    // The list stays honest: every name and scene in it exists, and every entry still differs.
    for (name, ids, why) in DECLARED_DIFFERENCES {
        assert!(!why.is_empty(), "{name}: no reason");
        let declared = by_name
            .get(name)
            .unwrap_or_else(|| panic!("DECLARED_DIFFERENCES names `{name}`, which no scene has"));
        for id in *ids {
            assert!(
                declared.iter().any(|(s, _)| s == id),
                "DECLARED_DIFFERENCES: scene {id} has no `{name}`"
            );
        }
        let mut forms: Vec<&String> = declared.iter().map(|(_, d)| d).collect();
        forms.sort_unstable();
        forms.dedup();
        assert!(
            forms.len() > 1,
            "DECLARED_DIFFERENCES: `{name}` is declared alike everywhere now; remove its entry"
        );
    }
}
