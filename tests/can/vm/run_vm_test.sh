#!/usr/bin/env bash
# The real SocketCAN test: boots Debian's kernel (linux-image-amd64) under
# qemu-system-x86_64 (TCG, no network device) with an initramfs that loads the CAN
# modules, creates vcan0, captures it with candump and runs sva_can_node (a live
# mission) against a bridge stand-in (both statically linked). The capture comes back
# over the second serial port and is decoded on the host with cantools; it must hold
# the plan the core produces for the mission, then the live mission's plan after the
# bridge's clock frame (past the first window's start: a visit under way) and its loss
# of UAV 1, and the bridge's NACK BAD_VERSION to a PLAN_BEGIN of protocol version 1.
# Fails, never skips, when anything is missing.
# Usage: run_vm_test.sh WORKDIR NODE_STATIC BRIDGE_STATIC FRAMES_TOOL MISSION PYTHON
set -euo pipefail
work=$1 node=$2 bridge=$3 tool=$4 mission=$5 python=$6
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "run_vm_test: FAIL: $*" >&2; exit 1; }
command -v qemu-system-x86_64 >/dev/null || die "qemu-system-x86_64 not found (apt: qemu-system-x86)"
for f in "$node" "$bridge" "$tool" "$mission" "$python"; do [ -e "$f" ] || die "$f missing"; done

mkdir -p "$work"
# The clock frame's tick: one past the earliest window's start.
"$python" -c 'import json, sys; print(min(t["start"] for t in json.load(open(sys.argv[1]))["targets"]) + 1)' \
    "$mission" > "$work/clock_tick"
tick=$(cat "$work/clock_tick")
echo "encode SVA_PLAN_BEGIN counter=0 version=1 plan_id=77 item_count=1 algorithm=0 plan_status=1 route_count=1" \
    | "$tool" codec > "$work/bad_begin.frame"
grep -q '^101#' "$work/bad_begin.frame" || die "cannot encode the version-1 BEGIN"
t0=$(date +%s.%N)
"$here/build_initramfs.sh" "$work" "$node" "$bridge" "$mission"
t1=$(date +%s.%N)
rm -f "$work/console.log" "$work/ser1.log"
# Bounded: the guest powers off by itself; timeout catches a hung boot.
rc=0
timeout --kill-after=5 120 qemu-system-x86_64 -machine accel=tcg -cpu max -m 256 -smp 1 \
    -nographic -monitor none -no-reboot -nic none \
    -kernel "$(cat "$work/kernel")" -initrd "$work/initrd.gz" \
    -append "console=ttyS0 panic=-1 quiet" \
    -serial "file:$work/console.log" -serial "file:$work/ser1.log" </dev/null || rc=$?
t2=$(date +%s.%N)
[ "$rc" -eq 0 ] || { tail -20 "$work/console.log" >&2 || true; die "qemu exited with $rc (124 = timeout)"; }
[ -s "$work/ser1.log" ] || { tail -20 "$work/console.log" >&2 || true; die "no output on the second serial port"; }

# What the core plans on the host for the same mission: plan 1 with every UAV;
# plan 2, the live mission's replan after the clock frame and the loss of UAV 1.
"$tool" plan "$mission" sva 1 > "$work/expected1.json"
"$tool" live "$mission" sva "$tick" 1 > "$work/expected2.json"

"$python" "$here/check_vm_capture.py" "$work/ser1.log" "$work/expected1.json" "$work/expected2.json" "$tick"
awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN { printf "run_vm_test: initramfs %.1f s, VM boot+test %.1f s\n", b-a, c-b }'
