#!/usr/bin/env bash
# End-to-end latency of the LCM link: mission published (ground) -> plan received
# (ground), over real udpm multicast in a private network namespace (root needed).
#   tools/bench/lcm_latency.sh [--results] [ROUNDS] [MISSION.json] [ALGORITHM]
# --results also writes this configuration's part of docs/results.md
# (docs/results/lcm_latency.<options>.md, tools/bench/results.py).
# Defaults: 500 rounds, fixtures/missions/rand_25_1.json (25 targets, 5 UAVs), sva.
# Environment:
#   NODE_OPTS="--rt-priority 20 --mlock"   extra sva_node options (docs/lcm.md, Latency)
#   GROUND_RT=20                           run the ground process under SCHED_FIFO 20
# Prints median, p90, p99 and max in microseconds, split at the node's plan timestamp,
# and the node's solve time.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
results=""
if [ "${1:-}" = "--results" ]; then results=1; shift; fi
args="$*"
rounds=${1:-500}
mission=${2:-$root/fixtures/missions/rand_25_1.json}
algo=${3:-sva}
node="$root/build/bin/sva_node"
[ -x "$node" ] || { echo "lcm_latency.sh: build first (scripts/build.sh): no $node" >&2; exit 2; }
ground=()
if [ -n "${GROUND_RT:-}" ]; then ground=(chrt -f "$GROUND_RT"); fi
ns="sva-lcm-bench-$$"
cleanup() {
    [ -n "${pid:-}" ] && kill -TERM "$pid" 2>/dev/null && wait "$pid" 2>/dev/null || true
    ip netns del "$ns" 2>/dev/null || true
}
trap cleanup EXIT INT TERM
ip netns add "$ns"
ip -n "$ns" link set lo up multicast on
ip -n "$ns" route add 224.0.0.0/4 dev lo
# shellcheck disable=SC2086  # NODE_OPTS is a list of options
ip netns exec "$ns" "$node" --prefix BENCH_ --algorithm "$algo" ${NODE_OPTS:-} 2>/dev/null &
pid=$!
sleep 0.3
kill -0 "$pid" 2>/dev/null || { echo "lcm_latency.sh: sva_node did not start (options: ${NODE_OPTS:-none})" >&2; exit 1; }
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
echo "node options: ${NODE_OPTS:-none}; ground: ${GROUND_RT:+SCHED_FIFO }${GROUND_RT:-normal}; load: $load_start"
out=$(mktemp)
trap 'cleanup; rm -f "$out"' EXIT INT TERM
ip netns exec "$ns" "${ground[@]}" env PYTHONPATH="$root/tools" SVA_LCM_PYTHON_TYPES="$root/build/port/lcm/python" \
    "$root/.venv/bin/python" "$root/tools/bench/lcm_latency.py" "$mission" "$rounds" | tee "$out"
[ -n "$results" ] || exit 0

env_prefix="${NODE_OPTS:+NODE_OPTS=\"$NODE_OPTS\" }${GROUND_RT:+GROUND_RT=$GROUND_RT }"
part=$(printf 'node_%s_ground_%s' "${NODE_OPTS:-default}" "${GROUND_RT:-default}" | tr -cs 'A-Za-z0-9' '_')
{
    sed -n '1s/^mission \(.*\), status.*$/Mission \1, algorithm '"$algo"'. Node options: '"${NODE_OPTS:-none}"'; ground process: '"${GROUND_RT:+SCHED_FIFO }${GROUND_RT:-default scheduling}"'./p' "$out"
    echo
    echo "| µs | median | p90 | p99 | max |"
    echo "|---|---|---|---|---|"
    awk '/^latency us:/ {printf "| mission published -> plan received | %s | %s | %s | %s |\n", $4, $6, $8, $10}
         /^ground -> node planned us:/ {printf "| ground -> node planned | %s | %s | %s | %s |\n", $7, $9, $11, $13}
         /^node -> ground handler us:/ {printf "| node -> ground handler | %s | %s | %s | %s |\n", $7, $9, $11, $13}
         /^node solve us:/ {printf "| node `sva_plan` | %s | | %s | %s |\n", $5, $7, $9}' "$out"
} | python3 "$root/tools/bench/results.py" write "lcm_latency.$part" \
      --command "${env_prefix}tools/bench/lcm_latency.sh --results${args:+ $args}" --load-start "$load_start" \
      --title "node ${NODE_OPTS:-default options}, ground ${GROUND_RT:+SCHED_FIFO }${GROUND_RT:-default scheduling}"
