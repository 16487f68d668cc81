#!/usr/bin/env bash
# gcc -fanalyzer, warnings as errors (ctest analysis_gcc_fanalyzer):
# - the core, core/src/*/*.c and core/src/*.c, for the tiny, default and max bound
#   profiles;
# - the ports and the CLI (port/*/src/*.c, port/*/node/*.c, port/mavlink/bridge/*.c,
#   tools/cli/*.c; tests/analysis/host_sources.py), each file with the include paths and
#   definitions the build compiles it with (BUILD_DIR/compile_commands.json), in the
#   build's profile.
# Both sets are globbed when the test runs. Planted defects must be rejected first, or
# the analyzer checks nothing: a use-after-free (canary/analyzer_canary.c) and, with a
# port's flags, a stream leak in host code (canary/analyzer_host_canary.c).
# Usage: run_fanalyzer.sh SOURCE_ROOT WORK_DIR GCC BUILD_DIR [PYTHON]
set -euo pipefail
root=$1
work=$2
cc=${3:-gcc}
build=$4
python=${5:-python3}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
"$cc" --version | head -1
rm -rf "$work" && mkdir -p "$work/host"
cd "$root"
flags=(-std=c99 -pedantic -O2 -fanalyzer -Wall -Wextra -Werror)

if "$cc" "${flags[@]}" -c "$here/canary/analyzer_canary.c" -o "$work/canary.o" >"$work/canary.txt" 2>&1 ||
        ! grep -q 'Werror=analyzer-use-after-free' "$work/canary.txt"; then
    echo "FAIL: gcc -fanalyzer did not reject the planted use-after-free in canary/analyzer_canary.c"
    cat "$work/canary.txt"
    exit 1
fi
[ -f "$build/compile_commands.json" ] ||
    { echo "FAIL: $build/compile_commands.json missing: configure and build first (scripts/build.sh)"; exit 1; }
mapfile -t host < <("$python" "$here/host_sources.py" list "$root")
host_flags() {  # host_flags FILE: its build flags, one per line; the test fails without them
    "$python" "$here/host_sources.py" flags "$root" "$build" "$1" ||
        { echo "FAIL: no build flags for $1" >&2; return 1; }
}
out=$(host_flags "${host[0]}")
mapfile -t first_flags <<<"$out"
if "$cc" "${flags[@]}" "${first_flags[@]}" -c "$here/canary/analyzer_host_canary.c" \
        -o "$work/host_canary.o" >"$work/host_canary.txt" 2>&1 ||
        ! grep -q 'Werror=analyzer-file-leak' "$work/host_canary.txt"; then
    echo "FAIL: gcc -fanalyzer did not reject the planted stream leak in canary/analyzer_host_canary.c"
    cat "$work/host_canary.txt"
    exit 1
fi

status=0
n=0
for profile in tiny default max; do
    for src in core/src/*/*.c core/src/*.c; do
        n=$((n + 1))
        if ! "$cc" "${flags[@]}" -Icore/include -Icore/src -Icore/profiles \
                "-DSVA_CONFIG_HEADER=\"sva_profile_${profile}.h\"" \
                -c "$src" -o "$work/$(basename "$src" .c)_${profile}.o"; then
            echo "  ^ in profile $profile"
            status=1
        fi
    done
done
n_host=0
for src in "${host[@]}"; do
    n_host=$((n_host + 1))
    out=$(host_flags "$src")
    mapfile -t src_flags <<<"$out"
    if ! "$cc" "${flags[@]}" "${src_flags[@]}" -c "$src" -o "$work/host/${src//\//_}.o"; then
        status=1
    fi
done
if [ "$status" -ne 0 ]; then
    echo "FAIL: gcc -fanalyzer findings"
else
    echo "gcc -fanalyzer: 0 findings in $n compilations (core/src x tiny, default, max)" \
         "and $n_host (the ports and the CLI)"
fi
exit "$status"
