#!/usr/bin/env bash
# Core benchmark: plans per second and median solve time per algorithm on the paper's
# sizes, and the planner's memory. Builds first. Usage: scripts/bench.sh [missions] [repeats]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/build.sh >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "build: $(grep -m1 CMAKE_BUILD_TYPE build/CMakeCache.txt)"
build/bin/bench_core "$@"
