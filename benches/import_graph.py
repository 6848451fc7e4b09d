#!/usr/bin/env python3
"""Import circles among the modules of `src/`.

Reads every `src/**/*.rs`, turns the `use crate::…`, `use super::…`, `use self::…` and
`use child::…` declarations and the `crate::…` / `super::…` paths written in code (comments and
strings left out) into edges between modules, and prints each circle with the lines that close
it. Exit status 1 when there is a circle between separate modules.

An edge is lifted to the two sibling modules that hold its ends (`cli -> headless::shard` counts
as `cli -> headless`), so a circle is one between parts of the same parent. A module and its own
submodules (`render::plot` and `render::plot::draw`) naming each other's items is Rust's way of
splitting one module into files; such circles are listed apart and not counted.

    python3 benches/import_graph.py              # use declarations and paths in code
    python3 benches/import_graph.py --use-only   # use declarations only
    python3 benches/import_graph.py --under tui --edges   # the graph of src/tui
"""

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent / "src"


def module_of(path: Path) -> tuple:
    """`src/tui/app.rs` -> ("tui", "app"); `src/lib.rs` -> (); `src/x/mod.rs` -> ("x",)."""
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts == ["lib"]:
        return ()
    if parts == ["main"]:
        return ("<main>",)
    if parts[-1] == "mod":
        parts.pop()
    return tuple(parts)


def strip_comments(text: str) -> list:
    """Lines with `//` comments and string literals blanked (line numbers kept)."""
    out = []
    in_block = False
    for line in text.split("\n"):
        s = line
        if in_block:
            end = s.find("*/")
            if end < 0:
                out.append("")
                continue
            s = s[end + 2 :]
            in_block = False
        s = re.sub(r'"(?:\\.|[^"\\])*"', '""', s)
        start = s.find("/*")
        if start >= 0 and s.find("*/", start) < 0:
            s = s[:start]
            in_block = True
        s = re.sub(r"/\*.*?\*/", "", s)
        cut = s.find("//")
        if cut >= 0:
            s = s[:cut]
        out.append(s)
    return out


def expand_use_tree(tree: str) -> list:
    """`a::{b::C, d}` -> [["a","b","C"], ["a","d"]]."""
    tree = re.sub(r"\s+as\s+\w+", "", tree)
    tree = re.sub(r"\s+", "", tree)

    def parse(s, i):
        # returns (list of paths, index after)
        prefix = []
        seg = ""
        while i < len(s):
            c = s[i]
            if c == "{":
                if seg:
                    prefix.append(seg)
                    seg = ""
                paths = []
                i += 1
                while True:
                    sub, i = parse(s, i)
                    paths.extend(sub)
                    if i < len(s) and s[i] == ",":
                        i += 1
                        continue
                    if i < len(s) and s[i] == "}":
                        i += 1
                    break
                return [prefix + p for p in paths], i
            if c in ",}":
                break
            if s.startswith("::", i):
                prefix.append(seg)
                seg = ""
                i += 2
                continue
            seg += c
            i += 1
        if seg:
            prefix.append(seg)
        return [prefix], i

    paths, _ = parse(tree, 0)
    return [[p for p in path if p] for path in paths]


def resolve(path: list, here: tuple, modules: set):
    """The module a use path names (the longest module prefix), or None for other crates."""
    if not path:
        return None
    head = path[0]
    if here and here[0] == "<main>":
        return None  # the binary reaches the library through `adhesion::`
    if head == "crate":
        base, rest = (), path[1:]
    elif head in ("super", "self"):
        base, rest = here, list(path)
        while rest and rest[0] in ("super", "self"):
            if rest[0] == "super":
                base = base[:-1]
            rest = rest[1:]
    elif here + (head,) in modules:
        base, rest = here, path
    else:
        return None
    best = base
    for k in range(1, len(rest) + 1):
        cand = base + tuple(rest[:k])
        if cand in modules:
            best = cand
        else:
            break
    return best


