#!/usr/bin/env python3
"""Boots the Cortex-M test images of tests/target in qemu-system-arm and judges them
(ctest label `target`, docs/embedded.md "Unit tests on the target").

  run_target.py run --qemu QEMU --machine BOARD --elf test_<unit>.elf [--timeout S] [--icount]
  run_target.py figures --manifest BUILD/target/images.txt [--qemu QEMU] [--size SIZE]
                        [--results]

`run` boots one image with Arm semihosting (qemu writes the guest's output to its
stderr) and fails, with one `FAIL: <image>: <why>` line, on:
- no exit within the timeout (a hang; faults end the run at once, below);
- a fault: the image's handlers print `sva target: fault <name> pc=...` (status 3);
- a stack that reached the end of .bss (status 4);
- no Unity summary (`N Tests F Failures I Ignored`, then OK or FAIL), e.g. after an
  abort() from a failed assert;
- any failed test, a FAIL verdict, or an exit status other than 0.
--icount runs qemu with -icount shift=0: the virtual clock advances 1 ns per
instruction, so the SysTick count the image prints gives the instructions executed.

`figures` runs every image of the manifest (written by tests/target/CMakeLists.txt:
test name, machine, processor clock, image) twice, plain for the wall time and under
-icount for the instructions, and prints a Markdown table with the tests run and
ignored, both figures, the stack used and the sections from arm-none-eabi-size -A.
"""

import argparse
import re
import subprocess
import sys
import time
from pathlib import Path

SUMMARY_RE = re.compile(r"^(\d+) Tests (\d+) Failures (\d+) Ignored\s*$")
FAULT_RE = re.compile(r"^sva target: fault (.*)$")
STATS_RE = re.compile(r"^sva target: stack (\d+) of (\d+) B, heap (\d+) of (\d+) B, systick (\d+)$")
EXIT_RE = re.compile(r"^sva target: exit (-?\d+)$")


def qemu_command(qemu, machine, elf, icount):
    cmd = [qemu, "-M", machine, "-nographic", "-monitor", "none", "-serial", "none",
           "-semihosting-config", "enable=on,target=native", "-kernel", str(elf)]
    if icount:
        cmd += ["-icount", "shift=0,align=off,sleep=off"]
    return cmd


def boot(qemu, machine, elf, timeout, icount=False):
    """Runs one image; returns (exit status or None on timeout, output lines, seconds)."""
    cmd = qemu_command(qemu, machine, elf, icount)
    start = time.monotonic()
    try:
        run = subprocess.run(cmd, capture_output=True, timeout=timeout)
        status, out, err = run.returncode, run.stdout, run.stderr
    except subprocess.TimeoutExpired as expired:
        status, out, err = None, expired.stdout or b"", expired.stderr or b""
    seconds = time.monotonic() - start
    text = (out + err).decode("utf-8", errors="replace")
    return status, text.splitlines(), seconds


def judge(name, status, lines, timeout):
    """Returns (failures, summary dict or None, stats match or None)."""
    failures = []
    summary = None
    verdict = None
    stats = None
    for i, line in enumerate(lines):
        m = SUMMARY_RE.match(line)
        if m:
            summary = {"tests": int(m.group(1)), "failures": int(m.group(2)), "ignored": int(m.group(3))}
            verdict = lines[i + 1].strip() if i + 1 < len(lines) else None
        m = FAULT_RE.match(line)
        if m:
            failures.append(f"fault {m.group(1)}")
        m = STATS_RE.match(line)
        if m:
            stats = m
        m = EXIT_RE.match(line)
        if m:
            failures.append(f"exit({m.group(1)}) called (abort or a failed assert?)")
        if line.startswith("sva target: stack overflow"):
            failures.append("stack overflow")
    if status is None:
        failures.append(f"no exit within {timeout:.0f} s (a hang, or too slow for this timeout)")
    if summary is None:
        failures.append("no Unity summary ('N Tests F Failures I Ignored')")
    else:
        if summary["failures"] != 0:
            failures.append(f"{summary['failures']} of {summary['tests']} tests failed")
        if verdict not in ("OK", "FAIL"):
            failures.append(f"no OK/FAIL verdict after the summary (got {verdict!r})")
        elif (verdict == "OK") != (summary["failures"] == 0):
            failures.append(f"verdict {verdict} with {summary['failures']} failures")
    if status is not None and status != 0 and not failures:
        failures.append(f"exit status {status}")
    return failures, summary, stats


