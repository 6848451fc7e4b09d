//! The solver core stays independent of the front ends: nothing in numerics, models, scenes or
//! the figure/job/params plumbing uses ratatui, crossterm, plotters, threads or channels.
//! Also checks that CI runs exactly the README's test command.

use crate::common::root;

fn rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

#[test]
fn solver_core_does_not_use_front_end_crates() {
    let src = root().join("src");
    let mut files = Vec::new();
    for d in ["numerics", "models", "scenes"] {
        rust_files(&src.join(d), &mut files);
    }
    for f in [
        "numerics.rs",
        "models.rs",
        "scenes.rs",
        "figure.rs",
        "job.rs",
        "params.rs",
        "error.rs",
    ] {
        files.push(src.join(f));
    }
    let forbidden = [
        "ratatui",
        "crossterm",
        "plotters",
        "std::thread",
        "mpsc",
        "println!",
        "eprintln!",
    ];
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        for word in forbidden {
            assert!(!text.contains(word), "{} uses `{word}`", f.display());
        }
    }
}

#[test]
fn readme_test_command_is_ci() {
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let command = ci
        .lines()
        .rev()
        .find(|l| !l.starts_with('#') && !l.trim().is_empty())
        .unwrap();
    assert!(command.starts_with("cargo "), "last line of .ci/run: {command}");
    assert!(
        readme.contains(&format!("```sh\n{command}\n```")),
        "README does not show `{command}` as its test command"
    );
}
