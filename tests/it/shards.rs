//! Sharded sweeps (`--shard I/N`, `--merge`), run as processes: the merged figure of three
//! shards is the unsharded figure bit for bit (CSV, and the JSON but for its run time); a shard
//! rerun after losing points computes only those; a missing point makes the merge fail naming
//! it; a folder of another parameter set is refused; non-sweep scenes are refused. In-process:
//! every sweep scene assembles the same figure from points computed in any grouping.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use adhesion::headless::resolve_values;
use adhesion::headless::shard::{folder, point_path};
use adhesion::job::Job;
use adhesion::render::data::csv;
use adhesion::scenes;

fn adhesion(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesion"))
        .args(args)
        .output()
        .expect("binary runs")
}

#[track_caller]
fn ok(args: &[&str]) -> Output {
    let o = adhesion(args);
    assert!(
        o.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// Assert failure with one line on stderr containing every needle; returns the line.
#[track_caller]
fn rejected(args: &[&str], needles: &[&str]) -> String {
    let o = adhesion(args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "{args:?} succeeded");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "{args:?}: not one line:\n{stderr}"
    );
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: `{n}` not in: {stderr}");
    }
    stderr
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// The sweep folder of `id` in quick form with `sets` under `out`, as the binary computes it.
fn quick_folder(out: &Path, id: &str, sets: &[String]) -> PathBuf {
    let scene = scenes::find(id).unwrap();
    let values = resolve_values(scene, None, sets, true).unwrap();
    folder(out, id, &values)
}

/// The JSON export without its run time (the one line that differs between runs).
fn json_without_run_time(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim_start().starts_with("\"run_time_s\""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Three shards then a merge into one folder, an unsharded run into another; CSV bytes equal,
/// JSON equal but for the run time, and the results really present.
fn three_shards_equal_the_unsharded_run(id: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (sharded, single) = (dir.path().join("sharded"), dir.path().join("single"));
    for i in 0..3 {
        let part = format!("{i}/3");
        let o = ok(&[
            "--headless",
            "--figure",
            id,
            "--quick",
            "--shard",
            &part,
            "--out",
            s(&sharded),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(&format!("{id} shard {i}/3: ")), "{stderr}");
    }
    ok(&[
        "--headless",
        "--figure",
        id,
        "--quick",
        "--merge",
        "--format",
        "csv,json",
        "--out",
        s(&sharded),
    ]);
    ok(&[
        "--headless",
        "--figure",
        id,
        "--quick",
        "--format",
        "csv,json",
        "--out",
        s(&single),
    ]);
    let file = |d: &Path, ext: &str| d.join(format!("{id}.{ext}"));
    let (a, b) = (
        std::fs::read(file(&sharded, "csv")).unwrap(),
        std::fs::read(file(&single, "csv")).unwrap(),
    );
    assert!(a.len() > 100, "{id}: CSV too short");
    assert!(a == b, "{id}: merged CSV differs from the unsharded run");
    let (ja, jb) = (
        json_without_run_time(&file(&sharded, "json")),
        json_without_run_time(&file(&single, "json")),
    );
    assert!(ja.contains("\"results\""));
    assert_eq!(ja, jb, "{id}: merged JSON differs from the unsharded run");
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file(&sharded, "json")).unwrap()).unwrap();
    assert!(
        !record["results"].as_object().unwrap().is_empty(),
        "{id}: no results"
    );
}

#[test]
fn fig5_8_three_shards_merge_to_the_unsharded_run_bit_for_bit() {
    three_shards_equal_the_unsharded_run("fig5.8");
}

#[test]
fn fig3_8_three_shards_merge_to_the_unsharded_run_bit_for_bit() {
    three_shards_equal_the_unsharded_run("fig3.8");
}

#[test]
fn a_rerun_shard_computes_only_the_points_it_lost() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let args = [
        "--headless",
        "--figure",
        "fig5.8",
        "--quick",
        "--shard",
        "1/3",
        "--out",
        s(&out),
    ];
    ok(&args);
    let f = quick_folder(&out, "fig5.8", &[]);
    // Shard 1 of 3 of the 18 quick points: 1, 4, 7, 10, 13, 16.
    let mine: Vec<usize> = (1..18).step_by(3).collect();
    let stamp = |k: usize| std::fs::metadata(point_path(&f, k)).unwrap().modified().unwrap();
    let before: BTreeMap<usize, _> = mine
        .iter()
        .map(|&k| (k, (stamp(k), std::fs::read(point_path(&f, k)).unwrap())))
        .collect();
    for k in [0, 2, 3] {
        assert!(!point_path(&f, k).exists(), "point {k} belongs to another shard");
    }
    // A job killed after four points: two files lost; a fifth damaged (cut short).
    std::fs::remove_file(point_path(&f, 4)).unwrap();
    std::fs::remove_file(point_path(&f, 13)).unwrap();
    std::fs::write(point_path(&f, 16), "{\"scene\":\"fig5.8\",\"po").unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    let o = ok(&args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("6 of the 18 points, 3 already done") && stderr.contains("3 to compute"),
        "{stderr}"
    );
    assert!(stderr.contains("3/3 done"), "{stderr}");
    for (k, (t, bytes)) in &before {
        let recomputed = [4, 13, 16].contains(k);
        assert_eq!(stamp(*k) == *t, !recomputed, "point {k}: file time");
        // Recomputed points give the same numbers (the time taken may differ).
        let values = |b: &[u8]| serde_json::from_slice::<serde_json::Value>(b).unwrap()["values"].clone();
        assert_eq!(
            values(&std::fs::read(point_path(&f, *k)).unwrap()),
            values(bytes),
            "point {k}"
        );
    }
    // Nothing left to do on a third run.
    let o = ok(&args);
    assert!(String::from_utf8_lossy(&o.stderr).contains("0 to compute"));
}

/// A shard process killed (SIGKILL) after its first points, then run again: it computes only
/// the points that were not written, and the points written before the kill stay untouched.
#[test]
fn a_killed_shard_resumes_where_it_stopped() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // Four points of a few tenths of a second each, one thread: time to kill between them.
    let sets = ["stiffness_exponents=6,7", "roughness_points=2"];
    let mut args = vec![
        "--headless",
        "--figure",
        "fig5.8",
        "--shard",
        "0/1",
        "--out",
        s(&out),
    ];
    for a in &sets {
        args.extend(["--set", a]);
    }
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_adhesion"))
            .args(&args)
            .env("RAYON_NUM_THREADS", "1")
            .stderr(std::process::Stdio::piped())
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let sets: Vec<String> = sets.iter().map(ToString::to_string).collect();
    let scene = scenes::find("fig5.8").unwrap();
    let f = folder(
        &out,
        "fig5.8",
        &resolve_values(scene, None, &sets, false).unwrap(),
    );
    let written = || {
        (0..4)
            .filter(|&k| point_path(&f, k).exists())
            .collect::<Vec<usize>>()
    };
    let mut child = run();
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while written().is_empty() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let kept = written();
    assert!(
        !kept.is_empty() && kept.len() < 4,
        "killed with points {kept:?} written"
    );
    let stamps: Vec<_> = kept
        .iter()
        .map(|&k| std::fs::metadata(point_path(&f, k)).unwrap().modified().unwrap())
        .collect();
    let o = run().wait_with_output().unwrap();
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    let expected = format!("4 of the 4 points, {} already done", kept.len());
    assert!(stderr.contains(&expected), "{stderr}");
    assert!(
        stderr.contains(&format!("{} to compute", 4 - kept.len())),
        "{stderr}"
    );
    assert_eq!(written(), vec![0, 1, 2, 3]);
    for (&k, t) in kept.iter().zip(&stamps) {
        let now = std::fs::metadata(point_path(&f, k)).unwrap().modified().unwrap();
        assert_eq!(now, *t, "point {k} was written again");
    }
}

