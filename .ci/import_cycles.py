#!/usr/bin/env python3
"""Fails on an import circle among the top-level modules of a crate.

For each `.rs` file under SRC (default crates/cli/src), the top-level module it belongs to is
the first component of its path (`serve/api.rs` -> `serve`; `lib.rs` and `main.rs` are the
crate root and left out). Every `crate::NAME` it names, and every `super::NAME` that leaves its
own top-level module, is an edge to module NAME. Test modules (from a `#[cfg(test)]` line to
the end of the file) are skipped: tests may reach across. Prints the edges and exits with
status 1 naming a cycle when the graph has one.

Usage: .ci/import_cycles.py [SRC ...]
"""

import pathlib
import re
import sys


def top_level(src: pathlib.Path, path: pathlib.Path) -> list[str]:
    parts = list(path.relative_to(src).with_suffix("").parts)
    if parts[-1] == "mod":
        parts.pop()
    return parts


def edges_of(src: pathlib.Path) -> dict[str, set[str]]:
    modules = {p.stem if p.is_file() else p.name for p in src.iterdir()} - {"lib", "main"}
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for path in sorted(src.rglob("*.rs")):
        parts = top_level(src, path)
        if not parts or parts[0] in ("lib", "main"):
            continue
        here = parts[0]
        text = path.read_text()
        cut = text.find("#[cfg(test)]")
        if cut >= 0:
            text = text[:cut]
        code = "\n".join(line.split("//")[0] for line in text.splitlines())
        for name in re.findall(r"\bcrate::(\w+)", code):
            if name in modules and name != here:
                graph[here].add(name)
        # `super::` from a file `a/b.rs` (module a::b) names `a`'s items; only from a
        # top-level file (depth 1) does it reach the crate root's modules.
        if len(parts) == 1:
            for name in re.findall(r"\bsuper::(\w+)", code):
                if name in modules and name != here:
                    graph[here].add(name)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def main() -> int:
    roots = sys.argv[1:] or ["crates/cli/src"]
    status = 0
    for root in roots:
        src = pathlib.Path(root)
        graph = edges_of(src)
        for module in sorted(graph):
            print(f"{root}: {module} -> {', '.join(sorted(graph[module])) or '(nothing)'}")
        cycle = find_cycle(graph)
        if cycle:
            print(f"{root}: import circle: {' -> '.join(cycle)}", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