def read_edges(with_paths: bool):
    files = sorted(ROOT.rglob("*.rs"))
    modules = {module_of(f) for f in files}
    edges = {}  # (a, b) -> list of "file:line"
    for f in files:
        here_file = module_of(f)
        lines = strip_comments(f.read_text(encoding="utf-8"))
        stack = []  # inline modules: (name, depth at which it closes)
        depth = 0
        i = 0
        while i < len(lines):
            line = lines[i]
            here = here_file + tuple(name for name, _ in stack)
            m = re.match(r"\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*\{", line)
            stmt_paths = []
            lineno = i + 1
            u = re.match(r"\s*(?:pub(?:\([^)]*\))?\s+)?use\s+(.*)", line)
            if u:
                text = u.group(1)
                j = i
                while ";" not in text and j + 1 < len(lines):
                    j += 1
                    text += lines[j]
                text = text.split(";")[0]
                stmt_paths = expand_use_tree(text)
                consumed = lines[i : j + 1]
                i = j
            else:
                consumed = [line]
                if with_paths:
                    for p in re.finditer(r"\b((?:crate|super)(?:::\w+)+)", line):
                        stmt_paths.append(p.group(1).split("::"))
            for path in stmt_paths:
                # Items of an inline module (`mod tests`) belong to its file's module.
                target = resolve(path, here, modules | {here})
                src = here_file
                if target is None or target == src:
                    continue
                edges.setdefault((src, target), []).append(f"{f.relative_to(ROOT.parent)}:{lineno}")
            for text in consumed:
                depth += text.count("{") - text.count("}")
            if m:
                stack.append((m.group(1), depth - 1))
            while stack and depth <= stack[-1][1]:
                stack.pop()
            i += 1
    return modules, edges


def sccs(nodes, adj):
    """Tarjan's strongly connected components."""
    index, low, on, st, out = {}, {}, set(), [], []
    counter = [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        st.append(v)
        on.add(v)
        for w in adj.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = st.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(comp)

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


def name(m: tuple) -> str:
    return "::".join(m) if m else "crate"


def contains(a: tuple, b: tuple) -> bool:
    """Whether module `a` contains module `b` (is a proper ancestor)."""
    return len(a) < len(b) and b[: len(a)] == a


def siblings(a: tuple, b: tuple):
    """The two children of the closest common ancestor that hold `a` and `b`; None when one
    module contains the other (a file split, not a circle between parts)."""
    if contains(a, b) or contains(b, a) or a == b:
        return None
    k = 0
    while a[k] == b[k]:
        k += 1
    return a[: k + 1], b[: k + 1]


def circles(pairs):
    """Strongly connected components of more than one node."""
    adj = {}
    for a, b in pairs:
        adj.setdefault(a, []).append(b)
    return [c for c in sccs({m for p in pairs for m in p}, adj) if len(c) > 1]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--use-only", action="store_true", help="only use declarations, not paths in code")
    ap.add_argument("--under", default="", help="only modules under this one (e.g. tui)")
    ap.add_argument("--edges", action="store_true", help="print the edges as well")
    args = ap.parse_args()
    modules, edges = read_edges(not args.use_only)
    under = tuple(args.under.split("::")) if args.under else ()
    keep = lambda m: m[: len(under)] == under
    edges = {k: v for k, v in edges.items() if keep(k[0]) and keep(k[1])}
    if args.edges:
        for (a, b), where in sorted(edges.items()):
            print(f"{name(a)} -> {name(b)}   ({where[0]})")
        print()

    # Circles between parts: each edge lifted to the two sibling modules that hold its ends
    # (`cli -> headless::shard` is an edge `cli -> headless`); edges between a module and its
    # own submodules are left out here.
    lifted = {}
    for (a, b), where in edges.items():
        pair = siblings(a, b)
        if pair:
            lifted.setdefault(pair, []).append(((a, b), where))
    found = circles(set(lifted))
    print(f"import circles between separate modules: {len(found)}")
    for c in sorted(found, key=sorted):
        members = set(c)
        print("  circle: " + " <-> ".join(name(m) for m in sorted(c)))
        for pair, under_edges in sorted(lifted.items()):
            if pair[0] in members and pair[1] in members:
                for (a, b), where in sorted(under_edges):
                    more = f" (+{len(where) - 1})" if len(where) > 1 else ""
                    print(f"    {name(a)} -> {name(b)}   {where[0]}{more}")
    # A module and its own submodules naming each other's items.
    split = {(a, b) for (a, b) in edges if contains(a, b) or contains(b, a)}
    family = circles(split)
    print(f"circles between a module and its own submodules (file splits, not counted): {len(family)}")
    for c in sorted(family, key=sorted):
        print("  " + " <-> ".join(name(m) for m in sorted(c)))
    kind = "use declarations" if args.use_only else "use declarations and crate::/super:: paths in code"
    print(f"({len(modules)} modules, {len(edges)} edges; {kind})")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
