#!/usr/bin/env bash
# cppcheck (ctest analysis_cppcheck):
# - with its MISRA C 2012 addon over core/;
# - without the addon (MISRA is the core's rule set) over the ports and the CLI
#   (port/*/src/*.c, port/*/node/*.c, port/mavlink/bridge/*.c, tools/cli/*.c, globbed
#   by tests/analysis/host_sources.py), each file with the include paths and
#   definitions the build compiles it with (BUILD_DIR/compile_commands.json), on Linux.
# Every finding must be covered by a row of docs/misra-deviations.md (rule, file, count,
# reason); anything beyond is a new finding and fails the test. The MISRA rule texts
# are not available, so findings carry rule numbers only. Planted defects must be
# reported first: a rule 15.5 violation (canary/misra_canary.c), or the addon is not
# working, and an out-of-bounds write checked as a port is (canary/cppcheck_canary.c).
# Usage: run_cppcheck.sh SOURCE_ROOT WORK_DIR PYTHON BUILD_DIR
set -euo pipefail
root=$1
work=$2
python=${3:-python3}
build=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
command -v cppcheck >/dev/null || { echo "cppcheck not installed (scripts/setup.sh installs it)"; exit 1; }
[ -f "$build/compile_commands.json" ] ||
    { echo "FAIL: $build/compile_commands.json missing: configure and build first (scripts/build.sh)"; exit 1; }
rm -rf "$work" && mkdir -p "$work/build" "$work/canary-build" "$work/host-build"
echo "$(cppcheck --version), MISRA C 2012 addon"

own=(--std=c99 --enable=warning,style,performance,portability
     --suppress=missingIncludeSystem
     --template='{file}:{line}:{severity}:{id}:{message}')
common=(--addon=misra "${own[@]}")

# The canary first: it proves the addon runs and reports.
cppcheck "${common[@]}" --cppcheck-build-dir="$work/canary-build" \
    --output-file="$work/canary.txt" "$here/canary/misra_canary.c" >/dev/null
if ! grep -q 'misra-c2012-15.5' "$work/canary.txt"; then
    echo "FAIL: the MISRA addon did not report the planted rule 15.5 violation:"
    cat "$work/canary.txt"
    exit 1
fi
cppcheck "${own[@]}" --cppcheck-build-dir="$work/canary-build" \
    --output-file="$work/host-canary.txt" "$here/canary/cppcheck_canary.c" >/dev/null
if ! grep -q ':arrayIndexOutOfBounds:' "$work/host-canary.txt"; then
    echo "FAIL: cppcheck did not report the planted out-of-bounds write in canary/cppcheck_canary.c:"
    cat "$work/host-canary.txt"
    exit 1
fi

# The core, in the default profile's configuration (one configuration, as built).
cd "$root"
cppcheck "${common[@]}" --cppcheck-build-dir="$work/build" --output-file="$work/findings.txt" \
    -Icore/include -Icore/src -Icore/profiles '-DSVA_CONFIG_HEADER="sva_profile_default.h"' \
    core/src/*/*.c core/src/*.c >/dev/null

# The ports and the CLI, file by file with their build flags (less -std, which cppcheck
# takes as --std, and the third-party include paths, which it is not given, as it is
# not given the system headers). __linux__: the host the nodes are built for.
mapfile -t host < <("$python" "$here/host_sources.py" list "$root")
for src in "${host[@]}"; do
    out=$("$python" "$here/host_sources.py" flags "$root" "$build" "$src" --user-includes) ||
        { echo "FAIL: no build flags for $src"; exit 1; }
    mapfile -t flags < <(grep -v '^-std=' <<<"$out")
    cppcheck "${own[@]}" --cppcheck-build-dir="$work/host-build" --output-file="$work/host.txt" \
        -D__linux__ "${flags[@]}" "$src" >/dev/null
    sed "s|^$root/||" "$work/host.txt" >>"$work/findings.txt"
done
echo "cppcheck: core/src with the MISRA addon; ${#host[@]} files of the ports and the CLI without it"
"$python" "$here/check_deviations.py" "$work/findings.txt" "$root/docs/misra-deviations.md"
