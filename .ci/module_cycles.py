#!/usr/bin/env python3
"""Fail when the modules of a crate import each other in a cycle.

A module may use the modules below it, never one that (directly or through others) uses it
back: that keeps the layers of the library (and of the command line) in one direction, so a
room can be changed or tested without the ones above it.

Checked for each crate root given (default: the library `src/` and the command line
`cli/src/`), at every depth: among the top-level modules (`data`, `synth`, ...: `src/data/**` is
one node), among the children of each top-level module (`study::metrics`, `study::spec`, ...),
among the children of each of those (`data::import::rows`, `data::import::table`, ...), and so
on down to the deepest file. At each depth a module's subtree is one node and only siblings
(children of one parent) are compared: a path between cousins is a path between their
ancestors, checked a level up.

A dependency is any path through `crate::`, `super::` or `self::` in code (comments and string
literals are ignored): `use` trees and paths written inline. A path through a re-export
(`crate::study::Prepared`, re-exported from `study::sweep`) counts as a dependency on the module
that defines the item. A module's own `mod.rs` may use its children and they may use it (that
is what declaring, re-exporting and a shared error type are), so paths between a parent and its
children do not count. Unit-test modules (`#[cfg(test)] mod tests { ... }`) are left out: they
are not part of the library's layers, and a test may build its fixture with a layer above the
code it tests (a synthetic world for a fit, say).

Prints every cycle found (one per line) and exits 1 if there is any, else prints a summary and
exits 0. `--self-test` checks the checker on small crates written to a temporary directory (a
cycle three levels deep is found; a parent and its children using each other is not one).
"""

import os
import re
import sys
import tempfile

from rust_source import code_only

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def module_of(root, path):
    """Module path of a source file (`src/data/mod.rs` -> ['data'])."""
    rel = os.path.relpath(path, root)[:-3].split(os.sep)
    if rel[-1] == "mod" or rel == ["lib"] or rel == ["main"]:
        rel = rel[:-1]
    return rel


def expand_use(tree):
    """Paths of a `use` tree (`a::{b, c::{d}}` -> ['a::b', 'a::c::d'])."""
    tree = re.sub(r"\s+", "", tree)
    m = re.match(r"^(.*?)\{(.*)\}$", tree)
    if not m:
        return [re.sub(r"\bas\w.*$", "", tree)]
    prefix, body = m.group(1), m.group(2)
    parts, depth, cur = [], 0, ""
    for ch in body:
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += ch == "{"
        depth -= ch == "}"
        cur += ch
    parts.append(cur)
    return [p for part in parts if part for p in expand_use(prefix + part)]


def paths_in(text, file_module):
    """(module-of-the-code, absolute path) for every crate-relative path in a stripped source."""
    # Inline modules (`mod tests { ... }`) change what `super` and `self` mean.
    stack, depth, found = [], 0, []
    tokens = re.finditer(
        r"\bmod\s+(" + IDENT + r")\s*\{|\{|\}|\buse\s+([^;]*);|\b((?:crate|super|self)(?:\s*::\s*" + IDENT + r")+)",
        text,
    )
    for t in tokens:
        s = t.group(0)
        if t.group(1):
            depth += 1
            stack.append((t.group(1), depth))
        elif s == "{":
            depth += 1
        elif s == "}":
            if stack and stack[-1][1] == depth:
                stack.pop()
            depth -= 1
        else:
            if any(name == "tests" for name, _ in stack):
                continue
            here = file_module + [name for name, _ in stack]
            raw = expand_use(t.group(2)) if t.group(2) else [s]
            for p in raw:
                segs = [x for x in re.split(r"\s*::\s*", p.strip()) if x]
                if not segs or segs[0] not in ("crate", "super", "self"):
                    continue
                if segs[0] == "crate":
                    absolute = segs[1:]
                else:
                    base = list(here)
                    while segs and segs[0] in ("super", "self"):
                        if segs.pop(0) == "super":
                            base = base[:-1]
                    absolute = base + segs
                found.append((here, absolute))
    return found


def cycles(edges):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, on, stack, out, counter = {}, {}, set(), [], [], [0]
    nodes = sorted(set(edges) | {v for vs in edges.values() for v in vs})

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in nodes:
        if v not in index:
            visit(v)
    return out


def witness(edges, comp, refs, start):
    """One shortest cycle through `start`, with a file that makes each step."""
    prev, queue = {start: None}, [start]
    while queue:
        v = queue.pop(0)
        for w in sorted(edges.get(v, ())):
            if w == start:
                path = [v]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                path = list(reversed(path)) + [start]
                return " -> ".join(
                    f"{a} ({refs[(a, b)]})" for a, b in zip(path, path[1:])
                ) + f" -> {start}"
            if w in comp and w not in prev:
                prev[w] = v
                queue.append(w)
    return " <-> ".join(comp)


