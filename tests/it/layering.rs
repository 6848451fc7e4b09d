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

/// The module of a source file: `scenes::fig4::fe` for `src/scenes/fig4/fe.rs`, `` for
/// `src/lib.rs`; `None` for the binary's `src/main.rs`.
fn module_of(src: &std::path::Path, file: &std::path::Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?.with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    match parts.as_slice() {
        [only] if only == "main" => return None,
        [only] if only == "lib" => return Some(String::new()),
        _ => {}
    }
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    Some(parts.join("::"))
}

/// The paths of a `use` tree: `crate::a::{b, c::{d, e as f}}` gives `crate::a::b`,
/// `crate::a::c::d`, `crate::a::c::e`.
fn use_paths(tree: &str) -> Vec<String> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or(tree);
        return vec![path.trim().to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
    let (mut parts, mut depth, mut current) = (Vec::new(), 0, String::new());
    for c in inner.chars() {
        match c {
            ',' if depth == 0 => parts.push(std::mem::take(&mut current)),
            _ => {
                depth += i32::from(c == '{') - i32::from(c == '}');
                current.push(c);
            }
        }
    }
    parts.push(current);
    parts
        .iter()
        .filter(|p| !p.trim().is_empty())
        .flat_map(|p| use_paths(p).into_iter().map(|q| format!("{prefix}{q}")))
        .collect()
}

/// The modules each module of the library imports with its `use` lines (`crate::`, `super::`,
/// `self::` and child paths; a `use` inside a function or an inline module counts with its
/// `crate::` paths only).
fn import_graph(
    src: &std::path::Path,
) -> std::collections::BTreeMap<String, std::collections::BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: std::collections::BTreeMap<String, std::path::PathBuf> = files
        .into_iter()
        .filter_map(|f| Some((module_of(src, &f)?, f)))
        .collect();
    let segments = |m: &str| -> Vec<String> {
        m.split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .collect()
    };
    let mut graph = std::collections::BTreeMap::new();
    for (module, file) in &modules {
        let text = std::fs::read_to_string(file).unwrap();
        let mut edges = std::collections::BTreeSet::new();
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let body = line.trim_start();
            let body = match body.strip_prefix("pub") {
                Some(after) => after.trim_start_matches(|c| c != ' ').trim_start(),
                None => body,
            };
            let Some(first) = body.strip_prefix("use ") else {
                continue;
            };
            let mut statement = first.to_string();
            for next in &lines[i + 1..] {
                if statement.contains(';') {
                    break;
                }
                statement.push_str(next);
            }
            let tree = statement.split(';').next().unwrap_or("");
            let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
            let indented = line.starts_with([' ', '\t']);
            for path in use_paths(&tree) {
                let mut segs: Vec<String> = path.split("::").map(|s| s.trim().to_string()).collect();
                let mut full = segments(module);
                match segs.first().map(String::as_str) {
                    Some("crate") => {
                        full.clear();
                        segs.remove(0);
                    }
                    _ if indented => continue,
                    Some("self" | "super") => {
                        while let Some(s) = segs.first().filter(|s| *s == "self" || *s == "super") {
                            if s == "super" {
                                full.pop();
                            }
                            segs.remove(0);
                        }
                    }
                    Some(first)
                        if modules.contains_key(
                            &[segments(module), vec![first.to_string()]].concat().join("::"),
                        ) => {}
                    _ => continue,
                }
                full.extend(segs);
                if let Some(target) = (0..=full.len())
                    .rev()
                    .map(|k| full[..k].join("::"))
                    .find(|m| modules.contains_key(m))
                    .filter(|m| m != module)
                {
                    edges.insert(target);
                }
            }
        }
        graph.insert(module.clone(), edges);
    }
    graph
}

/// No two modules of the library import each other, directly or round a circle (the terminal
/// UI's state and its drawing, the errors and the parameters, a parent that re-exported its
/// children's items while they used its helpers were such circles): checked on the `use` lines
/// of `src/`, a parent and its children included. All circles are listed.
#[test]
fn no_import_circle_in_src() {
    let graph = import_graph(&root().join("src"));
    assert!(graph.len() > 100, "{} modules read", graph.len());
    assert!(
        graph["scenes::fig4::fe"].contains("scenes::groups"),
        "{:?}",
        graph["scenes::fig4::fe"]
    );
    // Depth-first search; every edge back to a module on the current path closes a circle.
    fn visit<'a>(
        node: &'a str,
        graph: &'a std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
        state: &mut std::collections::BTreeMap<&'a str, bool>,
        path: &mut Vec<&'a str>,
        circles: &mut Vec<String>,
    ) {
        match state.get(node) {
            Some(true) => {
                let from = path.iter().position(|m| *m == node).unwrap_or(0);
                circles.push([&path[from..], &[node]].concat().join(" -> "));
                return;
            }
            Some(false) => return,
            None => {}
        }
        state.insert(node, true);
        path.push(node);
        for next in &graph[node] {
            visit(next, graph, state, path, circles);
        }
        path.pop();
        state.insert(node, false);
    }
    let (mut state, mut circles) = (std::collections::BTreeMap::new(), Vec::new());
    for module in graph.keys() {
        visit(module, &graph, &mut state, &mut Vec::new(), &mut circles);
    }
    assert!(circles.is_empty(), "import circles:\n{}", circles.join("\n"));
}
