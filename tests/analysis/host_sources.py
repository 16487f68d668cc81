#!/usr/bin/env python3
"""The C files of the ports and the CLI that tests/analysis checks, and each one's
preprocessor flags as the build compiles it (docs/analysis.md).

  host_sources.py list ROOT
      every file the globs below match, one per line, relative to ROOT (globbed when
      run, so a new file is analysed without editing the tests)
  host_sources.py flags ROOT BUILD_DIR FILE [--user-includes]
      FILE's -std, -D, -U, -I and -isystem flags from BUILD_DIR/compile_commands.json,
      one per line (the build's include paths: the ports' own, the generated LCM and
      MAVLink headers in the build tree, Jansson, PROJ, LCM). A file the build does not
      compile on this host (socketcan_other.c, geodesy_none.c) takes the flags of a
      compiled file of its own folder. --user-includes drops the -isystem paths (what
      cppcheck is given: it does not parse the system and third-party headers).
"""
import glob
import json
import os
import shlex
import sys

GLOBS = ("port/*/src/*.c", "port/*/node/*.c", "port/mavlink/bridge/*.c", "tools/cli/*.c")


def sources(root):
    found = set()
    for pattern in GLOBS:
        found.update(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, pattern)))
    return sorted(found)


def split_flags(entry):
    if "arguments" in entry:
        args = list(entry["arguments"])
    else:
        args = shlex.split(entry["command"])
    flags = []
    i = 0
    while i < len(args):
        a = args[i]
        for opt in ("-I", "-isystem", "-D", "-U", "-iquote"):
            if a == opt and i + 1 < len(args):
                flags.append((opt, args[i + 1]))
                i += 1
                break
            if a.startswith(opt) and len(a) > len(opt) and opt != "-isystem":
                flags.append((opt, a[len(opt):]))
                break
        else:
            if a.startswith("-std="):
                flags.append((a, None))
        i += 1
    return flags


def absolute(entry, path):
    return os.path.normpath(os.path.join(entry.get("directory", ""), path))


def flags_for(root, build, rel):
    db_path = os.path.join(build, "compile_commands.json")
    if not os.path.isfile(db_path):
        sys.exit(f"{db_path} missing: configure and build {build} first (scripts/build.sh)")
    with open(db_path, encoding="utf-8") as f:
        db = json.load(f)
    by_file = {}
    build_abs = os.path.realpath(build)
    for e in db:
        src = os.path.realpath(absolute(e, e["file"]))
        # The tests compile some of these files again (sanitized builds, fuzzers): take
        # the product's own compilation, not one under build/tests.
        in_tests = os.path.realpath(e.get("directory", "")).startswith(os.path.join(build_abs, "tests")) or \
            "/tests/" in e.get("output", "")
        if src not in by_file or (by_file[src][1] and not in_tests):
            by_file[src] = (e, in_tests)
    target = os.path.realpath(os.path.join(root, rel))
    if target not in by_file:
        folder = os.path.dirname(target)
        siblings = sorted(s for s in by_file if os.path.dirname(s) == folder)
        if not siblings:
            sys.exit(f"{rel}: neither it nor a file of its folder is in {db_path}; "
                     "is its port configured in this build?")
        target = siblings[0]
    entry = by_file[target][0]
    out = []
    for opt, value in split_flags(entry):
        if value is None:
            out.append(opt)
        elif opt in ("-I", "-isystem", "-iquote"):
            out.extend([opt, absolute(entry, value)])
        elif not (opt == "-D" and value == "NDEBUG"):
            # NDEBUG is the build type's (RelWithDebInfo), not the target's: the
            # analysers see the asserts, as in the core's analysis.
            out.append(opt + value)
    return out


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "list":
        print("\n".join(sources(sys.argv[2])))
    elif len(sys.argv) in (5, 6) and sys.argv[1] == "flags":
        flags = flags_for(sys.argv[2], sys.argv[3], sys.argv[4])
        if len(sys.argv) == 6 and sys.argv[5] == "--user-includes":
            kept = []
            skip = False
            for f in flags:
                if skip:
                    skip = False
                    continue
                if f == "-isystem":
                    skip = True
                    continue
                kept.append(f)
            flags = kept
        print("\n".join(flags))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