#[test]
fn a_missing_point_fails_the_merge_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for i in 0..2 {
        let part = format!("{i}/2");
        ok(&[
            "--headless",
            "--figure",
            "fig5.8",
            "--quick",
            "--shard",
            &part,
            "--out",
            s(&out),
        ]);
    }
    let f = quick_folder(&out, "fig5.8", &[]);
    std::fs::remove_file(point_path(&f, 7)).unwrap();
    let merge = [
        "--headless",
        "--figure",
        "fig5.8",
        "--quick",
        "--merge",
        "--out",
        s(&out),
    ];
    rejected(
        &merge,
        &[
            "1 of the 18 points of fig5.8 are missing",
            "7 (n = 8, σ_rms/σ = 122.474",
        ],
    );
    assert!(!out.join("fig5.8.csv").exists() && !out.join("fig5.8.json").exists());
    // A merge of a sweep never started names the folder it expected.
    rejected(
        &[
            "--headless",
            "--figure",
            "fig5.8",
            "--quick",
            "--set",
            "seed=9",
            "--merge",
            "--out",
            s(&out),
        ],
        &[
            "no points of fig5.8 with these parameters",
            "run the shards first",
        ],
    );
    ok(&[
        "--headless",
        "--figure",
        "fig5.8",
        "--quick",
        "--shard",
        "1/2",
        "--out",
        s(&out),
    ]);
    ok(&merge);
    assert!(out.join("fig5.8.csv").exists() && out.join("fig5.8.png").exists());
}

