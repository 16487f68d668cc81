#!/usr/bin/env bash
# Installs what a part needs (scripts/setup.sh), configures and builds it into build/
# (or $SVA_BUILD_DIR), one line per step on stderr.
# Usage: scripts/build.sh [--part demo|live|flight|all] [extra cmake -D options]
#   demo, live  the sva CLI only (target sva); a fresh build dir is configured without
#               tests and ports, an existing one is kept as it is
#   flight      the CLI, sva_node, sva_mavlink_bridge and the LCM Python types (ports
#               on, tests off in a fresh build dir)
#   all         (default) everything: the core, the CLI, the ports, the tests
# The part may also come from $SVA_SETUP_PART (scripts/demo.sh --live sets it).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

log() { printf 'build: %s\n' "$*" >&2; }

part=${SVA_SETUP_PART:-all}
case "${1:-}" in
    --part) part=${2:?--part needs a value (demo, live, flight or all)}; shift 2 ;;
    --part=*) part=${1#--part=}; shift ;;
esac
build=${SVA_BUILD_DIR:-build}

scripts/setup.sh --part "$part"
jobs=$(nproc)
if [ "$part" = all ]; then
    # Unity, the C tests' framework, comes by FetchContent from its public repository;
    # a copy of the same release beside the checkout serves builds without internet.
    unity=()
    if [ -f "$root/../shared/unity/src/unity.c" ]; then
        unity=(-DFETCHCONTENT_SOURCE_DIR_UNITY="$(cd "$root/../shared/unity" && pwd)")
    fi
    log "configuring $build/ (everything: core, CLI, ports, tests)"
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
          -DSVA_BUILD_TESTS=ON -DSVA_BUILD_PORTS=ON -DPython3_EXECUTABLE="$root/.venv/bin/python" \
          "${unity[@]}" "$@" >/dev/null
    log "building $build/ (all targets, $jobs jobs)"
    cmake --build "$build" -j "$jobs"
elif [ "$part" = flight ]; then
    if [ ! -f "$build/CMakeCache.txt" ] || [ $# -gt 0 ]; then
        log "configuring $build/ (the CLI and the ports, no tests)"
        cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
              -DSVA_BUILD_TESTS=OFF -DSVA_BUILD_PORTS=ON "$@" >/dev/null
    fi
    log "building sva, sva_node, sva_mavlink_bridge ($jobs jobs)"
    if ! out=$(cmake --build "$build" -j "$jobs" --target sva sva_node sva_mavlink_bridge sva_lcm_python 2>&1); then
        printf '%s\n' "$out" >&2
        exit 1
    fi
else
    if [ ! -f "$build/CMakeCache.txt" ] || [ $# -gt 0 ]; then
        log "configuring $build/ (the sva CLI only: no tests, no ports)"
        cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
              -DSVA_BUILD_TESTS=OFF -DSVA_BUILD_PORTS=OFF "$@" >/dev/null
    fi
    log "building $build/bin/sva (target sva, $jobs jobs)"
    # quiet unless it fails
    if ! out=$(cmake --build "$build" -j "$jobs" --target sva 2>&1); then
        printf '%s\n' "$out" >&2
        exit 1
    fi
fi
