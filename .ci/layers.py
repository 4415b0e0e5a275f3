#!/usr/bin/env python3
"""Checks that src/ is a data flow: every `crate::` path (use lines and inline paths, `super::`
included) points to a file in the same or an earlier layer, and no two files import each other
through any chain (no cycle in the file graph; a `pub use` re-export counts as an import).

Layers, earliest first (the order in docs/method.md):
  model -> discrete -> solve -> strategy -> cases -> store -> sweep -> limits -> fit -> report
  -> render -> bench -> cli -> main.rs
lib.rs may re-export anything. The command line (src/cli/, src/main.rs) is the binary crate: its
`ehlmap::` paths are the library's, its `crate::cli::` paths its own. Exit 1 with one line per
violation."""
import os
import re
import sys

LAYERS = ["model", "discrete", "solve", "strategy", "cases", "store", "sweep", "limits", "fit",
          "report", "render", "bench", "cli"]
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")


def module_files():
    """module path (tuple) -> file path, for every .rs file under src/."""
    out = {}
    for d, _, fs in os.walk(ROOT):
        for f in fs:
            if not f.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(d, f), ROOT)[:-3].split(os.sep)
            if rel in (["lib"], ["main"]):
                mod = (rel[0],)
            elif rel[-1] == "mod":
                mod = tuple(rel[:-1])
            else:
                mod = tuple(rel)
            out[mod] = os.path.join(d, f)
    return out


def strip_comments(src):
    src = re.sub(r"/\*.*?\*/", "", src, flags=re.S)
    return "\n".join(line.split("//")[0] for line in src.splitlines())


PATH = re.compile(r"\b(crate|ehlmap|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)(::\{[^;]*?\})?")


def targets(mod, text, mods):
    """The files a file refers to through crate::, super:: and self:: paths."""
    found = set()
    for m in PATH.finditer(text):
        head, rest, group = m.group(1), m.group(2), m.group(3)
        if not rest and not group:
            continue
        parts = [p for p in rest.split("::") if p]
        here = [] if mod in (("lib",), ("main",)) else list(mod)
        if head in ("crate", "ehlmap"):
            base = []
        elif head == "self":
            base = here
        else:
            base = here[:-1]
            while parts and parts[0] == "super":
                parts.pop(0)
                base = base[:-1]
        paths = [base + parts]
        if group:
            inner = group[3:-1]
            for item in re.split(r",(?![^{]*\})", inner):
                item = item.strip().split(" as ")[0]
                if item and item != "self":
                    paths.append(base + parts + [p for p in re.split(r"::", item) if p and not p.startswith("{")])
        for p in paths:
            for k in range(len(p), 0, -1):
                if tuple(p[:k]) in mods:
                    found.add(tuple(p[:k]))
                    break
    # 2018-edition relative paths to a child module (`use ctx::Ctx;` in spec.rs with `mod ctx;`)
    here = [] if mod in (("lib",), ("main",)) else list(mod)
    for m in re.finditer(r"(?<![A-Za-z0-9_:])([a-z_][a-z0-9_]*)::", text):
        child = tuple(here + [m.group(1)])
        if child in mods:
            found.add(child)
    found.discard(mod)
    return found


def layer(mod):
    if mod[0] in ("lib", "main"):
        return len(LAYERS) if mod[0] == "main" else None
    return LAYERS.index(mod[0]) if mod[0] in LAYERS else -1


def main():
    mods = module_files()
    bad = []
    graph = {}
    for mod, path in sorted(mods.items()):
        text = strip_comments(open(path, encoding="utf-8").read())
        graph[mod] = targets(mod, text, mods)
        if layer(mod) == -1:
            bad.append(f"{path}: top-level module {mod[0]} is not in the layer list")
    for mod, outs in graph.items():
        lm = layer(mod)
        if lm is None:
            continue
        for t in sorted(outs):
            lt = layer(t)
            if lt is None or (lt is not None and lt > lm):
                bad.append(f"{'::'.join(mod)} imports {'::'.join(t)}: up the layer list")
    # cycles: Tarjan's strongly connected components
    index, low, stack, on, sccs = {}, {}, [], set(), []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                strong(w)
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
                sccs.append(comp)

    sys.setrecursionlimit(10000)
    for v in list(graph):
        if v not in index:
            strong(v)
    for comp in sccs:
        bad.append("import cycle: " + ", ".join(sorted("::".join(c) for c in comp)))
    for b in bad:
        print(b)
    n_edges = sum(len(v) for v in graph.values())
    print(f"layers: {len(graph)} files, {n_edges} imports, {len(bad)} violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
