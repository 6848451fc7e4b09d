//! Every scene in quick mode at the edges of each declared parameter range, one parameter at
//! a time: every run should end with finite results or a one-line error naming a user
//! parameter, and none may panic. A survey (`#[ignore]`): it prints the runs that fail these
//! rules and the counts.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use adhesion::params::{Bound, ParamKind};
use adhesion::scenes;

/// Edge values of a numeric range: the bounds (nudged inside when exclusive), ±1e300 where open.
fn edges(kind: &ParamKind, min: Bound, max: Bound) -> Vec<f64> {
    let inside = |b: f64, up: bool| {
        let step = if b == 0.0 { 1e-300 } else { b.abs() * 1e-12 };
        if up { b + step } else { b - step }
    };
    let mut v = Vec::new();
    match min {
        Bound::Inclusive(lo) => v.push(lo),
        Bound::Exclusive(lo) => v.push(inside(lo, true)),
        Bound::Open if matches!(kind, ParamKind::Float) => v.push(-1e300),
        Bound::Open => {}
    }
    match max {
        Bound::Inclusive(hi) => v.push(hi),
        Bound::Exclusive(hi) => v.push(inside(hi, false)),
        Bound::Open if matches!(kind, ParamKind::Float) => v.push(1e300),
        Bound::Open => {}
    }
    if matches!(kind, ParamKind::Int) {
        v.iter_mut().for_each(|x| *x = x.round());
        // Counts at the top of their range would run for hours even in quick mode.
        v.retain(|x| *x <= 4096.0);
    }
    v
}

/// Runs of the sweep: (runs, finite, errors naming a parameter, other outcomes as text, panics).
fn sweep() -> (usize, usize, usize, Vec<String>, usize) {
    let (mut runs, mut finite, mut named, mut bad, mut panics) = (0, 0, 0, Vec::new(), 0);
    for scene in scenes::all() {
        let id = scene.info().id;
        if id.starts_with("fig4") {
            continue;
        }
        let base = scene.defaults();
        for spec in scene.specs() {
            if !matches!(spec.kind, ParamKind::Float | ParamKind::Int) {
                continue;
            }
            for x in edges(&spec.kind, spec.range.min, spec.range.max) {
                let text = if matches!(spec.kind, ParamKind::Int) {
                    format!("{}={}", spec.name, x as i64)
                } else {
                    format!("{}={x:e}", spec.name)
                };
                let mut values = base.clone();
                runs += 1;
                let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    values.set_assignment(&text)?;
                    scene.validate(&values)?;
                    let values = scene.quick(&values)?;
                    let flag = Arc::new(AtomicBool::new(false));
                    let timer = {
                        let flag = flag.clone();
                        std::thread::spawn(move || {
                            std::thread::sleep(std::time::Duration::from_secs(20));
                            flag.store(true, Ordering::Relaxed);
                        })
                    };
                    drop(timer);
                    let job = adhesion::job::Job::quiet().with_cancel_flag(flag);
                    scene.run(&values, &job)
                }));
                match outcome {
                    Err(_) => {
                        panics += 1;
                        bad.push(format!("{id} {text}: PANIC"));
                    }
                    Ok(Ok(fig)) => {
                        let nonfinite: Vec<&str> = fig
                            .results
                            .iter()
                            .filter(|(_, v)| !v.is_finite())
                            .map(|(n, _)| n.as_str())
                            .collect();
                        if nonfinite.is_empty() {
                            finite += 1;
                        } else {
                            bad.push(format!("{id} {text}: non-finite {nonfinite:?}"));
                        }
                    }
                    Ok(Err(e)) => {
                        let msg = e.to_string();
                        let names_user = scene
                            .specs()
                            .iter()
                            .any(|s| msg.contains(&format!("`{}`", s.name)));
                        if names_user && !msg.contains('\n') && msg.len() < 400 {
                            named += 1;
                        } else {
                            bad.push(format!("{id} {text}: error `{msg}`"));
                        }
                    }
                }
            }
        }
    }
    (runs, finite, named, bad, panics)
}

// Every scene except chapter 4's (expensive; their quick mode runs in the presets test) at
// each edge of each numeric range, one parameter at a time, in quick mode (about 340 runs, a
// few seconds): none panics, and each run ends within its time bound (the job is cancelled
// after 20 s).
#[test]
fn no_scene_panics_at_the_edges_of_its_ranges() {
    let (runs, _, _, bad, panics) = sweep();
    let list: Vec<&String> = bad.iter().filter(|b| b.ends_with("PANIC")).collect();
    assert_eq!(panics, 0, "{panics} of {runs} runs panicked: {list:?}");
    assert!(runs > 300, "only {runs} runs");
}

// The survey of the same sweep: prints every run that ends with non-finite results or with an
// error that names no user parameter, and the counts.
#[test]
#[ignore = "survey: prints the runs that break the rules (seconds)"]
fn survey_of_every_scene_at_the_edges_of_its_ranges() {
    let (runs, finite, named, bad, panics) = sweep();
    for b in &bad {
        println!("{b}");
    }
    println!(
        "{runs} runs: {finite} finite, {named} one-line errors naming a parameter, {} other, {panics} panics",
        bad.len()
    );
}
