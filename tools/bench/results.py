#!/usr/bin/env python3
"""docs/results.md, assembled from one fragment per benchmark under docs/results/.

Each benchmark writes its own fragment when run with `--results` (scripts/bench.sh,
scripts/instructions.sh, tests/footprint/footprint.py results, tools/bench/flow_vs_ref.py,
tools/bench/flow_vs_peer.py, tools/bench/flow_latency.py, tools/bench/large_profile.py,
tools/bench/live_bench.py, tools/bench/campaign_bench.py, `sva-tools bench`,
tools/bench/lcm_latency.sh), then this script assembles docs/results.md; re-running a bench
rewrites only its own fragment.
A fragment is docs/results/SECTION.md (the section's text) or docs/results/SECTION.PART.md
(one part of it, e.g. one mission set; parts follow the section's own fragment, in name
order). Every fragment names the command that reproduces it (a line `Command: `...``)
and the machine it ran on (a line `Machine: ...`).

Usage:
    tools/bench/results.py [--root DIR]            assemble docs/results.md
    tools/bench/results.py check [--root DIR]      fail (exit 1) when docs/results.md differs
                                                   from the fragments, or a fragment lacks its
                                                   command or machine line, or has no section
    tools/bench/results.py write FRAGMENT --command CMD [--title T] [--load-start "L1 L5 L15"]
                                 [--compiler TEXT] [--note TEXT] [--root DIR] < BODY.md
        write docs/results/FRAGMENT.md: the title, the command, the machine line (cores,
        CPU model, load average, compiler, niceness, and --note or $SVA_RESULTS_NOTE, e.g.
        that the machine was shared) and the markdown body from stdin; then assemble.

$SVA_RESULTS_ROOT, when set, replaces the repository as the root (for tests).
Python's standard library only, so the shell benches can call it with any python3.
"""
import argparse
import os
import platform
import re
import subprocess
import sys

# The repository; $SVA_RESULTS_ROOT sends the fragments and the page elsewhere (tests).
ROOT = os.environ.get("SVA_RESULTS_ROOT") or os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Sections of docs/results.md in order: fragment name, heading.
SECTIONS = [
    ("setup", "First plan on a fresh Debian 12"),
    ("core", "Core speed and memory"),
    ("instructions", "Instructions per plan"),
    ("footprint", "Cortex-M footprint and stack"),
    ("flow_vs_ref", "flow against the exact optimum"),
    ("flow_vs_peer", "flow against the OR-tools routing peer"),
    ("large", "flow at 1,000 targets x 100 UAVs (the large profile)"),
    ("live", "Live missions"),
    ("sitl", "Flights in ArduCopter SITL"),
    ("campaign", "Regression campaigns"),
    ("paper", "The paper's evaluation"),
    ("lcm_latency", "LCM latency"),
]

HEADER = """# Measured results

Every figure here comes from a benchmark in the repository, with the command that
reproduces it and the machine it ran on. This page is generated: each benchmark run
with `--results` rewrites its own fragment under `docs/results/`, and
`tools/bench/results.py` assembles this page from them (`ctest -L tools` checks that
it matches). Do not edit it by hand.

Timings depend on the machine and its load; sizes, instruction counts and plan quality
(coverage, cost, gaps) do not.
"""

COMMAND_RE = re.compile(r"^Command: `[^`]+`", re.M)
MACHINE_RE = re.compile(r"^Machine: \S", re.M)


class ResultsError(Exception):
    pass


def _dir(root):
    return os.path.join(root, "docs", "results")


def fragments(root):
    """{section: [(fragment file name, text)]}, the section's own fragment first, then its
    parts in name order. Raises ResultsError on a fragment of no section, or one without
    its command or machine line."""
    d = _dir(root)
    names = sorted(f for f in os.listdir(d) if f.endswith(".md")) if os.path.isdir(d) else []
    known = [s for s, _ in SECTIONS]
    out = {s: [] for s in known}
    errors = []
    for f in names:
        section = f[:-3].split(".", 1)[0]
        if section not in out:
            errors.append(f"docs/results/{f}: no section {section!r} (sections: {', '.join(known)})")
            continue
        with open(os.path.join(d, f), encoding="utf-8") as fh:
            text = fh.read()
        if not COMMAND_RE.search(text):
            errors.append(f"docs/results/{f}: no line 'Command: `...`' naming the command that reproduces it")
        if not MACHINE_RE.search(text):
            errors.append(f"docs/results/{f}: no line 'Machine: ...' naming the machine it ran on")
        out[section].append((f, text))
    if errors:
        raise ResultsError("\n".join(errors))
    for s in out:  # the section's own fragment (SECTION.md) before its parts
        out[s].sort(key=lambda x: (x[0] != s + ".md", x[0]))
    return out


