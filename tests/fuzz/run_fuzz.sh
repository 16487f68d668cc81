#!/usr/bin/env bash
# The libFuzzer part of the fuzz tests (label fuzz; docs/fuzzing.md).
#   run_fuzz.sh build SOURCE_ROOT ENGINE_DIR [LCM_CMAKE_DIR LCM_GENERATED_DIR [MAVLINK_GENERATED_DIR]]
#       configures and builds tests/fuzz/engine with clang into ENGINE_DIR.
#   run_fuzz.sh run SOURCE_ROOT ENGINE_DIR TARGET SECONDS RUNS
#       runs one fuzzer for at most SECONDS and RUNS inputs, from the checked-in seeds
#       and reproducers; new inputs go to ENGINE_DIR/work/TARGET (not the source tree),
#       a crash to ENGINE_DIR/artifacts/ (then the test fails: copy the file into
#       tests/fuzz/regressions/TARGET/ once fixed).
set -euo pipefail
mode=$1
root=$2
engine=$3
case "$mode" in
build)
    command -v clang >/dev/null || { echo "clang not installed (scripts/setup.sh installs it)"; exit 1; }
    extra=()
    if [ $# -ge 5 ] && [ -n "$4" ] && [ -n "$5" ]; then
        extra=(-DSVA_LCM_CMAKE_DIR="$4" -DSVA_LCM_GENERATED_DIR="$5")
    fi
    if [ $# -ge 6 ] && [ -n "$6" ]; then
        extra+=(-DSVA_MAVLINK_GENERATED_DIR="$6")
    fi
    cmake -S "$root/tests/fuzz/engine" -B "$engine" -G Ninja -DCMAKE_C_COMPILER=clang \
        -DCMAKE_BUILD_TYPE= -DSVA_ROOT="$root" "${extra[@]}" >/dev/null
    cmake --build "$engine" -j 2
    ;;
run)
    target=$4
    seconds=$5
    runs=$6
    bin="$engine/bin/fuzz_$target"
    [ -x "$bin" ] || { echo "$bin missing (the fuzz_build test builds it)"; exit 1; }
    work="$engine/work/$target"
    mkdir -p "$work" "$engine/artifacts"
    opts=(-max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=2048
          -artifact_prefix="$engine/artifacts/${target}-" -print_final_stats=1)
    case "$target" in
    mission) opts+=(-max_len=8192 -dict="$root/tests/fuzz/mission.dict") ;;
    lcm) opts+=(-max_len=16384) ;;
    can) opts+=(-max_len=4096) ;;
    mavlink) opts+=(-max_len=4096) ;;
    esac
    dirs=("$work" "$root/tests/fuzz/corpus/$target")
    if [ -d "$root/tests/fuzz/regressions/$target" ]; then
        dirs+=("$root/tests/fuzz/regressions/$target")
    fi
    log="$engine/work/$target.log"
    rc=0
    "$bin" "${opts[@]}" "${dirs[@]}" >"$log" 2>&1 || rc=$?
    # The progress lines (NEW, REDUCE, pulse) are many; the rest is the report.
    grep -v '^#[0-9]*.*\(NEW\|REDUCE\|pulse\)' "$log" || true
    exit "$rc"
    ;;
*)
    echo "usage: run_fuzz.sh build|run ..." >&2
    exit 2
    ;;
esac