#[test]
fn a_different_parameter_set_is_refused_in_the_same_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    ok(&[
        "--headless",
        "--figure",
        "fig5.8",
        "--quick",
        "--shard",
        "0/2",
        "--out",
        s(&out),
    ]);
    // Another --set gives another folder; the first stays as it was.
    let seed2 = vec!["seed=2".to_string()];
    let (f1, f2) = (
        quick_folder(&out, "fig5.8", &[]),
        quick_folder(&out, "fig5.8", &seed2),
    );
    assert_ne!(f1, f2);
    // The points of seed 1 put where seed 2's belong (a copied or renamed folder): refused.
    std::fs::rename(&f1, &f2).unwrap();
    let n_before = std::fs::read_dir(&f2).unwrap().count();
    for extra in [&["--shard", "1/2"][..], &["--merge"][..]] {
        let mut args = vec![
            "--headless",
            "--figure",
            "fig5.8",
            "--quick",
            "--set",
            "seed=2",
            "--out",
            s(&out),
        ];
        args.extend_from_slice(extra);
        rejected(
            &args,
            &[
                "holds points of fig5.8 computed with seed = 1, not 2",
                "refusing to mix",
            ],
        );
    }
    assert_eq!(
        std::fs::read_dir(&f2).unwrap().count(),
        n_before,
        "files were added"
    );
    assert!(!out.join("fig5.8.csv").exists());
}

#[test]
fn shard_and_merge_need_a_sweep_scene_and_a_valid_shard() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = s(&out);
    rejected(
        &["--headless", "--figure", "fig1.1", "--shard", "0/2", "--out", o],
        &["scene fig1.1 is not a sweep", "fig5.8"],
    );
    rejected(
        &["--headless", "--figure", "fig1.1", "--merge", "--out", o],
        &["not a sweep"],
    );
    rejected(
        &["--headless", "--figure", "fig5.8", "--shard", "2/2", "--out", o],
        &["must be below N = 2"],
    );
    rejected(
        &["--headless", "--figure", "fig5.8", "--shard", "x", "--out", o],
        &["expected I/N"],
    );
    rejected(
        &["--headless", "--all", "--shard", "0/2", "--out", o],
        &["--shard applies to --figure only"],
    );
    rejected(
        &[
            "--headless",
            "--figure",
            "fig5.8",
            "--shard",
            "0/2",
            "--merge",
            "--out",
            o,
        ],
        &["cannot be used with"],
    );
    assert!(!out.exists(), "something was written");
}

#[test]
fn describe_gives_the_number_of_points() {
    let o = ok(&["--describe", "fig5.8"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("A sweep of 60 independent points at these defaults (18 in quick form)"),
        "{text}"
    );
    let o = ok(&["--describe", "fig1.1"]);
    assert!(!String::from_utf8_lossy(&o.stdout).contains("independent points"));
}

/// Every sweep scene: points computed in two interleaved groups (as two shards would) and
/// assembled give the figure `run` gives.
#[test]
fn every_sweep_assembles_the_same_figure_from_any_grouping_of_points() {
    let mut count = 0;
    for scene in scenes::all() {
        let Some(sweep) = scene.sweep() else { continue };
        count += 1;
        let id = scene.info().id;
        let values = scene.quick(&scene.defaults()).unwrap();
        let whole = scene.run(&values, &Job::quiet()).unwrap();
        let n = sweep.points(&values).unwrap().len();
        assert!(n >= 2, "{id}: {n} points");
        let results = std::sync::Mutex::new(vec![None; n]);
        for part in [0, 1] {
            let ids: Vec<usize> = (part..n).step_by(2).collect();
            sweep
                .run_points(&values, &ids, &Job::quiet(), &|k, task| {
                    let v = task()?;
                    results.lock().unwrap()[k] = Some(v);
                    Ok(())
                })
                .unwrap();
        }
        let points: Vec<Vec<f64>> = results
            .into_inner()
            .unwrap()
            .into_iter()
            .map(Option::unwrap)
            .collect();
        let merged = sweep.assemble(&values, &points, &Job::quiet()).unwrap();
        assert_eq!(csv(&merged), csv(&whole), "{id}");
        assert_eq!(merged.results.len(), whole.results.len(), "{id}");
        for ((na, a), (nb, b)) in merged.results.iter().zip(&whole.results) {
            assert!(
                na == nb && a.to_bits() == b.to_bits(),
                "{id}: {na} {a} vs {nb} {b}"
            );
        }
    }
    assert_eq!(
        count, 8,
        "sweep scenes: fig3.8, fig4.9b, fig4.9b-models, fig4.10, fig5.8, fig5.9, fig6.3, fig6.5"
    );
}
