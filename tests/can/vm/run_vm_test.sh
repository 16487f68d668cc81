#!/usr/bin/env bash
# The real SocketCAN test: boots Debian's kernel (linux-image-amd64) under
# qemu-system-x86_64 (TCG, no network device) with an initramfs that loads the CAN
# modules, creates vcan0, captures it with candump and runs sva_can_node against a
# bridge stand-in (both statically linked). The capture comes back over the second
# serial port and is decoded on the host with cantools; it must hold the plans the
# core produces for the mission (and for the mission without UAV 1, after the bridge
# reports it unavailable). Fails, never skips, when anything is missing.
# Usage: run_vm_test.sh WORKDIR NODE_STATIC BRIDGE_STATIC FRAMES_TOOL MISSION PYTHON
set -euo pipefail
work=$1 node=$2 bridge=$3 tool=$4 mission=$5 python=$6
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "run_vm_test: FAIL: $*" >&2; exit 1; }
command -v qemu-system-x86_64 >/dev/null || die "qemu-system-x86_64 not found (apt: qemu-system-x86)"
for f in "$node" "$bridge" "$tool" "$mission" "$python"; do [ -e "$f" ] || die "$f missing"; done

mkdir -p "$work"
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

# What the core plans on the host for the same mission: plan 1 with every UAV,
# plan 2 without UAV 1 (the bridge reported it unavailable).
"$tool" plan "$mission" sva 1 > "$work/expected1.json"
"$python" - "$mission" "$work/mission_no_uav1.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["uavs"] = [u for u in m["uavs"] if u["id"] != 1]
json.dump(m, open(sys.argv[2], "w"))
PY
"$tool" plan "$work/mission_no_uav1.json" sva 2 > "$work/expected2.json"

"$python" "$here/check_vm_capture.py" "$work/ser1.log" "$work/expected1.json" "$work/expected2.json"
awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN { printf "run_vm_test: initramfs %.1f s, VM boot+test %.1f s\n", b-a, c-b }'
