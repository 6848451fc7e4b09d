//! Snapshots of every scene's exported CSV (quick mode), compared with stored fixtures in
//! `tests/fixtures/snapshots/<id>.csv` row by row: the same panel, series and style, and
//! numbers equal to 1e-7 relative (plus 1e-12 of the column's range, for values near zero).
//! Regenerate after an intended change with `UPDATE_SNAPSHOTS=1 cargo test --release snapshots`
//! and review the diff. The same quick figures are checked for legends that cover data.

use std::sync::OnceLock;

use adhesion::figure::Figure;
use adhesion::job::Job;
use adhesion::render::data::{csv, parse_csv};
use adhesion::scenes;

use crate::common::root;

const REL_TOL: f64 = 1e-7;

/// Every scene's figure in quick mode, computed once for the tests of this module.
fn quick_figures() -> &'static [(&'static str, Figure)] {
    static FIGS: OnceLock<Vec<(&'static str, Figure)>> = OnceLock::new();
    FIGS.get_or_init(|| {
        scenes::all()
            .iter()
            .map(|s| {
                let id = s.info().id;
                let values = s.quick(&s.defaults()).unwrap();
                let fig = s
                    .run(&values, &Job::quiet())
                    .unwrap_or_else(|e| panic!("{id}: {e}"));
                (id, fig)
            })
            .collect()
    })
}

/// No legend box, nor the box of a panel's notes, holds a series point or a marker, in any
/// panel of any scene (the placement as the PNG renderer computes it); the two boxes do not
/// overlap.
#[test]
fn legends_cover_no_data_point_in_any_scene() {
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        for (k, layout) in adhesion::render::plot::panel_layouts(fig).into_iter().enumerate() {
            let Some(layout) = layout else { continue };
            for (what, b) in [("legend", layout.legend), ("notes", layout.notes)] {
                let Some((x0, y0, x1, y1)) = b else {
                    continue;
                };
                let inside = layout
                    .points
                    .iter()
                    .filter(|p| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
                    .count();
                if inside > 0 {
                    failures.push(format!("{id} panel {}: {inside} points under the {what}", k + 1));
                }
            }
            if let (Some(a), Some(b)) = (layout.legend, layout.notes)
                && a.0 < b.2
                && b.0 < a.2
                && a.1 < b.3
                && b.1 < a.3
            {
                failures.push(format!("{id} panel {}: the notes overlap the legend", k + 1));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn exported_csv_matches_the_stored_fixtures() {
    let update = std::env::var_os("UPDATE_SNAPSHOTS").is_some();
    let dir = root().join("tests/fixtures/snapshots");
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        let id = *id;
        let got = csv(fig);
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

/// Heat maps go into the SVG as embedded PNG images, not one rectangle per cell: figC.1 at its
/// default resolution (six maps) was 34 MB with 393 609 rectangles.
#[test]
fn fig_c1_svg_embeds_its_maps_and_stays_under_2_mb() {
    let scene = scenes::find("figC.1").expect("scene");
    let fig = scene.run(&scene.defaults(), &Job::quiet()).expect("run");
    let svg = adhesion::render::plot::svg_string(&fig).expect("svg");
    assert!(svg.len() < 2_000_000, "figC.1.svg is {} bytes", svg.len());
    assert_eq!(svg.matches("<image ").count(), 6, "one image per map");
    assert!(
        svg.matches("<rect").count() < 2_000,
        "{} rects",
        svg.matches("<rect").count()
    );
}