def check(root):
    files = []
    for d, _, fs in os.walk(root):
        files += [os.path.join(d, f) for f in fs if f.endswith(".rs")]
    modules = {tuple(module_of(root, f)) for f in files}
    sources = {f: code_only(open(f).read()) for f in files}
    # Re-exports (`pub use sweep::Prepared;` in study/mod.rs) lead to the module that defines
    # the item: `crate::study::Prepared` is a dependency on `study::sweep`.
    reexports = {}
    for f in files:
        here = module_of(root, f)
        for m in re.finditer(r"\bpub(?:\([^)]*\))?\s+use\s+([^;]*);", sources[f]):
            for q in expand_use(m.group(1)):
                alias = re.search(r"\bas\s+(" + IDENT + r")\s*$", q)
                bare = re.sub(r"\s+as\s+\w+\s*$", "", q).strip()
                segs = [x for x in re.split(r"\s*::\s*", bare) if x]
                if not segs or segs[-1] in ("*", "self"):
                    continue
                name = alias.group(1) if alias else segs[-1]
                if segs[0] == "crate":
                    target = segs[1:]
                else:
                    target = list(here)
                    while segs and segs[0] in ("super", "self"):
                        if segs.pop(0) == "super":
                            target = target[:-1]
                    target += segs
                reexports[tuple(here) + (name,)] = target

    # Every module and every module above one (a file's ancestors), as path tuples.
    prefixes = {m[:k] for m in modules for k in range(1, len(m) + 1)}
    depth = max((len(m) for m in modules), default=0)

    def resolve(path):
        for _ in range(8):
            for k in range(len(path), 0, -1):
                key = tuple(path[:k])
                if key in reexports and key not in modules and reexports[key] != list(key):
                    path = reexports[key] + list(path[k:])
                    break
            else:
                return path
        return path

    def node(path, level):
        """The module at depth `level` (1 = a top-level module) that `path` lies in, or None
        when the path is shorter or leads to no module that deep (an item of a parent)."""
        path = resolve(list(path))
        if len(path) < level or tuple(path[:level]) not in prefixes:
            return None
        return "::".join(path[:level])

    problems = []
    for level in range(1, depth + 1):
        edges, refs = {}, {}
        for f in sorted(files):
            for here, path in paths_in(sources[f], module_of(root, f)):
                a, b = node(here, level), node(path, level)
                if a is None or b is None or a == b:
                    continue
                # Siblings only: the children of one module, each with its subtree as one node
                # (a path to a cousin is a path between their ancestors, a level up).
                if a.rsplit("::", 1)[:-1] != b.rsplit("::", 1)[:-1]:
                    continue
                edges.setdefault(a, set()).add(b)
                refs.setdefault((a, b), os.path.relpath(f))
        for comp in cycles(edges):
            problems.append(f"{root}: modules in a cycle: {', '.join(comp)}")
            # Every mutual pair, then one longer cycle through the rest, each step with a file.
            pairs = [
                (a, b)
                for a in comp
                for b in comp
                if a < b and b in edges.get(a, ()) and a in edges.get(b, ())
            ]
            for a, b in pairs:
                problems.append(f"    {a} ({refs[(a, b)]}) <-> {b} ({refs[(b, a)]})")
            for start in comp:
                if not any(start in pair for pair in pairs):
                    problems.append(f"    {witness(edges, comp, refs, start)}")
        n = sum(len(v) for v in edges.values())
        print(
            f"{root}: level {level}: {len(set(edges) | {v for vs in edges.values() for v in vs})} "
            f"modules, {n} dependencies, {len(cycles(edges))} cycle(s)"
        )
    return problems


def self_test():
    """The checker on small crates: a cycle at depth 3 is found, parent <-> child is allowed."""
    crates = {
        "deep cycle": (
            {
                "lib.rs": "pub mod a;",
                "a/mod.rs": "pub mod b; pub struct Shared;",
                "a/b/mod.rs": "mod x; mod y; mod z;",
                "a/b/x.rs": "use super::y::Y; pub struct X;",
                "a/b/y.rs": "pub struct Y; fn f() { let _ = super::z::Z; }",
                "a/b/z.rs": "pub struct Z; use crate::a::b::x::X;",
            },
            ["a::b::x, a::b::y, a::b::z"],
        ),
        "parent and children": (
            {
                "lib.rs": "pub mod a;",
                "a/mod.rs": "mod x; mod y; pub use self::x::X; pub struct Shared;",
                "a/x.rs": "use super::Shared; use super::y::Y; pub struct X;",
                "a/y.rs": "pub struct Y; /* use super::x::X; */ const S: &str = \"super::x::X\";",
            },
            [],
        ),
    }
    failures = 0
    for name, (files, want) in crates.items():
        with tempfile.TemporaryDirectory() as root:
            for rel, text in files.items():
                os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
                with open(os.path.join(root, rel), "w") as f:
                    f.write(text)
            got = [
                p.split("modules in a cycle: ", 1)[1]
                for p in check(root)
                if "modules in a cycle: " in p
            ]
        if got != want:
            print(f"self-test {name}: found {got}, expected {want}")
            failures += 1
    print("self-test:", "failed" if failures else "passed")
    return 1 if failures else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) == 1:
        os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    roots = sys.argv[1:] or [r for r in ("src", "cli/src") if os.path.isdir(r)]
    problems = [p for r in roots for p in check(r)]
    for p in problems:
        print(p)
    if problems:
        print("module import cycles: move the shared item down a layer")
        return 1
    print("no module import cycles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
