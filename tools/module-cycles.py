#!/usr/bin/env python3
"""Module circles of the workspace's no_std crates.

Lists the module-level `crate::` / `super::` edges of each crate's src/ (test modules
left out: everything from `#[cfg(test)]` on in a file, and files named tests.rs) and
prints every circle: strongly connected groups of top-level modules (the layers), and
of files. Exit status 1 when a crate has a circle between its top-level modules.

A few nested modules may be layers of their own (SUBLAYERS). (A language's standard
cycles, which build the engine's cycle specifications, were one while they lived in
interp-core's lang::siemens; they are interp-siemens's `cycles` now.)

Usage: tools/module-cycles.py [--edges] [CRATE_DIR ...]   (default: canon interp-core motion-core)
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATH = re.compile(r"\b(crate|super)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
# Nested modules that are layers of their own, per crate.
SUBLAYERS = {}
USE_GROUP = re.compile(r"\buse\s+(crate|super)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{([^;]*)\}", re.S)


def modules(src):
    """Module path (tuple) of every .rs file under src."""
    out = {}
    for d, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(d, f), src).replace(os.sep, "/")[:-3].split("/")
            if rel[-1] in ("mod", "lib", "main"):
                rel = rel[:-1]
            out[tuple(rel)] = os.path.join(d, f)
    return out


def code_of(path):
    """The file without comments and without its test module."""
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"//[^\n]*", "", text)
    cut = re.search(r"#\[cfg\(test\)\]\s*(pub\s+)?mod\s+\w+\s*\{", text)
    return text[: cut.start()] if cut else text


def targets(mod, text, mods):
    """Modules `mod` names through crate:: or super:: paths."""
    found = set()
    paths = [(m.group(1), m.group(2)) for m in PATH.finditer(text)]
    for m in USE_GROUP.finditer(text):
        for item in re.split(r"[,\s{}]+", m.group(3)):
            name = item.split("::")[0]
            if name and name not in ("self", "*"):
                paths.append((m.group(1), m.group(2) + "::" + name))
            elif name == "self":
                paths.append((m.group(1), m.group(2)))
    for base, rest in paths:
        parts = [p for p in rest.split("::") if p]
        start = () if base == "crate" else (mod[:-1] if mod in mods and not is_dir_mod(mod, mods) else mod[:-1])
        while parts and parts[0] == "super":
            start, parts = start[:-1], parts[1:]
        full = start + tuple(parts)
        # the longest prefix that is a module file
        for n in range(len(full), 0, -1):
            if full[:n] in mods:
                if full[:n] != mod:
                    found.add(full[:n])
                break
    return found


def is_dir_mod(mod, mods):
    return any(k[: len(mod)] == mod and len(k) > len(mod) for k in mods)


def sccs(graph):
    """Tarjan's strongly connected components of size > 1."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
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

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main(args):
    show_edges = "--edges" in args
    crates = [a for a in args if not a.startswith("--")] or ["canon", "interp-core", "motion-core"]
    bad = False
    for crate in crates:
        src = os.path.join(ROOT, crate, "src")
        mods = modules(src)
        subs = SUBLAYERS.get(os.path.basename(os.path.normpath(crate)), [])

        def layer(m):
            for sub in subs:
                if m[: len(sub)] == sub:
                    return "::".join(sub)
            return m[0]

        files, top = {}, {}
        for mod, path in mods.items():
            if mod and mod[-1] == "tests":
                continue
            # `super::` in a file module (a.rs or a/b.rs) is its parent; in a/mod.rs too.
            deps = targets(mod, code_of(path), mods)
            files[mod] = {d for d in deps if not (d and d[-1] == "tests")}
            if not mod:
                continue
            for d in files[mod]:
                if d and layer(d) != layer(mod):
                    top.setdefault(layer(mod), set()).add(layer(d))
        print(f"== {crate}")
        if show_edges:
            for a in sorted(top):
                print(f"  {a} -> {', '.join(sorted(top[a]))}")
        layer_circles = sccs(top)
        for c in layer_circles:
            print(f"  circle of modules ({len(c)}): {' <-> '.join(c)}")
        file_circles = [c for c in sccs(files) if len({layer(m) for m in c if m}) > 1]
        for c in file_circles:
            print(f"  circle of files ({len(c)}): " + " ".join("::".join(m) or "lib" for m in c))
        if not layer_circles and not file_circles:
            print("  no circles")
        bad |= bool(layer_circles)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
