#!/usr/bin/env bash
# Core benchmark: plans per second and median solve time per algorithm on the paper's
# sizes, and the planner's memory. Builds first.
# Usage: scripts/bench.sh [--results] [missions] [repeats]
#   --results  also write its section of docs/results.md (docs/results/core.md)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
results=""
if [ "${1:-}" = "--results" ]; then results=1; shift; fi
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
scripts/build.sh >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "build: $(grep -m1 CMAKE_BUILD_TYPE build/CMakeCache.txt)"
out=build/bench_core.txt
build/bench/bench_core "$@" | tee "$out"
[ -n "$results" ] || exit 0

# Section: bench_core's output as a table (UAVs per size as in bench_core.c).
build_type=$(grep -m1 CMAKE_BUILD_TYPE build/CMakeCache.txt | cut -d= -f2)
{
    sed -n 's/^sizes: /Sizes of the structs (x86-64, default bounds): /p' "$out"
    echo
    sed -n 's/^method: \(.*\)$/Method: \1. Missions: a 20x20 grid, windows of 10 to 20 ticks, need 1, hover fuel 2 (bench_core.c). Build: '"$build_type"'./p' "$out"
    echo
    echo "| targets x UAVs | algorithm | plans/s | median µs | p95 µs | covered % | complete % |"
    echo "|---|---|---|---|---|---|---|"
    awk 'NR > 1 && $1 ~ /^[0-9]+$/ && NF == 7 {
        u = ($1 <= 5) ? 3 : 5; gsub(/%/, "", $6); gsub(/%/, "", $7)
        printf "| %s x %s | %s | %s | %s | %s | %s | %s |\n", $1, u, $2, $3, $4, $5, $6, $7
    }' "$out"
    echo
    echo "Against the goals:"
    awk '$1 == "sizes:" { b = $3; printf "- the planner struct for the default bounds is %s B (goal: under 1 MiB: %s).\n", b, (b < 1048576) ? "met" : "not met" }
         $1 == 25 && $2 == "sva" { printf "- sva at 25 x 5: median %s µs (goal: under 50 µs: %s).\n", $4, ($4 < 50) ? "met" : "not met" }
         $1 == 5 && $2 == "bfa" { printf "- bfa at 5 x 3: p95 %s µs (goal: under 10 ms: %s; the paper'"'"'s brute force took about 290 s).\n", $5, ($5 < 10000) ? "met" : "not met" }' "$out"
    echo
    echo "bfa runs up to 10 targets (its limits). Per-plan time: the mean of the repeats inside one process, so memory is warm."
} | python3 tools/bench/results.py write core --command "scripts/bench.sh --results${*:+ $*}" \
      --load-start "$load_start"
