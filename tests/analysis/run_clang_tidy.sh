#!/usr/bin/env bash
# clang-tidy, every warning an error (ctest analysis_clang_tidy):
# - the core, core/src/*/*.c and core/src/*.c, with the checked-in .clang-tidy, compiled
#   as the default profile builds it;
# - the ports and the CLI (port/*/src/*.c, port/*/node/*.c, port/mavlink/bridge/*.c,
#   tools/cli/*.c; tests/analysis/host_sources.py), with port/.clang-tidy (the same
#   checks, adjusted for POSIX host code), each file with the include paths and
#   definitions the build compiles it with (BUILD_DIR/compile_commands.json: the
#   generated LCM and MAVLink headers are in the build tree).
# Both sets are globbed when the test runs, so new files are analysed without edits here.
# Planted defects (canary/tidy_canary.c, and the same file under each configuration)
# must be rejected first, or clang-tidy checks nothing.
# Usage: run_clang_tidy.sh SOURCE_ROOT WORK_DIR PYTHON BUILD_DIR [CLANG_TIDY]
set -euo pipefail
root=$1
work=$2
python=${3:-python3}
build=$4
tidy=${5:-clang-tidy}
mkdir -p "$work"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
command -v "$tidy" >/dev/null || { echo "$tidy not installed (scripts/setup.sh installs clang-tidy)"; exit 1; }
cd "$root"
"$tidy" --version | grep -i version
core_flags=(-std=c99 -Icore/include -Icore/src -Icore/profiles '-DSVA_CONFIG_HEADER="sva_profile_default.h"')
host_config="$root/port/.clang-tidy"
[ -f "$build/compile_commands.json" ] ||
    { echo "FAIL: $build/compile_commands.json missing: configure and build first (scripts/build.sh)"; exit 1; }

# The canary, under the core's configuration and under the ports' (whose exceptions
# must not switch the planted checks off).
for config in "$root/.clang-tidy" "$host_config"; do
    canary=$("$tidy" --quiet --config-file="$config" "$here/canary/tidy_canary.c" -- -std=c99 2>&1) &&
        { echo "FAIL: clang-tidy ($config) accepted the planted defects in canary/tidy_canary.c"; exit 1; }
    for check in misc-no-recursion clang-analyzer-security.insecureAPI.strcpy cert-err33-c; do
        if ! grep -q "\[$check,.*-warnings-as-errors\]" <<<"$canary"; then
            echo "FAIL: clang-tidy ($config) did not report $check as an error in canary/tidy_canary.c:"
            echo "$canary"
            exit 1
        fi
    done
done

# Every finding is an error; each must be listed in docs/misra-deviations.md (id
# clang-tidy/<check>) or the test fails. A clang-tidy run that fails without a finding
# (e.g. a compile error) fails the test by itself. A header's finding counts once,
# however many files include it.
status=0
findings="$work/findings.txt"
: >"$findings.all"
: >"$work/diagnostics.txt"
run() {  # run CONFIG FILE FLAGS...
    local config=$1 src=$2
    shift 2
    local rc=0 out parsed
    out=$("$tidy" --quiet --config-file="$config" "$src" -- "$@" 2>&1) || rc=$?
    grep -E ': (error|warning): ' <<<"$out" >>"$work/diagnostics.txt" || true
    if ! parsed=$("$python" "$here/tidy_findings.py" "$root" <<<"$out"); then
        echo "$out"
        echo "FAIL: clang-tidy output on $src not understood"
        status=1
    fi
    if [ -n "$parsed" ]; then
        echo "$parsed" >>"$findings.all"
    elif [ "$rc" -ne 0 ]; then
        echo "$out"
        echo "FAIL: clang-tidy failed on $src without a finding"
        status=1
    fi
}
n_core=0
for src in core/src/*/*.c core/src/*.c; do
    run "$root/.clang-tidy" "$src" "${core_flags[@]}"
    n_core=$((n_core + 1))
done
n_host=0
mapfile -t host < <("$python" "$here/host_sources.py" list "$root")
for src in "${host[@]}"; do
    out=$("$python" "$here/host_sources.py" flags "$root" "$build" "$src") ||
        { echo "FAIL: no build flags for $src"; exit 1; }
    mapfile -t flags <<<"$out"
    run "$host_config" "$src" "${flags[@]}"
    n_host=$((n_host + 1))
done
sort -u "$work/diagnostics.txt"  # a header's diagnostic once, not once per file
sort -u "$findings.all" >"$findings"
if ! "$python" "$here/check_deviations.py" "$findings" "$root/docs/misra-deviations.md"; then
    status=1
fi
echo "clang-tidy: $(wc -l <"$findings") findings in $n_core files of core/src and $n_host of the ports and the CLI"
exit "$status"
