#!/usr/bin/env python3
"""Footprint and stack checks of the Cortex-M firmware image (examples/cortex-m).

  footprint.py size  --elf ELF --nm NM --size SIZE --budget FILE --build NAME
      text/data/bss/stack of the image against the build's line in the budget file;
      fails when a budget is exceeded or when the image links a heap function, a
      syscall stub or a floating-point helper.
  footprint.py stack --objdir DIR --root FUNC [--root ...] --budget FILE --build NAME
      per-function stack (-fstack-usage) and the worst call path from each root, from
      GCC's call graphs (-fcallgraph-info=su, *.ci files under DIR); fails on a call
      cycle (the core has no recursion), on a frame that is not static (VLA, alloca),
      or when the worst path from the first root exceeds the budget. Library leaf
      functions are outside the graph (libgcc's 64-bit division is not even a call
      there): --leaf-allowance adds their measured stack to every path.

  footprint.py results --builddir BUILD [--budget FILE] [--nm NM] [--size SIZE]
      after `ctest -L footprint` built the images: every build's sizes and worst stack
      path as docs/results.md's footprint section (docs/results/footprint.md,
      tools/bench/results.py); prints the same table.

The budget file (tests/footprint/budget.txt) has one line per build:
  NAME CPU PROFILE FLASH RAM PLANNER STACK
sizes in bytes ("-" for no budget). FLASH is text + data (the image in flash), RAM is
data + bss + the reserved main stack, PLANNER the size of the `planner` object, STACK
the worst call path of sva_plan.
"""

import argparse
import contextlib
import io
import os
import re
import subprocess
import sys
from pathlib import Path

BUDGET_FIELDS = ("cpu", "profile", "flash", "ram", "planner", "stack")


def read_budget(path, build):
    for raw in Path(path).read_text().splitlines():
        line = raw.split("#", 1)[0].split()
        if not line:
            continue
        if len(line) != 1 + len(BUDGET_FIELDS):
            sys.exit(f"{path}: malformed line: {raw!r}")
        if line[0] == build:
            row = dict(zip(BUDGET_FIELDS, line[1:]))
            for key in ("flash", "ram", "planner", "stack"):
                row[key] = None if row[key] == "-" else int(row[key])
            return row
    sys.exit(f"{path}: no line for build {build!r}")


# ---------------------------------------------------------------------------------
# size

# Symbols that must not be in the image: the heap, the syscall stubs of nosys (any
# call into them means the firmware would need an OS), stdio, and the floating-point
# helpers of the Arm run-time ABI and of libgcc's soft-float.
FORBIDDEN = [
    (re.compile(r"^_?(malloc|free|calloc|realloc|memalign|aligned_alloc)$"), "heap"),
    (re.compile(r"^_(malloc|free|calloc|realloc|memalign)_r$"), "heap"),
    (re.compile(r"^_?sbrk(_r)?$"), "heap (sbrk)"),
    (re.compile(r"^_(write|read|open|close|lseek|fstat|isatty|kill|getpid|exit)$"), "syscall stub"),
    (re.compile(r"^(printf|iprintf|fprintf|fiprintf|puts|fputs|fwrite|__sinit|__assert_func)$"), "stdio"),
    (re.compile(r"^__aeabi_(c?[fd]|u?[il]2[fd])"), "floating-point helper"),
    (re.compile(r"^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord)[sdtx]f[23]$"), "floating-point helper"),
    (re.compile(r"^__(fix|fixuns)[sdtx]f[sdt]i$|^__float(un)?[sdt]i[sdtx]f$"), "floating-point helper"),
    (re.compile(r"^__(extend|trunc)[sdtx]f[sdtx]f2$"), "floating-point helper"),
]


def section_sizes(size_tool, elf):
    out = subprocess.run([size_tool, "-A", "-d", elf], check=True, capture_output=True, text=True).stdout
    sizes = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[0].startswith(".") and parts[1].isdigit():
            sizes[parts[0]] = int(parts[1])
    return sizes


def symbols(nm_tool, elf):
    out = subprocess.run([nm_tool, "-S", elf], check=True, capture_output=True, text=True).stdout
    syms = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4:
            syms[parts[3]] = int(parts[1], 16)
        elif len(parts) >= 2:
            syms.setdefault(parts[-1], 0)
    return syms


