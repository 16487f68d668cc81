#!/usr/bin/env bash
# End-to-end latency of the LCM link: mission published (ground) -> plan received
# (ground), over real udpm multicast in a private network namespace (root needed).
#   port/lcm/bench/latency.sh [ROUNDS] [MISSION.json] [ALGORITHM]
# Defaults: 500 rounds, fixtures/missions/rand_25_1.json (25 targets, 5 UAVs), sva.
# Prints median, p90, p99 and max in microseconds, and the node's solve time.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
rounds=${1:-500}
mission=${2:-$root/fixtures/missions/rand_25_1.json}
algo=${3:-sva}
node="$root/build/bin/sva_node"
[ -x "$node" ] || { echo "latency.sh: build first (scripts/build.sh): no $node" >&2; exit 2; }
ns="sva-lcm-bench-$$"
cleanup() {
    [ -n "${pid:-}" ] && kill -TERM "$pid" 2>/dev/null && wait "$pid" 2>/dev/null || true
    ip netns del "$ns" 2>/dev/null || true
}
trap cleanup EXIT INT TERM
ip netns add "$ns"
ip -n "$ns" link set lo up multicast on
ip -n "$ns" route add 224.0.0.0/4 dev lo
ip netns exec "$ns" "$node" --prefix BENCH_ --algorithm "$algo" 2>/dev/null &
pid=$!
sleep 0.3
ip netns exec "$ns" env PYTHONPATH="$root/tools" SVA_LCM_PYTHON_TYPES="$root/build/port/lcm/python" \
    "$root/.venv/bin/python" "$root/port/lcm/bench/latency.py" "$mission" "$rounds"