def cmd_run(args):
    name = Path(args.elf).name
    if not Path(args.elf).is_file():
        print(f"FAIL: {name}: no image {args.elf} (did the target build run?)")
        return 1
    print("$ " + " ".join(qemu_command(args.qemu, args.machine, args.elf, args.icount)))
    status, lines, seconds = boot(args.qemu, args.machine, args.elf, args.timeout, args.icount)
    for line in lines:
        print("  target| " + line)
    failures, summary, stats = judge(name, status, lines, args.timeout)
    if summary is not None:
        print(f"{name}: {summary['tests']} tests, {summary['failures']} failures, "
              f"{summary['ignored']} ignored, {seconds:.2f} s under qemu ({args.machine})"
              + (f", stack {stats.group(1)} of {stats.group(2)} B" if stats else ""))
    for why in failures:
        print(f"FAIL: {name}: {why}")
    return 1 if failures else 0


def sections(size, elf):
    """text (vectors, code, read-only data), data, bss (with the heap) and stack, in bytes."""
    out = subprocess.run([size, "-A", str(elf)], capture_output=True, text=True, check=True).stdout
    got = {"text": 0, "data": 0, "bss": 0, "stack": 0}
    where = {".isr_vector": "text", ".text": "text", ".ARM.exidx": "text", ".data": "data",
             ".bss": "bss", ".stack": "stack"}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 2 and parts[0] in where and parts[1].isdigit():
            got[where[parts[0]]] += int(parts[1])
    return got


def cmd_figures(args):
    rows = []
    for entry in Path(args.manifest).read_text().splitlines():
        if not entry.strip():
            continue
        test, machine, hz, elf = entry.split()
        status, lines, wall = boot(args.qemu, machine, elf, args.timeout)
        failures, summary, _ = judge(test, status, lines, args.timeout)
        status_i, lines_i, wall_i = boot(args.qemu, machine, elf, args.timeout * 4, icount=True)
        failures_i, _, stats = judge(test, status_i, lines_i, args.timeout * 4)
        if failures or failures_i or summary is None or stats is None:
            print(f"FAIL: {test}: " + "; ".join(failures + failures_i), file=sys.stderr)
            return 1
        instructions = int(stats.group(5)) * 1_000_000_000 // int(hz)
        size = sections(args.size, elf)
        rows.append((test, machine, summary["tests"], summary["ignored"], wall, instructions,
                     wall_i, int(stats.group(1)), size))
        print(f"{test}: {summary['tests']} tests, {wall:.2f} s, {instructions / 1e6:.1f} M instructions",
              file=sys.stderr)
    out = ["| test | board | tests | ignored | wall | instructions | text | data | bss | stack used |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for test, machine, tests, ignored, wall, instructions, _, stack, size in rows:
        out.append(f"| `{test}` | {machine} | {tests} | {ignored} | {wall:.2f} s | "
                   f"{instructions / 1e6:,.1f} M | {size['text']:,} | {size['data']:,} | "
                   f"{size['bss']:,} | {stack:,} of {size['stack']:,} |")
    total_wall = sum(r[4] for r in rows)
    total_insns = sum(r[5] for r in rows)
    total_icount = sum(r[6] for r in rows)
    out.append(f"\n{len(rows)} images: {total_wall:.1f} s wall in all (one at a time), "
               f"{total_insns / 1e9:.2f} G instructions ({total_icount:.1f} s under -icount)")
    print("\n".join(out))
    if args.results:
        intro = ("The core's Unity tests (tests/core) built for the Cortex-M4F per bound "
                 "profile and booted in qemu-system-arm with Arm semihosting (ctest label "
                 "`target`; docs/embedded.md, \"Unit tests on the target\"). GCC `-Os`, full "
                 "newlib; wall time of a plain run, instructions from SysTick under "
                 "`-icount shift=0`; sections in bytes (bss includes the 8 KiB heap).")
        root = Path(__file__).resolve().parents[2]
        subprocess.run([sys.executable, str(root / "tools" / "bench" / "results.py"), "write",
                        "footprint.target", "--title", "Unit tests on the target",
                        "--command", "ctest --test-dir build -L target && .venv/bin/python "
                        "tests/target/run_target.py figures --manifest build/target/images.txt "
                        "--results"],
                       input=intro + "\n\n" + "\n".join(out) + "\n", text=True, check=True)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="boot one image and judge it")
    run.add_argument("--qemu", default="qemu-system-arm")
    run.add_argument("--machine", required=True)
    run.add_argument("--elf", required=True)
    run.add_argument("--timeout", type=float, default=60.0)
    run.add_argument("--icount", action="store_true", help="qemu -icount shift=0 (deterministic)")
    figures = sub.add_parser("figures", help="every image of a manifest: the docs' table")
    figures.add_argument("--manifest", required=True)
    figures.add_argument("--qemu", default="qemu-system-arm")
    figures.add_argument("--size", default="arm-none-eabi-size")
    figures.add_argument("--timeout", type=float, default=300.0)
    figures.add_argument("--results", action="store_true",
                         help="also write docs/results/footprint.target.md (tools/bench/results.py)")
    args = ap.parse_args()
    return cmd_run(args) if args.command == "run" else cmd_figures(args)


if __name__ == "__main__":
    sys.exit(main())