def cmd_size(args):
    budget = read_budget(args.budget, args.build)
    sec = section_sizes(args.size, args.elf)
    syms = symbols(args.nm, args.elf)
    text = sec.get(".isr_vector", 0) + sec.get(".text", 0) + sec.get(".ARM.exidx", 0)
    data = sec.get(".data", 0)
    bss = sec.get(".bss", 0)
    stack = sec.get(".stack", 0)
    flash = text + data
    ram = data + bss + stack
    planner = syms.get("planner")
    print(f"{args.build} ({budget['cpu']}, profile {budget['profile']}): "
          f"text {text} data {data} bss {bss} stack-reserve {stack}")
    failures = []
    rows = [("flash (text+data)", flash, budget["flash"]),
            ("RAM (data+bss+stack)", ram, budget["ram"]),
            ("planner object", planner, budget["planner"])]
    for what, value, limit in rows:
        if value is None:
            failures.append(f"{what}: not found in {args.elf}")
            continue
        verdict = "no budget" if limit is None else f"budget {limit}, {100.0 * value / limit:.1f} %"
        print(f"  {what:22} {value:9d} B  ({verdict})")
        if limit is not None and value > limit:
            failures.append(f"{what} is {value} B, over the budget of {limit} B "
                            f"({args.budget}, line {args.build})")
    bad = sorted(f"{name} ({why})" for name in syms for rx, why in FORBIDDEN if rx.search(name))
    if bad:
        failures.append("linked in: " + ", ".join(bad))
    else:
        print("  no heap, syscall stub, stdio or floating-point helper linked")
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


# ---------------------------------------------------------------------------------
# stack