def _anchor(title):
    return re.sub(r"[^a-z0-9 -]", "", title.lower()).replace(" ", "-")


def render(root):
    frags = fragments(root)
    present = [(s, t) for s, t in SECTIONS if frags[s]]
    md = [HEADER, "Sections:"]
    md += [f"- [{t}](#{_anchor(t)})" for s, t in present]
    md.append("")
    for s, title in present:
        md += [f"## {title}", ""]
        for _, text in frags[s]:
            md += [text.strip("\n"), ""]
    return "\n".join(md)


def assemble(root):
    text = render(root)
    with open(os.path.join(root, "docs", "results.md"), "w", encoding="utf-8") as f:
        f.write(text)
    return text


def check(root):
    path = os.path.join(root, "docs", "results.md")
    want = render(root)
    have = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
    if have != want:
        a, b = have.splitlines(), want.splitlines()
        line = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
        raise ResultsError(f"docs/results.md differs from its fragments from line {line + 1} on "
                           f"(has {a[line]!r} if any, fragments give {b[line] if line < len(b) else ''!r}); "
                           "edit docs/results/*.md or re-run the bench, then tools/bench/results.py")


def _first_line(cmd):
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        return out.splitlines()[0].strip() if out else None
    except (OSError, subprocess.CalledProcessError):
        return None


def host_compiler(root):
    """The C compiler of build/ (CMakeCache.txt), as its --version line."""
    cc = None
    try:
        with open(os.path.join(root, "build", "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                if line.startswith("CMAKE_C_COMPILER:"):
                    cc = line.split("=", 1)[1].strip()
    except OSError:
        pass
    return _first_line([cc or "cc", "--version"])


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine_line(root, load_start=None, compiler=None, note=None):
    load_end = " ".join(f"{x:.2f}" for x in os.getloadavg())
    load = (f"load average {load_start} at the start, {load_end} at the end" if load_start
            else f"load average {load_end} at the end")
    parts = [f"{os.cpu_count()} cores, {cpu_model()}", f"Linux {platform.release()}", load,
             f"niceness {os.nice(0)}", compiler or host_compiler(root) or "compiler unknown"]
    note = note if note is not None else os.environ.get("SVA_RESULTS_NOTE")
    return "Machine: " + "; ".join(parts) + (f"; {note}" if note else "") + "."


def write(root, name, command, body, title=None, load_start=None, compiler=None, note=None):
    """Write docs/results/NAME.md and reassemble docs/results.md; returns the fragment's path."""
    section = name.split(".", 1)[0]
    if section not in [s for s, _ in SECTIONS]:
        raise ResultsError(f"fragment {name!r}: no section {section!r}")
    lines = []
    if title:
        lines += [f"### {title}", ""]
    lines += [f"Command: `{command}`", "", machine_line(root, load_start, compiler, note), "",
              body.strip("\n"), ""]
    os.makedirs(_dir(root), exist_ok=True)
    path = os.path.join(_dir(root), name + ".md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    assemble(root)
    return path


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", nargs="?", default="assemble", choices=["assemble", "check", "write"])
    ap.add_argument("fragment", nargs="?")
    ap.add_argument("--root", default=ROOT)
    ap.add_argument("--command")
    ap.add_argument("--title")
    ap.add_argument("--load-start")
    ap.add_argument("--compiler")
    ap.add_argument("--note")
    args = ap.parse_args(argv)
    try:
        if args.action == "write":
            if not args.fragment or not args.command:
                ap.error("write needs FRAGMENT and --command")
            path = write(args.root, args.fragment, args.command, sys.stdin.read(), args.title,
                         args.load_start, args.compiler, args.note)
            print(f"results: wrote {os.path.relpath(path, args.root)} and docs/results.md", file=sys.stderr)
        elif args.action == "check":
            check(args.root)
            print("results: docs/results.md matches docs/results/*.md; every fragment names its command")
        else:
            assemble(args.root)
    except ResultsError as e:
        print(f"results: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
