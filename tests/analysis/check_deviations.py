#!/usr/bin/env python3
"""Compares cppcheck findings with the deviations table of docs/misra-deviations.md.

Table rows look like  | `misra-c2012-15.5` | `core/src/paper/bfa.c` | 7 | reason |
File `*` covers every file not named in its own row; count `*` allows any number
(project-wide deviations). A (rule, file) pair with more findings than its row allows,
or with no row, is a new finding: listed, exit status 1. Rows allowing more than is
found are reported so the table can be tightened, but do not fail.
"""
import collections
import re
import sys


def load_findings(path):
    findings = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            parts = line.rstrip("\n").split(":", 4)
            if len(parts) < 5 or not parts[1].isdigit():
                continue  # continuation lines of multi-line messages
            findings.append((parts[0], int(parts[1]), parts[2], parts[3], parts[4]))
    return findings


def load_deviations(path):
    rows = {}
    row = re.compile(r"^\|\s*`([^`]+)`\s*\|\s*`([^`]+)`\s*\|\s*(\*|\d+)\s*\|\s*(.+?)\s*\|\s*$")
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = row.match(line)
            if m:
                rule, file, count, reason = m.groups()
                if not reason or reason == "-":
                    sys.exit(f"{path}: deviation {rule} {file} has no reason")
                rows[(rule, file)] = None if count == "*" else int(count)
    return rows


def main():
    findings = load_findings(sys.argv[1])
    rows = load_deviations(sys.argv[2])
    by_key = collections.defaultdict(list)
    for f in findings:
        by_key[(f[3], f[0])].append(f)
    new = []
    per_rule = collections.Counter()
    for (rule, file), items in sorted(by_key.items()):
        per_rule[rule] += len(items)
        key = (rule, file) if (rule, file) in rows else (rule, "*")
        if key not in rows:
            new.extend(items)
            continue
        allowed = rows[key]
        if allowed is not None and len(items) > allowed:
            new.extend(items)
    print(f"findings: {len(findings)} in {len(per_rule)} rules; documented deviations: "
          f"{len(findings) - len(new)}; new: {len(new)}")
    for rule, n in sorted(per_rule.items()):
        print(f"  {rule}: {n}")
    for (rule, file), allowed in sorted(rows.items()):
        found = len(by_key.get((rule, file), [])) if file != "*" else None
        # Only rows of the tool that produced these findings (clang-tidy ids carry a
        # "clang-tidy/" prefix, cppcheck's do not).
        same_tool = rule.startswith("clang-tidy/") == any(r.startswith("clang-tidy/") for r in per_rule)
        if allowed is not None and found is not None and found < allowed and same_tool and per_rule:
            print(f"note: {rule} in {file} allows {allowed}, found {found} (tighten the table)")
    if new:
        print("FAIL: findings beyond docs/misra-deviations.md (fix them or document them there):")
        for file, line, severity, rule, msg in new:
            print(f"  {file}:{line}: {severity}: {rule}: {msg}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
