#!/usr/bin/env bash
# gcc -fanalyzer over core/src/*/*.c and core/src/*.c, warnings as errors, for the
# tiny, default and max bound profiles (ctest analysis_gcc_fanalyzer). A planted
# use-after-free (canary/analyzer_canary.c) must be rejected first, or the analyzer
# checks nothing.
# Usage: run_fanalyzer.sh SOURCE_ROOT WORK_DIR [GCC]
set -euo pipefail
root=$1
work=$2
cc=${3:-gcc}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
"$cc" --version | head -1
rm -rf "$work" && mkdir -p "$work"
cd "$root"
flags=(-std=c99 -pedantic -O2 -fanalyzer -Wall -Wextra -Werror)

if "$cc" "${flags[@]}" -c "$here/canary/analyzer_canary.c" -o "$work/canary.o" >"$work/canary.txt" 2>&1 ||
        ! grep -q 'Werror=analyzer-use-after-free' "$work/canary.txt"; then
    echo "FAIL: gcc -fanalyzer did not reject the planted use-after-free in canary/analyzer_canary.c"
    cat "$work/canary.txt"
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
if [ "$status" -ne 0 ]; then
    echo "FAIL: gcc -fanalyzer findings in core/"
else
    echo "gcc -fanalyzer: 0 findings in $n compilations (core/src x tiny, default, max)"
fi
exit "$status"
