#!/usr/bin/env python3
"""Reads clang-tidy's output on stdin and prints one line per finding for
check_deviations.py:  FILE:LINE:error:clang-tidy/CHECK:MESSAGE  (FILE relative to ROOT).

Usage: tidy_findings.py ROOT
A message may span several lines (clang-analyzer-optin.performance.Padding lists the
fields): it runs until the line that ends with the [check] tag. Exit status 1 when a
diagnostic has no check tag (the caller then shows the output).
"""
import os
import re
import sys

START = re.compile(r"^(.+?):(\d+):\d+: (error|warning): (.*)$")
TAG = re.compile(r"^(.*?)\s*\[([^],\s]+)(?:,[^]]*)?\]\s*$")


def main():
    root = os.path.realpath(sys.argv[1])
    lines = sys.stdin.read().splitlines()
    status = 0
    i = 0
    while i < len(lines):
        m = START.match(lines[i])
        i += 1
        if not m:
            continue
        path, line, _, message = m.groups()
        text = [message]
        while not TAG.match(text[-1]) and i < len(lines) and not START.match(lines[i]):
            text.append(lines[i].strip())
            i += 1
        whole = " ".join(t for t in text if t)
        tag = TAG.match(whole)
        if not tag:
            print(f"unparsed clang-tidy diagnostic: {lines[i - 1]}", file=sys.stderr)
            status = 1
            continue
        rel = os.path.relpath(os.path.realpath(path), root) if os.path.isabs(path) else path
        print(f"{rel}:{line}:error:clang-tidy/{tag.group(2)}:{tag.group(1)}")
    return status


if __name__ == "__main__":
    sys.exit(main())
