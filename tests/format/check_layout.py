#!/usr/bin/env python3
"""Checks the layout of the ports (port/*) and the sva command line (tools/cli), and that
dependencies point one way across the tree.

A part (--part DIR with its static libraries --lib and programs' objects --objs) fails on
the defects tests/core/check_core_layout.py finds in core/, with its functions: a call
cycle between files or folders (nm over the objects), an include cycle, a .c or .h file
over 600 lines.

The tree (--deps REPO) fails on an edge that points the wrong way:
- a file under core/ including a header from outside core/, or core's CMake files
  naming a path under port/, tools/ or tests/;
- a file under port/ or tools/ referring to a path under tests/ (C includes, CMake code,
  Python code, shell code);
- a file under port/ referring to tools/ (the same, and Python imports of sva_tools).
Comments and Python docstrings are prose, not edges: they are not read.

Usage: check_layout.py --nm NM --part DIR [--lib LIB.a ...] [--objs A.o:B.o:...]
       check_layout.py --deps REPO
       check_layout.py --nm NM --ar AR --cc CC --self-test
The self-test plants every defect (a part whose files call each other across folders, an
include cycle, a 601-line file; each wrong-way edge beside prose that must not count) in a
scratch tree and passes only if exactly the planted defects are reported.
"""
from __future__ import annotations

import argparse
import ast
import os
import re
import subprocess
import sys
import tempfile
from typing import Dict, List, Tuple

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "core"))
import check_core_layout as layout  # noqa: E402  (the core's checks, reused as they are)

