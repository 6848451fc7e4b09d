//! Snapshots of every scene's exported CSV (quick mode), compared with stored fixtures in
//! `tests/fixtures/snapshots/<id>.csv` row by row: the same panel, series and style, and
//! numbers equal to 1e-7 relative (plus 1e-12 of the column's range, for values near zero).
//! Regenerate after an intended change with `UPDATE_SNAPSHOTS=1 cargo test --release snapshots`
//! and review the diff.

use adhesion::job::Job;
use adhesion::render::data::{csv, parse_csv};
use adhesion::scenes;

use crate::common::root;

const REL_TOL: f64 = 1e-7;

#[test]
fn exported_csv_matches_the_stored_fixtures() {
    let update = std::env::var_os("UPDATE_SNAPSHOTS").is_some();
    let dir = root().join("tests/fixtures/snapshots");
    let mut failures = Vec::new();
    for s in scenes::all() {
        let id = s.info().id;
        let values = s.quick(&s.defaults()).unwrap();
        let fig = s
            .run(&values, &Job::quiet())
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        let got = csv(&fig);
        let path = dir.join(format!("{id}.csv"));
        if update {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &got).unwrap();
            continue;
        }
        let Ok(stored) = std::fs::read_to_string(&path) else {
            failures.push(format!(
                "{id}: no fixture {} (run with UPDATE_SNAPSHOTS=1)",
                path.display()
            ));
            continue;
        };
        if let Err(e) = compare(&parse_csv(&stored).unwrap(), &parse_csv(&got).unwrap()) {
            failures.push(format!("{id}: {e}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

type Row = (usize, String, String, f64, f64);

fn compare(expected: &[Row], got: &[Row]) -> Result<(), String> {
    if expected.len() != got.len() {
        return Err(format!("{} rows, expected {}", got.len(), expected.len()));
    }
    let span = |f: fn(&Row) -> f64| {
        let (lo, hi) = expected
            .iter()
            .map(f)
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        (hi - lo).abs().max(f64::MIN_POSITIVE)
    };
    let (sx, sy) = (span(|r| r.3), span(|r| r.4));
    for (k, (e, g)) in expected.iter().zip(got).enumerate() {
        if (e.0, &e.1, &e.2) != (g.0, &g.1, &g.2) {
            return Err(format!(
                "row {}: {:?} vs expected {:?}",
                k + 2,
                (g.0, &g.1, &g.2),
                (e.0, &e.1, &e.2)
            ));
        }
        for (a, b, s) in [(g.3, e.3, sx), (g.4, e.4, sy)] {
            let ok = (a.is_nan() && b.is_nan()) || (a - b).abs() <= REL_TOL * b.abs() + 1e-12 * s;
            if !ok {
                return Err(format!("row {} ({} {}): {a} vs expected {b}", k + 2, e.1, e.2));
            }
        }
    }
    Ok(())
}
