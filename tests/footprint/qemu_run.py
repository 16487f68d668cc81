#!/usr/bin/env python3
"""Runs the Cortex-M firmware's semihosting image under qemu-system-arm and checks
its plans against the host's (ctest footprint_<build>_qemu, docs/embedded.md).

  qemu_run.py --qemu QEMU --machine BOARD --elf sva_fw_semihost.elf --nm NM
              --mission fixtures/missions/hand_5_3.json (--sva SVA | --golden DIR)
              [--timeout SECONDS]

1. The image links no heap, syscall stub, stdio or floating-point helper (the
   footprint check's list, footprint.py FORBIDDEN), as the size-checked image.
2. qemu boots it on BOARD with semihosting; it must exit with status 0 within the
   timeout, having printed one "plan algo=..." line per algorithm and
   "done failures=0" (examples/cortex-m/main.c, SVA_FW_SEMIHOSTING).
3. Every plan equals the host's plan of the same mission (the image's mission.c is
   this JSON file transcribed into ROM): `sva plan --algo A MISSION` of the host CLI
   (or, without it, the golden fixture), compared on covered, cost, the routes (UAV
   id: target ids in visit order), and the counters the host reports (search nodes,
   pivots, flow work, flow's lower bound and optimality).
"""

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from footprint import FORBIDDEN, symbols  # noqa: E402

ALGORITHMS = ("sva", "ga", "hga", "bfa", "flow")
LINE_RE = re.compile(r"^plan algo=(\w+) status=(-?\d+)(.*)$")


def parse_fields(rest):
    return dict(kv.split("=", 1) for kv in rest.split())


def host_plan(args, algo):
    if args.sva:
        out = subprocess.run([args.sva, "plan", "--algo", algo, args.mission], capture_output=True,
                             text=True, timeout=60)
        if out.returncode != 0:
            sys.exit(f"FAIL: host `sva plan --algo {algo}` failed: {out.stderr.strip()}")
        return json.loads(out.stdout)
    golden = Path(args.golden) / algo / Path(args.mission).name
    return json.loads(golden.read_text())


def expected(plan):
    routes = ";".join(f"{r['uav']}:" + ",".join(str(t) for t in r["targets"]) for r in plan["routes"])
    want = {"covered": str(plan["covered"]), "cost": str(plan["cost"]), "routes": routes}
    stats = plan.get("stats")
    if stats is not None:  # the host CLI's plan; golden fixtures leave stats out
        for key in ("search_nodes", "pivots", "flow_work"):
            if key in stats:  # flow's counters only in flow's plans
                want[key] = str(stats[key])
        want["lower_bound"] = str(stats["lower_bound"]) if "lower_bound" in stats else "-"
        if "lower_bound" in stats:
            want["optimal"] = "1" if stats["optimal"] else "0"
    return want


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--qemu", required=True)
    ap.add_argument("--machine", required=True)
    ap.add_argument("--elf", required=True)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--mission", required=True)
    ap.add_argument("--sva")
    ap.add_argument("--golden")
    ap.add_argument("--timeout", type=float, default=60.0)
    args = ap.parse_args()
    failures = []

    bad = sorted(f"{n} ({why})" for n in symbols(args.nm, args.elf) for rx, why in FORBIDDEN if rx.search(n))
    if bad:
        failures.append("linked in: " + ", ".join(bad))
    else:
        print(f"{Path(args.elf).name}: no heap, syscall stub, stdio or floating-point helper linked")

    cmd = [args.qemu, "-M", args.machine, "-nographic", "-monitor", "none", "-serial", "none",
           "-semihosting-config", "enable=on,target=native", "-kernel", args.elf]
    print("$ " + " ".join(cmd))
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        print(f"FAIL: no exit within {args.timeout:.0f} s (the image hung or faulted)")
        return 1
    # qemu writes the guest's semihosting console to stderr; anything else is qemu's.
    lines = (run.stdout + run.stderr).splitlines()
    for line in lines:
        print("  fw| " + line)
    if run.returncode != 0:
        failures.append(f"exit status {run.returncode} (0: every plan succeeded)")
    if "done failures=0" not in lines:
        failures.append("no 'done failures=0' line")

    seen = {}
    for line in lines:
        m = LINE_RE.match(line)
        if m:
            seen[m.group(1)] = (int(m.group(2)), parse_fields(m.group(3)))
    for algo in ALGORITHMS:
        if algo not in seen:
            failures.append(f"{algo}: no plan line")
            continue
        status, got = seen[algo]
        if status != 0:
            failures.append(f"{algo}: status {status}")
            continue
        want = expected(host_plan(args, algo))
        diff = [f"{k} {got.get(k)} (host {v})" for k, v in want.items() if got.get(k) != v]
        if diff:
            failures.append(f"{algo}: differs from the host plan: " + ", ".join(diff))
        else:
            print(f"{algo}: same plan as the host (" + ", ".join(f"{k} {v}" for k, v in want.items()) + ")")

    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