SKIP = {".git", ".venv", "__pycache__", "node_modules"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
# What each top folder may not refer to, as path segments.
FORBIDDEN = {"port": ("tests", "tools"), "tools": ("tests",)}


def segment(name: str) -> re.Pattern:
    """A path segment `name/` not inside another name (sva_tools/, sva-tools/, x.tests/)."""
    return re.compile(r"(?<![\w.-])" + re.escape(name) + r"/")


def walk(repo: str, top: str) -> List[str]:
    found = []
    for root, dirs, files in os.walk(os.path.join(repo, top)):
        dirs[:] = sorted(d for d in dirs if d not in SKIP and not d.startswith("build"))
        found += [os.path.relpath(os.path.join(root, f), repo) for f in sorted(files)]
    return found


def strip_hash_comments(text: str) -> List[Tuple[int, str]]:
    """(line number, code) of CMake or shell text without its # comments (a # inside
    quotes or ${} is kept: only a # at the start or after blank space opens one)."""
    lines = []
    for n, line in enumerate(text.splitlines(), 1):
        m = re.search(r"(^|\s)#", line)
        lines.append((n, line[:m.start()] if m else line))
    return lines


def python_refs(text: str, names: Tuple[str, ...]) -> List[Tuple[int, str]]:
    """(line, what) of each import of a forbidden package and each string in the code
    (docstrings excepted) naming a forbidden folder."""
    try:
        tree = ast.parse(text)
    except SyntaxError as exc:
        return [(exc.lineno or 0, "does not parse")]
    docstrings = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = getattr(node, "body", [])
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                docstrings.add(id(body[0].value))
    packages = {"tests": "tests", "tools": "sva_tools"}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            mods = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            mods = [node.module or ""]
        else:
            mods = []
        for mod in mods:
            for name in names:
                if mod.split(".")[0] == packages[name]:
                    found.append((node.lineno, f"imports {mod}"))
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
            for name in names:
                m = segment(name).search(node.value)
                if node.value == name or m:
                    shown = node.value[max(0, m.start() - 20):m.end() + 30] if m else name
                    found.append((node.lineno, f'names "{shown}"'))
    return found


def resolves(name: str, bases: List[str], files: set) -> List[str]:
    return [os.path.normpath(os.path.join(b, name)) for b in bases
            if os.path.normpath(os.path.join(b, name)) in files]


def wrong_way(repo: str) -> List[str]:
    """Every edge that points the wrong way, each a line."""
    tops = {top: walk(repo, top) for top in ("core", "port", "tools", "tests", "examples")}
    every = set(f for files in tops.values() for f in files)
    headers: Dict[str, List[str]] = {}
    for f in every:
        if f.endswith(".h"):
            parts = f.split("/")
            for k in range(1, len(parts) + 1):
                headers.setdefault("/".join(parts[-k:]), []).append(f)
    problems = []
    core_bases = ["core/include", "core/src", "core/profiles"]
    checked = 0
    for f in tops["core"]:
        text = open(os.path.join(repo, f), encoding="utf-8", errors="replace").read()
        if f.endswith((".c", ".h")):
            checked += 1
            for m in INCLUDE.finditer(text):
                name = m.group(1)
                line = text.count("\n", 0, m.start()) + 1
                inside = resolves(name, [os.path.dirname(f)] + core_bases, every)
                if inside and all(p.startswith("core/") for p in inside):
                    continue
                outside = inside or [p for p in headers.get(os.path.normpath(name), [])
                                     if not p.startswith("core/")]
                if outside:
                    problems.append(f"{f}:{line}: includes {outside[0]}: core includes only core")
        elif os.path.basename(f) == "CMakeLists.txt" or f.endswith((".cmake", ".cmake.in")):
            checked += 1
            for n, code in strip_hash_comments(text):
                for name in ("port", "tools", "tests"):
                    if segment(name).search(code):
                        problems.append(f"{f}:{n}: names {name}/: core depends on nothing outside core")
    for top, names in FORBIDDEN.items():
        for f in tops[top]:
            path = os.path.join(repo, f)
            base = os.path.basename(f)
            kind = ("c" if f.endswith((".c", ".h")) else
                    "cmake" if base == "CMakeLists.txt" or f.endswith(".cmake") else
                    "py" if f.endswith(".py") else
                    "sh" if f.endswith(".sh") else None)
            if kind is None:
                continue
            checked += 1
            text = open(path, encoding="utf-8", errors="replace").read()
            refs: List[Tuple[int, str]] = []
            if kind == "c":
                for m in INCLUDE.finditer(text):
                    name = m.group(1)
                    line = text.count("\n", 0, m.start()) + 1
                    near = resolves(name, [os.path.dirname(f)], every)
                    where = near or headers.get(os.path.normpath(name), [])
                    allowed = [p for p in where if p.split("/")[0] not in names]
                    if any(segment(n).search(name) for n in names) or (where and not allowed):
                        refs.append((line, f"includes {(where or [name])[0]}"))
            elif kind == "py":
                refs = python_refs(text, names)
            else:
                for n, code in strip_hash_comments(text):
                    for name in names:
                        if segment(name).search(code):
                            refs.append((n, f"names {name}/"))
            for line, what in refs:
                problems.append(f"{f}:{line}: {what}: {top}/ may not depend on "
                                f"{' or '.join(n + '/' for n in names)}")
    print(f"checked {checked} files of core/, port/ and tools/ for edges that point the wrong way")
    return problems


PLANTED_PART = {
    "src/lib.c": "int planted_node(int x);\nint planted_lib(int x) { return x > 0 ? planted_node(x - 1) : 0; }\n",
    "node/node.c": '#include "node.h"\nint planted_lib(int x);\nint planted_node(int x) { return x > 0 ? planted_lib(x - 1) : 1; }\n',
    "node/node.h": '#include "other.h"\n',
    "node/other.h": '#include "node.h"\n',
    "src/long.c": "int planted_long;\n" + "/* line */\n" * layout.MAX_LINES,
}

PLANTED_TREE = {
    "core/src/model.h": "#define MODEL 1\n",
    "core/src/a.c": '#include <stdint.h>\n#include "model.h"\n#include "../../port/x/x.h"\n',
    "core/src/b.c": '#include "sva_port.h"\n',
    "core/CMakeLists.txt": "# port/x is not used here\nadd_library(c ${PROJECT_SOURCE_DIR}/tools/x.c)\n",
    "port/x/x.h": "#define X 1\n",
    "port/x/include/sva_port.h": "#define PORT 1\n",
    "port/x/x.c": '#include "x.h"\n#include "gen.h"\n',
    "port/x/CMakeLists.txt": "add_library(x x.c ${PROJECT_SOURCE_DIR}/tests/support/gen.c)  # tests/ here is prose\n",
    "port/x/bench.py": '"""Prose may name tests/lcm and tools/cli."""\nimport os\nimport sva_tools.lcm\n',
    "tests/support/gen.h": "#define GEN 1\n",
    "tools/z/run.py": ('"""Prose naming tests/x.sh."""\nfrom pathlib import Path\n\n'
                       'SCRIPT = Path(__file__).parents[2] / "tests" / "x.sh"\n'),
    "tools/z/run.sh": '#!/bin/sh\n# tests/x.sh in a comment\nexec "$ROOT/tests/x.sh"\n',
    "tools/z/ok.sh": '#!/bin/sh\nexec "$ROOT/tools/y.sh" "$HOME/my-tests/a"\n',
}


def self_test(nm: str, cc: str, ar: str) -> int:
    with tempfile.TemporaryDirectory() as tmp:
        part = os.path.join(tmp, "part")
        objs = []
        for rel, text in PLANTED_PART.items():
            os.makedirs(os.path.dirname(os.path.join(part, rel)), exist_ok=True)
            with open(os.path.join(part, rel), "w", encoding="utf-8") as fh:
                fh.write(text)
        for rel in PLANTED_PART:
            if rel.endswith(".c"):
                # The library's sources into an archive, the program's as an object file
                # under a build-like path (as TARGET_OBJECTS names them).
                obj = os.path.join(tmp, "obj", "prog.dir", rel + ".o")
                os.makedirs(os.path.dirname(obj), exist_ok=True)
                subprocess.run([cc, "-std=c99", "-c", "-o", obj, "-x", "c", "-"], check=True, text=True,
                               input=re.sub(r'#include "[^"]+"\n', "", PLANTED_PART[rel]))
                objs.append(obj)
        lib = os.path.join(tmp, "libpart.a")
        subprocess.run([ar, "rcs", lib] + [o for o in objs if "/src/" in o], check=True)
        problems = layout.check(part, nm, lib, layout.MAX_LINES,
                                tuple(o for o in objs if "/node/" in o), (), "planted part")
        tree = os.path.join(tmp, "tree")
        for rel, text in PLANTED_TREE.items():
            os.makedirs(os.path.dirname(os.path.join(tree, rel)), exist_ok=True)
            with open(os.path.join(tree, rel), "w", encoding="utf-8") as fh:
                fh.write(text)
        problems += wrong_way(tree)
    expected = [
        "call cycle between files: node/node.c <-> src/lib.c",
        "call cycle between folders: node <-> src",
        "include cycle: node/node.h <-> node/other.h",
        f"src/long.c: {layout.MAX_LINES + 1} lines, over the limit of {layout.MAX_LINES}",
        "core/src/a.c:3: includes port/x/x.h: core includes only core",
        "core/src/b.c:1: includes port/x/include/sva_port.h: core includes only core",
        "core/CMakeLists.txt:2: names tools/: core depends on nothing outside core",
        "port/x/CMakeLists.txt:1: names tests/: port/ may not depend on tests/ or tools/",
        "port/x/bench.py:3: imports sva_tools.lcm: port/ may not depend on tests/ or tools/",
        "port/x/x.c:2: includes tests/support/gen.h: port/ may not depend on tests/ or tools/",
        'tools/z/run.py:4: names "tests": tools/ may not depend on tests/',
        "tools/z/run.sh:3: names tests/: tools/ may not depend on tests/",
    ]
    for p in problems:
        print("planted, reported: " + p)
    missed = [e for e in expected if e not in problems]
    extra = [p for p in problems if p not in expected]
    for m in missed:
        print("self-test FAILED, not reported: " + m)
    for x in extra:
        print("self-test FAILED, reported though not planted: " + x)
    return 1 if missed or extra else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nm", default="nm")
    ap.add_argument("--ar", default="ar")
    ap.add_argument("--cc", default="cc")
    ap.add_argument("--part", help="a part's folder (port/lcm, tools/cli, ...)")
    ap.add_argument("--lib", action="append", default=[], help="a static library of the part")
    ap.add_argument("--objs", default="", help="object files of the part's programs, ':'-separated")
    ap.add_argument("--deps", metavar="REPO", help="scan the tree for wrong-way edges")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test(args.nm, args.cc, args.ar)
    if args.deps:
        problems = wrong_way(args.deps)
    elif args.part:
        objs = [o for o in args.objs.split(":") if o] + args.lib[1:]
        if not args.lib and not objs:
            ap.error("--part needs --lib or --objs")
        first = args.lib[0] if args.lib else objs.pop(0)
        problems = layout.check(args.part, args.nm, first, layout.MAX_LINES, tuple(objs), (),
                                os.path.basename(os.path.normpath(args.part)))
    else:
        ap.error("--part, --deps or --self-test is required")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
