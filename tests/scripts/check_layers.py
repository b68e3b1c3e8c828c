#!/usr/bin/env python3
"""The source folders form a stack (docs/architecture.md): a file includes only its own folder's files and
those of the folders below it; the case types know only their own folder and cases/common (the registry
knows them all); and no chain of includes between files comes back to where it started.

Usage: check_layers.py SRC_DIR. Prints each breach and exits 1 if there is one."""
import os
import re
import sys

# lowest first; folders on one line are side by side and must not include each other
LAYERS = [["core"], ["geometry"], ["dem", "lbm"], ["coupling"], ["parallel"], ["scenario"], ["analysis"], ["io"],
          ["sim"], ["cases"], ["app"]]
RANK = {folder: i for i, row in enumerate(LAYERS) for folder in row}
GENERATED = {"sabo"}  # sabo/version.h, written by CMake
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def files(src):
    for root, _, names in os.walk(src):
        for name in names:
            if name.endswith((".h", ".cpp")):
                yield os.path.relpath(os.path.join(root, name), src)


def breaches(src):
    graph, found = {}, []
    for f in sorted(files(src)):
        with open(os.path.join(src, f), encoding="utf-8") as text:
            includes = INCLUDE.findall(text.read())
        graph[f] = [i for i in includes if os.path.exists(os.path.join(src, i))]
        top = f.split("/")[0]
        for inc in includes:
            to = inc.split("/")[0]
            if to in GENERATED or to == top:
                if top == "cases" and to == "cases":
                    mine, theirs = f.split("/")[1], inc.split("/")[1]
                    if f != "cases/registry.cpp" and theirs not in (mine, "common") and "." not in theirs:
                        found.append(f"{f} includes {inc}: a case type knows only its folder and cases/common")
                    if mine == "common" and theirs != "common":
                        found.append(f"{f} includes {inc}: cases/common knows no case type")
                continue
            if to not in RANK:
                found.append(f"{f} includes {inc}: folder '{to}' is in no layer")
            elif RANK[to] >= RANK.get(top, -1):
                found.append(f"{f} includes {inc}: '{to}' is not below '{top}'")
    # circles between files
    state = {}

    def visit(node, path):
        state[node] = 1
        for nxt in graph.get(node, []):
            if state.get(nxt) == 1:
                found.append("circle: " + " -> ".join(path[path.index(nxt):] + [nxt]) if nxt in path
                             else f"circle through {nxt}")
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = 2

    for node in graph:
        if node not in state:
            visit(node, [node])
    return found


def main():
    src = sys.argv[1]
    found = breaches(src)
    for line in found:
        print(line)
    print(f"layers: {len(list(files(src)))} files, {len(found)} breaches")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
