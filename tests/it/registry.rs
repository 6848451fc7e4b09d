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
