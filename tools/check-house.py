#!/usr/bin/env python3
"""check-house.py BUILD_DIR — the house's arrows run one way.

A unit is a source file with its header (src/pipeline/clip.c and clip.h),
or a header alone. Unit A uses unit B when one of A's files includes one of
B's (#include "…"), or when A's object calls or reads a symbol that B's
object defines (nm of BUILD_DIR/src/**/*.o). A room is a folder of src/
(src/app/view/ belongs to src/app/). The check fails, naming the arrows,
when
  - units use each other in a loop (a cycle of files),
  - rooms use each other in a loop,
  - the program's render and view code (src/app/ apart from the studies'
    commands bench and truth) uses anything of src/studies/.
Prints one line "house: ..." when all holds. Python's standard library and
binutils' nm only."""

import os
import re
import subprocess
import sys

SRC = "src"
STUDY_COMMANDS = {"src/app/bench", "src/app/truth"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def units_of_tree():
    """unit -> its files."""
    units = {}
    for root, _, files in os.walk(SRC):
        for name in files:
            if name.endswith((".c", ".h")):
                path = os.path.join(root, name)
                units.setdefault(os.path.splitext(path)[0], []).append(path)
    return units


def resolve(including, target):
    for base in (os.path.dirname(including), SRC):
        path = os.path.normpath(os.path.join(base, target))
        if os.path.exists(path):
            return path
    return None  # a public header, or a system one: not a unit


def room_of(unit):
    parts = unit.split("/")
    return "/".join(parts[:2])


def symbols(obj):
    out = subprocess.run(["nm", "-P", obj], capture_output=True, text=True, check=True).stdout
    defined, used = set(), set()
    for line in out.splitlines():
        fields = line.split()
        if len(fields) < 2:
            continue
        name, kind = fields[0], fields[1]
        if kind == "U":
            used.add(name)
        elif kind.isupper() and kind not in "NW":
            defined.add(name)
    return defined, used


def arrows(units, build):
    """(a, b) -> why, for every unit a that uses unit b."""
    edges = {}
    for unit, files in units.items():
        for path in files:
            with open(path, encoding="utf-8") as f:
                for target in INCLUDE.findall(f.read()):
                    found = resolve(path, target)
                    if found:
                        other = os.path.splitext(found)[0]
                        if other != unit:
                            edges.setdefault((unit, other), set()).add("#include " + target)
    owner, uses = {}, {}
    for unit in units:
        obj = os.path.join(build, unit + ".o")
        if os.path.exists(unit + ".c") and not os.path.exists(obj):
            sys.exit(f"house: {obj} is missing: build it first")
        if os.path.exists(obj):
            defined, used = symbols(obj)
            uses[unit] = used
            for name in defined:
                owner[name] = unit
    for unit, used in uses.items():
        for name in used:
            other = owner.get(name)
            if other and other != unit:
                edges.setdefault((unit, other), set()).add(name)
    return edges


def cycles(nodes, edges):
    """The strongly connected components of more than one node (Tarjan)."""
    succ = {n: sorted(b for (a, b) in edges if a == n) for n in nodes}
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        work = [(v, 0)]
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        while work:
            node, i = work[-1]
            if i < len(succ[node]):
                work[-1] = (node, i + 1)
                w = succ[node][i]
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, 0))
                elif w in on:
                    low[node] = min(low[node], index[w])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    component.append(w)
                    if w == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))

    for n in sorted(nodes):
        if n not in index:
            visit(n)
    return found


def describe(component, edges):
    lines = []
    for (a, b), why in sorted(edges.items()):
        if a in component and b in component:
            lines.append(f"    {a} -> {b}: {', '.join(sorted(why)[:6])}")
    return "\n".join(lines)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.splitlines()[0])
    units = units_of_tree()
    edges = arrows(units, sys.argv[1])
    problems = []
    for component in cycles(set(units), edges):
        problems.append("files in a loop:\n" + describe(component, edges))
    room_edges = {}
    for (a, b), why in edges.items():
        if room_of(a) != room_of(b):
            room_edges.setdefault((room_of(a), room_of(b)), set()).update(f"{a} -> {b}" for _ in [0])
    rooms = {room_of(u) for u in units}
    for component in cycles(rooms, room_edges):
        problems.append("rooms in a loop:\n" + describe(component, room_edges))
    for (a, b), why in sorted(edges.items()):
        if a.startswith("src/app/") and a not in STUDY_COMMANDS and b.startswith("src/studies/"):
            problems.append(f"the program's {a} uses the studies' {b}: {', '.join(sorted(why))}")
    if problems:
        print("house: " + "\n".join(problems))
        return 1
    print(f"house: {len(units)} units in {len(rooms)} rooms, {len(edges)} arrows, no loop; "
          "render and view use nothing of the studies")
    return 0


if __name__ == "__main__":
    sys.exit(main())