NODE_RE = re.compile(r'^node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE_RE = re.compile(r'^edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)" label: "([^"]*)"')
BYTES_RE = re.compile(r"\\n(\d+) bytes \(([^)]*)\)")


def load_graph(objdir):
    """Functions defined under objdir: {(unit, name): (bytes, qualifier, where)} and
    the call edges {(unit, name): [(callee name, call site)]}."""
    defs, calls = {}, {}
    units = sorted(Path(objdir).rglob("*.ci"))
    if not units:
        sys.exit(f"no *.ci call graphs under {objdir} (build with -fcallgraph-info=su)")
    for ci in units:
        unit = str(ci)
        for line in ci.read_text().splitlines():
            m = NODE_RE.match(line)
            if m:
                b = BYTES_RE.search(m.group(2))
                if b:
                    where = m.group(2).split("\\n")[1] if "\\n" in m.group(2) else "?"
                    defs[(unit, m.group(1))] = (int(b.group(1)), b.group(2), where)
                continue
            m = EDGE_RE.match(line)
            if m:
                calls.setdefault((unit, m.group(1)), []).append((m.group(2), m.group(3)))
    return defs, calls


def resolve(defs, by_name, unit, name):
    """The definition a call from `unit` to `name` reaches: the unit's own (static or
    not) first, else the only one elsewhere; several (same static name in several
    units) resolve to the largest, which can only overestimate."""
    if (unit, name) in defs:
        return (unit, name)
    cands = by_name.get(name, [])
    if not cands:
        return None
    return max(cands, key=lambda k: defs[k][0])


def cmd_stack(args):
    budget = read_budget(args.budget, args.build)
    defs, calls = load_graph(args.objdir)
    by_name = {}
    for key in defs:
        by_name.setdefault(key[1], []).append(key)
    failures = []

    nonstatic = sorted((k[1], v[1]) for k, v in defs.items() if v[1] != "static")
    for name, qual in nonstatic:
        failures.append(f"{name}: stack frame is '{qual}', not static (VLA or alloca?)")

    # Edges between definitions; what is left are external calls (C library, libgcc)
    # and indirect calls (the caller's on_transport observer).
    graph, external, indirect = {}, {}, {}
    for key in defs:
        graph[key] = []
        for callee, site in calls.get(key, []):
            if callee == "__indirect_call":
                indirect.setdefault(key[1], []).append(site)
                continue
            target = resolve(defs, by_name, key[0], callee)
            if target is None:
                external.setdefault(callee, set()).add(key[1])
            else:
                graph[key].append(target)

    # No recursion: any cycle in the whole graph fails (iterative DFS, three colours).
    color = {k: 0 for k in graph}
    for start in sorted(graph):
        if color[start]:
            continue
        stack = [(start, iter(graph[start]))]
        path = [start]
        color[start] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                color[node] = 2
                stack.pop()
                path.pop()
            elif color[nxt] == 1:
                cyc = path[path.index(nxt):] + [nxt]
                failures.append("call cycle (recursion): " + " -> ".join(k[1] for k in cyc))
            elif color[nxt] == 0:
                color[nxt] = 1
                stack.append((nxt, iter(graph[nxt])))
                path.append(nxt)
    if any(f.startswith("call cycle") for f in failures):
        for f in failures:
            print(f"FAIL: {f}")
        return 1

    # Worst path (the graph is a DAG now), memoised.
    memo = {}

    def worst(key):
        if key not in memo:
            best = (0, [])
            for callee in graph[key]:
                cand = worst(callee)
                if cand[0] > best[0]:
                    best = cand
            memo[key] = (defs[key][0] + best[0], [key] + best[1])
        return memo[key]

    def short(name):  # GCC titles static functions "/path/file.c:name"
        return name.rsplit("/", 1)[-1]

    print(f"{args.build}: {len(defs)} functions with stack use (-fstack-usage), largest frames:")
    for key in sorted(defs, key=lambda k: (-defs[k][0], k[1]))[: args.top]:
        print(f"  {defs[key][0]:6d} B  {short(key[1])}")
    result = 0
    for i, root in enumerate(args.root):
        keys = by_name.get(root, [])
        if not keys:
            failures.append(f"root function {root} not found under {args.objdir}")
            continue
        frames, path = worst(max(keys, key=lambda k: worst(k)[0]))
        total = frames + args.leaf_allowance
        print(f"worst call path from {root}: {total} B = {frames} B of frames"
              f" + {args.leaf_allowance} B allowance for library leaf functions")
        for key in path:
            print(f"  {defs[key][0]:6d} B  {short(key[1])}")
        if i == 0:
            result = total
            limit = budget["stack"]
            if limit is not None:
                print(f"  budget {limit} B ({100.0 * total / limit:.1f} %)")
                if total > limit:
                    failures.append(f"worst stack path of {root} is {total} B, over the budget "
                                    f"of {limit} B ({args.budget}, line {args.build})")
    if external:
        print("not counted, outside the core (C library / libgcc leaf functions): "
              + ", ".join(f"{n} (from {', '.join(sorted(short(x) for x in c))})"
                            for n, c in sorted(external.items())))
    if indirect:
        print("not counted, indirect calls (the caller's observer adds its own stack): "
              + ", ".join(f"{short(n)} at {', '.join(short(x) for x in s)}"
                            for n, s in sorted(indirect.items())))
    for f in failures:
        print(f"FAIL: {f}")
    if args.report:
        Path(args.report).write_text(f"{result}\n")
    return 1 if failures else 0


# ---------------------------------------------------------------------------------
# results

LEAF_ALLOWANCE = 64  # tests/footprint/CMakeLists.txt, SVA_FOOTPRINT_LEAF_ALLOWANCE


def _stack_report(objdir, budget, build):
    """(bytes, [(frame bytes, function)]) of the worst path from sva_plan, via cmd_stack."""
    ns = argparse.Namespace(objdir=objdir, root=["sva_plan"], budget=budget, build=build, top=0,
                            leaf_allowance=LEAF_ALLOWANCE, report=None)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        cmd_stack(ns)
    lines = buf.getvalue().splitlines()
    total, path = None, []
    for i, line in enumerate(lines):
        m = re.match(r"worst call path from sva_plan: (\d+) B", line)
        if m:
            total = int(m.group(1))
            for nxt in lines[i + 1:]:
                f = re.match(r"^\s+(\d+) B  (\S+)$", nxt)
                if not f:
                    break
                path.append((int(f.group(1)), f.group(2)))
    return total, path


def cmd_results(args):
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "bench"))
    import results  # tools/bench/results.py
    rows, paths = [], []
    n = lambda v: "-" if v is None else f"{v:,}"
    for raw in Path(args.budget).read_text().splitlines():
        line = raw.split("#", 1)[0].split()
        if not line:
            continue
        build = line[0]
        budget = read_budget(args.budget, build)
        fwdir = Path(args.builddir) / "footprint" / build
        elf = fwdir / "sva_fw.elf"
        if not elf.exists():
            sys.exit(f"{elf}: missing; build and run `ctest --test-dir {args.builddir} -L footprint` first")
        sec = section_sizes(args.size, str(elf))
        planner = symbols(args.nm, str(elf)).get("planner")
        text = sec.get(".isr_vector", 0) + sec.get(".text", 0) + sec.get(".ARM.exidx", 0)
        data, bss, stack = sec.get(".data", 0), sec.get(".bss", 0), sec.get(".stack", 0)
        worst, path = _stack_report(str(fwdir), args.budget, build)
        lim = "{} / {} / {} / {}".format(*(n(budget[k]) for k in ("flash", "ram", "planner", "stack")))
        rows.append(f"| {build} | {budget['profile']} | {n(text)} | {n(data)} | {n(bss)} | {n(stack)} | "
                    f"{n(text + data)} | {n(data + bss + stack)} | {n(planner)} | {n(worst)} | {lim} |")
        paths.append(f"- {build}: " + " -> ".join(f"{fn} {b} B" for b, fn in path)
                     + f", plus {LEAF_ALLOWANCE} B for library leaf functions")
    gcc = subprocess.run([args.gcc, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    body = "\n".join([
        "The example image `examples/cortex-m/` (a static planner, the mission in flash, one "
        "`sva_plan()` call), `-Os`, newlib-nano, built from `tests/footprint/budget.txt`'s lines; "
        "bytes. flash = text + data, RAM = data + bss + the 4 KiB main stack the example reserves, "
        "`planner` = sizeof the static `sva_planner_t`; stack = the worst call path of `sva_plan` "
        "(`-fstack-usage` and `-fcallgraph-info=su`, with a 64 B allowance for C library and libgcc "
        "leaf functions). Budgets: flash / RAM / planner / stack (`-`: none).", "",
        "| build | profile | text | data | bss | stack reserved | flash | RAM | `planner` | stack of `sva_plan` | budget |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *rows, "",
        "Worst call paths of `sva_plan` (frame sizes):", "", *paths, "",
        "The test (`ctest -L footprint`) fails over a budget, on a call cycle, on a frame that is "
        "not static, or when the image links a heap function, a syscall stub, stdio or a "
        "floating-point helper; sizes do not depend on the machine's load."])
    print("\n".join(rows + paths))
    results.write(results.ROOT, "footprint",
                  f"ctest --test-dir {args.builddir} -L footprint && .venv/bin/python tests/footprint/footprint.py "
                  f"results --builddir {args.builddir}", body, compiler=gcc)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("size")
    s.add_argument("--elf", required=True)
    s.add_argument("--nm", required=True)
    s.add_argument("--size", required=True)
    s.add_argument("--budget", required=True)
    s.add_argument("--build", required=True)
    k = sub.add_parser("stack")
    k.add_argument("--objdir", required=True)
    k.add_argument("--root", action="append", required=True)
    k.add_argument("--budget", required=True)
    k.add_argument("--build", required=True)
    k.add_argument("--top", type=int, default=12)
    k.add_argument("--leaf-allowance", type=int, default=0,
                   help="bytes added to every path for C library / libgcc leaf functions, which "
                        "GCC's call graph does not show (64-bit division helpers, memset)")
    k.add_argument("--report", help="write the worst path's bytes of the first root here")
    r = sub.add_parser("results")
    r.add_argument("--builddir", default="build")
    r.add_argument("--budget", default=str(Path(__file__).with_name("budget.txt")))
    r.add_argument("--nm", default="arm-none-eabi-nm")
    r.add_argument("--size", default="arm-none-eabi-size")
    r.add_argument("--gcc", default="arm-none-eabi-gcc")
    args = ap.parse_args()
    if args.cmd == "results":
        return cmd_results(args)
    return cmd_size(args) if args.cmd == "size" else cmd_stack(args)


if __name__ == "__main__":
    sys.exit(main())
