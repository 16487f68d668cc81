#!/usr/bin/env python3
"""Checks the layout of core/ (DESIGN.md sections 7 and 9).

Fails on
- a call cycle between core files: file A calls file B when an object of the built
  core library leaves undefined (nm "U") a symbol that B's object defines; two files
  that call each other, directly or round a longer loop, are a cycle;
- a call cycle between core folders (src/model, src/paper, src/flow, src itself):
  the same graph with each file replaced by its folder;
- an include cycle between core headers and sources (#include "..." resolved from the
  including file's folder, then core/include and core/src);
- a core .c or .h file longer than the line limit (600).

Usage: check_core_layout.py --nm NM --core CORE_DIR --lib LIBSVA_CORE.a
       check_core_layout.py --nm NM --cc CC --self-test
The self-test plants each defect in a scratch tree (two files in two folders calling
each other, a header including itself through another, a 601-line file), compiles it
with CC, and passes only if every planted defect is reported: a check that silently
checks nothing cannot pass.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from typing import Dict, List, Set, Tuple

MAX_LINES = 600
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def objects_of(nm: str, lib: str) -> Dict[str, Tuple[Set[str], Set[str]]]:
    """Object name -> (defined global symbols, undefined symbols), for a static library
    (its members, by name) or one object file (by its path)."""
    out = subprocess.run([nm, "-A", "-P", lib], check=True, capture_output=True, text=True).stdout
    objs: Dict[str, Tuple[Set[str], Set[str]]] = {}
    for line in out.splitlines():
        # POSIX format: "lib.a[member.o]: name type [value size]" or "file.o: name type ..."
        m = re.match(r"^.*\[([^\]]+)\]: (\S+) (\S)", line)
        if not m and line.startswith(lib + ": "):
            m = re.match(r"^(.*): (\S+) (\S)", line)
        if not m:
            continue
        member, name, kind = m.groups()
        defined, undefined = objs.setdefault(member, (set(), set()))
        if kind == "U":
            undefined.add(name)
        elif kind.isupper() and kind not in ("N", "W", "V"):
            defined.add(name)
    return objs


def source_of(member: str, sources: List[str]) -> str:
    """The source an object was built from: an archive member by its file name
    ("flow_lp.c.o" -> src/flow/flow_lp.c), an object file by the end of its path
    (".../sva_node.dir/node/sva_node.c.o" -> node/sva_node.c)."""
    stem = re.sub(r"\.(c\.)?o(bj)?$", ".c", member).replace(os.sep, "/")
    if "/" in stem:
        found = [s for s in sources if stem.endswith("/" + s)]
        found = [s for s in found if len(s) == max(len(f) for f in found)]
    else:
        found = [s for s in sources if os.path.basename(s) == stem]
    if len(found) != 1:
        raise SystemExit(f"check_core_layout: object {member} matches "
                         f"{'no source' if not found else 'more than one source'}")
    return found[0]


def core_files(core: str, tops: Tuple[str, ...] = ("src", "include")) -> List[str]:
    """The .c and .h files under core/src and core/include (tops: () for every folder)."""
    found = []
    for top in tops or ("",):
        for root, _, files in os.walk(os.path.join(core, top)):
            found += [os.path.relpath(os.path.join(root, f), core) for f in files if f.endswith((".c", ".h"))]
    return sorted(found)


def cycles(graph: Dict[str, Set[str]]) -> List[List[str]]:
    """Strongly connected components with more than one node (Tarjan, iterative)."""
    index: Dict[str, int] = {}
    low: Dict[str, int] = {}
    stack: List[str] = []
    on: Set[str] = set()
    found: List[List[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            node, it = work[-1]
            advanced = False
            for nxt in it:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on.add(nxt)
                    work.append((nxt, iter(sorted(graph.get(nxt, ())))))
                    advanced = True
                    break
                if nxt in on:
                    low[node] = min(low[node], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    top = stack.pop()
                    on.discard(top)
                    comp.append(top)
                    if top == node:
                        break
                if len(comp) > 1:
                    found.append(sorted(comp))
    return found


def folder(path: str) -> str:
    return os.path.dirname(path) or "."


def include_graph(core: str, files: List[str]) -> Dict[str, Set[str]]:
    graph: Dict[str, Set[str]] = {}
    for f in files:
        text = open(os.path.join(core, f), encoding="utf-8").read()
        for name in INCLUDE.findall(text):
            for base in (os.path.dirname(f), "include", "include/sva", "src"):
                target = os.path.normpath(os.path.join(base, name))
                if target in files:
                    graph.setdefault(f, set()).add(target)
                    break
    return graph


def check(core: str, nm: str, lib: str, limit: int, more: Tuple[str, ...] = (),
          tops: Tuple[str, ...] = ("src", "include"), what: str = "core") -> List[str]:
    """Every problem found, each a line; prints what it checked. `core` is the part's
    folder; `lib` and `more` are its static libraries and object files; `tops` the
    folders whose .c and .h files are checked (() for all)."""
    files = core_files(core, tops)
    sources = [f for f in files if f.endswith(".c")]
    problems: List[str] = []
    objs: Dict[str, Tuple[Set[str], Set[str]]] = {}
    for path in (lib,) + tuple(more):
        objs.update(objects_of(nm, path))
    definer: Dict[str, str] = {}
    for member, (defined, _) in objs.items():
        for sym in defined:
            definer[sym] = source_of(member, sources)
    calls: Dict[str, Set[str]] = {}
    edges = 0
    for member, (_, undefined) in objs.items():
        src = source_of(member, sources)
        for sym in undefined:
            if sym in definer and definer[sym] != src:
                if definer[sym] not in calls.setdefault(src, set()):
                    edges += 1
                calls[src].add(definer[sym])
    for comp in cycles(calls):
        problems.append("call cycle between files: " + " <-> ".join(comp))
    folders: Dict[str, Set[str]] = {}
    for src, callees in calls.items():
        for callee in callees:
            if folder(src) != folder(callee):
                folders.setdefault(folder(src), set()).add(folder(callee))
    for comp in cycles(folders):
        problems.append("call cycle between folders: " + " <-> ".join(comp))
    includes = include_graph(core, files)
    for comp in cycles(includes):
        problems.append("include cycle: " + " <-> ".join(comp))
    for f in files:
        with open(os.path.join(core, f), encoding="utf-8") as fh:
            n = sum(1 for _ in fh)
        if n > limit:
            problems.append(f"{f}: {n} lines, over the limit of {limit}")
    dag = "; ".join(f"{k} -> {', '.join(sorted(v))}" for k, v in sorted(folders.items()))
    print(f"checked {len(objs)} objects of {', '.join(os.path.basename(p) for p in (lib,) + tuple(more))} "
          f"({edges} calls between files), {sum(len(v) for v in includes.values())} includes and "
          f"the length of {len(files)} {what} files (limit {limit} lines)")
    print(f"folder calls: {dag}")
    return problems


PLANTED = {
    "src/a/a.c": '#include "a.h"\nint planted_b(int x);\nint planted_a(int x) { return x > 0 ? planted_b(x - 1) : 0; }\n',
    "src/a/a.h": '#include "../b/b.h"\n',
    "src/b/b.c": '#include "b.h"\nint planted_a(int x);\nint planted_b(int x) { return x > 0 ? planted_a(x - 1) : 1; }\n',
    "src/b/b.h": '#include "../a/a.h"\n',
    "src/long.c": "int planted_long;\n" + "/* line */\n" * MAX_LINES,
}


def self_test(nm: str, cc: str, ar: str) -> int:
    with tempfile.TemporaryDirectory() as tmp:
        for rel, text in PLANTED.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w", encoding="utf-8") as fh:
                fh.write(text)
        os.makedirs(os.path.join(tmp, "include"))
        objs = []
        for rel in PLANTED:
            if rel.endswith(".c"):
                obj = os.path.join(tmp, os.path.basename(rel) + ".o")
                # Compiled without its #include lines (the planted headers include each
                # other for ever); the include check reads the files' text.
                subprocess.run([cc, "-std=c99", "-c", "-o", obj, "-x", "c", "-"],
                               input=re.sub(r'#include "[^"]+"\n', "", open(os.path.join(tmp, rel)).read()),
                               text=True, check=True)
                objs.append(obj)
        lib = os.path.join(tmp, "libplanted.a")
        subprocess.run([ar, "rcs", lib] + objs, check=True)
        problems = check(tmp, nm, lib, MAX_LINES)
    expected = ["call cycle between files: src/a/a.c <-> src/b/b.c",
                "call cycle between folders: src/a <-> src/b",
                "include cycle: src/a/a.h <-> src/b/b.h",
                f"src/long.c: {MAX_LINES + 1} lines, over the limit of {MAX_LINES}"]
    for p in problems:
        print("planted, reported: " + p)
    missed = [e for e in expected if e not in problems]
    for m in missed:
        print("self-test FAILED, not reported: " + m)
    return 1 if missed or len(problems) != len(expected) else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nm", default="nm")
    ap.add_argument("--ar", default="ar")
    ap.add_argument("--cc", default="cc")
    ap.add_argument("--core")
    ap.add_argument("--lib")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test(args.nm, args.cc, args.ar)
    if not args.core or not args.lib:
        ap.error("--core and --lib are required (or --self-test)")
    problems = check(args.core, args.nm, args.lib, MAX_LINES)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
