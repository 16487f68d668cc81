#!/usr/bin/env bash
# Runs a command inside a fresh network namespace with multicast on loopback only:
#   netns_run.sh CMD [ARGS...]
# The namespace has a unique name and is deleted on exit, even on failure. Needs root
# (ip netns); without it the test is skipped (exit 77, ctest SKIP_RETURN_CODE).
set -euo pipefail
if [ "$(id -u)" -ne 0 ] || ! command -v ip >/dev/null; then
    echo "netns_run: needs root and iproute2 (ip netns); skipping" >&2
    exit 77
fi
ns="sva-lcm-$$-$RANDOM"
cleanup() { ip netns del "$ns" 2>/dev/null || true; }
trap cleanup EXIT INT TERM
ip netns add "$ns"
ip -n "$ns" link set lo up multicast on
ip -n "$ns" route add 224.0.0.0/4 dev lo
# The command knows it is inside a namespace made for it (tests refuse to run otherwise).
ip netns exec "$ns" env SVA_LCM_NETNS="$ns" "$@"
