#!/usr/bin/env python3
"""Docs that run (ctest label `docs`): every runnable shell block of a document, run as written.

The convention (docs/README.md, "Runnable blocks"):

- A fenced block whose info string is ```` ```sh run ```` (or `bash run`) is runnable.
  GitHub highlights it as `sh` and shows nothing of the marker.
- A fenced block whose info string carries `file=PATH` (```` ```c file=app/main.c ````) is a
  file the page asks the reader to write: its text is written to PATH (relative, inside
  the checkout) before the blocks after it run.
- A runnable block followed directly (blank lines aside) by a ```` ```text output ````
  block must print exactly that text on stdout (trailing spaces and blank lines aside).
- The blocks of one document run in order, each with `bash -euo pipefail`, in one
  scratch folder: a fresh copy of the source tree as a checkout has it (git's tracked
  and untracked, not ignored, files; no build folders), with `build` a symbolic link to
  the build tree this test belongs to and `.venv` one to the repository's venv. So a
  block is written as a reader types it at the top of a built checkout (`build/bin/sva
  ...`, `$PWD/cmake/...`); PATH is not changed. What a block writes stays in the copy
  (the build tree aside: `cmake --install build` writes its install_manifest.txt there).
- Not marked: blocks that need root, the network, SITL, or minutes of CPU; the build
  itself (`scripts/build.sh`, `scripts/demo.sh`, `scripts/test.sh`, ctest); synopses with
  placeholders (`sva plan MISSION.json`).
- bash's -e does not stop at a failing command that is not the last of an `&&` or `||`
  list: give a step that must succeed a line of its own, or put it last.

A failing block fails the document's test with the document, the line of the failing
command, its exit status and the block's output.

Usage:
  run_docs.py run --source DIR --build DIR --work DIR DOC.md...
  run_docs.py list --source DIR          documents (README.md, docs/*.md) with runnable blocks
  run_docs.py check --source DIR --registered "README.md;docs/cli.md"
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

SHELLS = ("sh", "bash", "shell")
FENCE = re.compile(r"^( {0,3})(`{3,}|~{3,})(.*)$")
OUTPUT_LIMIT = 20000  # characters of a failing block's output shown (its tail)


class DocError(Exception):
    """A document breaks the convention (a marker on a block that cannot run, a bad path)."""


@dataclass
class Block:
    doc: str
    line: int  # line of the opening fence (1-based)
    info: list[str]
    text: str
    end: int  # line of the closing fence
    run: bool = False
    file: str | None = None
    output: str | None = None  # the expected stdout (a following `text output` block)


def parse(path: Path, name: str) -> list[Block]:
    """The fenced blocks of a Markdown document (CommonMark fences: ``` or ~~~, at most 3
    spaces of indentation, closed by a fence of the same character at least as long)."""
    lines = path.read_text(encoding="utf-8").split("\n")
    blocks: list[Block] = []
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m or (m.group(2)[0] == "`" and "`" in m.group(3)):
            i += 1
            continue
        indent, fence, info = len(m.group(1)), m.group(2), m.group(3).split()
        start = i
        body: list[str] = []
        i += 1
        while i < len(lines):
            c = FENCE.match(lines[i])
            if c and c.group(2)[0] == fence[0] and len(c.group(2)) >= len(fence) and not c.group(3).strip():
                break
            line = lines[i]
            body.append(line[min(indent, len(line) - len(line.lstrip(" "))):])
            i += 1
        blocks.append(Block(name, start + 1, info, "\n".join(body) + "\n", i + 1))
        i += 1
    return classify(blocks)


def classify(blocks: list[Block]) -> list[Block]:
    kept: list[Block] = []
    for b in blocks:
        lang, flags = (b.info[0] if b.info else ""), b.info[1:]
        where = f"{b.doc}:{b.line}"
        files = [f[len("file="):] for f in flags if f.startswith("file=")]
        if "run" in flags:
            if lang not in SHELLS:
                raise DocError(f"{where}: `run` marks shell blocks only ({'/'.join(SHELLS)}), not {lang or 'an unnamed block'}")
            if files:
                raise DocError(f"{where}: a block is `run` or `file=`, not both")
            b.run = True
        if files:
            p = Path(files[0])
            if len(files) > 1 or not files[0] or p.is_absolute() or ".." in p.parts:
                raise DocError(f"{where}: file= takes one relative path inside the checkout, got {' '.join(files)}")
            b.file = files[0]
        if lang == "text" and "output" in flags:
            prev = kept[-1] if kept else None
            if prev is None or not prev.run or prev.output is not None:
                raise DocError(f"{where}: a `text output` block must follow a runnable block")
            prev.output = b.text
            continue
        kept.append(b)
    return kept


def documents(source: Path) -> list[str]:
    docs = ["README.md"] + sorted(f"docs/{p.name}" for p in (source / "docs").glob("*.md"))
    return [d for d in docs if (source / d).is_file()]


def runnable_documents(source: Path) -> list[str]:
    return [d for d in documents(source) if any(b.run for b in parse(source / d, d))]


def checkout_files(source: Path) -> list[str]:
    """The files of the checkout as git sees it (tracked and untracked, not ignored); without
    git, every file outside the ignored build folders."""
    try:
        out = subprocess.run(["git", "-C", str(source), "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], check=True, capture_output=True).stdout
        return sorted({f for f in out.decode().split("\0") if f})
    except (OSError, subprocess.CalledProcessError):
        skip = re.compile(r"^(build[^/]*|\.venv|\.git)(/|$)|(^|/)__pycache__(/|$)")
        return sorted(str(p.relative_to(source)) for p in source.rglob("*")
                      if not p.is_dir() and not skip.search(str(p.relative_to(source))))


def make_scratch(source: Path, build: Path, root: Path) -> None:
    if root.exists():
        shutil.rmtree(root)
    root.mkdir(parents=True)
    for name in checkout_files(source):
        src = source / name
        if not src.exists() and not src.is_symlink():
            continue  # deleted in the work tree
        dst = root / name
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.is_symlink():
            os.symlink(os.readlink(src), dst)
        elif src.is_file():
            shutil.copy2(src, dst)
    (root / "build").symlink_to(build.resolve(), target_is_directory=True)
    if (source / ".venv").is_dir():
        (root / ".venv").symlink_to((source / ".venv").resolve(), target_is_directory=True)


def tail(text: str) -> str:
    return text if len(text) <= OUTPUT_LIMIT else "[...]\n" + text[-OUTPUT_LIMIT:]


def run_block(b: Block, cwd: Path, scripts: Path, timeout: float) -> str | None:
    """Runs one block; returns None when it passed, else the failure report."""
    script = scripts / f"line{b.line}.sh"
    failed = scripts / f"line{b.line}.err"
    failed.unlink(missing_ok=True)
    # Line 1 of the script is the trap, so that the block's line k is the script's line
    # k + 1 and the document's line b.line + k: LINENO maps back to the document.
    # The failing command goes to the file named by SVA_DOCS_FAILED: status, line, command.
    trap = (f"trap 'printf \"%s\\t%s\\t%s\\n\" \"$?\" \"$((LINENO + {b.line - 1}))\" "
            f"\"$BASH_COMMAND\" > \"$SVA_DOCS_FAILED\"' ERR\n")
    script.write_text(trap + b.text, encoding="utf-8")
    started = time.monotonic()
    try:
        env = dict(os.environ, SVA_DOCS_FAILED=str(failed))
        proc = subprocess.run(["bash", "-euo", "pipefail", str(script)], cwd=cwd, stdin=subprocess.DEVNULL, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace") + (e.stderr or b"").decode(errors="replace")
        return f"{b.doc}:{b.line}: the block (lines {b.line}-{b.end}) ran over {timeout:.0f} s\n{tail(out)}"
    stdout, stderr = proc.stdout.decode(errors="replace"), proc.stderr.decode(errors="replace")
    took = time.monotonic() - started
    if proc.returncode != 0:
        where = f"{b.doc}:{b.line}"
        what = f"the block (lines {b.line}-{b.end}) exited {proc.returncode}"
        if failed.exists():
            status, line, command = (failed.read_text().rstrip("\n").split("\t", 2) + ["", ""])[:3]
            where = f"{b.doc}:{line}"
            what = f"`{command}` exited {status} (block at lines {b.line}-{b.end})"
        return f"{where}: {what}\n--- stdout\n{tail(stdout)}--- stderr\n{tail(stderr)}"
    if b.output is not None:
        want = [s.rstrip() for s in b.output.rstrip().split("\n")]
        got = [s.rstrip() for s in stdout.rstrip().split("\n")]
        if want != got:
            return (f"{b.doc}:{b.line}: the block's output differs from the `text output` block after it\n"
                    f"--- documented\n{b.output.rstrip()}\n--- printed\n{tail(stdout.rstrip())}\n"
                    f"--- stderr\n{tail(stderr)}")
    print(f"{b.doc}:{b.line}: ok ({took:.1f} s)", flush=True)
    return None


def run_document(doc: str, source: Path, build: Path, work: Path, timeout: float) -> bool:
    blocks = parse(source / doc, doc)
    if not any(b.run for b in blocks):
        print(f"{doc}: no runnable block (```sh run)", file=sys.stderr)
        return False
    slug = re.sub(r"[^A-Za-z0-9]+", "_", doc.removesuffix(".md"))
    cwd, scripts = work / slug / "checkout", work / slug / "blocks"
    make_scratch(source, build, cwd)
    scripts.mkdir(parents=True, exist_ok=True)
    print(f"{doc}: {sum(b.run for b in blocks)} runnable blocks in {cwd}", flush=True)
    for b in blocks:
        if b.file is not None:
            target = cwd / b.file
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(b.text, encoding="utf-8")
            print(f"{doc}:{b.line}: wrote {b.file}", flush=True)
        elif b.run:
            failure = run_block(b, cwd, scripts, timeout)
            if failure is not None:
                print(failure, file=sys.stderr, flush=True)
                return False
    return True


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="run_docs.py", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run the runnable blocks of documents")
    run.add_argument("--source", type=Path, required=True)
    run.add_argument("--build", type=Path, required=True, help="the build tree, `build` in the scratch copy")
    run.add_argument("--work", type=Path, required=True, help="scratch folders go here")
    run.add_argument("--block-timeout", type=float, default=300)
    run.add_argument("docs", nargs="+", help="documents, relative to --source")
    lst = sub.add_parser("list", help="the documents with runnable blocks, one a line")
    lst.add_argument("--source", type=Path, required=True)
    chk = sub.add_parser("check", help="the registered documents are those with runnable blocks")
    chk.add_argument("--source", type=Path, required=True)
    chk.add_argument("--registered", required=True, help="';'-separated, as CMake registered them")
    args = parser.parse_args(argv)
    try:
        if args.command == "list":
            print("\n".join(runnable_documents(args.source)))
            return 0
        if args.command == "check":
            want = runnable_documents(args.source)
            have = [d for d in args.registered.split(";") if d]
            if want != have:
                print(f"run_docs: ctest runs the docs {have}, but the documents with runnable blocks are "
                      f"{want}: configure the build again (cmake -S . -B build)", file=sys.stderr)
                return 1
            print(f"run_docs: {len(want)} documents with runnable blocks, each a ctest test", flush=True)
            # parse every document, so that a broken marker anywhere fails here
            for d in documents(args.source):
                parse(args.source / d, d)
            return 0
        ok = True
        for doc in args.docs:
            ok = run_document(doc, args.source.resolve(), args.build, args.work.resolve(), args.block_timeout) and ok
        return 0 if ok else 1
    except DocError as e:
        print(f"run_docs: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
